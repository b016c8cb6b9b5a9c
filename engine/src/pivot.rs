//! A disc wedged around a resting one: from the seventeenth revision, a
//! light disc `L` pressed obliquely by a heavy disc `H` that slides nearly
//! past it and brakes less, where `L` lies against a third disc `P` at
//! rest that the push drives it into. `P`'s friction holds it where it is
//! as long as the push it passes on stays below `m_P alpha_P` (the most
//! friction can take), so `L` can only slide around `P`, just as far as
//! keeps it touching `H`, its friction braking `H`. The pressing contact
//! took this sustained push of a chain of three as a bounce every few
//! microseconds, `P` kicked and stopped and hit again each time, for
//! seconds; here it is taken at once (see [`carried_around`]), as
//! `push::carried` takes a wedged disc that moves freely and
//! `wedge::carried_along_wall` one held by an obstacle.

use crate::push;
use glam::DVec2;

/// Smallest share of the push on `L` along the direction it slides around
/// `P` (the cosine between the normal from `H` and that direction) for
/// which [`carried_around`] takes the chain: below it the contact force
/// that moves `L` grows without bound and `P` no longer holds.
const DRIVEN: f64 = 1e-3;

/// Where a carry around a held disc leaves the pusher and the carried
/// disc: each one's velocity and the uniform deceleration that stops it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Carry {
    pub pusher: (DVec2, f64),
    pub carried: (DVec2, f64),
}

/// The chain's shape: the pusher `H` sliding along its line, the carried
/// disc `L` touching it and the held disc `P`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Chain {
    /// Centres of `H`, `L` and `P`.
    pub at: [DVec2; 3],
    /// `H`'s unit direction of travel.
    pub dir: DVec2,
    /// Contact distances of `H` with `L`, and of `L` with `P`.
    pub reach: [f64; 2],
}

impl Chain {
    /// Where `L` lies, touching `P` and `H` once `H` has travelled `y`
    /// (the intersection of the two circles on `L`'s side of the line
    /// from `P` to `H`), or `None` where the circles no longer meet.
    fn carried_at(&self, y: f64, side: f64) -> Option<DVec2> {
        let [h0, _, p] = self.at;
        let [s1, s2] = self.reach;
        let d = h0 + self.dir * y - p;
        let dist = d.length();
        if !(dist > 0.0) {
            return None;
        }
        let u = d / dist;
        let a = (s2 * s2 - s1 * s1 + dist * dist) / (2.0 * dist);
        let high = s2 * s2 - a * a;
        if !(high >= 0.0) {
            return None;
        }
        Some(p + u * a + u.perp() * (side * high.sqrt()))
    }

    /// Which side of the line from `P` to `H` `L` lies on: `1` or `-1`.
    fn side(&self) -> f64 {
        let [h, l, p] = self.at;
        if (h - p).perp_dot(l - p) >= 0.0 {
            1.0
        } else {
            -1.0
        }
    }
}

