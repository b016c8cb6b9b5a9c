//! This engine, driven as a user would: a [`World`] with a chosen root
//! solver and broad phase, the Chapaev fall-off rule as its event handler
//! (a disc whose centre leaves the board is removed), run to the case's
//! time or event cap. Optionally every event is checked for overlapping
//! discs (the engine promises there are none).

use crate::outcome::{overlap_of, BodyEnd, Outcome};
use crate::scenes::Case;
use crate::LabError;
use engine::roots::Method;
use engine::world::BroadPhase;
use engine::{
    BodyId, EndReason, Event, EventHandler, ExitResponse, Limits, LineId, World, WorldConfig,
};
use std::time::Instant;

/// Removes discs that leave the board, counts collisions, and (if asked)
/// records the worst overlap seen at any event.
struct Rules {
    removed: Vec<BodyId>,
    collisions: u64,
    check_overlap: bool,
    max_overlap: f64,
}

impl EventHandler for Rules {
    fn on_event(&mut self, world: &World, event: &Event) {
        self.collisions += event.kind.is_collision() as u64;
        if self.check_overlap {
            let b: Vec<_> = world
                .bodies()
                .map(|b| (b.trajectory.position(event.t), b.material.radius))
                .collect();
            self.max_overlap = self.max_overlap.max(overlap_of(&b));
        }
    }

    fn on_region_exit(&mut self, _t: f64, body: BodyId, _line: LineId) -> ExitResponse {
        self.removed.push(body);
        ExitResponse::Remove
    }
}

/// Computes `case` with the engine; `check_overlap` costs O(n^2) per event.
pub fn run(
    case: &Case,
    solver: Method,
    broad_phase: BroadPhase,
    check_overlap: bool,
) -> Result<Outcome, LabError> {
    let start = Instant::now();
    let mut world = World::new(
        &case.scene,
        WorldConfig {
            solver,
            broad_phase,
            ..WorldConfig::default()
        },
    )?;
    let mut rules = Rules {
        removed: Vec::new(),
        collisions: 0,
        check_overlap,
        max_overlap: 0.0,
    };
    let limits = Limits {
        until: case.until,
        max_events: case.max_events,
        ..Limits::default()
    };
    let end = world.run(&limits, &mut rules);
    let secs = start.elapsed().as_secs_f64();
    let t = case.until.max(world.last_event_time());
    let mut bodies: Vec<BodyEnd> = case
        .scene
        .bodies
        .iter()
        .map(|spec| match world.body(spec.id) {
            Some(b) => BodyEnd {
                id: spec.id.0,
                pos: b.trajectory.position(t),
                vel: b.trajectory.velocity(t),
                removed: false,
            },
            None => BodyEnd {
                id: spec.id.0,
                pos: spec.pos,
                vel: spec.vel,
                removed: true,
            },
        })
        .collect();
    bodies.sort_by_key(|b| b.id);
    Ok(Outcome {
        bodies,
        collisions: rules.collisions,
        capped: end.reason == EndReason::MaxEvents,
        max_overlap: rules.max_overlap,
        secs,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes;

    #[test]
    fn engine_counts_galperin_four_digits_with_every_solver() {
        for m in Method::ALL {
            let out = run(&scenes::galperin(4), m, BroadPhase::Auto, false).unwrap();
            assert_eq!(out.collisions, 3141, "{}", m.name());
        }
    }

    #[test]
    fn break_shot_removes_discs_that_leave_the_board() {
        let out = run(
            &scenes::hard_break().unwrap(),
            Method::Production,
            BroadPhase::Auto,
            true,
        )
        .unwrap();
        assert!(out.bodies.iter().any(|b| b.removed));
        assert!(out.max_overlap <= 1e-9);
    }
}
