//! # hosted — bots that live on the server
//!
//! A hosted bot is a WebAssembly module the server runs itself, so it
//! plays whenever it is paired, with no process of its author's online.
//! Every bot gets the same computation, not the same wall time: each
//! decision runs under a fixed fuel budget (wasmi's fuel, about one unit
//! per instruction interpreted) and a memory limit, so a match between
//! hosted bots is reproducible bit for bit from its record.
//!
//! The module's contract is in [`abi`]: one exported function takes the
//! JSON of a [`game::decide::DecideRequest`] and returns the JSON of the
//! decision. Two host functions ([`host`]) let it simulate shots in
//! batches on the native engine, charged a fixed fuel price per shot, and
//! draw randomness from a stream derived from the match's secret
//! ([`randomness`]). Nothing else is imported: no WASI, no clock, no file
//! system.
//!
//! Modules: [`abi`] (names and layout a module follows), [`limits`] (the
//! budget of a load and of a decision), [`module`] (loading and checking a
//! module: [`BotModule`]), [`host`] (the host functions), [`randomness`]
//! (the per-decision stream), [`run`] (one decision: [`BotModule::decide`]).

pub mod abi;
pub mod host;
pub mod limits;
pub mod module;
pub mod randomness;
pub mod run;

pub use limits::Limits;
pub use module::{BotModule, LoadError};
pub use randomness::DecisionSeed;
pub use run::{DecideError, Decided};
