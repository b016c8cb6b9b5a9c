//! A disc wedged along a wall: from the sixteenth revision, a light disc
//! `L` lying against one obstacle, pressed obliquely by a heavy disc `H`
//! that slides nearly past it and brakes less, can only move along that
//! obstacle. The obstacle takes the part of the contact force across it,
//! and `L`, its inertia negligible, slides along the obstacle just as far
//! as keeps it touching `H`, its friction braking the pair with `H`'s
//! own. The pressing contact took this sustained push as a
//! bounce every few microseconds, for seconds; here it is taken at once
//! (see [`carried_along_wall`]), as `push::carried` takes a wedged disc
//! that moves freely.

use crate::push::{self, SAME};
use crate::revision::Revision;
use glam::DVec2;

/// Largest cosine of the angle between the pushing disc's direction and
/// the normal for which [`carried_along_wall`] takes a pair: `H` slides
/// past `L` (at least 60 degrees off the line of centres) rather than
/// driving it along the obstacle nearly head-on, where the pressing
/// contact's kicks move `L` far enough to be few (a hit 30 degrees off the
/// line of centres, carried so, sent `L` sliding 2.6 cm ahead of `H`).
const OBLIQUE: f64 = 0.5;

/// Largest mass of the wedged disc, as a fraction of the pushing one's,
/// for which its inertia is left out of the carry (as in
/// `push::carried`).
pub(crate) const LIGHT: f64 = 0.1;

/// From the sixteenth revision: the carry of a light disc `L` (index `l`,
/// 0 for `i`, 1 for `j`) held to the one obstacle it touches (`wall`, the
/// obstacle's unit normal towards `L`) by a heavy disc `H` sliding nearly
/// past it, `H` braking less. `u` are the velocities just before the
/// hit (`L` at rest or sliding along the obstacle), `m` the masses,
/// `alpha` the own brakings (`mu g`), `n` the unit normal from `j` to
/// `i`, `s` the contact distance.
///
/// The hit is plastic, with `L` held to the obstacle's line and `H` to
/// its own (its sideways share of the contact force is taken by whatever
/// else it touches, as in `push::carried`; see [`held_hit`]), so that the
/// pair no longer approaches. Take `nu` and `tau` across and along the
/// obstacle (`tau` the way `L` is pushed), and `x` the offset of `H`'s
/// centre from `L`'s line across the obstacle. As `H` travels `y`, `L`
/// slides along the obstacle by `z(y) = y d_tau - r_tau + sqrt(s^2 -
/// x(y)^2)` (`d` `H`'s direction, `r` the initial offset of `L` from
/// `H`), a concave rise that ends where `z' = 0` (`H` abreast of `L`, or
/// beyond it where `H` also moves along the obstacle), at `y_pass`. `L`'s
/// friction takes `m_L alpha_L z(y)` out of the pair, `H`'s own braking
/// `m_H alpha_H y`.
///
/// Where that work reaches the pair's kinetic energy before `y_pass`,
/// both stop at `y*`, as `push::carried` stops a wedged pair: `H` along
/// its line with the uniform deceleration that ends it at `y*`, `L` along
/// the obstacle at the speed the hit left it, decelerating to rest at the
/// same moment. The two then move apart along a straight line tangent to
/// the contact (the hit left no approach), so they never overlap, and
/// `L` slides `z'(0) y*`, a little beyond `z(y*)`. Where `H` has the
/// energy to pass, it pays `m_L alpha_L z(y_pass)` at once and keeps its
/// own braking, and `L` starts along the obstacle at `z'(0)` times `H`'s
/// speed and decelerates uniformly, so that its slide, as a function of
/// `H`'s travel, has a slope that falls linearly from `z'(0)` to zero at
/// `y_e`: where `z'` is convex (`H` not yet abreast of `L`), `y_e =
/// y_pass` (a chord above a convex function), else `y_e = s z'(0) /
/// d_nu^2` (`z'' <= -d_nu^2 / s` everywhere); either way `L` is always
/// at least as far along as the contact needs. `None` where the hit does
/// not drive `L` into the obstacle, `H` does not approach `L`'s line or
/// comes within 60 degrees of the line of centres, `L` is not light or
/// does not brake harder, the pass moves `L` no further than the pressing
/// contact's gap, or energy would be gained; else the velocities and
/// decelerations of `i` and `j`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn carried_along_wall(
    u: [DVec2; 2],
    m: [f64; 2],
    alpha: [f64; 2],
    n: DVec2,
    s: f64,
    l: usize,
    wall: DVec2,
    rev: Revision,
) -> Option<[(DVec2, f64); 2]> {
    carry(u, m, alpha, n, s, l, wall, rev, Pushed::Disc)
}

