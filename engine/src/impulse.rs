//! Impulses: how velocities change at a contact.
//!
//! At a contact with unit normal `n` (pointing from the other object to body
//! `i`) and relative normal velocity `w = (v_i - v_j) . n < 0`, the impulse is
//! `J = -(1 + e) w m*` with the reduced mass `m* = m_i m_j / (m_i + m_j)`,
//! `e` the smaller restitution of the two. With `e = 1` this is the thesis's
//! elastic formula (25); an obstacle is an infinite mass, formula (28).
//! The reduced mass is formed as `m_s - m_s (m_s / (m_s + m_b))` (`m_s` the
//! smaller mass) so that huge mass ratios (Galperin's billiard, 10^16)
//! neither overflow nor lose the small correction.
//!
//! A velocity that comes out of an impulse with no normal part beyond the
//! rounding of the sum that formed it, and a tangential part no larger than
//! the rounding of the contact normal leaves, is rounding, not motion, and
//! is set to zero: an equal-mass head-on hit stops the striker exactly, instead
//! of leaving it a unit in the last place of speed that meets the other
//! disc again 10^13 s later (one collision too many in Galperin's count).

use glam::DVec2;

/// The reduced mass `m_i m_j / (m_i + m_j)`, free of overflow.
pub(crate) fn reduced_mass(m_i: f64, m_j: f64) -> f64 {
    let (small, big) = if m_i <= m_j { (m_i, m_j) } else { (m_j, m_i) };
    small - small * (small / (small + big))
}

/// Each body's weight in a mass-weighted mean, `(m_i, m_j) / (m_i + m_j)`,
/// from one division and free of overflow: the lighter body's weight is
/// `q = small / (small + big)`, the heavier's `1 - q`.
pub(crate) fn weights(m_i: f64, m_j: f64) -> (f64, f64) {
    let (small, big) = if m_i <= m_j { (m_i, m_j) } else { (m_j, m_i) };
    let q = small / (small + big);
    if m_i <= m_j {
        (q, 1.0 - q)
    } else {
        (1.0 - q, q)
    }
}

/// New velocities of two discs after an impulse along `n` (from `j` to `i`).
/// Returns the velocities unchanged if they are not approaching.
#[inline(always)]
pub(crate) fn body_body(
    v_i: DVec2,
    v_j: DVec2,
    m_i: f64,
    m_j: f64,
    e: f64,
    n: DVec2,
) -> (DVec2, DVec2) {
    let w = (v_i - v_j).dot(n);
    if w >= 0.0 {
        return (v_i, v_j);
    }
    let j = -(1.0 + e) * w * reduced_mass(m_i, m_j);
    let (d_i, d_j) = (n * (j / m_i), n * (j / m_j));
    (
        denoised(v_i + d_i, v_i, d_i, n),
        denoised(v_j - d_j, v_j, d_j, n),
    )
}

/// Relative size, against the terms of the sum that formed it, under which
/// the normal part of a velocity is rounding noise.
const NOISE: f64 = 4.0 * f64::EPSILON;

/// Relative size under which the tangential part of a velocity that has no
/// normal part is noise too: it comes from the contact normal, which is
/// found from rounded positions and is off by up to about 1e-14 rad.
const TANGENT_NOISE: f64 = 1e-12;

/// `sum = a + b` (an impulse `b` along `n` added to `a`), or zero if its
/// normal part is below the rounding of that sum and its tangential part
/// below what the normal's own rounding leaves.
#[inline(always)]
fn denoised(sum: DVec2, a: DVec2, b: DVec2, n: DVec2) -> DVec2 {
    // One cheap test settles almost every impulse: a result above
    // `TANGENT_NOISE` of its terms is motion.
    let big = a.length_squared().max(b.length_squared());
    if sum.length_squared() > TANGENT_NOISE * TANGENT_NOISE * big {
        return sum;
    }
    let scale = big.sqrt();
    if sum.dot(n).abs() <= NOISE * scale && sum.perp_dot(n).abs() <= TANGENT_NOISE * scale {
        DVec2::ZERO
    } else {
        sum
    }
}

