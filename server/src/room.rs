//! A match room: one task per match held in memory, owning its
//! [`game::Game`], its seats and the connections watching it. Everything
//! that happens to a match goes through the room's command queue, one
//! command at a time, so a match never sees two moves at once. An accepted
//! move is resolved, written to the store in one transaction, and only then
//! broadcast; a refused one changes nothing and is answered with an `error`
//! to its sender alone. The room also runs the turn clock, the built-in
//! bot's moves, the grace period of dropped players, and leaves memory when
//! nobody has watched a finished (or still open) match for a while.

use crate::bot::{self, BotLevel, BotMove};
use crate::clock::{self, TurnClock, STRIKES_TO_FORFEIT};
use crate::hub::Hub;
use crate::refusal::Refusal;
use crate::store::{AfterMove, MoveWrite, Status, StoredMatch};
use game::noise::SplitMix64;
use game::protocol::{
    ClientMessage, ErrorCode, ForfeitReason, Players, ServerMessage, MAX_CHAT_CHARS,
};
use game::{Game, Phase, Played, Seat, Shot, Side};
use std::collections::HashMap;
use std::sync::Arc;
use std::time::Duration;
use tokio::sync::{mpsc, oneshot};
use tokio::time::Instant;
use tracing::{debug, error, info, warn};

/// Messages on their way to one connection, already JSON, in order. What
/// a room says while handling one command (a shot's outcome and the next
/// turn's clock, say) travels as one item: one wakeup of the connection's
/// task, one write to its socket.
pub type Outbound = Arc<[Arc<str>]>;

/// The receiving end of a connection's queue, one message at a time.
#[derive(Debug)]
pub struct Inbox {
    rx: mpsc::Receiver<Outbound>,
    /// The item being read and the index of its next message; let go of
    /// once read (an idle connection holds no old messages).
    batch: Option<(Outbound, usize)>,
}

impl Inbox {
    fn new(rx: mpsc::Receiver<Outbound>) -> Inbox {
        Inbox { rx, batch: None }
    }

