//! A match room: the tokio task that drives one match's
//! [`game::session::Session`] (the rules of a live match, without I/O).
//! Everything that happens to a match goes through the room's command
//! queue, one command at a time, so a match never sees two moves at once.
//! The room feeds each command to the session and carries out what it
//! answers, in order: an accepted move is written to the store (and the
//! write awaited) before anything said after it is delivered, so a move is
//! durable before its outcome is broadcast; what the session says while
//! handling one command reaches each connection as one queue item; a
//! connection too slow to take it is dropped. The room also wakes the
//! session when its next deadline passes (turn clock, grace periods, the
//! built-in bot's delay, idling out), computes a built-in bot's move on a
//! blocking thread (a hosted bot's within the server's budget for them,
//! [`crate::play::hosted`]), counts the match in the metrics, and leaves
//! memory when the session closes or the server shuts down.

use crate::config::Limits;
use crate::metrics::Metrics;
use crate::play::hosted::{HostedPool, HostedSeat};
use crate::refusal::Refusal;
use crate::store::{AfterMove, Store, StoredMatch};
use bots::{Bot, Context, Decision};
use bytestring::ByteString;
use game::protocol::{ClientMessage, ErrorCode, ForfeitReason, ServerMessage};
use game::session::{
    BotDecision, ConnId, Effect, Input, Moment, Request, SeatSpec, Session, SessionLimits, Status,
    To,
};
use game::token::{SeatToken, TokenHash};
use game::{Config, Game, MatchView, RecordedMove, Replay, Seat, Side};
use std::collections::{HashMap, VecDeque};
use std::future::Future;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::Arc;
use std::time::Duration;
use tokio::sync::{mpsc, oneshot};
use tokio::time::Instant;
use tracing::{debug, error, info, warn};

/// Messages on their way to one connection, already JSON, in order. What
/// a room says while handling one command (a shot's outcome and the next
/// turn's clock, say) travels as one item: one wakeup of the connection's
/// task, one write to its socket.
pub type Outbound = Arc<[ByteString]>;

/// The receiving end of a connection's queue, one message at a time.
#[derive(Debug)]
pub struct Inbox {
    rx: mpsc::Receiver<Outbound>,
    /// The item being read and the index of its next message; let go of
    /// once read (an idle connection holds no old messages).
    batch: Option<(Outbound, usize)>,
}

impl Inbox {
    pub(crate) fn new(rx: mpsc::Receiver<Outbound>) -> Inbox {
        Inbox { rx, batch: None }
    }

    /// The next message; `None` once the room has closed this connection
    /// and everything sent before is read. Cancel-safe.
    pub async fn recv(&mut self) -> Option<ByteString> {
        loop {
            if let Some((batch, next)) = &mut self.batch {
                if let Some(m) = batch.get(*next) {
                    let m = m.clone();
                    *next += 1;
                    if *next == batch.len() {
                        self.batch = None;
                    }
                    return Some(m);
                }
                self.batch = None;
            }
            self.batch = Some((self.rx.recv().await?, 0));
        }
    }
}

/// What a room needs of the server around it: the store, the metrics, the
/// limits, connection ids, a way to start a rematch, and to be forgotten
/// when it stops. (The hub provides them; tests provide their own.)
pub trait RoomHost: Clone + Send + Sync + 'static {
    /// The store.
    fn store(&self) -> &Arc<dyn Store>;
    /// The metrics.
    fn metrics(&self) -> &Arc<Metrics>;
    /// The limits.
    fn limits(&self) -> &Limits;
    /// A connection id never handed out before.
    fn next_conn_id(&self) -> u64;
    /// Stores and starts the rematch of match `of` (`seats` as they were
    /// in it, with their `accounts`; rated if it was); its id.
    fn start_rematch(
        &self,
        of: String,
        config: Config,
        turn: Duration,
        seats: [SeatSpec; 2],
        accounts: [Option<String>; 2],
        rated: bool,
    ) -> impl Future<Output = Result<String, Refusal>> + Send;
    /// Forgets the room of `id` (unless a newer one, of a later
    /// `generation`, took its place).
    fn remove(&self, id: &str, generation: u64);
    /// The match has just ended, its last move stored. By default nobody
    /// is told.
    fn finished(&self, _m: FinishedMatch) {}
    /// The hosted bots' budget and modules (`None`: this host plays no
    /// hosted bot, and a hosted seat never answers).
    fn hosted(&self) -> Option<&HostedPool> {
        None
    }
}

