//! The SQLite store: one file (`DATA_DIR/chapaev.sqlite3`) in write-ahead-log
//! mode, embedded in the server process: the default, for one machine.
//!
//! One connection writes (SQLite has one writer at a time anyway): the
//! [`GroupCommit`] writer thread's batches and the few other writes share
//! it. On disk, a few read-only connections ([`Readers`]) answer listings
//! and loads without waiting for a commit's sync, and a [`Checkpointer`]
//! copies the log back into the database file on its own thread. Stores
//! from older versions of the server are brought up to date on opening
//! (token hashes, the physics column, the account columns).

use super::group_commit::{BatchWriter, GroupCommit, QueuedMove};
use super::{hosted_accounts, HostedCreated, ModuleDeleted, ModuleStored, ModuleVersion, Profile};
use super::{
    now, physics_of, seat_rating, status_of, token_of, AfterMove, MoveWrite, Status, Store,
    StoreError, StoredMatch, StoredSeat, Summary,
};
use crate::config::SyncMode;
use crate::store::checkpointer::{Checkpointer, Nudge};
use crate::store::readers::{Readers, READERS};
use crate::store::{RatingPoint, MAX_LISTED};
use game::name::AccountName;
use game::rating::{Rating, RatingSystem, Score};
use game::token::TokenHash;
use game::RecordedMove;
use prometheus_client::registry::Registry;
use rusqlite::{params, Connection, OptionalExtension};
use std::path::Path;
use std::sync::{Arc, Mutex, MutexGuard};

/// The SQLite store (see the module's documentation).
pub struct SqliteStore {
    /// Declared first, so dropped first: what is queued is written before
    /// the checkpointer stops.
    commit: GroupCommit,
    /// The writer's connection (and, for a store in memory, the readers').
    conn: Arc<Mutex<Connection>>,
    /// Read-only connections of a store on disk.
    readers: Option<Readers>,
    /// Tells the checkpointer that a write added to the log.
    nudge: Option<Nudge>,
    /// Copies the log into the database file (a store on disk only).
    _checkpointer: Option<Checkpointer>,
}

/// The size past which the writer empties the log file.
pub const LOG_LIMIT: u64 = 64 << 20;

/// How many times the writer tries to empty an overgrown log between two
/// group commits (1 ms apart) while a checkpoint on the checkpointer's
/// thread holds it busy.
const TRUNCATE_TRIES: usize = 20;

/// A store's write-ahead log file and the size it may reach.
struct Log {
    path: std::path::PathBuf,
    limit: u64,
}

/// The group commit's backend: the writer's connection.
struct Writer {
    conn: Arc<Mutex<Connection>>,
    nudge: Option<Nudge>,
    /// The log file of a store on disk, emptied past its limit.
    log: Option<Log>,
}

const SCHEMA: &str = "
CREATE TABLE IF NOT EXISTS matches (
    id TEXT PRIMARY KEY,
    created_at INTEGER NOT NULL,
    updated_at INTEGER NOT NULL,
    config TEXT NOT NULL,
    seed INTEGER NOT NULL,
    status TEXT NOT NULL,
    bot TEXT,
    turn_seconds INTEGER NOT NULL,
    first_name TEXT,
    first_token_hash TEXT,
    second_name TEXT,
    second_token_hash TEXT,
    shots INTEGER NOT NULL DEFAULT 0,
    result TEXT,
    rematch_of TEXT
);
CREATE INDEX IF NOT EXISTS matches_by_status ON matches (status, updated_at);
CREATE TABLE IF NOT EXISTS moves (
    match_id TEXT NOT NULL REFERENCES matches (id),
    idx INTEGER NOT NULL,
    body TEXT NOT NULL,
    PRIMARY KEY (match_id, idx)
);
";

/// The accounts, their passwords and keys (names unique in any case).
const ACCOUNT_TABLES: &str = "
CREATE TABLE IF NOT EXISTS accounts (
    name TEXT PRIMARY KEY COLLATE NOCASE,
    bot INTEGER NOT NULL,
    created_at INTEGER NOT NULL,
    rating REAL NOT NULL,
    deviation REAL NOT NULL,
    volatility REAL NOT NULL,
    games INTEGER NOT NULL DEFAULT 0
);
CREATE INDEX IF NOT EXISTS accounts_by_rating ON accounts (bot, rating DESC);
CREATE TABLE IF NOT EXISTS account_passwords (
    account TEXT PRIMARY KEY COLLATE NOCASE REFERENCES accounts (name),
    hash TEXT NOT NULL,
    set_at INTEGER NOT NULL
);
CREATE TABLE IF NOT EXISTS account_keys (
    hash TEXT PRIMARY KEY,
    account TEXT NOT NULL REFERENCES accounts (name) COLLATE NOCASE,
    created_at INTEGER NOT NULL,
    revoked_at INTEGER
);
";

/// Each rated match's rating after it, per account.
const RATING_TABLES: &str = "
CREATE TABLE IF NOT EXISTS rating_history (
    account TEXT NOT NULL COLLATE NOCASE REFERENCES accounts (name),
    match_id TEXT NOT NULL REFERENCES matches (id),
    at INTEGER NOT NULL,
    rating REAL NOT NULL,
    deviation REAL NOT NULL,
    volatility REAL NOT NULL,
    PRIMARY KEY (account, match_id)
);
CREATE INDEX IF NOT EXISTS rating_history_by_match ON rating_history (match_id);
CREATE INDEX IF NOT EXISTS matches_by_first_account ON matches (first_account COLLATE NOCASE, updated_at);
CREATE INDEX IF NOT EXISTS matches_by_second_account ON matches (second_account COLLATE NOCASE, updated_at);
";

/// The versions of hosted bots' modules: their bytes, the SHA-256 that
/// names each, when it was first uploaded, and which one the account
/// plays with (at most one per account).
const MODULE_TABLES: &str = "
CREATE TABLE IF NOT EXISTS bot_modules (
    account TEXT NOT NULL COLLATE NOCASE REFERENCES accounts (name),
    hash TEXT NOT NULL,
    size INTEGER NOT NULL,
    uploaded_at INTEGER NOT NULL,
    active INTEGER NOT NULL DEFAULT 0,
    module BLOB NOT NULL,
    PRIMARY KEY (account, hash)
);
CREATE UNIQUE INDEX IF NOT EXISTS bot_modules_one_active ON bot_modules (account) WHERE active;
";

