//! The account event stream, `GET /api/stream`: the WebSocket an account's
//! client keeps open to be online (see `game::stream` for its messages),
//! and the driver of the [`Lobby`] behind it. The driver feeds the lobby
//! what happens (streams opening and closing, their messages, matches
//! ending, the clock) and carries out what it says: messages to streams,
//! and matches started through the hub, whose seat tokens go to their
//! players in `match-start`.
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
use crate::play::room::{FinishedMatch, MatchListener};
use crate::refusal::Refusal;
use crate::store::Status;
use crate::web::auth::from_browser;
use crate::web::ratelimit::TokenBucket;
use crate::web::ws::{
    admit, http_refusal, timely, too_large, FLOOD_CLOSE_AFTER, HELLO_WITHIN, PING_EVERY, SILENT_FOR,
};
use actix_web::{web, HttpRequest, HttpResponse};
use actix_ws::{AggregatedMessage, CloseCode, CloseReason, Session};
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
        let timer = streams.clone();
        tokio::spawn(async move { timer.run_timer().await });
        streams
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
            if Arc::strong_count(&self.inner) <= 2 {
                // Only this task and the hub's listener hold it.
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
        let new_seat = |p: &Player| match p {
            Player::Account(name) => NewSeat {
                name: Some(name.clone()),
                token: None,
                bot: None,
                account: Some(name.clone()),
            },
            Player::Computer(level) => NewSeat::computer(*level, computer_account(*level), rated),
        };
        let made = self
            .inner
            .hub
            .create_between(
                [new_seat(&seats[0]), new_seat(&seats[1])],
                rules.config(),
                turn_seconds,
                rated,
            )
            .await;
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
            Player::Account(a) => a.clone(),
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

async fn say(session: &mut Session, wt: Duration, msg: &StreamServerMessage) -> bool {
    timely(wt, session.text(msg.to_json())).await
}

/// Refuses with `r`, then closes; `true` if a write got stuck.
async fn refuse(session: &mut Session, wt: Duration, r: &Refusal) -> bool {
    if !say(session, wt, &StreamServerMessage::refused(r)).await {
        return true;
    }
    let reason = CloseReason {
        code: CloseCode::Policy,
        description: Some(r.code.as_str().into()),
    };
    !timely(wt, session.clone().close(Some(reason))).await
}

/// Waits for the hello and checks its key; the account, or the refusal.
async fn hello(
    hub: &Hub,
    browser: bool,
    messages: &mut actix_ws::AggregatedMessageStream,
) -> Result<crate::store::Profile, Option<Refusal>> {
    let no_hello = || {
        Some(Refusal::new(
            ErrorCode::NoHello,
            format!(
                "a stream opens with {{\"type\":\"hello\",\"protocol\":{PROTOCOL_VERSION},\"key\":ACCOUNT_KEY}} within 10 s"
            ),
        ))
    };
    let deadline = tokio::time::Instant::now() + HELLO_WITHIN;
    let text = loop {
        match tokio::time::timeout_at(deadline, messages.recv()).await {
            Err(_) => return Err(no_hello()),
            Ok(None | Some(Ok(AggregatedMessage::Close(_)))) => return Err(None),
            Ok(Some(Ok(AggregatedMessage::Text(text)))) => break text,
            Ok(Some(Ok(AggregatedMessage::Ping(_) | AggregatedMessage::Pong(_)))) => {}
            Ok(Some(Ok(AggregatedMessage::Binary(_)))) => return Err(no_hello()),
            Ok(Some(Err(e))) if too_large(&e) => {
                return Err(Some(Refusal::new(
                    ErrorCode::MessageTooLarge,
                    "the hello is too large",
                )))
            }
            Ok(Some(Err(_))) => return Err(None),
        }
    };
    let key = match StreamClientMessage::from_json(&text) {
        Ok(StreamClientMessage::Hello { protocol, key }) if protocol == PROTOCOL_VERSION => key,
        Ok(StreamClientMessage::Hello { .. }) => {
            return Err(Some(Refusal::new(
                ErrorCode::UnsupportedProtocol,
                format!("this server speaks protocol {PROTOCOL_VERSION}"),
            )))
        }
        Ok(_) => return Err(no_hello()),
        Err(e) => return Err(Some(Refusal::new(e.code, e.message))),
    };
    crate::web::auth::account_of_key(hub, key, browser)
        .await
        .map_err(Some)
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
    mut session: Session,
    messages: actix_ws::MessageStream,
) -> bool {
    let limits = hub.limits().clone();
    let wt = limits.write_timeout;
    let mut messages = messages
        .max_frame_size(limits.max_message_bytes)
        .aggregate_continuations()
        .max_continuation_size(limits.max_message_bytes);
    let account = match hello(hub, browser, &mut messages).await {
        Ok(a) => a,
        Err(Some(r)) => {
            hub.metrics().refused();
            return refuse(&mut session, wt, &r).await;
        }
        Err(None) => return false,
    };
    let matches = current_matches(hub, &account.name).await;
    let member = Member {
        name: account.name.clone(),
        bot: account.bot,
        rating: account.rating as f64,
    };
    // Open to events first, so none is missed; the welcome still goes
    // first (straight to the socket, ahead of the queue), and a challenge
    // made meanwhile may then be told twice, never not at all.
    let (id, mut rx) = streams.open(member);
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
    if !say(&mut session, wt, &welcome).await {
        streams.close(id);
        return true;
    }
    info!(account = %account.name, stream = id.0, "event stream open");
    let mut bucket = TokenBucket::new(limits.rate_per_sec, limits.rate_burst, Instant::now());
    let mut ping = tokio::time::interval(PING_EVERY);
    let mut last_heard = Instant::now();
    let mut last_said = Instant::now();
    let mut stuck = false;
    let reason = loop {
        tokio::select! {
            out = rx.recv() => match out {
                Some(msg) => {
                    last_said = Instant::now();
                    if !say(&mut session, wt, &msg).await {
                        stuck = true;
                        break None;
                    }
                }
                None => break Some(CloseReason {
                    code: CloseCode::Policy,
                    description: Some("the stream was not read".into()),
                }),
            },
            frame = messages.recv() => {
                last_heard = Instant::now();
                let text = match frame {
                    None | Some(Ok(AggregatedMessage::Close(_))) => break None,
                    Some(Ok(AggregatedMessage::Ping(b))) => {
                        if !timely(wt, session.pong(&b)).await {
                            stuck = true;
                            break None;
                        }
                        continue;
                    }
                    Some(Ok(AggregatedMessage::Pong(_))) => continue,
                    Some(Ok(AggregatedMessage::Text(text))) => Some(text),
                    Some(Ok(AggregatedMessage::Binary(_))) => None,
                    Some(Err(e)) if too_large(&e) => {
                        let r = Refusal::new(
                            ErrorCode::MessageTooLarge,
                            format!("messages are at most {} bytes", limits.max_message_bytes),
                        );
                        stuck = refuse(&mut session, wt, &r).await;
                        break None;
                    }
                    Some(Err(_)) => break Some(CloseReason { code: CloseCode::Protocol, description: None }),
                };
                if !bucket.take(Instant::now()) {
                    hub.metrics().refused();
                    if bucket.dropped_in_a_row >= FLOOD_CLOSE_AFTER {
                        break Some(CloseReason {
                            code: CloseCode::Policy,
                            description: Some("rate-limited".into()),
                        });
                    }
                    if bucket.dropped_in_a_row == 1 {
                        let r = Refusal::new(ErrorCode::RateLimited, "too many messages; slow down");
                        if !say(&mut session, wt, &StreamServerMessage::refused(&r)).await {
                            stuck = true;
                            break None;
                        }
                    }
                    continue;
                }
                let parsed = match text {
                    None => Err(Refusal::new(ErrorCode::BadMessage, "messages are JSON text frames")),
                    Some(text) => match StreamClientMessage::from_json(&text) {
                        Ok(msg) => resolved(hub, msg).await,
                        Err(e) => Err(Refusal::new(e.code, e.message)),
                    },
                };
                match parsed {
                    Ok(msg) => streams.feed(Input::Message { stream: id, msg }),
                    Err(r) => {
                        hub.metrics().refused();
                        if !say(&mut session, wt, &StreamServerMessage::refused(&r)).await {
                            stuck = true;
                            break None;
                        }
                    }
                }
            }
            _ = ping.tick() => {
                if last_heard.elapsed() > SILENT_FOR {
                    break Some(CloseReason {
                        code: CloseCode::Away,
                        description: Some("no answer to pings".into()),
                    });
                }
                if !timely(wt, session.ping(b"")).await {
                    stuck = true;
                    break None;
                }
                if last_said.elapsed() >= KEEP_ALIVE {
                    last_said = Instant::now();
                    if !say(&mut session, wt, &StreamServerMessage::KeepAlive).await {
                        stuck = true;
                        break None;
                    }
                }
            }
        }
    };
    streams.close(id);
    info!(account = %account.name, stream = id.0, "event stream closed");
    if stuck {
        return true;
    }
    !timely(wt, session.close(reason)).await
}