    /// The next message; `None` once the room has closed this connection
    /// and everything sent before is read. Cancel-safe.
    pub async fn recv(&mut self) -> Option<Arc<str>> {
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

/// Who a message a room says is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum To {
    All,
    AllBut(u64),
    Only(u64),
}

impl To {
    fn includes(self, conn: u64) -> bool {
        match self {
            To::All => true,
            To::AllBut(skip) => conn != skip,
            To::Only(only) => conn == only,
        }
    }
}

/// What a room is asked to do.
#[derive(Debug)]
pub enum Command {
    /// A WebSocket connects, with a seat token or as a spectator.
    Connect {
        token: Option<String>,
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
        token: String,
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
}

/// One seat of a match.
#[derive(Clone, Debug, Default)]
struct SeatState {
    name: Option<String>,
    token: Option<String>,
    bot: Option<BotLevel>,
    /// Open connections holding this seat.
    conns: usize,
    /// When a dropped player's seat is forfeited.
    away_until: Option<Instant>,
}

impl SeatState {
    fn taken(&self) -> bool {
        self.token.is_some() || self.bot.is_some()
    }
}

struct Conn {
    seat: Option<Seat>,
    tx: mpsc::Sender<Outbound>,
}

/// A move the room applies (from a player, a bot or the clock).
#[derive(Clone, Copy, Debug)]
enum Action {
    Shot(Side, Shot),
    Pie(Side, bool),
    Resign(Side),
    /// The turn clock ran out: the turn passes.
    Pass(Side),
    Forfeit(Side, ForfeitReason),
}

/// Why applying a move failed.
enum ApplyError {
    /// The game refused it; nothing changed.
    Refused(Refusal),
    /// The game took it but the store did not.
    Store(String),
}

impl<E: Into<Refusal>> From<E> for ApplyError {
    fn from(e: E) -> ApplyError {
        ApplyError::Refused(e.into())
    }
}

fn index(seat: Seat) -> usize {
    match seat {
        Seat::First => 0,
        Seat::Second => 1,
    }
}

const SEATS: [Seat; 2] = [Seat::First, Seat::Second];

/// A match in memory.
pub struct Room {
    id: String,
    generation: u64,
    game: Game,
    seats: [SeatState; 2],
    conns: HashMap<u64, Conn>,
    clock: TurnClock,
    status: Status,
    rematch_offer: Option<Seat>,
    rematch: Option<String>,
    bot_at: Option<Instant>,
    idle_since: Option<Instant>,
    rng: SplitMix64,
    hub: Hub,
    broken: bool,
    /// What the room has said while handling the command in hand; handed to
    /// the connections when it is done ([`Room::flush`]).
    outbox: Vec<(To, Arc<str>)>,
}

fn status_of(game: &Game, seats: &[SeatState; 2]) -> Status {
    if game.is_over() {
        Status::Finished
    } else if seats.iter().all(SeatState::taken) {
        Status::Live
    } else {
        Status::Open
    }
}

impl Room {
    /// A room for a stored match whose record has been replayed into `game`.
    pub fn new(stored: &StoredMatch, game: Game, hub: Hub, generation: u64) -> Room {
        let bot = stored.bot.as_deref().and_then(BotLevel::parse);
        let seats = [
            SeatState {
                name: stored.seats[0].name.clone(),
                token: stored.seats[0].token.clone(),
                ..SeatState::default()
            },
            SeatState {
                name: stored.seats[1].name.clone(),
                token: stored.seats[1].token.clone(),
                bot,
                ..SeatState::default()
            },
        ];
        let status = status_of(&game, &seats);
        let turn = Duration::from_secs(stored.turn_seconds.max(1));
        let rng = SplitMix64::new(stored.seed ^ 0xB07_B07);
        Room {
            id: stored.id.clone(),
            generation,
            game,
            seats,
            conns: HashMap::new(),
            clock: TurnClock::new(turn),
            status,
            rematch_offer: None,
            rematch: None,
            bot_at: None,
            idle_since: Some(Instant::now()),
            rng,
            hub,
            broken: false,
            outbox: Vec::new(),
        }
    }

    /// Runs the room until it is shut down, breaks, or idles out.
    pub async fn run(mut self, mut rx: mpsc::Receiver<Command>) {
        let metrics = self.hub.metrics().clone();
        metrics.room_opened();
        if self.status == Status::Live {
            metrics.live_changed(1);
        }
        self.schedule(Instant::now());
        loop {
            let timer = self.next_timer();
            tokio::select! {
                cmd = rx.recv() => match cmd {
                    None => break,
                    Some(Command::Shutdown { done }) => {
                        let _ = done.send(());
                        break;
                    }
                    Some(cmd) => self.handle(cmd).await,
                },
                _ = sleep_until(timer) => self.on_timer().await,
            }
            self.flush();
            if self.broken || self.idle_out(Instant::now()) {
                break;
            }
        }
        if self.status == Status::Live {
            metrics.live_changed(-1);
        }
        metrics.room_closed();
        self.hub.remove(&self.id, self.generation);
        debug!(match_id = %self.id, "room closed");
    }

    fn idle_out(&self, now: Instant) -> bool {
        self.status != Status::Live
            && self.conns.is_empty()
            && self
                .idle_since
                .is_some_and(|t| now >= t + self.hub.limits().idle)
    }

    fn next_timer(&self) -> Option<Instant> {
        let idle = if self.status != Status::Live && self.conns.is_empty() {
            self.idle_since.map(|t| t + self.hub.limits().idle)
        } else {
            None
        };
        [
            self.clock.deadline().map(|(_, d)| d),
            self.bot_at,
            self.seats[0].away_until,
            self.seats[1].away_until,
            idle,
        ]
        .into_iter()
        .flatten()
        .min()
    }

    async fn on_timer(&mut self) {
        let now = Instant::now();
        if let Some((seat, deadline)) = self.clock.deadline() {
            if deadline <= now {
                self.timed_out(seat).await;
            }
        }
        if self.bot_at.is_some_and(|t| t <= now) {
            self.bot_at = None;
            self.bot_move().await;
        }
        for seat in SEATS {
            if self.seats[index(seat)].away_until.is_some_and(|t| t <= now) {
                self.seats[index(seat)].away_until = None;
                self.abandoned(seat).await;
            }
        }
    }

