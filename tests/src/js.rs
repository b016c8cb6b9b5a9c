//! The JavaScript binding (`bots/js`, the `chapaev` npm package) from the
//! tests: building the package once with `bots/js/build.sh`, finding
//! `node`, running a script and reading its output.
//!
//! Without `node` the tests fail with a clear message unless
//! `CHAPAEV_SKIP_BINDINGS=1` says to skip them.

use crate::process::run_to_end;
use crate::{E2eError, Result};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::sync::{Mutex, OnceLock};
use std::time::Instant;

/// The variable that skips the binding tests where their tools are missing.
pub const SKIP_VAR: &str = "CHAPAEV_SKIP_BINDINGS";

/// The workspace root.
pub fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default()
}

/// `bots/js`.
pub fn package_dir() -> PathBuf {
    workspace().join("bots").join("js")
}

/// Whether the binding tests should be skipped (`CHAPAEV_SKIP_BINDINGS=1`).
pub fn skipped() -> bool {
    std::env::var(SKIP_VAR).is_ok_and(|v| v == "1")
}

/// `node --version`, or why there is no usable `node`.
pub fn node_version() -> Result<String> {
    let out = Command::new("node")
        .arg("--version")
        .output()
        .map_err(|e| {
            E2eError::Setup(format!(
                "`node` is not found ({e}): install Node.js 18 or newer, \
                 or set {SKIP_VAR}=1 to skip the JavaScript binding tests"
            ))
        })?;
    Ok(String::from_utf8_lossy(&out.stdout).trim().to_string())
}

/// Whether a test should run: `false` (and a note) when skipped on
/// purpose; a panic with what to do when `node` is missing.
pub fn ready_or_skip(test: &str) -> bool {
    if skipped() {
        eprintln!("{test}: skipped ({SKIP_VAR}=1)");
        return false;
    }
    if let Err(e) = node_version() {
        panic!("{e}");
    }
    true
}

/// Builds the package with `bots/js/build.sh` (fast when up to date),
/// once per test process; every caller gets the same outcome.
pub fn build_package() -> Result<()> {
    static BUILT: OnceLock<Mutex<Option<std::result::Result<(), String>>>> = OnceLock::new();
    let cell = BUILT.get_or_init(|| Mutex::new(None));
    let mut guard = cell.lock().unwrap_or_else(|p| p.into_inner());
    if guard.is_none() {
        let start = Instant::now();
        let script = package_dir().join("build.sh");
        let mut cmd = Command::new("bash");
        cmd.arg(&script)
            .current_dir(workspace())
            .stdin(Stdio::null());
        let outcome = match run_to_end(&format!("`{}`", script.display()), &mut cmd) {
            Ok(_) => {
                eprintln!("bots/js/build.sh: {:.1} s", start.elapsed().as_secs_f64());
                Ok(())
            }
            Err(e) => Err(e.to_string()),
        };
        *guard = Some(outcome);
    }
    match guard.as_ref() {
        Some(Ok(())) => Ok(()),
        Some(Err(e)) => Err(E2eError::Setup(e.clone())),
        None => Err(E2eError::Setup("the package build did not run".into())),
    }
}

/// Runs `node` with `args` in `bots/js`, its stdout and stderr captured; an
/// error unless it exits 0.
pub fn node(args: &[&std::ffi::OsStr]) -> Result<Output> {
    let mut cmd = Command::new("node");
    cmd.args(args)
        .current_dir(package_dir())
        .stdin(Stdio::null());
    run_to_end(&format!("node {args:?}"), &mut cmd)
}

/// The last `n` bytes of `s` (at a character boundary).
pub fn tail(s: &str, n: usize) -> &str {
    let mut start = s.len().saturating_sub(n);
    while !s.is_char_boundary(start) {
        start += 1;
    }
    &s[start..]
}

/// `npm install` in `dir` (the example bot), once per test process and only
/// when its `node_modules` lacks `ws` or `chapaev`; npm's registry must be
/// reachable the first time.
pub fn npm_install(dir: &Path) -> Result<()> {
    static LOCK: Mutex<()> = Mutex::new(());
    let _one_at_a_time = LOCK.lock().unwrap_or_else(|p| p.into_inner());
    let modules = dir.join("node_modules");
    if modules.join("ws").join("package.json").exists()
        && modules.join("chapaev").join("package.json").exists()
    {
        return Ok(());
    }
    let start = Instant::now();
    let out = Command::new("npm")
        .args(["install", "--no-audit", "--no-fund", "--loglevel=error"])
        .current_dir(dir)
        .stdin(Stdio::null())
        .output()
        .map_err(|e| {
            E2eError::Setup(format!(
                "`npm` is not found ({e}): install Node.js with npm, or set {SKIP_VAR}=1"
            ))
        })?;
    if !out.status.success() {
        return Err(E2eError::Setup(format!(
            "`npm install` in {} failed ({}):\n{}",
            dir.display(),
            out.status,
            tail(&String::from_utf8_lossy(&out.stderr), 4000)
        )));
    }
    eprintln!(
        "npm install in {}: {:.1} s",
        dir.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}
