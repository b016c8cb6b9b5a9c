//! The world: the live state of a computation and the loop that advances it
//! from event to event.
//!
//! Each body keeps its own [`Trajectory`]; the [`Calendar`] holds, for every
//! body, its own earliest predicted event. Processing an event rewrites only
//! the trajectories of the bodies involved, bumps their generation counters
//! and re-predicts just those bodies against their neighbours (all bodies,
//! or the 3x3 cells of the [`Grid`] broad phase). A prediction made against
//! a partner whose generation has since changed is stale; it is noticed when
//! it reaches the top of the calendar and the body is re-predicted then.
//! Bodies at rest are never advanced; a resting body is only looked at when
//! something happens next to it.
//!
//! Rules plug in through [`EventHandler`]: the game decides what happens to
//! a disc whose centre leaves the board (a sensor line).

use crate::calendar::Calendar;
use crate::contact::{self, LineHit};
use crate::event::{Event, EventKind};
use crate::grid::{Grid, Step};
use crate::id::{BodyId, LineId, PointId};
use crate::impulse;
use crate::obstacle::{Line, LineGeom, Point};
use crate::roots::Method;
use crate::scene::{BodySpec, Scene, SceneError};
use crate::trajectory::Trajectory;
use glam::DVec2;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// What the rules decide for a disc whose centre left a region.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExitResponse {
    /// The disc carries on (the engine's default).
    Stay,
    /// The disc leaves the scene now and takes no further part.
    Remove,
}

/// Rules and observers plugged into a computation.
///
/// `on_event` is the one required method; `()` implements it as a no-op.
pub trait EventHandler {
    /// Called after each event has been applied; `world` shows the state
    /// right after it. Must not assume anything about later events.
    fn on_event(&mut self, world: &World, event: &Event);

    /// Called when the centre of `body` crosses the sensor `line` from its
    /// inside (left) to its outside, at time `t`, before the event is
    /// recorded. Return [`ExitResponse::Remove`] to take the disc out of the
    /// scene at that moment. The default keeps it.
    fn on_region_exit(&mut self, _t: f64, _body: BodyId, _line: LineId) -> ExitResponse {
        ExitResponse::Stay
    }
}

impl EventHandler for () {
    fn on_event(&mut self, _world: &World, _event: &Event) {}
}

/// Counts events (the handler the benchmarks use).
#[derive(Clone, Copy, Debug, Default)]
pub struct Counter {
    pub events: u64,
    pub collisions: u64,
}

impl EventHandler for Counter {
    #[inline]
    fn on_event(&mut self, _world: &World, event: &Event) {
        self.events += 1;
        self.collisions += event.kind.is_collision() as u64;
    }
}

/// Which pairs of bodies are considered.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BroadPhase {
    /// Every pair (best for a handful of bodies).
    AllPairs,
    /// A uniform grid with cell-crossing events.
    Grid,
    /// The grid above 32 bodies, every pair below.
    #[default]
    Auto,
}

/// How a computation is done (not what is computed).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct WorldConfig {
    #[serde(skip)]
    pub solver: Method,
    pub broad_phase: BroadPhase,
}

/// When to stop a run.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Limits {
    /// Compute no further than this time.
    pub until: f64,
    /// Stop after this many collisions in this run.
    pub max_collisions: u64,
    /// Stop after this many events in this run (the hard cap).
    pub max_events: u64,
}

/// The hard cap on events when no other is given.
pub const DEFAULT_MAX_EVENTS: u64 = 10_000_000;

impl Default for Limits {
    fn default() -> Self {
        Limits {
            until: f64::INFINITY,
            max_collisions: u64::MAX,
            max_events: DEFAULT_MAX_EVENTS,
        }
    }
}

/// Why a run stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum EndReason {
    /// Nothing moves and nothing is pending.
    Rest,
    /// Bodies still move without friction, but no event can ever happen.
    Free,
    /// The time horizon was reached.
    Until,
    /// The collision limit was reached.
    MaxCollisions,
    /// The event cap was reached.
    MaxEvents,
}

