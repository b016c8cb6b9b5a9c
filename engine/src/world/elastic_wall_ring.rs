//! From the eighteenth revision, an elastic hit between two frictionless
//! discs that drives one of them into an obstacle it touches, the two then
//! ringing between the obstacle and each other within the rounding of
//! their positions, played to its end at once
//! (`Revision::plays_elastic_wall_rings_at_once`). A child of the world's
//! module: it reads the world's slots and leaves the hit as `World::collide`
//! leaves one.

use super::World;
use crate::impulse;
use crate::push;
use crate::ring;
use crate::trajectory::Trajectory;
use glam::DVec2;

/// Sweeps over the pair's contacts within which the elastic ring must end
/// (`ring::elastic_end`): a light disc between a wall and a disc `M/m`
/// times heavier turns about `pi sqrt(M / m) / 2` times, so this takes
/// discs up to some 25,000 times lighter than their partner; a longer ring
/// is left to its hits.
const ELASTIC_RING_SWEEPS: usize = 256;

/// The fraction of the pair's faster speed beyond which a contact of the
/// ring played in memory approaches (as `WALL_RING_NOISE`).
const ELASTIC_RING_NOISE: f64 = 1e-12;

impl World {
    /// From the eighteenth revision, an elastic hit (restitution 1) between
    /// the frictionless discs in slots `i` and `j` (at `p`, unit normal `n`
    /// towards `i`, velocities `u` before it), neither touching a disc but
    /// the other, after which the one that touches an obstacle is driven
    /// into that obstacle and back into its partner: the ring of elastic
    /// hits between the obstacle and the partner, played in memory to its end
    /// (`ring::elastic_end`), is taken at once. The discs touch within the
    /// rounding of their positions, so each hit of the ring comes within a
    /// few picometres of the one before and along the same normals: the
    /// event loop plays the same impulses one by one, a few hundred
    /// nanoseconds apart. Elastic hits lose no energy and the obstacle
    /// alone takes momentum, as each of its hits does. A light frictionless
    /// disc (2 g) in the corner, under a frictionless one (0.15 kg)
    /// squeezed against it by a row that a heavy disc sliding past pressed
    /// along the floor, rang between the side wall and its partner, two
    /// hits each turn, 10,735 of the last 20,000 events before the event
    /// cap at 3.4 s (mixed-box 401789). `false` (nothing done) where either
    /// disc brakes or is not elastic, either touches a third disc (a row of
    /// elastic discs against a wall, hit at one instant, rang on without
    /// end taken so: walled-cradle 3264), the hit drives it into no
    /// obstacle, or the ring does not end within [`ELASTIC_RING_SWEEPS`].
    pub(super) fn elastic_wall_ring(
        &mut self,
        i: usize,
        j: usize,
        [pi, pj]: [DVec2; 2],
        [ui, uj]: [DVec2; 2],
        n: DVec2,
        t: f64,
    ) -> bool {
        let (mi, mj) = (self.material[i], self.material[j]);
        if !(mi.restitution == 1.0 && mj.restitution == 1.0 && mi.mu == 0.0 && mj.mu == 0.0) {
            return false;
        }
        // A ring against a wall needs one of the two against an obstacle
        // (the test on the hits below refuses it otherwise): most elastic
        // hits have none, so leave before gathering the contacts.
        if !(self.may_touch_an_obstacle(i, t) || self.may_touch_an_obstacle(j, t)) {
            return false;
        }
        let contacts = self.contacts_among(&[i, j], t);
        if !contacts.iter().any(|c| c.a == 0 && c.b == Some(1)) {
            return false;
        }
        // Neither disc touches a disc but its partner: a third disc would
        // take a share of the ring, and a row of elastic discs against a
        // wall (a cradle) hands each turn on along the row.
        let at = self.positions(t);
        if [i, j]
            .into_iter()
            .any(|m| self.touching(m, &at).any(|c| c != i && c != j))
        {
            return false;
        }
        let (vi, vj) = impulse::body_body(ui, uj, mi.mass, mj.mass, 1.0, n);
        let noise = ELASTIC_RING_NOISE * ui.length().max(uj.length());
        let inv = [1.0 / mi.mass, 1.0 / mj.mass];
        let Some((end, hits)) =
            ring::elastic_end(&[vi, vj], &inv, &contacts, noise, ELASTIC_RING_SWEEPS)
        else {
            return false;
        };
        // A ring: an obstacle hit and the pair hit again after it.
        let again = contacts
            .iter()
            .zip(&hits)
            .any(|(c, &h)| c.b == Some(1) && h > 0);
        let walled = contacts
            .iter()
            .zip(&hits)
            .any(|(c, &h)| c.b.is_none() && h > 0);
        if !(again && walled) {
            return false;
        }
        let new_i = Trajectory::new(t, pi, end[0], 0.0);
        let new_j = Trajectory::new(t, pj, end[1], 0.0);
        self.leave_hit(i, j, new_i, new_j, t);
        true
    }

    /// Whether disc `c` at `t` lies within touching distance of a solid
    /// line or a point, by the test `World::contacts_among` makes: true
    /// wherever that would find an obstacle contact (and where its normal
    /// would be null, which it drops), so it only ever saves work.
    fn may_touch_an_obstacle(&self, c: usize, t: f64) -> bool {
        let (p, r) = (self.slots[c].traj.position(t), self.slots[c].radius);
        let touching = |gap: f64| gap <= r * (1.0 + push::TOUCHING);
        self.solid
            .iter()
            .any(|&line| touching(self.geoms[line as usize].distance(p)))
            || self.points.iter().any(|q| touching((p - q.pos).length()))
    }
}