/// Makes `account`'s version `hash` its only active one (two statements:
/// the one-active index is checked row by row).
fn set_active(tx: &rusqlite::Transaction<'_>, account: &str, hash: &str) -> Result<(), StoreError> {
    tx.execute(
        "UPDATE bot_modules SET active = 0 WHERE account = ?1 AND active",
        params![account],
    )?;
    tx.execute(
        "UPDATE bot_modules SET active = 1 WHERE account = ?1 AND hash = ?2",
        params![account, hash],
    )?;
    Ok(())
}

/// The version `hash` of `account`'s module, if it has one.
fn module_version(
    conn: &Connection,
    account: &str,
    hash: &str,
) -> Result<Option<ModuleVersion>, StoreError> {
    Ok(conn
        .query_row(
            "SELECT hash, size, uploaded_at, active FROM bot_modules WHERE account = ?1 AND hash = ?2",
            params![account, hash],
            |r| Ok(ModuleVersion::from_row(r.get(0)?, r.get(1)?, r.get(2)?, r.get(3)?)),
        )
        .optional()?)
}

/// Brings a store written before tokens were hashed up to date, in one
/// transaction: each plain seat token is replaced by its hash (so its
/// owner can still play) and the columns take their new names.
fn hash_plain_tokens(conn: &Connection) -> Result<(), StoreError> {
    let old: bool = conn.query_row(
        "SELECT count(*) FROM pragma_table_info('matches') WHERE name = 'first_token'",
        [],
        |row| row.get::<_, i64>(0).map(|n| n > 0),
    )?;
    if !old {
        return Ok(());
    }
    let tx = conn.unchecked_transaction()?;
    for column in ["first_token", "second_token"] {
        let plain: Vec<(String, String)> = tx
            .prepare(&format!(
                "SELECT id, {column} FROM matches WHERE {column} IS NOT NULL"
            ))?
            .query_map([], |row| Ok((row.get(0)?, row.get(1)?)))?
            .collect::<Result<_, _>>()?;
        for (id, token) in plain {
            tx.execute(
                &format!("UPDATE matches SET {column} = ?2 WHERE id = ?1"),
                params![id, TokenHash::of(&token).to_hex()],
            )?;
        }
        tx.execute_batch(&format!(
            "ALTER TABLE matches RENAME COLUMN {column} TO {column}_hash"
        ))?;
    }
    tx.commit()?;
    Ok(())
}

/// Adds the `physics` column to a `matches` table made before matches
/// kept their physics version (and to a new table: [`SCHEMA`] predates
/// it). Every match stored before then was played under version 1.
fn add_physics_column(conn: &Connection) -> Result<(), StoreError> {
    add_column(conn, "physics", "INTEGER NOT NULL DEFAULT 1")
}

/// Adds the columns of accounts to a `matches` table made before seats
/// had accounts: which account plays each seat, and whether the match is
/// rated (none of the matches stored before then is).
fn add_account_columns(conn: &Connection) -> Result<(), StoreError> {
    add_column(conn, "first_account", "TEXT")?;
    add_column(conn, "second_account", "TEXT")?;
    add_column(conn, "rated", "INTEGER NOT NULL DEFAULT 0")?;
    // A match's noise secret (NULL: a match keyed by its seed, from before).
    add_column(conn, "noise_secret", "TEXT")?;
    // The hosted module version playing each seat (NULL: none).
    add_column(conn, "first_module", "TEXT")?;
    add_column(conn, "second_module", "TEXT")?;
    // The public seed of a seeded casual match (NULL: a secret one).
    add_column(conn, "public_seed", "INTEGER")
}

/// Adds `column` to the `matches` table unless it has it.
fn add_column(conn: &Connection, column: &str, definition: &str) -> Result<(), StoreError> {
    let mut stmt = conn.prepare("PRAGMA table_info(matches)")?;
    let columns = stmt
        .query_map([], |r| r.get::<_, String>("name"))?
        .collect::<Result<Vec<_>, _>>()?;
    if !columns.iter().any(|c| c == column) {
        conn.execute_batch(&format!(
            "ALTER TABLE matches ADD COLUMN {column} {definition}"
        ))?;
    }
    Ok(())
}

/// Creates what a new store lacks and brings an older one up to date.
fn migrate(conn: &Connection) -> Result<(), StoreError> {
    conn.execute_batch(SCHEMA)?;
    hash_plain_tokens(conn)?;
    add_physics_column(conn)?;
    add_account_columns(conn)?;
    conn.execute_batch(ACCOUNT_TABLES)?;
    conn.execute_batch(RATING_TABLES)?;
    conn.execute_batch(MODULE_TABLES)?;
    conn.execute_batch(HOSTED_TABLES)?;
    let start = RatingSystem::default().start;
    for name in crate::store::computer_accounts() {
        conn.execute(
            "INSERT OR IGNORE INTO accounts (name, bot, created_at, rating, deviation, volatility)
             VALUES (?1, 1, ?2, ?3, ?4, ?5)",
            params![
                name,
                now() as i64,
                start.rating,
                start.deviation,
                start.volatility
            ],
        )?;
    }
    Ok(())
}

/// The store's file in its data folder.
pub const FILE_NAME: &str = "chapaev.sqlite3";

impl SqliteStore {
    /// Opens (creating if needed) `DIR/chapaev.sqlite3`.
    pub fn open(dir: &Path, sync: SyncMode) -> Result<SqliteStore, StoreError> {
        SqliteStore::open_with_log_limit(dir, sync, LOG_LIMIT)
    }

    /// [`SqliteStore::open`] with the size past which the log file is
    /// emptied.
    pub fn open_with_log_limit(
        dir: &Path,
        sync: SyncMode,
        log_limit: u64,
    ) -> Result<SqliteStore, StoreError> {
        std::fs::create_dir_all(dir).map_err(|source| StoreError::DataDir {
            path: dir.display().to_string(),
            source,
        })?;
        let path = dir.join(FILE_NAME);
        let conn = Connection::open(&path)?;
        // In log mode before the checkpointer's connection opens the file.
        conn.pragma_update(None, "journal_mode", "WAL")?;
        // Checkpoints run on their own thread, never inside a commit; a log
        // that a burst grew past 64 MiB is cut back when it starts over.
        conn.pragma_update(None, "wal_autocheckpoint", 0)?;
        conn.pragma_update(None, "journal_size_limit", log_limit as i64)?;
        let checkpointer = Checkpointer::start(&path, sync)?;
        let mut log = path.clone().into_os_string();
        log.push("-wal");
        let log = Log {
            path: log.into(),
            limit: log_limit,
        };
        SqliteStore::with_connection(conn, sync, Some((checkpointer, &path, log)))
    }

