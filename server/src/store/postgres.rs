//! The PostgreSQL store: the same tables and promises as [`super::sqlite`],
//! on a PostgreSQL server that several server nodes can share (chosen with
//! `--database-url postgres://…`).
//!
//! Reads and the few writes outside play take a connection from an `r2d2`
//! pool; moves go through the [`GroupCommit`] writer thread on a connection
//! of its own, one transaction per batch (PostgreSQL's commit is durable
//! once it returns, with its default `synchronous_commit`). A connection
//! that breaks (the database restarted) is replaced on the next use, and the
//! moves of a batch that failed are refused, never acknowledged.
//!
//! The schema is created and migrated on start by numbered migrations,
//! recorded in `schema_migrations` and applied under an advisory lock, so
//! that nodes starting together migrate once.
//!
//! Account names are unique in any case through `name_key`, the lower-case
//! name (names are ASCII), which the history and passwords refer to.

use super::group_commit::{BatchWriter, GroupCommit, QueuedMove};
use super::{
    now, physics_of, seat_rating, status_of, token_of, AfterMove, MoveWrite, Status, Store,
    StoreError, StoredMatch, StoredSeat, Summary,
};
use crate::store::MAX_LEADERBOARD;
use crate::store::{HostedCreated, ModuleDeleted, ModuleStored, ModuleVersion, Profile};
use crate::store::{RatingPoint, MAX_LISTED};
use ::postgres::{Client, GenericClient, NoTls, Row, Statement};
use game::name::AccountName;
use game::rating::{Rating, RatingSystem, Score};
use game::token::TokenHash;
use game::RecordedMove;
use prometheus_client::registry::Registry;
use r2d2_postgres::PostgresConnectionManager;
use std::collections::HashSet;
use std::time::Duration;

/// Connections in the read pool.
const POOL: u32 = 8;
/// How long connecting to the database may take.
const CONNECT_TIMEOUT: Duration = Duration::from_secs(10);
/// How long a caller waits for a pooled connection before its read fails.
/// While the database is down this bounds a room's wait to reload its
/// match after a failed write (the room then closes, and its clients
/// reconnect); and the pool, which tries to connect again after at most
/// half this wait, has its connections back within a second of the
/// database's return.
const POOL_WAIT: Duration = Duration::from_secs(2);
/// An arbitrary key for the advisory lock migrations run under.
const MIGRATION_LOCK: i64 = 0x0063_6861_7061_6576;

/// The migrations, in order: number `k + 1` is `MIGRATIONS[k]`. Never edit
/// one that has shipped; add the next.
const MIGRATIONS: &[&str] = &[
    "
CREATE TABLE matches (
    id TEXT PRIMARY KEY,
    created_at BIGINT NOT NULL,
    updated_at BIGINT NOT NULL,
    config TEXT NOT NULL,
    seed BIGINT NOT NULL,
    status TEXT NOT NULL,
    bot TEXT,
    turn_seconds BIGINT NOT NULL,
    first_name TEXT,
    first_token_hash TEXT,
    second_name TEXT,
    second_token_hash TEXT,
    shots BIGINT NOT NULL DEFAULT 0,
    result TEXT,
    rematch_of TEXT,
    physics BIGINT NOT NULL DEFAULT 1,
    first_account TEXT,
    second_account TEXT,
    rated BOOLEAN NOT NULL DEFAULT FALSE
);
CREATE INDEX matches_by_status ON matches (status, updated_at);
CREATE INDEX matches_by_first_account ON matches (lower(first_account), updated_at);
CREATE INDEX matches_by_second_account ON matches (lower(second_account), updated_at);
CREATE TABLE moves (
    match_id TEXT NOT NULL REFERENCES matches (id),
    idx BIGINT NOT NULL,
    body TEXT NOT NULL,
    PRIMARY KEY (match_id, idx)
);
CREATE TABLE accounts (
    name_key TEXT PRIMARY KEY,
    name TEXT NOT NULL UNIQUE,
    bot BOOLEAN NOT NULL,
    created_at BIGINT NOT NULL,
    rating DOUBLE PRECISION NOT NULL,
    deviation DOUBLE PRECISION NOT NULL,
    volatility DOUBLE PRECISION NOT NULL,
    games BIGINT NOT NULL DEFAULT 0
);
CREATE INDEX accounts_by_rating ON accounts (bot, rating DESC);
CREATE TABLE account_passwords (
    account_key TEXT PRIMARY KEY REFERENCES accounts (name_key),
    hash TEXT NOT NULL,
    set_at BIGINT NOT NULL
);
CREATE TABLE account_keys (
    hash TEXT PRIMARY KEY,
    account_key TEXT NOT NULL REFERENCES accounts (name_key),
    created_at BIGINT NOT NULL,
    revoked_at BIGINT
);
CREATE TABLE rating_history (
    seq BIGSERIAL PRIMARY KEY,
    account_key TEXT NOT NULL REFERENCES accounts (name_key),
    match_id TEXT NOT NULL REFERENCES matches (id),
    at BIGINT NOT NULL,
    rating DOUBLE PRECISION NOT NULL,
    deviation DOUBLE PRECISION NOT NULL,
    volatility DOUBLE PRECISION NOT NULL,
    UNIQUE (account_key, match_id)
);
CREATE INDEX rating_history_by_match ON rating_history (match_id);
",
    "
CREATE TABLE match_leases (
    match_id TEXT PRIMARY KEY REFERENCES matches (id),
    owner TEXT NOT NULL,
    expires_at TIMESTAMPTZ NOT NULL
);
CREATE INDEX match_leases_by_owner ON match_leases (owner);
CREATE TABLE cluster_nodes (
    id TEXT PRIMARY KEY,
    started_at TIMESTAMPTZ NOT NULL,
    seen_at TIMESTAMPTZ NOT NULL
);
",
    // A match's noise secret (NULL: a match keyed by its seed, from before).
    "ALTER TABLE matches ADD COLUMN noise_secret TEXT;",
    // The versions of hosted bots' modules (at most one active per account).
    "
CREATE TABLE bot_modules (
    seq BIGSERIAL PRIMARY KEY,
    account_key TEXT NOT NULL REFERENCES accounts (name_key),
    hash TEXT NOT NULL,
    size BIGINT NOT NULL,
    uploaded_at BIGINT NOT NULL,
    active BOOLEAN NOT NULL DEFAULT FALSE,
    module BYTEA NOT NULL,
    UNIQUE (account_key, hash)
);
CREATE UNIQUE INDEX bot_modules_one_active ON bot_modules (account_key) WHERE active;
",
    // The hosted module version playing each seat (NULL: none).
    "ALTER TABLE matches ADD COLUMN first_module TEXT, ADD COLUMN second_module TEXT;",
    // Where clients reach each node (`--public-url`; NULL: not given).
    "ALTER TABLE cluster_nodes ADD COLUMN public_url TEXT;",
    // The hosted bots' ladder claims: one row per bot ever paired on the
    // ladder, naming the match it was last claimed for; a claim whose
    // match is finished is free to take again (`Store::create_hosted`).
    // No foreign keys: a claim locks no account row.
    "
CREATE TABLE hosted_ladder (
    account_key TEXT PRIMARY KEY,
    match_id TEXT NOT NULL
);
",
    // The public seed of a seeded casual match (NULL: a secret one).
    "ALTER TABLE matches ADD COLUMN public_seed BIGINT;",
];

