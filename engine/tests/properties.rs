//! Property tests on random scenes: discs of random size, mass, friction
//! and restitution with random velocities in a box of segments (with a few
//! fixed points), checked after every event against the invariants of
//! `docs/model.md`:
//!
//! - no two discs overlap, no disc crosses a solid line or a point;
//! - every contact happens at contact distance;
//! - every body-body impulse conserves momentum, and kinetic energy when
//!   elastic; the relative normal speed is scaled by `-e`;
//! - every obstacle impulse keeps the tangential velocity and scales the
//!   normal one by `-e`;
//! - bodies an event does not involve keep their trajectories exactly;
//! - between events kinetic energy falls by the friction work
//!   `sum mu m g * distance`;
//! - nothing is NaN, time never goes back, and every run ends within its cap.

use engine::model::Model;
use engine::world::{BodyState, BroadPhase};
use engine::{
    BodyId, BodySpec, EndReason, Event, EventHandler, EventKind, Limits, Line, LineKind, Point,
    Scene, World, WorldConfig,
};
use glam::DVec2;
use proptest::prelude::*;
use proptest::test_runner::Config;
use std::collections::HashMap;

/// Relative tolerance of geometric and conservation checks.
const TOL: f64 = 1e-9;

/// Speeds below this are not resolved: squares of them underflow (a disc
/// with e < 1 and no friction trapped in a small gap slows down that far;
/// see `very_slow_frictionless_disc_does_not_hit_a_far_away_disc`).
const TINY_SPEED: f64 = 1e-140;

/// Lattice of 5 x 5 cells of side 0.2 over the unit box.
const CELLS: usize = 5;
const CELL: f64 = 1.0 / CELLS as f64;

#[derive(Clone, Debug)]
struct DiscParams {
    jitter: (f64, f64),
    radius: f64,
    log_mass: f64,
    mu: f64,
    restitution: f64,
    vel: (f64, f64),
}

/// With `friction`, mu is 0 or in [0.05, 0.5]; without, always 0.
fn disc_params(friction: bool) -> impl Strategy<Value = DiscParams> {
    let max_mu = if friction { 0.5 } else { 0.0 };
    (
        (-1.0..1.0f64, -1.0..1.0f64),
        0.01..0.09f64,
        -1.0..1.0f64,
        prop_oneof![
            Just(0.0),
            (0.05..=0.5f64).prop_map(move |mu| mu.min(max_mu))
        ],
        prop_oneof![Just(1.0), 0.3..1.0f64],
        (-3.0..3.0f64, -3.0..3.0f64),
    )
        .prop_map(
            |(jitter, radius, log_mass, mu, restitution, vel)| DiscParams {
                jitter,
                radius,
                log_mass,
                mu,
                restitution,
                vel,
            },
        )
}

fn square() -> Vec<Line> {
    let c = [
        DVec2::new(0.0, 0.0),
        DVec2::new(1.0, 0.0),
        DVec2::new(1.0, 1.0),
        DVec2::new(0.0, 1.0),
    ];
    (0..4)
        .map(|k| Line::new(c[k], c[(k + 1) % 4], LineKind::Segment))
        .collect()
}

fn cell_centre(k: usize) -> DVec2 {
    DVec2::new(
        ((k % CELLS) as f64 + 0.5) * CELL,
        ((k / CELLS) as f64 + 0.5) * CELL,
    )
}

/// Discs in distinct cells of the lattice (so they never overlap at the
/// start), fixed points at the centres of some other cells.
fn arb_scene(max_discs: usize, friction: bool) -> impl Strategy<Value = Scene> {
    (2..=max_discs, 0..=3usize)
        .prop_flat_map(move |(n, n_points)| {
            (
                proptest::sample::subsequence((0..CELLS * CELLS).collect::<Vec<_>>(), n + n_points)
                    .prop_shuffle(),
                proptest::collection::vec(disc_params(friction), n),
                Just(n_points),
            )
        })
        .prop_map(|(cells, discs, n_points)| {
            let bodies = discs
                .iter()
                .zip(&cells)
                .enumerate()
                .map(|(i, (d, &k))| {
                    let room = (0.5 * CELL - d.radius) * 0.9;
                    let pos = cell_centre(k) + DVec2::new(d.jitter.0, d.jitter.1) * room;
                    BodySpec::new(i as u64, pos, d.radius, 10f64.powf(d.log_mass), d.mu)
                        .with_velocity(DVec2::new(d.vel.0, d.vel.1))
                        .with_restitution(d.restitution)
                })
                .collect();
            let points = cells[discs.len()..discs.len() + n_points]
                .iter()
                .map(|&k| Point {
                    pos: cell_centre(k),
                })
                .collect();
            Scene {
                g: 9.81,
                t: 0.0,
                bodies,
                points,
                lines: square(),
            }
        })
}

