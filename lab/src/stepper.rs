//! The simple time-stepping baseline a programmer would write first: fixed
//! `dt`, semi-implicit Euler. Each step applies friction (speed falls by
//! `mu g dt`, clamped at zero so it never reverses), moves every disc, then
//! looks for overlaps (discs by a sort-and-sweep on x, lines and points by
//! distance) and applies the model's impulse to every overlapping pair that
//! is still approaching. No position correction, no sub-stepping: what
//! overlaps between two steps is resolved late, and what passes through
//! within one step is missed.

use crate::outcome::{BodyEnd, Outcome};
use crate::scenes::Case;
use engine::LineKind;
use glam::DVec2;
use std::time::Instant;

struct Seg {
    a: DVec2,
    b: DVec2,
    kind: LineKind,
}

impl Seg {
    /// The point of the line, ray or segment nearest to `p`.
    fn nearest(&self, p: DVec2) -> DVec2 {
        let d = self.b - self.a;
        let t = (p - self.a).dot(d) / d.length_squared();
        let t = match self.kind {
            LineKind::Line => t,
            LineKind::Ray => t.max(0.0),
            LineKind::Segment => t.clamp(0.0, 1.0),
        };
        self.a + d * t
    }
}

/// Computes `case` with time step `dt`, taking at most `max_steps` steps.
pub fn run(case: &Case, dt: f64, max_steps: u64) -> Outcome {
    let start = Instant::now();
    let sc = &case.scene;
    let n = sc.bodies.len();
    let mut p: Vec<DVec2> = sc.bodies.iter().map(|b| b.pos).collect();
    let mut v: Vec<DVec2> = sc.bodies.iter().map(|b| b.vel).collect();
    let r: Vec<f64> = sc.bodies.iter().map(|b| b.radius).collect();
    let inv_m: Vec<f64> = sc.bodies.iter().map(|b| 1.0 / b.mass).collect();
    let e: Vec<f64> = sc.bodies.iter().map(|b| b.restitution).collect();
    let decel: Vec<f64> = sc.bodies.iter().map(|b| b.mu * sc.g * dt).collect();
    let mut alive = vec![true; n];
    let segs: Vec<Seg> = sc
        .lines
        .iter()
        .filter(|l| !l.sensor)
        .map(|l| Seg {
            a: l.a,
            b: l.b,
            kind: l.kind,
        })
        .collect();
    let points: Vec<DVec2> = sc.points.iter().map(|q| q.pos).collect();
    let board = case.board();
    let max_r = r.iter().copied().fold(0.0, f64::max);
    let mut order: Vec<usize> = (0..n).collect();
    let mut collisions = 0u64;
    let mut max_overlap: f64 = 0.0;
    let steps_needed = (case.until / dt).ceil() as u64;
    let steps = steps_needed.min(max_steps);
    let mut t = sc.t;
    for _ in 0..steps {
        let h = dt.min(case.until - t).max(0.0);
        for i in 0..n {
            if !alive[i] {
                continue;
            }
            let speed = v[i].length();
            let dv = decel[i] * h / dt;
            v[i] = if speed <= dv {
                DVec2::ZERO
            } else {
                v[i] * (1.0 - dv / speed)
            };
            p[i] += v[i] * h;
        }
        t += h;
        // Sort-and-sweep on x (insertion sort: the order barely changes).
        for k in 1..n {
            let mut j = k;
            while j > 0 && p[order[j - 1]].x > p[order[j]].x {
                order.swap(j - 1, j);
                j -= 1;
            }
        }
        for a in 0..n {
            let i = order[a];
            if !alive[i] {
                continue;
            }
            for &j in &order[a + 1..] {
                if p[j].x - p[i].x > r[i] + max_r {
                    break;
                }
                if !alive[j] {
                    continue;
                }
                let s = r[i] + r[j];
                let d = p[i] - p[j];
                let dist2 = d.length_squared();
                if dist2 >= s * s || dist2 == 0.0 {
                    continue;
                }
                let dist = dist2.sqrt();
                max_overlap = max_overlap.max((s - dist) / s);
                let nrm = d / dist;
                let w = (v[i] - v[j]).dot(nrm);
                if w < 0.0 {
                    let jmp = -(1.0 + e[i].min(e[j])) * w / (inv_m[i] + inv_m[j]);
                    v[i] += nrm * (jmp * inv_m[i]);
                    v[j] -= nrm * (jmp * inv_m[j]);
                    collisions += 1;
                }
            }
        }
        for i in 0..n {
            if !alive[i] {
                continue;
            }
            let fixed = segs
                .iter()
                .map(|s| s.nearest(p[i]))
                .chain(points.iter().copied());
            for q in fixed {
                let d = p[i] - q;
                let dist = d.length();
                if dist >= r[i] || dist == 0.0 {
                    continue;
                }
                max_overlap = max_overlap.max((r[i] - dist) / r[i]);
                let nrm = d / dist;
                let w = v[i].dot(nrm);
                if w < 0.0 {
                    v[i] -= nrm * ((1.0 + e[i]) * w);
                    collisions += 1;
                }
            }
            if let Some(b) = &board {
                if !b.contains(p[i]) {
                    alive[i] = false;
                }
            }
        }
        if h == 0.0 {
            break;
        }
    }
    let mut bodies: Vec<BodyEnd> = (0..n)
        .map(|i| BodyEnd {
            id: sc.bodies[i].id.0,
            pos: p[i],
            vel: v[i],
            removed: !alive[i],
        })
        .collect();
    bodies.sort_by_key(|b| b.id);
    Outcome {
        bodies,
        collisions,
        capped: steps < steps_needed,
        max_overlap,
        secs: start.elapsed().as_secs_f64(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes;

    #[test]
    fn a_lone_sliding_disc_stops_near_the_closed_form_distance() {
        let mut case = scenes::fast_tiny();
        case.scene.lines.clear();
        case.scene.bodies[0].vel = DVec2::new(1.0, 0.0);
        case.until = 1.0;
        let out = run(&case, 1e-5, u64::MAX);
        let expected = case.scene.bodies[0].pos.x + 1.0 / (2.0 * 0.3 * 9.81);
        assert!((out.bodies[0].pos.x - expected).abs() < 1e-4);
        assert_eq!(out.bodies[0].vel, DVec2::ZERO);
    }

    #[test]
    fn large_steps_tunnel_through_a_thin_segment() {
        let out = run(&scenes::fast_tiny(), 1e-3, u64::MAX);
        assert_eq!(out.collisions, 0);
        assert!(out.bodies[0].pos.x > 0.5);
        let fine = run(&scenes::fast_tiny(), 1e-7, u64::MAX);
        assert_eq!(fine.collisions, 1);
        assert!(fine.bodies[0].pos.x < 0.5);
    }
}