/// A match that just ended, as its room saw it.
#[derive(Clone, Debug)]
pub struct FinishedMatch {
    pub match_id: String,
    /// The account playing each seat, if any.
    pub accounts: [Option<String>; 2],
    pub result: game::MatchResult,
    pub rated: bool,
}

/// Hears of every match that ends (after its last move is stored). One
/// required method; its implementation must not block (it runs on the
/// room's task).
pub trait MatchListener: Send + Sync {
    fn finished(&self, m: FinishedMatch);
}

/// What a connecting WebSocket claims.
#[derive(Clone, Debug)]
pub enum Claim {
    /// Nothing: it watches, and chats under this name (its hello's).
    Watch(String),
    /// The seat this token holds.
    Token(SeatToken),
    /// The seat this account holds (its key already checked).
    Account(String),
}

/// What a room is asked to do.
#[derive(Debug)]
pub enum Command {
    /// A WebSocket connects: with a seat token, as the account holding a
    /// seat, or as a spectator.
    Connect {
        claim: Claim,
        reply: oneshot::Sender<Result<Connected, Refusal>>,
    },
    /// A connection closed.
    Disconnect { conn: u64 },
    /// A connection sent a match message, which arrived at `received`.
    Message {
        conn: u64,
        msg: ClientMessage,
        received: std::time::Instant,
    },
    /// Someone takes the empty second seat (HTTP join).
    Join {
        name: String,
        /// The hash of the seat token made for them.
        token: TokenHash,
        /// Their account, if they signed in.
        account: Option<String>,
        reply: oneshot::Sender<Result<Seat, Refusal>>,
    },
    /// Finish the command in hand and stop (server shutdown).
    Shutdown { done: oneshot::Sender<()> },
}

impl Command {
    /// A match message from `conn` that arrived just now.
    pub fn message(conn: u64, msg: ClientMessage) -> Command {
        Command::Message {
            conn,
            msg,
            received: std::time::Instant::now(),
        }
    }
}

/// A connection admitted to a room.
#[derive(Debug)]
pub struct Connected {
    pub conn: u64,
    pub seat: Option<Seat>,
    /// Everything the room sends this connection, `match-state` first.
    pub rx: Inbox,
    /// How many of this connection's messages the room refused so far
    /// (the connection's flood guard charges them: junk is limited, legal
    /// moves are not).
    pub refused: Arc<AtomicU32>,
}

/// A bot's decision, computed off the room's task.
struct BotAnswer {
    seat: Seat,
    at_move: usize,
    decision: BotDecision,
    /// The bot, back from its thinking thread.
    bot: Thinker,
}

/// Who thought: a built-in level, or a hosted module (`None`: its module
/// could not be compiled; the next decision tries again).
enum Thinker {
    Builtin(Box<dyn Bot>),
    Hosted(Option<bots::hosted_bot::HostedBot>),
}

/// What carrying out one input's effects came to, for the command's
/// answer.
#[derive(Debug, Default)]
struct Carried {
    admitted: Option<Connected>,
    joined: Option<Seat>,
    /// A refused connection or join.
    refused: Option<Refusal>,
    /// A durable write failed (the rest of its effects were dropped).
    write_failed: bool,
    /// ...because this node of a cluster no longer holds the match's
    /// lease: another node may play it now, so the room stops.
    lease_lost: bool,
    /// A shot was stored.
    shot_stored: bool,
}

/// A match in memory.
pub struct Room<H: RoomHost> {
    id: String,
    generation: u64,
    session: Session,
    host: H,
    /// The session's epoch: when the room started.
    epoch: Instant,
    /// The connections' queues.
    conns: HashMap<u64, mpsc::Sender<Outbound>>,
    /// The count of refused messages of each connection.
    refused: HashMap<u64, Arc<AtomicU32>>,
    /// Whether the metrics count this match as live.
    live: bool,
    /// The built-in bot of each seat played by one, with its own
    /// generator (seeded from the system's randomness, never the match's
    /// seed); out of its slot while it thinks (behind a mutex only so that
    /// the room, held across awaits, can be shared: only the room touches
    /// it).
    bots: [std::sync::Mutex<Option<Box<dyn Bot>>>; 2],
    /// The hosted module playing each seat played by one.
    hosted: [Option<HostedSeat>; 2],
    /// The match's noise key (a hosted bot's random streams derive from
    /// its secret).
    noise: game::NoiseKey,
    /// For a seat the adaptive level plays against a person with an
    /// account: that account, until the level's first decision looks up
    /// what it learned of them ([`crate::play::adaptive_memory`]).
    adaptive_person: [Option<String>; 2],
    bot_tx: mpsc::Sender<BotAnswer>,
    bot_rx: Option<mpsc::Receiver<BotAnswer>>,
    /// What the session has said while handling the command in hand;
    /// handed to the connections when it is done ([`Room::flush`]).
    outbox: Vec<(To, ByteString)>,
    /// The account playing each seat, if any.
    accounts: [Option<String>; 2],
    /// Whether the match is rated (then both seats have accounts).
    rated: bool,
    /// The account of the join being handled, stored with the seat.
    joining: Option<String>,
    /// A write was refused because this node of a cluster no longer holds
    /// the match's lease: the room stops once it has said so (its
    /// connections end; their clients reconnect and find the node that
    /// plays the match now).
    lease_lost: bool,
}

