//! The relay's wire format: what one node publishes on another's Redis
//! channel. Every message is one JSON [`Envelope`], tagged by `kind`;
//! refusals and claims cross as [`WireRefusal`] and [`WireClaim`], plain
//! data that converts to and from the room's own types without loss.
//! Nothing here does I/O: the node encodes before it publishes and decodes
//! what its subscription reads.

use crate::play::room::Claim;
use crate::refusal::Refusal;
use game::protocol::ErrorCode;
use game::token::SeatToken;
use game::Seat;
use serde::{Deserialize, Serialize};

/// A refusal as it crosses Redis.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub(super) struct WireRefusal {
    pub code: ErrorCode,
    pub message: String,
}

impl From<&Refusal> for WireRefusal {
    fn from(r: &Refusal) -> WireRefusal {
        WireRefusal {
            code: r.code,
            message: r.message.clone(),
        }
    }
}

impl From<WireRefusal> for Refusal {
    fn from(r: WireRefusal) -> Refusal {
        Refusal::new(r.code, r.message)
    }
}

/// What a connection claims, as it crosses Redis.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "as", rename_all = "kebab-case")]
pub(super) enum WireClaim {
    /// A spectator, with the name it chats under (none from an older node).
    Watch {
        #[serde(default)]
        name: String,
    },
    Token {
        token: String,
    },
    Account {
        account: String,
    },
}

impl From<&Claim> for WireClaim {
    fn from(c: &Claim) -> WireClaim {
        match c {
            Claim::Watch(name) => WireClaim::Watch { name: name.clone() },
            Claim::Token(t) => WireClaim::Token {
                token: t.expose().to_string(),
            },
            Claim::Account(a) => WireClaim::Account { account: a.clone() },
        }
    }
}

impl From<WireClaim> for Claim {
    fn from(c: WireClaim) -> Claim {
        match c {
            WireClaim::Watch { name } => Claim::Watch(name),
            WireClaim::Token { token } => Claim::Token(SeatToken::new(token)),
            WireClaim::Account { account } => Claim::Account(account),
        }
    }
}

/// One message of a [`Envelope::Deliveries`] for one connection: its
/// number among that connection's messages, which of the envelope's texts
/// it is, and the owner's count of the connection's refused messages.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub(super) struct Addressed {
    pub link: u64,
    pub seq: u64,
    pub text: usize,
    pub refused: u32,
}

/// A message between two nodes, on the receiving node's channel.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub(super) enum Envelope {
    // To the owner of a match, from the node of a client (`from`).
    Connect {
        from: String,
        link: u64,
        match_id: String,
        claim: WireClaim,
    },
    Message {
        from: String,
        link: u64,
        text: String,
    },
    Disconnect {
        from: String,
        link: u64,
    },
    Join {
        from: String,
        request: u64,
        match_id: String,
        name: String,
        token: String,
        account: Option<String>,
    },
    // Back to the node of a client.
    Connected {
        link: u64,
        conn: u64,
        seat: Option<Seat>,
    },
    Refused {
        link: u64,
        refusal: WireRefusal,
    },
    /// What the owner's rooms sent the connections it serves for the
    /// receiving node's clients ([`super::outlet`]): each message once,
    /// addressed by `to`; then the connections the rooms `closed`.
    Deliveries {
        /// The node serving the connections.
        from: String,
        texts: Vec<String>,
        to: Vec<Addressed>,
        closed: Vec<u64>,
    },
    Joined {
        request: u64,
        result: Result<Seat, WireRefusal>,
    },
}

impl Envelope {
    /// Its text on the wire (`None` only if it cannot be serialised,
    /// which these plain fields never make happen).
    pub fn encode(&self) -> Option<String> {
        serde_json::to_string(self).ok()
    }

    /// An envelope read back from its text.
    pub fn decode(text: &str) -> Result<Envelope, serde_json::Error> {
        serde_json::from_str(text)
    }
}

