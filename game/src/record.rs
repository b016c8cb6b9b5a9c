//! The match record: the configuration, the seed, the physics version, and
//! every move in order with what it did — enough to replay the match bit
//! for bit. It is JSON with a `version` field (the record's format); a
//! record of an unknown format is refused with a clear error rather than
//! misread. A record of a physics version this build cannot play is still
//! read (it is data), but [`crate::Replay`] refuses to replay it.

use crate::config::Config;
use crate::outcome::{ForfeitReason, ShotOutcome};
use crate::physics_version::PhysicsVersion;
use crate::side::Side;
use serde::{Deserialize, Serialize};

/// The record format this crate writes. Version 3 added the `physics`
/// field; versions 1 (without passes and forfeits) and 2 are still read,
/// as records of physics version 1 (the only physics they were played
/// under).
pub const RECORD_VERSION: u32 = 3;

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
    /// The seed of the execution noise.
    pub seed: u64,
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
}

impl MatchRecord {
    /// An empty record of a match about to start under `physics`.
    pub fn new(config: Config, seed: u64, physics: PhysicsVersion) -> Self {
        MatchRecord {
            version: RECORD_VERSION,
            physics: physics.number(),
            config,
            seed,
            moves: Vec::new(),
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
        serde_json::from_str(text).map_err(|e| RecordError::Json(e.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_record_round_trips_through_json() {
        let mut r = MatchRecord::new(Config::default(), u64::MAX - 3, PhysicsVersion::CURRENT);
        r.moves.push(RecordedMove::Pie { swap: true });
        r.moves.push(RecordedMove::Pass { side: Side::White });
        r.moves.push(RecordedMove::Forfeit {
            side: Side::Black,
            reason: ForfeitReason::Abandoned,
        });
        let json = r.to_json();
        assert!(json.contains(r#""version":3,"physics":6,"#), "{json}");
        assert!(json.contains(r#"{"move":"pass","side":"white"}"#), "{json}");
        assert!(json.contains(r#""move":"pie""#), "{json}");
        assert_eq!(MatchRecord::from_json(&json).unwrap(), r);
    }

    #[test]
    fn an_unknown_version_is_refused_with_a_clear_error() {
        let mut v: serde_json::Value = serde_json::from_str(
            &MatchRecord::new(Config::default(), 1, PhysicsVersion::CURRENT).to_json(),
        )
        .unwrap();
        v["version"] = serde_json::json!(4);
        let err = MatchRecord::from_json(&v.to_string()).unwrap_err();
        assert_eq!(
            err,
            RecordError::UnsupportedVersion {
                found: "4".into(),
                oldest: 1,
                supported: 3
            }
        );
        assert!(err.to_string().contains("version 4 is not supported"));
        v["version"] = serde_json::json!("one");
        assert!(matches!(
            MatchRecord::from_json(&v.to_string()),
            Err(RecordError::UnsupportedVersion { .. })
        ));
    }

    #[test]
    fn a_version_1_record_is_still_read_as_physics_1() {
        let mut v: serde_json::Value = serde_json::from_str(
            &MatchRecord::new(Config::default(), 1, PhysicsVersion::CURRENT).to_json(),
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
        assert_eq!((r.version, r.physics, r.seed), (2, 1, 5));
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
