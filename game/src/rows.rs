//! Where each side sets up its row, and how rows move between rounds.
//!
//! Ranks count from White's edge: 0 is White's first row, 7 Black's. The
//! winner of a round moves its row one rank towards the opponent; once the
//! two rows are adjacent (they "meet"), the winner steps into the loser's
//! rank and pushes the loser one rank back. A side whose row reaches the far
//! edge (rank 7 for White, rank 0 for Black), or pushes the loser's row off
//! the board, wins the match. Under the `rows_keep_apart` variant the rows
//! meet two ranks apart and stay so: the winner advances one rank and
//! pushes the loser one back, keeping a clear rank between them.

use crate::config::BOARD_SQUARES;
use crate::side::Side;
use serde::{Deserialize, Serialize};

/// The two rows: White's rank is always below Black's.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(try_from = "RawRows")]
pub struct Rows {
    white: u8,
    black: u8,
}

#[derive(Deserialize, schemars::JsonSchema)]
struct RawRows {
    white: u8,
    black: u8,
}

/// Ranks that are not a legal pair of rows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("rows white {white}, black {black}: need white < black <= 7")]
pub struct BadRows {
    pub white: u8,
    pub black: u8,
}

impl TryFrom<RawRows> for Rows {
    type Error = BadRows;
    fn try_from(r: RawRows) -> Result<Rows, BadRows> {
        Rows::new(r.white, r.black)
    }
}

/// What a round win does to the rows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Advance {
    /// The rows for the next round.
    Rows(Rows),
    /// The winner's row reached the far edge: the match is won.
    FarEdge,
}

const LAST_RANK: u8 = BOARD_SQUARES - 1;

impl Rows {
    /// The rows of round 1: White on rank 0, Black on rank 7.
    pub fn initial() -> Rows {
        Rows {
            white: 0,
            black: LAST_RANK,
        }
    }

    /// Rows at the given ranks, if White's is below Black's on the board.
    pub fn new(white: u8, black: u8) -> Result<Rows, BadRows> {
        if white < black && black <= LAST_RANK {
            Ok(Rows { white, black })
        } else {
            Err(BadRows { white, black })
        }
    }

    /// The rank `side` sets up on.
    pub fn rank(self, side: Side) -> u8 {
        match side {
            Side::White => self.white,
            Side::Black => self.black,
        }
    }

    /// The rank whose reaching wins the match for `side`.
    pub fn far_edge(side: Side) -> u8 {
        match side {
            Side::White => LAST_RANK,
            Side::Black => 0,
        }
    }

    /// Whether the rows are adjacent (the next win pushes the loser back).
    pub fn have_met(self) -> bool {
        self.white + 1 == self.black
    }

    /// The rows after `winner` wins a round worth `steps` ranks.
    pub fn advance(self, winner: Side, steps: u8) -> Advance {
        self.advance_apart(winner, steps, 1)
    }

    /// The rows after `winner` wins a round worth `steps` ranks, when rows
    /// meet `closest` ranks apart (1: adjacent, the classic rule; 2: a
    /// clear rank between them).
    pub fn advance_apart(self, winner: Side, steps: u8, closest: u8) -> Advance {
        let mut rows = self;
        for _ in 0..steps {
            match rows.step(winner, closest.max(1)) {
                Advance::Rows(r) => rows = r,
                Advance::FarEdge => return Advance::FarEdge,
            }
        }
        Advance::Rows(rows)
    }

