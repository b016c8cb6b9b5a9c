//! Following a match from the server's announcements alone: a client that
//! holds a seat keeps the public [`MatchView`] the way docs/protocol.md
//! describes — the full view from every `match-state`, then each
//! `shot-played` applied with [`MatchView::after_shot`], each
//! `pie-decided` with [`MatchView::after_pie`], each `turn-passed` with
//! [`MatchView::after_pass`], `match-over` with [`MatchView::after_result`]
//! — and from it what is asked of the seat and by when (the last `clock`
//! for the seat). No socket here: the [`Follower`] is fed messages and
//! says what they meant, so the runner's logic is tested without a server.
//!
//! Every change of what the seat may be asked bumps a version number; a
//! decision is taken at most once per version, so a refused move is never
//! sent again until something changes.

use crate::bot::Ask;
use game::protocol::{ErrorCode, Players, ServerMessage};
use game::{MatchRecord, MatchResult, MatchView, Phase, Seat, ShotOutcome, Side};
use std::time::{Duration, Instant};

/// What a message from the server meant to the seat.
#[derive(Clone, Debug, PartialEq)]
pub enum Followed {
    /// The full state arrived (on every connection); the view is replaced.
    State,
    /// A shot was played (the bot's [`crate::Bot::on_shot`] is due).
    Shot(Box<ShotOutcome>),
    /// The view changed otherwise (a pie decision, a passed turn, the
    /// opponent's arrival).
    Changed,
    /// The clock of whoever must act.
    Clock,
    /// The match is over; the record, seed included, came with it.
    Over {
        result: MatchResult,
        record: Box<MatchRecord>,
    },
    /// A request of this seat was refused.
    Refused { code: ErrorCode, message: String },
    /// The announcements cannot be followed from the view held (a shot
    /// numbered out of order, or an update before any `match-state`): a
    /// fresh connection brings the full state again.
    OutOfSync(String),
    /// Nothing that concerns the view (chat, welcome, player left or back,
    /// timeouts, rematches).
    Nothing,
}

/// One seat's knowledge of a match, kept from the server's messages.
#[derive(Clone, Debug)]
pub struct Follower {
    seat: Seat,
    view: Option<MatchView>,
    players: Players,
    version: u64,
    changed_at: Instant,
    /// The seat's own clock: the version it was sent for and when it runs out.
    clock: Option<(u64, Instant)>,
    result: Option<MatchResult>,
    record: Option<MatchRecord>,
    my_shots: u32,
}

impl Follower {
    /// A follower for `seat`, before any message.
    pub fn new(seat: Seat) -> Follower {
        Follower {
            seat,
            view: None,
            players: Players::default(),
            version: 0,
            changed_at: Instant::now(),
            clock: None,
            result: None,
            record: None,
            my_shots: 0,
        }
    }

    /// The seat followed.
    pub fn seat(&self) -> Seat {
        self.seat
    }

    /// The view, once a `match-state` arrived.
    pub fn view(&self) -> Option<&MatchView> {
        self.view.as_ref()
    }

    /// The colour the seat plays now (`None` before the first state).
    pub fn side(&self) -> Option<Side> {
        self.view.as_ref().map(|v| self.seat.side(v.swapped))
    }

    /// Whether both seats are taken (before that, nobody may move).
    pub fn live(&self) -> bool {
        self.players.first.is_some() && self.players.second.is_some()
    }

    /// Bumped by every change that may change what is asked.
    pub fn version(&self) -> u64 {
        self.version
    }

    /// When the version last changed.
    pub fn changed_at(&self) -> Instant {
        self.changed_at
    }

    /// What the seat must decide now, if anything: a shot when the view
    /// says this seat's side shoots, the pie decision when it is pending
    /// and this seat plays Black.
    pub fn ask(&self) -> Option<Ask> {
        let view = self.view.as_ref()?;
        if !self.live() {
            return None;
        }
        let me = self.seat.side(view.swapped);
        match view.phase {
            Phase::Shooting if view.to_shoot() == Some(me) => Some(Ask::Shoot),
            Phase::PieDecision if me == Side::Black => Some(Ask::Pie),
            _ => None,
        }
    }

    /// When the seat's clock runs out, if the server sent it since the
    /// last change.
    pub fn deadline(&self) -> Option<Instant> {
        match self.clock {
            Some((v, at)) if v == self.version => Some(at),
            _ => None,
        }
    }

    /// The result, once the match is over.
    pub fn result(&self) -> Option<MatchResult> {
        self.result.or_else(|| match self.view.as_ref()?.phase {
            Phase::Over { result } => Some(result),
            _ => None,
        })
    }

    /// The record, if `match-over` brought it.
    pub fn record(&self) -> Option<&MatchRecord> {
        self.record.as_ref()
    }

    /// Shots played in the match so far.
    pub fn shots(&self) -> u32 {
        self.view.as_ref().map_or(0, |v| v.shots)
    }

    /// Shots this seat played.
    pub fn my_shots(&self) -> u32 {
        self.my_shots
    }

    fn bump(&mut self, now: Instant) {
        self.version += 1;
        self.changed_at = now;
    }

