//! Rated matches: how a finished match moves its two accounts' Glicko-2
//! ratings, and what is kept of it. The update runs inside the transaction
//! that stores the match's last move ([`rate_finished`], called by the
//! store's writer), so a crash leaves a finished match either rated once
//! with its last move stored, or neither: never finished and unrated, never
//! rated twice. Each rated match leaves one point per account in
//! `rating_history` (the rating after it), which is also what makes the
//! update idempotent. The built-in computer levels play rated matches as
//! the bot accounts `computer-easy`, `computer-medium` and `computer-hard`,
//! which the store creates (without keys: nobody can sign in as them).

use crate::store::{now, Store, StoreError, Summary};
use game::rating::{Rating, RatingSystem, Score};
use rusqlite::{params, Connection, OptionalExtension};
use serde::Serialize;

/// The prefix of the computer levels' account names, reserved.
pub const COMPUTER_PREFIX: &str = "computer-";

/// Most points or matches one account listing returns.
pub const MAX_LISTED: usize = 500;

const TABLES: &str = "
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

/// The account name of a built-in computer level.
pub fn computer_account(level: bots::Level) -> String {
    format!("{COMPUTER_PREFIX}{level}")
}

/// Creates the history table and the computer levels' accounts if the store
/// lacks them.
pub(crate) fn create_tables(conn: &Connection) -> Result<(), StoreError> {
    conn.execute_batch(TABLES)?;
    let start = RatingSystem::default().start;
    for level in bots::Level::ALL {
        conn.execute(
            "INSERT OR IGNORE INTO accounts (name, bot, created_at, rating, deviation, volatility)
             VALUES (?1, 1, ?2, ?3, ?4, ?5)",
            params![
                computer_account(level),
                now() as i64,
                start.rating,
                start.deviation,
                start.volatility
            ],
        )?;
    }
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

/// Rates match `id`, just finished with the first seat's `score`, if it is
/// rated, both its seats have accounts and it was not rated already: both
/// ratings move (Glicko-2, one match as one rating period), each account
/// counts one more game, and the history gains a point for each. Runs in
/// the caller's transaction.
pub(crate) fn rate_finished(conn: &Connection, id: &str, score: Score) -> Result<(), StoreError> {
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
    let system = RatingSystem::default();
    let (a, b) = system.after_match(rating_of(conn, &first)?, rating_of(conn, &second)?, score);
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

impl Store {
    /// The rating of `account` after each of its rated matches, oldest
    /// first (at most the last `limit`).
    pub fn rating_history(
        &self,
        account: &str,
        limit: usize,
    ) -> Result<Vec<RatingPoint>, StoreError> {
        let conn = self.read()?;
        let mut stmt = conn.prepare(
            "SELECT match_id, at, rating, deviation FROM (
                 SELECT match_id, at, rating, deviation, rowid FROM rating_history
                 WHERE account = ?1 ORDER BY at DESC, rowid DESC LIMIT ?2
             ) ORDER BY at, rowid",
        )?;
        let points = stmt
            .query_map(params![account, limit.min(MAX_LISTED) as i64], |r| {
                Ok(RatingPoint {
                    match_id: r.get(0)?,
                    at: r.get::<_, i64>(1)?.max(0) as u64,
                    rating: r.get::<_, f64>(2)?.round() as i64,
                    deviation: r.get::<_, f64>(3)?.round() as i64,
                })
            })?
            .collect::<Result<Vec<_>, _>>()?;
        Ok(points)
    }

    /// The matches `account` played a seat of, most recent first.
    pub fn matches_of(&self, account: &str, limit: usize) -> Result<Vec<Summary>, StoreError> {
        self.summaries_where(
            "m.first_account = ?1 COLLATE NOCASE OR m.second_account = ?1 COLLATE NOCASE",
            account,
            limit.min(MAX_LISTED),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accounts::AccountName;
    use crate::store::{AfterMove, Status, StoredMatch, StoredSeat};
    use game::{Config, MatchResult, RecordedMove, Seat, Side, WinReason};

    fn rated(id: &str, accounts: [&str; 2]) -> StoredMatch {
        StoredMatch {
            id: id.into(),
            created_at: 0,
            config: Config::default(),
            seed: 7,
            physics: 1,
            status: Status::Live,
            bot: None,
            turn_seconds: 60,
            seats: accounts.map(|a| StoredSeat {
                name: Some(a.into()),
                token: None,
                account: Some(a.into()),
            }),
            rematch_of: None,
            rated: true,
        }
    }

    fn resign_first(store: &Store, id: &str, index: usize) -> Result<(), StoreError> {
        let result = MatchResult::Won {
            side: Side::Black,
            reason: WinReason::Resignation,
        };
        store.append_move(
            id,
            index,
            &RecordedMove::Resign { side: Side::White },
            &AfterMove {
                status: Status::Finished,
                shots: 0,
                result: Some(&result),
                winner: Some(Seat::Second),
            },
        )
    }

    fn account(store: &Store, name: &str) -> crate::accounts::Profile {
        store.account(name).unwrap().unwrap()
    }

    #[test]
    fn the_last_move_of_a_rated_match_moves_both_ratings_once() {
        let store = Store::in_memory().unwrap();
        for n in ["Anka", "Petka"] {
            store
                .create_account(&AccountName::parse(n).unwrap(), false)
                .unwrap();
        }
        store.create(&rated("m1", ["Anka", "Petka"])).unwrap();
        resign_first(&store, "m1", 0).unwrap();
        let (anka, petka) = (account(&store, "Anka"), account(&store, "Petka"));
        assert!(
            anka.rating < 1500 && petka.rating > 1500,
            "{anka:?} {petka:?}"
        );
        assert_eq!(anka.rating + petka.rating, 3000, "equals exchange points");
        assert_eq!((anka.games, petka.games), (1, 1));
        // The same last move again is refused (its index is taken) and
        // rates nothing.
        assert!(resign_first(&store, "m1", 0).is_err());
        assert_eq!(account(&store, "Anka"), anka);
        let history = store.rating_history("anka", 10).unwrap();
        assert_eq!(history.len(), 1);
        assert_eq!(
            (history[0].match_id.as_str(), history[0].rating),
            ("m1", anka.rating)
        );
        let played = store.matches_of("PETKA", 10).unwrap();
        assert_eq!(played.len(), 1);
        assert!(played[0].rated);
        assert_eq!(played[0].second_rating.unwrap().rating, petka.rating);
    }

    #[test]
    fn a_casual_match_or_a_seat_without_an_account_rates_nothing() {
        let store = Store::in_memory().unwrap();
        for n in ["Anka", "Petka"] {
            store
                .create_account(&AccountName::parse(n).unwrap(), false)
                .unwrap();
        }
        let mut casual = rated("m1", ["Anka", "Petka"]);
        casual.rated = false;
        store.create(&casual).unwrap();
        resign_first(&store, "m1", 0).unwrap();
        let mut anonymous = rated("m2", ["Anka", "Petka"]);
        anonymous.seats[1].account = None;
        store.create(&anonymous).unwrap();
        resign_first(&store, "m2", 0).unwrap();
        for n in ["Anka", "Petka"] {
            let a = account(&store, n);
            assert_eq!((a.rating, a.games), (1500, 0), "{n}");
        }
        assert!(store.rating_history("Anka", 10).unwrap().is_empty());
    }

    #[test]
    fn the_computer_levels_have_bot_accounts_nobody_can_register() {
        let store = Store::in_memory().unwrap();
        for level in bots::Level::ALL {
            let a = account(&store, &computer_account(level));
            assert!(a.bot);
            assert_eq!(a.rating, 1500);
        }
        let taken = AccountName::parse("Computer-Hard").unwrap_err();
        assert_eq!(taken.code, game::protocol::ErrorCode::BadName);
    }
}