    fn step(self, winner: Side, closest: u8) -> Advance {
        let met = self.black - self.white <= closest;
        let Rows { white, black } = self;
        match winner {
            Side::White => {
                if white + 1 == LAST_RANK || (met && black == LAST_RANK) {
                    return Advance::FarEdge;
                }
                let black = if met { black + 1 } else { black };
                Advance::Rows(Rows {
                    white: white + 1,
                    black,
                })
            }
            Side::Black => {
                if black == 1 || (met && white == 0) {
                    return Advance::FarEdge;
                }
                let white = if met { white - 1 } else { white };
                Advance::Rows(Rows {
                    white,
                    black: black - 1,
                })
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows(w: u8, b: u8) -> Rows {
        Rows::new(w, b).unwrap()
    }

    #[test]
    fn round_one_puts_white_on_the_first_row_and_black_on_the_last() {
        assert_eq!(Rows::initial().rank(Side::White), 0);
        assert_eq!(Rows::initial().rank(Side::Black), 7);
    }

    #[test]
    fn a_round_winner_moves_its_row_one_rank_forward() {
        assert_eq!(
            Rows::initial().advance(Side::White, 1),
            Advance::Rows(rows(1, 7))
        );
        assert_eq!(
            Rows::initial().advance(Side::Black, 1),
            Advance::Rows(rows(0, 6))
        );
    }

    #[test]
    fn once_rows_meet_the_winner_advances_and_the_loser_is_pushed_back() {
        let met = rows(3, 4);
        assert!(met.have_met());
        assert_eq!(met.advance(Side::White, 1), Advance::Rows(rows(4, 5)));
        assert_eq!(met.advance(Side::Black, 1), Advance::Rows(rows(2, 3)));
        // Rows one apart meet after one more win, then push.
        assert_eq!(
            rows(2, 4).advance(Side::White, 2),
            Advance::Rows(rows(4, 5))
        );
    }

    #[test]
    fn reaching_the_far_edge_wins_the_match() {
        assert_eq!(rows(6, 7).advance(Side::White, 1), Advance::FarEdge);
        assert_eq!(
            rows(5, 7).advance(Side::White, 1),
            Advance::Rows(rows(6, 7))
        );
        assert_eq!(rows(0, 1).advance(Side::Black, 1), Advance::FarEdge);
        assert_eq!(
            rows(0, 2).advance(Side::Black, 1),
            Advance::Rows(rows(0, 1))
        );
        assert_eq!(
            rows(3, 7).advance(Side::Black, 1),
            Advance::Rows(rows(3, 6))
        );
    }

    #[test]
    fn rows_kept_apart_meet_two_ranks_apart_and_push_from_there() {
        let apart = |r: Rows, side| r.advance_apart(side, 1, 2);
        assert_eq!(apart(rows(0, 7), Side::White), Advance::Rows(rows(1, 7)));
        assert_eq!(apart(rows(2, 5), Side::White), Advance::Rows(rows(3, 5)));
        // Two apart: the winner advances and the loser is pushed back.
        assert_eq!(apart(rows(3, 5), Side::White), Advance::Rows(rows(4, 6)));
        assert_eq!(apart(rows(3, 5), Side::Black), Advance::Rows(rows(2, 4)));
        // A loser pushed off its own edge loses the match.
        assert_eq!(apart(rows(5, 7), Side::White), Advance::FarEdge);
        assert_eq!(apart(rows(0, 2), Side::Black), Advance::FarEdge);
        assert_eq!(
            rows(0, 7).advance_apart(Side::White, 2, 2),
            Advance::Rows(rows(2, 7))
        );
        // Closest 1 is the classic rule.
        for (w, b) in [(0, 7), (3, 4), (2, 4), (6, 7)] {
            for side in Side::BOTH {
                assert_eq!(
                    rows(w, b).advance_apart(side, 1, 1),
                    rows(w, b).advance(side, 1)
                );
            }
        }
    }

    #[test]
    fn two_row_advance_stops_at_the_far_edge() {
        assert_eq!(
            rows(0, 7).advance(Side::White, 2),
            Advance::Rows(rows(2, 7))
        );
        assert_eq!(rows(5, 7).advance(Side::White, 2), Advance::FarEdge);
        assert_eq!(rows(0, 2).advance(Side::Black, 2), Advance::FarEdge);
    }

    #[test]
    fn illegal_rows_are_refused_even_from_json() {
        assert!(Rows::new(4, 4).is_err());
        assert!(Rows::new(0, 8).is_err());
        assert!(serde_json::from_str::<Rows>(r#"{"white":5,"black":2}"#).is_err());
        let r: Rows = serde_json::from_str(r#"{"white":2,"black":5}"#).unwrap();
        assert_eq!(r, rows(2, 5));
    }
}
