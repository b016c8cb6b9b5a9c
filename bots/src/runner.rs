//! The runner: a [`Bot`] playing one seat of a match on a real Chapaev
//! server, over the documented HTTP + WebSocket protocol
//! (docs/protocol.md). It creates a match ([`Runner::create`], against a
//! person or a built-in level) or joins one ([`Runner::join`]), connects
//! the seat's WebSocket and follows the match from the announcements
//! ([`crate::follow::Follower`]). Whenever the seat is asked — its side to
//! shoot, or Black's pie decision — the bot decides on the blocking pool
//! (never on the async threads), with the deadline of the seat's last
//! `clock` less a safety margin, and its answer is sent. A refusal from
//! the server is noted in the [`RunReport`] and the match goes on: the bot
//! is asked again only when the match changes (a refused turn stays the
//! bot's until its clock runs out). A dropped connection or a restarted
//! server is reconnected with exponential backoff and full jitter (the
//! server sends the full state again); outgoing messages pass a token
//! bucket well below the server's rate limit. [`Runner::play`] returns when the match is over.

use crate::bot::{Bot, Context, Decision};
use crate::follow::{Followed, Follower};
use futures_util::{SinkExt, StreamExt};
use game::noise::SplitMix64;
use game::protocol::{ClientMessage, ErrorCode, ServerMessage, PROTOCOL_VERSION};
use game::token::SeatToken;
use game::{Config, MatchRecord, MatchResult, Seat, ShotOutcome, Side};
use serde::{Deserialize, Serialize};
use std::time::{Duration, Instant};
use tokio::net::TcpStream;
use tokio::task::JoinHandle;
use tokio_tungstenite::tungstenite::{self, Message};
use tokio_tungstenite::{MaybeTlsStream, WebSocketStream};

/// Why the runner could not play its match to the end.
#[derive(Debug, thiserror::Error)]
pub enum RunnerError {
    /// The server address is not `http://HOST[:PORT]`.
    #[error("bad server address {0:?}: expected http://HOST:PORT")]
    BadServer(String),
    /// An HTTP call did not get an answer.
    #[error("{what}: {source}")]
    Http {
        what: String,
        #[source]
        source: Box<ureq::Error>,
    },
    /// An HTTP answer could not be read.
    #[error("{what}: reading the answer: {source}")]
    Read {
        what: String,
        #[source]
        source: std::io::Error,
    },
    /// An answer was not the JSON the protocol promises.
    #[error("{what}: unexpected answer: {source}")]
    BadAnswer {
        what: String,
        #[source]
        source: serde_json::Error,
    },
    /// The server refused, for good (a bad token, no such match, a full
    /// match, a bad config...).
    #[error("{what}: refused with {code}: {message}")]
    Refused {
        what: String,
        code: ErrorCode,
        message: String,
    },
    /// The WebSocket could not be (re)connected within the backoff's limits.
    #[error("gave up on {url} after {attempts} attempts over {:.1} s: {source}", elapsed.as_secs_f64())]
    GaveUp {
        url: String,
        attempts: u32,
        elapsed: Duration,
        #[source]
        source: Box<tungstenite::Error>,
    },
    /// A blocking task (the bot deciding, or an HTTP call) panicked.
    #[error("{what} panicked: {source}")]
    Panicked {
        what: &'static str,
        #[source]
        source: tokio::task::JoinError,
    },
}

/// Who takes the other seat of a created match.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Opponent {
    /// A person (or another runner) joins it by id.
    Person,
    /// A built-in bot of the server, by level name (`easy`, `medium`).
    Level(String),
}

/// What to create: the body of `POST /api/matches`.
#[derive(Clone, Debug, PartialEq)]
pub struct CreateMatch {
    /// The creator's name (the server's default: `first`).
    pub name: Option<String>,
    pub opponent: Opponent,
    /// The rules; [`Config::standard`] for bot-against-bot play.
    pub config: Config,
    /// The match's turn clock (the server's default: 60 s).
    pub turn_seconds: Option<u64>,
    /// A public seed for the match's noise (casual matches): the noise of
    /// `bots match --seed` with the same seed.
    pub seed: Option<u64>,
}

