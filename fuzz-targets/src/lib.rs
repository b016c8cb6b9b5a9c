//! # fuzz-targets — what the fuzzers feed in and what they check
//!
//! One function per cargo-fuzz target, taking the fuzzer's bytes: the
//! `fuzz/` package (a cargo-fuzz workspace of its own) only calls them, and
//! this crate's tests replay every kept input (`fuzz/corpus/<target>/`,
//! `fuzz/artifacts/<target>/`) through the very same functions in
//! `cargo test -p fuzz-targets`, so a crash once found stays fixed.
//! A function returns quietly on input it has no use for and panics, with
//! the invariant that broke, on a bug.
//!
//! - [`protocol_session`]: a script of client frames, connections, clock
//!   steps and store failures driving a live match [`game::session::Session`];
//! - [`scene_json`]: a scene file through the engine, under an event cap;
//! - [`record_replay`]: a match record through replay.
//!
//! Modules: [`cursor`] (reading numbers off the fuzzer's bytes), [`script`]
//! (the operations a `protocol_session` input encodes), [`driver`] (a
//! session's driver that checks every answer), and one module per target.

pub mod cursor;
pub mod driver;
pub mod protocol_session;
pub mod record_replay;
pub mod scene_json;
pub mod script;

pub use protocol_session::protocol_session;
pub use record_replay::record_replay;
pub use scene_json::scene_json;

/// A target: runs one input, panicking on a bug.
pub type Target = fn(&[u8]);

/// The targets, by the names cargo-fuzz and the corpus folders know them.
pub const TARGETS: [(&str, Target); 3] = [
    ("protocol_session", protocol_session),
    ("scene_json", scene_json),
    ("record_replay", record_replay),
];
