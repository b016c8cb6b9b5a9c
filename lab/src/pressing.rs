//! The error of the engine's approximated oblique pressing contact (see
//! `engine::push::pressing_kick`), measured against an independent
//! integration of the constrained motion.
//!
//! Two touching discs slide with Coulomb friction, the rear one braking
//! less, their line of centres at an angle to their motion. The reference
//! integrates Newton's equations with the contact force that keeps them
//! exactly touching while it pushes (`N` from the second derivative of the
//! gap; a contact that would pull lets go), by classical Runge–Kutta at a
//! step of a microsecond, projecting the pair back onto contact after each
//! step; a disc whose speed would cross zero stops, and stays stopped while
//! the push on it is below its static friction. [`compare`] runs both to
//! rest and gives the distance between where each left each disc, relative
//! to how far the pair slid.

use engine::{BodyId, BodySpec, Limits, Revision, Scene, World, WorldConfig};
use glam::DVec2;

/// One pressed pair: disc 0 behind, disc 1 ahead at `angle` off their
/// common velocity `speed` along x.
#[derive(Clone, Copy, Debug)]
pub struct Pair {
    pub radius: f64,
    pub mass: [f64; 2],
    pub mu: [f64; 2],
    pub angle: f64,
    pub speed: f64,
}

const G: f64 = 9.81;

impl Pair {
    fn start(&self) -> [DVec2; 2] {
        let d = DVec2::new(self.angle.cos(), self.angle.sin()) * 2.0 * self.radius;
        [DVec2::ZERO, d]
    }

    fn scene(&self) -> Scene {
        let p = self.start();
        let v = DVec2::new(self.speed, 0.0);
        let body = |k: usize| {
            BodySpec::new(k as u64 + 1, p[k], self.radius, self.mass[k], self.mu[k])
                .with_velocity(v)
                .with_restitution(0.9)
        };
        Scene {
            g: G,
            t: 0.0,
            bodies: vec![body(0), body(1)],
            points: Vec::new(),
            lines: Vec::new(),
        }
    }

    /// Where the engine (`revision`) leaves both discs, and its count of
    /// approximated hits.
    pub fn engine(&self, revision: Revision) -> ([DVec2; 2], u64) {
        let config = WorldConfig {
            revision,
            ..WorldConfig::default()
        };
        let Ok(mut world) = World::new(&self.scene(), config) else {
            return ([DVec2::NAN; 2], 0);
        };
        let end = world.run(&Limits::default(), &mut ());
        let at = |id| {
            world
                .body(BodyId(id))
                .map_or(DVec2::NAN, |b| b.trajectory.position(end.t))
        };
        ([at(1), at(2)], world.stats().pressed)
    }

    /// Where the reference integration leaves both discs.
    pub fn reference(&self, dt: f64) -> [DVec2; 2] {
        let s = 2.0 * self.radius;
        let inv = [1.0 / self.mass[0], 1.0 / self.mass[1]];
        let alpha = [self.mu[0] * G, self.mu[1] * G];
        let mut p = self.start();
        let mut v = [DVec2::new(self.speed, 0.0); 2];
        // Accelerations of the state (p, v), with the contact force.
        let accel = |p: [DVec2; 2], v: [DVec2; 2]| -> [DVec2; 2] {
            let friction = |k: usize| -v[k] / v[k].length().max(STICK) * alpha[k];
            let mut a = [friction(0), friction(1)];
            let d = p[0] - p[1];
            let n = d / d.length();
            let dv = v[0] - v[1];
            if d.length() <= s * (1.0 + 1e-9) {
                // g'' = (a0 - a1).n + |dv_t|^2 / s = 0 with a0 += N n / m0
                // and a1 -= N n / m1; a contact that would pull lets go.
                let vt = dv - n * dv.dot(n);
                let free = (a[0] - a[1]).dot(n) + vt.length_squared() / s;
                if free < 0.0 {
                    let big_n = -free / (inv[0] + inv[1]);
                    a[0] += n * (big_n * inv[0]);
                    a[1] -= n * (big_n * inv[1]);
                }
            }
            a
        };
        let mut t = 0.0;
        while v[0].length().max(v[1].length()) > 1e-9 && t < 100.0 {
            // Classical RK4 on (p, v).
            let step = |p: [DVec2; 2], dp: [DVec2; 2], h: f64| [p[0] + dp[0] * h, p[1] + dp[1] * h];
            let k1v = accel(p, v);
            let (p2, v2) = (step(p, v, dt / 2.0), step(v, k1v, dt / 2.0));
            let k2v = accel(p2, v2);
            let (p3, v3) = (step(p, v2, dt / 2.0), step(v, k2v, dt / 2.0));
            let k3v = accel(p3, v3);
            let (p4, v4) = (step(p, v3, dt), step(v, k3v, dt));
            let k4v = accel(p4, v4);
            for k in 0..2 {
                p[k] += (v[k] + (v2[k] + v3[k]) * 2.0 + v4[k]) * (dt / 6.0);
                v[k] += (k1v[k] + (k2v[k] + k3v[k]) * 2.0 + k4v[k]) * (dt / 6.0);
            }
            // Back onto contact where they overlap or approach (momentum kept).
            let d = p[0] - p[1];
            let dist = d.length();
            if dist < s * (1.0 + 1e-6) {
                let n = d / dist;
                let w = inv[0] + inv[1];
                let gap = s - dist;
                if gap > 0.0 {
                    p[0] += n * (gap * inv[0] / w);
                    p[1] -= n * (gap * inv[1] / w);
                }
                let approach = (v[0] - v[1]).dot(n);
                if approach < 0.0 {
                    v[0] -= n * (approach * inv[0] / w);
                    v[1] += n * (approach * inv[1] / w);
                }
            }
            t += dt;
        }
        p
    }
}