impl CreateMatch {
    /// A match for a person (or another bot) to join, with `config`.
    pub fn open(config: Config) -> CreateMatch {
        CreateMatch {
            name: None,
            opponent: Opponent::Person,
            config,
            turn_seconds: None,
            seed: None,
        }
    }

    /// A match against the server's built-in `level`, with `config`.
    pub fn against(level: &str, config: Config) -> CreateMatch {
        CreateMatch {
            opponent: Opponent::Level(level.to_string()),
            ..CreateMatch::open(config)
        }
    }

    fn body(&self) -> serde_json::Value {
        let mut body = serde_json::json!({ "config": self.config });
        if let Some(name) = &self.name {
            body["name"] = name.as_str().into();
        }
        match &self.opponent {
            Opponent::Person => body["opponent"] = "person".into(),
            Opponent::Level(level) => {
                body["opponent"] = "bot".into();
                body["bot_level"] = level.as_str().into();
            }
        }
        if let Some(t) = self.turn_seconds {
            body["turn_seconds"] = t.into();
        }
        if let Some(seed) = self.seed {
            body["seed"] = seed.into();
        }
        body
    }
}

/// A seat handed out by the server: the answer to create and join.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct SeatGrant {
    pub match_id: String,
    pub seat: Seat,
    /// The only key to the seat: keep it secret.
    pub token: String,
    /// Path and query of the seat's WebSocket.
    pub ws: String,
}

/// How the runner reconnects a dropped WebSocket: waits up to `first`,
/// the ceiling doubling up to `max`, each wait drawn uniformly below its
/// ceiling (full jitter: the bots a server restart dropped together do not
/// come back together), and gives up after `max_attempts` failed attempts
/// in a row or `max_total` without a connection that brought the match
/// state.
#[derive(Clone, Debug, PartialEq)]
pub struct Backoff {
    pub first: Duration,
    pub max: Duration,
    pub max_attempts: u32,
    pub max_total: Duration,
}

impl Backoff {
    /// The wait under `ceiling`, drawn from `rng` (full jitter).
    pub fn jittered(&self, ceiling: Duration, rng: &mut SplitMix64) -> Duration {
        ceiling.mul_f64(rng.next_f64())
    }

    /// The jitter's generator for one match in this process: seeded by the
    /// process id and the match id, so that processes and matches differ
    /// and a run is reproducible from them.
    pub fn rng_for(match_id: &str) -> SplitMix64 {
        use std::hash::{Hash, Hasher};
        // SipHash with fixed keys: the same for the same match id.
        let mut hasher = std::hash::DefaultHasher::new();
        match_id.hash(&mut hasher);
        SplitMix64::for_shot(hasher.finish(), std::process::id())
    }
}

impl Default for Backoff {
    fn default() -> Self {
        Backoff {
            first: Duration::from_millis(100),
            max: Duration::from_secs(5),
            max_attempts: 30,
            max_total: Duration::from_secs(120),
        }
    }
}

/// The runner's settings.
#[derive(Clone, Debug, PartialEq)]
pub struct RunnerOptions {
    /// The name sent in `hello`.
    pub name: String,
    pub backoff: Backoff,
    /// Messages per second the runner sends at most, sustained (the
    /// server allows 20).
    pub rate_per_sec: f64,
    /// Messages the runner may send in a burst.
    pub rate_burst: f64,
    /// How long to wait for the seat's `clock` after a change before
    /// deciding without one.
    pub clock_wait: Duration,
    /// The bot's budget when no clock came.
    pub think_without_clock: Duration,
    /// A connection silent this long is taken as dropped (the server pings
    /// every 15 s).
    pub silence: Duration,
    /// The key of the account playing, sent in `hello` for a grant without
    /// a seat token (a match taken back after the process restarted).
    pub account_key: Option<String>,
}

