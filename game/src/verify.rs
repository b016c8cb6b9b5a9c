//! Checking a finished match's fairness from its record alone.
//!
//! [`verify`] takes the record a server publishes when a match is over and
//! checks three things, in order, each with its own error:
//! 1. the revealed secret hashes to the commitment published before the
//!    first shot (so the server could not pick the secret afterwards);
//! 2. every shot's `played` velocity is, bit for bit, its `aimed` velocity
//!    under the draw that the secret gives that shot's number (so no shot
//!    was given other noise than the secret's);
//! 3. replaying the whole match gives every recorded outcome bit for bit
//!    (so no outcome was made up).
//!
//! The same function is in the JavaScript and Python packages and behind
//! `bots verify record.json`. Anyone can also check (1) and (2) without
//! this code: a SHA-256, ChaCha20 and the Box–Muller formula of
//! [`crate::noise`].

use crate::noise::{NoiseDraw, NoiseKey, NoiseScheme};
use crate::physics_version::{PhysicsVersion, UnsupportedPhysics};
use crate::record::{MatchRecord, RecordError, RecordedMove};
use crate::replay::{Replay, ReplayError};
use crate::secret::NoiseCommitment;

/// What a successful [`verify`] checked.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Verification {
    /// The scheme the noise was drawn with.
    pub scheme: NoiseScheme,
    /// The commitment the revealed secret opened.
    pub commitment: NoiseCommitment,
    /// Shots whose noise and outcome were checked.
    pub shots: usize,
    /// Each shot's draw, in order (what the secret gave it).
    pub draws: Vec<NoiseDraw>,
}

/// Why a record does not verify.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum VerifyError {
    /// The record is of a format before commitments (1–3: a plain seed).
    #[error("a version {version} record has no noise commitment to verify (commitments start with version 4)")]
    Uncommitted { version: u32 },
    /// No secret revealed, or one that does not open the commitment.
    #[error(transparent)]
    Secret(RecordError),
    #[error(transparent)]
    Physics(#[from] UnsupportedPhysics),
    /// A shot was played with other noise than the secret gives it.
    #[error(
        "move {index} (shot {shot}): the played velocity is not the aimed one under the secret's draw"
    )]
    NoiseMismatch { index: usize, shot: u32 },
    /// The match does not replay to its recorded outcomes.
    #[error("the record's noise is right but the match does not replay: {0}")]
    Replay(#[from] ReplayError),
}

impl VerifyError {
    /// A stable short name of the failure, for the language packages'
    /// errors (`error.code` in JavaScript, `.code` in Python).
    pub fn code(&self) -> &'static str {
        match self {
            VerifyError::Uncommitted { .. } => "uncommitted",
            VerifyError::Secret(RecordError::SecretNotRevealed) => "secret-not-revealed",
            VerifyError::Secret(RecordError::CommitmentMismatch { .. }) => "commitment-mismatch",
            VerifyError::Secret(_) => "bad-record",
            VerifyError::Physics(_) => "unsupported-physics",
            VerifyError::NoiseMismatch { .. } => "noise-mismatch",
            VerifyError::Replay(ReplayError::Record(_)) => "bad-record",
            VerifyError::Replay(_) => "replay-diverged",
        }
    }
}

/// Checks a finished match's record: commitment, every draw, every outcome.
pub fn verify(record: &MatchRecord) -> Result<Verification, VerifyError> {
    let Some(commitment) = record.commitment() else {
        return Err(VerifyError::Uncommitted {
            version: record.version,
        });
    };
    let key = record.key().map_err(VerifyError::Secret)?;
    if !matches!(key, NoiseKey::ChaCha20(_)) {
        return Err(VerifyError::Uncommitted {
            version: record.version,
        });
    }
    let physics = PhysicsVersion::from_number(record.physics)?;
    let mut draws = Vec::new();
    for (index, m) in record.moves.iter().enumerate() {
        let RecordedMove::Shot(shot) = m else {
            continue;
        };
        let played = physics.played(&record.config, &key, shot.number, shot.aimed);
        let same = played.x.to_bits() == shot.played.x.to_bits()
            && played.y.to_bits() == shot.played.y.to_bits();
        if !same || shot.number as usize != draws.len() {
            return Err(VerifyError::NoiseMismatch {
                index,
                shot: shot.number,
            });
        }
        draws.push(key.draw(shot.number));
    }
    Replay::new(record.clone())?;
    Ok(Verification {
        scheme: key.scheme(),
        commitment,
        shots: draws.len(),
        draws,
    })
}

