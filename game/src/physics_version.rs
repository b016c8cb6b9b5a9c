//! The physics version: which computation decides what a shot does. It
//! covers everything between an aimed flick and its recorded outcome — the
//! [`engine`] (collisions, friction, the event order, the last bit of every
//! time), the game's physics setup ([`crate::physics`]: the scene, the
//! edges, the fall-off rule; the board's geometry), the execution noise
//! ([`crate::noise`]) and the turn rule that judges the result. Every match
//! is played under one version, and its record says which.
//!
//! A change that alters the outcome of any shot — one bit of one number is
//! enough — makes a new version: [`PHYSICS_VERSION`] goes up, a new variant
//! joins [`PhysicsVersion`], and the old variant keeps computing exactly
//! what it computed before (a frozen copy of the old code, or of the old
//! engine as a second dependency), so that matches recorded or begun under
//! it still replay and resume. The golden records in `game/tests/golden/`
//! hold each version to its word. Until then there is one version and its
//! one implementation; [`PhysicsVersion::played`] and
//! [`PhysicsVersion::resolve`] are where a version picks its physics.
//!
//! New matches, and every simulation of a shot that is not yet played
//! ([`crate::simulate`], the bots), use [`PhysicsVersion::CURRENT`].

use crate::board::Board;
use crate::config::Config;
use crate::noise::{self, NoiseKey};
use crate::physics::{self, Resolution};
use crate::piece::PieceId;
use engine::Revision;
use glam::DVec2;

/// The number of the physics version this build plays new matches under.
pub const PHYSICS_VERSION: u32 = 6;

/// A physics version this build can play.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PhysicsVersion {
    /// The event-driven engine with the fall-off edges and the SplitMix64
    /// noise, as every match was played from the first record on: the
    /// engine's first revision ([`Revision::R1`]).
    V1,
    /// As V1, on the engine's second revision ([`Revision::R2`]): pieces
    /// pressed together obliquely no longer drift into each other, and a
    /// chain of pieces collapsing against each other or the edge comes to
    /// its limit at once.
    V2,
    /// As V2, on the engine's third revision ([`Revision::R3`]): a piece
    /// pressed against a row or cluster of pieces, or against the edge, is
    /// kicked apart from all of them at once; pieces left sliding slower
    /// than their positions can show stop; and a shot whose events no
    /// longer move anything ends instead of running to the event cap.
    V3,
    /// As V3, on the engine's fourth revision ([`Revision::R4`]): pieces
    /// pressed against each other in one cluster are kicked apart together
    /// instead of in turn, and a pressed pair that stops stops the barely
    /// moving pieces touching it too.
    V4,
    /// As V4, on the engine's fifth revision ([`Revision::R5`]): pieces
    /// that slide pressed together and knock into each other again and
    /// again at one moment move as one at once, instead of after hundreds
    /// of ever gentler knocks.
    V5,
    /// As V5, on the engine's sixth revision ([`Revision::R6`]): pieces
    /// pressed together obliquely are kept within a gap of 1e-4 of their
    /// contact distance (3 micrometres between two checkers) instead of
    /// 1e-6, with a tenth of the knocks.
    V6,
}

/// A physics version this build cannot play: a record of it is refused
/// rather than replayed with other physics.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "the match was played under physics version {found}, which this build cannot play \
     (it plays versions {})",
    supported()
)]
pub struct UnsupportedPhysics {
    /// The version asked for.
    pub found: u32,
}

/// The versions this build plays, as `1, 2, ...`.
fn supported() -> String {
    PhysicsVersion::ALL
        .iter()
        .map(|v| v.number().to_string())
        .collect::<Vec<_>>()
        .join(", ")
}

impl PhysicsVersion {
    /// The version new matches are played under.
    pub const CURRENT: PhysicsVersion = PhysicsVersion::V6;

    /// Every version this build plays, oldest first.
    pub const ALL: [PhysicsVersion; 6] = [
        PhysicsVersion::V1,
        PhysicsVersion::V2,
        PhysicsVersion::V3,
        PhysicsVersion::V4,
        PhysicsVersion::V5,
        PhysicsVersion::V6,
    ];

    /// The version's number, as records and the store keep it.
    pub fn number(self) -> u32 {
        match self {
            PhysicsVersion::V1 => 1,
            PhysicsVersion::V2 => 2,
            PhysicsVersion::V3 => 3,
            PhysicsVersion::V4 => 4,
            PhysicsVersion::V5 => 5,
            PhysicsVersion::V6 => 6,
        }
    }

    /// The engine revision this version computes shots with.
    pub const fn revision(self) -> Revision {
        match self {
            PhysicsVersion::V1 => Revision::R1,
            PhysicsVersion::V2 => Revision::R2,
            PhysicsVersion::V3 => Revision::R3,
            PhysicsVersion::V4 => Revision::R4,
            PhysicsVersion::V5 => Revision::R5,
            PhysicsVersion::V6 => Revision::R6,
        }
    }

    /// The version numbered `number`, if this build plays it.
    pub fn from_number(number: u32) -> Result<PhysicsVersion, UnsupportedPhysics> {
        PhysicsVersion::ALL
            .into_iter()
            .find(|v| v.number() == number)
            .ok_or(UnsupportedPhysics { found: number })
    }

    /// The velocity actually played when `aimed` is shot as shot number
    /// `shot` of a match of `config` whose noise is keyed by `key`: with
    /// the match's execution noise, if it has any. (The key's scheme is the
    /// record format's business, not the physics version's: every version
    /// draws with whichever key the match has.)
    pub fn played(self, config: &Config, key: &NoiseKey, shot: u32, aimed: DVec2) -> DVec2 {
        match self {
            PhysicsVersion::V1
            | PhysicsVersion::V2
            | PhysicsVersion::V3
            | PhysicsVersion::V4
            | PhysicsVersion::V5
            | PhysicsVersion::V6 => match &config.variants.noise {
                Some(n) => noise::perturb(n, key, shot, aimed, config.max_speed),
                None => aimed,
            },
        }
    }

    /// `piece` flicked at `velocity` on `board`, computed to the end of its
    /// chain.
    pub fn resolve(
        self,
        config: &Config,
        board: &Board,
        piece: PieceId,
        velocity: DVec2,
    ) -> Result<Resolution, String> {
        physics::resolve(config, board, piece, velocity, self.revision())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_current_version_is_the_newest_and_carries_the_constants_number() {
        assert_eq!(PhysicsVersion::CURRENT.number(), PHYSICS_VERSION);
        assert_eq!(PhysicsVersion::ALL.last(), Some(&PhysicsVersion::CURRENT));
        for v in PhysicsVersion::ALL {
            assert_eq!(PhysicsVersion::from_number(v.number()), Ok(v));
        }
    }

    #[test]
    fn a_version_this_build_does_not_play_is_refused_by_number() {
        for n in [0, PHYSICS_VERSION + 1, u32::MAX] {
            let err = PhysicsVersion::from_number(n).unwrap_err();
            assert_eq!(err, UnsupportedPhysics { found: n });
            assert!(
                err.to_string().contains(&format!(
                    "physics version {n}, which this build cannot play"
                )),
                "{err}"
            );
            assert!(
                err.to_string().contains("plays versions 1, 2, 3, 4, 5, 6)"),
                "{err}"
            );
        }
    }
}
