//! Golden records: whole matches played by an earlier build and kept,
//! with what they came to, so that no later build changes what a shot does
//! without saying so. A golden record is a [`MatchRecord`] with a digest of
//! the board each shot left at rest and the match as it ended; checking it
//! plays every move again under the record's physics version and compares
//! every number the record holds by its bits, naming the first that
//! differs. This module owns the file format, making one from a record,
//! and that check; the files live in `game/tests/golden/physics-N/`, one
//! folder per physics version, and `game/tests/golden.rs` checks them all.
//!
//! A golden record that no longer replays means a shot's outcome changed:
//! the change needs a new physics version, with the old one kept playing
//! ([`WHAT_TO_DO`]). Golden records are only ever written for the current
//! version, by the bots crate, with [`BLESS_VAR`] set, and never over a
//! file that still says something else.

use crate::board::Board;
use crate::config::ConfigError;
use crate::game::{Game, GameError, MatchView, Phase};
use crate::outcome::ShotOutcome;
use crate::physics_version::{PhysicsVersion, UnsupportedPhysics, PHYSICS_VERSION};
use crate::record::{MatchRecord, RecordError, RecordedMove};
use crate::rows::Rows;
use crate::shot::{Shot, ShotError};
use crate::side::Side;
use serde::{Deserialize, Serialize};
use serde_json::Value;

/// The golden file format this crate reads and writes.
pub const GOLDEN_FORMAT: u32 = 1;

/// The environment variable that lets the bots crate write golden records
/// (`CHAPAEV_BLESS_GOLDEN=1`).
pub const BLESS_VAR: &str = "CHAPAEV_BLESS_GOLDEN";

/// What a developer does when a golden record no longer replays.
pub const WHAT_TO_DO: &str = "\
A golden record no longer replays bit for bit: a change altered the outcome of a shot \
(the engine, game::physics, the noise or the turn rule). Old matches must keep replaying \
and resuming, so do not regenerate the golden records over this. Either undo the change, \
or make it a new physics version: raise game::PHYSICS_VERSION, add a variant to \
game::PhysicsVersion that runs the new code, keep the old variant running the old code \
exactly (so these golden records pass again), and write the golden records of the new \
version with CHAPAEV_BLESS_GOLDEN=1 cargo test -p bots --test golden -- --ignored \
(it writes game/tests/golden/physics-N/ for the new version only).";

/// The folder name of physics version `physics`'s golden records.
pub fn folder_name(physics: u32) -> String {
    format!("physics-{physics}")
}

/// The match as it ended, as a golden record keeps it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GoldenEnd {
    /// Over (with the result), or where an unfinished match stood.
    pub phase: Phase,
    /// The side to shoot.
    pub turn: Side,
    /// Whether the pie rule swapped the seats.
    pub swapped: bool,
    /// The round, 1-based.
    pub round: u32,
    pub rows: Rows,
    /// The pieces, every position to the bit.
    pub board: Board,
    /// Shots played.
    pub shots: u32,
}

impl GoldenEnd {
    fn of(view: &MatchView) -> GoldenEnd {
        GoldenEnd {
            phase: view.phase,
            turn: view.turn,
            swapped: view.swapped,
            round: view.round,
            rows: view.rows,
            board: view.board.clone(),
            shots: view.shots,
        }
    }
}

/// A golden record: a whole match and what replaying it must give.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GoldenRecord {
    /// [`GOLDEN_FORMAT`].
    pub format: u32,
    /// What the match covers (rules, players, how it ended), for people.
    pub about: String,
    /// The match as it ended.
    pub end: GoldenEnd,
    /// Per shot, in order: [`board_digest`] of the board it left at rest
    /// (before a round end set up the next round).
    pub rests: Vec<String>,
    /// The match.
    pub record: MatchRecord,
}