    async fn handle(&mut self, cmd: Command) {
        match cmd {
            Command::Connect { token, reply } => {
                let r = self.connect(token);
                if let Err(Ok(c)) = reply.send(r) {
                    // The session went away before the answer.
                    self.disconnect(c.conn);
                }
            }
            Command::Disconnect { conn } => self.disconnect(conn),
            Command::Message {
                conn,
                msg,
                received,
            } => {
                if let Err(refusal) = self.message(conn, msg, received).await {
                    self.hub.metrics().refused();
                    self.send_to(conn, &refusal.to_message());
                }
            }
            Command::Join { name, token, reply } => {
                let r = self.join(name, token);
                let _ = reply.send(r);
            }
            Command::Shutdown { .. } => {}
        }
    }

    // ----- connections -----

    fn players(&self) -> Players {
        let name = |s: &SeatState| match s.bot {
            Some(level) => Some(format!("bot ({})", level.as_str())),
            None => s.name.clone(),
        };
        Players {
            first: name(&self.seats[0]),
            second: name(&self.seats[1]),
        }
    }

    fn state_for(&self, you: Option<Seat>) -> ServerMessage {
        ServerMessage::MatchState {
            match_id: self.id.clone(),
            you,
            players: self.players(),
            view: self.game.view(),
        }
    }

    fn clock_message(&self, now: Instant) -> Option<ServerMessage> {
        let (seat, deadline) = self.clock.deadline()?;
        Some(ServerMessage::Clock {
            seat,
            side: self.game.side_of(seat),
            remaining_ms: deadline.saturating_duration_since(now).as_millis() as u64,
        })
    }

    fn connect(&mut self, token: Option<String>) -> Result<Connected, Refusal> {
        if self.conns.len() >= self.hub.limits().max_connections_per_match {
            return Err(Refusal::new(
                ErrorCode::ServerBusy,
                "this match has as many watchers as it can take",
            ));
        }
        let seat = match token {
            None => None,
            Some(t) => Some(
                SEATS
                    .into_iter()
                    .find(|s| {
                        self.seats[index(*s)]
                            .token
                            .as_deref()
                            .is_some_and(|mine| crate::token::same_token(&t, mine))
                    })
                    .ok_or_else(|| {
                        Refusal::new(
                            ErrorCode::BadToken,
                            "this token holds no seat in this match",
                        )
                    })?,
            ),
        };
        let (tx, rx) = mpsc::channel(self.hub.limits().outbound_queue);
        let conn = self.hub.next_conn_id();
        let now = Instant::now();
        let mut first = vec![self.state_for(seat)];
        first.extend(self.clock_message(now));
        if let Some(by) = self.rematch_offer {
            first.push(ServerMessage::RematchOffered { by });
        }
        if let Some(id) = &self.rematch {
            first.push(ServerMessage::RematchStarted {
                match_id: id.clone(),
            });
        }
        let first: Outbound = first.iter().map(|m| Arc::from(m.to_json())).collect();
        // The queue is new and empty.
        let _ = tx.try_send(first);
        self.conns.insert(conn, Conn { seat, tx });
        self.idle_since = None;
        if let Some(s) = seat {
            let st = &mut self.seats[index(s)];
            st.conns += 1;
            if st.conns == 1 && st.away_until.take().is_some() {
                self.broadcast_except(conn, &ServerMessage::PlayerBack { seat: s });
            }
        }
        debug!(match_id = %self.id, conn, ?seat, "connected");
        Ok(Connected {
            conn,
            seat,
            rx: Inbox::new(rx),
        })
    }

