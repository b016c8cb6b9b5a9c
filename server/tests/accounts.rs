//! Accounts through the real server: created over HTTP, proved by the key
//! in an `Authorization: Bearer` header, revoked, listed on the
//! leaderboards; bad input gets a stable code and changes nothing; the
//! store never holds a key in plain text, and accounts survive a restart.

mod common;

use common::{http_with, Server};
use serde_json::Value;

fn json(text: &str) -> Value {
    serde_json::from_str(text).unwrap_or_else(|e| panic!("{e}: {text}"))
}

fn code(text: &str) -> String {
    json(text)["code"].as_str().unwrap_or_default().to_string()
}

async fn as_key(s: &Server, method: &str, path: &str, key: &str) -> (u16, String) {
    http_with(
        &s.addr,
        method,
        path,
        &format!("Authorization: Bearer {key}\r\n"),
        "",
    )
    .await
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_account_is_created_proved_by_its_key_revoked_and_listed() {
    let dir = tempfile::tempdir().unwrap();
    let mut s = Server::start(dir.path(), &[]);
    let (status, text) = s
        .http("POST", "/api/accounts", r#"{"name":"Furmanov","bot":true}"#)
        .await;
    assert_eq!(status, 201, "{text}");
    let made = json(&text);
    assert_eq!(made["account"]["name"], "Furmanov");
    assert_eq!(made["account"]["bot"], true);
    assert_eq!(made["account"]["rating"], 1500);
    assert_eq!(made["account"]["provisional"], true);
    let key = made["key"].as_str().unwrap().to_string();

    let (status, text) = as_key(&s, "GET", "/api/accounts/me", &key).await;
    assert_eq!(
        (status, json(&text)["name"].clone()),
        (200, "Furmanov".into())
    );
    let (status, text) = s.http("GET", "/api/accounts/furmanov", "").await;
    assert_eq!((status, json(&text)["bot"].clone()), (200, true.into()));
    let (status, text) = s.http("GET", "/api/leaderboard?bots=true", "").await;
    assert_eq!(status, 200, "{text}");
    assert_eq!(json(&text).as_array().unwrap().len(), 1);
    let (_, text) = s.http("GET", "/api/leaderboard", "").await;
    assert_eq!(json(&text), serde_json::json!([]), "no people yet");

    // A second key, then the first revoked: only the second proves it.
    let (status, text) = as_key(&s, "POST", "/api/accounts/me/keys", &key).await;
    assert_eq!(status, 201, "{text}");
    let second = json(&text)["key"].as_str().unwrap().to_string();
    let (status, _) = as_key(&s, "DELETE", "/api/accounts/me/keys/current", &key).await;
    assert_eq!(status, 204);
    let (status, text) = as_key(&s, "GET", "/api/accounts/me", &key).await;
    assert_eq!((status, code(&text)), (401, "bad-key".into()));

    // Neither key is in any file of the data folder; the account and the
    // second key outlive a restart.
    s.kill();
    let mut folders = vec![dir.path().to_path_buf()];
    let mut files = Vec::new();
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(folder).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                folders.push(path);
            } else {
                files.push(path);
            }
        }
    }
    assert!(!files.is_empty());
    for path in files {
        let bytes = std::fs::read(path).unwrap();
        let text = String::from_utf8_lossy(&bytes);
        assert!(!text.contains(&key) && !text.contains(&second));
    }
    let s = Server::start(dir.path(), &[]);
    let (status, text) = as_key(&s, "GET", "/api/accounts/me", &second).await;
    assert_eq!(
        (status, json(&text)["name"].clone()),
        (200, "Furmanov".into())
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bad_names_taken_names_and_wrong_keys_get_stable_codes_and_change_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let s = Server::start(dir.path(), &[]);
    let (status, _) = s.http("POST", "/api/accounts", r#"{"name":"Anka"}"#).await;
    assert_eq!(status, 201);
    for (body, want) in [
        (r#"{"name":"anka"}"#, (409, "name-taken")),
        (r#"{"name":"ab"}"#, (400, "bad-name")),
        (r#"{"name":"Анка"}"#, (400, "bad-name")),
        (r#"{"name":"x","admin":true}"#, (400, "bad-message")),
        (r#"{"name":"#, (400, "bad-json")),
    ] {
        let (status, text) = s.http("POST", "/api/accounts", body).await;
        assert_eq!((status, code(&text).as_str()), want, "{body}");
    }
    for key in ["", "0123456789abcdef0123456789abcdef", &"z".repeat(500)] {
        let (status, text) = as_key(&s, "GET", "/api/accounts/me", key).await;
        assert_eq!((status, code(&text)), (401, "bad-key".into()), "{key:?}");
    }
    let (status, text) = s.http("GET", "/api/accounts/me", "").await;
    assert_eq!((status, code(&text)), (401, "bad-key".into()));
    let (status, text) = s.http("GET", "/api/accounts/Petka", "").await;
    assert_eq!((status, code(&text)), (404, "no-such-account".into()));
    let (status, text) = s.http("GET", "/api/leaderboard?bots=maybe", "").await;
    assert_eq!((status, code(&text)), (400, "bad-message".into()));
    let (_, text) = s.http("GET", "/api/leaderboard", "").await;
    assert_eq!(json(&text).as_array().unwrap().len(), 1, "only Anka");
}
