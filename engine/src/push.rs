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
//!
//! Three or more touching discs sliding along one line form a chain
//! (`pooled`): contacts can only push, so the braking may not grow from
//! the rear of the chain to its front. Wherever a rear disc brakes less than
//! the disc in front, the two move as one block with their mass-weighted
//! mean braking and velocity, and blocks are pooled again until the braking
//! falls from rear to front (the pool-adjacent-violators construction).
//! The result is the exact solution of the chain's contact forces: every
//! force is a push, and only discs that move as one block press on each
//! other. Blocks then separate (the front ones brake less) and each stops
//! at its own time. Joining a whole chain at once is what keeps a chain
//! from re-joining pair after pair at one instant without end.

use crate::impulse;
use crate::instant::same_instant;
use crate::revision::Revision;
use crate::trajectory::Trajectory;
use glam::DVec2;

/// Relative tolerance for "the same velocity" and "along the line of
/// centres": rounding noise, far below any physical difference.
pub(crate) const SAME: f64 = 1e-9;

/// Relative slack on the squared contact distance under which two discs of
/// a chain count as touching.
pub(crate) const TOUCHING: f64 = 2e-9;

/// Whether the discs on `ti` and `tj`, touching at `now` with centres `pi`
/// and `pj`, push on each other: both move, with the same velocity (to
/// rounding) along the line of their centres, and their braking presses
/// them together (the rear one brakes less).
pub(crate) fn pushing(ti: &Trajectory, pi: DVec2, tj: &Trajectory, pj: DVec2, now: f64) -> bool {
    // Cheapest test first: without braking nothing presses (the last test
    // below compares zero with zero), and the lengths are never needed.
    if ti.alpha() == 0.0 && tj.alpha() == 0.0 {
        return false;
    }
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

/// From the seventeenth revision, the velocities of two touching discs
/// (`u`, masses `m`, unit normal `n` from `j` to `i`) that part along `n`
/// so slowly that the braking pressing them together (their accelerations
/// `acc` at `now`) brings them back into contact within the rounding of
/// the time `now`: their normal velocities made one (the plastic hit that
/// comes then, taken now, momentum kept and the energy of their relative
/// normal motion spent), so that the pair is the pushed pair it is.
/// Left apart, the contact is found again at `now` (its time falls on the
/// same number) while the pair still parts, and nothing changes, hit after
/// hit. `None` where the pair does not part, or its braking does not bring
/// it back within the rounding of `now`.
pub(crate) fn rejoined_at_once(
    u: [DVec2; 2],
    acc: [DVec2; 2],
    m: [f64; 2],
    n: DVec2,
    now: f64,
) -> Option<[DVec2; 2]> {
    let parting = (u[0] - u[1]).dot(n);
    let closing = -(acc[0] - acc[1]).dot(n);
    if !(parting > 0.0 && closing > 0.0) {
        return None;
    }
    // Back in contact after twice the time its braking takes to stop the
    // parting.
    let back = 2.0 * parting / closing;
    if now + back != now {
        return None;
    }
    let (w_i, w_j) = impulse::weights(m[0], m[1]);
    Some([u[0] - n * (parting * w_j), u[1] + n * (parting * w_i)])
}

/// The common velocity (mass-weighted, so momentum is kept) and braking of
/// two discs pushed together, from their velocities `v`, masses `m` and
/// own brakings `alpha` (`mu g`).
pub(crate) fn together(v: [DVec2; 2], m: [f64; 2], alpha: [f64; 2]) -> (DVec2, f64) {
    let (w_i, w_j) = impulse::weights(m[0], m[1]);
    (v[0] * w_i + v[1] * w_j, alpha[0] * w_i + alpha[1] * w_j)
}

/// Separation speed, relative to the speeds of the pair, under which a pair
/// whose braking presses it together is taken to chatter to rest on each
/// other (see [`chatters`]).
pub(crate) const CAPTURE: f64 = 1e-6;

/// Whether the discs on `ti` and `tj`, just hit along `n` (from `j` to
/// `i`), separate so slowly while their braking presses them together that
/// they would bounce again and again, each bounce `e` times slower and
/// sooner than the last: a chatter of infinitely many hits that ends, a
/// finite time `2 w / (a (1 - e))` later (`w` the separation speed, `a` the
/// pressing deceleration), with the pair moving as one. The engine takes
/// that end now, as one plastic hit: the centre of mass moves exactly as
/// in the chatter, and the discs' positions differ from it by at most
/// `w^2 / (a (1 - e))`: at most `w / 2v`, below `CAPTURE / 2`, of the
/// distance the pair slides in the meantime. Without this the last bounces fall below the
/// approach threshold and the discs drift into each other.
///
/// From the third revision (`rev`), a chatter whose next bounce would come
/// within the rounding of the time (late in a long run, where an instant
/// spans microseconds) is taken to its end too, however fast it parts:
/// the rounding of the absolute time, `origin + now` (`origin` the
/// absolute time of working time zero, see `clock`), however finely the
/// working time resolves.
#[inline]
pub(crate) fn chatters(
    ti: &Trajectory,
    tj: &Trajectory,
    n: DVec2,
    now: f64,
    origin: f64,
    rev: Revision,
) -> bool {
    let Some(a) = pressing_deceleration(ti, tj, n, now) else {
        return false;
    };
    let (vi, vj) = (ti.velocity(now), tj.velocity(now));
    let w = (vi - vj).dot(n);
    w <= CAPTURE * (vi.length() + vj.length())
        || (rev.at_least_r3() && next_within_rounding(origin + now, 2.0 * w / -a))
}

/// The deceleration `a < 0` with which the braking of the discs on `ti`
/// and `tj` presses them together along `n` (from `j` to `i`) at `now`,
/// both sliding; `None` where it does not. Cheapest test first: without
/// braking (frictionless pairs, Galperin's billiard) nothing else is
/// looked at.
#[inline]
fn pressing_deceleration(ti: &Trajectory, tj: &Trajectory, n: DVec2, now: f64) -> Option<f64> {
    if ti.alpha() == 0.0 && tj.alpha() == 0.0 {
        return None;
    }
    let a = (ti.acceleration(now) - tj.acceleration(now)).dot(n);
    if !(a < 0.0) || !ti.is_moving_at(now) || !tj.is_moving_at(now) {
        return None;
    }
    Some(a)
}

/// From the thirteenth revision, whether the discs on `ti` and `tj`, just
/// hit along `n` (from `j` to `i`) at contact distance `s` and both sliding
/// along that line (to [`SAME`] of their speeds), are pressed
/// together by their braking so hard for the speed at which they part that
/// the bounce never leaves touching distance: the gap it opens before their
/// braking closes it again, `w^2 / 2a` (`w` the separation speed, `a` the
/// pressing deceleration), is at most half of [`TOUCHING`] of `s` (1e-9 of
/// the contact distance; the engine takes discs that much apart as
/// touching). An elastic pair so pressed (a heavy frictionless disc pushing
/// a light braking one along its line) bounces for ever at the same height,
/// `w` kept by every hit: 4.5 million hits, 1.7e-7 s apart, for a disc at
/// 1.9e-2 m/s. Taken as the chatter's end (one plastic hit, see
/// [`chatters`]), the pair moves as one; its positions differ from the
/// bouncing ones by at most that gap, its centre of mass moves exactly as
/// in the bouncing, and the energy of the relative motion, `m w^2 / 2` with
/// `m` the pair's reduced mass, is lost.
#[inline]
pub(crate) fn bounces_within_touch(
    ti: &Trajectory,
    tj: &Trajectory,
    n: DVec2,
    s: f64,
    now: f64,
) -> bool {
    let Some((a, w, _)) = head_on_bounce(ti, tj, n, now) else {
        return false;
    };
    w * w <= TOUCHING * s * -a
}

/// The pressing deceleration `a` (see [`pressing_deceleration`]), the
/// separation speed `w` along `n` and the velocities at `now` of a pair
/// pressed together by its braking and sliding head-on: both along the
/// line of centres, to [`SAME`] of their speeds (an oblique pair turns as
/// it slides, and is the pressing kick's). `None` otherwise.
fn head_on_bounce(
    ti: &Trajectory,
    tj: &Trajectory,
    n: DVec2,
    now: f64,
) -> Option<(f64, f64, [DVec2; 2])> {
    let a = pressing_deceleration(ti, tj, n, now)?;
    let (vi, vj) = (ti.velocity(now), tj.velocity(now));
    let along = |v: DVec2| v.perp_dot(n).abs() <= SAME * v.length();
    if !along(vi) || !along(vj) {
        return None;
    }
    Some((a, (vi - vj).dot(n), [vi, vj]))
}

/// From the fifteenth revision, whether an elastic pair just hit along `n`
/// (from `j` to `i`) at contact distance `s`, both sliding along that line
/// (to [`SAME`] of their speeds) and pressed together by their braking, is
/// at the start of a long train of bounces within the pressing contact's
/// own gap: its bounce, `w^2 / 2a` high (`w` the separation speed, `a` the
/// pressing deceleration), stays within [`press_gap`] of `s`, and the pair
/// would bounce at least [`LONG_BOUNCES`] times before it stops. An elastic
/// pair so pressed keeps `w` at every hit (the relative motion is a bounce
/// of constant height and period `2 w / a`), while its centre of mass
/// brakes at the mass-weighted mean of the two brakings `A`, exactly as
/// a pushed pair's does; it stops after `V / A` (`V` its speed), so that
/// it bounces `V a / (2 w A)` times. A heavy frictionless elastic disc
/// pushing a light braking elastic one along the floor at 0.28 m/s, its
/// bounce 1.5e-10 m high (6.6e-9 of the contact distance, above the
/// thirteenth revision's 1e-9), made 170,000 hits 1.56e-5 s apart. Taken
/// as the chatter's end (one plastic hit), the pair moves as one: its
/// centre of mass as in the bouncing, each disc within the bounce's
/// height of its bouncing place, and the relative motion's energy, `m w^2
/// / 2` of the reduced mass `m`, is lost. `m` are the masses.
pub(crate) fn bounces_long_within_gap(
    ti: &Trajectory,
    tj: &Trajectory,
    m: [f64; 2],
    n: DVec2,
    s: f64,
    now: f64,
    rev: Revision,
) -> bool {
    let Some((a, w, [vi, vj])) = head_on_bounce(ti, tj, n, now) else {
        return false;
    };
    if !(w > 0.0) || w * w > 2.0 * -a * press_gap(rev) * s {
        return false;
    }
    let (v, braking) = together([vi, vj], m, [ti.alpha(), tj.alpha()]);
    // Bounces before the pair stops: its slide time over the period.
    v.length() * -a >= LONG_BOUNCES * 2.0 * w * braking
}

/// Least number of bounces before a pressed elastic pair stops for which
/// [`bounces_long_within_gap`] takes their train as one push: a tenth of
/// the hostile runner's event cap, far beyond any train that ends by
/// itself in a game.
pub(crate) const LONG_BOUNCES: f64 = 1e4;

/// Whether a bounce `dt` after a hit at absolute time `at` falls within the
/// rounding of that time (see [`same_instant`]): a pressed pair that
/// bounces so fast has come to rest for all a reported time can show.
/// It is the absolute time that decides, not the working time the hit was
/// computed in: from the seventh revision the world's clock moves its
/// origin up to the latest event (see `clock`), and measured from there
/// every bounce, however fast, would lie beyond the rounding, so that a
/// pressed pair whose bounces come ever faster (a disc held between a
/// wall and a braking one) would never be let come to rest and would end
/// the run `stuck`. Before the seventh revision the origin is zero and the
/// working time is the absolute time.
#[inline]
pub(crate) fn next_within_rounding(at: f64, dt: f64) -> bool {
    same_instant(at, at + dt)
}

/// Largest gap, as a fraction of the contact distance, that the
/// approximated oblique pressing contact (see [`pressing_kick`]) opens
/// between two discs, the bound on its position error, up to the fifth
/// revision.
pub(crate) const PRESS_GAP: f64 = 1e-6;

/// The same bound from the sixth revision: 3 micrometres between two
/// checkers. The pair bounces `sqrt(|g2| / (8 gap s))` times a second, so
/// the wider gap costs a tenth of the events: a disc wedged between a
/// heavy one sliding past and a wall, pressed for seconds, took 141,258
/// events with the narrow gap and 18,741 with this one, and came to rest
/// 0.6 mm (0.008 of its radius) from where the narrow gap leaves it.
pub(crate) const WIDE_PRESS_GAP: f64 = 1e-4;

/// The gap bound of the pressing contact under `rev`.
pub(crate) fn press_gap(rev: Revision) -> f64 {
    if rev.at_least_r6() {
        WIDE_PRESS_GAP
    } else {
        PRESS_GAP
    }
}

/// Largest separation speed the approximated pressing contact gives a pair,
/// as a fraction of the sum of their speeds: it never sets slow discs in
/// motion (the kinetic energy it adds is at most `PRESS_SPEED^2` of
/// theirs), and a pair bounces at most about `1 / (2 PRESS_SPEED)` times
/// before it stops.
pub(crate) const PRESS_SPEED: f64 = 0.05;

/// The most kinetic energy the pressing kick between a pair alone adds, as
/// a fraction of the pair's: `m w^2 / 2` of its reduced mass `m` with `w`
/// at most [`PRESS_SPEED`] of the sum of their speeds `a + b`, and
/// `m (a + b)^2 <= 2 m (a^2 + b^2) <= 4` times their energy (`m` is below
/// either mass), so at most `2 PRESS_SPEED^2`.
pub(crate) const PRESS_GAIN: f64 = 2.0 * PRESS_SPEED * PRESS_SPEED;

/// From the twelfth revision, the most kinetic energy a pressing kick over
/// a cluster adds, as a fraction of the scene's (see
/// `World::press_cluster`): twice the bound of a pair alone,
/// [`PRESS_GAIN`], for the kick parts the pair hit and, from the fourth
/// revision, the pairs its projection leaves pressed. Held to a fraction
/// of the cluster's own energy instead, the kicks of a pair pressed for
/// seconds in a cluster, each a few per cent of the cluster's energy and
/// far less of the scene's, parted it so slowly that runs which reached
/// their horizon under the eleventh revision ran into the event cap.
pub(crate) const CLUSTER_PRESS_GAIN: f64 = 2.0 * PRESS_GAIN;

/// Two discs pressed together obliquely: the separation speed to add to a
/// hit between them, or `None` where the model is exact.
///
/// Touching discs whose braking presses them together (the second
/// derivative of their gap, `g2 = (a_i - a_j) . n + |v_t|^2 / s`, is
/// negative with the relative normal velocity zero) slide along each other
/// and turn: a motion with no closed form. Along the line of centres it is
/// exact ([`pushing`], [`pooled`]); elsewhere the engine approximates it
/// by keeping the pair bouncing: every hit between them leaves them
/// separating at no less than `w = sqrt(2 |g2| PRESS_GAP s)`, so they meet
/// again `2 w / |g2|` later, each time exactly, and never overlap (`w` is
/// at most [`PRESS_SPEED`] of their speeds). The gap
/// between hits stays below `w^2 / (2 |g2|) <= PRESS_GAP s`, the contact
/// force averaged over a bounce is the pressing force, and the kinetic
/// energy added is at most `m w^2 / 2` of the pair's reduced mass `m` (once
/// per pressing episode: the bounces themselves are elastic). `vi`, `vj`
/// are the velocities after the hit, `ai`, `aj` the accelerations, `n` the
/// unit normal from `j` to `i`, `s` the contact distance, `at` the absolute
/// time of the hit (see [`next_within_rounding`]).
pub(crate) fn pressing_kick(
    [vi, vj]: [DVec2; 2],
    [ai, aj]: [DVec2; 2],
    n: DVec2,
    s: f64,
    at: f64,
    rev: Revision,
) -> Option<Press> {
    let (w, w_min, g2) = pressing([vi, vj], [ai, aj], n, s, rev)?;
    if w >= w_min {
        return None;
    }
    // From the third revision: a pair that would slide no further than the
    // approximation's own gap before it stops comes to rest here. Below
    // that, bounces capped at `PRESS_SPEED` of the speeds come ever faster
    // (their number grows as the log of the speed) for nothing a position
    // can show beyond the gap.
    if rev.at_least_r3() {
        let slide = |v: DVec2, a: DVec2| v.length_squared() / (2.0 * a.length());
        if slide(vi, ai).max(slide(vj, aj)) <= press_gap(rev) * s {
            return Some(Press::Rest);
        }
    }
    // So slow that the next bounce would fall within the rounding of the
    // time: the pair comes to rest here (it would within that time anyway).
    if next_within_rounding(at, 2.0 * w_min / -g2) {
        return Some(Press::Rest);
    }
    Some(Press::Part(w_min - w.max(0.0)))
}

/// The bounce speed of two touching discs pressed together obliquely (the
/// `w` of [`pressing_kick`], whatever they do now), or `None` where they
/// do not press or the model is exact.
pub(crate) fn bounce_speed(
    v: [DVec2; 2],
    a: [DVec2; 2],
    n: DVec2,
    s: f64,
    rev: Revision,
) -> Option<f64> {
    pressing(v, a, n, s, rev).map(|(_, w_min, _)| w_min)
}

/// From the eleventh revision: whether a pressed pair's kinetic energy
/// (velocities `v` after the hit, masses `m`) is no more than the braking of
/// each of its braking discs (decelerations `alpha`, zero for a frictionless
/// one) dissipates over the approximation's gap: friction being the only
/// thing that takes energy out of the pair, no braking disc of it can then
/// slide further than the gap, whatever a frictionless partner does. The
/// third revision's test (each disc's own slide within the gap) never holds
/// for a frictionless disc, whose slide is unbounded; this one does where a
/// heavy frictionless disc slowly presses a light braking one. `false`
/// where neither brakes.
pub(crate) fn spent_within_gap(
    v: [DVec2; 2],
    m: [f64; 2],
    alpha: [f64; 2],
    s: f64,
    rev: Revision,
) -> bool {
    let energy = pair_energy(v, m);
    let weakest = (0..2)
        .filter(|&k| alpha[k] > 0.0)
        .map(|k| m[k] * alpha[k])
        .fold(f64::INFINITY, f64::min);
    weakest.is_finite() && energy <= weakest * press_gap(rev) * s
}

/// From the fourteenth revision: a pressed pair taken as one sliding body
/// where a disc `H` slides nearly past a strongly braked one `L` and has to
/// wedge it aside (see `World::carried_press`). `v` are the velocities just
/// after a plastic hit along `n` (unit, from `j` to `i`; both share their
/// component along it), `m` the masses, `alpha` the own brakings (`mu g`),
/// `s` the contact distance. `L` is the disc that brakes harder, `H` the
/// other, and `L` must move along the normal only (it was at rest, or
/// moved along the line of centres), towards where `H` drives it, and at
/// most a tenth of `H`'s mass.
///
/// Pushed by the contact alone, `L` (whose inertia is negligible against
/// the contact force) moves along the line of centres at the speed that
/// keeps it touching, while `H` keeps its line: `L` follows the tractrix
/// of `H`'s path, the angle `theta` between `H`'s direction and the normal
/// growing as `tan(theta / 2) = tan(theta0 / 2) e^(y / s)` with `H`'s
/// travel `y`, and the friction of `L` takes `F s ln(sin theta /
/// sin theta0)` out of the pair (`F = m_L alpha_L`), `H`'s own braking
/// `m_H alpha_H y`. Where that work reaches the pair's kinetic energy
/// before `H` has passed (`theta` reaches a right angle), `H` stops there,
/// at `y*`: both are given that stop, `H` along its line with the uniform
/// deceleration that ends it at `y*`, `L` along the normal with the
/// normal share of `H`'s velocity, decelerating to rest at the same moment.
/// `L` then moves by the projection of `H`'s travel on the normal, so
/// that the two only part (their distance grows as the tangential part of
/// that travel), never overlap, and no energy is added: both only slow
/// down. `L` is moved a little further than the tractrix takes it (its
/// final position off by at most `y*^2 / 2 s`). The pair then does in two
/// trajectories what the approximated pressing contact did in thousands
/// of bounces, each capped at [`PRESS_SPEED`] of their speeds, `L`
/// stopping between them. Where `H` has the energy to pass, it pays the
/// whole tractrix's friction `F s ln(1 / sin theta0)` at once and keeps
/// its own braking, and `L` is carried ahead along the normal, starting at
/// twice the normal share of `H`'s velocity and decelerating to rest just
/// as `H` passes, again by the projection of `H`'s travel or more (only
/// where that adds no energy, leaves `L` out of `H`'s way and carries it
/// beyond the gap the pressing contact keeps). `None`
/// where the pair does not press obliquely, the bounce is not capped, or
/// the shape does not fit; else the velocities and decelerations of `i`
/// and `j`.
pub(crate) fn carried(
    [vi, vj]: [DVec2; 2],
    m: [f64; 2],
    alpha: [f64; 2],
    n: DVec2,
    s: f64,
    rev: Revision,
) -> Option<[(DVec2, f64); 2]> {
    // `L` brakes harder; the normal from `H` to `L`.
    let l = usize::from(alpha[1] > alpha[0]);
    let h = 1 - l;
    if !(alpha[l] > alpha[h]) {
        return None;
    }
    let v = [vi, vj];
    let to_l = if l == 0 { n } else { -n };
    let (vh, vl) = (v[h], v[l]);
    let speed = vh.length();
    let c = vh.dot(to_l);
    if !(alpha[l] > 0.0 && speed > 0.0 && c > 0.0 && c < speed) {
        return None;
    }

    // `L` carried along the normal only, at `H`'s normal speed.
    if (vl - to_l * c).length() > SAME * speed {
        return None;
    }
    // Pressed obliquely, with the bounce of the approximated contact capped
    // by its speeds (the chatter this takes at once).
    let acc = [
        -alpha[0] * vi.normalize_or_zero(),
        -alpha[1] * vj.normalize_or_zero(),
    ];
    let (_, w_min, g2) = pressing(v, acc, n, s, rev)?;
    if w_min * w_min >= 2.0 * -g2 * press_gap(rev) * s {
        return None;
    }
    let cos0 = c / speed;
    let sin0 = (1.0 - cos0 * cos0).sqrt();
    if !(sin0 >= CARRIED_SINE) {
        return None;
    }
    // ln tan(theta0 / 2), negative below a right angle.
    let psi0 = (sin0 / (1.0 + cos0)).ln();
    let (force, own) = (m[l] * alpha[l], m[h] * alpha[h]);
    let work = |y: f64| own * y + force * s * (psi0.cosh() / (psi0 + y / s).cosh()).ln();
    let pass = -psi0 * s;
    let energy = pair_energy(v, m);
    if !(pass > 0.0) {
        return None;
    }
    let mut out = [(DVec2::ZERO, 0.0); 2];
    if energy >= work(pass) {
        // `H` passes: it pays the friction of `L` along the whole tractrix
        // at once, `L` is carried ahead of it along the normal and stops
        // when `H` has passed, `H` keeping its own braking.
        let lost = force * s * psi0.cosh().ln();
        let passing = speed * speed - 2.0 * lost / m[h];
        if !(passing > 2.0 * alpha[h] * pass) {
            return None;
        }
        let passing = passing.sqrt();
        let duration = 2.0 * pass / (passing + (passing * passing - 2.0 * alpha[h] * pass).sqrt());
        let ahead = pass * cos0;
        // A pass that moves `L` no further than the gap the pressing
        // contact keeps (a grazing one, `s cos^2 theta0`) is its bounces'.
        if !(ahead > press_gap(rev) * s) {
            return None;
        }
        let carried = 2.0 * ahead / duration;
        // Never closer than the contact distance once `L` rests, and no
        // energy gained.
        let after = 0.5 * (m[h] * passing * passing + m[l] * carried * carried);
        if !((s + ahead) * sin0 >= s && after <= energy) {
            return None;
        }
        out[h] = (vh * (passing / speed), alpha[h]);
        out[l] = (to_l * carried, carried / duration);
        return Some(out);
    }
    let stop = spent_at(work, energy, pass);
    if !(stop > 0.0) {
        return None;
    }
    // Both stop together after `2 y* / |v_H|`.
    let duration = 2.0 * stop / speed;
    out[h] = (vh, speed / duration);
    out[l] = (vl, c / duration);
    Some(out)
}

/// Where `work`, growing on `[0, pass]`, spends `energy`: the upper end
/// of the bracket [`CARRY_BISECTIONS`] bisections (or the rounding of a
/// double) leave, so that the work there is at least the energy. The
/// pushing disc's stop in a carry (`carried`, `wedge::carried_along_wall`).
pub(crate) fn spent_at(work: impl Fn(f64) -> f64, energy: f64, pass: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, pass);
    for _ in 0..CARRY_BISECTIONS {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if work(mid) < energy {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hi
}

/// Least sine of the angle between the pushing disc's direction and the
/// normal for which [`carried`] takes a pair: nearer the line of centres
/// the two part sideways by less than rounding noise over the whole
/// carry, and the pair, left touching, is hit again at once.
const CARRIED_SINE: f64 = 1e-3;

/// From the fifteenth revision: the plastic hit of a pair (velocities `u`
/// before it, masses `m`, unit normal `n` from `j` to `i`) where disc `h`
/// (0 for `i`, 1 for `j`) slides along an obstacle (unit normal `wall`,
/// pointing from it to the disc) and the hit would drive it into it. The
/// obstacle holds `h` to its line: its normal force takes the part of the
/// contact force across it at once, as the sustained contact of a disc
/// pushed along a wall does, instead of a second hit a moment later. So
/// `h` moves along the obstacle only (the tangent `tau`), and the impulse
/// `J` along `n` that stops the pair's approach is `w / (1 / m_l + (n .
/// tau)^2 / m_h)` (`w` the approach): a plastic impact with a workless
/// constraint, which keeps the momentum along the obstacle and adds no
/// energy. `None` where `h` does not slide along the obstacle (to [`SAME`]
/// of its speed) or the pair does not approach.
pub(crate) fn plastic_along_wall(
    u: [DVec2; 2],
    m: [f64; 2],
    h: usize,
    n: DVec2,
    wall: DVec2,
) -> Option<[DVec2; 2]> {
    let l = 1 - h;
    if u[h].dot(wall).abs() > SAME * u[h].length() {
        return None;
    }
    // The normal from `h` to `l`, and the approach along it.
    let to_l = if l == 0 { n } else { -n };
    let approach = (u[h] - u[l]).dot(to_l);
    if !(approach > 0.0) {
        return None;
    }
    let tau = wall.perp();
    let along = to_l.dot(tau);
    let impulse = approach / (1.0 / m[l] + along * along / m[h]);
    let mut v = u;
    v[h] = tau * (u[h].dot(tau) - impulse * along / m[h]);
    v[l] = u[l] + to_l * (impulse / m[l]);
    Some(v)
}

/// Most bisection steps [`carried`] takes to find where a pushing disc
/// stops (each halves the interval; 64 reach the rounding of a double).
const CARRY_BISECTIONS: usize = 64;

/// The kinetic energy of a pair (velocities `v`, masses `m`).
pub(crate) fn pair_energy(v: [DVec2; 2], m: [f64; 2]) -> f64 {
    0.5 * (m[0] * v[0].length_squared() + m[1] * v[1].length_squared())
}

/// The relative normal velocity, the bounce speed and the gap's second
/// derivative of a pair pressed obliquely (see [`pressing_kick`]).
fn pressing(
    [vi, vj]: [DVec2; 2],
    [ai, aj]: [DVec2; 2],
    n: DVec2,
    s: f64,
    rev: Revision,
) -> Option<(f64, f64, f64)> {
    let dv = vi - vj;
    let w = dv.dot(n);
    let vt = dv - n * w;
    let g2 = (ai - aj).dot(n) + vt.length_squared() / s;
    if !(g2 < 0.0) {
        return None;
    }
    // Along the line of centres with one velocity: the exact pushing model.
    let (speed_i, speed_j) = (vi.length(), vj.length());
    let speed = speed_i.max(speed_j);
    if vt.length() <= SAME * speed && vi.perp_dot(n).abs() <= SAME * speed {
        return None;
    }
    let w_min = (2.0 * -g2 * press_gap(rev) * s)
        .sqrt()
        .min(PRESS_SPEED * (speed_i + speed_j));
    Some((w, w_min, g2))
}

/// What the approximated pressing contact does to a pair (see
/// [`pressing_kick`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Press {
    /// Add this separation speed along the normal, momentum kept.
    Part(f64),
    /// Both come to rest: their next bounce would fall within the rounding
    /// of the time (they move less than a rounding of their positions).
    Rest,
}

/// One disc of a pushing chain: its velocity, mass and own braking.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Part {
    pub vel: DVec2,
    pub mass: f64,
    pub alpha: f64,
}