    fn disconnect(&mut self, conn: u64) {
        let Some(c) = self.conns.remove(&conn) else {
            return;
        };
        if self.conns.is_empty() {
            self.idle_since = Some(Instant::now());
        }
        let Some(seat) = c.seat else {
            return;
        };
        let st = &mut self.seats[index(seat)];
        st.conns = st.conns.saturating_sub(1);
        if st.conns == 0 && self.status == Status::Live {
            let grace = self.hub.limits().grace;
            st.away_until = Some(Instant::now() + grace);
            self.broadcast(&ServerMessage::PlayerLeft {
                seat,
                grace_ms: grace.as_millis() as u64,
            });
        }
        debug!(match_id = %self.id, conn, ?seat, "disconnected");
    }

    fn send_to(&mut self, conn: u64, msg: &ServerMessage) {
        self.outbox.push((To::Only(conn), Arc::from(msg.to_json())));
    }

    fn broadcast(&mut self, msg: &ServerMessage) {
        self.outbox.push((To::All, Arc::from(msg.to_json())));
    }

    fn broadcast_except(&mut self, skip: u64, msg: &ServerMessage) {
        self.outbox
            .push((To::AllBut(skip), Arc::from(msg.to_json())));
    }

    /// Hands what the room has said to the connections' queues, one item
    /// per connection (shared by all of them when every message is for
    /// everyone); a connection whose queue is full is too slow to follow
    /// the match and is dropped (bounded memory).
    fn flush(&mut self) {
        // Dropping a connection may say more (a player left).
        while !self.outbox.is_empty() {
            let said = std::mem::take(&mut self.outbox);
            let everyone = said
                .iter()
                .all(|(to, _)| *to == To::All)
                .then(|| said.iter().map(|(_, m)| m.clone()).collect::<Outbound>());
            let mut slow = Vec::new();
            for (&id, c) in &self.conns {
                let item = match &everyone {
                    Some(all) => all.clone(),
                    None => {
                        let mine: Outbound = said
                            .iter()
                            .filter(|(to, _)| to.includes(id))
                            .map(|(_, m)| m.clone())
                            .collect();
                        if mine.is_empty() {
                            continue;
                        }
                        mine
                    }
                };
                if c.tx.try_send(item).is_err() {
                    slow.push(id);
                }
            }
            for conn in slow {
                self.drop_slow(conn);
            }
        }
    }

    fn drop_slow(&mut self, conn: u64) {
        warn!(match_id = %self.id, conn, "dropping a connection that does not keep up");
        self.disconnect(conn);
    }

    fn join(&mut self, name: String, token: String) -> Result<Seat, Refusal> {
        if self.game.is_over() {
            return Err(Refusal::new(ErrorCode::MatchOver, "the match is over"));
        }
        if self.seats[1].taken() {
            return Err(Refusal::new(
                ErrorCode::MatchFull,
                "both seats of this match are taken",
            ));
        }
        let store = self.hub.store().clone();
        let id = self.id.clone();
        tokio::task::block_in_place(|| store.seat_second(&id, &name, &token)).map_err(|e| {
            error!(match_id = %self.id, error = %e, "storing a join failed");
            Refusal::internal()
        })?;
        self.seats[1].name = Some(name.clone());
        self.seats[1].token = Some(token);
        self.set_status(status_of(&self.game, &self.seats));
        info!(match_id = %self.id, "second seat taken; match live");
        self.broadcast(&ServerMessage::PlayerJoined {
            seat: Seat::Second,
            name,
        });
        self.schedule(Instant::now());
        Ok(Seat::Second)
    }

    fn set_status(&mut self, status: Status) {
        if status == self.status {
            return;
        }
        let metrics = self.hub.metrics();
        if self.status == Status::Live {
            metrics.live_changed(-1);
        }
        if status == Status::Live {
            metrics.live_changed(1);
        }
        self.status = status;
    }

    // ----- client messages -----

