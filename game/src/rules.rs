//! The Chapaev turn rule, as pure functions of what a shot did.
//!
//! After a shot: if only one colour is left on the board, the round is won
//! by that colour; if none is left (the last pieces of both sides fell on
//! the same shot), the round is drawn. Otherwise, a shot that knocked off
//! at least one enemy piece and none of the shooter's own earns another
//! shot; anything else passes the turn.
//!
//! Between rounds ([`after_round`]): a drawn round is played again on the
//! same rows; a won round moves the winner's row ([`Rows::advance_apart`],
//! two ranks for a flawless win under `two_row_advance`, the rows meeting
//! two ranks apart under `rows_keep_apart`) and the match is won
//! when it reaches the far edge (or at once under `quick_match`). Who opens
//! the next round is the [`Opening`] rule's choice.

use crate::board::Board;
use crate::config::Variants;
use crate::outcome::{MatchResult, WinReason};
use crate::piece::PieceId;
use crate::rows::{Advance, Rows};
use crate::side::Side;
use serde::{Deserialize, Serialize};

pub use crate::outcome::RoundResult;

/// What happens after a shot (on the wire: `{"verdict": "shoot-again"}`,
/// `{"verdict": "pass-turn"}` or `{"verdict": "round-over", "result":
/// "won", "side": "white"}`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(tag = "verdict", rename_all = "kebab-case")]
pub enum Verdict {
    /// The shooter shoots again.
    ShootAgain,
    /// The other side shoots.
    PassTurn,
    /// The round is over.
    RoundOver(RoundResult),
}

/// The verdict on a shot by `shooter` that knocked off `knocked_off` and
/// left `after` on the board.
pub fn judge(shooter: Side, knocked_off: &[PieceId], after: &Board) -> Verdict {
    let (white, black) = (after.count(Side::White), after.count(Side::Black));
    match (white, black) {
        (0, 0) => return Verdict::RoundOver(RoundResult::Draw),
        (_, 0) => return Verdict::RoundOver(RoundResult::Won(Side::White)),
        (0, _) => return Verdict::RoundOver(RoundResult::Won(Side::Black)),
        _ => {}
    }
    let own = knocked_off.iter().any(|p| p.side() == shooter);
    let enemy = knocked_off.iter().any(|p| p.side() != shooter);
    if enemy && !own {
        Verdict::ShootAgain
    } else {
        Verdict::PassTurn
    }
}

/// Who opens each round after the first (White opens round 1).
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "kebab-case")]
pub enum Opening {
    /// The winner of a round opens the next; after a draw the side that
    /// opened it opens again.
    #[default]
    Winner,
    /// The loser of a round opens the next; after a draw the side that
    /// opened it opens again.
    Loser,
    /// The sides take turns, whatever the result: the side that did not
    /// open a round opens the next.
    Alternate,
}

impl Opening {
    /// Whether this is the default ([`Opening::Winner`]), which a recorded
    /// configuration leaves out.
    pub fn is_winner(&self) -> bool {
        *self == Opening::Winner
    }

    /// The side that opens the round after one opened by `opened` that
    /// ended with `result`.
    pub fn next(self, opened: Side, result: RoundResult) -> Side {
        match (self, result) {
            (Opening::Alternate, _) => opened.opponent(),
            (_, RoundResult::Draw) => opened,
            (Opening::Winner, RoundResult::Won(winner)) => winner,
            (Opening::Loser, RoundResult::Won(winner)) => winner.opponent(),
        }
    }
}

/// What the end of a round leads to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AfterRound {
    /// Another round, on `rows`, opened by `opens`.
    Next { rows: Rows, opens: Side },
    /// The match is over.
    Over(MatchResult),
}

