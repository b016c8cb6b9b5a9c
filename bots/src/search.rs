//! `search`: looks two plies deep and plans for missing. It scores every
//! candidate as greedy does, keeps the best few, then plays each of those
//! again under sampled execution noise (the match's public noise model, or
//! its own assumed imprecision where the match has none; the draws come
//! from its own generator, the same draws for every candidate so that they
//! are compared on equal terms) and answers each sampled result with the
//! best next shot — the opponent's, if the turn passes, its own if it
//! keeps it. A search given its own hand ([`SearchSettings::hand`], as the
//! `hard` level is) makes its candidates at that hand's full power and
//! plays each sample through that hand's error (then the match's noise,
//! if any) instead of the assumed noise. The candidates' samples run on all
//! cores (rayon, with the `parallel` feature; one after the other without
//! it, as in the browser), in a fixed order, so the choice depends only on
//! the position and the bot's seed.
//! The work per move is fixed (so the choice depends only on the position
//! and the bot's seed; about 0.1 s of CPU on a mid-game board); the time
//! budget and the context's deadline only cut the samples short on a
//! machine too loaded to finish in time.

use crate::bot::{Ask, Bot, Context, Decision};
use crate::candidates::{candidates, Spread};
use crate::clock::Instant;
use crate::eval;
use crate::eval::best_shot;
use crate::hand::{Aim, Bias, HandModel};
use crate::par;
use crate::simulator::Simulator;
use game::noise::{NoiseDraw, SplitMix64};
use game::{NoiseConfig, Shot};
use std::time::Duration;

/// How hard the search looks.
#[derive(Clone, Debug, PartialEq)]
pub struct SearchSettings {
    /// Candidates kept after the first, noiseless pass.
    pub keep: usize,
    /// Noise samples per kept candidate.
    pub samples: usize,
    /// How much the best next shot counts against the shot's own result
    /// (0: greedy under noise; 1: full two-ply).
    pub reply_weight: f64,
    /// The noise assumed for planning when the match has none (and the
    /// search has no hand of its own).
    pub assumed_noise: NoiseConfig,
    /// The bot's own hand, planned for on top of the match's noise.
    pub hand: Option<HandModel>,
    /// A safety cap on the time spent on one move (the context's deadline
    /// also caps it); normal moves take far less and are never cut.
    pub budget: Duration,
}

impl Default for SearchSettings {
    fn default() -> Self {
        SearchSettings {
            keep: 6,
            samples: 8,
            reply_weight: 0.6,
            assumed_noise: NoiseConfig {
                angle_sigma: 0.015,
                speed_sigma: 0.03,
            },
            hand: None,
            budget: Duration::from_secs(2),
        }
    }
}

/// The search bot.
#[derive(Clone, Debug)]
pub struct Search {
    settings: SearchSettings,
    rng: SplitMix64,
}

impl Search {
    /// A search bot with its own generator seeded by `seed`.
    pub fn new(seed: u64, settings: SearchSettings) -> Search {
        Search {
            settings,
            rng: SplitMix64::new(seed),
        }
    }

    fn best(&mut self, ctx: &Context) -> Option<Shot> {
        let started = Instant::now();
        let config = ctx.config();
        let board = &ctx.view.board;
        let me = ctx.me;
        let sim = Simulator::new(ctx.view);
        // First pass: every candidate as aimed.
        let mut power = config.clone();
        if let Some(hand) = &self.settings.hand {
            power.max_speed = config.max_speed * hand.full_power.clamp(0.05, 1.0);
        }
        let all = candidates(&power, board, me, &Spread::wide());
        let mut scored: Vec<(usize, f64)> = par::map(&all, |i, shot| {
            let r = sim.play(me, shot).ok()?;
            Some((i, eval::after_shot(config, &r, me)))
        })
        .into_iter()
        .flatten()
        .collect();
        scored.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
        let kept: Vec<usize> = scored
            .iter()
            .take(self.settings.keep)
            .map(|s| s.0)
            .collect();
        let first = *kept.first()?;
        // Second pass: the kept candidates under sampled noise, answered.
        let noise = ctx.noise().copied().unwrap_or(self.settings.assumed_noise);
        let draws: Vec<NoiseDraw> = (0..self.settings.samples)
            .map(|_| NoiseDraw::sample(&mut self.rng))
            .collect();
        let hand_draws: Vec<NoiseDraw> = match self.settings.hand {
            Some(_) => (0..self.settings.samples)
                .map(|_| NoiseDraw::sample(&mut self.rng))
                .collect(),
            None => Vec::new(),
        };
        let hand = self.settings.hand;
        let aims: Vec<Aim> = kept
            .iter()
            .map(|&i| Aim::of(config, board, &all[i]))
            .collect();
        let budget = self.settings.budget.min(ctx.time_left());
        let w = self.settings.reply_weight;
        let mut totals = vec![0.0; kept.len()];
        let mut done = 0;
        // Samples in rounds (one draw for every kept candidate per round),
        // stopping early only when the time budget runs out.
        for (d, draw) in draws.iter().enumerate() {
            if done > 0 && started.elapsed() >= budget.mul_f64(0.8) {
                break;
            }
            let values: Vec<f64> = par::map(&kept, |k, &i| {
                let aim = &aims[k];
                let played = match (&hand, hand_draws.get(d)) {
                    (Some(h), Some(&hd)) => {
                        let shot = h.shot(config, &all[i], aim, hd, Bias::default());
                        sim.play_noisy(me, &shot, *draw)
                    }
                    _ => sim.play_with(me, &all[i], &noise, *draw),
                };
                let Ok(r) = played else {
                    return -eval::ROUND;
                };
                let now = eval::after_shot(config, &r, me);
                if eval::round_over(&r) {
                    return now;
                }
                let next = eval::next_to_shoot(&r, me);
                let reply = best_shot(config, &r.board, next, &Spread::narrow())
                    .map(|(_, v)| if next == me { v } else { -v })
                    .unwrap_or(now);
                (1.0 - w) * now + w * reply
            });
            for (t, v) in totals.iter_mut().zip(values) {
                *t += v;
            }
            done += 1;
        }
        if done == 0 {
            return Some(all[first]);
        }
        let best = (0..kept.len())
            .max_by(|&a, &b| totals[a].total_cmp(&totals[b]).then(b.cmp(&a)))
            .map(|k| kept[k])?;
        Some(all[best])
    }
}

impl Bot for Search {
    fn decide(&mut self, ctx: &Context) -> Decision {
        if ctx.ask() == Some(Ask::Pie) {
            let seed = self.rng.next_u64();
            return Decision::Pie {
                swap: crate::pie::swap(ctx.view, &crate::pie::PieSettings::default(), seed),
            };
        }
        match self.best(ctx) {
            Some(shot) => Decision::Shot(shot),
            None => Decision::Resign,
        }
    }
}
