//! Contact prediction: when will a disc next touch another disc, a point or a
//! line, or cross a sensor — the exact time, from the closed-form trajectories.
//!
//! Only *approaching* contacts count: at the returned time the distance
//! function is decreasing (or the objects already touch and approach now).
//! A pair that touches and separates, or rests side by side, gives nothing,
//! which is also what stops a just-resolved contact from firing again.
//!
//! A disc moves along a straight line (friction only slows it), so every
//! contact with something that does not move is solved in closed form on the
//! path parameter and converted to time. Only two discs that both move, at
//! least one of them with friction, need the quartic
//! `|dp + dv t + da t^2/2|^2 - S^2 = 0`; that goes to the root solver, on the
//! interval until the first of the two stops (a stop is an event of its own
//! that re-predicts the body). Pairs whose remaining paths never come within
//! reach are rejected before any polynomial is formed.

use crate::graze;
use crate::obstacle::LineGeom;
use crate::push;
use crate::revision::Revision;
use crate::roots::RootSolver;
use crate::trajectory::Trajectory;
use glam::DVec2;

/// Relative distance under which two discs count as touching now: their
/// gap is below rounding noise of the contact distance.
const TOUCH: f64 = 1e-12;

/// Rounding of a gap between two positions, relative to their magnitude:
/// a few units in the last place of each coordinate.
const COORDINATE_NOISE: f64 = 8.0 * f64::EPSILON;

/// The moment a prediction is made from: the world's working time `now`
/// and the origin of its clock (see `clock`), which together give the
/// absolute time that the pressing test reads.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct When {
    /// Working time: seconds since `origin`.
    pub now: f64,
    /// The clock's origin (rounded to one `f64`).
    pub origin: f64,
}

impl When {
    /// `now` from the origin `origin`.
    pub(crate) fn new(now: f64, origin: f64) -> When {
        When { now, origin }
    }
}

/// A moving disc's path from time `now`, worked out once per prediction:
/// position `pos + w l`, where `l` is time (frictionless, `w` the velocity)
/// or distance travelled (with friction, `w` the unit direction).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Mover<'a> {
    pub tr: &'a Trajectory,
    pub now: f64,
    /// Position at `now`.
    pub pos: DVec2,
    w: DVec2,
    /// Distance travelled from the trajectory's start to `now` (friction only).
    travelled: f64,
}

