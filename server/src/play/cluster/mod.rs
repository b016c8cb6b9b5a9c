//! Several server nodes sharing one PostgreSQL store, with Redis relaying
//! live play between them (`--redis-url`).
//!
//! **Ownership.** Each live match is played by exactly one node at a time:
//! the node holding its row in `match_leases` (owner, expiry), which it
//! takes when it creates or loads the match and renews every third of the
//! lease (`--lease-seconds`) while it lives. The store fences every move:
//! a node writes a move only while its lease is unexpired
//! ([`crate::store::postgres`]), so a node that lost its lease (paused,
//! cut off) can never write behind its successor's back. A node that
//! cannot renew a lease stops that match's room.
//!
//! **Relaying.** A client may connect to any node. A node asked for a
//! match another node owns starts a *proxy room* for it: a task that takes
//! the same [`Command`]s as a real room (connect, message, disconnect,
//! join) and relays them over Redis pub/sub to the owner, whose
//! dispatcher hands them to the real room as if its client were local. The
//! owner relays everything the room sends that connection back, numbered
//! per connection, in one envelope per node for all that node's
//! connections at once (a message several of them are sent crosses once);
//! the relaying node fans it out and forwards each connection's messages
//! in order, and a gap (a message lost by pub/sub) ends the connection, so the client reconnects
//! and starts again from the full `match-state`: it never sees a gap or a
//! duplicate. Every client thus gets exactly the messages a client of the
//! owner gets, in the same order.
//!
//! **Routing.** A client may instead ask to be sent to the owner
//! (`/ws?match=ID&follow=1`): a node that knows the owner's public URL
//! (`--public-url`, recorded with each node's heartbeat) answers `307`
//! to it ([`Cluster::route`]), and the client plays on the owner as a
//! local one; where the owner is unknown or unreachable, it is relayed.
//!
//! **Takeover.** Every node looks, every second, for live matches whose
//! lease has expired (their node died) and takes them: it loads the match
//! from PostgreSQL (every acknowledged move is there) and resumes it. Proxy
//! rooms learn within a quarter of a second that their owner's lease
//! expired or moved; they end, their clients reconnect and reach the new
//! owner. A node that stops cleanly gives its leases up at once.
//!
//! Redis carries only live traffic (nothing in it needs to survive a Redis
//! restart; connections relayed through a lost subscription reconnect),
//! and it must be reachable only by the nodes: seat tokens cross it.

//!
//! The modules, each using only those listed before it:
//!
//! | module | what it is |
//! | --- | --- |
//! | [`wire`] | the envelopes nodes send each other, and their JSON |
//! | [`relay`] | relay sequencing: numbered deliveries, duplicates, gaps |
//! | [`outlet`] | what goes back to a node: its connections' messages batched into one envelope, each message once |
//! | [`leases`] | the lease rules (renewal, loss, takeover, moved proxies), without I/O |
//! | [`rooms`] | [`LocalRooms`], what the cluster needs of the node's own rooms |
//! | [`node`] | [`Cluster`]: a node's PostgreSQL and Redis connections and tables |
//! | [`serve`] | the owner's side of a relayed connection |
//! | [`inbox`] | the node's Redis channel and what it does with each envelope |
//! | [`proxy`] | proxy rooms and the check on their owners' leases |
//! | [`keeper`] | lease renewal and takeover |
//!
//! The cluster knows the node's rooms only through [`LocalRooms`], which
//! the hub implements: the hub uses the cluster, never the other way.

mod inbox;
mod keeper;
mod leases;
mod node;
mod outlet;
mod proxy;
mod relay;
mod rooms;
mod serve;
mod wire;

pub use leases::Lease;
pub use node::{Cluster, ClusterError};
pub(crate) use rooms::LocalRooms;

use std::sync::Arc;

impl Cluster {
    /// Starts this node's tasks on `rt`: the dispatcher of its Redis
    /// channel, lease renewal, takeover of orphaned matches, and the
    /// checks on the nodes it serves and on its proxies' owners.
    pub fn start<R: LocalRooms>(self: &Arc<Self>, rooms: &R, rt: &tokio::runtime::Handle) {
        rt.spawn(inbox::dispatch(self.clone(), rooms.clone()));
        rt.spawn(keeper::keep_leases(self.clone(), rooms.clone()));
        rt.spawn(keeper::take_over(self.clone(), rooms.clone()));
        rt.spawn(serve::check_served(self.clone()));
        rt.spawn(proxy::check_owners(self.clone()));
    }
}
