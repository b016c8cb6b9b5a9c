//! The turn clock. A live match gives the seat that must act (the shooter,
//! or Black for a pie decision) a deadline; a seat that misses it gets a
//! strike and the server acts for it: declines the pie swap, or passes the
//! turn (the game's pass move: nothing moves, the other side shoots). Three
//! strikes in a row forfeit the match. Acting in time clears the seat's
//! strikes.

use game::{Game, Seat, Side};
use std::time::Duration;
use tokio::time::Instant;

/// Timeouts in a row that forfeit a match.
pub const STRIKES_TO_FORFEIT: u32 = 3;

/// A match's turn clock.
#[derive(Clone, Debug)]
pub struct TurnClock {
    turn: Duration,
    deadline: Option<(Seat, Instant)>,
    strikes: [u32; 2],
}

fn index(seat: Seat) -> usize {
    match seat {
        Seat::First => 0,
        Seat::Second => 1,
    }
}

impl TurnClock {
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

    /// Starts the clock for `seat` (`None` stops it).
    pub fn start(&mut self, seat: Option<Seat>, now: Instant) {
        self.deadline = seat.map(|s| (s, now + self.turn));
    }

    /// Who must act by when.
    pub fn deadline(&self) -> Option<(Seat, Instant)> {
        self.deadline
    }

    /// `seat` acted in time.
    pub fn acted(&mut self, seat: Seat) {
        self.strikes[index(seat)] = 0;
    }

    /// `seat` timed out: its strikes in a row, now.
    pub fn strike(&mut self, seat: Seat) -> u32 {
        self.deadline = None;
        let s = &mut self.strikes[index(seat)];
        *s += 1;
        *s
    }
}

/// The seat that must act now, if any.
pub fn to_act(game: &Game) -> Option<Seat> {
    match game.phase() {
        game::Phase::Over { .. } => None,
        game::Phase::PieDecision => Some(game.seat_of(Side::Black)),
        game::Phase::Shooting => game.to_shoot().map(|s| game.seat_of(s)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strikes_count_in_a_row_and_acting_clears_them() {
        let mut c = TurnClock::new(Duration::from_secs(1));
        c.start(Some(Seat::First), Instant::now());
        assert_eq!(c.deadline().map(|d| d.0), Some(Seat::First));
        assert_eq!(c.strike(Seat::First), 1);
        assert_eq!(c.strike(Seat::First), 2);
        c.acted(Seat::First);
        assert_eq!(c.strike(Seat::First), 1);
        assert_eq!(c.strike(Seat::Second), 1);
        assert!(c.deadline().is_none());
    }
}
