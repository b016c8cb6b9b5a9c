//! The durable store: one SQLite file in write-ahead-log mode. A `matches`
//! row holds each match's configuration, seed, physics version, seats
//! (names, and the SHA-256 of each seat token: never the token itself),
//! status and result; a `moves` row holds each accepted move as the JSON of
//! its [`RecordedMove`]. Every accepted move is written in one transaction
//! (the move and the match row together) before its outcome is broadcast,
//! so the match record rebuilt from the store is exactly what players saw,
//! and a restarted server replays it through [`game::Replay`], under the
//! match's own physics version.

use crate::checkpointer::{Checkpointer, Nudge};
use crate::config::SyncMode;
use crate::metrics::Histogram;
use crate::readers::{Readers, READERS};
use game::rating::Score;
use game::token::TokenHash;
use game::Seat;
use game::{Config, MatchRecord, MatchResult, PhysicsVersion, RecordedMove, RECORD_VERSION};
use rusqlite::{params, Connection, OptionalExtension};
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::time::{Instant, SystemTime, UNIX_EPOCH};
use tokio::sync::oneshot;

/// A store operation failed.
#[derive(Debug, thiserror::Error)]
pub enum StoreError {
    #[error("sqlite: {0}")]
    Sqlite(#[from] rusqlite::Error),
    #[error("cannot create the data folder {path}: {source}")]
    DataDir {
        path: String,
        source: std::io::Error,
    },
    #[error("stored JSON is unreadable: {0}")]
    Json(#[from] serde_json::Error),
    #[error("the store is inconsistent: {0}")]
    Corrupt(String),
    #[error("the store's lock was poisoned by a panic")]
    Poisoned,
    #[error("cannot start the store's {0} thread: {1}")]
    Thread(&'static str, std::io::Error),
    /// The group commit that carried this write failed as a whole.
    #[error("the commit of a group of moves failed: {0}")]
    GroupCommit(String),
}

/// Where a match stands, as listed (the session's status, stored as is).
pub use game::session::Status;

/// One seat as stored.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct StoredSeat {
    pub name: Option<String>,
    /// The hash of the seat token (`None`: empty seat, or a bot's seat).
    pub token: Option<TokenHash>,
    /// The account playing the seat, if its player signed in (the seat's
    /// name is then the account's).
    pub account: Option<String>,
}

/// A match row.
#[derive(Clone, Debug, PartialEq)]
pub struct StoredMatch {
    pub id: String,
    pub created_at: u64,
    pub config: Config,
    pub seed: u64,
    /// The physics version the match is played under (see
    /// [`game::physics_version`]).
    pub physics: u32,
    pub status: Status,
    /// The built-in bots: a level (`easy`, `medium`, `hard`) for a bot in
    /// the second seat, or `FIRST/SECOND` for an exhibition where both
    /// seats are bots ([`StoredMatch::bots`] reads it).
    pub bot: Option<String>,
    pub turn_seconds: u64,
    pub seats: [StoredSeat; 2],
    pub rematch_of: Option<String>,
    /// Whether the result moves the two accounts' ratings.
    pub rated: bool,
}

impl StoredMatch {
    /// The `bot` column for bots in the seats: `None`, the second seat's
    /// level, or `FIRST/SECOND` when both seats are bots.
    pub fn bots_column(levels: [Option<bots::Level>; 2]) -> Option<String> {
        match levels {
            [None, None] => None,
            [None, Some(l)] => Some(l.as_str().to_string()),
            [Some(a), Some(b)] => Some(format!("{a}/{b}")),
            // A bot only ever takes the first seat in an exhibition.
            [Some(a), None] => Some(format!("{a}/")),
        }
    }

    /// The level of each seat's built-in bot, read from the `bot` column.
    pub fn bots(&self) -> [Option<bots::Level>; 2] {
        match self.bot.as_deref() {
            None => [None, None],
            Some(text) => match text.split_once('/') {
                Some((a, b)) => [bots::Level::parse(a), bots::Level::parse(b)],
                None => [None, bots::Level::parse(text)],
            },
        }
    }
}

/// What a listing shows of a match (no tokens).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    pub match_id: String,
    pub status: Status,
    pub created_at: u64,
    pub updated_at: u64,
    pub first: Option<String>,
    pub second: Option<String>,
    pub bot: Option<String>,
    pub shots: u32,
    pub turn_seconds: u64,
    pub result: Option<MatchResult>,
    /// The physics version the match is played under.
    pub physics: u32,
    /// Whether this server can play that version (a match it cannot play
    /// is kept as stored, not resumed, until a server that can).
    pub playable: bool,
    /// Whether the result moves the players' ratings.
    pub rated: bool,
    /// The current rating of the account in the first seat (`None`: the
    /// seat has no account).
    pub first_rating: Option<SeatRating>,
    /// The same for the second seat.
    pub second_rating: Option<SeatRating>,
}

/// An account's rating as a listing shows it next to a seat.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct SeatRating {
    /// Rounded.
    pub rating: i64,
    /// Whether it is still provisional (too few rated games).
    pub provisional: bool,
}

