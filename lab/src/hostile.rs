//! Hostile scenes: a seeded generator of the configurations an exact event
//! engine finds hardest, and the checks every run of one must pass.
//!
//! Each [`Kind`] builds scenes of one family — chains of touching discs
//! pushing along a line, chains pinned between two walls, Newton's cradles,
//! dense hexagonal clusters, discs resting on walls, wedges (two segments
//! meeting at a corner), mixed radii/masses/friction/restitution, grazing
//! shots, hits from a million metres away, shots at 10^4–10^6 m/s,
//! inelastic bouncing between two walls (event times that grow without
//! bound), Galperin's billiard in a random frame, game-like boards, elastic
//! cradles pinned between walls, mixed 0/1 restitution in a box and
//! plastic piles on lines. A
//! scene is a pure function of its kind and seed (a SplitMix64 stream), so
//! a failure is reproduced from the two numbers alone.
//!
//! [`run`] computes a scene with the engine under an event cap and checks,
//! at every event, the bodies it involves: finite positions, velocities and
//! times; no overlap with any other disc, solid line or point beyond
//! `OVERLAP` of the contact distance (plus the floating-point resolution of
//! the coordinates); no centre crossing a solid line; time never going
//! back; kinetic energy not gained beyond rounding ([`ENERGY`]; at a
//! pressing hit, beyond its documented bounce, [`PRESS_GAIN`]), and, where
//! nothing outside acts, momentum kept. At the end: every pair again, the
//! energy of an elastic, frictionless run kept, the end reason (an event
//! cap is a livelock; `stuck` and `out-of-range` are accepted only where
//! their definitions in docs/model.md hold), the kind's own expectation (a
//! hit that must happen, Galperin's count) and the run's CPU time against
//! [`SLOW`] (CPU time of its thread: the wall clock of a shared machine
//! counts other processes too).

use cpu_time::ThreadTime;
use engine::obstacle::LineGeom;
use engine::rng::Rng;
use engine::{
    BodyId, BodySpec, EndReason, Event, EventHandler, EventKind, ExitResponse, Limits, Line,
    LineId, LineKind, Point, Revision, Scene, World, WorldConfig,
};
use glam::DVec2;
use std::collections::VecDeque;
use std::fmt;
use std::time::Duration;

/// Overlap allowed at an event, as a fraction of the contact distance.
pub const OVERLAP: f64 = 1e-9;

/// The event cap of one run (the livelock bound).
pub const MAX_EVENTS: u64 = 100_000;

/// A run slower than this is a failure (pathological slowness).
pub const SLOW: Duration = Duration::from_secs(1);

/// Rounding allowed in kinetic energy and momentum, as a fraction of the
/// largest kinetic energy (or sum of `m |v|`) seen: an event may add no
/// more, and an elastic, frictionless run may lose no more in all.
pub const ENERGY: f64 = 1e-10;

/// Kinetic energy an event of the approximated pressing contact may add,
/// as a fraction of the largest kinetic energy seen: `m w^2 / 2` of the
/// pair's reduced mass `m` with `w <= 0.05 (|v_i| + |v_j|)` (docs/model.md)
/// is at most 0.005 of the pair's energy; a kick over a cluster gives the
/// bounce speed to several pairs at once (0.0089 is the most measured).
pub const PRESS_GAIN: f64 = 2e-2;

/// The families of hostile scenes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Kind {
    PushChain,
    PinnedChain,
    Cradle,
    Cluster,
    WallContact,
    Wedge,
    Mixed,
    Grazing,
    Far,
    Fast,
    BetweenWalls,
    Galperin,
    GameLike,
    WalledCradle,
    MixedBox,
    PlasticLines,
}

impl Kind {
    /// Every kind, in report order.
    pub const ALL: [Kind; 16] = [
        Kind::PushChain,
        Kind::PinnedChain,
        Kind::Cradle,
        Kind::Cluster,
        Kind::WallContact,
        Kind::Wedge,
        Kind::Mixed,
        Kind::Grazing,
        Kind::Far,
        Kind::Fast,
        Kind::BetweenWalls,
        Kind::Galperin,
        Kind::GameLike,
        Kind::WalledCradle,
        Kind::MixedBox,
        Kind::PlasticLines,
    ];

    /// The kind's name in reports and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Kind::PushChain => "push-chain",
            Kind::PinnedChain => "pinned-chain",
            Kind::Cradle => "cradle",
            Kind::Cluster => "cluster",
            Kind::WallContact => "wall-contact",
            Kind::Wedge => "wedge",
            Kind::Mixed => "mixed",
            Kind::Grazing => "grazing",
            Kind::Far => "far",
            Kind::Fast => "fast",
            Kind::BetweenWalls => "between-walls",
            Kind::Galperin => "galperin",
            Kind::GameLike => "game-like",
            Kind::WalledCradle => "walled-cradle",
            Kind::MixedBox => "mixed-box",
            Kind::PlasticLines => "plastic-lines",
        }
    }

    /// Whether `stuck` (no finite answer in the model) is a correct end for
    /// every scene of the kind.
    fn may_be_stuck(self) -> bool {
        matches!(self, Kind::PinnedChain)
    }
}

/// How a run failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Failure {
    /// The generator made a scene the engine refuses (a generator bug).
    Refused,
    /// A non-finite time, position or velocity.
    NotFinite,
    /// Two discs, or a disc and an obstacle, overlap beyond [`OVERLAP`].
    Overlap,
    /// A centre crossed a solid line.
    Tunnel,
    /// Time went backwards.
    Backwards,
    /// The event cap was reached.
    Livelock,
    /// The engine declared `stuck` where the model has a finite answer.
    Stuck,
    /// A hit that must happen did not.
    MissedHit,
    /// Galperin's count is wrong.
    Count,
    /// The run took more CPU time than [`SLOW`].
    Slow,
    /// The engine panicked.
    Panic,
    /// Kinetic energy grew at an event beyond rounding ([`ENERGY`]).
    EnergyGained,
    /// Kinetic energy fell where every disc is elastic and frictionless.
    EnergyLost,
    /// Momentum changed where no wall, point or friction acts.
    Momentum,
    /// The end reason does not hold of the final state (see
    /// `Checker::check_end`).
    EndReason,
}

impl Failure {
    /// Every failure, in report order.
    pub const ALL: [Failure; 15] = [
        Failure::Refused,
        Failure::NotFinite,
        Failure::Overlap,
        Failure::Tunnel,
        Failure::Backwards,
        Failure::Livelock,
        Failure::Stuck,
        Failure::MissedHit,
        Failure::Count,
        Failure::Slow,
        Failure::Panic,
        Failure::EnergyGained,
        Failure::EnergyLost,
        Failure::Momentum,
        Failure::EndReason,
    ];

