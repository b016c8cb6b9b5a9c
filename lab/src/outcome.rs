//! What a method's run produced, in one shape for every method (engine,
//! reference, fixed-step, rapier), and how two runs are compared: the final
//! state's worst position error over the case's length scale, the
//! collision counts, who fell off the board, and which side of each solid
//! line every disc ended on (a different side than the reference means the
//! disc tunnelled).

use crate::scenes::Case;
use engine::{LineKind, Scene};
use glam::DVec2;

/// One disc at the end of a run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyEnd {
    pub id: u64,
    pub pos: DVec2,
    pub vel: DVec2,
    /// Taken off the board (its state is then not compared).
    pub removed: bool,
}

/// The result of computing a case with one method.
#[derive(Clone, Debug, Default)]
pub struct Outcome {
    /// Sorted by id.
    pub bodies: Vec<BodyEnd>,
    pub collisions: u64,
    /// Stopped on the event/step cap before `until`.
    pub capped: bool,
    /// The largest overlap seen, as a fraction of the contact distance.
    pub max_overlap: f64,
    /// Wall time of the computation in seconds.
    pub secs: f64,
}

impl Outcome {
    /// Whether any final position or velocity is NaN or infinite.
    pub fn has_nan(&self) -> bool {
        self.bodies
            .iter()
            .any(|b| !(b.pos.is_finite() && b.vel.is_finite()))
    }
}

/// How a run differs from the reference.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Comparison {
    /// Worst position error of bodies present in both, over the scale
    /// (1.0 when some body fell off in one run only; infinite for NaN).
    pub error: f64,
    pub count_matches: bool,
    /// Some disc ended on the other side of a solid line.
    pub tunnelled: bool,
}

/// The maximum overlap between discs of a scene-like state, as a fraction
/// of the contact distance (0 when none overlap).
pub fn overlap_of(bodies: &[(DVec2, f64)]) -> f64 {
    let mut worst: f64 = 0.0;
    for i in 0..bodies.len() {
        for j in i + 1..bodies.len() {
            let s = bodies[i].1 + bodies[j].1;
            let d = (bodies[i].0 - bodies[j].0).length();
            worst = worst.max((s - d) / s);
        }
    }
    worst
}

/// Side of the line (through `a`, `b`) that `p` is on; 0 when beyond a
/// segment's extent (no side to cross).
fn side(kind: LineKind, a: DVec2, b: DVec2, p: DVec2) -> i8 {
    let t = b - a;
    let along = (p - a).dot(t) / t.length_squared();
    let within = match kind {
        LineKind::Line => true,
        LineKind::Ray => along >= 0.0,
        LineKind::Segment => (0.0..=1.0).contains(&along),
    };
    if !within {
        return 0;
    }
    if t.perp_dot(p - a) >= 0.0 {
        1
    } else {
        -1
    }
}

/// Compares `run` with `reference` on `case`.
pub fn compare(case: &Case, run: &Outcome, reference: &Outcome) -> Comparison {
    let count_matches = run.collisions == reference.collisions;
    if run.has_nan() {
        return Comparison {
            error: f64::INFINITY,
            count_matches,
            tunnelled: false,
        };
    }
    let mut error: f64 = 0.0;
    let mut tunnelled = false;
    for r in &reference.bodies {
        let Some(b) = run.bodies.iter().find(|b| b.id == r.id) else {
            error = error.max(1.0);
            continue;
        };
        if b.removed != r.removed {
            error = error.max(1.0);
            continue;
        }
        if b.removed {
            continue;
        }
        error = error.max((b.pos - r.pos).length() / case.scale);
        tunnelled |= crossed(&case.scene, b.pos, r.pos);
    }
    Comparison {
        error: error.min(1.0),
        count_matches,
        tunnelled,
    }
}

/// Whether `p` and `q` lie on strictly different sides of a solid line.
fn crossed(scene: &Scene, p: DVec2, q: DVec2) -> bool {
    scene.lines.iter().filter(|l| !l.sensor).any(|l| {
        let (sp, sq) = (side(l.kind, l.a, l.b, p), side(l.kind, l.a, l.b, q));
        sp != 0 && sq != 0 && sp != sq
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes;

    fn end(id: u64, x: f64) -> BodyEnd {
        BodyEnd {
            id,
            pos: DVec2::new(x, 0.0),
            vel: DVec2::ZERO,
            removed: false,
        }
    }

    #[test]
    fn crossing_a_wall_counts_as_tunnelling_and_errors_are_scaled() {
        let case = scenes::fast_tiny();
        let reference = Outcome {
            bodies: vec![end(1, -1.0)],
            collisions: 1,
            ..Outcome::default()
        };
        let run = Outcome {
            bodies: vec![end(1, 0.75)],
            ..Outcome::default()
        };
        let c = compare(&case, &run, &reference);
        assert!(c.tunnelled && !c.count_matches);
        assert_eq!(c.error, 1.0);
        let near = Outcome {
            bodies: vec![end(1, -1.0 + 1e-9)],
            collisions: 1,
            ..Outcome::default()
        };
        let c = compare(&case, &near, &reference);
        assert!(!c.tunnelled && c.count_matches && c.error < 2e-9);
    }

    #[test]
    fn overlap_is_a_fraction_of_the_contact_distance() {
        let o = overlap_of(&[(DVec2::ZERO, 1.0), (DVec2::new(1.5, 0.0), 1.0)]);
        assert!((o - 0.25).abs() < 1e-15);
        assert_eq!(
            overlap_of(&[(DVec2::ZERO, 1.0), (DVec2::new(3.0, 0.0), 1.0)]),
            0.0
        );
    }
}
