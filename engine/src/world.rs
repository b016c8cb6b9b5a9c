//! The world: the live state of a computation and the loop that advances it
//! from event to event.
//!
//! Each body keeps its own [`Trajectory`]; the `Calendar` holds, for every
//! body, its own earliest predicted event. Processing an event rewrites only
//! the trajectories of the bodies involved, bumps their generation counters
//! and re-predicts just those bodies against their neighbours (all bodies,
//! or the 3x3 cells of the `Grid` broad phase). A prediction made against
//! a partner whose generation has since changed is stale; it is noticed when
//! it reaches the top of the calendar and the body is re-predicted then.
//! Bodies at rest are never advanced; a resting body is only looked at when
//! something happens next to it.
//!
//! Rules plug in through [`EventHandler`] ([`handler`]): the game decides
//! what happens to a disc whose centre leaves the board (a sensor line).
//! When a run stops, and the guards that stop one with no finite answer,
//! are [`crate::limits`]'s; this module drives them.

mod cluster_ring;
mod corner_jam;
mod elastic_wall_ring;
pub mod handler;
mod reached_walls;
mod unmoved_kick;

pub use crate::limits::{End, EndReason, Limits};
pub use handler::{Counter, EventHandler, ExitResponse};

use crate::calendar::Calendar;
use crate::clock::Clock;
use crate::collapse;
use crate::contact::{self, Mover};
use crate::event::{Event, EventKind};
use crate::grid::{Grid, Step};
use crate::id::{BodyId, LineId, PointId};
use crate::impulse;
use crate::instant::same_instant;
use crate::limits::{
    snap, Crawl, Repeats, Watched, COLLAPSE_EVENTS, COLLAPSE_WINDOW, CRAWL_EVENTS,
    EARLY_REPEAT_HITS, EXACT_KICK_CLUSTER, FAR_FUTURE, GENTLE, KICK_SEARCHES_PER_INSTANT,
    MAX_COLLAPSE, MAX_COORDINATE, PRESS_ROUNDS, PRESS_SWEEPS, REPEAT_HITS, SETTLE, SNAP,
    STUCK_EVENTS, STUCK_EVENTS_PER_BODY,
};
use crate::obstacle::{Line, LineGeom, Point};
use crate::pivot;
use crate::push;
use crate::revision::Revision;
use crate::roots::Method;
use crate::scene::{BodySpec, Scene, SceneError};
use crate::trajectory::Trajectory;
use crate::wedge;
use glam::DVec2;
use serde::{Deserialize, Serialize};
use std::cell::Cell;

/// From the twelfth revision, the sine of the angle between two obstacles'
/// normals above which a disc touching both lies in a corner (see
/// `World::cornered_hit`): walls meeting at 30 degrees or more.
const CORNER_SINE: f64 = 0.5;

/// From the sixteenth revision, the largest part of its speed with which a
/// pushing disc may move across the line tangent to a disc pinned by its
/// walls and still be taken as sliding along it (see
/// `World::hit_along_wall`): a disc passing a curved side in a straight
/// line leaves it so, by 1.1e-7 of its speed a few microseconds after
/// they last met.
const PINNED_SLIDE: f64 = 1e-6;

/// From the twelfth revision, the fraction of the faster disc's speed under
/// which a plastic hit on a light disc in a corner approaches for it to be
/// taken with the walls (see `World::cornered_hit`): the rings it ends
/// approach at about a millionth of the speed of the disc sliding past
/// (mixed-box 1168, 49887, 98865), and a disc knocked into the corner is
/// left to its hits. A tenth of
/// `limits::GENTLE`: at that bound the rule also caught mixed-box 41699 in
/// its slide, which revision 11 brings to rest in 89,994 events and which
/// then ran to the event cap.
const CORNER_GENTLE: f64 = 1e-3;

/// From the thirteenth revision, the fraction of the faster disc's speed
/// beyond which a plastic hit drives a disc into an obstacle and its
/// partner back into it (see `World::hit_into_wall`): beyond the rounding
/// of the velocities the impulse forms.
const WALL_RING_NOISE: f64 = 1e-12;

/// From the thirteenth revision, turns of a disc between an obstacle and a
/// plastic partner (obstacle hit, pair hit) after which the sequence is
/// taken to its limit (see `World::hit_into_wall`): as many as the hits
/// of one pair at one instant that the tenth revision takes as a collapse
/// (`limits::EARLY_REPEAT_HITS`). A sequence that ends sooner (a light
/// disc knocking a heavy one against a wall, which stops it within a few
/// turns) is left to its hits.
const WALL_RINGS: usize = 8;

/// From the thirteenth revision, the share of the pair's first approach in
/// the sequence played in memory that it must still have after
/// [`WALL_RINGS`] turns for the hit to be taken to its limit (see
/// `World::hit_into_wall`): a ring losing less than a fifth of its
/// approach a turn, hundreds of turns long. Taken whenever the turns still
/// rang, the rule ended 26 of revision 12's 33 failures in the first
/// 100,000 mixed boxes but sent 59 others to the event cap or `stuck`
/// (impacts on piles, whose rings end fast, taken with part of the pile);
/// with 0.5, 0.8 it ended 11 and 10 of the 33, with 0.1, 0.02 16 and 19
/// but sent 1 and 7 of those 59 back to a failure.
const WALL_RING_KEEPS: f64 = 0.2;

/// From the fourteenth revision, the least cosine between a gentle hit's
/// normal and an obstacle's for the hit to count as driving a disc into
/// that obstacle (see `World::hit_into_wall`): a hit along a row of discs
/// lying on a wall, its normal parallel to the wall, drives them into it
/// only by the rounding of the impulse.
const GENTLE_WALL_COSINE: f64 = 1e-2;

/// From the fourteenth revision, the most discs a gentle hit into an
/// obstacle is taken with (the pair and the discs touching it through
/// plastic contacts; see `World::hit_into_wall`): in a plastic pile on a
/// line struck from above, each such limit at one instant set the next
/// pair of the pile ringing, 23,500 limits at one instant until `stuck`
/// (plastic-lines 5172), where the collapse rules of the instant take the
/// pile.
const GENTLE_WALL_MEMBERS: usize = 4;

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
    /// Without the event calendar's bookkeeping: after every event, every
    /// body's next event is recomputed from scratch (the naive a priori
    /// loop). Same results, for measuring what the calendar saves.
    #[serde(default)]
    pub recompute_all: bool,
    /// Which revision of the computation runs (see [`Revision`]).
    #[serde(default)]
    pub revision: Revision,
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
    /// Hits between discs pressed together obliquely, where the engine
    /// approximates the contact (see `push::pressing_kick`): not exact.
    pub pressed: u64,
    /// Inelastic collapses taken to their limit at once (see
    /// `World::collapse`): velocities of discs touching the ones of the
    /// event changed with it, momentum going into any obstacle they touch.
    pub collapses: u64,
}

impl Stats {
    /// Body–body, body–line and body–point events.
    pub fn collisions(&self) -> u64 {
        self.body_body + self.body_line + self.body_point
    }
}

/// The material of a disc (what does not change as it moves).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
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
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct BodyState {
    pub id: BodyId,
    pub material: Material,
    pub trajectory: Trajectory,
}

impl BodyState {
    /// A scene body moving from time `t` under gravity `g`.
    pub fn from_spec(spec: &BodySpec, t: f64, g: f64) -> Self {
        BodyState {
            id: spec.id,
            material: Material::of(spec),
            trajectory: Trajectory::new(t, spec.pos, spec.vel, spec.mu * g),
        }
    }

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
    const NONE: Best = Best {
        t: f64::INFINITY,
        next: Next::None,
    };

    /// Keeps `(t, next)` if it is strictly earlier (the first offered wins ties).
    #[inline(always)]
    fn offer(&mut self, t: f64, next: Next) {
        if t < self.t {
            self.t = t;
            self.next = next;
        }
    }
}

/// What the pair loop reads of each body, kept together.
#[derive(Clone, Copy, Debug)]
struct Slot {
    traj: Trajectory,
    radius: f64,
    gen: u32,
    alive: bool,
    /// Bit k set: the centre is inside (left of) sensor k.
    sides: u64,
}

/// A corner a disc can hit: the end of a ray or segment (shared ends once).
#[derive(Clone, Copy, Debug)]
struct Corner {
    pos: DVec2,
    line: u32,
    end: u8,
}

/// The live state of a computation.
#[derive(Clone, Debug)]
pub struct World {
    /// Where the computation stands, in working time (see `clock`): every
    /// time the world holds (these, the calendar's, the trajectories') is
    /// seconds since `clock`'s origin; what it shows is absolute.
    t: f64,
    last_event_t: f64,
    clock: Clock,
    g: f64,
    config: WorldConfig,
    ids: Vec<BodyId>,
    /// `(id, slot)` sorted by id, for lookups by id.
    by_id: Vec<(BodyId, u32)>,
    slots: Vec<Slot>,
    material: Vec<Material>,
    /// Each body's earliest real event.
    pending: Vec<Best>,
    /// Each body's next grid-cell crossing (infinity without a grid).
    cross: Vec<(f64, Step)>,
    calendar: Calendar,
    points: Vec<Point>,
    lines: Vec<Line>,
    geoms: Vec<LineGeom>,
    solid: Vec<u32>,
    corners: Vec<Corner>,
    sensors: Vec<u32>,
    grid: Option<Grid>,
    stats: Stats,
    /// The speed at which the latest hit's bodies approached (see
    /// [`Repeats`]).
    last_approach: f64,
    /// The instant of the latest factored kick search and how many were
    /// made at it (see `KICK_SEARCHES_PER_INSTANT`).
    kick_searches: Cell<(f64, u32)>,
}

impl Watched for World {
    fn slot_of(&self, id: BodyId) -> Option<usize> {
        let k = self.by_id.binary_search_by_key(&id, |e| e.0).ok()?;
        let i = self.by_id[k].1 as usize;
        self.slots[i].alive.then_some(i)
    }

    fn fastest_and_smallest(&self, t: f64) -> (f64, f64) {
        let mut speed: f64 = 0.0;
        let mut radius = f64::INFINITY;
        for s in self.slots.iter().filter(|s| s.alive) {
            speed = speed.max(s.traj.velocity(t).length());
            radius = radius.min(s.radius);
        }
        (speed, radius)
    }

    fn fastest_and_smallest_of(&self, slots: &[usize], t: f64) -> (f64, f64) {
        let mut speed: f64 = 0.0;
        let mut radius = f64::INFINITY;
        for s in slots.iter().filter_map(|&c| self.slots.get(c)) {
            if s.alive {
                speed = speed.max(s.traj.velocity(t).length());
                radius = radius.min(s.radius);
            }
        }
        if radius == f64::INFINITY {
            // No live disc among them: the whole scene decides.
            return self.fastest_and_smallest(t);
        }
        (speed, radius)
    }

    fn restitution(&self, a: usize, b: Option<usize>) -> f64 {
        let e = self.material[a].restitution;
        b.map_or(e, |b| e.min(self.material[b].restitution))
    }

    fn speed_at_last_event(&self, c: usize) -> f64 {
        self.slots[c].traj.velocity(self.last_event_t).length()
    }
}

impl World {
    /// A world at the scene's time, after validating the scene.
    pub fn new(scene: &Scene, config: WorldConfig) -> Result<World, SceneError> {
        scene.validate()?;
        let bodies = scene
            .bodies
            .iter()
            .map(|b| BodyState::from_spec(b, scene.t, scene.g))
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
        let solid: Vec<u32> = (0..lines.len() as u32)
            .filter(|&k| !lines[k as usize].sensor)
            .collect();
        let sensors: Vec<u32> = (0..lines.len() as u32)
            .filter(|&k| lines[k as usize].sensor)
            .collect();
        let mut corners: Vec<Corner> = Vec::new();
        for &k in &solid {
            for (end, q) in geoms[k as usize].ends.iter().enumerate() {
                if let Some(pos) = *q {
                    if !corners.iter().any(|c| c.pos == pos) {
                        corners.push(Corner {
                            pos,
                            line: k,
                            end: end as u8,
                        });
                    }
                }
            }
        }
        let mut by_id: Vec<(BodyId, u32)> = bodies
            .iter()
            .enumerate()
            .map(|(i, b)| (b.id, i as u32))
            .collect();
        by_id.sort_unstable();
        let slots = bodies
            .iter()
            .map(|b| {
                let p = b.trajectory.position(t);
                let mut sides = 0u64;
                for (bit, &k) in sensors.iter().enumerate() {
                    if geoms[k as usize].signed_distance(p) >= 0.0 {
                        sides |= 1 << bit;
                    }
                }
                Slot {
                    traj: b.trajectory,
                    radius: b.material.radius,
                    gen: 0,
                    alive: true,
                    sides,
                }
            })
            .collect();
        let mut w = World {
            t,
            last_event_t: t,
            clock: Clock::default(),
            g,
            config,
            ids: bodies.iter().map(|b| b.id).collect(),
            by_id,
            slots,
            material: bodies.iter().map(|b| b.material).collect(),
            pending: vec![Best::NONE; n],
            cross: vec![(f64::INFINITY, (0, 0)); n],
            calendar: Calendar::new(n),
            points,
            lines,
            geoms,
            solid,
            corners,
            sensors,
            grid: None,
            stats: Stats::default(),
            last_approach: 0.0,
            kick_searches: Cell::new((f64::NEG_INFINITY, 0)),
        };
        let use_grid = match config.broad_phase {
            BroadPhase::AllPairs => false,
            BroadPhase::Grid => true,
            BroadPhase::Auto => n > 32,
        };
        if use_grid && n > 0 {
            w.grid = Some(w.build_grid());
        }
        // Resting bodies need no prediction of their own: every contact with
        // them is found by the moving body.
        for i in 0..n {
            w.predict(i, false);
        }
        w
    }

    fn build_grid(&self) -> Grid {
        let t = self.t;
        let mut lo = DVec2::splat(f64::INFINITY);
        let mut hi = DVec2::splat(f64::NEG_INFINITY);
        let mut max_r: f64 = 0.0;
        for s in &self.slots {
            let tr = &s.traj;
            let p = tr.position(t);
            let stop = if tr.stop_time().is_finite() {
                tr.position(tr.stop_time())
            } else {
                p
            };
            for q in [p, stop] {
                lo = lo.min(q - s.radius);
                hi = hi.max(q + s.radius);
            }
            max_r = max_r.max(s.radius);
        }
        for l in &self.lines {
            lo = lo.min(l.a).min(l.b);
            hi = hi.max(l.a).max(l.b);
        }
        let n = self.slots.len();
        let mut grid = Grid::new(lo, hi, 2.0 * max_r * (1.0 + 1e-9), n);
        for (i, s) in self.slots.iter().enumerate() {
            grid.insert(i, s.traj.position(t));
        }
        grid
    }

    /// Current time: where the computation stands.
    pub fn time(&self) -> f64 {
        self.clock.absolute(self.t)
    }

    /// Time of the last event processed.
    pub fn last_event_time(&self) -> f64 {
        self.clock.absolute(self.last_event_t)
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

    fn state(&self, i: usize) -> BodyState {
        let traj = self.slots[i].traj;
        BodyState {
            id: self.ids[i],
            material: self.material[i],
            trajectory: if self.clock.moved() {
                traj.retimed(|t| self.clock.absolute(t))
            } else {
                traj
            },
        }
    }

    /// The bodies still in the scene, in the order they were given.
    pub fn bodies(&self) -> impl Iterator<Item = BodyState> + '_ {
        (0..self.slots.len())
            .filter(|&i| self.slots[i].alive)
            .map(|i| self.state(i))
    }

    /// One body still in the scene.
    pub fn body(&self, id: BodyId) -> Option<BodyState> {
        let k = self.by_id.binary_search_by_key(&id, |e| e.0).ok()?;
        let i = self.by_id[k].1 as usize;
        self.slots[i].alive.then(|| self.state(i))
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
        self.slots
            .iter()
            .any(|s| s.alive && s.traj.is_moving_at(self.t))
    }

    /// Advances the computation until a limit is reached or nothing more can
    /// happen, telling `handler` about every event.
    pub fn run<H: EventHandler + ?Sized>(&mut self, limits: &Limits, handler: &mut H) -> End {
        let mut events_left = limits.max_events;
        let mut collisions_left = limits.max_collisions;
        // Events within one instant since it began, and the bodies of the
        // latest of them (see `collapse`).
        let mut instant = (self.last_event_t, 0u64);
        let mut recent: Vec<usize> = Vec::new();
        let stuck_after = STUCK_EVENTS + STUCK_EVENTS_PER_BODY * self.slots.len() as u64;
        // Worked out only once events have shared an instant.
        let mut tick: Option<f64> = None;
        let mut crawl = Crawl::new(self.last_event_t, self.config.revision.at_least_r8());
        let r5 = self.config.revision.at_least_r5();
        let mut repeats = Repeats::new(if self.config.revision.at_least_r10() {
            EARLY_REPEAT_HITS
        } else {
            REPEAT_HITS
        })
        .decaying(self.config.revision.collapses_decaying_plastic_rings())
        .with_elastic(self.config.revision.collapses_rings_with_elastic_pairs())
        .squeezed(
            self.config
                .revision
                .collapses_rings_through_squeezed_discs(),
        )
        .geometric(
            self.config
                .revision
                .collapses_geometric_rings_through_squeezed_discs(),
        )
        .lasting(self.config.revision.leaves_fading_rings_to_their_hits());
        // From the seventh revision: the fine clock (see `clock`), and the
        // current instant's tick (see `World::instant_tick`), worked out
        // only once an event comes near it.
        let fine = self.config.revision.at_least_r7();
        // From the eighth revision, a crawl that outlasts its collapse
        // comes to rest (see `World::crawl_rest`).
        let crawl_rest = self.config.revision.at_least_r8();
        let mut until = self.clock.working(limits.until);
        let mut instant_tick: Option<f64> = None;
        loop {
            let Some((slot, t)) = self.calendar.peek() else {
                return self.end_at_rest();
            };
            if t == f64::INFINITY {
                // Nothing can ever happen again: that moment comes before
                // any horizon.
                return self.end_at_rest();
            }
            if t > until {
                self.t = self.t.max(until);
                return End {
                    t: limits.until,
                    reason: EndReason::Until,
                };
            }
            if events_left == 0 {
                return self.end_on(EndReason::MaxEvents);
            }
            if collisions_left == 0 {
                return self.end_on(EndReason::MaxCollisions);
            }
            if self.clock.may_pass(t, FAR_FUTURE)
                && self.clock.absolute(t) > FAR_FUTURE
                && !self.in_range_at(t)
            {
                return self.end_on(EndReason::OutOfRange);
            }
            let prev = self.last_event_t;
            if let Some(event) = self.process(slot, t, handler) {
                let same = if fine {
                    // One instant while no disc moves beyond the rounding
                    // of a position, however fine the clock.
                    t == instant.0
                        || ((instant.1 > 0 || same_instant(instant.0, t))
                            && t - instant.0
                                <= *instant_tick.get_or_insert_with(|| self.instant_tick()))
                } else {
                    t == instant.0
                        || same_instant(instant.0, t)
                        || (instant.1 > 0
                            && t - instant.0 <= *tick.get_or_insert_with(|| self.instant_tick()))
                };
                if same {
                    instant.1 += 1;
                    if instant.1 > stuck_after {
                        handler.on_event(self, &event);
                        return self.end_on(EndReason::Stuck);
                    }
                    let phase = instant.1 % COLLAPSE_EVENTS;
                    if phase + COLLAPSE_WINDOW >= COLLAPSE_EVENTS {
                        self.remember(&mut recent, &event);
                    }
                    if phase == 0 {
                        self.collapse(&mut recent, t, 0.0);
                        recent.clear();
                    }
                    if r5 && repeats.note(self, &event, self.last_approach) {
                        // From the sixteenth revision, a squeezed disc's
                        // ring is taken to its plastic limit alone, and
                        // one shrinking by one ratio a turn is solved by
                        // the active-set method before the projection's
                        // cap.
                        self.collapse_repeated(
                            &repeats.repeated(),
                            !repeats.by_squeeze(),
                            repeats.by_ratio(),
                            t,
                        );
                    }
                } else {
                    instant = (t, 0);
                    instant_tick = None;
                    recent.clear();
                    if r5 {
                        repeats.start(event, self.last_approach);
                    }
                }
                if self.config.revision.at_least_r3() {
                    if let Some(mut latest) = crawl.note(self, &event, t) {
                        if crawl.still() > stuck_after {
                            handler.on_event(self, &event);
                            return self.end_on(EndReason::Stuck);
                        }
                        if crawl_rest && crawl.still() > CRAWL_EVENTS {
                            self.crawl_rest(&mut latest, t, crawl.span());
                        } else {
                            self.collapse(&mut latest, t, crawl.span());
                        }
                    }
                }
                events_left -= 1;
                collisions_left -= event.kind.is_collision() as u64;
                if self.config.recompute_all {
                    self.recompute_all();
                }
                if fine && self.clock.moves_for(t - prev, t, same) {
                    self.rebase(t);
                    instant.0 -= t;
                    crawl.rebase(t);
                    until = self.clock.working(limits.until);
                }
                handler.on_event(self, &event);
            }
        }
    }