type Pool = r2d2::Pool<PostgresConnectionManager<NoTls>>;

/// The PostgreSQL store (see the module's documentation).
pub struct PostgresStore {
    commit: GroupCommit,
    pool: Pool,
}

/// On a node of a cluster, the first statement of every group commit:
/// locks the leases of the batch's matches that the node (`$2`) holds and
/// that have not expired by the clock now (`clock_timestamp()`, not the
/// transaction's start), in one order (so that it never deadlocks with
/// [`crate::play::cluster`]'s renewals). Only those matches' moves are
/// written. The lock holds until the commit: another node taking an
/// expired lease over waits for it, and so loads the match with these
/// moves in it. A node that lost a lease writes nothing more to its match.
const LOCK_LEASES: &str = "SELECT match_id FROM match_leases
    WHERE match_id = ANY($1) AND owner = $2 AND expires_at > clock_timestamp()
    ORDER BY match_id FOR SHARE";

/// How long PostgreSQL lets a node's writer sit idle inside a transaction
/// before it ends the session (rolling back): a group commit takes
/// milliseconds, so an idle one belongs to a node that stalled (paused,
/// frozen) while holding its leases' locks, and the nodes taking those
/// matches over wait at most this long.
const WRITER_IDLE_IN_TRANSACTION: &str = "3s";

/// The columns of a match row, in the order [`stored_match`] reads them.
const MATCH_COLUMNS: &str = super::sqlite::MATCH_COLUMNS;

/// A summary's columns (the same as SQLite's).
const SUMMARY_COLUMNS: &str = super::sqlite::SUMMARY_COLUMNS;

/// The tables a summary reads.
const SUMMARY_FROM: &str = "matches m
    LEFT JOIN accounts a ON a.name_key = lower(m.first_account)
    LEFT JOIN accounts b ON b.name_key = lower(m.second_account)";

/// An account's columns, in the order [`profile`] reads them.
const PROFILE_COLUMNS: &str = "name, bot, created_at, rating, deviation, games";

fn profile(r: &Row) -> Profile {
    Profile::from_row(r.get(0), r.get(1), r.get(2), r.get(3), r.get(4), r.get(5))
}

fn stored_match(r: &Row) -> Result<StoredMatch, StoreError> {
    let id: String = r.get(0);
    let config: String = r.get(2);
    Ok(StoredMatch {
        created_at: r.get::<_, i64>(1) as u64,
        config: serde_json::from_str(&config)?,
        noise: super::noise_of(&id, r.get(3), r.get(16))?,
        status: status_of(&id, r.get(4))?,
        bot: r.get(5),
        turn_seconds: r.get::<_, i64>(6) as u64,
        seats: [
            StoredSeat {
                name: r.get(7),
                token: token_of(&id, r.get(8))?,
                account: r.get(13),
                module: r.get(17),
            },
            StoredSeat {
                name: r.get(9),
                token: token_of(&id, r.get(10))?,
                account: r.get(14),
                module: r.get(18),
            },
        ],
        rematch_of: r.get(11),
        physics: physics_of(&id, r.get(12))?,
        rated: r.get(15),
        seed: r.get::<_, Option<i64>>(19).map(|s| s as u64),
        id,
    })
}

