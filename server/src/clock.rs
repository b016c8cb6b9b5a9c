//! The turn clock. A live match gives the seat that must act (the shooter,
//! or Black for a pie decision) a deadline; a seat that misses it gets a
//! strike and the server acts for it: declines the pie swap, or passes the
//! turn by playing the smallest legal flick (a "nudge" of about a
//! millimetre of the piece nearest the centre, towards the centre — the
//! game has no pass move, and a flick that knocks nothing off always passes
//! the turn). Three strikes in a row forfeit the match. Acting in time
//! clears the seat's strikes.

use game::{Game, Seat, Shot, Side};
use glam::DVec2;
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

/// The smallest legal flick for `side`: the piece nearest the centre of
/// the board slides about a fortieth of a square towards the centre.
pub fn nudge(game: &Game, side: Side) -> Option<Shot> {
    let config = game.config();
    let centre = DVec2::splat(config.board_size() / 2.0);
    let piece = game.board().of(side).min_by(|a, b| {
        (a.pos - centre)
            .length()
            .total_cmp(&(b.pos - centre).length())
    })?;
    let mut dir = centre - piece.pos;
    if dir.length() == 0.0 {
        dir = DVec2::Y;
    }
    let speed = config
        .speed_for_distance(config.square / 40.0)
        .min(config.max_speed);
    Shot::aimed(piece.id, dir, speed, config).ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use game::{Config, Next};

    #[test]
    fn a_nudge_passes_the_turn_and_barely_moves_one_piece() {
        let mut g = Game::new(Config::default(), 0).unwrap();
        let before = g.board().clone();
        let shot = nudge(&g, Side::White).unwrap();
        let out = g.play(Side::White, shot).unwrap().outcome;
        assert!(out.knocked_off.is_empty());
        assert_eq!(out.next, Next::Shoot { side: Side::Black });
        let moved = (g.board().piece(shot.piece()).unwrap().pos
            - before.piece(shot.piece()).unwrap().pos)
            .length();
        assert!(moved > 0.0 && moved < 0.002, "{moved}");
    }

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
