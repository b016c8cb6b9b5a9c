//! The match record: the configuration, the seed, and every move in order
//! with what it did — enough to replay the match bit for bit. It is JSON
//! with a `version` field; a record of an unknown version is refused with a
//! clear error rather than misread.

use crate::config::Config;
use crate::outcome::{ForfeitReason, ShotOutcome};
use crate::side::Side;
use serde::{Deserialize, Serialize};

/// The record format this crate writes. Version 1 (without passes and
/// forfeits) is still read.
pub const RECORD_VERSION: u32 = 2;

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
    pub version: u32,
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
}

impl MatchRecord {
    /// An empty record of a match about to start.
    pub fn new(config: Config, seed: u64) -> Self {
        MatchRecord {
            version: RECORD_VERSION,
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

    /// Reads a record, checking its version before anything else.
    pub fn from_json(text: &str) -> Result<MatchRecord, RecordError> {
        let value: serde_json::Value =
            serde_json::from_str(text).map_err(|e| RecordError::Json(e.to_string()))?;
        let version = value.get("version").ok_or(RecordError::MissingVersion)?;
        let readable = OLDEST_RECORD_VERSION as u64..=RECORD_VERSION as u64;
        if !version.as_u64().is_some_and(|v| readable.contains(&v)) {
            return Err(RecordError::UnsupportedVersion {
                found: version.to_string(),
                oldest: OLDEST_RECORD_VERSION,
                supported: RECORD_VERSION,
            });
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
        let mut r = MatchRecord::new(Config::default(), u64::MAX - 3);
        r.moves.push(RecordedMove::Pie { swap: true });
        r.moves.push(RecordedMove::Pass { side: Side::White });
        r.moves.push(RecordedMove::Forfeit {
            side: Side::Black,
            reason: ForfeitReason::Abandoned,
        });
        let json = r.to_json();
        assert!(json.contains(r#""version":2"#), "{json}");
        assert!(json.contains(r#"{"move":"pass","side":"white"}"#), "{json}");
        assert!(json.contains(r#""move":"pie""#), "{json}");
        assert_eq!(MatchRecord::from_json(&json).unwrap(), r);
    }

    #[test]
    fn an_unknown_version_is_refused_with_a_clear_error() {
        let mut v: serde_json::Value =
            serde_json::from_str(&MatchRecord::new(Config::default(), 1).to_json()).unwrap();
        v["version"] = serde_json::json!(3);
        let err = MatchRecord::from_json(&v.to_string()).unwrap_err();
        assert_eq!(
            err,
            RecordError::UnsupportedVersion {
                found: "3".into(),
                oldest: 1,
                supported: 2
            }
        );
        assert!(err.to_string().contains("version 3 is not supported"));
        v["version"] = serde_json::json!("one");
        assert!(matches!(
            MatchRecord::from_json(&v.to_string()),
            Err(RecordError::UnsupportedVersion { .. })
        ));
    }

    #[test]
    fn a_version_1_record_is_still_read() {
        let mut v: serde_json::Value =
            serde_json::from_str(&MatchRecord::new(Config::default(), 1).to_json()).unwrap();
        v["version"] = serde_json::json!(1);
        v["moves"] = serde_json::json!([{"move": "resign", "side": "white"}]);
        let r = MatchRecord::from_json(&v.to_string()).unwrap();
        assert_eq!(r.version, 1);
        assert_eq!(r.moves, vec![RecordedMove::Resign { side: Side::White }]);
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