impl Default for RunnerOptions {
    fn default() -> Self {
        RunnerOptions {
            name: "bot".into(),
            backoff: Backoff::default(),
            rate_per_sec: 5.0,
            rate_burst: 5.0,
            clock_wait: Duration::from_millis(500),
            think_without_clock: Duration::from_secs(2),
            silence: Duration::from_secs(40),
            account_key: None,
        }
    }
}

/// The budget a bot gets from a clock with `remaining` left: a fifth is
/// kept back for the network and the server, at least 200 ms, at most 2 s.
pub fn think_budget(remaining: Duration) -> Duration {
    let margin = (remaining / 5).clamp(Duration::from_millis(200), Duration::from_secs(2));
    remaining.saturating_sub(margin)
}

/// A refusal the server sent.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ServerError {
    pub code: ErrorCode,
    pub message: String,
}

/// How a runner's match went.
#[derive(Clone, Debug)]
pub struct RunReport {
    pub match_id: String,
    /// The seat played.
    pub seat: Seat,
    /// The colour the seat played at the end (after any pie swap).
    pub side: Option<Side>,
    /// The result (`None` only if the match's end was never seen).
    pub result: Option<MatchResult>,
    /// The record, seed included, as `match-over` or the record endpoint
    /// gave it.
    pub record: Option<MatchRecord>,
    /// Shots played in the match.
    pub shots: u32,
    /// Shots this seat played.
    pub my_shots: u32,
    /// Decisions sent (shots, pie decisions, resignations).
    pub sent: u32,
    /// Refusals the server sent, in order.
    pub errors: Vec<ServerError>,
    /// Connections after the first.
    pub reconnects: u32,
    /// Server messages that could not be read.
    pub unreadable: Vec<String>,
}

impl RunReport {
    /// Points for this seat: 1 won, ½ drawn, 0 lost (`None`: no result).
    pub fn score(&self) -> Option<f64> {
        let result = self.result?;
        Some(match (result.winner(), self.side) {
            (None, _) => 0.5,
            (Some(w), Some(me)) if w == me => 1.0,
            _ => 0.0,
        })
    }
}

/// A client of one server.
#[derive(Clone, Debug)]
pub struct Runner {
    base: String,
    options: RunnerOptions,
}

type Ws = WebSocketStream<MaybeTlsStream<TcpStream>>;

impl Runner {
    /// A runner for the server at `server` (`http://HOST:PORT`).
    pub fn new(server: &str) -> Result<Runner, RunnerError> {
        let base = server.trim_end_matches('/');
        let rest = base
            .strip_prefix("http://")
            .or_else(|| base.strip_prefix("https://"))
            .ok_or_else(|| RunnerError::BadServer(server.to_string()))?;
        if rest.is_empty() || rest.contains(['?', '#', ' ']) {
            return Err(RunnerError::BadServer(server.to_string()));
        }
        Ok(Runner {
            base: base.to_string(),
            options: RunnerOptions::default(),
        })
    }

    /// The same runner with `options`.
    pub fn with_options(mut self, options: RunnerOptions) -> Runner {
        self.options = options;
        self
    }

    pub fn options(&self) -> &RunnerOptions {
        &self.options
    }

    /// The server's base address.
    pub fn server(&self) -> &str {
        &self.base
    }

    /// Creates a match and takes its first seat.
    pub async fn create(&self, req: &CreateMatch) -> Result<SeatGrant, RunnerError> {
        let body = req.body().to_string();
        let text = self.http("POST", "/api/matches".into(), Some(body)).await?;
        parse("creating a match", &text)
    }

    /// Takes the second seat of `match_id`.
    pub async fn join(&self, match_id: &str, name: Option<&str>) -> Result<SeatGrant, RunnerError> {
        let body = match name {
            Some(n) => serde_json::json!({ "name": n }),
            None => serde_json::json!({}),
        };
        let path = format!("/api/matches/{match_id}/join");
        let text = self.http("POST", path, Some(body.to_string())).await?;
        parse(&format!("joining {match_id}"), &text)
    }