    /// The failure's name in reports.
    pub fn name(self) -> &'static str {
        match self {
            Failure::Refused => "refused",
            Failure::NotFinite => "not-finite",
            Failure::Overlap => "overlap",
            Failure::Tunnel => "tunnel",
            Failure::Backwards => "backwards",
            Failure::Livelock => "livelock",
            Failure::Stuck => "stuck",
            Failure::MissedHit => "missed-hit",
            Failure::Count => "count",
            Failure::Slow => "slow",
            Failure::Panic => "panic",
            Failure::EnergyGained => "energy-gained",
            Failure::EnergyLost => "energy-lost",
            Failure::Momentum => "momentum",
            Failure::EndReason => "end-reason",
        }
    }
}

/// A generated scene with what the run must show.
#[derive(Clone, Debug)]
pub struct Hostile {
    pub kind: Kind,
    pub seed: u64,
    pub scene: Scene,
    /// Compute no further (frictionless scenes that never end).
    pub until: f64,
    /// At least one collision must happen.
    pub must_hit: bool,
    /// Exactly this many collisions (Galperin).
    pub collisions: Option<u64>,
    /// Discs whose centre leaves a sensor are removed (the game's rule).
    pub remove_on_exit: bool,
    /// `stuck` is a correct end: the scene has no finite answer (a chain
    /// pressed between two walls).
    pub may_be_stuck: bool,
}

/// What one run showed.
#[derive(Clone, Debug)]
pub struct Report {
    pub failures: Vec<Failure>,
    pub events: u64,
    pub end: Option<EndReason>,
    /// Largest overlap seen, as a fraction of the contact distance.
    pub worst_overlap: f64,
    /// Largest gain of kinetic energy at one event, as a fraction of the
    /// largest kinetic energy seen.
    pub worst_gain: f64,
    /// The same at events of the approximated pressing contact (bounded by
    /// [`PRESS_GAIN`]).
    pub worst_press_gain: f64,
    /// CPU time of the run.
    pub elapsed: Duration,
    /// The most events in a row at one time (the same `f64`): a livelock
    /// at one instant runs this up to the event cap, a long run that
    /// advances in time does not.
    pub longest_instant: u64,
}

impl fmt::Display for Report {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names: Vec<&str> = self.failures.iter().map(|x| x.name()).collect();
        write!(
            f,
            "{} events, end {:?}, worst overlap {:.3e}, worst energy gain {:.3e} ({:.3e} pressing), {:.1} ms, longest run at one time {} events, failures [{}]",
            self.events,
            self.end,
            self.worst_overlap,
            self.worst_gain,
            self.worst_press_gain,
            self.elapsed.as_secs_f64() * 1e3,
            self.longest_instant,
            names.join(", ")
        )
    }
}

/// The stream of one hostile scene: SplitMix64 from the scene's seed.
fn stream(seed: u64) -> Rng {
    Rng::splitmix64(seed ^ 0x5851_f42d_4c95_7f2d)
}

/// The materials a hostile scene draws, on top of the plain draws.
trait MaterialDraws {
    /// Restitution: often exactly 0 or 1, else anywhere between.
    fn restitution(&mut self) -> f64;
    /// Friction: mixed, never zero.
    fn mu(&mut self) -> f64;
}

impl MaterialDraws for Rng {
    fn restitution(&mut self) -> f64 {
        match self.below(4) {
            0 => 0.0,
            1 => 1.0,
            _ => self.unit(),
        }
    }

    fn mu(&mut self) -> f64 {
        match self.below(4) {
            0 => 0.3,
            1 => self.log_range(1e-3, 30.0),
            _ => self.range(0.05, 0.6),
        }
    }
}

fn disc(id: u64, pos: DVec2, vel: DVec2, radius: f64, mass: f64, mu: f64, e: f64) -> BodySpec {
    BodySpec::new(id, pos, radius, mass, mu)
        .with_velocity(vel)
        .with_restitution(e)
}

fn scene(bodies: Vec<BodySpec>, points: Vec<Point>, lines: Vec<Line>) -> Scene {
    Scene {
        g: engine::scene::DEFAULT_G,
        t: 0.0,
        bodies,
        points,
        lines,
    }
}

impl Hostile {
    fn plain(kind: Kind, seed: u64, scene: Scene) -> Self {
        Hostile {
            kind,
            seed,
            scene,
            until: f64::INFINITY,
            must_hit: false,
            collisions: None,
            remove_on_exit: false,
            may_be_stuck: kind.may_be_stuck(),
        }
    }

    /// The scene of `kind` for `seed`.
    pub fn generate(kind: Kind, seed: u64) -> Hostile {
        let mut rng = stream(seed.wrapping_mul(31).wrapping_add(kind as u64));
        let r = &mut rng;
        match kind {
            Kind::PushChain => push_chain(r, kind, seed, false),
            Kind::PinnedChain => push_chain(r, kind, seed, true),
            Kind::Cradle => cradle(r, seed),
            Kind::Cluster => cluster(r, seed),
            Kind::WallContact => wall_contact(r, seed),
            Kind::Wedge => wedge(r, seed),
            Kind::Mixed => mixed(r, seed),
            Kind::Grazing => grazing(r, seed),
            Kind::Far => far(r, seed),
            Kind::Fast => fast(r, seed),
            Kind::BetweenWalls => between_walls(r, seed),
            Kind::Galperin => galperin(r, seed),
            Kind::GameLike => game_like(r, seed),
            Kind::WalledCradle => walled_cradle(r, seed),
            Kind::MixedBox => mixed_box(r, seed),
            Kind::PlasticLines => plastic_lines(r, seed),
        }
    }
}

/// Touching discs on a line, all with the same velocity along it; pinned:
/// with a wall touching each end of the chain.
fn push_chain(r: &mut Rng, kind: Kind, seed: u64, pinned: bool) -> Hostile {
    let n = 2 + r.below(5) as usize;
    let d = if r.chance(0.5) {
        DVec2::X
    } else {
        r.direction()
    };
    let speed = r.log_range(0.05, 5.0);
    let equal = r.chance(0.5);
    let r0 = r.range(0.01, 0.05);
    let ascending = r.chance(0.5);
    let base_mu = r.range(0.05, 0.3);
    let mut bodies = Vec::new();
    let mut x = 0.0;
    let mut prev = 0.0;
    for k in 0..n {
        let rad = if equal { r0 } else { r.range(0.01, 0.05) };
        if k > 0 {
            x += prev + rad;
        }
        prev = rad;
        let mu = if ascending {
            base_mu * (1 + k) as f64
        } else {
            r.mu()
        };
        let mass = if r.chance(0.5) {
            0.01
        } else {
            r.log_range(1e-3, 1.0)
        };
        let e = r.restitution();
        bodies.push(disc(k as u64 + 1, d * x, d * speed, rad, mass, mu, e));
    }
    let mut lines = Vec::new();
    if pinned {
        let first = &bodies[0];
        let last = &bodies[n - 1];
        let back = first.pos - d * first.radius;
        let front = last.pos + d * last.radius;
        let side = d.perp();
        lines.push(Line::new(back - side, back + side, LineKind::Line));
        lines.push(Line::new(front + side, front - side, LineKind::Line));
    }
    Hostile::plain(kind, seed, scene(bodies, Vec::new(), lines))
}

