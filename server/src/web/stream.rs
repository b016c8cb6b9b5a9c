//! The account event stream, `GET /api/stream`: the WebSocket an account's
//! client keeps open to be online (see `game::stream` for its messages),
//! and the driver of the [`Lobby`] behind it. The driver feeds the lobby
//! what happens (streams opening and closing, their messages, matches
//! ending, the clock) and carries out what it says: messages to streams,
//! and matches started through the hub, whose seat tokens go to their
//! players in `match-start`.
//!
//! The driver also keeps the lobby's list of hosted bots (the bot
//! accounts with an active module) fresh from the store, with who of them
//! is mid-match there (read once before the lobby's first round, so that
//! a match resumed after a restart is known), and starts a
//! hosted bot's match with its active module, compiled before the match
//! starts (a module that no longer loads starts no match).
//!
//! A stream opens with `{"type":"hello","protocol":1,"key":KEY}` within
//! 10 s; the answer is `welcome` with the full picture (the account's
//! matches not over, its open challenges), then events as they come, and
//! `keep-alive` after 30 s of quiet. Each stream has a bounded queue: a
//! client that stops reading is dropped, never buffered without end.

use crate::accounts::AccountError;
use crate::play::hub::{Hub, NewSeat};
use game::lobby::{LobbyLimits, Member, Pairing, StreamId};

/// The lobby with the server's computer levels on its ladder.
type Lobby = game::lobby::Lobby<bots::Level>;
type Effect = game::lobby::Effect<bots::Level>;
type Input = game::lobby::Input<bots::Level>;
type Player = game::lobby::Player<bots::Level>;

/// The hosted bots (bot accounts with an active module) and who of them is
/// mid-match (a seat of an unfinished match: on any node of a cluster, or
/// from before a restart), from the store, for the lobby.
fn read_hosted(store: &dyn crate::store::Store) -> Result<Input, crate::store::StoreError> {
    let bots = store
        .hosted_bots(MAX_HOSTED_BOTS)?
        .into_iter()
        .map(|p| Member {
            name: p.name,
            bot: true,
            rating: p.rating as f64,
        })
        .collect();
    let busy = store.hosted_seats(MAX_HOSTED_BOTS)?;
    Ok(Input::Hosted { bots, busy })
}

/// How often the hosted bots are read from the store: every ladder round,
/// at most [`HOSTED_REFRESH`] apart.
fn limits_refresh(streams: &Streams) -> Duration {
    locked(&streams.inner.lobby)
        .ladder_every()
        .min(HOSTED_REFRESH)
}
use crate::play::room::{FinishedMatch, MatchListener};
use crate::refusal::Refusal;
use crate::store::Status;
use crate::web::auth::from_browser;
use crate::web::pump;
use crate::web::ws::{admit, http_refusal};
use actix_web::{web, HttpRequest, HttpResponse};
use actix_ws::{CloseCode, CloseReason, Session};
use bytestring::ByteString;
use game::name::computer_account;
use game::protocol::{ErrorCode, PROTOCOL_VERSION};
use game::session::Moment;
use game::stream::{CurrentMatch, StreamClientMessage, StreamServerMessage};
use game::Seat;
use std::collections::{HashMap, HashSet};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};
use tokio::sync::{mpsc, Notify};
use tracing::{debug, info, warn};

/// Messages queued for one stream before it counts as not reading.
pub const STREAM_QUEUE: usize = 64;
/// Quiet time after which a stream gets a `keep-alive`.
pub const KEEP_ALIVE: Duration = Duration::from_secs(30);
/// The most time between two readings of the hosted bots from the store.
pub const HOSTED_REFRESH: Duration = Duration::from_secs(5);
/// Most hosted bots the lobby knows of.
pub const MAX_HOSTED_BOTS: usize = 10_000;

/// The lobby and every open stream (cheap to clone).
#[derive(Clone)]
pub struct Streams {
    inner: Arc<Inner>,
}

struct Inner {
    hub: Hub,
    lobby: Mutex<Lobby>,
    epoch: Instant,
    /// Each open stream's queue, with its account's name (lower case).
    streams: Mutex<HashMap<StreamId, (String, mpsc::Sender<StreamServerMessage>)>>,
    /// The matches the lobby started that have not ended.
    started: Mutex<HashSet<String>>,
    next: AtomicU64,
    /// Wakes the lobby's timer when its next deadline may have moved.
    wake: Notify,
}