    /// The record of a finished match.
    pub async fn record(&self, match_id: &str) -> Result<MatchRecord, RunnerError> {
        let text = self
            .http("GET", format!("/api/matches/{match_id}/record"), None)
            .await?;
        parse(&format!("the record of {match_id}"), &text)
    }

    async fn http(
        &self,
        method: &'static str,
        path: String,
        body: Option<String>,
    ) -> Result<String, RunnerError> {
        let url = format!("{}{path}", self.base);
        let what = format!("{method} {url}");
        let call = {
            let url = url.clone();
            move || {
                let agent = ureq::AgentBuilder::new()
                    .timeout(Duration::from_secs(15))
                    .build();
                let req = agent
                    .request(method, &url)
                    .set("Content-Type", "application/json");
                let answer = match body {
                    Some(b) => req.send_string(&b),
                    None => req.call(),
                };
                match answer {
                    Ok(r) => Ok((r.status(), r.into_string())),
                    Err(ureq::Error::Status(status, r)) => Ok((status, r.into_string())),
                    Err(e) => Err(Box::new(e)),
                }
            }
        };
        let (status, text) = tokio::task::spawn_blocking(call)
            .await
            .map_err(|source| RunnerError::Panicked {
                what: "an HTTP call",
                source,
            })?
            .map_err(|source| RunnerError::Http {
                what: what.clone(),
                source,
            })?;
        let text = text.map_err(|source| RunnerError::Read {
            what: what.clone(),
            source,
        })?;
        if status >= 400 {
            return Err(match ServerMessage::from_json(&text) {
                Ok(ServerMessage::Error { code, message }) => RunnerError::Refused {
                    what,
                    code,
                    message,
                },
                _ => RunnerError::Refused {
                    what,
                    code: ErrorCode::Internal,
                    message: format!("status {status}: {text}"),
                },
            });
        }
        Ok(text)
    }

    fn ws_url(&self, grant: &SeatGrant) -> String {
        let base = match self.base.strip_prefix("https://") {
            Some(rest) => format!("wss://{rest}"),
            None => format!("ws://{}", self.base.trim_start_matches("http://")),
        };
        format!("{base}{}", grant.ws)
    }

    /// Plays `grant`'s seat with `bot` until the match is over; the report
    /// and the bot back.
    pub async fn play<B: Bot + 'static>(
        &self,
        grant: &SeatGrant,
        bot: B,
    ) -> Result<(RunReport, B), RunnerError> {
        let url = self.ws_url(grant);
        let mut play = Play {
            bot: Some(bot),
            follower: Follower::new(grant.seat),
            decided: None,
            thinking: None,
            hooks: Vec::new(),
            bucket: TokenBucket::new(
                self.options.rate_per_sec,
                self.options.rate_burst,
                Instant::now(),
            ),
            sent: 0,
            errors: Vec::new(),
            unreadable: Vec::new(),
            options: self.options.clone(),
            token: SeatToken::new(grant.token.clone()),
        };
        let backoff = &self.options.backoff;
        let mut connections = 0u32;
        let mut attempts = 0u32;
        let mut wait = backoff.first;
        let mut jitter = Backoff::rng_for(&grant.match_id);
        let mut since = Instant::now();
        loop {
            // On the node that plays the match, if the server has several.
            let dropped = match crate::owner::connect(&url, false).await {
                Ok((mut ws, _)) => {
                    connections += 1;
                    let (end, got_state) = play.session(&mut ws).await?;
                    let _ = ws.close(None).await;
                    if got_state {
                        attempts = 0;
                        wait = backoff.first;
                        since = Instant::now();
                    }
                    match end {
                        SessionEnd::Over => break,
                        SessionEnd::Fatal(code, message) => {
                            return Err(RunnerError::Refused {
                                what: format!("playing {}", grant.match_id),
                                code,
                                message,
                            })
                        }
                        SessionEnd::Dropped(e) => e,
                    }
                }
                Err(e) => e,
            };
            attempts += 1;
            if attempts > backoff.max_attempts || since.elapsed() > backoff.max_total {
                return Err(RunnerError::GaveUp {
                    url,
                    attempts,
                    elapsed: since.elapsed(),
                    source: Box::new(dropped),
                });
            }
            tokio::time::sleep(backoff.jittered(wait, &mut jitter)).await;
            wait = (wait * 2).min(backoff.max);
        }
        // The bot may still be out deciding a move nobody asks for any more.
        if let Some((_, handle)) = play.thinking.take() {
            let (bot, _) = handle.await.map_err(|source| RunnerError::Panicked {
                what: "the bot",
                source,
            })?;
            play.bot = Some(bot);
        }
        let mut record = play.follower.record().cloned();
        if record.is_none() {
            if let Some(result) = play.follower.result() {
                // The end came while disconnected: the record from the API.
                if let Ok(r) = self.record(&grant.match_id).await {
                    play.hooks.push(Hook::Over(result, Box::new(r.clone())));
                    record = Some(r);
                }
            }
        }
        play.deliver_hooks();
        let f = &play.follower;
        let report = RunReport {
            match_id: grant.match_id.clone(),
            seat: f.seat(),
            side: f.side(),
            result: f.result(),
            record,
            shots: f.shots(),
            my_shots: f.my_shots(),
            sent: play.sent,
            errors: play.errors,
            reconnects: connections.saturating_sub(1),
            unreadable: play.unreadable,
        };
        match play.bot {
            Some(bot) => Ok((report, bot)),
            None => unreachable!("the bot is back once nothing is being decided"),
        }
    }
}

