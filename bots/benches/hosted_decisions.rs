//! A hosted bot's decisions per second, and what hosting costs: the Rust
//! starter bot (`bots/wasm-starter`) deciding natively, the same code as a
//! WebAssembly module run as the server hosts it (wasmi, fuel metered,
//! a fresh instance per decision), and the AssemblyScript starter
//! (`bots/wasm-starter-as`), each from the same mid-game position. The
//! modules are the built ones:
//!
//! ```sh
//! cargo build -p chapaev-starter-bot --target wasm32-unknown-unknown --release
//! (cd bots/wasm-starter-as && npm ci && npm run build)
//! cargo bench -p bots --bench hosted_decisions
//! ```
//!
//! A module not built is skipped, said out loud. Fuel per decision (the
//! interpreter's count, the same on every machine) is printed beside.
use bots::{Bot, Context, Decision};
use chapaev_bot_sdk::DecideRequest;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use game::{Config, Game, MatchView, NoiseSecret, Phase};
use hosted::{BotModule, DecisionSeed, Limits};
use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

/// A mid-game position: greedy against greedy for a dozen shots (as the
/// simulator bench).
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

/// The module at `path` (from the workspace root), or `None`, said out loud.
fn module(path: &str, build: &str) -> Option<BotModule> {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(path);
    let Ok(bytes) = std::fs::read(&file) else {
        eprintln!("skipped: {path} is not built ({build})");
        return None;
    };
    Some(BotModule::load(&bytes, &Limits::default()).expect("the starter loads"))
}

fn decisions(c: &mut Criterion) {
    let view = mid_game();
    let request = DecideRequest {
        me: view.turn,
        view: view.clone(),
    };
    let secret = NoiseSecret::from_seed(1);
    let seed = DecisionSeed::derive(&secret, &request);
    let mut g = c.benchmark_group("decision");
    g.throughput(Throughput::Elements(1));
    g.bench_function("rust_starter_native", |b| {
        b.iter(|| {
            let mut ctx = chapaev_bot_sdk::Context::new(black_box(request.clone()), 1);
            chapaev_starter_bot::decide(&mut ctx)
        })
    });
    let hosted = [
        (
            "rust_starter_hosted",
            "target/wasm32-unknown-unknown/release/chapaev_starter_bot.wasm",
            "cargo build -p chapaev-starter-bot --target wasm32-unknown-unknown --release",
        ),
        (
            "assemblyscript_starter_hosted",
            "bots/wasm-starter-as/build/starter.wasm",
            "cd bots/wasm-starter-as && npm ci && npm run build",
        ),
    ];
    for (name, path, build) in hosted {
        let Some(module) = module(path, build) else {
            continue;
        };
        let once = module.decide(&request, seed).expect("it decides");
        eprintln!(
            "{name}: {} bytes, {} fuel and {} simulated shots per decision",
            module.size(),
            once.fuel,
            once.shots
        );
        g.bench_function(name, |b| {
            b.iter(|| module.decide(black_box(&request), seed).unwrap())
        });
    }
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20).measurement_time(Duration::from_secs(5));
    targets = decisions
}
criterion_main!(benches);