/// New velocity of a disc after hitting an immovable object with normal `n`
/// (pointing from the object to the disc).
#[inline]
pub(crate) fn body_static(v: DVec2, e: f64, n: DVec2) -> DVec2 {
    let w = v.dot(n);
    if w >= 0.0 {
        return v;
    }
    let d = n * ((1.0 + e) * w);
    denoised(v - d, v, d, n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn head_on_elastic_hit_of_equal_masses_swaps_velocities() {
        let (a, b) = body_body(
            DVec2::new(2.0, 0.0),
            DVec2::ZERO,
            1.0,
            1.0,
            1.0,
            DVec2::new(-1.0, 0.0),
        );
        assert_eq!(a, DVec2::ZERO);
        assert_eq!(b, DVec2::new(2.0, 0.0));
    }

    #[test]
    fn glancing_elastic_hit_of_equal_masses_separates_at_right_angles() {
        let n = DVec2::new(-1.0, -1.0).normalize();
        let v = DVec2::new(1.0, 0.0);
        let (a, b) = body_body(v, DVec2::ZERO, 0.3, 0.3, 1.0, n);
        assert!(a.dot(b).abs() < 1e-15);
        assert!((a.length_squared() + b.length_squared() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn impulse_conserves_momentum_and_elastic_energy() {
        let n = DVec2::new(0.6, -0.8);
        let (vi, vj, mi, mj) = (DVec2::new(-1.0, 2.0), DVec2::new(0.5, -0.25), 2.0, 7.0);
        let (a, b) = body_body(vi, vj, mi, mj, 1.0, n);
        let p0 = vi * mi + vj * mj;
        let p1 = a * mi + b * mj;
        assert!((p0 - p1).length() < 1e-14);
        let e0 = mi * vi.length_squared() + mj * vj.length_squared();
        let e1 = mi * a.length_squared() + mj * b.length_squared();
        assert!((e0 - e1).abs() < 1e-14);
    }

    #[test]
    fn restitution_scales_the_separation_speed() {
        let n = DVec2::new(-1.0, 0.0);
        let (a, b) = body_body(DVec2::new(2.0, 0.0), DVec2::ZERO, 1.0, 1.0, 0.5, n);
        let w_after = (a - b).dot(n);
        assert!((w_after - 0.5 * 2.0).abs() < 1e-15);
        let v = body_static(DVec2::new(0.0, -3.0), 0.5, DVec2::new(0.0, 1.0));
        assert_eq!(v, DVec2::new(0.0, 1.5));
    }

    #[test]
    fn wall_reflection_mirrors_the_normal_component() {
        let v = body_static(DVec2::new(3.0, -4.0), 1.0, DVec2::new(0.0, 1.0));
        assert_eq!(v, DVec2::new(3.0, 4.0));
    }

    #[test]
    fn an_oblique_equal_mass_head_on_hit_stops_the_striker_exactly() {
        let mut kept = 0;
        for k in 1..2000 {
            let a = k as f64 * 0.001;
            let n = DVec2::new(a.cos(), a.sin());
            let v = -n * (1.0 + k as f64 * 0.37);
            let (vi, vj) = body_body(v, DVec2::ZERO, 0.5, 0.5, 1.0, n);
            kept += (vi != DVec2::ZERO) as u32;
            assert!((vj - v).length() <= 4.0 * f64::EPSILON * v.length());
        }
        assert_eq!(kept, 0);
        // A normal found from rounded positions, 1e-14 rad off the path.
        let n = DVec2::new(-1.0, 1e-14).normalize();
        let (vi, _) = body_body(DVec2::new(2.0, 0.0), DVec2::ZERO, 1.0, 1.0, 1.0, n);
        assert_eq!(vi, DVec2::ZERO);
        // A velocity well above rounding is kept.
        let n = DVec2::new(-1.0, 0.0);
        let (a, _) = body_body(DVec2::new(1.0, 1e-9), DVec2::ZERO, 1.0, 1.0, 1.0, n);
        assert_eq!(a, DVec2::new(0.0, 1e-9));
    }

    #[test]
    fn separating_bodies_get_no_impulse() {
        let n = DVec2::new(1.0, 0.0);
        let (a, b) = body_body(DVec2::new(1.0, 0.0), DVec2::ZERO, 1.0, 1.0, 1.0, n);
        assert_eq!((a, b), (DVec2::new(1.0, 0.0), DVec2::ZERO));
    }

    #[test]
    fn huge_mass_ratio_keeps_the_small_correction() {
        let m = reduced_mass(1.0, 1e16);
        assert!(m < 1.0 && m > 0.999_999_999_999_99);
        assert_eq!(reduced_mass(1e300, 1e300), 5e299);
    }

    #[test]
    fn mass_weights_sum_to_one_even_for_a_huge_ratio() {
        let (light, heavy) = weights(1.0, 1e16);
        assert!(light > 0.999e-16 && light < 1.001e-16);
        assert_eq!(heavy, 1.0 - light);
        assert_eq!(weights(1e16, 1.0), (heavy, light));
        assert_eq!(weights(1e300, 1e300), (0.5, 0.5));
    }
}