/// Where and why a run stopped.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct End {
    pub t: f64,
    pub reason: EndReason,
}

/// Running totals of a world.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Stats {
    pub events: u64,
    pub body_body: u64,
    pub body_line: u64,
    pub body_point: u64,
    pub stops: u64,
    pub region_exits: u64,
    /// Calendar entries found stale and re-predicted.
    pub stale: u64,
    /// Grid cell crossings.
    pub cell_crossings: u64,
}

impl Stats {
    /// Body–body, body–line and body–point events.
    pub fn collisions(&self) -> u64 {
        self.body_body + self.body_line + self.body_point
    }
}

/// The material of a disc (what does not change as it moves).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Material {
    pub radius: f64,
    pub mass: f64,
    pub mu: f64,
    pub restitution: f64,
}

impl Material {
    /// The material of a scene body.
    pub fn of(spec: &BodySpec) -> Self {
        Material {
            radius: spec.radius,
            mass: spec.mass,
            mu: spec.mu,
            restitution: spec.restitution,
        }
    }
}

/// A body as the world holds it: who, what, and how it moves.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct BodyState {
    pub id: BodyId,
    pub material: Material,
    pub trajectory: Trajectory,
}

impl BodyState {
    /// The body as a scene would describe it at time `t`.
    pub fn spec_at(&self, t: f64) -> BodySpec {
        BodySpec {
            id: self.id,
            pos: self.trajectory.position(t),
            vel: self.trajectory.velocity(t),
            radius: self.material.radius,
            mass: self.material.mass,
            mu: self.material.mu,
            restitution: self.material.restitution,
        }
    }
}

/// The earliest predicted event of one body.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Next {
    None,
    Stop,
    Body { other: u32, other_gen: u32 },
    Point(u32),
    Line(u32, Option<u8>),
    Sensor { line: u32, bit: u8, reported: bool },
    Cell(Step),
}

/// A body's pair whose time is already known (or is to be reported).
type Known = Option<(usize, Option<Option<f64>>)>;

/// The best candidate so far for a body's next event.
#[derive(Clone, Copy, Debug)]
struct Best {
    t: f64,
    next: Next,
}

impl Best {
    /// Keeps `(t, next)` if it is strictly earlier (the first offered wins ties).
    #[inline(always)]
    fn offer(&mut self, t: f64, next: Next) {
        if t < self.t {
            self.t = t;
            self.next = next;
        }
    }
}

/// The live state of a computation.
#[derive(Clone, Debug)]
pub struct World {
    t: f64,
    last_event_t: f64,
    g: f64,
    config: WorldConfig,
    ids: Vec<BodyId>,
    slot_of: HashMap<BodyId, usize>,
    material: Vec<Material>,
    traj: Vec<Trajectory>,
    gen: Vec<u32>,
    alive: Vec<bool>,
    /// Bit k set: the centre is inside (left of) sensor k.
    sides: Vec<u64>,
    next: Vec<Next>,
    calendar: Calendar,
    points: Vec<Point>,
    lines: Vec<Line>,
    geoms: Vec<LineGeom>,
    solid: Vec<u32>,
    sensors: Vec<u32>,
    grid: Option<Grid>,
    stats: Stats,
}

impl World {
    /// A world at the scene's time, after validating the scene.
    pub fn new(scene: &Scene, config: WorldConfig) -> Result<World, SceneError> {
        scene.validate()?;
        let bodies = scene
            .bodies
            .iter()
            .map(|b| BodyState {
                id: b.id,
                material: Material::of(b),
                trajectory: Trajectory::new(scene.t, b.pos, b.vel, b.mu * scene.g),
            })
            .collect();
        Ok(World::from_parts(
            scene.t,
            scene.g,
            bodies,
            scene.points.clone(),
            scene.lines.clone(),
            config,
        ))
    }

