//! Replaying a match record: every move is played again through a fresh
//! [`Game`], under the physics version the record names, and each shot's
//! outcome is checked, bit for bit, against the recorded one. A record of a
//! physics version this build cannot play is refused before anything is
//! played ([`ReplayError::Physics`]), never replayed with other physics. The replay keeps each shot's [`Film`] and the match state
//! around each move, so a viewer can scrub to any moment of any shot.

use crate::config::ConfigError;
use crate::film::Film;
use crate::game::{Game, GameError, MatchView};
use crate::outcome::ShotOutcome;
use crate::physics_version::{PhysicsVersion, UnsupportedPhysics};
use crate::record::{MatchRecord, RecordError, RecordedMove};
use crate::shot::{Shot, ShotError};
use engine::Scene;

/// Why a record could not be replayed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ReplayError {
    #[error(transparent)]
    Record(#[from] RecordError),
    #[error(transparent)]
    Physics(#[from] UnsupportedPhysics),
    #[error("the record's config is unplayable: {0}")]
    Config(#[from] ConfigError),
    #[error("move {index}: the recorded shot is refused: {error}")]
    IllegalShot { index: usize, error: ShotError },
    #[error("move {index}: the recorded move is refused: {error}")]
    IllegalMove { index: usize, error: GameError },
    #[error("move {index}: replaying the shot gives a different outcome than recorded")]
    Diverged { index: usize },
}

/// A replayed match.
#[derive(Clone, Debug)]
pub struct Replay {
    record: MatchRecord,
    /// `views[k]`: the match before move `k`; the last one is the final state.
    views: Vec<MatchView>,
    /// Per shot: the index of its move and its film.
    shots: Vec<(usize, Film)>,
    game: Game,
}

impl Replay {
    /// Replays a record read from JSON.
    pub fn from_json(text: &str) -> Result<Replay, ReplayError> {
        Replay::new(MatchRecord::from_json(text)?)
    }

    /// Replays `record` under its physics version, checking every shot's
    /// outcome against it.
    pub fn new(record: MatchRecord) -> Result<Replay, ReplayError> {
        let physics = PhysicsVersion::from_number(record.physics)?;
        let mut game = Game::with_physics(record.config.clone(), record.key()?, physics)?;
        let mut views = Vec::with_capacity(record.moves.len() + 1);
        let mut shots = Vec::new();
        for (index, m) in record.moves.iter().enumerate() {
            views.push(game.view());
            match m {
                RecordedMove::Shot(recorded) => {
                    let shot = Shot::new(recorded.piece, recorded.aimed, game.config())
                        .map_err(|error| ReplayError::IllegalShot { index, error })?;
                    let played = game
                        .play(recorded.shooter, shot)
                        .map_err(|error| ReplayError::IllegalShot { index, error })?;
                    if !same_bits(&played.outcome, recorded) {
                        return Err(ReplayError::Diverged { index });
                    }
                    shots.push((index, played.film));
                }
                RecordedMove::Pie { swap } => game
                    .decide_pie(crate::side::Side::Black, *swap)
                    .map_err(|error| ReplayError::IllegalMove { index, error })?,
                RecordedMove::Pass { side } => game
                    .pass(*side)
                    .map_err(|error| ReplayError::IllegalMove { index, error })?,
                RecordedMove::Forfeit { side, reason } => {
                    game.forfeit(*side, *reason)
                        .map_err(|error| ReplayError::IllegalMove { index, error })?;
                }
                RecordedMove::Resign { side } => {
                    game.resign(*side)
                        .map_err(|error| ReplayError::IllegalMove { index, error })?;
                }
            }
        }
        views.push(game.view());
        Ok(Replay {
            record,
            views,
            shots,
            game,
        })
    }

    /// The record replayed.
    pub fn record(&self) -> &MatchRecord {
        &self.record
    }

    /// The match as it ended (or stands, for an unfinished record).
    pub fn game(&self) -> &Game {
        &self.game
    }

    /// Number of shots in the match.
    pub fn shot_count(&self) -> usize {
        self.shots.len()
    }

    /// What shot `n` (0-based) did.
    pub fn outcome(&self, n: usize) -> Option<&ShotOutcome> {
        let (index, _) = self.shots.get(n)?;
        match &self.record.moves[*index] {
            RecordedMove::Shot(o) => Some(o),
            _ => None,
        }
    }

    /// The motion of shot `n`.
    pub fn film(&self, n: usize) -> Option<&Film> {
        self.shots.get(n).map(|(_, f)| f)
    }

    /// The pieces at time `t` (seconds from the flick) of shot `n`.
    pub fn scene_at(&self, n: usize, t: f64) -> Option<Scene> {
        self.film(n).map(|f| f.scene_at(t))
    }

    /// The match just before move `k` (`k == moves.len()`: the final state).
    pub fn view_before(&self, k: usize) -> Option<&MatchView> {
        self.views.get(k)
    }

    /// The match just before shot `n`.
    pub fn view_before_shot(&self, n: usize) -> Option<&MatchView> {
        self.shots.get(n).and_then(|(k, _)| self.views.get(*k))
    }
}

/// Equal to the last bit: with shortest round-trip float printing, two
/// outcomes print the same JSON exactly when every number has the same bits.
fn same_bits(a: &ShotOutcome, b: &ShotOutcome) -> bool {
    serde_json::to_string(a).ok() == serde_json::to_string(b).ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Config;
    use crate::testing::{random_match, variant_config};
    use engine::Scene;

    fn same_scene(a: &Scene, b: &Scene, what: &str) {
        assert_eq!(a.bodies.len(), b.bodies.len(), "{what}");
        for (x, y) in a.bodies.iter().zip(&b.bodies) {
            assert_eq!(x.id, y.id, "{what}");
            for (p, q) in [
                (x.pos.x, y.pos.x),
                (x.pos.y, y.pos.y),
                (x.vel.x, y.vel.x),
                (x.vel.y, y.vel.y),
            ] {
                assert_eq!(p.to_bits(), q.to_bits(), "{what}: {p} vs {q}");
            }
        }
    }

    #[test]
    fn random_matches_replayed_from_their_json_record_give_bit_identical_states() {
        for seed in 0..100 {
            let (game, films) = random_match(variant_config(seed), seed, 20_000);
            let json = game.record().to_json();
            let replay = Replay::from_json(&json).unwrap();
            assert_eq!(replay.shot_count(), films.len());
            assert_eq!(replay.record(), game.record());
            for (n, film) in films.iter().enumerate() {
                let again = replay.film(n).unwrap();
                for k in 0..=8 {
                    let t = film.end * k as f64 / 8.0;
                    same_scene(
                        &again.scene_at(t),
                        &film.scene_at(t),
                        &format!("seed {seed} shot {n} t {t}"),
                    );
                }
                assert_eq!(again.end.to_bits(), film.end.to_bits());
            }
            let (a, b) = (replay.game().board(), game.board());
            assert_eq!(a.pieces().len(), b.pieces().len());
            for (p, q) in a.pieces().iter().zip(b.pieces()) {
                assert_eq!(
                    (p.pos.x.to_bits(), p.pos.y.to_bits()),
                    (q.pos.x.to_bits(), q.pos.y.to_bits())
                );
            }
            assert_eq!(replay.game().view(), game.view());
            assert_eq!(replay.game().result(), game.result());
        }
    }

    #[test]
    fn any_moment_of_any_shot_can_be_shown() {
        let (game, _) = random_match(Config::default(), 3, 20_000);
        let replay = Replay::new(game.record().clone()).unwrap();
        assert!(replay.shot_count() > 0);
        for n in 0..replay.shot_count() {
            let film = replay.film(n).unwrap();
            let before = replay.view_before_shot(n).unwrap();
            // At the flick: the board as it stood before the shot.
            let start = replay.scene_at(n, 0.0).unwrap();
            let outcome = replay.outcome(n).unwrap();
            let fell_at_zero = outcome
                .events
                .iter()
                .filter(|e| e.t == 0.0 && e.kind.name() == "region-exit")
                .count();
            assert_eq!(
                start.bodies.len() + fell_at_zero,
                before.board.pieces().len()
            );
            // At the end: nothing moves and the knocked-off pieces are gone.
            let end = replay.scene_at(n, film.end).unwrap();
            assert!(end.bodies.iter().all(|b| b.vel == glam::DVec2::ZERO));
            assert_eq!(
                end.bodies.len(),
                before.board.pieces().len() - outcome.knocked_off.len()
            );
            // Halfway: every piece is on the board.
            let mid = replay.scene_at(n, film.end / 2.0).unwrap();
            assert!(mid
                .bodies
                .iter()
                .all(|b| crate::board::is_on_board(game.config(), b.pos)));
        }
        assert_eq!(
            replay.view_before(replay.record().moves.len()).unwrap(),
            &game.view()
        );
    }

    #[test]
    fn a_tampered_record_is_caught_as_diverging() {
        let (game, _) = random_match(Config::default(), 5, 20_000);
        let mut record = game.record().clone();
        let RecordedMove::Shot(first) = &mut record.moves[0] else {
            panic!("the first move is a shot");
        };
        first.played.x = f64::from_bits(first.played.x.to_bits() ^ 1);
        // One bit of one number is enough.
        assert!(matches!(
            Replay::new(record),
            Err(ReplayError::Diverged { index: 0 })
        ));
    }

    #[test]
    fn a_record_with_an_illegal_move_is_refused() {
        let mut record = MatchRecord::new(
            Config::default(),
            &crate::NoiseKey::SplitMix64(0),
            PhysicsVersion::CURRENT,
        );
        record.moves.push(RecordedMove::Pie { swap: true });
        assert!(matches!(
            Replay::new(record),
            Err(ReplayError::IllegalMove {
                index: 0,
                error: GameError::NoPieDecision
            })
        ));
        let json = r#"{"version": 99, "config": {}, "seed": 0, "moves": []}"#;
        assert!(matches!(
            Replay::from_json(json),
            Err(ReplayError::Record(RecordError::UnsupportedVersion { .. }))
        ));
    }

    #[test]
    fn a_record_of_a_physics_version_this_build_cannot_play_is_refused_not_replayed() {
        let (game, _) = random_match(Config::default(), 6, 20_000);
        let mut record = game.record().clone();
        assert_eq!(record.physics, crate::PHYSICS_VERSION);
        record.physics = crate::PHYSICS_VERSION + 1;
        let err = Replay::from_json(&record.to_json()).unwrap_err();
        assert_eq!(
            err,
            ReplayError::Physics(UnsupportedPhysics {
                found: crate::PHYSICS_VERSION + 1
            })
        );
        assert!(err.to_string().contains("cannot play"), "{err}");
    }

    #[test]
    fn a_version_2_record_without_physics_replays_under_physics_1() {
        let (game, _) = random_match(Config::default(), 8, 20_000);
        let mut v: serde_json::Value = serde_json::from_str(&game.record().to_json()).unwrap();
        v["version"] = serde_json::json!(2);
        v.as_object_mut().unwrap().remove("physics");
        // Formats before 4 keyed the noise with a seed (this match has none).
        v.as_object_mut().unwrap().remove("noise");
        v["seed"] = serde_json::json!(8);
        let replay = Replay::from_json(&v.to_string()).unwrap();
        assert_eq!(replay.game().physics(), PhysicsVersion::V1);
        // Played again from a seed, the match has no commitment to show.
        let mut view = game.view();
        view.noise_commitment = None;
        assert_eq!(replay.game().view(), view);
    }
}
