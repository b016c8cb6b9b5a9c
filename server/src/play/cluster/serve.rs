//! The owner's side of a relayed connection: a node serving one of its
//! matches to a client of another node connects that client to the real
//! room, as if it were local, and hands what the room sends it to the
//! outlet of the client's node ([`super::outlet`]), which numbers it and
//! publishes it together with what that node's other clients are sent.
//! Connections served for a node that died end.

use super::node::{lock, Cluster, Served};
use super::outlet::{envelope, events, next_batch, Outgoing};
use super::rooms::LocalRooms;
use super::wire::{Envelope, WireRefusal};
use crate::play::room::{Claim, Command, Connected};
use futures_util::stream::SelectAll;
use std::collections::{HashMap, HashSet};
use std::sync::Arc;
use tokio::sync::mpsc;
use tracing::warn;

/// Serves a connection to a match this node plays for a client of node
/// `from`: connects it to the room and relays what the room sends it.
pub(super) async fn serve<R: LocalRooms>(
    cluster: Arc<Cluster>,
    rooms: R,
    from: String,
    link: u64,
    id: String,
    claim: Claim,
) {
    let (room, connected) = match rooms.connect_owned(&id, claim).await {
        Ok(c) => c,
        Err(r) => {
            let refusal = WireRefusal::from(&r);
            cluster
                .send(&from, &Envelope::Refused { link, refusal })
                .await;
            return;
        }
    };
    let Connected {
        conn,
        seat,
        rx,
        refused,
    } = connected;
    lock(&cluster.served).insert((from.clone(), link), Served { room, conn });
    // Published before anything the outlet publishes for it.
    cluster
        .send(&from, &Envelope::Connected { link, conn, seat })
        .await;
    cluster.send_back(&from, Outgoing { link, rx, refused });
}

impl Cluster {
    /// Relays what the room sends a connection served for node `to`'s
    /// client, through that node's outlet (started if there is none).
    pub(super) fn send_back(self: &Arc<Self>, to: &str, o: Outgoing) {
        let mut outlets = lock(&self.outlets);
        let o = match outlets.get(to) {
            Some(tx) => match tx.send(o) {
                Ok(()) => return,
                // Its outlet ended: a new one takes it.
                Err(mpsc::error::SendError(o)) => o,
            },
            None => o,
        };
        let (tx, rx) = mpsc::unbounded_channel();
        let _ = tx.send(o);
        outlets.insert(to.to_string(), tx);
        tokio::spawn(outlet(self.clone(), to.to_string(), rx));
    }
}

/// The outlet to node `node` (see the module's documentation): `rx` hands
/// it the connections to relay.
async fn outlet(cluster: Arc<Cluster>, node: String, mut rx: mpsc::UnboundedReceiver<Outgoing>) {
    let mut streams = SelectAll::new();
    let mut seqs = HashMap::new();
    loop {
        if streams.is_empty() {
            // Ends with its last connection, unless one is on its way
            // (looked at under the lock that hands connections over).
            let mut outlets = lock(&cluster.outlets);
            match rx.try_recv() {
                Ok(o) => streams.push(events(o)),
                Err(_) => {
                    outlets.remove(&node);
                    return;
                }
            }
        }
        tokio::select! {
            biased;
            Some(o) = rx.recv() => streams.push(events(o)),
            batch = next_batch(&mut streams) => {
                if batch.is_empty() {
                    continue;
                }
                let e = envelope(&cluster.node, batch, &mut seqs);
                if let Envelope::Deliveries { closed, .. } = &e {
                    let mut served = lock(&cluster.served);
                    for link in closed {
                        served.remove(&(node.clone(), *link));
                    }
                }
                cluster.send(&node, &e).await;
            }
        }
    }
}

/// Every lease, ends the connections served for nodes that died (their
/// clients reconnect elsewhere).
pub(super) async fn check_served(cluster: Arc<Cluster>) {
    let mut tick = tokio::time::interval(cluster.lease);
    loop {
        tick.tick().await;
        let nodes: Vec<String> = {
            let served = lock(&cluster.served);
            let set: HashSet<&String> = served.keys().map(|(n, _)| n).collect();
            set.into_iter().cloned().collect()
        };
        let dead = match cluster.blocking(move |c| c.dead(&nodes)).await {
            Ok(d) => d,
            Err(e) => {
                warn!(error = %e, "checking the other nodes failed");
                continue;
            }
        };
        if dead.is_empty() {
            continue;
        }
        let gone: Vec<Served> = {
            let mut served = lock(&cluster.served);
            let keys: Vec<(String, u64)> = served
                .keys()
                .filter(|(n, _)| dead.contains(n))
                .cloned()
                .collect();
            keys.iter().filter_map(|k| served.remove(k)).collect()
        };
        for s in gone {
            let _ = s.room.send(Command::Disconnect { conn: s.conn }).await;
        }
    }
}
