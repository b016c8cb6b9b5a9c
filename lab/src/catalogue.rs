//! The polynomials the root solvers are scored on. Two sets:
//!
//! * the hard quartics of the literature — Orellana & De Michele 2020
//!   (ACM TOMS Algorithm 1010, accuracy cases 1–24) and Flocke 2015
//!   (Algorithm 954, quartic cases 1–13) — plus clustered, multiple and
//!   widely scaled roots of our own. Cases given by their roots are
//!   expanded in 320-bit arithmetic and rounded once to `f64`, so they keep
//!   their nominal roots for comparison too;
//! * contact quartics `|dp + dv t + da t^2/2|^2 - S^2` taken from real
//!   scenes: after every event of the engine, every pair of moving discs
//!   (at least one with friction) whose remaining paths come within
//!   reach, on the interval until the first of the two stops — the
//!   queries the engine itself makes.

use crate::hp::{self, big, F};
use crate::scenes::Case;
use engine::{Limits, World, WorldConfig};
use glam::DVec2;

/// One first-root query: the smallest root of `coeffs` in `[lo, hi)`.
#[derive(Clone, Debug)]
pub struct Query {
    pub name: String,
    /// Lowest degree first, degree 4.
    pub coeffs: [f64; 5],
    pub lo: f64,
    pub hi: f64,
    /// The nominal first real root (for cases built from their roots).
    pub nominal: Option<f64>,
}

/// Coefficients of `prod (x - r) * prod ((x - re)^2 + im^2)`, expanded in
/// high precision and rounded once.
fn expand(real: &[f64], pairs: &[(f64, f64)]) -> [f64; 5] {
    let mut c: Vec<F> = vec![big(1.0)];
    let mul = |c: &Vec<F>, f: &[F]| {
        let mut out = vec![hp::zero(); c.len() + f.len() - 1];
        for (i, a) in c.iter().enumerate() {
            for (j, b) in f.iter().enumerate() {
                out[i + j] = out[i + j].clone() + a.clone() * b;
            }
        }
        out
    };
    for &r in real {
        c = mul(&c, &[-big(r), big(1.0)]);
    }
    for &(re, im) in pairs {
        let (re, im) = (big(re), big(im));
        let q = [
            re.clone() * &re + im.clone() * &im,
            -(re * big(2.0)),
            big(1.0),
        ];
        c = mul(&c, &q);
    }
    let mut out = [0.0; 5];
    for (o, v) in out.iter_mut().zip(&c) {
        *o = hp::to_f64(v);
    }
    out
}

fn roots_case(name: &str, real: &[f64], pairs: &[(f64, f64)]) -> Query {
    Query {
        name: name.into(),
        coeffs: expand(real, pairs),
        lo: f64::NEG_INFINITY,
        hi: f64::INFINITY,
        nominal: real.iter().copied().reduce(f64::min),
    }
}

/// Coefficients printed highest degree first (as the papers do).
fn printed(name: &str, c: [f64; 5]) -> Query {
    let mut coeffs = c;
    coeffs.reverse();
    Query {
        name: name.into(),
        coeffs,
        lo: f64::NEG_INFINITY,
        hi: f64::INFINITY,
        nominal: None,
    }
}

