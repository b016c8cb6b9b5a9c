//! # server — Chapaev online's match server
//!
//! Players create and join matches over HTTP, then play over a WebSocket:
//! the server checks each shot against the rules, resolves it exactly with
//! the [`game`] crate, writes it to the store, and only then broadcasts what
//! it did to both players and every spectator. Built-in bots play from
//! inside the server; a turn clock keeps matches moving; a dropped player
//! keeps the seat for a grace period; a restarted server resumes every
//! match from the store. The wire protocol is `docs/protocol.md`.
//!
//! The rules of a live match (seats, turn clock, grace, rematch) are
//! [`game::session`], a state machine without I/O; a room drives one.
//!
//! The crate's rooms, each a layer that only calls the ones below it:
//!
//! | module | what it owns |
//! | --- | --- |
//! | [`app`] | startup and shutdown: the runtimes, the store, the cluster, the HTTP server |
//! | `web` | HTTP routes and the WebSocket endpoints: `matches` (the match API, `/api`, `/healthz`, `/metrics`), `accounts` (the accounts API), `auth`, `assets` (the embedded web client), `simulate`, `ws` (a match's socket), `stream` (the lobby's event stream), `reply`, `origin`, `client_addr` (the client's address behind trusted proxies), `ratelimit`, `blocking` |
//! | `play` | live matches: `hub` (the registry of rooms), `room` (one match's task), `adaptive_memory`, `cluster` (several nodes on PostgreSQL and Redis) |
//! | `accounts` | creating accounts, their keys and passwords (names follow `game::name`) |
//! | [`store`] | SQLite (with its read connections and checkpointer) or PostgreSQL, behind one trait |
//! | `backup` | `server backup` and `server restore`: the store copied out while it plays, and back in, proven by replaying every match |
//! | [`config`] | flags and limits |
//! | [`metrics`] | the Prometheus metrics |
//! | `limit_key` | what the per-address limits count by (an IPv6 client's /64) |
//! | `token` | seat tokens, account keys and ids |
//! | `refusal` | errors sent to clients, with their HTTP statuses |
//!
//! The throwaway PostgreSQL and Redis of the tests are the
//! `local-services` crate (`testkit/`), a dev-dependency only. Public are
//! only the modules the server's binaries and tests use. The HTTP client
//! those share is not here but in `tools/loopback.rs`, which each of them
//! includes.

mod accounts;
pub mod app;
mod backup;
pub mod config;
mod limit_key;
pub mod metrics;
mod play;
mod refusal;
pub mod store;
mod token;
mod web;
