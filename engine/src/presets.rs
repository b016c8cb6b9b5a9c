//! Ready-made scenes: the classics the tests, benchmarks, the `lab` charts
//! and the sandbox's presets all use, built in one place.
//!
//! Everything here is deterministic: random layouts come from a fixed-seed
//! xorshift generator, and no trigonometry is used.

use crate::obstacle::{Line, LineKind};
use crate::rng::{Rng, GOLDEN};
use crate::scene::{BodySpec, Scene};
use glam::DVec2;

/// The first `n` digits of pi as a number (`n <= 15`): Galperin's count.
pub fn pi_digits(n: u32) -> u64 {
    const PI: &str = "314159265358979";
    PI.get(..n.min(15) as usize)
        .and_then(|s| s.parse().ok())
        .unwrap_or(0)
}

/// Galperin's billiard for `n` digits of pi: a wall (an infinite line) at
/// x = 0, a disc of mass 1 at rest at x = 1, and a disc of mass `100^(n-1)`
/// at x = 3 moving towards them at speed 1, all frictionless. The number of
/// collisions is [`pi_digits`]`(n)`.
pub fn galperin(n: u32) -> Scene {
    let big = (1..n).fold(1.0, |m, _| m * 100.0);
    Scene {
        bodies: vec![
            BodySpec::new(1, DVec2::new(1.0, 0.0), 0.1, 1.0, 0.0),
            BodySpec::new(2, DVec2::new(3.0, 0.0), 0.5, big, 0.0)
                .with_velocity(DVec2::new(-1.0, 0.0)),
        ],
        lines: vec![Line::new(
            DVec2::new(0.0, -1.0),
            DVec2::new(0.0, 1.0),
            LineKind::Line,
        )],
        ..Scene::default()
    }
}

/// The four segments of the square `[0, side]^2`, counter-clockwise.
pub fn square_walls(side: f64) -> Vec<Line> {
    let c = [
        DVec2::new(0.0, 0.0),
        DVec2::new(side, 0.0),
        DVec2::new(side, side),
        DVec2::new(0.0, side),
    ];
    (0..4)
        .map(|k| Line::new(c[k], c[(k + 1) % 4], LineKind::Segment))
        .collect()
}

/// `n` discs of radius 1 cm and mass 10 g, friction `mu`, restitution 1, in
/// a closed square box at 10% area fraction: a jittered lattice with
/// velocities uniform in `[-1, 1)^2` m/s, from `seed`.
pub fn box_of_discs(n: usize, mu: f64, seed: u64) -> Scene {
    let r = 0.01;
    let side = (n as f64 * std::f64::consts::PI * r * r / 0.10).sqrt();
    let per_row = (n as f64).sqrt().ceil() as usize;
    let spacing = side / per_row as f64;
    let jitter = 0.9 * (0.5 * spacing - r);
    let mut rng = Rng::xorshift64_star(seed.wrapping_mul(GOLDEN) | 1);
    let bodies = (0..n)
        .map(|k| {
            let (i, j) = (k % per_row, k / per_row);
            let pos = DVec2::new(
                (i as f64 + 0.5) * spacing + jitter * rng.symmetric(),
                (j as f64 + 0.5) * spacing + jitter * rng.symmetric(),
            );
            let vel = DVec2::new(rng.symmetric(), rng.symmetric());
            BodySpec::new(k as u64 + 1, pos, r, 0.01, mu).with_velocity(vel)
        })
        .collect();
    Scene {
        bodies,
        lines: square_walls(side),
        ..Scene::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pi_digits_are_the_galperin_counts() {
        assert_eq!(pi_digits(1), 3);
        assert_eq!(pi_digits(7), 3141592);
        assert_eq!(pi_digits(0), 0);
    }

    #[test]
    fn presets_are_valid_scenes() {
        galperin(9).validate().unwrap();
        let b = box_of_discs(1000, 0.1, 7);
        b.validate().unwrap();
        assert_eq!(b.bodies.len(), 1000);
        assert_eq!(box_of_discs(50, 0.0, 3), box_of_discs(50, 0.0, 3));
    }
}