fn locked<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

impl Streams {
    /// The lobby, with the computer levels on the ladder at their stored
    /// ratings, its timer running on the current runtime, and the hub
    /// telling it of matches ending.
    pub fn start(hub: Hub, limits: LobbyLimits) -> Streams {
        let computers = bots::Level::ALL
            .iter()
            .map(|&l| {
                let rating = hub
                    .store()
                    .account(&computer_account(l))
                    .ok()
                    .flatten()
                    .map_or(1500.0, |p| p.rating as f64);
                (l, rating)
            })
            .collect();
        let streams = Streams {
            inner: Arc::new(Inner {
                lobby: Mutex::new(Lobby::new(
                    limits,
                    computers,
                    Moment::ZERO,
                    crate::token::seed().unwrap_or(0x5EED),
                )),
                hub: hub.clone(),
                epoch: Instant::now(),
                streams: Mutex::new(HashMap::new()),
                started: Mutex::new(HashSet::new()),
                next: AtomicU64::new(1),
                wake: Notify::new(),
            }),
        };
        hub.set_listener(Arc::new(streams.clone()));
        // Before any pairing: which hosted bots are mid-match (matches
        // resumed after a restart, or played on other nodes).
        match read_hosted(hub.store().as_ref()) {
            Ok(input) => streams.feed(input),
            Err(e) => warn!(error = %e, "reading the hosted bots failed"),
        }
        // Both tasks hold the streams before either runs: each ends once
        // only the tasks and the hub's listener hold them, which must not
        // be the case while the other is being spawned.
        let every = limits_refresh(&streams);
        let (timer, refresher) = (streams.clone(), streams.clone());
        tokio::spawn(async move { timer.run_timer().await });
        tokio::spawn(async move { refresher.refresh_hosted(every).await });
        streams
    }

    /// Reads the hosted bots from the store every `every`, for as long as
    /// anyone holds the streams, and tells the lobby.
    async fn refresh_hosted(self, every: Duration) {
        loop {
            let store = self.inner.hub.store().clone();
            match tokio::task::spawn_blocking(move || read_hosted(store.as_ref())).await {
                Ok(Ok(input)) => self.feed(input),
                Ok(Err(e)) => warn!(error = %e, "reading the hosted bots failed"),
                Err(e) => warn!(error = %e, "the task reading the hosted bots failed"),
            }
            tokio::time::sleep(every).await;
            if Arc::strong_count(&self.inner) <= 3 {
                // Only this task, the timer and the hub's listener hold it.
                return;
            }
        }
    }

    fn now(&self) -> Moment {
        Moment::new(self.inner.epoch.elapsed())
    }

    /// Feeds the lobby the clock, at each of its deadlines, for as long as
    /// anyone holds the streams.
    async fn run_timer(self) {
        loop {
            let next = locked(&self.inner.lobby).next_deadline();
            let at = self.inner.epoch + next.since_epoch();
            tokio::select! {
                _ = tokio::time::sleep_until(at.into()) => self.feed(Input::Tick),
                _ = self.inner.wake.notified() => {}
            }
            if Arc::strong_count(&self.inner) <= 3 {
                // Only this task, the hosted bots' refresher and the hub's
                // listener hold it.
                return;
            }
        }
    }

    fn feed(&self, input: Input) {
        let effects = locked(&self.inner.lobby).handle(input, self.now());
        self.inner.wake.notify_one();
        for e in effects {
            self.carry(e);
        }
    }

    /// Queues `msg` on `stream`; a stream whose queue is full is not
    /// reading, and is dropped (its session then closes).
    fn send(&self, stream: StreamId, msg: StreamServerMessage) {
        let mut streams = locked(&self.inner.streams);
        let full = match streams.get(&stream) {
            Some((_, tx)) => tx.try_send(msg).is_err(),
            None => false,
        };
        if full {
            debug!(stream = stream.0, "a stream that does not read is dropped");
            streams.remove(&stream);
        }
    }

    fn tell(&self, account: &str, msg: StreamServerMessage) {
        let k = account.to_ascii_lowercase();
        let ids: Vec<StreamId> = locked(&self.inner.streams)
            .iter()
            .filter(|(_, (a, _))| *a == k)
            .map(|(id, _)| *id)
            .collect();
        for id in ids {
            self.send(id, msg.clone());
        }
    }

