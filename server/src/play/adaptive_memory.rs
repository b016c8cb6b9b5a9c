//! What the adaptive level remembers of a person: nothing but the person's
//! own match history. The strength it opens a match with is replayed from
//! the results of the account's last finished matches against it (oldest
//! first, through [`AdaptiveSettings::next_start`]), so it needs no state
//! of its own, survives restarts and is the same on every node.

use crate::store::{Status, Store, StoreError};
use bots::adaptive::AdaptiveSettings;
use bots::Level;
use game::record::RecordedMove;
use game::Seat;

/// How many of the person's latest matches are looked at (those against
/// the adaptive level count).
pub const HISTORY: usize = 40;

/// The strength the adaptive level opens its next match against `account`
/// with.
pub fn start_for(
    store: &dyn Store,
    settings: &AdaptiveSettings,
    account: &str,
) -> Result<f64, StoreError> {
    let mut scores = Vec::new();
    for summary in store.matches_of(account, HISTORY)? {
        // Only finished matches with the adaptive level in a seat are read.
        let against_adaptive = summary
            .bot
            .as_deref()
            .is_some_and(|b| b.split('/').any(|l| l == Level::Adaptive.as_str()));
        if summary.status != Status::Finished || !against_adaptive {
            continue;
        }
        let Some(stored) = store.get(&summary.match_id)? else {
            continue;
        };
        let levels = stored.bots();
        let person = (0..2).find(|&i| {
            levels[1 - i] == Some(Level::Adaptive)
                && stored.seats[i]
                    .account
                    .as_deref()
                    .is_some_and(|a| a.eq_ignore_ascii_case(account))
        });
        let Some(person) = person else {
            continue;
        };
        // Only a match under the pie rule can have swapped seats.
        let swapped = stored.config.variants.pie_rule
            && store
                .moves(&stored.id)?
                .iter()
                .any(|m| matches!(m, RecordedMove::Pie { swap: true }));
        let side = [Seat::First, Seat::Second][person].side(swapped);
        let Some(result) = summary.result else {
            continue;
        };
        scores.push(match result.winner() {
            Some(w) if w == side => 1.0,
            Some(_) => 0.0,
            None => 0.5,
        });
    }
    // Most recent first from the store: replayed oldest first.
    Ok(scores.iter().rev().fold(settings.start, |start, &score| {
        settings.next_start(start, score)
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::store::{AfterMove, SqliteStore, StoredMatch, StoredSeat};
    use game::name::AccountName;
    use game::{Config, MatchResult, NoiseKey, Side, WinReason};

    /// A finished match of `account` (first seat, White) against `level`,
    /// resigned by `loser`.
    fn finished(store: &dyn Store, id: &str, account: &str, level: Level, loser: Side) {
        let m = StoredMatch {
            id: id.into(),
            created_at: 0,
            config: Config::default(),
            noise: NoiseKey::from(7),
            physics: game::PHYSICS_VERSION,
            status: Status::Live,
            bot: StoredMatch::bots_column([None, Some(level)]),
            turn_seconds: 60,
            seats: [
                StoredSeat {
                    name: Some(account.into()),
                    token: None,
                    account: Some(account.into()),
                    module: None,
                },
                StoredSeat {
                    name: Some(format!("bot ({level})")),
                    token: None,
                    account: None,
                    module: None,
                },
            ],
            rematch_of: None,
            rated: false,
            seed: None,
        };
        store.create(&m).unwrap();
        let result = MatchResult::Won {
            side: loser.opponent(),
            reason: WinReason::Resignation,
        };
        let after = AfterMove {
            status: Status::Finished,
            shots: 0,
            result: Some(&result),
            winner: Some(if loser == Side::White {
                Seat::Second
            } else {
                Seat::First
            }),
        };
        store
            .append_move(id, 0, &RecordedMove::Resign { side: loser }, &after)
            .unwrap();
    }

    #[test]
    fn the_adaptive_level_opens_stronger_against_a_person_who_beat_it_and_weaker_after_losses() {
        let sqlite = SqliteStore::in_memory().unwrap();
        let store: &dyn Store = &sqlite;
        let settings = AdaptiveSettings::default();
        for n in ["Anka", "Petka"] {
            store
                .create_account(&AccountName::parse(n).unwrap(), false)
                .unwrap();
        }
        assert_eq!(start_for(store, &settings, "Anka").unwrap(), settings.start);
        // Anka beat the adaptive level twice; a win against `hard` does
        // not count.
        finished(store, "a1", "Anka", Level::Adaptive, Side::Black);
        finished(store, "a2", "Anka", Level::Adaptive, Side::Black);
        finished(store, "a3", "Anka", Level::Hard, Side::Black);
        let up = settings.next_start(settings.next_start(settings.start, 1.0), 1.0);
        assert_eq!(start_for(store, &settings, "anka").unwrap(), up);
        // Petka lost to it once.
        finished(store, "p1", "Petka", Level::Adaptive, Side::White);
        let down = settings.next_start(settings.start, 0.0);
        assert_eq!(start_for(store, &settings, "Petka").unwrap(), down);
        assert!(down < settings.start && settings.start < up);
    }
}
