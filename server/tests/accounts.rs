//! Accounts through the real server: created over HTTP, proved by the key
//! in an `Authorization: Bearer` header, revoked, listed on the
//! leaderboards; bad input gets a stable code and changes nothing; the
//! store never holds a key in plain text, and accounts survive a restart.

mod common;

use common::{http_with, Client, Server};
use game::protocol::ClientMessage;
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
    let bots: Vec<String> = json(&text)
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["name"].as_str().unwrap().to_string())
        .collect();
    assert!(bots.contains(&"Furmanov".to_string()), "{bots:?}");
    assert_eq!(bots.len(), 5, "Furmanov and the four computer levels");
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
        (r#"{"name":"computer-hard"}"#, (400, "reserved-name")),
        (r#"{"name":"B0T"}"#, (400, "reserved-name")),
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

async fn account(s: &Server, name: &str, bot: bool) -> String {
    let body = format!(r#"{{"name":"{name}","bot":{bot}}}"#);
    let (status, text) = s.http("POST", "/api/accounts", &body).await;
    assert_eq!(status, 201, "{text}");
    json(&text)["key"].as_str().unwrap().to_string()
}

async fn with_key(s: &Server, path: &str, key: &str, extra: &str, body: &str) -> (u16, String) {
    http_with(
        &s.addr,
        "POST",
        path,
        &format!("Authorization: Bearer {key}\r\n{extra}"),
        body,
    )
    .await
}

fn profile_of(text: &str) -> (i64, u64) {
    let p = json(text);
    (p["rating"].as_i64().unwrap(), p["games"].as_u64().unwrap())
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_rated_match_between_two_accounts_moves_both_ratings_once_and_keeps_a_history() {
    let dir = tempfile::tempdir().unwrap();
    let mut s = Server::start(dir.path(), &[]);
    let anka = account(&s, "Anka", false).await;
    let petka = account(&s, "Petka", false).await;
    let furmanov = account(&s, "Furmanov", true).await;

    // Refused, changing nothing: rated without an account, rated under
    // other rules, joining without an account, as the same account, or
    // with a bot's key from a web page.
    let (status, text) = s.http("POST", "/api/matches", r#"{"rated":true}"#).await;
    assert_eq!((status, code(&text)), (401, "bad-key".into()));
    let casual = r#"{"rated":true,"rules":"casual"}"#;
    let (status, text) = with_key(&s, "/api/matches", &anka, "", casual).await;
    assert_eq!((status, code(&text)), (400, "bad-config".into()));
    let (status, text) = with_key(
        &s,
        "/api/matches",
        &anka,
        "",
        r#"{"rated":true,"name":"X"}"#,
    )
    .await;
    assert_eq!(status, 201, "{text}");
    let id = json(&text)["match_id"].as_str().unwrap().to_string();
    let first = json(&text)["token"].as_str().unwrap().to_string();
    let join = format!("/api/matches/{id}/join");
    let (status, text) = s.http("POST", &join, "{}").await;
    assert_eq!((status, code(&text)), (401, "bad-key".into()));
    let (status, text) = with_key(&s, &join, &anka, "", "{}").await;
    assert_eq!((status, code(&text)), (409, "same-account".into()));
    let page = "Sec-Fetch-Site: same-origin\r\n";
    let (status, text) = with_key(&s, &join, &furmanov, page, "{}").await;
    assert_eq!((status, code(&text)), (403, "bot-key-in-browser".into()));
    let (status, text) = s.http("GET", &format!("/api/matches/{id}"), "").await;
    assert_eq!(
        (status, json(&text)["status"].clone()),
        (200, "open".into()),
        "{text}"
    );

    let (status, text) = with_key(&s, &join, &petka, "", r#"{"name":"Y"}"#).await;
    assert_eq!(status, 200, "{text}");
    let second = json(&text)["token"].as_str().unwrap().to_string();
    let (_, text) = s.http("GET", &format!("/api/matches/{id}"), "").await;
    let summary = json(&text);
    assert_eq!(
        (summary["first"].clone(), summary["second"].clone()),
        ("Anka".into(), "Petka".into())
    );
    assert_eq!(summary["rated"], true);
    assert_eq!(
        summary["first_rating"],
        serde_json::json!({"rating": 1500, "provisional": true})
    );

    // Anka resigns: the match is over, and by then (the last move is
    // stored before it is announced) both ratings have moved.
    let mut a = Client::connect(&s.addr, &id, Some(&first)).await;
    let mut b = Client::connect(&s.addr, &id, Some(&second)).await;
    a.send(&ClientMessage::Resign).await;
    b.next_of("match-over").await;
    let (_, text) = s.http("GET", "/api/accounts/anka", "").await;
    let (anka_rating, games) = profile_of(&text);
    assert_eq!(games, 1);
    let (_, text) = s.http("GET", "/api/accounts/petka", "").await;
    let (petka_rating, _) = profile_of(&text);
    assert!(anka_rating < 1500 && petka_rating > 1500);
    assert!(
        (anka_rating + petka_rating - 3000).abs() <= 1,
        "{anka_rating} {petka_rating}"
    );
    let (status, text) = s.http("GET", "/api/accounts/Petka/history", "").await;
    assert_eq!(status, 200, "{text}");
    let history = json(&text);
    assert_eq!(history.as_array().unwrap().len(), 1);
    assert_eq!(
        (
            history[0]["match_id"].as_str(),
            history[0]["rating"].as_i64()
        ),
        (Some(id.as_str()), Some(petka_rating))
    );
    let (_, text) = s
        .http("GET", "/api/accounts/anka/matches?limit=5", "")
        .await;
    assert_eq!(json(&text)[0]["match_id"].as_str(), Some(id.as_str()));
    let (status, text) = s.http("GET", "/api/accounts/nobody/history", "").await;
    assert_eq!((status, code(&text)), (404, "no-such-account".into()));

    // Killed and started again: rated once, still.
    s.kill();
    let s = Server::start(dir.path(), &[]);
    let (_, text) = s.http("GET", "/api/accounts/anka", "").await;
    assert_eq!(profile_of(&text), (anka_rating, 1));
    let (_, text) = s.http("GET", "/api/accounts/anka/history", "").await;
    assert_eq!(json(&text).as_array().unwrap().len(), 1);

    // Against the computer, rated: the level plays as its account.
    let body = r#"{"rated":true,"opponent":"bot","bot_level":"easy"}"#;
    let (status, text) = with_key(&s, "/api/matches", &anka, "", body).await;
    assert_eq!(status, 201, "{text}");
    let id = json(&text)["match_id"].as_str().unwrap().to_string();
    let (_, text) = s.http("GET", &format!("/api/matches/{id}"), "").await;
    assert_eq!(json(&text)["second_rating"]["rating"], 1500, "{text}");
    let (_, text) = s
        .http("GET", "/api/accounts/computer-easy/matches", "")
        .await;
    assert_eq!(json(&text)[0]["match_id"].as_str(), Some(id.as_str()));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_person_signs_in_with_an_optional_password_for_a_new_key() {
    let dir = tempfile::tempdir().unwrap();
    let s = Server::start(dir.path(), &[]);
    let key = account(&s, "Anka", false).await;
    let set = |password: &str| format!(r#"{{"password":"{password}"}}"#);
    let put = |body: String| {
        let (addr, key) = (s.addr.clone(), key.clone());
        async move {
            http_with(
                &addr,
                "PUT",
                "/api/accounts/me/password",
                &format!("Authorization: Bearer {key}\r\n"),
                &body,
            )
            .await
        }
    };
    let (status, text) = put(set("short")).await;
    assert_eq!((status, code(&text)), (401, "bad-password".into()));
    let (status, _) = put(set("machine-gun cart")).await;
    assert_eq!(status, 204);
    let sign_in =
        |name: &str, password: &str| format!(r#"{{"name":"{name}","password":"{password}"}}"#);
    let (status, text) = s
        .http(
            "POST",
            "/api/accounts/sign-in",
            &sign_in("anka", "machine-gun car"),
        )
        .await;
    assert_eq!((status, code(&text)), (401, "bad-password".into()));
    let (status, text) = s
        .http(
            "POST",
            "/api/accounts/sign-in",
            &sign_in("anka", "machine-gun cart"),
        )
        .await;
    assert_eq!(status, 201, "{text}");
    let new_key = json(&text)["key"].as_str().unwrap().to_string();
    assert_ne!(new_key, key);
    let (status, text) = as_key(&s, "GET", "/api/accounts/me", &new_key).await;
    assert_eq!((status, json(&text)["name"].clone()), (200, "Anka".into()));
}