    /// Takes in one message received at `now`.
    pub fn apply(&mut self, msg: ServerMessage, now: Instant) -> Followed {
        match msg {
            ServerMessage::MatchState {
                you, players, view, ..
            } => {
                if let Some(you) = you {
                    self.seat = you;
                }
                if let Phase::Over { result } = view.phase {
                    self.result = Some(result);
                }
                self.players = players;
                self.view = Some(view);
                self.bump(now);
                Followed::State
            }
            ServerMessage::ShotPlayed {
                outcome,
                view: next,
                ..
            } => {
                let Some(view) = self.view.as_ref() else {
                    return Followed::OutOfSync("a shot before the match state".into());
                };
                if outcome.number != view.shots {
                    return Followed::OutOfSync(format!(
                        "shot number {} announced, {} expected",
                        outcome.number, view.shots
                    ));
                }
                if outcome.shooter == self.seat.side(view.swapped) {
                    self.my_shots += 1;
                }
                if let Phase::Over { result } = next.phase {
                    self.result = Some(result);
                }
                self.view = Some(next);
                self.bump(now);
                Followed::Shot(Box::new(outcome))
            }
            ServerMessage::PieDecided { swap } => self.update(now, |v| v.after_pie(swap)),
            ServerMessage::TurnPassed { side } => {
                match self.view.as_ref().and_then(MatchView::to_shoot) {
                    Some(s) if s == side => self.update(now, MatchView::after_pass),
                    _ => Followed::OutOfSync(format!("{side:?} passed out of turn")),
                }
            }
            ServerMessage::MatchOver { result, record } => {
                if let Some(v) = self.view.as_ref() {
                    self.view = Some(v.after_result(result));
                }
                self.result = Some(result);
                self.record = Some(record.clone());
                self.bump(now);
                Followed::Over {
                    result,
                    record: Box::new(record),
                }
            }
            ServerMessage::PlayerJoined { seat, name } => {
                match seat {
                    Seat::First => self.players.first = Some(name),
                    Seat::Second => self.players.second = Some(name),
                }
                self.bump(now);
                Followed::Changed
            }
            ServerMessage::Clock {
                seat, remaining_ms, ..
            } => {
                self.clock = (seat == self.seat)
                    .then(|| (self.version, now + Duration::from_millis(remaining_ms)));
                Followed::Clock
            }
            ServerMessage::Error { code, message } => Followed::Refused { code, message },
            ServerMessage::Welcome { .. }
            | ServerMessage::MatchCreated { .. }
            | ServerMessage::RematchOffered { .. }
            | ServerMessage::RematchStarted { .. }
            | ServerMessage::Chat { .. }
            | ServerMessage::PlayerLeft { .. }
            | ServerMessage::PlayerBack { .. }
            | ServerMessage::TurnTimedOut { .. }
            | ServerMessage::Forfeited { .. } => Followed::Nothing,
        }
    }