/// What [`carry`] carries along the obstacle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Pushed {
    /// One light disc ([`carried_along_wall`]): no heavier than [`LIGHT`]
    /// of the pushing disc, and not carried a pass that moves it no
    /// further than the pressing contact's gap (that is its bounces').
    Disc,
    /// A row of discs moving as one ([`carried_row_along_wall`]), however
    /// heavy, where the inertia it has at the rate the push carries it is
    /// no more than [`LIGHT`] of the pushing disc's, and carried a pass
    /// however short.
    Row,
}

/// From the twentieth revision, the carry of [`carried_along_wall`] for
/// a row of discs (slot `l`: the row as one body, its mass `m[l]` the
/// row's, `alpha[l]` the row's friction over that mass) wedged along the
/// obstacle (`wall`) it lies against by a disc `H` sliding along another
/// obstacle into the corner, nearly square to the row's line: the row's
/// inertia at the rate `r` the wedge carries it (`m_row r^2`) is left out
/// where it is no more than [`LIGHT`] of `H`'s mass, however heavy the
/// row, and a pass is carried however little it moves the row (a pass
/// shorter than the pressing contact's gap, left to the pressing contact,
/// kicked the row off at every hit). `u[l]` is the row's velocity along
/// the obstacle (at rest where its own motion is spent).
#[allow(clippy::too_many_arguments)]
pub(crate) fn carried_row_along_wall(
    u: [DVec2; 2],
    m: [f64; 2],
    alpha: [f64; 2],
    n: DVec2,
    s: f64,
    l: usize,
    wall: DVec2,
    rev: Revision,
) -> Option<[(DVec2, f64); 2]> {
    carry(u, m, alpha, n, s, l, wall, rev, Pushed::Row)
}

