//! The Chapaev turn rule, as pure functions of what a shot did.
//!
//! After a shot: if only one colour is left on the board, the round is won
//! by that colour; if none is left (the last pieces of both sides fell on
//! the same shot), the round is drawn. Otherwise, a shot that knocked off
//! at least one enemy piece and none of the shooter's own earns another
//! shot; anything else passes the turn.

use crate::board::Board;
use crate::piece::PieceId;
use crate::side::Side;
use serde::{Deserialize, Serialize};

/// How a round ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(tag = "result", content = "side", rename_all = "kebab-case")]
pub enum RoundResult {
    /// Only this colour is left on the board.
    Won(Side),
    /// The last pieces of both sides fell on the same shot.
    Draw,
}

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
}
