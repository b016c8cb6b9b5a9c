//! The wire protocol shared by the server, the bots and the client: JSON
//! messages tagged by a `"type"` field, one definition for all three.
//!
//! A client says hello with [`PROTOCOL_VERSION`], creates or joins a match,
//! then shoots, decides the pie rule, resigns, offers or accepts a rematch,
//! chats (in words or by a quick [`Phrase`]). The server answers with the full [`MatchView`] on connect, every
//! shot as [`ServerMessage::ShotPlayed`] — its outcome (the engine's event
//! chain, the pieces knocked off, whose turn is next) and its [`Film`]
//! (every piece's exact trajectory from the flick to rest), so a client
//! animates it exactly without running physics of its own — and errors with
//! stable string codes ([`ErrorCode`]); a request refused is a [`Refusal`],
//! a code with a message for people.
//!
//! ```
//! use game::protocol::{ClientMessage, ErrorCode};
//! let m = ClientMessage::from_json(r#"{"type":"shot","piece":3,"velocity":[0.0,1.5]}"#).unwrap();
//! assert!(matches!(m, ClientMessage::Shot { .. }));
//! assert_eq!(ClientMessage::from_json("{").unwrap_err().code, ErrorCode::BadJson);
//! ```

use crate::board::Board;
use crate::config::Config;
use crate::film::Film;
use crate::game::{GameError, MatchView, Played};
use crate::outcome::{MatchResult, ShotOutcome};
pub use crate::phrase::Phrase;
use crate::piece::PieceId;
use crate::record::MatchRecord;
use crate::shot::ShotError;
use crate::side::{Seat, Side};
use crate::token::SeatToken;
use glam::DVec2;
use serde::{Deserialize, Serialize};

/// The protocol version; a hello with another one is refused.
pub const PROTOCOL_VERSION: u32 = 1;

/// Longest chat message, in characters.
pub const MAX_CHAT_CHARS: usize = 500;

/// What a client sends.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum ClientMessage {
    /// The first message of a connection: the protocol spoken, a name, and
    /// the seat token to play a seat (none: watch). The token travels here,
    /// never in the URL, which proxies and browsers write down. Instead of
    /// the token, `key` (an account's key) plays the seat that account
    /// holds in the match: a bot process that restarted takes its matches
    /// back with the key it signed in with.
    Hello {
        protocol: u32,
        name: String,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        token: Option<SeatToken>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        key: Option<SeatToken>,
    },
    /// Create a match with this configuration (missing fields take the
    /// defaults); the creator takes [`Seat::First`].
    CreateMatch {
        #[serde(default)]
        config: Config,
    },
    /// Join a match as its second player.
    JoinMatch { match_id: String },
    /// Watch a match without playing.
    Watch { match_id: String },
    /// Flick `piece` with `velocity` (m/s, `[x, y]`).
    Shot {
        piece: PieceId,
        #[schemars(with = "[f64; 2]")]
        velocity: DVec2,
    },
    /// Black's pie-rule decision.
    PieDecision { swap: bool },
    /// Give up the match.
    Resign,
    /// Propose another match with the same opponent.
    OfferRematch,
    /// Accept the opponent's rematch offer.
    AcceptRematch,
    /// Say something to the match.
    Chat { text: String },
    /// Say one of the quick phrases, by its code: each reader's client
    /// shows it in the reader's language.
    Phrase { phrase: Phrase },
}

/// Who is in a match.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Players {
    pub first: Option<String>,
    pub second: Option<String>,
}

