//! # e2e — Chapaev online end to end
//!
//! Scenarios that cross crates: the real server process (built here as
//! `e2e-server`, web client embedded by `server/build.rs`) on a free port,
//! Debian's `chromedriver` driving headless Chromium with software WebGL,
//! and the game played through the page the way a person plays it — mouse
//! events on the canvas — with the app's test hooks (`window.chapaev_ready`,
//! `window.chapaev_state`) telling where its buttons and pieces are.
//!
//! Modules: [`process`] (child processes that die with the test),
//! [`browser`] (finding Chromium, the WebDriver session, pointer input),
//! [`picture`] (decoding screenshots, telling a drawn scene from a blank
//! one), [`layout`] (the rules every screen's controls keep), [`api`]
//! (reading the server's HTTP API), [`js`] and [`python`] (the bindings'
//! tools) and [`same_bits`] (their answers compared with native Rust's).
//!
//! Screenshots and logs go to [`artifacts_dir`]; without Chromium the test
//! fails unless `CHAPAEV_SKIP_BROWSER=1` says to skip it.

pub mod api;
pub mod browser;
pub mod js;
pub mod layout;
pub mod picture;
pub mod process;
pub mod python;
pub mod same_bits;

use std::path::PathBuf;

/// Something a scenario needed did not happen.
#[derive(Debug, thiserror::Error)]
pub enum E2eError {
    #[error("{0}")]
    Setup(String),
    #[error("timed out after {seconds} s waiting for {what}; last seen: {last}")]
    Timeout {
        what: String,
        seconds: u64,
        last: String,
    },
    #[error("WebDriver: {0}")]
    WebDriver(#[from] fantoccini::error::CmdError),
    #[error("WebDriver session: {0}")]
    Session(#[from] fantoccini::error::NewSessionError),
    #[error("{what}: {source}")]
    Io {
        what: String,
        source: std::io::Error,
    },
    #[error("{0}")]
    Check(String),
}

pub type Result<T> = std::result::Result<T, E2eError>;

/// Where screenshots and logs go: `$CHAPAEV_E2E_ARTIFACTS`, else
/// `e2e-artifacts` in the cargo target folder (never in git). Created.
pub fn artifacts_dir() -> Result<PathBuf> {
    let dir = match std::env::var_os("CHAPAEV_E2E_ARTIFACTS") {
        Some(d) if !d.is_empty() => PathBuf::from(d),
        _ => {
            let workspace = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
                .parent()
                .map(PathBuf::from)
                .unwrap_or_default();
            let target = match std::env::var_os("CARGO_TARGET_DIR") {
                Some(t) if !t.is_empty() => workspace.join(t),
                _ => workspace.join("target"),
            };
            target.join("e2e-artifacts")
        }
    };
    std::fs::create_dir_all(&dir).map_err(|source| E2eError::Io {
        what: format!("creating {}", dir.display()),
        source,
    })?;
    Ok(dir)
}