/// From the seventeenth revision: the carry of a light disc `L` around a
/// disc `P` at rest, by a disc `H` sliding nearly past `L` and driving it
/// into `P` (see the module). `chain` gives the shape (`H`'s direction
/// `d`, that of its velocity `v_h` after the hit), `energy` the kinetic
/// energy the pair has after the hit (never more than before it),
/// `m` the masses of `H` and `L`, and `brake` the most friction each of
/// `H`, `L` and `P` exerts (`m alpha`).
///
/// `L`'s inertia is left out: the contact forces on it balance its
/// friction. With `n_H` and `n_P` the unit normals from `H` and `P` to
/// `L` and `t` the direction `L` slides around `P`, the push from `H` is
/// `F_L / (n_H . t)` and the load `L` passes on to `P` is `F_L (-n_H .
/// n_P) / (n_H . t)`: a push (`n_H . n_P < 0`; else `L` leaves `P` and is
/// the pair's carry) that `P`'s friction takes while it is at most
/// `m_P alpha_P`. As `H` travels `y`, `L`, at the intersection of the
/// circles about `P` and about `H`, turns by `phi(y)` about `P`, its
/// friction taking `F_L s_P phi(y)` out of the chain, `H`'s own braking
/// `m_H alpha_H y`. The chain holds until `y_end`: `H` abreast of `L`
/// (`n_H . d` falls to zero), the push along `t` gone, `P`'s load beyond
/// its friction, or the circles parting. Where the work reaches the
/// energy before `y_end`, at `y*` ([`push::spent_at`]), both stop there,
/// as `push::carried` stops a wedged pair: `H` along its line with the
/// uniform deceleration that ends it at `y*`, `L` along the tangent `t0`
/// to `P` at its contact, by `y* (n_H . d) / (n_H . t0)` (the travel that
/// keeps the line of centres with `H` at right angles to their relative
/// motion), decelerating to rest at the same moment. Moving along the
/// tangent, `L` only parts from `P`; its motion relative to `H` is at
/// right angles to their line of centres at the hit, so the two only part
/// too; no energy is added (the two speeds share the pair's energy after
/// the hit). `L` ends within a second-order distance of the circle's path
/// (`s_P phi^2 / 2` off). `None` where the chain does not press as
/// described at the hit, `H` passes before the work spends the energy, or
/// the stop lies nowhere.
pub(crate) fn carried_around(
    chain: Chain,
    energy: f64,
    [m_h, m_l]: [f64; 2],
    [own, force, hold]: [f64; 3],
) -> Option<Carry> {
    let [h0, l0, p] = chain.at;
    let [s1, s2] = chain.reach;
    let d = chain.dir;
    if !(force > 0.0 && hold > 0.0 && energy > 0.0 && s1 > 0.0 && s2 > 0.0) {
        return None;
    }
    let side = chain.side();
    let q0 = chain.carried_at(0.0, side)?;
    // `t`: the tangent to `P` at `L`, the way `H` pushes `L` round.
    let frame = |y: f64| -> Option<(DVec2, DVec2, DVec2)> {
        let q = chain.carried_at(y, side)?;
        let n_h = (q - (h0 + d * y)) / s1;
        let n_p = (q - p) / s2;
        let t = n_p.perp();
        let t = if t.dot(n_h) >= 0.0 { t } else { -t };
        Some((n_h, n_p, t))
    };
    // The chain presses as described: `H` drives `L` round `P`, and `P`
    // holds.
    let holds = |y: f64| -> bool {
        frame(y).is_some_and(|(n_h, n_p, t)| {
            let along = n_h.dot(t);
            let into = -n_h.dot(n_p);
            n_h.dot(d) > 0.0 && along >= DRIVEN && into >= 0.0 && force * into <= hold * along
        })
    };
    // At the hit, from the disc's own position (the circles' intersection
    // rounds it).
    let n_h0 = (l0 - h0).normalize_or_zero();
    let n_p0 = (l0 - p).normalize_or_zero();
    let t0 = {
        let t = n_p0.perp();
        if t.dot(n_h0) >= 0.0 {
            t
        } else {
            -t
        }
    };
    let (along0, into0, drive0) = (n_h0.dot(t0), -n_h0.dot(n_p0), n_h0.dot(d));
    if !(drive0 > 0.0 && along0 >= DRIVEN && into0 > 0.0 && force * into0 <= hold * along0) {
        return None;
    }
    if !holds(0.0) {
        return None;
    }
    // The end of the chain: bisected on `[0, s1]`, over which `H` comes
    // abreast of `L` at the latest.
    let (mut lo, mut hi) = (0.0, s1);
    if holds(hi) {
        lo = hi;
    } else {
        for _ in 0..64 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if holds(mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
    }
    let end = lo;
    if !(end > 0.0 && hi > end) {
        return None;
    }
    let turned = |y: f64| -> f64 {
        chain.carried_at(y, side).map_or(f64::INFINITY, |q| {
            let (a, b) = (q0 - p, q - p);
            a.perp_dot(b).atan2(a.dot(b)).abs()
        })
    };
    let work = |y: f64| own * y + force * s2 * turned(y);
    // `L`'s travel along the tangent per unit of `H`'s.
    let ratio = drive0 / along0;
    if !(work(end) > energy) {
        return passed(
            chain,
            energy,
            [m_h, m_l],
            own,
            force * s2 * turned(end),
            [end, hi],
            ratio,
            t0,
        );
    }
    let stop = push::spent_at(work, energy, end);
    if !(stop > 0.0) {
        return None;
    }
    let speed = (2.0 * energy / (m_h + m_l * ratio * ratio)).sqrt();
    if !(speed > 0.0 && speed.is_finite()) {
        return None;
    }
    let duration = 2.0 * stop / speed;
    let carried = speed * ratio;
    Some(Carry {
        pusher: (d * speed, speed / duration),
        carried: (t0 * carried, carried / duration),
    })
}

/// The carry of [`carried_around`] where `H` has the energy to pass: it
/// pays `lost`, the friction of `L` round `P` up to `end` (`H` abreast of
/// `L`: the chain's end at `beyond` must be that, not `P` giving way), at
/// once and keeps its own braking, and `L` is carried ahead along the
/// tangent `t0` to `P`, decelerating to rest just as `H` has travelled
/// `end`. `L`'s travel, `ahead`, is at least `ratio` (the linear share of
/// `H`'s travel that keeps their line of centres at right angles to their
/// relative motion) times the distance `H` would cover at its passing
/// speed unbraked, so that `L`'s concave slide stays ahead of that
/// share of `H`'s travel all the way (the two only part), and at least
/// what takes `L` a contact distance off `H`'s line (`H` then passes it
/// by). `None` where `P` gives way first, `H` cannot pay, or energy
/// would be gained.
#[allow(clippy::too_many_arguments)]
fn passed(
    chain: Chain,
    energy: f64,
    [m_h, m_l]: [f64; 2],
    own: f64,
    lost: f64,
    [end, beyond]: [f64; 2],
    ratio: f64,
    t0: DVec2,
) -> Option<Carry> {
    let [h0, l0, _] = chain.at;
    let [s1, _] = chain.reach;
    let d = chain.dir;
    // The chain ends with `H` abreast of `L`.
    let side = chain.side();
    let abreast = chain
        .carried_at(beyond, side)
        .is_some_and(|q| (q - (h0 + d * beyond)).dot(d) <= 0.0);
    if !abreast {
        return None;
    }
    let brake = own / m_h;
    let passing2 = 2.0 * (energy - lost) / m_h;
    if !(passing2 > 2.0 * brake * end) {
        return None;
    }
    let passing = passing2.sqrt();
    let duration = 2.0 * end / (passing + (passing2 - 2.0 * brake * end).sqrt());
    // Off `H`'s line by a contact distance at the end.
    let across = {
        let c = d.perp();
        if c.dot(l0 - h0) >= 0.0 {
            c
        } else {
            -c
        }
    };
    let offset = (l0 - h0).dot(across);
    let lift = t0.dot(across);
    if !(lift > 0.0) {
        return None;
    }
    let clear = ((s1 - offset) / lift).max(0.0);
    let ahead = (ratio * passing * duration).max(clear);
    let carried = 2.0 * ahead / duration;
    let after = 0.5 * (m_h * passing2 + m_l * carried * carried);
    if !(after <= energy && ahead.is_finite()) {
        return None;
    }
    Some(Carry {
        pusher: (d * passing, brake),
        carried: (t0 * carried, carried / duration),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `H` on the floor sliding along +x, `L` nearly above it and a little
    /// ahead, `P` up and behind `L`: the shape of a heavy frictionless
    /// disc pushing a light braking one round a resting one.
    fn chain() -> Chain {
        let s = 0.0456;
        let h = DVec2::ZERO;
        let l = h + DVec2::new(0.0884, (1.0f64 - 0.0884 * 0.0884).sqrt()) * s;
        let p = l + DVec2::new(-0.876, (1.0f64 - 0.876 * 0.876).sqrt()) * s;
        Chain {
            at: [h, l, p],
            dir: DVec2::X,
            reach: [s, s],
        }
    }

    #[test]
    fn a_chain_short_of_energy_stops_with_the_carried_disc_along_the_held_discs_tangent() {
        let c = chain();
        let (m_h, m_l) = (0.72, 2.16e-3);
        let brake = [0.0, m_l * 2.943, 1.38e-2 * 2.943];
        let energy = 0.5 * m_h * 1.0e-3f64.powi(2);
        let out = carried_around(c, energy, [m_h, m_l], brake).expect("carried");
        let (vh, ah) = out.pusher;
        let (vl, al) = out.carried;
        // Both stop at the same moment.
        let (th, tl) = (vh.length() / ah, vl.length() / al);
        assert!((th - tl).abs() <= 1e-12 * th);
        // No energy gained.
        let after = 0.5 * (m_h * vh.length_squared() + m_l * vl.length_squared());
        assert!(after <= energy * (1.0 + 1e-12));
        // `L` slides along the tangent to `P`: it never nears `P`.
        let [h, l, p] = c.at;
        assert!(vl.dot(l - p).abs() <= 1e-12 * vl.length());
        // Nor `H`: their relative motion is across their line of centres.
        assert!((vl - vh).dot(l - h).abs() <= 1e-9 * vh.length() * c.reach[0]);
        // `H` stops where the work of `L`'s friction is the energy it had.
        let travel = vh.length() * th / 2.0;
        assert!(travel > 0.0 && travel < c.reach[0]);
    }

    #[test]
    fn a_chain_with_the_energy_to_pass_lets_the_pusher_through_paying_the_carried_discs_friction() {
        let c = chain();
        let (m_h, m_l) = (0.72, 2.16e-3);
        let brake = [0.0, m_l * 2.943, 1.38e-2 * 2.943];
        let energy = 0.5 * m_h * 1.0e-2f64.powi(2);
        let out = carried_around(c, energy, [m_h, m_l], brake).expect("carried");
        let (vh, ah) = out.pusher;
        let (vl, al) = out.carried;
        // The frictionless pusher keeps going, slower; no energy gained.
        assert_eq!(ah, 0.0);
        assert!(vh.length() < 1.0e-2 && vh.x > 0.0);
        let after = 0.5 * (m_h * vh.length_squared() + m_l * vl.length_squared());
        assert!(after <= energy);
        // The carried disc ends a contact distance off the pusher's line.
        let [h, l, p] = c.at;
        let rest = l + vl * (vl.length() / al / 2.0);
        assert!(rest.y - h.y >= c.reach[0] * (1.0 - 1e-12));
        // Along the tangent to the held disc: it never nears it.
        assert!(vl.dot(l - p).abs() <= 1e-12 * vl.length());
    }

    #[test]
    fn a_held_disc_whose_friction_cannot_take_the_load_is_not_a_pivot() {
        let c = chain();
        let (m_h, m_l) = (0.72, 2.16e-3);
        let brake = [0.0, m_l * 2.943, 1e-6];
        let energy = 0.5 * m_h * 1.0e-3f64.powi(2);
        assert_eq!(carried_around(c, energy, [m_h, m_l], brake), None);
    }
}
