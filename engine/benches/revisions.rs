//! What the later revisions cost where nothing was wrong: the break shot
//! (standard and hard) and Galperin's billiard, run under every revision
//! interleaved in one process, timed in CPU time of this thread per run
//! (medians; the machine's wall clock drifts and its CPU is shared).
//! `cargo bench -p engine --bench revisions`.

use cpu_time::ThreadTime;
use engine::world::Counter;
use engine::{BodyId, Limits, Revision, Scene, World, WorldConfig};
use glam::DVec2;
use std::hint::black_box;

const BREAK_JSON: &str = include_str!("../examples/break.json");

fn hard_break(mut scene: Scene) -> Scene {
    if let Some(striker) = scene.bodies.iter_mut().find(|b| b.id == BodyId(4)) {
        striker.vel = (DVec2::new(0.16, 0.30) - striker.pos).normalize() * 5.0;
    }
    scene
}

/// Runs `scene` to its end under `revision`: events and approximated hits.
fn run(scene: &Scene, revision: Revision) -> (u64, u64) {
    let config = WorldConfig {
        revision,
        ..WorldConfig::default()
    };
    let mut world = World::new(scene, config).expect("valid scene");
    let mut counter = Counter::default();
    world.run(&Limits::default(), &mut counter);
    (counter.events, world.stats().pressed)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let break_shot = Scene::from_json(BREAK_JSON).expect("examples/break.json is valid");
    let cases = [
        ("break shot", break_shot.clone(), 2001),
        ("hard break", hard_break(break_shot), 2001),
        ("galperin n5", engine::presets::galperin(5), 21),
    ];
    let unit = |s: f64| {
        if s < 1e-3 {
            format!("{:.1} µs", s * 1e6)
        } else {
            format!("{:.2} ms", s * 1e3)
        }
    };
    let names: Vec<String> = (1..=Revision::ALL.len()).map(|k| format!("r{k}")).collect();
    let ratios: Vec<String> = (1..Revision::ALL.len())
        .map(|k| format!("{} / {}", names[k], names[k - 1]))
        .collect();
    println!(
        "| scene | events {} | pressed {} | CPU per run {} | {} |",
        names.join(" / "),
        names[names.len() - 1],
        names.join(" | "),
        ratios.join(" | ")
    );
    println!(
        "|---|---|---|{}{}",
        "---|".repeat(names.len()),
        "---|".repeat(ratios.len())
    );
    for (name, scene, reps) in cases {
        let outcomes = Revision::ALL.map(|rev| run(&scene, rev));
        let mut t = Revision::ALL.map(|_| Vec::new());
        for _ in 0..reps {
            for (k, rev) in Revision::ALL.into_iter().enumerate() {
                let start = ThreadTime::now();
                black_box(run(black_box(&scene), rev));
                t[k].push(start.elapsed().as_secs_f64());
            }
        }
        let m = t.map(median);
        let events: Vec<String> = outcomes.iter().map(|o| o.0.to_string()).collect();
        let times: Vec<String> = m.iter().map(|&s| unit(s)).collect();
        let ratios: Vec<String> = m
            .windows(2)
            .map(|w| format!("{:.3}", w[1] / w[0]))
            .collect();
        println!(
            "| {name} | {} | {} | {} | {} |",
            events.join(" / "),
            outcomes[Revision::ALL.len() - 1].1,
            times.join(" | "),
            ratios.join(" | ")
        );
    }
}
