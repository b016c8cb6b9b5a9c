//! Named physical scenarios, each checked against a closed-form answer
//! (never against the engine's own earlier output).
//!
//! The formulas are those of `docs/model.md`: a disc slides with
//! constant deceleration `alpha = mu g`, so from speed `v` it stops after
//! `v^2 / (2 alpha)` at time `v / alpha`, and after a path `L` it has speed
//! `sqrt(v^2 - 2 alpha L)`; impulses follow formulas (25) and (28).

use engine::model::{Action, ActionError, Snapshot};
use engine::rng::Rng;
use engine::world::{BodyState, BroadPhase, Counter};
use engine::{
    BodyId, BodySpec, End, EndReason, Event, EventHandler, EventKind, ExitResponse, Limits, Line,
    LineId, LineKind, Model, Point, Revision, Scene, World, WorldConfig,
};
use glam::DVec2;
use std::collections::HashMap;
use std::process::{Command, Stdio};

// ---------------------------------------------------------------------------
// Helpers
// ---------------------------------------------------------------------------

fn v(x: f64, y: f64) -> DVec2 {
    DVec2::new(x, y)
}

fn disc(id: u64, pos: DVec2, vel: DVec2, radius: f64, mass: f64, mu: f64) -> BodySpec {
    BodySpec::new(id, pos, radius, mass, mu).with_velocity(vel)
}

fn scene(g: f64, bodies: Vec<BodySpec>, lines: Vec<Line>, points: Vec<Point>) -> Scene {
    Scene {
        g,
        t: 0.0,
        bodies,
        points,
        lines,
    }
}

/// `|actual - expected| <= tol * (1 + |expected|)`: relative for large
/// values, absolute for values near zero.
#[track_caller]
fn assert_close(actual: f64, expected: f64, tol: f64, what: &str) {
    assert!(
        actual.is_finite() && (actual - expected).abs() <= tol * (1.0 + expected.abs()),
        "{what}: got {actual:e}, expected {expected:e} (diff {:e}, tol {tol:e})",
        (actual - expected).abs()
    );
}

#[track_caller]
fn assert_vec_close(actual: DVec2, expected: DVec2, tol: f64, what: &str) {
    assert_close(actual.x, expected.x, tol, &format!("{what}.x"));
    assert_close(actual.y, expected.y, tol, &format!("{what}.y"));
}

/// Records every event and the state of every body right after it.
#[derive(Default)]
struct Trace {
    events: Vec<Event>,
    after: Vec<HashMap<BodyId, BodySpec>>,
}

impl EventHandler for Trace {
    fn on_event(&mut self, world: &World, event: &Event) {
        self.events.push(*event);
        self.after.push(
            world
                .scene_at(event.t)
                .bodies
                .into_iter()
                .map(|b| (b.id, b))
                .collect(),
        );
    }
}

/// Only the events.
#[derive(Default)]
struct Log(Vec<Event>);

impl EventHandler for Log {
    fn on_event(&mut self, _world: &World, event: &Event) {
        self.0.push(*event);
    }
}

fn run_traced(scene: &Scene, limits: Limits) -> (Trace, End, World) {
    let mut world = World::new(scene, WorldConfig::default()).expect("valid scene");
    let mut trace = Trace::default();
    let end = world.run(&limits, &mut trace);
    (trace, end, world)
}

fn state(world: &World, id: u64, t: f64) -> (DVec2, DVec2) {
    let b = world.body(BodyId(id)).expect("body in the scene");
    (b.trajectory.position(t), b.trajectory.velocity(t))
}

fn is_pair(kind: &EventKind, x: u64, y: u64) -> bool {
    matches!(*kind, EventKind::BodyBody { a, b }
        if (a, b) == (BodyId(x), BodyId(y)) || (a, b) == (BodyId(y), BodyId(x)))
}

fn collisions(events: &[Event]) -> usize {
    events.iter().filter(|e| e.kind.is_collision()).count()
}

/// The minimum over all pairs of `distance / (R_i + R_j)` in a scene.
fn min_pair_ratio(scene: &Scene) -> f64 {
    let mut worst = f64::INFINITY;
    for (i, a) in scene.bodies.iter().enumerate() {
        for b in &scene.bodies[i + 1..] {
            worst = worst.min((a.pos - b.pos).length() / (a.radius + b.radius));
        }
    }
    worst
}

/// The square box `[lo, hi]^2` of four solid segments.
fn square(lo: f64, hi: f64) -> Vec<Line> {
    let c = [v(lo, lo), v(hi, lo), v(hi, hi), v(lo, hi)];
    (0..4)
        .map(|k| Line::new(c[k], c[(k + 1) % 4], LineKind::Segment))
        .collect()
}

/// A small deterministic generator (xorshift64*), so scenes are fixed.
/// `n` discs on a lattice inside the box `[0, 1]^2`, random velocities.
fn lattice_scene(n: usize, seed: u64, mu: f64, restitution: f64, speed: f64) -> Scene {
    let mut rng = Rng::xorshift64_star(seed);
    let side = (n as f64).sqrt().ceil() as usize;
    let cell = 1.0 / side as f64;
    let bodies = (0..n)
        .map(|k| {
            let (cx, cy) = ((k % side) as f64, (k / side) as f64);
            let r = cell * rng.range(0.15, 0.3);
            let pos = v((cx + 0.5) * cell, (cy + 0.5) * cell);
            let vel = v(rng.range(-speed, speed), rng.range(-speed, speed));
            disc(k as u64, pos, vel, r, rng.range(0.5, 2.0), mu).with_restitution(restitution)
        })
        .collect();
    scene(9.81, bodies, square(0.0, 1.0), vec![])
}