impl<'a> Mover<'a> {
    /// The path of `tr` from `now`, or `None` if the disc is at rest then.
    #[inline]
    pub(crate) fn new(tr: &'a Trajectory, now: f64) -> Option<Mover<'a>> {
        if !tr.is_moving_at(now) {
            return None;
        }
        Some(if tr.is_frictionless() {
            Mover {
                tr,
                now,
                pos: tr.position(now),
                w: tr.start_velocity(),
                travelled: 0.0,
            }
        } else {
            let travelled = tr.sigma(now - tr.start_time());
            Mover {
                tr,
                now,
                pos: tr.start_position() + tr.direction() * travelled,
                w: tr.direction(),
                travelled,
            }
        })
    }

    /// The direction of the path parameter: velocity without friction, unit
    /// direction with it.
    #[inline]
    pub(crate) fn direction(&self) -> DVec2 {
        self.w
    }

    /// Absolute time at path parameter `l >= 0` past `now` (None if the
    /// disc stops first).
    #[inline]
    pub(crate) fn time_at(&self, l: f64) -> Option<f64> {
        if self.tr.is_frictionless() {
            Some(self.now + l)
        } else {
            self.tr
                .time_at_distance(self.travelled + l)
                .map(|t| t.max(self.now))
        }
    }
}

/// The first time `>= now` at which the moving disc touches the fixed point
/// `q` at centre distance `s`, approaching.
#[inline]
pub(crate) fn disc_point(m: &Mover, q: DVec2, s: f64, rev: Revision) -> Option<f64> {
    let d = m.pos - q;
    let (w, scale) = well_scaled(m.w);
    let b = d.dot(w);
    if b >= 0.0 {
        return None; // moving away (or sideways): a straight path never returns
    }
    let c = d.length_squared() - s * s;
    if c <= 0.0 {
        // Touching now: a contact only if the approach is more than noise,
        // and from the eighteenth revision more than a graze within the
        // rounding of the positions.
        let approaches = b < -APPROACH * s * w.length();
        let grazes = || rev.passes_grazes_within_rounding() && graze::within_rounding(m.pos, q, w);
        return (approaches && !grazes()).then_some(m.now);
    }
    let l = entry(w.length_squared(), b, c, d.perp_dot(w), s * s, rev)?;
    m.time_at(l * scale)
}

/// `w` rescaled by a power of two into the range where its squared length
/// neither underflows nor overflows, and the factor used (1 if none was):
/// a path `p + w l` is `p + (w * scale) (l / scale)`, so a parameter found
/// with the scaled vector is multiplied by `scale` to get back to `l`.
#[inline(always)]
fn well_scaled(w: DVec2) -> (DVec2, f64) {
    let a = w.length_squared();
    // `a.is_normal() && a < 1e300` for a square (never negative), in two
    // comparisons (NaN fails both).
    if (f64::MIN_POSITIVE..1e300).contains(&a) {
        return (w, 1.0);
    }
    let big = w.x.abs().max(w.y.abs());
    if big == 0.0 || !big.is_finite() {
        return (w, 1.0);
    }
    // 2^-e with big = m 2^e: exact scaling, no rounding.
    let scale = f64::from_bits((2046 - ((big.to_bits() >> 52) & 0x7ff).max(1)) << 52);
    (w * scale, scale)
}

/// The entering root `l > 0` of `a l^2 + 2 b l + c = 0` (with `b < 0`,
/// `c > 0`: approaching from outside), or `None` if the path misses or only
/// grazes: a double root, within rounding of the discriminant, is a touch
/// with no normal approach, not a contact.
///
/// The equation is `|d + w l|^2 = s^2` with `a = |w|^2`, `b = d . w`,
/// `c = |d|^2 - s^2`; `cross = d x w` and `s2 = s^2`. From far away
/// (`|d|` above [`FAR`] times `s`) `b^2` and `a c` nearly cancel: their
/// difference carries an error of a few units in the last place of `b^2`,
/// which moves the root by about `eps (|d| / s)^2` of `s` (by 7e-10 of the
/// time from `1.3e7 s`). There, and for near-grazes whose discriminant is
/// lost in that rounding, the discriminant is taken from Lagrange's
/// identity instead, `b^2 - a c = a s^2 - cross^2`, free of that
/// cancellation (only there, so nearby contacts keep their bits).
#[inline(always)]
fn entry(a: f64, b: f64, c: f64, cross: f64, s2: f64, rev: Revision) -> Option<f64> {
    let disc = b * b - a * c;
    if disc <= GRAZE * b * b || (rev.at_least_r2() && c > FAR * FAR * s2) {
        let exact = a * s2 - cross * cross;
        if !(exact > GRAZE * a * s2) {
            return None;
        }
        return Some(c / (-b + exact.sqrt()));
    }
    Some(c / (-b + disc.sqrt()))
}

/// Touching objects whose normal approach speed is below this fraction of
/// their speeds are not colliding: the approach is rounding noise (an
/// impulse that small would not change the velocities, and the same contact
/// would fire again at the same instant for ever, as in an inelastic
/// collapse). Ignoring it lets a pair drift into contact by at most this
/// fraction of the distance travelled.
const APPROACH: f64 = 1e-12;

/// From the third revision, a touching pair (or a disc touching a line)
/// that approaches slower than [`APPROACH`] of its speeds still meets: when
/// it is this fraction of the contact distance inside it (a hit that snaps
/// it back to touching). Ignored, such an approach let two discs sliding
/// side by side for hundreds of metres drift into each other by 1e-8 of
/// their contact distance, a disc bouncing along a wall drift into it by
/// 4e-9 of its radius, and frictionless discs through each other in 1e12 s.
const DRIFT: f64 = 1e-10;

/// From the twelfth revision, a touching pair of moving discs that does not
/// approach now (it parts no faster than rounding noise, or not at all) is
/// still looked for [`DRIFT`] inside its contact distance: braked
/// differently along a normal that turns as they slide past each other, two
/// discs left side by side by a plastic hit can come together with a
/// squared gap that falls as the cube of the time, whose approach at the
/// tangent root is below [`APPROACH`], and before, the contact was only
/// sought where the pair approached now, so they went into each other for
/// as long as they slid (1.8e-8 of their contact distance in a mixed box).
/// A pair parting faster than the noise is left to the roots of the gap
/// (its return is a crossing they find), and so is not solved for again
/// after every hit with friction.
#[inline(always)]
fn turns_in_after_touch(rev: Revision) -> bool {
    rev.at_least_r12()
}

/// Distance, in contact distances, beyond which the discriminant of a
/// contact is taken from Lagrange's identity (see [`entry`]): from there
/// on the rounding of `b^2 - a c` would move the contact by more than
/// 1e-12 of the contact distance. No two pieces on a board are that far
/// apart.
const FAR: f64 = 100.0;

/// Discriminants below this fraction of `b^2` are rounding noise around a
/// double root (a tangent pass). Skipping such a touch leaves at most a
/// rounding-level overlap: the normal approach speed there is below
/// `sqrt(GRAZE)` (about 5e-8) of the speed.
const GRAZE: f64 = 16.0 * f64::EPSILON;

/// A predicted hit on a line: the time, and which end if it is a corner.
/// (Only the tests ask: the world tries the ends of its lines once each,
/// as shared corners.)
#[cfg(test)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LineHit {
    pub t: f64,
    pub end: Option<u8>,
}