/// The row update that goes with a move.
#[derive(Clone, Debug)]
pub struct AfterMove<'a> {
    pub status: Status,
    pub shots: u32,
    pub result: Option<&'a MatchResult>,
    /// The seat that won, once the match is over and not drawn.
    pub winner: Option<Seat>,
}

/// The SQLite store: one connection for reads and writes (SQLite has one
/// writer at a time anyway) and, on disk, a [`Checkpointer`] with its own.
///
/// Moves are written by group commit on the store's own writer thread: a
/// writer queues its move ([`Store::submit_move`]) and waits for its
/// [`MoveWrite`] (asynchronously in a room, blocking in
/// [`Store::append_move`]); the writer thread takes every queued move and
/// writes them in one transaction (one disk sync for all of them), each in its
/// own savepoint so one bad move fails alone, and hands each writer its own
/// result. Under load this turns one sync per move into one per batch, and
/// no game thread ever blocks on the disk. Dropping the store writes what
/// is queued and stops the thread.
pub struct Store {
    shared: Arc<Shared>,
    writer: Option<std::thread::JoinHandle<()>>,
    /// Copies the log into the database file (a store on disk only).
    checkpointer: Option<Checkpointer>,
}

/// The size past which the writer empties the log file.
pub const LOG_LIMIT: u64 = 64 << 20;

/// A store's write-ahead log file and the size it may reach.
struct Log {
    path: std::path::PathBuf,
    limit: u64,
}

/// What the store's callers and its writer thread share.
struct Shared {
    /// The writer's connection (and, for a store in memory, the readers').
    conn: Mutex<Connection>,
    /// Read-only connections of a store on disk.
    readers: Option<Readers>,
    /// The log file of a store on disk, emptied past its limit.
    log: Option<Log>,
    queue: Mutex<Queue>,
    /// Signalled when a move is queued or the store closes.
    wake: Condvar,
    /// How long each group commit took, from taking the batch to its
    /// answers (writes, commit, sync).
    commits: Histogram,
    /// Moves written by those commits.
    moves_committed: AtomicU64,
    /// Tells the checkpointer that a commit added to the log.
    nudge: Option<Nudge>,
}

impl Shared {
    fn log_grew(&self) {
        if let Some(n) = &self.nudge {
            n.nudge();
        }
    }
}

/// Moves waiting for the next group commit.
#[derive(Default)]
struct Queue {
    moves: Vec<QueuedMove>,
    closing: bool,
}

/// A move waiting to be written, and where its writer waits for the result.
struct QueuedMove {
    id: String,
    index: i64,
    body: String,
    status: &'static str,
    shots: i64,
    result: Option<String>,
    /// For a finished match: the first seat's score, which rates a rated
    /// match in the move's own transaction.
    score: Option<Score>,
    done: Answer,
}

/// Where a queued move's writer waits for its result.
type Answer = oneshot::Sender<Result<(), StoreError>>;

/// A queued move's write: wait for it to learn whether the move is stored.
#[must_use = "a move is only stored once its write has completed"]
pub struct MoveWrite(oneshot::Receiver<Result<(), StoreError>>);

impl MoveWrite {
    /// Waits (asynchronously) until the move is committed or has failed.
    pub async fn done(self) -> Result<(), StoreError> {
        self.0
            .await
            .map_err(|_| StoreError::GroupCommit("the store closed first".into()))?
    }

    /// Blocks the thread until the move is committed or has failed (not
    /// from inside an async task: use [`MoveWrite::done`] there).
    pub fn wait(self) -> Result<(), StoreError> {
        self.0
            .blocking_recv()
            .map_err(|_| StoreError::GroupCommit("the store closed first".into()))?
    }
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
    add_column(conn, "rated", "INTEGER NOT NULL DEFAULT 0")
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

pub(crate) fn now() -> u64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0)
}

