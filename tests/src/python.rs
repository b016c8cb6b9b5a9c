//! The Python binding (`bots/python`) from the tests: its virtual
//! environment built and installed once per test binary by
//! `bots/python/build.sh` (idempotent: well under a second when already
//! installed at the current sources), and scripts run with its python.
//!
//! Without `python3` the tests fail with a clear message, unless
//! `CHAPAEV_SKIP_BINDINGS=1` says to skip them.

use crate::process::run_to_end;
use crate::{E2eError, Result};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::OnceLock;
use std::time::Instant;

/// The repository root.
pub fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default()
}

/// Whether `CHAPAEV_SKIP_BINDINGS=1` asks to skip the binding tests.
pub fn skip_requested() -> bool {
    std::env::var("CHAPAEV_SKIP_BINDINGS").is_ok_and(|v| v == "1")
}

/// The venv's python with `chapaev` installed at the current sources
/// (built by `build.sh` the first time it is asked for in this process);
/// `None` when there is no `python3` and the tests are to be skipped.
pub fn venv_python() -> Result<Option<PathBuf>> {
    static BUILT: OnceLock<std::result::Result<Option<PathBuf>, String>> = OnceLock::new();
    BUILT
        .get_or_init(|| build().map_err(|e| e.to_string()))
        .clone()
        .map_err(E2eError::Setup)
}

fn build() -> Result<Option<PathBuf>> {
    let python = std::env::var("PYTHON").unwrap_or_else(|_| "python3".into());
    let found = Command::new(&python)
        .arg("--version")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    if !found {
        if skip_requested() {
            eprintln!("python: {python} not found; skipped (CHAPAEV_SKIP_BINDINGS=1)");
            return Ok(None);
        }
        return Err(E2eError::Setup(format!(
            "{python} not found: the Python binding tests need Python 3.9 or later with pip \
             (or set CHAPAEV_SKIP_BINDINGS=1 to skip them)"
        )));
    }
    let script = repo_root().join("bots/python/build.sh");
    let start = Instant::now();
    let mut cmd = Command::new("bash");
    cmd.arg(&script).env("PYTHON", &python);
    // The binding builds in a target folder of its own (build.sh's
    // default), never in the one this test was built in.
    cmd.env_remove("CARGO_TARGET_DIR");
    cmd.stderr(Stdio::inherit());
    let out = run_to_end(&script.display().to_string(), &mut cmd)
        .map_err(|e| E2eError::Setup(format!("{e}; its output is above")))?;
    let stdout = String::from_utf8_lossy(&out.stdout);
    let venv_python = stdout
        .lines()
        .last()
        .map(|l| PathBuf::from(l.trim()))
        .ok_or_else(|| E2eError::Setup(format!("{} printed no python", script.display())))?;
    eprintln!(
        "python: {} ready in {:.1} s",
        venv_python.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(Some(venv_python))
}

/// `python script args...` run to the end; its stdout (stderr passes through).
pub fn run_script(python: &Path, script: &Path, args: &[&str]) -> Result<String> {
    let what = format!("{} {}", script.display(), args.join(" "));
    let mut cmd = Command::new(python);
    cmd.arg(script).args(args).stderr(Stdio::inherit());
    let out = run_to_end(&what, &mut cmd)?;
    String::from_utf8(out.stdout)
        .map_err(|e| E2eError::Check(format!("{}: stdout is not UTF-8: {e}", script.display())))
}
