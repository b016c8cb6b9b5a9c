//! A ring at one instant played in memory: the hits that follow one hit
//! among discs that touch each other and the obstacles they touch, each
//! contact that approaches hit in turn with its restitution, sweep after
//! sweep, as the event loop would play them at one instant. It tells a
//! ring that ends by itself (no contact approaches within a few sweeps,
//! or what approaches falls fast) from one that has no end, only a limit
//! (a heavy disc pressing a light one against a disc on a wall loses the
//! light one's share of its approach at each turn), and names the contacts
//! that ring. It changes nothing in the world: the caller takes the limit
//! (see `World::cluster_ring`).

use crate::collapse::Contact;
use glam::DVec2;

/// Sweeps over the contacts after which a ring that still approaches is
/// one without an end (see [`slow_ring`]): twice the turns after which the
/// thirteenth revision takes a disc ringing against a wall
/// (`World::hit_into_wall`), since a sweep over a chain of several discs
/// may carry a turn only part of the way along it.
pub(crate) const RING_SWEEPS: usize = 16;

/// The share of its first sweep's fastest approach that a ring must still
/// have after [`RING_SWEEPS`] sweeps to be one without an end (see
/// [`slow_ring`]): as for a disc ringing against a wall
/// (`World::hit_into_wall`), a ring losing less than a tenth of its
/// approach a sweep, hundreds of sweeps long. A faster one ends by itself
/// within the hits the event loop plays.
pub(crate) const RING_KEEPS: f64 = 0.2;

/// Plays in memory the hits among discs at velocities `vel` (inverse
/// masses `inv`, each positive) through their `contacts` (normals from
/// `b` to `a`; an obstacle's `b` is `None`), contact `k` hit with
/// restitution `restitution[k]` wherever it approaches faster than
/// `noise`: [`RING_SWEEPS`] sweeps over the contacts in order. `Some`,
/// with each contact's count of hits, where the last sweep still hit a
/// contact that is not elastic and its fastest approach kept at least
/// [`RING_KEEPS`] of the first sweep's: a ring
/// that goes on, losing little at each turn. `None` where a sweep hit
/// nothing (the ring ended), or it lost its approach faster, or only
/// elastic contacts ring (their sequence loses no energy and is left to
/// its hits).
pub(crate) fn slow_ring(
    vel: &[DVec2],
    inv: &[f64],
    contacts: &[Contact],
    restitution: &[f64],
    noise: f64,
) -> Option<Vec<u32>> {
    let mut v = vel.to_vec();
    let mut hits = vec![0u32; contacts.len()];
    let mut first = None;
    let mut last = 0.0;
    let mut lossy = false;
    for _ in 0..RING_SWEEPS {
        let mut fastest: f64 = 0.0;
        lossy = false;
        for (k, c) in contacts.iter().enumerate() {
            let rel = v[c.a] - c.b.map_or(DVec2::ZERO, |b| v[b]);
            let approach = -rel.dot(c.n);
            if approach <= noise {
                continue;
            }
            hit(&mut v, inv, c, restitution[k], approach);
            hits[k] += 1;
            fastest = fastest.max(approach);
            lossy |= restitution[k] < 1.0;
        }
        if fastest == 0.0 {
            return None;
        }
        first.get_or_insert(fastest);
        last = fastest;
    }
    let first = first?;
    (lossy && last >= RING_KEEPS * first).then_some(hits)
}

/// Hits contact `c` among discs at velocities `v` (inverse masses `inv`)
/// with restitution `e`, its approach `approach`.
fn hit(v: &mut [DVec2], inv: &[f64], c: &Contact, e: f64, approach: f64) {
    let w = inv[c.a] + c.b.map_or(0.0, |b| inv[b]);
    let j = (1.0 + e) * approach / w;
    v[c.a] += c.n * (j * inv[c.a]);
    if let Some(b) = c.b {
        v[b] -= c.n * (j * inv[b]);
    }
}

