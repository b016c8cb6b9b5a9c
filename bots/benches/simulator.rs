//! Simulated shots per second on a mid-game board — the figure a bot's
//! search depth rests on — and one decision of `greedy` and `search`. The
//! board is the one reached after 12 shots between two greedy bots under
//! the standard rules; every candidate of the wide spread is simulated as
//! aimed.
use bots::candidates::{candidates, Spread};
use bots::{Bot, Context, Decision, Simulator};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use game::{Config, Game, MatchView, Phase, Side};
use std::hint::black_box;
use std::time::Duration;

/// A mid-game position: greedy against greedy for a dozen shots.
fn mid_game() -> MatchView {
    let mut config = Config::standard();
    config.variants.pie_rule = false;
    let mut game = Game::new(config, 3).unwrap();
    let mut bot = bots::Greedy::default();
    while game.shots() < 12 && game.phase() == Phase::Shooting {
        let side = game.to_shoot().unwrap();
        let view = game.view();
        let Decision::Shot(shot) = bot.decide(&Context::new(&view, side, Duration::from_secs(5)))
        else {
            break;
        };
        game.play(side, shot).unwrap();
    }
    game.view()
}

fn simulate(c: &mut Criterion) {
    let view = mid_game();
    let side = view.turn;
    let shots = candidates(&view.config, &view.board, side, &Spread::wide());
    eprintln!(
        "mid-game board: {} white, {} black, {} candidates",
        view.board.count(Side::White),
        view.board.count(Side::Black),
        shots.len()
    );
    let mut g = c.benchmark_group("simulator");
    g.throughput(Throughput::Elements(shots.len() as u64));
    g.bench_function("mid_game_wide_spread", |b| {
        b.iter(|| {
            let sim = Simulator::new(&view);
            let mut n = 0;
            for s in &shots {
                n += sim
                    .play(side, black_box(s))
                    .map(|r| r.knocked_off.len())
                    .unwrap_or(0);
            }
            n
        })
    });
    g.finish();
}

/// One decision of each scripted bot on the mid-game board (the search
/// uses every core through rayon).
fn decide(c: &mut Criterion) {
    let view = mid_game();
    let mut g = c.benchmark_group("decide");
    g.sample_size(10);
    for name in ["greedy", "search"] {
        g.bench_function(format!("{name}_mid_game"), |b| {
            b.iter(|| {
                let mut bot = bots::by_name(name, 1).unwrap();
                bot.decide(&Context::new(&view, view.turn, Duration::from_secs(10)))
            })
        });
    }
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20).measurement_time(Duration::from_secs(5));
    targets = simulate, decide
}
criterion_main!(benches);