/// A bot's slot (a panic while it was held cannot leave it half-changed).
fn lock(
    slot: &std::sync::Mutex<Option<Box<dyn Bot>>>,
) -> std::sync::MutexGuard<'_, Option<Box<dyn Bot>>> {
    slot.lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

fn bot_seed() -> u64 {
    crate::token::seed().unwrap_or_else(|e| {
        warn!(error = %e, "no randomness for the bot; seeding it from the time");
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map(|d| d.as_nanos() as u64)
            .unwrap_or(0x5EED)
    })
}

impl<H: RoomHost> Room<H> {
    /// A room for a stored match whose record has been replayed into `game`.
    pub fn new(stored: &StoredMatch, game: Game, host: H, generation: u64) -> Room<H> {
        let levels = stored.bots();
        let hosted = [0, 1].map(|i| {
            let s = &stored.seats[i];
            let (account, hash) = (s.account.clone()?, s.module.clone()?);
            // Compiled when the match started, if it did just now.
            let bot = match (host.hosted().and_then(|p| p.cached(&hash)), &stored.noise) {
                (Some(m), game::NoiseKey::ChaCha20(secret)) => {
                    Some(bots::hosted_bot::HostedBot::new(m, *secret))
                }
                _ => None,
            };
            Some(HostedSeat {
                account,
                hash,
                bot,
                thinking: false,
            })
        });
        let seat = |i: usize| SeatSpec {
            name: stored.seats[i].name.clone(),
            token: stored.seats[i].token,
            bot: match &hosted[i] {
                Some(h) => Some(h.account.clone()),
                None => levels[i].map(|b| b.as_str().to_string()),
            },
        };
        let seats = [seat(0), seat(1)];
        // A seeded match seeds its computers as `bots match --seed` does
        // (the first seat's from the seed, the second's from the next).
        let mut seat_index = 0u64;
        let bots = levels.map(|l| {
            let seed = stored
                .seed
                .map_or_else(bot_seed, |s| s.wrapping_add(seat_index));
            seat_index += 1;
            std::sync::Mutex::new(l.map(|l| l.bot(seed)))
        });
        let l = host.limits();
        let limits = SessionLimits {
            turn: Duration::from_secs(stored.turn_seconds.max(1)),
            grace: l.grace,
            bot_delay: l.bot_delay,
            idle: l.idle,
            max_connections_per_match: l.max_connections_per_match,
        };
        let session = Session::new(stored.id.clone(), game, seats, limits, Moment::ZERO);
        let (bot_tx, bot_rx) = mpsc::channel(4);
        Room {
            id: stored.id.clone(),
            generation,
            session,
            host,
            epoch: Instant::now(),
            conns: HashMap::new(),
            refused: HashMap::new(),
            live: false,
            bots,
            hosted,
            noise: stored.noise,
            adaptive_person: [0, 1].map(|i| {
                (levels[i] == Some(bots::Level::Adaptive))
                    .then(|| stored.seats[1 - i].account.clone())
                    .flatten()
            }),
            bot_tx,
            bot_rx: Some(bot_rx),
            outbox: Vec::new(),
            accounts: stored.seats.clone().map(|s| s.account),
            rated: stored.rated,
            joining: None,
            lease_lost: false,
        }
    }

    /// Now, on the session's clock.
    fn now(&self) -> Moment {
        Moment::new(self.epoch.elapsed())
    }