    /// Processes calendar entries until one real event happens (or none can
    /// before `until`), and returns it.
    pub fn step<H: EventHandler + ?Sized>(&mut self, until: f64, handler: &mut H) -> Option<Event> {
        loop {
            let (slot, t) = self.calendar.peek()?;
            if t == f64::INFINITY || t > self.clock.working(until) {
                return None;
            }
            let prev = self.last_event_t;
            if let Some(event) = self.process(slot, t, handler) {
                if self.config.revision.at_least_r7()
                    && self.clock.moves_for(t - prev, t, same_instant(prev, t))
                {
                    self.rebase(t);
                }
                handler.on_event(self, &event);
                return Some(event);
            }
        }
    }

    /// From the seventh revision, moves the origin of the working time up
    /// to working time `by` (the latest event's; see `clock`): every time
    /// the world holds is re-expressed from there, so that what comes next
    /// is resolved to the rounding of its distance from the latest event
    /// rather than from the start.
    fn rebase(&mut self, by: f64) {
        self.clock.advance(by);
        self.t -= by;
        self.last_event_t -= by;
        for s in &mut self.slots {
            s.traj = s.traj.retimed(|t| t - by);
        }
        for p in &mut self.pending {
            p.t -= by;
        }
        for c in &mut self.cross {
            c.0 -= by;
        }
        self.calendar.shift(by);
    }

    /// How close in time two events must be to count as one instant beyond
    /// rounding of the time itself: while the fastest disc moves less than
    /// the rounding of a position at the scale of the smallest radius.
    /// From the seventh revision, whose clock resolves events far closer
    /// than the rounding of the time, this alone decides (worked out for
    /// each instant): a fast but finite sequence of hits, each moving a
    /// disc by more than that, is no longer one instant.
    fn instant_tick(&self) -> f64 {
        let (speed, radius) = self.fastest_and_smallest(self.t);
        if speed > 0.0 {
            2.5e-13 * radius / speed
        } else {
            0.0
        }
    }

    /// An inelastic collapse at one instant: discs of restitution below one
    /// hitting each other again and again at `t`, every hit slower than the
    /// last, a sequence whose limit has the discs that press on each other
    /// moving as one. When the latest events of such a run (`recent`,
    /// slots; `usize::MAX` for a hit on an obstacle) were all between discs
    /// touching along one line, that limit is taken at once for the whole
    /// touching chain they belong to: the plastic impact of a chain
    /// ([`push::plastic`]), momentum kept. Their braking is pooled by the
    /// pushing events that follow. From the second revision on, any other
    /// collapse (discs off one line, obstacles) is taken to its limit the
    /// same way, for every disc touching the ones involved: the plastic
    /// impact of all their contacts at once ([`collapse::plastic`]); from
    /// the third, so is a chain that touches an obstacle.
    /// Whatever is left ends the run as `stuck` if it goes on.
    /// From the seventh revision, nothing is taken where every disc
    /// touching the ones involved is elastic: their hits lose no energy;
    /// from the thirteenth, unless they rest on each other
    /// ([`World::elastic_ring_rests`]).
    fn collapse(&mut self, recent: &mut Vec<usize>, t: f64, span: f64) {
        recent.sort_unstable();
        recent.dedup();
        if self.config.revision.at_least_r7()
            && self.all_elastic(recent, t, span)
            && !self.elastic_ring_rests(recent, t)
        {
            return;
        }
        let taken = self.collapse_chain(recent, t)
            || (self.config.revision.at_least_r2() && self.collapse_cluster(recent, t))
            || (self.config.revision.at_least_r7() && self.collapse_recent(recent, t));
        self.stats.collapses += taken as u64;
    }

    /// From the eighth revision, the second block in a row of
    /// [`CRAWL_EVENTS`] events that moved none of the discs its latest
    /// events involve by more than `limits::CRAWL` of the smallest radius
    /// (the first was taken as a collapse, which did not end it): those
    /// discs (`recent`, slots; `usize::MAX` for an obstacle) come to rest
    /// where they are, and whatever touches them and would run into them
    /// (a heavy frictionless disc pushing the pile) is stopped against
    /// them, as against a wall: the plastic limit of the touching cluster
    /// with them held still. Such a pile has no plastic limit that ends
    /// it: a frictionless plastic disc sliding along braking ones, pressed
    /// against them by its own curvature, bounces off each in turn ever
    /// faster, the approximated pressing contact (see `push`) parting it
    /// again every time, while over two thousand events it slides less
    /// than a billionth of a radius. The same two blocks at one instant (a
    /// packed plastic pile struck, whose plastic limit neither the
    /// projection nor the exact solve finds) stop the discs hitting there
    /// whatever their speed: an approximation that loses energy and
    /// momentum, where the earlier revisions ended `stuck`. Where every
    /// disc touching them is elastic nothing is stopped: they lose no
    /// energy, and the run ends `stuck` if it goes on (from the thirteenth
    /// revision, unless they rest on each other,
    /// [`World::elastic_ring_rests`]). Counted as a collapse.
    fn crawl_rest(&mut self, recent: &mut Vec<usize>, t: f64, span: f64) {
        recent.retain(|&c| c != usize::MAX && self.slots.get(c).is_some_and(|s| s.alive));
        recent.sort_unstable();
        recent.dedup();
        if recent.is_empty()
            || (self.all_elastic(recent, t, span) && !self.elastic_ring_rests(recent, t))
        {
            return;
        }
        let (members, mut contacts) = self.touching_cluster(recent.clone(), t);
        let (vel, inv) = self.motion(&members, t);
        let still: Vec<bool> = members.iter().map(|c| recent.contains(c)).collect();
        let mut held = vel.clone();
        let mut inv_held = inv;
        for k in (0..members.len()).filter(|&k| still[k]) {
            (held[k], inv_held[k]) = (DVec2::ZERO, 0.0);
        }
        contacts.retain(|c| !still[c.a] || c.b.is_some_and(|b| !still[b]));
        let after = if contacts.is_empty() {
            None
        } else {
            collapse::resolve(&held, &inv_held, &contacts, PRESS_SWEEPS)
        };
        let after = after.unwrap_or(held);
        let changed = self.set_velocities(&members, &vel, &after, t);
        for &c in &changed {
            self.predict(c, true);
        }
        self.stats.collapses += !changed.is_empty() as u64;
    }

    /// From the seventh revision, where the plastic limit of the whole
    /// touching cluster has no answer the projection finds (a plastic
    /// disc hit again and again between a line and a disc of a packed
    /// pile, whose contacts are too many and redundant for the exact
    /// solve), the limit of the hits that repeat: the plastic impact of
    /// the contacts among the discs of `recent` (slots; `usize::MAX` for an
    /// obstacle) alone and of the lines and points they touch. `true` if
    /// any velocity changed.
    fn collapse_recent(&mut self, recent: &[usize], t: f64) -> bool {
        let members: Vec<usize> = recent
            .iter()
            .copied()
            .filter(|&c| c != usize::MAX)
            .collect();
        if members.is_empty() {
            return false;
        }
        let contacts = self.contacts_among(&members, t);
        self.collapse_contacts(&members, contacts, t)
    }

    /// Whether the discs of `recent` (slots; `usize::MAX` for an obstacle)
    /// and every disc touching them, or touching one that does, are all
    /// elastic: every contact among them, and with obstacles, has
    /// restitution 1. From the tenth revision, not where one of them
    /// moves so slowly that its friction would stop it within `span`, the
    /// time the events taken as a collapse took (zero at one instant): a
    /// frictionless elastic disc rattling against a braking one, 1e-10 s
    /// apart at 1e-9 m/s, loses its energy to that friction, where a chain
    /// pinned between two walls, rattling 1e-16 s an event, loses none.
    /// From the eleventh revision, not where a braking disc among them is
    /// at rest either: each hit on it settles it back to rest.
    fn all_elastic(&self, recent: &[usize], t: f64, span: f64) -> bool {
        let seed: Vec<usize> = recent
            .iter()
            .copied()
            .filter(|&c| c != usize::MAX)
            .collect();
        let (members, _) = self.touching_cluster(seed, t);
        // From the eleventh revision, a braking disc at rest among them
        // too: hit, it slides and loses what it was given (or, slower than
        // the rounding of its position, is put back at rest).
        let r11 = self.config.revision.at_least_r11();
        let braked = |c: usize| {
            let tr = &self.slots[c].traj;
            let speed = tr.velocity(t).length();
            (speed > 0.0 && speed <= tr.alpha() * span) || (r11 && speed == 0.0 && tr.alpha() > 0.0)
        };
        members.iter().all(|&c| self.material[c].restitution >= 1.0)
            && !(self.config.revision.at_least_r10() && members.iter().any(|&c| braked(c)))
    }

    /// From the thirteenth revision, whether the elastic discs of `recent`
    /// (slots; `usize::MAX` for an obstacle), ringing at one instant or
    /// crawling, rest on each other rather than rattle: one of them brakes,
    /// and none of the contacts among them (or with the lines and points
    /// they touch) approaches or parts faster than [`GENTLE`] of the speed
    /// of the fastest of them. Such a ring is then taken as an inelastic
    /// collapse is (`World::collapse`, `World::crawl_rest`), though every
    /// disc touching it is elastic: it is a chatter to rest
    /// (`push::chatters`) spread over more than two discs, or too slow to
    /// end. A frictionless disc pushing a braked pair, its velocity a few
    /// parts in a billion off theirs (beyond `push::SAME`, so never joined
    /// to their push), hit the middle disc at once, each hit giving that
    /// disc its own braking back, which the pair's push pooled again at
    /// once: 20,000 hits at one instant. An elastic pair on a braking floor
    /// bounced 1e-12 m/s apart, a bounce every 6e-14 s, for some 40,000
    /// hits before it would stop. Their plastic limit, the discs pressed
    /// together moving as one, differs from their hits by the ring's speeds
    /// and loses no more than their energy. A chain pinned between two
    /// walls, or any ring without braking, rattles at the speeds of its
    /// discs and is left to end `stuck` with its energy.
    fn elastic_ring_rests(&self, recent: &[usize], t: f64) -> bool {
        if !self.config.revision.collapses_resting_elastic_rings() {
            return false;
        }
        let mut ring: Vec<usize> = recent
            .iter()
            .copied()
            .filter(|&c| c != usize::MAX && self.slots.get(c).is_some_and(|s| s.alive))
            .collect();
        ring.sort_unstable();
        ring.dedup();
        let contacts = self.contacts_among(&ring, t);
        let (vel, _) = self.motion(&ring, t);
        let fastest = vel.iter().map(|v| v.length()).fold(0.0, f64::max);
        let brakes = ring.iter().any(|&c| self.material[c].mu > 0.0);
        let gentle = contacts.iter().all(|c| {
            let rel = vel[c.a] - c.b.map_or(DVec2::ZERO, |b| vel[b]);
            rel.dot(c.n).abs() <= GENTLE * fastest
        });
        brakes && fastest > 0.0 && !contacts.is_empty() && gentle
    }

    /// From the fifth revision, an instant at which one inelastic pair has
    /// been hit [`REPEAT_HITS`] times: the limit of the collapse, taken as
    /// the plastic projection of the contacts it involves: the `pairs` hit
    /// more than once at this instant (slots; `None` for an obstacle), and
    /// every plastic contact (restitution 0) touching them, through which
    /// the limit of plastic hits spreads whatever their order. A contact
    /// with restitution that was hit once (the last disc of a chain, sent
    /// off by the collapse behind it) is left to the hits that follow;
    /// from the eleventh revision, not one with an obstacle, which the
    /// limit would otherwise drive a disc into a picosecond later. From the
    /// thirteenth, `pairs` names the elastic pairs hit more than once too
    /// (see `limits::Repeats::with_elastic`). Followed by the kick of the
    /// pairs it leaves pressed where `kick` is set (from the sixteenth
    /// revision, not for a squeezed disc's ring: see
    /// `limits::Repeats::squeezed`).
    fn collapse_repeated(
        &mut self,
        pairs: &[(usize, Option<usize>)],
        kick: bool,
        active_first: bool,
        t: f64,
    ) {
        // From the eleventh revision, with every obstacle a member touches
        // (see `Revision::R11`).
        let walls = self.config.revision.at_least_r11();
        let involved = |w: &World, a: usize, b: Option<usize>| {
            w.restitution(a, b) == 0.0
                || (walls && b.is_none())
                || pairs.contains(&(a, b))
                || b.is_some_and(|b| pairs.contains(&(b, Some(a))))
        };
        let mut members: Vec<usize> = pairs
            .iter()
            .flat_map(|&(a, b)| [Some(a), b])
            .flatten()
            .collect();
        members.sort_unstable();
        members.dedup();
        let at = self.positions(t);
        let mut k = 0;
        while k < members.len() && members.len() < MAX_COLLAPSE {
            let m = members[k];
            for c in self.touching(m, &at) {
                if !members.contains(&c) && self.restitution(m, Some(c)) == 0.0 {
                    members.push(c);
                }
            }
            k += 1;
        }
        let mut contacts = self.contacts_among(&members, t);
        contacts.retain(|c| involved(self, members[c.a], c.b.map(|b| members[b])));
        let taken = self.collapse_contacts_kicked(&members, contacts, kick, active_first, t);
        self.stats.collapses += taken as u64;
    }

    /// The collapse of a chain of discs along one line (see `collapse`);
    /// `false` if `recent` is not one.
    fn collapse_chain(&mut self, recent: &[usize], t: f64) -> bool {
        if recent.len() < 2 || recent.last() == Some(&usize::MAX) {
            return false;
        }
        let p0 = self.slots[recent[0]].traj.position(t);
        let Some(far) = recent
            .iter()
            .map(|&c| self.slots[c].traj.position(t) - p0)
            .max_by(|a, b| a.length_squared().total_cmp(&b.length_squared()))
        else {
            return false;
        };
        let u = far.normalize_or_zero();
        if u == DVec2::ZERO {
            return false;
        }
        let on_line = |w: &World, c: usize| {
            let s = &w.slots[c];
            let v = s.traj.velocity(t);
            (s.traj.position(t) - p0).perp_dot(u).abs() <= push::SAME * s.radius
                && v.perp_dot(u).abs() <= push::SAME * v.length()
        };
        if !recent.iter().all(|&c| on_line(self, c)) {
            return false;
        }
        // The whole touching chain along the line.
        let chain = self.touching_chain(recent.to_vec(), t, u, |w, _, c| on_line(w, c));
        // From the third revision, a chain that touches an obstacle (or
        // touches discs that do) collapses with it, as a cluster: pressed
        // into a wall, its plastic limit without the wall would be undone
        // by the next hit on it, again and again at one instant.
        if self.config.revision.at_least_r3() {
            let (_, contacts) = self.touching_cluster(chain.clone(), t);
            if contacts.iter().any(|c| c.b.is_none()) {
                return false;
            }
        }
        let parts = self.chain_parts(&chain, t);
        for (&c, v) in chain.iter().zip(push::plastic(&parts, u)) {
            let p = self.slots[c].traj.position(t);
            self.slots[c].traj = Trajectory::new(t, p, v, self.material[c].mu * self.g);
            self.slots[c].gen = self.slots[c].gen.wrapping_add(1);
        }
        for &c in &chain {
            self.predict(c, true);
        }
        true
    }

    /// The plastic limit of a collapse among the discs of `recent` (slots;
    /// `usize::MAX` for an obstacle) and every disc touching them, against
    /// each other and the solid lines and points they touch; from the third
    /// revision, followed by the kick of whatever pairs it leaves pressed
    /// (see [`World::press_cluster`]). `true` if any velocity changed.
    fn collapse_cluster(&mut self, recent: &[usize], t: f64) -> bool {
        let seed: Vec<usize> = recent
            .iter()
            .copied()
            .filter(|&c| c != usize::MAX)
            .collect();
        if seed.is_empty() {
            return false;
        }
        let (members, contacts) = self.touching_cluster(seed, t);
        self.collapse_contacts(&members, contacts, t)
    }

    /// The plastic limit of the `contacts` among `members` (slots), and
    /// from the third revision the kick of whatever pairs it leaves
    /// pressed (see `collapse_cluster`). `true` if any velocity changed.
    fn collapse_contacts(
        &mut self,
        members: &[usize],
        contacts: Vec<collapse::Contact>,
        t: f64,
    ) -> bool {
        self.collapse_contacts_kicked(members, contacts, true, false, t)
    }

