//! One node of the cluster: its connections to PostgreSQL (the leases and
//! the nodes' heartbeats) and Redis (publishing to the other nodes, on a
//! connection that reconnects by itself after Redis restarts), whether it
//! reaches Redis now, and the tables of what it relays and serves. The
//! queries here only ask and record; what their answers mean is
//! [`super::leases`].

use super::leases::{self, Lease};
use super::outlet::Outgoing;
use super::relay::{LinkEnd, Links};
use super::wire::{channel, Envelope};
use crate::play::room::Command;
use crate::refusal::Refusal;
use crate::store::StoreError;
use game::protocol::ErrorCode;
use game::Seat;
use r2d2_postgres::PostgresConnectionManager;
use redis::AsyncCommands;
use std::collections::{HashMap, HashSet};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;
use tokio::sync::oneshot;
use tracing::warn;

/// Why the cluster could not start.
#[derive(Debug, thiserror::Error)]
pub enum ClusterError {
    #[error("redis: {0}")]
    Redis(#[from] redis::RedisError),
    #[error("postgresql: {0}")]
    Postgres(#[from] postgres::Error),
    #[error("no PostgreSQL connection: {0}")]
    Pool(#[from] r2d2::Error),
    #[error("this node cannot reach Redis")]
    NoRedis,
    #[error("PostgreSQL or Redis did not answer in time")]
    TimedOut,
}

impl From<ClusterError> for StoreError {
    fn from(e: ClusterError) -> StoreError {
        match e {
            ClusterError::Postgres(e) => StoreError::Postgres(e),
            ClusterError::Pool(e) => StoreError::Pool(e),
            ClusterError::Redis(e) => StoreError::Corrupt(format!("redis: {e}")),
            ClusterError::NoRedis => StoreError::Corrupt("this node cannot reach Redis".into()),
            ClusterError::TimedOut => {
                StoreError::Corrupt("PostgreSQL or Redis did not answer in time".into())
            }
        }
    }
}

/// What one node knows of the cluster (see the cluster's documentation).
pub struct Cluster {
    pub(super) node: String,
    pub(super) lease: Duration,
    /// Where clients reach this node (`--public-url`), told to the other
    /// nodes so that they send this node's matches' clients here.
    public_url: Option<String>,
    /// How many clients [`Cluster::route`] sent to another node.
    routed: AtomicU64,
    /// The live nodes' public URLs as last read ([`Cluster::public_urls`])
    /// and when.
    known_urls: Mutex<(Vec<String>, Option<std::time::Instant>)>,
    pool: r2d2::Pool<PostgresConnectionManager<postgres::NoTls>>,
    /// Reconnects after Redis restarts (meanwhile, publishing fails).
    publisher: redis::aio::ConnectionManager,
    pub(super) redis: redis::Client,
    /// Whether the last check reached Redis ([`Cluster::check_redis`]): a
    /// node that cannot reach it takes no lease.
    reaches_redis: AtomicBool,
    /// Numbers links, join requests and proxies.
    pub(super) next: AtomicU64,
    /// Relayed connections of this node's clients (proxy side), by link.
    pub(super) links: Mutex<Links>,
    /// Connects and joins waiting for their owner's answer, by link or
    /// request number.
    pub(super) pending_connects: Mutex<HashMap<u64, PendingConnect>>,
    pub(super) pending_joins: Mutex<HashMap<u64, oneshot::Sender<Result<Seat, Refusal>>>>,
    /// Connections this node's rooms serve for clients of other nodes
    /// (owner side), by (their node, their link).
    pub(super) served: Mutex<HashMap<(String, u64), Served>>,
    /// This node's proxy rooms: the node each relays to, and how to tell
    /// it that the match moved.
    pub(super) proxies: Mutex<HashMap<String, ProxyEntry>>,
    /// The outlets taking what this node's rooms send the connections it
    /// serves, one per node of their clients ([`super::outlet`]).
    pub(super) outlets: Mutex<HashMap<String, tokio::sync::mpsc::UnboundedSender<Outgoing>>>,
}

/// A relayed connect waiting for the owner: its connection's end, put in
/// place (before anything is delivered to it) when the owner admits it.
pub(super) struct PendingConnect {
    pub end: LinkEnd,
    pub reply: oneshot::Sender<Result<Option<Seat>, Refusal>>,
}

/// A proxy room as the check on its owner's lease sees it.
pub(super) struct ProxyEntry {
    /// Which proxy (a match may get a new one after its old one ended).
    pub number: u64,
    pub owner: String,
    pub moved: oneshot::Sender<()>,
}

/// A connection served for another node's client.
pub(super) struct Served {
    pub room: tokio::sync::mpsc::Sender<Command>,
    pub conn: u64,
}

/// The refusal of a relayed request whose owner did not answer in time,
/// or whose match moved meanwhile.
pub(super) fn moved() -> Refusal {
    Refusal::new(
        ErrorCode::ServerBusy,
        "the match is moving between server nodes; connect again",
    )
}

/// The refusal of a node that cannot reach Redis, and so the other nodes:
/// its client should connect to another node.
fn cut_off() -> Refusal {
    Refusal::new(
        ErrorCode::ServerBusy,
        "this server node cannot reach the other nodes; connect to another node",
    )
}

/// How long a publish or a check of Redis may take before it counts as
/// failed.
const REDIS_TIMEOUT: Duration = Duration::from_secs(1);

/// Locks `m`, even if a thread panicked holding it.
pub(super) fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

impl Cluster {
    /// Connects to PostgreSQL (the leases) and Redis (its connection
    /// driven on `rt`), and records this node. Blocks: call it outside the
    /// runtime.
    pub fn connect(
        node: String,
        public_url: Option<String>,
        database_url: &str,
        redis_url: &str,
        lease: Duration,
        rt: &tokio::runtime::Handle,
    ) -> Result<Arc<Cluster>, ClusterError> {
        // Every query here waits at most a third of a lease for its
        // connection: while PostgreSQL is down renewals fail in time, and
        // once it is back the pool reconnects within a sixth of a lease.
        let wait = leases::db_wait(lease);
        let mut config: postgres::Config = database_url.parse()?;
        config.connect_timeout(wait);
        let pool = r2d2::Pool::builder()
            .max_size(4)
            .connection_timeout(wait)
            .build(PostgresConnectionManager::new(config, postgres::NoTls))?;
        let redis = redis::Client::open(redis_url)?;
        // After a failure, trying again about twice a second (a constant
        // delay, with jitter) for as long as it takes.
        let reconnect = redis::aio::ConnectionManagerConfig::new()
            .set_factor(1)
            .set_max_delay(500)
            .set_number_of_retries(1_000_000)
            .set_connection_timeout(REDIS_TIMEOUT)
            .set_response_timeout(REDIS_TIMEOUT);
        let publisher = rt.block_on(redis::aio::ConnectionManager::new_with_config(
            redis.clone(),
            reconnect,
        ))?;
        let cluster = Arc::new(Cluster {
            node,
            lease,
            public_url,
            routed: AtomicU64::new(0),
            known_urls: Mutex::default(),
            pool,
            publisher,
            redis,
            reaches_redis: AtomicBool::new(true),
            next: AtomicU64::new(1),
            links: Mutex::default(),
            pending_connects: Mutex::default(),
            pending_joins: Mutex::default(),
            served: Mutex::default(),
            proxies: Mutex::default(),
            outlets: Mutex::default(),
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

    /// Checks that this node reaches Redis now (a `PING` answered within a
    /// second, and by `by`), and remembers the answer for
    /// [`Cluster::ensure_reachable`].
    pub(super) async fn check_redis(&self, by: tokio::time::Instant) -> bool {
        let mut conn = self.publisher.clone();
        let cmd = redis::cmd("PING");
        let ping = cmd.query_async::<String>(&mut conn);
        let by = by.min(tokio::time::Instant::now() + REDIS_TIMEOUT);
        let ok = matches!(tokio::time::timeout_at(by, ping).await, Ok(Ok(_)));
        if self.reaches_redis.swap(ok, Ordering::Relaxed) != ok {
            if ok {
                tracing::info!(node = %self.node, "this node reaches Redis again");
            } else {
                warn!(node = %self.node, "this node cannot reach Redis: it takes no match and lets its leases go");
            }
        }
        ok
    }

    /// Refuses (`server-busy`) while this node cannot reach Redis: it
    /// could neither relay to the other nodes nor keep its leases, so its
    /// clients are better served by another node.
    pub fn ensure_reachable(&self) -> Result<(), Refusal> {
        if self.reaches_redis.load(Ordering::Relaxed) {
            Ok(())
        } else {
            Err(cut_off())
        }
    }

    /// Runs `f` on a blocking thread with this cluster.
    pub(super) async fn blocking<T: Send + 'static>(
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

    /// Records that this node lives, and where its clients reach it.
    fn heartbeat(&self) -> Result<(), ClusterError> {
        self.db()?.execute(
            "INSERT INTO cluster_nodes (id, started_at, seen_at, public_url) VALUES ($1, now(), now(), $2)
             ON CONFLICT (id) DO UPDATE SET seen_at = now(), public_url = EXCLUDED.public_url",
            &[&self.node, &self.public_url],
        )?;
        Ok(())
    }

    /// Where clients reach the node that plays match `id`, when another
    /// node holds its lease (unexpired), that node lives and it was given
    /// a public URL (other than this node's); `None` otherwise: this node
    /// plays the match or takes it, or relays to its owner. (Blocking.)
    pub fn route(&self, id: &str) -> Result<Option<String>, ClusterError> {
        let row = self.db()?.query_opt(
            "SELECT n.public_url FROM match_leases l JOIN cluster_nodes n ON n.id = l.owner
             WHERE l.match_id = $1 AND l.expires_at >= now() AND l.owner <> $2
             AND n.seen_at >= now() - $3 * interval '1 millisecond'",
            &[&id, &self.node, &self.lease_ms()],
        )?;
        let url: Option<String> = row.and_then(|r| r.get(0));
        let url = url.filter(|u| Some(u) != self.public_url.as_ref());
        if url.is_some() {
            self.routed.fetch_add(1, Ordering::Relaxed);
        }
        Ok(url)
    }

    /// The public URLs of the cluster's live nodes (this one's included),
    /// read again when the last reading is older than `fresh` (marked read
    /// before asking, so that a burst of callers asks once). (Blocking
    /// when it reads.)
    pub fn public_urls(&self, fresh: Duration) -> Result<Vec<String>, ClusterError> {
        {
            let mut known = lock(&self.known_urls);
            if known.1.is_some_and(|at| at.elapsed() < fresh) {
                return Ok(known.0.clone());
            }
            known.1 = Some(std::time::Instant::now());
        }
        let rows = self.db()?.query(
            "SELECT public_url FROM cluster_nodes WHERE public_url IS NOT NULL
             AND seen_at >= now() - $1 * interval '1 millisecond'",
            &[&self.lease_ms()],
        )?;
        let urls: Vec<String> = rows.iter().map(|r| r.get(0)).collect();
        lock(&self.known_urls).0.clone_from(&urls);
        Ok(urls)
    }

    /// How many clients this node sent to the node playing their match.
    pub fn routed(&self) -> u64 {
        self.routed.load(Ordering::Relaxed)
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
        Ok(Lease::held_by(holder.map(|row| row.get(0))))
    }

    /// Of the matches `ids`, those whose lease is unexpired, with their
    /// owners. (Blocking.)
    pub(super) fn owners(&self, ids: &[String]) -> Result<HashMap<String, String>, ClusterError> {
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
    pub(super) fn renew(&self, ids: &[String]) -> Result<Vec<String>, ClusterError> {
        self.heartbeat()?;
        if ids.is_empty() {
            return Ok(Vec::new());
        }
        // The rows locked in the order the store's writer locks them (by
        // id), so that a renewal never deadlocks with a group commit.
        let rows = self.db()?.query(
            "UPDATE match_leases SET expires_at = now() + $3 * interval '1 millisecond'
             WHERE match_id IN (SELECT match_id FROM match_leases
                                WHERE owner = $1 AND match_id = ANY($2)
                                ORDER BY match_id FOR UPDATE)
             RETURNING match_id",
            &[&self.node, &ids, &self.lease_ms()],
        )?;
        let kept: HashSet<String> = rows.iter().map(|r| r.get(0)).collect();
        Ok(leases::lost(ids, &kept))
    }

    /// Live matches whose lease expired or was never taken. (Blocking.)
    pub(super) fn orphans(&self) -> Result<Vec<String>, ClusterError> {
        let rows = self.db()?.query(
            "SELECT m.id FROM matches m LEFT JOIN match_leases l ON l.match_id = m.id
             WHERE m.status = 'live' AND (l.match_id IS NULL OR l.expires_at < now())
             ORDER BY m.updated_at DESC LIMIT 500",
            &[],
        )?;
        Ok(rows.iter().map(|r| r.get(0)).collect())
    }

    /// Of `nodes`, those not seen within a lease. (Blocking.)
    pub(super) fn dead(&self, nodes: &[String]) -> Result<Vec<String>, ClusterError> {
        if nodes.is_empty() {
            return Ok(Vec::new());
        }
        let rows = self.db()?.query(
            "SELECT id FROM cluster_nodes WHERE id = ANY($1)
             AND seen_at >= now() - $2 * interval '1 millisecond'",
            &[&nodes, &self.lease_ms()],
        )?;
        let alive: HashSet<String> = rows.iter().map(|r| r.get(0)).collect();
        Ok(leases::dead(nodes, &alive))
    }

    /// Publishes `e` on `node`'s channel (lost if nobody listens, as
    /// pub/sub is).
    pub(super) async fn send(&self, node: &str, e: &Envelope) {
        let Some(text) = e.encode() else {
            return;
        };
        let mut conn = self.publisher.clone();
        let publish = conn.publish::<_, _, ()>(channel(node), text);
        match tokio::time::timeout(REDIS_TIMEOUT, publish).await {
            Ok(Ok(())) => {}
            Ok(Err(err)) => warn!(error = %err, node, "publishing to another node failed"),
            Err(_) => warn!(node, "publishing to another node timed out"),
        }
    }
}
