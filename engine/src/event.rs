//! Events: what happened, when, to whom.
//!
//! An [`Event`] is one entry of the model's chain. Its JSON form is flat, as
//! `sim` prints it: `{"t": 0.23, "kind": "body-body", "bodies": [1, 2]}`,
//! with `line` / `point` indices where they apply.

use crate::id::{BodyId, LineId, PointId};
use serde::{Deserialize, Serialize};

/// One thing that happened at time `t`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(into = "FlatEvent", try_from = "FlatEvent")]
pub struct Event {
    pub t: f64,
    pub kind: EventKind,
}

/// What happened.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EventKind {
    /// Two discs collided.
    BodyBody { a: BodyId, b: BodyId },
    /// A disc hit a fixed point.
    BodyPoint { body: BodyId, point: PointId },
    /// A disc hit a line; `end` is `Some(0)` / `Some(1)` for a corner hit on
    /// the line's `a` / `b` end.
    BodyLine {
        body: BodyId,
        line: LineId,
        end: Option<u8>,
    },
    /// A disc came to rest.
    Stop { body: BodyId },
    /// A disc's centre crossed a sensor line outwards; `removed` if the
    /// rules took it out of the scene there (a Chapaev piece falling off).
    RegionExit {
        body: BodyId,
        line: LineId,
        removed: bool,
    },
    /// A disc's centre crossed a sensor line inwards.
    RegionEntry { body: BodyId, line: LineId },
    /// The `index`-th action given to the model took effect.
    Action { index: u32 },
}

impl EventKind {
    /// Whether this is a collision (body–body, body–line or body–point).
    pub fn is_collision(&self) -> bool {
        matches!(
            self,
            EventKind::BodyBody { .. } | EventKind::BodyPoint { .. } | EventKind::BodyLine { .. }
        )
    }

    /// The kind's name as written in JSON.
    pub fn name(&self) -> &'static str {
        match self {
            EventKind::BodyBody { .. } => "body-body",
            EventKind::BodyPoint { .. } => "body-point",
            EventKind::BodyLine { .. } => "body-line",
            EventKind::Stop { .. } => "stop",
            EventKind::RegionExit { .. } => "region-exit",
            EventKind::RegionEntry { .. } => "region-entry",
            EventKind::Action { .. } => "action",
        }
    }

    /// The bodies involved (none for an action).
    pub fn bodies(&self) -> impl Iterator<Item = BodyId> {
        let (a, b) = match *self {
            EventKind::BodyBody { a, b } => (Some(a), Some(b)),
            EventKind::BodyPoint { body, .. }
            | EventKind::BodyLine { body, .. }
            | EventKind::Stop { body }
            | EventKind::RegionExit { body, .. }
            | EventKind::RegionEntry { body, .. } => (Some(body), None),
            EventKind::Action { .. } => (None, None),
        };
        a.into_iter().chain(b)
    }
}

/// The flat JSON form of an event.
#[derive(Clone, Debug, Serialize, Deserialize, schemars::JsonSchema)]
struct FlatEvent {
    t: f64,
    #[schemars(extend("enum" = ["body-body", "body-point", "body-line", "stop", "region-exit", "region-entry", "action"]))]
    kind: String,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    bodies: Vec<BodyId>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    line: Option<LineId>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    point: Option<PointId>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    end: Option<u8>,
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    removed: bool,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    action: Option<u32>,
}

impl From<Event> for FlatEvent {
    fn from(e: Event) -> Self {
        let mut f = FlatEvent {
            t: e.t,
            kind: e.kind.name().to_string(),
            bodies: e.kind.bodies().collect(),
            line: None,
            point: None,
            end: None,
            removed: false,
            action: None,
        };
        match e.kind {
            EventKind::BodyPoint { point, .. } => f.point = Some(point),
            EventKind::BodyLine { line, end, .. } => {
                f.line = Some(line);
                f.end = end;
            }
            EventKind::RegionExit { line, removed, .. } => {
                f.line = Some(line);
                f.removed = removed;
            }
            EventKind::RegionEntry { line, .. } => f.line = Some(line),
            EventKind::Action { index } => f.action = Some(index),
            EventKind::BodyBody { .. } | EventKind::Stop { .. } => {}
        }
        f
    }
}

