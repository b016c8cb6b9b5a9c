//! One decision of a bot that runs outside the Rust process — a
//! WebAssembly module on the server, or any program speaking JSON lines —
//! as plain JSON: the [`DecideRequest`] it is handed (its side and the
//! public [`MatchView`], never the noise secret) and its answer, which is
//! the very message a bot would send on a match's WebSocket for that
//! decision: `{"type":"shot","piece":3,"velocity":[0.0,1.5]}`,
//! `{"type":"pie-decision","swap":true}` or `{"type":"resign"}`
//! ([`ClientMessage`]). One definition for the server's runtime, the
//! `bots match` command and the bot SDK.

use crate::game::MatchView;
use crate::protocol::ClientMessage;
use crate::session::BotDecision;
use crate::shot::{Shot, ShotError};
use crate::side::Side;
use serde::{Deserialize, Serialize};

/// What a bot is asked: decide for `me` on `view` (a shot when it is
/// `me`'s turn to shoot, the pie rule when Black holds that decision).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DecideRequest {
    /// The side the bot decides for.
    pub me: Side,
    /// What any player may know of the match now.
    pub view: MatchView,
}

/// An answer that is not a decision.
#[derive(Debug, thiserror::Error)]
pub enum AnswerError {
    /// Not JSON, or not one of the client messages.
    #[error("the answer is not a client message: {0}")]
    Json(#[from] serde_json::Error),
    /// A client message, but not one that decides (a chat, a hello).
    #[error("a {0:?} message is not a decision: answer shot, pie-decision or resign")]
    NotADecision(&'static str),
    /// A shot the match's configuration refuses (not finite, too fast).
    #[error("the shot is not playable: {0}")]
    Shot(#[from] ShotError),
}

impl DecideRequest {
    /// The request as one line of JSON (no newline inside).
    pub fn to_json(&self) -> String {
        // A view holds only finite numbers and plain fields: it always
        // serializes.
        serde_json::to_string(self).unwrap_or_default()
    }

    /// Reads a bot's answer `text` as a decision under this request's
    /// configuration.
    pub fn answer(&self, text: &[u8]) -> Result<BotDecision, AnswerError> {
        let msg: ClientMessage = serde_json::from_slice(text)?;
        Ok(match msg {
            ClientMessage::Shot { piece, velocity } => {
                BotDecision::Shot(Shot::new(piece, velocity, &self.view.config)?)
            }
            ClientMessage::PieDecision { swap } => BotDecision::Pie { swap },
            ClientMessage::Resign => BotDecision::Resign,
            ClientMessage::Hello { .. } => return Err(AnswerError::NotADecision("hello")),
            ClientMessage::CreateMatch { .. } => {
                return Err(AnswerError::NotADecision("create-match"))
            }
            ClientMessage::JoinMatch { .. } => return Err(AnswerError::NotADecision("join-match")),
            ClientMessage::Watch { .. } => return Err(AnswerError::NotADecision("watch")),
            ClientMessage::OfferRematch => return Err(AnswerError::NotADecision("offer-rematch")),
            ClientMessage::AcceptRematch => {
                return Err(AnswerError::NotADecision("accept-rematch"))
            }
            ClientMessage::Chat { .. } => return Err(AnswerError::NotADecision("chat")),
            ClientMessage::Phrase { .. } => return Err(AnswerError::NotADecision("phrase")),
        })
    }
}

/// The message that carries `decision` (what a bot answers; `None` for
/// [`BotDecision::NoAnswer`], which has none).
pub fn answer_message(decision: &BotDecision) -> Option<ClientMessage> {
    Some(match *decision {
        BotDecision::Shot(shot) => ClientMessage::Shot {
            piece: shot.piece(),
            velocity: shot.velocity(),
        },
        BotDecision::Pie { swap } => ClientMessage::PieDecision { swap },
        BotDecision::Resign => ClientMessage::Resign,
        BotDecision::NoAnswer => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Config, Game};

    fn request() -> DecideRequest {
        DecideRequest {
            me: Side::White,
            view: Game::new(Config::standard(), 1).unwrap().view(),
        }
    }

    #[test]
    fn a_request_round_trips_through_one_line_of_json() {
        let r = request();
        let line = r.to_json();
        assert!(!line.contains('\n'));
        let back: DecideRequest = serde_json::from_str(&line).unwrap();
        assert_eq!(back, r);
    }

    #[test]
    fn answers_are_the_sockets_decision_messages_and_read_back() {
        let r = request();
        let shot = Shot::new(
            crate::PieceId::new(Side::White, 3).unwrap(),
            glam::DVec2::new(0.0, 1.5),
            &r.view.config,
        )
        .unwrap();
        for d in [
            BotDecision::Shot(shot),
            BotDecision::Pie { swap: true },
            BotDecision::Resign,
        ] {
            let text = serde_json::to_vec(&answer_message(&d).unwrap()).unwrap();
            assert_eq!(r.answer(&text).unwrap(), d);
        }
        assert_eq!(answer_message(&BotDecision::NoAnswer), None);
    }

    #[test]
    fn a_non_decision_or_an_unplayable_shot_is_refused_with_its_reason() {
        let r = request();
        assert!(matches!(
            r.answer(br#"{"type":"chat","text":"hi"}"#),
            Err(AnswerError::NotADecision("chat"))
        ));
        assert!(matches!(r.answer(b"{"), Err(AnswerError::Json(_))));
        assert!(matches!(
            r.answer(br#"{"type":"shot","piece":3,"velocity":[0.0,1e9]}"#),
            Err(AnswerError::Shot(ShotError::TooFast { .. }))
        ));
    }
}
