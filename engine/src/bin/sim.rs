//! `sim`: computes a scene file to its end and prints the events as JSON.
//!
//! A thin shell over the engine library: read the scene, run a [`World`],
//! print `{events, collisions, pressed, collapses, end, bodies}` (with
//! `--summary`, `events` is their number instead of their list). Exit
//! status 0 on success, 2 on invalid input (the message, naming the object
//! and field, on stderr).
//! The contract is `docs/scene-format.md`.

use clap::Parser;
use engine::world::Counter;
use engine::{BodyId, End, Event, EventHandler, Limits, Scene, World, WorldConfig};
use glam::DVec2;
use serde::Serialize;
use std::io::Read;
use std::process::ExitCode;

/// The event cap when none is given, so a frictionless closed box ends.
const DEFAULT_SIM_MAX_EVENTS: u64 = 1_000_000;

#[derive(Parser, Debug)]
#[command(
    version,
    about = "Compute a scene with the a priori engine and print its events as JSON"
)]
struct Args {
    /// The scene file (JSON), or `-` for standard input.
    scene: String,
    /// Stop at this time (seconds).
    #[arg(long, value_name = "T")]
    until: Option<f64>,
    /// Stop after this many collisions (body-body, body-line, body-point).
    #[arg(long, value_name = "N")]
    max_collisions: Option<u64>,
    /// Stop after this many events (default 1000000, a hard cap).
    #[arg(long, value_name = "N")]
    max_events: Option<u64>,
    /// Print the number of events instead of their list (counts, end and
    /// final state only: for long runs, such as Galperin's billiard at
    /// nine digits, whose list would not fit in memory).
    #[arg(long)]
    summary: bool,
}

/// The events of a run: their list, or with `--summary` their number.
#[derive(Serialize)]
#[serde(untagged)]
enum Events {
    List(Vec<Event>),
    Count(u64),
}

#[derive(Serialize)]
struct Output {
    events: Events,
    collisions: u64,
    /// Hits between discs pressed together obliquely, where the engine
    /// approximates the contact (0: every number is exact to rounding).
    pressed: u64,
    /// Inelastic collapses taken to their limit at once rather than hit by
    /// hit (0: every hit was computed one by one).
    collapses: u64,
    end: End,
    bodies: Vec<BodyOut>,
}

#[derive(Serialize)]
struct BodyOut {
    id: BodyId,
    pos: DVec2,
    vel: DVec2,
}

struct Collect(Vec<Event>);

impl EventHandler for Collect {
    fn on_event(&mut self, _world: &World, event: &Event) {
        self.0.push(*event);
    }
}

fn read_scene(path: &str) -> Result<String, String> {
    if path == "-" {
        let mut text = String::new();
        std::io::stdin()
            .read_to_string(&mut text)
            .map_err(|e| format!("cannot read standard input: {e}"))?;
        Ok(text)
    } else {
        std::fs::read_to_string(path).map_err(|e| format!("cannot read {path}: {e}"))
    }
}

fn run(args: &Args) -> Result<Output, String> {
    if let Some(t) = args.until {
        if t.is_nan() {
            return Err("--until: must be a number".into());
        }
    }
    let text = read_scene(&args.scene)?;
    let scene = Scene::from_json(&text).map_err(|e| e.to_string())?;
    let mut world = World::new(&scene, WorldConfig::default()).map_err(|e| e.to_string())?;
    let limits = Limits {
        until: args.until.unwrap_or(f64::INFINITY),
        max_collisions: args.max_collisions.unwrap_or(u64::MAX),
        max_events: args.max_events.unwrap_or(DEFAULT_SIM_MAX_EVENTS),
    };
    let (end, events) = if args.summary {
        let mut counter = Counter::default();
        let end = world.run(&limits, &mut counter);
        (end, Events::Count(counter.events))
    } else {
        let mut list = Collect(Vec::new());
        let end = world.run(&limits, &mut list);
        (end, Events::List(list.0))
    };
    let mut bodies: Vec<BodyOut> = world
        .bodies()
        .map(|b| BodyOut {
            id: b.id,
            pos: b.trajectory.position(end.t),
            vel: b.trajectory.velocity(end.t),
        })
        .collect();
    bodies.sort_by_key(|b| b.id);
    Ok(Output {
        collisions: world.stats().collisions(),
        pressed: world.stats().pressed,
        collapses: world.stats().collapses,
        events,
        end,
        bodies,
    })
}

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
        Ok(out) => {
            println!(
                "{}",
                serde_json::to_string_pretty(&out).expect("output always serialises")
            );
            ExitCode::SUCCESS
        }
        Err(msg) => {
            eprintln!("sim: {msg}");
            ExitCode::from(2)
        }
    }
}
