//! Support for the tests of several nodes: a node process on given
//! PostgreSQL and Redis, the services (shared, or private to a test that
//! restarts or cuts them), and clients that find their match again,
//! whichever node it moved to.

use super::{Client, Server};
use game::protocol::ServerMessage;
use local_services::skip::{self, Service};
use local_services::{LocalPostgres, LocalRedis};
use std::time::{Duration, Instant};

/// Seconds a lease lasts in these tests.
pub const LEASE: u64 = 2;

/// A node of a cluster on `db` and `redis`, named `node` (unique on its
/// Redis).
pub fn node(dir: &std::path::Path, db: &str, redis: &str, node: &str) -> Server {
    node_with(dir, db, redis, node, &[])
}

/// A node like [`node`] with `extra` flags.
pub fn node_with(
    dir: &std::path::Path,
    db: &str,
    redis: &str,
    node: &str,
    extra: &[&str],
) -> Server {
    start_node(dir, db, redis, node, false, extra)
}

/// A node like [`node`] that tells the others where its clients reach
/// it (`--public-url`, its own address), so that they send them there.
pub fn routed_node(dir: &std::path::Path, db: &str, redis: &str, node: &str) -> Server {
    start_node(dir, db, redis, node, true, &[])
}

fn start_node(
    dir: &std::path::Path,
    db: &str,
    redis: &str,
    node: &str,
    public: bool,
    extra: &[&str],
) -> Server {
    // A free port, known before the node starts: it may be in its URL.
    let port = std::net::TcpListener::bind("127.0.0.1:0")
        .and_then(|l| l.local_addr())
        .map(|a| a.port())
        .expect("a free port");
    let addr = format!("127.0.0.1:{port}");
    let lease = LEASE.to_string();
    let url = format!("http://{addr}");
    let mut args = vec![
        "--database-url",
        db,
        "--redis-url",
        redis,
        "--node-id",
        node,
        "--lease-seconds",
        &lease,
    ];
    if public {
        args.extend(["--public-url", &url]);
    }
    args.extend_from_slice(extra);
    Server::start_on(dir, &addr, &args)
}

/// The opening every cluster test plays: White knocks a piece off and
/// shoots again, then passes the turn; Black answers. Returns once White
/// has the three shots (broadcast after they were stored: acknowledged).
pub async fn three_shots(white: &mut Client, black: &mut Client) {
    white.send(&super::shot(4, 0.0, 2.0)).await;
    white.send(&super::shot(2, 0.0, 0.5)).await;
    until_shots(black, 2).await;
    black.send(&super::shot(10, 0.0, -0.5)).await;
    until_shots(white, 3).await;
}

/// The record of the finished match `id`, as `node` serves it.
pub async fn record(node: &Server, id: &str) -> game::MatchRecord {
    let (status, record) = node
        .http("GET", &format!("/api/matches/{id}/record"), "")
        .await;
    assert_eq!(status, 200, "{record}");
    serde_json::from_str(&record).expect("a record")
}

/// A fresh database and the shared Redis, or `None` (skipped). (They
/// block: off the runtime's thread.)
pub fn services(test: &str) -> Option<(String, String)> {
    tokio::task::block_in_place(|| {
        let db = local_services::local_postgres::shared_database(test)?;
        let redis = local_services::local_redis::shared(test)?.url();
        Some((db, redis))
    })
}

/// A Redis of this test's own (to restart or cut), or `None` (skipped).
/// Started on the runtime's thread, which lives as long as the test: the
/// service's parent-death signal is tied to the thread that starts it.
pub fn private_redis(test: &str) -> Option<LocalRedis> {
    match tokio::task::block_in_place(LocalRedis::start) {
        Ok(r) => Some(r),
        Err(e) => {
            skip::without(test, Service::Redis, &e.to_string());
            None
        }
    }
}

/// A PostgreSQL of this test's own (to restart) and the URL of a fresh
/// database on it, or `None` (skipped); started as [`private_redis`].
pub fn private_postgres(test: &str) -> Option<(LocalPostgres, String)> {
    let started = tokio::task::block_in_place(|| {
        let pg = LocalPostgres::start().map_err(|e| e.to_string())?;
        let url = pg.fresh_database("faults").map_err(|e| e.to_string())?;
        Ok::<_, String>((pg, url))
    });
    match started {
        Ok(p) => Some(p),
        Err(e) => {
            skip::without(test, Service::Postgres, &e);
            None
        }
    }
}

/// Reads `client` until it has seen `n` `shot-played` messages.
pub async fn until_shots(client: &mut Client, n: usize) {
    for _ in 0..n {
        client.next_of("shot-played").await;
    }
}

/// Connects to `id` on `server` until the match answers with its state
/// (while it moves between nodes the node may refuse or close).
pub async fn reconnect(server: &Server, id: &str, token: &str) -> (Client, game::MatchView) {
    reconnect_any(&[server], id, token).await
}

/// Connects to `id` through `node`, following it to the node that plays
/// the match, until the match answers with its state (while it moves, a
/// node may refuse, close, or send the client to a node that died): the
/// client, the state, and the address of the node it ended on.
pub async fn reconnect_following(
    node: &Server,
    id: &str,
    token: &str,
) -> (Client, game::MatchView, String) {
    let deadline = Instant::now() + Duration::from_secs(40);
    loop {
        assert!(Instant::now() < deadline, "the match did not come back");
        let attempt = tokio::time::timeout(Duration::from_secs(3), async {
            let (mut c, at) = Client::try_connect_following(&node.addr, id, Some(token))
                .await
                .ok()?;
            match c.try_next().await {
                Some(ServerMessage::MatchState { view, .. }) => Some((c, view, at)),
                _ => None,
            }
        })
        .await;
        if let Ok(Some(found)) = attempt {
            return found;
        }
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
}

/// Connects to `id` on each of `nodes` in turn until one answers with
/// the match's state: a client that finds its match again wherever it is
/// played (a node may refuse, close, or not answer while it moves).
pub async fn reconnect_any(nodes: &[&Server], id: &str, token: &str) -> (Client, game::MatchView) {
    let deadline = Instant::now() + Duration::from_secs(40);
    for k in 0.. {
        assert!(Instant::now() < deadline, "the match did not come back");
        let node = nodes[k % nodes.len()];
        let attempt = tokio::time::timeout(Duration::from_secs(3), async {
            let mut c = Client::try_connect(&node.addr, id, Some(token))
                .await
                .ok()?;
            match c.try_next().await {
                Some(ServerMessage::MatchState { view, .. }) => Some((c, view)),
                _ => None,
            }
        })
        .await;
        if let Ok(Some(found)) = attempt {
            return found;
        }
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
    unreachable!()
}
