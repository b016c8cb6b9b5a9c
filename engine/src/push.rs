//! Pushing contacts: two touching discs sliding together along the line of
//! their centres, the rear one braking less than the front one, press on
//! each other. No impulse parts them (they do not approach), and without a
//! contact force the rear one would slide into the front one.
//!
//! Pressed together they move as one body: the same velocity, braked by the
//! sum of their friction forces over the sum of their masses,
//! `alpha = (m_i alpha_i + m_j alpha_j) / (m_i + m_j)`. Each disc keeps a
//! closed-form Coulomb trajectory with that braking, and the two stop at
//! the same moment. This is exact when the motion is along the line of
//! centres, where the contact force (normal to the contact) can do all the
//! pushing. A pair pressing obliquely would slide along each other and turn,
//! which has no closed form and is not modelled.
//!
//! The pair stays together until an event on one of them (another hit, a
//! stop) gives each its own trajectory and friction again; if they still
//! push, they are joined again at once.

use crate::impulse;
use crate::trajectory::Trajectory;
use glam::DVec2;

/// Relative tolerance for "the same velocity" and "along the line of
/// centres": rounding noise, far below any physical difference.
const SAME: f64 = 1e-9;

/// Whether the discs on `ti` and `tj`, touching at `now` with centres `pi`
/// and `pj`, push on each other: both move, with the same velocity (to
/// rounding) along the line of their centres, and their braking presses
/// them together (the rear one brakes less).
pub fn pushing(ti: &Trajectory, pi: DVec2, tj: &Trajectory, pj: DVec2, now: f64) -> bool {
    if !ti.is_moving_at(now) || !tj.is_moving_at(now) {
        return false;
    }
    let (vi, vj) = (ti.velocity(now), tj.velocity(now));
    let speed = vi.length().max(vj.length());
    let d = pi - pj;
    let dist = d.length();
    if !(dist > 0.0 && speed > 0.0) {
        return false;
    }
    if (vi - vj).length() > SAME * speed || vi.perp_dot(d).abs() > SAME * speed * dist {
        return false;
    }
    // d'' . d < 0: the centres accelerate towards each other.
    let da = ti.acceleration(now) - tj.acceleration(now);
    da.dot(d) < -SAME * (ti.alpha() + tj.alpha()) * dist
}

/// The common velocity (mass-weighted, so momentum is kept) and braking of
/// two discs pushed together, from their velocities `v`, masses `m` and
/// own brakings `alpha` (`mu g`).
pub fn together(v: [DVec2; 2], m: [f64; 2], alpha: [f64; 2]) -> (DVec2, f64) {
    let (w_i, w_j) = impulse::weights(m[0], m[1]);
    (v[0] * w_i + v[1] * w_j, alpha[0] * w_i + alpha[1] * w_j)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sliding(x: f64, vx: f64, alpha: f64) -> Trajectory {
        Trajectory::new(0.0, DVec2::new(x, 0.0), DVec2::new(vx, 0.0), alpha)
    }

    #[test]
    fn a_rear_disc_braking_less_pushes_the_front_one() {
        let (rear, front) = (sliding(0.0, 1.0, 0.981), sliding(1.0, 1.0, 2.943));
        let (pr, pf) = (DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0));
        assert!(pushing(&rear, pr, &front, pf, 0.0));
        assert!(pushing(&front, pf, &rear, pr, 0.0));
        // The front one braking less runs away instead.
        let (rear, front) = (sliding(0.0, 1.0, 2.943), sliding(1.0, 1.0, 0.981));
        assert!(!pushing(&rear, pr, &front, pf, 0.0));
    }

    #[test]
    fn different_or_oblique_velocities_do_not_push() {
        let rear = sliding(0.0, 1.0, 0.1);
        let faster = sliding(1.0, 1.1, 0.3);
        let (pr, pf) = (DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0));
        assert!(!pushing(&rear, pr, &faster, pf, 0.0));
        let v = DVec2::new(0.6, 0.8);
        let a = Trajectory::new(0.0, pr, v, 0.1);
        let b = Trajectory::new(0.0, pf, v, 0.3);
        assert!(!pushing(&a, pr, &b, pf, 0.0));
    }

    #[test]
    fn a_pushed_pair_keeps_its_momentum_and_brakes_by_the_mean_friction() {
        let (v, alpha) = together(
            [DVec2::new(1.0, 0.0), DVec2::new(1.0, 0.0)],
            [1.0, 3.0],
            [0.2, 0.6],
        );
        assert_eq!(v, DVec2::new(1.0, 0.0));
        assert!((alpha - (0.2 + 3.0 * 0.6) / 4.0).abs() < 1e-15);
    }
}
