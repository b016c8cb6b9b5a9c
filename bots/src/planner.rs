//! The [`Planner`]: a one-ply chooser that knows its own hand. It tries
//! candidate shots ([`crate::candidates`], their speeds fractions of the
//! hand's own full power), keeps the best few as aimed, then plays each of
//! those again under several draws of its own hand's error (a fresh set
//! from its own generator for every decision, the same set for every
//! candidate so they are compared on equal terms) — and under the match's
//! public noise, if any — and plays the one whose mean value
//! ([`crate::eval::after_shot`]) is highest. A shaky hand thus prefers the
//! shots it can make: short, straight, soft enough to stay on the board;
//! a steady one goes for the long cut a perfect aimer would.
//!
//! The planner only chooses what to intend; a [`crate::Handed`] wrapper
//! plays the intention with the hand's actual error and the match's bias.
//! The planner does not know the bias (a person does not know which way
//! they will pull), only how wide its errors are.

use crate::bot::{Ask, Bot, Context, Decision};
use crate::candidates::{candidates, Spread};
use crate::eval;
use crate::hand::{Aim, Bias, HandModel};
use crate::par;
use crate::simulator::Simulator;
use game::noise::{NoiseDraw, SplitMix64};
use game::{Config, Shot, Side};

/// How the planner looks.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanSettings {
    /// The candidates; their speeds are fractions of the hand's full power.
    pub spread: Spread,
    /// Candidates kept from the first, as-aimed pass.
    pub keep: usize,
    /// Draws of the hand's error per kept candidate.
    pub samples: usize,
}

/// A bot choosing under its own hand's error.
#[derive(Clone, Debug)]
pub struct Planner {
    model: HandModel,
    settings: PlanSettings,
    rng: SplitMix64,
}

impl Planner {
    /// A planner for a hand of `model`, its draws following from `seed`.
    pub fn new(model: HandModel, settings: PlanSettings, seed: u64) -> Planner {
        Planner {
            model,
            settings,
            rng: SplitMix64::new(seed),
        }
    }

    /// The hand it plans for.
    pub fn model(&self) -> &HandModel {
        &self.model
    }

    /// Plans for another hand from now on.
    pub fn set_model(&mut self, model: HandModel) {
        self.model = model;
    }

    /// Every kept candidate with its mean value under the hand, best
    /// first (`side` to shoot on `ctx`'s board).
    pub fn ranked(&mut self, ctx: &Context, side: Side) -> Vec<(Shot, f64)> {
        let config = ctx.config();
        let board = &ctx.view.board;
        let sim = Simulator::new(ctx.view);
        let mut power = config.clone();
        power.max_speed = config.max_speed * self.model.full_power.clamp(0.05, 1.0);
        let all = candidates(&power, board, side, &self.settings.spread);
        let mut scored: Vec<(usize, f64)> = par::map(&all, |i, shot| {
            let r = sim.play(side, shot).ok()?;
            Some((i, eval::after_shot(config, &r, side)))
        })
        .into_iter()
        .flatten()
        .collect();
        scored.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
        scored.truncate(self.settings.keep.max(1));
        let shaky = self.model.angle_sigma > 0.0 || self.model.speed_sigma > 0.0;
        if !shaky && ctx.noise().is_none() {
            return scored.into_iter().map(|(i, v)| (all[i], v)).collect();
        }
        let draws: Vec<(NoiseDraw, NoiseDraw)> = (0..self.settings.samples.max(1))
            .map(|_| {
                (
                    NoiseDraw::sample(&mut self.rng),
                    NoiseDraw::sample(&mut self.rng),
                )
            })
            .collect();
        let model = self.model;
        let mut valued: Vec<(usize, usize, f64)> = par::map(&scored, |rank, &(i, _)| {
            let mean = mean_value(config, &sim, side, &model, &all[i], &draws);
            (rank, i, mean)
        });
        valued.sort_by(|a, b| b.2.total_cmp(&a.2).then(a.0.cmp(&b.0)));
        valued.into_iter().map(|(_, i, v)| (all[i], v)).collect()
    }
}

/// The mean value for `side` of `shot` played by a hand of `model` (no
/// bias) under each of `draws` (the hand's draw, then the match noise's).
pub fn mean_value(
    config: &Config,
    sim: &Simulator,
    side: Side,
    model: &HandModel,
    shot: &Shot,
    draws: &[(NoiseDraw, NoiseDraw)],
) -> f64 {
    let aim = Aim::of(config, sim.board(), shot);
    let total: f64 = draws
        .iter()
        .map(|&(hand, noise)| {
            let played = model.shot(config, shot, &aim, hand, Bias::default());
            match sim.play_noisy(side, &played, noise) {
                Ok(r) => eval::after_shot(config, &r, side),
                Err(_) => -eval::ROUND,
            }
        })
        .sum();
    total / draws.len().max(1) as f64
}

impl Bot for Planner {
    fn decide(&mut self, ctx: &Context) -> Decision {
        if ctx.ask() == Some(Ask::Pie) {
            let seed = self.rng.next_u64();
            return Decision::Pie {
                swap: crate::pie::swap(ctx.view, &crate::pie::PieSettings::default(), seed),
            };
        }
        match self.ranked(ctx, ctx.me).first() {
            Some(&(shot, _)) => Decision::Shot(shot),
            None => Decision::Resign,
        }
    }
}