/// What the end of a round on `rows`, opened by `opened`, leads to under
/// `variants`; `flawless`: the winner lost no piece in it.
pub fn after_round(
    variants: &Variants,
    rows: Rows,
    opened: Side,
    result: RoundResult,
    flawless: bool,
) -> AfterRound {
    let opens = variants.opening.next(opened, result);
    let winner = match result {
        RoundResult::Draw if variants.quick_match => return AfterRound::Over(MatchResult::Draw),
        RoundResult::Draw => return AfterRound::Next { rows, opens },
        RoundResult::Won(winner) => winner,
    };
    if variants.quick_match {
        return AfterRound::Over(MatchResult::Won {
            side: winner,
            reason: WinReason::QuickMatch,
        });
    }
    let steps = if variants.two_row_advance && flawless {
        2
    } else {
        1
    };
    let closest = if variants.rows_keep_apart { 2 } else { 1 };
    match rows.advance_apart(winner, steps, closest) {
        Advance::FarEdge => AfterRound::Over(MatchResult::Won {
            side: winner,
            reason: WinReason::FarEdge,
        }),
        Advance::Rows(rows) => AfterRound::Next { rows, opens },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::board::Piece;
    use glam::DVec2;

    fn w(f: u8) -> PieceId {
        PieceId::new(Side::White, f).unwrap()
    }
    fn b(f: u8) -> PieceId {
        PieceId::new(Side::Black, f).unwrap()
    }
    fn board(ids: &[PieceId]) -> Board {
        Board::from_pieces(ids.iter().map(|&id| Piece {
            id,
            pos: DVec2::ZERO,
        }))
    }

    #[test]
    fn knocking_off_an_enemy_and_none_of_your_own_earns_another_shot() {
        assert_eq!(
            judge(Side::White, &[b(1)], &board(&[w(0), b(0)])),
            Verdict::ShootAgain
        );
        assert_eq!(
            judge(Side::Black, &[w(1), w(2)], &board(&[w(0), b(0)])),
            Verdict::ShootAgain
        );
    }

    #[test]
    fn knocking_off_nothing_passes_the_turn() {
        assert_eq!(
            judge(Side::White, &[], &board(&[w(0), b(0)])),
            Verdict::PassTurn
        );
    }

    #[test]
    fn losing_your_own_piece_while_knocking_off_an_enemy_passes_the_turn() {
        assert_eq!(
            judge(Side::White, &[b(1), w(1)], &board(&[w(0), b(0)])),
            Verdict::PassTurn
        );
        assert_eq!(
            judge(Side::White, &[w(1)], &board(&[w(0), b(0)])),
            Verdict::PassTurn
        );
    }

    #[test]
    fn the_round_ends_when_only_one_colour_is_left() {
        assert_eq!(
            judge(Side::White, &[b(0)], &board(&[w(0), w(1)])),
            Verdict::RoundOver(RoundResult::Won(Side::White))
        );
        // Even by knocking off your own last piece.
        assert_eq!(
            judge(Side::White, &[w(0)], &board(&[b(3)])),
            Verdict::RoundOver(RoundResult::Won(Side::Black))
        );
    }

    #[test]
    fn the_last_pieces_of_both_sides_falling_together_is_a_draw() {
        assert_eq!(
            judge(Side::Black, &[w(0), b(0)], &board(&[])),
            Verdict::RoundOver(RoundResult::Draw)
        );
    }

    #[test]
    fn the_opening_rule_names_who_opens_the_next_round() {
        use Side::{Black, White};
        let won = |s| RoundResult::Won(s);
        assert_eq!(Opening::Winner.next(White, won(Black)), Black);
        assert_eq!(Opening::Winner.next(Black, RoundResult::Draw), Black);
        assert_eq!(Opening::Loser.next(White, won(White)), Black);
        assert_eq!(Opening::Loser.next(White, RoundResult::Draw), White);
        for result in [won(White), won(Black), RoundResult::Draw] {
            assert_eq!(Opening::Alternate.next(White, result), Black);
            assert_eq!(Opening::Alternate.next(Black, result), White);
        }
    }

    #[test]
    fn after_a_round_the_rows_move_and_the_match_ends_at_the_far_edge() {
        let mut v = Variants::default();
        let rows = Rows::initial();
        let white_won = RoundResult::Won(Side::White);
        assert_eq!(
            after_round(&v, rows, Side::White, white_won, true),
            AfterRound::Next {
                rows: Rows::new(1, 7).unwrap(),
                opens: Side::White
            }
        );
        v.two_row_advance = true;
        v.opening = Opening::Alternate;
        assert_eq!(
            after_round(&v, rows, Side::White, white_won, true),
            AfterRound::Next {
                rows: Rows::new(2, 7).unwrap(),
                opens: Side::Black
            }
        );
        assert_eq!(
            after_round(&v, rows, Side::Black, RoundResult::Draw, false),
            AfterRound::Next {
                rows,
                opens: Side::White
            }
        );
        let last = Rows::new(6, 7).unwrap();
        assert_eq!(
            after_round(&v, last, Side::White, white_won, false),
            AfterRound::Over(MatchResult::Won {
                side: Side::White,
                reason: WinReason::FarEdge
            })
        );
        v.quick_match = true;
        assert_eq!(
            after_round(&v, rows, Side::White, RoundResult::Draw, false),
            AfterRound::Over(MatchResult::Draw)
        );
    }
}
