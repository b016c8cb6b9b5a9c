//! `hostile`: runs the hostile scene generator (`lab::hostile`) over many
//! seeds of every kind and reports scenes run and failures by kind.
//! `cargo run --release -p lab --bin hostile -- --count 1000000`.

use clap::Parser;
use engine::Revision;
use lab::hostile::{run_caught, Failure, Hostile, Kind, Report, MAX_EVENTS};
use std::collections::BTreeMap;
use std::io::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// Hostile scenes of every kind through the engine, with their checks.
#[derive(Parser, Debug)]
#[command(version)]
struct Args {
    /// Scenes in all, spread evenly over the kinds.
    #[arg(long, default_value_t = 13_000)]
    count: u64,
    /// First seed.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Only this kind (by its report name).
    #[arg(long)]
    kind: Option<String>,
    /// Leave out these kinds (report names, comma-separated): CI leaves
    /// out the kinds with failures still open (lab's unit test runs their
    /// first seeds against its list of known open scenes).
    #[arg(long, value_delimiter = ',')]
    except: Vec<String>,
    /// Write each failing scene as JSON into this folder (the first 20 per kind).
    #[arg(long)]
    dump: Option<PathBuf>,
    /// Print every failing scene's kind, seed and report.
    #[arg(long)]
    verbose: bool,
    /// Failures (by report name, comma-separated) that are reported but do
    /// not fail the run: `--tolerate stuck,livelock`.
    #[arg(long, value_delimiter = ',')]
    tolerate: Vec<String>,
    /// The engine revision to run: `r1` (as before the fixes of
    /// pressed contacts, far hits and collapses), `r2`, `r3`, ...; the
    /// latest (`engine::Revision::LATEST`) when not given.
    #[arg(long)]
    revision: Option<Revision>,
    /// The event cap of one run: a run that reaches it fails as a
    /// livelock (`lab::hostile::MAX_EVENTS` unless told otherwise; a larger
    /// cap tells a long run from one that never ends).
    #[arg(long, default_value_t = MAX_EVENTS)]
    max_events: u64,
    /// Threads running scenes.
    #[arg(long, default_value_t = 1)]
    jobs: u64,
}

/// Writes a line to standard output, and ends `main` where it cannot (the
/// reader went away, as `head` does) with the status a shell gives a
/// program that a closed pipe stopped (128 + SIGPIPE), instead of a panic.
macro_rules! say {
    ($($arg:tt)*) => {
        if writeln!(std::io::stdout().lock(), $($arg)*).is_err() {
            return ExitCode::from(141);
        }
    };
}