    /// Handles a client's match message (which arrived at `received`).
    async fn message(
        &mut self,
        conn: u64,
        msg: ClientMessage,
        received: std::time::Instant,
    ) -> Result<(), Refusal> {
        let seat = self.conns.get(&conn).and_then(|c| c.seat);
        let seated = || {
            seat.ok_or_else(|| {
                Refusal::new(
                    ErrorCode::NotInMatch,
                    "spectators cannot do that; connect with a seat token",
                )
            })
        };
        match msg {
            ClientMessage::Shot { piece, velocity } => {
                let seat = seated()?;
                if self.status == Status::Open {
                    return Err(Refusal::new(
                        ErrorCode::NotYourTurn,
                        "waiting for an opponent to join",
                    ));
                }
                let side = self.game.side_of(seat);
                let shot = Shot::new(piece, velocity, self.game.config())?;
                self.game.check(side, &shot)?;
                self.apply(Action::Shot(side, shot)).await?;
                self.flush();
                self.hub.metrics().shot_broadcast(received.elapsed());
                self.clock.acted(seat);
            }
            ClientMessage::PieDecision { swap } => {
                let seat = seated()?;
                let side = self.game.side_of(seat);
                self.apply(Action::Pie(side, swap)).await?;
                self.clock.acted(seat);
            }
            ClientMessage::Resign => {
                let seat = seated()?;
                self.apply(Action::Resign(self.game.side_of(seat))).await?;
            }
            ClientMessage::Chat { text } => {
                let seat = seated()?;
                if text.chars().count() > MAX_CHAT_CHARS {
                    return Err(Refusal::new(
                        ErrorCode::ChatTooLong,
                        format!("chat messages are at most {MAX_CHAT_CHARS} characters"),
                    ));
                }
                let name = self.players().names(seat);
                self.broadcast(&ServerMessage::Chat {
                    from: Some(seat),
                    name,
                    text,
                });
            }
            ClientMessage::OfferRematch => {
                let seat = seated()?;
                if !self.game.is_over() {
                    return Err(Refusal::new(
                        ErrorCode::MatchNotOver,
                        "a rematch can be offered once the match is over",
                    ));
                }
                if let Some(id) = self.rematch.clone() {
                    self.send_to(conn, &ServerMessage::RematchStarted { match_id: id });
                    return Ok(());
                }
                self.rematch_offer = Some(seat);
                self.broadcast(&ServerMessage::RematchOffered { by: seat });
                if self.seats[index(seat.other())].bot.is_some() {
                    self.start_rematch().await?;
                }
            }
            ClientMessage::AcceptRematch => {
                let seat = seated()?;
                match self.rematch_offer {
                    Some(by) if by != seat => self.start_rematch().await?,
                    _ => {
                        return Err(Refusal::new(
                            ErrorCode::NoRematchOffer,
                            "the opponent has not offered a rematch",
                        ))
                    }
                }
            }
            ClientMessage::Hello { .. }
            | ClientMessage::CreateMatch { .. }
            | ClientMessage::JoinMatch { .. }
            | ClientMessage::Watch { .. } => {
                return Err(Refusal::new(
                    ErrorCode::BadMessage,
                    "matches are created and joined over HTTP (see /)",
                ))
            }
        }
        Ok(())
    }

    async fn start_rematch(&mut self) -> Result<(), Refusal> {
        let new_id = self
            .hub
            .create_rematch(
                &self.id,
                self.game.config().clone(),
                self.clock.turn(),
                self.seats.clone().map(|s| (s.name, s.token, s.bot)),
            )
            .await?;
        info!(match_id = %self.id, rematch = %new_id, "rematch started");
        self.rematch_offer = None;
        self.rematch = Some(new_id.clone());
        self.broadcast(&ServerMessage::RematchStarted { match_id: new_id });
        Ok(())
    }

    // ----- moves -----

