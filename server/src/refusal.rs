//! A refused request: the stable wire [`ErrorCode`] and a human-readable
//! message, sent as an `error` message over the WebSocket or as the JSON
//! body of an HTTP error (with a status code that fits).

use game::protocol::{ErrorCode, ServerMessage};
use game::{GameError, ShotError};

/// Why a request was refused.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{code}: {message}")]
pub struct Refusal {
    pub code: ErrorCode,
    pub message: String,
}

impl Refusal {
    pub fn new(code: ErrorCode, message: impl Into<String>) -> Refusal {
        Refusal {
            code,
            message: message.into(),
        }
    }

    /// The server failed (the cause is logged, not sent).
    pub fn internal() -> Refusal {
        Refusal::new(ErrorCode::Internal, "the server failed; try again")
    }

    /// The `error` message for this refusal.
    pub fn to_message(&self) -> ServerMessage {
        ServerMessage::error(self.code, self.message.clone())
    }

    /// The HTTP status that goes with the code.
    pub fn http_status(&self) -> u16 {
        match self.code {
            ErrorCode::NoSuchMatch => 404,
            ErrorCode::MatchFull | ErrorCode::MatchOver | ErrorCode::MatchNotOver => 409,
            ErrorCode::BadToken => 403,
            ErrorCode::RateLimited => 429,
            ErrorCode::MessageTooLarge => 413,
            ErrorCode::ServerBusy => 503,
            ErrorCode::Internal => 500,
            _ => 400,
        }
    }
}

impl From<ShotError> for Refusal {
    fn from(e: ShotError) -> Refusal {
        Refusal::new(e.code(), e.to_string())
    }
}

impl From<GameError> for Refusal {
    fn from(e: GameError) -> Refusal {
        Refusal::new(e.code(), e.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refusals_carry_the_game_codes_and_map_to_http_statuses() {
        let r: Refusal = ShotError::ZeroSpeed.into();
        assert_eq!(r.code.as_str(), "zero-speed");
        assert_eq!(r.http_status(), 400);
        assert_eq!(Refusal::new(ErrorCode::NoSuchMatch, "x").http_status(), 404);
        assert!(Refusal::internal()
            .to_message()
            .to_json()
            .starts_with(r#"{"type":"error","code":"internal""#));
    }
}