    /// A world at time `t` from bodies with their own trajectories (kept as
    /// they are, so a rewound computation continues bit for bit). The parts
    /// must come from a validated scene.
    pub fn from_parts(
        t: f64,
        g: f64,
        bodies: Vec<BodyState>,
        points: Vec<Point>,
        lines: Vec<Line>,
        config: WorldConfig,
    ) -> World {
        let n = bodies.len();
        let geoms: Vec<LineGeom> = lines
            .iter()
            .map(|l| LineGeom::new(l).expect("validated scenes have no degenerate lines"))
            .collect();
        let solid = (0..lines.len() as u32)
            .filter(|&k| !lines[k as usize].sensor)
            .collect();
        let sensors: Vec<u32> = (0..lines.len() as u32)
            .filter(|&k| lines[k as usize].sensor)
            .collect();
        let mut w = World {
            t,
            last_event_t: t,
            g,
            config,
            ids: bodies.iter().map(|b| b.id).collect(),
            slot_of: bodies.iter().enumerate().map(|(i, b)| (b.id, i)).collect(),
            material: bodies.iter().map(|b| b.material).collect(),
            traj: bodies.iter().map(|b| b.trajectory).collect(),
            gen: vec![0; n],
            alive: vec![true; n],
            sides: vec![0; n],
            next: vec![Next::None; n],
            calendar: Calendar::new(n),
            points,
            lines,
            geoms,
            solid,
            sensors,
            grid: None,
            stats: Stats::default(),
        };
        for i in 0..n {
            let p = w.traj[i].position(t);
            for (bit, &k) in w.sensors.iter().enumerate() {
                if w.geoms[k as usize].signed_distance(p) >= 0.0 {
                    w.sides[i] |= 1 << bit;
                }
            }
        }
        let use_grid = match config.broad_phase {
            BroadPhase::AllPairs => false,
            BroadPhase::Grid => true,
            BroadPhase::Auto => n > 32,
        };
        if use_grid && n > 0 {
            w.grid = Some(w.build_grid());
        }
        for i in 0..n {
            w.predict(i);
        }
        w
    }

    fn build_grid(&self) -> Grid {
        let t = self.t;
        let mut lo = DVec2::splat(f64::INFINITY);
        let mut hi = DVec2::splat(f64::NEG_INFINITY);
        let mut max_r: f64 = 0.0;
        for (i, tr) in self.traj.iter().enumerate() {
            let p = tr.position(t);
            let stop = if tr.stop_time().is_finite() {
                tr.position(tr.stop_time())
            } else {
                p
            };
            let r = self.material[i].radius;
            for q in [p, stop] {
                lo = lo.min(q - r);
                hi = hi.max(q + r);
            }
            max_r = max_r.max(r);
        }
        for l in &self.lines {
            lo = lo.min(l.a).min(l.b);
            hi = hi.max(l.a).max(l.b);
        }
        let n = self.traj.len();
        let mut grid = Grid::new(lo, hi, 2.0 * max_r * (1.0 + 1e-9), 2 * n);
        for (i, tr) in self.traj.iter().enumerate() {
            grid.insert(i, tr.position(t));
        }
        grid
    }

    /// Current time: where the computation stands.
    pub fn time(&self) -> f64 {
        self.t
    }

    /// Time of the last event processed.
    pub fn last_event_time(&self) -> f64 {
        self.last_event_t
    }

    /// Gravity.
    pub fn g(&self) -> f64 {
        self.g
    }

    /// Totals so far.
    pub fn stats(&self) -> &Stats {
        &self.stats
    }

    /// The points.
    pub fn points(&self) -> &[Point] {
        &self.points
    }

    /// The lines.
    pub fn lines(&self) -> &[Line] {
        &self.lines
    }

