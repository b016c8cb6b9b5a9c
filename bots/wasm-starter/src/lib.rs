//! A starter bot for the server to host. Build it with
//!
//! ```sh
//! cargo build -p chapaev-starter-bot --target wasm32-unknown-unknown --release
//! ```
//!
//! and upload `target/wasm32-unknown-unknown/release/chapaev_starter_bot.wasm`.
//! It aims each of its pieces straight at each enemy piece at three speeds,
//! simulates all of them in one batch on the server's engine, and plays
//! the one that knocks off the most enemies for the fewest of its own
//! (ties broken by the decision's random stream). It keeps its side under
//! the pie rule.

use chapaev_bot_sdk::{export_bot, BotDecision, Candidate, Context, Phase, Shot};

/// Fractions of the maximum speed tried.
const SPEEDS: [f64; 3] = [0.5, 0.75, 0.999];

/// The bot's decision.
pub fn decide(ctx: &mut Context) -> BotDecision {
    let view = ctx.view().clone();
    if view.phase == Phase::PieDecision {
        return BotDecision::Pie { swap: false };
    }
    let me = ctx.me();
    let mut candidates = Vec::new();
    for mine in view.board.of(me) {
        for enemy in view.board.of(me.opponent()) {
            let aim = enemy.pos - mine.pos;
            let Some(dir) = aim.try_normalize() else {
                continue;
            };
            for f in SPEEDS {
                candidates.push(Candidate {
                    piece: mine.id,
                    velocity: dir * (f * view.config.max_speed),
                });
            }
        }
    }
    let Ok(outcomes) = ctx.simulate(&ctx.board(), &candidates) else {
        return BotDecision::Resign;
    };
    let mut best: Option<(f64, Candidate)> = None;
    for (c, o) in candidates.iter().zip(&outcomes) {
        if !o.played() {
            continue;
        }
        let tie = (ctx.random() >> 11) as f64 / (1u64 << 53) as f64 * 0.01;
        let score = f64::from(o.lost(me.opponent())) - 1.5 * f64::from(o.lost(me))
            + if o.shoots_again() { 0.5 } else { 0.0 }
            + tie;
        if best.is_none_or(|(s, _)| score > s) {
            best = Some((score, *c));
        }
    }
    match best.and_then(|(_, c)| Shot::new(c.piece, c.velocity, &view.config).ok()) {
        Some(shot) => BotDecision::Shot(shot),
        None => BotDecision::Resign,
    }
}

export_bot!(decide);

#[cfg(test)]
mod tests {
    use super::*;
    use chapaev_bot_sdk::{DecideRequest, Side};

    #[test]
    fn from_the_opening_it_shoots_its_own_piece_within_the_speed_limit() {
        let view = game::Game::new(game::Config::standard(), 1).unwrap().view();
        let request = DecideRequest {
            me: Side::White,
            view: view.clone(),
        };
        let BotDecision::Shot(shot) = decide(&mut Context::new(request, 1)) else {
            panic!("a shot from the opening")
        };
        assert_eq!(shot.piece().side(), Side::White);
        assert!(shot.speed() <= view.config.max_speed);
    }
}
