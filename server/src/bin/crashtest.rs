//! `crashtest`: kill -9 during live matches, several times, with a verdict.
//! It starts the real server binary on a fresh data folder, creates M
//! person-vs-person matches over HTTP, plays them over WebSocket (two
//! players per match, gentle shots after a short think), and every few
//! seconds kills the server with SIGKILL while shots are in flight, then
//! starts it again on the same data folder and port. The players notice the
//! drop, reconnect with their seat tokens and carry on. A shot counts as
//! acknowledged once a client received its `shot-played` (the server stores
//! a move before it broadcasts it); after each restart every match must
//! come back (both seats get a `match-state` within the resume timeout) with
//! at least every acknowledged shot in its record, which is checked twice:
//! in the first `match-state` of the new server and in `GET
//! /api/matches/{id}`. It prints a table per kill and `VERDICT: PASS` (exit
//! 0) or `VERDICT: FAIL ...` (exit 1).
//!
//! ```sh
//! cargo build --release -p server --bin server --bin crashtest
//! target/release/crashtest --matches 1000 --kills 3 --play-seconds 10
//! ```

// The HTTP client shared with the tests (not in the server library).
#[path = "../../tools/loopback.rs"]
mod loopback;

use clap::Parser;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::Ordering;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Kill -9 the Chapaev server during live matches and check that no
/// acknowledged shot is lost and every match resumes.
#[derive(Parser, Debug, Clone)]
#[command(name = "crashtest", version)]
struct Args {
    /// Person-vs-person matches played at once (two WebSocket clients each).
    #[arg(long, default_value_t = 1000, value_parser = clap::value_parser!(u64).range(1..=5000))]
    matches: u64,
    /// How many times the server is killed and restarted.
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u64).range(1..=100))]
    kills: u64,
    /// Seconds of play before each kill.
    #[arg(long, default_value_t = 10)]
    play_seconds: u64,
    /// Mean pause before each shot, milliseconds (each pause is drawn
    /// between half and one and a half times it).
    #[arg(long, default_value_t = 200)]
    think_ms: u64,
    /// Seconds a match has, from the restarted server listening, to be back:
    /// both seats reconnected with their tokens and got a `match-state`.
    #[arg(long, default_value_t = 30)]
    resume_seconds: u64,
    /// Seconds the server has to print its address after a (re)start
    /// (it resumes every live match before it listens).
    #[arg(long, default_value_t = 300)]
    start_seconds: u64,
    /// The server binary (default: `server` next to this executable).
    #[arg(long)]
    server_bin: Option<PathBuf>,
    /// Folder for the server's store and its logs (`server-N.log`); default
    /// a fresh folder under the system's temporary folder, removed after a
    /// pass and kept after a failure. It must hold no store yet.
    #[arg(long)]
    data_dir: Option<PathBuf>,
    /// Keep the default temporary folder even after a pass.
    #[arg(long)]
    keep: bool,
    /// One more flag for the server (repeatable), e.g. `--server-arg=--sync=normal`.
    #[arg(long = "server-arg", allow_hyphen_values = true)]
    server_args: Vec<String>,
    /// Seed of the players' choices.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Threads of the clients' runtime (the server gets the other cores).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u16).range(1..=64))]
    threads: u16,
}

