//! Performance benchmarks of the event loop (criterion).
//!
//! * `break_shot_16` / `break_shot_16_hard`: a Chapaev break on an 8x8 board
//!   of 4 cm squares (16 discs, board edges are sensors; a disc whose centre
//!   leaves the board is removed, as in the game), from `World::new` to rest.
//! * `galperin_n7` / `galperin_n8`: Galperin's billiard; the collision count
//!   (the digits of pi) is asserted on every iteration.
//! * `galperin/bare_loop_n7`: the same billiard in a hand-written loop with
//!   the engine's formulas and none of its generality (two frictionless
//!   discs on a line and one wall, all three predictions redone after every
//!   event): not the engine, but the speed this machine allows at all, the
//!   yardstick for the engine's own rate.
//! * `galperin/bare_2d_n7`: the same billiard in a hand-written loop in the
//!   plane: positions and velocities as `DVec2`, the engine's contact
//!   quadratic for the pair and its line contact for the wall, the impulse
//!   along the contact normal as the engine forms it (reduced mass, one
//!   division by each mass); still no calendar and no guards. The engine
//!   is two-dimensional, so this is the like-for-like yardstick.
//! * `box_frictionless_{100,10000}`: discs in a closed box at ~10% area
//!   fraction, 20 000 events from a steady state (the world is built and
//!   warmed up once, then cloned per iteration, outside the timing).
//! * `box_friction_{100,10000}`: the same boxes with mu = 0.1, run to rest.
//! * `solver_choice`: the break shot with each root-finding method.
//!
//! Rates are printed as elements/s, where an element is one event. Before
//! criterion's Galperin group, a table times the engine and both bare loops
//! interleaved in CPU time (see [`galperin_cpu_table`]): the figures to
//! compare on a loaded machine.
//! Run with `cargo bench -p engine --bench engine`.

use cpu_time::ThreadTime;
use criterion::{
    black_box, criterion_group, criterion_main, BatchSize, BenchmarkId, Criterion, SamplingMode,
    Throughput,
};
use engine::roots::Method;
use engine::world::{Counter, Stats};
use engine::{
    BodyId, End, EndReason, Event, EventHandler, ExitResponse, Limits, LineId, Scene, World,
    WorldConfig,
};
use glam::DVec2;
use std::time::Duration;

const BREAK_JSON: &str = include_str!("../examples/break.json");

/// Counts events and takes a disc off the board when its centre leaves it
/// (the Chapaev rule).
#[derive(Default)]
struct FallOff(Counter);

impl EventHandler for FallOff {
    #[inline]
    fn on_event(&mut self, world: &World, event: &Event) {
        self.0.on_event(world, event);
    }

    fn on_region_exit(&mut self, _t: f64, _body: BodyId, _line: LineId) -> ExitResponse {
        ExitResponse::Remove
    }
}

/// The standard break: `examples/break.json` (striker at 3 m/s, slightly
/// off the file it stands on, so several pieces are hit).
fn break_scene() -> Scene {
    Scene::from_json(BREAK_JSON).expect("examples/break.json is a valid scene")
}

/// A harder break: the same board, the striker (body 4) aimed at the middle
/// of the opposite row (the gap between bodies 12 and 13) at 5 m/s.
fn hard_break_scene() -> Scene {
    let mut scene = break_scene();
    let striker = scene
        .bodies
        .iter_mut()
        .find(|b| b.id == BodyId(4))
        .expect("body 4 is the striker");
    let target = DVec2::new(0.16, 0.30);
    striker.vel = (target - striker.pos).normalize() * 5.0;
    scene
}

/// Builds the world and runs it to the end.
fn run_break(scene: &Scene, config: WorldConfig) -> (u64, End) {
    let mut world = World::new(scene, config).expect("valid scene");
    let mut handler = FallOff::default();
    let end = world.run(&Limits::default(), &mut handler);
    (handler.0.events, end)
}

fn galperin_scene(n: u32) -> Scene {
    engine::presets::galperin(n)
}

