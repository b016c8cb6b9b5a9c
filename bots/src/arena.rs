//! A whole match between two bots in this process: the game asks whichever
//! seat must act, hands its bot the public view (never the seed), applies
//! the decision, and tells both bots every shot. A shot the game refuses
//! or a decision that does not answer what was asked passes the turn, as
//! the server's clock would once it ran out. Tournaments play their games
//! here.

use crate::bot::{Bot, Context, Decision};
use game::{Config, ConfigError, ForfeitReason, Game, MatchRecord, MatchResult, Phase, Seat, Side};
use std::time::Duration;

/// How long a match may run.
#[derive(Clone, Debug, PartialEq)]
pub struct ArenaLimits {
    /// Time a bot gets for one decision.
    pub think: Duration,
    /// Shots after which the match is stopped and scored a draw.
    pub max_shots: u32,
    /// Refused decisions in a row after which the seat forfeits.
    pub max_refusals: u32,
}

impl Default for ArenaLimits {
    fn default() -> Self {
        ArenaLimits {
            think: Duration::from_secs(1),
            max_shots: 1500,
            max_refusals: 3,
        }
    }
}

/// How a match between two bots went.
#[derive(Clone, Debug)]
pub struct MatchReport {
    /// The result (`None`: stopped at [`ArenaLimits::max_shots`], a draw).
    pub result: Option<MatchResult>,
    /// The record, replayable in the web client.
    pub record: MatchRecord,
    /// Shots played.
    pub shots: u32,
    /// Whether Black took White's side under the pie rule.
    pub swapped: bool,
    /// Decisions the game refused.
    pub refusals: u32,
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

/// Plays a match of `config` with seed `seed`: `first` takes the first seat
/// (White, unless the pie rule swaps), `second` the other.
pub fn play_match(
    config: Config,
    seed: u64,
    first: &mut dyn Bot,
    second: &mut dyn Bot,
    limits: &ArenaLimits,
) -> Result<MatchReport, ConfigError> {
    let mut game = Game::new(config, seed)?;
    let mut refusals = [0u32; 2];
    let mut total_refusals = 0;
    while !game.is_over() && game.shots() < limits.max_shots {
        let side = match game.phase() {
            Phase::PieDecision => Side::Black,
            _ => game.to_shoot().unwrap_or(Side::White),
        };
        let seat = game.seat_of(side);
        let bot: &mut dyn Bot = match seat {
            Seat::First => first,
            Seat::Second => second,
        };
        let view = game.view();
        let decision = bot.decide(&Context::new(&view, side, limits.think));
        let applied = match (game.phase(), decision) {
            (Phase::Shooting, Decision::Shot(shot)) => match game.play(side, shot) {
                Ok(played) => {
                    first.on_shot(&played.outcome);
                    second.on_shot(&played.outcome);
                    true
                }
                Err(_) => false,
            },
            (Phase::PieDecision, Decision::Pie { swap }) => game.decide_pie(side, swap).is_ok(),
            (_, Decision::Resign) => game.resign(side).is_ok(),
            _ => false,
        };
        let k = seat_index(seat);
        if applied {
            refusals[k] = 0;
            continue;
        }
        refusals[k] += 1;
        total_refusals += 1;
        let _ = if refusals[k] >= limits.max_refusals {
            game.forfeit(side, ForfeitReason::Timeouts).map(|_| ())
        } else if game.phase() == Phase::PieDecision {
            game.decide_pie(side, false)
        } else {
            game.pass(side)
        };
    }
    let report = MatchReport {
        result: game.result(),
        record: game.record().clone(),
        shots: game.shots(),
        swapped: game.swapped(),
        refusals: total_refusals,
    };
    if let Some(result) = &report.result {
        first.on_match_over(result, &report.record);
        second.on_match_over(result, &report.record);
    }
    Ok(report)
}

fn seat_index(seat: Seat) -> usize {
    match seat {
        Seat::First => 0,
        Seat::Second => 1,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::level::by_name;

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
    fn a_bot_whose_shots_are_refused_loses_its_turns_then_the_match() {
        let mut good = by_name("greedy", 1).unwrap();
        let limits = ArenaLimits {
            max_refusals: 1,
            ..ArenaLimits::default()
        };
        let r = play_match(Config::default(), 1, &mut Cheater, &mut good, &limits).unwrap();
        assert_eq!(r.score(Seat::Second), 1.0);
        assert_eq!(r.refusals, 1);
        assert_eq!(
            r.result,
            Some(MatchResult::Won {
                side: Side::Black,
                reason: game::WinReason::Timeouts
            })
        );
    }
}