    /// As `collapse_contacts`, the kick left out where `kick` is not set
    /// (the plastic limit alone, see `limits::Repeats::squeezed`). Where
    /// `active_first` is set (a ring that shrinks by one ratio a turn, see
    /// `limits::Repeats::geometric`) the projection is given the pressing
    /// kick's [`PRESS_SWEEPS`] before the active-set method solves the
    /// limit, and its [`collapse::MAX_SWEEPS`] only where that fails: on
    /// such a ring it converges as slowly as the ring, sweep after sweep
    /// up to its cap, at every collapse. From the twentieth revision a
    /// cluster of more than `EXACT_KICK_CLUSTER` discs is solved by the
    /// factored active-set method after the kick's sweeps (see
    /// `Revision::solves_large_collapses_by_factored_active_set`).
    fn collapse_contacts_kicked(
        &mut self,
        members: &[usize],
        contacts: Vec<collapse::Contact>,
        kick: bool,
        active_first: bool,
        t: f64,
    ) -> bool {
        let (vel, inv) = self.motion(members, t);
        let r3 = self.config.revision.at_least_r3();
        let large = self
            .config
            .revision
            .solves_large_collapses_by_factored_active_set()
            && members.len() > EXACT_KICK_CLUSTER;
        let plastic = if active_first && large {
            // From the twentieth revision, a ring's collapse over a cluster
            // larger than a pressing kick's exact search takes (a pile):
            // where the factored active-set method leaves a contact
            // approaching, so did the eliminating one and the projection's
            // full sweeps, at the cost of a pile's sweeps at every collapse.
            collapse::resolve(&vel, &inv, &contacts, PRESS_SWEEPS)
                .or_else(|| collapse::factored_active_set(&vel, &inv, &contacts))
        } else if active_first {
            collapse::resolve(&vel, &inv, &contacts, PRESS_SWEEPS)
                .or_else(|| collapse::active_set(&vel, &inv, &contacts))
                .or_else(|| collapse::resolve(&vel, &inv, &contacts, collapse::MAX_SWEEPS))
        } else if r3 && large {
            // From the twentieth revision, a collapse of a cluster larger
            // than a pressing kick's exact search takes (a pile) is given
            // the kick's sweeps, then the factored active-set method, and
            // the full sweeps and the eliminating method only where that
            // fails: stalled on a pile, the projection ran its
            // `MAX_SWEEPS` at every collapse of a ring.
            collapse::resolve(&vel, &inv, &contacts, PRESS_SWEEPS)
                .or_else(|| collapse::factored_active_set(&vel, &inv, &contacts))
                .or_else(|| collapse::resolve(&vel, &inv, &contacts, collapse::MAX_SWEEPS))
                .or_else(|| collapse::active_set(&vel, &inv, &contacts))
        } else if r3 {
            collapse::resolve(&vel, &inv, &contacts, collapse::MAX_SWEEPS).or_else(|| {
                // From the ninth revision, where the projection stalls and
                // the exact solve of what it pushes is singular (a packed
                // pile), the active-set method finds the limit.
                self.config
                    .revision
                    .at_least_r9()
                    .then(|| collapse::active_set(&vel, &inv, &contacts))
                    .flatten()
            })
        } else {
            collapse::plastic(&vel, &inv, &contacts)
        };
        let Some(after) = plastic else {
            return false;
        };
        self.take_plastic_limit(members, contacts, (&vel, &inv), after, r3 && kick, t)
    }

    /// Sets the velocities of `members` (slots; `vel` and `inv` their
    /// velocities and inverse masses before) to the plastic limit `after`
    /// of their `contacts`, where `press` is set (the third revision on)
    /// kicked apart first where it leaves pairs pressed (see
    /// `collapse_cluster`), and predicts the discs it changed. `true` if
    /// any velocity changed. From the eighteenth revision, where the kick
    /// cannot move a braking disc beyond the rounding of its position,
    /// that disc is held instead (`World::held_against_kick`).
    fn take_plastic_limit(
        &mut self,
        members: &[usize],
        mut contacts: Vec<collapse::Contact>,
        (vel, inv): (&[DVec2], &[f64]),
        mut after: Vec<DVec2>,
        press: bool,
        t: f64,
    ) -> bool {
        let alpha = self.braking(members);
        // The contacts before the pressing biases, for the held kick alone.
        let unbiased = self
            .config
            .revision
            .holds_discs_kicks_cannot_move()
            .then(|| contacts.clone());
        if press && self.press_biases(members, &mut contacts, &after, &alpha) {
            if let Some(kicked) = self.press_closure(members, &mut contacts, &after, inv, &alpha, t)
            {
                // From the eighteenth revision, a braking disc the kick
                // cannot move beyond the rounding of its position is held
                // by its friction instead.
                if let Some(unbiased) = &unbiased {
                    if let Some(held) = self.held_against_kick(
                        members,
                        unbiased,
                        (vel, inv),
                        &alpha,
                        &after,
                        &kicked,
                        t,
                    ) {
                        let changed = self.set_velocities(members, vel, &held, t);
                        for &c in &changed {
                            self.predict(c, true);
                        }
                        return !changed.is_empty();
                    }
                }
                after = if self.config.revision.bounds_collapse_kick_energy() {
                    // From the fourteenth revision, held as the twelfth
                    // holds a pressing kick over a cluster: no more than
                    // its share of the scene's energy over the limit.
                    let scene = self.scene_energy(t);
                    within_press_bound(&after, inv, &contacts, kicked, scene).unwrap_or(after)
                } else {
                    kicked
                };
                self.stats.pressed += 1;
            }
        }
        let changed = self.set_velocities(members, vel, &after, t);
        for &c in &changed {
            self.predict(c, true);
        }
        !changed.is_empty()
    }

    /// The kinetic energy of every live disc at `t`, as their trajectories
    /// stand.
    fn scene_energy(&self, t: f64) -> f64 {
        self.slots
            .iter()
            .zip(&self.material)
            .filter(|(s, _)| s.alive)
            .map(|(s, m)| 0.5 * m.mass * s.traj.velocity(t).length_squared())
            .sum()
    }

    /// From the third revision, the pressing kick of a hit between `i` and
    /// `j` (their outgoing trajectories `ti`, `tj` already in place) taken
    /// over every disc touching them, in a chain or a cluster, and the
    /// lines and points they touch: one projection of all those contacts
    /// in which every pressed pair parts at its bounce speed
    /// ([`push::bounce_speed`]) and no other contact approaches. A kick
    /// between the two alone would drive one into its next neighbour,
    /// which would hit it back at the same instant, without end. `false`
    /// (nothing done) where `i` and `j` touch nothing else, or the
    /// projection has no answer (a pressed pair jammed between obstacles).
    /// From the eleventh revision, a pair whose energy cannot move its
    /// braking discs beyond the gap ([`push::spent_within_gap`]) rests
    /// even with a frictionless disc in it: the braking discs held, the
    /// frictionless one keeping what does not run into them. From the
    /// sixteenth revision, where the projection of that rest stalls on no
    /// more contacts than the free discs have directions (a frictionless
    /// disc wedged between a wall and a held disc, the two contacts 2e-5
    /// from parallel), the active-set method finds it: kicked instead, the
    /// held disc stopped 1e-10 s later and was hit again at that instant,
    /// until `stuck` (mixed-box 438889). From the seventeenth revision a
    /// spent pair that the hit leaves neither pressed nor parted rests so
    /// too: parting by 4e-19 m/s, which the braking of the disc ahead
    /// turned within the rounding of the time, a pair pushed at 2.9e-12
    /// m/s was met again at once, each hit changing nothing, until `stuck`
    /// (mixed-box 79139; `Revision::rests_spent_pairs_left_as_they_were`).
    /// From the nineteenth revision a braking disc of the cluster that
    /// slides beyond the gap on its own and, given its velocity back after
    /// that rest, runs into nothing of it keeps that velocity (mixed-box 142;
    /// `Revision::leaves_sliding_discs_out_of_spent_rests`).
    /// From the twentieth revision a rest of a pair a disc of which brakes
    /// with a pushed chain, whose held projection stalls in every try, is
    /// found by the active-set method, in clusters of up to
    /// `EXACT_KICK_CLUSTER` discs: given up, the hit gave that disc its
    /// own braking back, it ran into the disc it pushed at once, and the
    /// pair and the chain took turns at one instant (mixed-box 544105;
    /// `Revision::finds_stalled_cluster_rests_by_active_set`).
    fn press_cluster(
        &mut self,
        i: usize,
        j: usize,
        [ti, tj]: [Trajectory; 2],
        n: DVec2,
        braking: [f64; 2],
        t: f64,
    ) -> bool {
        // The pair itself first (cheap): pressed, and parting slower than
        // its bounce speed (or so slow that it comes to rest).
        let (vi, vj) = (ti.start_velocity(), tj.start_velocity());
        let s = self.slots[i].radius + self.slots[j].radius;
        let acc = [
            -braking[0] * vi.normalize_or_zero(),
            -braking[1] * vj.normalize_or_zero(),
        ];
        let at = self.clock.origin() + t;
        // From the eleventh revision, a pair whose energy cannot move its
        // braking discs beyond the gap (a heavy frictionless disc slowly
        // pressing a light braking one) comes to rest too, whether or not
        // the hit parts it faster than its bounce speed (an elastic hit on
        // a disc braking at 240 m/s^2 did, and the two chattered at one
        // instant). Where it cannot rest (the projection with its braking
        // discs held has no answer: a frictionless disc jammed between
        // them and a wall), it is kicked as before, or left to the hit.
        let r11 = self.config.revision.at_least_r11();
        let masses = [self.material[i].mass, self.material[j].mass];
        let spent =
            r11 && push::spent_within_gap([vi, vj], masses, braking, s, self.config.revision);
        let rev = self.config.revision;
        // From the seventeenth revision, a spent pair that its hit leaves
        // neither pressed nor parted rests too (see
        // `Revision::rests_spent_pairs_left_as_they_were`).
        let parted = spent
            && (push::bounce_speed([vi, vj], acc, n, s, rev).is_some()
                || rev.rests_spent_pairs_left_as_they_were());
        let Some(mut press) = push::pressing_kick([vi, vj], acc, n, s, at, rev)
            .or_else(|| parted.then_some(push::Press::Part(0.0)))
        else {
            return false;
        };
        let parted = parted && press == push::Press::Part(0.0);
        let mut kick = None;
        if spent && matches!(press, push::Press::Part(_)) {
            kick = Some(press);
            press = push::Press::Rest;
        }
        self.slots[i].traj = ti;
        self.slots[j].traj = tj;
        let (members, mut contacts) = self.touching_cluster(vec![i, j], t);
        let alone = members.len() == 2 && contacts.len() == 1;
        let (vel, inv) = self.motion(&members, t);
        let dw = match press {
            push::Press::Part(_) if alone => return false,
            push::Press::Part(dw) => dw,
            push::Press::Rest => {
                // So slow that it stops here: the pair comes to rest, and
                // whatever touches it and would run into it (one pushing
                // it, say) is stopped against it, as against a wall: the
                // plastic limit with the pair held still.
                // From the fourth revision, so does every disc of the
                // cluster still sliding, but no further than the gap (one
                // at rest already can still be pushed).
                // From the eleventh revision, where the pair rests by its
                // energy, only the braking discs of the pair: a
                // frictionless one keeps what does not run into them.
                let mut still = vec![false; members.len()];
                (still[0], still[1]) = if kick.is_some() {
                    (braking[0] > 0.0, braking[1] > 0.0)
                } else {
                    (true, true)
                };
                // From the eleventh revision, where the pair rests by its
                // energy, first with every braking disc (at rest or not)
                // that this energy cannot move beyond the gap held too:
                // left free, the frictionless disc pushed it off at once,
                // and two braking discs it pressed took turns at being
                // pushed, at one instant. Where that has no answer, without.
                let mut firm = still.clone();
                // From the nineteenth revision, the braking discs this
                // energy cannot move beyond the gap but that slide beyond
                // it on their own (see
                // `Revision::leaves_sliding_discs_out_of_spent_rests`).
                let mut sliding = vec![false; members.len()];
                if self.config.revision.at_least_r4() {
                    let alpha = self.braking(&members);
                    let gap = push::press_gap(self.config.revision) * s;
                    let energy = push::pair_energy([vi, vj], masses);
                    let frees_sliding = self
                        .config
                        .revision
                        .leaves_sliding_discs_out_of_spent_rests();
                    for k in 2..members.len() {
                        let slide = vel[k].length_squared() / (2.0 * alpha[k]);
                        still[k] = alpha[k] > 0.0 && slide > 0.0 && slide <= gap;
                        let mass = self.material[members[k]].mass;
                        let spent_on =
                            kick.is_some() && alpha[k] > 0.0 && energy <= mass * alpha[k] * gap;
                        sliding[k] = frees_sliding && spent_on && slide > gap;
                        firm[k] = still[k] || spent_on;
                    }
                }
                let tries = if firm != still {
                    vec![firm, still]
                } else {
                    vec![still]
                };
                let held_rest_by_active_set =
                    self.config.revision.rests_caged_discs_by_active_set();
                // From the sixteenth revision, a pair resting by its energy
                // whose projection stalls on fewer contacts (a frictionless
                // disc wedged between a wall and a held disc, the two
                // contacts nearly parallel) is solved exactly too.
                let spent_rest_by_active_set =
                    kick.is_some() && self.config.revision.rests_wedged_spent_pairs();
                let hold = |still: &[bool], exact: bool| {
                    let mut held = vel.clone();
                    let mut inv_held = inv.clone();
                    for k in (0..members.len()).filter(|&k| still[k]) {
                        (held[k], inv_held[k]) = (DVec2::ZERO, 0.0);
                    }
                    let mut contacts = contacts.clone();
                    contacts.retain(|c| !still[c.a] || c.b.is_some_and(|b| !still[b]));
                    if (alone && kick.is_none()) || contacts.is_empty() {
                        Some(held)
                    } else {
                        collapse::resolve(&held, &inv_held, &contacts, PRESS_SWEEPS).or_else(|| {
                            // From the twelfth revision, where the
                            // projection stalls on more contacts than the
                            // free discs have directions (a frictionless
                            // disc caged by held ones), the active-set
                            // method.
                            let free = inv_held.iter().filter(|&&k| k > 0.0).count();
                            (held_rest_by_active_set
                                && (contacts.len() > 2 * free || spent_rest_by_active_set || exact))
                                .then(|| collapse::active_set(&held, &inv_held, &contacts))
                                .flatten()
                        })
                    }
                };
                // From the twentieth revision, where no try reaches a rest
                // and a disc of the pair brakes with a pushed chain (not
                // with its own friction), the rest is found by the
                // active-set method, the tries taken in the same order, in
                // a cluster small enough for its search (see
                // `Revision::finds_stalled_cluster_rests_by_active_set`).
                let exact_rest = self
                    .config
                    .revision
                    .finds_stalled_cluster_rests_by_active_set()
                    && members.len() <= EXACT_KICK_CLUSTER
                    && [i, j]
                        .iter()
                        .zip(braking)
                        .any(|(&c, alpha)| alpha != self.material[c].mu * self.g);
                let after = tries
                    .iter()
                    .find_map(|still| hold(still, false).map(|after| (after, still)))
                    .or_else(|| {
                        exact_rest
                            .then(|| {
                                tries
                                    .iter()
                                    .find_map(|still| hold(still, true).map(|after| (after, still)))
                            })
                            .flatten()
                    });
                // From the nineteenth revision, a disc held only as sliding
                // beyond the gap keeps its velocity where, given it back,
                // it runs into nothing of the cluster as the rest leaves it.
                let after = after.map(|(mut after, still)| {
                    let mut kept: Vec<bool> =
                        (0..members.len()).map(|k| sliding[k] && still[k]).collect();
                    loop {
                        let back = given_back(&after, &vel, &kept);
                        let Some(k) = (0..members.len())
                            .find(|&k| kept[k] && !runs_into_nothing(k, &back, &kept, &contacts))
                        else {
                            break;
                        };
                        kept[k] = false;
                    }
                    after = given_back(&after, &vel, &kept);
                    after
                });
                // From the twentieth revision, a rest that has no answer
                // because a disc sliding into a corner wedges a row along
                // the other obstacle: the row carried as one body.
                if after.is_none()
                    && kick.is_some()
                    && self.config.revision.carries_rows_wedged_into_corners()
                    && self.corner_jam(&members, &contacts, &vel, [i, j], t)
                {
                    return true;
                }
                match (after, kick) {
                    (Some(mut after), _) => {
                        // From the eleventh revision, what the projection
                        // leaves of a speed within its rounding is none (a
                        // frictionless disc left at 1e-191 m/s hit the
                        // held one again at the same instant, for ever).
                        if kick.is_some() {
                            let noise = 1e-12 * vel.iter().map(|v| v.length()).fold(0.0, f64::max);
                            for v in &mut after {
                                if v.length() <= noise {
                                    *v = DVec2::ZERO;
                                }
                            }
                        }
                        // From the seventeenth revision, a disc of the pair
                        // left free still runs into its held partner where
                        // its approach is below the projection's tolerance
                        // (set by the fastest disc of the cluster) but not
                        // below the pair's own: that approach is taken off
                        // against the held disc, as against a wall.
                        if kick.is_some() && self.config.revision.rests_free_disc_on_held_partner()
                        {
                            stop_against_held(&mut after, [tries[0][0], tries[0][1]], &contacts);
                        }
                        self.kick_cluster(&members, &vel, &after, [i, j], t);
                        return true;
                    }
                    (None, Some(push::Press::Part(dw))) if !alone && !parted => dw,
                    (None, _) => return false,
                }
            }
        };
        // The kick between the two alone, where it drives neither into
        // anything else it touches.
        let (w_i, w_j) = impulse::weights(self.material[i].mass, self.material[j].mass);
        let mut kicked = vel.clone();
        kicked[0] += n * (dw * w_j);
        kicked[1] -= n * (dw * w_i);
        let noise = 1e-15 * (vi.length() + vj.length());
        let blocked = contacts.iter().any(|c| {
            let pair = c.a == 0 && c.b == Some(1);
            let ours = c.a < 2 || c.b.is_some_and(|b| b < 2);
            let rel = kicked[c.a] - c.b.map_or(DVec2::ZERO, |b| kicked[b]);
            !pair && ours && rel.dot(c.n) < -noise
        });
        if !blocked {
            let changed = self.set_velocities(&members[..2], &vel[..2], &kicked[..2], t);
            for c in [i, j] {
                if !changed.contains(&c) {
                    self.slots[c].gen = self.slots[c].gen.wrapping_add(1);
                }
            }
            for c in [i, j] {
                self.predict(c, true);
            }
            return true;
        }
        let mut alpha = self.braking(&members);
        (alpha[0], alpha[1]) = (braking[0], braking[1]);
        if !self.press_biases(&members, &mut contacts, &vel, &alpha) {
            return false;
        }
        let Some(mut after) = self.press_closure(&members, &mut contacts, &vel, &inv, &alpha, t)
        else {
            return false;
        };
        if self.config.revision.bounds_cluster_kick_energy() {
            // The scene's kinetic energy now, the hit's outgoing
            // trajectories in place.
            let scene: f64 = self
                .slots
                .iter()
                .zip(&self.material)
                .filter(|(s, _)| s.alive)
                .map(|(s, m)| 0.5 * m.mass * s.traj.velocity(t).length_squared())
                .sum();
            match within_press_bound(&vel, &inv, &contacts, after, scene) {
                Some(held) => after = held,
                None => return false,
            }
        }
        self.kick_cluster(&members, &vel, &after, [i, j], t);
        true
    }

