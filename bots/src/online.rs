//! A bot account online: the process keeps its account's event stream
//! (`/api/stream`, messages in `game::stream`) open, joins the ladder if
//! asked, accepts the challenges made to it (up to a number of matches at
//! once; past that it declines, saying it is busy), and plays every match
//! it is given — each on its own match WebSocket with a fresh bot, all at
//! once, through the [`Runner`]. A dropped stream is reopened with
//! exponential backoff, and the matches the welcome lists that this process
//! is not playing (left by a restart) are taken back with the account's
//! key. [`Online::run`] returns after a number of matches, or never.

use crate::bot::Bot;
use crate::runner::{Runner, RunnerError, RunnerOptions, SeatGrant};
use futures_util::{SinkExt, StreamExt};
use game::protocol::PROTOCOL_VERSION;
use game::stream::{StreamClientMessage, StreamServerMessage};
use game::token::SeatToken;
use std::collections::HashSet;
use std::sync::Arc;
use std::time::Duration;
use tokio::sync::mpsc;
use tokio_tungstenite::tungstenite::Message;

/// How an online bot behaves.
#[derive(Clone, Debug)]
pub struct OnlineOptions {
    /// Join the ladder (bot accounts): the server pairs it all day.
    pub ladder: bool,
    /// Most matches played at once; challenges past it are declined.
    pub max_matches: usize,
    /// Stop after this many matches have finished (`None`: run forever).
    pub stop_after: Option<u64>,
}

impl Default for OnlineOptions {
    fn default() -> OnlineOptions {
        OnlineOptions {
            ladder: true,
            max_matches: 4,
            stop_after: None,
        }
    }
}

/// What an online session came to.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct OnlineReport {
    /// Matches that finished.
    pub finished: u64,
    /// The account's rating after its last rated match.
    pub rating: Option<i64>,
    /// Matches whose runner failed (the match itself goes on on the
    /// server, which forfeits a seat left empty).
    pub failed: u64,
}

/// Why the stream could not be kept.
#[derive(Debug, thiserror::Error)]
pub enum OnlineError {
    #[error("the server refused the stream: {code}: {message}")]
    Refused {
        code: game::protocol::ErrorCode,
        message: String,
    },
    #[error("cannot open the event stream at {url}: {source}")]
    Connect {
        url: String,
        #[source]
        source: Box<tokio_tungstenite::tungstenite::Error>,
    },
    #[error("the event stream closed {0} times in a row without a welcome")]
    GaveUp(u32),
}

/// How long a process that played its last match waits for the stream to
/// tell that match's end (and the new rating).
const FINISH_GRACE: Duration = Duration::from_secs(5);

/// Sleeps until `at`, or for ever without it.
async fn sleep_until_some(at: Option<tokio::time::Instant>) {
    match at {
        Some(at) => tokio::time::sleep_until(at).await,
        None => std::future::pending().await,
    }
}

/// A bot account's process.
pub struct Online<F> {
    runner: Runner,
    key: String,
    make_bot: Arc<F>,
    options: OnlineOptions,
}

/// What a match task tells the stream loop: its match, and how it went.
struct Done {
    match_id: String,
    failed: Option<RunnerError>,
}