fn summary(r: &Row) -> Result<Summary, StoreError> {
    let id: String = r.get(0);
    let physics = physics_of(&id, r.get(10))?;
    let result: Option<String> = r.get(9);
    Ok(Summary {
        noise_commitment: super::commitment_of(&id, r.get(16))?,
        seed: r.get::<_, Option<i64>>(17).map(|s| s as u64),
        physics,
        playable: game::PhysicsVersion::from_number(physics).is_ok(),
        status: status_of(&id, r.get(1))?,
        created_at: r.get::<_, i64>(2) as u64,
        updated_at: r.get::<_, i64>(3) as u64,
        first: r.get(4),
        second: r.get(5),
        bot: r.get(6),
        shots: r.get::<_, i64>(7) as u32,
        turn_seconds: r.get::<_, i64>(8) as u64,
        result: result.map(|r| serde_json::from_str(&r)).transpose()?,
        rated: r.get(11),
        first_rating: seat_rating((r.get(12), r.get(13))),
        second_rating: seat_rating((r.get(14), r.get(15))),
        match_id: id,
    })
}

/// A module version's columns, in the order [`module_version`] reads them.
const MODULE_COLUMNS: &str = "hash, size, uploaded_at, active";

fn module_version(r: &Row) -> ModuleVersion {
    ModuleVersion::from_row(r.get(0), r.get(1), r.get(2), r.get(3))
}

/// Makes `account`'s version `hash` its only active one (two statements:
/// the one-active index is checked row by row).
fn set_active(tx: &mut impl GenericClient, account: &str, hash: &str) -> Result<(), StoreError> {
    tx.execute(
        "UPDATE bot_modules SET active = FALSE WHERE account_key = lower($1) AND active",
        &[&account],
    )?;
    tx.execute(
        "UPDATE bot_modules SET active = TRUE WHERE account_key = lower($1) AND hash = $2",
        &[&account, &hash],
    )?;
    Ok(())
}

/// Locks `account`'s row until the transaction ends, so that one
/// account's module changes run one at a time; then its version `hash`.
fn lock_account_module(
    tx: &mut impl GenericClient,
    account: &str,
    hash: &str,
) -> Result<Option<ModuleVersion>, StoreError> {
    tx.query_opt(
        "SELECT 1 FROM accounts WHERE name_key = lower($1) FOR UPDATE",
        &[&account],
    )?;
    let row = tx.query_opt(
        &format!(
            "SELECT {MODULE_COLUMNS} FROM bot_modules WHERE account_key = lower($1) AND hash = $2"
        ),
        &[&account, &hash],
    )?;
    Ok(row.as_ref().map(module_version))
}

/// Whether a match not finished yet plays a seat with `account`'s version
/// `hash`: the version's row locked first, so that a match being stored
/// with it ([`Store::create_hosted`]) is waited for and then seen.
fn module_in_use(
    tx: &mut impl GenericClient,
    account: &str,
    hash: &str,
) -> Result<bool, StoreError> {
    tx.query_opt(
        "SELECT 1 FROM bot_modules WHERE account_key = lower($1) AND hash = $2 FOR UPDATE",
        &[&account, &hash],
    )?;
    let row = tx.query_one(
        "SELECT EXISTS (SELECT 1 FROM matches WHERE status <> 'finished'
             AND ((lower(first_account) = lower($1) AND first_module = $2)
               OR (lower(second_account) = lower($1) AND second_module = $2)))",
        &[&account, &hash],
    )?;
    Ok(row.get(0))
}

/// Applies the migrations `client`'s database lacks, each in its own
/// transaction, under an advisory lock; then makes sure the computer
/// levels' accounts exist.
fn migrate(client: &mut Client) -> Result<(), StoreError> {
    let mut tx = client.transaction()?;
    tx.execute("SELECT pg_advisory_xact_lock($1)", &[&MIGRATION_LOCK])?;
    tx.batch_execute(
        "CREATE TABLE IF NOT EXISTS schema_migrations (
             version BIGINT PRIMARY KEY,
             applied_at BIGINT NOT NULL
         )",
    )?;
    let done: i64 = tx
        .query_one(
            "SELECT coalesce(max(version), 0) FROM schema_migrations",
            &[],
        )?
        .get(0);
    for (k, sql) in MIGRATIONS.iter().enumerate() {
        let version = k as i64 + 1;
        if version <= done {
            continue;
        }
        tx.batch_execute(sql)?;
        tx.execute(
            "INSERT INTO schema_migrations (version, applied_at) VALUES ($1, $2)",
            &[&version, &(now() as i64)],
        )?;
        tracing::info!(version, "applied a PostgreSQL migration");
    }
    let start = RatingSystem::default().start;
    for name in crate::store::computer_accounts() {
        tx.execute(
            "INSERT INTO accounts (name_key, name, bot, created_at, rating, deviation, volatility)
             VALUES (lower($1), $1, TRUE, $2, $3, $4, $5) ON CONFLICT DO NOTHING",
            &[
                &name,
                &(now() as i64),
                &start.rating,
                &start.deviation,
                &start.volatility,
            ],
        )?;
    }
    tx.commit()?;
    Ok(())
}