    /// A store in memory (tests).
    pub fn in_memory() -> Result<SqliteStore, StoreError> {
        SqliteStore::with_connection(Connection::open_in_memory()?, SyncMode::Normal, None)
    }

    /// The store on `conn`; on disk, also the checkpointer and the read
    /// connections to the file at the path.
    fn with_connection(
        conn: Connection,
        sync: SyncMode,
        on_disk: Option<(Checkpointer, &Path, Log)>,
    ) -> Result<SqliteStore, StoreError> {
        conn.pragma_update(None, "journal_mode", "WAL")?;
        conn.pragma_update(None, "synchronous", sync.pragma())?;
        conn.pragma_update(None, "foreign_keys", "ON")?;
        conn.busy_timeout(std::time::Duration::from_secs(5))?;
        migrate(&conn)?;
        let (checkpointer, readers, log) = match on_disk {
            Some((c, path, log)) => (Some(c), Some(Readers::open(path, READERS)?), Some(log)),
            None => (None, None, None),
        };
        let conn = Arc::new(Mutex::new(conn));
        let nudge = checkpointer.as_ref().map(Checkpointer::nudger);
        let commit = GroupCommit::start(Writer {
            conn: conn.clone(),
            nudge: nudge.clone(),
            log,
        })?;
        Ok(SqliteStore {
            commit,
            conn,
            readers,
            nudge,
            _checkpointer: checkpointer,
        })
    }

    /// The writer's connection.
    pub(crate) fn lock(&self) -> Result<MutexGuard<'_, Connection>, StoreError> {
        self.conn.lock().map_err(|_| StoreError::Poisoned)
    }

    /// A connection for reading: a free read connection, never the writer's
    /// (but for a store in memory, which has no other).
    fn read(&self) -> Result<MutexGuard<'_, Connection>, StoreError> {
        match &self.readers {
            Some(readers) => readers.get().map_err(|_| StoreError::Poisoned),
            None => self.lock(),
        }
    }

    /// Tells the checkpointer the log grew.
    fn log_grew(&self) {
        if let Some(n) = &self.nudge {
            n.nudge();
        }
    }

    fn row_to_match(row: &rusqlite::Row<'_>) -> rusqlite::Result<(StoredMatchRaw, String)> {
        Ok((
            StoredMatchRaw {
                id: row.get(0)?,
                created_at: row.get::<_, i64>(1)?,
                seed: row.get::<_, i64>(3)?,
                noise_secret: row.get(16)?,
                status: row.get(4)?,
                bot: row.get(5)?,
                turn_seconds: row.get::<_, i64>(6)?,
                first_name: row.get(7)?,
                first_token_hash: row.get(8)?,
                second_name: row.get(9)?,
                second_token_hash: row.get(10)?,
                rematch_of: row.get(11)?,
                physics: row.get(12)?,
                accounts: [row.get(13)?, row.get(14)?],
                modules: [row.get(17)?, row.get(18)?],
                rated: row.get(15)?,
                public_seed: row.get(19)?,
            },
            row.get(2)?,
        ))
    }

    /// The summaries of the matches that `condition` (on `m`, the match,
    /// with `?1` bound to `param`) selects, most recently played first.
    fn summaries_where(
        &self,
        condition: &str,
        param: impl rusqlite::ToSql,
        limit: usize,
    ) -> Result<Vec<Summary>, StoreError> {
        let conn = self.read()?;
        let mut stmt = conn.prepare(&format!(
            "SELECT {SUMMARY_COLUMNS} FROM {SUMMARY_FROM} WHERE {condition}
             ORDER BY m.updated_at DESC, m.id LIMIT ?2"
        ))?;
        let rows = stmt
            .query_map(params![param, limit as i64], SummaryRaw::read)?
            .collect::<Result<Vec<_>, _>>()?;
        rows.into_iter().map(SummaryRaw::finish).collect()
    }
}

/// The columns of a match row, in the order [`SqliteStore::row_to_match`]
/// reads them.
pub(crate) const MATCH_COLUMNS: &str = "id, created_at, config, seed, status, bot, turn_seconds,
    first_name, first_token_hash, second_name, second_token_hash, rematch_of, physics,
    first_account, second_account, rated, noise_secret, first_module, second_module, public_seed";

/// A summary's columns, read from `matches` joined to the seats' accounts
/// (`a` and `b`).
pub(crate) const SUMMARY_COLUMNS: &str = "m.id, m.status, m.created_at, m.updated_at, m.first_name,
    m.second_name, m.bot, m.shots, m.turn_seconds, m.result, m.physics, m.rated,
    a.rating, a.deviation, b.rating, b.deviation, m.noise_secret, m.public_seed";

/// The tables a summary reads.
const SUMMARY_FROM: &str = "matches m
    LEFT JOIN accounts a ON a.name = m.first_account
    LEFT JOIN accounts b ON b.name = m.second_account";

/// An account's columns, in the order [`profile`] reads them.
const PROFILE_COLUMNS: &str = "name, bot, created_at, rating, deviation, games";

fn profile(row: &rusqlite::Row<'_>) -> rusqlite::Result<Profile> {
    Ok(Profile::from_row(
        row.get(0)?,
        row.get(1)?,
        row.get(2)?,
        row.get(3)?,
        row.get(4)?,
        row.get(5)?,
    ))
}

/// Inserts a new match's row (no moves yet).
fn insert_match(conn: &Connection, m: &StoredMatch) -> Result<(), StoreError> {
    let (seed, secret) = super::noise_columns(&m.noise);
    let t = now();
    conn.execute(
        "INSERT INTO matches (id, created_at, updated_at, config, seed, status, bot, turn_seconds,
                              first_name, first_token_hash, second_name, second_token_hash, rematch_of,
                              physics, first_account, second_account, rated, noise_secret,
                              first_module, second_module, public_seed)
         VALUES (?1, ?2, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14, ?15, ?16, ?17,
                 ?18, ?19, ?20)",
        params![
            m.id,
            t as i64,
            serde_json::to_string(&m.config)?,
            seed,
            m.status.as_str(),
            m.bot,
            m.turn_seconds as i64,
            m.seats[0].name,
            m.seats[0].token.map(|h| h.to_hex()),
            m.seats[1].name,
            m.seats[1].token.map(|h| h.to_hex()),
            m.rematch_of,
            m.physics,
            m.seats[0].account,
            m.seats[1].account,
            m.rated,
            secret,
            m.seats[0].module,
            m.seats[1].module,
            m.seed.map(|s| s as i64),
        ],
    )?;
    Ok(())
}