impl<F, B> Online<F>
where
    F: Fn(u64) -> B + Send + Sync + 'static,
    B: Bot + 'static,
{
    /// The account proved by `key` on `runner`'s server, playing each match
    /// with `make_bot(n)` (n: the match's number in this process, for a
    /// seed).
    pub fn new(runner: Runner, key: &str, make_bot: F, options: OnlineOptions) -> Online<F> {
        Online {
            runner,
            key: key.to_string(),
            make_bot: Arc::new(make_bot),
            options,
        }
    }

    fn stream_url(&self) -> String {
        let base = self.runner.server();
        match base.strip_prefix("https://") {
            Some(rest) => format!("wss://{rest}/api/stream"),
            None => format!("ws://{}/api/stream", base.trim_start_matches("http://")),
        }
    }

    /// Plays `grant` with a new bot on its own task; tells `done` when over.
    fn spawn_match(&self, grant: SeatGrant, n: u64, done: &mpsc::UnboundedSender<Done>) {
        let runner = self.runner.clone().with_options(RunnerOptions {
            account_key: Some(self.key.clone()),
            ..self.runner.options().clone()
        });
        let bot = (self.make_bot)(n);
        let tx = done.clone();
        tokio::spawn(async move {
            let failed = runner.play(&grant, bot).await.err();
            let _ = tx.send(Done {
                match_id: grant.match_id,
                failed,
            });
        });
    }

    /// Stays online until `stop_after` matches have finished (forever
    /// without it); reopens a dropped stream, giving up after 8 failed
    /// attempts in a row.
    pub async fn run(&self) -> Result<OnlineReport, OnlineError> {
        let mut report = OnlineReport::default();
        let (done_tx, mut done_rx) = mpsc::unbounded_channel::<Done>();
        // The matches being played by this process.
        let mut playing: HashSet<String> = HashSet::new();
        // Matches played to the end here whose `match-finish` has not come.
        let mut unannounced: HashSet<String> = HashSet::new();
        // Matches whose `match-finish` came before their runner was done.
        let mut announced: HashSet<String> = HashSet::new();
        // When to stop, once `stop_after` matches are done.
        let mut stop_by: Option<tokio::time::Instant> = None;
        let mut started = 0u64;
        let mut failures = 0u32;
        let mut wait = Duration::from_millis(200);
        loop {
            let url = self.stream_url();
            let (mut ws, _) = match tokio_tungstenite::connect_async(&url).await {
                Ok(c) => c,
                Err(e) if failures >= 8 => {
                    return Err(OnlineError::Connect {
                        url,
                        source: Box::new(e),
                    })
                }
                Err(_) => {
                    failures += 1;
                    tokio::time::sleep(wait).await;
                    wait = (wait * 2).min(Duration::from_secs(10));
                    continue;
                }
            };
            let hello = StreamClientMessage::Hello {
                protocol: PROTOCOL_VERSION,
                key: SeatToken::new(self.key.clone()),
            };
            let _ = ws.send(Message::text(hello.to_json())).await;
            let mut welcomed = false;
            let mut me = String::new();
            loop {
                tokio::select! {
                    frame = ws.next() => {
                        let text = match frame {
                            Some(Ok(Message::Text(t))) => t,
                            Some(Ok(Message::Ping(_) | Message::Pong(_) | Message::Frame(_))) => continue,
                            Some(Ok(Message::Binary(_))) => continue,
                            Some(Ok(Message::Close(_))) | None | Some(Err(_)) => break,
                        };
                        let Ok(msg) = StreamServerMessage::from_json(&text) else {
                            continue;
                        };
                        match msg {
                            StreamServerMessage::Welcome { account, matches, .. } => {
                                me = account;
                                // Matches left by an earlier run of this
                                // process (or a dropped stream): taken back
                                // with the account's key.
                                for m in matches {
                                    if playing.insert(m.match_id.clone()) {
                                        started += 1;
                                        let grant = SeatGrant {
                                            ws: format!("/ws?match={}", m.match_id),
                                            match_id: m.match_id,
                                            seat: m.seat,
                                            token: String::new(),
                                        };
                                        self.spawn_match(grant, started, &done_tx);
                                    }
                                }
                                welcomed = true;
                                failures = 0;
                                wait = Duration::from_millis(200);
                                if self.options.ladder {
                                    let join = StreamClientMessage::Ladder { join: true };
                                    let _ = ws.send(Message::text(join.to_json())).await;
                                }
                            }
                            StreamServerMessage::Error { code, message } if !welcomed => {
                                return Err(OnlineError::Refused { code, message });
                            }
                            StreamServerMessage::Challenge { challenge } => {
                                let answer = if playing.len() < self.options.max_matches {
                                    StreamClientMessage::Accept { challenge: challenge.id }
                                } else {
                                    StreamClientMessage::Decline {
                                        challenge: challenge.id,
                                        reason: Some("busy".into()),
                                    }
                                };
                                // Challenges this account made are told to it too.
                                if challenge.to.eq_ignore_ascii_case(&me) {
                                    let _ = ws.send(Message::text(answer.to_json())).await;
                                }
                            }
                            StreamServerMessage::MatchStart { match_id, seat, token, ws: path, .. } => {
                                // Already played here when the stream dropped.
                                // A match started as this process stops is not played.
                                let fresh = stop_by.is_none() && playing.insert(match_id.clone());
                                if fresh {
                                    started += 1;
                                    let grant = SeatGrant { match_id, seat, token: token.expose().to_string(), ws: path };
                                    self.spawn_match(grant, started, &done_tx);
                                }
                            }
                            StreamServerMessage::MatchFinish { match_id, rating, .. } => {
                                if rating.is_some() {
                                    report.rating = rating;
                                }
                                if !unannounced.remove(&match_id) {
                                    announced.insert(match_id);
                                }
                            }
                            _ => {}
                        }
                    }
                    Some(done) = done_rx.recv() => {
                        playing.remove(&done.match_id);
                        if !announced.remove(&done.match_id) {
                            unannounced.insert(done.match_id);
                        }
                        report.finished += 1;
                        if let Some(e) = done.failed {
                            report.failed += 1;
                            eprintln!("a match's runner failed: {e}");
                        }
                        let enough = self.options.stop_after.is_some_and(|n| report.finished >= n);
                        if enough && stop_by.is_none() {
                            // Off the ladder at once, so it pairs us no more.
                            stop_by = Some(tokio::time::Instant::now() + FINISH_GRACE);
                            let leave = StreamClientMessage::Ladder { join: false };
                            let _ = ws.send(Message::text(leave.to_json())).await;
                        }
                    }
                    _ = sleep_until_some(stop_by) => stop_by = Some(tokio::time::Instant::now()),
                }
                // Done: once the stream has told the last matches' ends
                // (with the new rating), or the grace has run out.
                if stop_by
                    .is_some_and(|at| unannounced.is_empty() || at <= tokio::time::Instant::now())
                {
                    let _ = ws.close(None).await;
                    return Ok(report);
                }
            }
            if !welcomed {
                failures += 1;
                if failures >= 8 {
                    return Err(OnlineError::GaveUp(failures));
                }
            }
            tokio::time::sleep(wait).await;
            wait = (wait * 2).min(Duration::from_secs(10));
        }
    }
}
