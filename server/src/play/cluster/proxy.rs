//! Proxy rooms: a node asked for a match another node plays starts a task
//! that takes the same [`Command`]s as a real room and relays them to the
//! owner over Redis. It ends when the owner's lease expires or moves
//! ([`check_owners`], one query a quarter second for every proxy), when it
//! is shut down, or after a minute without connections ([`Idle`]); its
//! connections end with it, and their clients reconnect to wherever the
//! match is now.

use super::leases;
use super::node::{lock, moved, Cluster, PendingConnect, ProxyEntry};
use super::relay::LinkEnd;
use super::wire::{Envelope, WireClaim};
use crate::play::room::{Command, Connected, Inbox};
use std::collections::{HashMap, HashSet};
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::Arc;
use std::time::Duration;
use tokio::sync::{mpsc, oneshot};
use tokio::time::Instant;
use tracing::{debug, info, warn};

/// How long a relayed request (connect, join) waits for the owner.
const RELAY_TIMEOUT: Duration = Duration::from_secs(5);
/// How often the proxy rooms' owners' leases are checked (one query for
/// all of them): how late, at most, relayed clients learn that their
/// match's node died.
const OWNER_CHECK: Duration = Duration::from_millis(250);
/// A proxy room with no connection for this long ends.
const PROXY_IDLE: Duration = Duration::from_secs(60);
/// Messages queued for one relayed connection before it counts as too
/// slow and is dropped (as a local connection would be).
const LINK_QUEUE: usize = 256;

/// How long a proxy room has had no connection, on its clock.
#[derive(Clone, Copy, Debug)]
pub(super) struct Idle {
    limit: Duration,
    /// When it last had a connection (or started).
    since: Instant,
}

impl Idle {
    /// A proxy started at `now`, ending after `limit` without connections.
    pub fn new(limit: Duration, now: Instant) -> Idle {
        Idle { limit, since: now }
    }

    /// A check at `now`, with the proxy's open `connections`: `true` when
    /// it has had none for longer than the limit and ends.
    pub fn expired(&mut self, now: Instant, connections: usize) -> bool {
        if connections > 0 {
            self.since = now;
            return false;
        }
        now.saturating_duration_since(self.since) > self.limit
    }
}

impl Cluster {
    /// Starts a proxy room for match `id`, played on `owner`; its command
    /// queue is `rx`. It ends (and calls `done`) when the owner's lease
    /// expires or moves, when it is shut down, or when idle.
    pub fn proxy(
        self: &Arc<Self>,
        id: String,
        owner: String,
        rx: mpsc::Receiver<Command>,
        done: impl FnOnce() + Send + 'static,
        rt: &tokio::runtime::Handle,
    ) {
        rt.spawn(proxy_room(self.clone(), id, owner, rx, done));
    }
}

