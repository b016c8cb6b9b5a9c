//! The match state machine: whose turn it is, the board, the rows, the
//! rounds, the pie rule, resignation, and the record of it all.
//!
//! [`Game::play`] checks a shot against the state (refusing it with a
//! [`ShotError`] and changing nothing), adds the execution noise, resolves
//! it with the engine, applies the turn rule, and when a round ends moves
//! the rows and sets up the next round — or ends the match. Every accepted
//! move is appended to the game's [`MatchRecord`].

use crate::board::Board;
use crate::config::{Config, ConfigError};
use crate::film::Film;
use crate::noise;
use crate::outcome::{MatchResult, Next, RoundEnd, ShotOutcome, WinReason};
use crate::physics;
use crate::piece::PIECES_PER_SIDE;
use crate::record::{MatchRecord, RecordedMove};
use crate::rows::{Advance, Rows};
use crate::rules::{judge, RoundResult, Verdict};
use crate::shot::{check_velocity, Shot, ShotError};
use crate::side::{Seat, Side};
use serde::{Deserialize, Serialize};

/// Where the match stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "phase", rename_all = "kebab-case")]
pub enum Phase {
    /// Waiting for a shot by the side whose turn it is.
    Shooting,
    /// Waiting for Black's pie-rule decision.
    PieDecision,
    /// Finished.
    Over { result: MatchResult },
}

/// Why a pie decision or a resignation was refused.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum GameError {
    #[error("the match is over")]
    MatchOver,
    #[error("there is no pie-rule decision to make now")]
    NoPieDecision,
    #[error("the pie-rule decision is black's, not {0}'s")]
    NotYourDecision(Side),
}

impl GameError {
    /// The stable wire code of this error.
    pub fn code(&self) -> crate::protocol::ErrorCode {
        use crate::protocol::ErrorCode as C;
        match self {
            GameError::MatchOver => C::MatchOver,
            GameError::NoPieDecision => C::NoPieDecision,
            GameError::NotYourDecision(_) => C::NotYourDecision,
        }
    }
}

/// An accepted shot: what it did, and its motion to show.
#[derive(Clone, Debug, PartialEq)]
pub struct Played {
    pub outcome: ShotOutcome,
    pub film: Film,
}

/// What anyone watching the match may know (no seed: knowing it would let
/// a player predict the execution noise).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MatchView {
    pub config: Config,
    pub phase: Phase,
    /// The side to shoot (after the pie decision, if one is pending).
    pub turn: Side,
    /// Whether the pie rule swapped the seats.
    pub swapped: bool,
    /// The current round, 1-based.
    pub round: u32,
    pub rows: Rows,
    pub board: Board,
    /// Shots played in the match so far.
    pub shots: u32,
}

/// A match in progress (or over).
#[derive(Clone, Debug)]
pub struct Game {
    config: Config,
    seed: u64,
    rows: Rows,
    board: Board,
    round: u32,
    round_first: Side,
    turn: Side,
    phase: Phase,
    swapped: bool,
    shots: u32,
    record: MatchRecord,
}

impl Game {
    /// A new match: round 1, White on the first row, Black on the last,
    /// White to shoot. `seed` drives the execution noise (if enabled) and is
    /// kept in the record.
    pub fn new(config: Config, seed: u64) -> Result<Game, ConfigError> {
        config.validate()?;
        let rows = Rows::initial();
        Ok(Game {
            board: Board::setup(&config, rows),
            record: MatchRecord::new(config.clone(), seed),
            config,
            seed,
            rows,
            round: 1,
            round_first: Side::White,
            turn: Side::White,
            phase: Phase::Shooting,
            swapped: false,
            shots: 0,
        })
    }

    pub fn config(&self) -> &Config {
        &self.config
    }
    pub fn seed(&self) -> u64 {
        self.seed
    }
    pub fn board(&self) -> &Board {
        &self.board
    }
    pub fn rows(&self) -> Rows {
        self.rows
    }
    /// The current round, 1-based.
    pub fn round(&self) -> u32 {
        self.round
    }
    pub fn phase(&self) -> Phase {
        self.phase
    }
    /// Shots played so far.
    pub fn shots(&self) -> u32 {
        self.shots
    }
    /// The record of every move so far.
    pub fn record(&self) -> &MatchRecord {
        &self.record
    }
    /// Whether the pie rule swapped the seats.
    pub fn swapped(&self) -> bool {
        self.swapped
    }
    /// The colour a seat plays.
    pub fn side_of(&self, seat: Seat) -> Side {
        seat.side(self.swapped)
    }
    /// The seat playing a colour.
    pub fn seat_of(&self, side: Side) -> Seat {
        Seat::of(side, self.swapped)
    }

    /// The side that may shoot now (`None` while a pie decision is pending
    /// or once the match is over).
    pub fn to_shoot(&self) -> Option<Side> {
        (self.phase == Phase::Shooting).then_some(self.turn)
    }

    /// How the match ended, if it has.
    pub fn result(&self) -> Option<MatchResult> {
        match self.phase {
            Phase::Over { result } => Some(result),
            _ => None,
        }
    }

    /// Whether the match is over.
    pub fn is_over(&self) -> bool {
        self.result().is_some()
    }

    /// The state a client needs to show the match.
    pub fn view(&self) -> MatchView {
        MatchView {
            config: self.config.clone(),
            phase: self.phase,
            turn: self.turn,
            swapped: self.swapped,
            round: self.round,
            rows: self.rows,
            board: self.board.clone(),
            shots: self.shots,
        }
    }

