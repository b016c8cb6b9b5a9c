//! A driver of a live match [`Session`] that checks every answer it gets,
//! as the server's room would carry it out: it names connections, keeps the
//! clock, fires the session's deadlines, holds the store the session writes
//! to (and can make a write fail), and answers for the built-in bot and the
//! rematch. What it checks, beyond "no panic":
//!
//! - every effect is well-formed: a message reaches only admitted
//!   connections and reads back from its JSON as itself, an admitted
//!   connection first hears the match state with its own seat, a refusal
//!   answers the request that was made, the status said is the status;
//! - a refused request changes nothing (the session is the same after it)
//!   and says nothing else;
//! - every move is stored, in order, before any message tells of it, and
//!   the store holds exactly the session's record;
//! - a store failure reloads the match from the stored moves, which replay;
//! - nothing grows without bound: effects per answer, moves per input,
//!   connections, and each deadline fired moves the next one later;
//! - at the end the record reads back from its JSON and replays
//!   ([`game::replay`]) to the session's very match.

use game::protocol::{ErrorCode, Refusal, ServerMessage};
use game::record::{MatchRecord, RecordedMove};
use game::session::{
    BotDecision, ConnId, Effect, Input, Moment, Request, Session, SessionLimits, To,
};
use game::token::SeatToken;
use game::{Replay, Seat};
use std::time::Duration;

/// The limits the fuzzed sessions run under (the server's shape, shorter).
pub const LIMITS: SessionLimits = SessionLimits {
    turn: Duration::from_millis(10_000),
    grace: Duration::from_millis(5_000),
    bot_delay: Duration::from_millis(500),
    idle: Duration::from_millis(60_000),
    max_connections_per_match: 4,
};

/// Most effects one input may answer with.
pub const MAX_EFFECTS: usize = 32;

/// Most moves one input may add to the record (a timeout and two
/// abandoned seats at one moment).
pub const MAX_MOVES_PER_INPUT: usize = 3;

/// Most deadlines one wait may fire.
pub const MAX_TIMERS_PER_WAIT: usize = 64;

/// A connection the driver never admits.
pub const STRANGER: ConnId = ConnId(u64::MAX);

/// A session being driven, and what the driver knows of it.
#[derive(Debug)]
pub struct Driver {
    session: Session,
    now: Moment,
    /// The admitted connections still open, oldest first.
    open: Vec<ConnId>,
    /// The last connection named.
    last_conn: u64,
    /// The moves the store holds.
    stored: Vec<RecordedMove>,
    /// The next write fails; the match is then reloaded (`true`) or
    /// cannot be read back (`false`).
    fail_next_write: Option<bool>,
    /// The bot's requests, `(seat, at_move)`, latest last.
    bot_asked: Vec<(Seat, usize)>,
    /// A rematch was asked for and not answered yet.
    rematch_pending: bool,
}

impl Driver {
    /// Drives `session`, which is at `Moment::ZERO` with nothing stored.
    pub fn new(session: Session) -> Driver {
        let stored = session.game().record().moves.clone();
        Driver {
            session,
            now: Moment::ZERO,
            open: Vec::new(),
            last_conn: 0,
            stored,
            fail_next_write: None,
            bot_asked: Vec::new(),
            rematch_pending: false,
        }
    }

    /// The session.
    pub fn session(&self) -> &Session {
        &self.session
    }

    /// The connection `n` names: the `n`-th open one, modulo their number
    /// plus one, the last being one never admitted.
    pub fn conn(&self, n: u8) -> ConnId {
        let k = n as usize % (self.open.len() + 1);
        self.open.get(k).copied().unwrap_or(STRANGER)
    }

    /// A new connection presents `token`.
    pub fn connect(&mut self, token: Option<String>) {
        self.last_conn += 1;
        let conn = ConnId(self.last_conn);
        let token = token.map(SeatToken::new);
        self.feed(Input::Connect {
            conn,
            token,
            name: "watcher".into(),
        });
    }