    /// The projection of a pressing kick over a cluster: `members` (slots)
    /// from velocities `vel` (inverse masses `inv`, braking `alpha`), every
    /// contact of `contacts` biased where its pair presses. From the fourth
    /// revision, a pair that the projection itself leaves pressed (it did
    /// not press at `vel`) gets its bounce speed too and the projection is
    /// taken again, for at most [`PRESS_ROUNDS`] rounds: left out, it hit
    /// again at once and its own kick left the first pair pressed, the two
    /// trading the kick at one instant. `None` where a projection has no
    /// answer.
    fn press_closure(
        &self,
        members: &[usize],
        contacts: &mut [collapse::Contact],
        vel: &[DVec2],
        inv: &[f64],
        alpha: &[f64],
        t: f64,
    ) -> Option<Vec<DVec2>> {
        // From the nineteenth revision, where projected Gauss–Seidel stalls
        // on the biased contacts, the active-set method finds the kick, in
        // a cluster small enough for its search (`EXACT_KICK_CLUSTER`).
        // From the twentieth, in a larger one by the factored method, for
        // at most `KICK_SEARCHES_PER_INSTANT` searches at one instant.
        let revision = self.config.revision;
        let small = members.len() <= EXACT_KICK_CLUSTER;
        let exact = revision.finds_stalled_cluster_kicks_by_active_set() && small;
        let factored = revision.finds_large_cluster_kicks_by_factored_active_set()
            && !small
            && self.kick_searches_at(t) < KICK_SEARCHES_PER_INSTANT;
        let solve = |contacts: &[collapse::Contact]| {
            collapse::resolve(vel, inv, contacts, PRESS_SWEEPS).or_else(|| {
                if exact {
                    collapse::active_set(vel, inv, contacts)
                } else if factored {
                    let searched = self.kick_searches_at(t);
                    self.kick_searches.set((t, searched + 1));
                    collapse::factored_active_set(vel, inv, contacts)
                } else {
                    None
                }
            })
        };
        let mut after = solve(contacts)?;
        if !self.config.revision.at_least_r4() {
            return Some(after);
        }
        for _ in 0..PRESS_ROUNDS {
            if !self.press_biases(members, contacts, &after, alpha) {
                break;
            }
            after = solve(contacts)?;
        }
        Some(after)
    }

    /// How many factored kick searches were made at the instant of `t`.
    fn kick_searches_at(&self, t: f64) -> u32 {
        let (at, searched) = self.kick_searches.get();
        if t == at || (t >= at && same_instant(at, t)) {
            searched
        } else {
            0
        }
    }

    /// Gives `members` their velocities `after` a pressing kick or stop of
    /// the pair `i`, `j` (whose trajectories were replaced by the hit
    /// either way) and predicts every disc that changed.
    fn kick_cluster(
        &mut self,
        members: &[usize],
        before: &[DVec2],
        after: &[DVec2],
        [i, j]: [usize; 2],
        t: f64,
    ) {
        let mut changed = self.set_velocities(members, before, after, t);
        for c in [i, j] {
            if !changed.contains(&c) {
                self.slots[c].gen = self.slots[c].gen.wrapping_add(1);
                changed.push(c);
            }
        }
        for &c in &changed {
            self.predict(c, true);
        }
    }

    /// The velocities of `members` (slots) at `t` and their inverse masses.
    fn motion(&self, members: &[usize], t: f64) -> (Vec<DVec2>, Vec<f64>) {
        members
            .iter()
            .map(|&c| (self.slots[c].traj.velocity(t), 1.0 / self.material[c].mass))
            .unzip()
    }

    /// The braking each of `members` (slots) has now: a disc of a pushed
    /// chain brakes with the chain.
    fn braking(&self, members: &[usize]) -> Vec<f64> {
        members
            .iter()
            .map(|&c| self.slots[c].traj.alpha())
            .collect()
    }

    /// Sets the bias of every contact not biased yet between two discs of
    /// `members` that press each other obliquely at velocities `vel`, each
    /// braked by its `alpha` against its velocity, to their bounce speed;
    /// `true` if any does.
    fn press_biases(
        &self,
        members: &[usize],
        contacts: &mut [collapse::Contact],
        vel: &[DVec2],
        alpha: &[f64],
    ) -> bool {
        let braking = |k: usize| -alpha[k] * vel[k].normalize_or_zero();
        let mut any = false;
        for c in contacts.iter_mut().filter(|c| c.bias == 0.0) {
            let Some(b) = c.b else { continue };
            let (a, b) = (c.a, b);
            if vel[a] == DVec2::ZERO || vel[b] == DVec2::ZERO {
                continue;
            }
            let s = self.slots[members[a]].radius + self.slots[members[b]].radius;
            let (v, acc) = ([vel[a], vel[b]], [braking(a), braking(b)]);
            if let Some(w) = push::bounce_speed(v, acc, c.n, s, self.config.revision) {
                c.bias = w;
                any = true;
            }
        }
        any
    }

    /// Every live disc touching `seed` (slots) or touching one that does
    /// (at most [`MAX_COLLAPSE`]), at `t`, and their contacts with each
    /// other and with the solid lines and points they touch (indices into
    /// the members).
    fn touching_cluster(
        &self,
        mut members: Vec<usize>,
        t: f64,
    ) -> (Vec<usize>, Vec<collapse::Contact>) {
        // Grow to every disc touching a member.
        let at = self.positions(t);
        let mut k = 0;
        while k < members.len() && members.len() < MAX_COLLAPSE {
            for c in self.touching(members[k], &at) {
                if !members.contains(&c) {
                    members.push(c);
                }
            }
            k += 1;
        }
        let contacts = self.contacts_among(&members, t);
        (members, contacts)
    }

    /// Every slot's position at `t` (a dead one's too, never read), for
    /// [`World::touching`]: each formed once however many discs ask.
    fn positions(&self, t: f64) -> Vec<DVec2> {
        self.slots.iter().map(|s| s.traj.position(t)).collect()
    }

    /// The live discs other than `m` (slots) that touch it where the
    /// slots are at `at` ([`World::positions`]).
    fn touching<'a>(&'a self, m: usize, at: &'a [DVec2]) -> impl Iterator<Item = usize> + 'a {
        let pm = at[m];
        let rm = self.slots[m].radius;
        (0..self.slots.len()).filter(move |&c| {
            let s = &self.slots[c];
            c != m && s.alive && (at[c] - pm).length() <= (rm + s.radius) * (1.0 + push::TOUCHING)
        })
    }

    /// Every contact among `members` (slots) at `t`, and of each with the
    /// solid lines and points it touches, indexed into `members`.
    fn contacts_among(&self, members: &[usize], t: f64) -> Vec<collapse::Contact> {
        // Each member's position, formed once.
        let at: Vec<DVec2> = members
            .iter()
            .map(|&c| self.slots[c].traj.position(t))
            .collect();
        let touching = |gap: f64, s: f64| gap <= s * (1.0 + push::TOUCHING);
        let mut contacts = Vec::new();
        for (a, &ca) in members.iter().enumerate() {
            let (pa, r) = (at[a], self.slots[ca].radius);
            for (b, &cb) in members.iter().enumerate().skip(a + 1) {
                let d = pa - at[b];
                if touching(d.length(), r + self.slots[cb].radius) {
                    let n = d.normalize_or_zero();
                    contacts.push(collapse::Contact::plastic(a, Some(b), n));
                }
            }
            for &line in &self.solid {
                let g = &self.geoms[line as usize];
                if !touching(g.distance(pa), r) {
                    continue;
                }
                let n = if g.covers(pa) {
                    g.n * g.signed_distance(pa).signum()
                } else {
                    let end = g
                        .ends
                        .iter()
                        .flatten()
                        .min_by(|x, y| (pa - **x).length().total_cmp(&(pa - **y).length()));
                    end.map_or(DVec2::ZERO, |q| (pa - *q).normalize_or_zero())
                };
                contacts.push(collapse::Contact::plastic(a, None, n));
            }
            for q in &self.points {
                if touching((pa - q.pos).length(), r) {
                    let n = (pa - q.pos).normalize_or_zero();
                    contacts.push(collapse::Contact::plastic(a, None, n));
                }
            }
        }
        contacts.retain(|c| c.n != DVec2::ZERO);
        contacts
    }

    /// Gives each of `members` whose velocity `after` differs from `before`
    /// its new trajectory from `t` (marking its predictions stale); returns
    /// those slots. From the third revision, if every one of them that
    /// moves would slide less than the rounding of its position (see
    /// [`World::settled`]), they all rest instead.
    fn set_velocities(
        &mut self,
        members: &[usize],
        before: &[DVec2],
        after: &[DVec2],
        t: f64,
    ) -> Vec<usize> {
        let new = |w: &World, k: usize, c: usize| {
            let p = w.slots[c].traj.position(t);
            Trajectory::new(t, p, after[k], w.material[c].mu * w.g)
        };
        // Every member as it would go on, changed or not.
        let all_settle = self.config.revision.at_least_r3()
            && members.iter().enumerate().all(|(k, &c)| {
                let tr = if after[k] != before[k] {
                    new(self, k, c)
                } else {
                    self.slots[c].traj
                };
                !tr.is_moving_at(t) || !self.settled(tr, t).is_moving()
            });
        let mut changed = Vec::new();
        for (k, &c) in members.iter().enumerate() {
            let tr = if all_settle {
                if !self.slots[c].traj.is_moving_at(t) && after[k] == before[k] {
                    continue;
                }
                Trajectory::at_rest(
                    t,
                    self.slots[c].traj.position(t),
                    self.material[c].mu * self.g,
                )
            } else if after[k] != before[k] {
                new(self, k, c)
            } else {
                continue;
            };
            self.slots[c].traj = tr;
            self.slots[c].gen = self.slots[c].gen.wrapping_add(1);
            changed.push(c);
        }
        changed
    }

    /// `tr`, begun at `t`, or from the third revision a disc at rest there
    /// if what is left of its slide is shorter than the rounding of its
    /// position ([`SETTLE`]): such a motion changes nothing a position can
    /// show, yet a hit between two discs slower than 1e-13 m/s would repeat
    /// at about one instant for ever. Used where nothing else can approach
    /// the disc because of it: a hit on an obstacle, or a pair of which
    /// both settle (one alone at rest would be hit again by the other).
    fn settled(&self, tr: Trajectory, t: f64) -> Trajectory {
        if !self.config.revision.at_least_r3() || tr.alpha() == 0.0 || !tr.is_moving_at(t) {
            return tr;
        }
        let p = tr.position(t);
        if tr.stopping_distance() <= SETTLE * p.abs().max_element() {
            Trajectory::at_rest(t, p, tr.alpha())
        } else {
            tr
        }
    }

    /// Whether every moving body is still within the range where squared
    /// distances are finite at time `t` (only asked far in the future).
    fn in_range_at(&self, t: f64) -> bool {
        self.slots.iter().all(|s| {
            !s.alive || !s.traj.is_moving_at(t) || {
                let p = s.traj.position(t);
                p.x.abs() < MAX_COORDINATE && p.y.abs() < MAX_COORDINATE
            }
        })
    }

    fn end_on(&self, reason: EndReason) -> End {
        End {
            t: self.clock.absolute(self.last_event_t),
            reason,
        }
    }

