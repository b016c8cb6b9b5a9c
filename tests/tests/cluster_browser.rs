//! A browser in a cluster: two nodes on one PostgreSQL with Redis between
//! them, each with its public URL. A match against the computer created
//! on node B is played by B; a page node A served opens it, asks A where
//! the match's socket is (`/api/matches/ID/socket`), opens B's socket
//! itself (B accepts A's page: its origin is the cluster's) and plays there:
//! the client's report names B's socket, node A counts one client routed
//! and relays none. A third node, C, announces a public URL nothing answers
//! (a proxy route missing, a firewall): the page of A that opens C's match
//! is told C's socket, cannot open it, and plays through A's own socket
//! instead, A relaying. Skipped (with a note) without a browser,
//! PostgreSQL or Redis, unless `CHAPAEV_REQUIRE_POSTGRES` /
//! `CHAPAEV_REQUIRE_REDIS` say they must be there.

use e2e::browser::{self, Driver};
use e2e::process::Server;
use e2e::{api, artifacts_dir, E2eError, Result};
use fantoccini::Client;
use serde_json::Value;
use std::path::Path;
use std::time::Duration;
use tokio::io::{AsyncReadExt, AsyncWriteExt};

const STATE: &str = "return window.chapaev_state || null;";

/// A single-valued metric of the node at `addr`.
async fn metric(addr: &str, name: &str) -> Result<Option<u64>> {
    let io = |source| E2eError::Io {
        what: format!("GET /metrics on {addr}"),
        source,
    };
    let mut stream = tokio::net::TcpStream::connect(addr).await.map_err(io)?;
    let request = format!("GET /metrics HTTP/1.0\r\nHost: {addr}\r\n\r\n");
    stream.write_all(request.as_bytes()).await.map_err(io)?;
    let mut text = String::new();
    stream.read_to_string(&mut text).await.map_err(io)?;
    Ok(text
        .lines()
        .find(|l| l.starts_with(&format!("{name} ")))
        .and_then(|l| l.split(' ').nth(1)?.parse().ok()))
}

/// A loopback address with a port free at the time of asking (nothing
/// listens there once the listener asked with is dropped).
fn free_addr() -> String {
    let port = std::net::TcpListener::bind("127.0.0.1:0")
        .and_then(|l| l.local_addr())
        .map(|a| a.port())
        .expect("a free port");
    format!("127.0.0.1:{port}")
}