/// What the server sends.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum ServerMessage {
    /// Answer to a hello.
    Welcome { protocol: u32 },
    /// The match is created; share its id with the opponent.
    MatchCreated { match_id: String },
    /// The full state of a match (on join, watch or reconnect). `you` is
    /// the receiver's seat (`None` for a spectator).
    MatchState {
        match_id: String,
        you: Option<Seat>,
        players: Players,
        view: MatchView,
    },
    /// A shot was played: what it did and how everything moved.
    ShotPlayed {
        outcome: ShotOutcome,
        film: Film,
        /// Where the pieces came to rest: the film's end.
        after: Board,
        /// The match as it stands after the shot: at a round end, the new
        /// round's board and rows, and in `turn` the side that opens it.
        view: MatchView,
    },
    /// Black decided the pie rule.
    PieDecided { swap: bool },
    /// The match ended; the record (with its seed) is now public.
    MatchOver {
        result: MatchResult,
        record: MatchRecord,
    },
    /// A seat offered a rematch.
    RematchOffered { by: Seat },
    /// The rematch has started under this id.
    RematchStarted { match_id: String },
    /// Chat from a seat (`None`: a spectator, under the name it said
    /// hello with). A quick phrase comes with its code in `phrase`, and
    /// its English words in `text`.
    Chat {
        from: Option<Seat>,
        name: String,
        text: String,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        phrase: Option<Phrase>,
    },
    /// A request was refused.
    Error { code: ErrorCode, message: String },
    /// The empty seat was taken (the match starts).
    PlayerJoined { seat: Seat, name: String },
    /// A seated player's last connection dropped; the seat is kept for
    /// `grace_ms`, then forfeited if nobody reconnects with its token.
    PlayerLeft { seat: Seat, grace_ms: u64 },
    /// A seated player is connected again.
    PlayerBack { seat: Seat },
    /// The turn clock: `seat` (playing `side`) must act within
    /// `remaining_ms` (sent on connect and whenever the turn changes).
    Clock {
        seat: Seat,
        side: Side,
        remaining_ms: u64,
    },
    /// `seat` did not act in time: the turn passes (`turn-passed` follows;
    /// a pending pie decision is taken as "keep", `pie-decided`).
    /// `strikes` timeouts in a row; the third forfeits the match.
    TurnTimedOut { seat: Seat, strikes: u32 },
    /// `side`'s turn passed without a shot (its clock ran out); the other
    /// side shoots next.
    TurnPassed { side: Side },
    /// `seat` lost the match without playing it out (a `match-over`
    /// follows).
    Forfeited { seat: Seat, reason: ForfeitReason },
}

pub use crate::outcome::ForfeitReason;
pub use crate::refusal::{read, ErrorCode, ProtocolError, Refusal};

impl ProtocolError {
    /// The error message to send back.
    pub fn to_message(&self) -> ServerMessage {
        ServerMessage::Error {
            code: self.code,
            message: self.message.clone(),
        }
    }
}

impl Refusal {
    /// The `error` message for this refusal.
    pub fn to_message(&self) -> ServerMessage {
        ServerMessage::error(self.code, self.message.clone())
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

/// Where the server serves [`schema`] (and `docs/schema/` ships it).
pub const SCHEMA_PATH: &str = "/api/schema/v1.json";

/// The JSON Schema (draft 2020-12) of protocol version 1, generated from
/// these very types: `$defs` holds every shape, and the four roots are
/// `ClientMessage` (what a client sends on the WebSocket),
/// `ServerMessage` (what it receives), `SimulateRequest` and `Simulation`
/// (the body and answer of `POST /api/simulate`); `MatchRecord` is the
/// replayable record; `StreamClientMessage` and `StreamServerMessage` are
/// the account event stream's. A message is valid when it validates against
/// `{"$ref": "#/$defs/ServerMessage"}` within this document.
pub fn schema() -> serde_json::Value {
    let mut generator = schemars::generate::SchemaSettings::draft2020_12().into_generator();
    let roots = [
        ("ClientMessage", generator.subschema_for::<ClientMessage>()),
        ("ServerMessage", generator.subschema_for::<ServerMessage>()),
        (
            "SimulateRequest",
            generator.subschema_for::<crate::simulate::SimulateRequest>(),
        ),
        (
            "Simulation",
            generator.subschema_for::<crate::simulate::Simulation>(),
        ),
        ("MatchRecord", generator.subschema_for::<MatchRecord>()),
        (
            "StreamClientMessage",
            generator.subschema_for::<crate::stream::StreamClientMessage>(),
        ),
        (
            "StreamServerMessage",
            generator.subschema_for::<crate::stream::StreamServerMessage>(),
        ),
    ];
    let defs = generator.take_definitions(true);
    serde_json::json!({
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "$id": SCHEMA_PATH,
        "title": format!("Chapaev online protocol {PROTOCOL_VERSION}"),
        "description": "Every message of the match server's WebSocket and the bodies of POST /api/simulate, generated from the server's Rust types. Validate a message against {\"$ref\": \"#/$defs/ServerMessage\"} (or ClientMessage, SimulateRequest, Simulation, MatchRecord, and for the account event stream StreamClientMessage and StreamServerMessage).",
        "anyOf": roots.iter().map(|(name, _)| serde_json::json!({"$ref": format!("#/$defs/{name}")})).collect::<Vec<_>>(),
        "$defs": defs,
    })
}

impl ClientMessage {
    /// Whether it is a move of the match (a shot, a pie decision,
    /// resigning, a rematch offer or acceptance): play, which a server's
    /// flood guard must never drop, as opposed to talk (hello, chat).
    pub fn is_move(&self) -> bool {
        matches!(
            self,
            ClientMessage::Shot { .. }
                | ClientMessage::PieDecision { .. }
                | ClientMessage::Resign
                | ClientMessage::OfferRematch
                | ClientMessage::AcceptRematch
        )
    }

    /// Reads a client message; the error carries `bad-json` or `bad-message`.
    pub fn from_json(text: &str) -> Result<Self, ProtocolError> {
        read(text.as_bytes())
    }

    /// The message as JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).expect("client messages always serialise")
    }
}

impl ServerMessage {
    /// Reads a server message.
    pub fn from_json(text: &str) -> Result<Self, ProtocolError> {
        read(text.as_bytes())
    }