/// The velocity and braking of each disc of a chain (given from rear to
/// front) once its pushing blocks are joined: the pool-adjacent-violators
/// solution, so braking never increases from rear to front. Two discs
/// give exactly what [`together`] gives when they push, and their own
/// motion when they do not.
pub(crate) fn pooled(parts: &[Part]) -> Vec<(DVec2, f64)> {
    // Each block: index of its first part, mass, velocity and braking.
    let mut blocks: Vec<(usize, f64, DVec2, f64)> = Vec::with_capacity(parts.len());
    for (k, p) in parts.iter().enumerate() {
        blocks.push((k, p.mass, p.vel, p.alpha));
        while let [.., rear, front] = blocks[..] {
            if !(rear.3 < front.3) {
                break;
            }
            let (w_r, w_f) = impulse::weights(rear.1, front.1);
            let joined = (
                rear.0,
                rear.1 + front.1,
                rear.2 * w_r + front.2 * w_f,
                rear.3 * w_r + front.3 * w_f,
            );
            blocks.pop();
            if let Some(last) = blocks.last_mut() {
                *last = joined;
            }
        }
    }
    let mut out = Vec::with_capacity(parts.len());
    for (b, &(first, _, v, a)) in blocks.iter().enumerate() {
        let end = blocks.get(b + 1).map_or(parts.len(), |x| x.0);
        out.extend((first..end).map(|_| (v, a)));
    }
    out
}

