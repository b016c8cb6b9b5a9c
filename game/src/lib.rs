//! # game — Chapaev rules on the engine
//!
//! Chapaev is Russian flick-checkers: each side's eight checkers stand on
//! its row, and players take turns flicking one of their own pieces to knock
//! the opponent's off the board. This crate is the whole game without any
//! networking — the server, the bots and the client all play through it.
//! Every shot is resolved exactly by the [`engine`] (an event-driven disc
//! physics engine), and every match can be recorded and replayed bit for
//! bit.
//!
//! ```
//! use game::{Config, Game, PieceId, Shot, Side};
//! use glam::DVec2;
//!
//! let mut game = Game::new(Config::default(), 7).unwrap();
//! assert_eq!(game.to_shoot(), Some(Side::White));
//! // Flick White's e-piece straight up the board at full power: it crosses
//! // the board, hits Black's e-piece and knocks it off.
//! let piece = PieceId::new(Side::White, 4).unwrap();
//! let shot = Shot::new(piece, DVec2::new(0.0, 2.0), game.config()).unwrap();
//! let played = game.play(Side::White, shot).unwrap();
//! assert!(played.outcome.knocked_off.contains(&PieceId::new(Side::Black, 4).unwrap()));
//! // The state at any moment of the shot, for drawing it.
//! let halfway = played.film.scene_at(played.film.duration() / 2.0);
//! assert!(halfway.bodies.len() <= 16);
//! // It knocked a piece off, so White shoots again: Black is refused.
//! let black = PieceId::new(Side::Black, 0).unwrap();
//! let shot = Shot::new(black, DVec2::new(0.0, -1.0), game.config()).unwrap();
//! let err = game.play(Side::Black, shot).unwrap_err();
//! assert_eq!(err.code().as_str(), "not-your-turn");
//! ```
//!
//! Modules: [`config`] (geometry, physics, variants), [`side`] (colours and
//! seats), [`piece`] (piece identity), [`board`] (geometry and the pieces
//! between shots), [`rows`] (rows and how they move between rounds),
//! [`shot`] (a valid flick and why shots are refused), [`noise`]
//! (deterministic execution noise), [`secret`] (the match's noise secret
//! and its public commitment), [`verify`] (checking a finished match's
//! noise against its commitment), [`physics`] (a shot resolved by the
//! engine, with the fall-off rule), [`physics_version`] (which physics
//! decides a shot: the version every record carries), [`film`] (a shot's
//! motion at any time), [`rules`] (the turn rule), [`outcome`] (what
//! shots, rounds and matches came to), [`game`] (the match state machine),
//! [`record`] (the versioned match record), [`replay`] (bit-exact replay
//! and scrubbing), [`golden`] (records of earlier builds that every build
//! must replay bit for bit), [`simulate`] (one shot on any position, as
//! plain data for every language), [`batch`] (many shots in one flat array
//! of numbers, for the language bindings), [`protocol`] (the wire messages
//! and refusals) and [`session`] (a live match — seats, connections, turn
//! clock, rematch — as a state machine without I/O, driven by the server's
//! rooms and by tests on a virtual clock) and its twin [`lobby`]
//! (challenges, quick pairing and the bot ladder between accounts, the
//! same kind of state machine, driven by the server's event stream), with [`token`] (seat tokens and
//! the hashes a server keeps), [`rating`] (Glicko-2 ratings and how a
//! rated match moves them) and [`name`] (the account-name rule the server
//! enforces and the client checks).

pub mod batch;
pub mod board;
pub mod config;
pub mod decide;
pub mod film;
pub mod game;
pub mod golden;
pub mod lobby;
pub mod name;
pub mod noise;
pub mod outcome;
pub mod phrase;
pub mod physics;
pub mod physics_version;
pub mod piece;
pub mod protocol;
pub mod rating;
pub mod record;
pub mod refusal;
pub mod replay;
pub mod rows;
pub mod rules;
pub mod secret;
pub mod session;
pub mod shot;
pub mod side;
pub mod simulate;
pub mod stream;
#[cfg(test)]
mod testing;
pub mod token;
pub mod verify;

pub use board::{Board, Piece};
pub use config::{Config, ConfigError, NoiseConfig, Preset, Variants};
pub use film::Film;
pub use game::{Game, GameError, MatchView, Phase, Played};
pub use noise::{NoiseKey, NoiseScheme};
pub use outcome::{ForfeitReason, MatchResult, Next, RoundEnd, ShotOutcome, WinReason};
pub use physics_version::{PhysicsVersion, UnsupportedPhysics, PHYSICS_VERSION};
pub use piece::PieceId;
pub use record::{MatchRecord, RecordError, RecordedMove, SealedNoise, RECORD_VERSION};
pub use replay::{Replay, ReplayError};
pub use rows::Rows;
pub use rules::RoundResult;
pub use secret::{NoiseCommitment, NoiseSecret};
pub use shot::{Shot, ShotError};
pub use side::{Seat, Side};
pub use simulate::{SimulateError, SimulateRequest, Simulation};
pub use verify::{verify, verify_json, Verification, VerifyError};
