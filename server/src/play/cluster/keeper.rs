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
use super::node::{Cluster, ClusterError};
use super::rooms::LocalRooms;
use std::sync::Arc;
use std::time::Duration;
use tokio::time::{Instant, MissedTickBehavior};
use tracing::{debug, info, warn};

/// Renews this node's leases every third of a lease; stops the rooms of
/// the matches it lost, and all of them once no renewal has succeeded for
/// four fifths of a lease (it can no longer be sure it holds them). That
/// moment is kept even while a renewal still waits on PostgreSQL (a
/// renewal is given up at it), so the rooms stop before any other node
/// may take their matches over.
pub(super) async fn keep_leases<R: LocalRooms>(cluster: Arc<Cluster>, rooms: R) {
    let every = leases::renew_every(cluster.lease);
    let mut tick = tokio::time::interval(every);
    tick.set_missed_tick_behavior(MissedTickBehavior::Delay);
    let mut renewal = Renewal::new(cluster.lease, Instant::now());
    // Whether the rooms were stopped for the failures since the last
    // renewal that succeeded.
    let mut gave_up = false;
    loop {
        let deadline = renewal.deadline() + Duration::from_millis(1);
        tokio::select! {
            _ = tick.tick() => {}
            _ = tokio::time::sleep_until(deadline), if !gave_up => {
                stop_all(&rooms).await;
                gave_up = true;
                continue;
            }
        }
        let began = Instant::now();
        let owned = rooms.owned_matches();
        let ids = owned.clone();
        // Waits no longer than the next renewal, nor past the deadline
        // while the rooms still play.
        let until = if gave_up {
            began + every
        } else {
            (began + every).min(deadline)
        };
        let renewed = if cluster.check_redis(until).await {
            let renewal = cluster.blocking(move |c| c.renew(&ids));
            tokio::time::timeout_at(until, renewal)
                .await
                .unwrap_or(Err(ClusterError::TimedOut))
        } else {
            Err(ClusterError::NoRedis)
        };
        match renewed {
            Ok(lost) => {
                renewal.renewed(began);
                if gave_up {
                    info!(node = %cluster.node, "renewing the leases works again");
                }
                gave_up = false;
                for id in lost {
                    warn!(match_id = %id, "this node lost the match's lease; its room stops");
                    rooms.stop_room(&id).await;
                }
            }
            Err(e) => {
                warn!(error = %e, "renewing the leases failed");
                // Again while renewals keep failing: a room started
                // meanwhile (its match taken) stops too.
                if renewal.failed(Instant::now()) {
                    stop_all(&rooms).await;
                    gave_up = true;
                }
            }
        }
    }
}

/// Stops the rooms of every match this node plays: it can no longer be
/// sure it holds their leases.
async fn stop_all<R: LocalRooms>(rooms: &R) {
    let owned = rooms.owned_matches();
    if !owned.is_empty() {
        warn!(
            matches = owned.len(),
            "no lease renewal for four fifths of a lease: this node stops its rooms"
        );
    }
    for id in owned {
        rooms.stop_room(&id).await;
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