fn cradle(r: &mut Rng, seed: u64) -> Hostile {
    let n = 2 + r.below(7) as usize;
    let rad = r.range(0.01, 0.05);
    let e = r.restitution();
    let mu = r.range(0.0, 0.3);
    let mut bodies = Vec::new();
    for k in 0..n {
        let m = if r.chance(0.5) {
            0.01
        } else {
            r.log_range(1e-3, 1.0)
        };
        bodies.push(disc(
            k as u64 + 1,
            DVec2::new(2.0 * rad * k as f64, 0.0),
            DVec2::ZERO,
            rad,
            m,
            mu,
            e,
        ));
    }
    let gap = if r.chance(0.5) {
        0.0
    } else {
        r.range(0.0, 0.2)
    };
    let speed = r.log_range(0.05, 5.0);
    bodies.push(disc(
        n as u64 + 1,
        DVec2::new(-2.0 * rad - gap, 0.0),
        DVec2::new(speed, 0.0),
        rad,
        0.01,
        mu,
        r.restitution(),
    ));
    let mut h = Hostile::plain(Kind::Cradle, seed, scene(bodies, Vec::new(), Vec::new()));
    if mu == 0.0 {
        h.until = 100.0;
    }
    h
}

/// Hexagonal positions of `n` discs of radius `rad`, touching.
fn hex(n: usize, rad: f64) -> Vec<DVec2> {
    let mut out = Vec::new();
    let h = 3f64.sqrt() * rad;
    let mut row = 0i32;
    while out.len() < n {
        for col in 0..4 {
            if out.len() == n {
                break;
            }
            let x = 2.0 * rad * col as f64 + if row % 2 == 1 { rad } else { 0.0 };
            out.push(DVec2::new(x, h * row as f64));
        }
        row += 1;
    }
    out
}

fn cluster(r: &mut Rng, seed: u64) -> Hostile {
    let n = 3 + r.below(14) as usize;
    let rad = r.range(0.01, 0.03);
    let mut bodies: Vec<BodySpec> = hex(n, rad)
        .into_iter()
        .enumerate()
        .map(|(k, p)| {
            let m = if r.chance(0.5) {
                0.01
            } else {
                r.log_range(1e-3, 1.0)
            };
            let mu = if r.chance(0.5) { 0.3 } else { r.mu() };
            let e = r.restitution();
            disc(k as u64 + 1, p, DVec2::ZERO, rad, m, mu, e)
        })
        .collect();
    let centre = DVec2::new(3.0 * rad, 2.0 * rad);
    let from = centre - r.direction() * (10.0 * rad + r.range(0.0, 0.3));
    let aim = centre + DVec2::new(r.range(-3.0, 3.0), r.range(-3.0, 3.0)) * rad;
    let speed = r.log_range(0.1, 5.0);
    let vel = (aim - from).normalize() * speed;
    bodies.push(disc(
        n as u64 + 1,
        from,
        vel,
        rad,
        0.01,
        r.mu(),
        r.restitution(),
    ));
    Hostile::plain(Kind::Cluster, seed, scene(bodies, Vec::new(), Vec::new()))
}

fn box_walls(half: f64) -> Vec<Line> {
    let c = [
        DVec2::new(-half, -half),
        DVec2::new(half, -half),
        DVec2::new(half, half),
        DVec2::new(-half, half),
    ];
    (0..4)
        .map(|k| Line::new(c[k], c[(k + 1) % 4], LineKind::Segment))
        .collect()
}

fn wall_contact(r: &mut Rng, seed: u64) -> Hostile {
    let half = 0.3;
    let rad = r.range(0.01, 0.04);
    let mut bodies = Vec::new();
    let n = 2 + r.below(6) as usize;
    let mut x = -half + rad;
    for k in 0..n {
        // Touching the bottom wall, side by side, some touching each other.
        if k > 0 {
            x += 2.0 * rad + if r.chance(0.5) { 0.0 } else { 0.01 };
        }
        if x + rad > half {
            break; // the row is full: the next disc would cut the right wall
        }
        bodies.push(disc(
            k as u64 + 1,
            DVec2::new(x, -half + rad),
            DVec2::ZERO,
            rad,
            r.log_range(1e-3, 1.0),
            r.mu(),
            r.restitution(),
        ));
    }
    let speed = r.log_range(0.1, 5.0);
    let from = DVec2::new(r.range(-0.1, 0.2), r.range(0.0, 0.2));
    let aim = bodies[r.below(bodies.len() as u64) as usize].pos
        + DVec2::new(r.range(-1.0, 1.0) * rad, 0.0);
    let vel = (aim - from).normalize() * speed;
    bodies.push(disc(
        n as u64 + 1,
        from,
        vel,
        rad,
        0.01,
        r.mu(),
        r.restitution(),
    ));
    Hostile::plain(
        Kind::WallContact,
        seed,
        scene(bodies, Vec::new(), box_walls(half)),
    )
}

fn wedge(r: &mut Rng, seed: u64) -> Hostile {
    let angle = r.range(10f64.to_radians(), 170f64.to_radians());
    let corner = DVec2::ZERO;
    let len = 3.0;
    let a = DVec2::X * len;
    let b = DVec2::new(angle.cos(), angle.sin()) * len;
    let lines = vec![
        Line::new(a, corner, LineKind::Segment),
        Line::new(corner, b, LineKind::Segment),
    ];
    let rad = r.range(0.01, 0.05);
    let e = r.restitution();
    let mu = if r.chance(0.2) { 0.0 } else { r.mu() };
    let speed = r.log_range(0.1, 5.0);
    let mut bodies = Vec::new();
    if r.chance(0.5) {
        // Touching the first wall, sliding along it into the corner.
        let p = DVec2::new((0.5f64).max(3.0 * rad / angle.tan()), rad);
        bodies.push(disc(1, p, DVec2::new(-speed, 0.0), rad, 0.01, mu, e));
    } else {
        // Straight into the corner along the bisector (or near it).
        let bis = DVec2::new((angle / 2.0).cos(), (angle / 2.0).sin());
        // Clear of both walls however narrow the wedge.
        let p = bis * (0.5f64).max(2.0 * rad / (angle / 2.0).sin());
        let dir = -(bis + bis.perp() * r.range(-0.2, 0.2)).normalize();
        bodies.push(disc(1, p, dir * speed, rad, 0.01, mu, e));
    }
    if r.chance(0.4) {
        // A second disc following the first.
        let first = bodies[0];
        let back = first.pos - first.vel.normalize() * (2.0 * rad + r.range(0.0, 0.05));
        bodies.push(disc(2, back, first.vel, rad, 0.01, r.mu(), r.restitution()));
    }
    let mut h = Hostile::plain(Kind::Wedge, seed, scene(bodies, Vec::new(), lines));
    if mu == 0.0 {
        h.until = 100.0;
    }
    h
}