/// The first time `>= now` at which the moving disc of radius `r` touches
/// the solid line (its straight part or one of its ends), approaching.
#[cfg(test)]
pub(crate) fn disc_line(m: &Mover, line: &LineGeom, r: f64, rev: Revision) -> Option<LineHit> {
    let mut best = disc_line_body(m, line, r, rev).map(|t| LineHit { t, end: None });
    for (k, end) in line.ends.iter().enumerate() {
        if let Some(q) = end {
            if let Some(t) = disc_point(m, *q, r, rev) {
                if best.is_none_or(|b| t < b.t) {
                    best = Some(LineHit {
                        t,
                        end: Some(k as u8),
                    });
                }
            }
        }
    }
    best
}

/// The first time `>= now` at which the moving disc of radius `r` touches
/// the straight part of the line (not its ends), approaching.
#[inline]
pub(crate) fn disc_line_body(m: &Mover, line: &LineGeom, r: f64, rev: Revision) -> Option<f64> {
    let h = line.signed_distance(m.pos);
    let rate = line.n.dot(m.w);
    let side = if h > 0.0 || (h == 0.0 && rate < 0.0) {
        1.0
    } else {
        -1.0
    };
    if side * rate >= 0.0 {
        return None; // not approaching the line
    }
    let gap = side * h - r;
    let l = if gap > 0.0 {
        gap / (-side * rate)
    } else {
        touching_line(m, side * h, side * rate, r, rev)?
    };
    if line.is_bounded() && !line.covers(m.pos + m.w * l) {
        return None; // passes beyond the extent; the ends are checked as points
    }
    m.time_at(l)
}