impl Store {
    /// Opens (creating if needed) `DIR/chapaev.sqlite3`.
    pub fn open(dir: &Path, sync: SyncMode) -> Result<Store, StoreError> {
        Store::open_with_log_limit(dir, sync, LOG_LIMIT)
    }

    /// [`Store::open`] with the size past which the log file is emptied.
    pub fn open_with_log_limit(
        dir: &Path,
        sync: SyncMode,
        log_limit: u64,
    ) -> Result<Store, StoreError> {
        std::fs::create_dir_all(dir).map_err(|source| StoreError::DataDir {
            path: dir.display().to_string(),
            source,
        })?;
        let path = dir.join("chapaev.sqlite3");
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
        Store::with_connection(conn, sync, Some((checkpointer, &path, log)))
    }

    /// A store in memory (tests).
    pub fn in_memory() -> Result<Store, StoreError> {
        Store::with_connection(Connection::open_in_memory()?, SyncMode::Normal, None)
    }

    /// The store on `conn`; on disk, also the checkpointer and the read
    /// connections to the file at the path.
    fn with_connection(
        conn: Connection,
        sync: SyncMode,
        on_disk: Option<(Checkpointer, &Path, Log)>,
    ) -> Result<Store, StoreError> {
        conn.pragma_update(None, "journal_mode", "WAL")?;
        conn.pragma_update(None, "synchronous", sync.pragma())?;
        conn.pragma_update(None, "foreign_keys", "ON")?;
        conn.busy_timeout(std::time::Duration::from_secs(5))?;
        conn.execute_batch(SCHEMA)?;
        hash_plain_tokens(&conn)?;
        add_physics_column(&conn)?;
        add_account_columns(&conn)?;
        crate::accounts::create_tables(&conn)?;
        crate::ratings::create_tables(&conn)?;
        let (checkpointer, readers, log) = match on_disk {
            Some((c, path, log)) => (Some(c), Some(Readers::open(path, READERS)?), Some(log)),
            None => (None, None, None),
        };
        let shared = Arc::new(Shared {
            conn: Mutex::new(conn),
            readers,
            log,
            queue: Mutex::new(Queue::default()),
            wake: Condvar::new(),
            commits: Histogram::default(),
            moves_committed: AtomicU64::new(0),
            nudge: checkpointer.as_ref().map(Checkpointer::nudger),
        });
        let writer = {
            let shared = shared.clone();
            std::thread::Builder::new()
                .name("store-writer".into())
                .spawn(move || write_loop(&shared))
                .map_err(|e| StoreError::Thread("writer", e))?
        };
        Ok(Store {
            shared,
            writer: Some(writer),
            checkpointer,
        })
    }