/// [`carried_along_wall`] and [`carried_row_along_wall`].
#[allow(clippy::too_many_arguments)]
fn carry(
    u: [DVec2; 2],
    m: [f64; 2],
    alpha: [f64; 2],
    n: DVec2,
    s: f64,
    l: usize,
    wall: DVec2,
    rev: Revision,
    pushed: Pushed,
) -> Option<[(DVec2, f64); 2]> {
    let h = 1 - l;
    if !(alpha[l] > alpha[h] && (pushed == Pushed::Row || m[l] <= LIGHT * m[h])) {
        return None;
    }
    let to_l = if l == 0 { n } else { -n };
    // The hit drives `L` into its obstacle, which holds it to its line.
    let across = to_l.dot(wall);
    if !(across < 0.0) {
        return None;
    }
    let tau = if wall.perp().dot(to_l) >= 0.0 {
        wall.perp()
    } else {
        -wall.perp()
    };
    let along = tau.dot(to_l);
    // The plastic hit, `L` held to the obstacle's line and `H` to its own.
    let v = held_hit(u, m, l, to_l, tau)?;
    let (vh, speed) = (v[h], v[h].length());
    let c = vh.dot(to_l);
    if !(along > 0.0 && speed > 0.0 && c > 0.0 && c <= OBLIQUE * speed) {
        return None;
    }
    // `L` slides along the obstacle only, at the rate that keeps the pair
    // from approaching.
    let rate = c / (speed * along);
    if pushed == Pushed::Row && !(m[l] * rate * rate <= LIGHT * m[h]) {
        return None;
    }
    let vl = tau * (rate * speed);
    if (v[l] - vl).length() > SAME * speed {
        return None;
    }
    let d = vh / speed;
    let (d_nu, d_tau) = (d.dot(wall), d.dot(tau));
    if !(d_nu < 0.0) {
        return None;
    }
    let (r_nu, r_tau) = (s * across, s * along);
    // Where `H` passes: `x / sqrt(s^2 - x^2) = -d_tau / d_nu`.
    let q = -d_tau / d_nu;
    let x_pass = q * s / (1.0 + q * q).sqrt();
    let pass = (r_nu - x_pass) / d_nu;
    if !(pass > 0.0 && pass.is_finite()) {
        return None;
    }
    // `L`'s slide for `H`'s travel `y`, without the cancellation of
    // `sqrt(s^2 - x^2) - r_tau` (`s^2 - r_tau^2 = r_nu^2`).
    let rise = |y: f64| {
        let x = r_nu - y * d_nu;
        let root = (s * s - x * x).max(0.0).sqrt();
        y * d_tau + y * d_nu * (2.0 * r_nu - y * d_nu) / (root + r_tau)
    };
    let (force, own) = (m[l] * alpha[l], m[h] * alpha[h]);
    let work = |y: f64| own * y + force * rise(y);
    let energy = push::pair_energy(v, m);
    let mut out = [(DVec2::ZERO, 0.0); 2];
    if energy >= work(pass) {
        // A pass that slides `L` no further than the gap the pressing
        // contact keeps is its bounces'.
        let ahead = rise(pass);
        if pushed == Pushed::Disc && !(ahead > push::press_gap(rev) * s) {
            return None;
        }
        let passing = speed * speed - 2.0 * force * ahead / m[h];
        if !(passing > 2.0 * alpha[h] * pass) {
            return None;
        }
        let passing = passing.sqrt();
        let reach = if x_pass <= 0.0 {
            pass
        } else {
            (s * rate / (d_nu * d_nu)).max(pass)
        };
        let start = rate * passing;
        let after = 0.5 * (m[h] * passing * passing + m[l] * start * start);
        if !(after <= energy && reach.is_finite()) {
            return None;
        }
        out[h] = (d * passing, alpha[h]);
        out[l] = (tau * start, rate * passing * passing / reach);
        return Some(out);
    }
    // `work` grows on [0, pass]: where it spends the energy.
    let stop = push::spent_at(work, energy, pass);
    if !(stop > 0.0) {
        return None;
    }
    // Both stop together after `2 y* / |v_H|`.
    let duration = 2.0 * stop / speed;
    out[h] = (vh, speed / duration);
    out[l] = (vl, rate * speed / duration);
    Some(out)
}