/// Failures that end the run before a verdict.
#[derive(Debug, thiserror::Error)]
enum CrashError {
    #[error("I/O: {0}")]
    Io(#[from] std::io::Error),
    #[error("HTTP: {0}")]
    Http(String),
    #[error("HTTP: {0}")]
    Request(#[from] loopback::HttpError),
    #[error("JSON: {0}")]
    Json(#[from] serde_json::Error),
    #[error("server: {0}")]
    Server(String),
    #[error("setup: {0}")]
    Setup(String),
    #[error("{0}; the server was stopped")]
    Interrupted(&'static str),
}

mod child {
    //! The server under test as a child process: started on the data
    //! folder with the limits lifted, its address read from the one line
    //! it prints, its log written beside the store, killed with SIGKILL,
    //! and never left running (dropping it kills it).

    use super::CrashError;
    use std::io::{BufRead, BufReader};
    use std::path::{Path, PathBuf};
    use std::process::{Child, Command, Stdio};
    use std::time::{Duration, Instant};

    /// How to start the server: binary, data folder and extra flags.
    #[derive(Clone, Debug)]
    pub struct Recipe {
        pub bin: PathBuf,
        pub data_dir: PathBuf,
        pub extra: Vec<String>,
        /// How long a start may take until the server listens.
        pub within: Duration,
    }

    /// A running server.
    pub struct ServerChild {
        child: Child,
        /// `host:port` it listens on.
        pub addr: String,
        /// From spawning it to reading its address.
        pub start_time: Duration,
    }

    impl Recipe {
        /// The flags: every per-address and per-server limit well above the
        /// test's load, and clocks long enough that nobody forfeits while
        /// the server is down.
        fn args(&self, addr: &str) -> Vec<String> {
            let mut a: Vec<String> = [
                "--addr",
                addr,
                "--max-connections",
                "12000",
                "--max-matches",
                "2000",
                "--max-connections-per-address",
                "12000",
                "--create-per-sec",
                "10000",
                "--create-burst",
                "10000",
                "--grace-seconds",
                "600",
                "--turn-seconds",
                "600",
                "--log",
                "info",
            ]
            .iter()
            .map(|s| s.to_string())
            .collect();
            a.push("--data-dir".into());
            a.push(self.data_dir.display().to_string());
            a.extend(self.extra.iter().cloned());
            a
        }

        /// Starts the server on `addr` (`127.0.0.1:0`: a free port), its
        /// standard error in `log`; waits until it prints its address.
        pub async fn start(&self, addr: &str, log: &Path) -> Result<ServerChild, CrashError> {
            let started = Instant::now();
            let log_file = std::fs::File::create(log)?;
            let mut child = Command::new(&self.bin)
                .args(self.args(addr))
                .stdin(Stdio::null())
                .stdout(Stdio::piped())
                .stderr(log_file)
                .spawn()
                .map_err(|e| {
                    CrashError::Server(format!("cannot start {}: {e}", self.bin.display()))
                })?;
            let Some(stdout) = child.stdout.take() else {
                let _ = child.kill();
                let _ = child.wait();
                return Err(CrashError::Server("no standard output to read".into()));
            };
            let reading = tokio::task::spawn_blocking(move || {
                let mut reader = BufReader::new(stdout);
                let mut line = String::new();
                let read = reader.read_line(&mut line);
                // The rest of its output (there should be none) is drained
                // so that the server never blocks on a full pipe.
                std::thread::spawn(move || std::io::copy(&mut reader, &mut std::io::sink()));
                read.map(|_| line)
            });
            let line = match tokio::time::timeout(self.within, reading).await {
                Ok(Ok(Ok(line))) => line,
                Ok(Ok(Err(e))) => {
                    let _ = child.kill();
                    let _ = child.wait();
                    return Err(CrashError::Server(format!("reading its address: {e}")));
                }
                Ok(Err(e)) => {
                    let _ = child.kill();
                    let _ = child.wait();
                    return Err(CrashError::Server(format!("reading its address: {e}")));
                }
                Err(_) => {
                    let _ = child.kill();
                    let _ = child.wait();
                    return Err(CrashError::Server(format!(
                        "did not listen within {} s (log: {})",
                        self.within.as_secs(),
                        log.display()
                    )));
                }
            };
            match line.trim().strip_prefix("listening on http://") {
                Some(a) => Ok(ServerChild {
                    child,
                    addr: a.to_string(),
                    start_time: started.elapsed(),
                }),
                None => {
                    let _ = child.kill();
                    let status = child.wait()?;
                    Err(CrashError::Server(format!(
                        "exited ({status}) without listening; last log line: {}",
                        last_line(log)
                    )))
                }
            }
        }

        /// [`Recipe::start`] on a port the server had before, trying again
        /// for a while when the port is still taken (a client's reconnect
        /// may briefly hold it).
        pub async fn restart(&self, addr: &str, log: &Path) -> Result<ServerChild, CrashError> {
            let mut tries = 0;
            loop {
                match self.start(addr, log).await {
                    Err(CrashError::Server(e)) if e.contains("cannot listen") && tries < 40 => {
                        tries += 1;
                        tokio::time::sleep(Duration::from_millis(250)).await;
                    }
                    other => return other,
                }
            }
        }
    }

    impl ServerChild {
        /// SIGKILL, and waits for it to be gone.
        pub fn kill(&mut self) -> std::io::Result<()> {
            self.child.kill()?;
            self.child.wait()?;
            Ok(())
        }

        /// The process id (for the report).
        pub fn pid(&self) -> u32 {
            self.child.id()
        }
    }

    impl Drop for ServerChild {
        fn drop(&mut self) {
            let _ = self.child.kill();
            let _ = self.child.wait();
        }
    }

    fn last_line(log: &Path) -> String {
        std::fs::read_to_string(log)
            .ok()
            .and_then(|t| t.lines().last().map(str::to_string))
            .unwrap_or_default()
    }
}

mod ledger {
    //! What the clients saw, per match and per server incarnation (the
    //! first server is incarnation 0, the one started after kill k is k):
    //! the shots acknowledged by `shot-played` on connections to each
    //! incarnation, and after each restart the stored shot count of the
    //! first `match-state`, which seats came back and when, and any
    //! refusal. From it come each kill's figures: shots acknowledged before
    //! the kill, shots lost, matches not back in time.

    use std::sync::Mutex;
    use std::time::Instant;

    /// One match in one incarnation.
    #[derive(Clone, Debug, Default)]
    struct Seen {
        /// The most shots any `shot-played` announced (its number + 1).
        acked: u32,
        /// The fewest shots a `match-state` showed: the stored count as
        /// the incarnation started (shots only add up).
        stored: Option<u32>,
        /// Seats (bit 0 first, bit 1 second) that got a `match-state`.
        seats: u8,
        /// When the second seat got its `match-state`.
        back_at: Option<Instant>,
        /// Error codes answered to a hello.
        refusals: Vec<String>,
    }

    #[derive(Debug)]
    struct Entry {
        id: String,
        seen: Vec<Seen>,
    }

    /// The record of every match.
    pub struct Ledger {
        matches: Vec<Mutex<Entry>>,
    }

    /// One match whose record lost acknowledged shots.
    #[derive(Clone, Debug, PartialEq)]
    pub struct Loss {
        pub id: String,
        pub acked: u32,
        pub stored: u32,
    }

    /// One match that did not come back in time.
    #[derive(Clone, Debug, PartialEq)]
    pub struct Missing {
        pub id: String,
        /// Seats back (0, 1 or 2).
        pub seats: u32,
        pub refusals: Vec<String>,
    }

    /// What one kill did, as far as the WebSocket clients saw.
    #[derive(Clone, Debug, Default)]
    pub struct Figures {
        /// Shots acknowledged before the kill, over all matches.
        pub acked: u64,
        /// Shots stored beyond those acknowledged (in flight at the kill).
        pub unacked_stored: u64,
        pub lost: Vec<Loss>,
        pub missing: Vec<Missing>,
        /// When the last match came back (all of them back), if all did.
        pub all_back: Option<Instant>,
    }

    impl Ledger {
        /// Matches `ids`, for `incarnations` servers.
        pub fn new(ids: &[String], incarnations: usize) -> Ledger {
            Ledger {
                matches: ids
                    .iter()
                    .map(|id| {
                        Mutex::new(Entry {
                            id: id.clone(),
                            seen: vec![Seen::default(); incarnations],
                        })
                    })
                    .collect(),
            }
        }

        fn with<R>(&self, m: usize, inc: usize, f: impl FnOnce(&mut Seen) -> R) -> Option<R> {
            let mut e = self.matches.get(m)?.lock().ok()?;
            e.seen.get_mut(inc).map(f)
        }

        /// A `shot-played` for shot `number` arrived from incarnation `inc`.
        pub fn acked(&self, m: usize, inc: usize, number: u32) {
            self.with(m, inc, |s| s.acked = s.acked.max(number.saturating_add(1)));
        }

        /// Seat `seat` (0, 1) got a `match-state` showing `shots` from `inc`.
        pub fn state(&self, m: usize, inc: usize, seat: u8, shots: u32) {
            self.with(m, inc, |s| {
                s.stored = Some(s.stored.map_or(shots, |k| k.min(shots)));
                s.seats |= 1 << seat;
                if s.seats == 3 && s.back_at.is_none() {
                    s.back_at = Some(Instant::now());
                }
            });
        }

        /// A hello to `inc` was answered with error `code`.
        pub fn refused(&self, m: usize, inc: usize, code: &str) {
            self.with(m, inc, |s| {
                if s.refusals.len() < 8 {
                    s.refusals.push(code.to_string());
                }
            });
        }

        /// Matches with both seats back in incarnation `inc`.
        pub fn back(&self, inc: usize) -> usize {
            (0..self.matches.len())
                .filter(|&m| self.with(m, inc, |s| s.seats == 3).unwrap_or(false))
                .count()
        }

        /// Shots acknowledged so far, over all matches and incarnations.
        pub fn acked_total(&self) -> u64 {
            (0..self.matches.len())
                .map(|m| u64::from(self.acked_of(m)))
                .sum()
        }

        /// Shots of match `m` acknowledged so far.
        pub fn acked_of(&self, m: usize) -> u32 {
            self.matches
                .get(m)
                .and_then(|e| e.lock().ok())
                .map(|e| e.seen.iter().map(|s| s.acked).max().unwrap_or(0))
                .unwrap_or(0)
        }

        /// The figures of kill `k` (the incarnation it started), counting
        /// a match as back only if both seats were back by `deadline`.
        pub fn figures(&self, k: usize, deadline: Instant) -> Figures {
            let mut f = Figures::default();
            let mut last: Option<Instant> = None;
            let mut all = true;
            for e in &self.matches {
                let Ok(e) = e.lock() else { continue };
                let before = e.seen.iter().take(k).map(|s| s.acked).max().unwrap_or(0);
                f.acked += u64::from(before);
                let Some(now) = e.seen.get(k) else { continue };
                if let Some(stored) = now.stored {
                    if stored < before {
                        f.lost.push(Loss {
                            id: e.id.clone(),
                            acked: before,
                            stored,
                        });
                    }
                    f.unacked_stored += u64::from(stored.saturating_sub(before));
                }
                match now.back_at {
                    Some(t) if t <= deadline => last = Some(last.map_or(t, |l| l.max(t))),
                    _ => {
                        all = false;
                        f.missing.push(Missing {
                            id: e.id.clone(),
                            seats: now.seats.count_ones(),
                            refusals: now.refusals.clone(),
                        });
                    }
                }
            }
            f.all_back = if all { last } else { None };
            f
        }
    }
}

mod player {
    //! One seat of one match, played over WebSocket for the whole run: it
    //! says hello with its seat token, shoots a random own piece gently
    //! (0.2–0.7 m/s, random direction) after a short think whenever its
    //! turn comes, tells the ledger what it saw, and when the connection
    //! drops (the server was killed) reconnects with backoff and goes on.

    use super::ledger::Ledger;
    use futures_util::{SinkExt, StreamExt};
    use game::noise::SplitMix64;
    use game::protocol::{ClientMessage, ServerMessage, PROTOCOL_VERSION};
    use game::token::SeatToken;
    use game::{MatchView, Next, Phase, PieceId, Side};
    use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
    use std::sync::Arc;
    use std::time::Duration;
    use tokio::net::TcpStream;
    use tokio::sync::watch;
    use tokio::time::Instant;
    use tokio_tungstenite::tungstenite::Message;

    type Ws = tokio_tungstenite::WebSocketStream<tokio_tungstenite::MaybeTlsStream<TcpStream>>;

    /// A connection with no message for this long while the match is on
    /// is given up and opened again (the opponent thinks 0.3 s at most).
    const SILENCE: Duration = Duration::from_secs(20);

    /// What every player shares.
    pub struct Shared {
        pub addr: String,
        pub ledger: Arc<Ledger>,
        /// The server incarnation (kills so far); read before each connect.
        pub incarnation: AtomicUsize,
        pub think: Duration,
        /// Counters for the report.
        pub connects: AtomicU64,
        pub failed_connects: AtomicU64,
        pub play_errors: AtomicU64,
        pub stalls: AtomicU64,
        pub finished: AtomicU64,
    }

    impl Shared {
        pub fn new(addr: String, ledger: Arc<Ledger>, think: Duration) -> Shared {
            Shared {
                addr,
                ledger,
                incarnation: AtomicUsize::new(0),
                think,
                connects: AtomicU64::new(0),
                failed_connects: AtomicU64::new(0),
                play_errors: AtomicU64::new(0),
                stalls: AtomicU64::new(0),
                finished: AtomicU64::new(0),
            }
        }
    }

    /// Which seat this player holds.
    pub struct SeatOf {
        /// The match's index in the ledger.
        pub index: usize,
        pub match_id: String,
        /// 0: the creator's seat, 1: the joiner's.
        pub seat: u8,
        pub token: String,
    }

    /// How a connection ended.
    enum End {
        /// The run is over.
        Stop,
        /// The connection dropped or went silent: reconnect soon.
        Dropped,
        /// The hello was refused: reconnect after the backoff.
        Refused,
    }

    /// Plays seat `me` until `stop` turns true.
    pub async fn run(shared: Arc<Shared>, me: SeatOf, seed: u64, mut stop: watch::Receiver<bool>) {
        let mut rng = SplitMix64::new(seed);
        let mut backoff = Duration::from_millis(50);
        let mut finished = false;
        loop {
            if *stop.borrow() {
                return;
            }
            let inc = shared.incarnation.load(Ordering::SeqCst);
            let ws = tokio::select! {
                ws = connect(&shared.addr, &me) => ws,
                _ = stop.changed() => return,
            };
            let end = match ws {
                Some(ws) => {
                    shared.connects.fetch_add(1, Ordering::Relaxed);
                    play(ws, &shared, &me, inc, &mut rng, &mut stop, &mut finished).await
                }
                None => {
                    shared.failed_connects.fetch_add(1, Ordering::Relaxed);
                    End::Refused
                }
            };
            let pause = match end {
                End::Stop => return,
                End::Dropped => {
                    // Not all 2,000 at once.
                    backoff = Duration::from_millis(50);
                    Duration::from_millis(rng.next_u64() % 100)
                }
                End::Refused => {
                    let p = backoff.mul_f64(0.5 + rng.next_f64());
                    backoff = (backoff * 2).min(Duration::from_secs(1));
                    p
                }
            };
            tokio::select! {
                _ = tokio::time::sleep(pause) => {}
                _ = stop.changed() => return,
            }
        }
    }

    /// Opens the match's WebSocket and says hello with the seat token.
    async fn connect(addr: &str, me: &SeatOf) -> Option<Ws> {
        let url = format!("ws://{addr}/ws?match={}", me.match_id);
        let open = tokio_tungstenite::connect_async_with_config(url, None, true);
        let mut ws = tokio::time::timeout(Duration::from_secs(10), open)
            .await
            .ok()?
            .ok()?
            .0;
        let hello = ClientMessage::Hello {
            protocol: PROTOCOL_VERSION,
            name: "crash".into(),
            token: Some(SeatToken::new(me.token.clone())),
            key: None,
        };
        ws.send(Message::Text(hello.to_json())).await.ok()?;
        Some(ws)
    }

    /// The match as this player follows it.
    struct Follow {
        /// A `match-state` arrived on this connection.
        seated: bool,
        side: Side,
        own: Vec<PieceId>,
        my_turn: bool,
        /// A pie decision is this player's to make.
        my_decision: bool,
        over: bool,
        /// A shot was sent and its outcome not seen yet.
        pending: bool,
    }

    impl Follow {
        fn update(&mut self, seat: u8, view: &MatchView) {
            let seat = if seat == 0 {
                game::Seat::First
            } else {
                game::Seat::Second
            };
            self.side = seat.side(view.swapped);
            self.own = view.board.of(self.side).map(|p| p.id).collect();
            self.my_turn = view.phase == Phase::Shooting && view.turn == self.side;
            self.my_decision = view.phase == Phase::PieDecision && self.side == Side::Black;
            self.over = matches!(view.phase, Phase::Over { .. });
        }
    }

    /// One connection: reads, records, shoots; returns how it ended.
    async fn play(
        mut ws: Ws,
        shared: &Shared,
        me: &SeatOf,
        inc: usize,
        rng: &mut SplitMix64,
        stop: &mut watch::Receiver<bool>,
        finished: &mut bool,
    ) -> End {
        let ledger = &shared.ledger;
        let mut f = Follow {
            seated: false,
            side: Side::White,
            own: Vec::new(),
            my_turn: false,
            my_decision: false,
            over: false,
            pending: false,
        };
        let mut shoot_at: Option<Instant> = None;
        let mut last_heard = Instant::now();
        loop {
            if f.seated && !f.pending && shoot_at.is_none() && (f.my_turn || f.my_decision) {
                let think = shared.think.mul_f64(0.5 + rng.next_f64());
                shoot_at = Some(Instant::now() + think);
            }
            let quiet_until = last_heard + SILENCE;
            tokio::select! {
                _ = stop.changed() => {
                    let _ = ws.close(None).await;
                    return End::Stop;
                }
                _ = sleep_until(shoot_at) => {
                    shoot_at = None;
                    let m = if f.my_decision {
                        f.my_decision = false;
                        ClientMessage::PieDecision { swap: false }
                    } else {
                        let k = (rng.next_u64() % f.own.len().max(1) as u64) as usize;
                        let Some(piece) = f.own.get(k).copied() else {
                            f.my_turn = false;
                            continue;
                        };
                        let a = rng.next_f64() * std::f64::consts::TAU;
                        let speed = 0.2 + 0.5 * rng.next_f64();
                        ClientMessage::Shot {
                            piece,
                            velocity: glam::DVec2::new(a.cos(), a.sin()) * speed,
                        }
                    };
                    if ws.send(Message::Text(m.to_json())).await.is_err() {
                        return End::Dropped;
                    }
                    f.pending = true;
                    f.my_turn = false;
                }
                _ = tokio::time::sleep_until(quiet_until), if !f.over => {
                    shared.stalls.fetch_add(1, Ordering::Relaxed);
                    let _ = ws.close(None).await;
                    return if f.seated { End::Dropped } else { End::Refused };
                }
                frame = ws.next() => {
                    let text = match frame {
                        Some(Ok(Message::Text(t))) => t,
                        Some(Ok(Message::Close(_))) | None | Some(Err(_)) => {
                            return if f.seated { End::Dropped } else { End::Refused };
                        }
                        Some(Ok(_)) => continue,
                    };
                    last_heard = Instant::now();
                    let Ok(msg) = ServerMessage::from_json(&text) else {
                        continue;
                    };
                    match msg {
                        ServerMessage::MatchState { view, .. } => {
                            ledger.state(me.index, inc, me.seat, view.shots);
                            f.seated = true;
                            f.pending = false;
                            shoot_at = None;
                            f.update(me.seat, &view);
                        }
                        ServerMessage::ShotPlayed { outcome, view, .. } => {
                            ledger.acked(me.index, inc, outcome.number);
                            if outcome.shooter == f.side {
                                f.pending = false;
                            }
                            f.update(me.seat, &view);
                            if let Next::MatchOver { .. } = outcome.next {
                                f.over = true;
                            }
                        }
                        ServerMessage::PieDecided { .. } => {
                            // The turn and sides come with the next state;
                            // ask for it by reconnecting (the default rules
                            // have no pie rule, so this is rare).
                            let _ = ws.close(None).await;
                            return End::Dropped;
                        }
                        ServerMessage::MatchOver { .. } => f.over = true,
                        ServerMessage::Error { code, .. } => {
                            if !f.seated {
                                ledger.refused(me.index, inc, code.as_str());
                                let _ = ws.close(None).await;
                                return End::Refused;
                            }
                            // A shot refused: what this player believed is
                            // off; a fresh state puts it right.
                            shared.play_errors.fetch_add(1, Ordering::Relaxed);
                            let _ = ws.close(None).await;
                            return End::Dropped;
                        }
                        _ => {}
                    }
                    if f.over && !*finished {
                        *finished = true;
                        if me.seat == 0 {
                            shared.finished.fetch_add(1, Ordering::Relaxed);
                        }
                    }
                }
            }
        }
    }

    /// Sleeps until `at`, or for ever when there is nothing to wait for.
    async fn sleep_until(at: Option<Instant>) {
        match at {
            Some(t) => tokio::time::sleep_until(t).await,
            None => std::future::pending().await,
        }
    }
}

mod verdict {
    //! The report: one row per kill (matches, shots acknowledged before it,
    //! shots lost, matches not back, restart and resume times, the HTTP
    //! cross-check), evidence for any failure, and the verdict line.

    use super::ledger::{Figures, Loss, Missing};
    use std::time::Duration;

    /// One kill and restart.
    pub struct Round {
        pub kill: usize,
        pub matches: usize,
        pub figures: Figures,
        /// Shots acknowledged per second in the second before the kill.
        pub rate_at_kill: f64,
        /// The store's database file and write-ahead log at the kill, bytes.
        pub store_bytes: (u64, u64),
        /// From SIGKILL to the new server's address line.
        pub restart: Duration,
        /// From SIGKILL to the last match back (None: not all came back).
        pub resume_all: Option<Duration>,
        /// Matches whose stored summary (HTTP) had fewer shots than were
        /// acknowledged just before asking.
        pub http_behind: Vec<Loss>,
        /// Summaries that could not be read.
        pub http_failed: Vec<String>,
    }

    impl Round {
        pub fn lost(&self) -> u64 {
            self.figures
                .lost
                .iter()
                .map(|l| u64::from(l.acked - l.stored))
                .sum()
        }

        pub fn passed(&self) -> bool {
            self.figures.lost.is_empty()
                && self.figures.missing.is_empty()
                && self.http_behind.is_empty()
                && self.http_failed.is_empty()
        }
    }

    fn mib(bytes: u64) -> f64 {
        bytes as f64 / (1024.0 * 1024.0)
    }

    fn secs(d: Option<Duration>) -> String {
        d.map_or("-".into(), |d| format!("{:.2}", d.as_secs_f64()))
    }

    /// Prints the table and the evidence; returns the verdict line.
    pub fn report(rounds: &[Round]) -> (bool, String) {
        println!();
        println!(
            "{:>4} {:>7} {:>10} {:>9} {:>6} {:>11} {:>11} {:>10} {:>9} {:>9} {:>10} {:>12}",
            "kill",
            "matches",
            "acked",
            "shots/s",
            "lost",
            "not resumed",
            "http behind",
            "in flight",
            "db MiB",
            "log MiB",
            "restart s",
            "resume all s"
        );
        for r in rounds {
            println!(
                "{:>4} {:>7} {:>10} {:>9.0} {:>6} {:>11} {:>11} {:>10} {:>9.1} {:>9.1} {:>10} {:>12}",
                r.kill,
                r.matches,
                r.figures.acked,
                r.rate_at_kill,
                r.lost(),
                r.figures.missing.len(),
                r.http_behind.len() + r.http_failed.len(),
                r.figures.unacked_stored,
                mib(r.store_bytes.0),
                mib(r.store_bytes.1),
                secs(Some(r.restart)),
                secs(r.resume_all),
            );
        }
        println!(
            "(acked: shots acknowledged by a shot-played before the kill; shots/s: acknowledged \
             in the last second before it; in flight: shots stored but not yet acknowledged \
             when it came; db, log: the store's database file and write-ahead log at the kill; \
             restart: SIGKILL to listening; resume all: SIGKILL to the last match with both \
             seats back)"
        );
        for r in rounds {
            evidence(r);
        }
        let lost: u64 = rounds.iter().map(Round::lost).sum();
        let missing: usize = rounds.iter().map(|r| r.figures.missing.len()).sum();
        let behind: usize = rounds
            .iter()
            .map(|r| r.http_behind.len() + r.http_failed.len())
            .sum();
        let pass = rounds.iter().all(Round::passed);
        let line = if pass {
            "VERDICT: PASS (0 acknowledged shots lost, 0 matches not resumed)".to_string()
        } else {
            format!(
                "VERDICT: FAIL ({lost} acknowledged shots lost, {missing} matches not resumed, \
                 {behind} stored summaries behind or unreadable)"
            )
        };
        (pass, line)
    }

    fn evidence(r: &Round) {
        let show = 10;
        for Loss { id, acked, stored } in r.figures.lost.iter().take(show) {
            println!(
                "  kill {}: match {id}: {acked} shots acknowledged, {stored} in the resumed state",
                r.kill
            );
        }
        for Missing {
            id,
            seats,
            refusals,
        } in r.figures.missing.iter().take(show)
        {
            println!(
                "  kill {}: match {id} not back in time: {seats} of 2 seats, refusals {refusals:?}",
                r.kill
            );
        }
        for Loss { id, acked, stored } in r.http_behind.iter().take(show) {
            println!(
                "  kill {}: match {id}: {acked} shots acknowledged, {stored} in GET /api/matches/{id}",
                r.kill
            );
        }
        for e in r.http_failed.iter().take(show) {
            println!("  kill {}: summary unreadable: {e}", r.kill);
        }
    }
}

use child::{Recipe, ServerChild};
use futures_util::StreamExt;
use ledger::Ledger;
use player::{SeatOf, Shared};
use verdict::Round;

/// Creates a match and joins it: (id, creator's token, joiner's token).
async fn two_seats(addr: &str) -> Result<(String, String, String), CrashError> {
    let field = |v: &serde_json::Value, k: &str| {
        v[k].as_str()
            .map(str::to_string)
            .ok_or_else(|| CrashError::Http(format!("no {k} in {v}")))
    };
    let (status, body) =
        loopback::request(addr, "POST", "/api/matches", &[], r#"{"name":"crash"}"#).await?;
    if status != 201 {
        return Err(CrashError::Http(format!("create: {status} {body}")));
    }
    let created: serde_json::Value = serde_json::from_str(&body)?;
    let id = field(&created, "match_id")?;
    let path = format!("/api/matches/{id}/join");
    let (status, body) = loopback::request(addr, "POST", &path, &[], r#"{"name":"crash"}"#).await?;
    if status != 200 {
        return Err(CrashError::Http(format!("join {id}: {status} {body}")));
    }
    let joined: serde_json::Value = serde_json::from_str(&body)?;
    Ok((id, field(&created, "token")?, field(&joined, "token")?))
}

/// Reads every match's stored summary (a few at a time) and compares its
/// shots with those acknowledged just before asking: behind ones, and
/// summaries that could not be read.
async fn cross_check(
    addr: &str,
    ids: &[String],
    ledger: &Ledger,
) -> (Vec<ledger::Loss>, Vec<String>) {
    let checks = futures_util::stream::iter(ids.iter().enumerate())
        .map(|(m, id)| async move {
            let acked = ledger.acked_of(m);
            let answer =
                loopback::request(addr, "GET", &format!("/api/matches/{id}"), &[], "").await;
            let summary = match answer {
                Ok((200, body)) => serde_json::from_str::<server::store::Summary>(&body)
                    .map_err(|e| format!("{id}: {e}")),
                Ok((status, body)) => Err(format!("{id}: {status} {body}")),
                Err(e) => Err(format!("{id}: {e}")),
            };
            summary.map(|s| (id.clone(), acked, s.shots))
        })
        .buffer_unordered(8)
        .collect::<Vec<_>>()
        .await;
    let (mut behind, mut failed) = (Vec::new(), Vec::new());
    for c in checks {
        match c {
            Ok((id, acked, stored)) if stored < acked => {
                behind.push(ledger::Loss { id, acked, stored })
            }
            Ok(_) => {}
            Err(e) => failed.push(e),
        }
    }
    (behind, failed)
}

/// Waits until `want` matches are back in incarnation `inc`, or `deadline`.
async fn wait_back(ledger: &Ledger, inc: usize, want: usize, deadline: Instant) -> usize {
    loop {
        let back = ledger.back(inc);
        if back >= want || Instant::now() >= deadline {
            return back;
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
}

/// The data folder: the one given (which must hold no store yet), or a
/// fresh temporary one (true: made here).
fn data_folder(given: Option<&PathBuf>) -> Result<(PathBuf, bool), CrashError> {
    if let Some(dir) = given {
        if dir.join("chapaev.sqlite3").exists() {
            return Err(CrashError::Setup(format!(
                "{} already holds a store; give an empty folder",
                dir.display()
            )));
        }
        std::fs::create_dir_all(dir)?;
        return Ok((dir.clone(), false));
    }
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_nanos())
        .unwrap_or_default();
    let dir =
        std::env::temp_dir().join(format!("chapaev-crashtest-{}-{nanos}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    Ok((dir, true))
}

/// Runs the whole test; returns whether it passed.
async fn run(args: Args, data_dir: PathBuf) -> Result<bool, CrashError> {
    let bin = match &args.server_bin {
        Some(b) => b.clone(),
        None => std::env::current_exe()?.with_file_name("server"),
    };
    let recipe = Recipe {
        bin,
        data_dir: data_dir.clone(),
        extra: args.server_args.clone(),
        within: Duration::from_secs(args.start_seconds),
    };
    let kills = usize::try_from(args.kills).unwrap_or(1);
    let log = |n: usize| data_dir.join(format!("server-{n}.log"));
    let mut server: ServerChild = recipe.start("127.0.0.1:0", &log(0)).await?;
    let addr = server.addr.clone();
    println!(
        "server {} listening on {addr} (pid {}, started in {:.2} s); data in {}",
        recipe.bin.display(),
        server.pid(),
        server.start_time.as_secs_f64(),
        data_dir.display()
    );

    let matches = usize::try_from(args.matches).unwrap_or(1);
    let t = Instant::now();
    let made = futures_util::stream::iter(0..matches)
        .map(|_| two_seats(&addr))
        .buffered(8)
        .collect::<Vec<_>>()
        .await;
    let seats = made.into_iter().collect::<Result<Vec<_>, _>>()?;
    let ids: Vec<String> = seats.iter().map(|s| s.0.clone()).collect();
    println!(
        "{matches} matches created and joined in {:.2} s",
        t.elapsed().as_secs_f64()
    );

    let ledger = Arc::new(Ledger::new(&ids, kills + 1));
    let shared = Arc::new(Shared::new(
        addr.clone(),
        ledger.clone(),
        Duration::from_millis(args.think_ms),
    ));
    let (stop_tx, stop_rx) = tokio::sync::watch::channel(false);
    let mut players = Vec::new();
    let t = Instant::now();
    for (m, (id, first, second)) in seats.into_iter().enumerate() {
        for (seat, token) in [(0u8, first), (1u8, second)] {
            let me = SeatOf {
                index: m,
                match_id: id.clone(),
                seat,
                token,
            };
            let seed = args
                .seed
                .wrapping_mul(0x9E37_79B9_7F4A_7C15)
                .wrapping_add(2 * m as u64 + u64::from(seat) + 1);
            players.push(tokio::spawn(player::run(
                shared.clone(),
                me,
                seed,
                stop_rx.clone(),
            )));
        }
    }
    let connected = wait_back(
        &ledger,
        0,
        matches,
        Instant::now() + Duration::from_secs(120),
    )
    .await;
    if connected < matches {
        let _ = stop_tx.send(true);
        return Err(CrashError::Setup(format!(
            "only {connected} of {matches} matches had both players connected within 120 s"
        )));
    }
    println!(
        "{} players connected in {:.2} s; playing {} s between kills, think {} ms",
        2 * matches,
        t.elapsed().as_secs_f64(),
        args.play_seconds,
        args.think_ms
    );

    let mut rounds = Vec::new();
    let resume_within = Duration::from_secs(args.resume_seconds);
    for k in 1..=kills {
        let play_until = Instant::now() + Duration::from_secs(args.play_seconds);
        let mut last_second = (Instant::now(), ledger.acked_total());
        let mut rate = 0.0;
        while Instant::now() < play_until {
            tokio::time::sleep(Duration::from_millis(250).min(play_until - Instant::now())).await;
            if last_second.0.elapsed() >= Duration::from_secs(1) {
                let now = (Instant::now(), ledger.acked_total());
                rate = (now.1 - last_second.1) as f64 / (now.0 - last_second.0).as_secs_f64();
                last_second = now;
            }
        }
        shared.incarnation.store(k, Ordering::SeqCst);
        let killed_at = Instant::now();
        server.kill()?;
        let size = |name: &str| {
            std::fs::metadata(data_dir.join(name))
                .map(|m| m.len())
                .unwrap_or(0)
        };
        let store_bytes = (size("chapaev.sqlite3"), size("chapaev.sqlite3-wal"));
        println!(
            "kill {k}: SIGKILL at {:.0} shots/s acknowledged, {} acknowledged so far; \
             store {:.1} MiB + log {:.1} MiB",
            rate,
            ledger.acked_total(),
            store_bytes.0 as f64 / 1048576.0,
            store_bytes.1 as f64 / 1048576.0
        );
        server = recipe.restart(&addr, &log(k)).await?;
        let restart = killed_at.elapsed();
        if server.addr != addr {
            return Err(CrashError::Server(format!(
                "restarted on {} instead of {addr}",
                server.addr
            )));
        }
        let listening = Instant::now();
        let back = wait_back(&ledger, k, matches, listening + resume_within).await;
        let figures = ledger.figures(k, listening + resume_within);
        let resume_all = figures.all_back.map(|t| t - killed_at);
        println!(
            "kill {k}: listening again after {:.2} s; {back} of {matches} matches back{}",
            restart.as_secs_f64(),
            resume_all.map_or(String::new(), |d| format!(
                " after {:.2} s",
                d.as_secs_f64()
            ))
        );
        let (http_behind, http_failed) = cross_check(&addr, &ids, &ledger).await;
        rounds.push(Round {
            kill: k,
            matches,
            figures,
            rate_at_kill: rate,
            store_bytes,
            restart,
            resume_all,
            http_behind,
            http_failed,
        });
    }

    let _ = stop_tx.send(true);
    for p in players {
        let _ = tokio::time::timeout(Duration::from_secs(10), p).await;
    }
    server.kill()?;
    println!(
        "clients: {} connections opened, {} attempts failed, {} silent connections reopened, \
         {} shots refused; {} of {matches} matches finished; {} shots acknowledged in all",
        shared.connects.load(Ordering::Relaxed),
        shared.failed_connects.load(Ordering::Relaxed),
        shared.stalls.load(Ordering::Relaxed),
        shared.play_errors.load(Ordering::Relaxed),
        shared.finished.load(Ordering::Relaxed),
        ledger.acked_total()
    );
    let (pass, line) = verdict::report(&rounds);
    println!("{line}");
    Ok(pass)
}

/// Waits for Ctrl-C or SIGTERM (never returns where neither can be caught).
async fn interrupted() -> &'static str {
    let ctrl_c = async {
        if tokio::signal::ctrl_c().await.is_err() {
            std::future::pending::<()>().await;
        }
    };
    #[cfg(unix)]
    {
        use tokio::signal::unix::{signal, SignalKind};
        if let Ok(mut term) = signal(SignalKind::terminate()) {
            return tokio::select! {
                _ = ctrl_c => "interrupted",
                _ = term.recv() => "terminated",
            };
        }
    }
    ctrl_c.await;
    "interrupted"
}

/// Builds the runtime and runs; the data folder made here is removed
/// after a pass (unless `--keep`) and kept for a look after a failure.
fn main() -> ExitCode {
    let args = Args::parse();
    let rt = match tokio::runtime::Builder::new_multi_thread()
        .worker_threads(usize::from(args.threads))
        .enable_all()
        .build()
    {
        Ok(rt) => rt,
        Err(e) => {
            eprintln!("crashtest: {e}");
            return ExitCode::FAILURE;
        }
    };
    let (data_dir, made) = match data_folder(args.data_dir.as_ref()) {
        Ok(d) => d,
        Err(e) => {
            eprintln!("crashtest: {e}");
            return ExitCode::FAILURE;
        }
    };
    let keep = args.keep;
    // An interruption drops the run, and with it the server child (killed).
    let outcome = rt.block_on(async {
        tokio::select! {
            outcome = run(args, data_dir.clone()) => outcome,
            why = interrupted() => Err(CrashError::Interrupted(why)),
        }
    });
    // Players still running are dropped with the runtime.
    rt.shutdown_timeout(Duration::from_secs(5));
    match outcome {
        Ok(true) => {
            if made && !keep {
                let _ = std::fs::remove_dir_all(&data_dir);
            }
            ExitCode::SUCCESS
        }
        Ok(false) => {
            println!("data and server logs kept in {}", data_dir.display());
            ExitCode::FAILURE
        }
        Err(e) => {
            eprintln!(
                "crashtest: {e} (data and server logs in {})",
                data_dir.display()
            );
            ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_kill_counts_lost_shots_and_matches_not_back() {
        let ids: Vec<String> = ["a", "b", "c"].iter().map(|s| s.to_string()).collect();
        let l = Ledger::new(&ids, 2);
        // Before the kill: a acknowledged 5, b 3, c 4.
        for n in 0..5 {
            l.acked(0, 0, n);
        }
        l.acked(1, 0, 2);
        l.acked(2, 0, 3);
        // After it: a stored 6 (one in flight), b only 2 (one lost), c only
        // one seat back.
        l.state(0, 1, 0, 6);
        l.state(0, 1, 1, 7);
        l.state(1, 1, 1, 2);
        l.state(1, 1, 0, 3);
        l.state(2, 1, 0, 4);
        l.refused(2, 1, "bad-token");
        let f = l.figures(1, Instant::now());
        assert_eq!(f.acked, 12);
        assert_eq!(f.unacked_stored, 1);
        assert_eq!(
            f.lost,
            vec![ledger::Loss {
                id: "b".into(),
                acked: 3,
                stored: 2
            }]
        );
        assert_eq!(f.missing.len(), 1);
        assert_eq!(f.missing[0].id, "c");
        assert_eq!(f.missing[0].seats, 1);
        assert_eq!(f.missing[0].refusals, vec!["bad-token".to_string()]);
        assert!(f.all_back.is_none());
        assert_eq!(l.back(1), 2);
        assert_eq!(l.acked_total(), 12);
    }

    #[test]
    fn a_match_back_after_the_deadline_is_not_resumed() {
        let ids = vec!["a".to_string()];
        let l = Ledger::new(&ids, 2);
        let deadline = Instant::now();
        std::thread::sleep(Duration::from_millis(5));
        l.state(0, 1, 0, 0);
        l.state(0, 1, 1, 0);
        assert_eq!(l.figures(1, deadline).missing.len(), 1);
        assert!(l.figures(1, Instant::now()).all_back.is_some());
    }
}
