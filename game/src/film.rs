//! The film of one shot: everything needed to show any moment of it exactly.
//!
//! A [`Film`] is the engine's chain in a compact, sendable form: the
//! snapshot (every piece with its trajectory) at the moment of the shot,
//! then one [`SceneDiff`] per distinct event time listing only the pieces
//! whose motion changed (a piece that fell off appears with `None`). The
//! state at any time `t` is the start with every diff up to `t` applied,
//! advanced in closed form — the same bits the engine's own model gives.

use engine::model::{SceneDiff, Snapshot};
use engine::{EventHandler, Model, Scene};
use serde::{Deserialize, Serialize};

/// One shot's motion, from the flick (t = 0) until everything rests.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Film {
    /// The pieces and their trajectories at t = 0.
    pub start: Snapshot,
    /// The changes at each event time, in time order.
    pub diffs: Vec<SceneDiff>,
    /// When the last piece came to rest (or the computation stopped).
    pub end: f64,
}

impl Film {
    /// Records the film of a computed model that started at t = 0.
    pub fn of<H: EventHandler>(model: &Model<H>, end: f64) -> Film {
        let mut start = model.snapshot_at(f64::NEG_INFINITY);
        start.t = 0.0;
        let mut diffs = Vec::new();
        let mut prev = f64::NEG_INFINITY;
        for e in model.events() {
            if e.t == prev {
                continue;
            }
            let mut d = model.diff(prev, e.t);
            d.from = prev.max(0.0);
            diffs.push(d);
            prev = e.t;
        }
        Film { start, diffs, end }
    }

    /// How long the shot lasts.
    pub fn duration(&self) -> f64 {
        self.end
    }

    /// Pieces and trajectories in effect at time `t` (clamped to `[0, end]`
    /// for the diffs; positions are then advanced to `t` by [`Film::scene_at`]).
    pub fn snapshot_at(&self, t: f64) -> Snapshot {
        let mut snap = self.start.clone();
        let n = self.diffs.partition_point(|d| d.to <= t);
        for d in &self.diffs[..n] {
            d.apply(&mut snap);
        }
        snap.t = t;
        snap
    }

    /// The scene (positions and velocities of the pieces still on the
    /// board) at time `t` of the shot.
    pub fn scene_at(&self, t: f64) -> Scene {
        self.snapshot_at(t).scene_at(t)
    }
}
