//! Sides and seats. A [`Side`] is a colour on the board (White or Black); a
//! [`Seat`] is a player of the match (the one who created it sits
//! [`Seat::First`]). Seats keep their colour for the whole match unless the
//! pie rule swaps them, so the server talks in seats and the rules in sides.

use serde::{Deserialize, Serialize};
use std::fmt;

/// A colour on the board.
#[derive(
    Clone,
    Copy,
    Debug,
    PartialEq,
    Eq,
    Hash,
    PartialOrd,
    Ord,
    Serialize,
    Deserialize,
    schemars::JsonSchema,
)]
#[serde(rename_all = "kebab-case")]
pub enum Side {
    /// Starts on the first row (rank 0) and shoots first in round 1.
    White,
    /// Starts on the last row (rank 7).
    Black,
}

impl Side {
    /// Both sides, White first.
    pub const BOTH: [Side; 2] = [Side::White, Side::Black];

    /// The other side.
    pub fn opponent(self) -> Side {
        match self {
            Side::White => Side::Black,
            Side::Black => Side::White,
        }
    }

    /// 0 for White, 1 for Black (for per-side arrays).
    pub fn index(self) -> usize {
        match self {
            Side::White => 0,
            Side::Black => 1,
        }
    }
}

impl fmt::Display for Side {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Side::White => "white",
            Side::Black => "black",
        })
    }
}

/// A player of a match, independent of colour.
#[derive(
    Clone,
    Copy,
    Debug,
    PartialEq,
    Eq,
    Hash,
    PartialOrd,
    Ord,
    Serialize,
    Deserialize,
    schemars::JsonSchema,
)]
#[serde(rename_all = "kebab-case")]
pub enum Seat {
    /// The player who created the match: White unless the pie rule swapped.
    First,
    /// The player who joined: Black unless the pie rule swapped.
    Second,
}

impl Seat {
    /// The colour this seat plays, given whether the pie rule swapped seats.
    pub fn side(self, swapped: bool) -> Side {
        match (self, swapped) {
            (Seat::First, false) | (Seat::Second, true) => Side::White,
            (Seat::Second, false) | (Seat::First, true) => Side::Black,
        }
    }

    /// The seat that plays `side`, given whether the pie rule swapped seats.
    pub fn of(side: Side, swapped: bool) -> Seat {
        match (side, swapped) {
            (Side::White, false) | (Side::Black, true) => Seat::First,
            (Side::Black, false) | (Side::White, true) => Seat::Second,
        }
    }

    /// 0 for the first seat, 1 for the second (for per-seat arrays).
    pub fn index(self) -> usize {
        match self {
            Seat::First => 0,
            Seat::Second => 1,
        }
    }

    /// The other seat.
    pub fn other(self) -> Seat {
        match self {
            Seat::First => Seat::Second,
            Seat::Second => Seat::First,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn opponent_of_opponent_is_the_side_itself() {
        for s in Side::BOTH {
            assert_ne!(s.opponent(), s);
            assert_eq!(s.opponent().opponent(), s);
        }
    }

    #[test]
    fn seats_play_their_colour_and_swap_under_the_pie_rule() {
        assert_eq!(Seat::First.side(false), Side::White);
        assert_eq!(Seat::Second.side(false), Side::Black);
        assert_eq!(Seat::First.side(true), Side::Black);
        for swapped in [false, true] {
            for seat in [Seat::First, Seat::Second] {
                assert_eq!(Seat::of(seat.side(swapped), swapped), seat);
            }
        }
    }

    #[test]
    fn sides_are_lowercase_in_json() {
        assert_eq!(serde_json::to_string(&Side::White).unwrap(), "\"white\"");
        assert_eq!(serde_json::to_string(&Seat::Second).unwrap(), "\"second\"");
    }
}
