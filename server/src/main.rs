//! `server`: runs the Chapaev online match server (see `--help`).

use clap::Parser;

fn main() -> std::process::ExitCode {
    let config = server::config::Config::parse();
    match server::app::run(config) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("server: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}
