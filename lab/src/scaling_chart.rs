//! Chart 3: scaling — events per second against the number of discs, in a
//! closed box at about 10% area fraction (moving frictionless discs, and
//! the same with friction `mu = 0.1`), with the grid broad phase and with
//! every pair (`BroadPhase::AllPairs`). Each run processes up to a fixed
//! number of events after the world is built; the build time is recorded
//! separately. All-pairs is skipped once its projected time (quadratic
//! from the previous size) passes the budget. A third series runs without
//! the event calendar's bookkeeping (`WorldConfig::recompute_all`: every
//! body re-predicted after every event, the naive a priori loop), on the
//! grid, skipped the same way.

use crate::files::{self, Csv};
use crate::plot::{self, Axes, Series, Style};
use crate::scenes::random_box;
use crate::LabError;
use engine::world::{BroadPhase, Counter};
use engine::{Limits, World, WorldConfig};
use std::path::Path;
use std::time::Instant;

/// One measured (or skipped) configuration.
#[derive(Clone, Debug)]
pub struct Row {
    pub n: usize,
    pub friction: bool,
    pub broad_phase: &'static str,
    pub build_s: f64,
    pub run_s: f64,
    pub events: u64,
    pub events_per_s: f64,
    pub skipped: bool,
}

/// Measures every size in `sizes`; `events` per run; writes
/// `scaling.csv` and `scaling.svg` into `out`.
pub fn run(
    sizes: &[usize],
    events: u64,
    budget_s: f64,
    out: &Path,
    tick: &mut dyn FnMut(&str),
) -> Result<Vec<Row>, LabError> {
    let mut rows = Vec::new();
    let mut series = Vec::new();
    for friction in [false, true] {
        for (bp, recompute_all, bp_name) in [
            (BroadPhase::Grid, false, "grid"),
            (BroadPhase::AllPairs, false, "all pairs"),
            (BroadPhase::Grid, true, "grid, no calendar"),
        ] {
            let mut pts = Vec::new();
            let mut last: Option<(usize, f64)> = None;
            for &n in sizes {
                let projected = last.map_or(0.0, |(m, s)| s * (n as f64 / m as f64).powi(2));
                let fr = if friction { "friction" } else { "frictionless" };
                if (bp == BroadPhase::AllPairs || recompute_all) && projected > budget_s {
                    rows.push(Row {
                        n,
                        friction,
                        broad_phase: bp_name,
                        build_s: 0.0,
                        run_s: 0.0,
                        events: 0,
                        events_per_s: 0.0,
                        skipped: true,
                    });
                    continue;
                }
                tick(&format!("scaling: {n} discs, {fr}, {bp_name}"));
                let scene = random_box(n, if friction { 0.1 } else { 0.0 }, 42 + n as u64);
                let t0 = Instant::now();
                let mut world = World::new(
                    &scene,
                    WorldConfig {
                        broad_phase: bp,
                        recompute_all,
                        ..WorldConfig::default()
                    },
                )?;
                let build_s = t0.elapsed().as_secs_f64();
                let mut counter = Counter::default();
                let limits = Limits {
                    max_events: events,
                    ..Limits::default()
                };
                let t1 = Instant::now();
                world.run(&limits, &mut counter);
                let run_s = t1.elapsed().as_secs_f64();
                let rate = counter.events as f64 / run_s.max(1e-9);
                last = Some((n, build_s + run_s));
                pts.push((n as f64, rate));
                rows.push(Row {
                    n,
                    friction,
                    broad_phase: bp_name,
                    build_s,
                    run_s,
                    events: counter.events,
                    events_per_s: rate,
                    skipped: false,
                });
            }
            series.push(Series {
                name: format!(
                    "{}, {bp_name}",
                    if friction {
                        "friction mu=0.1"
                    } else {
                        "frictionless"
                    }
                ),
                points: pts,
                style: Style::Line,
            });
        }
    }
    plot::log_log(
        &out.join("scaling.svg"),
        &Axes {
            title: &format!(
                "Events per second against discs in a box (up to {events} events per run)"
            ),
            x: "number of discs",
            y: "events per second",
            y_floor: 1.0,
        },
        &series,
    )?;
    let mut csv = Csv::new(&[
        "discs",
        "friction",
        "broad_phase",
        "build_s",
        "run_s",
        "events",
        "events_per_s",
        "skipped",
    ]);
    for r in &rows {
        csv.row(&[
            r.n.to_string(),
            r.friction.to_string(),
            r.broad_phase.to_string(),
            files::num(r.build_s),
            files::num(r.run_s),
            r.events.to_string(),
            format!("{:.0}", r.events_per_s),
            r.skipped.to_string(),
        ]);
    }
    csv.write(&out.join("scaling.csv"))?;
    Ok(rows)
}
