//! Replaying a match record: every move is played again through a fresh
//! [`Game`] and each shot's outcome is checked, bit for bit, against the
//! recorded one. The replay keeps each shot's [`Film`] and the match state
//! around each move, so a viewer can scrub to any moment of any shot.

use crate::config::ConfigError;
use crate::film::Film;
use crate::game::{Game, GameError, MatchView};
use crate::outcome::ShotOutcome;
use crate::record::{MatchRecord, RecordError, RecordedMove};
use crate::shot::{Shot, ShotError};
use engine::Scene;

/// Why a record could not be replayed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ReplayError {
    #[error(transparent)]
    Record(#[from] RecordError),
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

    /// Replays `record`, checking every shot's outcome against it.
    pub fn new(record: MatchRecord) -> Result<Replay, ReplayError> {
        let mut game = Game::new(record.config.clone(), record.seed)?;
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