    /// Connection `conn` closes.
    pub fn disconnect(&mut self, conn: ConnId) {
        let effects = self.feed(Input::Disconnect { conn });
        self.open.retain(|&c| c != conn);
        if conn == STRANGER {
            assert!(effects.is_empty(), "a stranger's disconnect does nothing");
        }
    }

    /// Time passes by `by`; every deadline on the way fires at its moment.
    pub fn wait(&mut self, by: Duration) {
        let until = self.now + by;
        let mut fired = 0;
        while let Some(deadline) = self.session.next_deadline().filter(|d| *d <= until) {
            fired += 1;
            assert!(
                fired <= MAX_TIMERS_PER_WAIT,
                "more than {MAX_TIMERS_PER_WAIT} deadlines in {by:?}"
            );
            self.now = self.now.max(deadline);
            self.feed(Input::Timer);
        }
        self.now = until;
    }

    /// Time passes to the next deadline, which fires.
    pub fn to_deadline(&mut self) {
        if let Some(deadline) = self.session.next_deadline() {
            self.now = self.now.max(deadline);
            self.feed(Input::Timer);
        }
    }

    /// The next store write fails.
    pub fn fail_next_write(&mut self, reload: bool) {
        self.fail_next_write = Some(reload);
    }

    /// The bot answers the request `stale` moves before the latest one
    /// (nothing if it was never asked).
    pub fn bot_answer(&mut self, stale: u8, decision: BotDecision) {
        let Some(&(seat, at_move)) = self.bot_asked.last() else {
            return;
        };
        let at_move = at_move.saturating_sub(stale as usize);
        let current = self.session.game().record().moves.len();
        let effects = self.feed(Input::BotMove {
            seat,
            at_move,
            decision,
        });
        if at_move != current {
            assert!(effects.is_empty(), "a stale bot move is ignored");
        }
    }

    /// The rematch asked for is created (or could not be); nothing if none
    /// was asked for.
    pub fn rematch_answer(&mut self, created: bool) {
        if !std::mem::take(&mut self.rematch_pending) {
            return;
        }
        self.feed(if created {
            Input::RematchCreated {
                match_id: "m2".into(),
            }
        } else {
            Input::RematchFailed {
                refusal: Refusal::new(ErrorCode::ServerBusy, "the server is full"),
            }
        });
    }

    /// Hands `input` to the session now, checks the answer and carries it
    /// out.
    pub fn feed(&mut self, input: Input) -> Vec<Effect> {
        let was_closed = self.session.is_closed();
        let refusable = matches!(
            input,
            Input::Connect { .. } | Input::Join { .. } | Input::Message { .. }
        );
        let before = refusable.then(|| format!("{:?}", self.session));
        let moves_before = self.session.game().record().moves.len();
        let admits = match &input {
            Input::Connect { token, .. } => Some(self.seat_of(token.as_ref())),
            _ => None,
        };
        let effects = self.session.handle(input.clone(), self.now);
        if was_closed {
            assert!(effects.is_empty(), "a closed session answers nothing");
            return effects;
        }
        assert!(
            effects.len() <= MAX_EFFECTS,
            "{} effects for one input",
            effects.len()
        );
        let failed = self.check_answer(&input, &effects, before.as_deref(), admits);
        let moves = self.session.game().record().moves.len();
        assert!(
            moves <= moves_before + MAX_MOVES_PER_INPUT,
            "one input added {} moves",
            moves - moves_before
        );
        if let Input::Disconnect { conn } = input {
            self.open.retain(|&c| c != conn);
        }
        match failed {
            Some(Failed::Move { index, reload }) => self.store_failed(index, reload),
            Some(Failed::Join) => {
                let effects = self.feed(Input::JoinFailed);
                assert!(
                    matches!(effects.first(), Some(Effect::Status(_))),
                    "a failed join restates the status"
                );
            }
            None => {
                // A call that asked for a write may leave the idle deadline
                // already past (the session stays to hear how the write
                // went): it fires at once, as the server's room fires it.
                let wrote = effects
                    .iter()
                    .any(|e| matches!(e, Effect::Store { .. } | Effect::StoreJoin { .. }));
                let past = self.session.next_deadline().is_some_and(|t| t <= self.now);
                if wrote && past {
                    self.feed(Input::Timer);
                } else {
                    self.check_state();
                }
            }
        }
        effects
    }

