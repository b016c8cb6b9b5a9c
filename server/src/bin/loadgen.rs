//! `loadgen`: a load generator for the match server. It creates M
//! person-vs-person matches over HTTP, opens N WebSocket clients (two
//! players per match, the rest spread over the matches as spectators), and
//! lets the players shoot as fast as their turns come for a while. It
//! reports the connections held, shots per second, the p50/p99 latency
//! from sending a shot to receiving its `shot-played` broadcast, beside the
//! same connections' ping-to-pong time (the floor without the match), the
//! server's own arrival-to-broadcast histogram and resident memory per
//! connection (from `/metrics`), and what else delayed the run: how often
//! the load generator itself could not run on time, and the machine's busy
//! and hypervisor-stolen CPU shares (`/proc/stat`, Linux).
//!
//! Given several server nodes (`--addr` repeated, or a comma-separated
//! list), it spreads the load over them: match k is created (and joined) on
//! node k round-robin, its first player connects to that node, its second
//! player to the next one, and its spectators round-robin from the node
//! after the creating one, so that a match's messages cross between nodes.
//! The server-side figures (connections, CPU, memory, histograms) are then
//! the sums over the nodes, and each node's own share is listed too: the
//! connections it holds, those it relays to another node or serves for
//! one, and its CPU seconds. With `--placement local` every client of a
//! match connects to the node that created (and plays) it instead, so
//! nothing is relayed: the two runs side by side give the cost of relayed
//! connections against local ones. With `--placement routed` the clients
//! connect where `spread` puts them but ask to be sent to the node that
//! plays their match (`follow=1`, [`bots::owner`]): nodes started with
//! `--public-url` answer `307` to it, and the client ends up local.
//!
//! With `--hosted-bots N --hosted-module FILE` it first makes N bot
//! accounts that each upload FILE as their hosted module, and waits
//! `--hosted-wait-seconds` for the server's ladder to pair them: the people's
//! matches are then measured while the server plays hosted bots beside
//! them (start the server with `--hosted-matches` at least N and a short
//! `--ladder-seconds`), and the hosted bots' decisions during the run are
//! reported.
//!
//! ```sh
//! cargo run --release -p server -- --data-dir /tmp/chapaev-load \
//!     --max-connections-per-address 100000 --create-per-sec 10000 --create-burst 10000 &
//! cargo run --release -p server --bin loadgen -- --matches 50 --clients 400 --seconds 20
//! # Over a local cluster of two nodes (scripts/cluster start):
//! cargo run --release -p server --bin loadgen -- --addr 127.0.0.1:8080,127.0.0.1:8081 \
//!     --matches 50 --clients 400 --seconds 20
//! ```

// The HTTP client shared with the tests (not in the server library).
#[path = "../../tools/loopback.rs"]
mod loopback;

use clap::Parser;
use futures_util::{SinkExt, StreamExt};
use game::noise::SplitMix64;
use game::protocol::{ClientMessage, ServerMessage, PROTOCOL_VERSION};
use game::token::SeatToken;
use game::{Next, Phase, PieceId, Seat, Side};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};
use tokio::net::TcpStream;
use tokio_tungstenite::tungstenite::Message;

/// Load generator for the Chapaev match server (loopback only).
#[derive(Parser, Debug)]
#[command(name = "loadgen", version)]
struct Args {
    /// Server address, `host:port`. Several nodes of one cluster: repeat
    /// the flag or separate them with commas; the load is spread over them.
    #[arg(long, default_value = "127.0.0.1:8080", value_delimiter = ',')]
    addr: Vec<String>,
    /// Matches played at once.
    #[arg(long, default_value_t = 20)]
    matches: usize,
    /// WebSocket clients in all (at least two per match; the rest watch).
    #[arg(long, default_value_t = 100)]
    clients: usize,
    /// How long the players shoot, seconds.
    #[arg(long, default_value_t = 20)]
    seconds: u64,
    /// Mean pause before each shot, milliseconds: each pause is drawn between
    /// half and one and a half times it (0: shoot as soon as it is your turn).
    #[arg(long, default_value_t = 0)]
    think_ms: u64,