    fn carry(&self, effect: Effect) {
        match effect {
            Effect::Send(stream, msg) => self.send(stream, msg),
            Effect::Tell(account, msg) => self.tell(&account, msg),
            Effect::Start {
                seats,
                rated,
                rules,
                turn_seconds,
                why,
            } => {
                let this = self.clone();
                tokio::spawn(async move {
                    this.start_match(seats, rated, rules, turn_seconds, why)
                        .await
                });
            }
        }
    }

    async fn start_match(
        &self,
        seats: [Player; 2],
        rated: bool,
        rules: game::Preset,
        turn_seconds: Option<u64>,
        why: Pairing,
    ) {
        // A hosted bot's active module, compiled now and held until its
        // room holds it.
        let mut modules = Vec::new();
        let mut new_seats = Vec::new();
        let mut refused = None;
        for p in &seats {
            new_seats.push(match p {
                Player::Account(name) => NewSeat {
                    name: Some(name.clone()),
                    token: None,
                    bot: None,
                    account: Some(name.clone()),
                    module: None,
                },
                Player::Computer(level) => {
                    NewSeat::computer(*level, computer_account(*level), rated)
                }
                Player::Hosted(name) => match self.hosted_module(name).await {
                    Ok(module) => {
                        let hash = module.hash_hex();
                        modules.push(module);
                        NewSeat::hosted(name.clone(), hash)
                    }
                    Err(r) => {
                        warn!(account = %name, message = %r.message, "a hosted bot's module does not start a match");
                        refused = Some(r);
                        break;
                    }
                },
            });
        }
        if let Some(r) = refused {
            for p in &seats {
                if let Player::Account(a) = p {
                    self.tell(a, StreamServerMessage::refused(&r));
                }
            }
            self.feed(Input::StartFailed { seats });
            return;
        }
        let [first, second]: [NewSeat; 2] = match new_seats.try_into() {
            Ok(pair) => pair,
            Err(_) => return,
        };
        let made = self
            .inner
            .hub
            .create_between(
                [first, second],
                rules.config(),
                turn_seconds,
                rated,
                why == Pairing::Ladder,
            )
            .await;
        drop(modules);
        let (id, tokens) = match made {
            Ok(made) => made,
            Err(r) => {
                warn!(code = %r.code, message = %r.message, ?why, "the lobby could not start a match");
                for p in &seats {
                    if let Player::Account(a) = p {
                        self.tell(a, StreamServerMessage::refused(&r));
                    }
                }
                self.feed(Input::StartFailed { seats });
                return;
            }
        };
        info!(match_id = %id, ?why, rated, "the lobby started a match");
        locked(&self.inner.started).insert(id.clone());
        let name = |p: &Player| match p {
            Player::Account(a) | Player::Hosted(a) => a.clone(),
            Player::Computer(l) => computer_account(*l),
        };
        for (i, token) in tokens.into_iter().enumerate() {
            let (Player::Account(account), Some(token)) = (&seats[i], token) else {
                continue;
            };
            self.tell(
                account,
                StreamServerMessage::MatchStart {
                    match_id: id.clone(),
                    seat: if i == 0 { Seat::First } else { Seat::Second },
                    token,
                    ws: format!("/ws?match={id}"),
                    opponent: name(&seats[1 - i]),
                    rated,
                },
            );
        }
    }

    /// `account`'s active module, compiled.
    async fn hosted_module(&self, account: &str) -> Result<Arc<hosted::BotModule>, Refusal> {
        let pool = self.inner.hub.hosted().clone();
        let store = self.inner.hub.store().clone();
        let name = account.to_string();
        let loaded = tokio::task::spawn_blocking(move || pool.active(store.as_ref(), &name))
            .await
            .map_err(|_| Refusal::internal())?;
        match loaded {
            Ok(Some(module)) => Ok(module),
            Ok(None) => Err(Refusal::new(
                ErrorCode::NoSuchAccount,
                format!("{account} has no active module"),
            )),
            Err(e) => {
                warn!(account, error = %e, "a hosted bot's module does not load");
                Err(Refusal::internal())
            }
        }
    }