fn parse<T: for<'de> Deserialize<'de>>(what: &str, text: &str) -> Result<T, RunnerError> {
    serde_json::from_str(text).map_err(|source| RunnerError::BadAnswer {
        what: what.to_string(),
        source,
    })
}

/// A client-side token bucket: `rate` tokens a second, at most `burst`.
#[derive(Clone, Debug)]
struct TokenBucket {
    rate: f64,
    burst: f64,
    tokens: f64,
    last: Instant,
}

impl TokenBucket {
    fn new(rate: f64, burst: f64, now: Instant) -> TokenBucket {
        let rate = if rate.is_finite() && rate > 0.0 {
            rate
        } else {
            1.0
        };
        let burst = if burst.is_finite() {
            burst.max(1.0)
        } else {
            1.0
        };
        TokenBucket {
            rate,
            burst,
            tokens: burst,
            last: now,
        }
    }

    /// Takes a token at `now`; how long to wait before using it.
    fn take(&mut self, now: Instant) -> Duration {
        let elapsed = now.saturating_duration_since(self.last).as_secs_f64();
        self.last = now.max(self.last);
        self.tokens = (self.tokens + elapsed * self.rate).min(self.burst);
        self.tokens -= 1.0;
        if self.tokens >= 0.0 {
            Duration::ZERO
        } else {
            Duration::from_secs_f64(-self.tokens / self.rate)
        }
    }
}

/// A hook the bot is due, kept while it is out deciding.
enum Hook {
    Shot(Box<ShotOutcome>),
    Over(MatchResult, Box<MatchRecord>),
}

enum SessionEnd {
    Over,
    Dropped(tungstenite::Error),
    Fatal(ErrorCode, String),
}

enum Event<B> {
    Frame(Option<Result<Message, tungstenite::Error>>),
    Thought(Result<(B, Decision), tokio::task::JoinError>),
    Wake,
    Silent,
}

/// One match being played: the follower, the bot (or the task it is
/// deciding on), what is due to it.
struct Play<B> {
    bot: Option<B>,
    follower: Follower,
    /// The follower's version a decision was last taken for.
    decided: Option<u64>,
    thinking: Option<(u64, JoinHandle<(B, Decision)>)>,
    hooks: Vec<Hook>,
    bucket: TokenBucket,
    sent: u32,
    errors: Vec<ServerError>,
    unreadable: Vec<String>,
    options: RunnerOptions,
    /// The seat's token, presented in each connection's hello.
    token: SeatToken,
}

