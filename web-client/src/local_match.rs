//! A match against the computer played in this page, with no server: the
//! very rules machine the server drives ([`Session`], fed the player's
//! messages and the page's clock), a noise secret drawn here, and the
//! computer level ([`Level`], from the `bots` crate) deciding in this
//! thread. It speaks to the Play screen as the server's socket does — it
//! takes the player's [`ClientMessage`]s and hands back the session's
//! [`ServerMessage`]s — so the screen keeps one code path for both.
//!
//! Such a match is casual: nothing is stored, nothing is rated, and it
//! ends with the page. The computer thinks on the page's only thread, so
//! the screen asks it to ([`LocalMatch::think`]) only once its question is
//! pending ([`LocalMatch::thinking`]) and the last shot's film has played;
//! a decision is held to [`THINK`] of the page's clock, after which a
//! search stops sampling (the `easy`, `medium` and `adaptive` levels do
//! their fixed work well within it).

use bots::{Bot, Context, Decision, Level};
use game::protocol::{ClientMessage, ServerMessage};
use game::session::{
    BotDecision, ConnId, Effect, Input, Moment, Request, SeatSpec, Session, SessionLimits,
};
use game::token::{SeatToken, TokenHash};
use game::{Config, ConfigError, Game, MatchView, NoiseSecret, Seat, Side};
use std::time::Duration;

/// The page's one connection to its session.
const PLAYER: ConnId = ConnId(1);

/// The seat token the page holds (nobody else can reach the session).
const TOKEN: &str = "offline-seat";

/// The time a decision may take on the page's clock.
pub const THINK: Duration = Duration::from_secs(1);

/// The turn clock of an offline match: the longest a match may have (the
/// player may think, or leave the page in the background, at leisure).
const TURN: Duration = Duration::from_secs(3600);

/// The computer's question, waiting for [`LocalMatch::think`].
struct Asked {
    seat: Seat,
    side: Side,
    at_move: usize,
    view: Box<MatchView>,
}

/// A match against a computer level, played in this page.
pub struct LocalMatch {
    session: Session,
    bot: Box<dyn Bot>,
    /// The page's clock at the last call, in seconds.
    now: f64,
    /// The session's messages for the player, not yet polled.
    inbox: Vec<ServerMessage>,
    asked: Option<Asked>,
}

/// A moment on the session's clock from the page's seconds.
fn moment(seconds: f64) -> Moment {
    Moment::new(Duration::try_from_secs_f64(seconds).unwrap_or_default())
}

impl LocalMatch {
    /// A match of the standard casual rules (the server's default) between
    /// `name` in the first seat (White) and `level` in the second, its noise
    /// keyed by `secret` and the computer's choices by `bot_seed`, starting
    /// at `now` (seconds on the page's clock). The player is seated at once:
    /// the first poll brings the match's state.
    pub fn new(
        level: Level,
        name: &str,
        secret: NoiseSecret,
        bot_seed: u64,
        now: f64,
    ) -> Result<LocalMatch, ConfigError> {
        let game = Game::new(Config::default(), secret)?;
        let seats = [
            SeatSpec {
                name: Some(name.to_string()),
                token: Some(TokenHash::of(TOKEN)),
                bot: None,
            },
            SeatSpec {
                name: None,
                token: None,
                bot: Some(level.as_str().to_string()),
            },
        ];
        let limits = SessionLimits {
            turn: TURN,
            grace: TURN,
            bot_delay: Duration::ZERO,
            idle: Duration::from_secs(24 * 3600),
            max_connections_per_match: 1,
        };
        let session = Session::new("offline", game, seats, limits, moment(now));
        let mut m = LocalMatch {
            session,
            bot: level.bot(bot_seed),
            now,
            inbox: Vec::new(),
            asked: None,
        };
        let connect = Input::Connect {
            conn: PLAYER,
            token: Some(SeatToken::new(TOKEN)),
            name: name.to_string(),
        };
        let effects = m.session.handle(connect, moment(now));
        m.carry_out(effects);
        Ok(m)
    }