    /// Runs the room until it is shut down or its session closes (idled
    /// out, or broken).
    pub async fn run(mut self, mut rx: mpsc::Receiver<Command>) {
        let metrics = self.host.metrics().clone();
        metrics.room_opened();
        self.set_live(self.session.status() == Status::Live);
        let Some(mut bots) = self.bot_rx.take() else {
            return;
        };
        while !self.session.is_closed() && !self.lease_lost {
            let timer = self
                .session
                .next_deadline()
                .map(|m| self.epoch + m.since_epoch());
            tokio::select! {
                cmd = rx.recv() => match cmd {
                    None => break,
                    Some(Command::Shutdown { done }) => {
                        let _ = done.send(());
                        break;
                    }
                    Some(cmd) => self.handle(cmd).await,
                },
                Some(a) = bots.recv() => {
                    match a.bot {
                        Thinker::Builtin(bot) => *lock(&self.bots[a.seat.index()]) = Some(bot),
                        Thinker::Hosted(bot) => {
                            if let Some(h) = &mut self.hosted[a.seat.index()] {
                                h.bot = bot;
                                h.thinking = false;
                            }
                        }
                    }
                    let input = Input::BotMove { seat: a.seat, at_move: a.at_move, decision: a.decision };
                    self.feed(input).await;
                }
                _ = sleep_until(timer) => {
                    self.feed(Input::Timer).await;
                }
            }
            self.flush().await;
        }
        self.set_live(false);
        metrics.room_closed();
        self.host.remove(&self.id, self.generation);
        debug!(match_id = %self.id, "room closed");
    }

    fn set_live(&mut self, live: bool) {
        if live != self.live {
            self.host.metrics().live_changed(if live { 1 } else { -1 });
            self.live = live;
        }
    }

    async fn handle(&mut self, cmd: Command) {
        match cmd {
            Command::Connect { claim, reply } => {
                let conn = ConnId(self.host.next_conn_id());
                let input = match claim {
                    Claim::Watch(name) => Input::Connect {
                        conn,
                        token: None,
                        name,
                    },
                    Claim::Token(t) => Input::Connect {
                        conn,
                        token: Some(t),
                        name: String::new(),
                    },
                    Claim::Account(account) => {
                        let seat = self.accounts.iter().position(|a| {
                            a.as_deref()
                                .is_some_and(|a| a.eq_ignore_ascii_case(&account))
                        });
                        match seat {
                            Some(0) => Input::ConnectSeat {
                                conn,
                                seat: Seat::First,
                            },
                            Some(_) => Input::ConnectSeat {
                                conn,
                                seat: Seat::Second,
                            },
                            None => {
                                let _ = reply.send(Err(Refusal::new(
                                    ErrorCode::BadKey,
                                    "this account holds no seat in this match",
                                )));
                                return;
                            }
                        }
                    }
                };
                let carried = self.feed(input).await;
                let answer = match (carried.admitted, carried.refused) {
                    (Some(c), _) => Ok(c),
                    (None, Some(r)) => Err(r),
                    (None, None) => Err(Refusal::internal()),
                };
                if let Err(Ok(c)) = reply.send(answer) {
                    // The session went away before the answer.
                    self.disconnect(c.conn).await;
                }
            }
            Command::Disconnect { conn } => self.disconnect(conn).await,
            Command::Message {
                conn,
                msg,
                received,
            } => {
                let shot = matches!(msg, ClientMessage::Shot { .. });
                let input = Input::Message {
                    conn: ConnId(conn),
                    msg,
                };
                let carried = self.feed(input).await;
                if carried.write_failed {
                    self.host.metrics().refused();
                    let refusal = if carried.lease_lost {
                        lease_lost()
                    } else {
                        Refusal::internal()
                    };
                    self.say(To::Only(ConnId(conn)), &refusal.to_message());
                } else if shot && carried.shot_stored {
                    self.flush().await;
                    self.host.metrics().shot_broadcast(received.elapsed());
                }
            }
            Command::Join {
                name,
                token,
                account,
                reply,
            } => {
                if let Err(r) = self.may_join(account.as_deref()) {
                    let _ = reply.send(Err(r));
                    return;
                }
                self.joining = account;
                let carried = self.feed(Input::Join { name, token }).await;
                let joining = self.joining.take();
                if carried.joined.is_some() && !carried.write_failed {
                    self.accounts[1] = joining;
                }
                let answer = match (carried.write_failed, carried.joined, carried.refused) {
                    (false, Some(seat), _) => Ok(seat),
                    (false, None, Some(r)) => Err(r),
                    _ => Err(Refusal::internal()),
                };
                let _ = reply.send(answer);
            }
            Command::Shutdown { .. } => {}
        }
    }

    /// Whether the holder of `account` (if signed in) may take the second
    /// seat: a rated match needs an account, and not the first seat's.
    fn may_join(&self, account: Option<&str>) -> Result<(), Refusal> {
        if !self.rated {
            return Ok(());
        }
        let Some(account) = account else {
            return Err(Refusal::new(
                ErrorCode::BadKey,
                "this match is rated: sign in (send your account key as \
                 'Authorization: Bearer KEY') to join it",
            ));
        };
        if self.accounts[0]
            .as_deref()
            .is_some_and(|a| a.eq_ignore_ascii_case(account))
        {
            return Err(Refusal::new(
                ErrorCode::SameAccount,
                "a rated match is between two accounts: this one holds the first seat",
            ));
        }
        Ok(())
    }

