//! Hosted bots' modules through the real server, on SQLite and on
//! PostgreSQL: a bot account uploads its WebAssembly module with its key,
//! lists the versions (named by their SHA-256, with upload times) and
//! makes an earlier one active; hostile uploads (too large, not
//! WebAssembly, importing WASI, a wrong key, a person's account, a page's
//! script, another account's version) get a stable code and change
//! nothing; the versions outlive a restart, and one not active can be
//! deleted. The starter bot, built for
//! wasm32 as its author would, is accepted as it is.

mod common;

use common::modules::{account, as_key, json, put_bytes, starter, upload};
use common::Server;

fn code(text: &str) -> String {
    json(text)["code"].as_str().unwrap_or_default().to_string()
}

/// A module the hosted runtime loads (it resigns); `k` gives each one its
/// own bytes, so its own hash.
fn module(k: u32) -> Vec<u8> {
    wat::parse_str(format!(
        r#"(module
            (memory (export "memory") 1)
            (data (i32.const 0) "{{\"type\":\"resign\"}}")
            (global i32 (i32.const {k}))
            (func (export "chapaev_alloc") (param i32) (result i32) i32.const 1024)
            (func (export "chapaev_decide") (param i32 i32) (result i64) i64.const 17))"#
    ))
    .unwrap()
}

/// The account's versions as (hash, active), newest first.
async fn versions(s: &Server, key: &str) -> Vec<(String, bool)> {
    let (status, text) = as_key(s, "GET", "/api/accounts/me/modules", key, "").await;
    assert_eq!(status, 200, "{text}");
    json(&text)
        .as_array()
        .unwrap()
        .iter()
        .map(|v| {
            (
                v["hash"].as_str().unwrap().to_string(),
                v["active"].as_bool().unwrap(),
            )
        })
        .collect()
}

fn hash_of(bytes: &[u8]) -> String {
    hosted::BotModule::load(bytes, &hosted::Limits::default())
        .unwrap()
        .hash_hex()
}