/// Inserts a new match's row (no moves yet).
fn insert_match(client: &mut impl GenericClient, m: &StoredMatch) -> Result<(), StoreError> {
    let (seed, secret) = super::noise_columns(&m.noise);
    let t = now() as i64;
    client.execute(
        "INSERT INTO matches (id, created_at, updated_at, config, seed, status, bot, turn_seconds,
                              first_name, first_token_hash, second_name, second_token_hash, rematch_of,
                              physics, first_account, second_account, rated, noise_secret,
                              first_module, second_module, public_seed)
         VALUES ($1, $2, $2, $3, $4, $5, $6, $7, $8, $9, $10, $11, $12, $13, $14, $15, $16, $17,
                 $18, $19, $20)",
        &[
            &m.id,
            &t,
            &serde_json::to_string(&m.config)?,
            &seed,
            &m.status.as_str(),
            &m.bot,
            &(m.turn_seconds as i64),
            &m.seats[0].name,
            &m.seats[0].token.map(|h| h.to_hex()),
            &m.seats[1].name,
            &m.seats[1].token.map(|h| h.to_hex()),
            &m.rematch_of,
            &i64::from(m.physics),
            &m.seats[0].account,
            &m.seats[1].account,
            &m.rated,
            &secret,
            &m.seats[0].module,
            &m.seats[1].module,
            &m.seed.map(|s| s as i64),
        ],
    )?;
    Ok(())
}

impl PostgresStore {
    /// Connects to the database at `url` (`postgres://user:password@host:port/db`
    /// or `host=… port=… user=… dbname=…`), migrates its schema and starts
    /// the writer.
    pub fn connect(url: &str) -> Result<PostgresStore, StoreError> {
        PostgresStore::connect_as(url, None)
    }

    /// [`PostgresStore::connect`] for a node of a cluster (`node`: its id):
    /// each move is written only while the node holds the match's lease
    /// (`match_leases`, which [`crate::play::cluster`] keeps).
    pub fn connect_as(url: &str, node: Option<&str>) -> Result<PostgresStore, StoreError> {
        let mut config: ::postgres::Config = url.parse()?;
        config.connect_timeout(CONNECT_TIMEOUT);
        if config.get_application_name().is_none() {
            config.application_name("chapaev-server");
        }
        let mut client = config.connect(NoTls)?;
        migrate(&mut client)?;
        let pool = r2d2::Pool::builder()
            .max_size(POOL)
            .min_idle(Some(1))
            .connection_timeout(POOL_WAIT)
            .build(PostgresConnectionManager::new(config.clone(), NoTls))?;
        let node = node.map(str::to_string);
        let commit = GroupCommit::start(Writer {
            conn: Some(WriterConn::prepare(client, node.as_deref())?),
            config,
            node,
        })?;
        Ok(PostgresStore { commit, pool })
    }

    fn conn(&self) -> Result<r2d2::PooledConnection<PostgresConnectionManager<NoTls>>, StoreError> {
        Ok(self.pool.get()?)
    }

    /// The summaries of the matches `condition` (on `m`, with `$1` bound to
    /// `param`) selects, most recently played first.
    fn summaries_where(
        &self,
        condition: &str,
        param: Option<&str>,
        limit: usize,
    ) -> Result<Vec<Summary>, StoreError> {
        let rows = self.conn()?.query(
            &format!(
                "SELECT {SUMMARY_COLUMNS} FROM {SUMMARY_FROM} WHERE {condition}
                 ORDER BY m.updated_at DESC, m.id COLLATE \"C\" LIMIT $2"
            ),
            &[&param, &(limit as i64)],
        )?;
        rows.iter().map(summary).collect()
    }
}

