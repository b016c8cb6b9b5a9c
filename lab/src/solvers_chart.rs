//! Chart 1: root solvers, time per first-root query against error. Every
//! solver the engine offers and the two published-algorithm peers
//! available as crates (`roots` 0.0.8 `find_roots_quartic`, `kurbo` 0.11
//! `common::solve_quartic`; for the peers, the first root is the smallest
//! of their roots in the interval) answer the same queries; each answer is
//! scored against the exact first root of the polynomial *as rounded to
//! `f64`* ([`hp::first_root_f64`]), and, where the case was built from its
//! roots, against the nominal root too (in the CSV). A missed root (the
//! reference has one, the solver returns none or a later one) and a
//! spurious one count as relative error 1 in the chart's worst case.

use crate::catalogue::Query;
use crate::files::{self, Csv};
use crate::hp;
use crate::plot::{self, Axes, Series, Style};
use crate::LabError;
use engine::roots::{Method, RootSolver};
use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

/// A solver under test.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Solver {
    Engine(Method),
    /// `roots::find_roots_quartic` (Ferrari / Neumark style).
    RootsCrate,
    /// `kurbo::common::solve_quartic` (Orellana & De Michele).
    Kurbo,
}

impl Solver {
    /// Every solver, the engine's first.
    pub fn all() -> Vec<Solver> {
        let mut v: Vec<Solver> = Method::ALL.iter().map(|&m| Solver::Engine(m)).collect();
        v.push(Solver::RootsCrate);
        v.push(Solver::Kurbo);
        v
    }

    pub fn name(self) -> String {
        match self {
            Solver::Engine(m) => format!("engine {}", m.name()),
            Solver::RootsCrate => "roots 0.0.8".into(),
            Solver::Kurbo => "kurbo 0.11".into(),
        }
    }

    /// The smallest root in `[lo, hi)`.
    pub fn first_root(self, c: &[f64; 5], lo: f64, hi: f64) -> Option<f64> {
        let pick = |rs: &[f64]| {
            rs.iter()
                .copied()
                .filter(|r| *r >= lo && *r < hi)
                .fold(None, |m: Option<f64>, r| Some(m.map_or(r, |m| m.min(r))))
        };
        match self {
            Solver::Engine(m) => m.first_root(c, lo, hi),
            Solver::RootsCrate => {
                let r = roots::find_roots_quartic(c[4], c[3], c[2], c[1], c[0]);
                pick(r.as_ref())
            }
            Solver::Kurbo => pick(&kurbo::common::solve_quartic(c[0], c[1], c[2], c[3], c[4])),
        }
    }
}

/// How one answer compares with the exact first root.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Verdict {
    /// Relative error of the root (0 when both agree there is none).
    Found(f64),
    Missed,
    Spurious,
}

impl Verdict {
    /// The error as charted: missed and spurious roots count as 1.
    pub fn charted(self) -> f64 {
        match self {
            Verdict::Found(e) => e.min(1.0),
            _ => 1.0,
        }
    }
}

/// Scores `got` against the exact first root `exact`.
pub fn judge(got: Option<f64>, exact: Option<f64>) -> Verdict {
    match (got, exact) {
        (None, None) => Verdict::Found(0.0),
        (None, Some(_)) => Verdict::Missed,
        (Some(_), None) => Verdict::Spurious,
        (Some(g), Some(x)) => {
            let rel = if x == 0.0 {
                g.abs()
            } else {
                ((g - x) / x).abs()
            };
            if rel <= 1e-2 {
                Verdict::Found(rel)
            } else if g > x {
                Verdict::Missed
            } else {
                Verdict::Spurious
            }
        }
    }
}

/// The summary of one solver on one query set.
#[derive(Clone, Debug)]
pub struct Summary {
    pub set: String,
    pub solver: String,
    pub queries: usize,
    pub ns_per_query: f64,
    pub median_err: f64,
    pub max_err: f64,
    pub missed: usize,
    pub spurious: usize,
}

fn time_solver(s: Solver, qs: &[Query], min_secs: f64) -> f64 {
    let mut reps = 0u64;
    let start = Instant::now();
    loop {
        for q in qs {
            black_box(s.first_root(black_box(&q.coeffs), q.lo, q.hi));
        }
        reps += 1;
        if start.elapsed().as_secs_f64() >= min_secs {
            break;
        }
    }
    start.elapsed().as_secs_f64() * 1e9 / (reps as f64 * qs.len().max(1) as f64)
}