/// The scene with every frictionless disc given mu = 0.1.
fn with_friction(mut scene: Scene) -> Scene {
    for b in &mut scene.bodies {
        if b.mu == 0.0 {
            b.mu = 0.1;
        }
    }
    scene
}

fn arb_broad_phase() -> impl Strategy<Value = BroadPhase> {
    prop_oneof![Just(BroadPhase::AllPairs), Just(BroadPhase::Grid)]
}

/// Distance from `x` to the segment `[a, b]`, and the nearest point.
fn to_segment(x: DVec2, a: DVec2, b: DVec2) -> (f64, DVec2) {
    let ab = b - a;
    let s = ((x - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
    let q = a + ab * s;
    ((x - q).length(), q)
}

fn kinetic(m: f64, v: DVec2) -> f64 {
    0.5 * m * v.length_squared()
}

/// Checks every invariant after every event; records the first violation.
struct Checker {
    prev_t: f64,
    prev: HashMap<BodyId, BodyState>,
    events: u64,
    failure: Option<String>,
    /// Collapses the world had taken at the last event.
    collapses: u64,
}

impl Checker {
    /// How far a velocity at absolute time `t` is known: alpha ulp(t).
    fn time_slack(&self, id: &BodyId, t: f64) -> f64 {
        8.0 * f64::EPSILON * self.prev[id].trajectory.alpha() * t.max(1.0)
    }

    fn new(world: &World) -> Self {
        Checker {
            prev_t: world.time(),
            prev: world.bodies().map(|b| (b.id, b)).collect(),
            events: 0,
            failure: None,
            collapses: 0,
        }
    }

    fn check(&mut self, world: &World, event: &Event) -> Result<(), String> {
        let t = event.t;
        if !t.is_finite() || t < self.prev_t {
            return Err(format!("time went from {} to {t}", self.prev_t));
        }
        let now: HashMap<BodyId, BodyState> = world.bodies().map(|b| (b.id, b)).collect();
        let involved: Vec<BodyId> = event.kind.bodies().collect();

        // No NaN; untouched bodies keep their trajectories: bit for bit,
        // except where revision 7's clock moved its origin at this event,
        // which re-expresses every trajectory's start from the new origin
        // (a rounding of its start time, see engine/src/clock.rs): then
        // the motion itself must stay the same to far below a nanometre.
        for (id, b) in &now {
            let (p, v) = (b.trajectory.position(t), b.trajectory.velocity(t));
            if !(p.is_finite() && v.is_finite()) {
                return Err(format!("{id} is not finite: {p} {v}"));
            }
            if involved.contains(id) {
                continue;
            }
            let same = match self.prev.get(id) {
                Some(before) if before == b => true,
                Some(before) => {
                    let (bp, bv) = (before.trajectory.position(t), before.trajectory.velocity(t));
                    (bp - p).length() <= 1e-12 * (1.0 + p.length())
                        && (bv - v).length() <= 1e-12 * (1.0 + v.length())
                }
                None => false,
            };
            if !same {
                return Err(format!(
                    "{id} is not in the event but its trajectory changed"
                ));
            }
        }

        // Friction work between the previous event and this one.
        let g = world.g();
        let (mut ke_then, mut ke_now, mut work, mut slack) = (0.0, 0.0, 0.0, 0.0);
        for b in self.prev.values() {
            let (m, tr) = (b.material.mass, &b.trajectory);
            let (v_then, v_now) = (tr.velocity(self.prev_t), tr.velocity(t));
            let (p_then, p_now) = (tr.position(self.prev_t), tr.position(t));
            ke_then += kinetic(m, v_then);
            ke_now += kinetic(m, v_now);
            let path = (p_now - p_then).length();
            let friction = b.material.mu * m * g;
            work += friction * path;
            // Times are absolute: a speed is known to alpha * ulp(t), a
            // position to ulp(p).
            slack += 8.0
                * f64::EPSILON
                * (m * v_then.length() * tr.alpha() * t.max(1.0)
                    + friction * (p_then.length() + p_now.length()));
        }
        if (ke_then - ke_now - work).abs() > TOL * ke_then + slack {
            return Err(format!(
                "between {} and {t}: kinetic energy fell by {:e}, friction work {work:e}",
                self.prev_t,
                ke_then - ke_now
            ));
        }

        // The impulse of this event.
        let pre = |id: &BodyId| -> Result<(DVec2, DVec2, f64, f64), String> {
            let b = self.prev.get(id).ok_or(format!("{id} appeared"))?;
            Ok((
                b.trajectory.position(t),
                b.trajectory.velocity(t),
                b.material.mass,
                b.material.restitution,
            ))
        };
        // The velocity the impulse gave: the start of the new trajectory.
        // (Its velocity at `t` itself may already be zero: a disc given a
        // speed below alpha * ulp(t) stops within the rounding of t.)
        let post = |id: &BodyId| -> Result<DVec2, String> {
            let b = now.get(id).ok_or(format!("{id} vanished"))?;
            if b.trajectory.start_time() != t {
                return Err(format!(
                    "{id} is in the event but its trajectory did not restart"
                ));
            }
            Ok(b.trajectory.start_velocity())
        };
        match event.kind {
            EventKind::BodyBody { a, b } => {
                let (pa, va, ma, ea) = pre(&a)?;
                let (pb, vb, mb, eb) = pre(&b)?;
                let (ua, ub) = (post(&a)?, post(&b)?);
                let (ra, rb) = (now[&a].material.radius, now[&b].material.radius);
                let d = (pa - pb).length();
                if (d - (ra + rb)).abs() > TOL * (ra + rb) {
                    return Err(format!(
                        "{a} and {b} collide at distance {d}, not {}",
                        ra + rb
                    ));
                }
                let p0 = va * ma + vb * mb;
                let p1 = ua * ma + ub * mb;
                let scale = ma * va.length() + mb * vb.length();
                if (p0 - p1).length() > TOL * scale {
                    return Err(format!(
                        "momentum {p0} became {p1}: masses {ma} {mb}, {va} {vb} -> {ua} {ub}"
                    ));
                }
                let (k0, k1) = (
                    kinetic(ma, va) + kinetic(mb, vb),
                    kinetic(ma, ua) + kinetic(mb, ub),
                );
                let e = ea.min(eb);
                if e == 1.0 && (k0 - k1).abs() > TOL * k0 {
                    return Err(format!("elastic hit: energy {k0:e} became {k1:e}"));
                }
                if k1 > k0 * (1.0 + TOL) {
                    return Err(format!("a hit created energy: {k0:e} -> {k1:e}"));
                }
                let n = (pa - pb) / d;
                let (w0, w1) = ((va - vb).dot(n), (ua - ub).dot(n));
                // Velocities are known to about eps |v|, and to alpha ulp(t)
                // (absolute times): a contact may be found approaching by
                // that much and then seen separating by that much.
                let alphas = self.prev[&a].trajectory.alpha() + self.prev[&b].trajectory.alpha();
                let rel = TOL * (va.length() + vb.length()).max(TINY_SPEED)
                    + 8.0 * f64::EPSILON * alphas * t.max(1.0);
                if w0 > rel {
                    return Err(format!(
                        "{a} and {b} collided while separating (w = {w0:e}): \
                         {pa} {va} (m {ma}, alpha {}) and {pb} {vb} (m {mb}, alpha {}), \
                         gap {:e}",
                        self.prev[&a].trajectory.alpha(),
                        self.prev[&b].trajectory.alpha(),
                        d - (ra + rb)
                    ));
                }
                if w0 < 0.0 && (w1 + e * w0).abs() > rel {
                    return Err(format!("normal speed {w0:e} became {w1:e}, e = {e}"));
                }
                for (v0, v1, id) in [(va, ua, a), (vb, ub, b)] {
                    if (v1 - v0).perp_dot(n).abs() > rel {
                        return Err(format!("{id}: the impulse is not along the normal"));
                    }
                }
            }
            EventKind::BodyLine { body, line, end } => {
                let l = world.lines()[line.0 as usize];
                let (p, v, _, e) = pre(&body)?;
                let r = now[&body].material.radius;
                let (d, n) = match end {
                    None => {
                        let (d, q) = to_segment(p, l.a, l.b);
                        (d, (p - q) / d)
                    }
                    Some(k) => {
                        let q = if k == 0 { l.a } else { l.b };
                        ((p - q).length(), (p - q) / (p - q).length())
                    }
                };
                if (d - r).abs() > TOL * r {
                    return Err(format!(
                        "{body} hits {line} ({end:?}) at distance {d}, not {r}"
                    ));
                }
                let slack = self.time_slack(&body, t);
                obstacle_impulse(v, post(&body)?, n, e, slack)
                    .map_err(|m| format!("{body} on {line}: {m}"))?;
            }
            EventKind::BodyPoint { body, point } => {
                let q = world.points()[point.0 as usize].pos;
                let (p, v, _, e) = pre(&body)?;
                let r = now[&body].material.radius;
                let d = (p - q).length();
                if (d - r).abs() > TOL * r {
                    return Err(format!("{body} hits {point} at distance {d}, not {r}"));
                }
                let slack = self.time_slack(&body, t);
                obstacle_impulse(v, post(&body)?, (p - q) / d, e, slack)
                    .map_err(|m| format!("{body} on {point}: {m}"))?;
            }
            EventKind::Stop { body } => {
                let (_, v, _, _) = pre(&body)?;
                if v.length() > 1e-12 || now[&body].trajectory.velocity(t) != DVec2::ZERO {
                    return Err(format!("{body} stopped at speed {}", v.length()));
                }
            }
            other => return Err(format!("unexpected event {other:?}")),
        }

        // Nothing overlaps, nothing is through a wall or a point.
        let states: Vec<(BodyId, DVec2, f64)> = now
            .values()
            .map(|b| (b.id, b.trajectory.position(t), b.material.radius))
            .collect();
        for (i, &(id, p, r)) in states.iter().enumerate() {
            if !(0.0..=1.0).contains(&p.x) || !(0.0..=1.0).contains(&p.y) {
                return Err(format!("{id} left the box: {p}"));
            }
            for (k, l) in world.lines().iter().enumerate() {
                let (d, _) = to_segment(p, l.a, l.b);
                if d < r * (1.0 - TOL) {
                    return Err(format!(
                        "{id} overlaps lines[{k}]: distance {d}, radius {r}"
                    ));
                }
            }
            for (k, q) in world.points().iter().enumerate() {
                let d = (p - q.pos).length();
                if d < r * (1.0 - TOL) {
                    return Err(format!(
                        "{id} overlaps points[{k}]: distance {d}, radius {r}"
                    ));
                }
            }
            for &(other, q, s) in &states[i + 1..] {
                let d = (p - q).length();
                if d < (r + s) * (1.0 - TOL) {
                    return Err(format!(
                        "{id} and {other} overlap: distance {d}, radii {r} + {s}"
                    ));
                }
            }
        }
        Ok(())
    }
}

/// An obstacle (infinite mass) with normal `n` turns `v` into `u`: the
/// tangential part is kept, the normal part is scaled by `-e`.
fn obstacle_impulse(v: DVec2, u: DVec2, n: DVec2, e: f64, slack: f64) -> Result<(), String> {
    let w0 = v.dot(n);
    let noise = TOL * v.length().max(TINY_SPEED) + slack;
    if w0 > noise {
        return Err(format!("hit while moving away (w = {w0:e})"));
    }
    if (u.perp_dot(n) - v.perp_dot(n)).abs() > noise {
        return Err(format!("tangential velocity changed: {v} -> {u}"));
    }
    if w0 < 0.0 && (u.dot(n) + e * w0).abs() > noise {
        return Err(format!(
            "normal speed {w0:e} became {:e}, e = {e}",
            u.dot(n)
        ));
    }
    Ok(())
}

impl EventHandler for Checker {
    fn on_event(&mut self, world: &World, event: &Event) {
        self.events += 1;
        // A collapse taken to its limit with this event changed discs
        // besides its own and gave momentum to obstacles: this event is
        // not one impulse, and the checks start again from after it.
        let collapsed = world.stats().collapses != self.collapses;
        self.collapses = world.stats().collapses;
        if self.failure.is_none() && !collapsed {
            if let Err(msg) = self.check(world, event) {
                self.failure = Some(format!("event {} {event:?}: {msg}", self.events));
            }
        }
        self.prev_t = event.t;
        self.prev = world.bodies().map(|b| (b.id, b)).collect();
    }
}

/// Runs `scene` with the invariant checker.
fn check_invariants(scene: Scene, broad_phase: BroadPhase) -> Result<(), TestCaseError> {
    let cap = 5_000;
    let config = WorldConfig {
        broad_phase,
        ..WorldConfig::default()
    };
    let mut world = World::new(&scene, config).unwrap();
    let mut checker = Checker::new(&world);
    // A horizon too: frictionless discs with e < 1 slow down forever,
    // and absolute times lose precision as they grow.
    let limits = Limits {
        until: 1e4,
        max_events: cap,
        ..Limits::default()
    };
    let end = world.run(&limits, &mut checker);
    prop_assert!(checker.failure.is_none(), "{}", checker.failure.unwrap());
    prop_assert!(checker.events <= cap);
    prop_assert!(end.t.is_finite());
    prop_assert!(
        matches!(
            end.reason,
            EndReason::MaxEvents | EndReason::Until | EndReason::Rest
        ),
        "{:?}",
        end
    );
    if end.reason == EndReason::Rest {
        prop_assert!(!world.any_moving());
        for b in world.bodies() {
            prop_assert_eq!(b.trajectory.velocity(end.t), DVec2::ZERO);
        }
    }
    Ok(())
}

fn config() -> Config {
    Config {
        cases: 256,
        failure_persistence: None,
        ..Config::default()
    }
}

proptest! {
    #![proptest_config(config())]

    /// Every invariant holds after every event, and the run ends within
    /// its cap: at rest, on the event cap or on the horizon (never `free`:
    /// the box is closed).
    #[test]
    #[ignore = "not modelled: random discs with different friction can press together obliquely (a pushing contact off the line of centres makes them slide along each other and turn: no closed form); pushing along the line of centres is modelled (engine::push)"]
    fn invariants_hold_after_every_event(
        scene in arb_scene(10, true),
        broad_phase in arb_broad_phase(),
    ) {
        check_invariants(scene, broad_phase)?;
    }

    /// The same without friction (no stops, no pushing contacts).
    #[test]
    fn invariants_hold_after_every_event_without_friction(
        scene in arb_scene(10, false),
        broad_phase in arb_broad_phase(),
    ) {
        check_invariants(scene, broad_phase)?;
    }


    /// When every disc has friction, kinetic energy drains at a rate of at
    /// least `min(mu) g sqrt(2 min(m) E)`, so everything comes to rest in
    /// finite time: the run must end `rest`, well within a generous cap.
    #[test]
    #[ignore = "not modelled: oblique pushing contacts between discs of different friction (see engine::push); the collapse loop itself is fixed"]
    fn scenes_with_friction_come_to_rest(scene in arb_scene(10, true).prop_map(with_friction)) {
        let mut world = World::new(&scene, WorldConfig::default()).unwrap();
        let mut checker = Checker::new(&world);
        let end = world.run(&Limits { max_events: 100_000, ..Limits::default() }, &mut checker);
        prop_assert!(checker.failure.is_none(), "{}", checker.failure.unwrap());
        prop_assert_eq!(end.reason, EndReason::Rest, "after {} events", checker.events);
    }

    /// The same scene computed twice gives bit-identical events.
    #[test]
    fn runs_are_bit_identical(scene in arb_scene(8, true), broad_phase in arb_broad_phase()) {
        let config = WorldConfig { broad_phase, ..WorldConfig::default() };
        let limits = Limits { max_events: 2_000, ..Limits::default() };
        let mut runs = Vec::new();
        for _ in 0..2 {
            let mut world = World::new(&scene, config).unwrap();
            let mut log = Log::default();
            let end = world.run(&limits, &mut log);
            let finals: Vec<[u64; 4]> = world
                .bodies()
                .map(|b| {
                    let (p, v) = (b.trajectory.position(end.t), b.trajectory.velocity(end.t));
                    [p.x.to_bits(), p.y.to_bits(), v.x.to_bits(), v.y.to_bits()]
                })
                .collect();
            runs.push((log.0, end.t.to_bits(), finals));
        }
        prop_assert!(runs[0] == runs[1]);
    }

    /// Model queries: the diff between any two times turns one snapshot
    /// into the other, and `scene_at` is the snapshot's closed form.
    #[test]
    fn model_diffs_turn_one_snapshot_into_another(
        scene in arb_scene(6, true),
        picks in proptest::collection::vec((0.0..1.0f64, 0.0..1.0f64), 8),
    ) {
        let mut model = Model::new(scene).unwrap();
        model.compute(&Limits { max_events: 500, ..Limits::default() });
        let last = model.events().last().map_or(1.0, |e| e.t);
        for (a, b) in picks {
            let (a, b) = (a * last * 1.1, b * last * 1.1);
            let mut snap = model.snapshot_at(a);
            model.diff(a, b).apply(&mut snap);
            prop_assert_eq!(&snap, &model.snapshot_at(b), "diff({}, {})", a, b);
            prop_assert_eq!(model.scene_at(b), model.snapshot_at(b).scene_at(b));
        }
    }
}

/// Keeps event times as bits, so two runs compare exactly.
#[derive(Default)]
struct Log(Vec<(u64, EventKind)>);

impl EventHandler for Log {
    fn on_event(&mut self, _world: &World, event: &Event) {
        self.0.push((event.t.to_bits(), event.kind));
    }
}
