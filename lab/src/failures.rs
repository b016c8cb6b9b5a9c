//! Where methods fail: every hard case run by every method, each outcome
//! classified against the reference (or, for Galperin's billiard, against
//! the digits of pi), written as `failures.md` and `failures.csv`; and the
//! largest Galperin `n` each method counts exactly.
//!
//! The outcome of a run is the first that applies of: `NaN`; `gave up at
//! cap` (event or step cap reached); `tunnelled` (a disc ended on the other
//! side of a solid line than in the reference); `stuck` (discs overlap by
//! more than 1% of their contact distance at the end); `wrong count`
//! (collision count differs); `overlap` (more than 1% overlap seen during
//! the run); `wrong state` (a final position off by more than 1% of the
//! smallest radius); otherwise `correct`.

use crate::apriori;
use crate::files::{self, Csv};
use crate::outcome::{compare, overlap_of, Outcome};
use crate::scenes::{self, Case};
use crate::{rapier_peer, reference, stepper, LabError};
use engine::roots::Method;
use engine::world::BroadPhase;
use std::path::Path;

/// A method of the table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method2 {
    Engine(Method),
    Stepper(f64),
    Rapier { dt: f64, ccd: bool },
}

impl Method2 {
    pub fn name(self) -> String {
        match self {
            Method2::Engine(m) => format!("engine {}", m.name()),
            Method2::Stepper(dt) => format!("fixed-step dt={dt:e}"),
            Method2::Rapier { dt, ccd: false } => format!("rapier dt={dt:e}"),
            Method2::Rapier { dt, ccd: true } => format!("rapier+CCD dt={dt:e}"),
        }
    }

    /// Computes `case` with this method (steppers: at most `cap` steps).
    pub fn run(self, case: &Case, cap: u64) -> Result<Outcome, LabError> {
        Ok(match self {
            Method2::Engine(m) => apriori::run(case, m, BroadPhase::Auto, true)?,
            Method2::Stepper(dt) => stepper::run(case, dt, cap),
            Method2::Rapier { dt, ccd } => rapier_peer::run(case, dt, ccd, cap),
        })
    }
}

/// The classified outcome of one run.
pub fn classify(case: &Case, run: &Outcome, reference: Option<&Outcome>) -> String {
    if run.has_nan() {
        return "NaN".into();
    }
    if run.capped {
        return "gave up at cap".into();
    }
    let live: Vec<_> = run
        .bodies
        .iter()
        .filter(|b| !b.removed)
        .filter_map(|b| {
            let s = case.scene.bodies.iter().find(|s| s.id.0 == b.id)?;
            Some((b.pos, s.radius))
        })
        .collect();
    let end_overlap = overlap_of(&live);
    let expected = reference.map(|r| r.collisions).or(case.expected_collisions);
    let cmp = reference.map(|r| compare(case, run, r));
    if cmp.is_some_and(|c| c.tunnelled) {
        return "tunnelled".into();
    }
    if end_overlap > 0.01 {
        return format!("stuck ({:.0}% overlap at end)", end_overlap * 100.0);
    }
    if let Some(x) = expected {
        if x != run.collisions {
            return format!("wrong count ({} vs {x})", run.collisions);
        }
    }
    if run.max_overlap > 0.01 {
        return format!("overlap ({:.0}%)", run.max_overlap * 100.0);
    }
    if let Some(c) = cmp {
        let tol = 0.01 * case.min_radius() / case.scale;
        if c.error > tol {
            return format!("wrong state (err {:.1e})", c.error);
        }
        return format!("correct (err {:.0e})", c.error);
    }
    "correct".into()
}

/// The largest Galperin n counted exactly, and the dt it took (steppers).
pub type GalperinBest = (u32, Option<f64>);

/// Case rows of the table and their methods' outcomes.
pub struct Table {
    pub methods: Vec<String>,
    pub rows: Vec<(String, Vec<String>)>,
    /// Per method: the largest Galperin n counted exactly, and at which dt.
    pub galperin: Vec<(String, Option<GalperinBest>)>,
}

impl Table {
    /// The table as markdown.
    pub fn markdown(&self) -> String {
        let mut s = String::from("| case | ");
        s += &self.methods.join(" | ");
        s += " |\n|---|";
        s += &"---|".repeat(self.methods.len());
        s.push('\n');
        for (case, cells) in &self.rows {
            s += &format!("| {case} | {} |\n", cells.join(" | "));
        }
        s += "\n**Largest Galperin n counted exactly** (n digits of pi; tried up to the n shown in the run's settings):\n\n| method | largest n |\n|---|---|\n";
        for (m, g) in &self.galperin {
            let cell = match g {
                Some((n, Some(dt))) => format!("{n} (at dt={dt:e})"),
                Some((n, None)) => n.to_string(),
                None => "none (fails n=3)".into(),
            };
            s += &format!("| {m} | {cell} |\n");
        }
        s
    }
}

/// Settings of the failure run.
pub struct Settings {
    pub stepper_dt: f64,
    pub rapier_dt: f64,
    pub galperin_large: u32,
    pub engine_max_n: u32,
    pub stepper_dts: Vec<f64>,
    pub rapier_dts: Vec<f64>,
    pub stepping_max_n: u32,
    /// The most steps one fixed-step run may take.
    pub stepper_cap: u64,
    /// The most steps one rapier run may take.
    pub rapier_cap: u64,
}

/// The hard cases.
pub fn hard_cases() -> Result<Vec<Case>, LabError> {
    Ok(vec![
        scenes::grazing(),
        scenes::simultaneous(),
        scenes::cradle(),
        scenes::resting_contact(),
        scenes::fast_tiny(),
        scenes::translated(1e7)?,
        scenes::scaled(1e-6)?,
        scenes::fast_motion(1e3)?,
        scenes::fast_motion(1e-3)?,
    ])
}

