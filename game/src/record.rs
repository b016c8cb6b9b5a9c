//! The match record: the configuration, the noise's key, the physics
//! version, and every move in order with what it did — enough to replay
//! the match bit for bit. It is JSON with a `version` field (the record's
//! format); a record of an unknown format is refused with a clear error
//! rather than misread. A record of a physics version this build cannot
//! play is still read (it is data), but [`crate::Replay`] refuses to replay
//! it.
//!
//! From format 4 on the noise is sealed ([`SealedNoise`]): the record names
//! the scheme and the commitment to the match's secret, and reveals the
//! secret itself once the match is over. Formats 1–3 carried a plain
//! 64-bit `seed` instead (the `splitmix64` scheme), and still replay.

use crate::config::Config;
use crate::noise::{NoiseKey, NoiseScheme};
use crate::outcome::{ForfeitReason, ShotOutcome};
use crate::physics_version::PhysicsVersion;
use crate::secret::{NoiseCommitment, NoiseSecret};
use crate::side::Side;
use serde::{Deserialize, Serialize};

/// The record format this crate writes. Version 4 sealed the noise (a
/// committed ChaCha20 secret instead of a seed); version 3 added the
/// `physics` field; versions 1 (without passes and forfeits) and 2 are
/// still read, as records of physics version 1 (the only physics they were
/// played under).
pub const RECORD_VERSION: u32 = 4;

/// The last record format that keys its noise with a plain `seed`.
const LAST_VERSION_WITH_SEED: u64 = 3;

/// The first record format that carries the `physics` field.
const FIRST_VERSION_WITH_PHYSICS: u64 = 3;

/// The physics version of a record written before records said (formats 1
/// and 2).
fn physics_of_old_records() -> u32 {
    1
}

/// The oldest record format this crate reads.
pub const OLDEST_RECORD_VERSION: u32 = 1;

/// One move of a match.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(tag = "move", rename_all = "kebab-case")]
pub enum RecordedMove {
    /// A shot (who, which piece, as aimed, and what it did).
    Shot(ShotOutcome),
    /// Black's pie-rule decision.
    Pie { swap: bool },
    /// A side resigned.
    Resign { side: Side },
    /// A side's turn clock ran out: its turn passed without a shot.
    Pass { side: Side },
    /// A side lost without playing on.
    Forfeit { side: Side, reason: ForfeitReason },
}

/// A match's noise as a record of format 4 or later keeps it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SealedNoise {
    /// How the secret becomes draws (`chacha20`).
    pub scheme: NoiseScheme,
    /// The SHA-256 of the secret, published before the first shot.
    pub commitment: NoiseCommitment,
    /// The secret, revealed once the match is over (absent before).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub secret: Option<NoiseSecret>,
}

/// A whole match.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct MatchRecord {
    /// The record's format.
    pub version: u32,
    /// The physics version the match was played under: the version of
    /// everything that decides what a shot does. A record is replayed only
    /// under its own version. Records of formats 1 and 2 lack the field and
    /// are of version 1.
    #[serde(default = "physics_of_old_records")]
    pub physics: u32,
    pub config: Config,
    /// Formats 1–3: the seed of the `splitmix64` noise (absent from format
    /// 4 on).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    /// Format 4 on: the sealed noise.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub noise: Option<SealedNoise>,
    /// The hosted bot module that played each seat (first, second), named
    /// by its SHA-256 in hex, `null` for a seat no module played; absent
    /// when none did. With the revealed secret, it lets anyone run the
    /// same modules again and get the same moves.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hosted: Option<[Option<String>; 2]>,
    pub moves: Vec<RecordedMove>,
}

