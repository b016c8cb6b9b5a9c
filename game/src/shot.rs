//! A shot: which piece is flicked, and with what velocity — and every reason
//! a shot can be refused.
//!
//! A [`Shot`] can only be built valid on its own terms (finite, moving, not
//! faster than the configuration allows); whether it may be played *now*
//! (whose turn, whose piece, is it still on the board, is the match over)
//! is checked by [`crate::Game::play`]. Both kinds of refusal are a
//! [`ShotError`], and a refused shot changes nothing.

use crate::config::Config;
use crate::piece::PieceId;
use crate::side::Side;
use glam::DVec2;
use serde::Serialize;

/// A valid flick of one piece: finite velocity, `0 < speed <= max_speed`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Shot {
    piece: PieceId,
    velocity: DVec2,
}

/// Why a shot was refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ShotError {
    #[error("it is {turn}'s turn, not {side}'s")]
    NotYourTurn { side: Side, turn: Side },
    #[error("{piece} is not {side}'s")]
    NotYourPiece { piece: PieceId, side: Side },
    #[error("{0} is no longer on the board")]
    PieceOffBoard(PieceId),
    #[error("the velocity must be finite numbers")]
    NotFinite,
    #[error("a shot must have a speed above zero")]
    ZeroSpeed,
    #[error("speed {speed} is above the maximum {max}")]
    TooFast { speed: f64, max: f64 },
    #[error("the match is over")]
    MatchOver,
    #[error("waiting for black's pie-rule decision")]
    PieDecisionPending,
    #[error("the engine could not resolve the shot: {0}")]
    Physics(String),
}

impl ShotError {
    /// The stable wire code of this error (see [`crate::refusal::ErrorCode`]).
    pub fn code(&self) -> crate::refusal::ErrorCode {
        use crate::refusal::ErrorCode as C;
        match self {
            ShotError::NotYourTurn { .. } => C::NotYourTurn,
            ShotError::NotYourPiece { .. } => C::NotYourPiece,
            ShotError::PieceOffBoard(_) => C::PieceOffBoard,
            ShotError::NotFinite => C::NotFinite,
            ShotError::ZeroSpeed => C::ZeroSpeed,
            ShotError::TooFast { .. } => C::TooFast,
            ShotError::MatchOver => C::MatchOver,
            ShotError::PieDecisionPending => C::PieDecisionPending,
            ShotError::Physics(_) => C::Internal,
        }
    }
}

impl Shot {
    /// A shot of `piece` with `velocity` (m/s), if it is finite, non-zero
    /// and within `config.max_speed`.
    pub fn new(piece: PieceId, velocity: DVec2, config: &Config) -> Result<Shot, ShotError> {
        check_velocity(velocity, config.max_speed)?;
        Ok(Shot { piece, velocity })
    }

    /// A shot of `piece` along `direction` (any length) at `speed`.
    pub fn aimed(
        piece: PieceId,
        direction: DVec2,
        speed: f64,
        config: &Config,
    ) -> Result<Shot, ShotError> {
        if !direction.is_finite() || !speed.is_finite() {
            return Err(ShotError::NotFinite);
        }
        let len = direction.length();
        if len == 0.0 || !len.is_finite() {
            return Err(ShotError::ZeroSpeed);
        }
        Shot::new(piece, direction / len * speed, config)
    }

    /// The piece flicked.
    pub fn piece(&self) -> PieceId {
        self.piece
    }

    /// Its velocity as aimed, m/s.
    pub fn velocity(&self) -> DVec2 {
        self.velocity
    }

    /// Its speed as aimed, m/s.
    pub fn speed(&self) -> f64 {
        self.velocity.length()
    }
}

/// Finite, non-zero, at most `max_speed`.
pub(crate) fn check_velocity(velocity: DVec2, max_speed: f64) -> Result<(), ShotError> {
    if !velocity.is_finite() {
        return Err(ShotError::NotFinite);
    }
    let speed = velocity.length();
    if !speed.is_finite() {
        return Err(ShotError::NotFinite);
    }
    if speed == 0.0 {
        return Err(ShotError::ZeroSpeed);
    }
    if speed > max_speed {
        return Err(ShotError::TooFast {
            speed,
            max: max_speed,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn piece() -> PieceId {
        PieceId::new(Side::White, 0).unwrap()
    }

    #[test]
    fn non_finite_velocities_are_refused() {
        let c = Config::default();
        for v in [
            DVec2::new(f64::NAN, 0.0),
            DVec2::new(0.0, f64::INFINITY),
            DVec2::new(1e300, 1e300),
        ] {
            let e = Shot::new(piece(), v, &c).unwrap_err();
            assert!(
                matches!(e, ShotError::NotFinite | ShotError::TooFast { .. }),
                "{e:?}"
            );
        }
        assert_eq!(
            Shot::new(piece(), DVec2::new(f64::NAN, 0.0), &c),
            Err(ShotError::NotFinite)
        );
        assert_eq!(
            Shot::aimed(piece(), DVec2::Y, f64::NAN, &c),
            Err(ShotError::NotFinite)
        );
    }

    #[test]
    fn zero_speed_is_refused() {
        let c = Config::default();
        assert_eq!(
            Shot::new(piece(), DVec2::ZERO, &c),
            Err(ShotError::ZeroSpeed)
        );
        assert_eq!(
            Shot::aimed(piece(), DVec2::ZERO, 1.0, &c),
            Err(ShotError::ZeroSpeed)
        );
        assert_eq!(
            Shot::aimed(piece(), DVec2::Y, 0.0, &c),
            Err(ShotError::ZeroSpeed)
        );
    }

    #[test]
    fn too_high_speed_is_refused_and_the_maximum_itself_is_allowed() {
        let c = Config::default();
        let e = Shot::new(piece(), DVec2::new(0.0, 2.0 + 1e-9), &c).unwrap_err();
        assert!(matches!(e, ShotError::TooFast { max, .. } if max == 2.0));
        let s = Shot::new(piece(), DVec2::new(0.0, 2.0), &c).unwrap();
        assert_eq!(s.speed(), 2.0);
        let s = Shot::aimed(piece(), DVec2::new(3.0, 4.0), 1.0, &c).unwrap();
        assert!((s.velocity() - DVec2::new(0.6, 0.8)).length() < 1e-15);
    }

    #[test]
    fn error_codes_are_stable_strings() {
        assert_eq!(
            ShotError::NotYourTurn {
                side: Side::White,
                turn: Side::Black
            }
            .code()
            .as_str(),
            "not-your-turn"
        );
        assert_eq!(
            ShotError::PieceOffBoard(piece()).code().as_str(),
            "piece-off-board"
        );
        assert_eq!(ShotError::MatchOver.code().as_str(), "match-over");
    }
}
