//! What a shot, a round and a match came to: the facts the record keeps and
//! the server announces.

use crate::piece::PieceId;
use crate::rows::Rows;
use crate::side::Side;
use engine::{EndReason, Event};
use glam::DVec2;
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

/// Why a match was won.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum WinReason {
    /// The winner's row reached the far edge.
    FarEdge,
    /// The winner won the single round of a quick match.
    QuickMatch,
    /// The other side resigned.
    Resignation,
    /// The other side let its turn clock run out three times in a row.
    Timeouts,
    /// The other side stayed disconnected past the grace period.
    Abandoned,
}

/// Why a side forfeited (lost without playing the match out).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum ForfeitReason {
    /// Three turn-clock timeouts in a row.
    Timeouts,
    /// Disconnected for longer than the grace period.
    Abandoned,
}

impl ForfeitReason {
    /// The winner's reason when the other side forfeits for this one.
    pub fn win_reason(self) -> WinReason {
        match self {
            ForfeitReason::Timeouts => WinReason::Timeouts,
            ForfeitReason::Abandoned => WinReason::Abandoned,
        }
    }
}

/// How a match ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(tag = "result", rename_all = "kebab-case")]
pub enum MatchResult {
    Won {
        side: Side,
        reason: WinReason,
    },
    /// Only a quick match can be drawn (its single round was drawn).
    Draw,
}

impl MatchResult {
    /// The winner, if any.
    pub fn winner(&self) -> Option<Side> {
        match self {
            MatchResult::Won { side, .. } => Some(*side),
            MatchResult::Draw => None,
        }
    }
}

/// What comes after a shot.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(tag = "next", rename_all = "kebab-case")]
pub enum Next {
    /// `side` shoots next.
    Shoot { side: Side },
    /// Black decides whether to swap seats (pie rule), then White shoots
    /// again if it earned it, else Black.
    PieDecision { then: Side },
    /// The match is over.
    MatchOver { result: MatchResult },
}

/// The end of a round.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct RoundEnd {
    pub result: RoundResult,
    /// The rows of the next round (`None` when the match ended).
    pub next_rows: Option<Rows>,
}

/// Everything one shot did, as recorded and announced.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct ShotOutcome {
    /// Shots played in the match before this one (also picks its noise).
    pub number: u32,
    /// The round it was played in (1-based).
    pub round: u32,
    pub shooter: Side,
    pub piece: PieceId,
    /// The velocity as aimed.
    #[schemars(with = "[f64; 2]")]
    pub aimed: DVec2,
    /// The velocity actually played (after execution noise, if any).
    #[schemars(with = "[f64; 2]")]
    pub played: DVec2,
    /// The engine's event chain (times from the flick, t = 0).
    pub events: Vec<Event>,
    /// Pieces that fell off, in the order they fell.
    pub knocked_off: Vec<PieceId>,
    /// When everything came to rest.
    pub duration: f64,
    /// How the engine's computation ended (`rest` unless a cap was hit).
    pub end_reason: EndReason,
    /// Set if the shot ended the round.
    pub round_end: Option<RoundEnd>,
    /// Whose turn it is next.
    pub next: Next,
}