/// [`verify`] of a record's JSON text (read with every number's exact bits).
pub fn verify_json(text: &str) -> Result<Verification, VerifyError> {
    let record = MatchRecord::from_json(text).map_err(|e| VerifyError::Replay(e.into()))?;
    verify(&record)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Config;
    use crate::game::Game;
    use crate::testing::random_match;
    use crate::NoiseSecret;

    fn finished() -> MatchRecord {
        let (game, _) = random_match(Config::standard(), 5, 20_000);
        assert!(game.is_over());
        game.record().clone()
    }

    #[test]
    fn a_finished_match_verifies_and_reports_each_draw() {
        let record = finished();
        let v = verify(&record).unwrap();
        assert_eq!(v.scheme, NoiseScheme::Chacha20);
        assert_eq!(v.shots, record.shots().count());
        assert!(v.shots > 0);
        assert_eq!(Some(v.commitment), record.commitment());
        assert_eq!(verify_json(&record.to_json()), Ok(v));
    }

    #[test]
    fn tampering_with_one_shot_of_a_record_is_caught() {
        let record = finished();
        let index = record
            .moves
            .iter()
            .position(|m| matches!(m, RecordedMove::Shot(s) if s.number == 3))
            .unwrap();
        // A server that gave shot 3 a gentler hand than the secret's.
        let mut softer = record.clone();
        if let RecordedMove::Shot(s) = &mut softer.moves[index] {
            s.played = s.aimed;
        }
        assert_eq!(
            verify(&softer),
            Err(VerifyError::NoiseMismatch { index, shot: 3 })
        );
        // One that claimed another aim for the same result.
        let mut reaimed = record.clone();
        if let RecordedMove::Shot(s) = &mut reaimed.moves[index] {
            s.aimed.x = f64::from_bits(s.aimed.x.to_bits() ^ 1);
        }
        assert!(matches!(
            verify(&reaimed),
            Err(VerifyError::NoiseMismatch { .. })
        ));
        // One that made up what a shot knocked off.
        let mut invented = record.clone();
        if let RecordedMove::Shot(s) = &mut invented.moves[index] {
            s.duration = f64::from_bits(s.duration.to_bits() ^ 1);
        }
        assert!(matches!(verify(&invented), Err(VerifyError::Replay(_))));
    }

    #[test]
    fn a_secret_other_than_the_committed_one_is_caught() {
        let mut record = finished();
        record.noise.as_mut().unwrap().secret = Some(NoiseSecret::from_seed(6));
        assert!(matches!(
            verify(&record),
            Err(VerifyError::Secret(RecordError::CommitmentMismatch { .. }))
        ));
        record.noise.as_mut().unwrap().secret = None;
        assert_eq!(
            verify(&record),
            Err(VerifyError::Secret(RecordError::SecretNotRevealed))
        );
    }

    #[test]
    fn a_live_match_reveals_nothing_and_a_finished_one_reveals_its_secret() {
        let mut game = Game::new(Config::standard(), NoiseSecret::from_bytes([3; 32])).unwrap();
        let json = game.record().to_json();
        assert!(!json.contains(&NoiseSecret::from_bytes([3; 32]).to_hex()));
        assert!(game.view().noise_commitment.is_some());
        game.resign(crate::Side::White).unwrap();
        let json = game.record().to_json();
        assert!(json.contains(&NoiseSecret::from_bytes([3; 32]).to_hex()));
        assert_eq!(verify_json(&json).map(|v| v.shots), Ok(0));
    }

    #[test]
    fn an_old_record_with_a_plain_seed_has_nothing_to_verify() {
        let game = Game::new(Config::standard(), NoiseKey::SplitMix64(4)).unwrap();
        assert_eq!(
            verify(game.record()),
            Err(VerifyError::Uncommitted { version: 3 })
        );
    }
}
