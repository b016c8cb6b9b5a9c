//! What the protocol refuses, and how: the stable wire [`ErrorCode`]s, a
//! [`Refusal`] (a code and a message for people), a [`ProtocolError`] (a
//! message that could not be read) and [`read`], which reads any JSON
//! message with the code its refusal carries. Every module that refuses
//! something uses these; [`crate::protocol`] re-exports them with the
//! messages that carry them.

use serde::{Deserialize, Serialize};
use std::fmt;

/// Stable error codes (kebab-case strings on the wire).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum ErrorCode {
    /// The message is not JSON.
    BadJson,
    /// JSON, but not a message this protocol knows.
    BadMessage,
    /// The hello named another protocol version.
    UnsupportedProtocol,
    /// Something was sent before the hello.
    NoHello,
    NoSuchMatch,
    MatchFull,
    /// A match action from a connection not seated in a match.
    NotInMatch,
    NotYourTurn,
    NotYourPiece,
    PieceOffBoard,
    NotFinite,
    ZeroSpeed,
    TooFast,
    MatchOver,
    PieDecisionPending,
    NoPieDecision,
    NotYourDecision,
    /// A config in a create request is unplayable.
    BadConfig,
    NoRematchOffer,
    ChatTooLong,
    /// The server failed; not the client's fault.
    Internal,
    /// The seat token is not this match's.
    BadToken,
    /// Too many messages too fast; this one was dropped.
    RateLimited,
    /// A frame or message above the server's size limit.
    MessageTooLarge,
    /// A server limit (matches, connections) is reached; try later.
    ServerBusy,
    /// The record of a match is public only once it is over.
    MatchNotOver,
    /// A position given to simulate is impossible (a piece twice, off
    /// the board, or two pieces overlapping).
    BadBoard,
    /// A page of another site tried to act (its `Origin` is not allowed).
    ForbiddenOrigin,
    /// The match was played under a physics version this server cannot
    /// play; it is kept as stored, for a server that can.
    UnsupportedPhysics,
    /// A name that is not allowed (length, characters).
    BadName,
    /// A name that passes for one of the computer's (`bot (hard)`,
    /// `computer-easy`, in any case or look-alike letters).
    ReservedName,
    /// The account name is someone else's.
    NameTaken,
    /// No account has this name.
    NoSuchAccount,
    /// The account key is missing, wrong or revoked.
    BadKey,
    /// Both seats of a rated match would be the same account.
    SameAccount,
    /// A password too short or too long, or a sign-in with a wrong name
    /// or password.
    BadPassword,
    /// No open challenge has this id (for this account): it was answered,
    /// withdrawn or expired, or was never made to it.
    NoSuchChallenge,
    /// A bot's key was sent from a web page (a browser's request carries
    /// an `Origin`): bot keys are for bot processes only.
    BotKeyInBrowser,
    /// No file of this name is served here (`/sdk/`: none, or not that one).
    NoSuchFile,
    /// An uploaded bot module the server cannot host: not WebAssembly,
    /// an import other than the host's (WASI), the documented exports
    /// missing or of the wrong type (the message says which).
    BadModule,
    /// Only a bot's account can host a module.
    NotABot,
    /// The account has no uploaded module version with this hash.
    NoSuchVersion,
    /// The account keeps as many module versions as it may.
    TooManyVersions,
    /// The module version plays a seat of a match not finished yet (the
    /// match resumes with it after a restart): it can be deleted once
    /// that match ends.
    ModuleInUse,
}

impl ErrorCode {
    /// The code as it appears on the wire.
    pub fn as_str(self) -> &'static str {
        match self {
            ErrorCode::BadJson => "bad-json",
            ErrorCode::BadMessage => "bad-message",
            ErrorCode::UnsupportedProtocol => "unsupported-protocol",
            ErrorCode::NoHello => "no-hello",
            ErrorCode::NoSuchMatch => "no-such-match",
            ErrorCode::MatchFull => "match-full",
            ErrorCode::NotInMatch => "not-in-match",
            ErrorCode::NotYourTurn => "not-your-turn",
            ErrorCode::NotYourPiece => "not-your-piece",
            ErrorCode::PieceOffBoard => "piece-off-board",
            ErrorCode::NotFinite => "not-finite",
            ErrorCode::ZeroSpeed => "zero-speed",
            ErrorCode::TooFast => "too-fast",
            ErrorCode::MatchOver => "match-over",
            ErrorCode::PieDecisionPending => "pie-decision-pending",
            ErrorCode::NoPieDecision => "no-pie-decision",
            ErrorCode::NotYourDecision => "not-your-decision",
            ErrorCode::BadConfig => "bad-config",
            ErrorCode::NoRematchOffer => "no-rematch-offer",
            ErrorCode::ChatTooLong => "chat-too-long",
            ErrorCode::Internal => "internal",
            ErrorCode::BadToken => "bad-token",
            ErrorCode::RateLimited => "rate-limited",
            ErrorCode::MessageTooLarge => "message-too-large",
            ErrorCode::ServerBusy => "server-busy",
            ErrorCode::MatchNotOver => "match-not-over",
            ErrorCode::BadBoard => "bad-board",
            ErrorCode::ForbiddenOrigin => "forbidden-origin",
            ErrorCode::UnsupportedPhysics => "unsupported-physics",
            ErrorCode::BadName => "bad-name",
            ErrorCode::ReservedName => "reserved-name",
            ErrorCode::NameTaken => "name-taken",
            ErrorCode::NoSuchAccount => "no-such-account",
            ErrorCode::BadKey => "bad-key",
            ErrorCode::SameAccount => "same-account",
            ErrorCode::NoSuchChallenge => "no-such-challenge",
            ErrorCode::BadPassword => "bad-password",
            ErrorCode::BotKeyInBrowser => "bot-key-in-browser",
            ErrorCode::NoSuchFile => "no-such-file",
            ErrorCode::BadModule => "bad-module",
            ErrorCode::NotABot => "not-a-bot",
            ErrorCode::NoSuchVersion => "no-such-version",
            ErrorCode::TooManyVersions => "too-many-versions",
            ErrorCode::ModuleInUse => "module-in-use",
        }
    }
}

impl fmt::Display for ErrorCode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// A message that could not be read, with the code to answer it with.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{code}: {message}")]
pub struct ProtocolError {
    pub code: ErrorCode,
    pub message: String,
}

/// A refused request: the stable wire [`ErrorCode`] and a human-readable
/// message, sent to a client as an `error` message (or, by the server, as
/// the JSON body of an HTTP error).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{code}: {message}")]
pub struct Refusal {
    /// The stable code.
    pub code: ErrorCode,
    /// What went wrong, for people.
    pub message: String,
}

impl Refusal {
    /// A refusal with `code` and `message`.
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
}

/// Reads any JSON body or message of this protocol, with the code its
/// refusal carries: `bad-json` for text that is not JSON, `not-finite` for
/// a number beyond the range of a double (JSON has no NaN or infinity, so
/// `1e400` is how a non-finite number arrives), `bad-message` for JSON
/// that is not the expected message.
pub fn read<T: for<'de> Deserialize<'de>>(text: &[u8]) -> Result<T, ProtocolError> {
    serde_json::from_slice(text).map_err(|e| {
        let message = e.to_string();
        let code = if message.starts_with("number out of range") {
            ErrorCode::NotFinite
        } else if e.is_syntax() || e.is_eof() {
            ErrorCode::BadJson
        } else {
            ErrorCode::BadMessage
        };
        ProtocolError { code, message }
    })
}
