//! Galperin's billiard: counts the collisions of a small and a big disc and
//! a wall; the count is the first `n` digits of pi.
//!
//! `cargo run --release -p engine --example galperin -- 7`

use engine::world::Counter;
use engine::{presets, Limits, World, WorldConfig};
use std::time::Instant;

fn main() {
    let n: u32 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(7);
    let scene = presets::galperin(n);
    let mut world = World::new(&scene, WorldConfig::default()).expect("a valid scene");
    let mut counter = Counter::default();
    let limits = Limits {
        max_events: u64::MAX,
        ..Limits::default()
    };
    let start = Instant::now();
    let end = world.run(&limits, &mut counter);
    let secs = start.elapsed().as_secs_f64();
    println!(
        "n = {n}: {} collisions ({:?}), {:.1} million events/s",
        counter.collisions,
        end.reason,
        counter.events as f64 / secs / 1e6
    );
}