fn main() -> ExitCode {
    let args = Args::parse();
    let kinds: Vec<Kind> = Kind::ALL
        .into_iter()
        .filter(|k| args.kind.as_deref().is_none_or(|n| n == k.name()))
        .filter(|k| !args.except.iter().any(|n| n == k.name()))
        .collect();
    if let Some(bad) = args
        .except
        .iter()
        .find(|n| !Kind::ALL.iter().any(|k| k.name() == n.as_str()))
    {
        eprintln!("hostile: --except {bad:?}: no such kind");
        return ExitCode::FAILURE;
    }
    if kinds.is_empty() {
        let names: Vec<&str> = Kind::ALL.iter().map(|k| k.name()).collect();
        eprintln!(
            "hostile: --kind {:?}: no such kind ({})",
            args.kind.as_deref().unwrap_or_default(),
            names.join(", ")
        );
        return ExitCode::FAILURE;
    }
    if let Some(dir) = &args.dump {
        if let Err(e) = std::fs::create_dir_all(dir) {
            eprintln!("hostile: {}: {e}", dir.display());
            return ExitCode::FAILURE;
        }
    }
    let per_kind = args.count.div_ceil(kinds.len() as u64);
    let started = Instant::now();
    let mut total = 0u64;
    let mut failed = 0u64;
    let mut table: BTreeMap<(Kind, Failure), u64> = BTreeMap::new();
    let mut slowest = (0.0f64, Kind::PushChain, 0u64);
    let mut worst = (0.0f64, Kind::PushChain, 0u64);
    let mut gain = (0.0f64, Kind::PushChain, 0u64);
    let mut press_gain = (0.0f64, Kind::PushChain, 0u64);
    if let Some(bad) = args
        .tolerate
        .iter()
        .find(|t| !Failure::ALL.iter().any(|f| f.name() == t.as_str()))
    {
        let names: Vec<&str> = Failure::ALL.iter().map(|f| f.name()).collect();
        eprintln!(
            "hostile: --tolerate {bad:?}: no such failure ({})",
            names.join(", ")
        );
        return ExitCode::FAILURE;
    }
    let jobs = args.jobs.max(1);
    let revision = args.revision.unwrap_or(Revision::LATEST);
    let max_events = args.max_events;
    let mut instant = (0u64, Kind::PushChain, 0u64);
    for &kind in &kinds {
        let mut dumped = 0;
        // Each thread runs every `jobs`-th seed; reports are folded in seed
        // order, so the output does not depend on the threads.
        let mut reports: Vec<(u64, Report)> = std::thread::scope(|scope| {
            let handles: Vec<_> = (0..jobs)
                .map(|j| {
                    scope.spawn(move || {
                        (args.seed + j..args.seed + per_kind)
                            .step_by(jobs as usize)
                            .map(|seed| {
                                (
                                    seed,
                                    run_caught(
                                        &Hostile::generate(kind, seed),
                                        revision,
                                        max_events,
                                    ),
                                )
                            })
                            .collect::<Vec<_>>()
                    })
                })
                .collect();
            handles
                .into_iter()
                // `run_caught` catches a scene's panic; any other is ours.
                .flat_map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
                .collect()
        });
        reports.sort_by_key(|(seed, _)| *seed);
        for (seed, report) in reports {
            total += 1;
            let ms = report.elapsed.as_secs_f64() * 1e3;
            if ms > slowest.0 {
                slowest = (ms, kind, seed);
            }
            if report.worst_overlap > worst.0 {
                worst = (report.worst_overlap, kind, seed);
            }
            if report.worst_gain > gain.0 {
                gain = (report.worst_gain, kind, seed);
            }
            if report.longest_instant > instant.0 {
                instant = (report.longest_instant, kind, seed);
            }
            if report.worst_press_gain > press_gain.0 {
                press_gain = (report.worst_press_gain, kind, seed);
            }
            if report.failures.is_empty() {
                continue;
            }
            failed += 1;
            for &f in &report.failures {
                *table.entry((kind, f)).or_default() += 1;
            }
            if args.verbose {
                say!("{} seed {seed}: {report}", kind.name());
            }
            if let Some(dir) = &args.dump {
                if dumped < 20 {
                    dumped += 1;
                    let path = dir.join(format!("{}-{seed}.json", kind.name()));
                    let scene = Hostile::generate(kind, seed).scene;
                    if let Err(e) = std::fs::write(&path, scene.to_json()) {
                        eprintln!("hostile: {}: {e}", path.display());
                    }
                }
            }
        }
    }
    say!(
        "{total} scenes ({per_kind} per kind), {failed} failed, in {:.1} s",
        started.elapsed().as_secs_f64()
    );
    say!(
        "slowest {:.1} ms ({} seed {}), worst overlap {:.3e} of the contact distance ({} seed {})",
        slowest.0,
        slowest.1.name(),
        slowest.2,
        worst.0,
        worst.1.name(),
        worst.2
    );
    say!(
        "largest energy gain at one event {:.3e} of the energy ({} seed {}); \
         at a pressing hit {:.3e} ({} seed {})",
        gain.0,
        gain.1.name(),
        gain.2,
        press_gain.0,
        press_gain.1.name(),
        press_gain.2
    );
    say!(
        "longest run of events at one time {} ({} seed {})",
        instant.0,
        instant.1.name(),
        instant.2
    );
    if !table.is_empty() {
        say!("| kind | failure | scenes |\n| --- | --- | ---: |");
        for ((kind, f), n) in &table {
            say!("| {} | {} | {n} |", kind.name(), f.name());
        }
    }
    let fatal: u64 = table
        .iter()
        .filter(|((_, f), _)| !args.tolerate.iter().any(|t| t == f.name()))
        .map(|(_, n)| n)
        .sum();
    if fatal == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
