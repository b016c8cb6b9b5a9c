//! `e2e-server`: the match server, built inside this package so that its
//! tests can start the real thing as a process (`CARGO_BIN_EXE_e2e-server`
//! exists only for a package's own binaries). Same code as `server`'s
//! `main`: the library's flags and `app::run`, web client embedded.

use clap::Parser;

fn main() -> std::process::ExitCode {
    let config = server::config::Config::parse();
    match server::app::run(config) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("e2e-server: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}