/// The path parameter of a contact with a line the disc touches now (its
/// distance from the line `h <= r`, approaching it at `rate < 0`): at once,
/// unless the approach is rounding noise. Kept out of line: it is rare, and
/// inlined, the length of `m.w` was computed on every prediction.
#[cold]
#[inline(never)]
fn touching_line(m: &Mover, h: f64, rate: f64, r: f64, rev: Revision) -> Option<f64> {
    if rate <= -APPROACH * m.w.length() {
        Some(0.0)
    } else if rev.at_least_r3() {
        // Touching, approaching below rounding noise: meets DRIFT inside
        // the contact distance (see DRIFT).
        Some((h - r * (1.0 - DRIFT)).max(0.0) / -rate)
    } else {
        None // touching, approaching by no more than rounding noise
    }
}

/// The first time `>= now` at which the moving centre crosses the sensor
/// line, leaving its current side (`inside` = the left side, positive signed
/// distance). Returns the time and whether the crossing is within the
/// sensor's extent (a crossing outside a ray or segment is only bookkeeping).
pub(crate) fn centre_crossing(m: &Mover, line: &LineGeom, inside: bool) -> Option<(f64, bool)> {
    let h = line.signed_distance(m.pos);
    let rate = line.n.dot(m.w);
    let (h, rate) = if inside { (h, rate) } else { (-h, -rate) };
    if rate >= 0.0 {
        return None; // moving deeper into its side, or along the line
    }
    let l = if h <= 0.0 { 0.0 } else { h / -rate };
    let t = m.time_at(l)?;
    Some((t, line.covers(m.pos + m.w * l)))
}

/// The first time `>= now` at which two discs at centre distance `s` touch
/// while approaching. `mi` is the path of the first disc if it moves;
/// `solver` finds the roots of the quartic when both move with friction.
#[inline(always)]
pub(crate) fn disc_disc(
    ti: &Trajectory,
    mi: Option<&Mover>,
    tj: &Trajectory,
    s: f64,
    when: When,
    solver: &impl RootSolver,
    rev: Revision,
) -> Option<f64> {
    let now = when.now;
    match (mi, tj.is_moving_at(now)) {
        (None, false) => None,
        (Some(m), false) => disc_point(m, tj.position(now), s, rev),
        (None, true) => disc_point(&Mover::new(tj, now)?, ti.position(now), s, rev),
        (Some(m), true) if ti.is_frictionless() && tj.is_frictionless() => {
            linear_pair(m.pos, ti, tj, s, now, rev)
        }
        (Some(m), true) => curved_pair(m.pos, ti, tj, s, when, solver, rev),
    }
}

/// Both move without friction: relative motion is linear, the contact
/// equation quadratic.
#[inline(always)]
fn linear_pair(
    pi: DVec2,
    ti: &Trajectory,
    tj: &Trajectory,
    s: f64,
    now: f64,
    rev: Revision,
) -> Option<f64> {
    let dp = pi - tj.position(now);
    let (dv, scale) = well_scaled(ti.start_velocity() - tj.start_velocity());
    let b = dp.dot(dv);
    if b >= 0.0 {
        return None;
    }
    let c = dp.length_squared() - s * s;
    if c <= 0.0 {
        let noise = APPROACH * s * scale * (ti.speed() + tj.speed());
        if b < -noise {
            return Some(now);
        }
        if !rev.at_least_r3() {
            return None;
        }
        // Approaching below noise: meets DRIFT inside the contact distance
        // (see DRIFT).
        let target = (s * (1.0 - DRIFT)).powi(2);
        let c = dp.length_squared() - target;
        if c <= 0.0 {
            return Some(now);
        }
        let t = entry(dv.length_squared(), b, c, dp.perp_dot(dv), target, rev)?;
        return Some(now + t * scale);
    }
    Some(now + entry(dv.length_squared(), b, c, dp.perp_dot(dv), s * s, rev)? * scale)
}

