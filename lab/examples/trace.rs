//! `trace`: where a hostile scene's events go. Prints the scene's discs,
//! how the time advanced over the run, which pairs the last events hit,
//! how far apart in time, and the discs still moving at the end.
//! `cargo run --release -p lab --example trace -- mixed-box 1168 r12 [TAIL]`
//! (kind, seed, revision, events listed at the end). `TRACE_BODIES=1,5`
//! adds those discs' states after each listed event, `TRACE_FULL=1` prints
//! them in full with their braking, `TRACE_CAP=N` stops the run after N
//! events (to look at the middle of a run).

use engine::{Event, EventHandler, EventKind, Limits, Revision, World, WorldConfig};
use lab::hostile::{Hostile, Kind, MAX_EVENTS};
use std::collections::HashMap;
use std::io::Write as _;
use std::process::ExitCode;

/// Writes a line to `out`, and ends `main` quietly where it cannot (the
/// reader went away, as `head` does).
macro_rules! say {
    ($out:expr, $($arg:tt)*) => {
        if writeln!($out, $($arg)*).is_err() {
            return ExitCode::SUCCESS;
        }
    };
}

/// Every event with the world's totals after it.
struct Trace {
    events: Vec<(Event, u64, u64, f64)>,
    /// Bodies whose state is kept after each event (`TRACE_BODIES=1,5`).
    watch: Vec<u64>,
    /// Their velocities in full, with their braking (`TRACE_FULL=1`).
    full: bool,
    states: Vec<String>,
}

impl EventHandler for Trace {
    fn on_event(&mut self, world: &World, event: &Event) {
        let s = world.stats();
        let fastest = world
            .bodies()
            .map(|b| b.trajectory.velocity(world.last_event_time()).length())
            .fold(0.0, f64::max);
        self.events.push((*event, s.collapses, s.pressed, fastest));
        let t = world.last_event_time();
        let mut line = String::new();
        for b in world.bodies().filter(|b| self.watch.contains(&b.id.0)) {
            let (p, v) = (b.trajectory.position(t), b.trajectory.velocity(t));
            line += &if self.full {
                format!(
                    " [{} p ({:e},{:e}) v ({:e},{:e}) a {:e}]",
                    b.id.0,
                    p.x,
                    p.y,
                    v.x,
                    v.y,
                    b.trajectory.alpha()
                )
            } else {
                format!(
                    " [{} p ({:.12},{:.12}) v ({:.4e},{:.4e})]",
                    b.id.0, p.x, p.y, v.x, v.y
                )
            };
        }
        self.states.push(line);
    }
}

