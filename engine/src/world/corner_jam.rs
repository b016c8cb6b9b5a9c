//! From the twentieth revision, a corner jam: a disc `H` sliding along one
//! obstacle into a corner, just above the line of a row of discs lying
//! against the other obstacle, wedges the whole row along that obstacle,
//! nearly square to its own motion. `H` can only go on by pushing the row
//! aside at a small rate of its own speed, the row's friction braking it;
//! the row, pressed together and against its obstacle, moves as one body.
//! The pressing contact took this as bounces: each kick set the row moving
//! far faster than the wedge carries it, its braking discs stopped, the
//! next pressed pair of the row hit again, and `H`, losing nothing, drove
//! it again, a hit every nanosecond until `stuck`. Here it is taken at
//! once as the sixteenth revision carries one wedged disc
//! (`wedge::carried_row_along_wall`): both stop together where the row's
//! friction has spent `H`'s energy, or `H` pays that friction at once and
//! passes (`Revision::carries_rows_wedged_into_corners`).

use super::World;
use crate::collapse::Contact;
use crate::push;
use crate::trajectory::Trajectory;
use crate::wedge;
use glam::DVec2;

/// A corner jam found in a cluster: indices into its members.
struct Jam {
    /// The disc sliding into the corner along its obstacle.
    pusher: usize,
    /// The row's disc it touches.
    wedged: usize,
    /// The unit normal of the obstacle the row lies against, towards it.
    wall: DVec2,
    /// The unit direction along that obstacle away from the pusher.
    tau: DVec2,
    /// The pusher's velocity along its own obstacle.
    slide: DVec2,
}

/// Velocity `v` of the pusher of a jam, touching an obstacle (unit normal
/// `wall` towards it) and the row's disc on its other side (their two
/// normals nearly opposite), with its motion across the obstacle taken
/// off: into the obstacle, the obstacle's plastic share; off it, into the
/// row's disc (taken at rest), that disc's.
fn along_wall(v: DVec2, wall: DVec2) -> DVec2 {
    v - wall * v.dot(wall)
}

impl World {
    /// From the twentieth revision, where a pair of a cluster (`members`,
    /// slots; `contacts` among them and with obstacles; `vel` their
    /// velocities) rests by its energy (`push::spent_within_gap`) but the
    /// rest has no answer (a disc wedged between an obstacle and the row,
    /// their two contacts nearly opposite, stalls every solve): the row
    /// wedged by a disc sliding into the corner along the other obstacle
    /// is carried as one body ([`wedge::carried_row_along_wall`]), the
    /// row's own motion spent (no more kinetic energy than its friction
    /// spends over the pressing contact's gap). `false` (nothing done)
    /// where the cluster holds no such jam or the carry refuses it.
    pub(super) fn corner_jam(
        &mut self,
        members: &[usize],
        contacts: &[Contact],
        vel: &[DVec2],
        [i, j]: [usize; 2],
        t: f64,
    ) -> bool {
        let Some(jam) = self.find_jam(members, contacts, vel) else {
            return false;
        };
        let row = row_of(&jam, members.len(), contacts);
        // The row's obstacles: it slides along them or leaves them.
        let blocked = contacts
            .iter()
            .any(|c| row[c.a] && c.b.is_none() && jam.tau.dot(c.n) < 0.0);
        if blocked {
            return false;
        }
        let at: Vec<DVec2> = members
            .iter()
            .map(|&c| self.slots[c].traj.position(t))
            .collect();
        let p = |k: usize| at[k];
        let material: Vec<(f64, f64)> = members
            .iter()
            .map(|&c| (self.material[c].mass, self.material[c].mu * self.g))
            .collect();
        let mass = |k: usize| material[k].0;
        let alpha = |k: usize| material[k].1;
        let in_row: Vec<usize> = (0..members.len()).filter(|&k| row[k]).collect();
        let row_mass: f64 = in_row.iter().map(|&k| mass(k)).sum();
        let friction: f64 = in_row.iter().map(|&k| mass(k) * alpha(k)).sum();
        let own: f64 = in_row
            .iter()
            .map(|&k| 0.5 * mass(k) * vel[k].length_squared())
            .sum();
        let s = self.slots[members[jam.wedged]].radius + self.slots[members[jam.pusher]].radius;
        let gap = push::press_gap(self.config.revision) * s;
        if !(row_mass > 0.0 && friction > 0.0 && own <= friction * gap) {
            return false;
        }
        let n = (p(jam.wedged) - p(jam.pusher)).normalize_or_zero();
        let u = [DVec2::ZERO, jam.slide];
        let m = [row_mass, mass(jam.pusher)];
        let a = [friction / row_mass, alpha(jam.pusher)];
        let Some([(v_row, a_row), (v_h, a_h)]) =
            wedge::carried_row_along_wall(u, m, a, n, s, 0, jam.wall, self.config.revision)
        else {
            return false;
        };
        // The row as one body: at rest together where its slide is below
        // the rounding of every position of it.
        let row_traj = |k: usize| Trajectory::new(t, p(k), v_row, a_row);
        let settles = in_row
            .iter()
            .all(|&k| !self.settled(row_traj(k), t).is_moving());
        let mut changed: Vec<usize> = Vec::new();
        for &k in &in_row {
            let c = members[k];
            self.slots[c].traj = if settles {
                Trajectory::at_rest(t, p(k), alpha(k))
            } else {
                row_traj(k)
            };
            changed.push(c);
        }
        let c = members[jam.pusher];
        self.slots[c].traj = Trajectory::new(t, p(jam.pusher), v_h, a_h);
        changed.push(c);
        for c in [i, j] {
            if !changed.contains(&c) {
                changed.push(c);
            }
        }
        for &c in &changed {
            self.slots[c].gen = self.slots[c].gen.wrapping_add(1);
        }
        for &c in &changed {
            self.predict(c, true);
        }
        true
    }

