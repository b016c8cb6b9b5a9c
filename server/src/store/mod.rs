//! The durable store, behind one interface ([`Store`]) with two
//! implementations: [`sqlite`] (one embedded file, the default) and
//! [`postgres`] (a PostgreSQL server, chosen with `--database-url`, which
//! several server nodes can share).
//!
//! Both keep the same tables: a `matches` row holds each match's
//! configuration, seed, physics version, seats (names, accounts, and the
//! SHA-256 of each seat token: never the token itself), status and result;
//! a `moves` row holds each accepted move as the JSON of its
//! [`RecordedMove`]; then the accounts, their keys, passwords and rating
//! history. Both make the same promise: every accepted move is written in
//! one transaction with its match row (and, for the last move of a rated
//! match, both ratings) before its outcome is broadcast, through a
//! [`group_commit`] on the store's own writer thread; so the record rebuilt
//! from the store is exactly what players saw, and a restarted server
//! replays it through [`game::Replay`] under the match's own physics
//! version.
//!
//! Rated matches move their two accounts' Glicko-2 ratings inside the
//! transaction that stores the match's last move (each backend's
//! [`group_commit`]), so a crash leaves a finished match either rated once
//! with its last move stored, or neither: never finished and unrated, never
//! rated twice. Each rated match leaves one [`RatingPoint`] per account in
//! `rating_history` (the rating after it), which is also what makes the
//! update idempotent. The built-in computer levels play rated matches as
//! the bot accounts `computer-easy`, `computer-medium`, `computer-hard` and
//! `computer-adaptive`, which every store creates without keys (nobody can
//! sign in as them).

pub(crate) mod checkpointer;
pub mod group_commit;
pub mod postgres;
pub(crate) mod readers;
pub mod sqlite;
#[cfg(test)]
mod tests;

use crate::config::Config as ServerConfig;
use game::name::AccountName;
use game::rating::{Rating, RatingSystem};
use game::token::TokenHash;
use game::{Config, MatchRecord, MatchResult, NoiseKey, NoiseSecret, PhysicsVersion, RecordedMove};
use prometheus_client::registry::Registry;
use serde::{Deserialize, Serialize};
use std::sync::Arc;
use std::time::{SystemTime, UNIX_EPOCH};

/// Most accounts one leaderboard lists.
pub const MAX_LEADERBOARD: usize = 100;

/// A leaderboard lists only the accounts active in this many days: made,
/// or rated in a match, since then. An account whose key is lost can never
/// play again, so it leaves the boards once this much time has passed.
pub const LEADERBOARD_ACTIVE_DAYS: u64 = 180;

/// The `…_at` time (seconds) before which an account has not been active
/// enough to be listed.
pub(crate) fn leaderboard_cutoff() -> i64 {
    now().saturating_sub(LEADERBOARD_ACTIVE_DAYS * 24 * 3600) as i64
}

/// Most points or matches one account listing returns.
pub const MAX_LISTED: usize = 500;

/// The computer levels' account names, which every store creates.
pub(crate) fn computer_accounts() -> impl Iterator<Item = String> {
    bots::Level::ALL
        .into_iter()
        .map(game::name::computer_account)
}

/// A person's or a bot's account as everyone may see it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Profile {
    pub name: String,
    /// Whether the account is a bot's.
    pub bot: bool,
    pub created_at: u64,
    /// The rating, rounded.
    pub rating: i64,
    /// Its deviation, rounded.
    pub deviation: i64,
    /// Whether the rating is still provisional (too few rated games).
    pub provisional: bool,
    /// Rated matches played.
    pub games: u64,
}

impl Profile {
    /// A profile from an account row's columns.
    pub(crate) fn from_row(
        name: String,
        bot: bool,
        created_at: i64,
        rating: f64,
        deviation: f64,
        games: i64,
    ) -> Profile {
        Profile {
            name,
            bot,
            created_at: created_at.max(0) as u64,
            rating: rating.round() as i64,
            deviation: deviation.round() as i64,
            provisional: deviation > RatingSystem::default().provisional_above,
            games: games.max(0) as u64,
        }
    }
}

