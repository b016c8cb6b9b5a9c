//! A live match as a state machine without I/O, in the style of
//! quinn-proto: the rules of a match being played by people (and built-in
//! bots) over connections, with no sockets, no store and no clock of its
//! own. A [`Session`] owns the [`Game`], the two seats (who holds them, by
//! which token, whether a built-in bot plays one, which connections hold
//! them, and the grace period of a player who dropped), the connections
//! admitted, the turn clock with its strikes and forfeits, the pie decision
//! on timeout, resignation, chat, the rematch offer, the match's
//! [`Status`], the idle-out of a match nobody watches and the delay before
//! a built-in bot acts: while anyone watches a match between two bots (an
//! exhibition), each bot waits for the film of the shot before it to end
//! and a pause more ([`WATCHED_PAUSE`]), so people can follow it; bots
//! alone play on at full speed.
//!
//! A driver (the server's room task, a test, a tournament) feeds it
//! [`Input`]s with the time they happen, as a [`Moment`] on a clock the
//! driver chooses, and carries out the [`Effect`]s it answers with, in
//! order: messages to connections, writes to the store, a rematch to
//! create, a bot to ask for its move. The session never reads a clock: the
//! driver asks [`Session::next_deadline`] when to come back with
//! [`Input::Timer`]. The same inputs at the same moments always give the
//! same effects.
//!
//! The durability promise: an accepted move's [`Effect::Store`] comes
//! before every [`Effect::Send`] that tells of it, and the driver makes the
//! write durable before it delivers any later `Send`. When a write fails
//! the driver drops the rest of that answer's effects and hands the
//! session the match as the store has it ([`Input::StoreFailed`],
//! [`Input::JoinFailed`]).

use crate::config::Config;
use crate::game::{Game, MatchView, Phase};
use crate::outcome::{ForfeitReason, MatchResult};
use crate::protocol::{
    ClientMessage, ErrorCode, Phrase, Players, Refusal, ServerMessage, MAX_CHAT_CHARS,
};
use crate::record::RecordedMove;
use crate::shot::Shot;
use crate::side::{Seat, Side};
use crate::token::{SeatToken, TokenHash};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::ops::Add;
use std::time::Duration;

/// The pause after a shot's film before a bot shoots again in a match
/// between two bots that someone watches.
pub const WATCHED_PAUSE: Duration = Duration::from_millis(1_500);

/// The longest a shot's film may hold up a watched bot (a film is never
/// longer in play; this bounds a corrupt one).
const LONGEST_FILM: Duration = Duration::from_secs(30);

/// Timeouts in a row that forfeit a match.
pub const STRIKES_TO_FORFEIT: u32 = 3;

/// A moment on the driver's clock: the time since an epoch the driver
/// chose (the server: when the room started; tests and tournaments: a
/// virtual clock starting at zero).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Moment(Duration);

impl Moment {
    /// The epoch itself.
    pub const ZERO: Moment = Moment(Duration::ZERO);

    /// The moment `since_epoch` after the epoch.
    pub fn new(since_epoch: Duration) -> Moment {
        Moment(since_epoch)
    }

    /// The moment `ms` milliseconds after the epoch.
    pub fn from_millis(ms: u64) -> Moment {
        Moment(Duration::from_millis(ms))
    }

    /// The time since the epoch.
    pub fn since_epoch(self) -> Duration {
        self.0
    }

    /// The time from `earlier` to this moment (zero if `earlier` is later).
    pub fn saturating_since(self, earlier: Moment) -> Duration {
        self.0.saturating_sub(earlier.0)
    }
}

impl Add<Duration> for Moment {
    type Output = Moment;
    fn add(self, d: Duration) -> Moment {
        Moment(self.0.saturating_add(d))
    }
}

/// A connection, named by the driver (unique within a session).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct ConnId(pub u64);

/// Where a match stands, as listed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Status {
    /// Waiting for a second player.
    Open,
    /// Both seats taken, being played.
    Live,
    /// Over.
    Finished,
}

impl Status {
    /// The status as stored and listed.
    pub fn as_str(self) -> &'static str {
        match self {
            Status::Open => "open",
            Status::Live => "live",
            Status::Finished => "finished",
        }
    }

    /// Reads a status written by [`Status::as_str`].
    pub fn parse(s: &str) -> Option<Status> {
        match s {
            "open" => Some(Status::Open),
            "live" => Some(Status::Live),
            "finished" => Some(Status::Finished),
            _ => None,
        }
    }
}

/// A match's turn clock. A live match gives the seat that must act (the
/// shooter, or Black for a pie decision) a deadline; a seat that misses it
/// gets a strike and the session acts for it: declines the pie swap, or
/// passes the turn (the game's pass move: nothing moves, the other side
/// shoots). [`STRIKES_TO_FORFEIT`] strikes in a row forfeit the match.
/// Acting in time clears the seat's strikes.
#[derive(Clone, Debug)]
pub struct TurnClock {
    turn: Duration,
    deadline: Option<(Seat, Moment)>,
    strikes: [u32; 2],
}

impl TurnClock {
    /// A stopped clock allowing `turn` for each turn.
    pub fn new(turn: Duration) -> TurnClock {
        TurnClock {
            turn,
            deadline: None,
            strikes: [0, 0],
        }
    }

    /// The time allowed for one turn.
    pub fn turn(&self) -> Duration {
        self.turn
    }

    /// Starts the clock for `seat` at `now` (`None` stops it).
    pub fn start(&mut self, seat: Option<Seat>, now: Moment) {
        self.deadline = seat.map(|s| (s, now + self.turn));
    }

    /// Who must act by when.
    pub fn deadline(&self) -> Option<(Seat, Moment)> {
        self.deadline
    }

    /// `seat` acted in time.
    pub fn acted(&mut self, seat: Seat) {
        self.strikes[seat.index()] = 0;
    }

    /// `seat` timed out: its strikes in a row, now.
    pub fn strike(&mut self, seat: Seat) -> u32 {
        self.deadline = None;
        let s = &mut self.strikes[seat.index()];
        *s += 1;
        *s
    }
}

/// The turn clocks a match may have, in seconds.
pub const TURN_SECONDS: std::ops::RangeInclusive<u64> = 1..=3600;

/// `seconds` if it is a turn clock a match may have ([`TURN_SECONDS`]),
/// else `bad-config`.
pub fn check_turn_seconds(seconds: u64) -> Result<u64, Refusal> {
    if TURN_SECONDS.contains(&seconds) {
        Ok(seconds)
    } else {
        Err(Refusal::new(
            ErrorCode::BadConfig,
            "turn_seconds must be between 1 and 3600",
        ))
    }
}

/// The seat that must act now, if any.
pub fn to_act(game: &Game) -> Option<Seat> {
    match game.phase() {
        Phase::Over { .. } => None,
        Phase::PieDecision => Some(game.seat_of(Side::Black)),
        Phase::Shooting => game.to_shoot().map(|s| game.seat_of(s)),
    }
}

/// Who holds a seat: a person (by name and token), a built-in bot, or
/// nobody yet.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SeatSpec {
    /// The player's name.
    pub name: Option<String>,
    /// The hash of the seat token (`None`: an empty seat, or a bot's).
    pub token: Option<TokenHash>,
    /// The level of the built-in bot playing the seat (`"easy"`,
    /// `"medium"`: the bot's own business), if one does.
    pub bot: Option<String>,
}

impl SeatSpec {
    fn taken(&self) -> bool {
        self.token.is_some() || self.bot.is_some()
    }
}

/// The times and sizes a session works with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SessionLimits {
    /// The time allowed for one turn.
    pub turn: Duration,
    /// How long a dropped player keeps the seat.
    pub grace: Duration,
    /// How long a built-in bot waits before it acts. Zero means at once,
    /// always (tests, tournaments); otherwise, while anyone watches two bots
    /// play, each waits for the last shot's film and [`WATCHED_PAUSE`].
    pub bot_delay: Duration,
    /// How long a match that is not live stays with nobody connected.
    pub idle: Duration,
    /// Connections admitted at once.
    pub max_connections_per_match: usize,
}

/// Who a message is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum To {
    /// Every connection admitted.
    All,
    /// Every connection but this one.
    AllBut(ConnId),
    /// This connection alone.
    Only(ConnId),
}

impl To {
    /// Whether `conn` gets the message.
    pub fn includes(self, conn: ConnId) -> bool {
        match self {
            To::All => true,
            To::AllBut(skip) => conn != skip,
            To::Only(only) => conn == only,
        }
    }
}