fn mixed(r: &mut Rng, seed: u64) -> Hostile {
    let half = 0.5;
    // A fixed point in a corner of the box; no disc may start on it.
    let post = DVec2::new(0.9 * half, 0.9 * half);
    let n = 2 + r.below(10) as usize;
    let mut bodies: Vec<BodySpec> = Vec::new();
    let mut tries = 0;
    while bodies.len() < n && tries < 200 {
        tries += 1;
        let rad = r.log_range(0.005, 0.08);
        let p = DVec2::new(r.range(-half, half), r.range(-half, half)) * (1.0 - 0.2);
        if (post - p).length() <= rad
            || bodies.iter().any(|b| (b.pos - p).length() < b.radius + rad)
        {
            continue;
        }
        let vel = if r.chance(0.5) {
            r.direction() * r.log_range(0.01, 5.0)
        } else {
            DVec2::ZERO
        };
        bodies.push(disc(
            bodies.len() as u64 + 1,
            p,
            vel,
            rad,
            r.log_range(1e-3, 10.0),
            r.mu(),
            r.restitution(),
        ));
    }
    if let Some(b) = bodies.first_mut() {
        b.vel = r.direction() * r.log_range(0.1, 5.0);
    }
    let points = vec![Point { pos: post }];
    Hostile::plain(Kind::Mixed, seed, scene(bodies, points, box_walls(half)))
}

fn grazing(r: &mut Rng, seed: u64) -> Hostile {
    let rad = r.range(0.01, 0.05);
    let target = DVec2::new(r.range(0.2, 1.0), 0.0);
    let offset = 2.0 * rad * (1.0 + r.range(-1e-12, 1e-12));
    let mu = if r.chance(0.3) { 0.0 } else { r.mu() };
    let speed = r.log_range(0.5, 5.0);
    let bodies = vec![
        disc(
            1,
            DVec2::new(0.0, offset),
            DVec2::new(speed, 0.0),
            rad,
            0.01,
            mu,
            r.restitution(),
        ),
        disc(2, target, DVec2::ZERO, rad, 0.01, r.mu(), r.restitution()),
    ];
    let points = vec![Point {
        pos: DVec2::new(target.x + 0.3, -offset / 2.0),
    }];
    let mut h = Hostile::plain(Kind::Grazing, seed, scene(bodies, points, Vec::new()));
    if mu == 0.0 {
        h.until = 1e3;
    }
    h
}

fn far(r: &mut Rng, seed: u64) -> Hostile {
    let dist = r.log_range(1e5, 1e7);
    let rad = r.log_range(0.01, 1.0);
    let d = if r.chance(0.5) {
        DVec2::X
    } else {
        r.direction()
    };
    let speed = r.log_range(0.1, 100.0);
    let start = d * -dist;
    let mut bodies = vec![disc(1, start, d * speed, rad, 1.0, 0.0, r.restitution())];
    let mut lines = Vec::new();
    if r.chance(0.5) {
        bodies.push(disc(2, DVec2::ZERO, DVec2::ZERO, rad, 1.0, r.mu(), 1.0));
    } else {
        let side = d.perp();
        lines.push(Line::new(-side, side, LineKind::Segment));
    }
    let mut h = Hostile::plain(Kind::Far, seed, scene(bodies, Vec::new(), lines));
    h.must_hit = true;
    h.until = 1e12;
    h
}

fn fast(r: &mut Rng, seed: u64) -> Hostile {
    let speed = r.log_range(1e4, 1e6);
    let rad = r.range(0.01, 0.05);
    let d = if r.chance(0.5) {
        DVec2::X
    } else {
        r.direction()
    };
    let side = d.perp();
    let gap = r.range(0.1, 2.0);
    let mu = if r.chance(0.5) { 0.0 } else { r.mu() };
    let mut lines = vec![Line::new(d * gap - side, d * gap + side, LineKind::Line)];
    if mu == 0.0 {
        // Frictionless: bouncing between two walls, a few thousand times.
        lines.push(Line::new(-d * gap + side, -d * gap - side, LineKind::Line));
    }
    let bodies = vec![disc(
        1,
        DVec2::ZERO,
        d * speed,
        rad,
        0.01,
        mu,
        r.restitution(),
    )];
    let mut h = Hostile::plain(Kind::Fast, seed, scene(bodies, Vec::new(), lines));
    h.must_hit = true;
    if mu == 0.0 {
        h.until = 1e-3;
    }
    h
}

fn between_walls(r: &mut Rng, seed: u64) -> Hostile {
    let e = r.range(0.05, 0.95);
    let rad = r.range(0.01, 0.05);
    let w = r.range(0.1, 1.0);
    let lines = vec![
        Line::new(DVec2::new(-w, 1.0), DVec2::new(-w, -1.0), LineKind::Line),
        Line::new(DVec2::new(w, -1.0), DVec2::new(w, 1.0), LineKind::Line),
    ];
    let mut bodies = vec![disc(
        1,
        DVec2::ZERO,
        DVec2::new(r.log_range(0.1, 10.0), 0.0),
        rad,
        0.01,
        0.0,
        e,
    )];
    for k in 0..r.below(3) {
        bodies.push(disc(
            k + 2,
            DVec2::new(0.0, 2.0 + k as f64),
            DVec2::new(0.0, r.log_range(0.1, 10.0)),
            rad,
            0.01,
            0.0,
            1.0,
        ));
    }
    Hostile::plain(Kind::BetweenWalls, seed, scene(bodies, Vec::new(), lines))
}

fn galperin(r: &mut Rng, seed: u64) -> Hostile {
    let digits = 1 + r.below(3);
    let expected = [3, 31, 314][digits as usize - 1];
    let big = 100f64.powi(digits as i32 - 1);
    // Off the axes, rounding puts the discs off their common line by an
    // ulp, and every hit of the small disc on the big one (a convex
    // scatterer) multiplies that: past about a hundred hits the billiard is
    // chaotic in floating point, whatever the engine. So 314 is counted on
    // an axis; 3 and 31 in any direction.
    let d = if r.chance(0.3) || digits == 3 {
        DVec2::X
    } else {
        r.direction()
    };
    let rad = r.range(0.01, 0.2);
    let wall = DVec2::ZERO;
    let small_at = r.range(2.0, 5.0) * rad;
    let big_at = small_at + 2.0 * rad + r.range(0.01, 2.0);
    let speed = r.log_range(0.1, 10.0);
    let side = d.perp();
    let lines = vec![Line::new(wall + side, wall - side, LineKind::Line)];
    let bodies = vec![
        disc(1, d * small_at, DVec2::ZERO, rad, 1.0, 0.0, 1.0),
        disc(2, d * big_at, -d * speed, rad, big, 0.0, 1.0),
    ];
    let mut h = Hostile::plain(Kind::Galperin, seed, scene(bodies, Vec::new(), lines));
    h.collisions = Some(expected);
    h
}