/// The hosted bots' ladder claims: one row per bot ever paired on the
/// ladder, naming the match it was last claimed for; a claim whose match
/// is finished is free to take again ([`Store::create_hosted`]).
const HOSTED_TABLES: &str = "
CREATE TABLE IF NOT EXISTS hosted_ladder (
    account TEXT PRIMARY KEY COLLATE NOCASE,
    match_id TEXT NOT NULL
);
";

/// Whether a match not finished yet plays a seat with version `?2` of
/// account `?1`'s module.
const MODULE_IN_USE: &str = "SELECT EXISTS (SELECT 1 FROM matches WHERE status <> 'finished'
    AND ((lower(first_account) = lower(?1) AND first_module = ?2)
      OR (lower(second_account) = lower(?1) AND second_module = ?2)))";

/// The accounts of the hosted seats of the matches not finished yet.
const HOSTED_SEATS: &str = "
    SELECT first_account FROM matches
     WHERE status IN ('open', 'live') AND first_module IS NOT NULL AND first_account IS NOT NULL
    UNION ALL
    SELECT second_account FROM matches
     WHERE status IN ('open', 'live') AND second_module IS NOT NULL AND second_account IS NOT NULL
    LIMIT ?1";

impl Store for SqliteStore {
    fn backend(&self) -> &'static str {
        "sqlite"
    }

    fn create(&self, m: &StoredMatch) -> Result<(), StoreError> {
        insert_match(&*self.lock()?, m)?;
        self.log_grew();
        Ok(())
    }

    fn create_hosted(&self, m: &StoredMatch, ladder: bool) -> Result<HostedCreated, StoreError> {
        let mut conn = self.lock()?;
        let tx = conn.transaction()?;
        let hosted = hosted_accounts(m);
        for (account, hash) in &hosted {
            if module_version(&tx, account, hash)?.is_none() {
                return Ok(HostedCreated::NoVersion(account.to_string()));
            }
        }
        insert_match(&tx, m)?;
        if ladder {
            for (account, _) in &hosted {
                let claimed = tx.execute(
                    "INSERT INTO hosted_ladder (account, match_id) VALUES (?1, ?2)
                     ON CONFLICT (account) DO UPDATE SET match_id = excluded.match_id
                     WHERE EXISTS (SELECT 1 FROM matches f
                                   WHERE f.id = hosted_ladder.match_id AND f.status = 'finished')",
                    params![account, m.id],
                )?;
                if claimed != 1 {
                    return Ok(HostedCreated::Busy(account.to_string()));
                }
            }
        }
        tx.commit()?;
        self.log_grew();
        Ok(HostedCreated::Created)
    }

    fn hosted_seats(&self, limit: usize) -> Result<Vec<String>, StoreError> {
        let conn = self.read()?;
        let mut stmt = conn.prepare(HOSTED_SEATS)?;
        let rows = stmt
            .query_map(params![limit as i64], |r| r.get(0))?
            .collect::<Result<Vec<_>, _>>()?;
        Ok(rows)
    }

    fn seat_second(
        &self,
        id: &str,
        name: &str,
        token: &TokenHash,
        account: Option<&str>,
    ) -> Result<(), StoreError> {
        let conn = self.lock()?;
        let n = conn.execute(
            "UPDATE matches SET second_name = ?2, second_token_hash = ?3, second_account = ?5,
                                status = 'live', updated_at = ?4
             WHERE id = ?1 AND second_token_hash IS NULL AND bot IS NULL",
            params![id, name, token.to_hex(), now() as i64, account],
        )?;
        self.log_grew();
        if n != 1 {
            return Err(StoreError::Corrupt(format!(
                "match {id} has no empty second seat"
            )));
        }
        Ok(())
    }

    fn submit_move(
        &self,
        id: &str,
        index: usize,
        m: &RecordedMove,
        after: &AfterMove<'_>,
    ) -> Result<MoveWrite, StoreError> {
        self.commit.submit(id, index, m, after)
    }

    fn get(&self, id: &str) -> Result<Option<StoredMatch>, StoreError> {
        let conn = self.read()?;
        let raw = conn
            .query_row(
                &format!("SELECT {MATCH_COLUMNS} FROM matches WHERE id = ?1"),
                params![id],
                Self::row_to_match,
            )
            .optional()?;
        raw.map(|(r, config)| r.finish(&config)).transpose()
    }

    fn live(&self) -> Result<Vec<String>, StoreError> {
        let conn = self.read()?;
        let mut stmt = conn
            .prepare("SELECT id FROM matches WHERE status = 'live' ORDER BY updated_at DESC, id")?;
        let ids = stmt
            .query_map([], |r| r.get::<_, String>(0))?
            .collect::<Result<Vec<_>, _>>()?;
        Ok(ids)
    }

    fn match_ids(&self, after: Option<&str>, limit: usize) -> Result<Vec<String>, StoreError> {
        let conn = self.read()?;
        let mut stmt = conn
            .prepare("SELECT id FROM matches WHERE ?1 IS NULL OR id > ?1 ORDER BY id LIMIT ?2")?;
        let limit = i64::try_from(limit).unwrap_or(i64::MAX);
        let ids = stmt
            .query_map(params![after, limit], |r| r.get::<_, String>(0))?
            .collect::<Result<Vec<_>, _>>()?;
        Ok(ids)
    }

    fn expire_open(
        &self,
        older_than: u64,
        keep: &dyn Fn(&str) -> bool,
    ) -> Result<Vec<String>, StoreError> {
        let cutoff = now().saturating_sub(older_than) as i64;
        let conn = self.lock()?;
        let tx = conn.unchecked_transaction()?;
        let stale: Vec<String> = tx
            .prepare("SELECT id FROM matches WHERE status = 'open' AND updated_at < ?1")?
            .query_map(params![cutoff], |r| r.get(0))?
            .collect::<Result<_, _>>()?;
        let expired: Vec<String> = stale.into_iter().filter(|id| !keep(id)).collect();
        for id in &expired {
            tx.execute("DELETE FROM moves WHERE match_id = ?1", params![id])?;
            tx.execute(
                "DELETE FROM matches WHERE id = ?1 AND status = 'open'",
                params![id],
            )?;
        }
        tx.commit()?;
        if !expired.is_empty() {
            self.log_grew();
        }
        Ok(expired)
    }

    fn moves(&self, id: &str) -> Result<Vec<RecordedMove>, StoreError> {
        let conn = self.read()?;
        let mut stmt =
            conn.prepare("SELECT idx, body FROM moves WHERE match_id = ?1 ORDER BY idx")?;
        let rows = stmt
            .query_map(params![id], |r| {
                Ok((r.get::<_, i64>(0)?, r.get::<_, String>(1)?))
            })?
            .collect::<Result<Vec<_>, _>>()?;
        super::moves_in_order(id, rows)
    }

    fn list(&self, status: Option<Status>, limit: usize) -> Result<Vec<Summary>, StoreError> {
        self.summaries_where(
            "?1 IS NULL OR m.status = ?1",
            status.map(Status::as_str),
            limit,
        )
    }

    fn summary(&self, id: &str) -> Result<Option<Summary>, StoreError> {
        let conn = self.read()?;
        let raw = conn
            .query_row(
                &format!("SELECT {SUMMARY_COLUMNS} FROM {SUMMARY_FROM} WHERE m.id = ?1"),
                params![id],
                SummaryRaw::read,
            )
            .optional()?;
        raw.map(SummaryRaw::finish).transpose()
    }

    fn matches_of(&self, account: &str, limit: usize) -> Result<Vec<Summary>, StoreError> {
        self.summaries_where(
            "m.first_account = ?1 COLLATE NOCASE OR m.second_account = ?1 COLLATE NOCASE",
            account,
            limit.min(MAX_LISTED),
        )
    }

    fn insert_account(
        &self,
        name: &AccountName,
        bot: bool,
        start: Rating,
        key: &TokenHash,
    ) -> Result<bool, StoreError> {
        let mut conn = self.lock()?;
        let tx = conn.transaction()?;
        let taken: bool = tx.query_row(
            "SELECT count(*) FROM accounts WHERE name = ?1",
            params![name.as_str()],
            |r| r.get::<_, i64>(0).map(|n| n > 0),
        )?;
        if taken {
            return Ok(false);
        }
        let t = now() as i64;
        tx.execute(
            "INSERT INTO accounts (name, bot, created_at, rating, deviation, volatility)
             VALUES (?1, ?2, ?3, ?4, ?5, ?6)",
            params![
                name.as_str(),
                bot,
                t,
                start.rating,
                start.deviation,
                start.volatility
            ],
        )?;
        tx.execute(
            "INSERT INTO account_keys (hash, account, created_at) VALUES (?1, ?2, ?3)",
            params![key.to_hex(), name.as_str(), t],
        )?;
        tx.commit()?;
        self.log_grew();
        Ok(true)
    }

    fn account(&self, name: &str) -> Result<Option<Profile>, StoreError> {
        let conn = self.read()?;
        Ok(conn
            .query_row(
                &format!("SELECT {PROFILE_COLUMNS} FROM accounts WHERE name = ?1"),
                params![name],
                profile,
            )
            .optional()?)
    }

    fn key(&self, hash: &TokenHash) -> Result<Option<(String, String)>, StoreError> {
        let conn = self.read()?;
        Ok(conn
            .query_row(
                "SELECT hash, account FROM account_keys WHERE hash = ?1 AND revoked_at IS NULL",
                params![hash.to_hex()],
                |r| Ok((r.get(0)?, r.get(1)?)),
            )
            .optional()?)
    }

    fn insert_key(&self, account: &str, hash: &TokenHash) -> Result<(), StoreError> {
        self.lock()?.execute(
            "INSERT INTO account_keys (hash, account, created_at) VALUES (?1, ?2, ?3)",
            params![hash.to_hex(), account, now() as i64],
        )?;
        self.log_grew();
        Ok(())
    }

    fn revoke(&self, hash: &TokenHash) -> Result<bool, StoreError> {
        let n = self.lock()?.execute(
            "UPDATE account_keys SET revoked_at = ?2 WHERE hash = ?1 AND revoked_at IS NULL",
            params![hash.to_hex(), now() as i64],
        )?;
        self.log_grew();
        Ok(n == 1)
    }

    fn put_password(&self, account: &str, hash: &str) -> Result<(), StoreError> {
        self.lock()?.execute(
            "INSERT INTO account_passwords (account, hash, set_at) VALUES (?1, ?2, ?3)
             ON CONFLICT (account) DO UPDATE SET hash = ?2, set_at = ?3",
            params![account, hash, now() as i64],
        )?;
        self.log_grew();
        Ok(())
    }

    fn password(&self, name: &str) -> Result<Option<(String, String)>, StoreError> {
        Ok(self
            .read()?
            .query_row(
                "SELECT account, hash FROM account_passwords WHERE account = ?1",
                params![name],
                |r| Ok((r.get(0)?, r.get(1)?)),
            )
            .optional()?)
    }

    fn leaderboard(&self, bots: bool, limit: usize) -> Result<Vec<Profile>, StoreError> {
        let conn = self.read()?;
        let mut stmt = conn.prepare(&format!(
            "SELECT {PROFILE_COLUMNS} FROM accounts WHERE bot = ?1
               AND (created_at >= ?4 OR EXISTS (SELECT 1 FROM rating_history h
                    WHERE h.account = accounts.name AND h.at >= ?4))
             ORDER BY deviation > ?2, rating DESC, name LIMIT ?3"
        ))?;
        let rows = stmt
            .query_map(
                params![
                    bots,
                    RatingSystem::default().provisional_above,
                    limit.min(super::MAX_LEADERBOARD) as i64,
                    super::leaderboard_cutoff()
                ],
                profile,
            )?
            .collect::<Result<Vec<_>, _>>()?;
        Ok(rows)
    }

    fn rating_history(&self, account: &str, limit: usize) -> Result<Vec<RatingPoint>, StoreError> {
        let conn = self.read()?;
        let mut stmt = conn.prepare(
            "SELECT match_id, at, rating, deviation FROM (
                 SELECT match_id, at, rating, deviation, rowid FROM rating_history
                 WHERE account = ?1 ORDER BY at DESC, rowid DESC LIMIT ?2
             ) ORDER BY at, rowid",
        )?;
        let points = stmt
            .query_map(params![account, limit.min(MAX_LISTED) as i64], |r| {
                Ok(RatingPoint::from_row(
                    r.get(0)?,
                    r.get(1)?,
                    r.get(2)?,
                    r.get(3)?,
                ))
            })?
            .collect::<Result<Vec<_>, _>>()?;
        Ok(points)
    }

    fn insert_module(
        &self,
        account: &str,
        hash: &str,
        bytes: &[u8],
        max_versions: usize,
    ) -> Result<ModuleStored, StoreError> {
        let mut conn = self.lock()?;
        let tx = conn.transaction()?;
        let stored = match module_version(&tx, account, hash)? {
            Some(v) => ModuleStored::Existing(ModuleVersion { active: true, ..v }),
            None => {
                let held: i64 = tx.query_row(
                    "SELECT count(*) FROM bot_modules WHERE account = ?1",
                    params![account],
                    |r| r.get(0),
                )?;
                if held >= max_versions as i64 {
                    return Ok(ModuleStored::TooMany {
                        limit: max_versions,
                    });
                }
                let at = now() as i64;
                tx.execute(
                    "INSERT INTO bot_modules (account, hash, size, uploaded_at, module)
                     VALUES (?1, ?2, ?3, ?4, ?5)",
                    params![account, hash, bytes.len() as i64, at, bytes],
                )?;
                ModuleStored::New(ModuleVersion::from_row(
                    hash.to_string(),
                    bytes.len() as i64,
                    at,
                    true,
                ))
            }
        };
        set_active(&tx, account, hash)?;
        tx.commit()?;
        self.log_grew();
        Ok(stored)
    }

    fn modules(&self, account: &str) -> Result<Vec<ModuleVersion>, StoreError> {
        let conn = self.read()?;
        let mut stmt = conn.prepare(
            "SELECT hash, size, uploaded_at, active FROM bot_modules WHERE account = ?1
             ORDER BY uploaded_at DESC, rowid DESC",
        )?;
        let rows = stmt
            .query_map(params![account], |r| {
                Ok(ModuleVersion::from_row(
                    r.get(0)?,
                    r.get(1)?,
                    r.get(2)?,
                    r.get(3)?,
                ))
            })?
            .collect::<Result<Vec<_>, _>>()?;
        Ok(rows)
    }

    fn activate_module(
        &self,
        account: &str,
        hash: &str,
    ) -> Result<Option<ModuleVersion>, StoreError> {
        let mut conn = self.lock()?;
        let tx = conn.transaction()?;
        let Some(version) = module_version(&tx, account, hash)? else {
            return Ok(None);
        };
        set_active(&tx, account, hash)?;
        tx.commit()?;
        self.log_grew();
        Ok(Some(ModuleVersion {
            active: true,
            ..version
        }))
    }

    fn delete_module(&self, account: &str, hash: &str) -> Result<ModuleDeleted, StoreError> {
        let mut conn = self.lock()?;
        let tx = conn.transaction()?;
        let deleted = match module_version(&tx, account, hash)? {
            None => ModuleDeleted::Missing,
            Some(v) if v.active => ModuleDeleted::Active,
            Some(_)
                if tx.query_row(MODULE_IN_USE, params![account, hash], |r| {
                    r.get::<_, bool>(0)
                })? =>
            {
                ModuleDeleted::InUse
            }
            Some(_) => {
                tx.execute(
                    "DELETE FROM bot_modules WHERE account = ?1 AND hash = ?2",
                    params![account, hash],
                )?;
                ModuleDeleted::Deleted
            }
        };
        tx.commit()?;
        self.log_grew();
        Ok(deleted)
    }

    fn active_module(&self, account: &str) -> Result<Option<(ModuleVersion, Vec<u8>)>, StoreError> {
        Ok(self
            .read()?
            .query_row(
                "SELECT hash, size, uploaded_at, active, module FROM bot_modules
                 WHERE account = ?1 AND active",
                params![account],
                |r| {
                    Ok((
                        ModuleVersion::from_row(r.get(0)?, r.get(1)?, r.get(2)?, r.get(3)?),
                        r.get(4)?,
                    ))
                },
            )
            .optional()?)
    }

    fn module_bytes(&self, account: &str, hash: &str) -> Result<Option<Vec<u8>>, StoreError> {
        Ok(self
            .read()?
            .query_row(
                "SELECT module FROM bot_modules WHERE account = ?1 AND hash = ?2",
                params![account, hash],
                |r| r.get(0),
            )
            .optional()?)
    }

    fn hosted_bots(&self, limit: usize) -> Result<Vec<Profile>, StoreError> {
        let conn = self.read()?;
        let mut stmt = conn.prepare(&format!(
            "SELECT {PROFILE_COLUMNS} FROM accounts
             WHERE bot AND name IN (SELECT account FROM bot_modules WHERE active)
             ORDER BY name LIMIT ?1"
        ))?;
        let rows = stmt
            .query_map(params![limit as i64], profile)?
            .collect::<Result<Vec<_>, _>>()?;
        Ok(rows)
    }

    fn register_metrics(&self, registry: &mut Registry) {
        self.commit.register_metrics(registry);
    }

    fn checkpoint(&self) -> Result<(), StoreError> {
        let conn = self.lock()?;
        conn.query_row("PRAGMA wal_checkpoint(TRUNCATE)", [], |_| Ok(()))?;
        Ok(())
    }
}

