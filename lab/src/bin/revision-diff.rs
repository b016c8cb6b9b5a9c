//! `revision-diff`: how one engine revision changes the outcomes of the
//! hostile scenes against another (`lab::revision_diff`), kind by kind.
//! `cargo run --release -p lab --bin revision-diff -- --old r4 --new r5`.

use clap::Parser;
use engine::Revision;
use lab::hostile::Kind;
use lab::revision_diff::compare;
use std::process::ExitCode;

/// Hostile scenes of every kind under two engine revisions: how many
/// outcomes differ, and by how much.
#[derive(Parser, Debug)]
#[command(version)]
struct Args {
    /// Scenes of each kind.
    #[arg(long, default_value_t = 1_000)]
    count: u64,
    /// First seed.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// The revision compared against (`r1`, `r2`, ...).
    #[arg(long)]
    old: Revision,
    /// The revision compared; the latest when not given.
    #[arg(long)]
    new: Option<Revision>,
}

fn main() -> ExitCode {
    let args = Args::parse();
    let new = args.new.unwrap_or(Revision::LATEST);
    println!(
        "| kind | scenes | outcomes changed | at rest under one only | largest move of a resting disc (radii) | events {:?} | events {:?} |",
        args.old, new
    );
    println!("| --- | ---: | ---: | ---: | --- | ---: | ---: |");
    for kind in Kind::ALL {
        let d = compare(kind, args.seed, args.count, args.old, new);
        let moved = d.moved.map_or("–".to_owned(), |(m, seed)| {
            format!("{m:.2e} (seed {seed})")
        });
        println!(
            "| {} | {} | {} | {} | {moved} | {} | {} |",
            kind.name(),
            d.scenes,
            d.differ,
            d.rest_changed,
            d.events.0,
            d.events.1
        );
    }
    ExitCode::SUCCESS
}