    pub(crate) fn lock(&self) -> Result<MutexGuard<'_, Connection>, StoreError> {
        self.shared.conn.lock().map_err(|_| StoreError::Poisoned)
    }

    /// A connection for reading: a free read connection, never the writer's
    /// (but for a store in memory, which has no other).
    pub(crate) fn read(&self) -> Result<MutexGuard<'_, Connection>, StoreError> {
        match &self.shared.readers {
            Some(readers) => readers.get().map_err(|_| StoreError::Poisoned),
            None => self.lock(),
        }
    }

    /// Stores a new match (no moves yet).
    pub fn create(&self, m: &StoredMatch) -> Result<(), StoreError> {
        let conn = self.lock()?;
        let t = now();
        conn.execute(
            "INSERT INTO matches (id, created_at, updated_at, config, seed, status, bot, turn_seconds,
                                  first_name, first_token_hash, second_name, second_token_hash, rematch_of,
                                  physics, first_account, second_account, rated)
             VALUES (?1, ?2, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14, ?15, ?16)",
            params![
                m.id,
                t as i64,
                serde_json::to_string(&m.config)?,
                m.seed as i64,
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
            ],
        )?;
        self.shared.log_grew();
        Ok(())
    }

    /// Fills the second seat (with the account playing it, if any); the
    /// match becomes live.
    pub fn seat_second(
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
        self.shared.log_grew();
        if n != 1 {
            return Err(StoreError::Corrupt(format!(
                "match {id} has no empty second seat"
            )));
        }
        Ok(())
    }

    /// Appends move number `index` and updates the match row, in one
    /// transaction: both are stored, or neither. Blocks until it is done.
    pub fn append_move(
        &self,
        id: &str,
        index: usize,
        m: &RecordedMove,
        after: &AfterMove<'_>,
    ) -> Result<(), StoreError> {
        self.submit_move(id, index, m, after)?.wait()
    }

    /// Queues move number `index` and the match row's update for the next
    /// group commit (one transaction: both are stored, or neither); the
    /// returned [`MoveWrite`] tells when it is stored.
    pub fn submit_move(
        &self,
        id: &str,
        index: usize,
        m: &RecordedMove,
        after: &AfterMove<'_>,
    ) -> Result<MoveWrite, StoreError> {
        let body = serde_json::to_string(m)?;
        let result = after.result.map(serde_json::to_string).transpose()?;
        let (done, answer) = oneshot::channel();
        let mut queue = self.shared.queue.lock().map_err(|_| StoreError::Poisoned)?;
        if queue.closing {
            return Err(StoreError::GroupCommit("the store is closing".into()));
        }
        queue.moves.push(QueuedMove {
            id: id.to_string(),
            index: index as i64,
            body,
            status: after.status.as_str(),
            shots: after.shots as i64,
            score: match (after.status, after.winner) {
                (Status::Finished, Some(Seat::First)) => Some(Score::Win),
                (Status::Finished, Some(Seat::Second)) => Some(Score::Loss),
                (Status::Finished, None) => Some(Score::Draw),
                _ => None,
            },
            result,
            done,
        });
        drop(queue);
        self.shared.wake.notify_one();
        Ok(MoveWrite(answer))
    }

    fn row_to_match(row: &rusqlite::Row<'_>) -> rusqlite::Result<(StoredMatchRaw, String)> {
        Ok((
            StoredMatchRaw {
                id: row.get(0)?,
                created_at: row.get::<_, i64>(1)?,
                seed: row.get::<_, i64>(3)?,
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
                rated: row.get(15)?,
            },
            row.get(2)?,
        ))
    }

    const MATCH_COLUMNS: &'static str = "id, created_at, config, seed, status, bot, turn_seconds,
        first_name, first_token_hash, second_name, second_token_hash, rematch_of, physics,
        first_account, second_account, rated";

    /// One match row.
    pub fn get(&self, id: &str) -> Result<Option<StoredMatch>, StoreError> {
        let conn = self.read()?;
        let raw = conn
            .query_row(
                &format!("SELECT {} FROM matches WHERE id = ?1", Self::MATCH_COLUMNS),
                params![id],
                Self::row_to_match,
            )
            .optional()?;
        raw.map(|(r, config)| r.finish(&config)).transpose()
    }

    /// Ids of the live matches, the most recently played first (to resume
    /// on start; open ones are loaded when someone comes for them).
    pub fn live(&self) -> Result<Vec<String>, StoreError> {
        let conn = self.read()?;
        let mut stmt = conn
            .prepare("SELECT id FROM matches WHERE status = 'live' ORDER BY updated_at DESC, id")?;
        let ids = stmt
            .query_map([], |r| r.get::<_, String>(0))?
            .collect::<Result<Vec<_>, _>>()?;
        Ok(ids)
    }

    /// Deletes the open matches (never joined, so without moves) untouched
    /// for `older_than` seconds, except those `keep` names (in memory, so
    /// still waited for); their ids. One transaction.
    pub fn expire_open(
        &self,
        older_than: u64,
        keep: impl Fn(&str) -> bool,
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
            self.shared.log_grew();
        }
        Ok(expired)
    }

    /// The moves of a match, in order.
    pub fn moves(&self, id: &str) -> Result<Vec<RecordedMove>, StoreError> {
        let conn = self.read()?;
        let mut stmt =
            conn.prepare("SELECT idx, body FROM moves WHERE match_id = ?1 ORDER BY idx")?;
        let rows = stmt
            .query_map(params![id], |r| {
                Ok((r.get::<_, i64>(0)?, r.get::<_, String>(1)?))
            })?
            .collect::<Result<Vec<_>, _>>()?;
        let mut moves = Vec::with_capacity(rows.len());
        for (k, (idx, body)) in rows.into_iter().enumerate() {
            if idx != k as i64 {
                return Err(StoreError::Corrupt(format!(
                    "match {id}: move {k} is missing (found {idx})"
                )));
            }
            moves.push(serde_json::from_str(&body)?);
        }
        Ok(moves)
    }

    /// A match row and its record (config, seed, physics version, every
    /// move).
    pub fn load(&self, id: &str) -> Result<Option<(StoredMatch, MatchRecord)>, StoreError> {
        let Some(m) = self.get(id)? else {
            return Ok(None);
        };
        let moves = self.moves(id)?;
        let record = MatchRecord {
            version: RECORD_VERSION,
            physics: m.physics,
            config: m.config.clone(),
            seed: m.seed,
            moves,
        };
        Ok(Some((m, record)))
    }

    /// Summaries, newest first, optionally of one status only.
    pub fn list(&self, status: Option<Status>, limit: usize) -> Result<Vec<Summary>, StoreError> {
        self.summaries_where(
            "?1 IS NULL OR m.status = ?1",
            status.map(Status::as_str),
            limit,
        )
    }

    /// The summaries of the matches that `condition` (on `m`, the match,
    /// with `?1` bound to `param`) selects, most recently played first.
    pub(crate) fn summaries_where(
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

    /// One match's summary.
    pub fn summary(&self, id: &str) -> Result<Option<Summary>, StoreError> {
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

    /// The store's metrics as Prometheus text: group commits (count and
    /// duration) and the moves they wrote.
    pub fn render_metrics(&self, out: &mut String) {
        use std::fmt::Write as _;
        let moves = self.shared.moves_committed.load(Ordering::Relaxed);
        let _ = writeln!(
            out,
            "# HELP chapaev_store_moves_committed_total Moves handed to group commits.\n\
             # TYPE chapaev_store_moves_committed_total counter\n\
             chapaev_store_moves_committed_total {moves}"
        );
        self.shared.commits.render(
            out,
            "chapaev_store_commit_seconds",
            "Time of each group commit: the batch's writes, the commit and its sync.",
        );
    }

    /// Makes sure everything written is in the main database file (on shutdown).
    pub fn checkpoint(&self) -> Result<(), StoreError> {
        let conn = self.lock()?;
        conn.query_row("PRAGMA wal_checkpoint(TRUNCATE)", [], |_| Ok(()))?;
        Ok(())
    }
}

/// A summary's columns, read from `matches` joined to the seats' accounts
/// (`a` and `b`).
const SUMMARY_COLUMNS: &str = "m.id, m.status, m.created_at, m.updated_at, m.first_name,
    m.second_name, m.bot, m.shots, m.turn_seconds, m.result, m.physics, m.rated,
    a.rating, a.deviation, b.rating, b.deviation";

/// The tables a summary reads.
const SUMMARY_FROM: &str = "matches m
    LEFT JOIN accounts a ON a.name = m.first_account
    LEFT JOIN accounts b ON b.name = m.second_account";

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
}