    /// The game as it stands.
    #[cfg(test)]
    pub fn game(&self) -> &Game {
        self.session.game()
    }

    /// Whether the computer has a question pending ([`LocalMatch::think`]
    /// answers it).
    pub fn thinking(&self) -> bool {
        self.asked.is_some()
    }

    /// Takes the player's message, as the server would; always `true` (an
    /// offline match is always reachable).
    pub fn send(&mut self, msg: &ClientMessage) -> bool {
        let input = Input::Message {
            conn: PLAYER,
            msg: msg.clone(),
        };
        let effects = self.session.handle(input, moment(self.now));
        self.carry_out(effects);
        true
    }

    /// Runs the session's clock to `now` (seconds on the page's clock) and
    /// hands over the messages for the player since the last poll.
    pub fn poll(&mut self, now: f64) -> Vec<ServerMessage> {
        self.now = self.now.max(now);
        let at = moment(self.now);
        // Each deadline moves the session on; a few at most are due at once.
        for _ in 0..8 {
            match self.session.next_deadline() {
                Some(deadline) if deadline <= at => {
                    let effects = self.session.handle(Input::Timer, at);
                    self.carry_out(effects);
                }
                _ => break,
            }
        }
        std::mem::take(&mut self.inbox)
    }

    /// The computer decides its pending question now, in this thread, and
    /// plays its answer; `false` if it had none.
    pub fn think(&mut self) -> bool {
        let Some(asked) = self.asked.take() else {
            return false;
        };
        let ctx = Context::new(&asked.view, asked.side, THINK);
        let decision = match self.bot.decide(&ctx) {
            Decision::Shot(shot) => BotDecision::Shot(shot),
            Decision::Pie { swap } => BotDecision::Pie { swap },
            Decision::Resign => BotDecision::Resign,
            Decision::NoAnswer => BotDecision::NoAnswer,
        };
        let input = Input::BotMove {
            seat: asked.seat,
            at_move: asked.at_move,
            decision,
        };
        let effects = self.session.handle(input, moment(self.now));
        self.carry_out(effects);
        true
    }

