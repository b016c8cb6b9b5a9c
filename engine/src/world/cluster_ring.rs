//! From the fourteenth revision, a plastic hit whose touching cluster
//! rings without end, taken at once to the plastic limit of the contacts
//! that ring (`Revision::takes_cluster_rings_at_once`). A child of the
//! world's module: it reads the world's slots and takes the limit with the
//! world's own collapse.

use super::World;
use crate::impulse;
use crate::limits::SETTLE;
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
    /// tens of thousands of times). From the eighteenth revision the ring
    /// is played without the pairs of the cluster that only graze
    /// (`graze::within_rounding`): a disc sliding down a wall 2.6e-10 m
    /// above the line of a row on the floor, 9.2e-19 m of carry left, gave
    /// the row its wedge's speed again at every limit, and the row's
    /// braking disc, kicked off the next, was caught again 1.5e-13 s
    /// later, until `stuck` (mixed-box 129558;
    /// `Revision::passes_grazes_within_rounding`). `false` (nothing done)
    /// where the pair is pressed, the cluster is the pair alone or too
    /// large, it does not ring, or the limit changes nothing.
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
        let mut contacts = self.contacts_among(&members, t);
        let (mut vel, inv) = self.motion(&members, t);
        (vel[0], vel[1]) = (vi, vj);
        let fastest = vel.iter().map(|v| v.length()).fold(0.0, f64::max);
        // From the eighteenth revision, a pair of the cluster other than
        // the hit one that approaches beyond the ring's noise but only
        // grazes, closing no more than the rounding of its positions, is
        // no contact of the ring: a disc sliding down a wall past the end
        // of a row, 2.6e-10 m above its line, drove the row at every hit
        // of it by a carry the positions cannot show.
        if self.config.revision.passes_grazes_within_rounding() {
            contacts.retain(|c| {
                c.b.is_none_or(|b| {
                    let w = vel[c.a] - vel[b];
                    let (pa, pb) = (at[members[c.a]], at[members[b]]);
                    (c.a, b) == (0, 1)
                        || -w.dot(c.n) <= RING_NOISE * fastest
                        || !crate::graze::within_rounding(pa, pb, w)
                })
            });
        }
        let restitution: Vec<f64> = contacts
            .iter()
            .map(|c| {
                let e = self.material[members[c.a]].restitution;
                c.b.map_or(e, |b| e.min(self.material[members[b]].restitution))
            })
            .collect();
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
        // From the fifteenth revision, a ring whose energy its braking
        // spends within the rounding of its positions comes to rest.
        if self.config.revision.rests_spent_rings() && self.spent_ring_rest(&slots, &vel, &inv, t) {
            return true;
        }
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

    /// From the fifteenth revision, the discs of a ring (`slots`, with
    /// velocities `vel` and inverse masses `inv` at `t`) whose kinetic
    /// energy is no more than what the friction of each of its braking
    /// discs does over the rounding of that disc's position (`SETTLE` of
    /// its largest coordinate), brought to rest: friction being all that
    /// takes energy out of the ring's braking discs, none of them could
    /// slide further than a position can show, so they are held where
    /// they are (as `World::settled` puts a disc whose slide is that short
    /// at rest), and its frictionless discs keep only what does not run
    /// into them or into the obstacles they touch (the plastic limit
    /// against the held discs, by the active-set method, as the eleventh
    /// revision rests a spent pair in `World::press_cluster`; a speed it
    /// leaves within 1e-12 of the ring's fastest is none). A frictionless
    /// disc sliding down a wall into the corner, its contact with a disc
    /// on the floor tilted 1.5e-6 from its motion, drove that disc into
    /// braking ones at a millionth of its speed: each limit of the ring
    /// took from it only that share, the braking discs, slowed by their
    /// friction, were caught again at the same instant, 20,000 limits
    /// until `stuck`, the wedging disc still sliding at 3e-10 m/s
    /// (mixed-box 442739). `false` (nothing done) where the energy is
    /// more, no disc brakes, or the limit against the held discs has no
    /// answer. Held to the pressing contact's gap instead of the rounding,
    /// the rest took rings far from rest, and a ring in a corner that
    /// reached its horizon went on to `stuck` (mixed-box 136800). From the
    /// sixteenth revision a ring of `World::hit_into_wall` rests so too
    /// (`Revision::rests_spent_hits_into_walls`). From the seventeenth the
    /// energy weighed is that of what the rest takes away (`sum m |v -
    /// v'|^2 / 2`, what runs into the held discs), not all the ring has: a
    /// frictionless disc sliding past a ring along its tangent at 6.1e-5
    /// m/s brought 2.5e-10 J to one of 1.5e-26 J, and the ring, kicked
    /// apart at every hit instead, ended `stuck` (mixed-box 439482;
    /// `Revision::rests_rings_spent_by_what_runs_into_them`).
    pub(super) fn spent_ring_rest(
        &mut self,
        slots: &[usize],
        vel: &[DVec2],
        inv: &[f64],
        t: f64,
    ) -> bool {
        let alpha = self.braking(slots);
        // The least work a braking disc's friction does over the rounding
        // of its position.
        let weakest = slots
            .iter()
            .zip(&alpha)
            .filter(|(_, &a)| a > 0.0)
            .map(|(&c, &a)| {
                let rounding = SETTLE * self.slots[c].traj.position(t).abs().max_element();
                self.material[c].mass * a * rounding
            })
            .fold(f64::INFINITY, f64::min);
        if !weakest.is_finite() {
            return false;
        }
        // From the seventeenth revision, the energy the rest takes (what
        // runs into the held discs) rather than all the ring has: a disc
        // grazing the ring keeps its motion, and spends none of it on them.
        let by_loss = self
            .config
            .revision
            .rests_rings_spent_by_what_runs_into_them();
        if !by_loss && super::kinetic_energy(vel, inv) > weakest {
            return false;
        }
        let still: Vec<bool> = alpha.iter().map(|&a| a > 0.0).collect();
        // The rest takes all the braking discs have: where that is more,
        // no projection is needed to refuse it.
        if by_loss {
            let braking: f64 = (0..slots.len())
                .filter(|&k| still[k])
                .map(|k| 0.5 * vel[k].length_squared() / inv[k])
                .sum();
            if braking > weakest {
                return false;
            }
        }
        let mut held = vel.to_vec();
        let mut inv_held = inv.to_vec();
        for k in (0..slots.len()).filter(|&k| still[k]) {
            (held[k], inv_held[k]) = (DVec2::ZERO, 0.0);
        }
        let mut contacts = self.contacts_among(slots, t);
        contacts.retain(|c| !still[c.a] || c.b.is_some_and(|b| !still[b]));
        let after = if contacts.is_empty() {
            Some(held)
        } else {
            crate::collapse::active_set(&held, &inv_held, &contacts).or_else(|| {
                crate::collapse::resolve(&held, &inv_held, &contacts, super::PRESS_SWEEPS)
            })
        };
        let Some(mut after) = after else {
            return false;
        };
        let noise = 1e-12 * vel.iter().map(|v| v.length()).fold(0.0, f64::max);
        for v in &mut after {
            if v.length() <= noise {
                *v = DVec2::ZERO;
            }
        }
        if by_loss {
            // The kinetic energy of what the rest takes away (for a
            // projection, the energy it loses, found without the
            // cancellation of two totals).
            let taken: Vec<DVec2> = vel.iter().zip(&after).map(|(v, w)| *v - *w).collect();
            if super::kinetic_energy(&taken, inv) > weakest {
                return false;
            }
        }
        let changed = self.set_velocities(slots, vel, &after, t);
        for &c in &changed {
            self.predict(c, true);
        }
        !changed.is_empty()
    }
}
