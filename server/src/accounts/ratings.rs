//! Rated matches: how a finished match moves its two accounts' Glicko-2
//! ratings, and what is kept of it. The update runs inside the transaction
//! that stores the match's last move (in each store backend's group
//! commit, [`crate::store::group_commit`]), so a crash leaves a finished match either rated once
//! with its last move stored, or neither: never finished and unrated, never
//! rated twice. Each rated match leaves one point per account in
//! `rating_history` (the rating after it), which is also what makes the
//! update idempotent. The built-in computer levels play rated matches as
//! the bot accounts `computer-easy`, `computer-medium`, `computer-hard` and
//! `computer-adaptive`,
//! which the store creates (without keys: nobody can sign in as them).

use serde::Serialize;

/// The prefix of the computer levels' account names, reserved.
pub const COMPUTER_PREFIX: &str = "computer-";

/// Most points or matches one account listing returns.
pub const MAX_LISTED: usize = 500;

/// The account name of a built-in computer level.
pub fn computer_account(level: bots::Level) -> String {
    format!("{COMPUTER_PREFIX}{level}")
}

/// The computer levels' account names, which every store creates.
pub fn computer_accounts() -> impl Iterator<Item = String> {
    bots::Level::ALL.into_iter().map(computer_account)
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