impl TryFrom<FlatEvent> for Event {
    type Error = String;
    fn try_from(f: FlatEvent) -> Result<Self, String> {
        let body = |n: usize| -> Result<BodyId, String> {
            if f.bodies.len() != n {
                return Err(format!(
                    "a {} event needs {} bodies, got {}",
                    f.kind,
                    n,
                    f.bodies.len()
                ));
            }
            Ok(f.bodies[0])
        };
        let need = |x: Option<u32>, what: &str| {
            x.ok_or_else(|| format!("a {} event needs \"{what}\"", f.kind))
        };
        let kind = match f.kind.as_str() {
            "body-body" => {
                body(2)?;
                EventKind::BodyBody {
                    a: f.bodies[0],
                    b: f.bodies[1],
                }
            }
            "body-point" => EventKind::BodyPoint {
                body: body(1)?,
                point: PointId(need(f.point.map(|p| p.0), "point")?),
            },
            "body-line" => EventKind::BodyLine {
                body: body(1)?,
                line: LineId(need(f.line.map(|l| l.0), "line")?),
                end: f.end,
            },
            "stop" => EventKind::Stop { body: body(1)? },
            "region-exit" => EventKind::RegionExit {
                body: body(1)?,
                line: LineId(need(f.line.map(|l| l.0), "line")?),
                removed: f.removed,
            },
            "region-entry" => EventKind::RegionEntry {
                body: body(1)?,
                line: LineId(need(f.line.map(|l| l.0), "line")?),
            },
            "action" => EventKind::Action {
                index: need(f.action, "action")?,
            },
            other => return Err(format!("unknown event kind \"{other}\"")),
        };
        Ok(Event { t: f.t, kind })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn events_serialise_flat_as_sim_prints_them() {
        let e = Event {
            t: 0.5,
            kind: EventKind::BodyBody {
                a: BodyId(1),
                b: BodyId(2),
            },
        };
        assert_eq!(
            serde_json::to_string(&e).unwrap(),
            r#"{"t":0.5,"kind":"body-body","bodies":[1,2]}"#
        );
        let e = Event {
            t: 1.0,
            kind: EventKind::BodyLine {
                body: BodyId(3),
                line: LineId(0),
                end: None,
            },
        };
        assert_eq!(
            serde_json::to_string(&e).unwrap(),
            r#"{"t":1.0,"kind":"body-line","bodies":[3],"line":0}"#
        );
    }

    #[test]
    fn every_kind_round_trips_through_json() {
        let kinds = [
            EventKind::BodyBody {
                a: BodyId(1),
                b: BodyId(2),
            },
            EventKind::BodyPoint {
                body: BodyId(1),
                point: PointId(3),
            },
            EventKind::BodyLine {
                body: BodyId(1),
                line: LineId(2),
                end: Some(1),
            },
            EventKind::Stop { body: BodyId(4) },
            EventKind::RegionExit {
                body: BodyId(4),
                line: LineId(1),
                removed: true,
            },
            EventKind::RegionEntry {
                body: BodyId(4),
                line: LineId(1),
            },
            EventKind::Action { index: 7 },
        ];
        for kind in kinds {
            let e = Event { t: 0.25, kind };
            let back: Event = serde_json::from_str(&serde_json::to_string(&e).unwrap()).unwrap();
            assert_eq!(back, e);
        }
    }

    #[test]
    fn malformed_events_are_rejected_with_a_reason() {
        let err = serde_json::from_str::<Event>(r#"{"t":1,"kind":"stop","bodies":[]}"#)
            .unwrap_err()
            .to_string();
        assert!(err.contains("needs 1 bodies, got 0"), "{err}");
        let err = serde_json::from_str::<Event>(r#"{"t":1,"kind":"teleport"}"#)
            .unwrap_err()
            .to_string();
        assert!(err.contains("unknown event kind"), "{err}");
    }
}