impl Store for PostgresStore {
    fn backend(&self) -> &'static str {
        "postgresql"
    }

    fn create(&self, m: &StoredMatch) -> Result<(), StoreError> {
        insert_match(&mut *self.conn()?, m)
    }

    fn create_hosted(&self, m: &StoredMatch, ladder: bool) -> Result<HostedCreated, StoreError> {
        let mut conn = self.conn()?;
        let mut tx = conn.transaction()?;
        let hosted = super::hosted_accounts(m);
        for (account, hash) in &hosted {
            // Holds the version until the commit: a deletion waits, then
            // sees this match (and one that came first leaves no row).
            let kept = tx.query_opt(
                "SELECT 1 FROM bot_modules WHERE account_key = lower($1) AND hash = $2
                 FOR KEY SHARE",
                &[account, hash],
            )?;
            if kept.is_none() {
                return Ok(HostedCreated::NoVersion(account.to_string()));
            }
        }
        insert_match(&mut tx, m)?;
        if ladder {
            for (account, _) in &hosted {
                // A claim being taken by another node is waited for; its
                // match, not yet in this statement's snapshot, counts as
                // not finished.
                let claimed = tx.execute(
                    "INSERT INTO hosted_ladder (account_key, match_id) VALUES (lower($1), $2)
                     ON CONFLICT (account_key) DO UPDATE SET match_id = EXCLUDED.match_id
                     WHERE EXISTS (SELECT 1 FROM matches f
                                   WHERE f.id = hosted_ladder.match_id AND f.status = 'finished')",
                    &[account, &m.id],
                )?;
                if claimed != 1 {
                    return Ok(HostedCreated::Busy(account.to_string()));
                }
            }
        }
        tx.commit()?;
        Ok(HostedCreated::Created)
    }

    fn hosted_seats(&self, limit: usize) -> Result<Vec<String>, StoreError> {
        let limit = i64::try_from(limit).unwrap_or(i64::MAX);
        let rows = self.conn()?.query(
            "SELECT first_account FROM matches
              WHERE status IN ('open', 'live') AND first_module IS NOT NULL
                AND first_account IS NOT NULL
             UNION ALL
             SELECT second_account FROM matches
              WHERE status IN ('open', 'live') AND second_module IS NOT NULL
                AND second_account IS NOT NULL
             LIMIT $1",
            &[&limit],
        )?;
        Ok(rows.iter().map(|r| r.get(0)).collect())
    }

    fn seat_second(
        &self,
        id: &str,
        name: &str,
        token: &TokenHash,
        account: Option<&str>,
    ) -> Result<(), StoreError> {
        let n = self.conn()?.execute(
            "UPDATE matches SET second_name = $2, second_token_hash = $3, second_account = $5,
                                status = 'live', updated_at = $4
             WHERE id = $1 AND second_token_hash IS NULL AND bot IS NULL",
            &[&id, &name, &token.to_hex(), &(now() as i64), &account],
        )?;
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
        let row = self.conn()?.query_opt(
            &format!("SELECT {MATCH_COLUMNS} FROM matches WHERE id = $1"),
            &[&id],
        )?;
        row.as_ref().map(stored_match).transpose()
    }

    fn live(&self) -> Result<Vec<String>, StoreError> {
        let rows = self.conn()?.query(
            "SELECT id FROM matches WHERE status = 'live' ORDER BY updated_at DESC, id COLLATE \"C\"",
            &[],
        )?;
        Ok(rows.iter().map(|r| r.get(0)).collect())
    }

    fn match_ids(&self, after: Option<&str>, limit: usize) -> Result<Vec<String>, StoreError> {
        let limit = i64::try_from(limit).unwrap_or(i64::MAX);
        let rows = self.conn()?.query(
            "SELECT id FROM matches WHERE $1::text IS NULL OR id COLLATE \"C\" > $1
             ORDER BY id COLLATE \"C\" LIMIT $2",
            &[&after, &limit],
        )?;
        Ok(rows.iter().map(|r| r.get(0)).collect())
    }

    fn expire_open(
        &self,
        older_than: u64,
        keep: &dyn Fn(&str) -> bool,
    ) -> Result<Vec<String>, StoreError> {
        let cutoff = now().saturating_sub(older_than) as i64;
        let mut conn = self.conn()?;
        let mut tx = conn.transaction()?;
        // On a cluster, an open match whose node holds its lease is still
        // waited for there (that node's memory is not this one's).
        let stale = tx.query(
            "SELECT id FROM matches m WHERE status = 'open' AND updated_at < $1
             AND NOT EXISTS (SELECT 1 FROM match_leases l
                             WHERE l.match_id = m.id AND l.expires_at >= now())
             FOR UPDATE",
            &[&cutoff],
        )?;
        let expired: Vec<String> = stale
            .iter()
            .map(|r| r.get::<_, String>(0))
            .filter(|id| !keep(id))
            .collect();
        if !expired.is_empty() {
            tx.execute("DELETE FROM moves WHERE match_id = ANY($1)", &[&expired])?;
            tx.execute(
                "DELETE FROM match_leases WHERE match_id = ANY($1)",
                &[&expired],
            )?;
            tx.execute(
                "DELETE FROM matches WHERE id = ANY($1) AND status = 'open'",
                &[&expired],
            )?;
        }
        tx.commit()?;
        Ok(expired)
    }

    fn moves(&self, id: &str) -> Result<Vec<RecordedMove>, StoreError> {
        let rows = self.conn()?.query(
            "SELECT idx, body FROM moves WHERE match_id = $1 ORDER BY idx",
            &[&id],
        )?;
        super::moves_in_order(id, rows.iter().map(|r| (r.get(0), r.get(1))).collect())
    }

    fn list(&self, status: Option<Status>, limit: usize) -> Result<Vec<Summary>, StoreError> {
        self.summaries_where(
            "$1::TEXT IS NULL OR m.status = $1",
            status.map(Status::as_str),
            limit,
        )
    }

    fn summary(&self, id: &str) -> Result<Option<Summary>, StoreError> {
        let row = self.conn()?.query_opt(
            &format!("SELECT {SUMMARY_COLUMNS} FROM {SUMMARY_FROM} WHERE m.id = $1"),
            &[&id],
        )?;
        row.as_ref().map(summary).transpose()
    }

    fn matches_of(&self, account: &str, limit: usize) -> Result<Vec<Summary>, StoreError> {
        self.summaries_where(
            "lower(m.first_account) = lower($1) OR lower(m.second_account) = lower($1)",
            Some(account),
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
        let mut conn = self.conn()?;
        let mut tx = conn.transaction()?;
        let t = now() as i64;
        let n = tx.execute(
            "INSERT INTO accounts (name_key, name, bot, created_at, rating, deviation, volatility)
             VALUES (lower($1), $1, $2, $3, $4, $5, $6) ON CONFLICT DO NOTHING",
            &[
                &name.as_str(),
                &bot,
                &t,
                &start.rating,
                &start.deviation,
                &start.volatility,
            ],
        )?;
        if n != 1 {
            return Ok(false);
        }
        tx.execute(
            "INSERT INTO account_keys (hash, account_key, created_at) VALUES ($1, lower($2), $3)",
            &[&key.to_hex(), &name.as_str(), &t],
        )?;
        tx.commit()?;
        Ok(true)
    }

    fn account(&self, name: &str) -> Result<Option<Profile>, StoreError> {
        let row = self.conn()?.query_opt(
            &format!("SELECT {PROFILE_COLUMNS} FROM accounts WHERE name_key = lower($1)"),
            &[&name],
        )?;
        Ok(row.as_ref().map(profile))
    }

    fn key(&self, hash: &TokenHash) -> Result<Option<(String, String)>, StoreError> {
        let row = self.conn()?.query_opt(
            "SELECT k.hash, a.name FROM account_keys k JOIN accounts a ON a.name_key = k.account_key
             WHERE k.hash = $1 AND k.revoked_at IS NULL",
            &[&hash.to_hex()],
        )?;
        Ok(row.map(|r| (r.get(0), r.get(1))))
    }

    fn insert_key(&self, account: &str, hash: &TokenHash) -> Result<(), StoreError> {
        self.conn()?.execute(
            "INSERT INTO account_keys (hash, account_key, created_at) VALUES ($1, lower($2), $3)",
            &[&hash.to_hex(), &account, &(now() as i64)],
        )?;
        Ok(())
    }

    fn revoke(&self, hash: &TokenHash) -> Result<bool, StoreError> {
        let n = self.conn()?.execute(
            "UPDATE account_keys SET revoked_at = $2 WHERE hash = $1 AND revoked_at IS NULL",
            &[&hash.to_hex(), &(now() as i64)],
        )?;
        Ok(n == 1)
    }

    fn put_password(&self, account: &str, hash: &str) -> Result<(), StoreError> {
        self.conn()?.execute(
            "INSERT INTO account_passwords (account_key, hash, set_at) VALUES (lower($1), $2, $3)
             ON CONFLICT (account_key) DO UPDATE SET hash = $2, set_at = $3",
            &[&account, &hash, &(now() as i64)],
        )?;
        Ok(())
    }

    fn password(&self, name: &str) -> Result<Option<(String, String)>, StoreError> {
        let row = self.conn()?.query_opt(
            "SELECT a.name, p.hash FROM account_passwords p
             JOIN accounts a ON a.name_key = p.account_key WHERE p.account_key = lower($1)",
            &[&name],
        )?;
        Ok(row.map(|r| (r.get(0), r.get(1))))
    }

    fn insert_module(
        &self,
        account: &str,
        hash: &str,
        bytes: &[u8],
        max_versions: usize,
    ) -> Result<ModuleStored, StoreError> {
        let mut conn = self.conn()?;
        let mut tx = conn.transaction()?;
        let stored = match lock_account_module(&mut tx, account, hash)? {
            Some(v) => ModuleStored::Existing(ModuleVersion { active: true, ..v }),
            None => {
                let held: i64 = tx
                    .query_one(
                        "SELECT count(*) FROM bot_modules WHERE account_key = lower($1)",
                        &[&account],
                    )?
                    .get(0);
                if held >= max_versions as i64 {
                    return Ok(ModuleStored::TooMany {
                        limit: max_versions,
                    });
                }
                let (size, at) = (bytes.len() as i64, now() as i64);
                tx.execute(
                    "INSERT INTO bot_modules (account_key, hash, size, uploaded_at, module)
                     VALUES (lower($1), $2, $3, $4, $5)",
                    &[&account, &hash, &size, &at, &bytes],
                )?;
                ModuleStored::New(ModuleVersion::from_row(hash.to_string(), size, at, true))
            }
        };
        set_active(&mut tx, account, hash)?;
        tx.commit()?;
        Ok(stored)
    }

    fn modules(&self, account: &str) -> Result<Vec<ModuleVersion>, StoreError> {
        let rows = self.conn()?.query(
            &format!(
                "SELECT {MODULE_COLUMNS} FROM bot_modules WHERE account_key = lower($1)
                 ORDER BY uploaded_at DESC, seq DESC"
            ),
            &[&account],
        )?;
        Ok(rows.iter().map(module_version).collect())
    }

    fn activate_module(
        &self,
        account: &str,
        hash: &str,
    ) -> Result<Option<ModuleVersion>, StoreError> {
        let mut conn = self.conn()?;
        let mut tx = conn.transaction()?;
        let Some(version) = lock_account_module(&mut tx, account, hash)? else {
            return Ok(None);
        };
        set_active(&mut tx, account, hash)?;
        tx.commit()?;
        Ok(Some(ModuleVersion {
            active: true,
            ..version
        }))
    }

    fn delete_module(&self, account: &str, hash: &str) -> Result<ModuleDeleted, StoreError> {
        let mut conn = self.conn()?;
        let mut tx = conn.transaction()?;
        let deleted = match lock_account_module(&mut tx, account, hash)? {
            None => ModuleDeleted::Missing,
            Some(v) if v.active => ModuleDeleted::Active,
            Some(_) if module_in_use(&mut tx, account, hash)? => ModuleDeleted::InUse,
            Some(_) => {
                tx.execute(
                    "DELETE FROM bot_modules WHERE account_key = lower($1) AND hash = $2",
                    &[&account, &hash],
                )?;
                ModuleDeleted::Deleted
            }
        };
        tx.commit()?;
        Ok(deleted)
    }

    fn active_module(&self, account: &str) -> Result<Option<(ModuleVersion, Vec<u8>)>, StoreError> {
        let row = self.conn()?.query_opt(
            &format!(
                "SELECT {MODULE_COLUMNS}, module FROM bot_modules
                 WHERE account_key = lower($1) AND active"
            ),
            &[&account],
        )?;
        Ok(row.map(|r| (module_version(&r), r.get(4))))
    }

    fn module_bytes(&self, account: &str, hash: &str) -> Result<Option<Vec<u8>>, StoreError> {
        let row = self.conn()?.query_opt(
            "SELECT module FROM bot_modules WHERE account_key = lower($1) AND hash = $2",
            &[&account, &hash],
        )?;
        Ok(row.map(|r| r.get(0)))
    }

    fn hosted_bots(&self, limit: usize) -> Result<Vec<Profile>, StoreError> {
        let limit = i64::try_from(limit).unwrap_or(i64::MAX);
        let rows = self.conn()?.query(
            &format!(
                "SELECT {PROFILE_COLUMNS} FROM accounts
                 WHERE bot AND name_key IN (SELECT account_key FROM bot_modules WHERE active)
                 ORDER BY name_key LIMIT $1"
            ),
            &[&limit],
        )?;
        Ok(rows.iter().map(profile).collect())
    }

    fn leaderboard(&self, bots: bool, limit: usize) -> Result<Vec<Profile>, StoreError> {
        let rows = self.conn()?.query(
            &format!(
                "SELECT {PROFILE_COLUMNS} FROM accounts WHERE bot = $1
                   AND (created_at >= $4 OR EXISTS (SELECT 1 FROM rating_history h
                        WHERE h.account_key = accounts.name_key AND h.at >= $4))
                 ORDER BY deviation > $2, rating DESC, name_key COLLATE \"C\" LIMIT $3"
            ),
            &[
                &bots,
                &RatingSystem::default().provisional_above,
                &(limit.min(MAX_LEADERBOARD) as i64),
                &super::leaderboard_cutoff(),
            ],
        )?;
        Ok(rows.iter().map(profile).collect())
    }

    fn rating_history(&self, account: &str, limit: usize) -> Result<Vec<RatingPoint>, StoreError> {
        let rows = self.conn()?.query(
            "SELECT match_id, at, rating, deviation FROM (
                 SELECT match_id, at, rating, deviation, seq FROM rating_history
                 WHERE account_key = lower($1) ORDER BY at DESC, seq DESC LIMIT $2
             ) latest ORDER BY at, seq",
            &[&account, &(limit.min(MAX_LISTED) as i64)],
        )?;
        Ok(rows
            .iter()
            .map(|r| RatingPoint::from_row(r.get(0), r.get(1), r.get(2), r.get(3)))
            .collect())
    }

    fn register_metrics(&self, registry: &mut Registry) {
        self.commit.register_metrics(registry);
    }
}