/// A proxy room (see the module's documentation).
async fn proxy_room(
    cluster: Arc<Cluster>,
    id: String,
    owner: String,
    mut rx: mpsc::Receiver<Command>,
    done: impl FnOnce(),
) {
    debug!(match_id = %id, owner, "relaying a match played on another node");
    let (moved_tx, mut has_moved) = oneshot::channel();
    let number = cluster.next.fetch_add(1, Ordering::Relaxed);
    let entry = ProxyEntry {
        number,
        owner: owner.clone(),
        moved: moved_tx,
    };
    lock(&cluster.proxies).insert(id.clone(), entry);
    let mut mine: HashSet<u64> = HashSet::new();
    let mut check = tokio::time::interval(OWNER_CHECK);
    let mut idle = Idle::new(PROXY_IDLE, Instant::now());
    loop {
        tokio::select! {
            cmd = rx.recv() => match cmd {
                None | Some(Command::Shutdown { .. }) => break,
                Some(Command::Connect { claim, reply }) => {
                    let link = cluster.next.fetch_add(1, Ordering::Relaxed);
                    mine.insert(link);
                    let (reply_tx, answer) = oneshot::channel();
                    let (tx, inbox) = mpsc::channel(LINK_QUEUE);
                    let refused = Arc::new(AtomicU32::new(0));
                    let end = LinkEnd::new(tx, refused.clone());
                    lock(&cluster.pending_connects).insert(link, PendingConnect { end, reply: reply_tx });
                    cluster.send(&owner, &Envelope::Connect {
                        from: cluster.node.clone(),
                        link,
                        match_id: id.clone(),
                        claim: WireClaim::from(&claim),
                    }).await;
                    let c = cluster.clone();
                    tokio::spawn(async move {
                        let answer = tokio::time::timeout(RELAY_TIMEOUT, answer).await;
                        lock(&c.pending_connects).remove(&link);
                        let connected = match answer {
                            Ok(Ok(Ok(seat))) => {
                                Ok(Connected { conn: link, seat, rx: Inbox::new(inbox), refused })
                            }
                            Ok(Ok(Err(r))) => Err(r),
                            _ => Err(moved()),
                        };
                        let _ = reply.send(connected);
                    });
                }
                Some(Command::Message { conn, msg, .. }) => {
                    if let Ok(text) = serde_json::to_string(&msg) {
                        cluster.send(&owner, &Envelope::Message { from: cluster.node.clone(), link: conn, text }).await;
                    }
                }
                Some(Command::Disconnect { conn }) => {
                    mine.remove(&conn);
                    lock(&cluster.links).remove(&conn);
                    cluster.send(&owner, &Envelope::Disconnect { from: cluster.node.clone(), link: conn }).await;
                }
                Some(Command::Join { name, token, account, reply }) => {
                    let request = cluster.next.fetch_add(1, Ordering::Relaxed);
                    let (tx, answer) = oneshot::channel();
                    lock(&cluster.pending_joins).insert(request, tx);
                    cluster.send(&owner, &Envelope::Join {
                        from: cluster.node.clone(),
                        request,
                        match_id: id.clone(),
                        name,
                        token: token.to_hex(),
                        account,
                    }).await;
                    let c = cluster.clone();
                    tokio::spawn(async move {
                        let answer = tokio::time::timeout(RELAY_TIMEOUT, answer).await;
                        lock(&c.pending_joins).remove(&request);
                        let _ = reply.send(match answer {
                            Ok(Ok(r)) => r,
                            _ => Err(moved()),
                        });
                    });
                }
            },
            _ = check.tick() => {
                // Connections the owner closed are gone from the links.
                {
                    let links = lock(&cluster.links);
                    let pending = lock(&cluster.pending_connects);
                    mine.retain(|l| links.contains(l) || pending.contains_key(l));
                }
                if idle.expired(Instant::now(), mine.len()) {
                    break;
                }
            }
            _ = &mut has_moved => {
                info!(match_id = %id, owner, "the match's node lost its lease; its relayed clients reconnect");
                break;
            }
        }
    }
    {
        let mut proxies = lock(&cluster.proxies);
        if proxies.get(&id).is_some_and(|p| p.number == number) {
            proxies.remove(&id);
        }
    }
    // Dropping the links' senders ends their connections: the clients
    // reconnect and find the match where it is now.
    {
        let mut links = lock(&cluster.links);
        for link in &mine {
            links.remove(link);
        }
    }
    for link in mine {
        cluster
            .send(
                &owner,
                &Envelope::Disconnect {
                    from: cluster.node.clone(),
                    link,
                },
            )
            .await;
    }
    done();
}

/// Every quarter second, one query for every proxy room's match: the
/// proxies whose owner no longer holds the lease (expired, or moved) end.
pub(super) async fn check_owners(cluster: Arc<Cluster>) {
    let mut tick = tokio::time::interval(OWNER_CHECK);
    loop {
        tick.tick().await;
        let asked: HashMap<String, u64> = lock(&cluster.proxies)
            .iter()
            .map(|(id, p)| (id.clone(), p.number))
            .collect();
        let ids: Vec<String> = asked.keys().cloned().collect();
        let owners = match cluster.blocking(move |c| c.owners(&ids)).await {
            Ok(o) => o,
            Err(e) => {
                warn!(error = %e, "checking the relayed matches' leases failed");
                continue;
            }
        };
        let mut proxies = lock(&cluster.proxies);
        let current = proxies
            .iter()
            .map(|(id, p)| (id, p.number, p.owner.as_str()));
        for id in leases::moved(current, &asked, &owners) {
            if let Some(p) = proxies.remove(&id) {
                let _ = p.moved.send(());
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ms(n: u64) -> Duration {
        Duration::from_millis(n)
    }

    #[test]
    fn a_proxy_without_connections_ends_after_the_idle_limit() {
        let t0 = Instant::now();
        let mut idle = Idle::new(ms(60_000), t0);
        assert!(!idle.expired(t0 + ms(30_000), 0));
        assert!(
            !idle.expired(t0 + ms(60_000), 0),
            "exactly the limit is not past it"
        );
        assert!(idle.expired(t0 + ms(60_001), 0));
    }

    #[test]
    fn a_connection_keeps_a_proxy_alive_and_the_idle_time_counts_from_its_last_check() {
        let t0 = Instant::now();
        let mut idle = Idle::new(ms(60_000), t0);
        assert!(!idle.expired(t0 + ms(59_000), 1));
        assert!(!idle.expired(t0 + ms(200_000), 2), "never while connected");
        // The last connection went: a full limit from the last check that
        // saw one.
        assert!(!idle.expired(t0 + ms(260_000), 0));
        assert!(idle.expired(t0 + ms(260_001), 0));
    }
}
