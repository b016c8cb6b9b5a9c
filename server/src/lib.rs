//! # server — Chapaev online's match server
//!
//! Players create and join matches over HTTP, then play over a WebSocket:
//! the server checks each shot against the rules, resolves it exactly with
//! the [`game`] crate, writes it to SQLite, and only then broadcasts what it
//! did to both players and every spectator. Built-in bots play from inside
//! the server; a turn clock keeps matches moving; a dropped player keeps the
//! seat for a grace period; a restarted server resumes every match from the
//! store. The wire protocol is `docs/protocol.md`.
//!
//! The rules of a live match (seats, turn clock, grace, rematch) are
//! [`game::session`], a state machine without I/O; a [`room`] drives one.
//!
//! Modules: [`config`] (flags and limits), [`token`] (seat tokens and ids),
//! [`accounts`] (names, keys and ratings that last; their HTTP API is
//! [`accounts_api`]),
//! [`refusal`] (errors sent to clients, with their HTTP statuses),
//! [`store`] (SQLite, with [`readers`], its read connections, or PostgreSQL; [`local_postgres`] and [`local_redis`] start throwaway servers for tests), [`metrics`] (Prometheus), [`origin`] (cross-site
//! requests refused), [`ratelimit`]
//! (per-connection token bucket), [`room`] (the task that drives one
//! match's session and asks the computer levels of the [`bots`] crate for
//! their moves), [`hub`] (the registry of
//! rooms), [`http`] (the HTTP API), [`simulate`] (`POST /api/simulate`,
//! limited per address), [`assets`] (the embedded web client at
//! `/`), [`ws`] (the WebSocket sessions), [`cluster`] (several nodes on one PostgreSQL store, with Redis relaying live play), [`app`] (startup and
//! shutdown) and [`loopback`] (the HTTP client of the server's own tools).

pub mod accounts;
pub mod accounts_api;
pub mod adaptive_memory;
pub mod app;
pub mod assets;
pub mod auth;
pub mod blocking;
pub mod checkpointer;
pub mod cluster;
pub mod config;
pub mod http;
pub mod hub;
pub mod lobby;
pub mod local_postgres;
pub mod local_redis;
pub mod loopback;
pub mod metrics;
pub mod origin;
pub mod ratelimit;
pub mod ratings;
pub mod readers;
pub mod refusal;
pub mod room;
pub mod simulate;
pub mod store;
pub mod stream;
pub mod token;
pub mod ws;