/// What a refusal answers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Request {
    /// [`Input::Connect`] of this connection: it is not admitted.
    Connect(ConnId),
    /// [`Input::Join`].
    Join,
    /// A message from this connection (or its rematch, which could not be
    /// created): answer it with the refusal's `error` message.
    Message(ConnId),
    /// The built-in bot's move for this seat.
    Bot(Seat),
    /// A move the session made for a seat (a timeout, an abandoned seat).
    Clock,
}

/// The match row as it stands after a move, stored with the move.
#[derive(Clone, Debug, PartialEq)]
pub struct AfterMove {
    /// The match's status.
    pub status: Status,
    /// Shots played so far.
    pub shots: u32,
    /// The result, once the match is over.
    pub result: Option<MatchResult>,
    /// The seat that won, once the match is over and was not drawn (the
    /// pie rule may have given the first seat Black).
    pub winner: Option<Seat>,
}

/// What a built-in bot decided to do.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BotDecision {
    /// Play this shot.
    Shot(Shot),
    /// Decide the pie rule.
    Pie {
        /// Take the other side.
        swap: bool,
    },
    /// Give up (the bot found nothing to do).
    Resign,
    /// No answer (a hosted bot that ran out of fuel or failed): the turn
    /// times out at once, as a refused bot move does.
    NoAnswer,
}

/// What happens to a session.
#[derive(Clone, Debug)]
pub enum Input {
    /// A connection asks to be admitted, with a seat token or as a
    /// spectator.
    Connect {
        /// The connection, named by the driver.
        conn: ConnId,
        /// The seat token presented.
        token: Option<SeatToken>,
        /// The name it said hello with: a spectator chats under it, once
        /// held to the rule of names ([`spectator_name`]).
        name: String,
    },
    /// A connection the driver has proved to play `seat` another way
    /// (the key of the account holding it) asks to be admitted to it.
    ConnectSeat {
        /// The connection, named by the driver.
        conn: ConnId,
        seat: Seat,
    },
    /// A connection closed.
    Disconnect {
        /// The connection.
        conn: ConnId,
    },
    /// A connection sent a match message.
    Message {
        /// The sender.
        conn: ConnId,
        /// What it said.
        msg: ClientMessage,
    },
    /// Someone takes the empty second seat.
    Join {
        /// The player's name.
        name: String,
        /// The hash of the seat token made for them.
        token: TokenHash,
    },
    /// The deadline of [`Session::next_deadline`] has passed.
    Timer,
    /// A built-in bot's decision, asked for by [`Effect::BotToAct`].
    BotMove {
        /// The bot's seat.
        seat: Seat,
        /// The `at_move` of the request it answers.
        at_move: usize,
        /// What the bot does.
        decision: BotDecision,
    },
    /// The rematch of [`Effect::CreateRematch`] exists.
    RematchCreated {
        /// The new match.
        match_id: String,
    },
    /// The rematch of [`Effect::CreateRematch`] could not be created.
    RematchFailed {
        /// Why, for whoever asked for it.
        refusal: Refusal,
    },
    /// An [`Effect::Store`] failed; the store is the truth, so here is the
    /// match replayed from it (`None`: it cannot be read back; the session
    /// closes).
    StoreFailed {
        /// The match as stored.
        reloaded: Option<Box<Game>>,
    },
    /// An [`Effect::StoreJoin`] failed: the second seat stays empty.
    JoinFailed,
}

/// What a session asks its driver to do, in order.
#[derive(Clone, Debug)]
pub enum Effect {
    /// The connection is admitted (holding `seat`, or watching); its
    /// first messages follow as `Send`s.
    Admitted {
        /// The connection.
        conn: ConnId,
        /// Its seat.
        seat: Option<Seat>,
    },
    /// The join is taken: its seat (once its [`Effect::StoreJoin`] is done).
    Joined {
        /// The seat taken.
        seat: Seat,
    },
    /// A request is refused; nothing changed.
    Refused {
        /// What is refused.
        request: Request,
        /// Why.
        refusal: Refusal,
    },
    /// A message to connections.
    Send {
        /// Who gets it.
        to: To,
        /// The message.
        msg: ServerMessage,
    },
    /// Store move number `index`, with the match row as it is after it,
    /// durably, before delivering any later `Send`.
    Store {
        /// The move's index in the record.
        index: usize,
        /// The move.
        mv: RecordedMove,
        /// The match row after it.
        after: AfterMove,
    },
    /// Store the second seat's player, durably, before going on.
    StoreJoin {
        /// The player's name.
        name: String,
        /// The hash of the seat token.
        token: TokenHash,
    },
    /// Create the rematch of this match; answer with
    /// [`Input::RematchCreated`] or [`Input::RematchFailed`].
    CreateRematch {
        /// The configuration (the same as this match's).
        config: Config,
        /// The time allowed for one turn.
        turn: Duration,
        /// This match's seats (the rematch exchanges the players').
        seats: [SeatSpec; 2],
    },
    /// A built-in bot is to act: compute its decision from this public
    /// view (never the game itself, which holds the seed: a built-in bot
    /// knows no more than a player) and answer with [`Input::BotMove`].
    BotToAct {
        /// The bot's seat.
        seat: Seat,
        /// The side it acts for.
        side: Side,
        /// The bot's level.
        level: String,
        /// Moves played when asked (an answer for another is stale).
        at_move: usize,
        /// What any player may know of the match now.
        view: Box<MatchView>,
    },
    /// The match's status changed (or, after a failed write, is restated).
    Status(Status),
    /// Nobody has watched this match, not live, for the idle time: it can
    /// leave memory.
    Close,
}

/// One seat of a match in play.
#[derive(Clone, Debug, Default)]
struct SeatState {
    spec: SeatSpec,
    /// Open connections holding this seat.
    conns: usize,
    /// When a dropped player's seat is forfeited.
    away_until: Option<Moment>,
}

/// A move the session applies (from a player, a bot or the clock).
#[derive(Clone, Copy, Debug)]
enum Action {
    Shot(Side, Shot),
    Pie(Side, bool),
    Resign(Side),
    /// The turn clock ran out: the turn passes.
    Pass(Side),
    Forfeit(Side, ForfeitReason),
}

const SEATS: [Seat; 2] = [Seat::First, Seat::Second];

fn status_of(game: &Game, seats: &[SeatState; 2]) -> Status {
    if game.is_over() {
        Status::Finished
    } else if seats.iter().all(|s| s.spec.taken()) {
        Status::Live
    } else {
        Status::Open
    }
}

/// What a spectator who said hello with `raw` is called in the chat: the
/// name held to the rule of names ([`crate::name::seat_name`]: normalised, no
/// invisible or reordering characters, nothing that passes for the
/// computer), or "spectator" where it breaks the rule.
pub fn spectator_name(raw: &str) -> String {
    crate::name::seat_name(raw).unwrap_or_else(|_| SPECTATOR.to_string())
}

/// A spectator's name when the one it gave breaks the rule of names.
pub const SPECTATOR: &str = "spectator";

fn not_seated() -> Refusal {
    Refusal::new(
        ErrorCode::NotInMatch,
        "spectators cannot do that; connect with a seat token",
    )
}

/// A match being played, without I/O (see the module doc).
#[derive(Clone, Debug)]
pub struct Session {
    match_id: String,
    game: Game,
    seats: [SeatState; 2],
    /// The connections admitted, and the seat each holds.
    conns: BTreeMap<ConnId, Option<Seat>>,
    /// The spectators' names, for their chat.
    spectators: BTreeMap<ConnId, String>,
    limits: SessionLimits,
    clock: TurnClock,
    status: Status,
    rematch_offer: Option<Seat>,
    rematch: Option<String>,
    /// A rematch being created, and the connection that asked for it.
    rematch_pending: Option<ConnId>,
    /// When the bot that must act is asked for its move.
    bot_at: Option<Moment>,
    /// How long the film of the last shot lasts.
    last_film: Duration,
    /// The bot asked for its move, and the moves played when asked.
    bot_asked: Option<(Seat, usize)>,
    /// Since when nobody has been connected.
    idle_since: Option<Moment>,
    closed: bool,
    out: Vec<Effect>,
}

impl Session {
    /// A session for match `match_id`, whose record has been replayed into
    /// `game`, starting at `now`.
    pub fn new(
        match_id: impl Into<String>,
        game: Game,
        seats: [SeatSpec; 2],
        limits: SessionLimits,
        now: Moment,
    ) -> Session {
        let seats = seats.map(|spec| SeatState {
            spec,
            ..SeatState::default()
        });
        let status = status_of(&game, &seats);
        let mut session = Session {
            match_id: match_id.into(),
            game,
            seats,
            conns: BTreeMap::new(),
            spectators: BTreeMap::new(),
            limits,
            clock: TurnClock::new(limits.turn),
            status,
            rematch_offer: None,
            rematch: None,
            rematch_pending: None,
            bot_at: None,
            last_film: Duration::ZERO,
            bot_asked: None,
            idle_since: Some(now),
            closed: false,
            out: Vec::new(),
        };
        // Nobody is connected yet: the clock's first message goes nowhere.
        session.schedule(now);
        session.out.clear();
        session
    }

