//! The Python binding gives the very bits of native Rust: 10,000 random
//! simulation requests (`game::simulate::random_request`, a fixed seed)
//! run through `chapaev.simulate` by `bots/python/tests/same_bits.py` and
//! natively through `SimulateRequest::run`, every result compared as its
//! JSON text (serde_json writes the shortest text that reads back to the
//! same bits, so equal text is equal bits); and hostile requests are
//! refused with the server's codes.
//!
//! The binding is built into its venv by `bots/python/build.sh` when its
//! sources changed (minutes the first time). Without `python3` the test
//! fails, unless `CHAPAEV_SKIP_BINDINGS=1`.

use e2e::python::{repo_root, run_script, venv_python};
use e2e::same_bits;
use game::noise::SplitMix64;
use game::simulate::{random_request, SimulateRequest, Simulation};
use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

const REQUESTS: usize = 10_000;
const SEED: u64 = 0xC4A9_AE75;

fn python() -> Option<PathBuf> {
    venv_python().unwrap_or_else(|e| panic!("{e}"))
}

/// `lines` written as a JSON-lines file in `dir`, run through same_bits.py;
/// its output lines.
fn through_python(
    python: &std::path::Path,
    dir: &std::path::Path,
    lines: &[String],
) -> Vec<String> {
    let input = dir.join("requests.jsonl");
    let mut f = std::fs::File::create(&input).unwrap();
    for l in lines {
        writeln!(f, "{l}").unwrap();
    }
    drop(f);
    let script = repo_root().join("bots/python/tests/same_bits.py");
    let out =
        run_script(python, &script, &[input.to_str().unwrap()]).unwrap_or_else(|e| panic!("{e}"));
    out.lines().map(str::to_string).collect()
}

#[test]
fn python_simulates_ten_thousand_random_requests_with_the_bits_of_native_rust() {
    let Some(python) = python() else { return };
    let mut rng = SplitMix64::new(SEED);
    let requests: Vec<SimulateRequest> = (0..REQUESTS).map(|_| random_request(&mut rng)).collect();
    let lines: Vec<String> = requests
        .iter()
        .map(|r| serde_json::to_string(r).unwrap())
        .collect();

    let scratch = tempfile::tempdir().unwrap();
    let start = Instant::now();
    let python_lines = through_python(&python, scratch.path(), &lines);
    let python_s = start.elapsed().as_secs_f64();
    eprintln!("{REQUESTS} requests: python (start, JSON and all) {python_s:.2} s");
    let same_bits::Tally { knocked, .. } =
        same_bits::check("python", SEED, &requests, &python_lines)
            .unwrap_or_else(|e| panic!("{e}"));
    assert!(
        knocked > REQUESTS / 5,
        "the shots knock pieces off: {knocked}"
    );
}

#[test]
fn python_refuses_hostile_requests_with_the_servers_codes() {
    let Some(python) = python() else { return };
    let board = r#"[{"id": 4, "pos": [0.18, 0.02]}, {"id": 12, "pos": [0.18, 0.30]}]"#;
    let ok = |rest: &str| format!(r#"{{"board": {board}, "piece": 4, {rest}}}"#);
    let cases: Vec<(String, &str)> = vec![
        (ok(r#""velocity": [NaN, 1.0]"#), "not-finite"),
        (ok(r#""velocity": [0.0, 1e9]"#), "too-fast"),
        (ok(r#""velocity": [0.0, 0.0]"#), "zero-speed"),
        (ok(r#""velocity": [0.0, "fast"]"#), "bad-message"),
        (ok(r#""velocity": [0.0, 1.0, 2.0]"#), "bad-message"),
        (ok(r#""velocity": [0.0, 1.0], "colour": "red""#), "bad-message"),
        (ok(r#""velocity": [0.0, 1.0], "config": {"mu": -1.0}"#), "bad-config"),
        (ok(r#""velocity": [0.0, 1.0], "config": {"mu": NaN}"#), "bad-config"),
        (
            ok(r#""velocity": [0.0, 1.0], "config": {"variants": {"noise": {"angle_sigma": 0.1, "speed_sigma": 0.1}}}, "noise": {"angle": Infinity, "speed": 0.0}"#),
            "not-finite",
        ),
        (r#"{"piece": 4, "velocity": [0.0, 1.0]}"#.into(), "bad-message"),
        (r#"[1, 2, 3]"#.into(), "bad-message"),
        (
            r#"{"board": [{"id": 16, "pos": [0.1, 0.1]}], "piece": 4, "velocity": [0.0, 1.0]}"#.into(),
            "bad-message",
        ),
        (
            r#"{"board": [{"id": 4, "pos": [0.1, 0.1]}, {"id": 4, "pos": [0.2, 0.2]}], "piece": 4, "velocity": [0.0, 1.0]}"#.into(),
            "bad-board",
        ),
        (
            r#"{"board": [{"id": 4, "pos": [0.1, 0.1]}, {"id": 5, "pos": [0.11, 0.1]}], "piece": 4, "velocity": [0.0, 1.0]}"#.into(),
            "bad-board",
        ),
        (
            r#"{"board": [{"id": 4, "pos": [NaN, 0.1]}], "piece": 4, "velocity": [0.0, 1.0]}"#.into(),
            "bad-board",
        ),
        (
            r#"{"board": [{"id": 4, "pos": [0.1, 0.1]}], "piece": 12, "velocity": [0.0, 1.0]}"#.into(),
            "piece-off-board",
        ),
    ];
    let scratch = tempfile::tempdir().unwrap();
    let lines: Vec<String> = cases.iter().map(|(l, _)| l.clone()).collect();
    let out = through_python(&python, scratch.path(), &lines);
    assert_eq!(out.len(), cases.len());
    for ((request, code), got) in cases.iter().zip(&out) {
        let got: serde_json::Value = serde_json::from_str(got).unwrap();
        assert_eq!(got["error"], *code, "{request} gave {got}");
    }
    // And the very same request, well formed, plays.
    let fine = through_python(&python, scratch.path(), &[ok(r#""velocity": [0.0, 2.0]"#)]);
    let sim: Simulation = serde_json::from_str(&fine[0]).unwrap();
    assert_eq!(
        sim.knocked_off
            .iter()
            .map(|p| u8::from(*p))
            .collect::<Vec<_>>(),
        vec![12]
    );
}