fn game_like(r: &mut Rng, seed: u64) -> Hostile {
    let side = 0.32;
    let rad = 0.016;
    let mut bodies: Vec<BodySpec> = Vec::new();
    let clusters = 1 + r.below(3);
    for _ in 0..clusters {
        let n = 2 + r.below(6) as usize;
        let at = DVec2::new(r.range(0.05, 0.2), r.range(0.05, 0.2));
        for p in hex(n, rad) {
            let pos = at + p;
            let free = bodies.iter().all(|b| (b.pos - pos).length() >= 2.0 * rad);
            if free && pos.x < side && pos.y < side {
                let id = bodies.len() as u64 + 1;
                bodies.push(disc(id, pos, DVec2::ZERO, rad, 0.005, 0.3, 0.9));
            }
        }
    }
    if let Some(k) = (!bodies.is_empty()).then(|| r.below(bodies.len() as u64) as usize) {
        bodies[k].vel = r.direction() * r.range(0.05, 2.0);
    }
    let c = [
        DVec2::new(0.0, 0.0),
        DVec2::new(side, 0.0),
        DVec2::new(side, side),
        DVec2::new(0.0, side),
    ];
    let lines = (0..4)
        .map(|k| Line::sensor(c[k], c[(k + 1) % 4], LineKind::Line))
        .collect();
    let mut h = Hostile::plain(Kind::GameLike, seed, scene(bodies, Vec::new(), lines));
    h.remove_on_exit = true;
    h
}

/// A Newton's cradle on a line between two walls: elastic, frictionless
/// discs of mixed masses and radii, some touching, one or two moving. Where
/// every disc touches its neighbours and both walls (pinned) a moving disc
/// has no finite answer (`stuck`); with a gap anywhere the cradle rings
/// for ever and its energy must be kept to rounding.
fn walled_cradle(r: &mut Rng, seed: u64) -> Hostile {
    let n = 2 + r.below(7) as usize;
    let d = if r.chance(0.5) {
        DVec2::X
    } else {
        r.direction()
    };
    let base = r.range(0.01, 0.05);
    let equal = r.chance(0.5);
    let pinned = r.chance(0.4);
    let gap = |r: &mut Rng| {
        if pinned || r.chance(0.6) {
            0.0
        } else {
            r.log_range(1e-4, 1.0) * base
        }
    };
    let back_gap = gap(r);
    let mut bodies = Vec::new();
    let mut x = back_gap;
    let mut gaps = vec![back_gap];
    for k in 0..n {
        let rad = if equal { base } else { r.range(0.01, 0.05) };
        if k > 0 {
            let g = gap(r);
            gaps.push(g);
            x += g + rad;
        } else {
            x += rad;
        }
        let mass = if r.chance(0.5) {
            0.01
        } else {
            r.log_range(1e-3, 1.0)
        };
        bodies.push(disc(k as u64 + 1, d * x, DVec2::ZERO, rad, mass, 0.0, 1.0));
        x += rad;
    }
    let front_gap = gap(r);
    gaps.push(front_gap);
    let side = d.perp();
    let front = d * (x + front_gap);
    let lines = vec![
        Line::new(-side, side, LineKind::Line),
        Line::new(front + side, front - side, LineKind::Line),
    ];
    let mut fastest: f64 = 0.0;
    for _ in 0..1 + r.below(2) {
        let k = r.below(n as u64) as usize;
        let speed = r.log_range(0.05, 5.0);
        fastest = fastest.max(speed);
        bodies[k].vel = d * if r.chance(0.5) { speed } else { -speed };
    }
    let mut h = Hostile::plain(Kind::WalledCradle, seed, scene(bodies, Vec::new(), lines));
    // A ring through the cradle takes at least its narrowest gap at the
    // fastest speed: about 5,000 events in all.
    let narrowest = gaps
        .iter()
        .copied()
        .filter(|&g| g > 0.0)
        .fold(f64::INFINITY, f64::min);
    h.until = if narrowest.is_finite() {
        5_000.0 * narrowest / (fastest * (n + 2) as f64)
    } else {
        1.0
    };
    h.may_be_stuck = gaps.iter().all(|&g| g == 0.0);
    h
}

/// Discs of restitution exactly 0 or 1 (so plastic and elastic contacts
/// meet in one cluster) in a box: a hexagonal cluster in a corner touching
/// both walls, loose discs around it, the first one shot.
fn mixed_box(r: &mut Rng, seed: u64) -> Hostile {
    let half = 0.3;
    let rad = r.range(0.01, 0.03);
    let corner = DVec2::new(-half + rad, -half + rad);
    let e = |r: &mut Rng| if r.chance(0.5) { 0.0 } else { 1.0 };
    let mu = |r: &mut Rng| if r.chance(0.2) { 0.0 } else { r.mu() };
    let mut bodies: Vec<BodySpec> = Vec::new();
    for p in hex(2 + r.below(10) as usize, rad) {
        let m = r.log_range(1e-3, 1.0);
        let (mu, e) = (mu(r), e(r));
        bodies.push(disc(
            bodies.len() as u64 + 1,
            corner + p,
            DVec2::ZERO,
            rad,
            m,
            mu,
            e,
        ));
    }
    let mut tries = 0;
    while bodies.len() < 14 && tries < 20 {
        tries += 1;
        let rad = r.range(0.01, 0.03);
        let lim = half - rad;
        let p = DVec2::new(r.range(-lim, lim), r.range(-lim, lim));
        if bodies.iter().any(|b| (b.pos - p).length() < b.radius + rad) {
            continue;
        }
        let vel = if r.chance(0.3) {
            r.direction() * r.log_range(0.01, 5.0)
        } else {
            DVec2::ZERO
        };
        let m = r.log_range(1e-3, 1.0);
        let (mu, e) = (mu(r), e(r));
        bodies.push(disc(bodies.len() as u64 + 1, p, vel, rad, m, mu, e));
    }
    // The shot: the last disc (loose if any) aimed at the cluster.
    let aim = corner + DVec2::new(r.range(0.0, 4.0), r.range(0.0, 3.0)) * rad;
    if let Some(b) = bodies.last_mut() {
        let dir = (aim - b.pos).normalize_or_zero();
        b.vel = dir * r.log_range(0.1, 5.0);
    }
    let mut h = Hostile::plain(
        Kind::MixedBox,
        seed,
        scene(bodies, Vec::new(), box_walls(half)),
    );
    h.until = 100.0;
    h
}

