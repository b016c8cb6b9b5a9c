//! The `scene_json` target: bytes read as a scene file
//! ([`engine::Scene::from_json`]) and, when it is a valid scene, computed by
//! the engine as `sim` computes it — a [`World`] run to its end — under an
//! event cap of [`MAX_EVENTS`], so that a scene whose chain never ends
//! (a frictionless box, a pushing chain that livelocks) is bounded, not a
//! hang. Checked: a refused scene is told why; a valid one reads back from
//! its own JSON export as itself, builds a world, and every event and the
//! final state are finite, with time never running backwards. A disc whose
//! centre leaves a sensor region is taken out of the scene for inputs of
//! odd length (the game's fall-off rule) and stays for even ones.

use engine::{
    BodyId, EndReason, Event, EventHandler, ExitResponse, Limits, LineId, Scene, World, WorldConfig,
};
use glam::DVec2;

/// The event cap of one run.
pub const MAX_EVENTS: u64 = 20_000;

/// Runs the scene `data` holds, if it holds one.
pub fn scene_json(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let scene = match Scene::from_json(text) {
        Ok(scene) => scene,
        Err(e) => {
            assert!(!e.to_string().is_empty(), "a refused scene is told why");
            return;
        }
    };
    let exported = scene.to_json();
    match Scene::from_json(&exported) {
        Ok(again) => assert_eq!(again, scene, "a scene reads back from its export"),
        Err(e) => panic!("a valid scene's export is refused: {e}\n{exported}"),
    }
    let mut world = match World::new(&scene, WorldConfig::default()) {
        Ok(world) => world,
        Err(e) => panic!("a valid scene is refused by the world: {e}"),
    };
    let limits = Limits {
        until: f64::INFINITY,
        max_collisions: u64::MAX,
        max_events: MAX_EVENTS,
    };
    let mut checked = Checked {
        last: scene.t,
        remove: data.len() % 2 == 1,
    };
    let end = world.run(&limits, &mut checked);
    assert!(
        end.t.is_finite() && end.t >= scene.t,
        "the run ended at {}",
        end.t
    );
    for body in world.bodies() {
        let pos = body.trajectory.position(end.t);
        let vel = body.trajectory.velocity(end.t);
        assert!(
            finite(pos) && finite(vel),
            "{:?} at the end: {pos} {vel}",
            body.id
        );
        if end.reason == EndReason::Rest {
            assert_eq!(vel, DVec2::ZERO, "{:?} moves at rest", body.id);
        }
    }
}

fn finite(v: DVec2) -> bool {
    v.is_finite()
}

/// Checks every event as it happens.
struct Checked {
    /// The time of the last event (or the scene's).
    last: f64,
    /// Whether a disc leaving a region is removed.
    remove: bool,
}

impl EventHandler for Checked {
    fn on_event(&mut self, world: &World, event: &Event) {
        assert!(
            event.t.is_finite() && event.t >= self.last,
            "{event:?} after t = {}",
            self.last
        );
        self.last = event.t;
        for id in event.kind.bodies() {
            if let Some(body) = world.body(id) {
                let pos = body.trajectory.position(event.t);
                let vel = body.trajectory.velocity(event.t);
                assert!(
                    finite(pos) && finite(vel),
                    "{event:?}: {id:?} at {pos} {vel}"
                );
            }
        }
    }

    fn on_region_exit(&mut self, _t: f64, _body: BodyId, _line: LineId) -> ExitResponse {
        if self.remove {
            ExitResponse::Remove
        } else {
            ExitResponse::Stay
        }
    }
}
