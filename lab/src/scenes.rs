//! The test situations every method is run on: a [`Case`] is an engine
//! [`Scene`] plus how long to compute it, an event cap, the length scale
//! errors are measured in, and (for Chapaev boards) the rule that a disc
//! whose centre leaves the board is taken off. Builders here make the break
//! shots, Galperin's billiard, boxes of discs and the hard cases of the
//! failure table, all from the shipped examples or from a seeded generator.

use crate::error::LabError;
use engine::rng::{Rng, GOLDEN};
use engine::{BodyId, BodySpec, Line, LineKind, Scene};
use glam::DVec2;

/// The shipped break shot (`engine/examples/break.json`).
pub const BREAK_JSON: &str = include_str!("../../engine/examples/break.json");
/// The shipped box of 100 discs (`engine/examples/box.json`).
pub const BOX_JSON: &str = include_str!("../../engine/examples/box.json");

/// An axis-aligned board: a disc whose centre leaves it is removed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Board {
    pub lo: DVec2,
    pub hi: DVec2,
}

impl Board {
    /// The bounding box of the scene's sensor lines, if it has any.
    pub fn of(scene: &Scene) -> Option<Board> {
        let mut it = scene.lines.iter().filter(|l| l.sensor).peekable();
        it.peek()?;
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for l in it {
            lo = lo.min(l.a).min(l.b);
            hi = hi.max(l.a).max(l.b);
        }
        Some(Board { lo, hi })
    }

    /// Whether `p` is inside (or on) the board.
    pub fn contains(&self, p: DVec2) -> bool {
        p.x >= self.lo.x && p.x <= self.hi.x && p.y >= self.lo.y && p.y <= self.hi.y
    }
}

/// One situation to compute.
#[derive(Clone, Debug)]
pub struct Case {
    pub name: String,
    pub scene: Scene,
    /// Compute to this time; the final state is compared here.
    pub until: f64,
    /// Hard cap on events (and, for the steppers, on steps).
    pub max_events: u64,
    /// Length that position errors are divided by.
    pub scale: f64,
    /// A known collision count (Galperin), when there is one.
    pub expected_collisions: Option<u64>,
}

impl Case {
    /// The fall-off board of the scene, if any.
    pub fn board(&self) -> Option<Board> {
        Board::of(&self.scene)
    }

    /// The smallest disc radius.
    pub fn min_radius(&self) -> f64 {
        self.scene
            .bodies
            .iter()
            .map(|b| b.radius)
            .fold(f64::INFINITY, f64::min)
    }
}

/// The standard break shot.
pub fn break_shot() -> Result<Case, LabError> {
    let scene = Scene::from_json(BREAK_JSON)?;
    Ok(Case {
        name: "break".into(),
        scene,
        until: 1.5,
        max_events: 100_000,
        scale: 0.32,
        expected_collisions: None,
    })
}

/// The hard break: striker (body 4) aimed at the gap between bodies 12 and
/// 13 of the far row at 5 m/s (as in the engine's benchmarks).
pub fn hard_break() -> Result<Case, LabError> {
    let mut case = break_shot()?;
    let striker = case
        .scene
        .bodies
        .iter_mut()
        .find(|b| b.id == BodyId(4))
        .ok_or_else(|| LabError::Invalid("break.json has no body 4".into()))?;
    striker.vel = (DVec2::new(0.16, 0.30) - striker.pos).normalize() * 5.0;
    case.name = "break-hard".into();
    case.until = 2.0;
    Ok(case)
}

/// The first `n` digits of pi as a number: Galperin's collision count.
pub fn pi_digits(n: u32) -> u64 {
    engine::presets::pi_digits(n)
}

/// Galperin's billiard for `n` digits (as `engine/examples/galperin.rs`):
/// a wall at x = 0, mass 1 at x = 1, mass `100^(n-1)` at x = 3 moving at -1.
pub fn galperin(n: u32) -> Case {
    let scene = engine::presets::galperin(n);
    Case {
        name: format!("galperin-{n}"),
        scene,
        until: 12.0,
        max_events: 2 * pi_digits(n) + 1_000,
        scale: 1.0,
        expected_collisions: Some(pi_digits(n)),
    }
}