/// The hard quartics.
pub fn hard_quartics() -> Vec<Query> {
    let s = 1e30;
    let mut v = vec![
        roots_case("A1010 1", &[1e9, 1e6, 1e3, 1.0], &[]),
        roots_case("A1010 2", &[2.003, 2.002, 2.001, 2.0], &[]),
        roots_case("A1010 3", &[1e53, 1e50, 1e49, 1e47], &[]),
        roots_case("A1010 4", &[1e14, 2.0, 1.0, -1.0], &[]),
        roots_case("A1010 5", &[-2e7, 1e7, 1.0, -1.0], &[]),
        roots_case("A1010 6", &[1e7, -1e6], &[(1.0, 1.0)]),
        roots_case("A1010 7", &[-7.0, -4.0], &[(-1e6, 1e5)]),
        roots_case("A1010 8", &[1e8, 11.0], &[(1e3, 1.0)]),
        roots_case("A1010 9", &[], &[(1e7, 1e6), (1.0, 2.0)]),
        roots_case("A1010 10", &[], &[(1e4, 3.0), (-7.0, 1e3)]),
        roots_case("A1010 11", &[], &[(1.001, 4.998), (1.0, 5.001)]),
        roots_case("A1010 12", &[], &[(1e3, 3.0), (1e3, 1.0)]),
        roots_case("A1010 13", &[], &[(2.0, 1e4), (1.0, 1e3)]),
        roots_case("A1010 14", &[1e3, 1e3, 1e3, 1e3], &[]),
        roots_case("A1010 15", &[1e3, 1e3, 1e3, 2f64.powi(-48)], &[]),
        roots_case("A1010 16", &[], &[(1e16, 1e7), (1.0, 0.1)]),
        roots_case("A1010 17", &[1e4, 10001.0, 10010.0, 10100.0], &[]),
        roots_case("A1010 18", &[], &[(4e5, 3e2), (3e4, 7e3)]),
        roots_case("A1010 19", &[1e44, 1e30, 1e30, 1.0], &[]),
        roots_case("A1010 20", &[1e14, 1e7, 1e7, 1.0], &[]),
        roots_case("A1010 21", &[1e15, 1e7, 1e7, 1.0], &[]),
        roots_case("A1010 22", &[1e154, 1e152, 10.0, 1.0], &[]),
        Query {
            name: "A1010 23".into(),
            coeffs: [0.001, 0.375, 1.0, 1.0, 1.0],
            lo: f64::NEG_INFINITY,
            hi: f64::INFINITY,
            nominal: None,
        },
        Query {
            name: "A1010 24".into(),
            coeffs: [-s, s * s + s, 1.0 / s - s * s, -(1.0 + 1.0 / s), 1.0],
            lo: f64::NEG_INFINITY,
            hi: f64::INFINITY,
            nominal: None,
        },
        printed(
            "F954 1",
            [
                1.0,
                -1001001001.0,
                1001002001001000.0,
                -1001001001000000000.0,
                1e18,
            ],
        ),
        printed("F954 2", [1.0, -4.006, 6.018011, -4.018022006, 1.006011006]),
        printed(
            "F954 3",
            [1.0, -9.98899e79, -1.1008989e157, -1.010999e233, -1e307],
        ),
        printed(
            "F954 4",
            [
                1.0,
                -1.00000000000002e14,
                1.99999999999999e14,
                1.00000000000002e14,
                -2e14,
            ],
        ),
        printed("F954 5", [1.0, 1e7, -2.00000000000001e14, -1e7, 2e14]),
        printed(
            "F954 6",
            [1.0, -9.000002e6, -0.9999981999998e13, 1.9999982e13, -2e13],
        ),
        printed(
            "F954 7",
            [1.0, 2.000011e6, 1.010022000028e12, 1.1110056e13, 2.828e13],
        ),
        printed(
            "F954 8",
            [
                1.0,
                -1.00002011e8,
                2.01101022001e11,
                -1.02200111000011e14,
                1.1000011e15,
            ],
        ),
        printed(
            "F954 9",
            [
                1.0,
                -2.0000002e7,
                1.01000040000005e14,
                -2.020001e14,
                5.05e14,
            ],
        ),
        printed(
            "F954 10",
            [
                1.0,
                -1.9986e4,
                1.00720058e8,
                -1.8600979874e10,
                1.00004909000441e14,
            ],
        ),
        printed(
            "F954 11",
            [
                1.0,
                -4.006,
                5.6008018e1,
                -1.04148036024e2,
                6.75896068064016e2,
            ],
        ),
        printed(
            "F954 12",
            [1.0, -4e3, 6.00001e6, -4.00002e9, 1.000010000009e12],
        ),
        printed(
            "F954 13",
            [1.0, -6.0, 1.01000013e8, -2.04000012e8, 1.00000104000004e14],
        ),
        roots_case(
            "cluster 1+k 1e-7",
            &[1.0, 1.0 + 1e-7, 1.0 + 2e-7, 1.0 + 3e-7],
            &[],
        ),
        roots_case("cluster 1,1+1e-7,2,3", &[1.0, 1.0 + 1e-7, 2.0, 3.0], &[]),
        roots_case(
            "cluster 1e-3+-1e-12",
            &[1e-3 - 1e-12, 1e-3 + 1e-12, -1.0, 5.0],
            &[],
        ),
        roots_case("pair above complex", &[0.5, 0.5 + 1e-4], &[(0.5, 1e-3)]),
        printed("double 1 exact", [1.0, -7.0, 17.0, -17.0, 6.0]),
        roots_case("double 0.1 rounded", &[0.1, 0.1, 0.3, -0.7], &[]),
        printed("two doubles exact", [1.0, -6.0, 13.0, -12.0, 4.0]),
        printed("quadruple 1 exact", [1.0, -4.0, 6.0, -4.0, 1.0]),
        roots_case("quadruple 0.3 rounded", &[0.3, 0.3, 0.3, 0.3], &[]),
        roots_case("scaled 1e-8..1e8", &[1e-8, 1e-3, 1e3, 1e8], &[]),
        roots_case("scaled -1e8..1e4", &[-1e8, -1e-8, 1e-4, 1e4], &[]),
        printed("tiny leading 1e-12", [1e-12, 0.0, 1.0, 0.0, -1.0]),
    ];
    // Grazing: a near-double root just above a simple one, positive half-line.
    for k in [10, 20, 26, 30] {
        let eps = 2f64.powi(-k);
        v.push(roots_case(
            &format!("near-double 2^-{k}"),
            &[0.5, 0.5 + eps, 2.0, 3.0],
            &[],
        ));
    }
    v
}