    fn end_at_rest(&self) -> End {
        self.end_on(if self.any_moving() {
            EndReason::Free
        } else {
            EndReason::Rest
        })
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
        if self.cross[i].0 <= self.pending[i].t {
            self.cross_cell(i);
            return None;
        }
        let kind = match self.pending[i].next {
            Next::None => {
                self.calendar.set(i, f64::INFINITY);
                return None;
            }
            Next::Body { other, other_gen } => {
                let j = other as usize;
                if !self.slots[j].alive || self.slots[j].gen != other_gen {
                    // Re-predict, scanning even if `i` rests: a mover may have
                    // predicted against `i` while `i` still moved (only up to
                    // its stop) and be relying on `i`'s entry for the rest.
                    self.stats.stale += 1;
                    self.predict(i, true);
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
                let tr = &self.slots[i].traj;
                self.slots[i].traj = Trajectory::at_rest(t, tr.position(t), tr.alpha());
                self.changed(i);
                self.stats.stops += 1;
                EventKind::Stop { body: self.ids[i] }
            }
            Next::Line(k, end) => {
                let geom = &self.geoms[k as usize];
                let p = self.slots[i].traj.position(t);
                let (n, dist) = match end {
                    Some(e) => {
                        let d = p - geom.ends[e as usize].unwrap_or(p);
                        (d.normalize_or_zero(), d.length())
                    }
                    None => {
                        let d = geom.signed_distance(p);
                        (if d >= 0.0 { geom.n } else { -geom.n }, d.abs())
                    }
                };
                self.bounce(i, t, n, dist);
                self.stats.body_line += 1;
                EventKind::BodyLine {
                    body: self.ids[i],
                    line: LineId(k),
                    end,
                }
            }
            Next::Point(k) => {
                let p = self.slots[i].traj.position(t);
                let d = p - self.points[k as usize].pos;
                self.bounce(i, t, d.normalize_or_zero(), d.length());
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
                let was_inside = self.slots[i].sides & (1 << bit) != 0;
                self.slots[i].sides ^= 1 << bit;
                if !reported {
                    self.predict(i, true);
                    return None;
                }
                let (body, line) = (self.ids[i], LineId(line));
                if !was_inside {
                    self.predict(i, true);
                    EventKind::RegionEntry { body, line }
                } else {
                    let removed = handler.on_region_exit(self.clock.absolute(t), body, line)
                        == ExitResponse::Remove;
                    if removed {
                        self.remove_slot(i, t);
                    } else {
                        self.predict(i, true);
                    }
                    self.stats.region_exits += 1;
                    EventKind::RegionExit {
                        body,
                        line,
                        removed,
                    }
                }
            }
        };
        self.last_event_t = t;
        self.stats.events += 1;
        Some(Event {
            t: self.clock.absolute(t),
            kind,
        })
    }

    /// Every body's next event from scratch (the naive loop, for comparison).
    fn recompute_all(&mut self) {
        for i in 0..self.slots.len() {
            if self.slots[i].alive {
                self.predict(i, true);
            }
        }
    }

    /// Body `i` moves into the next grid cell: its pending event stays valid
    /// (its motion did not change); only the cells that came into reach are
    /// searched, and the next crossing is found.
    fn cross_cell(&mut self, i: usize) {
        self.stats.cell_crossings += 1;
        let step = self.cross[i].1;
        let Some(grid) = self.grid.as_mut() else {
            self.cross[i].0 = f64::INFINITY;
            return;
        };
        grid.step(i, step);
        let mut best = self.pending[i];
        let tr = self.slots[i].traj;
        let mover = Mover::new(&tr, self.t);
        let mut unused = None;
        let grid = self.grid.as_ref().expect("checked above");
        let si = &self.slots[i];
        for cell in grid.entered_cells(i, step) {
            for &j in cell {
                let j = j as usize;
                if let Some(sj) = self.slots.get(j) {
                    let m = mover.as_ref();
                    self.offer_pair(i, si, m, j, sj, None, &mut best, &mut unused);
                }
            }
        }
        self.cross[i] = mover
            .and_then(|m| grid.next_crossing(i, &m))
            .unwrap_or((f64::INFINITY, (0, 0)));
        self.pending[i] = best;
        self.calendar.set(i, best.t.min(self.cross[i].0));
    }

    fn collide(&mut self, i: usize, j: usize, t: f64) {
        let (ti, tj) = (self.slots[i].traj, self.slots[j].traj);
        let (mut pi, mut pj) = (ti.position(t), tj.position(t));
        let (mi, mj) = (self.material[i], self.material[j]);
        let d = pi - pj;
        let n = d.normalize_or_zero();
        let s = mi.radius + mj.radius;
        // The square first: only a distance off by nearly SNAP needs a root.
        if self.config.revision.at_least_r2()
            && (d.length_squared() - s * s).abs() > 1.9 * SNAP * s * s
        {
            let gap = snap(s, d.length());
            let (w_i, w_j) = impulse::weights(mi.mass, mj.mass);
            pi += n * (gap * w_j);
            pj -= n * (gap * w_i);
        }
        let e = mi.restitution.min(mj.restitution);
        let (ui, uj) = (ti.velocity(t), tj.velocity(t));
        self.last_approach = (uj - ui).dot(n);
        // From the seventeenth revision, a pair parting so slowly that its
        // braking brings it back within the rounding of `t` is taken as the
        // pushed pair it is, its normal velocities made one.
        let (ui, uj) = match self
            .config
            .revision
            .rejoins_pairs_parting_within_instant()
            .then(|| {
                push::rejoined_at_once(
                    [ui, uj],
                    [ti.acceleration(t), tj.acceleration(t)],
                    [mi.mass, mj.mass],
                    n,
                    t,
                )
            })
            .flatten()
        {
            Some([vi, vj]) => (vi, vj),
            None => (ui, uj),
        };
        // From the twelfth revision, a gentle plastic hit on a light disc
        // in a corner is taken with the walls it touches.
        if e == 0.0
            && self.config.revision.takes_cornered_hit_with_walls()
            && self.last_approach.abs() <= CORNER_GENTLE * ui.length().max(uj.length())
            && self.cornered_hit(i, j, t)
        {
            self.stats.collapses += 1;
            return;
        }
        // From the thirteenth revision, a plastic hit that drives a light
        // plastic disc into an obstacle it touches is taken with it.
        if e == 0.0
            && self.config.revision.takes_walled_hit_with_wall()
            && self.walled_hit(i, j, [ui, uj], n, t)
        {
            self.stats.collapses += 1;
            return;
        }
        // From the nineteenth revision, a plastic hit that drives a disc
        // sliding along the one obstacle it touches into it, as that disc
        // wedges a braking one aside, is carried before it is taken as a
        // ring into that obstacle.
        if e == 0.0
            && self.config.revision.carries_wedges_before_wall_rings()
            && self.carried_press(i, j, [pi, pj], [ui, uj], n, Carry::AlongOwnWall, t)
        {
            self.stats.pressed += 1;
            return;
        }
        // From the thirteenth revision, a plastic hit that drives a disc
        // into an obstacle it touches, the two then ringing between the
        // obstacle and each other, is taken with the obstacle.
        if e == 0.0
            && self.config.revision.takes_hit_into_wall_with_wall()
            && self.hit_into_wall(i, j, n, [ui, uj], false, t)
        {
            self.stats.collapses += 1;
            return;
        }
        // From the fourteenth revision, a plastic hit whose touching
        // cluster rings without end is taken to the limit of its ring.
        if e == 0.0
            && self.config.revision.takes_cluster_rings_at_once()
            && self.cluster_ring(i, j, n, [ui, uj], t)
        {
            self.stats.collapses += 1;
            return;
        }
        // From the fourteenth revision, a disc wedging a strongly braked
        // one aside as it slides past takes it along as one body.
        if self.config.revision.carries_wedged_discs()
            && self.carried_press(i, j, [pi, pj], [ui, uj], n, Carry::Any, t)
        {
            self.stats.pressed += 1;
            return;
        }
        // From the eighteenth revision, an elastic hit of two frictionless
        // discs that rings between an obstacle and the pair is played to
        // its end at once.
        if e == 1.0
            && self.config.revision.plays_elastic_wall_rings_at_once()
            && self.elastic_wall_ring(i, j, [pi, pj], [ui, uj], n, t)
        {
            self.stats.collapses += 1;
            return;
        }
        let (mut vi, mut vj) = impulse::body_body(ui, uj, mi.mass, mj.mass, e, n);
        // Each gets its own friction back (a pushed pair shares one).
        let alpha = [mi.mu * self.g, mj.mu * self.g];
        let (mut new_i, mut new_j) = (
            Trajectory::new(t, pi, vi, alpha[0]),
            Trajectory::new(t, pj, vj, alpha[1]),
        );
        let origin = self.clock.origin();
        if e > 0.0
            && (push::chatters(&new_i, &new_j, n, t, origin, self.config.revision)
                || (self.config.revision.ends_bounces_within_touch()
                    && push::bounces_within_touch(&new_i, &new_j, n, s, t))
                || (e == 1.0
                    && self.config.revision.ends_long_bounces_within_gap()
                    && push::bounces_long_within_gap(
                        &new_i,
                        &new_j,
                        [mi.mass, mj.mass],
                        n,
                        s,
                        t,
                        self.config.revision,
                    )))
        {
            // From the fourteenth revision, a chatter's end that drives a
            // disc into an obstacle it touches, the two then ringing, is
            // taken with the obstacle, as a plastic hit is.
            if self
                .config
                .revision
                .takes_captured_hit_into_wall_with_wall()
                && self.hit_into_wall(i, j, n, [ui, uj], true, t)
            {
                self.stats.collapses += 1;
                return;
            }
            // The pair would bounce ever faster into a pressing contact:
            // take the chatter's end, one plastic hit, now.
            (vi, vj) = impulse::body_body(ui, uj, mi.mass, mj.mass, 0.0, n);
            (new_i, new_j) = (
                Trajectory::new(t, pi, vi, alpha[0]),
                Trajectory::new(t, pj, vj, alpha[1]),
            );
        }
        if push::pushing(&new_i, pi, &new_j, pj, t) {
            self.slots[i].traj = new_i;
            self.slots[j].traj = new_j;
            if self.push_chain(i, j, t) {
                return;
            }
            let (v, a) = push::together([vi, vj], [mi.mass, mj.mass], alpha);
            (new_i, new_j) = (Trajectory::new(t, pi, v, a), Trajectory::new(t, pj, v, a));
        } else if self.config.revision.at_least_r3()
            && (ti.alpha() > 0.0 || tj.alpha() > 0.0)
            && self.press_cluster(i, j, [new_i, new_j], n, [ti.alpha(), tj.alpha()], t)
        {
            // Pressed together obliquely, with the braking each had (a disc
            // of a pushed chain brakes with the chain), and touching others:
            // the approximated contact over the whole touching cluster.
            self.stats.pressed += 1;
            return;
        } else if let Some(press) = self.pressing(&new_i, &new_j, n, s, t) {
            // Pressed together obliquely: the approximated contact.

            (new_i, new_j) = match press {
                push::Press::Part(dw) => {
                    let (w_i, w_j) = impulse::weights(mi.mass, mj.mass);
                    vi += n * (dw * w_j);
                    vj -= n * (dw * w_i);
                    (
                        Trajectory::new(t, pi, vi, alpha[0]),
                        Trajectory::new(t, pj, vj, alpha[1]),
                    )
                }
                push::Press::Rest => (
                    Trajectory::at_rest(t, pi, alpha[0]),
                    Trajectory::at_rest(t, pj, alpha[1]),
                ),
            };
            self.stats.pressed += 1;
        }
        // From the seventeenth revision, a hit that settles both discs
        // stops whatever runs into them (see `World::settled_hit`).
        if self.config.revision.stops_discs_running_into_settled_hits()
            && self.settled_hit(i, j, [new_i, new_j], [ui, uj], t)
        {
            return;
        }
        self.leave_hit(i, j, new_i, new_j, t);
    }

    /// From the seventeenth revision, a hit that leaves both discs in
    /// slots `i` and `j` (on `new`, `u` their velocities before it) at
    /// rest, their slides below the rounding of their positions
    /// (`World::settled`), where a disc touching them still runs into
    /// them: whatever runs into the pair (or into one that does) keeps
    /// only what does not run into it, the plastic limit with the pair
    /// held, as the third revision stops it against a pressed pair that
    /// rests; only where both discs of the pair brake and what runs in
    /// has no more kinetic energy than the weaker of their friction
    /// forces spends over the pressing contact's gap (friction holds
    /// them, as `push::spent_within_gap` rests a pressed pair by its
    /// energy). Left moving, the disc behind hit the resting one again at
    /// once, and a pushed pair caught a light disc it had pressed into a
    /// heavily braked one, the hit against that one settling the light
    /// disc each time, the frictionless pusher losing only the light
    /// disc's share of its speed (0.63 per cent) a turn: a frictionless
    /// disc (0.31 kg) at 5.6e-9 m/s pushing a 1.9 g disc into one braking
    /// at 240 m/s^2, 1,708 events at one instant until `stuck`. `false`
    /// (nothing done) where either disc moves on, neither moved before,
    /// no disc runs into the pair, what runs in has the energy to move
    /// it, or the limit has no answer. From the eighteenth revision a disc
    /// that runs into a member only once the limit has stopped it is taken
    /// in too, the limit solved again until none does: a frictionless disc
    /// sliding down the side wall along a light one on the floor shared
    /// its motion along their normal, ran into it once it was stopped,
    /// and hit it again at that instant, until the event cap (mixed-box
    /// 531237; `Revision::stops_discs_running_into_stopped_discs`). Where
    /// the wider limit fails the test of energy or has no answer, the
    /// narrower one is kept (refused whole, mixed-box 425978 went back to
    /// `stuck`).
    fn settled_hit(
        &mut self,
        i: usize,
        j: usize,
        [new_i, new_j]: [Trajectory; 2],
        [ui, uj]: [DVec2; 2],
        t: f64,
    ) -> bool {
        let (rest_i, rest_j) = (self.settled(new_i, t), self.settled(new_j, t));
        if rest_i.is_moving() || rest_j.is_moving() || (ui == DVec2::ZERO && uj == DVec2::ZERO) {
            return false;
        }
        let (old_i, old_j) = (self.slots[i].traj, self.slots[j].traj);
        self.slots[i].traj = rest_i;
        self.slots[j].traj = rest_j;
        // The pair, and every disc that runs into a member, in turn.
        let at = self.positions(t);
        let noise = 1e-12 * ui.length().max(uj.length());
        let mut members = vec![i, j];
        let mut k = 0;
        while k < members.len() && members.len() < MAX_COLLAPSE {
            let m = members[k];
            let vm = self.slots[m].traj.velocity(t);
            let behind: Vec<usize> = self
                .touching(m, &at)
                .filter(|c| !members.contains(c))
                .filter(|&c| {
                    let n = (at[m] - at[c]).normalize_or_zero();
                    (vm - self.slots[c].traj.velocity(t)).dot(n) < -noise
                })
                .collect();
            members.extend(behind);
            k += 1;
        }
        // Held by their friction: what runs into them has no more kinetic
        // energy than the weaker of their friction forces spends over the
        // pressing contact's gap, as a pressed pair rests by its energy
        // (`push::spent_within_gap`).
        let (mi, mj) = (self.material[i], self.material[j]);
        let weakest = (mi.mass * mi.mu).min(mj.mass * mj.mu) * self.g;
        let gap = push::press_gap(self.config.revision) * (mi.radius + mj.radius);
        // From the eighteenth revision, a disc that runs into a member as
        // the limit leaves it (stopped against the pair) is taken in too,
        // and the limit solved again, until none does.
        let closed = self
            .config
            .revision
            .stops_discs_running_into_stopped_discs();
        // The last limit found before the discs running into it were
        // taken in: kept where the wider one is refused.
        let mut narrower: Option<(usize, Vec<DVec2>, Vec<DVec2>)> = None;
        let (vel, after) = loop {
            let mut contacts = self.contacts_among(&members, t);
            let (vel, mut inv) = self.motion(&members, t);
            (inv[0], inv[1]) = (0.0, 0.0);
            let energy: f64 = members[2..]
                .iter()
                .zip(&vel[2..])
                .map(|(&c, v)| 0.5 * self.material[c].mass * v.length_squared())
                .sum();
            let after = if weakest > 0.0 && energy <= weakest * gap {
                contacts.retain(|c| c.a >= 2 || c.b.is_some_and(|b| b >= 2));
                (members.len() > 2)
                    .then(|| {
                        collapse::resolve(&vel, &inv, &contacts, PRESS_SWEEPS)
                            .or_else(|| collapse::active_set(&vel, &inv, &contacts))
                    })
                    .flatten()
            } else {
                None
            };
            let Some(after) = after else {
                match narrower {
                    Some((len, vel, after)) => {
                        members.truncate(len);
                        break (vel, Some(after));
                    }
                    None => break (vel, None),
                }
            };
            if !closed {
                break (vel, Some(after));
            }
            let behind = self.running_into(&members, &after, &at, noise, t);
            if behind.is_empty() || members.len() + behind.len() > MAX_COLLAPSE {
                break (vel, Some(after));
            }
            narrower = Some((members.len(), vel, after));
            members.extend(behind);
        };
        let Some(mut after) = after else {
            self.slots[i].traj = old_i;
            self.slots[j].traj = old_j;
            return false;
        };
        for v in &mut after {
            if v.length() <= noise {
                *v = DVec2::ZERO;
            }
        }
        self.kick_cluster(&members, &vel, &after, [i, j], t);
        true
    }

    /// The live discs outside `members` (slots) that touch one of them
    /// (the slots at `at`, [`World::positions`]) and run into it faster
    /// than `noise` where the members move at `after` (their velocities
    /// out of a limit), the discs outside at their own velocities at `t`.
    fn running_into(
        &self,
        members: &[usize],
        after: &[DVec2],
        at: &[DVec2],
        noise: f64,
        t: f64,
    ) -> Vec<usize> {
        let mut behind: Vec<usize> = Vec::new();
        for (&m, &vm) in members.iter().zip(after) {
            for c in self.touching(m, at) {
                let n = (at[m] - at[c]).normalize_or_zero();
                if !members.contains(&c)
                    && !behind.contains(&c)
                    && (vm - self.slots[c].traj.velocity(t)).dot(n) < -noise
                {
                    behind.push(c);
                }
            }
        }
        behind
    }

    /// Puts the discs in slots `i` and `j` on their trajectories out of a
    /// hit at `t`, both at rest if neither would move beyond the rounding
    /// of `t` (one alone at rest would be hit again by the other at once),
    /// and predicts their next events.
    fn leave_hit(&mut self, i: usize, j: usize, new_i: Trajectory, new_j: Trajectory, t: f64) {
        let (rest_i, rest_j) = (self.settled(new_i, t), self.settled(new_j, t));
        let (new_i, new_j) = if !rest_i.is_moving() && !rest_j.is_moving() {
            (rest_i, rest_j)
        } else {
            (new_i, new_j)
        };
        self.slots[i].traj = new_i;
        self.slots[j].traj = new_j;
        self.slots[i].gen = self.slots[i].gen.wrapping_add(1);
        self.slots[j].gen = self.slots[j].gen.wrapping_add(1);
        // The pair (i, j) is solved once, for both.
        let pair = self.predict_with(i, true, Some((j, None)));
        self.predict_with(j, true, Some((i, pair)));
    }

    /// From the fourteenth revision, a hit between the discs in slots `i`
    /// and `j` (at `p`, unit normal `n` towards `i`, velocities `u` before
    /// it) after which one of them, sliding nearly past the other, presses
    /// it obliquely and has to wedge it aside, the pushed one braking
    /// harder and carried along the normal only (see [`push::carried`]):
    /// taken at once as the pair's pressing limit, one sliding body that
    /// stops where the pushed disc's friction has spent the pair's energy
    /// along the tractrix (or, where the pusher can pass, has it pay that
    /// friction at once), instead of the approximated contact's bounces.
    /// Only where the pushing disc touches something else that takes the
    /// sideways part of the contact force (a wall it slides along, a disc
    /// it slides past): a free one would be turned away by it; only where
    /// the pushed disc touches nothing else; and once an instant (neither
    /// disc already hit at `t`: a pair carried and pressed again at once
    /// by its neighbours rang at one instant). The hit is
    /// plastic (an elastic pair so pressed is at the end of its chatter, as
    /// `push::chatters` takes one). Nor where the hit drives the pushing
    /// disc into an obstacle it touches (a disc sliding along a wall): the
    /// obstacle's hit, at once, took its carried braking away, and the
    /// pushed disc stopped before it passed. A heavy frictionless disc
    /// touching another slid past a light disc braking at 150 m/s^2, which
    /// the pressing contact kicked aside at every hit; it stopped a
    /// microsecond later and was caught again, two events a cycle until the
    /// event cap. `false` (nothing done) where the rule does not apply.
    /// With [`Carry::AlongOwnWall`] (the nineteenth revision's call before
    /// the hit is taken as a ring into an obstacle), only where the plastic
    /// hit drives the pushing disc into the one obstacle it slides along.
    #[allow(clippy::too_many_arguments)]
    fn carried_press(
        &mut self,
        i: usize,
        j: usize,
        [pi, pj]: [DVec2; 2],
        [ui, uj]: [DVec2; 2],
        n: DVec2,
        scope: Carry,
        t: f64,
    ) -> bool {
        let (mi, mj) = (self.material[i], self.material[j]);
        let alpha = [mi.mu * self.g, mj.mu * self.g];
        // One disc brakes harder (never so between discs of one material,
        // as in the game: the test ends there).
        if alpha[0] == alpha[1] {
            return false;
        }
        // Once an instant: a pair already carried (or hit) at `t` that
        // meets again at `t` is pressed by something else as well, and is
        // left to the pressing contact and the collapse rules.
        if self.slots[i].traj.start_time() == t || self.slots[j].traj.start_time() == t {
            return false;
        }
        let (mut vi, mut vj) = impulse::body_body(ui, uj, mi.mass, mj.mass, 0.0, n);
        // From the fifteenth revision, a pushing disc sliding along the one
        // obstacle it touches, which the hit would drive into it, is held
        // to it through the hit (see `World::hit_along_wall`).
        let mut along_wall = false;
        // From the sixteenth revision, the disc pinned by its walls that
        // holds the pushing disc instead of a wall (see
        // `World::pinning_disc`).
        let mut pinning = None;
        if self.config.revision.carries_wedged_discs_along_walls()
            || self.config.revision.carries_along_walls()
        {
            if let Some(([wi, wj], p)) = self.hit_along_wall(i, j, [ui, uj], [vi, vj], n, alpha, t)
            {
                (vi, vj) = (wi, wj);
                along_wall = true;
                pinning = p;
            }
        }
        // From the nineteenth revision, asked before the hit is taken as a
        // ring into an obstacle: only a pushing disc that the hit drives
        // into the one obstacle it slides along (see
        // `Revision::carries_wedges_before_wall_rings`).
        if scope == Carry::AlongOwnWall && !(along_wall && pinning.is_none()) {
            return false;
        }
        let s = mi.radius + mj.radius;
        // Only where the approximated contact would kick the pair apart
        // (not where it rests it: too slow to slide beyond its gap, or its
        // next bounce within the rounding of the time).
        let plastic = (
            Trajectory::new(t, pi, vi, alpha[0]),
            Trajectory::new(t, pj, vj, alpha[1]),
        );
        if !matches!(
            self.pressing(&plastic.0, &plastic.1, n, s, t),
            Some(push::Press::Part(_))
        ) {
            return false;
        }
        // From the sixteenth revision, a pushed disc held to the one
        // obstacle it touches slides along it (see `World::wedged_along_wall`).
        if self
            .config
            .revision
            .carries_wedged_discs_along_their_walls()
            && self.wedged_along_wall(i, j, [pi, pj], [ui, uj], n, t)
        {
            return true;
        }
        let before = [vi, vj];
        let Some([(vi, ai), (vj, aj)]) = push::carried(
            [vi, vj],
            [mi.mass, mj.mass],
            alpha,
            n,
            s,
            self.config.revision,
        ) else {
            return false;
        };
        // The pushing disc (the one braking less) must touch something
        // besides its partner, and the pushed one nothing else (carried
        // along the normal, it would be driven into it, and hit back at
        // once: the cluster is the pressing kick's).
        let (h, l) = if alpha[1] > alpha[0] { (i, j) } else { (j, i) };
        let at = self.positions(t);
        let held =
            self.touching(h, &at).any(|c| c != l) || !self.contacts_among(&[h], t).is_empty();
        let free = self.touching(l, &at).all(|c| c == h) && self.contacts_among(&[l], t).is_empty();
        // From the seventeenth revision, a pushed disc driven into a disc
        // at rest that holds it is carried round it (see
        // `World::carried_around_held`).
        if held
            && !free
            && self.config.revision.carries_discs_round_held_discs()
            && self.carried_around_held(h, l, [i, j], [pi, pj], before, &at, t)
        {
            return true;
        }
        if !(held && free) {
            return false;
        }
        // Held by the obstacle through the hit, in two cases. Where the
        // pair stops together (the pushing disc keeps its velocity and
        // brakes to the common stop), only where the pushing disc touches
        // no other disc: a frictionless one sliding behind it caught it at
        // once as it braked, and the two were hit in turn, a microsecond
        // apart (mixed-box 62000 and 56990 ran so to the event cap). Where
        // the pusher passes, carrying the pushed disc ahead beyond the
        // pressing contact's gap, only where the pushed disc's whole carry
        // keeps clear of every other disc: carried into a neighbour close
        // by, it was hit back, the pusher hit it again at that instant,
        // and the carried braking was lost.
        if along_wall {
            let (v_h, a_h, alpha_h) = if h == i {
                (vi, ai, alpha[0])
            } else {
                (vj, aj, alpha[1])
            };
            let stops = v_h == before[usize::from(h == j)];
            if stops {
                let alone = self
                    .touching(h, &at)
                    .all(|c| c == i || c == j || Some(c) == pinning);
                if !(self.config.revision.carries_wedged_discs_along_walls() && alone) {
                    return false;
                }
            } else {
                if !(self.config.revision.carries_along_walls() && a_h == alpha_h) {
                    return false;
                }
                let (v_l, a_l) = if l == i { (vi, ai) } else { (vj, aj) };
                if self.slide_blocked(l, h, v_l, a_l, &at) {
                    return false;
                }
            }
        }
        // Nor where the hit drives the pushing disc into an obstacle it
        // touches: the obstacle's hit, at once, takes its carried braking
        // away, and the pushed disc stops before it passes.
        let v_h = if h == i { vi } else { vj };
        let noise = 1e-12 * v_h.length();
        if self
            .contacts_among(&[h], t)
            .iter()
            .any(|c| c.b.is_none() && v_h.dot(c.n) < -noise)
        {
            return false;
        }
        // Left as `World::collide` leaves a hit.
        let new_i = Trajectory::new(t, pi, vi, ai);
        let new_j = Trajectory::new(t, pj, vj, aj);
        self.leave_hit(i, j, new_i, new_j, t);
        true
    }

    /// From the seventeenth revision, a hit about to be carried
    /// ([`World::carried_press`]: the pushing disc in slot `h`, the pushed
    /// one in slot `l`, the pair's slots `ij` at `p` with velocities `v`
    /// just after the plastic hit) whose pushed disc `L`, light, touches
    /// no obstacle and one disc `P` besides the pusher `H`, at rest and
    /// braking, that the push drives it into: `P`'s friction holds it, and
    /// `L` is carried round it as `H` slides past
    /// ([`pivot::carried_around`]), where `H` touches no other disc that
    /// moves (stopped, it would be caught at once), the hit does not drive
    /// `H` into an obstacle it touches, and `L`'s slide keeps clear of
    /// every disc but `H` and `P`. A heavy frictionless disc (0.72 kg)
    /// sliding along the floor at 2.3e-3 m/s under a light braking one
    /// (2.2 g) pressed it into a braking disc at rest (14 g): each hit
    /// kicked the resting disc off by the pressing contact's bounce, it
    /// stopped 8e-6 s later, the light disc ran into it and stopped, and
    /// the heavy one caught it again 1e-5 s on, three events a cycle,
    /// 4.5e-5 of its speed lost each, until the event cap. `false`
    /// (nothing done) where the rule does not apply.
    #[allow(clippy::too_many_arguments)]
    fn carried_around_held(
        &mut self,
        h: usize,
        l: usize,
        [i, j]: [usize; 2],
        [pi, pj]: [DVec2; 2],
        [vi, vj]: [DVec2; 2],
        at: &[DVec2],
        t: f64,
    ) -> bool {
        let others: Vec<usize> = self.touching(l, at).filter(|&c| c != h).collect();
        let [p] = others[..] else {
            return false;
        };
        if !self.contacts_among(&[l], t).is_empty() || self.slots[p].traj.velocity(t) != DVec2::ZERO
        {
            return false;
        }
        let (mh, ml, mp) = (self.material[h], self.material[l], self.material[p]);
        if !(ml.mass <= wedge::LIGHT * mh.mass) {
            return false;
        }
        let still = |c: usize| self.slots[c].traj.velocity(t) == DVec2::ZERO;
        if self.touching(h, at).any(|c| c != l && !still(c)) {
            return false;
        }
        let (v_h, p_h, p_l) = if h == i { (vi, pi, pj) } else { (vj, pj, pi) };
        let Some(dir) = v_h.try_normalize() else {
            return false;
        };
        let chain = pivot::Chain {
            at: [p_h, p_l, at[p]],
            dir,
            reach: [mh.radius + ml.radius, ml.radius + mp.radius],
        };
        let energy = push::pair_energy([vi, vj], [self.material[i].mass, self.material[j].mass]);
        let brake = [
            mh.mass * mh.mu * self.g,
            ml.mass * ml.mu * self.g,
            mp.mass * mp.mu * self.g,
        ];
        let Some(carry) = pivot::carried_around(chain, energy, [mh.mass, ml.mass], brake) else {
            return false;
        };
        let (v_h, a_h) = carry.pusher;
        let (v_l, a_l) = carry.carried;
        let noise = 1e-12 * v_h.length();
        if self
            .contacts_among(&[h], t)
            .iter()
            .any(|c| c.b.is_none() && v_h.dot(c.n) < -noise)
        {
            return false;
        }
        if self.slide_blocked_but(l, &[h, p], v_l, a_l, at) {
            return false;
        }
        let (new_h, new_l) = (
            Trajectory::new(t, p_h, v_h, a_h),
            Trajectory::new(t, p_l, v_l, a_l),
        );
        if h == i {
            self.leave_hit(i, j, new_h, new_l, t);
        } else {
            self.leave_hit(i, j, new_l, new_h, t);
        }
        true
    }

    /// Whether the carried disc in slot `l`, sliding from `at[l]` at `v_l`
    /// and braking at `a_l` until it stops, could reach any live disc but
    /// itself and its pusher `h` (or its slide has no finite length): a
    /// carry is taken only where the carried disc's whole slide keeps
    /// clear of every other disc.
    fn slide_blocked(&self, l: usize, h: usize, v_l: DVec2, a_l: f64, at: &[DVec2]) -> bool {
        self.slide_blocked_but(l, &[h], v_l, a_l, at)
    }

    /// [`World::slide_blocked`], with every disc in `but` left out (the
    /// discs the carried one touches and slides along).
    fn slide_blocked_but(
        &self,
        l: usize,
        but: &[usize],
        v_l: DVec2,
        a_l: f64,
        at: &[DVec2],
    ) -> bool {
        let reach = v_l.length_squared() / (2.0 * a_l);
        let r_l = self.slots[l].radius;
        let blocked = (0..self.slots.len()).any(|c| {
            c != l
                && !but.contains(&c)
                && self.slots[c].alive
                && (at[c] - at[l]).length() - (r_l + self.slots[c].radius) <= reach
        });
        blocked || !reach.is_finite()
    }

    /// From the sixteenth revision, a hit about to be carried
    /// ([`World::carried_press`]: the discs in slots `i` and `j` at `p`,
    /// velocities `u` before it, unit normal `n` towards `i`) whose pushed
    /// disc `L` (the one braking harder) lies against the one obstacle it
    /// touches and touches no disc but the pushing one `H`, which touches
    /// no obstacle but some other disc (which takes the sideways share of
    /// the contact force, as in `push::carried`): the hit is taken with the
    /// obstacle holding `L` to its line and the other disc `H` to its own,
    /// and `L` is carried along the obstacle as `H` slides past it
    /// ([`wedge::carried_along_wall`]), where `L`'s whole slide keeps clear
    /// of every other disc. A heavy frictionless disc sliding towards a
    /// wall between a disc in the corner and a light braking disc against
    /// the wall pressed the light one up the wall, one hit every 1e-5 s,
    /// each kick spent by its friction before the next, until the event
    /// cap 0.24 s on (7 s of such hits were left). `false` (nothing done)
    /// where the rule does not apply.
    fn wedged_along_wall(
        &mut self,
        i: usize,
        j: usize,
        [pi, pj]: [DVec2; 2],
        u: [DVec2; 2],
        n: DVec2,
        t: f64,
    ) -> bool {
        let (mi, mj) = (self.material[i], self.material[j]);
        let alpha = [mi.mu * self.g, mj.mu * self.g];
        let (h, l) = if alpha[1] > alpha[0] { (i, j) } else { (j, i) };
        let at = self.positions(t);
        let walls = self.contacts_among(&[l], t);
        let [wall] = walls[..] else {
            return false;
        };
        // `H` touches another disc, which takes its sideways share of the
        // contact force, and no obstacle.
        let held = self.touching(h, &at).any(|c| c != l) && self.contacts_among(&[h], t).is_empty();
        // From the eighteenth revision, or the one obstacle it slides along,
        // which takes that share (see `World::held_on_own_wall`).
        let held = held
            || (self.config.revision.carries_wedged_discs_between_walls()
                && self.held_on_own_wall(h, l, u[usize::from(h == j)], &at, t));
        let alone = self.touching(l, &at).all(|c| c == h);
        if !(held && alone && wall.b.is_none()) {
            return false;
        }
        let m = [mi.mass, mj.mass];
        let k = usize::from(l == j);
        let s = mi.radius + mj.radius;
        let Some([(vi, ai), (vj, aj)]) =
            wedge::carried_along_wall(u, m, alpha, n, s, k, wall.n, self.config.revision)
        else {
            return false;
        };
        // The pushed disc's whole slide keeps clear of every other disc.
        let (v_l, a_l) = if l == i { (vi, ai) } else { (vj, aj) };
        if self.slide_blocked(l, h, v_l, a_l, &at) {
            return false;
        }
        let new_i = Trajectory::new(t, pi, vi, ai);
        let new_j = Trajectory::new(t, pj, vj, aj);
        self.leave_hit(i, j, new_i, new_j, t);
        true
    }

    /// From the eighteenth revision, whether the pushing disc in slot `h`
    /// of a pair about to be wedged along a wall ([`World::wedged_along_wall`];
    /// the pushed disc in slot `l`, `at` every disc's centre, `u_h` `H`'s
    /// velocity before the hit) is held to its line by the one obstacle
    /// it touches, as the sixteenth revision holds it by a disc: `H`
    /// touches no disc but `L`, slides along that obstacle (its velocity
    /// across it within [`push::SAME`] of its speed), and the push from
    /// `L` drives it into the obstacle, which takes the push's share
    /// across it. A heavy frictionless disc (0.64 kg) sliding down the side
    /// wall at 3.9e-4 m/s into the corner past a light disc (6.6 g,
    /// braking at 2.0 m/s^2) on the floor pressed it along the floor, one
    /// hit and one stop every 4.3e-5 s, each kick spent by its friction
    /// before the next, until the event cap at 20.3 s.
    fn held_on_own_wall(&self, h: usize, l: usize, u_h: DVec2, at: &[DVec2], t: f64) -> bool {
        let walls = self.contacts_among(&[h], t);
        let [wall] = walls[..] else {
            return false;
        };
        let speed = u_h.length();
        let from_l = (at[h] - at[l]).normalize_or_zero();
        wall.b.is_none()
            && self.touching(h, at).all(|c| c == l)
            && speed > 0.0
            && u_h.dot(wall.n).abs() <= push::SAME * speed
            && from_l.dot(wall.n) < 0.0
    }

    /// From the fifteenth revision, the plastic hit of a pair about to be
    /// carried ([`World::carried_press`]) whose pushing disc `H` (the one
    /// braking less) slides along the one obstacle it touches, the plastic
    /// hit (`v`, from the velocities `u` before it) driving it into that
    /// obstacle: taken with the obstacle holding `H` to its line (see
    /// [`push::plastic_along_wall`]), so that `H` leaves along it and the
    /// carry is not undone by the obstacle's hit a moment later. A heavy
    /// frictionless disc sliding along the floor past a light braking one
    /// above it pressed it up and forward, each plastic hit sending the
    /// heavy disc into the floor by the light one's share of the approach:
    /// the carry was refused there, and the pressing contact kicked the
    /// pair apart every 1.8e-5 s until the event cap. `None` where `H`
    /// touches more than one obstacle, none that the hit drives it into,
    /// or does not slide along it; and `World::carried_press` takes the
    /// carry so only in its two guarded cases: the pair stopping together
    /// with `H` touching no other disc, or `H` passing with the carried
    /// disc's slide clear of every other disc (see there). From the
    /// sixteenth revision, where `H` touches no obstacle, a disc pinned
    /// by its walls against `H` ([`World::pinning_disc`]) holds it so
    /// instead, to the line tangent to both at their contact; the pinning
    /// disc's slot comes with the velocities.
    #[allow(clippy::too_many_arguments)]
    fn hit_along_wall(
        &self,
        i: usize,
        j: usize,
        u: [DVec2; 2],
        v: [DVec2; 2],
        n: DVec2,
        alpha: [f64; 2],
        t: f64,
    ) -> Option<([DVec2; 2], Option<usize>)> {
        let h = usize::from(alpha[1] < alpha[0]);
        let (slot, other) = if h == 0 { (i, j) } else { (j, i) };
        let walls: Vec<DVec2> = self
            .contacts_among(&[slot], t)
            .iter()
            .filter(|c| c.b.is_none())
            .map(|c| c.n)
            .collect();
        let (wall, pinning) = match walls[..] {
            [wall] => (wall, None),
            [] if self.config.revision.holds_pushers_on_pinned_discs() => {
                let (p, wall) = self.pinning_disc(slot, other, t)?;
                (wall, Some(p))
            }
            _ => return None,
        };
        if !(v[h].dot(wall) < -1e-12 * v[h].length()) {
            return None;
        }
        let mut u = u;
        if pinning.is_some() {
            // `H` slides past the pinning disc's curved side in a straight
            // line: within [`PINNED_SLIDE`] of its speed, the turn of the
            // tangent since they last met, it slides along it.
            let across = u[h].dot(wall);
            if !(across.abs() <= PINNED_SLIDE * u[h].length()) {
                return None;
            }
            u[h] -= wall * across;
        }
        let m = [self.material[i].mass, self.material[j].mass];
        push::plastic_along_wall(u, m, h, n, wall).map(|v| (v, pinning))
    }

    /// From the sixteenth revision, the one disc other than `other` that
    /// the disc in slot `h` touches at `t`, where that disc is at rest,
    /// touches no disc but `h` and discs at rest (not `other`: no chain),
    /// and two obstacles that are not parallel
    /// (see [`CORNER_SINE`]), and those obstacles' normal forces can take
    /// any push from `h` along the line of centres (the direction from
    /// `h` to it lies in the cone of the obstacles' inward normals): such
    /// a disc cannot move before `h`, and holds it as a wall along the
    /// tangent at their contact would. Its slot and the unit normal from
    /// it to `h`; `None` where `h` touches no such disc, or another disc
    /// besides.
    fn pinning_disc(&self, h: usize, other: usize, t: f64) -> Option<(usize, DVec2)> {
        let at = self.positions(t);
        let discs: Vec<usize> = self.touching(h, &at).filter(|&c| c != other).collect();
        let [p] = discs[..] else {
            return None;
        };
        let resting = |c: usize| self.slots[c].traj.velocity(t) == DVec2::ZERO;
        if !resting(p)
            || self
                .touching(p, &at)
                .any(|c| c != h && (c == other || !resting(c)))
        {
            return None;
        }
        let walls: Vec<DVec2> = self
            .contacts_among(&[p], t)
            .iter()
            .filter(|c| c.b.is_none())
            .map(|c| c.n)
            .collect();
        let [w1, w2] = walls[..] else {
            return None;
        };
        let det = w1.perp_dot(w2);
        if !(det.abs() > CORNER_SINE) {
            return None;
        }
        // The push's direction, from `h` to `p`, as `-(a w1 + b w2)`: the
        // obstacles take it where `a` and `b` are not negative.
        let d = (at[p] - at[h]).normalize();
        let (a, b) = ((-d).perp_dot(w2) / det, w1.perp_dot(-d) / det);
        if !(a >= 0.0 && b >= 0.0) {
            return None;
        }
        Some((p, -d))
    }

    /// From the twelfth revision, a gentle plastic hit between the discs in
    /// slots `i` and `j` (see `World::collide`), the lighter of which is
    /// plastic and lies in a corner (touches two obstacles that are not
    /// parallel, see [`CORNER_SINE`]), taken at once as the plastic limit
    /// of the two, every disc touching either of them through a plastic
    /// contact, and the obstacles the plastic ones touch (see
    /// `World::collapse_contacts`). Taken alone, the hit sent the light
    /// disc into one of its walls, which it hit a picosecond to a
    /// nanosecond later, and its heavier partner, still pressing, hit it
    /// again at that same instant, losing only the light disc's small
    /// share of its approach each time: a ring of two or three hits an
    /// instant, instant after instant, never the eight hits of a pair at
    /// one instant that `World::collapse_repeated` waits for. Only the
    /// plastic contacts take part (an elastic one does not end in the
    /// limit). `false` (nothing done) where no such disc is, the two are
    /// not found touching, or the limit changes nothing.
    fn cornered_hit(&mut self, i: usize, j: usize, t: f64) -> bool {
        let plastic = |w: &World, c: usize| w.material[c].restitution == 0.0;
        let mut members = vec![i, j];
        let at = self.positions(t);
        for m in [i, j] {
            for c in self.touching(m, &at) {
                if !members.contains(&c) && (plastic(self, m) || plastic(self, c)) {
                    members.push(c);
                }
            }
        }
        let mut contacts = self.contacts_among(&members, t);
        if !contacts.iter().any(|c| c.a == 0 && c.b == Some(1)) {
            return false;
        }
        contacts.retain(|c| match c.b {
            Some(b) => plastic(self, members[c.a]) || plastic(self, members[b]),
            None => plastic(self, members[c.a]),
        });
        let cornered = |k: usize| {
            let walls: Vec<DVec2> = contacts
                .iter()
                .filter(|c| c.a == k && c.b.is_none())
                .map(|c| c.n)
                .collect();
            walls.iter().enumerate().any(|(x, a)| {
                walls[x + 1..]
                    .iter()
                    .any(|b| a.perp_dot(*b).abs() > CORNER_SINE)
            })
        };
        let lighter =
            |k: usize| self.material[members[k]].mass < self.material[members[1 - k]].mass;
        if !((cornered(0) && lighter(0)) || (cornered(1) && lighter(1))) {
            return false;
        }
        self.collapse_contacts(&members, contacts, t)
    }

    /// From the thirteenth revision, a plastic hit between the discs in
    /// slots `i` and `j` (velocities `u` before it, normal `n` from `j` to
    /// `i`) whose lighter disc is plastic, touches an obstacle and is
    /// driven into it by the hit, taken at once as the plastic limit of the
    /// two and the obstacles the plastic ones touch (see
    /// `World::collapse_contacts`), where neither touches another disc
    /// through a plastic contact and their braking does not press them
    /// together. Taken alone, the hit sends the light
    /// disc into the obstacle, a rounding of a position away, which it hits
    /// a tenth of a picosecond later; the heavy one, still approaching,
    /// hits it again at that same instant, losing only the light disc's
    /// share of its approach: an inelastic collapse against the wall whose
    /// every instant holds one hit of the pair (a heavy disc sliding along
    /// a light one against a wall, 10,000 such instants in 3.2 ms). Its
    /// limit, the plastic projection of the pair and the wall, is what the
    /// hits converge to. A pressed pair is left to the pressing contact
    /// (its limit, kicked apart at once, was hit again at every event), and
    /// a pair within a pile to its hits (taken within a struck pile of
    /// five, the limit sent mixed-box 270, near the event cap under the
    /// twelfth revision, over it). `false` (nothing done) where no such
    /// disc is, the two are not found touching, or the limit changes
    /// nothing.
    fn walled_hit(&mut self, i: usize, j: usize, u: [DVec2; 2], n: DVec2, t: f64) -> bool {
        let plastic = |w: &World, c: usize| w.material[c].restitution == 0.0;
        let (mi, mj) = (self.material[i].mass, self.material[j].mass);
        let light = usize::from(mj < mi);
        if !plastic(self, [i, j][light]) {
            return false;
        }
        let (vi, vj) = impulse::body_body(u[0], u[1], mi, mj, 0.0, n);
        let v_light = [vi, vj][light];
        // A pair its braking presses together is left to the pressing
        // contact: its limit would be kicked apart at once, and hit again.
        if self.braking_presses(i, j, [vi, vj], n, t) {
            return false;
        }
        let mut members = vec![i, j];
        let at = self.positions(t);
        for m in [i, j] {
            for c in self.touching(m, &at) {
                if !members.contains(&c) && (plastic(self, m) || plastic(self, c)) {
                    members.push(c);
                }
            }
        }
        // Only a pair that touches no other disc through a plastic contact.
        if members.len() > 2 {
            return false;
        }
        let mut contacts = self.contacts_among(&members, t);
        if !contacts.iter().any(|c| c.a == 0 && c.b == Some(1)) {
            return false;
        }
        contacts.retain(|c| match c.b {
            Some(b) => plastic(self, members[c.a]) || plastic(self, members[b]),
            None => plastic(self, members[c.a]),
        });
        let driven = contacts
            .iter()
            .any(|c| c.a == light && c.b.is_none() && v_light.dot(c.n) < 0.0);
        driven && self.collapse_contacts(&members, contacts, t)
    }

    /// From the thirteenth revision, a plastic hit between the discs in
    /// slots `i` and `j` (unit normal `n` towards `i`, velocities `u`
    /// before it) that drives one of them into an obstacle it touches,
    /// where the hits that follow, played in memory (that disc hits the
    /// obstacle with its restitution, its partner meets it again, a plastic
    /// hit), still ring after [`WALL_RINGS`] turns: taken at once as the
    /// plastic limit of the two, every disc touching either of them through
    /// a plastic contact, the obstacles the plastic ones touch and those
    /// of the disc that rings (the limit `World::cornered_hit` takes).
    /// Such a sequence has no end, only that limit: the partner loses the
    /// driven disc's share of its approach at each turn. Only a slow ring
    /// is taken, one that keeps [`WALL_RING_KEEPS`] of its approach over
    /// those turns; a faster one ends by itself. Hit by hit, a
    /// heavy disc driven slowly into a light plastic one against a wall
    /// lost a few parts in a thousand of its speed a turn; each obstacle
    /// hit moved the light disc by the rounding of its position, so that
    /// its partner met it again picoseconds later, at a new instant, three
    /// events a turn until the event cap, however straight the hit; a light
    /// elastic disc between a wall and a heavy plastic one rang so at one
    /// instant, the collapse taken after repeated hits ending each ring
    /// only for the next to begin. A sequence that ends within those turns,
    /// or loses its approach faster (a light disc knocking a heavy one
    /// against a wall), is left to its hits. `false` (nothing done) where
    /// no such disc is, the two are not found touching, or the limit
    /// changes nothing.
    ///
    /// From the fourteenth revision, the same for a hit of a pair with
    /// restitution taken as the end of its chatter (`chatter_end`, see
    /// `push::chatters`): that hit is plastic too, and so is every hit of
    /// the pair the ring would bring, so that the limit takes the pair's
    /// own contact with the obstacles, whatever the discs' restitution.
    /// From the fourteenth revision, too, a gentle hit (its approach within
    /// [`GENTLE`] of the faster disc's speed: discs pressed together as
    /// they slide, not an impact) that drives a plastic disc into an
    /// obstacle its normal meets at an angle ([`GENTLE_WALL_COSINE`]), the
    /// disc then coming back into its partner, is taken however fast its
    /// ring would fade, unless the pair's braking presses it together
    /// (`World::braking_presses`): every hit of that ring is plastic, the
    /// disc stopping against the obstacle and its partner catching it
    /// again, and the ring's end is the limit the plastic projection takes
    /// at once. Hit by
    /// hit it ended at the rounding of the speeds, a tenth of the approach
    /// left each turn, and the light partner, pressed between it and a
    /// third disc, drove into it again tens of microseconds later, until
    /// the event cap (mixed-box 453647). An elastic disc is left to its
    /// hits: its ring ends with it bouncing off the obstacle, which the
    /// limit would take from it (a disc grazing over an elastic one on the
    /// floor, each hit so taken, met it again at once, 10,000 such limits
    /// until the event cap, mixed-box 98120).
    ///
    /// From the sixteenth revision an elastic disc so driven is taken too
    /// (`Revision::takes_gentle_hit_on_elastic_disc_into_wall`), where the
    /// limit drives none of its discs into a disc outside it
    /// (`World::drives_into_others`): a ring that converges ends with both
    /// contacts closed, the disc neither leaving the obstacle nor its
    /// partner, and two closed contacts with impulses along their normals
    /// alone fix that end, which is the plastic limit. A light elastic disc
    /// on the floor under a plastic one nine times heavier bounced back
    /// into it, 0.29 of its speed into the floor left a turn; the collapse
    /// after repeated hits ended each ring, and the pile pressing the pair
    /// began the next microseconds later, until the event cap (mixed-box
    /// 28232, 506944, 555153). Where the limit hands its motion on at once
    /// (mixed-box 98120, the disc at the end of a frictionless row) it is
    /// left to its hits as before.
    ///
    /// From the sixteenth revision, too, a ring whose discs have no more kinetic
    /// energy than each of its braking discs' friction does over the
    /// rounding of its position comes to rest as a cluster's spent ring
    /// does (`World::spent_ring_rest`): taken to its limit and kicked
    /// apart by the pressing contact, a frictionless disc sliding down a
    /// wall at 7e-9 m/s into a heavy braking one on the floor sent it off
    /// at 3.5e-10 m/s, to stop 3e-11 s later and be hit again at once,
    /// until `stuck` (mixed-box 536265).
    fn hit_into_wall(
        &mut self,
        i: usize,
        j: usize,
        n: DVec2,
        u: [DVec2; 2],
        chatter_end: bool,
        t: f64,
    ) -> bool {
        let (mi, mj) = (self.material[i].mass, self.material[j].mass);
        let (vi, vj) = impulse::body_body(u[0], u[1], mi, mj, 0.0, n);
        let plastic = |w: &World, c: usize| w.material[c].restitution == 0.0;
        // The pair's own contacts first (most plastic hits drive nothing
        // into an obstacle): the neighbours only where it rings.
        let pair = self.contacts_among(&[i, j], t);
        if !pair.iter().any(|c| c.a == 0 && c.b == Some(1)) {
            return false;
        }
        let noise = WALL_RING_NOISE * u[0].length().max(u[1].length());
        let masses = [mi, mj];
        // Whether the hits that follow, played in memory, still ring after
        // `WALL_RINGS` turns: disc `k` of the two (0 for `i`) hits the
        // obstacles it touches and approaches (each in turn, with its
        // restitution), and the pair approaches again and hits (plastic).
        // The pair's approach at its first and last turn, where it still
        // rings after `turns`.
        let play = |k: usize, turns: usize| {
            let e = self.material[[i, j][k]].restitution;
            let mut w = [vi, vj];
            let mut first = None;
            let mut approach = 0.0;
            for _ in 0..turns {
                let mut hit = false;
                for c in pair.iter().filter(|c| c.a == k && c.b.is_none()) {
                    let into = w[k].dot(c.n);
                    if into < -noise {
                        w[k] -= c.n * ((1.0 + e) * into);
                        hit = true;
                    }
                }
                approach = -(w[0] - w[1]).dot(n);
                if !hit || approach <= noise {
                    return None;
                }
                first.get_or_insert(approach);
                let (a, b) = impulse::body_body(w[0], w[1], masses[0], masses[1], 0.0, n);
                w = [a, b];
            }
            first.map(|first| (first, approach))
        };
        // Slowly: a ring that loses more falls below the rounding of
        // the speeds within a few hundred hits, and is left to them.
        let rings = |k: usize| {
            play(k, WALL_RINGS).is_some_and(|(first, last)| last >= WALL_RING_KEEPS * first)
        };
        // From the fourteenth revision, a gentle hit whose driven disc
        // comes back into its partner at all, however fast the ring fades.
        let gentle = self.config.revision.takes_gentle_hit_into_wall_with_wall()
            && (u[1] - u[0]).dot(n) <= GENTLE * u[0].length().max(u[1].length())
            && !self.braking_presses(i, j, [vi, vj], n, t);
        // One turn of it, counting only the obstacles the pair's normal
        // meets at an angle (`GENTLE_WALL_COSINE`): a hit along a row on a
        // wall drives its discs into the wall by rounding alone.
        let gentle_turn = |k: usize| {
            // From the sixteenth revision a disc with restitution too, hit
            // by a plastic partner (not at a chatter's end).
            let e = self.material[[i, j][k]].restitution;
            if e != 0.0
                && (chatter_end
                    || !self
                        .config
                        .revision
                        .takes_gentle_hit_on_elastic_disc_into_wall())
            {
                return false;
            }
            let mut w = [vi, vj];
            let mut hit = false;
            for c in pair
                .iter()
                .filter(|c| c.a == k && c.b.is_none() && c.n.dot(n).abs() >= GENTLE_WALL_COSINE)
            {
                let into = w[k].dot(c.n);
                if into < -noise {
                    w[k] -= c.n * ((1.0 + e) * into);
                    hit = true;
                }
            }
            hit && -(w[0] - w[1]).dot(n) > noise
        };
        let slow = [rings(0), rings(1)];
        let ringing = [
            slow[0] || (gentle && gentle_turn(0)),
            slow[1] || (gentle && gentle_turn(1)),
        ];
        if !(ringing[0] || ringing[1]) {
            return false;
        }
        let mut members = vec![i, j];
        let at = self.positions(t);
        for m in [i, j] {
            for c in self.touching(m, &at) {
                if !members.contains(&c) && (plastic(self, m) || plastic(self, c)) {
                    members.push(c);
                }
            }
        }
        // A gentle hit in a pile is left to the collapse rules of its
        // instant (`GENTLE_WALL_MEMBERS`).
        if !(slow[0] || slow[1]) && members.len() > GENTLE_WALL_MEMBERS {
            return false;
        }
        // From the sixteenth revision, a ring whose energy its braking
        // spends within the rounding of its positions comes to rest, as a
        // cluster's ring does.
        if self.config.revision.rests_spent_hits_into_walls() {
            let (vel, inv) = self.motion(&members, t);
            if self.spent_ring_rest(&members, &vel, &inv, t) {
                return true;
            }
        }
        let mut contacts = self.contacts_among(&members, t);
        // From the fifteenth revision, every obstacle a member touches, for
        // those the limit drives its discs into.
        let walls: Vec<_> = if self
            .config
            .revision
            .takes_ring_limits_with_walls_they_reach()
        {
            contacts.iter().filter(|c| c.b.is_none()).copied().collect()
        } else {
            Vec::new()
        };
        // The plastic contacts, and the obstacles of a disc that rings
        // against them whatever its restitution: its partner's plastic
        // hits take what it brings back from them.
        contacts.retain(|c| match c.b {
            Some(b) => {
                plastic(self, members[c.a])
                    || plastic(self, members[b])
                    || (chatter_end && c.a == 0 && b == 1)
            }
            None => plastic(self, members[c.a]) || (c.a < 2 && ringing[c.a]),
        });
        if walls.is_empty() {
            return self.collapse_few_contacts(&members, contacts, t);
        }
        // From the sixteenth revision, an elastic disc rung gently against
        // an obstacle: only a limit that hands no motion on to a disc
        // outside the ring.
        let elastic_ring =
            (0..2).any(|k| ringing[k] && !slow[k] && self.material[[i, j][k]].restitution != 0.0);
        self.collapse_few_contacts_reaching(&members, contacts, &walls, noise, elastic_ring, t)
    }

    /// Whether the discs in slots `i` and `j`, leaving a hit along `n` (from
    /// `j` to `i`) at velocities `v`, are pressed together by their braking
    /// (`push::bounce_speed`), as `World::walled_hit` asks: such a pair is
    /// left to the pressing contact (a fourteenth revision rule's limit,
    /// taken instead, let a disc sliding up a wall into a resting one hit
    /// it again at once, 8,677 times until the event cap, mixed-box 21985).
    fn braking_presses(&self, i: usize, j: usize, v: [DVec2; 2], n: DVec2, t: f64) -> bool {
        let (pi, pj) = (
            self.slots[i].traj.position(t),
            self.slots[j].traj.position(t),
        );
        let acc = [
            Trajectory::new(t, pi, v[0], self.material[i].mu * self.g).acceleration(t),
            Trajectory::new(t, pj, v[1], self.material[j].mu * self.g).acceleration(t),
        ];
        let s = self.material[i].radius + self.material[j].radius;
        push::bounce_speed(v, acc, n, s, self.config.revision).is_some()
    }

    /// As `World::collapse_contacts`, for the few contacts of one hit and
    /// its neighbours (see `World::hit_into_wall`): the plastic limit by
    /// the active-set method first, which solves it in as many steps as
    /// contacts push, and by the projection only where that fails. A
    /// light disc between a heavy one and walls stalls projected
    /// Gauss–Seidel, and where the exact solve of what it pushes is left
    /// approaching by rounding, the projection ran all its sweeps every
    /// time.
    fn collapse_few_contacts(
        &mut self,
        members: &[usize],
        contacts: Vec<collapse::Contact>,
        t: f64,
    ) -> bool {
        let (vel, inv) = self.motion(members, t);
        let plastic = collapse::active_set(&vel, &inv, &contacts)
            .or_else(|| collapse::resolve(&vel, &inv, &contacts, collapse::MAX_SWEEPS));
        let Some(after) = plastic else {
            return false;
        };
        self.take_plastic_limit(members, contacts, (&vel, &inv), after, true, t)
    }

    /// As `World::collapse_few_contacts`, with those of `walls` (obstacle
    /// contacts of `members`) that the limit drives its discs into faster
    /// than `noise` (`reached_walls::with_walls_reached`; the fifteenth
    /// revision's `World::hit_into_wall`).
    fn collapse_few_contacts_reaching(
        &mut self,
        members: &[usize],
        contacts: Vec<collapse::Contact>,
        walls: &[collapse::Contact],
        noise: f64,
        closed: bool,
        t: f64,
    ) -> bool {
        let (vel, inv) = self.motion(members, t);
        let plastic = collapse::active_set(&vel, &inv, &contacts)
            .or_else(|| collapse::resolve(&vel, &inv, &contacts, collapse::MAX_SWEEPS));
        let Some(after) = plastic else {
            return false;
        };
        let (contacts, after) =
            reached_walls::with_walls_reached(&vel, &inv, contacts, after, walls, noise);
        if closed && self.drives_into_others(members, &after, noise, t) {
            return false;
        }
        self.take_plastic_limit(members, contacts, (&vel, &inv), after, true, t)
    }

    /// Whether `members` (slots), leaving a limit at velocities `after`,
    /// would approach a disc outside them that one of them touches faster
    /// than `noise`: a limit that hands its motion on at once (the sixteenth
    /// revision's elastic disc rung against an obstacle, see
    /// `World::hit_into_wall`).
    fn drives_into_others(&self, members: &[usize], after: &[DVec2], noise: f64, t: f64) -> bool {
        let at = self.positions(t);
        members.iter().zip(after).any(|(&m, &v)| {
            self.touching(m, &at)
                .filter(|c| !members.contains(c))
                .any(|c| {
                    let n = (at[c] - at[m]).normalize_or_zero();
                    (v - self.slots[c].traj.velocity(t)).dot(n) > noise
                })
        })
    }

    /// What the approximated pressing contact does to two discs just hit
    /// along `n` (their outgoing trajectories `ti`, `tj`, contact distance
    /// `s`), from the second revision on: `None` where the model is exact
    /// (see [`push::pressing_kick`]).
    fn pressing(
        &self,
        ti: &Trajectory,
        tj: &Trajectory,
        n: DVec2,
        s: f64,
        t: f64,
    ) -> Option<push::Press> {
        // Frictionless discs never press (their gap's second derivative is
        // |v_t|^2 / s >= 0), and a disc at rest is not pressed by braking.
        if !self.config.revision.at_least_r2()
            || (ti.alpha() == 0.0 && tj.alpha() == 0.0)
            || !ti.is_moving_at(t)
            || !tj.is_moving_at(t)
        {
            return None;
        }
        // Both just began at `t`: their start velocities are the impulse's.
        push::pressing_kick(
            [ti.start_velocity(), tj.start_velocity()],
            [ti.acceleration(t), tj.acceleration(t)],
            n,
            s,
            self.clock.origin() + t,
            self.config.revision,
        )
    }

    /// `chain` grown by every live disc that touches one of its members `m`
    /// at `t` and that `joins(world, m, disc)` admits, then ordered along
    /// `dir` (ties by index).
    fn touching_chain(
        &self,
        mut chain: Vec<usize>,
        t: f64,
        dir: DVec2,
        joins: impl Fn(&World, usize, usize) -> bool,
    ) -> Vec<usize> {
        let mut k = 0;
        while k < chain.len() {
            let m = chain[k];
            let pm = self.slots[m].traj.position(t);
            for c in 0..self.slots.len() {
                if !self.slots[c].alive || chain.contains(&c) {
                    continue;
                }
                let s = self.slots[m].radius + self.slots[c].radius;
                let gap = self.slots[c].traj.position(t) - pm;
                if gap.length_squared() - s * s <= push::TOUCHING * s * s && joins(self, m, c) {
                    chain.push(c);
                }
            }
            k += 1;
        }
        chain.sort_by(|&a, &b| {
            let (pa, pb) = (
                self.slots[a].traj.position(t),
                self.slots[b].traj.position(t),
            );
            pa.dot(dir).total_cmp(&pb.dot(dir)).then(a.cmp(&b))
        });
        chain
    }

    /// What [`push`] needs of each disc of `chain` at `t`.
    fn chain_parts(&self, chain: &[usize], t: f64) -> Vec<push::Part> {
        chain
            .iter()
            .map(|&c| push::Part {
                vel: self.slots[c].traj.velocity(t),
                mass: self.material[c].mass,
                alpha: self.material[c].mu * self.g,
            })
            .collect()
    }

    /// `i` and `j` push on each other: if other touching discs slide with
    /// them along the same line, the whole chain is joined (each block of
    /// it moving as one, see [`push::pooled`]) and `true` returned; a lone
    /// pair is left to the caller.
    fn push_chain(&mut self, i: usize, j: usize, t: f64) -> bool {
        let v = self.slots[i].traj.velocity(t);
        let speed = v.length();
        let d = v / speed;
        let chain = self.touching_chain(vec![i, j], t, d, |w, m, c| {
            let sc = &w.slots[c];
            let s = w.slots[m].radius + sc.radius;
            let gap = sc.traj.position(t) - w.slots[m].traj.position(t);
            sc.traj.is_moving_at(t)
                && (sc.traj.velocity(t) - v).length() <= push::SAME * speed
                && gap.perp_dot(d).abs() <= push::SAME * s
        });
        if chain.len() == 2 {
            return false;
        }
        let parts = self.chain_parts(&chain, t);
        for (&c, (v, a)) in chain.iter().zip(push::pooled(&parts)) {
            let p = self.slots[c].traj.position(t);
            self.slots[c].traj = Trajectory::new(t, p, v, a);
            self.slots[c].gen = self.slots[c].gen.wrapping_add(1);
        }
        for &c in &chain {
            self.predict(c, true);
        }
        true
    }

    /// `i` hits an obstacle at `t`, along `n` (pointing from the obstacle to
    /// the centre), its centre `dist` from it.
    fn bounce(&mut self, i: usize, t: f64, n: DVec2, dist: f64) {
        let tr = self.slots[i].traj;
        let m = &self.material[i];
        self.last_approach = -tr.velocity(t).dot(n);
        let v = impulse::body_static(tr.velocity(t), m.restitution, n);
        let mut p = tr.position(t);
        if self.config.revision.at_least_r2() {
            p += n * snap(m.radius, dist);
        }
        self.slots[i].traj = self.settled(Trajectory::new(t, p, v, m.mu * self.g), t);
        self.changed(i);
    }

    /// `i`'s trajectory was replaced: invalidate others' predictions about it
    /// and predict it afresh.
    fn changed(&mut self, i: usize) {
        self.slots[i].gen = self.slots[i].gen.wrapping_add(1);
        self.predict(i, true);
    }

    fn remove_slot(&mut self, i: usize, t: f64) {
        let s = &mut self.slots[i];
        s.alive = false;
        s.gen = s.gen.wrapping_add(1);
        s.traj = Trajectory::at_rest(t, s.traj.position(t), 0.0);
        self.pending[i] = Best::NONE;
        self.cross[i].0 = f64::INFINITY;
        self.calendar.set(i, f64::INFINITY);
        if let Some(grid) = self.grid.as_mut() {
            grid.remove(i);
        }
    }

    /// Recomputes the earliest event of body `i` from the current time.
    /// A resting body is only searched (for movers about to hit it) when
    /// `scan_if_resting`: whenever its motion changed or its entry went
    /// stale. Only at the start, when every mover predicts against it as a
    /// fixed obstacle, can a resting body skip that.
    fn predict(&mut self, i: usize, scan_if_resting: bool) {
        self.predict_with(i, scan_if_resting, None);
    }

    /// As `predict`; with `known = Some((j, t))` the pair `(i, j)` is not
    /// solved if `t` is given (it was, for `j`), and its time is returned.
    fn predict_with(
        &mut self,
        i: usize,
        scan_if_resting: bool,
        known: Known,
    ) -> Option<Option<f64>> {
        let mover = Mover::new(&self.slots[i].traj, self.t);
        let mut pair = None;
        let best = if mover.is_none() && !scan_if_resting {
            Best::NONE
        } else {
            self.earliest(i, mover.as_ref(), known, &mut pair)
        };
        self.pending[i] = best;
        // Without a grid there are no crossings: `cross` stays at infinity
        // (and `best.t` is never NaN, so the minimum is `best.t`).
        let t = match &self.grid {
            None => best.t,
            Some(grid) => {
                let cross = mover
                    .and_then(|m| grid.next_crossing(i, &m))
                    .unwrap_or((f64::INFINITY, (0, 0)));
                self.cross[i] = cross;
                best.t.min(cross.0)
            }
        };
        self.calendar.set(i, t);
        pair
    }

    /// The earliest real event of body `i` from the current time.
    #[inline(always)]
    fn earliest(
        &self,
        i: usize,
        mover: Option<&Mover>,
        known: Known,
        pair: &mut Option<Option<f64>>,
    ) -> Best {
        let mut best = Best::NONE;
        let si = &self.slots[i];
        match &self.grid {
            Some(grid) => {
                for cell in grid.neighbour_cells(i) {
                    for &j in cell {
                        let j = j as usize;
                        if let Some(sj) = self.slots.get(j) {
                            self.offer_pair(i, si, mover, j, sj, known, &mut best, pair);
                        }
                    }
                }
            }
            None => {
                for (j, sj) in self.slots.iter().enumerate() {
                    self.offer_pair(i, si, mover, j, sj, known, &mut best, pair);
                }
            }
        }
        let Some(m) = mover else {
            return best;
        };
        let r = self.slots[i].radius;
        for &k in &self.solid {
            if let Some(t) =
                contact::disc_line_body(m, &self.geoms[k as usize], r, self.config.revision)
            {
                best.offer(t, Next::Line(k, None));
            }
        }
        for c in &self.corners {
            if let Some(t) = contact::disc_point(m, c.pos, r, self.config.revision) {
                best.offer(t, Next::Line(c.line, Some(c.end)));
            }
        }
        for (k, p) in self.points.iter().enumerate() {
            if let Some(t) = contact::disc_point(m, p.pos, r, self.config.revision) {
                best.offer(t, Next::Point(k as u32));
            }
        }
        let sides = self.slots[i].sides;
        for (bit, &k) in self.sensors.iter().enumerate() {
            let inside = sides & (1 << bit) != 0;
            if let Some((t, reported)) =
                contact::centre_crossing(m, &self.geoms[k as usize], inside)
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
        best.offer(m.tr.stop_time(), Next::Stop);
        best
    }

    /// Offers the contact of bodies `i` (on path `mover`, if moving) and `j`
    /// as `i`'s next event.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn offer_pair(
        &self,
        i: usize,
        si: &Slot,
        mover: Option<&Mover>,
        j: usize,
        sj: &Slot,
        known: Known,
        best: &mut Best,
        pair: &mut Option<Option<f64>>,
    ) {
        if j == i || !sj.alive {
            return;
        }
        let now = self.t;
        if mover.is_none() && !sj.traj.is_moving_at(now) {
            return;
        }
        let hit = match known {
            Some((k, Some(t))) if k == j => t,
            _ => {
                let s = si.radius + sj.radius;
                let t = contact::disc_disc(
                    &si.traj,
                    mover,
                    &sj.traj,
                    s,
                    contact::When::new(now, self.clock.origin()),
                    &self.config.solver,
                    self.config.revision,
                );
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
                    other_gen: sj.gen,
                },
            );
        }
    }
}