    async fn disconnect(&mut self, conn: u64) {
        self.refused.remove(&conn);
        if self.conns.remove(&conn).is_some() {
            debug!(match_id = %self.id, conn, "disconnected");
        }
        self.feed(Input::Disconnect { conn: ConnId(conn) }).await;
    }

    fn say(&mut self, to: To, msg: &ServerMessage) {
        // Serialised once; each connection's copy shares the bytes.
        self.outbox.push((to, ByteString::from(msg.to_json())));
    }

    /// Feeds `input` to the session and carries out its effects, in order
    /// (and those of what the room feeds it back meanwhile: a rematch
    /// created, a write that failed).
    async fn feed(&mut self, input: Input) -> Carried {
        let started = std::time::Instant::now();
        let mut carried = Carried::default();
        let mut queue: VecDeque<Effect> = self.session.handle(input, self.now()).into();
        while let Some(effect) = queue.pop_front() {
            match effect {
                Effect::Admitted { conn, seat } => {
                    let (tx, rx) = mpsc::channel(self.host.limits().outbound_queue);
                    self.conns.insert(conn.0, tx);
                    let refused = Arc::new(AtomicU32::new(0));
                    self.refused.insert(conn.0, refused.clone());
                    debug!(match_id = %self.id, conn = conn.0, ?seat, "connected");
                    carried.admitted = Some(Connected {
                        conn: conn.0,
                        seat,
                        rx: Inbox::new(rx),
                        refused,
                    });
                }
                Effect::Joined { seat } => {
                    info!(match_id = %self.id, "second seat taken; match live");
                    carried.joined = Some(seat);
                }
                Effect::Refused { request, refusal } => match request {
                    Request::Connect(_) | Request::Join => carried.refused = Some(refusal),
                    Request::Message(conn) => {
                        self.host.metrics().refused();
                        if let Some(count) = self.refused.get(&conn.0) {
                            count.fetch_add(1, Ordering::Relaxed);
                        }
                        self.say(To::Only(conn), &refusal.to_message());
                    }
                    Request::Bot(seat) => {
                        warn!(match_id = %self.id, ?seat, refusal = %refusal, "the bot's move was refused");
                    }
                    Request::Clock => {
                        warn!(match_id = %self.id, refusal = %refusal, "the move for a timed-out or abandoned seat was refused");
                    }
                },
                Effect::Send { to, msg } => {
                    self.log(&msg);
                    self.say(to, &msg);
                }
                Effect::Store { index, mv, after } => {
                    let shot = matches!(mv, RecordedMove::Shot(_));
                    match self.store_move(index, &mv, &after).await {
                        Ok(()) => {
                            if shot {
                                self.host.metrics().shot_resolved(started.elapsed());
                                carried.shot_stored = true;
                            }
                        }
                        Err(e @ crate::store::StoreError::LeaseLost { .. }) => {
                            // Nothing was written; what the session said
                            // after the move is dropped, and the room stops.
                            warn!(match_id = %self.id, error = %e, "this node lost the match's lease; its room stops");
                            carried.write_failed = true;
                            carried.lease_lost = true;
                            self.lease_lost = true;
                            queue.clear();
                        }
                        Err(e) => {
                            error!(match_id = %self.id, error = %e, "storing a move failed; reloading the match from the store");
                            carried.write_failed = true;
                            let reloaded = self.reload().await;
                            if reloaded.is_none() {
                                error!(match_id = %self.id, "cannot reload the match; closing it");
                            }
                            let input = Input::StoreFailed {
                                reloaded: reloaded.map(Box::new),
                            };
                            queue = self.session.handle(input, self.now()).into();
                        }
                    }
                }
                Effect::StoreJoin { name, token } => {
                    let store = self.host.store().clone();
                    let id = self.id.clone();
                    let account = self.joining.clone();
                    let stored = tokio::task::spawn_blocking(move || {
                        store.seat_second(&id, &name, &token, account.as_deref())
                    })
                    .await
                    .map_err(|e| e.to_string())
                    .and_then(|r| r.map_err(|e| e.to_string()));
                    if let Err(e) = stored {
                        error!(match_id = %self.id, error = %e, "storing a join failed");
                        carried.write_failed = true;
                        queue = self.session.handle(Input::JoinFailed, self.now()).into();
                    }
                }
                Effect::CreateRematch { .. } if self.hosted.iter().any(Option::is_some) => {
                    let refusal = Refusal::new(
                        ErrorCode::BadMessage,
                        "a hosted bot plays no rematch: challenge it again from the event stream",
                    );
                    let input = Input::RematchFailed { refusal };
                    queue.extend(self.session.handle(input, self.now()));
                }
                Effect::CreateRematch {
                    config,
                    turn,
                    seats,
                } => {
                    let created = self
                        .host
                        .start_rematch(
                            self.id.clone(),
                            config,
                            turn,
                            seats,
                            self.accounts.clone(),
                            self.rated,
                        )
                        .await;
                    let input = match created {
                        Ok(match_id) => {
                            info!(match_id = %self.id, rematch = %match_id, "rematch started");
                            Input::RematchCreated { match_id }
                        }
                        Err(refusal) => Input::RematchFailed { refusal },
                    };
                    queue.extend(self.session.handle(input, self.now()));
                }
                Effect::BotToAct {
                    seat,
                    side,
                    level,
                    at_move,
                    view,
                } => {
                    if self.hosted[seat.index()].is_some() {
                        self.ask_hosted(seat, side, at_move, view);
                    } else {
                        self.ask_bot(seat, side, &level, at_move, view);
                    }
                }
                Effect::Status(status) => {
                    self.set_live(status == Status::Live);
                    if let (Status::Finished, Some(result)) = (status, self.session.game().result())
                    {
                        self.host.finished(FinishedMatch {
                            match_id: self.id.clone(),
                            accounts: self.accounts.clone(),
                            result,
                            rated: self.rated,
                        });
                    }
                }
                Effect::Close => debug!(match_id = %self.id, "the session closed"),
            }
        }
        carried
    }

