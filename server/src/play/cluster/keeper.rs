//! The lease keeper: a node's two tasks that keep its share of the
//! matches right. One renews its leases and stops the rooms of those it
//! lost (or of all, once it can no longer be sure it holds any); the other
//! takes over the live matches whose node died. When to do what is
//! [`super::leases`]; this module only runs it.
//!
//! A node renews only while it reaches Redis as well as PostgreSQL: a node
//! cut off from Redis can relay nothing to the other nodes' clients, so it
//! lets its leases run out (its rooms stop, as after any failed renewal)
//! and other nodes, which reach both, take its matches over.

use super::leases::{self, Renewal};
use super::node::Cluster;
use super::rooms::LocalRooms;
use std::sync::Arc;
use tokio::time::Instant;
use tracing::{debug, info, warn};

/// Renews this node's leases every third of a lease; stops the rooms of
/// the matches it lost, and all of them if it could not renew for most of
/// a lease (it can no longer be sure it holds them).
pub(super) async fn keep_leases<R: LocalRooms>(cluster: Arc<Cluster>, rooms: R) {
    let mut tick = tokio::time::interval(leases::renew_every(cluster.lease));
    let mut renewal = Renewal::new(cluster.lease, Instant::now());
    loop {
        tick.tick().await;
        let owned = rooms.owned_matches();
        let ids = owned.clone();
        let renewed = if cluster.check_redis().await {
            cluster.blocking(move |c| c.renew(&ids)).await
        } else {
            Err(super::node::ClusterError::NoRedis)
        };
        match renewed {
            Ok(lost) => {
                renewal.renewed(Instant::now());
                for id in lost {
                    warn!(match_id = %id, "this node lost the match's lease; its room stops");
                    rooms.stop_room(&id).await;
                }
            }
            Err(e) => {
                warn!(error = %e, "renewing the leases failed");
                if renewal.failed(Instant::now()) {
                    for id in owned {
                        rooms.stop_room(&id).await;
                    }
                }
            }
        }
    }
}

/// Every second (or half lease, if shorter), takes the live matches whose
/// node died: within a lease and a second of its death, even with none of
/// their clients back.
pub(super) async fn take_over<R: LocalRooms>(cluster: Arc<Cluster>, rooms: R) {
    let mut tick = tokio::time::interval(leases::look_for_orphans_every(cluster.lease));
    loop {
        tick.tick().await;
        let orphans = match cluster.blocking(|c| c.orphans()).await {
            Ok(o) => o,
            Err(e) => {
                warn!(error = %e, "looking for orphaned matches failed");
                continue;
            }
        };
        for id in orphans {
            match rooms.own(&id).await {
                Ok(true) => {
                    info!(match_id = %id, node = %cluster.node, "took over a match whose node stopped")
                }
                Ok(false) => {}
                Err(r) => debug!(match_id = %id, refusal = %r, "could not take over a match"),
            }
        }
    }
}