/// At least one of two moving discs slows down: solve the quartic on the
/// interval until the first of them stops.
fn curved_pair(
    pi: DVec2,
    ti: &Trajectory,
    tj: &Trajectory,
    s: f64,
    when: When,
    solver: &impl RootSolver,
    rev: Revision,
) -> Option<f64> {
    let now = when.now;
    let pj = tj.position(now);
    let horizon = ti.stop_time().min(tj.stop_time()) - now;
    if paths_never_within(ti, pi, tj, pj, s, now) {
        return None;
    }
    let dp = pi - pj;
    let dv = ti.velocity(now) - tj.velocity(now);
    let da = ti.acceleration(now) - tj.acceleration(now);
    let c0 = dp.length_squared() - s * s;
    let c1 = 2.0 * dp.dot(dv);
    let c2 = dv.length_squared() + dp.dot(da);
    let c3 = dv.dot(da);
    let c4 = 0.25 * da.length_squared();
    // f' = 2 (dp . dv) at a contact: an approach slower than `APPROACH` of
    // the speeds is rounding noise, not a contact.
    let min_slope = -2.0 * s * APPROACH * (ti.speed() + tj.speed());
    // Touching: the gap is below `TOUCH` of the contact distance, or, far
    // from the origin, below the rounding of the coordinates themselves
    // (there a gap of a few units in the last place is all a position can
    // say, and a touching pair must not be taken for one about to meet).
    let resolution = COORDINATE_NOISE * (pi.abs().max_element() + pj.abs().max_element());
    let touching = c0 <= 2.0 * s * (TOUCH * s).max(resolution);
    if touching && (c1 < min_slope || push::pushing(ti, pi, tj, pj, now)) {
        // Approaching, or pressed together by their braking: an event now.
        return Some(now);
    }
    if touching
        && rev.at_least_r2()
        && c1 < -min_slope
        && pressing(ti, tj, dp, s, when, -min_slope, rev)
    {
        // Neither approaching nor parting, and pressed together obliquely:
        // the approximated contact, now (see `push::pressing_kick`).
        return Some(now);
    }
    if touching {
        // f(t) = t g(t) with g the cubic below; f crosses downwards where g
        // does, with slope f'(r) = r g'(r).
        let g = [c1, c2, c3, c4];
        for &r in solver.roots_in(&g, 0.0, horizon).iter() {
            if r > 0.0 && r * (c2 + r * (2.0 * c3 + r * 3.0 * c4)) < min_slope {
                return Some(now + r);
            }
        }
        if rev.at_least_r3() && (c1 < 0.0 || (turns_in_after_touch(rev) && c1 < -min_slope)) {
            // Approaching below noise (or, from the twelfth revision,
            // parting no faster than noise, which the braking may yet
            // bring together): meets DRIFT inside the contact distance
            // (see DRIFT).
            let c = dp.length_squared() - (s * (1.0 - DRIFT)).powi(2);
            if c <= 0.0 {
                return Some(now);
            }
            let shifted = [c, c1, c2, c3, c4];
            for &r in solver.roots_in(&shifted, 0.0, horizon).iter() {
                if c1 + r * (2.0 * c2 + r * (3.0 * c3 + r * 4.0 * c4)) < 0.0 {
                    return Some(now + r);
                }
            }
        }
        return None;
    }
    let f = [c0, c1, c2, c3, c4];
    for &r in solver.roots_in(&f, 0.0, horizon).iter() {
        let slope = c1 + r * (2.0 * c2 + r * (3.0 * c3 + r * 4.0 * c4));
        if slope < min_slope {
            return Some(now + r);
        }
    }
    None
}

/// Whether two touching moving discs (centres `dp` apart, contact
/// distance `s`) are pressed together obliquely, so that the approximated
/// contact would part them faster than `noise` (in units of `2 s` times a
/// speed, as the slope of the squared gap).
fn pressing(
    ti: &Trajectory,
    tj: &Trajectory,
    dp: DVec2,
    s: f64,
    when: When,
    noise: f64,
    rev: Revision,
) -> bool {
    let now = when.now;
    if !ti.is_moving_at(now) || !tj.is_moving_at(now) {
        return false;
    }
    let (vi, vj) = (ti.velocity(now), tj.velocity(now));
    let n = dp.normalize_or_zero();
    let accelerations = [ti.acceleration(now), tj.acceleration(now)];
    match push::pressing_kick([vi, vj], accelerations, n, s, when.origin + now, rev) {
        Some(push::Press::Part(dw)) => 2.0 * s * ((vi - vj).dot(n).max(0.0) + dw) > noise,
        Some(push::Press::Rest) => true,
        None => false,
    }
}

