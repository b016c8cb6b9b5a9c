//! # engine — an exact a priori engine for sliding discs
//!
//! Discs slide on a plane under Coulomb friction, hit each other, fixed
//! points and lines, and stop. Between two events every trajectory is a
//! closed-form function of time, so the engine *computes* when the next
//! contact happens (a polynomial root) and jumps there: no time step, no
//! tunnelling, no overlap to repair. The result is a chain of timed scenes
//! ([`Model`]) that can be queried at any time, rewound and replayed exactly.
//!
//! ```
//! use engine::{Scene, Model, Limits};
//! let scene = Scene::from_json(r#"{
//!   "bodies": [
//!     { "id": 1, "pos": [0.0, 0.0], "vel": [2.0, 0.0], "radius": 0.016, "mass": 0.01, "mu": 0.3 },
//!     { "id": 2, "pos": [0.5, 0.0], "vel": [0.0, 0.0], "radius": 0.016, "mass": 0.01, "mu": 0.3 }
//!   ]
//! }"#).unwrap();
//! let mut model = Model::new(scene).unwrap();
//! let end = model.compute(&Limits::default());
//! assert_eq!(model.events()[0].kind.name(), "body-body");
//! // Equal masses, head on: the striker stops, the target slides on.
//! let at_end = model.scene_at(end.t);
//! assert_eq!(at_end.bodies[0].vel.length(), 0.0);
//! ```
//!
//! Modules, from the bottom up: [`roots`] (polynomial root solvers),
//! [`trajectory`] (closed-form motion), [`obstacle`] (points and lines),
//! [`contact`] (when two things touch), [`impulse`] (what a contact does),
//! [`push`] (touching discs that brake unequally and press together),
//! [`wedge`] (a light disc wedged along a wall by one sliding past it),
//! [`collapse`] (the limit of endless hits at one instant), [`ring`] (a
//! ring of hits at one instant played in memory),
//! [`calendar`] and [`grid`] (which event is next, who is near whom),
//! [`instant`] (when two event times are one moment), [`limits`] (when a
//! run stops, and the guards that make sure it does), [`world`] (the event
//! loop; rules plug in through [`world::handler`]), [`model`] (the chain of scenes: queries at any
//! time, actions, rewind, diffs), [`scene`] (the JSON scene format),
//! [`revision`] (which rules a computation runs, so old records replay),
//! [`presets`] (ready-made scenes) and [`rng`] (the fixed random streams of
//! layouts, tools and tests).
//! The library does no I/O; the `sim` binary is a thin shell over it.

// `!(x > 0.0)` is deliberate throughout: it is also true for NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod calendar;
pub mod clock;
pub mod collapse;
pub mod contact;
pub mod event;
mod graze;
pub mod grid;
pub mod id;
pub mod impulse;
pub mod instant;
pub mod limits;
pub mod model;
pub mod obstacle;
mod pivot;
pub mod presets;
pub mod push;
pub mod revision;
pub mod ring;
pub mod rng;
pub mod roots;
pub mod scene;
pub mod trajectory;
pub mod wedge;
pub mod world;

pub use event::{Event, EventKind};
pub use id::{BodyId, LineId, PointId};
pub use limits::{End, EndReason, Limits};
pub use model::{Action, Model, ModelRecord, SceneDiff, Snapshot, TimedAction};
pub use obstacle::{Line, LineKind, Point};
pub use revision::{Revision, UnknownRevision};
pub use scene::{BodySpec, Scene, SceneError};
pub use trajectory::Trajectory;
pub use world::{EventHandler, ExitResponse, World, WorldConfig};