/// The writer's connection and the statements every batch runs.
struct WriterConn {
    client: Client,
    insert_move: Statement,
    update_match: Statement,
    /// [`LOCK_LEASES`], on a node of a cluster.
    lock_leases: Option<Statement>,
}

impl WriterConn {
    /// Prepares the statements on `client`; fenced by `node`'s leases if
    /// it is a node of a cluster.
    fn prepare(mut client: Client, node: Option<&str>) -> Result<WriterConn, StoreError> {
        let insert_move =
            client.prepare("INSERT INTO moves (match_id, idx, body) VALUES ($1, $2, $3)")?;
        let update_match = client.prepare(
            "UPDATE matches SET status = $2, shots = $3, result = $4, updated_at = $5 \
             WHERE id = $1",
        )?;
        let lock_leases = match node {
            None => None,
            Some(_) => {
                client.batch_execute(&format!(
                    "SET idle_in_transaction_session_timeout = '{WRITER_IDLE_IN_TRANSACTION}'"
                ))?;
                Some(client.prepare(LOCK_LEASES)?)
            }
        };
        Ok(WriterConn {
            client,
            insert_move,
            update_match,
            lock_leases,
        })
    }
}

/// The group commit's backend: a connection of its own, made again after
/// it breaks.
struct Writer {
    config: ::postgres::Config,
    conn: Option<WriterConn>,
    /// The node's id, on a node of a cluster (its moves are fenced).
    node: Option<String>,
}

