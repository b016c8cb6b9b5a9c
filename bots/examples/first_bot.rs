//! The bot of `docs/first-bot.md`, played against `greedy` in this process:
//! `cargo run --release -p bots --example first_bot`.

use bots::{play_match, ArenaLimits, Ask, Bot, Context, Decision, Simulator};
use game::noise::{NoiseDraw, SplitMix64};
use game::{Config, Seat, Shot};

/// Tries every own piece at every enemy piece at three speeds, plays each
/// 8 times under the match's public noise (its own draws), and keeps the
/// shot that knocks off the most enemies on average.
struct Counter {
    rng: SplitMix64,
}

impl Bot for Counter {
    fn decide(&mut self, ctx: &Context) -> Decision {
        if ctx.ask() == Some(Ask::Pie) {
            return Decision::Pie { swap: false };
        }
        let sim = Simulator::new(ctx.view);
        let draws: Vec<NoiseDraw> = (0..8).map(|_| NoiseDraw::sample(&mut self.rng)).collect();
        let mut best = (f64::NEG_INFINITY, None);
        for me in ctx.view.board.of(ctx.me) {
            for enemy in ctx.view.board.of(ctx.me.opponent()) {
                for speed in [0.6, 0.8, 1.0] {
                    let speed = speed * ctx.config().max_speed;
                    let Ok(shot) = Shot::aimed(me.id, enemy.pos - me.pos, speed, ctx.config())
                    else {
                        continue;
                    };
                    let mut score = 0.0;
                    for draw in &draws {
                        if let Ok(r) = sim.play_noisy(ctx.me, &shot, *draw) {
                            score += r.lost(ctx.me.opponent()) as f64 - 1.5 * r.lost(ctx.me) as f64;
                        }
                    }
                    if score > best.0 {
                        best = (score, Some(shot));
                    }
                }
            }
        }
        best.1.map_or(Decision::Resign, Decision::Shot)
    }
}

fn main() {
    let mut points = 0.0;
    let games = 6;
    for seed in 0..games {
        let mut mine = Counter {
            rng: SplitMix64::new(seed),
        };
        let mut greedy = bots::Greedy::default();
        let limits = ArenaLimits::default();
        // Alternate the seats.
        let (report, seat) = if seed % 2 == 0 {
            let r = play_match(Config::standard(), seed, &mut mine, &mut greedy, &limits);
            (r, Seat::First)
        } else {
            let r = play_match(Config::standard(), seed, &mut greedy, &mut mine, &limits);
            (r, Seat::Second)
        };
        let report = report.expect("the standard rules are valid");
        println!(
            "game {seed}: {} shots, counter scored {}",
            report.shots,
            report.score(seat)
        );
        points += report.score(seat);
    }
    println!("counter against greedy: {points} / {games}");
}
