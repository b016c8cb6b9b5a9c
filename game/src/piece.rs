//! Piece identity. Each side has eight pieces, one per file; a [`PieceId`]
//! names one of the sixteen and can only hold a valid value (0–7 White's on
//! files a–h, 8–15 Black's). The engine body of a piece has the same number
//! as its id, so events name pieces directly.

use crate::side::Side;
use engine::BodyId;
use serde::{Deserialize, Serialize};
use std::fmt;

/// Pieces per side (one per file of the board).
pub const PIECES_PER_SIDE: u8 = 8;

/// One of the sixteen pieces (serialised as its number, 0–15).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(try_from = "u8", into = "u8")]
pub struct PieceId(u8);

impl schemars::JsonSchema for PieceId {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "PieceId".into()
    }

    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        schemars::json_schema!({
            "description": "One of the sixteen pieces: 0-7 White's on files a-h, 8-15 Black's.",
            "type": "integer",
            "minimum": 0,
            "maximum": 15,
        })
    }
}

/// A number that names no piece.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("no piece has number {0} (pieces are 0-15)")]
pub struct BadPieceId(pub u64);

impl PieceId {
    /// The piece of `side` that starts on `file` (0–7), if the file exists.
    pub fn new(side: Side, file: u8) -> Option<PieceId> {
        (file < PIECES_PER_SIDE).then(|| PieceId(side.index() as u8 * PIECES_PER_SIDE + file))
    }

    /// All sixteen pieces, White's first.
    pub fn all() -> impl Iterator<Item = PieceId> {
        (0..2 * PIECES_PER_SIDE).map(PieceId)
    }

    /// The eight pieces of one side.
    pub fn of(side: Side) -> impl Iterator<Item = PieceId> {
        (0..PIECES_PER_SIDE).filter_map(move |f| PieceId::new(side, f))
    }

    /// Whose piece it is.
    pub fn side(self) -> Side {
        if self.0 < PIECES_PER_SIDE {
            Side::White
        } else {
            Side::Black
        }
    }

    /// The file (0–7) it starts each round on.
    pub fn file(self) -> u8 {
        self.0 % PIECES_PER_SIDE
    }

    /// Its number, 0–15.
    pub fn number(self) -> u8 {
        self.0
    }

    /// The engine body that plays it.
    pub fn body(self) -> BodyId {
        BodyId(self.0 as u64)
    }

    /// The piece an engine body plays.
    pub fn from_body(body: BodyId) -> Result<PieceId, BadPieceId> {
        u8::try_from(body.0)
            .ok()
            .and_then(|n| PieceId::try_from(n).ok())
            .ok_or(BadPieceId(body.0))
    }
}

impl TryFrom<u8> for PieceId {
    type Error = BadPieceId;
    fn try_from(n: u8) -> Result<Self, BadPieceId> {
        if n < 2 * PIECES_PER_SIDE {
            Ok(PieceId(n))
        } else {
            Err(BadPieceId(n as u64))
        }
    }
}

impl From<PieceId> for u8 {
    fn from(p: PieceId) -> u8 {
        p.0
    }
}

impl fmt::Display for PieceId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let file = (b'a' + self.file()) as char;
        write!(f, "{} piece {file}", self.side())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_name_side_and_file() {
        let p = PieceId::new(Side::Black, 2).unwrap();
        assert_eq!(p.side(), Side::Black);
        assert_eq!(p.file(), 2);
        assert_eq!(p.number(), 10);
        assert_eq!(p.to_string(), "black piece c");
        assert!(PieceId::new(Side::White, 8).is_none());
        assert_eq!(PieceId::all().count(), 16);
        assert!(PieceId::of(Side::White).all(|p| p.side() == Side::White));
    }

    #[test]
    fn out_of_range_numbers_are_not_pieces_even_from_json() {
        assert!(PieceId::try_from(16).is_err());
        assert!(serde_json::from_str::<PieceId>("16").is_err());
        assert_eq!(
            serde_json::from_str::<PieceId>("15").unwrap().side(),
            Side::Black
        );
        assert!(PieceId::from_body(BodyId(300)).is_err());
        assert_eq!(PieceId::from_body(BodyId(3)).unwrap().number(), 3);
    }
}