/// An account's rating after one rated match.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RatingPoint {
    pub match_id: String,
    /// When the match finished (seconds since 1970).
    pub at: u64,
    /// Rounded.
    pub rating: i64,
    /// Rounded.
    pub deviation: i64,
}

impl RatingPoint {
    /// A point from a history row's columns.
    pub(crate) fn from_row(match_id: String, at: i64, rating: f64, deviation: f64) -> RatingPoint {
        RatingPoint {
            match_id,
            at: at.max(0) as u64,
            rating: rating.round() as i64,
            deviation: deviation.round() as i64,
        }
    }
}

/// One uploaded version of a bot account's hosted module (its bytes are
/// kept beside it, read only to play it).
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct ModuleVersion {
    /// The SHA-256 of the module's bytes, 64 lowercase hex digits: the
    /// version's name.
    pub hash: String,
    /// The module's size in bytes.
    pub size: u64,
    /// When it was first uploaded (seconds since 1970).
    pub uploaded_at: u64,
    /// Whether it is the version the account plays with.
    pub active: bool,
}

impl ModuleVersion {
    /// A version from its row's columns.
    pub(crate) fn from_row(
        hash: String,
        size: i64,
        uploaded_at: i64,
        active: bool,
    ) -> ModuleVersion {
        ModuleVersion {
            hash,
            size: size.max(0) as u64,
            uploaded_at: uploaded_at.max(0) as u64,
            active,
        }
    }
}

/// What deleting a module version did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModuleDeleted {
    /// The version is gone.
    Deleted,
    /// It is the active version: kept (make another one active first).
    Active,
    /// A match not finished yet plays a seat with it (it resumes with it
    /// after a restart): kept until that match ends.
    InUse,
    /// The account has no such version.
    Missing,
}

/// What storing a match with hosted seats did ([`Store::create_hosted`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum HostedCreated {
    /// The match is stored (and, on the ladder, its hosted bots claimed).
    Created,
    /// This hosted bot (its account) plays a ladder match not finished
    /// yet: nothing was written.
    Busy(String),
    /// This hosted bot's version was deleted since the match was paired:
    /// nothing was written.
    NoVersion(String),
}

/// What storing an uploaded module did.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ModuleStored {
    /// A new version, now the active one.
    New(ModuleVersion),
    /// The account had this version already (same hash): it is now the
    /// active one, its first upload time kept.
    Existing(ModuleVersion),
    /// The account keeps `limit` versions already: nothing was written.
    TooMany { limit: usize },
}

pub use group_commit::MoveWrite;
pub use postgres::PostgresStore;
pub use sqlite::SqliteStore;

/// The hosted seats of `m`: each one's account and module version.
pub(crate) fn hosted_accounts(m: &StoredMatch) -> Vec<(&str, &str)> {
    let mut seats: Vec<(&str, &str)> = m
        .seats
        .iter()
        .filter_map(|s| Some((s.account.as_deref()?, s.module.as_deref()?)))
        .collect();
    // In one order on every node, so that two claims never wait on each
    // other's.
    seats.sort_by_key(|(a, _)| a.to_ascii_lowercase());
    seats
}

