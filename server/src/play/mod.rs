//! The play layer: live matches and the lobby around them, between the web
//! layer ([`crate::web`]) and the store.
//!
//! - [`hub`]: the registry of this node's rooms; creates, joins, finds and
//!   stops matches;
//! - [`room`]: the task that drives one match's [`game::session`] and asks
//!   the computer levels of the [`bots`] crate for their moves;
//! - [`hosted`]: the budget hosted bots' decisions run under, and their
//!   compiled modules;
//! - [`adaptive_memory`]: where the adaptive level starts against a
//!   returning person, from the store;
//! - [`cluster`]: several nodes on one PostgreSQL store, with Redis relaying
//!   live play between them.

pub(crate) mod adaptive_memory;
pub(crate) mod cluster;
pub(crate) mod hosted;
pub(crate) mod hub;
pub(crate) mod room;
