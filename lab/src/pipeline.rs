//! The whole run: the three charts and the failure table, written into one
//! folder, with a progress bar. [`Options::quick`] shrinks every part (few
//! scenes, short runs) so CI can check the pipeline end to end in seconds;
//! the full run is what `docs/charts/` holds. `summary.md` collects the key
//! figures of the run in one page.

use crate::catalogue::{self, Query};
use crate::failures::{self, Settings};
use crate::files;
use crate::outcome::Outcome;
use crate::scenes::{self, Case};
use crate::timestep_chart::{self, Steps};
use crate::{reference, scaling_chart, solvers_chart, LabError};
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// What to run and where.
#[derive(Clone, Debug)]
pub struct Options {
    pub out: PathBuf,
    pub quick: bool,
    pub progress: bool,
}

/// What the run measured, for the summary.
pub struct Report {
    pub secs: f64,
    pub solvers: Vec<solvers_chart::Summary>,
    pub timestep: Vec<timestep_chart::Row>,
    pub scaling: Vec<scaling_chart::Row>,
    pub failures: failures::Table,
}

fn contact_set(quick: bool) -> Result<Vec<Query>, LabError> {
    let per = if quick { 60 } else { 1500 };
    let mut v = Vec::new();
    let mut big_box = scenes::box100()?;
    big_box.name = "box-300".into();
    big_box.scene = scenes::random_box(300, 0.2, 3);
    for case in [
        scenes::hard_break()?,
        scenes::box100()?,
        big_box,
        scenes::grazing(),
    ] {
        v.extend(catalogue::contact_quartics(&case, per));
    }
    Ok(v)
}

fn timestep_cases(quick: bool) -> Result<Vec<Case>, LabError> {
    Ok(if quick {
        vec![scenes::break_shot()?, scenes::galperin(3)]
    } else {
        let mut v = vec![scenes::break_shot()?, scenes::hard_break()?];
        v.extend((3..=6).map(scenes::galperin));
        v.push(scenes::box100()?);
        v
    })
}

/// Runs everything into `opts.out`.
pub fn run_pipeline(opts: &Options) -> Result<Report, LabError> {
    let start = Instant::now();
    std::fs::create_dir_all(&opts.out).map_err(|source| LabError::Io {
        path: opts.out.display().to_string(),
        source,
    })?;
    let bar = if opts.progress {
        let b = ProgressBar::new_spinner();
        let style = ProgressStyle::with_template("{spinner} [{elapsed_precise}] {msg}")
            .map_err(|e| LabError::Invalid(e.to_string()))?;
        b.set_style(style);
        b.enable_steady_tick(Duration::from_millis(120));
        b
    } else {
        ProgressBar::hidden()
    };
    let mut tick = |msg: &str| bar.set_message(msg.to_string());
    let q = opts.quick;

    tick("solvers: building the query sets");
    let sets = vec![
        ("hard", catalogue::hard_quartics()),
        ("contact", contact_set(q)?),
    ];
    let solvers = solvers_chart::run(&sets, if q { 0.002 } else { 0.3 }, &opts.out, &mut tick)?;

    let mut cases: Vec<(Case, Outcome)> = Vec::new();
    for case in timestep_cases(q)? {
        tick(&format!(
            "a priori vs stepping: 320-bit reference of {}",
            case.name
        ));
        let r = reference::run(&case);
        cases.push((case, r));
    }
    let steps = if q {
        Steps {
            stepper: vec![1e-3, 1e-4],
            rapier: vec![1e-3],
        }
    } else {
        Steps {
            stepper: vec![1e-3, 1e-4, 1e-5, 1e-6],
            rapier: vec![1.0 / 60.0, 1e-3, 1e-4],
        }
    };
    let timestep = timestep_chart::run(
        &cases,
        &steps,
        if q { 0.0 } else { 0.2 },
        &opts.out,
        &mut tick,
    )?;

    let sizes: Vec<usize> = if q {
        vec![10, 100]
    } else {
        vec![10, 30, 100, 300, 1000, 3000, 10_000, 30_000, 100_000]
    };
    let scaling = scaling_chart::run(
        &sizes,
        if q { 1_000 } else { 20_000 },
        if q { 0.5 } else { 5.0 },
        &opts.out,
        &mut tick,
    )?;

    let settings = if q {
        Settings {
            stepper_dt: 1e-4,
            rapier_dt: 1e-3,
            galperin_large: 4,
            engine_max_n: 4,
            stepper_dts: vec![1e-4],
            rapier_dts: vec![1e-3],
            stepping_max_n: 3,
            stepper_cap: 1_000_000,
            rapier_cap: 10_000,
        }
    } else {
        Settings {
            stepper_dt: 1e-5,
            rapier_dt: 1e-4,
            galperin_large: 7,
            engine_max_n: 8,
            stepper_dts: vec![1e-4, 1e-5, 1e-6, 1e-7],
            rapier_dts: vec![1e-3, 1e-4, 1e-5],
            stepping_max_n: 5,
            stepper_cap: 20_000_000,
            rapier_cap: 1_000_000,
        }
    };
    let failures = failures::run(&settings, &opts.out, &mut tick)?;
    bar.finish_and_clear();
    let report = Report {
        secs: start.elapsed().as_secs_f64(),
        solvers,
        timestep,
        scaling,
        failures,
    };
    files::write_text(&opts.out.join("summary.md"), &summary(&report, q))?;
    Ok(report)
}