/// A store operation failed.
#[derive(Debug, thiserror::Error)]
pub enum StoreError {
    #[error("sqlite: {0}")]
    Sqlite(#[from] rusqlite::Error),
    #[error("postgresql: {0}")]
    Postgres(#[from] ::postgres::Error),
    #[error("no PostgreSQL connection: {0}")]
    Pool(#[from] r2d2::Error),
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
    /// A node of a cluster wrote a move of a match whose lease it does not
    /// hold (any more): refused, nothing written.
    #[error("node {node} does not hold the lease of match {match_id}")]
    LeaseLost { match_id: String, node: String },
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
    /// The version (SHA-256, hex) of the account's hosted module that the
    /// server plays the seat with, if it does.
    pub module: Option<String>,
}

/// A match row.
#[derive(Clone, Debug, PartialEq)]
pub struct StoredMatch {
    pub id: String,
    pub created_at: u64,
    pub config: Config,
    /// What the match's noise is drawn from: its secret (kept here, and
    /// revealed to players only in the record of the finished match), or
    /// the plain seed of a match begun before secrets.
    pub noise: NoiseKey,
    /// The physics version the match is played under (see
    /// [`game::physics_version`]).
    pub physics: u32,
    pub status: Status,
    /// The built-in bots: a level (`easy`, `medium`, `hard`) for a bot in
    /// the second seat, or `FIRST/SECOND` (either side empty where no
    /// computer sits) when the first seat is a computer's
    /// ([`StoredMatch::bots`] reads it).
    pub bot: Option<String>,
    pub turn_seconds: u64,
    pub seats: [StoredSeat; 2],
    pub rematch_of: Option<String>,
    /// Whether the result moves the two accounts' ratings.
    pub rated: bool,
    /// The public seed a casual match was created with: its secret is
    /// `NoiseSecret::from_seed(seed)`, so anyone who knows the seed can
    /// draw its noise (`None`: a secret nobody knows until the end).
    pub seed: Option<u64>,
}

impl StoredMatch {
    /// The `bot` column for bots in the seats: `None`, the second seat's
    /// level, or `FIRST/SECOND` when both seats are bots.
    pub fn bots_column(levels: [Option<bots::Level>; 2]) -> Option<String> {
        match levels {
            [None, None] => None,
            [None, Some(l)] => Some(l.as_str().to_string()),
            [Some(a), Some(b)] => Some(format!("{a}/{b}")),
            // The first seat's level alone: the bot ladder seats a
            // computer level first against an account.
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
    /// The SHA-256 of the match's noise secret (lowercase hex), published
    /// from its creation; the record reveals the secret once it is over.
    /// Absent for a match begun before secrets (keyed by a plain seed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub noise_commitment: Option<game::NoiseCommitment>,
    /// The public seed of a seeded casual match: its noise is known to
    /// anyone from the start (absent: a secret until the end).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
}

/// An account's rating as a listing shows it next to a seat.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct SeatRating {
    /// Rounded.
    pub rating: i64,
    /// Whether it is still provisional (too few rated games).
    pub provisional: bool,
}

/// A seat's account's rating and deviation, as read, for a listing.
pub(crate) fn seat_rating((rating, deviation): (Option<f64>, Option<f64>)) -> Option<SeatRating> {
    let (rating, deviation) = (rating?, deviation?);
    Some(SeatRating {
        rating: rating.round() as i64,
        provisional: deviation > game::rating::RatingSystem::default().provisional_above,
    })
}

/// The row update that goes with a move.
#[derive(Clone, Debug)]
pub struct AfterMove<'a> {
    pub status: Status,
    pub shots: u32,
    pub result: Option<&'a MatchResult>,
    /// The seat that won, once the match is over and not drawn.
    pub winner: Option<game::Seat>,
}

/// A stored physics version, checked to be one.
pub(crate) fn physics_of(id: &str, stored: i64) -> Result<u32, StoreError> {
    u32::try_from(stored)
        .map_err(|_| StoreError::Corrupt(format!("match {id}: physics version {stored}")))
}

/// The `seed` and `noise_secret` columns of a match's noise key: a secret
/// as 64 hex digits (the seed column then 0), or a seed of a match begun
/// before secrets (stored as the i64 with the same bits; no secret).
pub(crate) fn noise_columns(key: &NoiseKey) -> (i64, Option<String>) {
    match key {
        NoiseKey::SplitMix64(seed) => (*seed as i64, None),
        NoiseKey::ChaCha20(secret) => (0, Some(secret.to_hex())),
    }
}

/// A match's noise key from its `seed` and `noise_secret` columns.
pub(crate) fn noise_of(
    id: &str,
    seed: i64,
    secret: Option<String>,
) -> Result<NoiseKey, StoreError> {
    match secret {
        None => Ok(NoiseKey::SplitMix64(seed as u64)),
        Some(hex) => NoiseSecret::from_hex(&hex)
            .map(NoiseKey::ChaCha20)
            .map_err(|e| StoreError::Corrupt(format!("match {id}: noise secret: {e}"))),
    }
}

/// The public commitment of a match with this `noise_secret` column.
pub(crate) fn commitment_of(
    id: &str,
    secret: Option<String>,
) -> Result<Option<game::NoiseCommitment>, StoreError> {
    Ok(match noise_of(id, 0, secret)? {
        NoiseKey::ChaCha20(secret) => Some(secret.commitment()),
        NoiseKey::SplitMix64(_) => None,
    })
}

/// A stored status, checked to be one.
pub(crate) fn status_of(id: &str, stored: &str) -> Result<Status, StoreError> {
    Status::parse(stored).ok_or_else(|| StoreError::Corrupt(format!("match {id}: status {stored}")))
}

/// A stored token hash, checked to be one.
pub(crate) fn token_of(id: &str, hex: Option<String>) -> Result<Option<TokenHash>, StoreError> {
    hex.map(|h| TokenHash::from_hex(&h))
        .transpose()
        .map_err(|e| StoreError::Corrupt(format!("match {id}: {e}")))
}

/// A match's moves from their `(idx, body)` rows, ordered by index: each
/// index present once, from 0 up.
pub(crate) fn moves_in_order(
    id: &str,
    rows: Vec<(i64, String)>,
) -> Result<Vec<RecordedMove>, StoreError> {
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

/// Seconds since 1970, as stored in every `…_at` column.
pub(crate) fn now() -> u64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0)
}

/// What the server keeps: matches, their moves, accounts and ratings.
///
/// Every method blocks on the database: call it from a blocking thread
/// (`tokio::task::spawn_blocking`), never from an async task, except
/// [`Store::submit_move`], which only queues. Implementations are
/// [`SqliteStore`] and [`PostgresStore`]; `server::store::tests` runs the
/// same tests against both.
pub trait Store: Send + Sync {
    /// The backend's name, for logs and metrics (`sqlite`, `postgresql`).
    fn backend(&self) -> &'static str;

    // --- matches ---

    /// Stores a new match (no moves yet).
    fn create(&self, m: &StoredMatch) -> Result<(), StoreError>;

    /// Fills the second seat (with the account playing it, if any); the
    /// match becomes live. Fails if the seat is taken.
    fn seat_second(
        &self,
        id: &str,
        name: &str,
        token: &TokenHash,
        account: Option<&str>,
    ) -> Result<(), StoreError>;

    /// Queues move number `index` and the match row's update for the next
    /// group commit (one transaction: both are stored, or neither; with the
    /// ratings for the last move of a rated match); the returned
    /// [`MoveWrite`] tells when it is stored. Never blocks on the database.
    fn submit_move(
        &self,
        id: &str,
        index: usize,
        m: &RecordedMove,
        after: &AfterMove<'_>,
    ) -> Result<MoveWrite, StoreError>;

    /// One match row.
    fn get(&self, id: &str) -> Result<Option<StoredMatch>, StoreError>;

    /// Ids of the live matches, the most recently played first (to resume
    /// on start; open ones are loaded when someone comes for them).
    fn live(&self) -> Result<Vec<String>, StoreError>;

    /// Ids of every match, in byte order, the first `limit` after `after`
    /// (from the first without): a walk over the whole store in pages of
    /// bounded size (what a restored store is checked with).
    fn match_ids(&self, after: Option<&str>, limit: usize) -> Result<Vec<String>, StoreError>;

    /// Deletes the open matches (never joined, so without moves) untouched
    /// for `older_than` seconds, except those `keep` names (in memory, so
    /// still waited for); their ids. One transaction.
    fn expire_open(
        &self,
        older_than: u64,
        keep: &dyn Fn(&str) -> bool,
    ) -> Result<Vec<String>, StoreError>;

    /// The moves of a match, in order.
    fn moves(&self, id: &str) -> Result<Vec<RecordedMove>, StoreError>;

    /// Summaries, most recently played first, optionally of one status only.
    fn list(&self, status: Option<Status>, limit: usize) -> Result<Vec<Summary>, StoreError>;

    /// One match's summary.
    fn summary(&self, id: &str) -> Result<Option<Summary>, StoreError>;

    /// The matches `account` (in any case) played a seat of, most recent
    /// first.
    fn matches_of(&self, account: &str, limit: usize) -> Result<Vec<Summary>, StoreError>;

    // --- accounts (the rules around them are in [`crate::accounts`]) ---

    /// Inserts an account with its starting rating and its first key, in
    /// one transaction; `false` (and nothing written) if the name is taken
    /// in any case.
    fn insert_account(
        &self,
        name: &AccountName,
        bot: bool,
        start: Rating,
        key: &TokenHash,
    ) -> Result<bool, StoreError>;

    /// The account named `name` (in any case), if there is one.
    fn account(&self, name: &str) -> Result<Option<Profile>, StoreError>;

    /// The stored hash equal to `hash` of a key not revoked, and its
    /// account's name.
    fn key(&self, hash: &TokenHash) -> Result<Option<(String, String)>, StoreError>;

    /// Adds a key (by its hash) to `account`.
    fn insert_key(&self, account: &str, hash: &TokenHash) -> Result<(), StoreError>;

    /// Revokes the key with `hash`; `false` if no such key was valid.
    fn revoke(&self, hash: &TokenHash) -> Result<bool, StoreError>;

    /// Sets or replaces `account`'s password hash (PHC string).
    fn put_password(&self, account: &str, hash: &str) -> Result<(), StoreError>;

    /// The account named `name` (in any case) and its password hash, if it
    /// has a password.
    fn password(&self, name: &str) -> Result<Option<(String, String)>, StoreError>;

    /// The accounts of people (or of bots) by rating, highest first, those
    /// whose rating is established before the provisional ones; only those
    /// active in the last [`LEADERBOARD_ACTIVE_DAYS`] (made or rated since).
    fn leaderboard(&self, bots: bool, limit: usize) -> Result<Vec<Profile>, StoreError>;

    /// The rating of `account` after each of its rated matches, oldest
    /// first (at most the last `limit`).
    fn rating_history(&self, account: &str, limit: usize) -> Result<Vec<RatingPoint>, StoreError>;

    // --- hosted bots' modules (the rules are in [`crate::accounts::modules`]) ---

    /// Stores `bytes` (whose SHA-256 is `hash`) as a version of
    /// `account`'s module and makes it the active one, in one transaction;
    /// an account holding `max_versions` others already gets
    /// [`ModuleStored::TooMany`] and nothing is written.
    fn insert_module(
        &self,
        account: &str,
        hash: &str,
        bytes: &[u8],
        max_versions: usize,
    ) -> Result<ModuleStored, StoreError>;

    /// The versions of `account`'s module, newest first.
    fn modules(&self, account: &str) -> Result<Vec<ModuleVersion>, StoreError>;

    /// Makes `account`'s version `hash` the active one; `None` (and nothing
    /// changed) if the account has no such version.
    fn activate_module(
        &self,
        account: &str,
        hash: &str,
    ) -> Result<Option<ModuleVersion>, StoreError>;

    /// Deletes `account`'s version `hash` unless it is the active one or
    /// a match not finished yet plays a seat with it
    /// ([`ModuleDeleted::InUse`]: a match resumed after a restart reads its
    /// version from the store).
    fn delete_module(&self, account: &str, hash: &str) -> Result<ModuleDeleted, StoreError>;

    /// `account`'s active version and its bytes, if it has one.
    fn active_module(&self, account: &str) -> Result<Option<(ModuleVersion, Vec<u8>)>, StoreError>;

    /// The bytes of `account`'s version `hash`, if it has it (active or not).
    fn module_bytes(&self, account: &str, hash: &str) -> Result<Option<Vec<u8>>, StoreError>;

    /// The bot accounts with an active module (the hosted bots), as their
    /// profiles, at most `limit` of them.
    fn hosted_bots(&self, limit: usize) -> Result<Vec<Profile>, StoreError>;

    /// Stores a new match whose seats include hosted ones (each seat's
    /// `module` names its version), in one transaction with the hosted
    /// rules: each seat's version must still be stored (the match keeps
    /// it from being deleted until it ends); and for a ladder match
    /// (`ladder`), each hosted bot is claimed for it. A bot holds one
    /// ladder claim at a time, until the match it was claimed for is
    /// finished: whichever node plays that match (it outlives the node
    /// that started it, as the match does) and across restarts. Nothing
    /// is written unless everything is.
    fn create_hosted(&self, m: &StoredMatch, ladder: bool) -> Result<HostedCreated, StoreError>;

    /// The account of each hosted seat of the matches not finished yet
    /// (an account in two such matches is named twice), at most `limit`:
    /// who is mid-match, on every node and from before a restart.
    fn hosted_seats(&self, limit: usize) -> Result<Vec<String>, StoreError>;

    // --- operations ---

    /// Registers the store's metrics (group commits: count and duration,
    /// and the moves they wrote) in `registry`.
    fn register_metrics(&self, registry: &mut Registry);

    /// The store's metrics alone, as Prometheus text appended to `out`.
    fn render_metrics(&self, out: &mut String) {
        let mut registry = Registry::default();
        self.register_metrics(&mut registry);
        out.push_str(&crate::metrics::encode(&registry));
    }

    /// Makes sure everything written is where a fresh start reads it first
    /// (on shutdown; SQLite copies its log into the database file).
    fn checkpoint(&self) -> Result<(), StoreError> {
        Ok(())
    }

    // --- provided ---

    /// [`Store::submit_move`], then blocks until it is stored (not from an
    /// async task).
    fn append_move(
        &self,
        id: &str,
        index: usize,
        m: &RecordedMove,
        after: &AfterMove<'_>,
    ) -> Result<(), StoreError> {
        self.submit_move(id, index, m, after)?.wait()
    }

    /// A match row and its record (config, noise, physics version, every
    /// move), with the noise's secret revealed: what resumes the match, or,
    /// once it is over, what its players may see.
    fn load(&self, id: &str) -> Result<Option<(StoredMatch, MatchRecord)>, StoreError> {
        let Some(m) = self.get(id)? else {
            return Ok(None);
        };
        let mut record = MatchRecord::new(m.config.clone(), &m.noise, PhysicsVersion::CURRENT);
        record.physics = m.physics;
        record.reveal(&m.noise);
        let modules = m.seats.clone().map(|s| s.module);
        record.hosted = modules.iter().any(Option::is_some).then_some(modules);
        record.moves = self.moves(id)?;
        Ok(Some((m, record)))
    }
}

/// The store a server uses, shared by its tasks.
pub type SharedStore = Arc<dyn Store>;

/// Opens the store the configuration names: PostgreSQL at
/// `--database-url`, or else SQLite in `--data-dir`. Either way its schema
/// is brought up to date first.
pub fn open(config: &ServerConfig) -> Result<SharedStore, StoreError> {
    Ok(match &config.database_url {
        Some(url) => Arc::new(PostgresStore::connect_as(
            url,
            config.cluster_node().as_deref(),
        )?),
        None => Arc::new(SqliteStore::open(&config.data_dir, config.sync)?),
    })
}
