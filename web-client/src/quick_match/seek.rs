//! A quick match's wait, without drawing or I/O: what to say on the
//! account's event stream once it opens (hello, then the seek), what the
//! server's answers mean (a match started for us, a refusal), how long
//! the player has waited, when the adaptive computer is offered instead
//! ([`OFFER_COMPUTER_AFTER`]), and when a dropped stream is opened again
//! (it says hello and seeks once more: the server forgets a seek with its
//! stream).

use crate::i18n::t;
use game::protocol::PROTOCOL_VERSION;
use game::stream::{StreamClientMessage, StreamServerMessage};
use game::token::SeatToken;

/// Seconds of waiting after which the player is offered the adaptive
/// computer level instead of a stranger.
pub const OFFER_COMPUTER_AFTER: f64 = 20.0;
/// Seconds before a dropped stream is opened again.
pub const RETRY_AFTER: f64 = 2.0;

/// Where the wait stands.
#[derive(Clone, Debug, PartialEq)]
pub enum Phase {
    /// The stream is opening (or opening again).
    Connecting,
    /// Seeking: the server knows we wait.
    Waiting,
    /// The stream dropped; it opens again at this clock time.
    Retrying { at: f64 },
    /// A match started for us: play its seat with this token.
    Paired { match_id: String, token: SeatToken },
    /// The server refused, for this reason; nothing more is tried.
    Refused(String),
}

/// A quick match being looked for.
#[derive(Clone, Debug)]
pub struct Seek {
    /// A rated match (against a similar rating) or a casual one.
    pub rated: bool,
    pub phase: Phase,
    /// Seconds since the player pressed Quick match.
    pub waited: f64,
}

impl Seek {
    /// A wait for a rated or a casual match; the stream is opening.
    pub fn new(rated: bool) -> Seek {
        Seek {
            rated,
            phase: Phase::Connecting,
            waited: 0.0,
        }
    }

    /// `dt` seconds went by; whether the stream is due to be opened again.
    pub fn tick(&mut self, dt: f64) -> bool {
        self.waited += dt;
        match self.phase {
            Phase::Retrying { at } if self.waited >= at => {
                self.phase = Phase::Connecting;
                true
            }
            _ => false,
        }
    }

    /// The stream opened: what to send on it (hello with the account's
    /// `key`, then the seek).
    pub fn opened(&mut self, key: &str) -> [StreamClientMessage; 2] {
        self.phase = Phase::Waiting;
        [
            StreamClientMessage::Hello {
                protocol: PROTOCOL_VERSION,
                key: SeatToken::new(key),
            },
            StreamClientMessage::Seek {
                rated: self.rated,
                cancel: false,
            },
        ]
    }

    /// The server said `msg`. A `match-start` pairs us; an error refuses
    /// the wait; anything else (the welcome, keep-alives, challenges)
    /// changes nothing.
    pub fn heard(&mut self, msg: StreamServerMessage) {
        if matches!(self.phase, Phase::Paired { .. } | Phase::Refused(_)) {
            return;
        }
        match msg {
            StreamServerMessage::MatchStart {
                match_id, token, ..
            } => self.phase = Phase::Paired { match_id, token },
            StreamServerMessage::Error { code, message } => {
                self.phase = Phase::Refused(format!("{message} ({code})"))
            }
            _ => {}
        }
    }

    /// The wait cannot be: nobody is looked for, for this reason.
    pub fn refuse(&mut self, why: impl Into<String>) {
        self.phase = Phase::Refused(why.into());
    }

    /// The stream closed: it is opened again after [`RETRY_AFTER`] unless
    /// the wait is over.
    pub fn closed(&mut self) {
        if matches!(self.phase, Phase::Connecting | Phase::Waiting) {
            self.phase = Phase::Retrying {
                at: self.waited + RETRY_AFTER,
            };
        }
    }

    /// What withdraws the seek.
    pub fn cancel(&self) -> StreamClientMessage {
        StreamClientMessage::Seek {
            rated: self.rated,
            cancel: true,
        }
    }

    /// Whether the adaptive computer is offered: the player has waited
    /// [`OFFER_COMPUTER_AFTER`] seconds, or no stranger can be found at all.
    pub fn offer_computer(&self) -> bool {
        self.waited >= OFFER_COMPUTER_AFTER || matches!(self.phase, Phase::Refused(_))
    }