fn name(kind: &EventKind) -> String {
    match *kind {
        EventKind::BodyBody { a, b } => format!("{}-{}", a.0, b.0),
        EventKind::BodyLine { body, line, .. } => format!("{}-L{}", body.0, line.0),
        EventKind::BodyPoint { body, point } => format!("{}-P{}", body.0, point.0),
        EventKind::Stop { body } => format!("{} stop", body.0),
        other => format!("{other:?}"),
    }
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (Some(kind), Some(seed), Some(revision)) = (
        args.first()
            .and_then(|k| Kind::ALL.into_iter().find(|x| x.name() == k)),
        args.get(1).and_then(|s| s.parse::<u64>().ok()),
        args.get(2).and_then(|r| r.parse::<Revision>().ok()),
    ) else {
        eprintln!("usage: trace KIND SEED REVISION [TAIL]");
        return ExitCode::FAILURE;
    };
    let mut out = std::io::stdout().lock();
    let tail: usize = args.get(3).and_then(|t| t.parse().ok()).unwrap_or(40);
    let h = Hostile::generate(kind, seed);
    for b in &h.scene.bodies {
        say!(
            out,
            "disc {:2} r {:.4} m {:.3e} mu {:.3} e {} pos ({:.5},{:.5}) vel ({:.3e},{:.3e})",
            b.id.0,
            b.radius,
            b.mass,
            b.mu,
            b.restitution,
            b.pos.x,
            b.pos.y,
            b.vel.x,
            b.vel.y
        );
    }
    let config = WorldConfig {
        revision,
        ..WorldConfig::default()
    };
    let Ok(mut world) = World::new(&h.scene, config) else {
        say!(out, "refused");
        return ExitCode::FAILURE;
    };
    let limits = Limits {
        until: h.until,
        max_collisions: u64::MAX,
        // `TRACE_CAP=N` stops the run after N events, to look at the
        // middle of a run.
        max_events: std::env::var("TRACE_CAP")
            .ok()
            .and_then(|c| c.parse().ok())
            .unwrap_or(MAX_EVENTS),
    };
    let watch = std::env::var("TRACE_BODIES")
        .unwrap_or_default()
        .split(',')
        .filter_map(|w| w.parse().ok())
        .collect();
    let mut trace = Trace {
        events: Vec::new(),
        watch,
        full: std::env::var("TRACE_FULL").is_ok_and(|f| f == "1"),
        states: Vec::new(),
    };
    let end = world.run(&limits, &mut trace);
    let ev = &trace.events;
    say!(
        out,
        "end {:?} at {:e} after {} events, collapses {}, pressed {}",
        end.reason,
        end.t,
        ev.len(),
        world.stats().collapses,
        world.stats().pressed
    );
    for k in [
        0usize, 1000, 5000, 10_000, 20_000, 40_000, 60_000, 80_000, 99_999,
    ] {
        if let Some((e, c, p, f)) = ev.get(k) {
            say!(
                out,
                "event {k:6}: t {:.15e} collapses {c} pressed {p} fastest {f:.3e}",
                e.t
            );
        }
    }
    // Where the cap's events began: the first of the last 20,000.
    let from = ev.len().saturating_sub(20_000);
    let mut pairs: HashMap<String, usize> = HashMap::new();
    let (mut zero, mut gaps) = (0usize, Vec::new());
    for w in ev[from..].windows(2) {
        *pairs.entry(name(&w[1].0.kind)).or_default() += 1;
        let dt = w[1].0.t - w[0].0.t;
        if dt == 0.0 {
            zero += 1;
        } else {
            gaps.push(dt);
        }
    }
    gaps.sort_by(f64::total_cmp);
    let mut pairs: Vec<_> = pairs.into_iter().collect();
    pairs.sort_by_key(|p| std::cmp::Reverse(p.1));
    say!(
        out,
        "last {} events: span {:e} s, {} at the same time, gaps min {:e} median {:e} max {:e}",
        ev.len() - from,
        ev.last().map_or(0.0, |l| l.0.t) - ev[from].0.t,
        zero,
        gaps.first().copied().unwrap_or(0.0),
        gaps.get(gaps.len() / 2).copied().unwrap_or(0.0),
        gaps.last().copied().unwrap_or(0.0)
    );
    say!(out, "pairs: {:?}", &pairs[..pairs.len().min(12)]);
    for (k, w) in ev
        .windows(2)
        .enumerate()
        .skip(ev.len().saturating_sub(tail + 1))
    {
        say!(
            out,
            "{:6} t {:.17e} dt {:+.3e} {} collapses {} pressed {} fastest {:.3e}",
            k + 1,
            w[1].0.t,
            w[1].0.t - w[0].0.t,
            name(&w[1].0.kind),
            w[1].1,
            w[1].2,
            w[1].3
        );
        if !trace.states[k + 1].is_empty() {
            say!(out, "       {}", trace.states[k + 1]);
        }
    }
    let t = world.last_event_time();
    for b in world.bodies() {
        let v = b.trajectory.velocity(t);
        if v.length() > 0.0 {
            let p = b.trajectory.position(t);
            say!(
                out,
                "moving {:2} pos ({:.9},{:.9}) vel ({:.3e},{:.3e}) |v| {:.3e} alpha {:.3e}",
                b.id.0,
                p.x,
                p.y,
                v.x,
                v.y,
                v.length(),
                b.trajectory.alpha()
            );
        }
    }
    ExitCode::SUCCESS
}
