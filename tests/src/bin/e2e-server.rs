//! `e2e-server`: the match server, built inside this package so that its
//! tests can start the real thing as a process (`CARGO_BIN_EXE_e2e-server`
//! exists only for a package's own binaries). The same `main` as
//! `server`'s, [`server::app::main`], web client embedded.

fn main() -> std::process::ExitCode {
    server::app::main("e2e-server")
}
