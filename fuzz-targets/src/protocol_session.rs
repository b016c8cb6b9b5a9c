//! The `protocol_session` target: a [`Script`] of client WebSocket frames
//! and everything else that happens to a live match, run through the
//! sans-IO [`Session`] by a checking [`Driver`]. A frame is read as the
//! server reads it, with [`game::protocol::read`]: a frame that does not
//! read is refused with one of the reading codes (the server answers it
//! itself), one that reads must read back from its own JSON as itself and
//! goes to the session. See [`crate::driver`] for what is checked.

use crate::driver::{Driver, LIMITS};
use crate::script::{Decided, Op, Rules, Said, Script, Second, Token};
use game::protocol::{self, ClientMessage, ErrorCode};
use game::session::{BotDecision, Moment, SeatSpec, Session};
use game::token::TokenHash;
use game::{Config, Game, PieceId, Shot, Side, Variants};
use glam::DVec2;
use std::time::Duration;

/// The seat tokens of the first and second seats.
pub const TOKENS: [&str; 2] = ["tok-first-0123", "tok-second-4567"];

/// Runs the script `data` encodes (see [`Script::decode`]).
pub fn protocol_session(data: &[u8]) {
    let script = Script::decode(data);
    let game = match Game::new(config(script.rules), u64::from(script.seed)) {
        Ok(game) => game,
        Err(e) => panic!("the scripted rules are unplayable: {e}"),
    };
    let first = SeatSpec {
        name: Some("Petka".into()),
        token: Some(TokenHash::of(TOKENS[0])),
        bot: None,
    };
    let second = match script.second {
        Second::Empty => SeatSpec::default(),
        Second::Person => SeatSpec {
            name: Some("Anka".into()),
            token: Some(TokenHash::of(TOKENS[1])),
            bot: None,
        },
        Second::Bot => SeatSpec {
            bot: Some("easy".into()),
            ..SeatSpec::default()
        },
    };
    let session = Session::new("m1", game, [first, second], LIMITS, Moment::ZERO);
    let mut driver = Driver::new(session);
    for op in script.ops {
        run(&mut driver, op);
    }
    driver.finish();
}

fn config(rules: Rules) -> Config {
    match rules {
        Rules::Casual => Config::default(),
        Rules::Standard => Config::standard(),
        Rules::QuickMatch => Config {
            variants: Variants {
                quick_match: true,
                ..Variants::default()
            },
            ..Config::default()
        },
        Rules::TwoRowsAndPie => Config {
            variants: Variants {
                two_row_advance: true,
                pie_rule: true,
                ..Variants::default()
            },
            ..Config::default()
        },
    }
}

fn run(driver: &mut Driver, op: Op) {
    match op {
        Op::Connect { token } => {
            let token = match token {
                Token::None => None,
                Token::First => Some(TOKENS[0].to_string()),
                Token::Second => Some(TOKENS[1].to_string()),
                Token::Wrong => Some("tok-nobody-0000".to_string()),
                Token::Prefix => Some(TOKENS[0][..TOKENS[0].len() - 1].to_string()),
            };
            driver.connect(token);
        }
        Op::Disconnect { conn } => driver.disconnect(driver.conn(conn)),
        Op::Frame { conn, bytes } => {
            if let Some(msg) = read_frame(&bytes) {
                let conn = driver.conn(conn);
                driver.feed(game::session::Input::Message { conn, msg });
            }
        }
        Op::Say { conn, said } => {
            let msg = message(said);
            // Sent as its JSON and read as the server reads a frame.
            let Some(read) = read_frame(msg.to_json().as_bytes()) else {
                panic!("a well-formed message does not read: {}", msg.to_json());
            };
            assert_eq!(read, msg);
            let conn = driver.conn(conn);
            driver.feed(game::session::Input::Message { conn, msg });
        }
        Op::Wait { step } => {
            let ms = u64::from(step) * u64::from(step) * 4;
            driver.wait(Duration::from_millis(ms));
        }
        Op::Deadline => driver.to_deadline(),
        Op::Join { name } => {
            let name = String::from_utf8_lossy(&name).into_owned();
            driver.feed(game::session::Input::Join {
                name,
                token: TokenHash::of(TOKENS[1]),
            });
        }
        Op::FailNextWrite { reload } => driver.fail_next_write(reload),
        Op::BotAnswer { stale, decided } => {
            let decision = match decided {
                Decided::Shot { piece, vx, vy } => {
                    let config = driver.session().game().config();
                    match Shot::new(piece_id(piece), velocity(vx, vy), config) {
                        Ok(shot) => BotDecision::Shot(shot),
                        // A bot only ever decides a valid flick.
                        Err(_) => return,
                    }
                }
                Decided::Pie { swap } => BotDecision::Pie { swap },
                Decided::Resign => BotDecision::Resign,
            };
            driver.bot_answer(stale, decision);
        }
        Op::RematchAnswer { created } => driver.rematch_answer(created),
    }
}

/// Reads a frame as the server does; a frame that does not read must be
/// refused with a reading code.
fn read_frame(bytes: &[u8]) -> Option<ClientMessage> {
    match protocol::read::<ClientMessage>(bytes) {
        Ok(msg) => {
            let json = msg.to_json();
            assert_eq!(
                ClientMessage::from_json(&json).as_ref(),
                Ok(&msg),
                "a message read reads back from its own JSON"
            );
            Some(msg)
        }
        Err(e) => {
            assert!(
                matches!(
                    e.code,
                    ErrorCode::BadJson | ErrorCode::BadMessage | ErrorCode::NotFinite
                ),
                "a frame refused with {}",
                e.code
            );
            assert!(!e.message.is_empty(), "a refused frame is told why");
            None
        }
    }
}

fn piece_id(piece: u8) -> PieceId {
    let side = if piece % 16 < 8 {
        Side::White
    } else {
        Side::Black
    };
    match PieceId::new(side, piece % 8) {
        Some(id) => id,
        None => unreachable!("files 0 to 7 are pieces"),
    }
}

fn velocity(vx: i8, vy: i8) -> DVec2 {
    DVec2::new(f64::from(vx), f64::from(vy)) / 60.0
}

fn message(said: Said) -> ClientMessage {
    match said {
        Said::Shot { piece, vx, vy } => ClientMessage::Shot {
            piece: piece_id(piece),
            velocity: velocity(vx, vy),
        },
        Said::Pie { swap } => ClientMessage::PieDecision { swap },
        Said::Resign => ClientMessage::Resign,
        Said::OfferRematch => ClientMessage::OfferRematch,
        Said::AcceptRematch => ClientMessage::AcceptRematch,
        // Two bytes a character: the limit counts characters.
        Said::Chat { len } => ClientMessage::Chat {
            text: "ж".repeat(usize::from(len) % 1024),
        },
        Said::Hello => ClientMessage::Hello {
            protocol: protocol::PROTOCOL_VERSION,
            name: "Furmanov".into(),
            token: None,
            key: None,
        },
    }
}