fn run_galperin(scene: &Scene) -> (Counter, Stats) {
    let mut world = World::new(scene, WorldConfig::default()).expect("valid scene");
    let mut counter = Counter::default();
    let limits = Limits {
        max_events: 100_000_000,
        ..Limits::default()
    };
    let end = world.run(&limits, &mut counter);
    assert_ne!(end.reason, EndReason::MaxEvents, "Galperin run hit the cap");
    (counter, *world.stats())
}

/// `n` discs of radius 1 cm with random velocities (|v_x|, |v_y| < 1 m/s) in
/// a closed square box of four segments, area fraction 10%, restitution 1.
fn box_scene(n: usize, mu: f64) -> Scene {
    engine::presets::box_of_discs(n, mu, 1)
}

/// The benchmark groups of this file.
const GROUPS: [&str; 5] = [
    "break_shot_16",
    "galperin",
    "box_frictionless",
    "box_friction",
    "solver_choice",
];

/// Whether the command line's filter (if any) can select `id` (a group, or
/// `group/parameter`), so that the costly set-up of a benchmark (a
/// 31-million-event Galperin run, a box warm-up) is skipped when profiling
/// another one with `--profile-time`.
fn selected(id: &str) -> bool {
    let filters: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-') && a.parse::<f64>().is_err())
        .filter(|a| {
            GROUPS
                .iter()
                .any(|g| a.starts_with(g) || g.contains(a.as_str()))
        })
        .collect();
    filters.is_empty()
        || filters
            .iter()
            .any(|f| f == id || f.starts_with(&format!("{id}/")) || id.contains(f.as_str()))
}

/// Events measured per iteration of the frictionless boxes.
const BOX_EVENTS: u64 = 20_000;

fn limits_events(max_events: u64) -> Limits {
    Limits {
        max_events,
        ..Limits::default()
    }
}

fn break_shot(c: &mut Criterion) {
    if !selected("break_shot_16") {
        return;
    }
    let mut group = c.benchmark_group("break_shot_16");
    for (name, scene) in [("standard", break_scene()), ("hard", hard_break_scene())] {
        let (events, end) = run_break(&scene, WorldConfig::default());
        assert_eq!(
            end.reason,
            EndReason::Rest,
            "{name}: the break must come to rest"
        );
        println!(
            "break_shot_16/{name}: {events} events, rest at t = {:.4} s",
            end.t
        );
        group.throughput(Throughput::Elements(events));
        group.bench_with_input(BenchmarkId::from_parameter(name), &scene, |b, scene| {
            b.iter(|| run_break(black_box(scene), WorldConfig::default()))
        });
    }
    group.finish();
}

fn solver_choice(c: &mut Criterion) {
    if !selected("solver_choice") {
        return;
    }
    let mut group = c.benchmark_group("solver_choice");
    for (name, scene) in [("standard", break_scene()), ("hard", hard_break_scene())] {
        for method in Method::ALL {
            let config = WorldConfig {
                solver: method,
                ..WorldConfig::default()
            };
            let (events, end) = run_break(&scene, config);
            println!(
                "solver_choice/{}/{name}: {events} events, {:?} at t = {:.6} s",
                method.name(),
                end.reason,
                end.t
            );
            group.throughput(Throughput::Elements(events));
            let id = BenchmarkId::new(method.name(), name);
            group.bench_with_input(id, &scene, |b, scene| {
                b.iter(|| run_break(black_box(scene), config))
            });
        }
    }
    group.finish();
}

