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
//! per connection; the relaying node forwards it in order, and a gap (a
//! message lost by pub/sub) ends the connection, so the client reconnects
//! and starts again from the full `match-state`: it never sees a gap or a
//! duplicate. Every client thus gets exactly the messages a client of the
//! owner gets, in the same order.
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

use crate::play::hub::Hub;
use crate::play::room::{Claim, Command, Connected, Inbox, Outbound};
use crate::refusal::Refusal;
use crate::store::StoreError;
use bytestring::ByteString;
use futures_util::StreamExt;
use game::protocol::{ClientMessage, ErrorCode};
use game::token::{SeatToken, TokenHash};
use game::Seat;
use r2d2_postgres::PostgresConnectionManager;
use redis::AsyncCommands;
use serde::{Deserialize, Serialize};
use std::collections::{HashMap, HashSet};
use std::sync::atomic::{AtomicU32, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;
use tokio::sync::{mpsc, oneshot};
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

/// Why the cluster could not start.
#[derive(Debug, thiserror::Error)]
pub enum ClusterError {
    #[error("redis: {0}")]
    Redis(#[from] redis::RedisError),
    #[error("postgresql: {0}")]
    Postgres(#[from] postgres::Error),
    #[error("no PostgreSQL connection: {0}")]
    Pool(#[from] r2d2::Error),
}

impl From<ClusterError> for StoreError {
    fn from(e: ClusterError) -> StoreError {
        match e {
            ClusterError::Postgres(e) => StoreError::Postgres(e),
            ClusterError::Pool(e) => StoreError::Pool(e),
            ClusterError::Redis(e) => StoreError::Corrupt(format!("redis: {e}")),
        }
    }
}

/// What one node knows of the cluster (see the module's documentation).
pub struct Cluster {
    node: String,
    lease: Duration,
    pool: r2d2::Pool<PostgresConnectionManager<postgres::NoTls>>,
    publisher: redis::aio::MultiplexedConnection,
    redis: redis::Client,
    next: AtomicU64,
    /// Relayed connections of this node's clients (proxy side), by link.
    links: Mutex<HashMap<u64, LinkEnd>>,
    /// Connects and joins waiting for their owner's answer, by link or
    /// request number.
    pending_connects: Mutex<HashMap<u64, PendingConnect>>,
    pending_joins: Mutex<HashMap<u64, oneshot::Sender<Result<Seat, Refusal>>>>,
    /// Connections this node's rooms serve for clients of other nodes
    /// (owner side), by (their node, their link).
    served: Mutex<HashMap<(String, u64), Served>>,
    /// This node's proxy rooms: the node each relays to, and how to tell
    /// it that the match moved.
    proxies: Mutex<HashMap<String, ProxyEntry>>,
}

/// A relayed connection, as its client's node holds it.
struct LinkEnd {
    tx: mpsc::Sender<Outbound>,
    /// The number the next message must carry.
    next: u64,
    refused: Arc<AtomicU32>,
}

/// A relayed connect waiting for the owner: its connection's end, put in
/// place (before anything is delivered to it) when the owner admits it.
struct PendingConnect {
    end: LinkEnd,
    reply: oneshot::Sender<Result<Option<Seat>, Refusal>>,
}

/// A proxy room as [`check_owners`] sees it.
struct ProxyEntry {
    /// Which proxy (a match may get a new one after its old one ended).
    number: u64,
    owner: String,
    moved: oneshot::Sender<()>,
}

/// A connection served for another node's client.
struct Served {
    room: mpsc::Sender<Command>,
    conn: u64,
}

/// A refusal as it crosses Redis.
#[derive(Clone, Debug, Serialize, Deserialize)]
struct WireRefusal {
    code: ErrorCode,
    message: String,
}

impl From<&Refusal> for WireRefusal {
    fn from(r: &Refusal) -> WireRefusal {
        WireRefusal {
            code: r.code,
            message: r.message.clone(),
        }
    }
}

impl From<WireRefusal> for Refusal {
    fn from(r: WireRefusal) -> Refusal {
        Refusal::new(r.code, r.message)
    }
}

/// What a connection claims, as it crosses Redis.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(tag = "as", rename_all = "kebab-case")]
enum WireClaim {
    Watch,
    Token { token: String },
    Account { account: String },
}

impl From<&Claim> for WireClaim {
    fn from(c: &Claim) -> WireClaim {
        match c {
            Claim::Watch => WireClaim::Watch,
            Claim::Token(t) => WireClaim::Token {
                token: t.expose().to_string(),
            },
            Claim::Account(a) => WireClaim::Account { account: a.clone() },
        }
    }
}

impl From<WireClaim> for Claim {
    fn from(c: WireClaim) -> Claim {
        match c {
            WireClaim::Watch => Claim::Watch,
            WireClaim::Token { token } => Claim::Token(SeatToken::new(token)),
            WireClaim::Account { account } => Claim::Account(account),
        }
    }
}

/// A message between two nodes, on the receiving node's channel.
#[derive(Debug, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
enum Envelope {
    // To the owner of a match, from the node of a client (`from`).
    Connect {
        from: String,
        link: u64,
        match_id: String,
        claim: WireClaim,
    },
    Message {
        from: String,
        link: u64,
        text: String,
    },
    Disconnect {
        from: String,
        link: u64,
    },
    Join {
        from: String,
        request: u64,
        match_id: String,
        name: String,
        token: String,
        account: Option<String>,
    },
    // Back to the node of a client.
    Connected {
        link: u64,
        conn: u64,
        seat: Option<Seat>,
    },
    Refused {
        link: u64,
        refusal: WireRefusal,
    },
    Deliver {
        /// The node serving the connection.
        from: String,
        link: u64,
        seq: u64,
        text: String,
        refused: u32,
    },
    Closed {
        link: u64,
    },
    Joined {
        request: u64,
        result: Result<Seat, WireRefusal>,
    },
}

/// The Redis channel of `node`.
fn channel(node: &str) -> String {
    format!("chapaev:node:{node}")
}

/// Who holds a match's lease.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Lease {
    /// This node, now.
    Ours,
    /// Another node, unexpired.
    Theirs(String),
}

fn moved() -> Refusal {
    Refusal::new(
        ErrorCode::ServerBusy,
        "the match is moving between server nodes; connect again",
    )
}

impl Cluster {
    /// Connects to PostgreSQL (the leases) and Redis (its connection
    /// driven on `rt`), and records this node. Blocks: call it outside the
    /// runtime.
    pub fn connect(
        node: String,
        database_url: &str,
        redis_url: &str,
        lease: Duration,
        rt: &tokio::runtime::Handle,
    ) -> Result<Arc<Cluster>, ClusterError> {
        let config: postgres::Config = database_url.parse()?;
        let pool = r2d2::Pool::builder()
            .max_size(4)
            .connection_timeout(Duration::from_secs(10))
            .build(PostgresConnectionManager::new(config, postgres::NoTls))?;
        let redis = redis::Client::open(redis_url)?;
        let publisher = rt.block_on(redis.get_multiplexed_async_connection())?;
        let cluster = Arc::new(Cluster {
            node,
            lease,
            pool,
            publisher,
            redis,
            next: AtomicU64::new(1),
            links: Mutex::default(),
            pending_connects: Mutex::default(),
            pending_joins: Mutex::default(),
            served: Mutex::default(),
            proxies: Mutex::default(),
        });
        cluster.heartbeat()?;
        Ok(cluster)
    }

    /// This node's id.
    pub fn node(&self) -> &str {
        &self.node
    }

    /// The connections this node relays to other nodes, and those it
    /// serves for them.
    pub fn connection_counts(&self) -> (usize, usize) {
        (lock(&self.links).len(), lock(&self.served).len())
    }

    /// Runs `f` on a blocking thread with this cluster.
    async fn blocking<T: Send + 'static>(
        self: &Arc<Self>,
        f: impl FnOnce(&Cluster) -> Result<T, ClusterError> + Send + 'static,
    ) -> Result<T, ClusterError> {
        let me = self.clone();
        match tokio::task::spawn_blocking(move || f(&me)).await {
            Ok(r) => r,
            Err(e) => Err(ClusterError::Redis(redis::RedisError::from((
                redis::ErrorKind::ClientError,
                "a blocking task failed",
                e.to_string(),
            )))),
        }
    }

    fn db(
        &self,
    ) -> Result<r2d2::PooledConnection<PostgresConnectionManager<postgres::NoTls>>, ClusterError>
    {
        Ok(self.pool.get()?)
    }

    fn lease_ms(&self) -> f64 {
        self.lease.as_secs_f64() * 1000.0
    }

    /// Records that this node lives.
    fn heartbeat(&self) -> Result<(), ClusterError> {
        self.db()?.execute(
            "INSERT INTO cluster_nodes (id, started_at, seen_at) VALUES ($1, now(), now())
             ON CONFLICT (id) DO UPDATE SET seen_at = now()",
            &[&self.node],
        )?;
        Ok(())
    }

    /// Takes the lease of match `id` if it is free, expired or already
    /// ours; otherwise says who holds it. (Blocking.)
    pub fn acquire(&self, id: &str) -> Result<Lease, ClusterError> {
        let mut db = self.db()?;
        let taken = db.query_opt(
            "INSERT INTO match_leases (match_id, owner, expires_at)
             SELECT $1, $2, now() + $3 * interval '1 millisecond'
             WHERE EXISTS (SELECT 1 FROM matches WHERE id = $1)
             ON CONFLICT (match_id) DO UPDATE SET owner = EXCLUDED.owner, expires_at = EXCLUDED.expires_at
             WHERE match_leases.owner = EXCLUDED.owner OR match_leases.expires_at < now()
             RETURNING owner",
            &[&id, &self.node, &self.lease_ms()],
        )?;
        if taken.is_some() {
            return Ok(Lease::Ours);
        }
        let holder = db.query_opt(
            "SELECT owner FROM match_leases WHERE match_id = $1 AND expires_at >= now()",
            &[&id],
        )?;
        Ok(match holder {
            Some(row) => Lease::Theirs(row.get(0)),
            // No such match (or it expired between the two): nobody holds
            // it; the caller finds no match, or tries again.
            None => Lease::Theirs(String::new()),
        })
    }

    /// Of the matches `ids`, those whose lease is unexpired, with their
    /// owners. (Blocking.)
    fn owners(&self, ids: &[String]) -> Result<HashMap<String, String>, ClusterError> {
        if ids.is_empty() {
            return Ok(HashMap::new());
        }
        let rows = self.db()?.query(
            "SELECT match_id, owner FROM match_leases WHERE match_id = ANY($1) AND expires_at >= now()",
            &[&ids],
        )?;
        Ok(rows.iter().map(|r| (r.get(0), r.get(1))).collect())
    }

    /// Gives up the lease of `id` (the match's room stopped). (Blocking.)
    pub fn release(&self, id: &str) -> Result<(), ClusterError> {
        self.db()?.execute(
            "DELETE FROM match_leases WHERE match_id = $1 AND owner = $2",
            &[&id, &self.node],
        )?;
        Ok(())
    }

    /// Gives up every lease of this node (it is stopping). (Blocking.)
    pub fn release_all(&self) -> Result<(), ClusterError> {
        let mut db = self.db()?;
        db.execute("DELETE FROM match_leases WHERE owner = $1", &[&self.node])?;
        db.execute("DELETE FROM cluster_nodes WHERE id = $1", &[&self.node])?;
        Ok(())
    }

    /// Renews the leases of `ids`; the ids whose lease this node no longer
    /// holds. (Blocking.)
    fn renew(&self, ids: &[String]) -> Result<Vec<String>, ClusterError> {
        self.heartbeat()?;
        if ids.is_empty() {
            return Ok(Vec::new());
        }
        let rows = self.db()?.query(
            "UPDATE match_leases SET expires_at = now() + $3 * interval '1 millisecond'
             WHERE owner = $1 AND match_id = ANY($2) RETURNING match_id",
            &[&self.node, &ids, &self.lease_ms()],
        )?;
        let kept: HashSet<String> = rows.iter().map(|r| r.get(0)).collect();
        Ok(ids
            .iter()
            .filter(|id| !kept.contains(*id))
            .cloned()
            .collect())
    }

    /// Live matches whose lease expired or was never taken. (Blocking.)
    fn orphans(&self) -> Result<Vec<String>, ClusterError> {
        let rows = self.db()?.query(
            "SELECT m.id FROM matches m LEFT JOIN match_leases l ON l.match_id = m.id
             WHERE m.status = 'live' AND (l.match_id IS NULL OR l.expires_at < now())
             ORDER BY m.updated_at DESC LIMIT 500",
            &[],
        )?;
        Ok(rows.iter().map(|r| r.get(0)).collect())
    }

    /// Of `nodes`, those not seen within a lease. (Blocking.)
    fn dead(&self, nodes: &[String]) -> Result<Vec<String>, ClusterError> {
        if nodes.is_empty() {
            return Ok(Vec::new());
        }
        let rows = self.db()?.query(
            "SELECT id FROM cluster_nodes WHERE id = ANY($1)
             AND seen_at >= now() - $2 * interval '1 millisecond'",
            &[&nodes, &self.lease_ms()],
        )?;
        let alive: HashSet<String> = rows.iter().map(|r| r.get(0)).collect();
        Ok(nodes
            .iter()
            .filter(|n| !alive.contains(*n))
            .cloned()
            .collect())
    }

    /// Publishes `e` on `node`'s channel (lost if nobody listens, as
    /// pub/sub is).
    async fn send(&self, node: &str, e: &Envelope) {
        let Ok(text) = serde_json::to_string(e) else {
            return;
        };
        let mut conn = self.publisher.clone();
        if let Err(err) = conn.publish::<_, _, ()>(channel(node), text).await {
            warn!(error = %err, node, "publishing to another node failed");
        }
    }

    /// Starts this node's tasks on the hub's runtime: the dispatcher of
    /// its Redis channel, lease renewal, takeover of orphaned matches, and
    /// the check on the nodes it serves.
    pub fn start(self: &Arc<Self>, hub: &Hub, rt: &tokio::runtime::Handle) {
        rt.spawn(dispatch(self.clone(), hub.clone()));
        rt.spawn(keep_leases(self.clone(), hub.clone()));
        rt.spawn(take_over(self.clone(), hub.clone()));
        rt.spawn(check_served(self.clone()));
        rt.spawn(check_owners(self.clone()));
    }

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
    let mut idle_since = tokio::time::Instant::now();
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
                    let end = LinkEnd { tx, next: 0, refused: refused.clone() };
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
                    mine.retain(|l| links.contains_key(l) || pending.contains_key(l));
                }
                if !mine.is_empty() {
                    idle_since = tokio::time::Instant::now();
                } else if idle_since.elapsed() > PROXY_IDLE {
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

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Reads this node's channel for good (subscribing again after Redis
/// breaks; the connections relayed meanwhile end, since their messages
/// may be lost) and handles each envelope.
async fn dispatch(cluster: Arc<Cluster>, hub: Hub) {
    loop {
        match cluster.redis.get_async_pubsub().await {
            Ok(mut pubsub) => {
                if let Err(e) = pubsub.subscribe(channel(&cluster.node)).await {
                    warn!(error = %e, "subscribing to this node's channel failed");
                } else {
                    let mut messages = pubsub.on_message();
                    while let Some(m) = messages.next().await {
                        let Ok(text) = m.get_payload::<String>() else {
                            continue;
                        };
                        match serde_json::from_str::<Envelope>(&text) {
                            Ok(e) => handle(&cluster, &hub, e).await,
                            Err(e) => warn!(error = %e, "an unreadable message from another node"),
                        }
                    }
                    warn!("this node's Redis subscription ended; subscribing again");
                }
            }
            Err(e) => warn!(error = %e, "cannot reach Redis; trying again"),
        }
        lock(&cluster.links).clear();
        tokio::time::sleep(Duration::from_secs(1)).await;
    }
}

async fn handle(cluster: &Arc<Cluster>, hub: &Hub, e: Envelope) {
    match e {
        Envelope::Connect {
            from,
            link,
            match_id,
            claim,
        } => {
            let (cluster, hub) = (cluster.clone(), hub.clone());
            tokio::spawn(serve(cluster, hub, from, link, match_id, claim.into()));
        }
        Envelope::Message { from, link, text } => {
            let target = lock(&cluster.served)
                .get(&(from, link))
                .map(|s| (s.room.clone(), s.conn));
            if let (Some((room, conn)), Ok(msg)) = (target, ClientMessage::from_json(&text)) {
                let _ = room.send(Command::message(conn, msg)).await;
            }
        }
        Envelope::Disconnect { from, link } => {
            let served = lock(&cluster.served).remove(&(from, link));
            if let Some(s) = served {
                let _ = s.room.send(Command::Disconnect { conn: s.conn }).await;
            }
        }
        Envelope::Join {
            from,
            request,
            match_id,
            name,
            token,
            account,
        } => {
            let (cluster, hub) = (cluster.clone(), hub.clone());
            tokio::spawn(async move {
                let result = match TokenHash::from_hex(&token) {
                    Ok(token) => hub.join_owned(&match_id, name, token, account).await,
                    Err(_) => Err(Refusal::new(ErrorCode::BadToken, "a malformed token hash")),
                };
                let result = result.map_err(|r| WireRefusal::from(&r));
                cluster
                    .send(&from, &Envelope::Joined { request, result })
                    .await;
            });
        }
        Envelope::Connected { link, conn, seat } => {
            let pending = lock(&cluster.pending_connects).remove(&link);
            if let Some(p) = pending {
                // In place before the first delivery is read.
                lock(&cluster.links).insert(link, p.end);
                let _ = p.reply.send(Ok(seat));
            }
            debug!(link, conn, "a relayed connection was admitted");
        }
        Envelope::Refused { link, refusal } => {
            if let Some(p) = lock(&cluster.pending_connects).remove(&link) {
                let _ = p.reply.send(Err(refusal.into()));
            }
        }
        Envelope::Deliver {
            from,
            link,
            seq,
            text,
            refused,
        } => {
            if !deliver(cluster, link, seq, text, refused) {
                // A connection this node no longer has (it closed, or its
                // connect was given up as late): the owner stops serving it.
                let node = cluster.node.clone();
                cluster
                    .send(&from, &Envelope::Disconnect { from: node, link })
                    .await;
            }
        }
        Envelope::Closed { link } => {
            lock(&cluster.links).remove(&link);
        }
        Envelope::Joined { request, result } => {
            if let Some(tx) = lock(&cluster.pending_joins).remove(&request) {
                let _ = tx.send(result.map_err(Refusal::from));
            }
        }
    }
}

/// Hands message number `seq` to relayed connection `link`; `false` if
/// this node has no such connection.
fn deliver(cluster: &Cluster, link: u64, seq: u64, text: String, refused: u32) -> bool {
    let mut links = lock(&cluster.links);
    let Some(end) = links.get_mut(&link) else {
        return false;
    };
    end.refused.store(refused, Ordering::Relaxed);
    if seq < end.next {
        return true; // a duplicate
    }
    let item: Outbound = Arc::from(vec![ByteString::from(text)]);
    if seq > end.next || end.tx.try_send(item).is_err() {
        // A gap, or a client too slow: its connection ends (and its
        // session tells the owner); it reconnects and starts again from
        // the full state.
        debug!(link, seq, expected = end.next, "a relayed connection ends");
        links.remove(&link);
        return true;
    }
    end.next += 1;
    true
}

/// Serves a connection to a match this node plays for a client of node
/// `from`: connects it to the room and relays what the room sends it.
async fn serve(cluster: Arc<Cluster>, hub: Hub, from: String, link: u64, id: String, claim: Claim) {
    let (room, connected) = match hub.connect_owned(&id, claim).await {
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
    lock(&cluster.served).insert(
        (from.clone(), link),
        Served {
            room: room.tx.clone(),
            conn,
        },
    );
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

/// Renews this node's leases every third of a lease; stops the rooms of
/// the matches it lost, and all of them if it could not renew for most of
/// a lease (it can no longer be sure it holds them).
async fn keep_leases(cluster: Arc<Cluster>, hub: Hub) {
    let mut tick = tokio::time::interval(cluster.lease / 3);
    let mut renewed = tokio::time::Instant::now();
    loop {
        tick.tick().await;
        let owned = hub.owned_matches();
        let ids = owned.clone();
        match cluster.blocking(move |c| c.renew(&ids)).await {
            Ok(lost) => {
                renewed = tokio::time::Instant::now();
                for id in lost {
                    warn!(match_id = %id, "this node lost the match's lease; its room stops");
                    hub.stop_room(&id).await;
                }
            }
            Err(e) => {
                warn!(error = %e, "renewing the leases failed");
                if renewed.elapsed() > cluster.lease * 4 / 5 {
                    for id in owned {
                        hub.stop_room(&id).await;
                    }
                }
            }
        }
    }
}

/// Every second (or half lease, if shorter), takes the live matches whose
/// node died: within a lease and a second of its death, even with none of
/// their clients back.
async fn take_over(cluster: Arc<Cluster>, hub: Hub) {
    let mut tick = tokio::time::interval((cluster.lease / 2).min(Duration::from_secs(1)));
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
            match hub.own(&id).await {
                Ok(true) => {
                    info!(match_id = %id, node = %cluster.node, "took over a match whose node stopped")
                }
                Ok(false) => {}
                Err(r) => debug!(match_id = %id, refusal = %r, "could not take over a match"),
            }
        }
    }
}

/// Every second, one query for every proxy room's match: the proxies whose
/// owner no longer holds the lease (expired, or moved) end.
async fn check_owners(cluster: Arc<Cluster>) {
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
        let moved: Vec<String> = proxies
            .iter()
            // Only the proxies asked about (a newer one waits for the next
            // round).
            .filter(|(id, p)| asked.get(*id) == Some(&p.number))
            .filter(|(id, p)| owners.get(*id) != Some(&p.owner))
            .map(|(id, _)| id.clone())
            .collect();
        for id in moved {
            if let Some(p) = proxies.remove(&id) {
                let _ = p.moved.send(());
            }
        }
    }
}

/// Every lease, ends the connections served for nodes that died (their
/// clients reconnect elsewhere).
async fn check_served(cluster: Arc<Cluster>) {
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
