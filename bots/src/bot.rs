//! The [`Bot`] trait: what a bot is asked, what it may know, and what it
//! answers. A bot sees exactly what a player sees — the public
//! [`MatchView`] (the board, the rules, the public noise model, whose turn
//! it is), never the match's seed or the noise draw of a shot not yet
//! played — and answers one [`Decision`] before its deadline. Optional
//! hooks tell it what happened; each has a no-op default, so a bot
//! implements only [`Bot::decide`].

use crate::clock::Instant;
use game::session::BotDecision;
use game::{
    Config, MatchRecord, MatchResult, MatchView, NoiseConfig, Phase, Shot, ShotOutcome, Side,
};
use std::time::Duration;

/// What a bot is asked to decide.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ask {
    /// A shot for the side to shoot.
    Shoot,
    /// Black's pie-rule decision: swap sides with White, or keep.
    Pie,
}

/// Everything a bot may know when it decides: what any player may know.
#[derive(Clone, Debug)]
pub struct Context<'a> {
    /// The public state of the match (board, rules, turn, round).
    pub view: &'a MatchView,
    /// The side the bot decides for.
    pub me: Side,
    /// Answer before this instant; a late answer may find the turn passed.
    pub deadline: Instant,
}

impl<'a> Context<'a> {
    /// A context for `me` on `view`, answering within `budget` from now.
    pub fn new(view: &'a MatchView, me: Side, budget: Duration) -> Context<'a> {
        Context {
            view,
            me,
            deadline: Instant::now() + budget,
        }
    }

    /// What is asked now (`None` when the match is over or it is not
    /// `me`'s to decide).
    pub fn ask(&self) -> Option<Ask> {
        match self.view.phase {
            Phase::Shooting if self.view.turn == self.me => Some(Ask::Shoot),
            Phase::PieDecision if self.me == Side::Black => Some(Ask::Pie),
            _ => None,
        }
    }

    /// The match's configuration: geometry, physics and rule variants.
    pub fn config(&self) -> &Config {
        &self.view.config
    }

    /// The public execution-noise model every shot of this match is played
    /// with (`None`: shots are played exactly as aimed). The draw itself is
    /// secret until the shot is played.
    pub fn noise(&self) -> Option<&NoiseConfig> {
        self.view.config.variants.noise.as_ref()
    }

    /// Time left before the deadline.
    pub fn time_left(&self) -> Duration {
        self.deadline.saturating_duration_since(Instant::now())
    }
}

/// A bot's answer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Decision {
    /// Flick a piece (the shot was built valid for the match's config).
    Shot(Shot),
    /// The pie-rule decision.
    Pie { swap: bool },
    /// Give up the match.
    Resign,
    /// No answer this turn (a hosted bot that ran out of fuel or failed):
    /// nothing is sent, and the turn runs out on the match's clock.
    NoAnswer,
}

/// A decision as the session and the JSON answers carry it.
impl From<BotDecision> for Decision {
    fn from(d: BotDecision) -> Decision {
        match d {
            BotDecision::Shot(shot) => Decision::Shot(shot),
            BotDecision::Pie { swap } => Decision::Pie { swap },
            BotDecision::Resign => Decision::Resign,
            BotDecision::NoAnswer => Decision::NoAnswer,
        }
    }
}

/// A Chapaev bot. One required method; the hooks default to doing nothing.
///
/// ```
/// use bots::{Bot, Context, Decision, Simulator};
/// use game::Shot;
///
/// /// Flicks its first piece straight at the enemy's nearest piece, full power.
/// struct Straight;
///
/// impl Bot for Straight {
///     fn decide(&mut self, ctx: &Context) -> Decision {
///         let board = &ctx.view.board;
///         let me = board.of(ctx.me).next().expect("a side to shoot has a piece");
///         let target = board
///             .of(ctx.me.opponent())
///             .min_by(|a, b| a.pos.distance(me.pos).total_cmp(&b.pos.distance(me.pos)))
///             .expect("the round goes on, so the enemy has a piece");
///         let speed = ctx.config().max_speed;
///         match Shot::aimed(me.id, target.pos - me.pos, speed, ctx.config()) {
///             Ok(shot) => Decision::Shot(shot),
///             Err(_) => Decision::Resign,
///         }
///     }
/// }
///
/// let view = game::Game::new(game::Config::default(), 1).unwrap().view();
/// let ctx = Context::new(&view, game::Side::White, std::time::Duration::from_secs(1));
/// let Decision::Shot(shot) = Straight.decide(&ctx) else { panic!() };
/// // What it would do, with exactly the server's physics:
/// let after = Simulator::new(&view).play(game::Side::White, &shot).unwrap();
/// assert_eq!(after.knocked_off.len(), 1);
/// ```
pub trait Bot: Send {
    /// The bot's answer to what `ctx.ask()` asks: a [`Decision::Shot`] when
    /// it is to shoot, a [`Decision::Pie`] when it holds Black's pie
    /// decision, or [`Decision::Resign`]. A shot that the game refuses (not
    /// the bot's piece, too fast) is answered with the refusal and the turn
    /// stays the bot's until its clock runs out. Must return before
    /// `ctx.deadline`.
    fn decide(&mut self, ctx: &Context) -> Decision;

    /// Called with every shot played in the match, the bot's own and the
    /// opponent's, after the server resolved it (with the noise the server
    /// drew). Default: nothing.
    fn on_shot(&mut self, outcome: &ShotOutcome) {
        let _ = outcome;
    }

    /// Called once when the match is over, with its record (which now
    /// includes the seed). Default: nothing.
    fn on_match_over(&mut self, result: &MatchResult, record: &MatchRecord) {
        let _ = (result, record);
    }
}

impl<B: Bot + ?Sized> Bot for Box<B> {
    fn decide(&mut self, ctx: &Context) -> Decision {
        (**self).decide(ctx)
    }
    fn on_shot(&mut self, outcome: &ShotOutcome) {
        (**self).on_shot(outcome)
    }
    fn on_match_over(&mut self, result: &MatchResult, record: &MatchRecord) {
        (**self).on_match_over(result, record)
    }
}