/// The kinetic energy of discs at velocities `v` with inverse masses `inv`.
fn kinetic_energy(v: &[DVec2], inv: &[f64]) -> f64 {
    v.iter()
        .zip(inv)
        .map(|(v, &k)| 0.5 * v.length_squared() / k)
        .sum()
}

/// From the twelfth revision, the kick over a cluster `after` (from the
/// velocities `vel` of discs with inverse masses `inv`, the `contacts`
/// biased where a pair presses) held to add no more than
/// [`push::CLUSTER_PRESS_GAIN`] of the kinetic energy of the `scene` (all
/// its discs, at least those of the cluster). The pair's bounce speed is
/// set by its own speeds, but where one of the two is jammed (against a
/// wall, or a chain of discs against one) the projection gives the whole
/// separation to whatever it can move, a heavy disc behind the other
/// among them: parting a light disc at 5 per cent of its speed set a disc
/// forty times heavier moving at that speed, 7 per cent of the scene's
/// energy from nothing. Held, the kick is the blend
/// `plastic + l (after - plastic)` of the cluster's plastic limit (no
/// bias: it adds no energy) and the biased projection with the largest
/// `l` in [0, 1] whose energy is within the bound: every contact's normal
/// speed is linear in `l` and parts at least at `l` times its bias, so no
/// contact approaches and each pressed pair still parts, slower. `after`
/// itself where it is within the bound (what the eleventh revision does);
/// `None` where the plastic limit has no answer.
fn within_press_bound(
    vel: &[DVec2],
    inv: &[f64],
    contacts: &[collapse::Contact],
    after: Vec<DVec2>,
    scene: f64,
) -> Option<Vec<DVec2>> {
    let energy = |v: &[DVec2]| kinetic_energy(v, inv);
    let before = energy(vel);
    let budget = before + push::CLUSTER_PRESS_GAIN * scene.max(before);
    if energy(&after) <= budget {
        return Some(after);
    }
    let unbiased: Vec<collapse::Contact> = contacts
        .iter()
        .map(|c| collapse::Contact { bias: 0.0, ..*c })
        .collect();
    let plastic = collapse::resolve(vel, inv, &unbiased, PRESS_SWEEPS)?;
    // E(l) = E_p + l b + l^2 a, increasing on [0, 1] where it matters.
    let (mut a, mut b) = (0.0, 0.0);
    for ((p, q), &k) in plastic.iter().zip(&after).zip(inv) {
        let d = *q - *p;
        a += 0.5 * d.length_squared() / k;
        b += p.dot(d) / k;
    }
    let c = energy(&plastic) - budget;
    let l = if c >= 0.0 || a <= 0.0 {
        0.0
    } else {
        ((-b + (b * b - 4.0 * a * c).sqrt()) / (2.0 * a)).clamp(0.0, 1.0)
    };
    Some(
        plastic
            .iter()
            .zip(&after)
            .map(|(p, q)| *p + (*q - *p) * l)
            .collect(),
    )
}

