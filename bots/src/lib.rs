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

/// The README's example, compiled and run as a doctest.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;

pub mod adaptive;
pub mod arena;
pub mod bot;
pub mod candidates;
pub mod eval;
pub mod follow;
pub mod greedy;
pub mod hand;
pub mod handed;
pub mod hosted_bot;
pub mod level;
pub mod misses;
pub mod online;
pub mod owner;
pub mod pie;
pub mod planner;
pub mod program;
pub mod random;
pub mod remote;
pub mod runner;
pub mod search;
pub mod simulator;
pub mod stats;
pub mod tournament;

pub use adaptive::{Adaptive, AdaptiveSettings};
pub use arena::{play_match, ArenaLimits, MatchReport};
pub use bot::{Ask, Bot, Context, Decision};
pub use greedy::Greedy;
pub use hand::{Aim, Bias, Hand, HandModel};
pub use handed::{Handed, Throw};
pub use level::{by_name, Imprecise, Level, BOT_NAMES};
pub use planner::{PlanSettings, Planner};
pub use random::RandomBot;
pub use runner::{CreateMatch, Opponent, RunReport, Runner, RunnerError, RunnerOptions, SeatGrant};
pub use search::{Search, SearchSettings};
pub use simulator::{Simulated, Simulator};