/// Why a golden record does not hold.
#[derive(Debug, thiserror::Error)]
pub enum GoldenError {
    #[error("not a golden record: {0}")]
    Json(#[from] serde_json::Error),
    #[error("golden format {found} is not the format {GOLDEN_FORMAT} this build reads")]
    Format { found: u32 },
    #[error(transparent)]
    Physics(#[from] UnsupportedPhysics),
    #[error("the record's noise: {0}")]
    Noise(#[from] RecordError),
    #[error("the record's config is unplayable: {0}")]
    Config(#[from] ConfigError),
    #[error("move {index}: the recorded shot is refused now: {source}")]
    IllegalShot { index: usize, source: ShotError },
    #[error("move {index}: the recorded move is refused now: {source}")]
    IllegalMove { index: usize, source: GameError },
    #[error("{at}, {path}: recorded {recorded}, replayed {now}")]
    Diverged {
        /// Which move (and shot), or the end.
        at: String,
        /// Where in it, as a JSON path.
        path: String,
        /// The recorded value (numbers with their bits).
        recorded: String,
        /// What replaying gives now.
        now: String,
    },
    #[error("the record has {shots} shots but {rests} rest boards")]
    Rests { shots: usize, rests: usize },
}

impl GoldenError {
    /// Whether this error says that a shot's outcome changed (as opposed to
    /// a file that cannot be read).
    pub fn is_divergence(&self) -> bool {
        matches!(
            self,
            GoldenError::Diverged { .. }
                | GoldenError::IllegalShot { .. }
                | GoldenError::IllegalMove { .. }
                | GoldenError::Rests { .. }
        )
    }
}

/// A digest of `board` that changes with any bit of any position: FNV-1a
/// over every piece's number and the bits of its coordinates, as 16 hex
/// digits.
pub fn board_digest(board: &Board) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |bytes: &[u8]| {
        for &b in bytes {
            h ^= b as u64;
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
    };
    for p in board.pieces() {
        eat(&[p.id.number()]);
        eat(&p.pos.x.to_bits().to_le_bytes());
        eat(&p.pos.y.to_bits().to_le_bytes());
    }
    format!("{h:016x}")
}

/// What a shot gave when played again.
struct Replayed {
    /// What it did.
    outcome: ShotOutcome,
    /// The board it left at rest.
    rest: Board,
}

/// Plays `record` again under its physics version, move by move, calling
/// `each` with every shot's move index and what it gave now; `each` may
/// stop the replay with an error.
fn play_again(
    record: &MatchRecord,
    mut each: impl FnMut(usize, Replayed) -> Result<(), GoldenError>,
) -> Result<Game, GoldenError> {
    let physics = PhysicsVersion::from_number(record.physics)?;
    let mut game = Game::with_physics(record.config.clone(), record.key()?, physics)?;
    for (index, m) in record.moves.iter().enumerate() {
        let illegal = |source| GoldenError::IllegalMove { index, source };
        match m {
            RecordedMove::Shot(recorded) => {
                let shot = Shot::new(recorded.piece, recorded.aimed, game.config())
                    .map_err(|source| GoldenError::IllegalShot { index, source })?;
                let played = game
                    .play(recorded.shooter, shot)
                    .map_err(|source| GoldenError::IllegalShot { index, source })?;
                each(
                    index,
                    Replayed {
                        outcome: played.outcome,
                        rest: played.after,
                    },
                )?;
            }
            RecordedMove::Pie { swap } => game.decide_pie(Side::Black, *swap).map_err(illegal)?,
            RecordedMove::Resign { side } => {
                game.resign(*side).map_err(illegal)?;
            }
            RecordedMove::Pass { side } => game.pass(*side).map_err(illegal)?,
            RecordedMove::Forfeit { side, reason } => {
                game.forfeit(*side, *reason).map_err(illegal)?;
            }
        }
    }
    Ok(game)
}

impl GoldenRecord {
    /// The golden record of `record`, played again now to learn the boards
    /// its shots left and how it ended. `about` says what it covers.
    pub fn of(about: impl Into<String>, record: &MatchRecord) -> Result<GoldenRecord, GoldenError> {
        let mut rests = Vec::new();
        let game = play_again(record, |_, replayed| {
            rests.push(board_digest(&replayed.rest));
            Ok(())
        })?;
        Ok(GoldenRecord {
            format: GOLDEN_FORMAT,
            about: about.into(),
            end: GoldenEnd::of(&game.view()),
            rests,
            record: game.record().clone(),
        })
    }

    /// Plays the record again under its physics version and checks, bit
    /// for bit, every shot's outcome (every number of it: the velocity
    /// played, every event's time, the duration), the verdicts (round ends,
    /// who is next, the result), the board each shot left and the match as
    /// it ended. The first difference is the error.
    pub fn check(&self) -> Result<(), GoldenError> {
        if self.format != GOLDEN_FORMAT {
            return Err(GoldenError::Format { found: self.format });
        }
        let shots = self.record.shots().count();
        if shots != self.rests.len() {
            return Err(GoldenError::Rests {
                shots,
                rests: self.rests.len(),
            });
        }
        let mut shot = 0;
        let game = play_again(&self.record, |index, replayed| {
            let at = format!("move {index} (shot {shot})");
            let recorded = serde_json::to_value(&self.record.moves[index])?;
            let now = serde_json::to_value(RecordedMove::Shot(replayed.outcome))?;
            if let Some((path, a, b)) = first_difference(&recorded, &now) {
                return Err(diverged(at, path, a, b));
            }
            let now = board_digest(&replayed.rest);
            let recorded = &self.rests[shot];
            if &now != recorded {
                return Err(GoldenError::Diverged {
                    at,
                    path: "the board at rest (digest)".into(),
                    recorded: recorded.clone(),
                    now,
                });
            }
            shot += 1;
            Ok(())
        })?;
        let recorded = serde_json::to_value(&self.end)?;
        let now = serde_json::to_value(GoldenEnd::of(&game.view()))?;
        match first_difference(&recorded, &now) {
            Some((path, a, b)) => Err(diverged("the end".into(), path, a, b)),
            None => Ok(()),
        }
    }

    /// Reads a golden record.
    pub fn from_json(text: &str) -> Result<GoldenRecord, GoldenError> {
        Ok(serde_json::from_str(text)?)
    }

    /// The golden record as JSON: the header on the first lines, then one
    /// line per move (so that a change shows move by move in a diff).
    pub fn to_json(&self) -> Result<String, GoldenError> {
        let mut record = serde_json::to_value(&self.record)?;
        let moves = match record.as_object_mut().and_then(|o| o.remove("moves")) {
            Some(Value::Array(moves)) => moves,
            _ => Vec::new(),
        };
        let mut out = format!(
            "{{\"format\":{},\"about\":{},\n\"end\":{},\n\"rests\":{},\n\"record\":",
            self.format,
            serde_json::to_string(&self.about)?,
            serde_json::to_string(&self.end)?,
            serde_json::to_string(&self.rests)?,
        );
        let head = serde_json::to_string(&record)?;
        // `head` is an object; reopen it to append the moves.
        out.push_str(head.strip_suffix('}').unwrap_or(&head));
        if head != "{}" {
            out.push(',');
        }
        out.push_str("\"moves\":[\n");
        let lines = moves
            .iter()
            .map(serde_json::to_string)
            .collect::<Result<Vec<_>, _>>()?;
        out.push_str(&lines.join(",\n"));
        out.push_str("\n]}}\n");
        Ok(out)
    }

    /// Whether this record is of the physics version new matches are
    /// played under.
    pub fn is_current(&self) -> bool {
        self.record.physics == PHYSICS_VERSION
    }
}

fn diverged(at: String, path: String, recorded: &Value, now: &Value) -> GoldenError {
    GoldenError::Diverged {
        at,
        path,
        recorded: show(recorded),
        now: show(now),
    }
}

/// A value for a message: a float with its bits.
fn show(v: &Value) -> String {
    match v {
        Value::Number(n) if n.is_f64() => match n.as_f64() {
            Some(x) => format!("{x:?} (bits {:#018x})", x.to_bits()),
            None => n.to_string(),
        },
        other => other.to_string(),
    }
}

/// The first place where `a` and `b` differ: its path and the two values.
/// Numbers are equal when they are the same integer or floats with the same
/// bits (so `0.0` and `-0.0` differ).
fn first_difference<'v>(a: &'v Value, b: &'v Value) -> Option<(String, &'v Value, &'v Value)> {
    fn walk<'v>(
        path: &mut String,
        a: &'v Value,
        b: &'v Value,
    ) -> Option<(String, &'v Value, &'v Value)> {
        let here = |path: &String| {
            let p = if path.is_empty() { "." } else { path.as_str() };
            Some((p.to_string(), a, b))
        };
        match (a, b) {
            (Value::Number(x), Value::Number(y)) => {
                let same = if x.is_f64() || y.is_f64() {
                    match (x.as_f64(), y.as_f64()) {
                        (Some(p), Some(q)) => {
                            p.to_bits() == q.to_bits() && x.is_f64() == y.is_f64()
                        }
                        _ => false,
                    }
                } else {
                    x == y
                };
                if same {
                    None
                } else {
                    here(path)
                }
            }
            (Value::Array(xs), Value::Array(ys)) => {
                for (k, (x, y)) in xs.iter().zip(ys).enumerate() {
                    let len = path.len();
                    path.push_str(&format!("[{k}]"));
                    let found = walk(path, x, y);
                    path.truncate(len);
                    if found.is_some() {
                        return found;
                    }
                }
                if xs.len() != ys.len() {
                    path.push_str(".length");
                    let found = Some((path.clone(), a, b));
                    return found;
                }
                None
            }
            (Value::Object(xs), Value::Object(ys)) => {
                let keys: std::collections::BTreeSet<&String> =
                    xs.keys().chain(ys.keys()).collect();
                for k in keys {
                    let len = path.len();
                    path.push('.');
                    path.push_str(k);
                    let found = match (xs.get(k), ys.get(k)) {
                        (Some(x), Some(y)) => walk(path, x, y),
                        (x, y) => Some((
                            path.clone(),
                            x.unwrap_or(&Value::Null),
                            y.unwrap_or(&Value::Null),
                        )),
                    };
                    path.truncate(len);
                    if found.is_some() {
                        return found;
                    }
                }
                None
            }
            _ if a == b => None,
            _ => here(path),
        }
    }
    walk(&mut String::new(), a, b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{random_match, variant_config};

    fn golden(seed: u64) -> GoldenRecord {
        let (game, _) = random_match(variant_config(seed), seed, 20_000);
        GoldenRecord::of("a random match", game.record()).unwrap()
    }

    #[test]
    fn a_golden_record_of_a_match_played_now_checks_and_round_trips_through_its_file() {
        for seed in [1, 4] {
            let g = golden(seed);
            assert_eq!(g.rests.len(), g.record.shots().count());
            assert!(g.is_current());
            g.check().unwrap();
            let text = g.to_json().unwrap();
            assert_eq!(text.lines().count(), 5 + g.record.moves.len());
            let back = GoldenRecord::from_json(&text).unwrap();
            assert_eq!(back, g);
            back.check().unwrap();
        }
    }

    #[test]
    fn one_bit_of_one_event_time_is_caught_and_named() {
        let mut g = golden(2);
        let Some((index, RecordedMove::Shot(shot))) = g
            .record
            .moves
            .iter_mut()
            .enumerate()
            .find(|(_, m)| matches!(m, RecordedMove::Shot(s) if s.events.len() > 1))
        else {
            panic!("a shot with events");
        };
        let t = &mut shot.events[1].t;
        *t = f64::from_bits(t.to_bits() ^ 1);
        let err = g.check().unwrap_err();
        assert!(err.is_divergence());
        let text = err.to_string();
        assert!(text.starts_with(&format!("move {index} (shot ")), "{text}");
        assert!(text.contains(".events[1].t: recorded "), "{text}");
        assert!(text.contains("(bits 0x"), "{text}");
    }

    #[test]
    fn a_different_rest_board_or_end_is_caught() {
        let mut g = golden(3);
        g.rests[0] = "0000000000000000".into();
        let err = g.check().unwrap_err();
        assert!(err.to_string().contains("the board at rest"), "{err}");

        let mut g = golden(3);
        g.end.round += 1;
        let err = g.check().unwrap_err();
        assert!(err.to_string().starts_with("the end, .round:"), "{err}");

        let mut g = golden(3);
        g.rests.pop();
        assert!(matches!(g.check(), Err(GoldenError::Rests { .. })));
    }

    #[test]
    fn a_golden_record_of_a_physics_version_this_build_cannot_play_is_refused() {
        let mut g = golden(0);
        g.record.physics = PHYSICS_VERSION + 1;
        let err = g.check().unwrap_err();
        assert!(matches!(err, GoldenError::Physics(_)), "{err}");
        assert!(!err.is_divergence());
    }

    #[test]
    fn minus_zero_is_not_zero_and_a_missing_field_is_named() {
        let a = serde_json::json!({"x": [1, 0.0], "y": 2});
        let b = serde_json::json!({"x": [1, -0.0], "y": 2});
        assert_eq!(first_difference(&a, &b).unwrap().0, ".x[1]");
        let c = serde_json::json!({"x": [1, 0.0]});
        assert_eq!(first_difference(&a, &c).unwrap().0, ".y");
        let d = serde_json::json!({"x": [1, 0.0, 3], "y": 2});
        assert_eq!(first_difference(&a, &d).unwrap().0, ".x.length");
        assert!(first_difference(&a, &a.clone()).is_none());
        let e = serde_json::json!({"x": [1, 0.0], "y": 2.0});
        assert_eq!(first_difference(&a, &e).unwrap().0, ".y");
    }
}
