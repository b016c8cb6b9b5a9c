//! `hostile`: runs the hostile scene generator (`lab::hostile`) over many
//! seeds of every kind and reports scenes run and failures by kind.
//! `cargo run --release -p lab --bin hostile -- --count 1000000`.

use clap::Parser;
use lab::hostile::{run_caught, Failure, Hostile, Kind};
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// Hostile scenes of every kind through the engine, with their checks.
#[derive(Parser, Debug)]
#[command(version, about)]
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
    /// Write each failing scene as JSON into this folder (the first 20 per kind).
    #[arg(long)]
    dump: Option<PathBuf>,
    /// Print every failing scene's kind, seed and report.
    #[arg(long)]
    verbose: bool,
}

fn main() -> ExitCode {
    let args = Args::parse();
    let kinds: Vec<Kind> = Kind::ALL
        .into_iter()
        .filter(|k| args.kind.as_deref().is_none_or(|n| n == k.name()))
        .collect();
    if kinds.is_empty() {
        eprintln!("hostile: no kind named {:?}", args.kind);
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
    for &kind in &kinds {
        let mut dumped = 0;
        for seed in args.seed..args.seed + per_kind {
            let h = Hostile::generate(kind, seed);
            let report = run_caught(&h);
            total += 1;
            let ms = report.elapsed.as_secs_f64() * 1e3;
            if ms > slowest.0 {
                slowest = (ms, kind, seed);
            }
            if report.worst_overlap > worst.0 {
                worst = (report.worst_overlap, kind, seed);
            }
            if report.failures.is_empty() {
                continue;
            }
            failed += 1;
            for &f in &report.failures {
                *table.entry((kind, f)).or_default() += 1;
            }
            if args.verbose {
                println!("{} seed {seed}: {report}", kind.name());
            }
            if let Some(dir) = &args.dump {
                if dumped < 20 {
                    dumped += 1;
                    let path = dir.join(format!("{}-{seed}.json", kind.name()));
                    if let Err(e) = std::fs::write(&path, h.scene.to_json()) {
                        eprintln!("hostile: {}: {e}", path.display());
                    }
                }
            }
        }
    }
    println!(
        "{total} scenes ({per_kind} per kind), {failed} failed, in {:.1} s",
        started.elapsed().as_secs_f64()
    );
    println!(
        "slowest {:.1} ms ({} seed {}), worst overlap {:.3e} of the contact distance ({} seed {})",
        slowest.0,
        slowest.1.name(),
        slowest.2,
        worst.0,
        worst.1.name(),
        worst.2
    );
    if !table.is_empty() {
        println!("| kind | failure | scenes |\n| --- | --- | ---: |");
        for ((kind, f), n) in &table {
            println!("| {} | {} | {n} |", kind.name(), f.name());
        }
    }
    if failed == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