    /// Whether `side` may play `shot` now.
    pub fn check(&self, side: Side, shot: &Shot) -> Result<(), ShotError> {
        match self.phase {
            Phase::Over { .. } => return Err(ShotError::MatchOver),
            Phase::PieDecision => return Err(ShotError::PieDecisionPending),
            Phase::Shooting => {}
        }
        if side != self.turn {
            return Err(ShotError::NotYourTurn { side, turn: self.turn });
        }
        let piece = shot.piece();
        if piece.side() != side {
            return Err(ShotError::NotYourPiece { piece, side });
        }
        if !self.board.contains(piece) {
            return Err(ShotError::PieceOffBoard(piece));
        }
        // The shot may have been built against another configuration.
        check_velocity(shot.velocity(), self.config.max_speed)
    }

    /// Plays `shot` for `side`: resolves it to the end of its chain and
    /// applies the rules. A refused shot changes nothing.
    pub fn play(&mut self, side: Side, shot: Shot) -> Result<Played, ShotError> {
        self.check(side, &shot)?;
        let aimed = shot.velocity();
        let played = match &self.config.variants.noise {
            Some(n) => noise::perturb(n, self.seed, self.shots, aimed, self.config.max_speed),
            None => aimed,
        };
        let res = physics::resolve(&self.config, &self.board, shot.piece(), played).map_err(ShotError::Physics)?;
        // Accepted: commit.
        let number = self.shots;
        let round = self.round;
        self.shots += 1;
        self.board = res.board;
        let mut round_end = None;
        match judge(side, &res.knocked_off, &self.board) {
            Verdict::ShootAgain => {}
            Verdict::PassTurn => self.turn = side.opponent(),
            Verdict::RoundOver(result) => {
                let next_rows = self.end_round(result);
                round_end = Some(RoundEnd { result, next_rows });
            }
        }
        if self.config.variants.pie_rule && number == 0 && !self.is_over() {
            self.phase = Phase::PieDecision;
        }
        let next = match self.phase {
            Phase::Shooting => Next::Shoot { side: self.turn },
            Phase::PieDecision => Next::PieDecision { then: self.turn },
            Phase::Over { result } => Next::MatchOver { result },
        };
        let outcome = ShotOutcome {
            number,
            round,
            shooter: side,
            piece: shot.piece(),
            aimed,
            played,
            events: res.events,
            knocked_off: res.knocked_off,
            duration: res.end.t,
            end_reason: res.end.reason,
            round_end,
            next,
        };
        self.record.moves.push(RecordedMove::Shot(outcome.clone()));
        Ok(Played {
            outcome,
            film: res.film,
        })
    }

    /// Ends the round; returns the next round's rows, or `None` if the match
    /// is over.
    fn end_round(&mut self, result: RoundResult) -> Option<Rows> {
        let winner = match result {
            RoundResult::Won(w) => w,
            RoundResult::Draw => {
                if self.config.variants.quick_match {
                    self.phase = Phase::Over {
                        result: MatchResult::Draw,
                    };
                    return None;
                }
                // Drawn: same rows, the same side starts again.
                self.start_round(self.round_first);
                return Some(self.rows);
            }
        };
        if self.config.variants.quick_match {
            self.phase = Phase::Over {
                result: MatchResult::Won {
                    side: winner,
                    reason: WinReason::QuickMatch,
                },
            };
            return None;
        }
        let flawless = self.board.count(winner) == PIECES_PER_SIDE as usize;
        let steps = if self.config.variants.two_row_advance && flawless { 2 } else { 1 };
        match self.rows.advance(winner, steps) {
            Advance::FarEdge => {
                self.phase = Phase::Over {
                    result: MatchResult::Won {
                        side: winner,
                        reason: WinReason::FarEdge,
                    },
                };
                None
            }
            Advance::Rows(rows) => {
                self.rows = rows;
                self.start_round(winner);
                Some(rows)
            }
        }
    }

    fn start_round(&mut self, first: Side) {
        self.round += 1;
        self.round_first = first;
        self.turn = first;
        self.board = Board::setup(&self.config, self.rows);
    }

    /// Black's pie-rule decision: `swap` exchanges the seats (the player who
    /// was Black takes White's position and White's turn, if it has one).
    pub fn decide_pie(&mut self, side: Side, swap: bool) -> Result<(), GameError> {
        match self.phase {
            Phase::Over { .. } => return Err(GameError::MatchOver),
            Phase::Shooting => return Err(GameError::NoPieDecision),
            Phase::PieDecision => {}
        }
        if side != Side::Black {
            return Err(GameError::NotYourDecision(side));
        }
        self.swapped ^= swap;
        self.phase = Phase::Shooting;
        self.record.moves.push(RecordedMove::Pie { swap });
        Ok(())
    }

    /// `side` resigns: the other side wins the match.
    pub fn resign(&mut self, side: Side) -> Result<MatchResult, GameError> {
        if self.is_over() {
            return Err(GameError::MatchOver);
        }
        let result = MatchResult::Won {
            side: side.opponent(),
            reason: WinReason::Resignation,
        };
        self.phase = Phase::Over { result };
        self.record.moves.push(RecordedMove::Resign { side });
        Ok(result)
    }

    /// Sets up a position by hand (tests of particular situations).
    #[cfg(test)]
    pub(crate) fn set_position(&mut self, board: Board, rows: Rows, turn: Side) {
        self.board = board;
        self.rows = rows;
        self.turn = turn;
    }
}
