//! How rules and observers plug into a computation: the [`EventHandler`]
//! a run calls after every event and at every region exit, what it may
//! answer ([`ExitResponse`]), and the two handlers the crate ships (`()`,
//! which does nothing, and [`Counter`]).
//!
//! A handler is handed the [`World`] as it stands after each event, so this
//! module is a part of the world's: it is the world's child, the one place
//! it names its parent.

use super::World;
use crate::event::Event;
use crate::id::{BodyId, LineId};

/// What the rules decide for a disc whose centre left a region.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExitResponse {
    /// The disc carries on (the engine's default).
    Stay,
    /// The disc leaves the scene now and takes no further part.
    Remove,
}

/// Rules and observers plugged into a computation.
///
/// `on_event` is the one required method; `()` implements it as a no-op.
pub trait EventHandler {
    /// Called after each event has been applied; `world` shows the state
    /// right after it. Must not assume anything about later events.
    fn on_event(&mut self, world: &World, event: &Event);

    /// Called when the centre of `body` crosses the sensor `line` from its
    /// inside (left) to its outside, at time `t`, before the event is
    /// recorded. Return [`ExitResponse::Remove`] to take the disc out of the
    /// scene at that moment. The default keeps it.
    fn on_region_exit(&mut self, _t: f64, _body: BodyId, _line: LineId) -> ExitResponse {
        ExitResponse::Stay
    }
}

impl EventHandler for () {
    fn on_event(&mut self, _world: &World, _event: &Event) {}
}

/// Counts events (the handler the benchmarks use).
#[derive(Clone, Copy, Debug, Default)]
pub struct Counter {
    pub events: u64,
    pub collisions: u64,
}

impl EventHandler for Counter {
    #[inline]
    fn on_event(&mut self, _world: &World, event: &Event) {
        self.events += 1;
        self.collisions += event.kind.is_collision() as u64;
    }
}