/// Which wedged pushes `World::carried_press` takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Carry {
    /// Every push it applies to (from the fourteenth revision).
    Any,
    /// From the nineteenth revision, asked before a plastic hit is taken as
    /// a ring into an obstacle: only a pushing disc that the hit drives
    /// into the one obstacle it slides along (`World::hit_along_wall`, no
    /// pinning disc; `Revision::carries_wedges_before_wall_rings`).
    AlongOwnWall,
}

/// From the nineteenth revision: whether disc `k` of a cluster
/// (velocities `vel`) approaches none of the discs and obstacles it
/// touches (`contacts`, each normal from `b` to `a`), those `kept` moving
/// with it apart: what those do to each other is left to their own hits.
fn runs_into_nothing(
    k: usize,
    vel: &[DVec2],
    kept: &[bool],
    contacts: &[collapse::Contact],
) -> bool {
    contacts
        .iter()
        .filter(|c| (c.a == k && c.b.is_none_or(|b| !kept[b])) || (c.b == Some(k) && !kept[c.a]))
        .all(|c| (vel[c.a] - c.b.map_or(DVec2::ZERO, |b| vel[b])).dot(c.n) >= 0.0)
}

/// `after` with the discs `kept` given back their velocities `before`.
fn given_back(after: &[DVec2], before: &[DVec2], kept: &[bool]) -> Vec<DVec2> {
    after
        .iter()
        .zip(before)
        .zip(kept)
        .map(|((&a, &b), &k)| if k { b } else { a })
        .collect()
}