    /// The message as JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).expect("server messages always serialise")
    }

    /// The announcement of an accepted shot, with the match's view after it.
    pub fn shot_played(played: Played, view: MatchView) -> Self {
        ServerMessage::ShotPlayed {
            outcome: played.outcome,
            film: played.film,
            after: played.after,
            view,
        }
    }

    /// An error message.
    pub fn error(code: ErrorCode, message: impl Into<String>) -> Self {
        ServerMessage::Error {
            code,
            message: message.into(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::game::Game;
    use crate::shot::{Shot, ShotError};
    use crate::side::Side;

    #[test]
    fn client_messages_are_tagged_by_type_in_kebab_case() {
        let m = ClientMessage::Shot {
            piece: PieceId::new(Side::White, 3).unwrap(),
            velocity: DVec2::new(0.25, 1.5),
        };
        assert_eq!(
            m.to_json(),
            r#"{"type":"shot","piece":3,"velocity":[0.25,1.5]}"#
        );
        assert_eq!(ClientMessage::Resign.to_json(), r#"{"type":"resign"}"#);
        assert_eq!(
            ClientMessage::from_json(r#"{"type":"offer-rematch"}"#).unwrap(),
            ClientMessage::OfferRematch
        );
        let create = ClientMessage::from_json(r#"{"type":"create-match"}"#).unwrap();
        assert_eq!(
            create,
            ClientMessage::CreateMatch {
                config: Config::default()
            }
        );
    }

    #[test]
    fn every_client_message_round_trips() {
        let all = [
            ClientMessage::Hello {
                protocol: PROTOCOL_VERSION,
                name: "Petka".into(),
                token: None,
                key: None,
            },
            ClientMessage::Hello {
                protocol: PROTOCOL_VERSION,
                name: "Anka".into(),
                token: Some(SeatToken::new("540a0bf048fe73e1505aeb84de7f0fcd")),
                key: None,
            },
            ClientMessage::CreateMatch {
                config: Config::default(),
            },
            ClientMessage::JoinMatch {
                match_id: "m1".into(),
            },
            ClientMessage::Watch {
                match_id: "m1".into(),
            },
            ClientMessage::Shot {
                piece: PieceId::new(Side::Black, 7).unwrap(),
                velocity: DVec2::new(-0.1, -1.9),
            },
            ClientMessage::PieDecision { swap: true },
            ClientMessage::Resign,
            ClientMessage::OfferRematch,
            ClientMessage::AcceptRematch,
            ClientMessage::Chat {
                text: "Vasily Ivanovich!".into(),
            },
            ClientMessage::Phrase {
                phrase: Phrase::GoodShot,
            },
        ];
        for m in all {
            assert_eq!(ClientMessage::from_json(&m.to_json()).unwrap(), m);
        }
    }

    #[test]
    fn the_schema_shipped_in_docs_is_the_one_the_types_generate() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../docs/schema/protocol-v1.json"
        );
        let generated = serde_json::to_string_pretty(&schema()).unwrap() + "\n";
        if std::env::var_os("CHAPAEV_BLESS").is_some() {
            std::fs::write(path, &generated).unwrap();
        }
        let shipped = std::fs::read_to_string(path).unwrap_or_default();
        assert!(
            shipped == generated,
            "docs/schema/protocol-v1.json is stale: CHAPAEV_BLESS=1 cargo test -p game schema"
        );
        let defs = &schema()["$defs"];
        for root in [
            "ClientMessage",
            "ServerMessage",
            "SimulateRequest",
            "Simulation",
        ] {
            assert!(defs.get(root).is_some(), "{root} is defined");
        }
    }

    #[test]
    fn unreadable_messages_get_stable_error_codes() {
        assert_eq!(
            ClientMessage::from_json("not json").unwrap_err().code,
            ErrorCode::BadJson
        );
        assert_eq!(
            ClientMessage::from_json(r#"{"type":"teleport"}"#)
                .unwrap_err()
                .code,
            ErrorCode::BadMessage
        );
        assert_eq!(
            ClientMessage::from_json(r#"{"type":"shot","piece":16,"velocity":[0,1]}"#)
                .unwrap_err()
                .code,
            ErrorCode::BadMessage
        );
        // JSON has no NaN; a number beyond a double's range is how a
        // non-finite velocity arrives.
        assert_eq!(
            ClientMessage::from_json(r#"{"type":"shot","piece":4,"velocity":[0,1e400]}"#)
                .unwrap_err()
                .code,
            ErrorCode::NotFinite
        );
        assert_eq!(
            ClientMessage::from_json(r#"{"type":"shot","piece":4,"velocity":[0,NaN]}"#)
                .unwrap_err()
                .code,
            ErrorCode::BadJson
        );
        let e = ClientMessage::from_json("[").unwrap_err().to_message();
        assert!(
            e.to_json()
                .starts_with(r#"{"type":"error","code":"bad-json""#),
            "{}",
            e.to_json()
        );
    }

    #[test]
    fn error_codes_serialise_as_their_stable_strings() {
        for code in [
            ErrorCode::BadJson,
            ErrorCode::NotYourTurn,
            ErrorCode::PieceOffBoard,
            ErrorCode::PieDecisionPending,
            ErrorCode::Internal,
            ErrorCode::TooFast,
            ErrorCode::UnsupportedPhysics,
        ] {
            assert_eq!(
                serde_json::to_string(&code).unwrap(),
                format!("\"{}\"", code.as_str())
            );
        }
        assert_eq!(ShotError::NotFinite.code().as_str(), "not-finite");
        assert_eq!(
            crate::game::GameError::NoPieDecision.code().as_str(),
            "no-pie-decision"
        );
    }

    #[test]
    fn a_played_shot_and_the_match_state_travel_as_server_messages() {
        let mut g = Game::new(Config::default(), 1).unwrap();
        let state = ServerMessage::MatchState {
            match_id: "m".into(),
            you: Some(Seat::First),
            players: Players {
                first: Some("a".into()),
                second: None,
            },
            view: g.view(),
        };
        assert_eq!(ServerMessage::from_json(&state.to_json()).unwrap(), state);
        let piece = PieceId::new(Side::White, 4).unwrap();
        let shot = Shot::new(piece, DVec2::new(0.0, 2.0), g.config()).unwrap();
        let played = g.play(Side::White, shot).unwrap();
        let msg = ServerMessage::shot_played(played, g.view());
        let json = msg.to_json();
        assert!(json.starts_with(r#"{"type":"shot-played""#));
        assert_eq!(ServerMessage::from_json(&json).unwrap(), msg);
        let over = ServerMessage::MatchOver {
            result: g.resign(Side::Black).unwrap(),
            record: g.record().clone(),
        };
        assert_eq!(ServerMessage::from_json(&over.to_json()).unwrap(), over);
    }
}