/// A large hexagonal cluster of plastic discs (restitution 0) resting on
/// a solid line, often against a second one at its side, struck from
/// above.
fn plastic_lines(r: &mut Rng, seed: u64) -> Hostile {
    let n = 3 + r.below(38) as usize;
    let rad = r.range(0.01, 0.03);
    let mu = |r: &mut Rng| if r.chance(0.5) { 0.3 } else { r.mu() };
    let mut bodies: Vec<BodySpec> = hex(n, rad)
        .into_iter()
        .enumerate()
        .map(|(k, p)| {
            let m = if r.chance(0.5) {
                0.01
            } else {
                r.log_range(1e-3, 1.0)
            };
            disc(k as u64 + 1, p, DVec2::ZERO, rad, m, mu(r), 0.0)
        })
        .collect();
    let mut lines = vec![Line::new(
        DVec2::new(1.0, -rad),
        DVec2::new(-1.0, -rad),
        LineKind::Line,
    )];
    if r.chance(0.5) {
        lines.push(Line::new(
            DVec2::new(-rad, -1.0),
            DVec2::new(-rad, 1.0),
            LineKind::Line,
        ));
    }
    let top = bodies.iter().map(|b| b.pos.y).fold(0.0, f64::max);
    let from = DVec2::new(r.range(1.0, 8.0) * rad, top + r.range(3.0, 10.0) * rad);
    let aim = DVec2::new(r.range(0.0, 7.0) * rad, r.range(0.0, top));
    let vel = (aim - from).normalize() * r.log_range(0.1, 5.0);
    let e = if r.chance(0.5) { 0.0 } else { r.restitution() };
    bodies.push(disc(n as u64 + 1, from, vel, rad, 0.01, mu(r), e));
    Hostile::plain(Kind::PlasticLines, seed, scene(bodies, Vec::new(), lines))
}

/// Checks every event as it happens.
struct Checker {
    last: f64,
    solid: Vec<LineGeom>,
    /// Each body's side of each solid infinite line at the start.
    sides: Vec<(BodyId, Vec<f64>)>,
    points: Vec<DVec2>,
    remove: bool,
    failures: Vec<Failure>,
    worst: f64,
    collisions: u64,
    /// Kinetic energy at the latest event, and the largest seen.
    energy: f64,
    energy_scale: f64,
    /// Every disc elastic and frictionless: the energy at the start.
    elastic: Option<f64>,
    /// No wall, point, friction or removal: the momentum at the start and
    /// the sum of `m |v|` (its scale).
    isolated: Option<(DVec2, f64)>,
    /// Largest gain of energy at one event, of the largest energy seen:
    /// at an event of the pressing approximation, and at any other.
    worst_gain: f64,
    worst_press_gain: f64,
    /// Hits of the pressing approximation so far.
    pressed: u64,
    /// Events in a row at the latest event's time, and the most seen.
    instant: u64,
    longest_instant: u64,
    /// The revision the run is under, and the bodies of its latest
    /// [`STUCK_WINDOW`] events (oldest first): from the eighth revision a
    /// crawl that ends a run `stuck` is measured on those discs.
    revision: Revision,
    latest: VecDeque<EventKind>,
}

/// Latest events whose discs the check of a `stuck` end measures a crawl
/// on, as the engine's crawl does from the eighth revision (its collapse
/// window).
const STUCK_WINDOW: usize = 64;

impl Checker {
    fn fail(&mut self, f: Failure) {
        if !self.failures.contains(&f) {
            self.failures.push(f);
        }
    }

    fn check_body(&mut self, world: &World, id: BodyId, t: f64) {
        let Some(b) = world.body(id) else {
            return;
        };
        let p = b.trajectory.position(t);
        let v = b.trajectory.velocity(t);
        if !(p.is_finite() && v.is_finite()) {
            self.fail(Failure::NotFinite);
            return;
        }
        let r = b.material.radius;
        // Where a position can be known at all: the rounding of its
        // coordinates, and how far it moves in the rounding of the time.
        // A position is `p0 + u s`: its rounding scales with both terms.
        let mag = p.abs().max_element() + v.length() * t.abs();
        for other in world.bodies() {
            if other.id == id {
                continue;
            }
            let q = other.trajectory.position(t);
            let w = other.trajectory.velocity(t);
            let s = r + other.material.radius;
            let mag_q = q.abs().max_element() + w.length() * t.abs();
            self.overlap(s, (p - q).length(), mag + mag_q);
        }
        for k in 0..self.solid.len() {
            let d = self.solid[k].distance(p);
            self.overlap(r, d, mag);
        }
        for k in 0..self.points.len() {
            let q = self.points[k];
            self.overlap(r, (p - q).length(), mag);
        }
        if let Some((_, sides)) = self.sides.iter().find(|(b, _)| *b == id) {
            let crossed = sides
                .iter()
                .zip(&self.solid)
                .any(|(&s0, g)| !g.is_bounded() && s0 * g.signed_distance(p) < 0.0);
            if crossed {
                self.fail(Failure::Tunnel);
            }
        }
    }

    /// Checks the energy (and momentum, where nothing outside acts) of the
    /// world at `t`, the time of its latest event.
    fn check_energy(&mut self, world: &World, t: f64) {
        let (mut energy, mut momentum, mut scale) = (0.0, DVec2::ZERO, 0.0);
        for b in world.bodies() {
            let v = b.trajectory.velocity(t);
            let m = b.material.mass;
            energy += 0.5 * m * v.length_squared();
            momentum += m * v;
            scale += m * v.length();
        }
        let gain = (energy - self.energy) / self.energy_scale.max(f64::MIN_POSITIVE);
        // The approximated pressing contact parts a pressed pair at its
        // bounce speed whatever it hit at: a gain, bounded in docs/model.md.
        let pressed = world.stats().pressed;
        let allowed = if pressed > self.pressed {
            self.worst_press_gain = self.worst_press_gain.max(gain);
            PRESS_GAIN
        } else {
            self.worst_gain = self.worst_gain.max(gain);
            ENERGY
        };
        self.pressed = pressed;
        if energy > self.energy + allowed * self.energy_scale {
            self.fail(Failure::EnergyGained);
        }
        self.energy = energy;
        self.energy_scale = self.energy_scale.max(energy);
        if let Some(start) = self.elastic {
            if energy < start - ENERGY * start {
                self.fail(Failure::EnergyLost);
            }
        }
        if let Some((start, start_scale)) = self.isolated {
            if (momentum - start).length() > ENERGY * start_scale.max(scale) {
                self.fail(Failure::Momentum);
            }
        }
    }