    /// The bodies still in the scene, in the order they were given.
    pub fn bodies(&self) -> impl Iterator<Item = BodyState> + '_ {
        (0..self.ids.len())
            .filter(|&i| self.alive[i])
            .map(|i| BodyState {
                id: self.ids[i],
                material: self.material[i],
                trajectory: self.traj[i],
            })
    }

    /// One body still in the scene.
    pub fn body(&self, id: BodyId) -> Option<BodyState> {
        let &i = self.slot_of.get(&id)?;
        self.alive[i].then(|| BodyState {
            id,
            material: self.material[i],
            trajectory: self.traj[i],
        })
    }

    /// The scene at time `t >= last_event_time()` (positions and velocities
    /// from the current trajectories).
    pub fn scene_at(&self, t: f64) -> Scene {
        Scene {
            g: self.g,
            t,
            bodies: self.bodies().map(|b| b.spec_at(t)).collect(),
            points: self.points.clone(),
            lines: self.lines.clone(),
        }
    }

    /// Whether any body still moves at the current time.
    pub fn any_moving(&self) -> bool {
        (0..self.ids.len()).any(|i| self.alive[i] && self.traj[i].is_moving_at(self.t))
    }

    /// Advances the computation until a limit is reached or nothing more can
    /// happen, telling `handler` about every event.
    pub fn run<H: EventHandler + ?Sized>(&mut self, limits: &Limits, handler: &mut H) -> End {
        let mut events = 0u64;
        let mut collisions = 0u64;
        loop {
            let Some((slot, t)) = self.calendar.peek() else {
                return self.end_at_rest();
            };
            if t == f64::INFINITY {
                return self.end_at_rest();
            }
            if t > limits.until {
                self.t = self.t.max(limits.until);
                return End {
                    t: limits.until,
                    reason: EndReason::Until,
                };
            }
            if events >= limits.max_events {
                return End {
                    t: self.last_event_t,
                    reason: EndReason::MaxEvents,
                };
            }
            if collisions >= limits.max_collisions {
                return End {
                    t: self.last_event_t,
                    reason: EndReason::MaxCollisions,
                };
            }
            if let Some(event) = self.process(slot, t, handler) {
                events += 1;
                collisions += event.kind.is_collision() as u64;
                handler.on_event(self, &event);
            }
        }
    }

    /// Processes calendar entries until one real event happens (or none can
    /// before `until`), and returns it.
    pub fn step<H: EventHandler + ?Sized>(&mut self, until: f64, handler: &mut H) -> Option<Event> {
        loop {
            let (slot, t) = self.calendar.peek()?;
            if t == f64::INFINITY || t > until {
                return None;
            }
            if let Some(event) = self.process(slot, t, handler) {
                handler.on_event(self, &event);
                return Some(event);
            }
        }
    }

    fn end_at_rest(&self) -> End {
        let reason = if self.any_moving() {
            EndReason::Free
        } else {
            EndReason::Rest
        };
        End {
            t: self.last_event_t,
            reason,
        }
    }

    /// Handles the calendar entry of `i` at time `t`; returns the event if a
    /// real one happened (stale entries and cell crossings are internal).
    fn process<H: EventHandler + ?Sized>(
        &mut self,
        i: usize,
        t: f64,
        handler: &mut H,
    ) -> Option<Event> {
        self.t = t;
        let kind = match self.next[i] {
            Next::None => {
                self.calendar.set(i, f64::INFINITY);
                return None;
            }
            Next::Body { other, other_gen } => {
                let j = other as usize;
                if !self.alive[j] || self.gen[j] != other_gen {
                    self.stats.stale += 1;
                    self.predict(i);
                    return None;
                }
                self.collide(i, j, t);
                self.stats.body_body += 1;
                EventKind::BodyBody {
                    a: self.ids[i],
                    b: self.ids[j],
                }
            }
            Next::Stop => {
                let p = self.traj[i].position(t);
                self.traj[i] = Trajectory::at_rest(t, p, self.traj[i].alpha());
                self.changed(i);
                self.stats.stops += 1;
                EventKind::Stop { body: self.ids[i] }
            }
            Next::Line(k, end) => {
                let geom = self.geoms[k as usize];
                let p = self.traj[i].position(t);
                let n = match end {
                    Some(e) => (p - geom.ends[e as usize].unwrap_or(p)).normalize_or_zero(),
                    None => {
                        if geom.signed_distance(p) >= 0.0 {
                            geom.n
                        } else {
                            -geom.n
                        }
                    }
                };
                self.bounce(i, t, n);
                self.stats.body_line += 1;
                EventKind::BodyLine {
                    body: self.ids[i],
                    line: LineId(k),
                    end,
                }
            }
            Next::Point(k) => {
                let p = self.traj[i].position(t);
                let n = (p - self.points[k as usize].pos).normalize_or_zero();
                self.bounce(i, t, n);
                self.stats.body_point += 1;
                EventKind::BodyPoint {
                    body: self.ids[i],
                    point: PointId(k),
                }
            }
            Next::Sensor {
                line,
                bit,
                reported,
            } => {
                let was_inside = self.sides[i] & (1 << bit) != 0;
                self.sides[i] ^= 1 << bit;
                if !reported {
                    self.predict(i);
                    return None;
                }
                let (body, line) = (self.ids[i], LineId(line));
                if !was_inside {
                    self.predict(i);
                    EventKind::RegionEntry { body, line }
                } else {
                    let removed = handler.on_region_exit(t, body, line) == ExitResponse::Remove;
                    if removed {
                        self.remove_slot(i, t);
                    } else {
                        self.predict(i);
                    }
                    self.stats.region_exits += 1;
                    EventKind::RegionExit {
                        body,
                        line,
                        removed,
                    }
                }
            }
            Next::Cell(step) => {
                self.stats.cell_crossings += 1;
                if let Some(grid) = self.grid.as_mut() {
                    grid.step(i, step);
                }
                self.predict(i);
                return None;
            }
        };
        self.last_event_t = t;
        self.stats.events += 1;
        Some(Event { t, kind })
    }

    fn collide(&mut self, i: usize, j: usize, t: f64) {
        let (pi, pj) = (self.traj[i].position(t), self.traj[j].position(t));
        let (vi, vj) = (self.traj[i].velocity(t), self.traj[j].velocity(t));
        let (mi, mj) = (&self.material[i], &self.material[j]);
        let n = (pi - pj).normalize_or_zero();
        let e = mi.restitution.min(mj.restitution);
        let (vi, vj) = impulse::body_body(vi, vj, mi.mass, mj.mass, e, n);
        self.traj[i] = Trajectory::new(t, pi, vi, self.traj[i].alpha());
        self.traj[j] = Trajectory::new(t, pj, vj, self.traj[j].alpha());
        self.gen[i] = self.gen[i].wrapping_add(1);
        self.gen[j] = self.gen[j].wrapping_add(1);
        // The pair (i, j) is solved once, for both.
        let pair = self.predict_with(i, Some((j, None)));
        self.predict_with(j, Some((i, pair)));
    }

    fn bounce(&mut self, i: usize, t: f64, n: DVec2) {
        let p = self.traj[i].position(t);
        let v = impulse::body_static(self.traj[i].velocity(t), self.material[i].restitution, n);
        self.traj[i] = Trajectory::new(t, p, v, self.traj[i].alpha());
        self.changed(i);
    }

    /// `i`'s trajectory was replaced: invalidate others' predictions about it
    /// and predict it afresh.
    fn changed(&mut self, i: usize) {
        self.gen[i] = self.gen[i].wrapping_add(1);
        self.predict(i);
    }

    fn remove_slot(&mut self, i: usize, t: f64) {
        self.alive[i] = false;
        self.gen[i] = self.gen[i].wrapping_add(1);
        self.traj[i] = Trajectory::at_rest(t, self.traj[i].position(t), 0.0);
        self.next[i] = Next::None;
        self.calendar.set(i, f64::INFINITY);
        if let Some(grid) = self.grid.as_mut() {
            grid.remove(i);
        }
    }

    /// Recomputes the earliest event of body `i` from the current time.
    fn predict(&mut self, i: usize) {
        self.predict_with(i, None);
    }

    /// As `predict`; with `known = Some((j, t))` the pair `(i, j)` is not
    /// solved if `t` is given (it was, for `j`), and its time is returned.
    fn predict_with(&mut self, i: usize, known: Known) -> Option<Option<f64>> {
        let (best, pair) = self.earliest(i, known);
        self.next[i] = best.next;
        self.calendar.set(i, best.t);
        pair
    }

    /// The earliest event of body `i` from the current time (and the time
    /// of its pair with `known`'s body, if that was asked for).
    fn earliest(&self, i: usize, known: Known) -> (Best, Option<Option<f64>>) {
        let now = self.t;
        let tr = &self.traj[i];
        let r = self.material[i].radius;
        let moving = tr.is_moving_at(now);
        let mut best = Best {
            t: f64::INFINITY,
            next: Next::None,
        };
        let mut pair = None;
        match &self.grid {
            Some(grid) => {
                for cell in grid.neighbour_cells(i) {
                    for &j in cell {
                        self.offer_pair(i, j as usize, moving, known, &mut best, &mut pair);
                    }
                }
            }
            None => {
                for j in 0..self.traj.len() {
                    self.offer_pair(i, j, moving, known, &mut best, &mut pair);
                }
            }
        }
        if !moving {
            return (best, pair);
        }
        for &k in &self.solid {
            if let Some(LineHit { t, end }) =
                contact::disc_line(tr, &self.geoms[k as usize], r, now)
            {
                best.offer(t, Next::Line(k, end));
            }
        }
        for (k, p) in self.points.iter().enumerate() {
            if let Some(t) = contact::disc_point(tr, p.pos, r, now) {
                best.offer(t, Next::Point(k as u32));
            }
        }
        for (bit, &k) in self.sensors.iter().enumerate() {
            let inside = self.sides[i] & (1 << bit) != 0;
            if let Some((t, reported)) =
                contact::centre_crossing(tr, &self.geoms[k as usize], inside, now)
            {
                let bit = bit as u8;
                best.offer(
                    t,
                    Next::Sensor {
                        line: k,
                        bit,
                        reported,
                    },
                );
            }
        }
        best.offer(tr.stop_time(), Next::Stop);
        if let Some(grid) = &self.grid {
            if let Some((t, step)) = grid.next_crossing(i, tr, now) {
                best.offer(t, Next::Cell(step));
            }
        }
        (best, pair)
    }

    /// Offers the contact of bodies `i` and `j` as `i`'s next event.
    #[inline(always)]
    fn offer_pair(
        &self,
        i: usize,
        j: usize,
        i_moving: bool,
        known: Known,
        best: &mut Best,
        pair: &mut Option<Option<f64>>,
    ) {
        if j == i || !self.alive[j] {
            return;
        }
        let now = self.t;
        let tj = &self.traj[j];
        if !i_moving && !tj.is_moving_at(now) {
            return;
        }
        let hit = match known {
            Some((k, Some(t))) if k == j => t,
            _ => {
                let s = self.material[i].radius + self.material[j].radius;
                let t = contact::disc_disc(&self.traj[i], tj, s, now, &self.config.solver);
                if matches!(known, Some((k, None)) if k == j) {
                    *pair = Some(t);
                }
                t
            }
        };
        if let Some(t) = hit {
            best.offer(
                t,
                Next::Body {
                    other: j as u32,
                    other_gen: self.gen[j],
                },
            );
        }
    }
}