/// The matches of a batch whose moves may be written: all of them (not a
/// node of a cluster), or those whose lease [`LOCK_LEASES`] locked.
enum Fence {
    Open,
    Held(HashSet<String>),
}

impl Fence {
    /// Locks the leases of `batch`'s matches (on a node of a cluster) in
    /// transaction `tx`.
    fn lock(
        tx: &mut ::postgres::Transaction<'_>,
        lock_leases: Option<&Statement>,
        node: Option<&str>,
        batch: &[QueuedMove],
    ) -> Result<Fence, StoreError> {
        let (Some(statement), Some(node)) = (lock_leases, node) else {
            return Ok(Fence::Open);
        };
        let mut ids: Vec<&str> = batch.iter().map(|m| m.id.as_str()).collect();
        ids.sort_unstable();
        ids.dedup();
        let rows = tx.query(statement, &[&ids, &node])?;
        Ok(Fence::Held(rows.iter().map(|r| r.get(0)).collect()))
    }

    /// Whether `m` may be written; if not, why.
    fn check(&self, m: &QueuedMove, node: Option<&str>) -> Result<(), StoreError> {
        match self {
            Fence::Held(held) if !held.contains(&m.id) => Err(StoreError::LeaseLost {
                match_id: m.id.clone(),
                node: node.unwrap_or_default().to_string(),
            }),
            _ => Ok(()),
        }
    }
}

impl Writer {
    /// The connection, connecting first if there is none or it broke.
    fn conn(&mut self) -> Result<&mut WriterConn, StoreError> {
        if self.conn.as_ref().is_some_and(|c| c.client.is_closed()) {
            self.conn = None;
        }
        if self.conn.is_none() {
            let client = self.config.connect(NoTls)?;
            self.conn = Some(WriterConn::prepare(client, self.node.as_deref())?);
        }
        self.conn
            .as_mut()
            .ok_or_else(|| StoreError::GroupCommit("no connection".into()))
    }

