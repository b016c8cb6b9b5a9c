//! `random`: legal random shots — a random own piece, mostly towards a
//! random enemy, otherwise in a random direction, at a random speed. The
//! floor every other bot is measured against.

use crate::bot::{Ask, Bot, Context, Decision};
use game::noise::SplitMix64;
use game::Shot;
use glam::DVec2;

/// The random bot, with its own generator.
#[derive(Clone, Debug)]
pub struct RandomBot {
    rng: SplitMix64,
}

impl RandomBot {
    /// A random bot whose choices follow from `seed`.
    pub fn new(seed: u64) -> RandomBot {
        RandomBot {
            rng: SplitMix64::new(seed),
        }
    }
}

fn pick<'a, T>(items: &'a [T], rng: &mut SplitMix64) -> Option<&'a T> {
    if items.is_empty() {
        return None;
    }
    items.get((rng.next_u64() % items.len() as u64) as usize)
}

impl Bot for RandomBot {
    fn decide(&mut self, ctx: &Context) -> Decision {
        if ctx.ask() == Some(Ask::Pie) {
            return Decision::Pie {
                swap: self.rng.next_u64() & 1 == 1,
            };
        }
        let config = ctx.config();
        let board = &ctx.view.board;
        let own: Vec<_> = board.of(ctx.me).collect();
        let enemy: Vec<_> = board.of(ctx.me.opponent()).collect();
        let Some(me) = pick(&own, &mut self.rng) else {
            return Decision::Resign;
        };
        let dir = match pick(&enemy, &mut self.rng) {
            Some(target) if self.rng.next_f64() < 0.7 => target.pos - me.pos,
            _ => {
                let a = self.rng.next_f64() * std::f64::consts::TAU;
                DVec2::new(a.cos(), a.sin())
            }
        };
        let speed = config.max_speed * (0.3 + 0.7 * self.rng.next_f64());
        match Shot::aimed(me.id, dir, speed, config) {
            Ok(shot) => Decision::Shot(shot),
            Err(_) => Decision::Resign,
        }
    }
}