    /// Where the clients of a match connect over several nodes: `spread`
    /// (its second player and spectators on the other nodes, relayed to
    /// the node that plays it), `local` (all on that node) or `routed`
    /// (where `spread` puts them, asking to be sent to the node that plays
    /// the match, which the nodes do when given `--public-url`).
    #[arg(long, value_enum, default_value_t = Placement::Spread)]
    placement: Placement,

    /// Threads of the load generator's own runtime. It shares the machine
    /// with the server it measures; one thread drives 10,000 connections and
    /// leaves the other cores to the server.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u16).range(1..=64))]
    threads: u16,

    /// Hosted bots to put on the server's ladder before the run (bot
    /// accounts made on the first node, each uploading `--hosted-module`).
    #[arg(long, default_value_t = 0)]
    hosted_bots: usize,
    /// The WebAssembly module the hosted bots upload.
    #[arg(long, value_name = "FILE")]
    hosted_module: Option<std::path::PathBuf>,
    /// Seconds to wait after the uploads for the ladder to pair them.
    #[arg(long, default_value_t = 5)]
    hosted_wait_seconds: u64,
}

/// Where the clients of a match connect (see `--placement`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum Placement {
    Spread,
    Local,
    Routed,
}

/// Failures that end the run.
#[derive(Debug, thiserror::Error)]
enum LoadError {
    #[error("I/O: {0}")]
    Io(#[from] std::io::Error),
    #[error("HTTP: {0}")]
    Http(String),
    #[error("WebSocket: {0}")]
    Ws(#[from] tokio_tungstenite::tungstenite::Error),
    #[error("JSON: {0}")]
    Json(#[from] serde_json::Error),
}

/// One request; the body of a 2xx answer.
async fn http(addr: &str, method: &str, path: &str, body: &str) -> Result<String, LoadError> {
    let (status, text) = loopback::request(addr, method, path, &[], body)
        .await
        .map_err(|e| LoadError::Http(e.to_string()))?;
    if !(200..300).contains(&status) {
        return Err(LoadError::Http(format!("{method} {path}: status {status}")));
    }
    Ok(text)
}

/// Makes `count` bot accounts on `addr` that each upload the module at
/// `path` as their hosted module.
async fn hosted_bots(addr: &str, count: usize, path: &std::path::Path) -> Result<(), LoadError> {
    let bytes = Arc::new(std::fs::read(path)?);
    let tag = std::process::id();
    for k in 0..count {
        let body = format!(r#"{{"name":"load-{tag}-{k}","bot":true}}"#);
        let created: serde_json::Value =
            serde_json::from_str(&http(addr, "POST", "/api/accounts", &body).await?)?;
        let key = created["key"].as_str().unwrap_or_default().to_string();
        let url = format!("http://{addr}/api/accounts/me/module");
        let bytes = bytes.clone();
        let put = tokio::task::spawn_blocking(move || {
            ureq::put(&url)
                .set("Authorization", &format!("Bearer {key}"))
                .send_bytes(&bytes)
                .map(|_| ())
                .map_err(|e| format!("PUT {url}: {e}"))
        })
        .await
        .map_err(|e| LoadError::Http(e.to_string()))?;
        put.map_err(LoadError::Http)?;
    }
    Ok(())
}

/// The cumulative buckets of a histogram in the text of `/metrics`: (upper
/// bound in seconds, observations up to it).
fn buckets(metrics: &str, name: &str) -> Vec<(f64, f64)> {
    let prefix = format!("{name}_bucket{{le=\"");
    metrics
        .lines()
        .filter_map(|l| l.strip_prefix(prefix.as_str()))
        .filter_map(|l| {
            let (le, n) = l.split_once("\"} ")?;
            Some((le.parse().ok()?, n.trim().parse().ok()?))
        })
        .collect()
}

/// A latency histogram of the servers' `/metrics` (`name` without the
/// `_bucket` suffix), summed over the nodes (one text each; they share the
/// bucket bounds): the bucket bounds (ms) holding the median and the 99th
/// percentile, and the share of observations within 10 ms.
fn server_side<S: AsRef<str>>(metrics: &[S], name: &str) -> Option<(f64, f64, f64)> {
    let mut buckets: Vec<(f64, f64)> = Vec::new();
    for text in metrics {
        let node = self::buckets(text.as_ref(), name);
        if buckets.is_empty() {
            buckets = node;
        } else if node.len() == buckets.len() {
            for (sum, (_, n)) in buckets.iter_mut().zip(node) {
                sum.1 += n;
            }
        }
    }
    let total = buckets.last()?.1;
    if total <= 0.0 {
        return None;
    }
    let at = |q: f64| {
        buckets
            .iter()
            .find(|(_, n)| *n >= q * total)
            .map(|(le, _)| le * 1e3)
    };
    let within = buckets.iter().find(|(le, _)| *le == 0.01)?.1 / total * 100.0;
    Some((at(0.5)?, at(0.99)?, within))
}

/// Ticks every millisecond until `until` and counts the ticks that came more
/// than 10 ms late: when the load generator itself could not run (CPU
/// contention, a stalled virtual machine), its latencies include that wait.
async fn own_stalls(until: Instant) -> (u64, Duration) {
    let (mut late, mut longest) = (0, Duration::ZERO);
    while Instant::now() < until {
        let t = Instant::now();
        tokio::time::sleep(Duration::from_millis(1)).await;
        let lag = t.elapsed().saturating_sub(Duration::from_millis(1));
        if lag > Duration::from_millis(10) {
            late += 1;
        }
        longest = longest.max(lag);
    }
    (late, longest)
}

/// Machine-wide CPU jiffies from `/proc/stat` (Linux): all, idle, stolen.
struct CpuTimes {
    total: u64,
    idle: u64,
    steal: u64,
}

impl CpuTimes {
    /// Busy and stolen shares (percent) between `earlier` and `self`.
    fn since(&self, earlier: &CpuTimes) -> (f64, f64) {
        let total = self.total.saturating_sub(earlier.total).max(1) as f64;
        let idle = self.idle.saturating_sub(earlier.idle) as f64;
        let steal = self.steal.saturating_sub(earlier.steal) as f64;
        (
            100.0 * (total - idle - steal) / total,
            100.0 * steal / total,
        )
    }
}

fn cpu_times() -> Option<CpuTimes> {
    let stat = std::fs::read_to_string("/proc/stat").ok()?;
    let fields: Vec<u64> = stat
        .lines()
        .next()?
        .split_whitespace()
        .skip(1)
        .filter_map(|v| v.parse().ok())
        .collect();
    // user nice system idle iowait irq softirq steal ...
    Some(CpuTimes {
        total: fields.iter().take(8).sum(),
        idle: fields.get(3)? + fields.get(4)?,
        steal: *fields.get(7)?,
    })
}

/// A single-valued metric in the text of `/metrics`.
fn metric_value(metrics: &str, name: &str) -> Option<f64> {
    metrics
        .lines()
        .find_map(|l| l.strip_prefix(name)?.strip_prefix(' '))
        .and_then(|v| v.trim().parse().ok())
}

/// Every node's `/metrics`, fetched now (an empty text where one did not answer).
async fn all_metrics(addrs: &[String]) -> Vec<String> {
    let mut texts = Vec::new();
    for addr in addrs {
        texts.push(http(addr, "GET", "/metrics", "").await.unwrap_or_default());
    }
    texts
}

/// A single-valued metric summed over the nodes' `/metrics` texts; none if
/// a node does not report it.
fn metric_sum(metrics: &[String], name: &str) -> Option<f64> {
    metrics.iter().map(|m| metric_value(m, name)).sum()
}

/// The single-valued metric of every node, fetched now, summed.
async fn server_metric(addrs: &[String], name: &str) -> Option<f64> {
    metric_sum(&all_metrics(addrs).await, name)
}

async fn resident_bytes(addrs: &[String]) -> Option<u64> {
    server_metric(addrs, "process_resident_memory_bytes")
        .await
        .map(|b| b as u64)
}

#[derive(Default)]
struct Totals {
    shots: AtomicU64,
    messages: AtomicU64,
    errors: AtomicU64,
    finished: AtomicU64,
}

type Ws = tokio_tungstenite::WebSocketStream<tokio_tungstenite::MaybeTlsStream<TcpStream>>;

/// Opens a match's WebSocket (on the node that plays it, if `follow`)
/// and says hello with `token` (none: watch).
async fn connect(addr: &str, id: &str, token: Option<&str>, follow: bool) -> Result<Ws, LoadError> {
    let url = format!("ws://{addr}/ws?match={id}");
    // No Nagle: a shot is one small frame and must leave at once.
    let mut ws = if follow {
        bots::owner::connect(&url, true).await?.0
    } else {
        tokio_tungstenite::connect_async_with_config(url, None, true)
            .await?
            .0
    };
    let hello = ClientMessage::Hello {
        protocol: PROTOCOL_VERSION,
        name: "loadgen".into(),
        token: token.map(SeatToken::new),
        key: None,
    };
    ws.send(Message::Text(hello.to_json())).await?;
    Ok(ws)
}

/// What one player measured.
#[derive(Default)]
struct Measured {
    /// From sending each shot to receiving its `shot-played`.
    shots: Vec<Duration>,
    /// From sending a WebSocket ping as each shot's outcome arrives to its
    /// pong: the same connection and machine under the same load, without
    /// the match (the session answers pings itself), so the floor under the
    /// shots' latencies.
    pongs: Vec<Duration>,
}

/// A player: shoots a random own piece whenever its turn comes, and pings
/// as each of its shots' outcome arrives.
async fn player(
    mut ws: Ws,
    seed: u64,
    until: Instant,
    think: Duration,
    totals: Arc<Totals>,
    counts_finish: bool,
) -> Measured {
    let mut rng = SplitMix64::new(seed);
    let mut measured = Measured::default();
    let mut ping_sent: Option<Instant> = None;
    let mut me = Side::White;
    let mut own: Vec<PieceId> = Vec::new();
    let mut pending: Option<Instant> = None;
    let mut my_turn = false;
    loop {
        if my_turn && pending.is_none() && Instant::now() < until {
            if !think.is_zero() {
                // Players aim for a while, not in lockstep: between half and
                // one and a half times the mean thinking time.
                tokio::time::sleep(think.mul_f64(0.5 + rng.next_f64())).await;
            }
            let k = (rng.next_u64() % own.len().max(1) as u64) as usize;
            let Some(piece) = own.get(k).copied() else {
                break;
            };
            let a = rng.next_f64() * std::f64::consts::TAU;
            let speed = 0.2 + 0.5 * rng.next_f64();
            let m = ClientMessage::Shot {
                piece,
                velocity: glam::DVec2::new(a.cos(), a.sin()) * speed,
            };
            if ws.send(Message::Text(m.to_json())).await.is_err() {
                break;
            }
            pending = Some(Instant::now());
            my_turn = false;
        }
        if Instant::now() >= until && pending.is_none() {
            break;
        }
        let frame = match tokio::time::timeout(Duration::from_secs(10), ws.next()).await {
            Ok(Some(Ok(f))) => f,
            _ => break,
        };
        let text = match frame {
            Message::Text(text) => text,
            Message::Pong(_) => {
                if let Some(t) = ping_sent.take() {
                    measured.pongs.push(t.elapsed());
                }
                continue;
            }
            _ => continue,
        };
        totals.messages.fetch_add(1, Ordering::Relaxed);
        let Ok(msg) = ServerMessage::from_json(&text) else {
            continue;
        };
        match msg {
            ServerMessage::MatchState { you, view, .. } => {
                me = you.unwrap_or(Seat::First).side(view.swapped);
                own = view.board.of(me).map(|p| p.id).collect();
                my_turn = view.phase == Phase::Shooting && view.turn == me;
            }
            ServerMessage::ShotPlayed { outcome, .. } => {
                if let Some(t) = pending.take() {
                    if outcome.shooter == me {
                        measured.shots.push(t.elapsed());
                        totals.shots.fetch_add(1, Ordering::Relaxed);
                        // The floor, measured now rather than with the shot:
                        // a pong written just before the outcome would hold
                        // the outcome back (Nagle) until the pong's ACK.
                        if ping_sent.is_none() {
                            if ws.send(Message::Ping(Vec::new())).await.is_err() {
                                break;
                            }
                            ping_sent = Some(Instant::now());
                        }
                    } else {
                        pending = Some(t);
                    }
                }
                own.retain(|p| !outcome.knocked_off.contains(p));
                if outcome.round_end.is_some() {
                    own = PieceId::of(me).collect();
                }
                match outcome.next {
                    Next::Shoot { side } => my_turn = side == me,
                    Next::PieDecision { .. } => my_turn = false,
                    Next::MatchOver { .. } => {
                        if counts_finish {
                            totals.finished.fetch_add(1, Ordering::Relaxed);
                        }
                        break;
                    }
                }
            }
            ServerMessage::Error { .. } => {
                totals.errors.fetch_add(1, Ordering::Relaxed);
                pending = None;
                my_turn = true;
            }
            ServerMessage::MatchOver { .. } => break,
            _ => {}
        }
    }
    let _ = ws.close(None).await;
    measured
}

/// A spectator: reads until the end.
async fn spectator(mut ws: Ws, until: Instant, totals: Arc<Totals>) {
    while Instant::now() < until {
        match tokio::time::timeout(until.saturating_duration_since(Instant::now()), ws.next()).await
        {
            Ok(Some(Ok(Message::Text(_)))) => {
                totals.messages.fetch_add(1, Ordering::Relaxed);
            }
            Ok(Some(Ok(_))) => {}
            _ => break,
        }
    }
    let _ = ws.close(None).await;
}

fn percentile(sorted: &[Duration], p: f64) -> Duration {
    if sorted.is_empty() {
        return Duration::ZERO;
    }
    let k = ((sorted.len() as f64 - 1.0) * p).round() as usize;
    sorted[k.min(sorted.len() - 1)]
}

/// The p50, p99 and maximum of sorted latencies, in milliseconds.
fn spread(sorted: &[Duration]) -> String {
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    format!(
        "p50 {:.2} ms, p99 {:.2} ms, max {:.2} ms",
        ms(percentile(sorted, 0.5)),
        ms(percentile(sorted, 0.99)),
        ms(sorted.last().copied().unwrap_or_default())
    )
}

async fn run(args: Args) -> Result<(), LoadError> {
    let addrs: Vec<String> = args
        .addr
        .iter()
        .map(|a| a.trim().to_string())
        .filter(|a| !a.is_empty())
        .collect();
    let addrs = &addrs;
    let nodes = addrs.len();
    if nodes == 0 {
        return Err(LoadError::Http("no server address (--addr)".into()));
    }
    // Node `k` round-robin.
    let node = |k: usize| addrs[k % nodes].as_str();
    // The node of a client of match `m` that would be on node `k`.
    let client_node = |m: usize, k: usize| match args.placement {
        Placement::Spread | Placement::Routed => node(k),
        Placement::Local => node(m),
    };
    if args.hosted_bots > 0 {
        let Some(path) = &args.hosted_module else {
            return Err(LoadError::Http(
                "--hosted-bots needs --hosted-module".into(),
            ));
        };
        hosted_bots(node(0), args.hosted_bots, path).await?;
        tokio::time::sleep(Duration::from_secs(args.hosted_wait_seconds)).await;
    }
    let follow = args.placement == Placement::Routed;
    let matches = args.matches.max(1);
    let clients = args.clients.max(2 * matches);
    let rss_before = resident_bytes(addrs).await;
    let mut seats = Vec::new();
    for m in 0..matches {
        // Match m lives on node m (created and joined there).
        let created: serde_json::Value = serde_json::from_str(
            &http(node(m), "POST", "/api/matches", r#"{"name":"load"}"#).await?,
        )?;
        let id = created["match_id"].as_str().unwrap_or_default().to_string();
        let joined: serde_json::Value = serde_json::from_str(
            &http(
                node(m),
                "POST",
                &format!("/api/matches/{id}/join"),
                r#"{"name":"load"}"#,
            )
            .await?,
        )?;
        let a = created["token"].as_str().unwrap_or_default().to_string();
        let b = joined["token"].as_str().unwrap_or_default().to_string();
        seats.push((id, a, b));
    }
    let started = Instant::now();
    let mut players = Vec::new();
    let mut watchers = Vec::new();
    for (m, (id, a, b)) in seats.iter().enumerate() {
        // The first player on the creating node, the second on the next one.
        players.push(connect(node(m), id, Some(a), follow).await?);
        players.push(connect(client_node(m, m + 1), id, Some(b), follow).await?);
    }
    for k in 0..clients - 2 * matches {
        // Spectator k watches match k % matches, as its (k / matches)-th
        // spectator: round-robin over the nodes from the one after the
        // creating node.
        let m = k % matches;
        watchers.push(
            connect(
                client_node(m, m + 1 + k / matches),
                &seats[m].0,
                None,
                follow,
            )
            .await?,
        );
    }
    let connect_time = started.elapsed();
    // Let the servers settle, then weigh them.
    tokio::time::sleep(Duration::from_millis(500)).await;
    let rss_held = resident_bytes(addrs).await;
    let mut gauges = Vec::new();
    let mut held_metrics = Vec::new();
    for addr in addrs {
        let metrics = http(addr, "GET", "/metrics", "").await?;
        held_metrics.push(metrics.clone());
        gauges.push(
            metrics
                .lines()
                .find_map(|l| l.strip_prefix("chapaev_connections "))
                .unwrap_or("?")
                .trim()
                .to_string(),
        );
    }
    let held = match gauges
        .iter()
        .map(|g| g.parse::<u64>().ok())
        .sum::<Option<u64>>()
    {
        Some(sum) if nodes > 1 => format!("{sum} ({}: server gauges)", gauges.join(" + ")),
        Some(sum) => format!("{sum} (server gauge)"),
        None => format!("{} (server gauges)", gauges.join(" + ")),
    };

    let totals = Arc::new(Totals::default());
    let until = Instant::now() + Duration::from_secs(args.seconds);
    let stalls = tokio::spawn(own_stalls(until));
    let cpu_before = cpu_times();
    let metrics_before = all_metrics(addrs).await;
    let server_cpu_before = metric_sum(&metrics_before, "process_cpu_seconds_total");
    let own_cpu_before = server::metrics::cpu_seconds();
    let play_start = Instant::now();
    let think = Duration::from_millis(args.think_ms);
    let mut tasks = Vec::new();
    for (k, ws) in players.into_iter().enumerate() {
        tasks.push(tokio::spawn(player(
            ws,
            k as u64 + 1,
            until,
            think,
            totals.clone(),
            k % 2 == 0,
        )));
    }
    let mut watch_tasks = Vec::new();
    for ws in watchers {
        watch_tasks.push(tokio::spawn(spectator(ws, until, totals.clone())));
    }
    let (mut latencies, mut pongs) = (Vec::new(), Vec::new());
    for t in tasks {
        if let Ok(m) = t.await {
            latencies.extend(m.shots);
            pongs.extend(m.pongs);
        }
    }
    for t in watch_tasks {
        let _ = t.await;
    }
    let elapsed = play_start.elapsed().as_secs_f64();
    let cpu = cpu_before.zip(cpu_times()).map(|(a, b)| b.since(&a));
    let own_cpu = own_cpu_before
        .zip(server::metrics::cpu_seconds())
        .map(|(a, b)| b - a);
    // One read of the servers' metrics after the play: their CPU and histograms.
    let metrics = all_metrics(addrs).await;
    let server_cpu = server_cpu_before
        .zip(metric_sum(&metrics, "process_cpu_seconds_total"))
        .map(|(a, b)| b - a);
    let (stalled, longest) = stalls.await.unwrap_or_default();
    latencies.sort();
    pongs.sort();
    let shots = totals.shots.load(Ordering::Relaxed);
    if nodes > 1 {
        println!(
            "nodes:                  {nodes} ({}); matches created round-robin, {}",
            addrs.join(", "),
            match args.placement {
                Placement::Spread => "each one's players on two nodes, spectators spread",
                Placement::Local => "all of each one's clients on its node",
                Placement::Routed => {
                    "each one's clients asking two or more nodes, sent to the node playing it"
                }
            }
        );
    } else {
        println!("nodes:                  1 ({})", addrs[0]);
    }
    println!("matches:                {matches}");
    if args.hosted_bots > 0 {
        let decided = |m: &[String], name: &str| metric_sum(m, name).unwrap_or(0.0);
        let held_live = metric_sum(&held_metrics, "chapaev_live_matches").unwrap_or(0.0);
        println!(
            "hosted bots:            {} on the ladder; {:.0} matches live with the clients connected ({matches} of them people's); {:.0} hosted decisions during the run ({:.0} failed)",
            args.hosted_bots,
            held_live,
            decided(&metrics, "chapaev_hosted_decisions_total")
                - decided(&metrics_before, "chapaev_hosted_decisions_total"),
            decided(&metrics, "chapaev_hosted_decision_failures_total")
                - decided(&metrics_before, "chapaev_hosted_decision_failures_total"),
        );
    }
    println!(
        "clients:                {clients} ({} players, {} spectators), opened in {:.2} s",
        2 * matches,
        clients - 2 * matches,
        connect_time.as_secs_f64()
    );
    println!("connections held:       {held}");
    println!(
        "shots resolved:         {shots} in {elapsed:.1} s = {:.1} shots/s",
        shots as f64 / elapsed
    );
    println!(
        "messages received:      {} ({:.0}/s)",
        totals.messages.load(Ordering::Relaxed),
        totals.messages.load(Ordering::Relaxed) as f64 / elapsed
    );
    println!("shot-to-broadcast:      {}", spread(&latencies));
    println!(
        "ping-to-pong floor:     {} (a ping sent as each shot's outcome arrives)",
        spread(&pongs)
    );
    match server_side(&metrics, "chapaev_shot_to_broadcast_seconds") {
        Some((p50, p99, within)) => println!(
            "server side:            p50 <= {p50} ms, p99 <= {p99} ms, {within:.2}% within 10 ms (arrival to broadcast, /metrics buckets)"
        ),
        None => println!("server side:            not reported by /metrics"),
    }
    if let Some((p50, p99, within)) = server_side(&metrics, "chapaev_shot_resolution_seconds") {
        println!(
            "  of which in the room:  p50 <= {p50} ms, p99 <= {p99} ms, {within:.2}% within 10 ms (its turn in the match to broadcast: physics, store)"
        );
    }
    if let Some((p50, p99, within)) = server_side(&metrics, "chapaev_store_commit_seconds") {
        println!(
            "store group commits:    p50 <= {p50} ms, p99 <= {p99} ms, {within:.2}% within 10 ms"
        );
    }
    println!(
        "load generator stalls:  {stalled} of its 1 ms ticks late by over 10 ms, longest {:.1} ms",
        longest.as_secs_f64() * 1e3
    );
    // CPU time is what the hypervisor's stealing does not blur: the cost
    // of the work itself.
    let per_shot = |secs: f64| secs * 1e6 / shots.max(1) as f64;
    if let (Some(server), Some(own)) = (server_cpu, own_cpu) {
        println!(
            "CPU while playing:      server{} {server:.2} s ({:.0} us per shot), load generator {own:.2} s ({:.0} us per shot)",
            if nodes > 1 { format!("s ({nodes} nodes together)") } else { String::new() },
            per_shot(server),
            per_shot(own)
        );
    }
    if let Some(server) = server_cpu {
        println!(
            "shots per server CPU-s: {:.1} (the servers' utime + stime, /proc/PID/stat)",
            shots as f64 / server.max(1e-9)
        );
    }
    if nodes > 1 {
        for (k, (addr, (before, after))) in addrs
            .iter()
            .zip(metrics_before.iter().zip(&metrics))
            .enumerate()
        {
            // The gauges as they stood with every client connected.
            let held = &held_metrics[k];
            let gauge =
                |name: &str| metric_value(held, name).map_or("?".into(), |v| format!("{v:.0}"));
            let cpu = metric_value(before, "process_cpu_seconds_total")
                .zip(metric_value(after, "process_cpu_seconds_total"))
                .map_or("?".into(), |(a, b)| format!("{:.2}", b - a));
            println!(
                "  node {} ({addr}): CPU {cpu} s; connections {}; matches played {}, relayed {}; connections relayed {}, served for other nodes {}, sent to the node playing their match {}",
                k + 1,
                gauge("chapaev_connections"),
                gauge("chapaev_cluster_matches_owned"),
                gauge("chapaev_cluster_matches_relayed"),
                gauge("chapaev_cluster_connections_relayed"),
                gauge("chapaev_cluster_connections_served"),
                gauge("chapaev_cluster_connections_routed"),
            );
        }
    }
    if let Some((busy, steal)) = cpu {
        println!(
            "machine CPU:            {busy:.0}% busy, {steal:.1}% stolen by the hypervisor (/proc/stat)"
        );
    }
    println!(
        "errors answered:        {}",
        totals.errors.load(Ordering::Relaxed)
    );
    println!(
        "matches finished:       {}",
        totals.finished.load(Ordering::Relaxed)
    );
    match (rss_before, rss_held) {
        (Some(a), Some(b)) => println!(
            "server memory:          {:.1} MiB before, {:.1} MiB with the clients connected{}: {:.1} KiB per connection (matches included)",
            a as f64 / 1048576.0,
            b as f64 / 1048576.0,
            if nodes > 1 { format!(" ({nodes} nodes together)") } else { String::new() },
            (b.saturating_sub(a)) as f64 / 1024.0 / clients as f64
        ),
        _ => println!("server memory:          not reported by /metrics"),
    }
    Ok(())
}

fn main() -> std::process::ExitCode {
    let args = Args::parse();
    let rt = match tokio::runtime::Builder::new_multi_thread()
        .worker_threads(usize::from(args.threads))
        .enable_all()
        .build()
    {
        Ok(rt) => rt,
        Err(e) => {
            eprintln!("loadgen: {e}");
            return std::process::ExitCode::FAILURE;
        }
    };
    match rt.block_on(run(args)) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("loadgen: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn server_side_percentiles_come_from_the_cumulative_buckets() {
        let m = server::metrics::Metrics::default();
        for ms in [1, 1, 2, 2, 2, 3, 3, 4, 4, 30] {
            m.shot_broadcast(Duration::from_micros(ms * 900));
        }
        let name = "chapaev_shot_to_broadcast_seconds";
        let (p50, p99, within) = server_side(&[m.render()], name).expect("histogram present");
        assert_eq!((p50, p99), (2.5, 50.0));
        assert!((within - 90.0).abs() < 1e-9, "{within}");
        assert!(server_side(&["no metrics here"], name).is_none());
    }

    #[test]
    fn several_nodes_histograms_and_gauges_are_summed() {
        let (a, b) = (
            server::metrics::Metrics::default(),
            server::metrics::Metrics::default(),
        );
        for ms in [1, 1, 2, 2, 2] {
            a.shot_broadcast(Duration::from_micros(ms * 900));
        }
        for ms in [3, 3, 4, 4, 30] {
            b.shot_broadcast(Duration::from_micros(ms * 900));
        }
        let name = "chapaev_shot_to_broadcast_seconds";
        let (p50, p99, within) =
            server_side(&[a.render(), b.render()], name).expect("histograms present");
        assert_eq!((p50, p99), (2.5, 50.0));
        assert!((within - 90.0).abs() < 1e-9, "{within}");
        let texts = ["x 2\ny 1".to_string(), "x 3.5".to_string()];
        assert_eq!(metric_sum(&texts, "x"), Some(5.5));
        assert_eq!(metric_sum(&texts, "y"), None);
    }
}