/// From the eighteenth revision: plays in memory, to its end, a ring whose
/// contacts are all elastic (discs at velocities `vel`, inverse masses
/// `inv`, contacts `contacts` hit with restitution 1 wherever they
/// approach faster than `noise`), sweep after sweep, as the event loop
/// would play them where the gaps between the hits are below the rounding
/// of the positions. An elastic sequence loses no energy, but one between
/// a wall and a heavier disc ends by itself: the light disc hands the
/// heavy one a share of its approach each turn, until neither contact
/// approaches (a light disc between a wall and a disc `M/m` times heavier
/// ends in about `pi sqrt(M / m) / 2` turns). `Some`, with the velocities
/// at its end and the count of hits of each contact, where a sweep within
/// `sweeps` hits nothing; `None` where it still approaches after them.
pub(crate) fn elastic_end(
    vel: &[DVec2],
    inv: &[f64],
    contacts: &[Contact],
    noise: f64,
    sweeps: usize,
) -> Option<(Vec<DVec2>, Vec<u32>)> {
    let mut v = vel.to_vec();
    let mut hits = vec![0u32; contacts.len()];
    for _ in 0..sweeps {
        let mut any = false;
        for (k, c) in contacts.iter().enumerate() {
            let rel = v[c.a] - c.b.map_or(DVec2::ZERO, |b| v[b]);
            let approach = -rel.dot(c.n);
            if approach <= noise {
                continue;
            }
            hit(&mut v, inv, c, 1.0, approach);
            hits[k] += 1;
            any = true;
        }
        if !any {
            return Some((v, hits));
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A heavy disc (slot 0) pressing a light plastic one (1) against a
    /// heavy disc (2) resting on a wall, along x: the contacts 0-1, 1-2
    /// and 2-wall.
    fn chain(e_wall: f64, light: f64) -> (Vec<DVec2>, Vec<f64>, Vec<Contact>, Vec<f64>) {
        let vel = vec![DVec2::new(-1.0, 0.0), DVec2::ZERO, DVec2::ZERO];
        let inv = vec![1.0, 1.0 / light, 1.0];
        let contacts = vec![
            Contact::plastic(0, Some(1), DVec2::X),
            Contact::plastic(1, Some(2), DVec2::X),
            Contact::plastic(2, None, DVec2::X),
        ];
        (vel, inv, contacts, vec![0.0, 0.0, e_wall])
    }

    #[test]
    fn a_heavy_disc_pressing_a_light_one_against_a_disc_on_a_wall_rings_without_end() {
        let (vel, inv, contacts, e) = chain(1.0, 0.01);
        let hits = slow_ring(&vel, &inv, &contacts, &e, 1e-12).expect("a ring without end");
        assert!(
            hits.iter().all(|&h| h >= 2),
            "every contact rings: {hits:?}"
        );
    }

    #[test]
    fn a_light_disc_knocking_a_chain_against_a_wall_ends_by_itself() {
        // The striker is the light one: its approach is gone in a few turns.
        let vel = vec![DVec2::new(-1.0, 0.0), DVec2::ZERO, DVec2::ZERO];
        let inv = vec![100.0, 1.0, 1.0];
        let (_, _, contacts, e) = chain(0.0, 1.0);
        assert_eq!(slow_ring(&vel, &inv, &contacts, &e, 1e-12), None);
    }

    #[test]
    fn an_elastic_ring_is_left_to_its_hits() {
        let (vel, inv, contacts, _) = chain(1.0, 0.01);
        assert_eq!(slow_ring(&vel, &inv, &contacts, &[1.0; 3], 1e-12), None);
    }

    /// Galperin's billiard with its gaps closed: a light disc (slot 0)
    /// against a wall, a disc `big` times heavier (1) running into it.
    fn galperin(big: f64) -> (Vec<DVec2>, Vec<f64>, Vec<Contact>) {
        let vel = vec![DVec2::ZERO, DVec2::new(-1.0, 0.0)];
        let inv = vec![1.0, 1.0 / big];
        let contacts = vec![
            Contact::plastic(0, Some(1), -DVec2::X),
            Contact::plastic(0, None, DVec2::X),
        ];
        (vel, inv, contacts)
    }

    #[test]
    fn an_elastic_ring_between_a_wall_and_a_heavy_disc_ends_after_galperins_count_of_hits() {
        for (big, count) in [(1.0, 3), (100.0, 31), (1e4, 314)] {
            let (vel, inv, contacts) = galperin(big);
            let (end, hits) =
                elastic_end(&vel, &inv, &contacts, 1e-12, 256).expect("the ring ends");
            assert_eq!(hits.iter().sum::<u32>(), count, "mass ratio {big}");
            // Both leave the wall, the light disc no faster than the heavy
            // one, with the energy they had.
            assert!(end[0].x >= 0.0 && end[0].x <= end[1].x, "{end:?}");
            let energy = 0.5 * end[0].length_squared() + 0.5 * big * end[1].length_squared();
            assert!(
                (energy - 0.5 * big).abs() <= 1e-12 * big,
                "{energy} of {}",
                0.5 * big
            );
        }
    }

    #[test]
    fn an_elastic_ring_longer_than_its_sweeps_is_left_to_its_hits() {
        let (vel, inv, contacts) = galperin(1e8);
        assert_eq!(elastic_end(&vel, &inv, &contacts, 1e-12, 256), None);
    }

    #[test]
    fn discs_that_part_at_once_do_not_ring() {
        let (_, inv, contacts, e) = chain(0.0, 0.01);
        let vel = vec![DVec2::new(1.0, 0.0), DVec2::ZERO, DVec2::ZERO];
        assert_eq!(slow_ring(&vel, &inv, &contacts, &e, 1e-12), None);
    }
}
