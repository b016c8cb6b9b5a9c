//! What the engine's scenario tests share: event handlers that measure a
//! run as it goes.

use engine::{Event, EventHandler, World};

/// The deepest overlap between any two discs at any event, as a fraction
/// of their contact distance.
#[derive(Default)]
pub struct Deepest(pub f64);

impl EventHandler for Deepest {
    fn on_event(&mut self, world: &World, event: &Event) {
        let bodies: Vec<_> = world.bodies().collect();
        for (k, a) in bodies.iter().enumerate() {
            for b in &bodies[k + 1..] {
                let s = a.material.radius + b.material.radius;
                let d = (a.trajectory.position(event.t) - b.trajectory.position(event.t)).length();
                self.0 = self.0.max((s - d) / s);
            }
        }
    }
}
