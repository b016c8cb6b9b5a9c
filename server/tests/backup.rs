//! `server backup` taken while matches are being played, `server restore`
//! into a fresh store, and every match of the restored store replayed: the
//! backup holds a consistent prefix of each match, at least every shot
//! acknowledged before it began.

mod common;

use common::Server;
use server::store::{SqliteStore, Status, Store};
use std::collections::HashMap;
use std::path::Path;
use std::time::Duration;

/// Runs the server binary with `args`; its success, standard output and error.
async fn server_command(args: Vec<String>) -> (bool, String, String) {
    tokio::task::spawn_blocking(move || {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_server"))
            .args(&args)
            .output()
            .expect("the server binary runs");
        (
            out.status.success(),
            String::from_utf8_lossy(&out.stdout).into_owned(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    })
    .await
    .unwrap()
}

fn path(p: &Path) -> String {
    p.to_str().unwrap().to_string()
}

async fn shots(server: &Server, id: &str) -> (u32, String) {
    let (status, text) = server.http("GET", &format!("/api/matches/{id}"), "").await;
    assert_eq!(status, 200, "{text}");
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    (
        u32::try_from(v["shots"].as_u64().unwrap()).unwrap(),
        v["status"].as_str().unwrap().to_string(),
    )
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_backup_taken_mid_play_restores_into_a_fresh_store_where_every_match_replays() {
    let dir = tempfile::tempdir().unwrap();
    let mut server = Server::start(dir.path(), &[]);
    // Exhibitions play themselves, move after move, while the backup runs.
    let mut ids = Vec::new();
    for _ in 0..4 {
        let body = r#"{"first":"hard","second":"hard"}"#;
        let (status, text) = server.http("POST", "/api/exhibitions", body).await;
        assert_eq!(status, 201, "{text}");
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        ids.push(v["match_id"].as_str().unwrap().to_string());
    }
    // Some shots played in each first.
    let mut acknowledged = HashMap::new();
    for id in &ids {
        for _ in 0..600 {
            let (n, _) = shots(&server, id).await;
            if n >= 2 {
                acknowledged.insert(id.clone(), n);
                break;
            }
            tokio::time::sleep(Duration::from_millis(50)).await;
        }
        assert!(acknowledged.contains_key(id), "match {id} plays");
    }
    let file = dir.path().join("backup.sqlite3");
    let data = dir.path().join("data");
    let (ok, out, err) = server_command(vec![
        "backup".into(),
        "--to".into(),
        path(&file),
        "--data-dir".into(),
        path(&data),
    ])
    .await;
    assert!(ok, "backup failed: {err}");
    assert!(out.starts_with("backed up to"), "{out}");
    // Backing up over the file is refused, and leaves it alone.
    let size = std::fs::metadata(&file).unwrap().len();
    let again = vec![
        "backup".into(),
        "--to".into(),
        path(&file),
        "--data-dir".into(),
        path(&data),
    ];
    let (ok, _, err) = server_command(again).await;
    assert!(!ok && err.contains("already exists"), "{err}");
    assert_eq!(std::fs::metadata(&file).unwrap().len(), size);

    let fresh = dir.path().join("restored");
    let (ok, out, err) = server_command(vec![
        "restore".into(),
        "--from".into(),
        path(&file),
        "--data-dir".into(),
        path(&fresh),
    ])
    .await;
    assert!(ok, "restore failed: {err}");
    assert!(out.contains("every one replayed"), "{out}");
    // Restoring over a store is refused.
    let (ok, _, err) = server_command(vec![
        "restore".into(),
        "--from".into(),
        path(&file),
        "--data-dir".into(),
        path(&fresh),
    ])
    .await;
    assert!(!ok && err.contains("already holds a store"), "{err}");

    // The matches went on meanwhile; then the server stops.
    assert!(server.terminate(), "a clean stop");
    let restored = SqliteStore::open(&fresh, server::config::SyncMode::Full).unwrap();
    let original = SqliteStore::open(&data, server::config::SyncMode::Full).unwrap();
    let mut live_in_backup = 0;
    for id in &ids {
        let (m, record) = restored
            .load(id)
            .unwrap()
            .expect("the match is in the backup");
        let (_, played) = original.load(id).unwrap().unwrap();
        let kept = record.moves.len();
        assert!(
            kept >= acknowledged[id] as usize,
            "{id}: {kept} moves kept, {} acknowledged before the backup",
            acknowledged[id]
        );
        // A consistent prefix of what was played.
        let json = |moves: &[game::RecordedMove]| serde_json::to_string(moves).unwrap();
        assert_eq!(json(&record.moves), json(&played.moves[..kept]), "{id}");
        game::Replay::new(record).expect("the restored match replays");
        if m.status == Status::Live {
            live_in_backup += 1;
        }
    }
    assert!(live_in_backup > 0, "the backup was taken mid-play");
}
