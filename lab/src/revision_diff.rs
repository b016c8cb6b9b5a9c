//! How one engine revision changes outcomes against another, on the hostile
//! scenes of [`crate::hostile`]: a new revision must change no scene it does
//! not mean to, and change the ones it does by a measured amount. Each
//! scene runs under both revisions to its end (or the generator's event
//! cap); the outcomes differ if the end time, the end reason or any final
//! position differs by a bit, and for scenes that end at rest under both
//! the change is the farthest any disc comes to rest from where the other
//! revision left it, in its own radii.

use crate::hostile::{Hostile, Kind, MAX_EVENTS};
use engine::{BodyId, EndReason, Limits, Revision, World, WorldConfig};
use glam::DVec2;

/// How a run of a scene ended.
#[derive(Clone, Debug, PartialEq)]
pub struct Ending {
    pub t: f64,
    pub reason: EndReason,
    pub events: u64,
    /// Each disc still in the scene at the end: id, position, radius.
    pub discs: Vec<(BodyId, DVec2, f64)>,
}

/// Runs `h` under `revision` to its end.
pub fn ending(h: &Hostile, revision: Revision) -> Option<Ending> {
    let config = WorldConfig {
        revision,
        ..WorldConfig::default()
    };
    let mut world = World::new(&h.scene, config).ok()?;
    let limits = Limits {
        until: h.until,
        max_collisions: u64::MAX,
        max_events: MAX_EVENTS,
    };
    let end = world.run(&limits, &mut ());
    let discs = world
        .bodies()
        .map(|b| (b.id, b.trajectory.position(end.t), b.material.radius))
        .collect();
    Some(Ending {
        t: end.t,
        reason: end.reason,
        events: world.stats().events,
        discs,
    })
}

/// What changed between two endings of one scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Change {
    /// Anything differs, to the bit.
    pub differs: bool,
    /// Where both end at rest with the same discs: the farthest a disc
    /// comes to rest from where the other left it, in its radii.
    pub moved: Option<f64>,
}

/// Compares two endings of one scene.
pub fn change(a: &Ending, b: &Ending) -> Change {
    let differs = a.t.to_bits() != b.t.to_bits() || a.reason != b.reason || a.discs != b.discs;
    let same_discs =
        a.discs.len() == b.discs.len() && a.discs.iter().zip(&b.discs).all(|(x, y)| x.0 == y.0);
    let moved =
        (a.reason == EndReason::Rest && b.reason == EndReason::Rest && same_discs).then(|| {
            a.discs
                .iter()
                .zip(&b.discs)
                .map(|(x, y)| (x.1 - y.1).length() / x.2)
                .fold(0.0, f64::max)
        });
    Change { differs, moved }
}

/// One kind's scenes under two revisions.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct KindDiff {
    pub scenes: u64,
    /// Scenes whose outcomes differ at all.
    pub differ: u64,
    /// The largest [`Change::moved`], and its seed.
    pub moved: Option<(f64, u64)>,
    /// Scenes that end at rest under one revision and not the other.
    pub rest_changed: u64,
    /// Events in all, under the old revision and the new.
    pub events: (u64, u64),
}

/// Compares `old` and `new` on `count` scenes of `kind` from `seed`.
pub fn compare(kind: Kind, seed: u64, count: u64, old: Revision, new: Revision) -> KindDiff {
    let mut d = KindDiff::default();
    for s in seed..seed + count {
        let h = Hostile::generate(kind, s);
        let (Some(a), Some(b)) = (ending(&h, old), ending(&h, new)) else {
            continue;
        };
        d.scenes += 1;
        d.events.0 += a.events;
        d.events.1 += b.events;
        let c = change(&a, &b);
        d.differ += u64::from(c.differs);
        d.rest_changed += u64::from((a.reason == EndReason::Rest) != (b.reason == EndReason::Rest));
        if let Some(m) = c.moved {
            if c.differs && d.moved.is_none_or(|(w, _)| m > w) {
                d.moved = Some((m, s));
            }
        }
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_revision_against_itself_changes_nothing() {
        let d = compare(Kind::Cluster, 0, 5, Revision::R4, Revision::R4);
        assert_eq!(d.scenes, 5);
        assert_eq!((d.differ, d.rest_changed, d.moved), (0, 0, None));
        assert_eq!(d.events.0, d.events.1);
    }

    #[test]
    fn revision_5_leaves_game_like_boards_and_cradles_as_they_were() {
        for kind in [Kind::GameLike, Kind::Cradle] {
            let d = compare(kind, 0, 20, Revision::R4, Revision::R5);
            assert_eq!(d.differ, 0, "{}", kind.name());
        }
    }

    #[test]
    fn a_change_measures_how_far_a_resting_disc_moved_in_radii() {
        let end = |x: f64| Ending {
            t: 1.0,
            reason: EndReason::Rest,
            events: 3,
            discs: vec![(BodyId(1), DVec2::new(x, 0.0), 0.5)],
        };
        assert!(!change(&end(0.0), &end(0.0)).differs);
        let c = change(&end(0.0), &end(0.25));
        assert!(c.differs);
        assert_eq!(c.moved, Some(0.5));
    }
}