/// A record that cannot be read.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RecordError {
    #[error("not a valid match record: {0}")]
    Json(String),
    #[error("the record has no \"version\" field")]
    MissingVersion,
    #[error("record version {found} is not supported (this build reads versions {oldest} to {supported})")]
    UnsupportedVersion {
        found: String,
        oldest: u32,
        supported: u32,
    },
    #[error("a version {version} record must say its \"physics\" version")]
    MissingPhysics { version: u64 },
    #[error("a version {version} record must carry its noise {field:?}")]
    MissingNoise { version: u64, field: &'static str },
    #[error("a version {version} record keys its noise with {found:?}, not {expected:?}")]
    WrongNoiseScheme {
        version: u64,
        found: NoiseScheme,
        expected: NoiseScheme,
    },
    #[error("the record does not reveal its noise secret (the match is not over)")]
    SecretNotRevealed,
    #[error("the revealed noise secret does not hash to the commitment {commitment}")]
    CommitmentMismatch { commitment: NoiseCommitment },
}

impl MatchRecord {
    /// An empty record of a match about to start under `physics` with its
    /// noise keyed by `key`: of format 4 with the secret sealed (committed
    /// to, not revealed), or of format 3 with a plain seed for a
    /// `splitmix64` key (a match of an old record played again).
    pub fn new(config: Config, key: &NoiseKey, physics: PhysicsVersion) -> Self {
        let (version, seed, noise) = match key {
            NoiseKey::SplitMix64(seed) => (LAST_VERSION_WITH_SEED as u32, Some(*seed), None),
            NoiseKey::ChaCha20(secret) => (
                RECORD_VERSION,
                None,
                Some(SealedNoise {
                    scheme: NoiseScheme::Chacha20,
                    commitment: secret.commitment(),
                    secret: None,
                }),
            ),
        };
        MatchRecord {
            version,
            physics: physics.number(),
            config,
            seed,
            noise,
            hosted: None,
            moves: Vec::new(),
        }
    }

    /// The commitment to the noise secret (records of format 4 on).
    pub fn commitment(&self) -> Option<NoiseCommitment> {
        self.noise.as_ref().map(|n| n.commitment)
    }

    /// The key the match's noise was drawn with: the seed of a record of
    /// format 1–3, or the revealed secret of a later one — which must hash
    /// to the record's commitment.
    pub fn key(&self) -> Result<NoiseKey, RecordError> {
        match (&self.noise, self.seed) {
            (Some(sealed), _) => {
                let secret = sealed.secret.ok_or(RecordError::SecretNotRevealed)?;
                if !sealed.commitment.opens_to(&secret) {
                    return Err(RecordError::CommitmentMismatch {
                        commitment: sealed.commitment,
                    });
                }
                Ok(NoiseKey::ChaCha20(secret))
            }
            (None, Some(seed)) => Ok(NoiseKey::SplitMix64(seed)),
            (None, None) => Err(RecordError::MissingNoise {
                version: self.version.into(),
                field: if u64::from(self.version) <= LAST_VERSION_WITH_SEED {
                    "seed"
                } else {
                    "noise"
                },
            }),
        }
    }

    /// Reveals `key`'s secret in the record (a game does it once the match
    /// is over; a server's store, to resume a match it keeps privately).
    /// Nothing changes for a `splitmix64` key, whose seed is always there.
    pub fn reveal(&mut self, key: &NoiseKey) {
        if let (Some(sealed), NoiseKey::ChaCha20(secret)) = (&mut self.noise, key) {
            sealed.secret = Some(*secret);
        }
    }

    /// The shots, in order.
    pub fn shots(&self) -> impl Iterator<Item = &ShotOutcome> {
        self.moves.iter().filter_map(|m| match m {
            RecordedMove::Shot(s) => Some(s),
            _ => None,
        })
    }