/// The shipped box of 100 discs (friction, restitution 0.95), compared at
/// 0.3 s (about 150 collisions, before chaos amplifies rounding to O(1)).
pub fn box100() -> Result<Case, LabError> {
    let scene = Scene::from_json(BOX_JSON)?;
    Ok(Case {
        name: "box-100".into(),
        scene,
        until: 0.3,
        max_events: 1_000_000,
        scale: 1.0,
        expected_collisions: None,
    })
}

/// `n` discs of radius 0.01 at about 10% area fraction in a closed square
/// box, on a jittered lattice, unit speeds in random directions.
pub fn random_box(n: usize, mu: f64, seed: u64) -> Scene {
    let r = 0.01;
    let side = (n as f64 * std::f64::consts::PI * r * r / 0.1).sqrt();
    let k = (n as f64).sqrt().ceil() as usize;
    let pitch = side / k as f64;
    let mut rng = Rng::xorshift64(seed.wrapping_mul(GOLDEN) | 1);
    let jitter = (pitch - 2.0 * r) * 0.4;
    let bodies = (0..n)
        .map(|i| {
            let c = DVec2::new((i % k) as f64 + 0.5, (i / k) as f64 + 0.5) * pitch;
            let j = DVec2::new(rng.unit() - 0.5, rng.unit() - 0.5) * jitter;
            let a = rng.unit() * std::f64::consts::TAU;
            BodySpec::new(i as u64 + 1, c + j, r, 0.01, mu)
                .with_velocity(DVec2::new(a.cos(), a.sin()))
        })
        .collect();
    Scene {
        bodies,
        lines: engine::presets::square_walls(side),
        ..Scene::default()
    }
}

fn small_case(name: &str, scene: Scene, until: f64, scale: f64) -> Case {
    Case {
        name: name.into(),
        scene,
        until,
        max_events: 100_000,
        scale,
        expected_collisions: None,
    }
}

const R: f64 = 0.016;
const M: f64 = 0.01;
const MU: f64 = 0.3;

/// Two sliding discs on antiparallel paths whose centres pass at
/// `S (1 - 2^-30)`: a near-double root of the contact quartic (both move
/// with friction, so the root solver decides).
pub fn grazing() -> Case {
    let h = 2.0 * R * (1.0 - 2f64.powi(-30));
    let scene = Scene {
        bodies: vec![
            BodySpec::new(1, DVec2::new(-0.2, 0.0), R, M, MU).with_velocity(DVec2::new(2.0, 0.0)),
            BodySpec::new(2, DVec2::new(0.2, h), R, M, MU).with_velocity(DVec2::new(-2.0, 0.0)),
        ],
        ..Scene::default()
    };
    small_case("grazing contact", scene, 1.0, 0.4)
}

/// A striker meets two touching discs at the same instant.
pub fn simultaneous() -> Case {
    let scene = Scene {
        bodies: vec![
            BodySpec::new(1, DVec2::new(0.0, 0.0), R, M, MU).with_velocity(DVec2::new(2.0, 0.0)),
            BodySpec::new(2, DVec2::new(0.2, R), R, M, MU),
            BodySpec::new(3, DVec2::new(0.2, -R), R, M, MU),
        ],
        ..Scene::default()
    };
    small_case("simultaneous contacts", scene, 1.0, 0.4)
}

/// Newton's cradle: a striker hits a row of four touching discs.
pub fn cradle() -> Case {
    let mut bodies =
        vec![BodySpec::new(1, DVec2::ZERO, R, M, MU).with_velocity(DVec2::new(1.5, 0.0))];
    for k in 0..4 {
        bodies.push(BodySpec::new(
            k + 2,
            DVec2::new(0.2 + 2.0 * R * k as f64, 0.0),
            R,
            M,
            MU,
        ));
    }
    let scene = Scene {
        bodies,
        ..Scene::default()
    };
    small_case("Newton's cradle", scene, 1.0, 0.4)
}