    /// Writes a move and its row update (one transaction) and waits until
    /// it is durable; no game thread waits on the disk.
    async fn store_move(
        &self,
        index: usize,
        mv: &RecordedMove,
        after: &game::session::AfterMove,
    ) -> Result<(), crate::store::StoreError> {
        let after = AfterMove {
            status: after.status,
            shots: after.shots,
            result: after.result.as_ref(),
            winner: after.winner,
        };
        self.host
            .store()
            .submit_move(&self.id, index, mv, &after)?
            .done()
            .await
    }

    /// After a failed write: the store is the truth, so take the match
    /// from it (`None`: it cannot be read back).
    async fn reload(&self) -> Option<Game> {
        let store = self.host.store().clone();
        let id = self.id.clone();
        let loaded = tokio::task::spawn_blocking(move || -> Result<Game, String> {
            let (_, record) = store
                .load(&id)
                .map_err(|e| e.to_string())?
                .ok_or_else(|| "the match is gone".to_string())?;
            let replay = Replay::new(record).map_err(|e| e.to_string())?;
            Ok(replay.game().clone())
        })
        .await;
        match loaded {
            Ok(Ok(game)) => Some(game),
            Ok(Err(e)) => {
                error!(match_id = %self.id, error = %e, "the stored match does not load");
                None
            }
            Err(e) => {
                error!(match_id = %self.id, error = %e, "the reload task failed");
                None
            }
        }
    }

    /// Computes the built-in bot's move on a blocking thread from the
    /// public view; the answer (and the bot) come back through the room's
    /// bot queue.
    fn ask_bot(
        &mut self,
        seat: Seat,
        side: Side,
        level: &str,
        at_move: usize,
        view: Box<MatchView>,
    ) {
        let Some(mut bot) = lock(&self.bots[seat.index()]).take() else {
            warn!(match_id = %self.id, level, ?seat, "no bot in this seat (or it is still thinking)");
            return;
        };
        let tx = self.bot_tx.clone();
        let think = self.host.limits().bot_think;
        let person = self.adaptive_person[seat.index()].take();
        let store = self.host.store().clone();
        let match_id = self.id.clone();
        tokio::task::spawn_blocking(move || {
            if let Some(account) = person {
                let settings = bots::AdaptiveSettings::default();
                match crate::play::adaptive_memory::start_for(store.as_ref(), &settings, &account) {
                    Ok(start) => {
                        bot = Box::new(bots::Adaptive::with_start(settings, start, bot_seed()));
                    }
                    Err(e) => {
                        warn!(%match_id, error = %e, "the person's history does not load; the adaptive level starts afresh");
                    }
                }
            }
            let ctx = Context::new(&view, side, think);
            let decision = match bot.decide(&ctx) {
                Decision::Shot(shot) => BotDecision::Shot(shot),
                Decision::Pie { swap } => BotDecision::Pie { swap },
                Decision::Resign => BotDecision::Resign,
                Decision::NoAnswer => BotDecision::NoAnswer,
            };
            // The room may have stopped meanwhile.
            let _ = tx.blocking_send(BotAnswer {
                seat,
                at_move,
                decision,
                bot: Thinker::Builtin(bot),
            });
        });
    }