    /// The match's id.
    pub fn match_id(&self) -> &str {
        &self.match_id
    }

    /// The game as it stands.
    pub fn game(&self) -> &Game {
        &self.game
    }

    /// The match's status.
    pub fn status(&self) -> Status {
        self.status
    }

    /// The seats' holders.
    pub fn seats(&self) -> [SeatSpec; 2] {
        self.seats.clone().map(|s| s.spec)
    }

    /// The players' names as shown (a bot as `bot (level)`).
    pub fn players(&self) -> Players {
        let name = |s: &SeatState| match &s.spec.bot {
            Some(level) => Some(format!("bot ({level})")),
            None => s.spec.name.clone(),
        };
        Players {
            first: name(&self.seats[0]),
            second: name(&self.seats[1]),
        }
    }

    /// Connections admitted.
    pub fn connections(&self) -> usize {
        self.conns.len()
    }

    /// Whether the session has closed ([`Effect::Close`]); it ignores
    /// every input from then on.
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// When the driver must come back with [`Input::Timer`], if ever.
    pub fn next_deadline(&self) -> Option<Moment> {
        if self.closed {
            return None;
        }
        [
            self.clock.deadline().map(|(_, d)| d),
            self.bot_at,
            self.seats[0].away_until,
            self.seats[1].away_until,
            self.idle_deadline(),
        ]
        .into_iter()
        .flatten()
        .min()
    }

    /// Handles `input`, which happened at `now`: what to do about it, in
    /// order.
    pub fn handle(&mut self, input: Input, now: Moment) -> Vec<Effect> {
        if self.closed {
            return Vec::new();
        }
        match input {
            Input::Connect { conn, token, name } => self.connect(conn, token, name, now),
            Input::ConnectSeat { conn, seat } => self.admit(conn, Some(seat), now),
            Input::Disconnect { conn } => self.disconnect(conn, now),
            Input::Message { conn, msg } => {
                if let Err(refusal) = self.message(conn, msg, now) {
                    self.refuse(Request::Message(conn), refusal);
                }
            }
            Input::Join { name, token } => {
                if let Err(refusal) = self.join(name, token, now) {
                    self.refuse(Request::Join, refusal);
                }
            }
            Input::Timer => self.timer(now),
            Input::BotMove {
                seat,
                at_move,
                decision,
            } => self.bot_move(seat, at_move, decision, now),
            Input::RematchCreated { match_id } => {
                self.rematch_pending = None;
                self.rematch_offer = None;
                self.rematch = Some(match_id.clone());
                self.broadcast(ServerMessage::RematchStarted { match_id });
            }
            Input::RematchFailed { refusal } => {
                if let Some(conn) = self.rematch_pending.take() {
                    self.refuse(Request::Message(conn), refusal);
                }
            }
            Input::StoreFailed { reloaded } => match reloaded {
                Some(game) => {
                    self.game = *game;
                    self.restate(now);
                }
                None => {
                    self.closed = true;
                    self.out.push(Effect::Close);
                }
            },
            Input::JoinFailed => {
                let second = &mut self.seats[Seat::Second.index()].spec;
                second.name = None;
                second.token = None;
                self.restate(now);
            }
        }
        // A call that asked for a write does not close for idleness: the
        // write may yet fail, and the session must be there to hear it
        // (its deadline, already past, fires on the next timer).
        let writes = self
            .out
            .iter()
            .any(|e| matches!(e, Effect::Store { .. } | Effect::StoreJoin { .. }));
        if !self.closed && !writes && self.idle_deadline().is_some_and(|t| t <= now) {
            self.closed = true;
            self.out.push(Effect::Close);
        }
        std::mem::take(&mut self.out)
    }

    // ----- effects -----

    fn send(&mut self, to: To, msg: ServerMessage) {
        self.out.push(Effect::Send { to, msg });
    }

    fn broadcast(&mut self, msg: ServerMessage) {
        self.send(To::All, msg);
    }

    fn refuse(&mut self, request: Request, refusal: Refusal) {
        self.out.push(Effect::Refused { request, refusal });
    }

    fn set_status(&mut self, status: Status) {
        if status != self.status {
            self.status = status;
            self.out.push(Effect::Status(status));
        }
    }

    /// After a failed write: the status as the store's match has it, said
    /// again, and the clock restarted for whoever must act.
    fn restate(&mut self, now: Moment) {
        self.status = status_of(&self.game, &self.seats);
        self.out.push(Effect::Status(self.status));
        self.bot_at = None;
        self.bot_asked = None;
        self.schedule(now);
    }

    fn idle_deadline(&self) -> Option<Moment> {
        if self.status != Status::Live && self.conns.is_empty() {
            self.idle_since.map(|t| t + self.limits.idle)
        } else {
            None
        }
    }

    // ----- connections -----

    fn state_for(&self, you: Option<Seat>) -> ServerMessage {
        ServerMessage::MatchState {
            match_id: self.match_id.clone(),
            you,
            players: self.players(),
            view: self.game.view(),
        }
    }

    fn clock_message(&self, now: Moment) -> Option<ServerMessage> {
        let (seat, deadline) = self.clock.deadline()?;
        Some(ServerMessage::Clock {
            seat,
            side: self.game.side_of(seat),
            remaining_ms: deadline.saturating_since(now).as_millis() as u64,
        })
    }

    fn seat_of_token(&self, token: &SeatToken) -> Option<Seat> {
        SEATS.into_iter().find(|s| {
            self.seats[s.index()]
                .spec
                .token
                .is_some_and(|mine| mine.matches(token))
        })
    }

    fn connect(&mut self, conn: ConnId, token: Option<SeatToken>, name: String, now: Moment) {
        let seat = match token {
            None => {
                self.admit(conn, None, now);
                if self.conns.contains_key(&conn) {
                    self.spectators.insert(conn, spectator_name(&name));
                }
                return;
            }
            Some(t) => match self.seat_of_token(&t) {
                Some(seat) => Some(seat),
                None => {
                    return self.refuse(
                        Request::Connect(conn),
                        Refusal::new(
                            ErrorCode::BadToken,
                            "this token holds no seat in this match",
                        ),
                    )
                }
            },
        };
        self.admit(conn, seat, now);
    }

    /// Admits `conn` to `seat` (none: to watch), whose right to it is
    /// settled.
    fn admit(&mut self, conn: ConnId, seat: Option<Seat>, now: Moment) {
        if self.conns.contains_key(&conn) {
            // The driver names each connection once.
            return self.refuse(Request::Connect(conn), Refusal::internal());
        }
        if self.conns.len() >= self.limits.max_connections_per_match {
            return self.refuse(
                Request::Connect(conn),
                Refusal::new(
                    ErrorCode::ServerBusy,
                    "this match has as many watchers as it can take",
                ),
            );
        }
        self.out.push(Effect::Admitted { conn, seat });
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
        for msg in first {
            self.send(To::Only(conn), msg);
        }
        self.conns.insert(conn, seat);
        self.idle_since = None;
        if let Some(s) = seat {
            let st = &mut self.seats[s.index()];
            st.conns += 1;
            if st.conns == 1 && st.away_until.take().is_some() {
                self.send(To::AllBut(conn), ServerMessage::PlayerBack { seat: s });
            }
        }
    }

    fn disconnect(&mut self, conn: ConnId, now: Moment) {
        let Some(seat) = self.conns.remove(&conn) else {
            return;
        };
        self.spectators.remove(&conn);
        if self.conns.is_empty() {
            self.idle_since = Some(now);
        }
        let Some(seat) = seat else {
            return;
        };
        let grace = self.limits.grace;
        let st = &mut self.seats[seat.index()];
        st.conns = st.conns.saturating_sub(1);
        if st.conns == 0 && self.status == Status::Live {
            st.away_until = Some(now + grace);
            self.broadcast(ServerMessage::PlayerLeft {
                seat,
                grace_ms: grace.as_millis() as u64,
            });
        }
    }