/// Two discs at rest, touching each other and a wall, struck towards it.
pub fn resting_contact() -> Case {
    let scene = Scene {
        bodies: vec![
            BodySpec::new(1, DVec2::new(R, 0.0), R, M, MU),
            BodySpec::new(2, DVec2::new(3.0 * R, 0.0), R, M, MU),
            BodySpec::new(3, DVec2::new(0.2, 0.0), R, M, MU).with_velocity(DVec2::new(-2.0, 0.0)),
        ],
        lines: vec![Line::new(
            DVec2::new(0.0, -1.0),
            DVec2::new(0.0, 1.0),
            LineKind::Segment,
        )],
        ..Scene::default()
    };
    small_case("resting contact", scene, 1.5, 0.4)
}

/// A 0.1 mm disc at 100 m/s against a segment of zero thickness.
pub fn fast_tiny() -> Case {
    let scene = Scene {
        bodies: vec![BodySpec::new(1, DVec2::new(0.0123, 0.0), 1e-4, 1e-4, MU)
            .with_velocity(DVec2::new(100.0, 0.0))],
        lines: vec![Line::new(
            DVec2::new(0.5, -0.1),
            DVec2::new(0.5, 0.1),
            LineKind::Segment,
        )],
        ..Scene::default()
    };
    small_case("fast tiny disc vs thin segment", scene, 0.03, 1.0)
}

/// The hard break moved to coordinates around `(offset, offset)`.
pub fn translated(offset: f64) -> Result<Case, LabError> {
    let mut c = hard_break()?;
    let d = DVec2::splat(offset);
    for b in &mut c.scene.bodies {
        b.pos += d;
    }
    for l in &mut c.scene.lines {
        l.a += d;
        l.b += d;
    }
    c.name = format!("huge coordinates (+{offset:e} m)");
    Ok(c)
}

/// The hard break with every length scaled by `k` (g too, so times stay).
pub fn scaled(k: f64) -> Result<Case, LabError> {
    let mut c = hard_break()?;
    for b in &mut c.scene.bodies {
        b.pos *= k;
        b.vel *= k;
        b.radius *= k;
    }
    for l in &mut c.scene.lines {
        l.a *= k;
        l.b *= k;
    }
    c.scene.g *= k;
    c.scale *= k;
    c.name = format!("tiny coordinates (x{k:e})");
    Ok(c)
}

/// The hard break with speeds scaled by `k` and g by `k^2` (the same paths,
/// run `1/k` times faster).
pub fn fast_motion(k: f64) -> Result<Case, LabError> {
    let mut c = hard_break()?;
    for b in &mut c.scene.bodies {
        b.vel *= k;
    }
    c.scene.g *= k * k;
    c.until /= k;
    c.name = if k > 1.0 {
        format!("huge speeds (x{k:e})")
    } else {
        format!("tiny speeds (x{k:e})")
    };
    Ok(c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_builder_makes_a_valid_scene() {
        let mut cases = vec![
            break_shot().unwrap(),
            hard_break().unwrap(),
            galperin(3),
            box100().unwrap(),
            grazing(),
            simultaneous(),
            cradle(),
            resting_contact(),
            fast_tiny(),
            translated(1e7).unwrap(),
            scaled(1e-6).unwrap(),
            fast_motion(1e3).unwrap(),
        ];
        cases.push(Case {
            scene: random_box(500, 0.1, 7),
            ..galperin(3)
        });
        for c in cases {
            c.scene
                .validate()
                .unwrap_or_else(|e| panic!("{}: {e}", c.name));
        }
    }

    #[test]
    fn break_board_is_the_eight_by_eight_square() {
        let b = break_shot().unwrap().board().unwrap();
        assert_eq!((b.lo, b.hi), (DVec2::ZERO, DVec2::splat(0.32)));
    }

    #[test]
    fn pi_digits_are_galperins_counts() {
        assert_eq!(pi_digits(3), 314);
        assert_eq!(pi_digits(8), 31415926);
    }
}