    /// Checks that the end reason holds of the final state, by the model's
    /// definitions (docs/model.md), then runs `world` one event further to
    /// see what was pending: `rest`: nothing moves; `free`: something moves
    /// without friction and no event follows; `until`: it ended at the
    /// horizon; `stuck`: something moves and the next event comes before
    /// the fastest disc moves [`engine::limits`]' crawl (1e-9 of the
    /// smallest radius); `out-of-range`: the next event lies beyond 1e150 s
    /// and a disc is then beyond 1e154 m.
    fn check_end(&mut self, world: &mut World, end: &engine::End, until: f64) {
        let t = end.t;
        let moving = |w: &World| {
            w.bodies()
                // The largest coordinate: squares of tiny speeds underflow.
                .map(|b| b.trajectory.velocity(t).abs().max_element())
                .fold(0.0, f64::max)
        };
        let fastest = moving(world);
        let smallest = world
            .bodies()
            .map(|b| b.material.radius)
            .fold(f64::INFINITY, f64::min);
        let frictionless = world
            .bodies()
            .all(|b| b.trajectory.velocity(t) == DVec2::ZERO || b.trajectory.alpha() == 0.0);
        // From the eighth revision a crawl is measured on the discs of the
        // latest events; the smallest radius is theirs too.
        let involved = |w: &World| {
            let ids: Vec<BodyId> = self.latest.iter().flat_map(|k| k.bodies()).collect();
            w.bodies()
                .filter(|b| ids.contains(&b.id))
                .fold((0.0, f64::INFINITY), |(v, r), b| {
                    let speed = b.trajectory.velocity(t).abs().max_element();
                    (f64::max(v, speed), f64::min(r, b.material.radius))
                })
        };
        let (local_fastest, local_smallest) = involved(world);
        let crawl_measured_locally = self.revision.at_least_r8();
        let holds = match end.reason {
            EndReason::Rest => fastest == 0.0,
            EndReason::Free => {
                fastest > 0.0 && frictionless && world.step(f64::INFINITY, &mut ()).is_none()
            }
            EndReason::Until => t == until,
            EndReason::Stuck => {
                fastest > 0.0
                    && world.step(f64::INFINITY, &mut ()).is_some_and(|next| {
                        let dt = next.t - t;
                        dt * fastest <= 1e-9 * smallest
                            || (crawl_measured_locally
                                && dt * local_fastest <= 1e-9 * local_smallest)
                    })
            }
            EndReason::OutOfRange => world.step(f64::INFINITY, &mut ()).is_some_and(|next| {
                next.t > 1e150
                    && world
                        .bodies()
                        .any(|b| b.trajectory.position(next.t).abs().max_element() > 1e154)
            }),
            EndReason::MaxEvents | EndReason::MaxCollisions => true,
        };
        if !holds {
            self.fail(Failure::EndReason);
        }
    }

    /// Contact distance `s`, centre distance `d`, coordinate magnitude `mag`.
    fn overlap(&mut self, s: f64, d: f64, mag: f64) {
        let depth = (s - d) / s;
        let resolution = 4.0 * f64::EPSILON * mag / s;
        if depth > self.worst {
            self.worst = depth;
        }
        if depth > OVERLAP + resolution {
            self.fail(Failure::Overlap);
        }
    }
}

impl EventHandler for Checker {
    fn on_event(&mut self, world: &World, event: &Event) {
        if !event.t.is_finite() {
            self.fail(Failure::NotFinite);
            return;
        }
        if event.t < self.last {
            self.fail(Failure::Backwards);
        }
        self.instant = if event.t == self.last {
            self.instant + 1
        } else {
            1
        };
        self.longest_instant = self.longest_instant.max(self.instant);
        if self.latest.len() == STUCK_WINDOW {
            self.latest.pop_front();
        }
        self.latest.push_back(event.kind);
        self.last = event.t;
        self.collisions += event.kind.is_collision() as u64;
        for id in event.kind.bodies() {
            self.check_body(world, id, event.t);
        }
        self.check_energy(world, event.t);
    }

    fn on_region_exit(&mut self, _t: f64, _body: BodyId, _line: LineId) -> ExitResponse {
        if self.remove {
            ExitResponse::Remove
        } else {
            ExitResponse::Stay
        }
    }
}

/// Runs one hostile scene and checks it.
pub fn run(h: &Hostile) -> Report {
    run_under(h, Revision::LATEST)
}

/// Runs one hostile scene under the engine's `revision` and checks it.
pub fn run_under(h: &Hostile, revision: Revision) -> Report {
    run_capped(h, revision, MAX_EVENTS)
}

/// Runs one hostile scene under the engine's `revision` with an event cap
/// of `max_events` (a run that reaches it is a livelock) and checks it.
pub fn run_capped(h: &Hostile, revision: Revision, max_events: u64) -> Report {
    let started = ThreadTime::now();
    let mut report = Report {
        failures: Vec::new(),
        events: 0,
        end: None,
        worst_overlap: 0.0,
        worst_gain: 0.0,
        worst_press_gain: 0.0,
        elapsed: Duration::ZERO,
        longest_instant: 0,
    };
    let config = WorldConfig {
        revision,
        ..WorldConfig::default()
    };
    let mut world = match World::new(&h.scene, config) {
        Ok(w) => w,
        Err(_) => {
            report.failures.push(Failure::Refused);
            return report;
        }
    };
    let solid: Vec<LineGeom> = h
        .scene
        .lines
        .iter()
        .filter(|l| !l.sensor)
        .filter_map(LineGeom::new)
        .collect();
    let sides = h
        .scene
        .bodies
        .iter()
        .map(|b| {
            (
                b.id,
                solid.iter().map(|g| g.signed_distance(b.pos)).collect(),
            )
        })
        .collect();
    let mut checker = Checker {
        last: h.scene.t,
        solid,
        sides,
        points: h.scene.points.iter().map(|p| p.pos).collect(),
        remove: h.remove_on_exit,
        failures: Vec::new(),
        worst: 0.0,
        collisions: 0,
        energy: 0.0,
        energy_scale: 0.0,
        elastic: None,
        isolated: None,
        worst_gain: 0.0,
        worst_press_gain: 0.0,
        pressed: 0,
        instant: 0,
        longest_instant: 0,
        revision,
        latest: VecDeque::with_capacity(STUCK_WINDOW),
    };
    let bodies = &h.scene.bodies;
    let energy: f64 = bodies
        .iter()
        .map(|b| 0.5 * b.mass * b.vel.length_squared())
        .sum();
    (checker.energy, checker.energy_scale) = (energy, energy);
    let frictionless = bodies.iter().all(|b| b.mu == 0.0);
    if frictionless && bodies.iter().all(|b| b.restitution == 1.0) {
        checker.elastic = Some(energy);
    }
    let walls = h.scene.lines.iter().any(|l| !l.sensor) || !h.scene.points.is_empty();
    if frictionless && !walls && !h.remove_on_exit {
        checker.isolated = Some((
            bodies.iter().map(|b| b.mass * b.vel).sum(),
            bodies.iter().map(|b| b.mass * b.vel.length()).sum(),
        ));
    }
    let limits = Limits {
        until: h.until,
        max_collisions: u64::MAX,
        max_events,
    };
    let end = world.run(&limits, &mut checker);
    report.events = world.stats().events;
    report.end = Some(end.reason);

    // Every pair at the end.
    let t = end.t;
    if !t.is_finite() {
        checker.fail(Failure::NotFinite);
    } else {
        let ids: Vec<BodyId> = world.bodies().map(|b| b.id).collect();
        for id in ids {
            checker.check_body(&world, id, t);
        }
    }
    checker.check_end(&mut world, &end, h.until);
    match end.reason {
        EndReason::MaxEvents => checker.fail(Failure::Livelock),
        EndReason::Stuck if !h.may_be_stuck => checker.fail(Failure::Stuck),
        _ => {}
    }
    if h.must_hit && checker.collisions == 0 {
        checker.fail(Failure::MissedHit);
    }
    if let Some(n) = h.collisions {
        if checker.collisions != n {
            checker.fail(Failure::Count);
        }
    }
    report.elapsed = started.elapsed();
    if report.elapsed > SLOW {
        checker.fail(Failure::Slow);
    }
    report.failures = checker.failures;
    report.worst_overlap = checker.worst;
    report.worst_gain = checker.worst_gain;
    report.worst_press_gain = checker.worst_press_gain;
    report.longest_instant = checker.longest_instant;
    report
}

