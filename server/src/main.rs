//! `server`: runs the Chapaev online match server (see `--help`).

fn main() -> std::process::ExitCode {
    server::app::main("server")
}