/// Up to `limit` contact quartics from running `case` with the engine.
pub fn contact_quartics(case: &Case, limit: usize) -> Vec<Query> {
    let mut out = Vec::new();
    let Ok(mut world) = World::new(&case.scene, WorldConfig::default()) else {
        return out;
    };
    let mut events = 0u64;
    let limits = Limits::default();
    while out.len() < limit && events < case.max_events.min(limits.max_events) {
        let now = world.time();
        let bodies: Vec<_> = world.bodies().collect();
        for (i, a) in bodies.iter().enumerate() {
            for b in &bodies[i + 1..] {
                let (ta, tb) = (&a.trajectory, &b.trajectory);
                if !ta.is_moving_at(now) || !tb.is_moving_at(now) {
                    continue;
                }
                if ta.is_frictionless() && tb.is_frictionless() {
                    continue;
                }
                let s = a.material.radius + b.material.radius;
                let (pa, pb) = (ta.position(now), tb.position(now));
                let (ea, eb) = (ta.position(ta.stop_time()), tb.position(tb.stop_time()));
                let reach = |t: &engine::Trajectory, p: DVec2, e: DVec2| {
                    if t.is_frictionless() {
                        p + t.velocity(now) * 1e3
                    } else {
                        e
                    }
                };
                if engine::contact::segment_distance(pa, reach(ta, pa, ea), pb, reach(tb, pb, eb))
                    > s
                {
                    continue;
                }
                let dp = pa - pb;
                let dv = ta.velocity(now) - tb.velocity(now);
                let da = ta.acceleration(now) - tb.acceleration(now);
                let c0 = dp.length_squared() - s * s;
                if c0 <= 2e-12 * s * s {
                    continue; // touching now: the engine solves a cubic instead
                }
                out.push(Query {
                    name: format!("{} t={now:.6} {}-{}", case.name, a.id.0, b.id.0),
                    coeffs: [
                        c0,
                        2.0 * dp.dot(dv),
                        dv.length_squared() + dp.dot(da),
                        dv.dot(da),
                        0.25 * da.length_squared(),
                    ],
                    lo: 0.0,
                    hi: ta.stop_time().min(tb.stop_time()) - now,
                    nominal: None,
                });
                if out.len() >= limit {
                    return out;
                }
            }
        }
        if world.step(case.until, &mut ()).is_none() {
            break;
        }
        events += 1;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes;

    #[test]
    fn expanded_cases_round_their_roots_into_the_coefficients() {
        let q = roots_case("t", &[1.0, 2.0, 3.0, 4.0], &[]);
        assert_eq!(q.coeffs, [24.0, -50.0, 35.0, -10.0, 1.0]);
        assert_eq!(q.nominal, Some(1.0));
    }

    #[test]
    fn hard_table_holds_the_published_cases() {
        let t = hard_quartics();
        assert_eq!(t.iter().filter(|q| q.name.starts_with("A1010")).count(), 24);
        assert_eq!(t.iter().filter(|q| q.name.starts_with("F954")).count(), 13);
        assert!(t.iter().all(|q| q.coeffs[4] != 0.0));
    }

    #[test]
    fn real_scenes_give_contact_quartics_with_positive_horizons() {
        let q = contact_quartics(&scenes::box100().unwrap(), 50);
        assert_eq!(q.len(), 50);
        assert!(q.iter().all(|q| q.hi > 0.0 && q.coeffs[0] > 0.0));
    }
}