/// A node of the cluster on `db` and `redis`, named `name`, announcing
/// `public` as its public URL (its own address when `None`).
fn node(
    scratch: &Path,
    artifacts: &Path,
    (db, redis): (&str, &str),
    name: &str,
    public: Option<&str>,
) -> Server {
    let addr = free_addr();
    let url = public.map_or_else(|| format!("http://{addr}"), str::to_string);
    Server::start_with(
        Path::new(env!("CARGO_BIN_EXE_e2e-server")),
        &scratch.join(name),
        &artifacts.join(format!("server-{name}.log")),
        &addr,
        &[
            "--database-url",
            db,
            "--redis-url",
            redis,
            "--node-id",
            name,
            "--lease-seconds",
            "2",
            "--public-url",
            &url,
        ],
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_page_from_one_node_plays_a_match_another_node_owns_on_that_nodes_socket() {
    let Some(programs) = browser::find_programs().unwrap_or_else(|e| panic!("{e}")) else {
        return;
    };
    let services = tokio::task::block_in_place(|| {
        let db = local_services::local_postgres::shared_database("browser_cluster")?;
        let redis = local_services::local_redis::shared("browser_cluster")?.url();
        Some((db, redis))
    });
    let Some((db, redis)) = services else {
        return;
    };
    let artifacts = artifacts_dir().unwrap_or_else(|e| panic!("{e}"));
    let scratch = tempfile::tempdir().unwrap();
    let services = (db.as_str(), redis.as_str());
    let a = node(scratch.path(), &artifacts, services, "page-a", None);
    let b = node(scratch.path(), &artifacts, services, "owner-b", None);
    // Port 9 (discard): no port a test asks the system for is under 1024,
    // so no node of this test can come to listen there (a port asked for
    // and let go could be handed to node C itself).
    let unreachable = "http://127.0.0.1:9".to_string();
    let c = node(
        scratch.path(),
        &artifacts,
        services,
        "unreachable-c",
        Some(&unreachable),
    );
    let driver = Driver::start(&programs, &artifacts.join("chromedriver-cluster.log"))
        .unwrap_or_else(|e| panic!("{e}"));
    let client = driver
        .session(&programs, &scratch.path().join("profile-cluster"))
        .await
        .unwrap_or_else(|e| panic!("{e}"));
    let outcome = match page_of_a_plays_on_b(&client, &a, &b).await {
        Ok(()) => page_of_a_falls_back_to_a_when_cs_socket_is_unreachable(&client, &a, &c).await,
        Err(e) => Err(e),
    };
    if let Err(e) = outcome {
        let _ = browser::screenshot(&client, &artifacts.join("failure-cluster.png")).await;
        if let Ok(state) = browser::eval(&client, STATE).await {
            eprintln!("e2e: chapaev_state at the failure: {state}");
        }
        let _ = client.close().await;
        panic!("{e} (logs in {})", artifacts.display());
    }
    let _ = client.close().await;
}

/// Creates a match against the computer on `owner` (so `owner` plays it)
/// and opens it, seat and all, in a page `page` served; returns the state
/// at the player's first turn.
async fn open_on(
    client: &Client,
    page: &Server,
    owner: &Server,
    name: &str,
) -> Result<(String, Value)> {
    let body = serde_json::json!({"name": name, "opponent": "bot", "bot_level": "easy"});
    let (status, grant) = api::post_json(&owner.addr, "/api/matches", &body).await?;
    let (Some(id), Some(token)) = (grant["match_id"].as_str(), grant["token"].as_str()) else {
        return Err(E2eError::Check(format!(
            "no seat from {} ({status}): {grant}",
            owner.addr
        )));
    };
    // The page comes from `page`, which holds the seat's token as if it
    // had created the match.
    client.goto(&page.url("/")).await?;
    let keep = format!(
        "localStorage.setItem('chapaev.token.{id}', '{token}'); \
         localStorage.setItem('chapaev.name', '{name}'); return true;"
    );
    browser::eval(client, &keep).await?;
    client.goto(&page.url(&format!("/#/play/{id}"))).await?;
    client.refresh().await?;
    let state = browser::poll(
        client,
        &format!(
            "our turn in the match {} plays, on the page of {}",
            owner.addr, page.addr
        ),
        STATE,
        Duration::from_secs(30),
        Duration::from_millis(50),
        |s: &Value| s["screen"] == "play" && s["connected"] == true && s["my_turn"] == true,
    )
    .await?;
    Ok((id.to_string(), state))
}

async fn page_of_a_plays_on_b(client: &Client, a: &Server, b: &Server) -> Result<()> {
    // Node B creates the match, so node B plays it.
    let (id, state) = open_on(client, a, b, "Petka").await?;
    let owner = format!("ws://{}/ws?match={id}", b.addr);
    if state["socket"] != owner.as_str() {
        return Err(E2eError::Check(format!(
            "the page's socket is {}, not node B's {owner}",
            state["socket"]
        )));
    }
    let routed = metric(&a.addr, "chapaev_cluster_connections_routed").await?;
    let relayed = metric(&a.addr, "chapaev_cluster_connections_relayed").await?;
    let on_b = metric(&b.addr, "chapaev_connections").await?;
    // Each load of the match's page asks node A once (the page may load it
    // twice here: the address change, then the reload); none of it relays.
    if routed.unwrap_or(0) < 1 || relayed != Some(0) || on_b != Some(1) {
        return Err(E2eError::Check(format!(
            "node A routed {routed:?} and relays {relayed:?} (want at least 1 and 0); \
             node B holds {on_b:?} connections (want 1)"
        )));
    }
    Ok(())
}

async fn page_of_a_falls_back_to_a_when_cs_socket_is_unreachable(
    client: &Client,
    a: &Server,
    c: &Server,
) -> Result<()> {
    // Node C creates the match and plays it, but its announced socket
    // answers nobody: the page must fall back to node A's own socket.
    let (id, state) = open_on(client, a, c, "Anka").await?;
    let own = format!("ws://{}/ws?match={id}", a.addr);
    if state["socket"] != own.as_str() {
        return Err(E2eError::Check(format!(
            "the page's socket is {}, not node A's own {own} (node C's is unreachable)",
            state["socket"]
        )));
    }
    let relayed = metric(&a.addr, "chapaev_cluster_connections_relayed").await?;
    if relayed.unwrap_or(0) < 1 {
        return Err(E2eError::Check(format!(
            "node A relays {relayed:?} connections to node C (want at least 1)"
        )));
    }
    Ok(())
}