    /// The wait in words: "Looking for an opponent (rated) · 0:12".
    pub fn status(&self) -> String {
        let kind = if self.rated { "rated" } else { "casual" };
        let kind = t!("quick-kind", kind = kind);
        let secs = self.waited.max(0.0) as u64;
        let clock = format!("{}:{:02}", secs / 60, secs % 60);
        match &self.phase {
            Phase::Connecting => t!("quick-connecting", kind = kind, clock = clock),
            Phase::Waiting => t!("quick-looking", kind = kind, clock = clock),
            Phase::Retrying { .. } => t!("quick-retrying", clock = clock),
            Phase::Paired { .. } => t!("quick-found"),
            Phase::Refused(why) => t!("quick-refused", why = why.as_str()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use game::protocol::ErrorCode;
    use game::Seat;

    fn start(match_id: &str) -> StreamServerMessage {
        StreamServerMessage::MatchStart {
            match_id: match_id.into(),
            seat: Seat::Second,
            token: SeatToken::new("t0k"),
            ws: format!("/ws?match={match_id}"),
            opponent: "Anka".into(),
            rated: true,
        }
    }

    #[test]
    fn an_open_stream_says_hello_with_the_key_then_seeks_of_the_kind_asked() {
        let mut s = Seek::new(true);
        let [hello, seek] = s.opened("k3y");
        assert_eq!(
            hello,
            StreamClientMessage::Hello {
                protocol: PROTOCOL_VERSION,
                key: SeatToken::new("k3y")
            }
        );
        assert_eq!(
            seek,
            StreamClientMessage::Seek {
                rated: true,
                cancel: false
            }
        );
        assert_eq!(s.phase, Phase::Waiting);
        assert_eq!(
            s.cancel(),
            StreamClientMessage::Seek {
                rated: true,
                cancel: true
            }
        );
    }

    #[test]
    fn a_match_start_pairs_the_wait_and_other_messages_change_nothing() {
        let mut s = Seek::new(false);
        s.opened("k");
        s.heard(StreamServerMessage::KeepAlive);
        assert_eq!(s.phase, Phase::Waiting);
        s.heard(start("m7"));
        assert_eq!(
            s.phase,
            Phase::Paired {
                match_id: "m7".into(),
                token: SeatToken::new("t0k")
            }
        );
        // Once paired, a later message does not undo it.
        s.heard(StreamServerMessage::Error {
            code: ErrorCode::BadMessage,
            message: "late".into(),
        });
        assert!(matches!(s.phase, Phase::Paired { .. }));
    }

    #[test]
    fn the_computer_is_offered_after_twenty_seconds_of_waiting() {
        let mut s = Seek::new(false);
        s.opened("k");
        s.tick(OFFER_COMPUTER_AFTER - 0.5);
        assert!(!s.offer_computer());
        assert_eq!(s.status(), "Looking for an opponent (casual) · 0:19");
        s.tick(0.5);
        assert!(s.offer_computer());
        assert_eq!(s.status(), "Looking for an opponent (casual) · 0:20");
    }

    #[test]
    fn a_dropped_stream_opens_again_after_a_pause_and_seeks_again() {
        let mut s = Seek::new(true);
        s.opened("k");
        s.tick(3.0);
        s.closed();
        assert_eq!(
            s.phase,
            Phase::Retrying {
                at: 3.0 + RETRY_AFTER
            }
        );
        assert!(!s.tick(RETRY_AFTER - 0.1));
        assert!(s.tick(0.2), "due again");
        assert_eq!(s.phase, Phase::Connecting);
        let [_, seek] = s.opened("k");
        assert!(matches!(
            seek,
            StreamClientMessage::Seek { cancel: false, .. }
        ));
    }

    #[test]
    fn a_refusal_ends_the_wait_says_why_and_offers_the_computer_at_once() {
        let mut s = Seek::new(true);
        s.opened("bad");
        s.heard(StreamServerMessage::Error {
            code: ErrorCode::BadMessage,
            message: "no such key".into(),
        });
        assert!(matches!(s.phase, Phase::Refused(_)));
        assert!(s.status().starts_with("No quick match: no such key"));
        assert!(s.offer_computer());
        // A refused wait is not retried when its stream closes.
        s.closed();
        assert!(matches!(s.phase, Phase::Refused(_)));
    }
}