struct SummaryRaw {
    id: String,
    status: String,
    created_at: i64,
    updated_at: i64,
    first: Option<String>,
    second: Option<String>,
    bot: Option<String>,
    shots: i64,
    turn_seconds: i64,
    result: Option<String>,
    physics: i64,
    rated: bool,
    /// Each seat's account's rating and deviation.
    ratings: [(Option<f64>, Option<f64>); 2],
    noise_secret: Option<String>,
    public_seed: Option<i64>,
}

impl SummaryRaw {
    fn read(r: &rusqlite::Row<'_>) -> rusqlite::Result<SummaryRaw> {
        Ok(SummaryRaw {
            id: r.get(0)?,
            status: r.get(1)?,
            created_at: r.get(2)?,
            updated_at: r.get(3)?,
            first: r.get(4)?,
            second: r.get(5)?,
            bot: r.get(6)?,
            shots: r.get(7)?,
            turn_seconds: r.get(8)?,
            result: r.get(9)?,
            physics: r.get(10)?,
            rated: r.get(11)?,
            ratings: [(r.get(12)?, r.get(13)?), (r.get(14)?, r.get(15)?)],
            noise_secret: r.get(16)?,
            public_seed: r.get(17)?,
        })
    }

    fn finish(self) -> Result<Summary, StoreError> {
        let physics = physics_of(&self.id, self.physics)?;
        let noise_commitment = super::commitment_of(&self.id, self.noise_secret)?;
        Ok(Summary {
            noise_commitment,
            seed: self.public_seed.map(|s| s as u64),
            physics,
            playable: game::PhysicsVersion::from_number(physics).is_ok(),
            status: status_of(&self.id, &self.status)?,
            match_id: self.id,
            created_at: self.created_at as u64,
            updated_at: self.updated_at as u64,
            first: self.first,
            second: self.second,
            bot: self.bot,
            shots: self.shots as u32,
            turn_seconds: self.turn_seconds as u64,
            result: self.result.map(|r| serde_json::from_str(&r)).transpose()?,
            rated: self.rated,
            first_rating: seat_rating(self.ratings[0]),
            second_rating: seat_rating(self.ratings[1]),
        })
    }
}

