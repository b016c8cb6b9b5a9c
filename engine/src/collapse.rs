//! The limit of an inelastic collapse: discs touching each other and
//! obstacles, hitting again and again at one instant, each hit slower than
//! the last.
//!
//! Such a sequence converges (every hit takes energy out of the approach
//! it stops) but never ends: a disc sliding into a wedge of two plastic
//! walls bounces from one to the other, its speed shrinking by the cosine
//! of the angle each time; a striker pressing a cluster into a wall does
//! the same over many contacts. Its limit is the plastic impact of all the
//! touching contacts at once: the velocities nearest to the ones before
//! (in kinetic energy, so momentum and the centre of mass are kept where
//! no obstacle takes part) at which no contact approaches. [`plastic`]
//! computes it by projected Gauss–Seidel on the contact impulses (each
//! impulse a push, never a pull), which is the same sequence of hits run
//! in memory until it has converged to rounding.

use glam::DVec2;

/// A touching contact: disc `a` against disc `b`, or against an obstacle
/// (`b` is `None`); `n` is the unit normal pointing from `b` (or the
/// obstacle) to `a`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    pub a: usize,
    pub b: Option<usize>,
    pub n: DVec2,
}

/// Speed, as a fraction of the fastest before the collapse, under which a
/// disc after it is at rest.
pub const REST: f64 = 1e-12;

/// A speed (m/s) under which a disc after a collapse is at rest whatever
/// it began with: in the 1e150 s a run may reach, it would not move 1e-50 m.
/// (A collapse that went on long enough has driven speeds this far down.)
pub const NEGLIGIBLE: f64 = 1e-200;

/// Sweeps over the contacts at most (each sweep is one hit per contact).
pub const MAX_SWEEPS: usize = 10_000;

/// The velocities `vel` (of discs with inverse masses `inv_mass`) after a
/// plastic impact of every contact at once: no contact approaches faster
/// than `1e-15` of the fastest speed. `None` if the impulses have not
/// converged within [`MAX_SWEEPS`] (the caller keeps the velocities).
pub fn plastic(vel: &[DVec2], inv_mass: &[f64], contacts: &[Contact]) -> Option<Vec<DVec2>> {
    let mut v = vel.to_vec();
    // The largest coordinate, not the length: squares of tiny speeds underflow.
    let scale = vel
        .iter()
        .map(|u| u.abs().max_element())
        .fold(0.0, f64::max);
    if contacts.is_empty() || scale == 0.0 || !scale.is_finite() {
        return Some(v);
    }
    if scale <= NEGLIGIBLE {
        return Some(vec![DVec2::ZERO; vel.len()]);
    }
    let tolerance = 1e-15 * scale;
    // Accumulated impulse of each contact and its effective inverse mass.
    let mut impulse = vec![0.0f64; contacts.len()];
    let weight: Vec<f64> = contacts
        .iter()
        .map(|c| inv_mass[c.a] + c.b.map_or(0.0, |b| inv_mass[b]))
        .collect();
    for _ in 0..MAX_SWEEPS {
        for (k, c) in contacts.iter().enumerate() {
            let rel = v[c.a] - c.b.map_or(DVec2::ZERO, |b| v[b]);
            let approach = -rel.dot(c.n);
            let next = (impulse[k] + approach / weight[k]).max(0.0);
            let delta = next - impulse[k];
            if delta == 0.0 {
                continue;
            }
            impulse[k] = next;
            v[c.a] += c.n * (delta * inv_mass[c.a]);
            if let Some(b) = c.b {
                v[b] -= c.n * (delta * inv_mass[b]);
            }
        }
        // Converged: no contact approaches (impulses are never negative, so
        // none pulls).
        let approaching = contacts.iter().any(|c| {
            let rel = v[c.a] - c.b.map_or(DVec2::ZERO, |b| v[b]);
            rel.dot(c.n) < -tolerance
        });
        if !approaching {
            // What the collapse left moving slower than rounding of the
            // speeds it began with has stopped (a disc in a plastic wedge).
            for u in &mut v {
                if u.abs().max_element() <= (REST * scale).max(NEGLIGIBLE) {
                    *u = DVec2::ZERO;
                }
            }
            return Some(v);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_disc_driven_into_a_plastic_wedge_stops_dead() {
        // Walls with normals at +-60 degrees from the direction of travel.
        let (c, s) = (0.5f64, 0.75f64.sqrt());
        let contacts = [
            Contact {
                a: 0,
                b: None,
                n: DVec2::new(-c, s),
            },
            Contact {
                a: 0,
                b: None,
                n: DVec2::new(-c, -s),
            },
        ];
        let v = plastic(&[DVec2::new(1.0, 0.3)], &[1.0], &contacts).unwrap();
        assert!(v[0].length() < 1e-14, "{v:?}");
    }

    #[test]
    fn a_disc_sliding_out_of_a_wedge_is_left_alone() {
        let contacts = [Contact {
            a: 0,
            b: None,
            n: DVec2::Y,
        }];
        let v = plastic(&[DVec2::new(1.0, 0.5)], &[1.0], &contacts).unwrap();
        assert_eq!(v[0], DVec2::new(1.0, 0.5));
    }

    #[test]
    fn a_plastic_impact_between_discs_keeps_momentum_and_stops_the_approach() {
        // Disc 0 runs into disc 1, which touches disc 2 obliquely.
        let n01 = DVec2::new(-1.0, 0.0);
        let n12 = DVec2::new(-0.6, -0.8);
        let contacts = [
            Contact {
                a: 0,
                b: Some(1),
                n: n01,
            },
            Contact {
                a: 1,
                b: Some(2),
                n: n12,
            },
        ];
        let (m, inv) = ([1.0, 2.0, 3.0], [1.0, 0.5, 1.0 / 3.0]);
        let vel = [DVec2::new(2.0, 0.0), DVec2::ZERO, DVec2::ZERO];
        let v = plastic(&vel, &inv, &contacts).unwrap();
        let p: DVec2 = (0..3).map(|k| v[k] * m[k]).sum();
        assert!((p - DVec2::new(2.0, 0.0)).length() < 1e-14, "{p}");
        for c in &contacts {
            let rel = v[c.a] - v[c.b.unwrap()];
            assert!(rel.dot(c.n) >= -1e-14, "{v:?}");
        }
        let energy = |v: &[DVec2]| (0..3).map(|k| m[k] * v[k].length_squared()).sum::<f64>();
        assert!(energy(&v) < energy(&vel));
    }
}
