//! A bot author without a Rust toolchain: `scripts/build-sdk` builds the
//! Python wheel and the npm tarball, the real server (`e2e-server`) hands
//! them out at `/sdk/`, and each installs from the server's address into a
//! fresh place (a new virtual environment; a new npm project) and
//! simulates a shot with the bits of native Rust.
//!
//! Without `python3` or `npm` the test fails with a clear message, unless
//! `CHAPAEV_SKIP_BINDINGS=1` says to skip it (it says so out loud).

use e2e::process::{run_to_end, Server};
use e2e::python::{repo_root, skip_requested};
use e2e::{api, artifacts_dir, same_bits};
use game::simulate::SimulateRequest;
use std::path::Path;
use std::process::{Command, Stdio};

/// Whether `program --version` runs.
fn found(program: &str) -> bool {
    Command::new(program)
        .arg("--version")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

/// The request every package simulates: White's piece 3 straight up the
/// opening board at 1.5 m/s, as aimed.
fn request() -> SimulateRequest {
    let view = game::Game::new(game::Config::standard(), 1)
        .expect("the standard rules")
        .view();
    serde_json::from_value(serde_json::json!({
        "config": view.config,
        "board": view.board,
        "piece": 3,
        "velocity": [0.0, 1.5],
    }))
    .expect("a simulate request")
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_server_hands_out_packages_that_install_without_rust_and_simulate_with_its_bits() {
    if !found("python3") || !found("npm") {
        assert!(
            skip_requested(),
            "the SDK test needs python3 and npm (or CHAPAEV_SKIP_BINDINGS=1 to skip it)"
        );
        eprintln!("skipped: python3 or npm is not installed (CHAPAEV_SKIP_BINDINGS=1)");
        return;
    }
    let scratch = tempfile::tempdir().unwrap();
    let sdk = scratch.path().join("sdk");
    let mut build = Command::new("bash");
    build
        .arg(repo_root().join("scripts/build-sdk"))
        .arg(&sdk)
        .current_dir(repo_root())
        .stdin(Stdio::null());
    run_to_end("scripts/build-sdk", &mut build).unwrap_or_else(|e| panic!("{e}"));

    let log = artifacts_dir().unwrap().join("sdk-server.log");
    let server = Server::start_with(
        Path::new(env!("CARGO_BIN_EXE_e2e-server")),
        &scratch.path().join("data"),
        &log,
        "127.0.0.1:0",
        &["--sdk-dir", sdk.to_str().unwrap()],
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let (status, index) = api::get_json(&server.addr, "/sdk/").await.unwrap();
    assert_eq!(status, 200, "{index}");
    assert_eq!(index["physics_version"], game::PHYSICS_VERSION);
    let url_of = |kind: &str| {
        index["files"]
            .as_array()
            .unwrap()
            .iter()
            .find(|f| f["kind"] == kind)
            .and_then(|f| f["url"].as_str())
            .unwrap_or_else(|| panic!("no {kind} in {index}"))
            .to_string()
    };

    // What native Rust answers; each package's answer is read back into
    // the game's types and written again, so only bits can differ.
    let request = request();
    let native = same_bits::native_line(&request);
    let request_json = serde_json::to_string(&request).unwrap();

    // Python: a fresh venv, `pip install http://HOST/sdk/<wheel>`.
    let venv = scratch.path().join("venv");
    run_to_end(
        "python3 -m venv",
        Command::new("python3").arg("-m").arg("venv").arg(&venv),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let python = venv.join("bin/python");
    run_to_end(
        "pip install from /sdk/",
        Command::new(&python)
            .args([
                "-m",
                "pip",
                "install",
                "--quiet",
                "--disable-pip-version-check",
            ])
            .arg(url_of("python-wheel")),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let out = run_to_end(
        "python simulates",
        Command::new(&python).args([
            "-c",
            "import chapaev, json, sys; print(json.dumps(chapaev.simulate(json.loads(sys.argv[1]))))",
            &request_json,
        ]),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let from_python = same_bits::normalise(&String::from_utf8_lossy(&out.stdout)).unwrap();
    assert_eq!(
        from_python, native,
        "the wheel's simulation differs from native"
    );

    // npm: a fresh project, `npm install http://HOST/sdk/chapaev-….tgz`.
    let project = scratch.path().join("node-bot");
    std::fs::create_dir_all(&project).unwrap();
    std::fs::write(project.join("package.json"), r#"{"private": true}"#).unwrap();
    run_to_end(
        "npm install from /sdk/",
        Command::new("npm")
            .args(["install", "--no-audit", "--no-fund", "--loglevel=error"])
            .arg(url_of("npm-tarball"))
            .current_dir(&project),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let out = run_to_end(
        "node simulates",
        Command::new("node")
            .args([
                "--input-type=module",
                "-e",
                "import { simulate } from 'chapaev'; console.log(JSON.stringify(simulate(JSON.parse(process.argv[1]))));",
                &request_json,
            ])
            .current_dir(&project),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let from_node = same_bits::normalise(&String::from_utf8_lossy(&out.stdout)).unwrap();
    assert_eq!(
        from_node, native,
        "the npm package's simulation differs from native"
    );
    server.kill();
}
