//! The account event stream's messages: one WebSocket per signed-in
//! account (`/api/stream`), over which a bot process (or a person's
//! browser) stays online, hears of challenges and of its matches starting
//! and finishing, challenges others, asks for a quick pairing and joins the
//! bot ladder. The match itself is played on its own match WebSocket
//! ([`crate::protocol`]), with the seat token that
//! [`StreamServerMessage::MatchStart`] hands over.
//!
//! ```
//! use game::stream::StreamClientMessage;
//! let m = StreamClientMessage::from_json(r#"{"type":"ladder","join":true}"#).unwrap();
//! assert_eq!(m, StreamClientMessage::Ladder { join: true });
//! ```

use crate::outcome::MatchResult;
use crate::refusal::{read, ErrorCode, ProtocolError, Refusal};
use crate::side::{Seat, Side};
use crate::token::SeatToken;
use serde::{Deserialize, Serialize};

/// What an account's client sends on its event stream.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum StreamClientMessage {
    /// The first message: the protocol spoken and the account's key (it
    /// travels here, never in the URL).
    Hello { protocol: u32, key: SeatToken },
    /// Challenge the account `to` to one match.
    Challenge {
        to: String,
        /// Whether the result moves both ratings (then under the
        /// `standard` rules).
        #[serde(default)]
        rated: bool,
        /// The rules: `standard` (the default) or `casual` (unrated only).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        rules: Option<String>,
        /// The turn clock, 1–3600 s (default: the server's).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        turn_seconds: Option<u64>,
        /// The challenger's colour (default: drawn when it is accepted).
        /// Under the pie rule Black may still swap after White's opening.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        color: Option<Side>,
    },
    /// Accept a challenge made to this account.
    Accept { challenge: String },
    /// Decline a challenge made to this account, saying why.
    Decline {
        challenge: String,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        reason: Option<String>,
    },
    /// Withdraw a challenge this account made.
    Withdraw { challenge: String },
    /// Ask to be paired with the next account that seeks (rated: of a
    /// similar rating); `cancel` withdraws the seek.
    Seek {
        #[serde(default)]
        rated: bool,
        #[serde(default)]
        cancel: bool,
    },
    /// A bot account joins (or leaves) the ladder: while its stream is
    /// open, the server pairs it with other ladder bots, every match rated.
    Ladder { join: bool },
}

/// A challenge as both accounts see it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct ChallengeInfo {
    pub id: String,
    pub from: String,
    pub to: String,
    pub rated: bool,
    /// `standard` or `casual`.
    pub rules: String,
    pub turn_seconds: u64,
    /// The challenger's colour (`None`: drawn on acceptance).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub color: Option<Side>,
    /// Seconds until it expires unanswered.
    pub expires_in: u64,
}

/// A match of this account that is not over.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct CurrentMatch {
    pub match_id: String,
    pub seat: Seat,
    pub opponent: Option<String>,
    pub rated: bool,
}

/// What the server sends on an account's event stream.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum StreamServerMessage {
    /// The answer to the hello: who this stream is, and the full picture
    /// (its matches not over yet, the challenges open to or from it).
    Welcome {
        protocol: u32,
        account: String,
        bot: bool,
        rating: i64,
        provisional: bool,
        matches: Vec<CurrentMatch>,
        challenges: Vec<ChallengeInfo>,
    },
    /// A challenge made to or by this account.
    Challenge { challenge: ChallengeInfo },
    /// A challenge ended unplayed: declined (with the reason given),
    /// withdrawn, or expired.
    ChallengeClosed {
        id: String,
        /// `declined`, `withdrawn` or `expired`.
        why: String,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        reason: Option<String>,
    },
    /// A match of this account started: play its seat on the match
    /// WebSocket `ws` with `token` (shown once; the server keeps a hash).
    MatchStart {
        match_id: String,
        seat: Seat,
        token: SeatToken,
        ws: String,
        opponent: String,
        rated: bool,
    },
    /// A match of this account is over.
    MatchFinish {
        match_id: String,
        result: MatchResult,
        /// The account's rating after it (rated matches).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        rating: Option<i64>,
    },
    /// Sent when the stream has been quiet for a while: the connection
    /// is alive.
    KeepAlive,
    /// A request refused, with a stable code.
    Error { code: ErrorCode, message: String },
}

impl StreamClientMessage {
    /// Parses one message; the error carries the code to answer with.
    pub fn from_json(text: &str) -> Result<Self, ProtocolError> {
        read(text.as_bytes())
    }

    pub fn to_json(&self) -> String {
        serde_json::to_string(self).expect("stream messages always serialise")
    }
}

impl StreamServerMessage {
    /// Parses one message.
    pub fn from_json(text: &str) -> Result<Self, ProtocolError> {
        read(text.as_bytes())
    }

    pub fn to_json(&self) -> String {
        serde_json::to_string(self).expect("stream messages always serialise")
    }

    /// The `error` message of a refusal.
    pub fn refused(r: &Refusal) -> StreamServerMessage {
        StreamServerMessage::Error {
            code: r.code,
            message: r.message.clone(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stream_messages_round_trip_and_unknown_fields_are_refused() {
        let m = StreamClientMessage::Challenge {
            to: "Furmanov".into(),
            rated: true,
            rules: None,
            turn_seconds: Some(30),
            color: Some(Side::Black),
        };
        assert_eq!(StreamClientMessage::from_json(&m.to_json()).unwrap(), m);
        let bad = StreamClientMessage::from_json(r#"{"type":"ladder","join":true,"x":1}"#);
        assert_eq!(bad.unwrap_err().code, ErrorCode::BadMessage);
        let e = StreamServerMessage::KeepAlive;
        assert_eq!(e.to_json(), r#"{"type":"keep-alive"}"#);
    }
}