/// Rounds of the interleaved CPU-time table of [`galperin_cpu_table`], per `n`.
const GALPERIN_ROUNDS: [(u32, usize); 2] = [(7, 9), (8, 3)];

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Galperin's billiard through `World` and in the two bare loops, one after
/// the other round after round in one process, in CPU time of this thread
/// (the hypervisor's steal and the wall clock's drift are not counted): the
/// fair comparison of the rates on a loaded machine. Prints the median
/// round of each, as events per CPU second, and the engine's share of each
/// bare loop's rate (the one-dimensional loop of [`bare_galperin`] and the
/// planar one of [`bare_galperin_2d`]).
fn galperin_cpu_table() {
    let chosen: Vec<_> = GALPERIN_ROUNDS
        .into_iter()
        .filter(|(n, _)| selected(&format!("galperin/n{n}")))
        .collect();
    if chosen.is_empty() {
        return;
    }
    println!("Galperin: events per CPU second, median of interleaved rounds");
    println!("| n | rounds | engine | bare 1-D | bare 2-D | engine / 1-D | engine / 2-D |");
    println!("|---|---:|---:|---:|---:|---:|---:|");
    for (n, rounds) in chosen {
        let scene = galperin_scene(n);
        let digits = engine::presets::pi_digits(n);
        let (mut engine, mut bare, mut plane) = (Vec::new(), Vec::new(), Vec::new());
        for _ in 0..rounds {
            let start = ThreadTime::now();
            let (counter, _) = run_galperin(black_box(&scene));
            engine.push(counter.events as f64 / start.elapsed().as_secs_f64());
            assert_eq!(counter.collisions, digits);
            let start = ThreadTime::now();
            let events = bare_galperin(black_box(n));
            bare.push(events as f64 / start.elapsed().as_secs_f64());
            assert_eq!(events, digits);
            let start = ThreadTime::now();
            let events = bare_galperin_2d(black_box(n));
            plane.push(events as f64 / start.elapsed().as_secs_f64());
            assert_eq!(events, digits);
        }
        let (e, b, p) = (median(engine), median(bare), median(plane));
        println!(
            "| {n} | {rounds} | {:.2} M/s | {:.2} M/s | {:.2} M/s | {:.0} % | {:.0} % |",
            e * 1e-6,
            b * 1e-6,
            p * 1e-6,
            100.0 * e / b,
            100.0 * e / p
        );
    }
}

fn galperin(c: &mut Criterion) {
    if !selected("galperin") {
        return;
    }
    galperin_cpu_table();
    let mut group = c.benchmark_group("galperin");
    group.sample_size(10).sampling_mode(SamplingMode::Flat);
    for (n, digits) in [(7u32, 3_141_592u64), (8, 31_415_926)] {
        if !selected(&format!("galperin/n{n}")) {
            continue;
        }
        let scene = galperin_scene(n);
        let (counter, stats) = run_galperin(&scene);
        assert_eq!(counter.collisions, digits, "Galperin n = {n}");
        println!(
            "galperin_n{n}: {} collisions, {} events; {stats:?}",
            counter.collisions, counter.events
        );
        group.throughput(Throughput::Elements(counter.events));
        group.bench_with_input(
            BenchmarkId::from_parameter(format!("n{n}")),
            &scene,
            |b, scene| {
                b.iter(|| {
                    let (counter, _) = run_galperin(black_box(scene));
                    assert_eq!(counter.collisions, digits, "Galperin n = {n}");
                    counter
                })
            },
        );
    }
    if selected("galperin/bare_loop_n7") {
        assert_eq!(bare_galperin(7), 3_141_592, "bare loop, n = 7");
        group.throughput(Throughput::Elements(3_141_592));
        group.bench_function("bare_loop_n7", |b| b.iter(|| bare_galperin(black_box(7))));
    }
    if selected("galperin/bare_2d_n7") {
        assert_eq!(bare_galperin_2d(7), 3_141_592, "planar bare loop, n = 7");
        group.throughput(Throughput::Elements(3_141_592));
        group.bench_function("bare_2d_n7", |b| b.iter(|| bare_galperin_2d(black_box(7))));
    }
    group.finish();
}

/// A disc on the x axis for [`bare_galperin`]: position and velocity at `t0`.
#[derive(Clone, Copy)]
struct BareDisc {
    t0: f64,
    x: f64,
    v: f64,
    r: f64,
    m: f64,
}

impl BareDisc {
    fn x_at(&self, t: f64) -> f64 {
        self.x + self.v * (t - self.t0)
    }
}

