//! What the cluster needs of the node's own rooms: the one seam between
//! the cluster's tasks and the registry of rooms that plays matches
//! (the hub implements it). The cluster never reaches
//! the registry any other way, so the dependency runs one way: the hub
//! knows the cluster, the cluster knows only this trait.
//!
//! Every method acts on matches *this node plays*: none relays on to
//! another node (a relayed request that reached the wrong node is refused,
//! and its client's node asks again where the match is now).

use crate::play::room::{Claim, Command, Connected};
use crate::refusal::Refusal;
use game::token::TokenHash;
use game::Seat;
use std::future::Future;
use tokio::sync::mpsc;

/// The node's own rooms, as the cluster sees them (see the module's
/// documentation). Cheap to clone: each task keeps its own handle.
pub(crate) trait LocalRooms: Clone + Send + Sync + 'static {
    /// Admits a connection relayed from another node to match `id`,
    /// loading the match and taking its lease if nobody holds it: the
    /// room's command queue, and the connection. Refused (`server-busy`)
    /// if another node plays the match.
    fn connect_owned(
        &self,
        id: &str,
        claim: Claim,
    ) -> impl Future<Output = Result<(mpsc::Sender<Command>, Connected), Refusal>> + Send;

    /// Takes the empty second seat of `id` for the holder of the token
    /// with this hash (a join relayed from another node).
    fn join_owned(
        &self,
        id: &str,
        name: String,
        token: TokenHash,
        account: Option<String>,
    ) -> impl Future<Output = Result<Seat, Refusal>> + Send;

    /// Plays match `id` if nobody else does (taking over a match whose
    /// node died): `true` if this node started playing it now, `false` if
    /// it already did.
    fn own(&self, id: &str) -> impl Future<Output = Result<bool, Refusal>> + Send;

    /// The ids of the matches this node plays (not those it relays): the
    /// leases it must renew.
    fn owned_matches(&self) -> Vec<String>;

    /// Stops the room of `id` (its lease is lost): it finishes the command
    /// in hand, and its connections end (their clients reconnect). Nothing
    /// happens if there is no such room.
    fn stop_room(&self, id: &str) -> impl Future<Output = ()> + Send;
}