/// The whole story on the server started with `extra` flags.
async fn uploads_and_versions(extra: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let mut s = Server::start(dir.path(), extra);
    let key = account(&s, "Furmanov", true).await;
    let (first, second) = (module(1), module(2));
    let (h1, h2) = (hash_of(&first), hash_of(&second));

    let (status, text) = upload(&s, &key, first.clone()).await;
    assert_eq!(status, 201, "{text}");
    let v = json(&text);
    assert_eq!(v["hash"], h1.as_str());
    assert_eq!(v["size"], first.len());
    assert_eq!(v["active"], true);
    assert!(v["uploaded_at"].as_u64().unwrap() > 1_700_000_000);
    // The same bytes again: the same version, 200.
    let (status, again) = upload(&s, &key, first.clone()).await;
    assert_eq!((status, json(&again)), (200, v.clone()));
    let (status, text) = upload(&s, &key, second.clone()).await;
    assert_eq!(status, 201, "{text}");
    assert_eq!(
        versions(&s, &key).await,
        [(h2.clone(), true), (h1.clone(), false)]
    );
    let (status, text) = as_key(
        &s,
        "PUT",
        "/api/accounts/me/modules/active",
        &key,
        &format!(r#"{{"hash":"{h1}"}}"#),
    )
    .await;
    assert_eq!(
        (status, json(&text)["hash"].clone()),
        (200, h1.as_str().into())
    );
    let settled = vec![(h2.clone(), false), (h1.clone(), true)];
    assert_eq!(versions(&s, &key).await, settled);

    // Hostile input: each refused with its code, nothing changed.
    let wasi = wat::parse_str(
        r#"(module
            (import "wasi_snapshot_preview1" "fd_write" (func (param i32 i32 i32 i32) (result i32)))
            (memory (export "memory") 1)
            (func (export "chapaev_alloc") (param i32) (result i32) i32.const 0)
            (func (export "chapaev_decide") (param i32 i32) (result i64) i64.const 0))"#,
    )
    .unwrap();
    let (status, text) = upload(&s, &key, wasi).await;
    assert_eq!((status, code(&text)), (400, "bad-module".into()));
    assert!(
        json(&text)["message"].as_str().unwrap().contains("no WASI"),
        "{text}"
    );
    let (status, text) = upload(&s, &key, b"#!/bin/sh\necho hi\n".to_vec()).await;
    assert_eq!((status, code(&text)), (400, "bad-module".into()));
    assert!(
        json(&text)["message"]
            .as_str()
            .unwrap()
            .contains("does not start with"),
        "{text}"
    );
    let (status, text) = upload(&s, &key, Vec::new()).await;
    assert_eq!((status, code(&text)), (400, "bad-module".into()));
    let mut huge = module(3);
    huge.resize((4 << 20) + 1, 0);
    let (status, text) = upload(&s, &key, huge).await;
    assert_eq!((status, code(&text)), (413, "message-too-large".into()));
    assert!(
        json(&text)["message"].as_str().unwrap().contains("4194304"),
        "{text}"
    );
    let (status, text) = upload(&s, &"0".repeat(32), module(4)).await;
    assert_eq!((status, code(&text)), (401, "bad-key".into()));
    let (status, text) = put_bytes(&s, "/api/accounts/me/module", &[], module(4)).await;
    assert_eq!((status, code(&text)), (401, "bad-key".into()));
    // A page's scripts never act as the bot.
    let auth = format!("Bearer {key}");
    let host = s.addr.clone();
    let origin = format!("http://{host}");
    let (status, text) = put_bytes(
        &s,
        "/api/accounts/me/module",
        &[("Authorization", &auth), ("Origin", &origin)],
        module(4),
    )
    .await;
    assert_eq!((status, code(&text)), (403, "bot-key-in-browser".into()));
    // A person's account hosts nothing.
    let person = account(&s, "Anka", false).await;
    let (status, text) = upload(&s, &person, module(4)).await;
    assert_eq!((status, code(&text)), (403, "not-a-bot".into()));
    // Another bot cannot make Furmanov's version its own, nor touch his.
    let other = account(&s, "Chapaev", true).await;
    let (status, text) = as_key(
        &s,
        "PUT",
        "/api/accounts/me/modules/active",
        &other,
        &format!(r#"{{"hash":"{h2}"}}"#),
    )
    .await;
    assert_eq!((status, code(&text)), (404, "no-such-version".into()));
    assert!(versions(&s, &other).await.is_empty());
    for body in [
        r#"{"hash":"abc"}"#,
        r#"{"hash":1}"#,
        "{",
        r#"{"hash":"x","more":1}"#,
    ] {
        let (status, text) = as_key(&s, "PUT", "/api/accounts/me/modules/active", &key, body).await;
        assert!(status == 400 || status == 404, "{body}: {status} {text}");
    }
    assert_eq!(versions(&s, &key).await, settled);
    // The active version cannot be deleted, nor another account's.
    let (status, text) = as_key(
        &s,
        "DELETE",
        &format!("/api/accounts/me/modules/{h1}"),
        &key,
        "",
    )
    .await;
    assert_eq!((status, code(&text)), (400, "bad-message".into()));
    let (status, text) = as_key(
        &s,
        "DELETE",
        &format!("/api/accounts/me/modules/{h2}"),
        &other,
        "",
    )
    .await;
    assert_eq!((status, code(&text)), (404, "no-such-version".into()));
    assert_eq!(versions(&s, &key).await, settled);

    // The versions outlive a restart; a version not active can be deleted.
    s.kill();
    let s = Server::start(dir.path(), extra);
    assert_eq!(versions(&s, &key).await, settled);
    let (status, text) = as_key(
        &s,
        "DELETE",
        &format!("/api/accounts/me/modules/{h2}"),
        &key,
        "",
    )
    .await;
    assert_eq!(status, 204, "{text}");
    assert_eq!(versions(&s, &key).await, [(h1, true)]);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn on_sqlite_a_bot_uploads_lists_and_activates_versions_and_hostile_uploads_change_nothing() {
    uploads_and_versions(&[]).await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn on_postgresql_a_bot_uploads_lists_and_activates_versions_and_hostile_uploads_change_nothing(
) {
    let Some(url) = tokio::task::block_in_place(|| {
        local_services::local_postgres::shared_database("modules_on_postgresql")
    }) else {
        return;
    };
    uploads_and_versions(&[&format!("--database-url={url}")]).await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_starter_bot_built_for_wasm32_is_accepted_as_the_active_version() {
    let bytes = tokio::task::block_in_place(starter);
    let dir = tempfile::tempdir().unwrap();
    let s = Server::start(dir.path(), &[]);
    let key = account(&s, "Starter", true).await;
    let (status, text) = upload(&s, &key, bytes.clone()).await;
    assert_eq!(status, 201, "{text}");
    assert_eq!(json(&text)["size"], bytes.len());
    assert_eq!(versions(&s, &key).await, [(hash_of(&bytes), true)]);
}
