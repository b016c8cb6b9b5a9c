//! The board: its geometry (square centres, the four edges as engine sensor
//! lines) and the pieces standing on it between shots.
//!
//! Coordinates are metres with the origin at the corner of White's first
//! row on file a: x runs along the files, y along the ranks, so the board is
//! `[0, L] x [0, L]` with `L = 8 * square`. The edges are sensors walked
//! counter-clockwise, so the board is on their left (their inside): a piece
//! whose centre crosses one outwards has fallen off.

use crate::config::Config;
use crate::piece::PieceId;
use crate::rows::Rows;
use crate::side::Side;
use engine::{Line, LineKind};
use glam::DVec2;
use serde::{Deserialize, Serialize};

/// A piece standing on the board.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Piece {
    pub id: PieceId,
    #[schemars(with = "[f64; 2]")]
    pub pos: DVec2,
}

/// The pieces on the board, in id order, all at rest.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(transparent)]
pub struct Board {
    pieces: Vec<Piece>,
}

impl Board {
    /// Both rows set up for a round: every piece on its file, at its side's rank.
    pub fn setup(config: &Config, rows: Rows) -> Board {
        let pieces = PieceId::all()
            .map(|id| Piece {
                id,
                pos: square_centre(config, id.file(), rows.rank(id.side())),
            })
            .collect();
        Board { pieces }
    }

    /// A board holding exactly `pieces` (sorted by id; a later duplicate
    /// replaces an earlier one). Used for the state after a shot and for
    /// positions set up by hand.
    pub fn from_pieces(pieces: impl IntoIterator<Item = Piece>) -> Board {
        let mut v: Vec<Piece> = Vec::new();
        for p in pieces {
            match v.iter_mut().find(|q| q.id == p.id) {
                Some(q) => *q = p,
                None => v.push(p),
            }
        }
        v.sort_by_key(|p| p.id);
        Board { pieces: v }
    }

    /// The pieces, in id order.
    pub fn pieces(&self) -> &[Piece] {
        &self.pieces
    }

    /// One piece, if it is on the board.
    pub fn piece(&self, id: PieceId) -> Option<&Piece> {
        self.pieces.iter().find(|p| p.id == id)
    }

    /// Whether the piece is on the board.
    pub fn contains(&self, id: PieceId) -> bool {
        self.piece(id).is_some()
    }

    /// How many pieces `side` has on the board.
    pub fn count(&self, side: Side) -> usize {
        self.pieces.iter().filter(|p| p.id.side() == side).count()
    }

    /// The pieces of one side.
    pub fn of(&self, side: Side) -> impl Iterator<Item = &Piece> {
        self.pieces.iter().filter(move |p| p.id.side() == side)
    }
}

/// The centre of the square on `file`, `rank` (both 0–7).
pub fn square_centre(config: &Config, file: u8, rank: u8) -> DVec2 {
    DVec2::new(
        (file as f64 + 0.5) * config.square,
        (rank as f64 + 0.5) * config.square,
    )
}

/// Whether a centre at `pos` is on the board (edges included).
pub fn is_on_board(config: &Config, pos: DVec2) -> bool {
    let l = config.board_size();
    (0.0..=l).contains(&pos.x) && (0.0..=l).contains(&pos.y)
}

/// The four board edges as sensor lines, counter-clockwise (bottom, right,
/// top, left), so the board is on the left of each: a centre crossing one
/// outwards fires the engine's region exit.
pub fn edges(config: &Config) -> [Line; 4] {
    let l = config.board_size();
    let corners = [
        DVec2::new(0.0, 0.0),
        DVec2::new(l, 0.0),
        DVec2::new(l, l),
        DVec2::new(0.0, l),
    ];
    std::array::from_fn(|k| Line::sensor(corners[k], corners[(k + 1) % 4], LineKind::Line))
}

#[cfg(test)]
mod tests {
    use super::*;
    use engine::obstacle::LineGeom;

    #[test]
    fn setup_puts_one_piece_per_square_of_each_row() {
        let c = Config::default();
        let b = Board::setup(&c, Rows::initial());
        assert_eq!(b.count(Side::White), 8);
        assert_eq!(b.count(Side::Black), 8);
        for p in b.pieces() {
            let rank = if p.id.side() == Side::White { 0 } else { 7 };
            assert_eq!(p.pos, square_centre(&c, p.id.file(), rank));
        }
        let e = PieceId::new(Side::White, 4).unwrap();
        assert_eq!(b.piece(e).unwrap().pos, DVec2::new(0.18, 0.02));
    }

    #[test]
    fn neighbouring_pieces_do_not_touch() {
        let c = Config::default();
        let b = Board::setup(&c, Rows::new(3, 4).unwrap());
        for p in b.pieces() {
            for q in b.pieces() {
                if p.id != q.id {
                    assert!((p.pos - q.pos).length() > 2.0 * c.piece_radius);
                }
            }
        }
    }

    #[test]
    fn edges_run_counter_clockwise_with_the_board_on_their_left() {
        let c = Config::default();
        let centre = DVec2::splat(c.board_size() / 2.0);
        for e in edges(&c) {
            assert!(e.sensor);
            let g = LineGeom::new(&e).unwrap();
            assert!(g.signed_distance(centre) > 0.0);
            assert_eq!(g.signed_distance(centre), c.board_size() / 2.0);
        }
    }

    #[test]
    fn from_pieces_sorts_by_id_and_keeps_one_per_id() {
        let a = PieceId::new(Side::Black, 0).unwrap();
        let b = PieceId::new(Side::White, 0).unwrap();
        let board = Board::from_pieces([
            Piece {
                id: a,
                pos: DVec2::ZERO,
            },
            Piece {
                id: b,
                pos: DVec2::ONE,
            },
            Piece {
                id: a,
                pos: DVec2::X,
            },
        ]);
        assert_eq!(board.pieces().len(), 2);
        assert_eq!(board.pieces()[0].id, b);
        assert_eq!(board.piece(a).unwrap().pos, DVec2::X);
        assert!(is_on_board(&Config::default(), DVec2::new(0.32, 0.0)));
        assert!(!is_on_board(&Config::default(), DVec2::new(0.33, 0.1)));
    }
}