    /// Plays `action` on the game and queues it for the store: the played
    /// shot (for shots) and the pending write. A refused move changes
    /// nothing.
    fn resolve(&mut self, action: Action) -> Result<(Option<Played>, MoveWrite), ApplyError> {
        let game = &mut self.game;
        let played = match action {
            Action::Shot(side, shot) => Some(game.play(side, shot)?),
            Action::Pie(side, swap) => {
                game.decide_pie(side, swap)?;
                None
            }
            Action::Resign(side) => {
                game.resign(side)?;
                None
            }
            Action::Pass(side) => {
                game.pass(side)?;
                None
            }
            Action::Forfeit(side, reason) => {
                game.forfeit(side, reason)?;
                None
            }
        };
        let moves = &game.record().moves;
        let (index, last) = (moves.len() - 1, &moves[moves.len() - 1]);
        let result = game.result();
        let after = AfterMove {
            status: status_of(game, &self.seats),
            shots: game.shots(),
            result: result.as_ref(),
        };
        let write = self
            .hub
            .store()
            .submit_move(&self.id, index, last, &after)
            .map_err(|e| ApplyError::Store(e.to_string()))?;
        Ok((played, write))
    }

    /// Applies an accepted move: resolves it, stores it, then broadcasts it.
    async fn apply(&mut self, action: Action) -> Result<(), Refusal> {
        let started = std::time::Instant::now();
        // Resolving a shot is microseconds of CPU, done here; the write is
        // awaited, so no game thread waits on the disk.
        let outcome = match self.resolve(action) {
            Ok((played, write)) => write
                .done()
                .await
                .map(|()| played)
                .map_err(|e| ApplyError::Store(e.to_string())),
            Err(e) => Err(e),
        };
        let played = match outcome {
            Ok(p) => p,
            Err(ApplyError::Refused(refusal)) => return Err(refusal),
            Err(ApplyError::Store(store_error)) => {
                error!(match_id = %self.id, error = %store_error, "storing a move failed; reloading the match from the store");
                self.reload();
                return Err(Refusal::internal());
            }
        };
        match (action, played) {
            (Action::Shot(..), Some(played)) => {
                self.hub.metrics().shot_resolved(started.elapsed());
                self.broadcast(&ServerMessage::ShotPlayed {
                    outcome: played.outcome,
                    film: played.film,
                });
            }
            (Action::Pie(_, swap), _) => self.broadcast(&ServerMessage::PieDecided { swap }),
            (Action::Pass(side), _) => self.broadcast(&ServerMessage::TurnPassed { side }),
            _ => {}
        }
        if let Some(result) = self.game.result() {
            info!(match_id = %self.id, ?result, "match over");
            self.set_status(Status::Finished);
            self.broadcast(&ServerMessage::MatchOver {
                result,
                record: self.game.record().clone(),
            });
        }
        self.schedule(Instant::now());
        Ok(())
    }

    /// After a failed write: the store is the truth, so take the match from it.
    fn reload(&mut self) {
        let store = self.hub.store().clone();
        let loaded = tokio::task::block_in_place(|| store.load(&self.id));
        match loaded {
            Ok(Some((_, record))) => match game::Replay::new(record) {
                Ok(replay) => self.game = replay.game().clone(),
                Err(e) => {
                    error!(match_id = %self.id, error = %e, "stored record does not replay; closing the match");
                    self.broken = true;
                }
            },
            Ok(None) | Err(_) => {
                error!(match_id = %self.id, "cannot reload the match; closing it");
                self.broken = true;
            }
        }
    }

    /// Restarts the turn clock (or the bot's move) for whoever must act.
    fn schedule(&mut self, now: Instant) {
        let acting = if self.status == Status::Live {
            clock::to_act(&self.game)
        } else {
            None
        };
        match acting {
            Some(seat) if self.seats[index(seat)].bot.is_some() => {
                self.clock.start(None, now);
                if self.bot_at.is_none() {
                    self.bot_at = Some(now + self.hub.limits().bot_delay);
                }
            }
            Some(seat) => {
                self.bot_at = None;
                self.clock.start(Some(seat), now);
                if let Some(m) = self.clock_message(now) {
                    self.broadcast(&m);
                }
            }
            None => {
                self.bot_at = None;
                self.clock.start(None, now);
            }
        }
    }

