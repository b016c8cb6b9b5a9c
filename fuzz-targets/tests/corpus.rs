//! Every input kept for a fuzz target — its seeds in `fuzz/corpus/<target>/`
//! and the crash inputs in `fuzz/artifacts/<target>/` — runs through the
//! target's function here, as the fuzzer runs it, so a bug once found
//! stays fixed without the fuzzer.

use std::panic;
use std::path::{Path, PathBuf};

fn fuzz_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz")
}

/// The files kept for `target`, seeds first, in name order.
fn kept(target: &str) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for kind in ["corpus", "artifacts"] {
        let dir = fuzz_dir().join(kind).join(target);
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        let mut these: Vec<PathBuf> = entries
            .map(|e| e.expect("a readable folder entry").path())
            .filter(|p| p.is_file())
            .collect();
        these.sort();
        files.extend(these);
    }
    files
}

/// Runs every kept input of `target`; fails naming each one that panics.
fn replay_kept(target: &str) {
    let run = fuzz_targets::TARGETS
        .iter()
        .find(|(name, _)| *name == target)
        .map(|(_, run)| *run)
        .expect("a known target");
    let files = kept(target);
    assert!(
        files.len() >= 3,
        "{target} keeps only {} inputs",
        files.len()
    );
    let failed: Vec<String> = files
        .iter()
        .filter(|path| {
            let data = std::fs::read(path).expect("a readable kept input");
            panic::catch_unwind(|| run(&data)).is_err()
        })
        .map(|path| path.display().to_string())
        .collect();
    assert!(failed.is_empty(), "{target} fails on {failed:#?}");
}

#[test]
fn every_kept_protocol_session_input_runs_clean() {
    replay_kept("protocol_session");
}

#[test]
fn every_kept_scene_json_input_runs_clean() {
    replay_kept("scene_json");
}

#[test]
fn every_kept_record_replay_input_runs_clean() {
    replay_kept("record_replay");
}

#[test]
fn every_target_has_a_cargo_fuzz_entry_point() {
    for (target, _) in fuzz_targets::TARGETS {
        let main = fuzz_dir().join("fuzz_targets").join(format!("{target}.rs"));
        let text = std::fs::read_to_string(&main).unwrap_or_default();
        assert!(
            text.contains(&format!("fuzz_targets::{target}(")),
            "{} calls fuzz_targets::{target}",
            main.display()
        );
    }
}
