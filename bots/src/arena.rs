//! A whole match between two bots in this process, through the very same
//! [`game::session::Session`] the server drives — seats with tokens, the
//! turn clock, the pie decision, passes and forfeits — on a virtual clock.
//! Each seat follows the match from the session's messages alone
//! ([`Follower`], as a client on the network does), so its bot is handed
//! the public view, never the seed. A bot decides at most once per change
//! of the match: a shot the session refuses is not retried, and the
//! virtual clock jumps to the turn's deadline, which passes the turn (three
//! in a row forfeit). Thinking takes a fixed virtual time, so a match is
//! repeatable for its seeds however long the bots really think.
//! Tournaments play their games here.

use crate::bot::{Bot, Context};
use crate::follow::{Followed, Follower};
use crate::runner::message;
use game::protocol::ServerMessage;
use game::session::{ConnId, Effect, Input, Moment, Request, SeatSpec, Session, SessionLimits, To};
use game::token::{SeatToken, TokenHash};
use game::{Config, ConfigError, Game, MatchRecord, MatchResult, Seat};
use std::time::{Duration, Instant};

/// How long a match may run.
#[derive(Clone, Debug, PartialEq)]
pub struct ArenaLimits {
    /// Real time a bot gets for one decision (its context's deadline).
    pub think: Duration,
    /// The turn clock, on the virtual clock.
    pub turn: Duration,
    /// Virtual time one decision takes (less than `turn`).
    pub virtual_think: Duration,
    /// Shots after which the match is stopped and scored a draw.
    pub max_shots: u32,
}

impl Default for ArenaLimits {
    fn default() -> Self {
        ArenaLimits {
            think: Duration::from_secs(1),
            turn: Duration::from_secs(60),
            virtual_think: Duration::from_secs(1),
            max_shots: 1500,
        }
    }
}

/// How a match between two bots went.
#[derive(Clone, Debug)]
pub struct MatchReport {
    /// The result (`None`: stopped at [`ArenaLimits::max_shots`], a draw).
    pub result: Option<MatchResult>,
    /// The record, replayable.
    pub record: MatchRecord,
    /// Shots played.
    pub shots: u32,
    /// Whether Black took White's side under the pie rule.
    pub swapped: bool,
    /// Decisions the session refused.
    pub refusals: u32,
    /// Turns the clock passed (after refusals).
    pub timeouts: u32,
}

impl MatchReport {
    /// The points `seat` scored: 1 for a win, ½ for a draw, 0 for a loss.
    pub fn score(&self, seat: Seat) -> f64 {
        match self.result.as_ref().and_then(MatchResult::winner) {
            Some(side) if Seat::of(side, self.swapped) == seat => 1.0,
            Some(_) => 0.0,
            None => 0.5,
        }
    }
}

/// The two seats: their connections, followers, bots and the version each
/// last decided on.
struct Seats<'a> {
    conns: [ConnId; 2],
    followers: [Follower; 2],
    bots: [&'a mut dyn Bot; 2],
    decided: [Option<u64>; 2],
    refusals: u32,
    timeouts: u32,
}

impl Seats<'_> {
    /// Delivers what the session said to the seats it is for, and tells
    /// their bots of every shot and of the end.
    fn deliver(&mut self, effects: Vec<Effect>) {
        for effect in effects {
            // A refused message is answered to its sender alone, as the
            // server's room does.
            let (to, msg) = match effect {
                Effect::Send { to, msg } => (to, msg),
                Effect::Refused {
                    request: Request::Message(conn),
                    refusal,
                } => (To::Only(conn), refusal.to_message()),
                _ => continue,
            };
            if matches!(msg, ServerMessage::TurnPassed { .. }) {
                self.timeouts += 1;
            }
            for k in 0..2 {
                if !to.includes(self.conns[k]) {
                    continue;
                }
                match self.followers[k].apply(msg.clone(), Instant::now()) {
                    Followed::Shot(outcome) => self.bots[k].on_shot(&outcome),
                    Followed::Over { result, record } => {
                        self.bots[k].on_match_over(&result, &record)
                    }
                    Followed::Refused { .. } => self.refusals += 1,
                    _ => {}
                }
            }
        }
    }
}

