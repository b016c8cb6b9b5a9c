//! The crash test binary (`src/bin/crashtest.rs`) at a small size: it kills
//! and restarts the real server during live matches, reports a passing
//! verdict with exit status 0, and leaves no server process behind, also
//! when it cannot start one.

use std::path::Path;
use std::process::Command;

/// Processes (other than this one) whose command line names `path`.
fn processes_naming(path: &Path) -> Vec<String> {
    let needle = path.display().to_string();
    let Ok(entries) = std::fs::read_dir("/proc") else {
        return Vec::new();
    };
    entries
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().parse::<u32>().is_ok())
        .filter_map(|e| std::fs::read(e.path().join("cmdline")).ok())
        .map(|raw| String::from_utf8_lossy(&raw).replace('\0', " "))
        .filter(|cmd| cmd.contains(&needle))
        .collect()
}

#[test]
fn a_small_crash_test_passes_kills_twice_and_leaves_no_server_behind() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("data");
    let out = Command::new(env!("CARGO_BIN_EXE_crashtest"))
        .args(["--matches", "6", "--kills", "2", "--play-seconds", "1"])
        .args([
            "--think-ms",
            "50",
            "--server-bin",
            env!("CARGO_BIN_EXE_server"),
        ])
        .arg("--data-dir")
        .arg(&data)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stdout}\n{stderr}");
    assert!(stdout.contains("VERDICT: PASS"), "{stdout}");
    assert_eq!(stdout.matches("SIGKILL at").count(), 2, "{stdout}");
    // Each incarnation wrote its log; the store is there.
    for n in 0..3 {
        assert!(data.join(format!("server-{n}.log")).exists(), "{stdout}");
    }
    assert!(data.join("chapaev.sqlite3").exists());
    assert!(
        processes_naming(&data).is_empty(),
        "{:?}",
        processes_naming(&data)
    );
}

#[test]
fn on_postgresql_a_small_crash_test_passes_and_every_acknowledged_shot_is_in_the_database() {
    let Some(url) = local_services::local_postgres::shared_database(
        "on_postgresql_a_small_crash_test_passes_and_every_acknowledged_shot_is_in_the_database",
    ) else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("data");
    let out = Command::new(env!("CARGO_BIN_EXE_crashtest"))
        .args(["--matches", "6", "--kills", "2", "--play-seconds", "1"])
        .args([
            "--think-ms",
            "50",
            "--server-bin",
            env!("CARGO_BIN_EXE_server"),
        ])
        .arg(format!("--server-arg=--database-url={url}"))
        .arg("--data-dir")
        .arg(&data)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stdout}\n{stderr}");
    assert!(stdout.contains("VERDICT: PASS"), "{stdout}");
    assert_eq!(stdout.matches("SIGKILL at").count(), 2, "{stdout}");
    // Everything went to PostgreSQL: no SQLite file was made.
    assert!(!data.join("chapaev.sqlite3").exists());
    let mut db = postgres::Client::connect(&url, postgres::NoTls).unwrap();
    let matches: i64 = db
        .query_one("SELECT count(*) FROM matches WHERE status <> 'open'", &[])
        .unwrap()
        .get(0);
    assert_eq!(matches, 6, "{stdout}");
    assert!(processes_naming(&data).is_empty());
}

#[test]
fn a_server_that_cannot_start_ends_the_run_with_failure() {
    let dir = tempfile::tempdir().unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_crashtest"))
        .args(["--matches", "2", "--server-bin"])
        .arg(dir.path().join("no-such-server"))
        .arg("--data-dir")
        .arg(dir.path().join("data"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("cannot start"), "{stderr}");
}