/// The Redis channel of `node`.
pub(super) fn channel(node: &str) -> String {
    format!("chapaev:node:{node}")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One envelope of every kind.
    fn every_kind() -> Vec<Envelope> {
        let refusal = WireRefusal {
            code: ErrorCode::MatchFull,
            message: "taken".into(),
        };
        vec![
            Envelope::Connect {
                from: "a".into(),
                link: 1,
                match_id: "m1".into(),
                claim: WireClaim::Token {
                    token: "tok".into(),
                },
            },
            Envelope::Message {
                from: "a".into(),
                link: 1,
                text: r#"{"type":"ping"}"#.into(),
            },
            Envelope::Disconnect {
                from: "a".into(),
                link: 1,
            },
            Envelope::Join {
                from: "a".into(),
                request: 7,
                match_id: "m1".into(),
                name: "Anka".into(),
                token: "00ff".into(),
                account: Some("anka".into()),
            },
            Envelope::Connected {
                link: 1,
                conn: 42,
                seat: Some(Seat::Second),
            },
            Envelope::Refused {
                link: 1,
                refusal: refusal.clone(),
            },
            Envelope::Deliveries {
                from: "b".into(),
                texts: vec![
                    "{\"type\":\"match-state\",\"quote\":\"\\\"\"}".into(),
                    r#"{"type":"clock"}"#.into(),
                ],
                to: vec![
                    Addressed {
                        link: 1,
                        seq: 3,
                        text: 0,
                        refused: 2,
                    },
                    Addressed {
                        link: 4,
                        seq: 0,
                        text: 0,
                        refused: 0,
                    },
                    Addressed {
                        link: 1,
                        seq: 4,
                        text: 1,
                        refused: 2,
                    },
                ],
                closed: vec![4],
            },
            Envelope::Joined {
                request: 7,
                result: Ok(Seat::Second),
            },
            Envelope::Joined {
                request: 8,
                result: Err(refusal),
            },
        ]
    }

    #[test]
    fn every_envelope_comes_back_from_its_text_as_it_was_sent() {
        for e in every_kind() {
            let text = e.encode().unwrap();
            assert_eq!(Envelope::decode(&text).unwrap(), e, "{text}");
        }
    }

    #[test]
    fn envelopes_are_tagged_by_a_kebab_case_kind_and_claims_by_as() {
        let connect = every_kind().remove(0).encode().unwrap();
        assert!(connect.starts_with(r#"{"kind":"connect","#), "{connect}");
        assert!(
            connect.contains(r#""claim":{"as":"token","token":"tok"}"#),
            "{connect}"
        );
        let watch = Envelope::decode(
            r#"{"kind":"connect","from":"a","link":2,"match_id":"m","claim":{"as":"watch"}}"#,
        )
        .unwrap();
        assert!(matches!(
            watch,
            Envelope::Connect {
                claim: WireClaim::Watch { .. },
                ..
            }
        ));
    }

    #[test]
    fn an_unknown_kind_or_a_missing_field_does_not_decode() {
        assert!(Envelope::decode(r#"{"kind":"teleport","link":1}"#).is_err());
        assert!(Envelope::decode(r#"{"kind":"deliveries","from":"b"}"#).is_err());
        assert!(Envelope::decode("not json").is_err());
    }

    #[test]
    fn a_refusal_crosses_with_its_code_and_message() {
        let r = Refusal::new(ErrorCode::ServerBusy, "full");
        let back = Refusal::from(WireRefusal::from(&r));
        assert_eq!((back.code, back.message), (r.code, r.message));
    }

    #[test]
    fn every_claim_crosses_as_what_it_claims() {
        let token = SeatToken::new("540a0bf048fe73e1505aeb84de7f0fcd");
        let cases = [
            Claim::Watch("Furmanov".into()),
            Claim::Token(token.clone()),
            Claim::Account("anka".into()),
        ];
        for c in cases {
            let wire = WireClaim::from(&c);
            let text = serde_json::to_string(&wire).unwrap();
            let back = Claim::from(serde_json::from_str::<WireClaim>(&text).unwrap());
            match (c, back) {
                (Claim::Watch(a), Claim::Watch(b)) => assert_eq!(a, b),
                (Claim::Token(a), Claim::Token(b)) => assert_eq!(a.expose(), b.expose()),
                (Claim::Account(a), Claim::Account(b)) => assert_eq!(a, b),
                (a, b) => panic!("{a:?} came back as {b:?}"),
            }
        }
    }

    #[test]
    fn each_node_listens_on_a_channel_named_after_it() {
        assert_eq!(channel("node-a"), "chapaev:node:node-a");
        assert_ne!(channel("a"), channel("b"));
    }
}
