//! The `record_replay` target: bytes read as a match record
//! ([`MatchRecord::from_json`]) and replayed ([`Replay::new`]). A record
//! that reads must read back from its own JSON as itself, and is either
//! replayed or refused with an error; a replayed one must agree with
//! itself — one view per move and the final one, one film per recorded
//! shot, each finite from the flick to its end, and the replayed match
//! recording the very moves it was given.

use game::{MatchRecord, Replay};

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