    /// Asks the hosted module of `seat` for its move: the decision waits
    /// for a permit of the server's budget, then runs on a blocking
    /// thread; a failed one (out of fuel, a trap, a bad answer, a module
    /// that does not load) is no answer, and the turn times out.
    fn ask_hosted(&mut self, seat: Seat, side: Side, at_move: usize, view: Box<MatchView>) {
        let Some(h) = &mut self.hosted[seat.index()] else {
            return;
        };
        if h.thinking {
            warn!(match_id = %self.id, ?seat, "the hosted bot is still thinking");
            return;
        }
        let tx = self.bot_tx.clone();
        let Some(pool) = self.host.hosted().cloned() else {
            let _ = tx.try_send(BotAnswer {
                seat,
                at_move,
                decision: BotDecision::NoAnswer,
                bot: Thinker::Hosted(h.bot.take()),
            });
            return;
        };
        h.thinking = true;
        let bot = h.bot.take();
        let (account, hash) = (h.account.clone(), h.hash.clone());
        let store = self.host.store().clone();
        let noise = self.noise;
        let match_id = self.id.clone();
        let metrics = self.host.metrics().clone();
        tokio::spawn(async move {
            let runner = pool.clone();
            let ran = runner
                .run(move || {
                    crate::play::hosted::decide(
                        &pool,
                        store.as_ref(),
                        (account.as_str(), hash.as_str()),
                        &noise,
                        bot,
                        side,
                        *view,
                    )
                })
                .await;
            let (decision, bot) = match ran {
                Some((decision, bot, failure)) => {
                    metrics.hosted_decided(failure.is_some());
                    if let Some(e) = failure {
                        warn!(%match_id, ?seat, error = %e, "a hosted bot's decision failed: no answer");
                    }
                    (decision, bot)
                }
                None => (BotDecision::NoAnswer, None),
            };
            // The room may have stopped meanwhile.
            let _ = tx
                .send(BotAnswer {
                    seat,
                    at_move,
                    decision,
                    bot: Thinker::Hosted(bot),
                })
                .await;
        });
    }

    fn log(&self, msg: &ServerMessage) {
        match msg {
            ServerMessage::TurnTimedOut { seat, strikes } => {
                info!(match_id = %self.id, ?seat, strikes, "turn timed out");
            }
            ServerMessage::Forfeited {
                seat,
                reason: ForfeitReason::Abandoned,
            } => info!(match_id = %self.id, ?seat, "seat abandoned"),
            ServerMessage::MatchOver { result, .. } => {
                info!(match_id = %self.id, ?result, "match over");
            }
            _ => {}
        }
    }

    /// Hands what the session has said to the connections' queues, one
    /// item per connection (shared by all of them when every message is
    /// for everyone); a connection whose queue is full is too slow to
    /// follow the match and is dropped (bounded memory).
    async fn flush(&mut self) {
        // Dropping a connection may say more (a player left).
        while !self.outbox.is_empty() {
            let said = std::mem::take(&mut self.outbox);
            let everyone = said
                .iter()
                .all(|(to, _)| *to == To::All)
                .then(|| said.iter().map(|(_, m)| m.clone()).collect::<Outbound>());
            let mut slow = Vec::new();
            for (&id, tx) in &self.conns {
                let item = match &everyone {
                    Some(all) => all.clone(),
                    None => {
                        let mine: Outbound = said
                            .iter()
                            .filter(|(to, _)| to.includes(ConnId(id)))
                            .map(|(_, m)| m.clone())
                            .collect();
                        if mine.is_empty() {
                            continue;
                        }
                        mine
                    }
                };
                match tx.try_send(item) {
                    Ok(()) => {}
                    Err(mpsc::error::TrySendError::Full(_)) => slow.push((id, true)),
                    // Its session has ended; the disconnect is on its way.
                    Err(mpsc::error::TrySendError::Closed(_)) => slow.push((id, false)),
                }
            }
            for (conn, behind) in slow {
                if behind {
                    warn!(match_id = %self.id, conn, "dropping a connection that does not keep up");
                }
                self.disconnect(conn).await;
            }
        }
    }
}