    /// The seat a token admits to: `Some(seat)` (`None`: a spectator), or
    /// `None` for a token that holds no seat.
    fn seat_of(&self, token: Option<&SeatToken>) -> Option<Option<Seat>> {
        let Some(token) = token else {
            return Some(None);
        };
        let seats = self.session.seats();
        [Seat::First, Seat::Second]
            .into_iter()
            .find(|s| seats[s.index()].token == Some(token.hash()))
            .map(Some)
    }

    /// Checks one answer and keeps what it stores; says which write the
    /// driver makes fail.
    fn check_answer(
        &mut self,
        input: &Input,
        effects: &[Effect],
        before: Option<&str>,
        admits: Option<Option<Option<Seat>>>,
    ) -> Option<Failed> {
        let from = match input {
            Input::Connect { conn, .. }
            | Input::Disconnect { conn }
            | Input::Message { conn, .. } => Some(*conn),
            _ => None,
        };
        let mut stores = 0;
        let mut failed = None;
        let mut status = None;
        for (i, effect) in effects.iter().enumerate() {
            match effect {
                Effect::Admitted { conn, seat } => {
                    assert_eq!(Some(*conn), from, "admitted without asking");
                    assert!(!self.open.contains(conn), "{conn:?} admitted twice");
                    assert_eq!(admits, Some(Some(*seat)), "admitted to the wrong seat");
                    assert!(
                        matches!(
                            effects.get(i + 1),
                            Some(Effect::Send {
                                to: To::Only(to),
                                msg: ServerMessage::MatchState { you, .. },
                            }) if to == conn && you == seat
                        ),
                        "an admitted connection first hears the match state with its seat"
                    );
                    self.open.push(*conn);
                }
                Effect::Refused { request, refusal } => {
                    assert!(!refusal.message.is_empty(), "a refusal says why");
                    let answers = match (request, input) {
                        (Request::Connect(c), Input::Connect { conn, .. })
                        | (Request::Message(c), Input::Message { conn, .. }) => c == conn,
                        (Request::Join, Input::Join { .. })
                        | (Request::Message(_), Input::RematchFailed { .. })
                        | (Request::Bot(_), Input::BotMove { .. })
                        | (Request::Clock, Input::Timer | Input::BotMove { .. }) => true,
                        _ => false,
                    };
                    assert!(answers, "{request:?} refused in answer to {input:?}");
                    if let Some(before) = before {
                        assert_eq!(effects.len(), 1, "a refused request does nothing else");
                        assert!(
                            before == format!("{:?}", self.session),
                            "a refused {input:?} changed the session"
                        );
                    }
                }
                Effect::Send { to, msg } => {
                    match to {
                        To::All => {}
                        To::Only(c) => assert!(self.open.contains(c), "sent to {c:?}, not open"),
                        To::AllBut(c) => assert_eq!(Some(*c), from, "all but {c:?}"),
                    }
                    let json = msg.to_json();
                    assert_eq!(
                        ServerMessage::from_json(&json).as_ref(),
                        Ok(msg),
                        "a message reads back as itself: {json}"
                    );
                    if let ServerMessage::Clock { remaining_ms, .. } = msg {
                        assert!(*remaining_ms <= LIMITS.turn.as_millis() as u64);
                    }
                    if tells_of_a_move(msg) {
                        assert!(stores > 0, "told of a move before storing it: {json}");
                    }
                }
                Effect::Store { index, mv, .. } => {
                    assert_eq!(*index, self.stored.len(), "moves are stored in order");
                    self.stored.push(mv.clone());
                    stores += 1;
                    if failed.is_none() {
                        if let Some(reload) = self.fail_next_write.take() {
                            failed = Some(Failed::Move {
                                index: *index,
                                reload,
                            });
                        }
                    }
                }
                Effect::StoreJoin { name, token } => {
                    assert!(
                        matches!(input, Input::Join { name: n, token: t } if n == name && t == token),
                        "stored a join nobody made"
                    );
                    if failed.is_none() && self.fail_next_write.take().is_some() {
                        failed = Some(Failed::Join);
                    }
                }
                Effect::Joined { seat } => assert_eq!(*seat, Seat::Second),
                Effect::CreateRematch { config, .. } => {
                    assert_eq!(config, self.session.game().config());
                    self.rematch_pending = true;
                }
                Effect::BotToAct {
                    seat,
                    level,
                    at_move,
                    view,
                    ..
                } => {
                    let game = self.session.game();
                    assert_eq!(*at_move, game.record().moves.len());
                    assert_eq!(**view, game.view(), "the bot sees the match as it is");
                    let bot = self.session.seats()[seat.index()].bot.clone();
                    assert_eq!(bot.as_ref(), Some(level), "asked a seat no bot holds");
                    self.bot_asked.push((*seat, *at_move));
                }
                Effect::Status(s) => status = Some(*s),
                Effect::Close => {
                    assert_eq!(i + 1, effects.len(), "closing is the last effect");
                    assert!(self.session.is_closed());
                }
            }
        }
        if let Some(s) = status {
            if failed.is_none() {
                assert_eq!(s, self.session.status(), "the status said is the status");
            }
        }
        failed
    }