struct StoredMatchRaw {
    id: String,
    created_at: i64,
    seed: i64,
    noise_secret: Option<String>,
    status: String,
    bot: Option<String>,
    turn_seconds: i64,
    first_name: Option<String>,
    first_token_hash: Option<String>,
    second_name: Option<String>,
    second_token_hash: Option<String>,
    rematch_of: Option<String>,
    physics: i64,
    accounts: [Option<String>; 2],
    modules: [Option<String>; 2],
    rated: bool,
    public_seed: Option<i64>,
}

impl StoredMatchRaw {
    fn finish(self, config: &str) -> Result<StoredMatch, StoreError> {
        let tokens = [
            token_of(&self.id, self.first_token_hash)?,
            token_of(&self.id, self.second_token_hash)?,
        ];
        let [first_account, second_account] = self.accounts;
        let [first_module, second_module] = self.modules;
        Ok(StoredMatch {
            physics: physics_of(&self.id, self.physics)?,
            config: serde_json::from_str(config)?,
            created_at: self.created_at as u64,
            noise: super::noise_of(&self.id, self.seed, self.noise_secret)?,
            status: status_of(&self.id, &self.status)?,
            bot: self.bot,
            turn_seconds: self.turn_seconds as u64,
            seats: [
                StoredSeat {
                    name: self.first_name,
                    token: tokens[0],
                    account: first_account,
                    module: first_module,
                },
                StoredSeat {
                    name: self.second_name,
                    token: tokens[1],
                    account: second_account,
                    module: second_module,
                },
            ],
            rematch_of: self.rematch_of,
            rated: self.rated,
            seed: self.public_seed.map(|s| s as u64),
            id: self.id,
        })
    }
}

