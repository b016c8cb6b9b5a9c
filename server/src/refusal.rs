//! A refused request as the server answers it: the [`Refusal`] itself (the
//! stable wire [`ErrorCode`] and a human-readable message) lives in
//! [`game::protocol`], where the match session makes it; this module adds
//! the HTTP status that goes with each code, for refusals sent as the JSON
//! body of an HTTP error.

use game::protocol::ErrorCode;
pub use game::protocol::Refusal;

/// The HTTP status of a refusal.
pub trait HttpStatus {
    /// The HTTP status that goes with the refusal's code.
    fn http_status(&self) -> u16;
}

impl HttpStatus for Refusal {
    fn http_status(&self) -> u16 {
        match self.code {
            ErrorCode::NoSuchMatch
            | ErrorCode::NoSuchAccount
            | ErrorCode::NoSuchChallenge
            | ErrorCode::NoSuchFile
            | ErrorCode::NoSuchVersion => 404,
            ErrorCode::BadKey | ErrorCode::BadPassword => 401,
            ErrorCode::MatchFull
            | ErrorCode::NameTaken
            | ErrorCode::MatchOver
            | ErrorCode::MatchNotOver
            | ErrorCode::SameAccount
            | ErrorCode::UnsupportedPhysics
            | ErrorCode::TooManyVersions
            | ErrorCode::ModuleInUse => 409,
            ErrorCode::BadToken
            | ErrorCode::ForbiddenOrigin
            | ErrorCode::BotKeyInBrowser
            | ErrorCode::NotABot => 403,
            ErrorCode::RateLimited => 429,
            ErrorCode::MessageTooLarge => 413,
            ErrorCode::ServerBusy => 503,
            ErrorCode::Internal => 500,
            _ => 400,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use game::ShotError;

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