    /// Says `text` (a quick `phrase`'s words) from `conn` to everyone
    /// connected: under its seat's name from a seat, under the name it
    /// said hello with from a spectator.
    fn chat(
        &mut self,
        conn: ConnId,
        seat: Option<Seat>,
        text: String,
        phrase: Option<Phrase>,
    ) -> Result<(), Refusal> {
        let name = match seat {
            Some(seat) => {
                let players = self.players();
                match seat {
                    Seat::First => players.first,
                    Seat::Second => players.second,
                }
                .unwrap_or_else(|| match seat {
                    Seat::First => "first".into(),
                    Seat::Second => "second".into(),
                })
            }
            None => {
                let name = self.spectators.get(&conn).ok_or_else(not_seated)?;
                // A spectator never chats under a name that passes for a
                // player's: its lines would read as the player's own.
                let players = self.players();
                let impostor = [players.first, players.second]
                    .iter()
                    .flatten()
                    .any(|player| crate::name::passes_for(name, player));
                if impostor {
                    SPECTATOR.to_string()
                } else {
                    name.clone()
                }
            }
        };
        self.broadcast(ServerMessage::Chat {
            from: seat,
            name,
            text,
            phrase,
        });
        Ok(())
    }

    fn join(&mut self, name: String, token: TokenHash, now: Moment) -> Result<(), Refusal> {
        if self.game.is_over() {
            return Err(Refusal::new(ErrorCode::MatchOver, "the match is over"));
        }
        if self.seats[Seat::Second.index()].spec.taken() {
            return Err(Refusal::new(
                ErrorCode::MatchFull,
                "both seats of this match are taken",
            ));
        }
        self.out.push(Effect::StoreJoin {
            name: name.clone(),
            token,
        });
        let second = &mut self.seats[Seat::Second.index()].spec;
        second.name = Some(name.clone());
        second.token = Some(token);
        self.set_status(status_of(&self.game, &self.seats));
        self.out.push(Effect::Joined { seat: Seat::Second });
        self.broadcast(ServerMessage::PlayerJoined {
            seat: Seat::Second,
            name,
        });
        self.schedule(now);
        Ok(())
    }

    // ----- client messages -----