fn dropped(why: &str) -> tungstenite::Error {
    tungstenite::Error::Io(std::io::Error::new(std::io::ErrorKind::TimedOut, why))
}

async fn sleep_until(at: Option<Instant>) {
    match at {
        Some(t) => tokio::time::sleep_until(t.into()).await,
        None => std::future::pending().await,
    }
}

/// The message that sends `decision`.
pub fn message(decision: Decision) -> Option<ClientMessage> {
    Some(match decision {
        Decision::Shot(shot) => ClientMessage::Shot {
            piece: shot.piece(),
            velocity: shot.velocity(),
        },
        Decision::Pie { swap } => ClientMessage::PieDecision { swap },
        Decision::Resign => ClientMessage::Resign,
        Decision::NoAnswer => return None,
    })
}

impl<B: Bot + 'static> Play<B> {
    /// One connection, until the match is over, the connection drops or
    /// the server refuses the seat for good; also whether the match state
    /// arrived on it.
    async fn session(&mut self, ws: &mut Ws) -> Result<(SessionEnd, bool), RunnerError> {
        let mut got_state = false;
        let hello = ClientMessage::Hello {
            protocol: PROTOCOL_VERSION,
            name: self.options.name.clone(),
            // A grant without a token (a match taken back after a restart)
            // is played with the account's key.
            token: (!self.token.expose().is_empty()).then(|| self.token.clone()),
            key: self.options.account_key.clone().map(SeatToken::new),
        };
        if let Err(e) = self.send(ws, &hello).await {
            return Ok((SessionEnd::Dropped(e), false));
        }
        let mut heard = Instant::now();
        loop {
            self.maybe_decide(Instant::now());
            let wake = self.wake_at();
            let silent_at = heard + self.options.silence;
            let event = {
                let thinking = self.thinking.as_mut();
                tokio::select! {
                    frame = ws.next() => Event::Frame(frame),
                    joined = async {
                        match thinking {
                            Some((_, handle)) => handle.await,
                            None => std::future::pending().await,
                        }
                    } => Event::Thought(joined),
                    _ = sleep_until(wake) => Event::Wake,
                    _ = tokio::time::sleep_until(silent_at.into()) => Event::Silent,
                }
            };
            let end = match event {
                Event::Frame(None) | Event::Frame(Some(Ok(Message::Close(_)))) => {
                    Some(SessionEnd::Dropped(tungstenite::Error::ConnectionClosed))
                }
                Event::Frame(Some(Err(e))) => Some(SessionEnd::Dropped(e)),
                Event::Frame(Some(Ok(Message::Text(text)))) => {
                    heard = Instant::now();
                    let version = self.follower.version();
                    let end = self.on_text(&text, heard);
                    // The state is every connection's first message: any change means it came.
                    got_state |= self.follower.version() != version;
                    end
                }
                Event::Frame(Some(Ok(_))) => {
                    heard = Instant::now();
                    None
                }
                Event::Thought(joined) => {
                    let (bot, decision) = joined.map_err(|source| RunnerError::Panicked {
                        what: "the bot",
                        source,
                    })?;
                    let version = self.thinking.take().map(|(v, _)| v);
                    self.bot = Some(bot);
                    self.deliver_hooks();
                    // Sent only if nothing changed while the bot thought.
                    let msg = message(decision);
                    if let (Some(msg), true) = (
                        msg,
                        version == Some(self.follower.version()) && self.follower.ask().is_some(),
                    ) {
                        match self.send(ws, &msg).await {
                            Ok(()) => {
                                self.sent += 1;
                                None
                            }
                            Err(e) => Some(SessionEnd::Dropped(e)),
                        }
                    } else {
                        None
                    }
                }
                Event::Wake => None,
                Event::Silent => Some(SessionEnd::Dropped(dropped("the server fell silent"))),
            };
            if let Some(end) = end {
                return Ok((end, got_state));
            }
        }
    }

    /// A text frame from the server.
    fn on_text(&mut self, text: &str, now: Instant) -> Option<SessionEnd> {
        let msg = match ServerMessage::from_json(text) {
            Ok(m) => m,
            Err(e) => {
                let head: String = text.chars().take(200).collect();
                self.unreadable.push(format!("{e}: {head}"));
                return None;
            }
        };
        let end = match self.follower.apply(msg, now) {
            Followed::State => self.follower.result().map(|_| SessionEnd::Over),
            Followed::Shot(outcome) => {
                self.hooks.push(Hook::Shot(outcome));
                None
            }
            Followed::Over { result, record } => {
                self.hooks.push(Hook::Over(result, record));
                Some(SessionEnd::Over)
            }
            Followed::Refused { code, message } => {
                self.errors.push(ServerError {
                    code,
                    message: message.clone(),
                });
                matches!(
                    code,
                    ErrorCode::BadToken
                        | ErrorCode::NoSuchMatch
                        | ErrorCode::UnsupportedProtocol
                        | ErrorCode::UnsupportedPhysics
                )
                .then_some(SessionEnd::Fatal(code, message))
            }
            Followed::OutOfSync(why) => {
                self.unreadable.push(why.clone());
                Some(SessionEnd::Dropped(dropped(&why)))
            }
            Followed::Changed | Followed::Clock | Followed::Nothing => None,
        };
        self.deliver_hooks();
        end
    }

    /// The budget for a decision due now, if one is due: the seat's clock
    /// less the margin, or the budget without a clock once none came in time.
    fn due(&self, now: Instant) -> Option<Result<Instant, Instant>> {
        if self.thinking.is_some() || self.bot.is_none() || self.follower.ask().is_none() {
            return None;
        }
        if self.decided == Some(self.follower.version()) {
            return None;
        }
        Some(match self.follower.deadline() {
            Some(out) => Ok(now + think_budget(out.saturating_duration_since(now))),
            None => {
                let wait_until = self.follower.changed_at() + self.options.clock_wait;
                if now >= wait_until {
                    Ok(now + self.options.think_without_clock)
                } else {
                    Err(wait_until)
                }
            }
        })
    }

    /// When to look again for a clock that has not come.
    fn wake_at(&self) -> Option<Instant> {
        match self.due(Instant::now()) {
            Some(Err(at)) => Some(at),
            _ => None,
        }
    }

    /// Sends the bot off to decide, on the blocking pool, if it is asked.
    fn maybe_decide(&mut self, now: Instant) {
        let Some(Ok(deadline)) = self.due(now) else {
            return;
        };
        let (Some(view), Some(me)) = (self.follower.view().cloned(), self.follower.side()) else {
            return;
        };
        let Some(mut bot) = self.bot.take() else {
            return;
        };
        let version = self.follower.version();
        self.decided = Some(version);
        let handle = tokio::task::spawn_blocking(move || {
            let ctx = Context {
                view: &view,
                me,
                deadline,
            };
            let decision = bot.decide(&ctx);
            (bot, decision)
        });
        self.thinking = Some((version, handle));
    }

    /// Tells the bot, if it is here, what happened since it last heard.
    fn deliver_hooks(&mut self) {
        let Some(bot) = self.bot.as_mut() else {
            return;
        };
        for hook in self.hooks.drain(..) {
            match hook {
                Hook::Shot(outcome) => bot.on_shot(&outcome),
                Hook::Over(result, record) => bot.on_match_over(&result, &record),
            }
        }
    }

    /// Sends `msg` once the token bucket allows.
    async fn send(&mut self, ws: &mut Ws, msg: &ClientMessage) -> Result<(), tungstenite::Error> {
        let wait = self.bucket.take(Instant::now());
        if !wait.is_zero() {
            tokio::time::sleep(wait).await;
        }
        ws.send(Message::Text(msg.to_json())).await
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_token_bucket_allows_its_burst_then_its_rate() {
        let t0 = Instant::now();
        let mut b = TokenBucket::new(5.0, 5.0, t0);
        for _ in 0..5 {
            assert_eq!(b.take(t0), Duration::ZERO);
        }
        let wait = b.take(t0);
        assert!((wait.as_secs_f64() - 0.2).abs() < 1e-9, "{wait:?}");
        let wait = b.take(t0);
        assert!((wait.as_secs_f64() - 0.4).abs() < 1e-9, "{wait:?}");
        // A second later the debt is paid and three tokens are back.
        let t1 = t0 + Duration::from_secs(1);
        for _ in 0..3 {
            assert_eq!(b.take(t1), Duration::ZERO);
        }
        assert!(b.take(t1) > Duration::ZERO);
    }

    #[test]
    fn reconnection_waits_are_drawn_below_their_ceiling_and_differ_by_match() {
        let backoff = Backoff::default();
        let ceiling = Duration::from_secs(1);
        let mut rng = Backoff::rng_for("m1");
        let waits: Vec<Duration> = (0..1000)
            .map(|_| backoff.jittered(ceiling, &mut rng))
            .collect();
        assert!(waits.iter().all(|w| *w < ceiling));
        assert!(waits.iter().any(|w| *w < Duration::from_millis(100)));
        assert!(waits.iter().any(|w| *w > Duration::from_millis(900)));
        // Reproducible for a match in this process; another match differs.
        let again = backoff.jittered(ceiling, &mut Backoff::rng_for("m1"));
        assert_eq!(again, waits[0]);
        let other = backoff.jittered(ceiling, &mut Backoff::rng_for("m2"));
        assert_ne!(other, waits[0]);
    }

    #[test]
    fn the_budget_keeps_a_margin_for_the_network() {
        assert_eq!(
            think_budget(Duration::from_secs(60)),
            Duration::from_secs(58)
        );
        assert_eq!(
            think_budget(Duration::from_secs(2)),
            Duration::from_millis(1600)
        );
        assert_eq!(
            think_budget(Duration::from_millis(500)),
            Duration::from_millis(300)
        );
        assert_eq!(think_budget(Duration::from_millis(100)), Duration::ZERO);
    }

    #[test]
    fn server_addresses_are_http_urls_and_the_socket_follows_them() {
        assert!(Runner::new("127.0.0.1:8080").is_err());
        assert!(Runner::new("http://").is_err());
        let r = Runner::new("http://127.0.0.1:8080/").unwrap();
        assert_eq!(r.server(), "http://127.0.0.1:8080");
        let grant = SeatGrant {
            match_id: "m".into(),
            seat: Seat::First,
            token: "t".into(),
            ws: "/ws?match=m".into(),
        };
        assert_eq!(r.ws_url(&grant), "ws://127.0.0.1:8080/ws?match=m");
    }

    #[test]
    fn create_bodies_say_who_the_opponent_is() {
        let b = CreateMatch::against("easy", Config::standard()).body();
        assert_eq!(b["opponent"], "bot");
        assert_eq!(b["bot_level"], "easy");
        assert_eq!(b["config"]["variants"]["pie_rule"], true);
        let mut open = CreateMatch::open(Config::default());
        open.turn_seconds = Some(2);
        open.name = Some("Petka".into());
        let b = open.body();
        assert_eq!(b["opponent"], "person");
        assert_eq!(b["turn_seconds"], 2);
        assert_eq!(b["name"], "Petka");
        assert!(b.get("bot_level").is_none());
        assert!(b.get("seed").is_none());
        open.seed = Some(42);
        assert_eq!(open.body()["seed"], 42);
    }

    #[test]
    fn decisions_become_the_protocols_messages() {
        assert_eq!(
            message(Decision::Pie { swap: true }).map(|m| m.to_json()),
            Some(r#"{"type":"pie-decision","swap":true}"#.to_string())
        );
        assert_eq!(
            message(Decision::Resign).map(|m| m.to_json()),
            Some(r#"{"type":"resign"}"#.to_string())
        );
        assert!(message(Decision::NoAnswer).is_none());
    }
}
