//! Support for the tests of hosted bots: bot accounts, uploading a module
//! with its key, and the starter bot built for wasm32 as its author would.

use super::{http_with, Server};
use serde_json::Value;
use std::path::Path;
use std::process::Command;

/// `text` as JSON (a test fails on anything else, showing the text).
pub fn json(text: &str) -> Value {
    serde_json::from_str(text).unwrap_or_else(|e| panic!("{e}: {text}"))
}

/// A request with the account key `key`; the status and body.
pub async fn as_key(s: &Server, method: &str, path: &str, key: &str, body: &str) -> (u16, String) {
    http_with(
        &s.addr,
        method,
        path,
        &format!("Authorization: Bearer {key}\r\n"),
        body,
    )
    .await
}

/// Creates the account `name` (a bot account if `bot`); its key.
pub async fn account(s: &Server, name: &str, bot: bool) -> String {
    let (status, text) = s
        .http(
            "POST",
            "/api/accounts",
            &format!(r#"{{"name":"{name}","bot":{bot}}}"#),
        )
        .await;
    assert_eq!(status, 201, "{text}");
    json(&text)["key"].as_str().unwrap().to_string()
}

/// `PUT`s `bytes` as the body, with extra headers; the status and body.
pub async fn put_bytes(
    s: &Server,
    path: &str,
    headers: &[(&str, &str)],
    bytes: Vec<u8>,
) -> (u16, String) {
    let url = format!("http://{}{path}", s.addr);
    let headers: Vec<(String, String)> = headers
        .iter()
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect();
    tokio::task::spawn_blocking(move || {
        let mut req = ureq::put(&url).set("Content-Type", "application/wasm");
        for (k, v) in &headers {
            req = req.set(k, v);
        }
        let answer = match req.send_bytes(&bytes) {
            Ok(a) => a,
            Err(ureq::Error::Status(_, a)) => a,
            Err(e) => panic!("no answer to PUT {url}: {e}"),
        };
        (answer.status(), answer.into_string().unwrap())
    })
    .await
    .unwrap()
}

/// Uploads `bytes` as the module of the account whose key is `key`; the
/// status and body.
pub async fn upload(s: &Server, key: &str, bytes: Vec<u8>) -> (u16, String) {
    let auth = format!("Bearer {key}");
    put_bytes(
        s,
        "/api/accounts/me/module",
        &[("Authorization", &auth)],
        bytes,
    )
    .await
}

/// The starter bot (`bots/wasm-starter`) built for wasm32 in release, as
/// its author would, into this workspace's target folder.
pub fn starter() -> Vec<u8> {
    let target = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .parent()
        .expect("the temporary folder is inside the target folder")
        .to_path_buf();
    let status = Command::new(env!("CARGO"))
        .args(["build", "-p", "chapaev-starter-bot", "--release"])
        .args(["--target", "wasm32-unknown-unknown", "--target-dir"])
        .arg(&target)
        .current_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join(".."))
        .status()
        .expect("cargo runs");
    assert!(
        status.success(),
        "building the starter bot failed (it needs `rustup target add wasm32-unknown-unknown`)"
    );
    std::fs::read(target.join("wasm32-unknown-unknown/release/chapaev_starter_bot.wasm"))
        .expect("the starter's wasm was built")
}
