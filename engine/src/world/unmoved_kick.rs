//! From the eighteenth revision, a pressing kick after a plastic limit that
//! cannot move a braking disc: where the kick (`World::press_closure`)
//! sets a braking disc moving so slowly that it stops within the rounding
//! of its position, and the limit had left it as still, the kick opens no
//! gap; the disc stops where it is, and its partner, still pressed into
//! it, is hit again at the same position as soon as it has stopped, kick
//! after kick. Such a disc is held by its friction instead, as a pair
//! resting by its energy holds its braking discs (`push::spent_within_gap`,
//! `World::settled_hit`): where what the limit moves has no more kinetic
//! energy than each held disc's friction spends over the pressing
//! contact's gap, the limit is solved again with the held discs still, and
//! its discs keep only what does not run into them; no kick follows
//! (`Revision::holds_discs_kicks_cannot_move`).

use super::{World, PRESS_SWEEPS};
use crate::collapse::{self, Contact};
use crate::push;
use crate::trajectory::Trajectory;
use glam::DVec2;

impl World {
    /// The limit of `contacts` (unbiased) among `members` (slots; `vel`,
    /// `inv` their velocities and inverse masses before the limit, `alpha`
    /// their braking), with the braking discs that both the limit `after`
    /// and the pressing kick `kicked` leave within the rounding of their
    /// positions, the kick moving them, held still; `None` where the kick
    /// moves no such disc, what moves has the energy to push one beyond the
    /// pressing contact's gap, or the held limit has no answer.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn held_against_kick(
        &self,
        members: &[usize],
        contacts: &[Contact],
        (vel, inv): (&[DVec2], &[f64]),
        alpha: &[f64],
        after: &[DVec2],
        kicked: &[DVec2],
        t: f64,
    ) -> Option<Vec<DVec2>> {
        let stops = |k: usize, v: DVec2| {
            let p = self.slots[members[k]].traj.position(t);
            !self
                .settled(Trajectory::new(t, p, v, alpha[k]), t)
                .is_moving_at(t)
        };
        let still: Vec<bool> = (0..members.len())
            .map(|k| {
                alpha[k] > 0.0 && kicked[k] != after[k] && stops(k, after[k]) && stops(k, kicked[k])
            })
            .collect();
        if !still.contains(&true) {
            return None;
        }
        // The least work a held disc's friction does over the gap.
        let weakest = (0..members.len())
            .filter(|&k| still[k])
            .map(|k| {
                let gap =
                    push::press_gap(self.config.revision) * 2.0 * self.slots[members[k]].radius;
                self.material[members[k]].mass * alpha[k] * gap
            })
            .fold(f64::INFINITY, f64::min);
        let moving: f64 = (0..members.len())
            .filter(|&k| !still[k])
            .map(|k| 0.5 * vel[k].length_squared() / inv[k])
            .sum();
        if moving > weakest {
            return None;
        }
        let mut held = vel.to_vec();
        let mut inv_held = inv.to_vec();
        for k in (0..members.len()).filter(|&k| still[k]) {
            (held[k], inv_held[k]) = (DVec2::ZERO, 0.0);
        }
        let contacts: Vec<Contact> = contacts
            .iter()
            .filter(|c| !still[c.a] || c.b.is_some_and(|b| !still[b]))
            .copied()
            .collect();
        let mut limit = if contacts.is_empty() {
            held
        } else {
            collapse::resolve(&held, &inv_held, &contacts, PRESS_SWEEPS)
                .or_else(|| collapse::active_set(&held, &inv_held, &contacts))?
        };
        let noise = 1e-12 * vel.iter().map(|v| v.length()).fold(0.0, f64::max);
        for v in &mut limit {
            if v.length() <= noise {
                *v = DVec2::ZERO;
            }
        }
        Some(limit)
    }
}