/// The key figures as markdown.
pub fn summary(r: &Report, quick: bool) -> String {
    let mut s = format!(
        "# Key figures ({} run, {:.0} s)\n\n## Root solvers (time per first-root query, relative error; missed/spurious roots)\n\n\
         | set | solver | ns/query | median err | worst err | missed | spurious |\n|---|---|---|---|---|---|---|\n",
        if quick { "quick" } else { "full" },
        r.secs
    );
    for x in &r.solvers {
        s += &format!(
            "| {} | {} | {:.0} | {:.1e} | {:.1e} | {} | {} |\n",
            x.set, x.solver, x.ns_per_query, x.median_err, x.max_err, x.missed, x.spurious
        );
    }
    s += "\n## A priori against time-stepping (final-state error / scene size)\n\n\
          | case | method | dt | wall s | error | collisions (ref) | max overlap |\n|---|---|---|---|---|---|---|\n";
    for x in &r.timestep {
        s += &format!(
            "| {} | {} | {} | {:.2e} | {:.1e} | {} ({}) | {:.1e} |\n",
            x.case,
            x.method,
            x.dt.map(|d| format!("{d:.0e}")).unwrap_or_default(),
            x.secs,
            x.error,
            x.collisions,
            x.reference_collisions,
            x.max_overlap
        );
    }
    s += "\n## Scaling (events per second)\n\n| discs | friction | broad phase | events/s | build s |\n|---|---|---|---|---|\n";
    for x in &r.scaling {
        let rate = if x.skipped {
            "skipped".to_string()
        } else {
            format!("{:.2e}", x.events_per_s)
        };
        s += &format!(
            "| {} | {} | {} | {} | {:.2e} |\n",
            x.n, x.friction, x.broad_phase, rate, x.build_s
        );
    }
    s += "\n## Failures\n\n";
    s += &r.failures.markdown();
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The CI check: the quick pipeline writes every file with sane contents.
    #[test]
    fn quick_pipeline_writes_every_chart_csv_and_table() {
        let dir = tempfile::tempdir().unwrap();
        let opts = Options {
            out: dir.path().to_path_buf(),
            quick: true,
            progress: false,
        };
        let report = run_pipeline(&opts).unwrap();
        for f in [
            "solvers_hard.svg",
            "solvers_contact.svg",
            "timestep_break.svg",
            "timestep_galperin-3.svg",
            "scaling.svg",
        ] {
            let svg = std::fs::read_to_string(dir.path().join(f)).unwrap();
            assert!(svg.starts_with("<svg") && svg.len() > 1000, "{f}");
        }
        let csv = std::fs::read_to_string(dir.path().join("solvers.csv")).unwrap();
        assert!(csv.lines().count() == 1 + 2 * 5, "{csv}");
        assert!(csv.contains("engine production") && csv.contains("kurbo"));
        let ts = std::fs::read_to_string(dir.path().join("timestep.csv")).unwrap();
        assert!(ts.contains("galperin-3,engine production,,"));
        let md = std::fs::read_to_string(dir.path().join("failures.md")).unwrap();
        assert!(md.contains("grazing contact") && md.contains("Largest Galperin n"));
        for f in [
            "scaling.csv",
            "failures.csv",
            "solvers_cases.csv",
            "summary.md",
        ] {
            assert!(dir.path().join(f).exists(), "{f}");
        }
        // The engine counts Galperin exactly and matches the reference.
        let g = report
            .timestep
            .iter()
            .find(|r| r.case == "galperin-3" && r.method == "engine production")
            .unwrap();
        assert_eq!((g.collisions, g.reference_collisions), (314, 314));
        assert!(g.error < 1e-12, "{}", g.error);
    }
}
