//! The owner's side of a relayed connection: a node serving one of its
//! matches to a client of another node connects that client to the real
//! room, as if it were local, and publishes everything the room sends it,
//! numbered from 0 (the numbering [`super::relay`] checks on the other
//! side). Connections served for a node that died end.

use super::node::{lock, Cluster, Served};
use super::rooms::LocalRooms;
use super::wire::{Envelope, WireRefusal};
use crate::play::room::{Claim, Command, Connected};
use std::collections::HashSet;
use std::sync::atomic::Ordering;
use std::sync::Arc;
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
        mut rx,
        refused,
    } = connected;
    lock(&cluster.served).insert((from.clone(), link), Served { room, conn });
    cluster
        .send(&from, &Envelope::Connected { link, conn, seat })
        .await;
    let mut seq = 0;
    while let Some(text) = rx.recv().await {
        let e = Envelope::Deliver {
            from: cluster.node.clone(),
            link,
            seq,
            text: text.to_string(),
            refused: refused.load(Ordering::Relaxed),
        };
        cluster.send(&from, &e).await;
        seq += 1;
    }
    cluster.send(&from, &Envelope::Closed { link }).await;
    lock(&cluster.served).remove(&(from, link));
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