    fn message(&mut self, conn: ConnId, msg: ClientMessage, now: Moment) -> Result<(), Refusal> {
        let seat = self.conns.get(&conn).copied().flatten();
        match msg {
            ClientMessage::Shot { piece, velocity } => {
                let seat = seat.ok_or_else(not_seated)?;
                if self.status == Status::Open {
                    return Err(Refusal::new(
                        ErrorCode::NotYourTurn,
                        "waiting for an opponent to join",
                    ));
                }
                let side = self.game.side_of(seat);
                let shot = Shot::new(piece, velocity, self.game.config())?;
                self.game.check(side, &shot)?;
                self.apply(Action::Shot(side, shot), Vec::new(), now)?;
                self.clock.acted(seat);
            }
            ClientMessage::PieDecision { swap } => {
                let seat = seat.ok_or_else(not_seated)?;
                let side = self.game.side_of(seat);
                self.apply(Action::Pie(side, swap), Vec::new(), now)?;
                self.clock.acted(seat);
            }
            ClientMessage::Resign => {
                let seat = seat.ok_or_else(not_seated)?;
                let side = self.game.side_of(seat);
                self.apply(Action::Resign(side), Vec::new(), now)?;
            }
            ClientMessage::Chat { text } => {
                if text.chars().count() > MAX_CHAT_CHARS {
                    return Err(Refusal::new(
                        ErrorCode::ChatTooLong,
                        format!("chat messages are at most {MAX_CHAT_CHARS} characters"),
                    ));
                }
                self.chat(conn, seat, text, None)?;
            }
            ClientMessage::Phrase { phrase } => {
                self.chat(conn, seat, phrase.english().to_string(), Some(phrase))?;
            }
            ClientMessage::OfferRematch => {
                let seat = seat.ok_or_else(not_seated)?;
                if !self.game.is_over() {
                    return Err(Refusal::new(
                        ErrorCode::MatchNotOver,
                        "a rematch can be offered once the match is over",
                    ));
                }
                if let Some(id) = self.rematch.clone() {
                    self.send(
                        To::Only(conn),
                        ServerMessage::RematchStarted { match_id: id },
                    );
                    return Ok(());
                }
                self.rematch_offer = Some(seat);
                self.broadcast(ServerMessage::RematchOffered { by: seat });
                if self.seats[seat.other().index()].spec.bot.is_some() {
                    self.start_rematch(conn);
                }
            }
            ClientMessage::AcceptRematch => {
                let seat = seat.ok_or_else(not_seated)?;
                match self.rematch_offer {
                    Some(by) if by != seat => self.start_rematch(conn),
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
                    "matches are created and joined over HTTP (see /api)",
                ))
            }
        }
        Ok(())
    }

    /// Asks the driver for the rematch (once), on behalf of `conn`.
    fn start_rematch(&mut self, conn: ConnId) {
        if self.rematch_pending.is_some() {
            return;
        }
        self.rematch_pending = Some(conn);
        self.out.push(Effect::CreateRematch {
            config: self.game.config().clone(),
            turn: self.clock.turn(),
            seats: self.seats(),
        });
    }

    // ----- moves -----

    /// Plays `action` on the game, then says so: the move to store, the
    /// status after it, `announce` (what led to it), the move itself, the
    /// result if the match is over, and the next turn's clock. A refused
    /// move changes nothing and says nothing.
    fn apply(
        &mut self,
        action: Action,
        announce: Vec<ServerMessage>,
        now: Moment,
    ) -> Result<(), Refusal> {
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
        let moves = &self.game.record().moves;
        let Some(mv) = moves.last().cloned() else {
            return Err(Refusal::internal());
        };
        let status = status_of(&self.game, &self.seats);
        let result = self.game.result();
        self.out.push(Effect::Store {
            index: moves.len() - 1,
            mv,
            after: AfterMove {
                status,
                shots: self.game.shots(),
                winner: result
                    .as_ref()
                    .and_then(MatchResult::winner)
                    .map(|side| self.game.seat_of(side)),
                result,
            },
        });
        self.set_status(status);
        for msg in announce {
            self.broadcast(msg);
        }
        match (action, played) {
            (Action::Shot(..), Some(played)) => {
                let film = played.film.duration();
                self.last_film = if film.is_finite() && film > 0.0 {
                    Duration::from_secs_f64(film).min(LONGEST_FILM)
                } else {
                    Duration::ZERO
                };
                let view = self.game.view();
                self.broadcast(ServerMessage::shot_played(played, view))
            }
            (Action::Pie(_, swap), _) => self.broadcast(ServerMessage::PieDecided { swap }),
            (Action::Pass(side), _) => self.broadcast(ServerMessage::TurnPassed { side }),
            _ => {}
        }
        if let Some(result) = result {
            self.broadcast(ServerMessage::MatchOver {
                result,
                record: self.game.record().clone(),
            });
        }
        self.schedule(now);
        Ok(())
    }

    /// Restarts the turn clock (or arms the bot) for whoever must act.
    fn schedule(&mut self, now: Moment) {
        let acting = if self.status == Status::Live {
            to_act(&self.game)
        } else {
            None
        };
        match acting {
            Some(seat) if self.seats[seat.index()].spec.bot.is_some() => {
                self.clock.start(None, now);
                let at_move = self.game.record().moves.len();
                if self.bot_asked != Some((seat, at_move)) {
                    self.bot_asked = None;
                    if self.bot_at.is_none() {
                        self.bot_at = Some(now + self.bot_delay());
                    }
                }
            }
            Some(seat) => {
                self.bot_at = None;
                self.bot_asked = None;
                self.clock.start(Some(seat), now);
                if let Some(m) = self.clock_message(now) {
                    self.broadcast(m);
                }
            }
            None => {
                self.bot_at = None;
                self.bot_asked = None;
                self.clock.start(None, now);
            }
        }
    }

    /// How long the bot that must act waits: the film of the last shot and
    /// a pause when people watch two bots play (unless the delay is zero),
    /// else the configured delay.
    fn bot_delay(&self) -> Duration {
        let exhibition = self.seats.iter().all(|s| s.spec.bot.is_some());
        let paced = !self.limits.bot_delay.is_zero();
        if paced && exhibition && !self.conns.is_empty() {
            self.limits.bot_delay.max(self.last_film + WATCHED_PAUSE)
        } else {
            self.limits.bot_delay
        }
    }

    /// The side the seat that must act acts for (Black for a pie decision).
    fn acting_side(&self, seat: Seat) -> Side {
        match self.game.phase() {
            Phase::PieDecision => Side::Black,
            _ => self.game.side_of(seat),
        }
    }

    fn timer(&mut self, now: Moment) {
        if let Some((seat, deadline)) = self.clock.deadline() {
            if deadline <= now {
                self.timed_out(seat, now);
            }
        }
        if self.bot_at.is_some_and(|t| t <= now) {
            self.bot_at = None;
            self.ask_bot();
        }
        for seat in SEATS {
            if self.seats[seat.index()]
                .away_until
                .is_some_and(|t| t <= now)
            {
                self.seats[seat.index()].away_until = None;
                self.abandoned(seat, now);
            }
        }
    }

    fn ask_bot(&mut self) {
        let Some(seat) = to_act(&self.game) else {
            return;
        };
        let Some(level) = self.seats[seat.index()].spec.bot.clone() else {
            return;
        };
        let at_move = self.game.record().moves.len();
        self.bot_asked = Some((seat, at_move));
        self.out.push(Effect::BotToAct {
            seat,
            side: self.acting_side(seat),
            level,
            at_move,
            view: Box::new(self.game.view()),
        });
    }

    fn bot_move(&mut self, seat: Seat, at_move: usize, decision: BotDecision, now: Moment) {
        let current = self.game.record().moves.len();
        if self.bot_asked != Some((seat, at_move))
            || current != at_move
            || to_act(&self.game) != Some(seat)
        {
            // Stale: the turn it was for has passed.
            return;
        }
        self.bot_asked = None;
        let side = self.acting_side(seat);
        let action = match decision {
            BotDecision::Shot(shot) => Action::Shot(side, shot),
            BotDecision::Pie { swap } => Action::Pie(side, swap),
            BotDecision::Resign => Action::Resign(side),
            BotDecision::NoAnswer => return self.timed_out(seat, now),
        };
        if let Err(refusal) = self.apply(action, Vec::new(), now) {
            self.refuse(Request::Bot(seat), refusal);
            // A bot seat has no clock to run out: a move the game refuses
            // counts as a timeout at once, so the match never waits on it
            // (three in a row forfeit, as for a person).
            self.timed_out(seat, now);
        }
    }

    fn timed_out(&mut self, seat: Seat, now: Moment) {
        let strikes = self.clock.strike(seat);
        let side = self.game.side_of(seat);
        let mut announce = vec![ServerMessage::TurnTimedOut { seat, strikes }];
        let action = if strikes >= STRIKES_TO_FORFEIT {
            announce.push(ServerMessage::Forfeited {
                seat,
                reason: ForfeitReason::Timeouts,
            });
            Action::Forfeit(side, ForfeitReason::Timeouts)
        } else if self.game.phase() == Phase::PieDecision {
            Action::Pie(Side::Black, false)
        } else {
            Action::Pass(side)
        };
        if let Err(refusal) = self.apply(action, announce.clone(), now) {
            for msg in announce {
                self.broadcast(msg);
            }
            self.refuse(Request::Clock, refusal);
            self.schedule(now);
        }
    }

    fn abandoned(&mut self, seat: Seat, now: Moment) {
        if self.status != Status::Live || self.seats[seat.index()].conns > 0 {
            return;
        }
        let side = self.game.side_of(seat);
        let announce = vec![ServerMessage::Forfeited {
            seat,
            reason: ForfeitReason::Abandoned,
        }];
        let action = Action::Forfeit(side, ForfeitReason::Abandoned);
        if let Err(refusal) = self.apply(action, announce, now) {
            self.refuse(Request::Clock, refusal);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::piece::PieceId;
    use glam::DVec2;

    const A: ConnId = ConnId(1);
    const B: ConnId = ConnId(2);
    const WATCHER: ConnId = ConnId(3);

    fn at(ms: u64) -> Moment {
        Moment::from_millis(ms)
    }

    fn limits() -> SessionLimits {
        SessionLimits {
            turn: Duration::from_millis(10_000),
            grace: Duration::from_millis(5_000),
            bot_delay: Duration::from_millis(500),
            idle: Duration::from_millis(60_000),
            max_connections_per_match: 4,
        }
    }

    fn person(name: &str, token: &str) -> SeatSpec {
        SeatSpec {
            name: Some(name.into()),
            token: Some(TokenHash::of(token)),
            bot: None,
        }
    }

    fn bot(level: &str) -> SeatSpec {
        SeatSpec {
            bot: Some(level.into()),
            ..SeatSpec::default()
        }
    }

    fn session_with(config: Config, second: SeatSpec) -> Session {
        let game = Game::new(config, 7).unwrap();
        let seats = [person("Petka", "tok-a"), second];
        Session::new("m1", game, seats, limits(), at(0))
    }

    /// A live match between two people, both connected at 0.
    fn live() -> Session {
        live_with(Config::default())
    }

    fn live_with(config: Config) -> Session {
        let mut s = session_with(config, person("Anka", "tok-b"));
        connect(&mut s, A, Some("tok-a"), 0);
        connect(&mut s, B, Some("tok-b"), 0);
        s
    }

    fn connect(s: &mut Session, conn: ConnId, token: Option<&str>, ms: u64) -> Vec<Effect> {
        let token = token.map(SeatToken::new);
        let name = if token.is_some() { "" } else { "Furmanov" }.to_string();
        s.handle(Input::Connect { conn, token, name }, at(ms))
    }

    fn say(s: &mut Session, conn: ConnId, msg: ClientMessage, ms: u64) -> Vec<Effect> {
        s.handle(Input::Message { conn, msg }, at(ms))
    }

    /// White's e-piece straight up the board at full power: it knocks
    /// Black's e-piece off, so White shoots again.
    fn knock_off() -> ClientMessage {
        ClientMessage::Shot {
            piece: PieceId::new(Side::White, 4).unwrap(),
            velocity: DVec2::new(0.0, 2.0),
        }
    }

    /// A gentle White shot that hits nothing: the turn passes to Black.
    fn nudge() -> ClientMessage {
        ClientMessage::Shot {
            piece: PieceId::new(Side::White, 0).unwrap(),
            velocity: DVec2::new(0.0, 0.5),
        }
    }

    /// Each effect as a short word: `send:<type>`, `store:<move>`, ….
    fn kinds(effects: &[Effect]) -> Vec<String> {
        effects
            .iter()
            .map(|e| match e {
                Effect::Send { msg, .. } => {
                    let v: serde_json::Value = serde_json::from_str(&msg.to_json()).unwrap();
                    format!("send:{}", v["type"].as_str().unwrap())
                }
                Effect::Store { mv, .. } => {
                    let debug = format!("{mv:?}");
                    let kind: String = debug
                        .chars()
                        .take_while(char::is_ascii_alphabetic)
                        .collect();
                    format!("store:{kind}")
                }
                Effect::Status(s) => format!("status:{}", s.as_str()),
                Effect::Admitted { .. } => "admitted".into(),
                Effect::Joined { .. } => "joined".into(),
                Effect::Refused { refusal, .. } => format!("refused:{}", refusal.code),
                Effect::StoreJoin { .. } => "store-join".into(),
                Effect::CreateRematch { .. } => "create-rematch".into(),
                Effect::BotToAct { .. } => "bot-to-act".into(),
                Effect::Close => "close".into(),
            })
            .collect()
    }

    fn refusal(effects: &[Effect]) -> Option<(Request, ErrorCode)> {
        effects.iter().find_map(|e| match e {
            Effect::Refused { request, refusal } => Some((*request, refusal.code)),
            _ => None,
        })
    }

    #[test]
    fn the_turn_clock_passes_the_turn_when_it_runs_out_and_the_third_timeout_in_a_row_forfeits() {
        let mut s = live();
        assert_eq!(s.next_deadline(), Some(at(10_000)));
        // First (White) and Second (Black) each time out twice, turn about.
        let mut t = 10_000;
        for round in 1..=2 {
            for seat in [Seat::First, Seat::Second] {
                let e = s.handle(Input::Timer, at(t));
                assert_eq!(
                    kinds(&e),
                    [
                        "store:Pass",
                        "send:turn-timed-out",
                        "send:turn-passed",
                        "send:clock"
                    ],
                    "timeout {round} of {seat:?}"
                );
                assert!(matches!(
                    &e[1],
                    Effect::Send { to: To::All, msg: ServerMessage::TurnTimedOut { seat: s, strikes } }
                        if *s == seat && *strikes == round
                ));
                t += 10_000;
                assert_eq!(s.next_deadline(), Some(at(t)));
            }
        }
        // Not yet: a timer early does nothing.
        assert!(s.handle(Input::Timer, at(t - 1)).is_empty());
        let e = s.handle(Input::Timer, at(t));
        assert_eq!(
            kinds(&e),
            [
                "store:Forfeit",
                "status:finished",
                "send:turn-timed-out",
                "send:forfeited",
                "send:match-over"
            ]
        );
        let Effect::Store { index, mv, after } = &e[0] else {
            unreachable!()
        };
        assert_eq!(*index, 4);
        assert_eq!(
            *mv,
            RecordedMove::Forfeit {
                side: Side::White,
                reason: ForfeitReason::Timeouts
            }
        );
        assert_eq!(after.status, Status::Finished);
        assert!(after.result.is_some());
        assert_eq!(s.status(), Status::Finished);
        assert_eq!(s.next_deadline(), None, "both players are still here");
    }

    #[test]
    fn acting_in_time_clears_the_strikes() {
        let mut s = live();
        // White times out, Black times out, White shoots in time.
        s.handle(Input::Timer, at(10_000));
        s.handle(Input::Timer, at(20_000));
        let e = say(&mut s, A, knock_off(), 21_000);
        assert_eq!(kinds(&e), ["store:Shot", "send:shot-played", "send:clock"]);
        // White shoots again (it knocked a piece off) and times out: the
        // first strike again, not the second.
        let e = s.handle(Input::Timer, at(31_000));
        assert!(e.iter().any(|e| matches!(
            e,
            Effect::Send {
                msg: ServerMessage::TurnTimedOut {
                    seat: Seat::First,
                    strikes: 1
                },
                ..
            }
        )));
    }

    #[test]
    fn a_pending_pie_decision_on_timeout_is_taken_as_keep() {
        let mut config = Config::default();
        config.variants.pie_rule = true;
        let mut s = live_with(config);
        say(&mut s, A, nudge(), 1_000);
        assert_eq!(s.game().phase(), Phase::PieDecision);
        assert_eq!(s.next_deadline(), Some(at(11_000)));
        let e = s.handle(Input::Timer, at(11_000));
        assert_eq!(
            kinds(&e),
            [
                "store:Pie",
                "send:turn-timed-out",
                "send:pie-decided",
                "send:clock"
            ]
        );
        assert!(matches!(
            &e[0],
            Effect::Store {
                mv: RecordedMove::Pie { swap: false },
                ..
            }
        ));
        assert_eq!(s.game().phase(), Phase::Shooting);
        assert!(!s.game().swapped());
    }

    #[test]
    fn a_dropped_players_seat_is_forfeited_as_abandoned_after_the_grace_period() {
        let mut s = live();
        let e = s.handle(Input::Disconnect { conn: B }, at(1_000));
        assert!(matches!(
            &e[..],
            [Effect::Send {
                to: To::All,
                msg: ServerMessage::PlayerLeft {
                    seat: Seat::Second,
                    grace_ms: 5_000
                }
            }]
        ));
        assert_eq!(s.next_deadline(), Some(at(6_000)));
        let e = s.handle(Input::Timer, at(6_000));
        assert_eq!(
            kinds(&e),
            [
                "store:Forfeit",
                "status:finished",
                "send:forfeited",
                "send:match-over"
            ]
        );
        assert!(matches!(
            &e[0],
            Effect::Store {
                mv: RecordedMove::Forfeit {
                    side: Side::Black,
                    reason: ForfeitReason::Abandoned
                },
                ..
            }
        ));
    }

    #[test]
    fn reconnecting_within_the_grace_period_says_player_back_and_forfeits_nothing() {
        let mut s = live();
        s.handle(Input::Disconnect { conn: B }, at(1_000));
        let e = connect(&mut s, ConnId(9), Some("tok-b"), 3_000);
        assert_eq!(
            kinds(&e),
            [
                "admitted",
                "send:match-state",
                "send:clock",
                "send:player-back"
            ]
        );
        assert!(matches!(
            e.last(),
            Some(Effect::Send {
                to: To::AllBut(ConnId(9)),
                msg: ServerMessage::PlayerBack { seat: Seat::Second }
            })
        ));
        // Only the turn clock is left to wait for.
        assert_eq!(s.next_deadline(), Some(at(10_000)));
        assert!(s.handle(Input::Timer, at(6_000)).is_empty());
        assert_eq!(s.status(), Status::Live);
    }

    #[test]
    fn a_rematch_offered_and_accepted_is_created_and_then_started() {
        let mut s = live();
        say(&mut s, A, ClientMessage::Resign, 1_000);
        assert_eq!(s.status(), Status::Finished);
        let e = say(&mut s, B, ClientMessage::AcceptRematch, 1_500);
        assert_eq!(
            refusal(&e),
            Some((Request::Message(B), ErrorCode::NoRematchOffer))
        );
        let e = say(&mut s, A, ClientMessage::OfferRematch, 2_000);
        assert_eq!(kinds(&e), ["send:rematch-offered"]);
        let e = say(&mut s, B, ClientMessage::AcceptRematch, 3_000);
        assert_eq!(kinds(&e), ["create-rematch"]);
        let Effect::CreateRematch { turn, seats, .. } = &e[0] else {
            unreachable!()
        };
        assert_eq!(*turn, limits().turn);
        assert_eq!(seats[1].token, Some(TokenHash::of("tok-b")));
        // Accepting again while it is being created asks for nothing more.
        assert!(say(&mut s, B, ClientMessage::AcceptRematch, 3_100).is_empty());
        let e = s.handle(
            Input::RematchCreated {
                match_id: "m2".into(),
            },
            at(3_200),
        );
        assert!(matches!(
            &e[..],
            [Effect::Send {
                to: To::All,
                msg: ServerMessage::RematchStarted { match_id }
            }] if match_id == "m2"
        ));
        // A late comer hears of it on connecting.
        let e = connect(&mut s, WATCHER, None, 4_000);
        assert_eq!(
            kinds(&e),
            ["admitted", "send:match-state", "send:rematch-started"]
        );
    }

    #[test]
    fn a_rematch_that_cannot_be_created_is_refused_to_whoever_asked() {
        let mut s = live();
        say(&mut s, A, ClientMessage::Resign, 1_000);
        say(&mut s, A, ClientMessage::OfferRematch, 2_000);
        say(&mut s, B, ClientMessage::AcceptRematch, 3_000);
        let busy = Refusal::new(ErrorCode::ServerBusy, "full");
        let e = s.handle(Input::RematchFailed { refusal: busy }, at(3_100));
        assert_eq!(
            refusal(&e),
            Some((Request::Message(B), ErrorCode::ServerBusy))
        );
    }

    #[test]
    fn an_offer_to_a_bot_seat_starts_the_rematch_at_once() {
        let mut s = session_with(Config::default(), bot("easy"));
        connect(&mut s, A, Some("tok-a"), 0);
        say(&mut s, A, ClientMessage::Resign, 1_000);
        let e = say(&mut s, A, ClientMessage::OfferRematch, 2_000);
        assert_eq!(kinds(&e), ["send:rematch-offered", "create-rematch"]);
        let Effect::CreateRematch { seats, .. } = &e[1] else {
            unreachable!()
        };
        assert_eq!(seats[1].bot.as_deref(), Some("easy"));
    }

    #[test]
    fn a_spectator_cannot_shoot_but_chats_under_the_name_it_said_hello_with() {
        let mut s = live();
        connect(&mut s, WATCHER, None, 0);
        let e = say(&mut s, WATCHER, knock_off(), 100);
        assert_eq!(
            refusal(&e),
            Some((Request::Message(WATCHER), ErrorCode::NotInMatch))
        );
        assert_eq!(kinds(&e).len(), 1, "nothing else happens");
        let chat = ClientMessage::Chat { text: "hi".into() };
        let e = say(&mut s, WATCHER, chat, 100);
        assert!(
            matches!(
                &e[..],
                [Effect::Send {
                    to: To::All,
                    msg: ServerMessage::Chat { from: None, name, text, phrase: None }
                }] if name == "Furmanov" && text == "hi"
            ),
            "{e:?}"
        );
        let long = "x".repeat(MAX_CHAT_CHARS + 1);
        let e = say(&mut s, WATCHER, ClientMessage::Chat { text: long }, 120);
        assert_eq!(
            refusal(&e),
            Some((Request::Message(WATCHER), ErrorCode::ChatTooLong))
        );
        assert_eq!(s.game().shots(), 0);
    }

    /// What a spectator connected under `raw` sends when it says "hi" in a
    /// live match: the chat line everyone receives, and its author's seat.
    fn watcher_chats_as(raw: &str) -> (String, Option<Seat>) {
        let mut s = live();
        s.handle(
            Input::Connect {
                conn: WATCHER,
                token: None,
                name: raw.to_string(),
            },
            at(0),
        );
        let e = say(
            &mut s,
            WATCHER,
            ClientMessage::Chat { text: "hi".into() },
            10,
        );
        match &e[..] {
            [Effect::Send {
                msg: ServerMessage::Chat { name, from, .. },
                ..
            }] => (name.clone(), *from),
            _ => panic!("{raw:?}: not one chat line: {e:?}"),
        }
    }

    #[test]
    fn a_spectator_whose_name_breaks_the_rule_chats_as_spectator() {
        for raw in ["bot (hard)", "", "Pet\u{202E}ka", &"x".repeat(41)] {
            assert_eq!(
                watcher_chats_as(raw),
                (SPECTATOR.to_string(), None),
                "{raw:?}"
            );
        }
        assert_eq!(spectator_name(" Ｆurmanov "), "Furmanov");
    }

    #[test]
    fn a_spectator_named_like_a_player_chats_as_spectator() {
        // The players of `live()` are Petka and Anka; the third
        // impostor writes Anka with a Cyrillic "А".
        for raw in ["Anka", "anka", "\u{410}nka", "PETKA"] {
            assert_eq!(
                watcher_chats_as(raw),
                (SPECTATOR.to_string(), None),
                "{raw:?}"
            );
        }
    }

    #[test]
    fn a_quick_phrase_reaches_everyone_with_its_code_and_its_english_words() {
        let mut s = live();
        connect(&mut s, WATCHER, None, 0);
        for (conn, from, name) in [(B, Some(Seat::Second), "Anka"), (WATCHER, None, "Furmanov")] {
            let phrase = ClientMessage::Phrase {
                phrase: Phrase::GoodShot,
            };
            let e = say(&mut s, conn, phrase, 10);
            assert!(
                matches!(
                    &e[..],
                    [Effect::Send {
                        to: To::All,
                        msg: ServerMessage::Chat { from: f, name: n, text, phrase: Some(Phrase::GoodShot) }
                    }] if *f == from && n == name && text == "Good shot!"
                ),
                "{e:?}"
            );
        }
        // A spectator that left says nothing more.
        s.handle(Input::Disconnect { conn: WATCHER }, at(20));
        let e = say(
            &mut s,
            WATCHER,
            ClientMessage::Chat { text: "hi".into() },
            30,
        );
        assert!(e.iter().all(|e| !matches!(
            e,
            Effect::Send {
                msg: ServerMessage::Chat { .. },
                ..
            }
        )));
    }

    #[test]
    fn chat_reaches_everyone_with_the_seats_name_and_a_long_one_is_refused() {
        let mut s = live();
        let e = say(&mut s, B, ClientMessage::Chat { text: "hi".into() }, 10);
        assert!(matches!(
            &e[..],
            [Effect::Send {
                to: To::All,
                msg: ServerMessage::Chat { from: Some(Seat::Second), name, .. }
            }] if name == "Anka"
        ));
        let long = "x".repeat(MAX_CHAT_CHARS + 1);
        let e = say(&mut s, B, ClientMessage::Chat { text: long }, 20);
        assert_eq!(
            refusal(&e),
            Some((Request::Message(B), ErrorCode::ChatTooLong))
        );
    }

    #[test]
    fn a_bad_token_is_refused_and_so_is_a_connection_too_many() {
        let mut s = live();
        let e = connect(&mut s, WATCHER, Some("f".repeat(32).as_str()), 10);
        assert_eq!(kinds(&e), ["refused:bad-token"]);
        assert_eq!(
            refusal(&e),
            Some((Request::Connect(WATCHER), ErrorCode::BadToken))
        );
        assert_eq!(s.connections(), 2);
        connect(&mut s, ConnId(10), None, 20);
        connect(&mut s, ConnId(11), None, 20);
        let e = connect(&mut s, ConnId(12), None, 20);
        assert_eq!(
            refusal(&e),
            Some((Request::Connect(ConnId(12)), ErrorCode::ServerBusy))
        );
        assert_eq!(s.connections(), 4);
    }

    #[test]
    fn the_second_seat_is_joined_after_it_is_stored_and_a_failed_store_leaves_it_empty() {
        let mut s = session_with(Config::default(), SeatSpec::default());
        connect(&mut s, A, Some("tok-a"), 0);
        assert_eq!(s.status(), Status::Open);
        let e = say(&mut s, A, knock_off(), 10);
        assert_eq!(
            refusal(&e),
            Some((Request::Message(A), ErrorCode::NotYourTurn))
        );
        let join = |s: &mut Session, ms| {
            s.handle(
                Input::Join {
                    name: "Anka".into(),
                    token: TokenHash::of("tok-b"),
                },
                at(ms),
            )
        };
        let e = join(&mut s, 100);
        assert_eq!(
            kinds(&e),
            [
                "store-join",
                "status:live",
                "joined",
                "send:player-joined",
                "send:clock"
            ]
        );
        // The store refused: the seat is empty again.
        let e = s.handle(Input::JoinFailed, at(200));
        assert_eq!(kinds(&e), ["status:open"]);
        assert_eq!(s.next_deadline(), None, "no clock while open");
        assert_eq!(kinds(&join(&mut s, 300))[0], "store-join");
        let e = join(&mut s, 400);
        assert_eq!(refusal(&e), Some((Request::Join, ErrorCode::MatchFull)));
        assert!(connect(&mut s, B, Some("tok-b"), 500)
            .iter()
            .any(|e| matches!(
                e,
                Effect::Admitted {
                    seat: Some(Seat::Second),
                    ..
                }
            )));
    }

    #[test]
    fn every_accepted_move_yields_its_store_effect_before_its_broadcast() {
        let mut config = Config::default();
        config.variants.pie_rule = true;
        let mut s = live_with(config);
        let mut batches = vec![
            say(&mut s, A, nudge(), 100),
            say(&mut s, B, ClientMessage::PieDecision { swap: true }, 200),
        ];
        let mut t = 200;
        while s.status() == Status::Live {
            t = s.next_deadline().unwrap().since_epoch().as_millis() as u64;
            batches.push(s.handle(Input::Timer, at(t)));
        }
        batches.push(say(&mut s, A, ClientMessage::Resign, t + 1));
        let mut stored = 0;
        for e in &batches {
            let k = kinds(e);
            let first_store = k.iter().position(|k| k.starts_with("store:"));
            let first_news = k.iter().position(|k| {
                [
                    "send:shot-played",
                    "send:pie-decided",
                    "send:turn-passed",
                    "send:turn-timed-out",
                    "send:forfeited",
                    "send:match-over",
                ]
                .contains(&k.as_str())
            });
            if let Some(news) = first_news {
                assert!(first_store.is_some_and(|st| st < news), "{k:?}");
            }
            for effect in e {
                if let Effect::Store { index, .. } = effect {
                    assert_eq!(*index, stored, "moves are stored in order");
                    stored += 1;
                }
            }
        }
        assert_eq!(stored, s.game().record().moves.len());
        // The resignation after the end was refused, not stored.
        assert_eq!(
            refusal(batches.last().unwrap()),
            Some((Request::Message(A), ErrorCode::MatchOver))
        );
    }

    #[test]
    fn a_failed_store_takes_the_match_back_as_stored() {
        let mut s = live();
        let before = s.game().clone();
        let e = say(&mut s, A, ClientMessage::Resign, 100);
        assert_eq!(s.status(), Status::Finished);
        assert!(matches!(e[0], Effect::Store { index: 0, .. }));
        let e = s.handle(
            Input::StoreFailed {
                reloaded: Some(Box::new(before)),
            },
            at(150),
        );
        assert_eq!(kinds(&e), ["status:live", "send:clock"]);
        assert_eq!(s.status(), Status::Live);
        assert!(!s.game().is_over());
        let e = s.handle(Input::StoreFailed { reloaded: None }, at(200));
        assert_eq!(kinds(&e), ["close"]);
        assert!(s.is_closed());
        assert!(s.handle(Input::Timer, at(300)).is_empty());
    }

    #[test]
    fn a_session_past_its_idle_time_stays_to_hear_about_its_last_write() {
        let mut s = session_with(Config::default(), bot("easy"));
        connect(&mut s, A, Some("tok-a"), 0);
        say(&mut s, A, nudge(), 0);
        s.handle(Input::Disconnect { conn: A }, at(100));
        s.handle(Input::Timer, at(500));
        // The bot resigns long after anyone watched: the match ends, and
        // its last move is still to be written.
        let resign = Input::BotMove {
            seat: Seat::Second,
            at_move: 1,
            decision: BotDecision::Resign,
        };
        let e = s.handle(resign, at(100_000));
        assert_eq!(s.status(), Status::Finished);
        assert!(
            kinds(&e).contains(&"store:Resign".to_string()),
            "{:?}",
            kinds(&e)
        );
        assert!(!s.is_closed(), "not closed before the write is through");
        assert!(s.next_deadline().is_some_and(|t| t <= at(100_000)));
        let e = s.handle(Input::StoreFailed { reloaded: None }, at(100_001));
        assert_eq!(kinds(&e), ["close"]);
    }

    #[test]
    fn a_match_nobody_watches_idles_out_unless_it_is_live() {
        let mut s = session_with(Config::default(), SeatSpec::default());
        assert_eq!(s.next_deadline(), Some(at(60_000)));
        connect(&mut s, A, Some("tok-a"), 1_000);
        assert_eq!(s.next_deadline(), None);
        assert!(s
            .handle(Input::Disconnect { conn: A }, at(2_000))
            .is_empty());
        assert_eq!(s.next_deadline(), Some(at(62_000)));
        assert!(s.handle(Input::Timer, at(61_999)).is_empty());
        assert_eq!(kinds(&s.handle(Input::Timer, at(62_000))), ["close"]);
        assert_eq!(s.next_deadline(), None);
        // A live match stays, watched or not.
        let live = session_with(Config::default(), person("Anka", "tok-b"));
        assert_eq!(
            live.next_deadline(),
            Some(at(10_000)),
            "the turn clock only"
        );
    }

    /// A match between two bots, watched by a spectator or not: the first
    /// bot's shot is played at 5 s; how long after it the second bot is
    /// asked, and how long the shot's film lasts.
    fn second_bot_asked_after(watched: bool) -> (Duration, Duration) {
        let game = Game::new(Config::default(), 7).unwrap();
        let mut s = Session::new("m1", game, [bot("easy"), bot("hard")], limits(), at(0));
        if watched {
            connect(&mut s, A, None, 0);
        }
        let first = s.next_deadline().expect("the first bot is armed");
        let e = s.handle(Input::Timer, first);
        assert_eq!(kinds(&e), ["bot-to-act"]);
        let shot = Shot::new(
            PieceId::new(Side::White, 4).unwrap(),
            DVec2::new(0.0, 2.0),
            s.game().config(),
        )
        .unwrap();
        let answer = Input::BotMove {
            seat: Seat::First,
            at_move: 0,
            decision: BotDecision::Shot(shot),
        };
        let answered = at(5_000);
        let e = s.handle(answer, answered);
        assert_eq!(kinds(&e)[..2], ["store:Shot", "send:shot-played"]);
        let Some(Effect::Send {
            msg: ServerMessage::ShotPlayed { film, .. },
            ..
        }) = e.get(1)
        else {
            panic!("{:?}", kinds(&e))
        };
        let next = s.next_deadline().expect("a bot is armed");
        (
            next.saturating_since(answered),
            Duration::from_secs_f64(film.duration()),
        )
    }

    #[test]
    fn watched_bots_wait_for_each_shots_film_and_a_pause_and_bots_alone_do_not() {
        let (alone, _) = second_bot_asked_after(false);
        assert_eq!(alone, limits().bot_delay);
        let (watched, film) = second_bot_asked_after(true);
        assert!(film > Duration::ZERO);
        assert_eq!(watched, film + WATCHED_PAUSE);
        assert!(watched > alone);
    }

    #[test]
    fn a_bot_seat_is_asked_after_the_bot_delay_and_a_stale_bot_move_is_ignored() {
        let mut s = session_with(Config::default(), bot("medium"));
        assert_eq!(s.players().second.as_deref(), Some("bot (medium)"));
        connect(&mut s, A, Some("tok-a"), 0);
        let e = say(&mut s, A, nudge(), 1_000);
        assert_eq!(
            kinds(&e),
            ["store:Shot", "send:shot-played"],
            "no clock for a bot"
        );
        assert_eq!(s.next_deadline(), Some(at(1_500)));
        assert!(s.handle(Input::Timer, at(1_499)).is_empty());
        let e = s.handle(Input::Timer, at(1_500));
        let [Effect::BotToAct {
            seat,
            side,
            level,
            at_move,
            view,
        }] = &e[..]
        else {
            panic!("{:?}", kinds(&e))
        };
        assert_eq!(
            (*seat, *side, level.as_str(), *at_move),
            (Seat::Second, Side::Black, "medium", 1)
        );
        assert_eq!(view.shots, 1);
        assert_eq!(
            s.next_deadline(),
            None,
            "asked once, waiting for the answer"
        );
        // An answer for another move, or another seat, is stale.
        let shot = Shot::new(
            PieceId::new(Side::Black, 3).unwrap(),
            DVec2::new(0.0, -0.5),
            s.game().config(),
        )
        .unwrap();
        let decision = BotDecision::Shot(shot);
        for (seat, at_move) in [(Seat::Second, 0), (Seat::First, 1)] {
            let stale = Input::BotMove {
                seat,
                at_move,
                decision,
            };
            assert!(s.handle(stale, at(1_600)).is_empty());
        }
        let answer = Input::BotMove {
            seat: Seat::Second,
            at_move: 1,
            decision,
        };
        let e = s.handle(answer.clone(), at(1_700));
        assert_eq!(kinds(&e)[..2], ["store:Shot", "send:shot-played"]);
        assert_eq!(s.game().shots(), 2);
        // The same answer again is stale now.
        assert!(s.handle(answer, at(1_800)).is_empty());
    }

    #[test]
    fn a_bot_move_the_game_refuses_passes_the_turn_like_a_timeout() {
        let mut s = session_with(Config::default(), bot("easy"));
        connect(&mut s, A, Some("tok-a"), 0);
        say(&mut s, A, nudge(), 0);
        s.handle(Input::Timer, at(500));
        // White's piece, for Black: refused.
        let wrong = Shot::new(
            PieceId::new(Side::White, 0).unwrap(),
            DVec2::new(0.0, 0.5),
            s.game().config(),
        )
        .unwrap();
        let answer = Input::BotMove {
            seat: Seat::Second,
            at_move: 1,
            decision: BotDecision::Shot(wrong),
        };
        let e = s.handle(answer, at(600));
        assert_eq!(
            kinds(&e),
            [
                "refused:not-your-piece",
                "store:Pass",
                "send:turn-timed-out",
                "send:turn-passed",
                "send:clock"
            ]
        );
        assert_eq!(
            s.game().to_shoot(),
            Some(Side::White),
            "the turn passed back"
        );
    }

    #[test]
    fn a_bot_answer_after_its_turn_ended_another_way_is_ignored() {
        let mut s = session_with(Config::default(), bot("easy"));
        connect(&mut s, A, Some("tok-a"), 0);
        say(&mut s, A, nudge(), 0);
        s.handle(Input::Timer, at(500));
        // The human resigns while the bot thinks.
        say(&mut s, A, ClientMessage::Resign, 600);
        let late = Input::BotMove {
            seat: Seat::Second,
            at_move: 1,
            decision: BotDecision::Resign,
        };
        assert!(s.handle(late, at(700)).is_empty());
        assert_eq!(s.game().record().moves.len(), 2);
    }

    #[test]
    fn the_session_is_deterministic() {
        let run = || {
            let mut config = Config::default();
            config.variants.pie_rule = true;
            let mut s = live_with(config);
            let mut log = Vec::new();
            let inputs = [
                (
                    100,
                    Input::Message {
                        conn: A,
                        msg: nudge(),
                    },
                ),
                (
                    200,
                    Input::Connect {
                        conn: WATCHER,
                        token: None,
                        name: "Furmanov".into(),
                    },
                ),
                (
                    300,
                    Input::Message {
                        conn: B,
                        msg: ClientMessage::PieDecision { swap: true },
                    },
                ),
                (400, Input::Disconnect { conn: A }),
                (10_300, Input::Timer),
                (20_300, Input::Timer),
                (
                    20_400,
                    Input::Message {
                        conn: B,
                        msg: ClientMessage::Chat { text: "gg".into() },
                    },
                ),
            ];
            for (ms, input) in inputs {
                log.push(format!("{:?}", s.handle(input, at(ms))));
                log.push(format!("{:?}", s.next_deadline()));
            }
            log
        };
        let first = run();
        assert_eq!(first, run());
        assert!(first.len() > 10);
    }

    #[test]
    fn strikes_count_in_a_row_and_acting_clears_them() {
        let mut c = TurnClock::new(Duration::from_secs(1));
        c.start(Some(Seat::First), at(5));
        assert_eq!(c.deadline(), Some((Seat::First, at(1_005))));
        assert_eq!(c.strike(Seat::First), 1);
        assert_eq!(c.strike(Seat::First), 2);
        c.acted(Seat::First);
        assert_eq!(c.strike(Seat::First), 1);
        assert_eq!(c.strike(Seat::Second), 1);
        assert!(c.deadline().is_none());
    }
}
