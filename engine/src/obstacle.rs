//! Immovable obstacles: points and lines (infinite lines, rays, segments).
//!
//! A line is given by two points `a`, `b` and a kind. Its geometry in normal
//! form (`n . x + c = 0` with `|n| = 1`) and its extent along the tangent are
//! derived once by [`LineGeom`]. The ends of a ray or segment act as points,
//! so a disc can hit a corner. A line marked `sensor` is not solid: discs
//! pass through it, and the engine reports when a centre crosses it (the
//! region-exit event the game uses for the board edge). The inside of a
//! sensor is its left side, walking from `a` to `b`.

use glam::DVec2;
use serde::{Deserialize, Serialize};

/// An immovable point.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Point {
    #[schemars(with = "[f64; 2]")]
    pub pos: DVec2,
}

/// What part of the line through `a` and `b` exists.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum LineKind {
    /// Infinite both ways.
    Line,
    /// From `a` through `b` and on.
    Ray,
    /// From `a` to `b`.
    Segment,
}

/// An immovable line, ray or segment; or, with `sensor`, a boundary that
/// reports crossings instead of stopping discs.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Line {
    #[schemars(with = "[f64; 2]")]
    pub a: DVec2,
    #[schemars(with = "[f64; 2]")]
    pub b: DVec2,
    pub kind: LineKind,
    /// Not solid: report centre crossings (region exits) instead.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub sensor: bool,
}

impl Line {
    /// A solid line of the given kind.
    pub fn new(a: DVec2, b: DVec2, kind: LineKind) -> Self {
        Line {
            a,
            b,
            kind,
            sensor: false,
        }
    }

    /// A sensor (region boundary) of the given kind; its inside is on the left of `a -> b`.
    pub fn sensor(a: DVec2, b: DVec2, kind: LineKind) -> Self {
        Line {
            a,
            b,
            kind,
            sensor: true,
        }
    }
}

/// Derived geometry of a line: normal form, tangent and extent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineGeom {
    /// Unit normal, pointing to the left of `a -> b` (the inside of a sensor).
    pub n: DVec2,
    /// Offset: the signed distance of `x` is `n . x + c`.
    pub c: f64,
    /// Start point and unit tangent `(b - a)/|b - a|`.
    pub a: DVec2,
    pub tangent: DVec2,
    /// Extent along the tangent from `a`: `[lo, hi]`.
    pub lo: f64,
    pub hi: f64,
    /// The end points that act as corners (`a` for ray and segment, `b` for segment).
    pub ends: [Option<DVec2>; 2],
}

impl LineGeom {
    /// The geometry of `line`, or `None` if its two points coincide.
    pub fn new(line: &Line) -> Option<Self> {
        let d = line.b - line.a;
        let len = d.length();
        if !(len > 0.0) || !len.is_finite() {
            return None;
        }
        let tangent = d / len;
        let n = tangent.perp();
        let c = -n.dot(line.a);
        let (lo, hi, ends) = match line.kind {
            LineKind::Line => (f64::NEG_INFINITY, f64::INFINITY, [None, None]),
            LineKind::Ray => (0.0, f64::INFINITY, [Some(line.a), None]),
            LineKind::Segment => (0.0, len, [Some(line.a), Some(line.b)]),
        };
        Some(LineGeom {
            n,
            c,
            a: line.a,
            tangent,
            lo,
            hi,
            ends,
        })
    }

    /// Signed distance of `x` from the line (positive on the left / inside).
    pub fn signed_distance(&self, x: DVec2) -> f64 {
        self.n.dot(x) + self.c
    }

    /// Whether the line ends somewhere (a ray or a segment).
    #[inline]
    pub fn is_bounded(&self) -> bool {
        self.lo != f64::NEG_INFINITY || self.hi != f64::INFINITY
    }

    /// Whether the foot of the perpendicular from `x` lies on the line's extent.
    pub fn covers(&self, x: DVec2) -> bool {
        let along = (x - self.a).dot(self.tangent);
        along >= self.lo && along <= self.hi
    }

    /// Distance from `x` to the nearest point of the line, ray or segment.
    pub fn distance(&self, x: DVec2) -> f64 {
        let along = (x - self.a).dot(self.tangent);
        let clamped = along.clamp(self.lo, self.hi);
        if clamped == along {
            self.signed_distance(x).abs()
        } else {
            (self.a + self.tangent * clamped - x).length()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segment_distance_uses_the_nearest_end_beyond_its_extent() {
        let seg = Line::new(DVec2::ZERO, DVec2::new(2.0, 0.0), LineKind::Segment);
        let g = LineGeom::new(&seg).unwrap();
        assert_eq!(g.distance(DVec2::new(1.0, 3.0)), 3.0);
        assert_eq!(g.distance(DVec2::new(5.0, 4.0)), 5.0);
        assert_eq!(g.signed_distance(DVec2::new(1.0, 3.0)), 3.0);
        assert_eq!(g.signed_distance(DVec2::new(1.0, -3.0)), -3.0);
    }

    #[test]
    fn a_line_with_coinciding_points_has_no_geometry() {
        let l = Line::new(DVec2::ONE, DVec2::ONE, LineKind::Line);
        assert!(LineGeom::new(&l).is_none());
    }

    #[test]
    fn kinds_use_kebab_case_names_in_json() {
        let l: Line = serde_json::from_str(r#"{"a":[0,0],"b":[1,0],"kind":"ray"}"#).unwrap();
        assert_eq!(l.kind, LineKind::Ray);
        assert!(!l.sensor);
    }
}
