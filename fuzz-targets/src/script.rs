//! The script a `protocol_session` input encodes: how the match is set up,
//! then operations on it — connect with the right, a wrong or no seat token,
//! send a raw frame or a well-formed message, let time pass, take the empty
//! seat, make the store fail, answer for a built-in bot or the rematch.
//!
//! Every byte string decodes to a script ([`Script::decode`]: a missing
//! byte reads as zero, an operation code wraps around), and
//! [`Script::encode`] writes the bytes that decode to a given script, for
//! hand-written seeds.

use crate::cursor::Cursor;

/// Most operations read from one input, so one run stays short.
pub const MAX_OPS: usize = 200;

/// The rules the match is played under.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rules {
    /// The defaults.
    Casual,
    /// Execution noise and the pie rule.
    Standard,
    /// A single round.
    QuickMatch,
    /// Two-row advances and the pie rule, no noise.
    TwoRowsAndPie,
}

/// Who holds the second seat at the start (the first is a person's).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Second {
    /// Nobody: the match is open until someone joins.
    Empty,
    /// A person, with the second token.
    Person,
    /// A built-in bot.
    Bot,
}

/// The seat token a connection presents.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Token {
    /// None: a spectator.
    None,
    /// The first seat's.
    First,
    /// The second seat's.
    Second,
    /// One that holds no seat.
    Wrong,
    /// The first seat's without its last character.
    Prefix,
}

/// A well-formed client message, sent as its JSON.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Said {
    /// Flick piece `piece % 16` with velocity `(vx, vy) / 60` m/s.
    Shot {
        piece: u8,
        vx: i8,
        vy: i8,
    },
    /// The pie-rule decision.
    Pie {
        swap: bool,
    },
    Resign,
    OfferRematch,
    AcceptRematch,
    /// A chat message of `len % 1024` characters.
    Chat {
        len: u16,
    },
    /// A hello (refused inside a match).
    Hello,
}

/// What a built-in bot decides.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Decided {
    /// As [`Said::Shot`].
    Shot {
        piece: u8,
        vx: i8,
        vy: i8,
    },
    Pie {
        swap: bool,
    },
    Resign,
}

/// One operation of a script. A connection is named by its index among
/// the open ones (modulo their number plus one: the last names one never
/// admitted).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Op {
    /// A new connection asks to be admitted.
    Connect { token: Token },
    /// A connection closes.
    Disconnect { conn: u8 },
    /// A connection sends a raw text frame.
    Frame { conn: u8, bytes: Vec<u8> },
    /// A connection sends a well-formed message.
    Say { conn: u8, said: Said },
    /// Time passes: `step² × 4` ms, the session's deadlines firing on the way.
    Wait { step: u8 },
    /// Time passes to the session's next deadline, which fires.
    Deadline,
    /// Someone takes the empty second seat under this name.
    Join { name: Vec<u8> },
    /// The next store write fails; the match is reloaded from the store
    /// (or, without `reload`, cannot be read back).
    FailNextWrite { reload: bool },
    /// The built-in bot answers the request `stale` moves before the one
    /// it was asked for (0: the current one).
    BotAnswer { stale: u8, decided: Decided },
    /// The rematch asked for is created, or could not be.
    RematchAnswer { created: bool },
}

/// A whole `protocol_session` input.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Script {
    pub rules: Rules,
    pub second: Second,
    /// The match's seed (drives the execution noise).
    pub seed: u8,
    pub ops: Vec<Op>,
}

impl Script {
    /// The script `data` encodes (at most [`MAX_OPS`] operations).
    pub fn decode(data: &[u8]) -> Script {
        let mut c = Cursor::new(data);
        let rules = match c.choice(4) {
            0 => Rules::Casual,
            1 => Rules::Standard,
            2 => Rules::QuickMatch,
            _ => Rules::TwoRowsAndPie,
        };
        let second = match c.choice(3) {
            0 => Second::Empty,
            1 => Second::Person,
            _ => Second::Bot,
        };
        let seed = c.byte();
        let mut ops = Vec::new();
        while !c.is_empty() && ops.len() < MAX_OPS {
            ops.push(Op::decode(&mut c));
        }
        Script {
            rules,
            second,
            seed,
            ops,
        }
    }

    /// The bytes that decode to this script.
    pub fn encode(&self) -> Vec<u8> {
        let rules = match self.rules {
            Rules::Casual => 0,
            Rules::Standard => 1,
            Rules::QuickMatch => 2,
            Rules::TwoRowsAndPie => 3,
        };
        let second = match self.second {
            Second::Empty => 0,
            Second::Person => 1,
            Second::Bot => 2,
        };
        let mut out = vec![rules, second, self.seed];
        for op in &self.ops {
            op.encode(&mut out);
        }
        out
    }
}