/// Runs the table; writes `failures.md` and `failures.csv` into `out`.
pub fn run(settings: &Settings, out: &Path, tick: &mut dyn FnMut(&str)) -> Result<Table, LabError> {
    let mut methods: Vec<Method2> = Method::ALL.iter().map(|&m| Method2::Engine(m)).collect();
    methods.push(Method2::Stepper(settings.stepper_dt));
    methods.push(Method2::Rapier {
        dt: settings.rapier_dt,
        ccd: false,
    });
    methods.push(Method2::Rapier {
        dt: settings.rapier_dt,
        ccd: true,
    });
    let mut csv = Csv::new(&[
        "case",
        "method",
        "outcome",
        "collisions",
        "reference_collisions",
        "wall_s",
    ]);
    let mut rows = Vec::new();
    let mut cases = hard_cases()?;
    cases.push(scenes::galperin(settings.galperin_large));
    for case in &cases {
        tick(&format!("failures: reference for {}", case.name));
        let reference = case
            .expected_collisions
            .is_none()
            .then(|| reference::run(case));
        let mut cells = Vec::new();
        for m in &methods {
            tick(&format!("failures: {} / {}", case.name, m.name()));
            let cap = match m {
                Method2::Rapier { .. } => settings.rapier_cap,
                _ => settings.stepper_cap,
            };
            let o = m.run(case, cap)?;
            let verdict = classify(case, &o, reference.as_ref());
            csv.row(&[
                case.name.clone(),
                m.name(),
                verdict.clone(),
                o.collisions.to_string(),
                reference
                    .as_ref()
                    .map(|r| r.collisions)
                    .or(case.expected_collisions)
                    .map(|c| c.to_string())
                    .unwrap_or_default(),
                files::num(o.secs),
            ]);
            cells.push(verdict);
        }
        let name = if case.expected_collisions.is_some() {
            format!(
                "Galperin n={} ({} collisions)",
                settings.galperin_large,
                scenes::pi_digits(settings.galperin_large)
            )
        } else {
            case.name.clone()
        };
        rows.push((name, cells));
    }
    csv.write(&out.join("failures.csv"))?;
    let mut galperin = Vec::new();
    for m in Method::ALL {
        let mut best = None;
        for n in 3..=settings.engine_max_n {
            tick(&format!(
                "failures: largest Galperin n, engine {} n={n}",
                m.name()
            ));
            let o = apriori::run(&scenes::galperin(n), m, BroadPhase::Auto, false)?;
            if o.collisions != scenes::pi_digits(n) {
                break;
            }
            best = Some((n, None));
        }
        galperin.push((format!("engine {}", m.name()), best));
    }
    let stepping: [(&str, &Vec<f64>, Option<bool>); 3] = [
        ("fixed-step", &settings.stepper_dts, None),
        ("rapier", &settings.rapier_dts, Some(false)),
        ("rapier+CCD", &settings.rapier_dts, Some(true)),
    ];
    for (name, dts, ccd) in stepping {
        let mut best = None;
        'n: for n in 3..=settings.stepping_max_n {
            for &dt in dts {
                tick(&format!(
                    "failures: largest Galperin n, {name} n={n} dt={dt:e}"
                ));
                let case = scenes::galperin(n);
                let o = match ccd {
                    None => stepper::run(&case, dt, settings.stepper_cap),
                    Some(ccd) => rapier_peer::run(&case, dt, ccd, settings.rapier_cap),
                };
                if o.collisions == scenes::pi_digits(n) && !o.capped {
                    best = Some((n, Some(dt)));
                    continue 'n;
                }
            }
            break;
        }
        let dts_s: Vec<String> = dts.iter().map(|d| format!("{d:e}")).collect();
        galperin.push((format!("{name} (dt tried: {})", dts_s.join(", ")), best));
    }
    let table = Table {
        methods: methods.iter().map(|m| m.name()).collect(),
        rows,
        galperin,
    };
    let md = format!(
        "# Where methods fail\n\nGenerated by `cargo run --release -p lab -- --out docs/charts`; \
         every outcome is against the 320-bit reference model (Galperin: against the digits of pi).\n\
         Outcomes, first that applies: NaN; gave up at cap; tunnelled; stuck (>1% overlap at the end); \
         wrong count (collisions vs reference); overlap (>1% during the run); wrong state \
         (final position off by more than 1% of the smallest radius); correct (err = worst final \
         position error / scene size).\n\n{}",
        table.markdown()
    );
    files::write_text(&out.join("failures.md"), &md)?;
    Ok(table)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn engine_gets_the_grazing_case_right_and_a_coarse_stepper_tunnels() {
        let case = scenes::grazing();
        let r = reference::run(&case);
        assert_eq!(r.collisions, 1);
        let e = Method2::Engine(Method::Production).run(&case, 0).unwrap();
        assert!(classify(&case, &e, Some(&r)).starts_with("correct"));
        let tiny = scenes::fast_tiny();
        let rt = reference::run(&tiny);
        let s = Method2::Stepper(1e-3).run(&tiny, u64::MAX).unwrap();
        assert_eq!(classify(&tiny, &s, Some(&rt)), "tunnelled");
    }

    #[test]
    fn markdown_has_one_row_per_case_and_a_galperin_table() {
        let t = Table {
            methods: vec!["a".into(), "b".into()],
            rows: vec![("c".into(), vec!["correct".into(), "NaN".into()])],
            galperin: vec![("a".into(), Some((5, None))), ("b".into(), None)],
        };
        let md = t.markdown();
        assert!(md.contains("| c | correct | NaN |"));
        assert!(md.contains("| a | 5 |") && md.contains("none (fails n=3)"));
    }
}