/// From the seventeenth revision, where a pair rests by its energy with
/// one disc held (`held`, for the pair's members 0 and 1 of `after`): the
/// approach the projection leaves the free disc into the held one along
/// their contact in `contacts` is taken off, as against a wall (see
/// `Revision::rests_free_disc_on_held_partner`).
fn stop_against_held(after: &mut [DVec2], held: [bool; 2], contacts: &[collapse::Contact]) {
    let Some((a, b, n)) = contacts.iter().find_map(|c| match c.b {
        Some(b) if c.a < 2 && b < 2 => Some((c.a, b, c.n)),
        _ => None,
    }) else {
        return;
    };
    let rel = (after[a] - after[b]).dot(n);
    if rel < 0.0 && held[a] != held[b] {
        if held[b] {
            after[a] -= n * rel;
        } else {
            after[b] += n * rel;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use super::kinetic_energy as energy;

    /// Disc 0 sliding along a wall at 1 m/s, touching disc 1 (at rest) on
    /// its other side, the pair parting at 0.05 m/s: the velocities and
    /// the contacts of the kick.
    fn against_a_wall() -> ([DVec2; 2], [collapse::Contact; 2]) {
        (
            [DVec2::new(0.0, 1.0), DVec2::ZERO],
            [
                collapse::Contact::plastic(0, None, DVec2::X),
                collapse::Contact {
                    a: 1,
                    b: Some(0),
                    n: DVec2::X,
                    bias: 0.05,
                },
            ],
        )
    }

    #[test]
    fn a_kick_parting_a_light_disc_against_a_wall_from_a_heavy_one_is_held_to_its_bound() {
        // Disc 0 (10 g) slides along a wall at 1 m/s, touching disc 1 (1 kg,
        // at rest) on its other side, the whole scene; the pair parts at
        // 0.05 m/s. Disc 0 cannot move into the wall, so the biased
        // projection sets disc 1 moving at 0.05 m/s: 1.25e-3 J, a quarter
        // of the 5e-3 J the two have.
        let (vel, contacts) = against_a_wall();
        let inv = [100.0, 1.0];
        let after = collapse::resolve(&vel, &inv, &contacts, PRESS_SWEEPS).expect("a kick");
        assert!((after[1].x - 0.05).abs() < 1e-12, "{after:?}");
        let held = within_press_bound(&vel, &inv, &contacts, after, energy(&vel, &inv))
            .expect("a plastic limit");
        let before = energy(&vel, &inv);
        let gained = energy(&held, &inv) - before;
        assert!(gained <= push::CLUSTER_PRESS_GAIN * before * (1.0 + 1e-12));
        assert!(gained > 0.99 * push::CLUSTER_PRESS_GAIN * before);
        // Still parting, slower, and not into the wall.
        assert!(held[1].x - held[0].x > 0.0 && held[1].x < 0.05);
        assert!(held[0].x >= 0.0);
        assert_eq!(held[0].y, 1.0);
    }

    #[test]
    fn a_kick_within_its_bound_is_left_as_the_projection_gives_it() {
        // The same, disc 1 as light as disc 0: 1.25e-5 J of 5e-3 J.
        let (vel, contacts) = against_a_wall();
        let inv = [100.0, 100.0];
        let after = collapse::resolve(&vel, &inv, &contacts, PRESS_SWEEPS).expect("a kick");
        let held = within_press_bound(&vel, &inv, &contacts, after.clone(), energy(&vel, &inv));
        assert_eq!(held, Some(after));
    }

    /// `bodies` on a table with one solid line from `line[0]` to `line[1]`,
    /// run under `revision` until `until` (at most 100,000 events): the
    /// world after the run and how it ended.
    fn run_against_a_line(
        bodies: Vec<BodySpec>,
        line: [DVec2; 2],
        revision: Revision,
        until: f64,
    ) -> (World, End) {
        let scene = Scene {
            g: 9.81,
            bodies,
            lines: vec![Line::new(line[0], line[1], crate::LineKind::Line)],
            ..Scene::default()
        };
        let config = WorldConfig {
            revision,
            ..WorldConfig::default()
        };
        let mut world = World::new(&scene, config).expect("a valid scene");
        let limits = Limits {
            until,
            max_events: 100_000,
            ..Limits::default()
        };
        let end = world.run(&limits, &mut ());
        (world, end)
    }

    /// A heavy frictionless disc sliding along the floor at 7.4e-4 m/s
    /// into a light braking one that lies on it, 0.023 rad ahead of its
    /// top (mixed-box 559777's pair): the end, the events, the heavy disc's
    /// velocity and the kinetic energy before and after, run under
    /// `revision` for 2 s.
    fn heavy_under_light_on_the_floor(revision: Revision) -> (EndReason, u64, DVec2, [f64; 2]) {
        let (rh, rl) = (0.0195, 0.0272);
        let s = rh + rl;
        let tilt = 0.0229_f64;
        let heavy = DVec2::new(0.0, rh);
        let light = heavy + DVec2::new(s * tilt.sin() + 1e-6, s * tilt.cos());
        let v = 7.447e-4;
        let bodies = vec![
            BodySpec::new(1, heavy, rh, 0.6626, 0.0)
                .with_restitution(0.0)
                .with_velocity(DVec2::new(v, 0.0)),
            BodySpec::new(2, light, rl, 3.286e-3, 0.3),
        ];
        let floor = [DVec2::new(-1.0, 0.0), DVec2::new(1.0, 0.0)];
        let (world, end) = run_against_a_line(bodies, floor, revision, 2.0);
        let before = 0.5 * 0.6626 * v * v;
        let t = world.time();
        let after: f64 = world
            .bodies()
            .map(|b| 0.5 * b.material.mass * b.trajectory.velocity(t).length_squared())
            .sum();
        let heavy = world.body(BodyId(1)).expect("disc 1");
        (
            end.reason,
            world.stats().events,
            heavy.trajectory.velocity(t),
            [before, after],
        )
    }

    #[test]
    fn a_heavy_disc_sliding_along_the_floor_takes_its_hit_with_the_floor_and_carries_a_braking_one_off_at_once(
    ) {
        let (old, old_events, _, _) = heavy_under_light_on_the_floor(Revision::R14);
        let (new, events, v, [before, after]) = heavy_under_light_on_the_floor(Revision::R15);
        // Revision 14 left it to the pressing contact: 75,650 events.
        assert_ne!(old, EndReason::Until);
        assert_eq!(new, EndReason::Until);
        assert!(events < 10, "{events} events");
        assert!(old_events > 100 * events, "{old_events} events under R14");
        // The heavy disc keeps to the floor, and no energy is gained.
        assert!(v.y.abs() <= 1e-12 * v.length() && v.x > 0.0, "{v}");
        assert!(after <= before, "{after:e} > {before:e}");
    }

    /// A heavy frictionless disc driven at 1e-3 m/s into a light plastic
    /// one that touches the wall `x = 0`, head-on, run under `revision`:
    /// the end, the events and the heavy disc's velocity at the end.
    fn heavy_into_light_against_a_wall(revision: Revision) -> (EndReason, u64, DVec2) {
        let r = 0.01;
        let bodies = vec![
            BodySpec::new(1, DVec2::new(r, 0.0), r, 1e-3, 0.3).with_restitution(0.0),
            BodySpec::new(2, DVec2::new(3.0 * r + 1e-4, 0.0), r, 1.0, 0.0)
                .with_velocity(DVec2::new(-1e-3, 0.0)),
        ];
        let wall = [DVec2::new(0.0, -1.0), DVec2::new(0.0, 1.0)];
        let (world, end) = run_against_a_line(bodies, wall, revision, 10.0);
        let heavy = world.body(BodyId(2)).expect("disc 2");
        (
            end.reason,
            world.stats().events,
            heavy.trajectory.velocity(world.time()),
        )
    }

    #[test]
    fn a_heavy_disc_driven_into_a_light_plastic_one_against_a_wall_stops_at_the_first_hit() {
        // The plastic limit of the pair against the wall: both at rest,
        // at the one hit between them.
        let (end, events, v) = heavy_into_light_against_a_wall(Revision::R13);
        assert_eq!((end, events, v), (EndReason::Rest, 1, DVec2::ZERO));
        // Revision 12 plays the sequence, each turn 0.1 per cent slower.
        let (_, events, _) = heavy_into_light_against_a_wall(Revision::R12);
        assert!(events > 100, "{events} events");
    }
}