    /// Opens a stream for `member`; its id and queue.
    fn open(&self, member: Member) -> (StreamId, mpsc::Receiver<StreamServerMessage>) {
        let id = StreamId(self.inner.next.fetch_add(1, Ordering::Relaxed));
        let (tx, rx) = mpsc::channel(STREAM_QUEUE);
        locked(&self.inner.streams).insert(id, (member.name.to_ascii_lowercase(), tx));
        self.feed(Input::Online { stream: id, member });
        (id, rx)
    }

    fn close(&self, id: StreamId) {
        locked(&self.inner.streams).remove(&id);
        self.feed(Input::Offline { stream: id });
    }
}

impl MatchListener for Streams {
    fn finished(&self, m: FinishedMatch) {
        let this = self.clone();
        tokio::spawn(async move {
            let store = this.inner.hub.store().clone();
            let accounts: Vec<String> = m.accounts.iter().flatten().cloned().collect();
            let names = accounts.clone();
            let ratings = tokio::task::spawn_blocking(move || {
                names
                    .iter()
                    .filter_map(|a| store.account(a).ok().flatten())
                    .map(|p| (p.name, p.rating))
                    .collect::<Vec<_>>()
            })
            .await
            .unwrap_or_default();
            for a in &accounts {
                let rating = ratings
                    .iter()
                    .find(|(n, _)| n.eq_ignore_ascii_case(a))
                    .map(|(_, r)| *r);
                this.tell(
                    a,
                    StreamServerMessage::MatchFinish {
                        match_id: m.match_id.clone(),
                        result: m.result,
                        rating: rating.filter(|_| m.rated),
                    },
                );
            }
            if locked(&this.inner.started).remove(&m.match_id) {
                let ratings = ratings.into_iter().map(|(n, r)| (n, r as f64)).collect();
                this.feed(Input::Finished { ratings });
            }
        });
    }
}

/// `GET /api/stream`: upgrades to an account's event stream.
pub async fn handler(
    req: HttpRequest,
    body: web::Payload,
    hub: web::Data<Hub>,
    streams: web::Data<Streams>,
) -> Result<HttpResponse, actix_web::Error> {
    let admitted = match admit(&req, &hub) {
        Ok(a) => a,
        Err(r) => return Ok(http_refusal(&r)),
    };
    let browser = from_browser(&req);
    let (response, session, messages) = actix_ws::handle(&req, body)?;
    let hub = hub.get_ref().clone();
    let streams = streams.get_ref().clone();
    actix_web::rt::spawn(async move {
        let stuck = run(&hub, &streams, browser, session, messages).await;
        admitted.release(&hub, stuck).await;
    });
    Ok(response)
}

/// The account's matches not over yet, for its welcome.
async fn current_matches(hub: &Hub, account: &str) -> Vec<CurrentMatch> {
    let store = hub.store().clone();
    let name = account.to_string();
    let listed = tokio::task::spawn_blocking(move || store.matches_of(&name, 100)).await;
    let Ok(Ok(list)) = listed else {
        return Vec::new();
    };
    list.into_iter()
        .filter(|m| m.status != Status::Finished)
        .map(|m| {
            let first = m
                .first
                .as_deref()
                .is_some_and(|f| f.eq_ignore_ascii_case(account));
            CurrentMatch {
                seat: if first { Seat::First } else { Seat::Second },
                opponent: if first { m.second } else { m.first },
                rated: m.rated,
                match_id: m.match_id,
            }
        })
        .collect()
}

/// Checks a challenge's addressee is an account, and names it as
/// registered; other messages pass as they are.
async fn resolved(hub: &Hub, msg: StreamClientMessage) -> Result<StreamClientMessage, Refusal> {
    let StreamClientMessage::Challenge {
        to,
        rated,
        rules,
        turn_seconds,
        color,
    } = msg
    else {
        return Ok(msg);
    };
    let store = hub.store().clone();
    let wanted = to.clone();
    let found = crate::web::blocking::run_account(move || -> Result<_, AccountError> {
        Ok(store.account(&wanted)?)
    })
    .await?;
    let account =
        found.ok_or_else(|| Refusal::new(ErrorCode::NoSuchAccount, format!("no account {to}")))?;
    Ok(StreamClientMessage::Challenge {
        to: account.name,
        rated,
        rules,
        turn_seconds,
        color,
    })
}