/// Speed (m/s) under which the reference's friction is proportional to the
/// speed instead of constant (so that a disc stops smoothly, not by a jump
/// the integrator cannot resolve): a disc slides at most `STICK^2 / alpha`,
/// about 1e-11 m, further than with Coulomb friction.
pub const STICK: f64 = 1e-5;

/// How one pair came out.
#[derive(Clone, Copy, Debug)]
pub struct Comparison {
    /// Largest distance between the engine's and the reference's final
    /// position of a disc, over the distance the rear disc slid.
    pub error: f64,
    /// The same for the reference at twice the step (its own error).
    pub reference_error: f64,
    /// Approximated hits in the engine's run.
    pub pressed: u64,
    /// How far the rear disc slid (m).
    pub slid: f64,
}

/// The reference's time step (s): its stops and contact changes are first
/// order in it, so its own error is measured at twice the step.
pub const FINE: f64 = 1e-6;

/// Runs `pair` in the engine (`revision`) and in the reference.
pub fn compare(pair: &Pair, revision: Revision) -> Comparison {
    let (engine, pressed) = pair.engine(revision);
    let fine = pair.reference(FINE);
    let coarse = pair.reference(2.0 * FINE);
    let slid = (fine[0] - pair.start()[0]).length().max(1e-300);
    let worst = |a: [DVec2; 2], b: [DVec2; 2]| (a[0] - b[0]).length().max((a[1] - b[1]).length());
    Comparison {
        error: worst(engine, fine) / slid,
        reference_error: worst(coarse, fine) / slid,
        pressed,
        slid,
    }
}

/// A spread of pressed pairs: angles from 5 to 60 degrees, friction
/// ratios from 1.5 to 10, masses equal and unequal.
pub fn pairs() -> Vec<Pair> {
    let mut out = Vec::new();
    for &angle in &[5.0f64, 15.0, 30.0, 45.0, 60.0] {
        for &(mu0, mu1) in &[(0.2, 0.3), (0.1, 0.5), (0.05, 0.5)] {
            for &mass in &[[0.005, 0.005], [0.01, 0.003]] {
                out.push(Pair {
                    radius: 0.016,
                    mass,
                    mu: [mu0, mu1],
                    angle: angle.to_radians(),
                    speed: 1.0,
                });
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Prints the table of `pairs` under `revision` and returns the worst
    /// error.
    fn table(pairs: impl Iterator<Item = Pair>, revision: Revision) -> f64 {
        let mut worst: f64 = 0.0;
        println!("{revision:?}");
        println!(
            "| angle | mu | masses | slid (m) | pressed hits | error / slide | reference's own |"
        );
        println!("|---|---|---|---|---|---|---|");
        for pair in pairs {
            let c = compare(&pair, revision);
            println!(
                "| {:.0} | {:?} | {:?} | {:.4} | {} | {:.2e} | {:.1e} |",
                pair.angle.to_degrees(),
                pair.mu,
                pair.mass,
                c.slid,
                c.pressed,
                c.error,
                c.reference_error
            );
            assert!(c.reference_error < 1e-7, "{pair:?}: {c:?}");
            worst = worst.max(c.error);
        }
        println!("worst {worst:.2e}");
        worst
    }

    /// Each revision's bound on the error, of the distance slid: revision
    /// 5 keeps pressed pairs within 1e-6 of their contact distance,
    /// revision 6 within 1e-4: ten times fewer hits, for about ten times
    /// the error. The latest revision, the one new worlds get, keeps
    /// revision 6's gap and so its bound (docs/model.md states it), and so
    /// does revision 12, whose kick over a cluster is held to the pair's
    /// own (a pair alone is kicked as before).
    const BOUNDS: [(Revision, f64); 4] = [
        (Revision::R5, 2e-4),
        (Revision::R6, 1e-3),
        (Revision::LATEST, 1e-3),
        (Revision::R12, 1e-3),
    ];

    /// Every `step`-th pair under each revision of [`BOUNDS`], within its
    /// bound.
    fn within_bounds(step: usize) {
        for (revision, bound) in BOUNDS {
            let worst = table(pairs().into_iter().step_by(step), revision);
            assert!(worst < bound, "{revision:?}: {worst:e}");
        }
    }

    /// Every third pair (all thirty: the ignored test below, as
    /// `cargo test -p lab --release pressing -- --ignored --nocapture`).
    #[test]
    fn the_approximated_pressing_contact_stays_within_its_bound_of_the_slide() {
        within_bounds(3);
    }

    #[test]
    #[ignore = "sixty integrations: about a minute"]
    fn every_pressed_pair_stays_within_its_bound_of_the_slide() {
        within_bounds(1);
    }
}