    fn try_write(
        &mut self,
        batch: &[QueuedMove],
    ) -> Result<Vec<Result<(), StoreError>>, StoreError> {
        let node = self.node.clone();
        let node = node.as_deref();
        let mut reconnected = false;
        loop {
            let conn = self.conn()?;
            // First the whole batch without savepoints (two round trips a
            // move fewer): moves almost never fail.
            let began = match conn.client.transaction() {
                Ok(mut tx) => {
                    let fence = Fence::lock(&mut tx, conn.lock_leases.as_ref(), node, batch)?;
                    let all = batch.iter().all(|m| {
                        fence.check(m, node).is_ok()
                            && write_move(&mut tx, &conn.insert_move, &conn.update_match, m).is_ok()
                    });
                    if all {
                        tx.commit()?;
                        return Ok(batch.iter().map(|_| Ok(())).collect());
                    }
                    // Dropped unfinished: rolled back.
                    Ok(())
                }
                Err(e) => Err(e),
            };
            if let Err(e) = began {
                // A connection the database ended since the last batch (it
                // restarted) fails at BEGIN, before anything is written:
                // the batch begins once more on a fresh connection, so the
                // first moves after a restart are not refused for it.
                if reconnected {
                    return Err(e.into());
                }
                tracing::info!(error = %e, "the store's writer connects again");
                self.conn = None;
                reconnected = true;
                continue;
            }
            // A move failed: again, each in a savepoint of its own, so that
            // it fails alone.
            let conn = self.conn()?;
            let mut tx = conn.client.transaction()?;
            let fence = Fence::lock(&mut tx, conn.lock_leases.as_ref(), node, batch)?;
            let mut results = Vec::with_capacity(batch.len());
            for m in batch {
                results.push(
                    fence.check(m, node).and_then(|()| {
                        write_one(&mut tx, &conn.insert_move, &conn.update_match, m)
                    }),
                );
            }
            tx.commit()?;
            return Ok(results);
        }
    }
}

impl BatchWriter for Writer {
    fn write(&mut self, batch: &[QueuedMove]) -> Vec<Result<(), StoreError>> {
        match self.try_write(batch) {
            Ok(results) => results,
            Err(e) => {
                // The next batch starts from a fresh connection.
                self.conn = None;
                tracing::warn!(error = %e, moves = batch.len(), "a group commit failed");
                batch
                    .iter()
                    .map(|_| Err(StoreError::GroupCommit(e.to_string())))
                    .collect()
            }
        }
    }
}

/// One move in a savepoint of its own ([`write_move`]): undone alone if
/// anything fails.
fn write_one(
    tx: &mut ::postgres::Transaction<'_>,
    insert_move: &Statement,
    update_match: &Statement,
    m: &QueuedMove,
) -> Result<(), StoreError> {
    let mut sp = tx.savepoint("move")?;
    write_move(&mut sp, insert_move, update_match, m)?;
    sp.commit()?;
    Ok(())
}

/// One move and its match row (and the ratings, for a rated match's last
/// move), in the caller's transaction.
fn write_move(
    sp: &mut impl GenericClient,
    insert_move: &Statement,
    update_match: &Statement,
    m: &QueuedMove,
) -> Result<(), StoreError> {
    sp.execute(insert_move, &[&m.id, &m.index, &m.body])?;
    let at = now() as i64;
    let n = sp.execute(update_match, &[&m.id, &m.status, &m.shots, &m.result, &at])?;
    if n != 1 {
        return Err(StoreError::Corrupt(format!("no match {}", m.id)));
    }
    if let Some(score) = m.score {
        rate_finished(sp, &m.id, score)?;
    }
    Ok(())
}

/// An account's rating as stored.
fn rating_of(conn: &mut impl GenericClient, account: &str) -> Result<Rating, StoreError> {
    let row = conn.query_one(
        "SELECT rating, deviation, volatility FROM accounts WHERE name_key = lower($1)",
        &[&account],
    )?;
    Rating::new(row.get(0), row.get(1), row.get(2))
        .map_err(|e| StoreError::Corrupt(format!("account {account}: {e}")))
}

/// Rates match `id`, just finished with the first seat's `score`, in the
/// caller's transaction ([`crate::store`] says when and how).
fn rate_finished(conn: &mut impl GenericClient, id: &str, score: Score) -> Result<(), StoreError> {
    let Some(row) = conn.query_opt(
        "SELECT rated, first_account, second_account FROM matches WHERE id = $1",
        &[&id],
    )?
    else {
        return Ok(());
    };
    let (rated, first, second): (bool, Option<String>, Option<String>) =
        (row.get(0), row.get(1), row.get(2));
    let (true, Some(first), Some(second)) = (rated, first, second) else {
        return Ok(());
    };
    let done: i64 = conn
        .query_one(
            "SELECT count(*) FROM rating_history WHERE match_id = $1",
            &[&id],
        )?
        .get(0);
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
            "UPDATE accounts SET rating = $2, deviation = $3, volatility = $4, games = games + 1
             WHERE name_key = lower($1)",
            &[account, &r.rating, &r.deviation, &r.volatility],
        )?;
        conn.execute(
            "INSERT INTO rating_history (account_key, match_id, at, rating, deviation, volatility)
             VALUES (lower($1), $2, $3, $4, $5, $6)",
            &[account, &id, &at, &r.rating, &r.deviation, &r.volatility],
        )?;
    }
    Ok(())
}