/// Runs `h` under `revision` with an event cap of `max_events`, turning a
/// panic into a [`Failure::Panic`].
pub fn run_caught(h: &Hostile, revision: Revision, max_events: u64) -> Report {
    match std::panic::catch_unwind(|| run_capped(h, revision, max_events)) {
        Ok(r) => r,
        Err(_) => Report {
            failures: vec![Failure::Panic],
            events: 0,
            end: None,
            worst_overlap: 0.0,
            worst_gain: 0.0,
            worst_press_gain: 0.0,
            elapsed: Duration::ZERO,
            longest_instant: 0,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_longest_run_at_one_time_counts_a_cradles_hits_at_one_instant() {
        // Three equal elastic discs in a row, touching, the first moving
        // into the others: its hit passes down the row at one instant (two
        // hits at t = 0), and the last disc slides off alone.
        let bodies = (0..3u32)
            .map(|k| {
                let vel = if k == 0 { DVec2::X } else { DVec2::ZERO };
                let pos = DVec2::new(0.1 * f64::from(k), 0.0);
                disc(u64::from(k) + 1, pos, vel, 0.05, 1.0, 0.0, 1.0)
            })
            .collect();
        let h = Hostile::plain(Kind::Cradle, 0, scene(bodies, Vec::new(), Vec::new()));
        let report = run(&h);
        assert!(report.failures.is_empty(), "{report}");
        assert_eq!(report.events, 2, "{report}");
        assert_eq!(report.longest_instant, 2, "{report}");
    }

    #[test]
    fn a_stuck_end_is_judged_on_the_crawling_discs_from_revision_8() {
        // Under the twelfth revision this mixed box ends `stuck`: a ring of
        // discs crawling, its latest events 1e-9 s apart, while a disc
        // elsewhere still slides at centimetres a second. The crawl is
        // measured on the ring's discs (docs/model.md), so the end is
        // true, though the scene's `stuck` is still a failure of its own.
        let h = Hostile::generate(Kind::MixedBox, 491_744);
        let report = run_under(&h, Revision::R12);
        assert_eq!(report.end, Some(EndReason::Stuck));
        assert_eq!(report.failures, vec![Failure::Stuck], "{report}");
    }

    #[test]
    fn every_kind_generates_valid_scenes() {
        for kind in Kind::ALL {
            for seed in 0..50 {
                let h = Hostile::generate(kind, seed);
                assert!(
                    h.scene.validate().is_ok(),
                    "{} seed {seed}: {:?}",
                    kind.name(),
                    h.scene.validate()
                );
            }
        }
    }

    #[test]
    fn a_scene_is_a_function_of_its_kind_and_seed() {
        let a = Hostile::generate(Kind::Cluster, 7);
        let b = Hostile::generate(Kind::Cluster, 7);
        assert_eq!(a.scene, b.scene);
    }

    #[test]
    fn a_mixed_scene_never_starts_a_disc_on_its_fixed_point() {
        // Seed 1,009,932 once put a disc over the corner point, and the
        // engine refused the scene.
        let h = Hostile::generate(Kind::Mixed, 1_009_932);
        assert!(World::new(&h.scene, WorldConfig::default()).is_ok());
    }

    /// Scenes among the first seeds of each kind that still fail: none
    /// since revision 8 (the last, mixed-box 36, a frictionless plastic
    /// disc creeping in a pile while an elastic disc crosses the box, ran
    /// into the event cap under revisions 6 and 7; it is kept in the
    /// engine's `tests/hostile/` and run by its `tests/revisions.rs`).
    /// A failure here is a regression.
    const KNOWN_OPEN: &[(Kind, &[u64])] = &[];

    /// Seeds run of each kind: plastic piles of up to 40 discs cost about
    /// a second of CPU each (the `hostile` binary runs many more).
    fn seeds(kind: Kind) -> u64 {
        if kind == Kind::PlasticLines {
            10
        } else {
            40
        }
    }

    fn known_open(kind: Kind, seed: u64) -> bool {
        KNOWN_OPEN
            .iter()
            .any(|(k, seeds)| *k == kind && seeds.contains(&seed))
    }

    #[test]
    fn hostile_scenes_of_every_kind_pass_their_checks() {
        let mut failed = Vec::new();
        let mut run = 0;
        for kind in Kind::ALL {
            for seed in 0..seeds(kind) {
                let h = Hostile::generate(kind, seed);
                let mut report = run_caught(&h, Revision::LATEST, MAX_EVENTS);
                run += 1;
                // Speed is measured by the `hostile` binary, not here.
                report.failures.retain(|f| *f != Failure::Slow);
                if !report.failures.is_empty() && !known_open(kind, seed) {
                    failed.push(format!("{} seed {seed}: {report}", kind.name()));
                }
            }
        }
        assert_eq!(run, 15 * 40 + 10);
        assert!(failed.is_empty(), "{}", failed.join("\n"));
    }
}
