//! The `record_replay` target: bytes read as a match record
//! ([`MatchRecord::from_json`]) and replayed ([`Replay::new`]). A record
//! that reads must read back from its own JSON as itself, and is either
//! replayed or refused with an error; a replayed one must agree with
//! itself — one view per move and the final one, one film per recorded
//! shot, each finite from the flick to its end, and the replayed match
//! recording the very moves it was given.
//!
//! Whatever the replay says, the record's rules and moves are also played
//! afresh through a [`Game`] (its first [`MAX_PLAYED_SHOTS`] shots that are
//! legal, as aimed; the moves the game refuses skipped), and that match must
//! replay from its own JSON record to the same state: the bit-exact replay
//! promise, under any valid configuration the fuzzer finds.

use game::config::Config;
use game::record::RecordedMove;
use game::{Game, MatchRecord, NoiseKey, Replay, Shot, Side};

/// Most shots played afresh from one record (each may take up to the
/// config's event cap).
pub const MAX_PLAYED_SHOTS: usize = 3;

/// Replays the record `data` holds, if it holds one.
pub fn record_replay(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let record = match MatchRecord::from_json(text) {
        Ok(record) => record,
        Err(e) => {
            assert!(!e.to_string().is_empty(), "a refused record is told why");
            return;
        }
    };
    assert_eq!(
        MatchRecord::from_json(&record.to_json()).as_ref(),
        Ok(&record),
        "a record reads back from its own JSON"
    );
    match Replay::new(record.clone()) {
        Ok(replay) => check(&record, &replay),
        Err(e) => assert!(!e.to_string().is_empty(), "a refused replay is told why"),
    }
    play_again(&record);
}

/// Plays the record's moves afresh and replays the match that makes.
fn play_again(record: &MatchRecord) {
    // Beyond the default event cap a shot may take seconds: not a finding.
    if record.config.max_events_per_shot > Config::default().max_events_per_shot {
        return;
    }
    let key = record.key().unwrap_or(NoiseKey::SplitMix64(0));
    let Ok(mut game) = Game::new(record.config.clone(), key) else {
        return;
    };
    let mut shots = 0;
    for m in &record.moves {
        // A refused move changes nothing; the next one is tried.
        match m {
            RecordedMove::Shot(o) => {
                if shots == MAX_PLAYED_SHOTS {
                    break;
                }
                if let Ok(shot) = Shot::new(o.piece, o.aimed, game.config()) {
                    shots += usize::from(game.play(o.shooter, shot).is_ok());
                }
            }
            RecordedMove::Pie { swap } => {
                let _ = game.decide_pie(Side::Black, *swap);
            }
            RecordedMove::Pass { side } => {
                let _ = game.pass(*side);
            }
            RecordedMove::Resign { side } => {
                let _ = game.resign(*side);
            }
            RecordedMove::Forfeit { side, reason } => {
                let _ = game.forfeit(*side, *reason);
            }
        }
    }
    let json = game.private_record().to_json();
    match Replay::from_json(&json) {
        Ok(replay) => {
            assert_eq!(
                replay.game().view(),
                game.view(),
                "the replay ends as the match"
            );
            assert_eq!(replay.game().result(), game.result());
        }
        Err(e) => panic!("a match played under these rules does not replay: {e}\n{json}"),
    }
}

fn check(record: &MatchRecord, replay: &Replay) {
    assert_eq!(replay.record(), record);
    let moves = record.moves.len();
    assert!(replay.view_before(moves).is_some() && replay.view_before(moves + 1).is_none());
    assert_eq!(replay.view_before(moves), Some(&replay.game().view()));
    assert_eq!(
        serde_json::to_string(&replay.game().record().moves).ok(),
        serde_json::to_string(&record.moves).ok(),
        "the replayed match records the moves it was given"
    );
    assert_eq!(replay.shot_count(), record.shots().count());
    for n in 0..replay.shot_count() {
        let (Some(film), Some(_), Some(_)) = (
            replay.film(n),
            replay.outcome(n),
            replay.view_before_shot(n),
        ) else {
            panic!("shot {n} of {} is missing", replay.shot_count());
        };
        assert!(
            film.end.is_finite() && film.end >= 0.0,
            "shot {n} ends at {}",
            film.end
        );
        for t in [0.0, film.end / 2.0, film.end] {
            for body in film.scene_at(t).bodies {
                assert!(
                    body.pos.is_finite() && body.vel.is_finite(),
                    "shot {n} at {t}: {body:?}"
                );
            }
        }
    }
}
