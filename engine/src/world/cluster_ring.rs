//! From the fourteenth revision, a plastic hit whose touching cluster
//! rings without end, taken at once to the plastic limit of the contacts
//! that ring (`Revision::takes_cluster_rings_at_once`). A child of the
//! world's module: it reads the world's slots and takes the limit with the
//! world's own collapse.

use super::World;
use crate::impulse;
use crate::ring;
use glam::DVec2;

/// Discs of a hit's touching cluster beyond which its ring is not played:
/// the rings this takes are among four or five discs; a larger pile is
/// left to the collapse rules of the instant.
const RING_CLUSTER: usize = 12;

/// The fraction of the fastest disc's speed beyond which a contact of the
/// ring played in memory approaches: beyond the rounding of the velocities
/// its impulses form (`WALL_RING_NOISE`'s bound).
const RING_NOISE: f64 = 1e-12;

/// Whether the limit of a ring is followed by the pressing kick of the
/// pairs it leaves pressed (as `World::hit_into_wall`'s is): not. Kicked,
/// a pair of frictionless discs pressing a braking one at 1e-16 m/s was
/// parted after every limit and met again 7e-15 s later, until `stuck`
/// (mixed-box 452632); the plastic limit alone adds no energy.
const PRESS_AFTER_RING: bool = false;

impl World {
    /// From the fourteenth revision, a plastic hit between the discs in
    /// slots `i` and `j` (unit normal `n` towards `i`, velocities `u`
    /// before it) whose touching cluster (the discs touching either, or
    /// touching one that does, and the obstacles they touch; at most
    /// [`RING_CLUSTER`] discs) rings without end when its hits are played
    /// in memory from the hit (`ring::slow_ring`): taken at once as the
    /// plastic limit of the contacts that ring (hit more than once in that
    /// play, elastic or not), found by the active-set method. Hit by hit,
    /// a heavy disc pressing a light plastic one against a disc on a wall
    /// lost the light disc's share of its approach at each turn; each turn
    /// moved the discs by the rounding of a position, so that the next
    /// began picoseconds later, a few hits an instant, never the eight
    /// hits of one pair that `World::collapse_repeated` counts, nor an
    /// obstacle hit by the driven disc itself that `World::hit_into_wall`
    /// plays. The limit is the projection every collapse takes, which adds
    /// no energy. A pair its braking presses together is left to the
    /// pressing contact (taken, its limit was hit again 2.5e-5 s later,
    /// tens of thousands of times). `false` (nothing done) where the pair
    /// is pressed, the cluster is the pair alone or too large, it does not
    /// ring, or the limit changes nothing.
    pub(super) fn cluster_ring(
        &mut self,
        i: usize,
        j: usize,
        n: DVec2,
        u: [DVec2; 2],
        t: f64,
    ) -> bool {
        let (mi, mj) = (self.material[i].mass, self.material[j].mass);
        let (vi, vj) = impulse::body_body(u[0], u[1], mi, mj, 0.0, n);
        // A pair its braking presses together is left to the pressing
        // contact, as `World::walled_hit` leaves it.
        if self.braking_presses(i, j, [vi, vj], n, t) {
            return false;
        }
        // The touching cluster, grown no further than its bound.
        let at = self.positions(t);
        let mut members = vec![i, j];
        let mut k = 0;
        while k < members.len() {
            for c in self.touching(members[k], &at) {
                if !members.contains(&c) {
                    members.push(c);
                }
            }
            if members.len() > RING_CLUSTER {
                return false;
            }
            k += 1;
        }
        if members.len() <= 2 {
            return false;
        }
        let contacts = self.contacts_among(&members, t);
        let (mut vel, inv) = self.motion(&members, t);
        (vel[0], vel[1]) = (vi, vj);
        let restitution: Vec<f64> = contacts
            .iter()
            .map(|c| {
                let e = self.material[members[c.a]].restitution;
                c.b.map_or(e, |b| e.min(self.material[members[b]].restitution))
            })
            .collect();
        let fastest = vel.iter().map(|v| v.length()).fold(0.0, f64::max);
        let Some(hits) = ring::slow_ring(&vel, &inv, &contacts, &restitution, RING_NOISE * fastest)
        else {
            return false;
        };
        // The contacts that ring, and the discs they join.
        let ringing: Vec<_> = contacts
            .iter()
            .zip(&hits)
            .filter(|(_, &h)| h > 1)
            .map(|(c, _)| *c)
            .collect();
        let mut keep: Vec<usize> = ringing
            .iter()
            .flat_map(|c| [Some(c.a), c.b])
            .flatten()
            .collect();
        keep.sort_unstable();
        keep.dedup();
        if !keep.contains(&0) || !keep.contains(&1) {
            return false;
        }
        let index = |k: usize| keep.iter().position(|&x| x == k);
        let mut limit = Vec::with_capacity(ringing.len());
        for c in ringing {
            let (Some(a), b) = (index(c.a), c.b.map(index)) else {
                return false;
            };
            let b = match b {
                Some(None) => return false,
                Some(b) => b,
                None => None,
            };
            limit.push(crate::collapse::Contact { a, b, ..c });
        }
        let slots: Vec<usize> = keep.iter().map(|&k| members[k]).collect();
        let (vel, inv) = self.motion(&slots, t);
        let Some(after) = crate::collapse::active_set(&vel, &inv, &limit)
            .or_else(|| crate::collapse::resolve(&vel, &inv, &limit, crate::collapse::MAX_SWEEPS))
        else {
            return false;
        };
        // From the fifteenth revision, with the obstacles the limit drives
        // its discs into.
        let (limit, after) = if self
            .config
            .revision
            .takes_ring_limits_with_walls_they_reach()
        {
            let walls: Vec<_> = contacts
                .iter()
                .filter(|c| c.b.is_none())
                .filter_map(|c| index(c.a).map(|a| crate::collapse::Contact { a, ..*c }))
                .collect();
            super::reached_walls::with_walls_reached(
                &vel,
                &inv,
                limit,
                after,
                &walls,
                RING_NOISE * fastest,
            )
        } else {
            (limit, after)
        };
        self.take_plastic_limit(&slots, limit, (&vel, &inv), after, PRESS_AFTER_RING, t)
    }
}