    async fn bot_move(&mut self) {
        let Some(seat) = clock::to_act(&self.game) else {
            return;
        };
        let Some(level) = self.seats[index(seat)].bot else {
            return;
        };
        let side = match self.game.phase() {
            Phase::PieDecision => Side::Black,
            _ => self.game.side_of(seat),
        };
        let game = &self.game;
        let rng = &mut self.rng;
        let choice = tokio::task::block_in_place(|| bot::choose(level, game, side, rng));
        let action = match choice {
            Some(BotMove::Shot(shot)) => Action::Shot(side, shot),
            Some(BotMove::Pie { swap }) => Action::Pie(side, swap),
            None => Action::Resign(side),
        };
        if let Err(r) = self.apply(action).await {
            warn!(match_id = %self.id, refusal = %r, "the bot's move was refused");
        }
    }

    async fn timed_out(&mut self, seat: Seat) {
        let strikes = self.clock.strike(seat);
        info!(match_id = %self.id, ?seat, strikes, "turn timed out");
        self.broadcast(&ServerMessage::TurnTimedOut { seat, strikes });
        let side = self.game.side_of(seat);
        let action = if strikes >= STRIKES_TO_FORFEIT {
            self.broadcast(&ServerMessage::Forfeited {
                seat,
                reason: ForfeitReason::Timeouts,
            });
            Action::Forfeit(side, ForfeitReason::Timeouts)
        } else if self.game.phase() == Phase::PieDecision {
            Action::Pie(Side::Black, false)
        } else {
            Action::Pass(side)
        };
        if let Err(r) = self.apply(action).await {
            warn!(match_id = %self.id, refusal = %r, "the timeout move was refused");
            self.schedule(Instant::now());
        }
    }

    async fn abandoned(&mut self, seat: Seat) {
        if self.status != Status::Live || self.seats[index(seat)].conns > 0 {
            return;
        }
        info!(match_id = %self.id, ?seat, "seat abandoned");
        self.broadcast(&ServerMessage::Forfeited {
            seat,
            reason: ForfeitReason::Abandoned,
        });
        let side = self.game.side_of(seat);
        if let Err(r) = self
            .apply(Action::Forfeit(side, ForfeitReason::Abandoned))
            .await
        {
            warn!(match_id = %self.id, refusal = %r, "forfeiting an abandoned seat failed");
        }
    }
}

trait SeatName {
    fn names(&self, seat: Seat) -> String;
}

impl SeatName for Players {
    fn names(&self, seat: Seat) -> String {
        let n = match seat {
            Seat::First => &self.first,
            Seat::Second => &self.second,
        };
        n.clone().unwrap_or_else(|| match seat {
            Seat::First => "first".into(),
            Seat::Second => "second".into(),
        })
    }
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
    use crate::config::Limits;
    use crate::hub::{NewMatch, Opponent};
    use crate::metrics::Metrics;
    use crate::store::Store;
    use game::{Config, PieceId};
    use glam::DVec2;

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn a_shot_and_the_next_turn_clock_reach_each_connection_as_one_item() {
        let hub = Hub::new(
            Arc::new(Store::in_memory().unwrap()),
            Arc::new(Metrics::default()),
            Limits::default(),
            tokio::runtime::Handle::current(),
        );
        let a = hub
            .create(NewMatch {
                name: "Petka".into(),
                opponent: Opponent::Person,
                config: Config::default(),
                turn_seconds: None,
            })
            .await
            .unwrap();
        hub.join(&a.match_id, "Anka".into()).await.unwrap();
        let (room, white) = hub.connect(&a.match_id, Some(a.token)).await.unwrap();
        let (_, mut watcher) = hub.connect(&a.match_id, None).await.unwrap();
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
        room.tx
            .send(Command::message(white.conn, shot))
            .await
            .unwrap();
        let item = watcher.rx.rx.recv().await.unwrap();
        assert_eq!(kinds(&item), ["shot-played", "clock"]);
        // Read one at a time, the same messages come in the same order.
        let mut inbox = Inbox::new(mpsc::channel(1).1);
        inbox.batch = Some((item.clone(), 0));
        assert_eq!(inbox.recv().await.as_deref(), Some(&*item[0]));
        assert_eq!(inbox.recv().await.as_deref(), Some(&*item[1]));
        assert_eq!(inbox.recv().await, None, "the sender is gone");
    }
}