/// Galperin's billiard (the preset's scene) in the leanest possible loop:
/// the pair's contact from the same stable quadratic root as the engine
/// (a square root and a division), the wall's from one division, the
/// impulse from the mass shares. Returns the number of collisions.
fn bare_galperin(n: u32) -> u64 {
    let big = (1..n).fold(1.0, |m, _| m * 100.0);
    let mut small = BareDisc {
        t0: 0.0,
        x: 1.0,
        v: 0.0,
        r: 0.1,
        m: 1.0,
    };
    let mut heavy = BareDisc {
        t0: 0.0,
        x: 3.0,
        v: -1.0,
        r: 0.5,
        m: big,
    };
    let (mut now, mut events) = (0.0, 0u64);
    loop {
        let pair = {
            let (dp, dv) = (small.x_at(now) - heavy.x_at(now), small.v - heavy.v);
            let (b, s) = (dp * dv, small.r + heavy.r);
            let (a, c) = (dv * dv, dp * dp - s * s);
            let disc = b * b - a * c;
            if b >= 0.0 || disc <= 0.0 {
                f64::INFINITY
            } else {
                now + c / (-b + disc.sqrt())
            }
        };
        let wall = |d: &BareDisc| {
            if d.v >= 0.0 {
                f64::INFINITY
            } else {
                now + (d.x_at(now) - d.r) / -d.v
            }
        };
        let (ws, wh) = (wall(&small), wall(&heavy));
        let t = pair.min(ws).min(wh);
        if t == f64::INFINITY {
            return events;
        }
        now = t;
        events += 1;
        if t == pair {
            let q = small.m / (small.m + heavy.m);
            let k = -2.0 * (small.v - heavy.v);
            small = BareDisc {
                t0: t,
                x: small.x_at(t),
                v: small.v + k * (1.0 - q),
                ..small
            };
            heavy = BareDisc {
                t0: t,
                x: heavy.x_at(t),
                v: heavy.v - k * q,
                ..heavy
            };
        } else if t == ws {
            small = BareDisc {
                t0: t,
                x: small.x_at(t),
                v: -small.v,
                ..small
            };
        } else {
            heavy = BareDisc {
                t0: t,
                x: heavy.x_at(t),
                v: -heavy.v,
                ..heavy
            };
        }
    }
}

/// A disc in the plane for [`bare_galperin_2d`]: position and velocity at
/// `t0`.
#[derive(Clone, Copy)]
struct PlaneDisc {
    t0: f64,
    p: DVec2,
    v: DVec2,
    r: f64,
    m: f64,
}

impl PlaneDisc {
    fn at(&self, t: f64) -> DVec2 {
        self.p + self.v * (t - self.t0)
    }

    /// Moving on from `t` with velocity `v`.
    fn moved(&self, t: f64, v: DVec2) -> PlaneDisc {
        PlaneDisc {
            t0: t,
            p: self.at(t),
            v,
            ..*self
        }
    }
}

/// Galperin's billiard (the preset's scene) in a bare loop in the plane,
/// with the engine's formulas: the pair's contact from the quadratic
/// `|dp + dv l|^2 = s^2` and its stable root (a square root and a
/// division), the wall as a line `n . p + c = 0` (signed distance, rate of
/// approach, one division), the hit's impulse along the unit contact normal
/// (a square root and a division) with the reduced mass formed as
/// `impulse::reduced_mass` does and one division by each mass, the bounce
/// mirroring the normal part. All three predictions are redone after every
/// event; no calendar, no guards. Returns the number of collisions.
fn bare_galperin_2d(n: u32) -> u64 {
    let big = (1..n).fold(1.0, |m, _| m * 100.0);
    let mut small = PlaneDisc {
        t0: 0.0,
        p: DVec2::new(1.0, 0.0),
        v: DVec2::ZERO,
        r: 0.1,
        m: 1.0,
    };
    let mut heavy = PlaneDisc {
        t0: 0.0,
        p: DVec2::new(3.0, 0.0),
        v: DVec2::new(-1.0, 0.0),
        r: 0.5,
        m: big,
    };
    // The wall: the line through (0, -1) and (0, 1), its unit normal and
    // offset as `LineGeom` holds them.
    let (wall_n, wall_c) = (DVec2::new(1.0, 0.0), 0.0);
    let (mut now, mut events) = (0.0, 0u64);
    loop {
        let pair = {
            let dp = small.at(now) - heavy.at(now);
            let dv = small.v - heavy.v;
            let s = small.r + heavy.r;
            let b = dp.dot(dv);
            let (a, c) = (dv.length_squared(), dp.length_squared() - s * s);
            let disc = b * b - a * c;
            if b >= 0.0 || disc <= 0.0 {
                f64::INFINITY
            } else {
                now + c / (-b + disc.sqrt())
            }
        };
        let wall = |d: &PlaneDisc| {
            let h = wall_n.dot(d.at(now)) + wall_c;
            let rate = wall_n.dot(d.v);
            if rate >= 0.0 {
                f64::INFINITY
            } else {
                now + (h - d.r) / -rate
            }
        };
        let (ws, wh) = (wall(&small), wall(&heavy));
        let t = pair.min(ws).min(wh);
        if t == f64::INFINITY {
            return events;
        }
        now = t;
        events += 1;
        if t == pair {
            let (ps, ph) = (small.at(t), heavy.at(t));
            let normal = (ps - ph).normalize();
            let w = (small.v - heavy.v).dot(normal);
            let (light, weighty) = if small.m <= heavy.m {
                (small.m, heavy.m)
            } else {
                (heavy.m, small.m)
            };
            let reduced = light - light * (light / (light + weighty));
            let j = -2.0 * w * reduced;
            let (vs, vh) = (
                small.v + normal * (j / small.m),
                heavy.v - normal * (j / heavy.m),
            );
            small = small.moved(t, vs);
            heavy = heavy.moved(t, vh);
        } else {
            let d = if t == ws { &mut small } else { &mut heavy };
            let v = d.v - wall_n * (2.0 * wall_n.dot(d.v));
            *d = d.moved(t, v);
        }
    }
}