    /// Does what the session asks: messages for the player to its inbox,
    /// the computer's question to [`LocalMatch::think`]. Nothing is
    /// stored, and a rematch is a new offline match (the screen's).
    fn carry_out(&mut self, effects: Vec<Effect>) {
        for effect in effects {
            match effect {
                // A person playing the computer in the page is not timed:
                // the session's hour-long clock only passes the turn of a
                // page left alone, and is not shown as a countdown.
                Effect::Send {
                    msg: ServerMessage::Clock { .. },
                    ..
                } => {}
                Effect::Send { to, msg } if to.includes(PLAYER) => self.inbox.push(msg),
                Effect::Refused {
                    request: Request::Message(PLAYER),
                    refusal,
                } => self.inbox.push(refusal.to_message()),
                Effect::BotToAct {
                    seat,
                    side,
                    at_move,
                    view,
                    ..
                } => {
                    self.asked = Some(Asked {
                        seat,
                        side,
                        at_move,
                        view,
                    })
                }
                _ => {}
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use game::record::RecordedMove;
    use game::{Phase, Shot};

    /// The person's side of the test: a random shot (a perfect aimer such
    /// as greedy sweeps a match without rules noise, never handing the
    /// computer the turn).
    fn person_shot(m: &LocalMatch, person: &mut bots::RandomBot) -> Option<ClientMessage> {
        let view = m.game().view();
        if view.phase != Phase::Shooting || view.turn != Side::White {
            return None;
        }
        let ctx = Context::new(&view, Side::White, Duration::from_secs(5));
        match person.decide(&ctx) {
            Decision::Shot(shot) => Some(ClientMessage::Shot {
                piece: shot.piece(),
                velocity: shot.velocity(),
            }),
            _ => None,
        }
    }

    /// Plays a whole offline match against `level`: the messages the
    /// player got, and how many times the computer answered.
    fn play_out(m: &mut LocalMatch) -> (Vec<ServerMessage>, u32) {
        let mut got = m.poll(0.0);
        let (mut now, mut answers) = (0.0, 0);
        let mut person = bots::RandomBot::new(3);
        for _ in 0..2000 {
            if m.game().is_over() {
                break;
            }
            now += 0.5;
            got.extend(m.poll(now));
            if m.thinking() {
                assert!(m.think());
                answers += 1;
            } else if let Some(shot) = person_shot(m, &mut person) {
                assert!(m.send(&shot));
            }
        }
        got.extend(m.poll(now + 1.0));
        (got, answers)
    }

    #[test]
    fn an_offline_match_against_a_level_is_played_to_its_end_and_the_player_hears_all_of_it() {
        let secret = NoiseSecret::from_seed(11);
        let mut m = LocalMatch::new(Level::Easy, "Petka", secret, 5, 0.0).unwrap();
        let (got, answers) = play_out(&mut m);
        assert!(m.game().is_over(), "{} shots", m.game().shots());
        assert!(answers >= 1, "the computer answered");
        assert!(
            matches!(got.first(), Some(ServerMessage::MatchState { .. })),
            "{:?}",
            got.first()
        );
        let shots = got
            .iter()
            .filter(|g| matches!(g, ServerMessage::ShotPlayed { .. }))
            .count();
        assert_eq!(shots as u32, m.game().shots());
        assert!(got
            .iter()
            .any(|g| matches!(g, ServerMessage::MatchOver { .. })));
        assert!(
            !got.iter().any(|g| matches!(g, ServerMessage::Clock { .. })),
            "an offline match shows no turn clock"
        );
    }

    #[test]
    fn an_offline_match_is_bit_for_bit_the_game_its_secret_and_shots_make() {
        let secret = NoiseSecret::from_seed(23);
        let mut m = LocalMatch::new(Level::Medium, "Petka", secret, 9, 0.0).unwrap();
        play_out(&mut m);
        assert!(m.game().is_over());
        let computer_shot =
            |mv: &RecordedMove| matches!(mv, RecordedMove::Shot(o) if o.shooter == Side::Black);
        assert!(m.game().record().moves.iter().any(computer_shot));
        // The same shots, by the same sides, on a plain game of the same key.
        let mut plain = Game::new(Config::default(), secret).unwrap();
        for mv in &m.game().record().moves {
            match mv {
                RecordedMove::Shot(o) => {
                    let shot = Shot::new(o.piece, o.aimed, plain.config()).unwrap();
                    let played = plain.play(o.shooter, shot).unwrap();
                    assert_eq!(&played.outcome, o);
                }
                other => panic!("only shots in this match, not {other:?}"),
            }
        }
        assert_eq!(plain.result(), m.game().result());
        let bits = |g: &Game| {
            g.board()
                .pieces()
                .iter()
                .map(|p| (p.id, p.pos.x.to_bits(), p.pos.y.to_bits()))
                .collect::<Vec<_>>()
        };
        assert_eq!(bits(&plain), bits(m.game()));
        assert_eq!(plain.private_record(), m.game().private_record());
    }

    #[test]
    fn a_refused_shot_is_answered_to_the_player_and_changes_nothing() {
        let mut m =
            LocalMatch::new(Level::Hard, "Petka", NoiseSecret::from_seed(1), 1, 0.0).unwrap();
        m.poll(0.0);
        let black = game::PieceId::new(Side::Black, 0).unwrap();
        let theirs = ClientMessage::Shot {
            piece: black,
            velocity: glam::DVec2::new(0.0, -1.0),
        };
        assert!(m.send(&theirs));
        let got = m.poll(0.1);
        assert!(
            matches!(got.as_slice(), [ServerMessage::Error { .. }]),
            "{got:?}"
        );
        assert_eq!(m.game().shots(), 0);
        assert!(!m.thinking());
    }
}