/// Scores and times every solver on `sets` (name, queries); writes
/// `solvers.csv`, `solvers_cases.csv` and one chart per set into `out`.
pub fn run(
    sets: &[(&str, Vec<Query>)],
    min_secs: f64,
    out: &Path,
    tick: &mut dyn FnMut(&str),
) -> Result<Vec<Summary>, LabError> {
    let mut cases = Csv::new(&[
        "set",
        "case",
        "solver",
        "exact_root",
        "nominal_root",
        "solver_root",
        "rel_err",
        "rel_err_vs_nominal",
        "verdict",
    ]);
    let mut sums = Vec::new();
    for (set, qs) in sets {
        tick(&format!(
            "solvers: exact roots of {} {set} queries",
            qs.len()
        ));
        let exact: Vec<Option<f64>> = qs
            .iter()
            .map(|q| hp::first_root_f64(&q.coeffs, q.lo, q.hi))
            .collect();
        let mut series = Vec::new();
        for s in Solver::all() {
            tick(&format!("solvers: {} on {set}", s.name()));
            let mut errs = Vec::new();
            let (mut missed, mut spurious) = (0, 0);
            for (q, x) in qs.iter().zip(&exact) {
                let got = s.first_root(&q.coeffs, q.lo, q.hi);
                let v = judge(got, *x);
                match v {
                    Verdict::Missed => missed += 1,
                    Verdict::Spurious => spurious += 1,
                    Verdict::Found(_) => {}
                }
                errs.push(v.charted());
                let vs_nominal = match (got, q.nominal) {
                    (Some(g), Some(n)) => files::num(((g - n) / n).abs()),
                    _ => String::new(),
                };
                cases.row(&[
                    set.to_string(),
                    q.name.clone(),
                    s.name(),
                    x.map(files::num).unwrap_or_default(),
                    q.nominal.map(files::num).unwrap_or_default(),
                    got.map(files::num).unwrap_or_default(),
                    match v {
                        Verdict::Found(e) => files::num(e),
                        _ => String::new(),
                    },
                    vs_nominal,
                    format!("{v:?}")
                        .split('(')
                        .next()
                        .unwrap_or("")
                        .to_lowercase(),
                ]);
            }
            errs.sort_by(f64::total_cmp);
            let median = errs.get(errs.len() / 2).copied().unwrap_or(0.0);
            let max = errs.last().copied().unwrap_or(0.0);
            let ns = time_solver(s, qs, min_secs);
            series.push(Series {
                name: format!("{} (missed {missed}, spurious {spurious})", s.name()),
                points: vec![(ns, median), (ns, max)],
                style: Style::Line,
            });
            sums.push(Summary {
                set: set.to_string(),
                solver: s.name(),
                queries: qs.len(),
                ns_per_query: ns,
                median_err: median,
                max_err: max,
                missed,
                spurious,
            });
        }
        let title = format!("Root solvers on {set}: median to worst relative error");
        plot::log_log(
            &out.join(format!("solvers_{set}.svg")),
            &Axes {
                title: &title,
                x: "time per first-root query (ns)",
                y: "relative error of the first root (missed = 1; 1e-18 = exact)",
                y_floor: 1e-18,
            },
            &series,
        )?;
    }
    cases.write(&out.join("solvers_cases.csv"))?;
    let mut csv = Csv::new(&[
        "set",
        "solver",
        "queries",
        "ns_per_query",
        "median_rel_err",
        "max_rel_err",
        "missed",
        "spurious",
    ]);
    for s in &sums {
        csv.row(&[
            s.set.clone(),
            s.solver.clone(),
            s.queries.to_string(),
            format!("{:.1}", s.ns_per_query),
            files::num(s.median_err),
            files::num(s.max_err),
            s.missed.to_string(),
            s.spurious.to_string(),
        ]);
    }
    csv.write(&out.join("solvers.csv"))?;
    Ok(sums)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn judge_separates_missed_spurious_and_found_roots() {
        assert_eq!(judge(None, None), Verdict::Found(0.0));
        assert_eq!(judge(None, Some(1.0)), Verdict::Missed);
        assert_eq!(judge(Some(1.0), None), Verdict::Spurious);
        assert_eq!(judge(Some(2.0), Some(1.0)), Verdict::Missed);
        assert_eq!(judge(Some(0.5), Some(1.0)), Verdict::Spurious);
        match judge(Some(1.0 + 1e-12), Some(1.0)) {
            Verdict::Found(e) => assert!(e > 0.0 && e < 2e-12),
            v => panic!("{v:?}"),
        }
    }

    #[test]
    fn every_solver_finds_the_first_root_of_a_plain_quartic() {
        let c = [24.0, -50.0, 35.0, -10.0, 1.0];
        for s in Solver::all() {
            let r = s.first_root(&c, 0.0, f64::INFINITY).unwrap();
            assert!((r - 1.0).abs() < 1e-9, "{}", s.name());
            let r = s.first_root(&c, 1.5, 3.5).unwrap();
            assert!((r - 2.0).abs() < 1e-9, "{}", s.name());
        }
    }
}