fn example(name: &str) -> String {
    format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

// ---------------------------------------------------------------------------
// Sliding and stopping
// ---------------------------------------------------------------------------

#[test]
fn sliding_disc_stops_after_v_squared_over_two_mu_g_at_time_v_over_mu_g() {
    let (mu, g) = (0.3, 9.81);
    let p0 = v(0.25, 0.5);
    let u = v(1.2, -1.6); // speed 2, direction (0.6, -0.8)
    let speed = 2.0;
    let sc = scene(g, vec![disc(7, p0, u, 0.016, 0.01, mu)], vec![], vec![]);
    let (trace, end, world) = run_traced(&sc, Limits::default());

    let t_stop = speed / (mu * g);
    let d_stop = speed * speed / (2.0 * mu * g);
    assert_eq!(trace.events.len(), 1, "{:?}", trace.events);
    assert_eq!(trace.events[0].kind, EventKind::Stop { body: BodyId(7) });
    assert_close(trace.events[0].t, t_stop, 1e-14, "stop time");
    assert_eq!(end.reason, EndReason::Rest);
    assert_close(end.t, t_stop, 1e-14, "end time");

    let expected = p0 + v(0.6, -0.8) * d_stop;
    let (p, vel) = state(&world, 7, end.t);
    assert_vec_close(p, expected, 1e-14, "final position");
    assert_eq!(vel, DVec2::ZERO);
    // It stays there.
    let (p_late, vel_late) = state(&world, 7, end.t + 100.0);
    assert_eq!((p_late, vel_late), (p, DVec2::ZERO));
}

#[test]
fn model_scene_at_any_time_follows_the_sliding_formula() {
    let (mu, g, speed) = (0.25, 9.81, 3.0);
    let alpha = mu * g;
    let dir = v(0.8, 0.6);
    let p0 = v(-1.0, 2.0);
    let sc = scene(
        g,
        vec![disc(1, p0, dir * speed, 0.1, 1.0, mu)],
        vec![],
        vec![],
    );
    let mut model = Model::new(sc).unwrap();
    model.compute(&Limits::default());
    let t_stop = speed / alpha;
    // Deliberately out of order: queries are independent of each other.
    for &t in &[
        0.7,
        0.0,
        1.1,
        0.05,
        t_stop * 0.999,
        0.3,
        t_stop,
        t_stop + 5.0,
        0.9,
    ] {
        let s = t.min(t_stop);
        let expected_p = p0 + dir * (speed * s - 0.5 * alpha * s * s);
        let expected_v = dir * (speed - alpha * s);
        let b = model.scene_at(t).bodies[0];
        assert_vec_close(b.pos, expected_p, 1e-14, &format!("pos at {t}"));
        assert_vec_close(b.vel, expected_v, 1e-14, &format!("vel at {t}"));
    }
}

// ---------------------------------------------------------------------------
// Disc-disc impulses
// ---------------------------------------------------------------------------

#[test]
fn head_on_equal_masses_striker_stops_and_target_leaves_with_the_contact_speed() {
    let (mu, g, v0, r, m, d): (f64, f64, f64, f64, f64, f64) = (0.2, 9.81, 2.0, 0.016, 0.01, 0.5);
    let alpha = mu * g;
    let gap = d - 2.0 * r;
    let vc = (v0 * v0 - 2.0 * alpha * gap).sqrt();
    let tc = (v0 - vc) / alpha;
    let t_stop = tc + vc / alpha;
    let sc = scene(
        g,
        vec![
            disc(1, v(0.0, 0.0), v(v0, 0.0), r, m, mu),
            disc(2, v(d, 0.0), DVec2::ZERO, r, m, mu),
        ],
        vec![],
        vec![],
    );
    let (trace, end, world) = run_traced(&sc, Limits::default());
    assert_eq!(trace.events.len(), 2, "{:?}", trace.events);
    assert!(
        is_pair(&trace.events[0].kind, 1, 2),
        "{:?}",
        trace.events[0]
    );
    assert_close(trace.events[0].t, tc, 1e-13, "contact time");
    let after = &trace.after[0];
    assert_vec_close(
        after[&BodyId(1)].pos,
        v(gap, 0.0),
        1e-13,
        "striker at contact",
    );
    assert!(
        after[&BodyId(1)].vel.length() <= 1e-13,
        "striker must stop: {:?}",
        after[&BodyId(1)].vel
    );
    assert_vec_close(after[&BodyId(2)].vel, v(vc, 0.0), 1e-13, "target velocity");

    assert_eq!(trace.events[1].kind, EventKind::Stop { body: BodyId(2) });
    assert_close(trace.events[1].t, t_stop, 1e-13, "target stop time");
    assert_eq!(end.reason, EndReason::Rest);
    let (p2, v2) = state(&world, 2, end.t);
    assert_vec_close(
        p2,
        v(d + vc * vc / (2.0 * alpha), 0.0),
        1e-13,
        "target final position",
    );
    assert_eq!(v2, DVec2::ZERO);
    let (p1, _) = state(&world, 1, end.t);
    assert_vec_close(p1, v(gap, 0.0), 1e-13, "striker final position");
}

#[test]
fn glancing_elastic_hit_of_equal_masses_separates_at_right_angles() {
    // Striker along y = 0, target centred 0.3 above the path, R + R = 0.5:
    // contact when the striker has travelled 0.6, normal (-0.8, -0.6).
    let (mu, g, v0, r): (f64, f64, f64, f64) = (0.1, 9.81, 2.0, 0.25);
    let alpha = mu * g;
    let vc = (v0 * v0 - 2.0 * alpha * 0.6).sqrt();
    let tc = (v0 - vc) / alpha;
    let sc = scene(
        g,
        vec![
            disc(1, v(0.0, 0.0), v(v0, 0.0), r, 0.5, mu),
            disc(2, v(1.0, 0.3), DVec2::ZERO, r, 0.5, mu),
        ],
        vec![],
        vec![],
    );
    let (trace, end, world) = run_traced(&sc, Limits::default());
    assert!(is_pair(&trace.events[0].kind, 1, 2), "{:?}", trace.events);
    assert_close(trace.events[0].t, tc, 1e-13, "contact time");
    let (v1, v2) = (
        trace.after[0][&BodyId(1)].vel,
        trace.after[0][&BodyId(2)].vel,
    );
    assert!(
        v1.dot(v2).abs() <= 1e-13 * vc * vc,
        "not at right angles: {v1} {v2}"
    );
    assert_vec_close(v1, v(0.36, -0.48) * vc, 1e-13, "striker velocity");
    assert_vec_close(v2, v(0.64, 0.48) * vc, 1e-13, "target velocity");
    assert_close(
        v1.length_squared() + v2.length_squared(),
        vc * vc,
        1e-13,
        "energy",
    );

    // Each then slides straight to rest; no further contact.
    assert_eq!(collisions(&trace.events), 1, "{:?}", trace.events);
    assert_eq!(end.reason, EndReason::Rest);
    let s1 = v1.length_squared() / (2.0 * alpha);
    let s2 = v2.length_squared() / (2.0 * alpha);
    assert_vec_close(
        state(&world, 1, end.t).0,
        v(0.6, 0.0) + v(0.6, -0.8) * s1,
        1e-12,
        "striker rest",
    );
    assert_vec_close(
        state(&world, 2, end.t).0,
        v(1.0, 0.3) + v(0.8, 0.6) * s2,
        1e-12,
        "target rest",
    );
}

#[test]
fn restitution_scales_the_relative_normal_speed_of_two_discs() {
    // Masses 1 and 3, e = min(0.6, 0.9) = 0.6, frictionless, head on at 2:
    // v1' = (2 - 3 * 0.6 * 2) / 4 = -0.4, v2' = (2 + 0.6 * 2) / 4 = 0.8.
    let sc = scene(
        9.81,
        vec![
            disc(1, v(0.0, 0.0), v(2.0, 0.0), 0.1, 1.0, 0.0).with_restitution(0.6),
            disc(2, v(1.0, 0.0), DVec2::ZERO, 0.1, 3.0, 0.0).with_restitution(0.9),
        ],
        vec![],
        vec![],
    );
    let (trace, end, _) = run_traced(&sc, Limits::default());
    assert_eq!(trace.events.len(), 1, "{:?}", trace.events);
    assert_close(trace.events[0].t, 0.4, 1e-15, "contact time");
    assert_vec_close(trace.after[0][&BodyId(1)].vel, v(-0.4, 0.0), 1e-15, "v1");
    assert_vec_close(trace.after[0][&BodyId(2)].vel, v(0.8, 0.0), 1e-15, "v2");
    assert_eq!(end.reason, EndReason::Free);
}

// ---------------------------------------------------------------------------
// Walls
// ---------------------------------------------------------------------------

/// A disc of radius 0.2 from the origin with velocity `u` (a multiple of
/// (2, 1)) against the wall x + y = 3 given as `kind`; returns the velocity
/// after the bounce and the bounce time.
fn tilted_wall_bounce(kind: LineKind, mu: f64, e: f64) -> (DVec2, f64, Vec<Event>) {
    let (out, t, events) = tilted_wall_bounce_unchecked(kind, mu, e);
    assert_eq!(collisions(&events), 1, "{events:?}");
    (out, t, events)
}

/// The frictionless bounce with restitution `e`, however many events follow.
fn tilted_wall_bounce_events(kind: LineKind, e: f64) -> (DVec2, f64, Vec<Event>) {
    tilted_wall_bounce_unchecked(kind, 0.0, e)
}

fn tilted_wall_bounce_unchecked(kind: LineKind, mu: f64, e: f64) -> (DVec2, f64, Vec<Event>) {
    let g = 9.81;
    let u = v(2.0, 1.0);
    let wall = Line::new(v(3.0, 0.0), v(0.0, 3.0), kind);
    let sc = scene(
        g,
        vec![disc(1, DVec2::ZERO, u, 0.2, 1.0, mu).with_restitution(e)],
        vec![wall],
        vec![],
    );
    let (trace, _, _) = run_traced(&sc, Limits::default());
    let hit = trace
        .events
        .iter()
        .position(|e| e.kind.is_collision())
        .expect("the disc must hit the wall");
    assert_eq!(
        trace.events[hit].kind,
        EventKind::BodyLine {
            body: BodyId(1),
            line: LineId(0),
            end: None
        }
    );
    (
        trace.after[hit][&BodyId(1)].vel,
        trace.events[hit].t,
        trace.events,
    )
}

#[test]
fn wall_reflection_angle_in_equals_angle_out_for_line_ray_and_segment() {
    // Contact when (x + y - 3) / sqrt 2 = -0.2 along (2t, t): t = (3 - 0.2 sqrt 2) / 3.
    let n = v(-1.0, -1.0) / 2f64.sqrt();
    let tan = v(-1.0, 1.0) / 2f64.sqrt();
    let u = v(2.0, 1.0);
    let tc = (3.0 - 0.2 * 2f64.sqrt()) / 3.0;
    for kind in [LineKind::Line, LineKind::Ray, LineKind::Segment] {
        let (out, t, _) = tilted_wall_bounce(kind, 0.0, 1.0);
        assert_close(t, tc, 1e-15, &format!("{kind:?} contact time"));
        assert_vec_close(
            out,
            v(-1.0, -2.0),
            1e-14,
            &format!("{kind:?} reflected velocity"),
        );
        assert_close(out.dot(tan), u.dot(tan), 1e-14, "tangential speed kept");
        assert_close(out.dot(n), -u.dot(n), 1e-14, "normal speed reversed");
    }
}

#[test]
fn wall_reflection_with_friction_uses_the_speed_at_contact() {
    let (mu, g) = (0.1, 9.81);
    let alpha = mu * g;
    let u = v(2.0, 1.0);
    let path = u.length() * (3.0 - 0.2 * 2f64.sqrt()) / 3.0;
    let vc = (u.length_squared() - 2.0 * alpha * path).sqrt();
    let tc = (u.length() - vc) / alpha;
    for kind in [LineKind::Line, LineKind::Ray, LineKind::Segment] {
        let (out, t, events) = tilted_wall_bounce(kind, mu, 1.0);
        assert_close(t, tc, 1e-14, &format!("{kind:?} contact time"));
        assert_vec_close(
            out,
            v(-1.0, -2.0) * (vc / u.length()),
            1e-14,
            &format!("{kind:?} velocity"),
        );
        assert_eq!(
            events.last().unwrap().kind,
            EventKind::Stop { body: BodyId(1) }
        );
    }
}

#[test]
fn wall_restitution_below_one_scales_only_the_normal_speed() {
    let n = v(-1.0, -1.0) / 2f64.sqrt();
    let tan = v(-1.0, 1.0) / 2f64.sqrt();
    let u = v(2.0, 1.0);
    // (With e = 0 on a ray or segment the disc then slides along the wall
    // and off its end: see the sliding tests.)
    for (e, kinds) in [
        (0.0, &[LineKind::Line][..]),
        (0.5, &[LineKind::Line, LineKind::Ray, LineKind::Segment][..]),
        (0.9, &[LineKind::Line, LineKind::Ray, LineKind::Segment][..]),
    ] {
        for &kind in kinds {
            let (out, _, _) = tilted_wall_bounce(kind, 0.0, e);
            assert_close(
                out.dot(tan),
                u.dot(tan),
                1e-14,
                &format!("e={e} tangential"),
            );
            assert_close(out.dot(n), -e * u.dot(n), 1e-14, &format!("e={e} normal"));
        }
    }
}

// ---------------------------------------------------------------------------
// Galperin's billiard: the number of collisions spells pi
// ---------------------------------------------------------------------------

fn galperin(digits: i32) -> (u64, End) {
    galperin_from(digits, 0.0, Revision::LATEST)
}

/// Galperin's billiard for `digits` digits begun at time `t`, computed
/// under `revision`.
fn galperin_from(digits: i32, t: f64, revision: Revision) -> (u64, End) {
    let big = 100f64.powi(digits - 1);
    let mut sc = scene(
        9.81,
        vec![
            disc(1, v(1.0, 0.0), DVec2::ZERO, 0.1, 1.0, 0.0),
            disc(2, v(3.0, 0.0), v(-1.0, 0.0), 0.5, big, 0.0),
        ],
        vec![Line::new(v(0.0, -1.0), v(0.0, 1.0), LineKind::Line)],
        vec![],
    );
    sc.t = t;
    let config = WorldConfig {
        revision,
        ..WorldConfig::default()
    };
    let mut world = World::new(&sc, config).unwrap();
    let mut counter = Counter::default();
    let limits = Limits {
        max_events: 10_000_000_000,
        ..Limits::default()
    };
    let end = world.run(&limits, &mut counter);
    assert_eq!(counter.events, counter.collisions, "only collisions happen");
    (counter.collisions, end)
}

macro_rules! galperin_test {
    ($name:ident, $digits:expr, $count:expr $(, $ignore:meta)?) => {
        #[test]
        $(#[$ignore])?
        fn $name() {
            let (count, end) = galperin($digits);
            assert_eq!(count, $count, "collisions with mass ratio 100^{}", $digits - 1);
            assert_eq!(end.reason, EndReason::Free);
        }
    };
}

galperin_test!(galperin_billiard_mass_ratio_1_makes_3_collisions, 1, 3);
galperin_test!(galperin_billiard_mass_ratio_100_makes_31_collisions, 2, 31);
galperin_test!(
    galperin_billiard_mass_ratio_1e4_makes_314_collisions,
    3,
    314
);
galperin_test!(
    galperin_billiard_mass_ratio_1e6_makes_3141_collisions,
    4,
    3141
);
galperin_test!(
    galperin_billiard_mass_ratio_1e8_makes_31415_collisions,
    5,
    31415
);
galperin_test!(
    galperin_billiard_mass_ratio_1e10_makes_314159_collisions,
    6,
    314159
);
galperin_test!(
    galperin_billiard_mass_ratio_1e12_makes_3141592_collisions,
    7,
    3141592
);
galperin_test!(
    galperin_billiard_mass_ratio_1e14_makes_31415926_collisions,
    8,
    31415926,
    ignore = "slow: 31 million events, about 5 s with --release"
);
galperin_test!(
    galperin_billiard_mass_ratio_1e16_makes_314159265_collisions,
    9,
    314159265,
    ignore = "slow: 314 million events, about 30 s of CPU with --release"
);
galperin_test!(
    galperin_billiard_mass_ratio_1e18_makes_3141592653_collisions,
    10,
    3141592653,
    ignore = "slow: 3.1 billion events, about 4.5 min of CPU with --release"
);

/// Begun at t = 1e9 s, where an f64 time resolves 1.2e-7 s, Galperin's
/// billiard at five digits hits about 2e-8 s apart near its end: as at
/// nine digits from t = 0, its hits share one number of time. The fine clock
/// of the seventh revision tells them apart and counts exactly; the sixth
/// revision cannot.
#[test]
fn galperin_billiard_counts_exactly_where_its_hits_are_closer_than_the_rounding_of_the_time() {
    let late = 1e9;
    assert_eq!(galperin_from(5, 0.0, Revision::R6).0, 31415);
    let (count, end) = galperin_from(5, late, Revision::R7);
    assert_eq!(count, 31415);
    assert_eq!(end.reason, EndReason::Free);
    assert!(end.t > late);
    let (old, _) = galperin_from(5, late, Revision::R6);
    assert_ne!(
        old, 31415,
        "the sixth revision's f64 time resolves these hits"
    );
}

// ---------------------------------------------------------------------------
// Newton's cradle
// ---------------------------------------------------------------------------

/// Five equal discs touching in a row (x = 0..4, R = 0.5) and a striker
/// from x = -2 with speed 1 (plus friction `mu`): contact at path 1.
fn cradle(mu: f64) -> Scene {
    let mut bodies: Vec<BodySpec> = (1..=5)
        .map(|k| disc(k, v((k - 1) as f64, 0.0), DVec2::ZERO, 0.5, 0.2, mu))
        .collect();
    bodies.push(disc(0, v(-2.0, 0.0), v(2.0, 0.0), 0.5, 0.2, mu));
    scene(9.81, bodies, vec![], vec![])
}

#[test]
fn newtons_cradle_frictionless_only_the_far_disc_leaves_with_the_striker_speed() {
    let sc = cradle(0.0);
    let (trace, end, world) = run_traced(&sc, Limits::default());
    assert_eq!(trace.events.len(), 5, "{:?}", trace.events);
    for (k, e) in trace.events.iter().enumerate() {
        assert!(is_pair(&e.kind, k as u64, k as u64 + 1), "event {k}: {e:?}");
        assert_close(e.t, 0.5, 1e-15, "all contacts at the same time");
    }
    assert_eq!(end.reason, EndReason::Free);
    for id in 0..5 {
        let (_, vel) = state(&world, id, end.t);
        assert!(vel.length() <= 1e-14, "disc {id} must end at rest: {vel}");
    }
    let (_, far) = state(&world, 5, end.t);
    assert_vec_close(far, v(2.0, 0.0), 1e-14, "far disc velocity");

    let mut model = Model::new(sc).unwrap();
    model.compute(&Limits::default());
    for t in [0.25, 0.5, 0.5 + 1e-9, 0.75, 1.0, 10.0] {
        let ratio = min_pair_ratio(&model.scene_at(t));
        assert!(
            ratio >= 1.0 - 1e-12,
            "overlap at t={t}: distance/(R+R) = {ratio}"
        );
    }
}

#[test]
fn newtons_cradle_with_friction_passes_the_contact_speed_through_the_row() {
    let (mu, g) = (0.2, 9.81);
    let alpha = mu * g;
    let vc = (4.0 - 2.0 * alpha * 1.0f64).sqrt();
    let tc = (2.0 - vc) / alpha;
    let (trace, end, world) = run_traced(&cradle(mu), Limits::default());
    let hits: Vec<&Event> = trace
        .events
        .iter()
        .filter(|e| e.kind.is_collision())
        .collect();
    assert_eq!(hits.len(), 5, "{:?}", trace.events);
    for (k, e) in hits.iter().enumerate() {
        assert!(is_pair(&e.kind, k as u64, k as u64 + 1), "{e:?}");
        assert_close(e.t, tc, 1e-14, "contact time");
    }
    assert_eq!(
        trace.events.len(),
        6,
        "then only the far disc stops: {:?}",
        trace.events
    );
    assert_eq!(trace.events[5].kind, EventKind::Stop { body: BodyId(5) });
    assert_close(
        trace.events[5].t,
        tc + vc / alpha,
        1e-13,
        "far disc stop time",
    );
    assert_eq!(end.reason, EndReason::Rest);
    assert_vec_close(
        state(&world, 5, end.t).0,
        v(4.0 + vc * vc / (2.0 * alpha), 0.0),
        1e-13,
        "far disc rest",
    );
    for k in 1..5 {
        assert_vec_close(
            state(&world, k, end.t).0,
            v((k - 1) as f64, 0.0),
            1e-15,
            "middle discs stay",
        );
    }
}

// ---------------------------------------------------------------------------
// Grazing and resting contacts
// ---------------------------------------------------------------------------

#[test]
fn grazing_a_resting_disc_exactly_tangent_does_not_deflect_or_overlap() {
    for mu in [0.0, 0.05] {
        // The mover's centre passes at distance exactly R + R = 1 from the
        // resting disc (a double root of the contact equation).
        let sc = scene(
            9.81,
            vec![
                disc(1, v(0.0, 0.0), DVec2::ZERO, 0.5, 1.0, mu),
                disc(2, v(-3.0, 1.0), v(3.0, 0.0), 0.5, 1.0, mu),
            ],
            vec![],
            vec![],
        );
        let (trace, end, world) = run_traced(&sc, Limits::default());
        let hits = collisions(&trace.events);
        assert!(
            hits <= 1,
            "mu={mu}: a grazing contact fired {hits} times: {:?}",
            trace.events
        );
        let (p1, v1) = state(&world, 1, end.t.max(10.0));
        assert!(
            v1.length() <= 1e-12,
            "mu={mu}: the resting disc was pushed: {v1}"
        );
        assert!(
            p1.length() <= 1e-12,
            "mu={mu}: the resting disc moved: {p1}"
        );
        let alpha = mu * 9.81;
        let t_end = if mu > 0.0 { 3.0 / alpha } else { 2.0 };
        let x_end = if mu > 0.0 {
            -3.0 + 9.0 / (2.0 * alpha)
        } else {
            3.0
        };
        let (p2, v2) = state(&world, 2, t_end);
        assert_vec_close(p2, v(x_end, 1.0), 1e-12, &format!("mu={mu}: mover path"));
        if mu == 0.0 {
            assert_vec_close(v2, v(3.0, 0.0), 1e-12, "mover velocity");
        }
        let mut model = Model::new(sc).unwrap();
        model.compute(&Limits::default());
        let t_tan = if mu > 0.0 {
            (3.0 - (9.0 - 2.0 * alpha * 3.0f64).sqrt()) / alpha
        } else {
            1.0
        };
        for dt in [-1e-3, -1e-9, 0.0, 1e-9, 1e-3] {
            let ratio = min_pair_ratio(&model.scene_at(t_tan + dt));
            assert!(
                ratio >= 1.0 - 1e-12,
                "mu={mu}: overlap {ratio} at t_tan{dt:+e}"
            );
        }
    }
}

#[test]
fn two_sliding_discs_passing_exactly_tangent_do_not_deflect() {
    // Antiparallel, same speed and friction, centre lines 1 = R + R apart:
    // f(t) = (2 sigma(t) - 6)^2, a double root of the quartic at sigma = 3.
    let (mu, g, speed) = (0.1, 9.81, 3.0);
    let alpha = mu * g;
    let sc = scene(
        g,
        vec![
            disc(1, v(-3.0, 0.5), v(speed, 0.0), 0.5, 1.0, mu),
            disc(2, v(3.0, -0.5), v(-speed, 0.0), 0.5, 1.0, mu),
        ],
        vec![],
        vec![],
    );
    let (trace, end, world) = run_traced(&sc, Limits::default());
    assert!(collisions(&trace.events) <= 1, "{:?}", trace.events);
    assert_eq!(end.reason, EndReason::Rest);
    let d = speed * speed / (2.0 * alpha);
    assert_vec_close(
        state(&world, 1, end.t).0,
        v(-3.0 + d, 0.5),
        1e-9,
        "disc 1 rest",
    );
    assert_vec_close(
        state(&world, 2, end.t).0,
        v(3.0 - d, -0.5),
        1e-9,
        "disc 2 rest",
    );
    let mut model = Model::new(sc).unwrap();
    model.compute(&Limits::default());
    let t_tan = (speed - (speed * speed - 2.0 * alpha * 3.0).sqrt()) / alpha;
    for dt in [-1e-2, -1e-6, 0.0, 1e-6, 1e-2] {
        let ratio = min_pair_ratio(&model.scene_at(t_tan + dt));
        assert!(ratio >= 1.0 - 1e-12, "overlap {ratio} at t_tan{dt:+e}");
    }
}

#[test]
fn two_touching_discs_at_rest_produce_no_events() {
    let sc = scene(
        9.81,
        vec![
            disc(1, v(0.0, 0.0), DVec2::ZERO, 0.5, 1.0, 0.3),
            disc(2, v(1.0, 0.0), DVec2::ZERO, 0.5, 1.0, 0.3),
            disc(3, v(0.5, 0.75f64.sqrt()), DVec2::ZERO, 0.5, 1.0, 0.0),
        ],
        vec![],
        vec![],
    );
    let (trace, end, _) = run_traced(&sc, Limits::default());
    assert!(trace.events.is_empty(), "{:?}", trace.events);
    assert_eq!(
        end,
        End {
            t: 0.0,
            reason: EndReason::Rest
        }
    );
}

#[test]
fn disc_resting_against_a_wall_produces_no_events() {
    for kind in [LineKind::Line, LineKind::Ray, LineKind::Segment] {
        let sc = scene(
            9.81,
            vec![disc(1, v(0.5, 0.0), DVec2::ZERO, 0.5, 1.0, 0.0)],
            vec![Line::new(v(0.0, -1.0), v(0.0, 1.0), kind)],
            vec![Point { pos: v(0.5, 0.5) }],
        );
        let (trace, end, _) = run_traced(&sc, Limits::default());
        assert!(trace.events.is_empty(), "{kind:?}: {:?}", trace.events);
        assert_eq!(end.reason, EndReason::Rest);
    }
}

#[test]
fn disc_sliding_along_a_wall_while_touching_it_produces_no_collision() {
    // With friction the disc stops before the segment's end; without, it
    // slides past the end tangentially (see also the next test).
    for mu in [0.0, 0.3] {
        for kind in [LineKind::Line, LineKind::Segment] {
            let sc = scene(
                9.81,
                vec![disc(1, v(0.0, 0.5), v(2.0, 0.0), 0.5, 1.0, mu)],
                vec![Line::new(v(-10.0, 0.0), v(10.0, 0.0), kind)],
                vec![],
            );
            let (trace, end, _) = run_traced(&sc, Limits::default());
            assert_eq!(
                collisions(&trace.events),
                0,
                "mu={mu} {kind:?}: {:?}",
                trace.events
            );
            if mu == 0.0 {
                // Nothing can ever happen: along the line, nor (tangentially)
                // at the segment's end.
                assert_eq!(end.reason, EndReason::Free, "{kind:?}");
            } else {
                assert_eq!(trace.events.len(), 1);
                assert_eq!(end.reason, EndReason::Rest);
            }
        }
    }
}

#[test]
fn disc_sliding_along_a_segment_and_off_its_end_produces_no_collision() {
    // The disc touches the segment all along and leaves it tangentially
    // past its end: the distance to the end point has a double root there
    // (it never decreases through R), so there is no approaching contact.
    let seg = Line::new(v(-10.0, 0.0), v(10.0, 0.0), LineKind::Segment);
    let sc = scene(
        9.81,
        vec![disc(1, v(0.0, 0.5), v(2.0, 0.0), 0.5, 1.0, 0.0)],
        vec![seg],
        vec![],
    );
    let (trace, end, world) = run_traced(&sc, Limits::default());
    assert_eq!(collisions(&trace.events), 0, "{:?}", trace.events);
    assert_eq!(end.reason, EndReason::Free);
    assert_eq!(state(&world, 1, 10.0), (v(20.0, 0.5), v(2.0, 0.0)));

    // The same after a perfectly inelastic (e = 0) hit on a tilted segment:
    // the disc then slides along it towards its end (3, 0).
    let (out, _, events) = tilted_wall_bounce_events(LineKind::Segment, 0.0);
    assert_vec_close(
        out,
        v(0.5, -0.5),
        1e-14,
        "e = 0 keeps the tangential velocity",
    );
    assert_eq!(collisions(&events), 1, "{events:?}");
}

#[test]
fn disc_sliding_past_a_touching_resting_disc_or_leaving_it_produces_no_collision() {
    let sc = scene(
        9.81,
        vec![
            disc(1, v(0.0, 0.0), DVec2::ZERO, 0.5, 1.0, 0.2),
            disc(2, v(0.0, 1.0), v(1.0, 0.0), 0.5, 1.0, 0.2),
            disc(3, v(1.0, 0.0), v(1.0, 0.5), 0.5, 1.0, 0.2),
        ],
        vec![],
        vec![],
    );
    let (trace, _, _) = run_traced(&sc, Limits::default());
    assert_eq!(collisions(&trace.events), 0, "{:?}", trace.events);
}

#[test]
fn very_slow_frictionless_disc_does_not_hit_a_far_away_disc() {
    // Disc 2 creeps straight down x = 0.7 at 1e-170 per second; disc 1
    // rests at x = 0.3: their centres never come closer than 0.4 > 0.02.
    // (Found by the property tests: a frictionless disc with e < 1
    // bouncing between two walls slows down geometrically.)
    let sc = scene(
        9.81,
        vec![
            disc(1, v(0.3, 0.3), DVec2::ZERO, 0.01, 1.0, 0.0),
            disc(2, v(0.7, 0.5), v(0.0, -1e-170), 0.01, 1.0, 0.0),
        ],
        vec![],
        vec![],
    );
    let (trace, end, _) = run_traced(&sc, Limits::default());
    assert!(trace.events.is_empty(), "{:?}", trace.events);
    assert_eq!(end.reason, EndReason::Free);
}

/// Two touching discs sliding together at (1, 0), the rear one braking at
/// 0.981 and the front one at 3 * 0.981: the rear one pushes.
fn pushing_pair() -> Vec<BodySpec> {
    vec![
        disc(1, v(0.0, 0.0), v(1.0, 0.0), 0.5, 1.0, 0.1),
        disc(2, v(1.0, 0.0), v(1.0, 0.0), 0.5, 1.0, 0.3),
    ]
}

#[test]
fn touching_discs_sliding_together_move_as_one_when_the_rear_one_slides_easier() {
    // Both move at (1, 0) touching; the front disc brakes at 3 * 0.981, the
    // rear one at 0.981, so the rear one pushes the front one (the distance
    // has a double root at t = 0 and then would fall). Friction forces do
    // not depend on the contact, so the pair brakes at the mean
    // a = (alpha_a + alpha_b) / 2 = 1.962 and stops together at T = 1 / a,
    // each 1 / (2 a) further on.
    let sc = scene(9.81, pushing_pair(), vec![], vec![]);
    let limits = Limits {
        max_events: 100_000,
        ..Limits::default()
    };
    let (trace, end, world) = run_traced(&sc, limits);
    let mut model = Model::new(sc).unwrap();
    model.compute(&limits);
    for k in 0..=40 {
        let t = 0.6 * k as f64 / 40.0;
        let ratio = min_pair_ratio(&model.scene_at(t));
        assert!(
            ratio >= 1.0 - 1e-9,
            "overlap at t={t}: distance/(R+R) = {ratio}"
        );
    }
    assert_eq!(end.reason, EndReason::Rest, "{:?}", trace.events);
    let a = 0.5 * (0.1 + 0.3) * 9.81;
    assert_close(end.t, 1.0 / a, 1e-12, "both stop at 1 / a");
    assert!(
        trace.events.len() <= 4,
        "one push and two stops: {:?}",
        trace.events
    );
    let (p1, v1) = state(&world, 1, 10.0);
    let (p2, v2) = state(&world, 2, 10.0);
    assert_vec_close(p1, v(0.5 / a, 0.0), 1e-12, "rear disc at rest");
    assert_vec_close(p2, v(1.0 + 0.5 / a, 0.0), 1e-12, "front disc at rest");
    assert_eq!((v1, v2), (DVec2::ZERO, DVec2::ZERO));
}

#[test]
fn a_pushed_pair_parts_when_a_third_disc_hits_the_front_one_head_on() {
    // The pair of the test above; a frictionless disc comes the other way
    // along the same line and hits the front disc at speed 2: the run ends
    // at rest with no overlap (the pair's shared braking does not outlive
    // the hit).
    let sc = scene(
        9.81,
        [
            pushing_pair(),
            vec![disc(3, v(2.5, 0.0), v(-2.0, 0.0), 0.5, 1.0, 0.2)],
        ]
        .concat(),
        vec![],
        vec![],
    );
    let limits = Limits {
        max_events: 10_000,
        ..Limits::default()
    };
    let (trace, end, _) = run_traced(&sc, limits);
    assert_eq!(end.reason, EndReason::Rest, "{:?}", trace.events);
    assert!(trace.events.iter().any(|e| is_pair(&e.kind, 2, 3)));
    let mut model = Model::new(sc).unwrap();
    model.compute(&limits);
    for k in 0..=60 {
        let t = end.t * k as f64 / 60.0;
        let ratio = min_pair_ratio(&model.scene_at(t));
        assert!(ratio >= 1.0 - 1e-9, "overlap at t={t}: {ratio}");
    }
}

#[test]
fn a_disc_that_stopped_is_still_hit_after_its_first_predicted_partner_turns_away() {
    // A slides briefly and stops at x = 0.1^2 / (2 * 0.5 * 9.81). C comes
    // down towards A but bounces off a wall first; B comes along y = 0 and
    // must hit A head on, when its centre reaches x_A - 0.2.
    let (mu, g) = (0.5, 9.81);
    let x_a = 0.01 / (2.0 * mu * g);
    let sc = scene(
        g,
        vec![
            disc(1, v(0.0, 0.0), v(0.1, 0.0), 0.1, 1.0, mu),
            disc(2, v(-2.0, 0.0), v(1.0, 0.0), 0.1, 1.0, 0.0),
            disc(3, v(0.0, 1.0), v(0.0, -1.0), 0.1, 1.0, 0.0),
        ],
        vec![Line::new(v(-0.3, 0.5), v(0.3, 0.5), LineKind::Segment)],
        vec![],
    );
    let (trace, _, world) = run_traced(&sc, Limits::default());
    let hit = trace
        .events
        .iter()
        .find(|e| is_pair(&e.kind, 1, 2))
        .unwrap_or_else(|| panic!("B passed through A: {:?}", trace.events));
    assert_close(hit.t, 1.8 + x_a, 1e-12, "contact time");
    // Equal masses head on: B stops, A slides 1 / (2 mu g) further.
    let (p1, _) = state(&world, 1, 100.0);
    let (p2, v2) = state(&world, 2, 100.0);
    assert_vec_close(p1, v(x_a + 1.0 / (2.0 * mu * g), 0.0), 1e-12, "A at rest");
    assert_vec_close(p2, v(x_a - 0.2, 0.0), 1e-12, "B at rest");
    assert_eq!(v2, DVec2::ZERO);
}

/// A light disc (e = 0.3) squeezed between the floor of the unit box and a
/// heavier disc: the contacts alternate faster and faster (inelastic
/// collapse), and both have friction, so they must come to rest.
fn squeeze_scene() -> Scene {
    scene(
        9.81,
        vec![
            disc(
                0,
                v(0.7000000000000001, 0.5),
                v(0.0, -1.8959052099413232),
                0.08483924427697022,
                0.1536445301851759,
                0.2910057958277648,
            )
            .with_restitution(0.3),
            disc(
                1,
                v(0.7000000000000001, 0.9),
                v(-1.1556795368112232, 0.785746437034337),
                0.01,
                1.0,
                0.05,
            ),
        ],
        square(0.0, 1.0),
        vec![],
    )
}

#[test]
fn disc_squeezed_between_a_wall_and_a_disc_comes_to_rest() {
    let mut world = World::new(&squeeze_scene(), WorldConfig::default()).unwrap();
    let mut log = Log::default();
    let end = world.run(
        &Limits {
            max_events: 100_000,
            ..Limits::default()
        },
        &mut log,
    );
    // Each event must change something: no instant may hold more than a
    // handful of events between two discs and a wall.
    let mut most_at_one_time = 0;
    for run in log.0.chunk_by(|a, b| a.t == b.t) {
        most_at_one_time = most_at_one_time.max(run.len());
    }
    assert!(
        most_at_one_time <= 100,
        "{most_at_one_time} events at one instant"
    );
    assert_eq!(end.reason, EndReason::Rest, "after {} events", log.0.len());
}

// ---------------------------------------------------------------------------
// Corners and tunnelling
// ---------------------------------------------------------------------------

#[test]
fn disc_aimed_at_a_segment_end_bounces_off_the_corner_like_off_a_point() {
    // Segment x = 0, y in [-1, 1]; a disc of R = 0.5 along y = 1.3 hits the
    // end (0, 1) when its centre is at (-0.4, 1.3): normal (-0.8, 0.6).
    let seg = Line::new(v(0.0, -1.0), v(0.0, 1.0), LineKind::Segment);
    let sc = scene(
        9.81,
        vec![disc(1, v(-3.0, 1.3), v(1.0, 0.0), 0.5, 1.0, 0.0)],
        vec![seg],
        vec![],
    );
    let (trace, end, _) = run_traced(&sc, Limits::default());
    assert_eq!(trace.events.len(), 1, "{:?}", trace.events);
    assert_eq!(
        trace.events[0].kind,
        EventKind::BodyLine {
            body: BodyId(1),
            line: LineId(0),
            end: Some(1)
        }
    );
    assert_close(trace.events[0].t, 2.6, 1e-15, "corner contact time");
    // v' = v - 2 (v.n) n with n = (-0.8, 0.6).
    assert_vec_close(
        trace.after[0][&BodyId(1)].vel,
        v(-0.28, 0.96),
        1e-15,
        "corner bounce",
    );
    assert_eq!(end.reason, EndReason::Free);

    // The same through the start of a ray from (0, 1) downwards.
    let ray = Line::new(v(0.0, 1.0), v(0.0, -1.0), LineKind::Ray);
    let sc = scene(
        9.81,
        vec![disc(1, v(-3.0, 1.3), v(1.0, 0.0), 0.5, 1.0, 0.0)],
        vec![ray],
        vec![],
    );
    let (trace, _, _) = run_traced(&sc, Limits::default());
    assert_eq!(trace.events.len(), 1, "{:?}", trace.events);
    assert!(
        matches!(
            trace.events[0].kind,
            EventKind::BodyLine { end: Some(0), .. }
        ),
        "{:?}",
        trace.events
    );
    assert_vec_close(
        trace.after[0][&BodyId(1)].vel,
        v(-0.28, 0.96),
        1e-15,
        "ray corner bounce",
    );

    // Aimed dead at the end: straight back.
    let sc = scene(
        9.81,
        vec![disc(1, v(-3.0, 1.0), v(1.0, 0.0), 0.5, 1.0, 0.0)],
        vec![seg],
        vec![],
    );
    let (trace, _, _) = run_traced(&sc, Limits::default());
    assert_eq!(trace.events.len(), 1, "{:?}", trace.events);
    assert_close(trace.events[0].t, 2.5, 1e-15, "head-on corner time");
    assert_vec_close(
        trace.after[0][&BodyId(1)].vel,
        v(-1.0, 0.0),
        1e-15,
        "head-on corner bounce",
    );
}

#[test]
fn disc_aimed_just_beyond_a_segment_end_passes_by() {
    let seg = Line::new(v(0.0, -1.0), v(0.0, 1.0), LineKind::Segment);
    for mu in [0.0, 0.01] {
        let sc = scene(
            9.81,
            vec![disc(1, v(-3.0, 1.5 + 1e-9), v(3.0, 0.0), 0.5, 1.0, mu)],
            vec![seg],
            vec![],
        );
        let (trace, _, world) = run_traced(&sc, Limits::default());
        assert_eq!(collisions(&trace.events), 0, "{:?}", trace.events);
        let (p, _) = state(&world, 1, 10.0);
        assert!(
            p.x > 0.5 && p.y == 1.5 + 1e-9,
            "it must pass straight by: {p}"
        );
    }
}

#[test]
fn fast_tiny_disc_never_tunnels_through_a_thin_segment() {
    // R = 1e-4 at 10^4 per second against a zero-thickness segment.
    let (r, speed) = (1e-4, 1e4);
    let u = v(0.8, 0.6) * speed;
    let seg = Line::new(v(1.0, -1.0), v(1.0, 1.0), LineKind::Segment);
    let sc = scene(
        9.81,
        vec![disc(1, v(0.0, 0.0), u, r, 1e-6, 0.0)],
        vec![seg],
        vec![],
    );
    let (trace, _, world) = run_traced(&sc, Limits::default());
    assert_eq!(trace.events.len(), 1, "{:?}", trace.events);
    assert_close(trace.events[0].t, (1.0 - r) / u.x, 1e-15, "contact time");
    let (p, vel) = state(&world, 1, 1.0);
    assert!(p.x < 1.0 - r, "tunnelled: {p}");
    assert_vec_close(vel, v(-u.x, u.y), 1e-12, "reflected");
}

/// Fails the test if a disc leaves the box `[0, 1]^2` (by more than 1e-9 R).
struct StaysInBox {
    events: u64,
}

impl EventHandler for StaysInBox {
    fn on_event(&mut self, world: &World, event: &Event) {
        self.events += 1;
        for b in world.bodies() {
            let p = b.trajectory.position(event.t);
            // A centre moving at speed u is placed no better than u times
            // the rounding of t: allow that on top of 1e-9 R.
            let slack = 4.0 * f64::EPSILON * b.trajectory.speed() * event.t.max(1.0);
            let r = b.material.radius * (1.0 - 1e-9) - slack;
            assert!(
                p.x >= r && p.y >= r && p.x <= 1.0 - r && p.y <= 1.0 - r,
                "{} left the box at t={} ({event:?}): {p}",
                b.id,
                event.t
            );
        }
    }
}

#[test]
fn fast_tiny_discs_in_a_box_of_thin_segments_never_leave_it() {
    let bodies = vec![
        disc(1, v(0.5, 0.5), v(9876.5, 4321.0), 1e-4, 1.0, 0.0),
        disc(2, v(0.25, 0.75), v(-3333.3, 7777.7), 2e-4, 2.0, 0.0),
        disc(3, v(0.75, 0.25), v(123.4, -9999.9), 1e-4, 0.5, 0.0),
    ];
    let sc = scene(9.81, bodies, square(0.0, 1.0), vec![]);
    let mut world = World::new(&sc, WorldConfig::default()).unwrap();
    let mut check = StaysInBox { events: 0 };
    let end = world.run(
        &Limits {
            max_events: 20_000,
            ..Limits::default()
        },
        &mut check,
    );
    assert_eq!(end.reason, EndReason::MaxEvents);
    assert_eq!(check.events, 20_000);
}

// ---------------------------------------------------------------------------
// Sensors
// ---------------------------------------------------------------------------

/// Removes every disc whose centre leaves a region; logs events.
#[derive(Default)]
struct FallOff {
    exits: Vec<(f64, BodyId, LineId)>,
    events: Vec<Event>,
    counts_after: Vec<usize>,
}

impl EventHandler for FallOff {
    fn on_event(&mut self, world: &World, event: &Event) {
        self.events.push(*event);
        self.counts_after.push(world.bodies().count());
    }

    fn on_region_exit(&mut self, t: f64, body: BodyId, line: LineId) -> ExitResponse {
        self.exits.push((t, body, line));
        ExitResponse::Remove
    }
}

/// Sensor x = 1 (inside x < 1), a wall at x = 2; a disc from the origin
/// with speed 3 and mu = 0.1 goes out, bounces, comes back in and stops.
fn sensor_scene() -> Scene {
    scene(
        9.81,
        vec![disc(1, v(0.0, 0.0), v(3.0, 0.0), 0.1, 1.0, 0.1)],
        vec![
            Line::sensor(v(1.0, -1.0), v(1.0, 1.0), LineKind::Line),
            Line::new(v(2.0, -1.0), v(2.0, 1.0), LineKind::Line),
        ],
        vec![],
    )
}

#[test]
fn sensor_line_reports_region_exit_exactly_once_when_the_centre_crosses_outwards() {
    let alpha: f64 = 0.1 * 9.81;
    let time_at = |path: f64| (3.0 - (9.0 - 2.0 * alpha * path).sqrt()) / alpha;
    let (trace, end, world) = run_traced(&sensor_scene(), Limits::default());
    let kinds: Vec<&str> = trace.events.iter().map(|e| e.kind.name()).collect();
    assert_eq!(
        kinds,
        ["region-exit", "body-line", "region-entry", "stop"],
        "{:?}",
        trace.events
    );
    assert_eq!(
        trace.events[0].kind,
        EventKind::RegionExit {
            body: BodyId(1),
            line: LineId(0),
            removed: false
        }
    );
    assert_close(trace.events[0].t, time_at(1.0), 1e-14, "exit time");
    assert_close(trace.events[1].t, time_at(1.9), 1e-14, "wall time");
    assert_close(trace.events[2].t, time_at(2.8), 1e-14, "entry time");
    assert_eq!(end.reason, EndReason::Rest);
    let d = 9.0 / (2.0 * alpha);
    assert_vec_close(
        state(&world, 1, end.t).0,
        v(1.9 - (d - 1.9), 0.0),
        1e-13,
        "rest position",
    );
}

#[test]
fn sensor_exit_with_remove_takes_the_disc_out_of_the_scene() {
    // Without the rule, disc 1 would cross the sensor at x = 1 and then hit
    // disc 2 resting at x = 1.5.
    let mut sc = sensor_scene();
    sc.bodies
        .push(disc(2, v(1.5, 0.0), DVec2::ZERO, 0.1, 1.0, 0.1));
    let (trace, _, _) = run_traced(&sc, Limits::default());
    assert!(
        trace.events.iter().any(|e| is_pair(&e.kind, 1, 2)),
        "{:?}",
        trace.events
    );

    let mut world = World::new(&sc, WorldConfig::default()).unwrap();
    let mut rules = FallOff::default();
    let end = world.run(&Limits::default(), &mut rules);
    let alpha: f64 = 0.1 * 9.81;
    let t_exit = (3.0 - (9.0 - 2.0 * alpha).sqrt()) / alpha;
    assert_eq!(rules.exits.len(), 1);
    assert_eq!((rules.exits[0].1, rules.exits[0].2), (BodyId(1), LineId(0)));
    assert_close(rules.exits[0].0, t_exit, 1e-14, "exit time");
    assert_eq!(
        rules.events,
        vec![Event {
            t: rules.exits[0].0,
            kind: EventKind::RegionExit {
                body: BodyId(1),
                line: LineId(0),
                removed: true
            }
        }]
    );
    assert_eq!(rules.counts_after, [1]);
    assert!(world.body(BodyId(1)).is_none());
    assert_eq!(
        world.bodies().map(|b| b.id).collect::<Vec<_>>(),
        [BodyId(2)]
    );
    assert_eq!(state(&world, 2, 100.0), (v(1.5, 0.0), DVec2::ZERO));
    assert_eq!(end.reason, EndReason::Rest);
    assert_eq!(world.stats().region_exits, 1);

    // A model records the removal: the disc is gone after the exit only.
    let mut model = Model::with_rules(sc, FallOff::default(), WorldConfig::default()).unwrap();
    model.compute(&Limits::default());
    assert_eq!(model.scene_at(t_exit * 0.5).bodies.len(), 2);
    assert!(model.body_at(BodyId(1), t_exit * 0.5).is_some());
    assert_eq!(model.scene_at(t_exit + 1e-9).bodies.len(), 1);
    assert!(model.body_at(BodyId(1), 10.0).is_none());
}

// ---------------------------------------------------------------------------
// Limits
// ---------------------------------------------------------------------------

/// One frictionless disc bouncing in the unit box: a wall every 0.9 / 2 s
/// along x (from 0.5 at speed 2), never at rest.
fn bouncing_box() -> Scene {
    scene(
        9.81,
        vec![disc(1, v(0.5, 0.5), v(2.0, 0.0), 0.05, 1.0, 0.0)],
        square(0.0, 1.0),
        vec![],
    )
}

#[test]
fn limit_until_stops_at_the_horizon_with_reason_until() {
    let (trace, end, _) = run_traced(
        &bouncing_box(),
        Limits {
            until: 1.0,
            ..Limits::default()
        },
    );
    // Hits at 0.225, 0.675 (then 1.125 > 1).
    assert_eq!(
        end,
        End {
            t: 1.0,
            reason: EndReason::Until
        }
    );
    assert_eq!(trace.events.len(), 2, "{:?}", trace.events);
    assert_close(trace.events[0].t, 0.225, 1e-15, "first hit");
    assert_close(trace.events[1].t, 0.675, 1e-15, "second hit");
}

#[test]
fn limit_max_collisions_stops_after_exactly_that_many() {
    let (trace, end, _) = run_traced(
        &bouncing_box(),
        Limits {
            max_collisions: 3,
            ..Limits::default()
        },
    );
    assert_eq!(end.reason, EndReason::MaxCollisions);
    assert_eq!(collisions(&trace.events), 3);
    assert_eq!(end.t, trace.events[2].t);
}

#[test]
fn limit_max_events_stops_after_exactly_that_many() {
    let (trace, end, _) = run_traced(
        &bouncing_box(),
        Limits {
            max_events: 5,
            ..Limits::default()
        },
    );
    assert_eq!(end.reason, EndReason::MaxEvents);
    assert_eq!(trace.events.len(), 5);
    assert_eq!(end.t, trace.events[4].t);
}

#[test]
fn frictionless_closed_box_ends_on_the_event_cap_instead_of_looping() {
    let sc = lattice_scene(16, 42, 0.0, 1.0, 2.0);
    let mut world = World::new(&sc, WorldConfig::default()).unwrap();
    let mut counter = Counter::default();
    let end = world.run(
        &Limits {
            max_events: 100_000,
            ..Limits::default()
        },
        &mut counter,
    );
    assert_eq!(end.reason, EndReason::MaxEvents);
    assert_eq!(counter.events, 100_000);
    assert_eq!(counter.collisions, 100_000);
}

#[test]
fn sim_max_events_option_ends_a_frictionless_box_with_max_events() {
    let sc = lattice_scene(4, 7, 0.0, 1.0, 1.0);
    let out = sim(&["-", "--max-events", "1000"], Some(&sc.to_json()));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["end"]["reason"], "max-events");
    assert_eq!(json["events"].as_array().unwrap().len(), 1000);
}

// ---------------------------------------------------------------------------
// Model: queries, actions, rewind, diffs
// ---------------------------------------------------------------------------

/// A striker, a target head on, and a third disc the target grazes later.
fn three_disc_scene() -> Scene {
    scene(
        9.81,
        vec![
            disc(1, v(0.0, 0.0), v(2.0, 0.0), 0.016, 0.01, 0.2),
            disc(2, v(0.5, 0.0), DVec2::ZERO, 0.016, 0.01, 0.2),
            disc(3, v(1.0, 0.02), DVec2::ZERO, 0.016, 0.02, 0.2),
        ],
        square(-0.5, 1.5),
        vec![],
    )
}

#[test]
fn model_scene_at_matches_the_head_on_closed_form_before_and_after_contact() {
    let (mu, g, v0, r, d): (f64, f64, f64, f64, f64) = (0.2, 9.81, 2.0, 0.016, 0.5);
    let alpha = mu * g;
    let gap = d - 2.0 * r;
    let vc = (v0 * v0 - 2.0 * alpha * gap).sqrt();
    let tc = (v0 - vc) / alpha;
    let sc = scene(
        g,
        vec![
            disc(1, v(0.0, 0.0), v(v0, 0.0), r, 0.01, mu),
            disc(2, v(d, 0.0), DVec2::ZERO, r, 0.01, mu),
        ],
        vec![],
        vec![],
    );
    let mut model = Model::new(sc).unwrap();
    model.compute(&Limits::default());
    let t_stop = tc + vc / alpha;
    // Not exactly at tc: which side of the event an instant within an ulp
    // of it falls on is not specified.
    for &t in &[
        tc * 0.5,
        t_stop * 2.0,
        tc * 1.000001,
        0.0,
        (tc + t_stop) * 0.5,
        tc * 0.999,
        t_stop,
    ] {
        let s = model.scene_at(t);
        let (x1, v1, x2, v2) = if t < tc {
            (v0 * t - 0.5 * alpha * t * t, v0 - alpha * t, d, 0.0)
        } else {
            let s = (t - tc).min(vc / alpha);
            (gap, 0.0, d + vc * s - 0.5 * alpha * s * s, vc - alpha * s)
        };
        assert_eq!((s.bodies[0].id, s.bodies[1].id), (BodyId(1), BodyId(2)));
        assert_vec_close(
            s.bodies[0].pos,
            v(x1, 0.0),
            1e-13,
            &format!("striker at {t}"),
        );
        assert_vec_close(
            s.bodies[0].vel,
            v(v1, 0.0),
            1e-13,
            &format!("striker vel at {t}"),
        );
        assert_vec_close(
            s.bodies[1].pos,
            v(x2, 0.0),
            1e-13,
            &format!("target at {t}"),
        );
        assert_vec_close(
            s.bodies[1].vel,
            v(v2, 0.0),
            1e-13,
            &format!("target vel at {t}"),
        );
        let b2 = model.body_at(BodyId(2), t).unwrap();
        assert_eq!(b2, s.bodies[1]);
    }
}

/// A body-body event with its two bodies in id order.
fn unordered(kind: EventKind) -> EventKind {
    match kind {
        EventKind::BodyBody { a, b } => EventKind::BodyBody {
            a: a.min(b),
            b: a.max(b),
        },
        other => other,
    }
}

/// Compares two event lists: same kinds, times within `tol` relative.
#[track_caller]
fn assert_same_events(a: &[Event], b: &[Event], tol: f64) {
    assert_eq!(a.len(), b.len(), "event counts differ:\n{a:?}\n{b:?}");
    for (k, (x, y)) in a.iter().zip(b).enumerate() {
        assert_eq!(
            unordered(x.kind),
            unordered(y.kind),
            "event {k} differs: {x:?} vs {y:?}"
        );
        assert!(
            (x.t - y.t).abs() <= tol * x.t.abs().max(y.t.abs()).max(1e-300),
            "event {k} time differs: {x:?} vs {y:?}"
        );
    }
}

#[track_caller]
fn assert_same_scene(a: &Scene, b: &Scene, tol: f64) {
    assert_eq!(a.bodies.len(), b.bodies.len());
    for (x, y) in a.bodies.iter().zip(&b.bodies) {
        assert_eq!(x.id, y.id);
        assert_vec_close(x.pos, y.pos, tol, &format!("{} pos", x.id));
        assert_vec_close(x.vel, y.vel, tol, &format!("{} vel", x.id));
    }
}

#[test]
fn model_action_in_the_past_drops_later_events_and_matches_a_fresh_model() {
    let sc = three_disc_scene();
    let mut model = Model::new(sc).unwrap();
    model.compute(&Limits::default());
    let original: Vec<Event> = model.events().to_vec();
    assert!(original.len() >= 3, "{original:?}");
    let t_a = original[0].t * 0.5; // before the first collision
    let before_action = model.scene_at(t_a);
    let kept = original.iter().filter(|e| e.t <= t_a).count();

    let shot = v(1.5, 0.3);
    model
        .apply(
            t_a,
            Action::SetVelocity {
                id: BodyId(1),
                vel: shot,
            },
        )
        .unwrap();
    assert_eq!(
        model.events().len(),
        kept + 1,
        "later events must be dropped"
    );
    assert_eq!(&model.events()[..kept], &original[..kept]);
    assert_eq!(
        model.events()[kept],
        Event {
            t: t_a,
            kind: EventKind::Action { index: 0 }
        }
    );
    assert_eq!(model.actions().len(), 1);
    model.compute(&Limits::default());

    let mut fresh_scene = before_action.clone();
    fresh_scene.bodies[0].vel = shot;
    let mut fresh = Model::new(fresh_scene).unwrap();
    fresh.compute(&Limits::default());
    assert_same_events(&model.events()[kept + 1..], fresh.events(), 1e-12);
    assert!(!fresh.events().is_empty());
    for t in [t_a, t_a + 0.01, 0.3, 0.6, 1.0, 5.0] {
        assert_same_scene(&model.scene_at(t), &fresh.scene_at(t), 1e-12);
    }
    // Before the action, nothing changed.
    let mut untouched = Model::new(three_disc_scene()).unwrap();
    untouched.compute(&Limits::default());
    for t in [0.0, t_a * 0.5, t_a * 0.999] {
        assert_eq!(model.scene_at(t), untouched.scene_at(t));
    }
}

#[test]
fn model_rewind_and_recompute_reproduces_the_same_chain() {
    let mut model = Model::new(three_disc_scene()).unwrap();
    model.compute(&Limits::default());
    let original: Vec<Event> = model.events().to_vec();
    let t = (original[0].t + original[1].t) * 0.5;
    model.rewind(t).unwrap();
    assert!(model.events().iter().all(|e| e.t <= t));
    model.compute(&Limits::default());
    assert_same_events(model.events(), &original, 1e-12);
}

#[test]
fn model_invalid_action_returns_an_error_and_changes_nothing() {
    let mut model = Model::new(three_disc_scene()).unwrap();
    model.compute(&Limits::default());
    let events = model.events().to_vec();
    let times = [0.0, 0.05, 0.2, 0.5, 2.0];
    let scenes: Vec<Scene> = times.iter().map(|&t| model.scene_at(t)).collect();
    let overlapping = disc(9, v(0.5, 0.01), DVec2::ZERO, 0.016, 0.01, 0.2);
    let cases: Vec<(f64, Action)> = vec![
        (0.1, Action::RemoveBody { id: BodyId(99) }),
        (
            0.1,
            Action::SetVelocity {
                id: BodyId(99),
                vel: v(1.0, 0.0),
            },
        ),
        (
            0.1,
            Action::SetVelocity {
                id: BodyId(1),
                vel: v(f64::NAN, 0.0),
            },
        ),
        (0.01, Action::AddBody { body: overlapping }),
        (
            0.1,
            Action::AddBody {
                body: disc(2, v(0.0, 1.0), DVec2::ZERO, 0.01, 1.0, 0.0),
            },
        ),
        (0.1, Action::RemoveLine { index: 4 }),
        (0.1, Action::RemovePoint { index: 0 }),
        (0.1, Action::SetGravity { g: -1.0 }),
        (f64::NAN, Action::RemoveBody { id: BodyId(1) }),
        (-1.0, Action::RemoveBody { id: BodyId(1) }),
    ];
    for (t, action) in cases {
        let err = model.apply(t, action.clone());
        assert!(err.is_err(), "{action:?} at {t} must be refused");
        assert_eq!(model.events(), &events[..], "{action:?} changed the events");
        assert!(model.actions().is_empty());
        for (&tq, s) in times.iter().zip(&scenes) {
            assert_eq!(
                &model.scene_at(tq),
                s,
                "{action:?} changed the scene at {tq}"
            );
        }
    }
    assert!(matches!(
        model.apply(0.1, Action::RemoveBody { id: BodyId(99) }),
        Err(ActionError::NoSuchBody(BodyId(99)))
    ));
    assert!(matches!(
        model.apply(0.01, Action::AddBody { body: overlapping }),
        Err(ActionError::Invalid(_))
    ));
}

#[test]
fn model_invalid_action_on_a_partly_computed_model_changes_nothing() {
    let mut model = Model::new(three_disc_scene()).unwrap();
    model.compute(&Limits {
        until: 0.01,
        ..Limits::default()
    });
    let events = model.events().to_vec();
    let end = model.end();
    let err = model.apply(1.0, Action::RemoveBody { id: BodyId(99) });
    assert!(err.is_err());
    assert_eq!(
        model.events(),
        &events[..],
        "a refused action extended the chain"
    );
    assert_eq!(model.end(), end);
}

/// A model with a removal by the rules, an added body and a gravity change.
fn busy_model() -> Model<FallOff> {
    let mut sc = lattice_scene(9, 3, 0.15, 0.9, 2.5);
    // Open the box's right side and watch it with a sensor instead.
    sc.lines[1] = Line::sensor(v(1.0, 0.0), v(1.0, 1.0), LineKind::Line);
    let mut model = Model::with_rules(sc, FallOff::default(), WorldConfig::default()).unwrap();
    model.compute(&Limits::default());
    let t_end = model.events().last().unwrap().t;
    // A new disc wherever there is room at that moment.
    let added = (0..100).any(|k| {
        let pos = v(0.05 + 0.09 * (k % 10) as f64, 0.05 + 0.09 * (k / 10) as f64);
        let body = disc(100, pos, v(0.5, 3.0), 0.015, 1.0, 0.2);
        model.apply(t_end * 0.3, Action::AddBody { body }).is_ok()
    });
    assert!(added);
    model.compute(&Limits::default());
    let t_end = model.events().last().unwrap().t;
    model
        .apply(t_end * 0.6, Action::SetGravity { g: 5.0 })
        .unwrap();
    model.compute(&Limits::default());
    model
}

#[test]
fn model_diff_applied_to_a_snapshot_gives_the_later_snapshot() {
    let model = busy_model();
    let events = model.events();
    assert!(events
        .iter()
        .any(|e| matches!(e.kind, EventKind::RegionExit { removed: true, .. })));
    assert!(events.len() > 20, "{}", events.len());
    let t_last = events.last().unwrap().t;
    let mut times: Vec<f64> = vec![0.0, t_last, t_last + 1.0];
    for k in [
        1,
        2,
        5,
        events.len() / 3,
        events.len() / 2,
        events.len() - 2,
    ] {
        times.push(events[k].t);
        times.push((events[k].t + events[k + 1].t) * 0.5);
    }
    for &a in &times {
        for &b in &times {
            let mut snap: Snapshot = model.snapshot_at(a);
            let diff = model.diff(a, b);
            diff.apply(&mut snap);
            assert_eq!(snap, model.snapshot_at(b), "diff({a}, {b})");
        }
    }
}

// ---------------------------------------------------------------------------
// Determinism and the `sim` command
// ---------------------------------------------------------------------------

fn bits(events: &[Event]) -> Vec<(u64, EventKind)> {
    events.iter().map(|e| (e.t.to_bits(), e.kind)).collect()
}

fn state_bits(world: &World, t: f64) -> Vec<(BodyId, [u64; 4])> {
    world
        .bodies()
        .map(|b: BodyState| {
            let (p, u) = (b.trajectory.position(t), b.trajectory.velocity(t));
            (
                b.id,
                [p.x.to_bits(), p.y.to_bits(), u.x.to_bits(), u.y.to_bits()],
            )
        })
        .collect()
}

#[test]
fn the_same_scene_run_twice_gives_bit_identical_events_and_final_states() {
    let text = std::fs::read_to_string(example("break.json")).unwrap();
    let scenes = [
        Scene::from_json(&text).unwrap(),
        lattice_scene(64, 11, 0.1, 0.9, 3.0),
        lattice_scene(25, 5, 0.0, 1.0, 1.0),
    ];
    for sc in &scenes {
        let limits = Limits {
            max_events: 20_000,
            ..Limits::default()
        };
        let mut runs = Vec::new();
        for _ in 0..2 {
            let mut world = World::new(sc, WorldConfig::default()).unwrap();
            let mut log = Log::default();
            let end = world.run(&limits, &mut log);
            runs.push((
                bits(&log.0),
                end.t.to_bits(),
                end.reason,
                state_bits(&world, end.t),
            ));
        }
        assert!(!runs[0].0.is_empty());
        assert!(runs[0] == runs[1], "two runs of the same scene differ");
    }
}

fn sim(args: &[&str], stdin: Option<&str>) -> std::process::Output {
    use std::io::Write;
    let mut child = Command::new(env!("CARGO_BIN_EXE_sim"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("sim starts");
    let mut pipe = child.stdin.take().unwrap();
    pipe.write_all(stdin.unwrap_or("").as_bytes()).unwrap();
    drop(pipe);
    child.wait_with_output().unwrap()
}

#[test]
fn sim_output_is_identical_across_two_runs_of_each_example() {
    for name in ["box.json", "break.json", "galperin.json"] {
        let path = example(name);
        let first = sim(&[&path], None);
        let second = sim(&[&path], None);
        assert!(
            first.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&first.stderr)
        );
        assert_eq!(first.stdout, second.stdout, "{name}: outputs differ");
        let json: serde_json::Value = serde_json::from_slice(&first.stdout).unwrap();
        let events = json["events"].as_array().unwrap();
        let hits = events
            .iter()
            .filter(|e| {
                ["body-body", "body-line", "body-point"].contains(&e["kind"].as_str().unwrap())
            })
            .count();
        assert_eq!(json["collisions"].as_u64().unwrap(), hits as u64, "{name}");
        let times: Vec<f64> = events.iter().map(|e| e["t"].as_f64().unwrap()).collect();
        assert!(
            times.windows(2).all(|w| w[0] <= w[1]),
            "{name}: events out of order"
        );
        if name == "galperin.json" {
            assert_eq!(hits, 31415);
            assert_eq!(json["end"]["reason"], "free");
        } else {
            assert_eq!(json["end"]["reason"], "rest", "{name}");
        }
    }
}

#[test]
fn sim_summary_gives_the_counts_end_and_bodies_of_the_full_output_without_the_events() {
    for name in ["break.json", "galperin.json"] {
        let path = example(name);
        let full = sim(&[&path], None);
        let summary = sim(&[&path, "--summary"], None);
        assert!(
            summary.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&summary.stderr)
        );
        let full: serde_json::Value = serde_json::from_slice(&full.stdout).unwrap();
        let summary: serde_json::Value = serde_json::from_slice(&summary.stdout).unwrap();
        let listed = full["events"].as_array().unwrap().len() as u64;
        assert_eq!(summary["events"].as_u64(), Some(listed), "{name}");
        for key in ["collisions", "pressed", "collapses", "end", "bodies"] {
            assert_eq!(summary[key], full[key], "{name}: {key}");
        }
    }
    let galperin = sim(&[&example("galperin.json"), "--summary"], None);
    let json: serde_json::Value = serde_json::from_slice(&galperin.stdout).unwrap();
    assert_eq!(json["collisions"].as_u64(), Some(31415));
    assert_eq!(json["end"]["reason"], "free");
}

#[test]
fn sim_rejects_an_invalid_scene_with_exit_status_2_naming_the_field() {
    let body = |fields: &str| {
        format!(r#"{{"bodies": [{{"id": 4, "pos": [0, 0], "vel": [1, 0], {fields}}}]}}"#)
    };
    let cases = [
        (body(r#""radius": 0.1, "mass": 0.0, "mu": 0.2"#), "mass"),
        (body(r#""radius": -1.0, "mass": 1.0, "mu": 0.2"#), "radius"),
        (body(r#""radius": 0.1, "mass": 1.0, "mu": -0.5"#), "mu"),
        (body(r#""radius": 0.1, "mu": 0.2"#), "mass"),
        (
            body(r#""radius": 0.1, "mass": 1.0, "mu": 0.2, "restitution": 2.0"#),
            "restitution",
        ),
    ];
    for (text, field) in &cases {
        let out = sim(&["-"], Some(text));
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{text}: {stderr}");
        assert!(
            stderr.contains(field),
            "{text}: the message must name {field}: {stderr}"
        );
        assert!(
            stderr.contains("bodies[0]"),
            "{text}: the message must name the body: {stderr}"
        );
        assert!(out.stdout.is_empty());
    }
    let out = sim(&["-"], Some(r#"{ "bodies": 3 }"#));
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("bodies"));
}

// ---------------------------------------------------------------------------
// Broad phase
// ---------------------------------------------------------------------------

#[test]
fn grid_broad_phase_gives_the_same_events_as_all_pairs_for_200_discs() {
    let sc = lattice_scene(200, 2024, 0.3, 0.9, 1.0);
    let mut logs = Vec::new();
    for broad_phase in [BroadPhase::AllPairs, BroadPhase::Grid] {
        let config = WorldConfig {
            broad_phase,
            ..WorldConfig::default()
        };
        let mut world = World::new(&sc, config).unwrap();
        let mut log = Log::default();
        let end = world.run(&Limits::default(), &mut log);
        assert_eq!(end.reason, EndReason::Rest, "{broad_phase:?}");
        logs.push(log.0);
    }
    assert!(
        collisions(&logs[0]) > 100,
        "the scene must be busy: {}",
        logs[0].len()
    );
    assert_same_events(&logs[0], &logs[1], 1e-9);
}

#[test]
fn recomputing_every_body_after_every_event_gives_the_same_events_as_the_calendar() {
    let sc = lattice_scene(60, 7, 0.3, 0.9, 1.0);
    let mut logs = Vec::new();
    for recompute_all in [false, true] {
        let config = WorldConfig {
            recompute_all,
            ..WorldConfig::default()
        };
        let mut world = World::new(&sc, config).unwrap();
        let mut log = Log::default();
        let end = world.run(&Limits::default(), &mut log);
        assert_eq!(
            end.reason,
            EndReason::Rest,
            "recompute_all = {recompute_all}"
        );
        logs.push(log.0);
    }
    assert!(collisions(&logs[0]) > 20, "the scene must be busy");
    assert_same_events(&logs[0], &logs[1], 1e-9);
}