/// The plastic hit of a pair (velocities `u` before it, masses `m`) whose
/// disc `l` is held to a line along `tau` (an obstacle's) and whose other
/// disc `h` to its own line of motion, along the unit normal `to_l` from
/// `h` to `l`: the impulse `J = w / ((to_l . tau)^2 / m_l + (to_l .
/// d)^2 / m_h)` (`w` the approach, `d` `h`'s direction) stops the
/// approach, each disc taking its share along its line only. Two workless
/// constraints and a plastic impact: no energy is added. `None` where
/// `l` does not rest or slide along `tau` (to [`SAME`] of its speed),
/// `h` does not move, or the pair does not approach.
fn held_hit(u: [DVec2; 2], m: [f64; 2], l: usize, to_l: DVec2, tau: DVec2) -> Option<[DVec2; 2]> {
    let h = 1 - l;
    if u[l].perp_dot(tau).abs() > SAME * u[l].length() {
        return None;
    }
    let speed = u[h].length();
    if !(speed > 0.0) {
        return None;
    }
    let d = u[h] / speed;
    let approach = (u[h] - u[l]).dot(to_l);
    if !(approach > 0.0) {
        return None;
    }
    let (on_l, on_h) = (to_l.dot(tau), to_l.dot(d));
    let impulse = approach / (on_l * on_l / m[l] + on_h * on_h / m[h]);
    let mut v = u;
    v[l] = tau * (u[l].dot(tau) + impulse * on_l / m[l]);
    v[h] = d * (speed - impulse * on_h / m[h]);
    Some(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Where a disc starting at `p` with velocity `v` and deceleration `a`
    /// is after `t`.
    fn at(p: DVec2, v: DVec2, a: f64, t: f64) -> DVec2 {
        let speed = v.length();
        if speed == 0.0 {
            return p;
        }
        let t = if a > 0.0 { t.min(speed / a) } else { t };
        p + v * t - v / speed * (0.5 * a * t * t)
    }

    /// A light braking disc `L` (slot 0) against the left wall, pressed by
    /// a heavy frictionless disc `H` (slot 1) below it and a little off the
    /// wall, sliding towards the wall at `speed`: the carry, and whether
    /// the two ever come closer than the contact distance over `span`.
    fn wedged(speed: f64) -> ([(DVec2, f64); 2], f64) {
        let (s, m, alpha) = (0.05, [0.01, 1.0], [3.0, 0.0]);
        let to_l = DVec2::new(-0.05, 1.0).normalize();
        let (pl, ph) = (DVec2::ZERO, -to_l * s);
        let u = [DVec2::ZERO, DVec2::new(-speed, 0.0)];
        let wall = DVec2::X;
        let out = carried_along_wall(u, m, alpha, to_l, s, 0, wall, Revision::R16)
            .expect("a wedged pair");
        let span = 0.01 / speed;
        let closest = (0..=10_000)
            .map(|k| {
                let t = span * f64::from(k) / 10_000.0;
                let l = at(pl, out[0].0, out[0].1, t);
                let h = at(ph, out[1].0, out[1].1, t);
                assert_eq!(l.x, 0.0, "L leaves the wall");
                (l - h).length()
            })
            .fold(f64::INFINITY, f64::min);
        (out, closest / s)
    }

    #[test]
    fn a_slow_heavy_disc_stops_with_the_wedged_one_on_the_wall_where_its_friction_spends_their_energy(
    ) {
        let (out, closest) = wedged(1e-3);
        // Both stop at one moment, `H` along its line.
        let (h, l) = (out[1], out[0]);
        assert!(h.1 > 0.0 && l.1 > 0.0);
        let (stop_h, stop_l) = (h.0.length() / h.1, l.0.length() / l.1);
        assert!((stop_h - stop_l).abs() <= 1e-12 * stop_h);
        assert_eq!(h.0.y, 0.0);
        // No energy gained, and never closer than touching.
        let energy = 0.5 * (0.01 * l.0.length_squared() + h.0.length_squared());
        assert!(energy <= 0.5 * 1e-6);
        assert!(closest >= 1.0 - 1e-12, "closest {closest}");
    }

    #[test]
    fn a_fast_heavy_disc_passes_paying_the_friction_and_the_wedged_one_keeps_ahead_of_it() {
        let (out, closest) = wedged(1e-2);
        let (h, l) = (out[1], out[0]);
        // `H` keeps its line and its own braking, slower.
        assert_eq!(h.1, 0.0);
        assert!(h.0.x < 0.0 && h.0.x > -1e-2 && h.0.y == 0.0);
        let energy = 0.5 * (0.01 * l.0.length_squared() + h.0.length_squared());
        assert!(energy <= 0.5 * 1e-4);
        assert!(closest >= 1.0 - 1e-12, "closest {closest}");
    }

    /// A heavy braking row (1.5 kg, 3.8 N of friction; slot 0) on the
    /// floor, wedged by a light frictionless disc `H` (20 g; slot 1)
    /// sliding down the side wall at `speed`, its centre 1e-4 m above the
    /// row's line: the carry, and the closest the two come over `span`
    /// (as a fraction of the contact distance).
    fn row_in_a_corner(speed: f64) -> ([(DVec2, f64); 2], f64) {
        let (s, h): (f64, f64) = (0.05, 1e-4);
        let (m, alpha) = ([1.5, 0.02], [3.8 / 1.5, 0.0]);
        let (pl, ph) = (DVec2::new((s * s - h * h).sqrt(), 0.0), DVec2::new(0.0, h));
        let n = (pl - ph) / s;
        let u = [DVec2::ZERO, DVec2::new(0.0, -speed)];
        let out = carried_row_along_wall(u, m, alpha, n, s, 0, DVec2::Y, Revision::R20)
            .expect("a wedged row");
        let span = 2.0 * h / speed;
        let closest = (0..=10_000)
            .map(|k| {
                let t = span * f64::from(k) / 10_000.0;
                let l = at(pl, out[0].0, out[0].1, t);
                let p = at(ph, out[1].0, out[1].1, t);
                assert_eq!(l.y, 0.0, "the row leaves the floor");
                assert_eq!(p.x, 0.0, "H leaves its wall");
                (l - p).length()
            })
            .fold(f64::INFINITY, f64::min);
        (out, closest / s)
    }

    #[test]
    fn a_light_disc_sliding_into_a_corner_stops_with_the_heavy_row_it_wedges() {
        let (out, closest) = row_in_a_corner(1e-3);
        let (row, h) = (out[0], out[1]);
        // Passing costs 3.8 N over 1e-7 m, 38 times H's 1e-8 J: both stop
        // at one moment.
        assert!(row.1 > 0.0 && h.1 > 0.0);
        let (stop_row, stop_h) = (row.0.length() / row.1, h.0.length() / h.1);
        assert!((stop_row - stop_h).abs() <= 1e-12 * stop_h);
        let energy = 0.5 * (1.5 * row.0.length_squared() + 0.02 * h.0.length_squared());
        assert!(energy <= 0.5 * 0.02 * 1e-6);
        assert!(closest >= 1.0 - 1e-12, "closest {closest}");
    }

    #[test]
    fn a_light_disc_sliding_into_a_corner_fast_passes_paying_the_row_it_wedges_aside() {
        let (out, closest) = row_in_a_corner(5e-2);
        let (row, h) = (out[0], out[1]);
        // H keeps its line and its own braking (none), slower by the
        // row's friction over its carry; the row slides ahead along the
        // floor.
        assert_eq!(h.1, 0.0);
        assert!(h.0.y < 0.0 && h.0.y > -5e-2);
        assert!(row.0.x > 0.0 && row.1 > 0.0);
        let energy = 0.5 * (1.5 * row.0.length_squared() + 0.02 * h.0.length_squared());
        assert!(energy <= 0.5 * 0.02 * 25e-4);
        assert!(closest >= 1.0 - 1e-12, "closest {closest}");
    }

    #[test]
    fn a_hit_that_lifts_the_disc_off_its_wall_or_a_heavier_wedged_disc_is_not_carried_along_it() {
        let (s, alpha) = (0.05, [3.0, 0.0]);
        let to_l = DVec2::new(0.05, 1.0).normalize();
        let u = [DVec2::ZERO, DVec2::new(-1e-3, 0.0)];
        // `L` pushed away from its wall.
        let off = carried_along_wall(u, [0.01, 1.0], alpha, to_l, s, 0, DVec2::X, Revision::R16);
        assert_eq!(off, None);
        // `L` as heavy as `H`.
        let to_l = DVec2::new(-0.05, 1.0).normalize();
        let heavy = carried_along_wall(u, [1.0, 1.0], alpha, to_l, s, 0, DVec2::X, Revision::R16);
        assert_eq!(heavy, None);
    }
}