    /// The record as JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).expect("a record always serialises")
    }

    /// Reads a record, checking its version before anything else (and
    /// that a record of format 3 or later names its physics version).
    pub fn from_json(text: &str) -> Result<MatchRecord, RecordError> {
        let value: serde_json::Value =
            serde_json::from_str(text).map_err(|e| RecordError::Json(e.to_string()))?;
        let version = value.get("version").ok_or(RecordError::MissingVersion)?;
        let readable = OLDEST_RECORD_VERSION as u64..=RECORD_VERSION as u64;
        let Some(version) = version.as_u64().filter(|v| readable.contains(v)) else {
            return Err(RecordError::UnsupportedVersion {
                found: version.to_string(),
                oldest: OLDEST_RECORD_VERSION,
                supported: RECORD_VERSION,
            });
        };
        if version >= FIRST_VERSION_WITH_PHYSICS && value.get("physics").is_none() {
            return Err(RecordError::MissingPhysics { version });
        }
        // Parse from the text, not the `Value`, so numbers keep their exact bits.
        let record: MatchRecord =
            serde_json::from_str(text).map_err(|e| RecordError::Json(e.to_string()))?;
        let missing = |field| RecordError::MissingNoise { version, field };
        if version <= LAST_VERSION_WITH_SEED {
            if record.seed.is_none() {
                return Err(missing("seed"));
            }
            if record.noise.is_some() {
                return Err(RecordError::Json(format!(
                    "a version {version} record keys its noise with \"seed\", not \"noise\""
                )));
            }
        } else {
            let sealed = record.noise.as_ref().ok_or(missing("noise"))?;
            if sealed.scheme != NoiseScheme::Chacha20 {
                return Err(RecordError::WrongNoiseScheme {
                    version,
                    found: sealed.scheme,
                    expected: NoiseScheme::Chacha20,
                });
            }
            if record.seed.is_some() {
                return Err(RecordError::Json(format!(
                    "a version {version} record keys its noise with \"noise\", not \"seed\""
                )));
            }
        }
        Ok(record)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_record_round_trips_through_json() {
        let key = NoiseKey::from(u64::MAX - 3);
        let mut r = MatchRecord::new(Config::default(), &key, PhysicsVersion::CURRENT);
        r.moves.push(RecordedMove::Pie { swap: true });
        r.moves.push(RecordedMove::Pass { side: Side::White });
        r.moves.push(RecordedMove::Forfeit {
            side: Side::Black,
            reason: ForfeitReason::Abandoned,
        });
        let json = r.to_json();
        assert!(json.contains(r#""version":4,"physics":6,"#), "{json}");
        assert!(json.contains(r#"{"move":"pass","side":"white"}"#), "{json}");
        assert!(json.contains(r#""move":"pie""#), "{json}");
        assert!(!json.contains("seed"), "{json}");
        assert_eq!(MatchRecord::from_json(&json).unwrap(), r);
        r.reveal(&key);
        assert_eq!(MatchRecord::from_json(&r.to_json()).unwrap(), r);
    }

    #[test]
    fn a_sealed_record_commits_before_it_reveals_and_the_key_must_open_the_commitment() {
        let key = NoiseKey::from(9);
        let NoiseKey::ChaCha20(secret) = key else {
            unreachable!("a number keys ChaCha20")
        };
        let mut r = MatchRecord::new(Config::default(), &key, PhysicsVersion::CURRENT);
        let json = r.to_json();
        let commitment = secret.commitment().to_hex();
        assert!(
            json.contains(&format!(
                r#""noise":{{"scheme":"chacha20","commitment":"{commitment}"}}"#
            )),
            "{json}"
        );
        assert!(!json.contains(&secret.to_hex()));
        assert_eq!(r.key(), Err(RecordError::SecretNotRevealed));
        r.reveal(&key);
        assert!(r
            .to_json()
            .contains(&format!(r#""secret":"{}""#, secret.to_hex())));
        assert_eq!(r.key(), Ok(key));
        // Another secret in place of the revealed one does not open it.
        r.noise.as_mut().unwrap().secret = Some(NoiseSecret::from_seed(10));
        let err = r.key().unwrap_err();
        assert!(matches!(err, RecordError::CommitmentMismatch { .. }));
        assert!(err.to_string().contains(&commitment), "{err}");
    }

    #[test]
    fn a_version_4_record_must_seal_its_noise_with_chacha20_and_not_carry_a_seed() {
        let json = r#"{"version":4,"physics":6,"config":{},"seed":5,"moves":[]}"#;
        assert_eq!(
            MatchRecord::from_json(json),
            Err(RecordError::MissingNoise {
                version: 4,
                field: "noise"
            })
        );
        let c = NoiseSecret::from_seed(1).commitment().to_hex();
        let json = format!(
            r#"{{"version":4,"physics":6,"config":{{}},"noise":{{"scheme":"splitmix64","commitment":"{c}"}},"moves":[]}}"#
        );
        assert!(matches!(
            MatchRecord::from_json(&json),
            Err(RecordError::WrongNoiseScheme { .. })
        ));
        let json = format!(
            r#"{{"version":4,"physics":6,"config":{{}},"seed":1,"noise":{{"scheme":"chacha20","commitment":"{c}"}},"moves":[]}}"#
        );
        assert!(matches!(
            MatchRecord::from_json(&json),
            Err(RecordError::Json(_))
        ));
        let json = r#"{"version":3,"physics":6,"config":{},"moves":[]}"#;
        assert_eq!(
            MatchRecord::from_json(json),
            Err(RecordError::MissingNoise {
                version: 3,
                field: "seed"
            })
        );
    }

    #[test]
    fn an_unknown_version_is_refused_with_a_clear_error() {
        let mut v: serde_json::Value = serde_json::from_str(
            &MatchRecord::new(Config::default(), &1.into(), PhysicsVersion::CURRENT).to_json(),
        )
        .unwrap();
        v["version"] = serde_json::json!(5);
        let err = MatchRecord::from_json(&v.to_string()).unwrap_err();
        assert_eq!(
            err,
            RecordError::UnsupportedVersion {
                found: "5".into(),
                oldest: 1,
                supported: 4
            }
        );
        assert!(err.to_string().contains("version 5 is not supported"));
        v["version"] = serde_json::json!("one");
        assert!(matches!(
            MatchRecord::from_json(&v.to_string()),
            Err(RecordError::UnsupportedVersion { .. })
        ));
    }

    #[test]
    fn a_version_1_record_is_still_read_as_physics_1() {
        let mut v: serde_json::Value = serde_json::from_str(
            &MatchRecord::new(
                Config::default(),
                &NoiseKey::SplitMix64(1),
                PhysicsVersion::CURRENT,
            )
            .to_json(),
        )
        .unwrap();
        v["version"] = serde_json::json!(1);
        v.as_object_mut().unwrap().remove("physics");
        v["moves"] = serde_json::json!([{"move": "resign", "side": "white"}]);
        let r = MatchRecord::from_json(&v.to_string()).unwrap();
        assert_eq!(r.version, 1);
        assert_eq!(r.physics, 1);
        assert_eq!(r.moves, vec![RecordedMove::Resign { side: Side::White }]);
    }

    #[test]
    fn a_version_2_record_without_physics_reads_as_physics_1() {
        let json = r#"{"version":2,"config":{},"seed":5,"moves":[{"move":"pass","side":"white"}]}"#;
        let r = MatchRecord::from_json(json).unwrap();
        assert_eq!((r.version, r.physics, r.seed), (2, 1, Some(5)));
        assert_eq!(r.key(), Ok(NoiseKey::SplitMix64(5)));
        assert_eq!(r.moves, vec![RecordedMove::Pass { side: Side::White }]);
    }

    #[test]
    fn a_version_3_record_must_name_its_physics() {
        let json = r#"{"version":3,"config":{},"seed":5,"moves":[]}"#;
        let err = MatchRecord::from_json(json).unwrap_err();
        assert_eq!(err, RecordError::MissingPhysics { version: 3 });
        assert!(err.to_string().contains("\"physics\""), "{err}");
    }

    #[test]
    fn a_record_of_a_physics_version_this_build_cannot_play_is_still_read() {
        let json = r#"{"version":3,"physics":7,"config":{},"seed":5,"moves":[]}"#;
        assert_eq!(MatchRecord::from_json(json).unwrap().physics, 7);
    }

    #[test]
    fn a_record_without_a_version_or_not_json_is_refused() {
        assert_eq!(
            MatchRecord::from_json(r#"{"config":{},"seed":1,"moves":[]}"#),
            Err(RecordError::MissingVersion)
        );
        assert!(matches!(
            MatchRecord::from_json("{"),
            Err(RecordError::Json(_))
        ));
    }
}