/// A seat's account's rating as listed.
fn seat_rating((rating, deviation): (Option<f64>, Option<f64>)) -> Option<SeatRating> {
    let (rating, deviation) = (rating?, deviation?);
    Some(SeatRating {
        rating: rating.round() as i64,
        provisional: deviation > game::rating::RatingSystem::default().provisional_above,
    })
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
        })
    }

    fn finish(self) -> Result<Summary, StoreError> {
        let physics = physics_of(&self.id, self.physics)?;
        Ok(Summary {
            physics,
            playable: PhysicsVersion::from_number(physics).is_ok(),
            status: Status::parse(&self.status).ok_or_else(|| {
                StoreError::Corrupt(format!("match {}: status {}", self.id, self.status))
            })?,
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
    rated: bool,
}

/// A stored physics version, checked to be one.
fn physics_of(id: &str, stored: i64) -> Result<u32, StoreError> {
    u32::try_from(stored)
        .map_err(|_| StoreError::Corrupt(format!("match {id}: physics version {stored}")))
}

impl StoredMatchRaw {
    fn finish(self, config: &str) -> Result<StoredMatch, StoreError> {
        let status = Status::parse(&self.status).ok_or_else(|| {
            StoreError::Corrupt(format!("match {}: status {}", self.id, self.status))
        })?;
        let hash = |hex: Option<String>| {
            hex.map(|h| TokenHash::from_hex(&h))
                .transpose()
                .map_err(|e| StoreError::Corrupt(format!("match {}: {e}", self.id)))
        };
        let tokens = [hash(self.first_token_hash)?, hash(self.second_token_hash)?];
        let [first_account, second_account] = self.accounts;
        Ok(StoredMatch {
            physics: physics_of(&self.id, self.physics)?,
            config: serde_json::from_str(config)?,
            created_at: self.created_at as u64,
            // Stored as the i64 with the same bits.
            seed: self.seed as u64,
            status,
            bot: self.bot,
            turn_seconds: self.turn_seconds as u64,
            seats: [
                StoredSeat {
                    name: self.first_name,
                    token: tokens[0],
                    account: first_account,
                },
                StoredSeat {
                    name: self.second_name,
                    token: tokens[1],
                    account: second_account,
                },
            ],
            rematch_of: self.rematch_of,
            rated: self.rated,
            id: self.id,
        })
    }
}

impl Drop for Store {
    /// Writes what is still queued, then stops the writer thread, then the
    /// checkpointer.
    fn drop(&mut self) {
        if let Ok(mut queue) = self.shared.queue.lock() {
            queue.closing = true;
        }
        self.shared.wake.notify_one();
        if let Some(writer) = self.writer.take() {
            let _ = writer.join();
        }
        drop(self.checkpointer.take());
    }
}

/// The writer thread: waits for queued moves and commits each batch, until
/// the store closes with nothing left to write.
fn write_loop(shared: &Shared) {
    loop {
        let batch = {
            let Ok(mut queue) = shared.queue.lock() else {
                return;
            };
            while queue.moves.is_empty() && !queue.closing {
                queue = match shared.wake.wait(queue) {
                    Ok(q) => q,
                    Err(_) => return,
                };
            }
            if queue.moves.is_empty() {
                return;
            }
            std::mem::take(&mut queue.moves)
        };
        let started = Instant::now();
        let moves = batch.len() as u64;
        let answers = match shared.conn.lock() {
            Ok(mut conn) => write_batch(&mut conn, batch),
            Err(_) => batch
                .into_iter()
                .map(|m| (m.done, Err(StoreError::Poisoned)))
                .collect(),
        };
        shared.commits.observe(started.elapsed());
        shared.moves_committed.fetch_add(moves, Ordering::Relaxed);
        shared.log_grew();
        for (done, result) in answers {
            let _ = done.send(result);
        }
        empty_a_full_log(shared);
    }
}

/// Under a steady stream of commits the checkpointer's passive checkpoints
/// never catch up and the log never starts over (it grew by 65 MB a second
/// at 4,900 moves a second). Past its limit, the writer empties it itself
/// between two group commits, the only moment without a writer: the moves
/// queued meanwhile wait for the copy of what the passive checkpoints left,
/// and go in the next group.
fn empty_a_full_log(shared: &Shared) {
    let Some(log) = &shared.log else {
        return;
    };
    let size = std::fs::metadata(&log.path).map(|m| m.len()).unwrap_or(0);
    if size <= log.limit {
        return;
    }
    if let Ok(conn) = shared.conn.lock() {
        if let Err(e) = conn.query_row("PRAGMA wal_checkpoint(TRUNCATE)", [], |_| Ok(())) {
            tracing::warn!(error = %e, size, "emptying the log failed; the next commit retries");
        }
    }
}

/// Writes `batch` in one transaction, each move in its own savepoint; the
/// answer for each writer.
fn write_batch(
    conn: &mut Connection,
    batch: Vec<QueuedMove>,
) -> Vec<(Answer, Result<(), StoreError>)> {
    let mut tx = match conn.transaction() {
        Ok(tx) => tx,
        Err(e) => {
            return batch
                .into_iter()
                .map(|m| (m.done, Err(StoreError::GroupCommit(e.to_string()))))
                .collect();
        }
    };
    let mut results = Vec::with_capacity(batch.len());
    for m in &batch {
        results.push(write_one(&mut tx, m));
    }
    let committed = tx.commit();
    batch
        .into_iter()
        .zip(results)
        .map(|(m, r)| {
            let r = match &committed {
                Ok(()) => r,
                Err(e) => Err(StoreError::GroupCommit(e.to_string())),
            };
            (m.done, r)
        })
        .collect()
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
        crate::ratings::rate_finished(&sp, &m.id, score)?;
    }
    sp.commit()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use game::{Game, PieceId, Shot, Side};
    use glam::DVec2;

    fn stored(id: &str) -> StoredMatch {
        StoredMatch {
            id: id.into(),
            created_at: 0,
            config: Config::default(),
            seed: u64::MAX - 1,
            physics: game::PHYSICS_VERSION,
            status: Status::Open,
            bot: None,
            turn_seconds: 60,
            seats: [
                StoredSeat {
                    name: Some("Petka".into()),
                    token: Some(TokenHash::of("t1")),
                    account: None,
                },
                StoredSeat::default(),
            ],
            rematch_of: None,
            rated: false,
        }
    }

    #[test]
    fn a_match_and_its_moves_come_back_as_a_replayable_record() {
        let store = Store::in_memory().unwrap();
        store.create(&stored("m1")).unwrap();
        store
            .seat_second("m1", "Anka", &TokenHash::of("t2"), None)
            .unwrap();
        let mut g = Game::new(Config::default(), u64::MAX - 1).unwrap();
        let piece = PieceId::new(Side::White, 4).unwrap();
        g.play(
            Side::White,
            Shot::new(piece, DVec2::new(0.0, 2.0), g.config()).unwrap(),
        )
        .unwrap();
        let after = AfterMove {
            status: Status::Live,
            shots: 1,
            result: None,
            winner: None,
        };
        store
            .append_move("m1", 0, &g.record().moves[0], &after)
            .unwrap();
        let (m, record) = store.load("m1").unwrap().unwrap();
        assert_eq!(m.seed, u64::MAX - 1);
        assert_eq!(m.status, Status::Live);
        assert_eq!(m.seats[1].token, Some(TokenHash::of("t2")));
        assert_eq!(&record, g.record());
        let replay = game::Replay::new(record).unwrap();
        assert_eq!(replay.game().view(), g.view());
        assert_eq!(store.live().unwrap(), vec!["m1".to_string()]);
    }

    #[test]
    fn moves_written_at_once_from_many_threads_all_land_and_a_bad_one_fails_alone() {
        let store = std::sync::Arc::new(Store::in_memory().unwrap());
        let ids: Vec<String> = (0..6).map(|k| format!("m{k}")).collect();
        for id in &ids {
            store.create(&stored(id)).unwrap();
        }
        let threads: Vec<_> = ids
            .iter()
            .cloned()
            .chain(["nope".to_string()])
            .map(|id| {
                let store = store.clone();
                std::thread::spawn(move || {
                    (0..40)
                        .map(|k| {
                            let after = AfterMove {
                                status: Status::Live,
                                shots: k + 1,
                                result: None,
                                winner: None,
                            };
                            let pass = RecordedMove::Pass { side: Side::White };
                            store.append_move(&id, k as usize, &pass, &after).is_ok()
                        })
                        .collect::<Vec<bool>>()
                })
            })
            .collect();
        let results: Vec<Vec<bool>> = threads.into_iter().map(|t| t.join().unwrap()).collect();
        for (id, ok) in ids.iter().zip(&results) {
            assert!(ok.iter().all(|&b| b), "{id}: every move is acknowledged");
            assert_eq!(
                store.moves(id).unwrap().len(),
                40,
                "{id}: every move is stored"
            );
            assert_eq!(store.summary(id).unwrap().unwrap().shots, 40);
        }
        assert!(
            results[6].iter().all(|&b| !b),
            "moves of an unknown match fail"
        );
        assert!(store.moves("nope").unwrap().is_empty());
    }

    #[test]
    fn a_move_index_is_written_once_and_a_failed_move_changes_nothing() {
        let store = Store::in_memory().unwrap();
        store.create(&stored("m1")).unwrap();
        let after = AfterMove {
            status: Status::Live,
            shots: 0,
            result: None,
            winner: None,
        };
        let resign = RecordedMove::Resign { side: Side::White };
        store.append_move("m1", 0, &resign, &after).unwrap();
        assert!(store.append_move("m1", 0, &resign, &after).is_err());
        // An unknown match: the move insert fails on the foreign key, nothing is written.
        assert!(store.append_move("nope", 0, &resign, &after).is_err());
        assert!(store.moves("nope").unwrap().is_empty());
        assert_eq!(store.moves("m1").unwrap(), vec![resign]);
    }

    #[test]
    fn the_second_seat_is_taken_once_and_listing_filters_by_status() {
        let store = Store::in_memory().unwrap();
        store.create(&stored("a")).unwrap();
        store.create(&stored("b")).unwrap();
        store
            .seat_second("a", "x", &TokenHash::of("t"), None)
            .unwrap();
        assert!(store
            .seat_second("a", "y", &TokenHash::of("u"), None)
            .is_err());
        let open = store.list(Some(Status::Open), 10).unwrap();
        assert_eq!(open.len(), 1);
        assert_eq!(open[0].match_id, "b");
        assert_eq!(store.list(None, 10).unwrap().len(), 2);
        assert_eq!(
            store.summary("a").unwrap().unwrap().second.as_deref(),
            Some("x")
        );
        assert!(store.summary("zz").unwrap().is_none());
    }

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
            let store = Store::open(dir.path(), SyncMode::Full).unwrap();
            let old = store.get("old").unwrap().unwrap();
            assert_eq!(old.seats[0].token, Some(TokenHash::of("plain-a")));
            assert_eq!(old.seats[1].token, Some(TokenHash::of("plain-b")));
            store.create(&stored("new")).unwrap();
        }
        // Nothing in the file is a token any more, and it opens again.
        let store = Store::open(dir.path(), SyncMode::Full).unwrap();
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
    fn open_matches_left_alone_expire_and_live_ones_are_resumed_newest_first() {
        let store = Store::in_memory().unwrap();
        for id in ["old-open", "waited-for", "live-a", "live-b", "new-open"] {
            store.create(&stored(id)).unwrap();
        }
        for id in ["live-a", "live-b"] {
            store
                .seat_second(id, "Anka", &TokenHash::of("t2"), None)
                .unwrap();
        }
        let age = |id: &str, at: i64| {
            store
                .lock()
                .unwrap()
                .execute(
                    "UPDATE matches SET updated_at = ?2 WHERE id = ?1",
                    params![id, at],
                )
                .unwrap();
        };
        for (id, at) in [
            ("old-open", 0),
            ("waited-for", 0),
            ("live-a", 5),
            ("live-b", 9),
        ] {
            age(id, at);
        }
        let expired = store.expire_open(3600, |id| id == "waited-for").unwrap();
        assert_eq!(expired, ["old-open"]);
        assert!(store.get("old-open").unwrap().is_none());
        for kept in ["waited-for", "new-open", "live-a"] {
            assert!(store.get(kept).unwrap().is_some(), "{kept}");
        }
        // Live matches, however old, never expire, and resume newest first.
        assert_eq!(store.live().unwrap(), ["live-b", "live-a"]);
    }

    fn live(id: &str) -> StoredMatch {
        StoredMatch {
            status: Status::Live,
            ..stored(id)
        }
    }

    #[test]
    fn the_log_file_stays_near_its_limit_under_a_steady_stream_of_commits() {
        let dir = tempfile::tempdir().unwrap();
        let log = dir.path().join("chapaev.sqlite3-wal");
        let limit = 512 << 10;
        let store = Store::open_with_log_limit(dir.path(), SyncMode::Normal, limit).unwrap();
        store.create(&live("m")).unwrap();
        let after = AfterMove {
            status: Status::Live,
            shots: 0,
            result: None,
            winner: None,
        };
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
        let store = Store::open(dir.path(), SyncMode::Full).unwrap();
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
            let store = Store::open(dir.path(), SyncMode::Full).unwrap();
            store.create(&stored("m")).unwrap();
        }
        let store = Store::open(dir.path(), SyncMode::Full).unwrap();
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
        let store = Store::open(dir.path(), SyncMode::Full).unwrap();
        let (m, record) = store.load("old").unwrap().unwrap();
        assert_eq!((m.physics, record.physics), (1, 1));
        assert_eq!(record.version, RECORD_VERSION);
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
        let store = Store::open(dir.path(), SyncMode::Full).unwrap();
        let (m, record) = store.load("new").unwrap().unwrap();
        assert_eq!((m.physics, record.physics), (7, 7));
        let summary = store.summary("new").unwrap().unwrap();
        assert_eq!((summary.physics, summary.playable), (7, false));
        assert!(matches!(
            game::Replay::new(record),
            Err(game::ReplayError::Physics(_))
        ));
    }

    #[test]
    fn group_commits_are_counted_and_timed_in_the_metrics() {
        let store = Store::in_memory().unwrap();
        store.create(&stored("m")).unwrap();
        let after = AfterMove {
            status: Status::Live,
            shots: 0,
            result: None,
            winner: None,
        };
        for k in 0..3 {
            let pass = RecordedMove::Pass { side: Side::White };
            store.append_move("m", k, &pass, &after).unwrap();
        }
        let mut text = String::new();
        store.render_metrics(&mut text);
        assert!(
            text.contains("chapaev_store_moves_committed_total 3\n"),
            "{text}"
        );
        // Each append waited for its own commit.
        assert!(
            text.contains("chapaev_store_commit_seconds_count 3\n"),
            "{text}"
        );
        assert!(text.contains("chapaev_store_commit_seconds_bucket{le=\"+Inf\"} 3\n"));
    }
}