    /// The corner jam of a cluster: a disc (`pusher`) that touches one
    /// obstacle and, its motion across it taken off ([`along_wall`]),
    /// runs along it into a disc (`wedged`, taken at rest) that touches
    /// one other obstacle, the pusher's contacts with the two nearly
    /// opposite (it lies in the corner just off the row's line).
    fn find_jam(&self, members: &[usize], contacts: &[Contact], vel: &[DVec2]) -> Option<Jam> {
        let walls = |k: usize| -> Vec<DVec2> {
            contacts
                .iter()
                .filter(|c| c.a == k && c.b.is_none())
                .map(|c| c.n)
                .collect()
        };
        (0..members.len()).find_map(|h| {
            let [own] = walls(h)[..] else {
                return None;
            };
            let slide = along_wall(vel[h], own);
            if !(slide.length() > 0.0) {
                return None;
            }
            contacts.iter().find_map(|c| {
                let (l, n) = match (c.a, c.b) {
                    (a, Some(b)) if a == h => (b, c.n),
                    (a, Some(b)) if b == h => (a, -c.n),
                    _ => return None,
                };
                // `n` from `l` to `h`: the pusher runs into `l` (the row
                // taken at rest, its own motion spent as the rest takes
                // it), and its obstacle nearly faces that contact.
                let [wall] = walls(l)[..] else {
                    return None;
                };
                let runs_in = slide.dot(n) < 0.0;
                let facing = n.dot(own) < -(1.0 - JAM_COSINE);
                let tau = if wall.perp().dot(n) <= 0.0 {
                    wall.perp()
                } else {
                    -wall.perp()
                };
                (runs_in && facing && wall.dot(own).abs() < 1.0 - JAM_COSINE).then_some(Jam {
                    pusher: h,
                    wedged: l,
                    wall,
                    tau,
                    slide,
                })
            })
        })
    }
}

/// How far from opposite the pusher's two contacts (its obstacle's and
/// the wedged disc's) may be, as one less the cosine of their angle: a
/// millionth, an angle of 1.4e-3 (the jams seen were 1e-6 and less).
const JAM_COSINE: f64 = 1e-6;

/// The row the jam's pusher wedges: its wedged disc and every member that
/// a member of the row touches ahead of it along the row's obstacle (a
/// disc the row would drive into as it moves along it), the pusher apart.
fn row_of(jam: &Jam, count: usize, contacts: &[Contact]) -> Vec<bool> {
    let mut row = vec![false; count];
    row[jam.wedged] = true;
    loop {
        let mut grew = false;
        for c in contacts {
            let Some(b) = c.b else { continue };
            if c.a == jam.pusher || b == jam.pusher || row[c.a] == row[b] {
                continue;
            }
            // The normal from the row's disc to the other.
            let (other, n) = if row[c.a] { (b, -c.n) } else { (c.a, c.n) };
            if jam.tau.dot(n) > 0.0 {
                row[other] = true;
                grew = true;
            }
        }
        if !grew {
            return row;
        }
    }
}
