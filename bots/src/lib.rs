//! # bots — Chapaev for machines
//!
//! Everything a bot author needs, in Rust: the [`Bot`] trait (one required
//! method: given what a player may know, decide), the [`Simulator`] that
//! plays a candidate shot with exactly the server's physics and rules,
//! scripted bots to learn from and measure against ([`RandomBot`],
//! [`Greedy`], [`Search`]), the computer levels people play
//! ([`Level`]: easy, medium, hard, each choosing for its own person-like
//! [`hand`], and adaptive, which tunes its hand to keep a match even), whole
//! matches in this process ([`arena`]), round-robin tournaments with Elo,
//! LOS and SPRT ([`tournament`], [`stats`]), and a bot playing on a real
//! server over the match protocol ([`runner`], following the match with
//! [`follow`]).
//!
//! Fair play is built in: a bot is handed a [`game::MatchView`], which has
//! no seed, so it can never know the execution noise of a shot before it
//! is played; the simulator applies only noise the bot drew itself.
//!
//! Modules: [`bot`] (the trait and its context), [`simulator`] (candidate
//! shots on a copy of the board), [`candidates`] (which shots to try),
//! [`eval`] (how good a result is), [`pie`] (the pie-rule decision by
//! playouts), [`random`], [`greedy`], [`search`] (the
//! scripted bots), [`hand`] (how a person misses), [`handed`] (a bot's
//! shots played by such a hand), [`planner`] (choosing for one's own
//! hand), [`adaptive`] (the level that keeps a match even), [`level`]
//! (computer levels and named bots), [`misses`] (how the levels miss,
//! measured), [`arena`] (one match in process), [`remote`] (one match on a
//! server), [`stats`] (Elo, LOS, SPRT), [`tournament`],
//! [`follow`] (a seat's view kept from the server's messages), [`runner`]
//! (a bot on a server: create or join, play, reconnect), [`owner`]
//! (connecting on the node of a cluster that plays the match), [`hosted_bot`] (a
//! WebAssembly bot as a [`Bot`]), [`program`] (any program speaking JSON
//! lines as a [`Bot`]).
//!
//! The levels and everything they stand on ([`bot`], [`clock`],
//! [`simulator`], [`candidates`], [`eval`], [`pie`], [`hand`], [`handed`],
//! [`planner`], [`search`], [`adaptive`], [`level`] and the scripted bots)
//! build without any feature, also for `wasm32-unknown-unknown`, where the
//! browser plays them offline. The rest (in process matches, tournaments,
//! the runner, hosted and program bots, the command line) needs the
//! default `runner` feature; the levels' work runs on all cores with
//! `parallel` (which `runner` turns on), else in the calling thread.

/// The README's example, compiled and run as a doctest.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;

pub mod adaptive;
#[cfg(feature = "runner")]
pub mod arena;
pub mod bot;
pub mod candidates;
pub mod clock;
pub mod eval;
#[cfg(feature = "runner")]
pub mod follow;
pub mod greedy;
pub mod hand;
pub mod handed;
#[cfg(feature = "runner")]
pub mod hosted_bot;
pub mod level;
#[cfg(feature = "runner")]
pub mod misses;
#[cfg(feature = "runner")]
pub mod online;
#[cfg(feature = "runner")]
pub mod owner;
mod par;
pub mod pie;
pub mod planner;
#[cfg(feature = "runner")]
pub mod program;
pub mod random;
#[cfg(feature = "runner")]
pub mod remote;
#[cfg(feature = "runner")]
pub mod runner;
pub mod search;
pub mod simulator;
pub mod stats;
#[cfg(feature = "runner")]
pub mod tournament;

pub use adaptive::{Adaptive, AdaptiveSettings};
#[cfg(feature = "runner")]
pub use arena::{play_match, ArenaLimits, MatchReport};
pub use bot::{Ask, Bot, Context, Decision};
pub use greedy::Greedy;
pub use hand::{Aim, Bias, Hand, HandModel};
pub use handed::{Handed, Throw};
pub use level::{by_name, Imprecise, Level, BOT_NAMES};
pub use planner::{PlanSettings, Planner};
pub use random::RandomBot;
#[cfg(feature = "runner")]
pub use runner::{CreateMatch, Opponent, RunReport, Runner, RunnerError, RunnerOptions, SeatGrant};
pub use search::{Search, SearchSettings};
pub use simulator::{Simulated, Simulator};