impl BatchWriter for Writer {
    fn write(&mut self, batch: &[QueuedMove]) -> Vec<Result<(), StoreError>> {
        let Ok(mut conn) = self.conn.lock() else {
            return batch.iter().map(|_| Err(StoreError::Poisoned)).collect();
        };
        let mut tx = match conn.transaction() {
            Ok(tx) => tx,
            Err(e) => {
                return batch
                    .iter()
                    .map(|_| Err(StoreError::GroupCommit(e.to_string())))
                    .collect();
            }
        };
        let results: Vec<_> = batch.iter().map(|m| write_one(&mut tx, m)).collect();
        let committed = tx.commit();
        if let Some(n) = &self.nudge {
            n.nudge();
        }
        match committed {
            Ok(()) => results,
            Err(e) => batch
                .iter()
                .map(|_| Err(StoreError::GroupCommit(e.to_string())))
                .collect(),
        }
    }

    /// Under a steady stream of commits the checkpointer's passive
    /// checkpoints never catch up and the log never starts over (it grew by
    /// 65 MB a second at 4,900 moves a second). Past its limit, the writer
    /// empties it itself between two group commits, the only moment
    /// without a writer: the moves queued meanwhile wait for the copy of
    /// what the passive checkpoints left, and go in the next group.
    fn after_batch(&mut self) {
        let Some(log) = &self.log else {
            return;
        };
        let size = std::fs::metadata(&log.path).map(|m| m.len()).unwrap_or(0);
        if size <= log.limit {
            return;
        }
        let Ok(conn) = self.conn.lock() else {
            return;
        };
        // Busy while the checkpointer's own (passive) checkpoint runs: that
        // one ends soon, so try again a few times rather than let the log
        // grow until the next commit (it did, on a loaded machine).
        for _ in 0..TRUNCATE_TRIES {
            match conn.query_row("PRAGMA wal_checkpoint(TRUNCATE)", [], |r| {
                r.get::<_, i64>(0)
            }) {
                Ok(0) => return,
                Ok(_) => std::thread::sleep(std::time::Duration::from_millis(1)),
                Err(e) => {
                    tracing::warn!(error = %e, size, "emptying the log failed; the next commit retries");
                    return;
                }
            }
        }
    }
}

/// One move and its match row, undone alone if either fails.
fn write_one(tx: &mut rusqlite::Transaction<'_>, m: &QueuedMove) -> Result<(), StoreError> {
    let sp = tx.savepoint()?;
    // Cached: the same two statements run for every move.
    sp.prepare_cached("INSERT INTO moves (match_id, idx, body) VALUES (?1, ?2, ?3)")?
        .execute(params![m.id, m.index, m.body])?;
    let n = sp
        .prepare_cached(
            "UPDATE matches SET status = ?2, shots = ?3, result = ?4, updated_at = ?5 WHERE id = ?1",
        )?
        .execute(params![m.id, m.status, m.shots, m.result, now() as i64])?;
    if n != 1 {
        // Dropping the savepoint unfinished rolls it back.
        return Err(StoreError::Corrupt(format!("no match {}", m.id)));
    }
    if let Some(score) = m.score {
        rate_finished(&sp, &m.id, score)?;
    }
    sp.commit()?;
    Ok(())
}

/// An account's rating as stored.
fn rating_of(conn: &Connection, account: &str) -> Result<Rating, StoreError> {
    let (r, d, v) = conn.query_row(
        "SELECT rating, deviation, volatility FROM accounts WHERE name = ?1",
        params![account],
        |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?)),
    )?;
    Rating::new(r, d, v).map_err(|e| StoreError::Corrupt(format!("account {account}: {e}")))
}