/// The refusal of a move this node may no longer write (its lease on the
/// match is lost): the client should connect again, and reaches the node
/// that plays the match now.
fn lease_lost() -> Refusal {
    Refusal::new(
        ErrorCode::ServerBusy,
        "the match moved to another server node; connect again",
    )
}

async fn sleep_until(t: Option<Instant>) {
    match t {
        Some(t) => tokio::time::sleep_until(t).await,
        None => std::future::pending().await,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::store::{SqliteStore, StoredSeat};
    use game::PieceId;
    use glam::DVec2;
    use std::sync::atomic::{AtomicU64, Ordering};

    /// A host with an in-memory store and no rematches.
    #[derive(Clone)]
    struct TestHost {
        store: Arc<dyn Store>,
        metrics: Arc<Metrics>,
        limits: Limits,
        next: Arc<AtomicU64>,
    }

    impl RoomHost for TestHost {
        fn store(&self) -> &Arc<dyn Store> {
            &self.store
        }
        fn metrics(&self) -> &Arc<Metrics> {
            &self.metrics
        }
        fn limits(&self) -> &Limits {
            &self.limits
        }
        fn next_conn_id(&self) -> u64 {
            self.next.fetch_add(1, Ordering::Relaxed)
        }
        async fn start_rematch(
            &self,
            _of: String,
            _config: Config,
            _turn: Duration,
            _seats: [SeatSpec; 2],
            _accounts: [Option<String>; 2],
            _rated: bool,
        ) -> Result<String, Refusal> {
            Err(Refusal::internal())
        }
        fn remove(&self, _id: &str, _generation: u64) {}
    }

    async fn connect(room: &mpsc::Sender<Command>, token: Option<&str>) -> Connected {
        let (reply, answer) = oneshot::channel();
        let token = token.map(SeatToken::new);
        let claim = token.map_or(Claim::Watch("Furmanov".into()), Claim::Token);
        room.send(Command::Connect { claim, reply }).await.unwrap();
        answer.await.unwrap().unwrap()
    }

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn a_shot_and_the_next_turn_clock_reach_each_connection_as_one_item() {
        let host = TestHost {
            store: Arc::new(SqliteStore::in_memory().unwrap()),
            metrics: Arc::new(Metrics::default()),
            limits: Limits::default(),
            next: Arc::new(AtomicU64::new(1)),
        };
        let seat = |name: &str, token: &str| StoredSeat {
            name: Some(name.into()),
            token: Some(TokenHash::of(token)),
            account: None,
            module: None,
        };
        let stored = StoredMatch {
            id: "m1".into(),
            created_at: 0,
            config: Config::default(),
            noise: game::NoiseKey::from(7),
            physics: game::PHYSICS_VERSION,
            status: Status::Live,
            bot: None,
            turn_seconds: 30,
            seats: [seat("Petka", "tok-a"), seat("Anka", "tok-b")],
            rematch_of: None,
            rated: false,
            seed: None,
        };
        host.store.create(&stored).unwrap();
        let game = Game::new(stored.config.clone(), stored.noise).unwrap();
        let (tx, rx) = mpsc::channel(16);
        tokio::spawn(Room::new(&stored, game, host.clone(), 1).run(rx));
        let white = connect(&tx, Some("tok-a")).await;
        let mut watcher = connect(&tx, None).await;
        let kinds = |item: &Outbound| -> Vec<String> {
            item.iter()
                .map(|m| {
                    let v: serde_json::Value = serde_json::from_str(m).unwrap();
                    v["type"].as_str().unwrap().to_string()
                })
                .collect()
        };
        let first = watcher.rx.rx.recv().await.unwrap();
        assert_eq!(kinds(&first), ["match-state", "clock"]);
        let shot = ClientMessage::Shot {
            piece: PieceId::new(Side::White, 4).unwrap(),
            velocity: DVec2::new(0.0, 2.0),
        };
        tx.send(Command::message(white.conn, shot)).await.unwrap();
        let item = watcher.rx.rx.recv().await.unwrap();
        assert_eq!(kinds(&item), ["shot-played", "clock"]);
        // Stored before it was said.
        assert_eq!(host.store.moves("m1").unwrap().len(), 1);
        assert_eq!(host.metrics.shots(), 1);
        // Read one at a time, the same messages come in the same order.
        let mut inbox = Inbox::new(mpsc::channel(1).1);
        inbox.batch = Some((item.clone(), 0));
        assert_eq!(inbox.recv().await.as_deref(), Some(&*item[0]));
        assert_eq!(inbox.recv().await.as_deref(), Some(&*item[1]));
        assert_eq!(inbox.recv().await, None, "the sender is gone");
    }
}