fn box_frictionless(c: &mut Criterion) {
    if !selected("box_frictionless") {
        return;
    }
    let mut group = c.benchmark_group("box_frictionless");
    for n in [100usize, 10_000] {
        if !selected(&format!("box_frictionless/{n}")) {
            continue;
        }
        let mut world = World::new(&box_scene(n, 0.0), WorldConfig::default()).expect("valid");
        let warm_up = (5 * n as u64).max(5_000);
        let end = world.run(&limits_events(warm_up), &mut Counter::default());
        assert_eq!(end.reason, EndReason::MaxEvents);
        let mut probe = world.clone();
        let before = *probe.stats();
        probe.run(&limits_events(BOX_EVENTS), &mut Counter::default());
        let after = probe.stats();
        println!(
            "box_frictionless/{n}: per {BOX_EVENTS} events: {} stale, {} cell crossings",
            after.stale - before.stale,
            after.cell_crossings - before.cell_crossings
        );
        group.throughput(Throughput::Elements(BOX_EVENTS));
        group.bench_with_input(BenchmarkId::from_parameter(n), &world, |b, world| {
            b.iter_batched(
                || world.clone(),
                |mut w| {
                    let mut counter = Counter::default();
                    w.run(&limits_events(BOX_EVENTS), &mut counter);
                    assert_eq!(counter.events, BOX_EVENTS);
                    w
                },
                BatchSize::LargeInput,
            )
        });
    }
    group.finish();
}

fn box_friction(c: &mut Criterion) {
    if !selected("box_friction") {
        return;
    }
    let mut group = c.benchmark_group("box_friction");
    group.sample_size(10);
    for n in [100usize, 10_000] {
        if !selected(&format!("box_friction/{n}")) {
            continue;
        }
        let world = World::new(&box_scene(n, 0.1), WorldConfig::default()).expect("valid");
        let cap = 2_000_000;
        let mut counter = Counter::default();
        let mut probe = world.clone();
        let end = probe.run(&limits_events(cap), &mut counter);
        println!(
            "box_friction/{n}: {} events ({} collisions), {:?} at t = {:.4} s; {:?}",
            counter.events,
            counter.collisions,
            end.reason,
            end.t,
            probe.stats()
        );
        group.throughput(Throughput::Elements(counter.events));
        group.bench_with_input(BenchmarkId::from_parameter(n), &world, |b, world| {
            b.iter_batched(
                || world.clone(),
                |mut w| {
                    w.run(&limits_events(cap), &mut Counter::default());
                    w
                },
                BatchSize::LargeInput,
            )
        });
    }
    group.finish();
}

fn config() -> Criterion {
    Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3))
}

criterion_group! {
    name = benches;
    config = config();
    targets = break_shot, galperin, box_frictionless, box_friction, solver_choice
}
criterion_main!(benches);