/// The velocities of a chain of touching discs on one line (given from
/// rear to front along `u`) after a plastic impact of the whole chain at
/// once: wherever a rear disc moves faster along `u` than the disc in
/// front, the two move as one with their momentum-weighted mean velocity,
/// pooled again until velocities never decrease from rear to front (the
/// same pool-adjacent-violators construction as [`pooled`]). This is the
/// limit of an endless sequence of ever slower inelastic hits at one
/// instant (an inelastic collapse).
pub(crate) fn plastic(parts: &[Part], u: DVec2) -> Vec<DVec2> {
    let mut blocks: Vec<(usize, f64, DVec2)> = Vec::with_capacity(parts.len());
    for (k, p) in parts.iter().enumerate() {
        blocks.push((k, p.mass, p.vel));
        while let [.., rear, front] = blocks[..] {
            if !(rear.2.dot(u) > front.2.dot(u)) {
                break;
            }
            let (w_r, w_f) = impulse::weights(rear.1, front.1);
            let joined = (rear.0, rear.1 + front.1, rear.2 * w_r + front.2 * w_f);
            blocks.pop();
            if let Some(last) = blocks.last_mut() {
                *last = joined;
            }
        }
    }
    let mut out = Vec::with_capacity(parts.len());
    for (b, &(first, _, v)) in blocks.iter().enumerate() {
        let end = blocks.get(b + 1).map_or(parts.len(), |x| x.0);
        out.extend((first..end).map(|_| v));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sliding(x: f64, vx: f64, alpha: f64) -> Trajectory {
        Trajectory::new(0.0, DVec2::new(x, 0.0), DVec2::new(vx, 0.0), alpha)
    }

    #[test]
    fn an_elastic_bounce_train_is_long_only_within_the_press_gap_and_above_ten_thousand_bounces() {
        // Mixed-box 84063: a heavy frictionless elastic disc (0.122 kg)
        // pushing a light one (2.72 g, braking at 5.058 m/s^2) along the
        // floor, the pair parting at 3.93e-5 m/s at every hit, contact
        // distance 0.0232 m (n from the front disc `j` to the rear `i`).
        let (s, m) = (0.0232, [0.1224, 2.72e-3]);
        let n = DVec2::new(-1.0, 0.0);
        let long = |v: f64, w: f64| {
            let rear = sliding(-s, v, 0.0);
            let front = sliding(0.0, v + w, 5.058);
            bounces_long_within_gap(&rear, &front, m, n, s, 0.0, Revision::R15)
        };
        // At 0.28 m/s the pair, braking at 0.11 m/s^2, bounces about
        // 164,000 times before it stops; at 5e-3 m/s about 2,900.
        assert!(long(0.28, 3.93e-5));
        assert!(!long(5e-3, 3.93e-5));
        // The bounce within the pressing gap (1e-4 of the contact
        // distance), reached near 4.84e-3 m/s, however long the train.
        assert!(long(100.0, 4.7e-3));
        assert!(!long(100.0, 5.0e-3));
        // Not a pair that approaches, nor a frictionless pair.
        assert!(!long(0.28, -3.93e-5));
        let free = sliding(0.0, 0.28 + 3.93e-5, 0.0);
        let rear = sliding(-s, 0.28, 0.0);
        assert!(!bounces_long_within_gap(
            &rear,
            &free,
            m,
            n,
            s,
            0.0,
            Revision::R15
        ));
    }

    #[test]
    fn a_plastic_hit_along_a_wall_stops_the_approach_keeps_the_pusher_on_the_wall_and_adds_no_energy(
    ) {
        // Mixed-box 466219: a heavy frictionless disc (0.93 kg) sliding
        // along the floor at 1.09e-4 m/s hits a light one (1.06 g) above
        // and ahead of it (the normal `n` from the heavy disc `j` to the
        // light one `i`, up and forward).
        let to_light = DVec2::new(0.21, 0.978).normalize();
        let (n, wall, m) = (to_light, DVec2::new(0.0, 1.0), [1.06e-3, 0.93]);
        let u = [DVec2::ZERO, DVec2::new(1.09e-4, 0.0)];
        let v = plastic_along_wall(u, m, 1, n, wall).expect("sliding along the floor");
        // The pusher stays on the floor, the approach is gone, momentum
        // along the floor is kept and no energy is added.
        assert_eq!(v[1].y, 0.0);
        assert!((v[0] - v[1]).dot(n).abs() <= 1e-15 * u[1].length());
        let along = |v: [DVec2; 2]| m[0] * v[0].x + m[1] * v[1].x;
        assert!((along(v) - along(u)).abs() <= 1e-15 * along(u));
        assert!(pair_energy(v, m) <= pair_energy(u, m));
        // The free plastic hit would have driven it into the floor.
        let (_, free) = impulse::body_body(u[0], u[1], m[0], m[1], 0.0, n);
        assert!(free.y < 0.0);
        // Not where the pusher moves off the floor's line, nor where the
        // pair does not approach.
        let lifted = [DVec2::ZERO, DVec2::new(1.09e-4, 1e-6)];
        assert!(plastic_along_wall(lifted, m, 1, n, wall).is_none());
        let parting = [to_light * 1e-4, DVec2::new(1.09e-4, 0.0)];
        assert!(plastic_along_wall(parting, m, 1, n, wall).is_none());
    }

    #[test]
    fn a_pressed_bounce_counts_as_touching_only_while_it_stays_within_touching_distance() {
        // Mixed-box 205984: a light braking disc (1.63 m/s^2) just sent
        // ahead of a frictionless one at 1.4e-7 m/s along the line of
        // centres (n from the front disc `j` to the rear one `i`, so the
        // pair parts at `w = (vi - vj) . n`), contact distance 0.029 m:
        // a bounce 6e-15 m high, 2e-13 of the contact distance.
        let s = 0.0292;
        let n = DVec2::new(-1.0, 0.0);
        let rear = sliding(-s, 1.858e-2, 0.0);
        let front = |w: f64| sliding(0.0, 1.858e-2 + w, 1.63);
        assert!(bounces_within_touch(&rear, &front(1.4e-7), n, s, 0.0));
        // The bounce height grows as the square of the speed: 1e-9 of the
        // contact distance is reached near 9.8e-6 m/s.
        assert!(bounces_within_touch(&rear, &front(9.0e-6), n, s, 0.0));
        assert!(!bounces_within_touch(&rear, &front(1.1e-5), n, s, 0.0));
        // Nothing presses a pair whose front disc brakes less, or a
        // frictionless pair.
        let free = sliding(0.0, 1.858e-2 + 1.4e-7, 0.0);
        assert!(!bounces_within_touch(&rear, &free, n, s, 0.0));
        let braking_rear = sliding(-s, 1.858e-2, 1.63);
        assert!(!bounces_within_touch(&braking_rear, &free, n, s, 0.0));
        // Nor an oblique pair, which turns as it slides: the same discs
        // sliding 30 degrees off their line of centres.
        let turn = |v: f64| DVec2::new(v * 0.75f64.sqrt(), v * 0.5);
        let oblique =
            |v: f64, x: f64, alpha: f64| Trajectory::new(0.0, DVec2::new(x, 0.0), turn(v), alpha);
        let (rear, front) = (
            oblique(1.858e-2, -s, 0.0),
            oblique(1.858e-2 + 1.4e-7, 0.0, 1.63),
        );
        assert!(!bounces_within_touch(&rear, &front, n, s, 0.0));
    }

    #[test]
    fn a_slow_frictionless_disc_cannot_push_a_braking_one_beyond_the_gap() {
        // A heavy frictionless disc (0.58 kg) at 2.7e-6 m/s against a light
        // braking one (5.6 g, 5.7 m/s^2): 2.1e-12 J against 3.2e-2 N over
        // 1e-4 of a contact distance of 0.024 m (7.7e-8 J).
        let v = [DVec2::new(-1.5e-7, 0.0), DVec2::new(0.0, -2.7e-6)];
        let (m, alpha) = ([0.0056, 0.577], [5.69, 0.0]);
        assert!(spent_within_gap(v, m, alpha, 0.0242, Revision::R11));
        // A hundred times faster (10^4 the energy) is still within it; a
        // thousand times more again is not.
        let fast = [v[0], v[1] * 100.0];
        assert!(spent_within_gap(fast, m, alpha, 0.0242, Revision::R11));
        let faster = [v[0], v[1] * 1e5];
        assert!(!spent_within_gap(faster, m, alpha, 0.0242, Revision::R11));
    }

    #[test]
    fn a_pair_with_no_braking_disc_is_never_spent_within_the_gap() {
        let v = [DVec2::ZERO, DVec2::new(1e-20, 0.0)];
        assert!(!spent_within_gap(
            v,
            [1.0, 1.0],
            [0.0, 0.0],
            0.02,
            Revision::R11
        ));
    }

    #[test]
    fn the_lightest_braking_disc_of_the_pair_bounds_its_energy() {
        // Two braking discs: the one with the smaller m alpha decides.
        let v = [DVec2::new(1e-3, 0.0), DVec2::ZERO];
        // 0.5 * 1 * 1e-6 = 5e-7 J; 1e-4 * 0.02 = 2e-6 m: needs m alpha >= 0.25 N.
        assert!(spent_within_gap(
            v,
            [1.0, 1.0],
            [1.0, 0.3],
            0.02,
            Revision::R11
        ));
        assert!(!spent_within_gap(
            v,
            [1.0, 1.0],
            [1.0, 0.2],
            0.02,
            Revision::R11
        ));
    }

    #[test]
    fn a_pressed_pair_rests_when_its_next_bounce_is_within_the_rounding_of_the_absolute_time() {
        // A frictionless disc sliding past a braking one that presses it
        // (1 m/s^2 along their normal): its next bounce is 1e-13 s away.
        let (v, a) = (
            [DVec2::new(0.0, 1e-12), DVec2::ZERO],
            [DVec2::ZERO, DVec2::X],
        );
        let kick = |at: f64| pressing_kick(v, a, DVec2::X, 0.04, at, Revision::R7);
        assert_eq!(kick(1.0), Some(Press::Rest), "within the rounding at 1 s");
        assert!(
            matches!(kick(1e-9), Some(Press::Part(_))),
            "beyond the rounding at 1 ns: it bounces"
        );
        assert!(next_within_rounding(1.0, 1e-13));
        assert!(!next_within_rounding(1e-9, 1e-13));
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

    fn part(alpha: f64, mass: f64) -> Part {
        Part {
            vel: DVec2::new(1.0, 0.0),
            mass,
            alpha,
        }
    }

    #[test]
    fn a_chain_braking_more_towards_the_front_moves_as_one() {
        let out = pooled(&[part(0.981, 1.0), part(1.962, 1.0), part(2.943, 1.0)]);
        assert_eq!(out.len(), 3);
        assert!(out.iter().all(|&x| x == out[0]));
        assert!((out[0].1 - 1.962).abs() < 1e-15);
    }

    #[test]
    fn a_chain_splits_where_the_front_brakes_less() {
        // Rear pair presses (0.1 < 0.5); the front disc (0.2) runs away.
        let out = pooled(&[part(0.1, 1.0), part(0.5, 1.0), part(0.2, 1.0)]);
        assert_eq!(out[0], out[1]);
        assert!((out[0].1 - 0.3).abs() < 1e-15);
        assert_eq!(out[2].1, 0.2);
        // Braking never grows from rear to front.
        let out = pooled(&[
            part(0.4, 2.0),
            part(0.1, 1.0),
            part(0.3, 1.0),
            part(0.35, 3.0),
        ]);
        assert!(out.windows(2).all(|w| w[0].1 >= w[1].1), "{out:?}");
    }

    #[test]
    fn a_pushing_pair_pools_exactly_as_together() {
        let (a, b) = (part(0.2, 1.0), part(0.6, 3.0));
        let out = pooled(&[a, b]);
        let (v, alpha) = together([a.vel, b.vel], [a.mass, b.mass], [a.alpha, b.alpha]);
        assert_eq!(out, vec![(v, alpha), (v, alpha)]);
        // Not pushing: each keeps its own motion.
        let out = pooled(&[b, a]);
        assert_eq!(out, vec![(b.vel, b.alpha), (a.vel, a.alpha)]);
    }

    #[test]
    fn a_plastic_chain_impact_merges_the_rear_that_runs_into_the_front() {
        let at = |v: f64, mass: f64| Part {
            vel: DVec2::new(v, 0.0),
            mass,
            alpha: 0.0,
        };
        // A striker into two resting discs: all three move on together.
        let out = plastic(&[at(3.0, 1.0), at(0.0, 1.0), at(0.0, 1.0)], DVec2::X);
        assert!(
            out.iter().all(|v| (v.x - 1.0).abs() < 1e-15 && v.y == 0.0),
            "{out:?}"
        );
        // A front disc already faster runs away untouched.
        let out = plastic(&[at(2.0, 1.0), at(0.0, 3.0), at(5.0, 1.0)], DVec2::X);
        assert!(
            (out[0].x - 0.5).abs() < 1e-15 && out[0] == out[1],
            "{out:?}"
        );
        assert_eq!(out[2].x, 5.0);
    }

    /// A light disc `L` at rest (braking `alpha_l`), touching a heavy one
    /// `H` sliding at `vh` with its centre `ahead` along `H`'s line and the
    /// rest across it, just hit plastically by `H`: velocities after the
    /// hit and the normal from `H` to `L` (`L` first, as `i`).
    fn wedged(s: f64, ahead: f64, vh: DVec2, m: [f64; 2]) -> ([DVec2; 2], DVec2) {
        let along = vh.normalize();
        let across = along.perp();
        let n = (along * ahead + across * (s * s - ahead * ahead).sqrt()) / s;
        let (vl, vh) = impulse::body_body(DVec2::ZERO, vh, m[0], m[1], 0.0, n);
        ([vl, vh], n)
    }

    /// The friction `L` meets along its tractrix while `H` travels `y`
    /// from contact angle `theta0` (cosine `cos0`), with `H`'s own braking
    /// force `own` and `L`'s `force`.
    fn tractrix_work(y: f64, cos0: f64, s: f64, own: f64, force: f64) -> f64 {
        let psi0 = ((1.0 - cos0 * cos0).sqrt() / (1.0 + cos0)).ln();
        own * y + force * s * (psi0.cosh() / (psi0 + y / s).cosh()).ln()
    }

    #[test]
    fn a_disc_wedging_a_braking_one_aside_stops_with_it_where_the_tractrix_spends_their_energy() {
        // Mixed-box 587207: heavy frictionless disc 9 (0.936 kg) slides up
        // the left wall at 6.3e-4 m/s past light disc 10 (2.26e-3 kg,
        // 2.943 m/s^2), whose centre lies 1.85 mm ahead of its own.
        let (s, m, alpha) = (0.049, [2.261e-3, 0.9357], [2.943, 0.0]);
        let (v, n) = wedged(s, 1.85e-3, DVec2::new(0.0, 6.3e-4), m);
        let out = carried(v, m, alpha, n, s, Revision::R14).expect("a wedged pair");
        let [(vl, al), (vh, ah)] = out;
        // Both keep the plastic hit's velocities: `L` along the normal at
        // `H`'s normal speed, and both stop at the same moment.
        assert_eq!((vl, vh), (v[0], v[1]));
        assert!(vl.perp_dot(n).abs() <= 1e-15 * vl.length());
        let (stop_l, stop_h) = (vl.length() / al, vh.length() / ah);
        assert!(
            (stop_l - stop_h).abs() <= 1e-12 * stop_h,
            "{stop_l} {stop_h}"
        );
        // `H` stops where `L`'s friction along the tractrix has taken the
        // pair's energy, short of where it would have passed.
        let travel = vh.length_squared() / (2.0 * ah);
        let cos0 = vh.normalize().dot(n);
        let work = tractrix_work(travel, cos0, s, 0.0, m[0] * alpha[0]);
        let energy = pair_energy(v, m);
        assert!(
            (work - energy).abs() <= 1e-9 * energy,
            "{work:e} {energy:e}"
        );
        assert!(travel < 1.85e-3, "{travel}");
    }

    #[test]
    fn a_disc_with_the_energy_to_pass_pays_the_whole_tractrix_and_carries_the_other_ahead() {
        // Mixed-box 134484: heavy frictionless disc 2 (0.896 kg) slides
        // along the floor at 7.9e-4 m/s past light disc 10 (2.02e-3 kg,
        // 2.943 m/s^2), whose centre lies 2.24 mm ahead of its own.
        let (s, m, alpha) = (0.0552, [2.018e-3, 0.8956], [2.943, 0.0]);
        let (v, n) = wedged(s, 2.237e-3, DVec2::new(7.9e-4, 0.0), m);
        let [(vl, al), (vh, ah)] = carried(v, m, alpha, n, s, Revision::R14).expect("passes");
        // `H` keeps its line and its own braking, slower by the whole
        // tractrix's friction.
        assert_eq!(ah, 0.0);
        assert!(vh.perp_dot(v[1]).abs() <= 1e-15 * v[1].length_squared());
        let cos0 = v[1].normalize().dot(n);
        let pass = -((1.0 - cos0 * cos0).sqrt() / (1.0 + cos0)).ln() * s;
        let lost = 0.5 * m[1] * (v[1].length_squared() - vh.length_squared());
        let whole = tractrix_work(pass, cos0, s, 0.0, m[0] * alpha[0]);
        assert!((lost - whole).abs() <= 1e-9 * whole, "{lost:e} {whole:e}");
        // `L` is carried along the normal and rests as `H` passes, never
        // gaining the pair energy.
        assert!(vl.perp_dot(n).abs() <= 1e-15 * vl.length());
        let rests = vl.length() / al;
        assert!((rests * vh.length() - pass).abs() <= 1e-9 * pass);
        assert!(pair_energy([vl, vh], m) <= pair_energy(v, m));
    }

    #[test]
    fn a_pair_pushed_head_on_or_without_a_harder_braked_disc_is_not_carried() {
        let (s, m) = (0.049, [2.261e-3, 0.9357]);
        // Head on: the exact pushing model.
        let v = [DVec2::new(0.0, 6.3e-4); 2];
        let n = DVec2::new(0.0, 1.0);
        assert_eq!(carried(v, m, [2.943, 0.0], n, s, Revision::R14), None);
        // Obliquely, but neither brakes.
        let (v, n) = wedged(s, 1.85e-3, DVec2::new(0.0, 6.3e-4), m);
        assert_eq!(carried(v, m, [0.0, 0.0], n, s, Revision::R14), None);
    }
}