/// True if the remaining paths (segments, or rays without friction) of the
/// two discs never come within `s` of each other.
fn paths_never_within(
    ti: &Trajectory,
    pi: DVec2,
    tj: &Trajectory,
    pj: DVec2,
    s: f64,
    now: f64,
) -> bool {
    if ti.is_frictionless() || tj.is_frictionless() {
        return false;
    }
    let li = ti.stopping_distance() - ti.sigma(now - ti.start_time());
    let lj = tj.stopping_distance() - tj.sigma(now - tj.start_time());
    segment_distance(pi, pi + ti.direction() * li, pj, pj + tj.direction() * lj) > s
}

/// Distance between segments `[a0, a1]` and `[b0, b1]`.
pub fn segment_distance(a0: DVec2, a1: DVec2, b0: DVec2, b1: DVec2) -> f64 {
    let da = a1 - a0;
    let db = b1 - b0;
    let cross = da.perp_dot(db);
    if cross != 0.0 {
        // Proper intersection?
        let w = b0 - a0;
        let s = w.perp_dot(db) / cross;
        let t = w.perp_dot(da) / cross;
        if (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t) {
            return 0.0;
        }
    }
    point_segment(a0, b0, b1)
        .min(point_segment(a1, b0, b1))
        .min(point_segment(b0, a0, a1))
        .min(point_segment(b1, a0, a1))
}

