//! From the fifteenth revision, the obstacles a ring's plastic limit
//! reaches: where the limit of the contacts that ring (a cluster's ring,
//! `World::cluster_ring`; a hit into a wall, `World::hit_into_wall`)
//! leaves one of its discs moving into an obstacle it touches that was not
//! among them (an elastic disc's wall, not hit in the play of the ring),
//! that obstacle is taken into the limit too
//! (`Revision::takes_ring_limits_with_walls_they_reach`). Left out, the
//! disc met the obstacle a rounding of a position away, bounced off it
//! into its partner at the same instant, and the same limit sent it back
//! into the obstacle, ring after ring until the event cap.

use crate::collapse::{self, Contact};
use glam::DVec2;

/// The limit `after` of `limit` (discs at velocities `vel`, inverse masses
/// `inv`), widened by each contact of `obstacles` (a disc of the limit
/// against an obstacle it touches) that it drives its disc into: the disc
/// leaves the limit moving into the obstacle faster than `noise`, and the
/// limit's impulses pushed it that way (a disc already moving into its
/// wall before, and not pushed, meets it by itself). Solved again with
/// them, until it drives into none: the limit and its velocities. Where
/// the wider limit has no solution, the narrower one is kept. The plastic
/// projection onto more contacts adds no energy: it only takes away
/// approach.
pub(super) fn with_walls_reached(
    vel: &[DVec2],
    inv: &[f64],
    mut limit: Vec<Contact>,
    mut after: Vec<DVec2>,
    obstacles: &[Contact],
    noise: f64,
) -> (Vec<Contact>, Vec<DVec2>) {
    for _ in 0..obstacles.len() {
        let reached: Vec<Contact> = obstacles
            .iter()
            .filter(|c| {
                let (into, pushed) = (after[c.a].dot(c.n), (after[c.a] - vel[c.a]).dot(c.n));
                c.b.is_none() && !limit.contains(c) && into < -noise && pushed < -noise
            })
            .copied()
            .collect();
        if reached.is_empty() {
            break;
        }
        let wider = [limit.as_slice(), &reached].concat();
        let Some(again) = collapse::active_set(vel, inv, &wider)
            .or_else(|| collapse::resolve(vel, inv, &wider, collapse::MAX_SWEEPS))
        else {
            break;
        };
        (limit, after) = (wider, again);
    }
    (limit, after)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A light elastic disc (slot 0) in a corner, a heavier one (1) sliding
    /// past it along `n` and pressing it towards both walls: the limit of
    /// the pair and the floor alone slides the light disc into the side
    /// wall.
    fn corner() -> (Vec<DVec2>, Vec<f64>, Vec<Contact>, Vec<Contact>) {
        let n = DVec2::new(-0.6, -0.8);
        let vel = vec![DVec2::ZERO, DVec2::new(-1.0, -1.0)];
        let inv = vec![10.0, 1.0];
        let limit = vec![
            Contact::plastic(0, Some(1), n),
            Contact::plastic(0, None, DVec2::Y),
        ];
        let walls = vec![
            Contact::plastic(0, None, DVec2::Y),
            Contact::plastic(0, None, DVec2::X),
        ];
        (vel, inv, limit, walls)
    }

    #[test]
    fn a_limit_that_drives_a_disc_into_a_wall_it_touches_takes_that_wall() {
        let (vel, inv, limit, walls) = corner();
        let after = collapse::active_set(&vel, &inv, &limit).expect("the narrow limit");
        assert!(after[0].x < 0.0, "the narrow limit drives into the wall");
        let (wider, after) = with_walls_reached(&vel, &inv, limit, after, &walls, 1e-12);
        assert_eq!(wider.len(), 3);
        assert!(after[0].x >= -1e-12, "held off the side wall: {after:?}");
        let approach = (after[1] - after[0]).dot(DVec2::new(-0.6, -0.8));
        assert!(
            approach <= 1e-12,
            "the pair no longer approaches: {approach}"
        );
        let energy = |v: &[DVec2]| {
            v.iter()
                .zip(&inv)
                .map(|(u, i)| u.length_squared() / i)
                .sum::<f64>()
        };
        assert!(energy(&after) <= energy(&vel), "no energy gained");
    }

    #[test]
    fn a_limit_that_leaves_its_walls_alone_is_kept_as_it_is() {
        let (_, inv, limit, walls) = corner();
        let away = vec![DVec2::ZERO, DVec2::new(1.0, 1.0)];
        let after = collapse::active_set(&away, &inv, &limit).expect("the limit");
        let (kept, same) =
            with_walls_reached(&away, &inv, limit.clone(), after.clone(), &walls, 1e-12);
        assert_eq!((kept, same), (limit, after));
    }

    #[test]
    fn a_disc_already_moving_into_its_wall_and_not_pushed_there_is_left_to_meet_it() {
        // The light disc slides into the side wall before the hit, and the
        // heavy one parts from it: the limit leaves it as it was.
        let (_, inv, limit, walls) = corner();
        let vel = vec![DVec2::new(-1.0, 0.0), DVec2::new(1.0, 1.0)];
        let after = collapse::active_set(&vel, &inv, &limit).expect("the limit");
        assert!(after[0].x < 0.0);
        let (kept, same) =
            with_walls_reached(&vel, &inv, limit.clone(), after.clone(), &walls, 1e-12);
        assert_eq!((kept, same), (limit, after));
    }
}