impl Op {
    fn decode(c: &mut Cursor) -> Op {
        match c.choice(10) {
            0 => Op::Connect {
                token: match c.choice(5) {
                    0 => Token::None,
                    1 => Token::First,
                    2 => Token::Second,
                    3 => Token::Wrong,
                    _ => Token::Prefix,
                },
            },
            1 => Op::Disconnect { conn: c.byte() },
            2 => {
                let conn = c.byte();
                let len = c.u16() as usize;
                Op::Frame {
                    conn,
                    bytes: c.take(len).to_vec(),
                }
            }
            3 => {
                let conn = c.byte();
                let said = match c.choice(7) {
                    0 => Said::Shot {
                        piece: c.byte(),
                        vx: c.byte() as i8,
                        vy: c.byte() as i8,
                    },
                    1 => Said::Pie { swap: c.flag() },
                    2 => Said::Resign,
                    3 => Said::OfferRematch,
                    4 => Said::AcceptRematch,
                    5 => Said::Chat { len: c.u16() },
                    _ => Said::Hello,
                };
                Op::Say { conn, said }
            }
            4 => Op::Wait { step: c.byte() },
            5 => Op::Deadline,
            6 => {
                let len = c.byte() as usize;
                Op::Join {
                    name: c.take(len).to_vec(),
                }
            }
            7 => Op::FailNextWrite { reload: c.flag() },
            8 => {
                let stale = c.byte();
                let decided = match c.choice(3) {
                    0 => Decided::Shot {
                        piece: c.byte(),
                        vx: c.byte() as i8,
                        vy: c.byte() as i8,
                    },
                    1 => Decided::Pie { swap: c.flag() },
                    _ => Decided::Resign,
                };
                Op::BotAnswer { stale, decided }
            }
            _ => Op::RematchAnswer { created: c.flag() },
        }
    }

    fn encode(&self, out: &mut Vec<u8>) {
        match self {
            Op::Connect { token } => {
                let t = match token {
                    Token::None => 0,
                    Token::First => 1,
                    Token::Second => 2,
                    Token::Wrong => 3,
                    Token::Prefix => 4,
                };
                out.extend([0, t]);
            }
            Op::Disconnect { conn } => out.extend([1, *conn]),
            Op::Frame { conn, bytes } => {
                let len = bytes.len().min(u16::MAX as usize);
                out.extend([2, *conn]);
                out.extend((len as u16).to_le_bytes());
                out.extend(&bytes[..len]);
            }
            Op::Say { conn, said } => {
                out.extend([3, *conn]);
                match *said {
                    Said::Shot { piece, vx, vy } => out.extend([0, piece, vx as u8, vy as u8]),
                    Said::Pie { swap } => out.extend([1, swap as u8]),
                    Said::Resign => out.push(2),
                    Said::OfferRematch => out.push(3),
                    Said::AcceptRematch => out.push(4),
                    Said::Chat { len } => {
                        out.push(5);
                        out.extend(len.to_le_bytes());
                    }
                    Said::Hello => out.push(6),
                }
            }
            Op::Wait { step } => out.extend([4, *step]),
            Op::Deadline => out.push(5),
            Op::Join { name } => {
                let len = name.len().min(u8::MAX as usize);
                out.extend([6, len as u8]);
                out.extend(&name[..len]);
            }
            Op::FailNextWrite { reload } => out.extend([7, *reload as u8]),
            Op::BotAnswer { stale, decided } => {
                out.extend([8, *stale]);
                match *decided {
                    Decided::Shot { piece, vx, vy } => out.extend([0, piece, vx as u8, vy as u8]),
                    Decided::Pie { swap } => out.extend([1, swap as u8]),
                    Decided::Resign => out.push(2),
                }
            }
            Op::RematchAnswer { created } => out.extend([9, *created as u8]),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn every_op() -> Vec<Op> {
        vec![
            Op::Connect {
                token: Token::Prefix,
            },
            Op::Disconnect { conn: 3 },
            Op::Frame {
                conn: 1,
                bytes: br#"{"type":"resign"}"#.to_vec(),
            },
            Op::Say {
                conn: 0,
                said: Said::Shot {
                    piece: 4,
                    vx: -3,
                    vy: 120,
                },
            },
            Op::Say {
                conn: 0,
                said: Said::Chat { len: 501 },
            },
            Op::Say {
                conn: 2,
                said: Said::Pie { swap: true },
            },
            Op::Wait { step: 50 },
            Op::Deadline,
            Op::Join {
                name: b"Anka".to_vec(),
            },
            Op::FailNextWrite { reload: true },
            Op::BotAnswer {
                stale: 0,
                decided: Decided::Shot {
                    piece: 12,
                    vx: 1,
                    vy: -90,
                },
            },
            Op::BotAnswer {
                stale: 1,
                decided: Decided::Pie { swap: false },
            },
            Op::RematchAnswer { created: true },
        ]
    }

    #[test]
    fn an_encoded_script_decodes_to_itself() {
        let script = Script {
            rules: Rules::TwoRowsAndPie,
            second: Second::Bot,
            seed: 9,
            ops: every_op(),
        };
        assert_eq!(Script::decode(&script.encode()), script);
    }

    #[test]
    fn any_bytes_decode_and_the_operations_are_capped() {
        assert_eq!(Script::decode(&[]).ops, []);
        let long = Script::decode(&[5; 10_000]);
        assert_eq!(long.ops.len(), MAX_OPS);
        assert!(long.ops.iter().all(|op| *op == Op::Deadline));
        // A frame longer than the input takes what is left.
        let s = Script::decode(&[0, 0, 0, 2, 0, 0xff, 0xff, b'{']);
        assert_eq!(
            s.ops,
            [Op::Frame {
                conn: 0,
                bytes: b"{".to_vec()
            }]
        );
    }
}