/// Runs one stream; `true` when it ended on a write that could not finish
/// in time.
async fn run(
    hub: &Hub,
    streams: &Streams,
    browser: bool,
    session: Session,
    messages: actix_ws::MessageStream,
) -> bool {
    let door = StreamDoor {
        hub: hub.clone(),
        streams: streams.clone(),
        browser,
    };
    pump::serve(door, hub.limits(), hub.metrics(), session, messages).await
}

/// How a stream opens: a `hello` with an account key, answered `welcome`
/// with the full picture; the stream is then online in the lobby.
struct StreamDoor {
    hub: Hub,
    streams: Streams,
    browser: bool,
}

impl pump::Door for StreamDoor {
    type Message = StreamClientMessage;
    type Endpoint = StreamEndpoint;
    type Outbox = mpsc::Receiver<StreamServerMessage>;

    async fn open(
        self,
        hello: StreamClientMessage,
        writer: &mut pump::Writer,
    ) -> Result<(StreamEndpoint, Self::Outbox), pump::Error> {
        let key = match hello {
            StreamClientMessage::Hello { protocol, key } if protocol == PROTOCOL_VERSION => key,
            StreamClientMessage::Hello { .. } => {
                return Err(Refusal::new(
                    ErrorCode::UnsupportedProtocol,
                    format!("this server speaks protocol {PROTOCOL_VERSION}"),
                )
                .into())
            }
            _ => return Err(self.no_hello("the first message was not a hello").into()),
        };
        let account = crate::web::auth::account_of_key(&self.hub, key, self.browser).await?;
        let (hub, streams) = (self.hub, self.streams);
        let matches = current_matches(&hub, &account.name).await;
        let member = Member {
            name: account.name.clone(),
            bot: account.bot,
            rating: account.rating as f64,
        };
        // Open to events first, so none is missed; the welcome still goes
        // first (straight to the socket, ahead of the queue), and a challenge
        // made meanwhile may then be told twice, never not at all.
        let (id, rx) = streams.open(member);
        let challenges = locked(&streams.inner.lobby).challenges_of(&account.name, streams.now());
        let welcome = StreamServerMessage::Welcome {
            protocol: PROTOCOL_VERSION,
            account: account.name.clone(),
            bot: account.bot,
            rating: account.rating,
            provisional: account.provisional,
            matches,
            challenges,
        };
        if let Err(gone) = writer.say(welcome.to_json()).await {
            streams.close(id);
            return Err(gone);
        }
        info!(account = %account.name, stream = id.0, "event stream open");
        let endpoint = StreamEndpoint {
            hub,
            streams,
            id,
            account: account.name,
        };
        Ok((endpoint, rx))
    }

    fn no_hello(&self, _why: &str) -> Refusal {
        Refusal::new(
            ErrorCode::NoHello,
            format!(
                "a stream opens with {{\"type\":\"hello\",\"protocol\":{PROTOCOL_VERSION},\"key\":ACCOUNT_KEY}} within 10 s"
            ),
        )
    }
}

/// What the lobby tells this stream, as it comes.
impl pump::Outbox for mpsc::Receiver<StreamServerMessage> {
    async fn next(&mut self) -> Option<ByteString> {
        self.recv().await.map(|msg| msg.to_json().into())
    }
}

/// An open stream: its messages go to the lobby; a quiet one is sent
/// `keep-alive`.
struct StreamEndpoint {
    hub: Hub,
    streams: Streams,
    id: StreamId,
    /// The account's name, as registered.
    account: String,
}

impl pump::Endpoint for StreamEndpoint {
    type Message = StreamClientMessage;

    const OVERSIZE_CLOSE: CloseCode = CloseCode::Policy;
    const SLOW_DOWN: &'static str = "too many messages; slow down";

    async fn on_message(&mut self, msg: StreamClientMessage) -> Result<(), pump::Error> {
        let msg = resolved(&self.hub, msg).await?;
        self.streams.feed(Input::Message {
            stream: self.id,
            msg,
        });
        Ok(())
    }

    fn on_quiet(&mut self, quiet: Duration) -> Option<ByteString> {
        (quiet >= KEEP_ALIVE).then(|| StreamServerMessage::KeepAlive.to_json().into())
    }

    fn outbox_closed(&self) -> CloseReason {
        CloseReason {
            code: CloseCode::Policy,
            description: Some("the stream was not read".into()),
        }
    }

    async fn on_close(&mut self) {
        self.streams.close(self.id);
        info!(account = %self.account, stream = self.id.0, "event stream closed");
    }
}