    /// The write of move `index` failed: the store holds the moves before
    /// it, and the session gets the match replayed from them.
    fn store_failed(&mut self, index: usize, reload: bool) {
        self.stored.truncate(index);
        let game = self.session.game();
        // What the store keeps: the secret, and the moves written.
        let mut record = game.private_record();
        record.moves = self.stored.clone();
        let reloaded = match Replay::new(record) {
            Ok(replay) => replay.game().clone(),
            Err(e) => panic!("the stored moves do not replay: {e}"),
        };
        let effects = self.feed(Input::StoreFailed {
            reloaded: reload.then(|| Box::new(reloaded)),
        });
        if !reload {
            assert!(matches!(effects[..], [Effect::Close]), "{effects:?}");
        }
    }

    /// What must hold between inputs.
    fn check_state(&self) {
        if self.session.is_closed() {
            assert_eq!(self.session.next_deadline(), None);
            return;
        }
        assert_eq!(
            self.session.game().record().moves,
            self.stored,
            "the store holds the session's record"
        );
        assert_eq!(self.session.connections(), self.open.len());
        assert!(self.open.len() <= LIMITS.max_connections_per_match);
        if let Some(deadline) = self.session.next_deadline() {
            assert!(deadline > self.now, "a deadline already past is pending");
        }
    }

    /// The checks at the end of a script: the record reads back from its
    /// JSON and replays to the session's match.
    pub fn finish(self) {
        let game = self.session.game();
        let record = game.record();
        let json = record.to_json();
        assert_eq!(
            MatchRecord::from_json(&json).as_ref(),
            Ok(record),
            "the record reads back from its JSON"
        );
        assert_eq!(
            record.noise.as_ref().is_some_and(|n| n.secret.is_some()),
            game.is_over(),
            "the secret is revealed exactly when the match is over"
        );
        let replay = match Replay::new(game.private_record()) {
            Ok(replay) => replay,
            Err(e) => panic!("the session's record does not replay: {e}"),
        };
        assert_eq!(
            replay.game().view(),
            game.view(),
            "the replay ends as the match"
        );
        assert_eq!(replay.game().result(), game.result());
    }
}

/// A write the driver made fail.
#[derive(Clone, Copy, Debug)]
enum Failed {
    /// The move with this index; the match is then reloaded from the
    /// store, or cannot be read back.
    Move { index: usize, reload: bool },
    /// The second seat's join.
    Join,
}

/// Whether `msg` tells of a move (which must be stored first).
fn tells_of_a_move(msg: &ServerMessage) -> bool {
    matches!(
        msg,
        ServerMessage::ShotPlayed { .. }
            | ServerMessage::PieDecided { .. }
            | ServerMessage::TurnPassed { .. }
            | ServerMessage::MatchOver { .. }
    )
}
