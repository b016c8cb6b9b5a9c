//! `lab`: regenerates the speed-against-accuracy charts, CSV data and the
//! failure table. `cargo run --release -p lab -- --out docs/charts`.

use clap::Parser;
use std::path::PathBuf;
use std::process::ExitCode;

/// Speed against accuracy: charts of the engine against a 320-bit
/// reference, fixed-step integration and rapier.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// Folder to write CSV, SVG and markdown into (created if missing).
    #[arg(long, default_value = "docs/charts")]
    out: PathBuf,
    /// A small, fast run that only checks the pipeline works.
    #[arg(long)]
    quick: bool,
    /// No progress bar.
    #[arg(long)]
    no_progress: bool,
}

fn main() -> ExitCode {
    let args = Args::parse();
    let opts = lab::Options {
        out: args.out,
        quick: args.quick,
        progress: !args.no_progress,
    };
    match lab::run_pipeline(&opts) {
        Ok(report) => {
            println!(
                "wrote {} in {:.0} s (key figures: {})",
                opts.out.display(),
                report.secs,
                opts.out.join("summary.md").display()
            );
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("lab: {e}");
            ExitCode::FAILURE
        }
    }
}
