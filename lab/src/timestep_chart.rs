//! Chart 2: a priori against time-stepping — wall time against final-state
//! error on the same scenes (the Chapaev break shots, Galperin's billiard,
//! the box of 100 discs), for the engine with each solver, the fixed-step
//! integrator at several `dt`, and rapier at several `dt` with and without
//! CCD. The error is the worst final position error over the scene's
//! length scale against the reference (1 when a disc fell off in one run
//! only); collision counts are compared too. The engine's wall time is the
//! best of repeated runs (it is too fast to time once); the steppers are
//! timed once.

use crate::apriori;
use crate::files::{self, Csv};
use crate::outcome::{compare, Outcome};
use crate::plot::{self, Axes, Series, Style};
use crate::scenes::Case;
use crate::{rapier_peer, stepper, LabError};
use engine::roots::Method;
use engine::world::BroadPhase;
use std::path::Path;

/// One method's run of one case, scored.
#[derive(Clone, Debug)]
pub struct Row {
    pub case: String,
    pub method: String,
    /// `dt` for the steppers.
    pub dt: Option<f64>,
    pub secs: f64,
    pub error: f64,
    pub collisions: u64,
    pub reference_collisions: u64,
    pub max_overlap: f64,
    pub tunnelled: bool,
}

/// The time steps tried.
#[derive(Clone, Debug)]
pub struct Steps {
    pub stepper: Vec<f64>,
    pub rapier: Vec<f64>,
}

/// Best-of wall time of the engine on `case` (repeats for at least `min_secs`).
pub fn engine_timed(case: &Case, m: Method, min_secs: f64) -> Result<Outcome, LabError> {
    let mut best = apriori::run(case, m, BroadPhase::Auto, false)?;
    let mut total = best.secs;
    while total < min_secs {
        let o = apriori::run(case, m, BroadPhase::Auto, false)?;
        total += o.secs;
        if o.secs < best.secs {
            best = o;
        }
    }
    Ok(best)
}

/// Runs every method on every `(case, reference)`, writes `timestep.csv`
/// and one chart per case into `out`.
pub fn run(
    cases: &[(Case, Outcome)],
    steps: &Steps,
    min_secs: f64,
    out: &Path,
    tick: &mut dyn FnMut(&str),
) -> Result<Vec<Row>, LabError> {
    let mut rows = Vec::new();
    for (case, reference) in cases {
        let mut series = Vec::new();
        let push = |rows: &mut Vec<Row>, method: String, dt: Option<f64>, o: &Outcome| {
            let c = compare(case, o, reference);
            rows.push(Row {
                case: case.name.clone(),
                method,
                dt,
                secs: o.secs,
                error: c.error,
                collisions: o.collisions,
                reference_collisions: reference.collisions,
                max_overlap: o.max_overlap,
                tunnelled: c.tunnelled,
            });
            (o.secs, c.error)
        };
        for m in Method::ALL {
            tick(&format!(
                "a priori vs stepping: {} / engine {}",
                case.name,
                m.name()
            ));
            let o = engine_timed(case, m, min_secs)?;
            let p = push(&mut rows, format!("engine {}", m.name()), None, &o);
            series.push(Series {
                name: format!("engine {}", m.name()),
                points: vec![p],
                style: Style::Points,
            });
        }
        let mut pts = Vec::new();
        for &dt in &steps.stepper {
            tick(&format!(
                "a priori vs stepping: {} / fixed-step dt={dt:e}",
                case.name
            ));
            let o = stepper::run(case, dt, u64::MAX);
            pts.push(push(&mut rows, "fixed-step".into(), Some(dt), &o));
        }
        series.push(Series {
            name: format!("fixed-step Euler, dt {}", dt_range(&steps.stepper)),
            points: pts,
            style: Style::Line,
        });
        for ccd in [false, true] {
            let name = if ccd { "rapier + CCD" } else { "rapier" };
            let mut pts = Vec::new();
            for &dt in &steps.rapier {
                tick(&format!(
                    "a priori vs stepping: {} / {name} dt={dt:e}",
                    case.name
                ));
                let o = rapier_peer::run(case, dt, ccd, u64::MAX);
                pts.push(push(&mut rows, name.into(), Some(dt), &o));
            }
            series.push(Series {
                name: format!("{name}, dt {}", dt_range(&steps.rapier)),
                points: pts,
                style: Style::Line,
            });
        }
        let title = format!(
            "{}: wall time against final-state error (reference: {} collisions)",
            case.name, reference.collisions
        );
        let file = format!("timestep_{}.svg", slug(&case.name));
        plot::log_log(
            &out.join(file),
            &Axes {
                title: &title,
                x: "wall time (s)",
                y: "worst final position error / scene size (1 = wrong outcome)",
                y_floor: 1e-17,
            },
            &series,
        )?;
    }
    let mut csv = Csv::new(&[
        "case",
        "method",
        "dt",
        "wall_s",
        "error",
        "collisions",
        "reference_collisions",
        "max_overlap",
        "tunnelled",
    ]);
    for r in &rows {
        csv.row(&[
            r.case.clone(),
            r.method.clone(),
            r.dt.map(files::num).unwrap_or_default(),
            files::num(r.secs),
            files::num(r.error),
            r.collisions.to_string(),
            r.reference_collisions.to_string(),
            files::num(r.max_overlap),
            r.tunnelled.to_string(),
        ]);
    }
    csv.write(&out.join("timestep.csv"))?;
    Ok(rows)
}

fn dt_range(dts: &[f64]) -> String {
    match (dts.first(), dts.last()) {
        (Some(a), Some(b)) => format!("{a:.0e}..{b:.0e}"),
        _ => String::new(),
    }
}

/// A file-name-safe form of a case name.
pub fn slug(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '-'
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slugs_are_file_name_safe() {
        assert_eq!(slug("Newton's cradle"), "newton-s-cradle");
        assert_eq!(slug("galperin-3"), "galperin-3");
    }
}
