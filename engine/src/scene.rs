//! The scene: bodies, points, lines and globals at one moment — the JSON
//! contract of `docs/scene-format.md` — and its validation.
//!
//! [`Scene::from_json`] parses and validates in one go, so every error names
//! the object and field at fault, as in
//! `bodies[1] (id 2): field "mass": must be > 0`. Validation never fixes
//! input silently and never panics.

use crate::id::BodyId;
use crate::obstacle::{Line, LineGeom, Point};
use glam::DVec2;
use serde::{Deserialize, Serialize};
use std::fmt;

/// Standard gravity, the default `g`.
pub const DEFAULT_G: f64 = 9.81;

fn default_g() -> f64 {
    DEFAULT_G
}
fn default_restitution() -> f64 {
    1.0
}

/// A disc as a scene describes it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    pub id: BodyId,
    pub pos: DVec2,
    pub vel: DVec2,
    pub radius: f64,
    pub mass: f64,
    pub mu: f64,
    #[serde(default = "default_restitution")]
    pub restitution: f64,
}

impl BodySpec {
    /// A disc at rest with restitution 1.
    pub fn new(id: u64, pos: DVec2, radius: f64, mass: f64, mu: f64) -> Self {
        BodySpec {
            id: BodyId(id),
            pos,
            vel: DVec2::ZERO,
            radius,
            mass,
            mu,
            restitution: 1.0,
        }
    }

    /// The same disc with velocity `vel`.
    pub fn with_velocity(mut self, vel: DVec2) -> Self {
        self.vel = vel;
        self
    }

    /// The same disc with restitution `e`.
    pub fn with_restitution(mut self, e: f64) -> Self {
        self.restitution = e;
        self
    }
}

/// A whole situation: what a scene file holds.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Scene {
    /// Gravity (for friction): deceleration of a body is `mu * g`.
    #[serde(default = "default_g")]
    pub g: f64,
    /// The time the scene describes (0 unless given).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub t: f64,
    pub bodies: Vec<BodySpec>,
    #[serde(default)]
    pub points: Vec<Point>,
    #[serde(default)]
    pub lines: Vec<Line>,
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

impl Default for Scene {
    fn default() -> Self {
        Scene {
            g: DEFAULT_G,
            t: 0.0,
            bodies: Vec::new(),
            points: Vec::new(),
            lines: Vec::new(),
        }
    }
}

/// Which object of a scene an error is about.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Object {
    Scene,
    Body { index: usize, id: Option<BodyId> },
    Point { index: usize },
    Line { index: usize },
}

impl fmt::Display for Object {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Object::Scene => write!(f, "scene"),
            Object::Body {
                index,
                id: Some(id),
            } => write!(f, "bodies[{index}] (id {})", id.0),
            Object::Body { index, id: None } => write!(f, "bodies[{index}]"),
            Object::Point { index } => write!(f, "points[{index}]"),
            Object::Line { index } => write!(f, "lines[{index}]"),
        }
    }
}

/// What is wrong with a field.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum Problem {
    #[error("must be a finite number")]
    NotFinite,
    #[error("must be > 0")]
    NotPositive,
    #[error("must be >= 0")]
    Negative,
    #[error("must be between 0 and 1")]
    OutOfUnitRange,
    #[error("duplicate id (also used by bodies[{0}])")]
    DuplicateId(usize),
    #[error("overlaps {0} at the start")]
    Overlaps(String),
    #[error("its two points coincide")]
    Degenerate,
    #[error("too large: the engine works with squares of lengths and speeds, so magnitudes must stay below 1e150")]
    TooLarge,
    #[error("mu * g overflows")]
    Overflow,
    #[error("too many sensor lines (at most {0})")]
    TooManySensors(usize),
    #[error("friction might only stop it beyond 1e150: the scene's kinetic energy over its friction force (mass * mu * g) is too large")]
    OutOfReach,
    #[error("must be a whole number from 0 to 18446744073709551615, not {0}")]
    BadId(String),
    #[error("{0}")]
    Malformed(String),
}

/// A scene that cannot be simulated, naming the object and field at fault.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SceneError {
    #[error("not valid JSON: {0}")]
    Json(String),
    #[error("{object}: field \"{field}\": {problem}")]
    Invalid {
        object: Object,
        field: &'static str,
        problem: Problem,
    },
    #[error("{object}: {problem}")]
    Shape { object: Object, problem: Problem },
}