fn point_segment(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + ab * t - p).length()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::obstacle::{Line, LineKind};
    use crate::roots::Production;

    fn mover(p: (f64, f64), u: (f64, f64), alpha: f64) -> Trajectory {
        Trajectory::new(0.0, DVec2::new(p.0, p.1), DVec2::new(u.0, u.1), alpha)
    }

    #[test]
    fn well_scaled_keeps_exactly_the_vectors_whose_square_is_normal_and_below_1e300() {
        // The test as `f64::is_normal` states it, and the rescaling.
        let reference = |w: DVec2| {
            let a = w.length_squared();
            if a.is_normal() && a < 1e300 {
                return (w, 1.0);
            }
            let big = w.x.abs().max(w.y.abs());
            if big == 0.0 || !big.is_finite() {
                return (w, 1.0);
            }
            let scale = f64::from_bits((2046 - ((big.to_bits() >> 52) & 0x7ff).max(1)) << 52);
            (w * scale, scale)
        };
        let parts = [
            0.0,
            -0.0,
            5e-324,
            f64::MIN_POSITIVE,
            1e-160,
            1e-154,
            1.5e-154,
            1e-3,
            1.0,
            3.0e149,
            1e150,
            1e155,
            f64::MAX,
            f64::INFINITY,
            f64::NAN,
        ];
        let bits = |(v, s): (DVec2, f64)| (v.x.to_bits(), v.y.to_bits(), s.to_bits());
        for &x in &parts {
            for &y in &parts {
                for w in [DVec2::new(x, y), DVec2::new(-y, x)] {
                    assert_eq!(bits(well_scaled(w)), bits(reference(w)), "{w:?}");
                }
            }
        }
    }

    /// `disc_point` for `tr` from time 0, under the latest revision.
    fn point_hit(tr: &Trajectory, q: DVec2, s: f64) -> Option<f64> {
        disc_point(&Mover::new(tr, 0.0).unwrap(), q, s, Revision::LATEST)
    }

    /// `disc_line` for `tr` from time 0, under the latest revision.
    fn line_hit(tr: &Trajectory, line: &LineGeom, r: f64) -> Option<LineHit> {
        disc_line(&Mover::new(tr, 0.0).unwrap(), line, r, Revision::LATEST)
    }

    /// `disc_disc` for `a` and `b` from time 0, under the latest revision.
    fn pair_hit(a: &Trajectory, b: &Trajectory, s: f64) -> Option<f64> {
        disc_disc(
            a,
            Mover::new(a, 0.0).as_ref(),
            b,
            s,
            When::new(0.0, 0.0),
            &Production,
            Revision::LATEST,
        )
    }

    #[test]
    fn frictionless_disc_meets_a_point_at_the_geometric_time() {
        let tr = mover((0.0, 0.0), (2.0, 0.0), 0.0);
        let t = point_hit(&tr, DVec2::new(5.0, 0.0), 1.0).unwrap();
        assert_eq!(t, 2.0);
    }

    #[test]
    fn sliding_disc_stopping_short_of_a_point_never_touches_it() {
        // Stops after v^2/(2 alpha) = 1.0; the point is 1.5 away at contact distance 0.4.
        let tr = mover((0.0, 0.0), (2.0, 0.0), 2.0);
        assert_eq!(point_hit(&tr, DVec2::new(1.5, 0.0), 0.4), None);
        let t = point_hit(&tr, DVec2::new(1.3, 0.0), 0.4).unwrap();
        // Travels 0.9: 2t - t^2 = 0.9.
        let exact = 1.0 - (1.0f64 - 0.9).sqrt();
        assert!((t - exact).abs() < 1e-15, "{t} vs {exact}");
    }

    #[test]
    fn a_creeping_disc_meets_a_point_at_the_geometric_time() {
        // Speeds whose squares underflow are rescaled, and scaled back.
        let tr = mover((0.0, 0.0), (1e-170, 0.0), 0.0);
        let t = point_hit(&tr, DVec2::new(5.0, 0.0), 1.0).unwrap();
        assert!((t - 4e170).abs() <= 4e170 * 1e-15, "{t}");
        let a = mover((0.0, 0.0), (1e-170, 0.0), 0.0);
        let b = mover((5.0, 0.0), (-1e-170, 0.0), 0.0);
        let t = pair_hit(&a, &b, 1.0).unwrap();
        assert!((t - 2e170).abs() <= 2e170 * 1e-15, "{t}");
    }

    #[test]
    fn a_disc_a_million_metres_away_heading_straight_at_a_point_hits_it() {
        for dist in [1e6, 3e6, 1e7] {
            let tr = mover((-dist, 0.0), (3.0, 0.0), 0.0);
            let m = Mover::new(&tr, 0.0).unwrap();
            let t = disc_point(&m, DVec2::ZERO, 0.02, Revision::LATEST).unwrap();
            assert!((t - (dist - 0.02) / 3.0).abs() <= 1e-15 * t, "{dist}: {t}");
            // Passing just wide of it still misses.
            let tr = mover((-dist, 0.0200001), (3.0, 0.0), 0.0);
            let m = Mover::new(&tr, 0.0).unwrap();
            assert_eq!(disc_point(&m, DVec2::ZERO, 0.02, Revision::LATEST), None);
        }
        let a = mover((-1e6, 0.0), (1.0, 0.0), 0.0);
        let b = mover((0.0, 0.0), (-1.0, 0.0), 0.0);
        let t = pair_hit(&a, &b, 0.04);
        assert_eq!(t, Some((1e6 - 0.04) / 2.0));
    }

    #[test]
    fn touching_and_separating_gives_no_contact() {
        let tr = mover((0.0, 0.0), (-1.0, 0.0), 0.0);
        assert_eq!(point_hit(&tr, DVec2::new(1.0, 0.0), 1.0), None);
    }

    #[test]
    fn touching_and_approaching_is_a_contact_now() {
        let tr = mover((0.0, 0.0), (1.0, 0.0), 0.5);
        assert_eq!(point_hit(&tr, DVec2::new(1.0, 0.0), 1.0), Some(0.0));
    }

    #[test]
    fn disc_hits_segment_interior_and_misses_beyond_its_end() {
        let seg = LineGeom::new(&Line::new(
            DVec2::new(2.0, -1.0),
            DVec2::new(2.0, 1.0),
            LineKind::Segment,
        ))
        .unwrap();
        let tr = mover((0.0, 0.0), (1.0, 0.0), 0.0);
        let hit = line_hit(&tr, &seg, 0.5).unwrap();
        assert_eq!(hit, LineHit { t: 1.5, end: None });
        let tr = mover((0.0, 3.0), (1.0, 0.0), 0.0);
        assert_eq!(line_hit(&tr, &seg, 0.5), None);
    }

    #[test]
    fn disc_grazing_a_segment_end_hits_the_corner() {
        let seg = LineGeom::new(&Line::new(
            DVec2::new(2.0, -1.0),
            DVec2::new(2.0, 1.0),
            LineKind::Segment,
        ))
        .unwrap();
        let tr = mover((0.0, 1.3), (1.0, 0.0), 0.0);
        let hit = line_hit(&tr, &seg, 0.5).unwrap();
        assert_eq!(hit.end, Some(1));
        let expected = 2.0 - (0.25f64 - 0.09).sqrt();
        assert!((hit.t - expected).abs() < 1e-15);
    }

    #[test]
    fn two_sliding_discs_meet_at_the_quartic_root() {
        let a = mover((0.0, 0.0), (2.0, 0.0), 1.0);
        let b = mover((1.5, 0.0), (-2.0, 0.0), 1.0);
        let t = pair_hit(&a, &b, 0.5).unwrap();
        // 2(2t - t^2/2) = 1  =>  t^2 - 4t + 1 = 0
        let exact = 2.0 - 3.0f64.sqrt();
        assert!((t - exact).abs() < 1e-15, "{t} vs {exact}");
    }

    #[test]
    fn paths_that_never_come_close_are_not_solved() {
        let a = mover((0.0, 0.0), (1.0, 0.0), 1.0);
        let b = mover((0.0, 5.0), (1.0, 0.0), 1.0);
        assert!(paths_never_within(
            &a,
            DVec2::ZERO,
            &b,
            DVec2::new(0.0, 5.0),
            1.0,
            0.0
        ));
        assert_eq!(pair_hit(&a, &b, 1.0), None);
    }

    #[test]
    fn sensor_crossing_fires_once_in_the_direction_of_travel() {
        let edge = LineGeom::new(&Line::sensor(
            DVec2::new(1.0, -1.0),
            DVec2::new(1.0, 1.0),
            LineKind::Line,
        ))
        .unwrap();
        // Left of (1,-1)->(1,1), walking north, is x < 1: the inside.
        let tr = mover((0.0, 0.0), (2.0, 0.0), 0.0);
        assert_eq!(
            centre_crossing(&Mover::new(&tr, 0.0).unwrap(), &edge, true),
            Some((0.5, true))
        );
        // Once outside and moving out, no further crossing.
        assert_eq!(
            centre_crossing(&Mover::new(&tr, 0.5).unwrap(), &edge, false),
            None
        );
    }

    #[test]
    fn segment_distance_handles_crossing_and_parallel_segments() {
        let d = segment_distance(
            DVec2::new(0.0, 0.0),
            DVec2::new(2.0, 0.0),
            DVec2::new(1.0, -1.0),
            DVec2::new(1.0, 1.0),
        );
        assert_eq!(d, 0.0);
        let d = segment_distance(
            DVec2::new(0.0, 0.0),
            DVec2::new(2.0, 0.0),
            DVec2::new(0.0, 3.0),
            DVec2::new(2.0, 3.0),
        );
        assert_eq!(d, 3.0);
    }
}