/// Plays a match of `config` with seed `seed`: `first` takes the first seat
/// (White, unless the pie rule swaps), `second` the other.
pub fn play_match(
    config: Config,
    seed: u64,
    first: &mut dyn Bot,
    second: &mut dyn Bot,
    limits: &ArenaLimits,
) -> Result<MatchReport, ConfigError> {
    let game = Game::new(config, seed)?;
    let seat = |name: &str| SeatSpec {
        name: Some(name.to_string()),
        token: Some(TokenHash::of(&format!("{name}-token"))),
        bot: None,
    };
    let session_limits = SessionLimits {
        turn: limits.turn,
        grace: limits.turn,
        bot_delay: Duration::ZERO,
        idle: Duration::from_secs(24 * 3600),
        max_connections_per_match: 2,
    };
    let mut now = Moment::ZERO;
    let mut session = Session::new(
        "arena",
        game,
        [seat("first"), seat("second")],
        session_limits,
        now,
    );
    let mut seats = Seats {
        conns: [ConnId(1), ConnId(2)],
        followers: [Follower::new(Seat::First), Follower::new(Seat::Second)],
        bots: [first, second],
        decided: [None, None],
        refusals: 0,
        timeouts: 0,
    };
    for (k, name) in ["first", "second"].into_iter().enumerate() {
        let input = Input::Connect {
            conn: seats.conns[k],
            token: Some(SeatToken::new(format!("{name}-token"))),
            name: name.to_string(),
        };
        let effects = session.handle(input, now);
        seats.deliver(effects);
    }
    while !session.game().is_over() && session.game().shots() < limits.max_shots {
        let asked = (0..2).find(|&k| {
            let f = &seats.followers[k];
            f.ask().is_some() && seats.decided[k] != Some(f.version())
        });
        match asked {
            Some(k) => {
                let f = &seats.followers[k];
                seats.decided[k] = Some(f.version());
                let (Some(view), Some(side)) = (f.view().cloned(), f.side()) else {
                    break;
                };
                let decision = seats.bots[k].decide(&Context::new(&view, side, limits.think));
                now = now + limits.virtual_think;
                // No answer: nothing is sent, and the clock passes the turn.
                if let Some(msg) = message(decision) {
                    let input = Input::Message {
                        conn: seats.conns[k],
                        msg,
                    };
                    let effects = session.handle(input, now);
                    seats.deliver(effects);
                }
            }
            None => {
                // Nobody has anything to decide (a refused move): the
                // clock runs to its deadline.
                let Some(deadline) = session.next_deadline() else {
                    break;
                };
                now = deadline;
                let effects = session.handle(Input::Timer, now);
                seats.deliver(effects);
            }
        }
    }
    let game = session.game();
    Ok(MatchReport {
        result: game.result(),
        // With its noise secret even when the arena stopped the match
        // unfinished: a local match keyed by a public seed hides nothing,
        // and its record must replay.
        record: game.private_record(),
        shots: game.shots(),
        swapped: game.swapped(),
        refusals: seats.refusals,
        timeouts: seats.timeouts,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bot::Decision;
    use crate::level::by_name;
    use game::Side;

    #[test]
    fn two_bots_play_a_match_to_its_end_and_the_record_replays() {
        let mut a = by_name("greedy", 1).unwrap();
        let mut b = by_name("random", 2).unwrap();
        let r = play_match(
            Config::standard(),
            7,
            &mut a,
            &mut b,
            &ArenaLimits::default(),
        )
        .unwrap();
        assert!(r.result.is_some(), "{} shots", r.shots);
        let replay = game::Replay::new(r.record.clone()).unwrap();
        assert_eq!(replay.game().result(), r.result);
        assert_eq!(r.score(Seat::First) + r.score(Seat::Second), 1.0);
    }

    struct Cheater;
    impl Bot for Cheater {
        fn decide(&mut self, ctx: &Context) -> Decision {
            // Always someone else's piece: refused every time.
            let theirs = ctx.view.board.of(ctx.me.opponent()).next().unwrap().id;
            Decision::Shot(game::Shot::new(theirs, glam::DVec2::X, ctx.config()).unwrap())
        }
    }

    #[test]
    fn a_bot_whose_shots_are_refused_loses_its_turns_on_the_clock_then_the_match() {
        let mut good = by_name("greedy", 1).unwrap();
        let r = play_match(
            Config::default(),
            1,
            &mut Cheater,
            &mut good,
            &ArenaLimits::default(),
        )
        .unwrap();
        assert_eq!(r.score(Seat::Second), 1.0);
        assert!(r.refusals >= 1, "{} refusals", r.refusals);
        assert!(r.timeouts >= 1, "the clock passed the refused turns");
        let replay = game::Replay::new(r.record.clone()).unwrap();
        assert_eq!(replay.game().result(), r.result);
    }

    #[test]
    fn three_refused_turns_in_a_row_forfeit_on_the_clock() {
        let mut also = Cheater;
        let r = play_match(
            Config::default(),
            2,
            &mut Cheater,
            &mut also,
            &ArenaLimits::default(),
        )
        .unwrap();
        assert_eq!(r.shots, 0);
        assert_eq!(
            r.result,
            Some(MatchResult::Won {
                side: Side::Black,
                reason: game::WinReason::Timeouts
            })
        );
        // White and Black pass twice each; White's third timeout forfeits.
        assert_eq!(r.timeouts, 4);
    }
}