    fn update(&mut self, now: Instant, f: impl FnOnce(&MatchView) -> MatchView) -> Followed {
        match self.view.as_ref() {
            Some(v) => {
                self.view = Some(f(v));
                self.bump(now);
                Followed::Changed
            }
            None => Followed::OutOfSync("an update before the match state".into()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bot::{Bot, Context, Decision};
    use crate::level::by_name;
    use game::{Config, ForfeitReason, Game};

    fn state(game: &Game, you: Seat) -> ServerMessage {
        ServerMessage::MatchState {
            match_id: "m".into(),
            you: Some(you),
            players: Players {
                first: Some("a".into()),
                second: Some("b".into()),
            },
            view: game.view(),
        }
    }

    /// Plays a whole match between two bots on a local [`Game`], announcing
    /// every move as the server does; both followers keep the game's view.
    #[test]
    fn followers_of_both_seats_keep_the_games_view_through_a_whole_match() {
        let mut game = Game::new(Config::standard(), 11).unwrap();
        let mut seats = [Follower::new(Seat::First), Follower::new(Seat::Second)];
        let mut bots = [by_name("greedy", 1).unwrap(), by_name("random", 2).unwrap()];
        let now = Instant::now();
        for (f, s) in seats.iter_mut().zip([Seat::First, Seat::Second]) {
            assert_eq!(f.apply(state(&game, s), now), Followed::State);
        }
        let mut passes = 0;
        while !game.is_over() {
            let acting: Vec<usize> = (0..2).filter(|&k| seats[k].ask().is_some()).collect();
            assert_eq!(acting.len(), 1, "exactly one seat is asked");
            let k = acting[0];
            let me = seats[k].side().unwrap();
            let view = seats[k].view().unwrap().clone();
            assert_eq!(view, game.view());
            let decision = bots[k].decide(&Context::new(&view, me, Duration::from_secs(1)));
            let msg = match (seats[k].ask().unwrap(), decision) {
                (Ask::Pie, Decision::Pie { swap }) => {
                    game.decide_pie(me, swap).unwrap();
                    ServerMessage::PieDecided { swap }
                }
                (Ask::Shoot, Decision::Shot(shot)) if passes < 3 && game.shots() % 7 == 3 => {
                    // Now and then the clock runs out instead.
                    let _ = shot;
                    passes += 1;
                    game.pass(me).unwrap();
                    ServerMessage::TurnPassed { side: me }
                }
                (Ask::Shoot, Decision::Shot(shot)) => {
                    let played = game.play(me, shot).unwrap();
                    ServerMessage::shot_played(played, game.view())
                }
                (ask, d) => panic!("asked {ask:?}, decided {d:?}"),
            };
            for f in seats.iter_mut() {
                let before = f.version();
                f.apply(msg.clone(), now);
                assert!(f.version() > before);
                if !game.is_over() {
                    assert_eq!(f.view().unwrap(), &game.view());
                }
            }
        }
        let result = game.result().unwrap();
        let over = ServerMessage::MatchOver {
            result,
            record: game.record().clone(),
        };
        for f in seats.iter_mut() {
            assert!(matches!(f.apply(over.clone(), now), Followed::Over { .. }));
            assert_eq!(f.result(), Some(result));
            assert_eq!(f.ask(), None);
            assert_eq!(f.record(), Some(game.record()));
        }
        assert_eq!(seats[0].my_shots() + seats[1].my_shots(), game.shots());
        assert_eq!(seats[0].shots(), game.shots());
    }

    #[test]
    fn nobody_is_asked_before_the_second_seat_is_taken() {
        let game = Game::new(Config::default(), 1).unwrap();
        let mut f = Follower::new(Seat::First);
        let now = Instant::now();
        f.apply(
            ServerMessage::MatchState {
                match_id: "m".into(),
                you: Some(Seat::First),
                players: Players {
                    first: Some("a".into()),
                    second: None,
                },
                view: game.view(),
            },
            now,
        );
        assert_eq!(f.ask(), None);
        f.apply(
            ServerMessage::PlayerJoined {
                seat: Seat::Second,
                name: "b".into(),
            },
            now,
        );
        assert_eq!(f.ask(), Some(Ask::Shoot));
    }

    #[test]
    fn the_deadline_is_the_seats_own_clock_sent_since_the_last_change() {
        let mut game = Game::new(Config::default(), 1).unwrap();
        let mut f = Follower::new(Seat::Second);
        let now = Instant::now();
        f.apply(state(&game, Seat::Second), now);
        f.apply(
            ServerMessage::Clock {
                seat: Seat::First,
                side: Side::White,
                remaining_ms: 5000,
            },
            now,
        );
        assert_eq!(f.deadline(), None, "the other seat's clock");
        game.pass(Side::White).unwrap();
        f.apply(ServerMessage::TurnPassed { side: Side::White }, now);
        assert_eq!(f.ask(), Some(Ask::Shoot));
        assert_eq!(f.deadline(), None, "no clock yet for this turn");
        f.apply(
            ServerMessage::Clock {
                seat: Seat::Second,
                side: Side::Black,
                remaining_ms: 2000,
            },
            now,
        );
        assert_eq!(f.deadline(), Some(now + Duration::from_millis(2000)));
        // A refusal changes nothing: same version, same deadline.
        let v = f.version();
        let refused = f.apply(
            ServerMessage::error(ErrorCode::NotYourPiece, "that piece is white's"),
            now,
        );
        assert!(matches!(
            refused,
            Followed::Refused {
                code: ErrorCode::NotYourPiece,
                ..
            }
        ));
        assert_eq!(f.version(), v);
        assert!(f.deadline().is_some());
    }

    #[test]
    fn a_shot_out_of_order_or_before_the_state_is_out_of_sync() {
        let mut game = Game::new(Config::default(), 1).unwrap();
        let now = Instant::now();
        let shot = game::Shot::new(
            game::PieceId::new(Side::White, 4).unwrap(),
            glam::DVec2::new(0.0, 1.0),
            game.config(),
        )
        .unwrap();
        let mut f = Follower::new(Seat::First);
        let early =
            Follower::new(Seat::First).apply(ServerMessage::TurnPassed { side: Side::White }, now);
        assert!(matches!(early, Followed::OutOfSync(_)));
        f.apply(state(&game, Seat::First), now);
        let played = game.play(Side::White, shot).unwrap();
        let mut wrong = played.clone();
        wrong.outcome.number = 5;
        let msg = ServerMessage::shot_played(wrong, game.view());
        assert!(matches!(f.apply(msg, now), Followed::OutOfSync(_)));
        let msg = ServerMessage::shot_played(played, game.view());
        assert!(matches!(f.apply(msg, now), Followed::Shot(_)));
        assert_eq!(f.view().unwrap(), &game.view());
        assert_eq!(f.my_shots(), 1);
    }

    #[test]
    fn a_state_of_a_finished_match_gives_its_result() {
        let mut game = Game::new(Config::default(), 1).unwrap();
        let result = game.forfeit(Side::Black, ForfeitReason::Abandoned).unwrap();
        let mut f = Follower::new(Seat::First);
        f.apply(state(&game, Seat::First), Instant::now());
        assert_eq!(f.result(), Some(result));
        assert_eq!(f.ask(), None);
        assert_eq!(f.record(), None);
    }
}