/// Rates match `id`, just finished with the first seat's `score`, in the
/// caller's transaction ([`crate::store`] says when and how).
fn rate_finished(conn: &Connection, id: &str, score: Score) -> Result<(), StoreError> {
    let row: Option<(bool, Option<String>, Option<String>)> = conn
        .prepare_cached("SELECT rated, first_account, second_account FROM matches WHERE id = ?1")?
        .query_row(params![id], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?)))
        .optional()?;
    let Some((true, Some(first), Some(second))) = row else {
        return Ok(());
    };
    let done: i64 = conn.query_row(
        "SELECT count(*) FROM rating_history WHERE match_id = ?1",
        params![id],
        |r| r.get(0),
    )?;
    if done > 0 {
        return Ok(());
    }
    let (a, b) = RatingSystem::default().after_match(
        rating_of(conn, &first)?,
        rating_of(conn, &second)?,
        score,
    );
    let at = now() as i64;
    for (account, r) in [(&first, a), (&second, b)] {
        conn.execute(
            "UPDATE accounts SET rating = ?2, deviation = ?3, volatility = ?4, games = games + 1
             WHERE name = ?1",
            params![account, r.rating, r.deviation, r.volatility],
        )?;
        conn.execute(
            "INSERT INTO rating_history (account, match_id, at, rating, deviation, volatility)
             VALUES (?1, ?2, ?3, ?4, ?5, ?6)",
            params![account, id, at, r.rating, r.deviation, r.volatility],
        )?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::store::tests::{stored, LIVE};
    use game::Side;
    use std::time::Instant;

    #[test]
    fn the_store_keeps_only_token_hashes_and_hashes_those_an_older_store_kept_plain() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("chapaev.sqlite3");
        {
            // A store as written before tokens were hashed.
            let conn = Connection::open(&path).unwrap();
            let old = SCHEMA
                .replace("first_token_hash", "first_token")
                .replace("second_token_hash", "second_token");
            conn.execute_batch(&old).unwrap();
            conn.execute(
                "INSERT INTO matches (id, created_at, updated_at, config, seed, status, turn_seconds,
                                      first_name, first_token, second_name, second_token)
                 VALUES ('old', 0, 0, '{}', 1, 'live', 60, 'Petka', 'plain-a', 'Anka', 'plain-b')",
                [],
            )
            .unwrap();
        }
        {
            let store = SqliteStore::open(dir.path(), SyncMode::Full).unwrap();
            let old = store.get("old").unwrap().unwrap();
            assert_eq!(old.seats[0].token, Some(TokenHash::of("plain-a")));
            assert_eq!(old.seats[1].token, Some(TokenHash::of("plain-b")));
            store.create(&stored("new")).unwrap();
        }
        // Nothing in the file is a token any more, and it opens again.
        let store = SqliteStore::open(dir.path(), SyncMode::Full).unwrap();
        assert_eq!(
            store.get("new").unwrap().unwrap().seats[0].token,
            Some(TokenHash::of("t1"))
        );
        let conn = Connection::open(&path).unwrap();
        let texts: Vec<String> = conn
            .prepare(
                "SELECT first_token_hash || ' ' || second_token_hash FROM matches WHERE id = 'old'",
            )
            .unwrap()
            .query_map([], |row| row.get(0))
            .unwrap()
            .collect::<Result<_, _>>()
            .unwrap();
        assert!(!texts[0].contains("plain"), "{texts:?}");
    }

    #[test]
    fn the_log_file_stays_near_its_limit_under_a_steady_stream_of_commits() {
        let dir = tempfile::tempdir().unwrap();
        let log = dir.path().join("chapaev.sqlite3-wal");
        let limit = 512 << 10;
        let store = SqliteStore::open_with_log_limit(dir.path(), SyncMode::Normal, limit).unwrap();
        store
            .create(&StoredMatch {
                status: Status::Live,
                ..stored("m")
            })
            .unwrap();
        let after = LIVE;
        let started = Instant::now();
        let (mut k, mut largest) = (0, 0);
        while started.elapsed() < std::time::Duration::from_secs(3) {
            // Commits back to back, as under heavy play.
            let pass = RecordedMove::Pass { side: Side::White };
            store.append_move("m", k, &pass, &after).unwrap();
            k += 1;
            largest = largest.max(std::fs::metadata(&log).map(|m| m.len()).unwrap_or(0));
        }
        assert!(
            largest < 8 * limit,
            "the log reached {largest} bytes over {k} commits (limit {limit})"
        );
        assert_eq!(store.moves("m").unwrap().len(), k);
    }

    #[test]
    fn reads_do_not_wait_for_the_writers_connection() {
        let dir = tempfile::tempdir().unwrap();
        let store = SqliteStore::open(dir.path(), SyncMode::Full).unwrap();
        store.create(&stored("m")).unwrap();
        // The writer's connection is busy (as in a commit's sync) ...
        let writer = store.lock().unwrap();
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::scope(|s| {
            s.spawn(|| {
                let listed = store.list(None, 10).unwrap().len();
                let loaded = store.load("m").unwrap().is_some();
                tx.send((listed, loaded)).unwrap();
            });
            // ... and every read still answers.
            let answer = rx.recv_timeout(std::time::Duration::from_secs(5));
            drop(writer);
            assert_eq!(answer, Ok((1, true)));
        });
    }

    #[test]
    fn the_store_survives_reopening_from_disk() {
        let dir = tempfile::tempdir().unwrap();
        {
            let store = SqliteStore::open(dir.path(), SyncMode::Full).unwrap();
            store.create(&stored("m")).unwrap();
        }
        let store = SqliteStore::open(dir.path(), SyncMode::Full).unwrap();
        assert_eq!(
            store.get("m").unwrap().unwrap().seats[0].name.as_deref(),
            Some("Petka")
        );
    }

    #[test]
    fn a_database_from_before_physics_versions_gains_the_column_and_its_matches_are_physics_1() {
        let dir = tempfile::tempdir().unwrap();
        {
            // A store as it was before the column: `SCHEMA` never had it.
            let conn = Connection::open(dir.path().join("chapaev.sqlite3")).unwrap();
            conn.execute_batch(SCHEMA).unwrap();
            conn.execute(
                "INSERT INTO matches (id, created_at, updated_at, config, seed, status, turn_seconds)
                 VALUES ('old', 1, 1, '{}', 5, 'live', 60)",
                [],
            )
            .unwrap();
        }
        let store = SqliteStore::open(dir.path(), SyncMode::Full).unwrap();
        let (m, record) = store.load("old").unwrap().unwrap();
        assert_eq!((m.physics, record.physics), (1, 1));
        // It was begun before noise secrets: it keeps its seed (format 3).
        assert_eq!(m.noise, game::NoiseKey::SplitMix64(5));
        assert_eq!((record.version, record.seed), (3, Some(5)));
        let summary = store.summary("old").unwrap().unwrap();
        assert_eq!((summary.physics, summary.playable), (1, true));
        store
            .create(&StoredMatch {
                physics: 7,
                ..stored("new")
            })
            .unwrap();
        drop(store);
        // Opened again: the column is there once, and keeps what it holds.
        let store = SqliteStore::open(dir.path(), SyncMode::Full).unwrap();
        let (m, record) = store.load("new").unwrap().unwrap();
        assert_eq!((m.physics, record.physics), (7, 7));
        let summary = store.summary("new").unwrap().unwrap();
        assert_eq!((summary.physics, summary.playable), (7, false));
        assert!(matches!(
            game::Replay::new(record),
            Err(game::ReplayError::Physics(_))
        ));
    }
}