/// Largest coordinate, speed or radius accepted: squares of these (contact
/// equations) must stay finite.
pub(crate) const MAX_MAGNITUDE: f64 = 1e150;

/// Most sensor lines a scene may have (each body tracks its side of each).
pub(crate) const MAX_SENSORS: usize = 64;

/// Relative slack when checking initial overlaps, so that discs placed
/// exactly touching (a Newton's cradle) are accepted despite rounding.
const TOUCH_SLACK: f64 = 1e-9;

impl Scene {
    /// Parses and validates a scene file.
    pub fn from_json(text: &str) -> Result<Scene, SceneError> {
        let value: serde_json::Value =
            serde_json::from_str(text).map_err(|e| SceneError::Json(e.to_string()))?;
        Scene::from_value(value)
    }

    /// Validates a scene given as a JSON value, naming the object at fault.
    pub fn from_value(value: serde_json::Value) -> Result<Scene, SceneError> {
        let serde_json::Value::Object(mut map) = value else {
            return Err(shape(Object::Scene, "a scene must be a JSON object"));
        };
        let g = match map.remove("g") {
            None => DEFAULT_G,
            Some(v) => number(v, Object::Scene, "g")?,
        };
        let t = match map.remove("t") {
            None => 0.0,
            Some(v) => number(v, Object::Scene, "t")?,
        };
        let bodies = list(&mut map, "bodies", true)?
            .into_iter()
            .enumerate()
            .map(|(index, v)| {
                let id = match v.get("id") {
                    Some(x) => match x.as_u64() {
                        Some(id) => Some(BodyId(id)),
                        None => {
                            let object = Object::Body { index, id: None };
                            return Err(invalid(object, "id", Problem::BadId(x.to_string())));
                        }
                    },
                    None => None,
                };
                item::<BodySpec>(v, Object::Body { index, id })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let points = list(&mut map, "points", false)?
            .into_iter()
            .enumerate()
            .map(|(index, v)| item::<Point>(v, Object::Point { index }))
            .collect::<Result<Vec<_>, _>>()?;
        let lines = list(&mut map, "lines", false)?
            .into_iter()
            .enumerate()
            .map(|(index, v)| item::<Line>(v, Object::Line { index }))
            .collect::<Result<Vec<_>, _>>()?;
        if let Some(key) = map.keys().next() {
            return Err(shape(Object::Scene, &format!("unknown field \"{key}\"")));
        }
        let scene = Scene {
            g,
            t,
            bodies,
            points,
            lines,
        };
        scene.validate()?;
        Ok(scene)
    }

    /// The scene as pretty JSON (the sandbox's export).
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("a scene always serialises")
    }

    /// Checks every rule of the scene format; the first violation is returned.
    pub fn validate(&self) -> Result<(), SceneError> {
        self.validate_with(true)
    }

    /// As [`Scene::validate`], optionally without the overlap check (for
    /// states the engine itself produced, where touching discs may overlap
    /// by rounding).
    pub fn validate_with(&self, check_overlaps: bool) -> Result<(), SceneError> {
        let sc = Object::Scene;
        finite(self.g, &sc, "g")?;
        if self.g < 0.0 {
            return Err(invalid(sc, "g", Problem::Negative));
        }
        finite(self.t, &Object::Scene, "t")?;
        // Duplicate ids: a scan of the earlier ids for game-sized scenes
        // (no allocation: bots validate thousands of scenes a second), a
        // map for large ones.
        let small = self.bodies.len() <= 32;
        let mut seen =
            std::collections::HashMap::with_capacity(if small { 0 } else { self.bodies.len() });
        for (index, b) in self.bodies.iter().enumerate() {
            let o = Object::Body {
                index,
                id: Some(b.id),
            };
            finite(b.pos.x, &o, "pos")?;
            finite(b.pos.y, &o, "pos")?;
            finite(b.vel.x, &o, "vel")?;
            finite(b.vel.y, &o, "vel")?;
            finite(b.radius, &o, "radius")?;
            finite(b.mass, &o, "mass")?;
            finite(b.mu, &o, "mu")?;
            finite(b.restitution, &o, "restitution")?;
            if b.radius <= 0.0 {
                return Err(invalid(o, "radius", Problem::NotPositive));
            }
            if b.mass <= 0.0 {
                return Err(invalid(o, "mass", Problem::NotPositive));
            }
            if b.mu < 0.0 {
                return Err(invalid(o, "mu", Problem::Negative));
            }
            if !(0.0..=1.0).contains(&b.restitution) {
                return Err(invalid(o, "restitution", Problem::OutOfUnitRange));
            }
            if b.pos.abs().max_element() > MAX_MAGNITUDE {
                return Err(invalid(o, "pos", Problem::TooLarge));
            }
            if b.vel.abs().max_element() > MAX_MAGNITUDE {
                return Err(invalid(o, "vel", Problem::TooLarge));
            }
            if b.radius > MAX_MAGNITUDE {
                return Err(invalid(o, "radius", Problem::TooLarge));
            }
            if !(b.mu * self.g).is_finite() {
                return Err(invalid(o, "mu", Problem::Overflow));
            }
            let earlier = if small {
                self.bodies[..index].iter().position(|o| o.id == b.id)
            } else {
                seen.insert(b.id, index)
            };
            if let Some(first) = earlier {
                return Err(invalid(o, "id", Problem::DuplicateId(first)));
            }
        }
        self.check_reach()?;
        for (index, p) in self.points.iter().enumerate() {
            let o = Object::Point { index };
            finite(p.pos.x, &o, "pos")?;
            finite(p.pos.y, &o, "pos")?;
        }
        let mut sensors = 0;
        for (index, l) in self.lines.iter().enumerate() {
            let o = Object::Line { index };
            for (v, f) in [(l.a, "a"), (l.b, "b")] {
                finite(v.x, &o, f)?;
                finite(v.y, &o, f)?;
                if v.abs().max_element() > MAX_MAGNITUDE {
                    return Err(invalid(o, f, Problem::TooLarge));
                }
            }
            if LineGeom::new(l).is_none() {
                return Err(SceneError::Shape {
                    object: o,
                    problem: Problem::Degenerate,
                });
            }
            sensors += l.sensor as usize;
            if sensors > MAX_SENSORS {
                return Err(invalid(o, "sensor", Problem::TooManySensors(MAX_SENSORS)));
            }
        }
        if check_overlaps {
            self.check_overlaps()?;
        }
        Ok(())
    }

    /// No disc with friction may ever slide beyond [`MAX_MAGNITUDE`]. Friction
    /// does `mass * mu * g` of work per metre a disc slides, and no disc ever
    /// holds more kinetic energy than the whole scene has at the start
    /// (collisions and pushes only lose energy), so a disc slides at most
    /// `energy / (mass * mu * g)` in all. Without this bound a disc could
    /// come to rest at a finite time at a position beyond any double.
    fn check_reach(&self) -> Result<(), SceneError> {
        let energy: f64 = self
            .bodies
            .iter()
            .map(|b| 0.5 * b.mass * b.vel.length_squared())
            .sum();
        if energy == 0.0 {
            return Ok(());
        }
        for (index, b) in self.bodies.iter().enumerate() {
            let alpha = b.mu * self.g;
            if alpha == 0.0 {
                // Frictionless: it never stops, and is only ever looked at
                // where something happens.
                continue;
            }
            // Per unit mass, so that a tiny mass cannot underflow the force.
            let reach = b.pos.abs().max_element() + energy / b.mass / alpha;
            if !(reach <= MAX_MAGNITUDE) {
                return Err(SceneError::Shape {
                    object: Object::Body {
                        index,
                        id: Some(b.id),
                    },
                    problem: Problem::OutOfReach,
                });
            }
        }
        Ok(())
    }

    /// No body may overlap another body, a solid line or a point at the start.
    fn check_overlaps(&self) -> Result<(), SceneError> {
        // Sweep along x: only bodies whose x-extents overlap are compared.
        let mut order: Vec<usize> = (0..self.bodies.len()).collect();
        order.sort_by(|&i, &j| {
            let bi = &self.bodies[i];
            let bj = &self.bodies[j];
            (bi.pos.x - bi.radius).total_cmp(&(bj.pos.x - bj.radius))
        });
        let max_r = self.bodies.iter().map(|b| b.radius).fold(0.0, f64::max);
        for (k, &i) in order.iter().enumerate() {
            let bi = &self.bodies[i];
            for &j in &order[k + 1..] {
                let bj = &self.bodies[j];
                if bj.pos.x - bj.radius > bi.pos.x + bi.radius + max_r * TOUCH_SLACK {
                    break;
                }
                let s = bi.radius + bj.radius;
                if (bi.pos - bj.pos).length() < s * (1.0 - TOUCH_SLACK) {
                    let (first, second) = if i < j { (i, j) } else { (j, i) };
                    let a = &self.bodies[first];
                    let b = &self.bodies[second];
                    return Err(invalid(
                        Object::Body {
                            index: second,
                            id: Some(b.id),
                        },
                        "pos",
                        Problem::Overlaps(
                            Object::Body {
                                index: first,
                                id: Some(a.id),
                            }
                            .to_string(),
                        ),
                    ));
                }
            }
        }
        let geoms: Vec<(usize, LineGeom)> = self
            .lines
            .iter()
            .enumerate()
            .filter(|(_, l)| !l.sensor)
            .filter_map(|(i, l)| LineGeom::new(l).map(|g| (i, g)))
            .collect();
        for (index, b) in self.bodies.iter().enumerate() {
            let o = || Object::Body {
                index,
                id: Some(b.id),
            };
            for (li, g) in &geoms {
                if g.distance(b.pos) < b.radius * (1.0 - TOUCH_SLACK) {
                    let other = Object::Line { index: *li }.to_string();
                    return Err(invalid(o(), "pos", Problem::Overlaps(other)));
                }
            }
            for (pi, p) in self.points.iter().enumerate() {
                if (p.pos - b.pos).length() < b.radius * (1.0 - TOUCH_SLACK) {
                    let other = Object::Point { index: pi }.to_string();
                    return Err(invalid(o(), "pos", Problem::Overlaps(other)));
                }
            }
        }
        Ok(())
    }
}

fn invalid(object: Object, field: &'static str, problem: Problem) -> SceneError {
    SceneError::Invalid {
        object,
        field,
        problem,
    }
}

fn shape(object: Object, msg: &str) -> SceneError {
    SceneError::Shape {
        object,
        problem: Problem::Malformed(msg.to_string()),
    }
}

fn finite(x: f64, object: &Object, field: &'static str) -> Result<(), SceneError> {
    if x.is_finite() {
        Ok(())
    } else {
        Err(invalid(object.clone(), field, Problem::NotFinite))
    }
}

fn number(v: serde_json::Value, object: Object, field: &'static str) -> Result<f64, SceneError> {
    match v.as_f64() {
        Some(x) => Ok(x),
        None => Err(invalid(object, field, Problem::NotFinite)),
    }
}

fn list(
    map: &mut serde_json::Map<String, serde_json::Value>,
    key: &'static str,
    required: bool,
) -> Result<Vec<serde_json::Value>, SceneError> {
    match map.remove(key) {
        Some(serde_json::Value::Array(items)) => Ok(items),
        Some(_) => Err(invalid(
            Object::Scene,
            key,
            Problem::Malformed("must be a list".into()),
        )),
        None if required => Err(invalid(
            Object::Scene,
            key,
            Problem::Malformed("missing".into()),
        )),
        None => Ok(Vec::new()),
    }
}

fn item<T: serde::de::DeserializeOwned>(
    v: serde_json::Value,
    object: Object,
) -> Result<T, SceneError> {
    serde_json::from_value(v).map_err(|e| SceneError::Shape {
        object,
        problem: Problem::Malformed(e.to_string()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"{
      "g": 9.81,
      "bodies": [
        { "id": 1, "pos": [0.0, 0.0], "vel": [2.0, 0.0], "radius": 0.016, "mass": 0.01, "mu": 0.3 },
        { "id": 2, "pos": [0.5, 0.0], "vel": [0.0, 0.0], "radius": 0.016, "mass": 0.01, "mu": 0.3, "restitution": 1.0 }
      ],
      "points": [ { "pos": [1.0, 1.0] } ],
      "lines":  [ { "a": [-1.0, -1.0], "b": [-1.0, 1.0], "kind": "segment" } ]
    }"#;

    fn err(text: &str) -> String {
        Scene::from_json(text).unwrap_err().to_string()
    }

    fn with_body(extra: &str) -> String {
        GOOD.replace(
            r#""restitution": 1.0 }"#,
            &format!(r#""restitution": 1.0 }}, {extra}"#),
        )
    }

    #[test]
    fn the_documented_example_parses_with_defaults() {
        let s = Scene::from_json(GOOD).unwrap();
        assert_eq!(s.bodies.len(), 2);
        assert_eq!(s.bodies[0].restitution, 1.0);
        let s = Scene::from_json(r#"{"bodies": []}"#).unwrap();
        assert_eq!(s.g, 9.81);
        assert!(s.points.is_empty() && s.lines.is_empty());
    }

    #[test]
    fn non_positive_radius_is_rejected_naming_body_and_field() {
        let text = GOOD.replace(
            r#""radius": 0.016, "mass": 0.01, "mu": 0.3, "restitution""#,
            r#""radius": 0.0, "mass": 0.01, "mu": 0.3, "restitution""#,
        );
        assert_eq!(
            err(&text),
            r#"bodies[1] (id 2): field "radius": must be > 0"#
        );
    }

    #[test]
    fn non_positive_mass_and_negative_mu_are_rejected() {
        let text = GOOD.replacen(r#""mass": 0.01"#, r#""mass": -1"#, 1);
        assert_eq!(err(&text), r#"bodies[0] (id 1): field "mass": must be > 0"#);
        let text = GOOD.replacen(r#""mu": 0.3"#, r#""mu": -0.1"#, 1);
        assert_eq!(err(&text), r#"bodies[0] (id 1): field "mu": must be >= 0"#);
    }

    #[test]
    fn missing_field_is_rejected_naming_body_and_field() {
        let text = GOOD.replacen(r#", "mu": 0.3"#, "", 1);
        let e = err(&text);
        assert!(e.starts_with("bodies[0] (id 1): missing field `mu`"), "{e}");
    }

    #[test]
    fn non_finite_numbers_are_rejected() {
        let text = GOOD.replacen("9.81", "1e999", 1);
        assert!(err(&text).starts_with("not valid JSON"), "{}", err(&text));
        let text = GOOD.replacen(r#""pos": [0.0, 0.0]"#, r#""pos": [0.0, null]"#, 1);
        assert!(err(&text).starts_with("bodies[0] (id 1)"), "{}", err(&text));
    }

    #[test]
    fn magnitudes_whose_squares_overflow_are_rejected() {
        let text = GOOD.replacen(r#""vel": [2.0, 0.0]"#, r#""vel": [1e200, 0.0]"#, 1);
        assert!(
            err(&text).starts_with(r#"bodies[0] (id 1): field "vel": too large"#),
            "{}",
            err(&text)
        );
        let text = GOOD
            .replacen(r#""mu": 0.3"#, r#""mu": 1e300"#, 1)
            .replace("9.81", "1e300");
        assert_eq!(
            err(&text),
            r#"bodies[0] (id 1): field "mu": mu * g overflows"#
        );
    }

    #[test]
    fn an_id_that_is_not_a_whole_number_is_refused_naming_the_body_and_field() {
        for (id, shown) in [("-1", "-1"), ("1.5", "1.5"), ("\"a\"", "\"a\"")] {
            let text = with_body(&format!(
                r#"{{ "id": {id}, "pos": [0.3, 0.3], "vel": [0, 0], "radius": 0.01, "mass": 1, "mu": 0 }}"#
            ));
            assert_eq!(
                err(&text),
                format!(
                    r#"bodies[2]: field "id": must be a whole number from 0 to 18446744073709551615, not {shown}"#
                )
            );
        }
    }

    #[test]
    fn duplicate_ids_are_rejected() {
        let text = with_body(
            r#"{ "id": 2, "pos": [0.3, 0.3], "vel": [0, 0], "radius": 0.01, "mass": 1, "mu": 0 }"#,
        );
        assert_eq!(
            err(&text),
            r#"bodies[2] (id 2): field "id": duplicate id (also used by bodies[1])"#
        );
    }

    #[test]
    fn overlapping_bodies_are_rejected_but_touching_ones_accepted() {
        let text = with_body(
            r#"{ "id": 3, "pos": [0.51, 0.0], "vel": [0, 0], "radius": 0.016, "mass": 1, "mu": 0 }"#,
        );
        assert_eq!(
            err(&text),
            r#"bodies[2] (id 3): field "pos": overlaps bodies[1] (id 2) at the start"#
        );
        let text = with_body(
            r#"{ "id": 3, "pos": [0.532, 0.0], "vel": [0, 0], "radius": 0.016, "mass": 1, "mu": 0 }"#,
        );
        Scene::from_json(&text).unwrap();
    }

    #[test]
    fn bodies_overlapping_a_line_or_point_are_rejected() {
        let text = with_body(
            r#"{ "id": 3, "pos": [-0.99, 0.0], "vel": [0, 0], "radius": 0.016, "mass": 1, "mu": 0 }"#,
        );
        assert_eq!(
            err(&text),
            r#"bodies[2] (id 3): field "pos": overlaps lines[0] at the start"#
        );
        let text = with_body(
            r#"{ "id": 3, "pos": [1.0, 0.99], "vel": [0, 0], "radius": 0.016, "mass": 1, "mu": 0 }"#,
        );
        assert_eq!(
            err(&text),
            r#"bodies[2] (id 3): field "pos": overlaps points[0] at the start"#
        );
    }

    #[test]
    fn a_line_whose_points_coincide_is_rejected() {
        let text = GOOD.replace(r#""b": [-1.0, 1.0]"#, r#""b": [-1.0, -1.0]"#);
        assert_eq!(err(&text), "lines[0]: its two points coincide");
    }

    #[test]
    fn unknown_line_kind_and_unknown_fields_are_rejected() {
        let text = GOOD.replace(r#""segment""#, r#""curve""#);
        assert!(
            err(&text).starts_with("lines[0]: unknown variant `curve`"),
            "{}",
            err(&text)
        );
        let text = GOOD.replace(r#""g": 9.81"#, r#""gravity": 9.81"#);
        assert_eq!(err(&text), r#"scene: unknown field "gravity""#);
    }

    #[test]
    fn malformed_json_is_rejected() {
        assert!(err("{ bodies: ").starts_with("not valid JSON"));
        assert_eq!(err("[1, 2]"), "scene: a scene must be a JSON object");
    }

    #[test]
    fn a_disc_that_friction_could_only_stop_beyond_1e150_is_refused() {
        // Found by the scene_json fuzzer: body 2 would stop at t = 1e229 at
        // a position beyond any double (it came out as [-inf, NaN]).
        let found = r#"{"g": 1e-080, "bodies": [
          {"id": 1, "pos": [-1e149, 0], "vel": [1e149, 1e-300], "radius": 1e-300, "mass": 1e300, "mu": 1e-300},
          {"id": 2, "pos": [1e148, 0], "vel": [-1e149, 0], "radius": 1e100, "mass": 1e-300, "mu": 1}
        ]}"#;
        assert_eq!(
            err(found),
            "bodies[1] (id 2): friction might only stop it beyond 1e150: \
             the scene's kinetic energy over its friction force (mass * mu * g) is too large"
        );
        // A disc at rest is refused too if the others' energy could carry
        // it that far: a heavy frictionless disc can pass it all on.
        let text = r#"{"bodies": [
          {"id": 1, "pos": [0, 0], "vel": [1e70, 0], "radius": 1, "mass": 1e10, "mu": 0},
          {"id": 2, "pos": [5, 0], "vel": [0, 0], "radius": 1, "mass": 1, "mu": 1e-3}
        ]}"#;
        assert!(err(text).starts_with("bodies[1] (id 2): friction might only stop it"));
        // Without friction nothing stops, so nothing is out of reach, and
        // a real scene is far inside the bound.
        Scene::from_json(&text.replace("1e-3", "0")).unwrap();
        Scene::from_json(&text.replace("1e70", "1e60")).unwrap();
    }

    #[test]
    fn a_scene_round_trips_through_json() {
        let s = Scene::from_json(GOOD).unwrap();
        assert_eq!(Scene::from_json(&s.to_json()).unwrap(), s);
    }
}
