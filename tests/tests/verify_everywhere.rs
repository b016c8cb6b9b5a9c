//! A finished match verifies the same way everywhere: natively
//! (`game::verify`), in the JavaScript package (`verify`, in Node), in the
//! Python package (`chapaev.verify`), and with the standard-library-only
//! script `bots/examples/python/verify_independent.py` (SHA-256, ChaCha20
//! and the game's arithmetic written out again, no engine). The same
//! tampered records are caught by each: a shot given gentler noise, a
//! secret other than the committed one, a secret not revealed; an outcome
//! made up is caught by the three that replay the physics (the independent
//! script checks the noise only, and says so).
//!
//! Without `node` or `python3` the binding parts fail, unless
//! `CHAPAEV_SKIP_BINDINGS=1` (then they say *skipped*).

use bots::{by_name, play_match, ArenaLimits};
use e2e::js;
use e2e::python::{repo_root, run_script, venv_python};
use game::noise::NoiseDraw;
use game::{Config, MatchRecord, NoiseKey, NoiseSecret, RecordedMove, ShotOutcome};
use std::path::{Path, PathBuf};

/// A finished standard match between two greedy bots, and tampered copies,
/// written to `dir`: `(file, what native verify says)`.
fn records(dir: &Path) -> Vec<(PathBuf, serde_json::Value)> {
    let mut a = by_name("greedy", 1).unwrap();
    let mut b = by_name("greedy", 2).unwrap();
    let report = play_match(
        Config::standard(),
        77,
        a.as_mut(),
        b.as_mut(),
        &ArenaLimits::default(),
    )
    .unwrap();
    let good = report.record;
    assert!(good.noise.as_ref().unwrap().secret.is_some(), "finished");
    fn shot(r: &mut MatchRecord, n: u32) -> &mut ShotOutcome {
        r.moves
            .iter_mut()
            .find_map(|m| match m {
                RecordedMove::Shot(s) if s.number == n => Some(s),
                _ => None,
            })
            .unwrap()
    }
    let mut softer = good.clone();
    let s = shot(&mut softer, 2);
    s.played = s.aimed;
    let mut invented = good.clone();
    let s = shot(&mut invented, 1);
    s.duration = f64::from_bits(s.duration.to_bits() ^ 1);
    let mut other_secret = good.clone();
    other_secret.noise.as_mut().unwrap().secret = Some(NoiseSecret::from_seed(78));
    let mut unrevealed = good.clone();
    unrevealed.noise.as_mut().unwrap().secret = None;
    let legacy = game::Game::new(Config::standard(), NoiseKey::SplitMix64(5))
        .unwrap()
        .record()
        .clone();
    [
        ("good", good),
        ("softer", softer),
        ("invented", invented),
        ("other-secret", other_secret),
        ("unrevealed", unrevealed),
        ("legacy", legacy),
    ]
    .into_iter()
    .map(|(name, record)| {
        let path = dir.join(format!("{name}.json"));
        std::fs::write(&path, record.to_json()).unwrap();
        let native = match game::verify(&record) {
            Ok(v) => serde_json::json!({"verified": true, "scheme": v.scheme,
                "commitment": v.commitment.to_hex(), "shots": v.shots, "draws": v.draws}),
            Err(e) => serde_json::json!({"verified": false, "code": e.code()}),
        };
        (path, native)
    })
    .collect()
}

/// Each line's verdict against native Rust's, draws compared bit for bit.
fn same_verdicts(who: &str, expected: &[(PathBuf, serde_json::Value)], out: &str) {
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), expected.len(), "{who}: one line per record");
    for ((path, native), line) in expected.iter().zip(lines) {
        let got: serde_json::Value = serde_json::from_str(line).unwrap();
        let draws = |v: &serde_json::Value| -> Option<Vec<(u64, u64)>> {
            let d: Vec<NoiseDraw> = serde_json::from_value(v.get("draws")?.clone()).ok()?;
            Some(
                d.iter()
                    .map(|d| (d.angle.to_bits(), d.speed.to_bits()))
                    .collect(),
            )
        };
        assert_eq!(
            draws(&got),
            draws(native),
            "{who}, {}: draws",
            path.display()
        );
        for field in ["verified", "code", "scheme", "commitment", "shots"] {
            assert_eq!(
                got.get(field),
                native.get(field),
                "{who}, {}: {field}",
                path.display()
            );
        }
    }
}

#[test]
fn native_verify_passes_the_finished_match_and_names_each_tampering() {
    let dir = tempfile::tempdir().unwrap();
    let codes: Vec<String> = records(dir.path())
        .iter()
        .map(|(_, v)| v.get("code").map_or("ok".into(), |c| c.to_string()))
        .collect();
    assert_eq!(
        codes,
        [
            "ok",
            "\"noise-mismatch\"",
            "\"replay-diverged\"",
            "\"commitment-mismatch\"",
            "\"secret-not-revealed\"",
            "\"uncommitted\""
        ]
    );
}

#[test]
fn the_javascript_package_verifies_with_the_bits_of_native_rust() {
    if !js::ready_or_skip("verify") {
        return;
    }
    js::build_package().unwrap_or_else(|e| panic!("{e}"));
    let dir = tempfile::tempdir().unwrap();
    let expected = records(dir.path());
    let mut args: Vec<&std::ffi::OsStr> = vec!["tests/verify.mjs".as_ref()];
    args.extend(expected.iter().map(|(p, _)| p.as_os_str()));
    let out = js::node(&args).unwrap_or_else(|e| panic!("{e}"));
    same_verdicts(
        "javascript",
        &expected,
        &String::from_utf8(out.stdout).unwrap(),
    );
}

#[test]
fn the_python_package_verifies_with_the_bits_of_native_rust() {
    let Some(python) = venv_python().unwrap_or_else(|e| panic!("{e}")) else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let expected = records(dir.path());
    let paths: Vec<&str> = expected.iter().map(|(p, _)| p.to_str().unwrap()).collect();
    let script = repo_root().join("bots/python/tests/verify.py");
    let out = run_script(&python, &script, &paths).unwrap_or_else(|e| panic!("{e}"));
    same_verdicts("python", &expected, &out);
}

#[test]
fn a_standard_library_python_script_checks_commitment_and_noise_without_the_engine() {
    let dir = tempfile::tempdir().unwrap();
    let expected = records(dir.path());
    let script = repo_root().join("bots/examples/python/verify_independent.py");
    let mut cmd = std::process::Command::new("python3");
    cmd.arg(&script);
    cmd.args(expected.iter().map(|(p, _)| p));
    let out = match cmd.output() {
        Ok(out) => out,
        Err(e) if e2e::python::skip_requested() => {
            eprintln!("skipped: python3 does not run ({e}) and CHAPAEV_SKIP_BINDINGS=1");
            return;
        }
        Err(e) => panic!("python3 {}: {e}", script.display()),
    };
    assert_eq!(out.status.code(), Some(1), "some records fail: exit 1");
    let stdout = String::from_utf8(out.stdout).unwrap();
    let verdicts: Vec<(bool, Option<u64>)> = stdout
        .lines()
        .map(|l| {
            let v: serde_json::Value = serde_json::from_str(l).unwrap();
            (v["verified"].as_bool().unwrap(), v["shots"].as_u64())
        })
        .collect();
    let shots = expected[0].1["shots"].as_u64();
    assert_eq!(
        verdicts,
        [
            (true, shots),
            (false, None),
            // Its noise is right: only a replay of the physics sees the made-up outcome.
            (true, shots),
            (false, None),
            (false, None),
            (false, None),
        ]
    );
}
