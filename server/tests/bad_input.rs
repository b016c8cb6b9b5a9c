//! Bad input never hurts a match: malformed JSON, unknown messages,
//! illegal shots, wrong tokens, oversized frames and floods are answered
//! with an `error` of a stable code, the connection survives where that
//! makes sense, and the match and the store are unchanged. Limits on
//! matches and connections hold.

mod common;

use common::{shot, view, Client, Server};
use game::protocol::ClientMessage;
use std::time::Duration;

#[tokio::test]
async fn malformed_json_unknown_messages_and_illegal_shots_get_stable_codes_and_change_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &[]);
    let (id, white_token, black_token) = server.two_player_match("").await;
    let mut white = server.ws(&id, Some(&white_token)).await;
    let mut black = server.ws(&id, Some(&black_token)).await;
    let before = view(white.next().await);
    view(black.next().await);

    white.send_text("{not json").await;
    assert_eq!(white.next_error().await, "bad-json");
    white.send_text(r#"{"type":"teleport"}"#).await;
    assert_eq!(white.next_error().await, "bad-message");
    white
        .send_text(r#"{"type":"shot","piece":99,"velocity":[0,1]}"#)
        .await;
    assert_eq!(white.next_error().await, "bad-message");
    // Hello opens a connection, and only opens it.
    white
        .send_text(r#"{"type":"hello","protocol":1,"name":"x"}"#)
        .await;
    assert_eq!(white.next_error().await, "bad-message");
    white.send(&shot(12, 0.0, -1.0)).await;
    assert_eq!(white.next_error().await, "not-your-piece");
    white.send(&shot(4, 0.0, 2.5)).await;
    assert_eq!(white.next_error().await, "too-fast");
    white.send(&shot(4, 0.0, 0.0)).await;
    assert_eq!(white.next_error().await, "zero-speed");
    white.send_text(r#"{"type":"create-match"}"#).await;
    assert_eq!(white.next_error().await, "bad-message");
    black.send(&shot(12, 0.0, -1.0)).await;
    assert_eq!(black.next_error().await, "not-your-turn");
    black.send(&ClientMessage::PieDecision { swap: true }).await;
    assert_eq!(black.next_error().await, "no-pie-decision");
    black.send(&ClientMessage::AcceptRematch).await;
    assert_eq!(black.next_error().await, "no-rematch-offer");
    black
        .send(&ClientMessage::Chat {
            text: "x".repeat(501),
        })
        .await;
    assert_eq!(black.next_error().await, "chat-too-long");
    let mut watcher = server.ws(&id, None).await;
    view(watcher.next().await);
    watcher.send(&shot(4, 0.0, 2.0)).await;
    assert_eq!(watcher.next_error().await, "not-in-match");

    // Nothing changed, and the connection still plays.
    let mut fresh = server.ws(&id, None).await;
    assert_eq!(view(fresh.next().await), before);
    white.send(&shot(4, 0.0, 2.0)).await;
    white.next_of("shot-played").await;
    let mut fresh = server.ws(&id, None).await;
    assert_eq!(view(fresh.next().await).shots, 1);
}

#[tokio::test]
async fn a_wrong_token_or_match_is_refused_with_a_stable_code() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &[]);
    let (id, white_token, _) = server.two_player_match("").await;
    let mut thief = server.ws(&id, Some(&"0".repeat(32))).await;
    assert_eq!(thief.next_error().await, "bad-token");
    assert!(thief.closes().await);
    let (other, _) = server.create("{}").await;
    // A real token, but of another match.
    let mut wrong = server.ws(&other, Some(&white_token)).await;
    assert_eq!(wrong.next_error().await, "bad-token");
    let mut lost = server.ws("feedfacefeedface", None).await;
    assert_eq!(lost.next_error().await, "no-such-match");
    let mut fresh = server.ws(&id, None).await;
    assert_eq!(view(fresh.next().await).shots, 0);
}

#[tokio::test]
async fn the_token_travels_in_the_hello_never_in_the_url_and_is_never_stored() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &[]);
    let (id, white_token, black_token) = server.two_player_match("").await;
    // The seat's answer names a WebSocket path without the secret.
    let (_, text) = server.http("GET", &format!("/api/matches/{id}"), "").await;
    assert!(!text.contains(&white_token), "{text}");
    // A token in the URL is refused before the upgrade, with the way to do it.
    let url = format!("ws://{}/ws?match={id}&token={white_token}", server.addr);
    match tokio_tungstenite::connect_async(url).await {
        Err(tokio_tungstenite::tungstenite::Error::Http(response)) => {
            assert_eq!(response.status().as_u16(), 400);
            let body = String::from_utf8_lossy(response.body().as_deref().unwrap_or_default());
            assert!(
                body.contains(r#""code":"bad-message""#) && body.contains("hello"),
                "{body}"
            );
        }
        other => panic!("expected HTTP 400, got {:?}", other.map(|_| ())),
    }
    // Anything but a hello first is refused with no-hello and closed.
    let mut rude = Client::connect_silent(&server.addr, &id).await.unwrap();
    rude.send(&shot(4, 0.0, 2.0)).await;
    assert_eq!(rude.next_error().await, "no-hello");
    assert!(rude.closes().await);
    let mut old = Client::connect_silent(&server.addr, &id).await.unwrap();
    old.send_text(r#"{"type":"hello","protocol":999,"name":"x"}"#)
        .await;
    assert_eq!(old.next_error().await, "unsupported-protocol");
    assert!(old.closes().await);
    // With the token in the hello, the seat plays.
    let mut white = server.ws(&id, Some(&white_token)).await;
    assert_eq!(white.received.len(), 1, "the welcome came first");
    let mut black = server.ws(&id, Some(&black_token)).await;
    view(white.next().await);
    view(black.next().await);
    white.send(&shot(4, 0.0, 2.0)).await;
    white.next_of("shot-played").await;
    // The store holds hashes only: neither token is anywhere in its files.
    drop(server);
    let files = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().path());
    for file in files.filter(|p| p.is_file()) {
        let bytes = std::fs::read(&file).unwrap();
        for token in [&white_token, &black_token] {
            let found = bytes.windows(token.len()).any(|w| w == token.as_bytes());
            assert!(!found, "a seat token was written to the store");
        }
    }
}

#[tokio::test]
async fn an_oversized_frame_is_refused_with_message_too_large_and_changes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &["--max-message-bytes", "4096"]);
    let (id, white_token, _) = server.two_player_match("").await;
    let mut white = server.ws(&id, Some(&white_token)).await;
    let before = view(white.next().await);
    let padding = " ".repeat(10_000);
    white
        .send_text(format!(
            r#"{{"type":"shot","piece":4,"velocity":[0,2]{padding}}}"#
        ))
        .await;
    assert_eq!(white.next_error().await, "message-too-large");
    assert!(white.closes().await);
    let mut white = server.ws(&id, Some(&white_token)).await;
    assert_eq!(view(white.next().await), before);
    white.send(&shot(4, 0.0, 2.0)).await;
    white.next_of("shot-played").await;
}

#[tokio::test]
async fn a_message_fragmented_past_the_size_limit_is_refused_with_message_too_large() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &["--max-message-bytes", "4096"]);
    let (id, white_token, _) = server.two_player_match("").await;
    let mut white = server.ws(&id, Some(&white_token)).await;
    view(white.next().await);
    let padding = " ".repeat(12_000);
    // Every frame is under the limit; the message they make is not.
    white
        .send_fragmented(&format!(r#"{{"type":"chat","text":"hi"{padding}}}"#), 3000)
        .await;
    assert_eq!(white.next_error().await, "message-too-large");
    assert!(white.closes().await);
}

#[tokio::test]
async fn hostile_seat_names_are_refused_and_names_are_shown_normalised() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &[]);
    let code = |body: &str| -> String {
        let v: serde_json::Value = serde_json::from_str(body).unwrap();
        v["code"].as_str().unwrap_or_default().to_string()
    };
    for (name, want) in [
        ("Petka\u{202E}akteP", "bad-name"),
        ("Pet\u{200B}ka", "bad-name"),
        ("Pet\u{2028}ka", "bad-name"),
        ("Pet\nka", "bad-name"),
        ("   ", "bad-name"),
        ("bot (hard)", "reserved-name"),
        ("computer-hard", "reserved-name"),
        ("Computer (easy)", "reserved-name"),
        ("ВОТ", "reserved-name"),
    ] {
        let body = serde_json::json!({ "name": name }).to_string();
        let (status, text) = server.http("POST", "/api/matches", &body).await;
        assert_eq!(
            (status, code(&text)),
            (400, want.to_string()),
            "{name:?}: {text}"
        );
    }
    // Full-width letters are normalised: the seat, and so the chat's
    // author, is plain "Petka".
    let (id, token) = server.create(r#"{"name":"Ｐｅｔｋａ"}"#).await;
    let join = format!("/api/matches/{id}/join");
    let (status, text) = server
        .http("POST", &join, r#"{"name":"bot (medium)"}"#)
        .await;
    assert_eq!((status, code(&text)), (400, "reserved-name".to_string()));
    let (status, _) = server.http("POST", &join, r#"{"name":"Anka"}"#).await;
    assert_eq!(status, 200);
    let mut white = server.ws(&id, Some(&token)).await;
    view(white.next().await);
    white
        .send(&ClientMessage::Chat {
            text: "hello".into(),
        })
        .await;
    match white.next_of("chat").await {
        game::protocol::ServerMessage::Chat { name, .. } => assert_eq!(name, "Petka"),
        other => panic!("{other:?}"),
    }
}

#[tokio::test]
async fn an_http_body_past_the_size_limit_gets_a_json_413() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &["--max-message-bytes", "4096"]);
    let body = format!(r#"{{"name":"{}"}}"#, "x".repeat(10_000));
    let (status, text) = server.http("POST", "/api/matches", &body).await;
    assert_eq!(status, 413, "{text}");
    let v: serde_json::Value =
        serde_json::from_str(&text).unwrap_or_else(|e| panic!("{e}: {text}"));
    assert_eq!(v["type"], "error");
    assert_eq!(v["code"], "message-too-large");
}

#[tokio::test]
async fn another_sites_page_cannot_create_join_or_play_but_the_own_origin_and_bots_can() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(
        dir.path(),
        &["--allowed-origins", "https://chapaev.example"],
    );
    let addr = server.addr.clone();
    let code = |body: &str| -> String {
        let v: serde_json::Value = serde_json::from_str(body).unwrap();
        v["code"].as_str().unwrap_or_default().to_string()
    };
    let foreign = "Origin: http://evil.example\r\n";
    let (s, b) = common::http_with(&addr, "POST", "/api/matches", foreign, "{}").await;
    assert_eq!((s, code(&b)), (403, "forbidden-origin".to_string()), "{b}");
    let (id, _) = server.create("{}").await;
    let join = format!("/api/matches/{id}/join");
    let (s, b) = common::http_with(&addr, "POST", &join, foreign, "{}").await;
    assert_eq!((s, code(&b)), (403, "forbidden-origin".to_string()), "{b}");
    // The WebSocket opening too.
    let ws = format!("/ws?match={id}");
    let upgrade = format!(
        "{foreign}Upgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Version: 13\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n"
    );
    let (s, b) = common::http_with(&addr, "GET", &ws, &upgrade, "").await;
    assert_eq!((s, code(&b)), (403, "forbidden-origin".to_string()), "{b}");
    // Reads are not checked; the own origin and a listed one may act.
    let (s, _) = common::http_with(&addr, "GET", "/api/matches", foreign, "").await;
    assert_eq!(s, 200);
    let own = format!("Origin: http://{addr}\r\n");
    let (s, b) = common::http_with(&addr, "POST", "/api/matches", &own, "{}").await;
    assert_eq!(s, 201, "{b}");
    let listed = "Origin: https://chapaev.example\r\n";
    let (s, b) = common::http_with(&addr, "POST", &join, listed, "{}").await;
    assert_eq!(s, 200, "{b}");
}

#[tokio::test]
async fn a_flood_is_rate_limited_and_the_connection_survives() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &["--rate-per-sec", "10", "--rate-burst", "10"]);
    let (id, white_token, _) = server.two_player_match("").await;
    let mut white = server.ws(&id, Some(&white_token)).await;
    view(white.next().await);
    for k in 0..60 {
        white
            .send(&ClientMessage::Chat {
                text: format!("spam {k}"),
            })
            .await;
    }
    assert_eq!(white.next_error().await, "rate-limited");
    tokio::time::sleep(Duration::from_millis(1500)).await;
    white
        .send(&ClientMessage::Chat {
            text: "still here".into(),
        })
        .await;
    loop {
        if let game::protocol::ServerMessage::Chat { text, .. } = white.next_of("chat").await {
            if text == "still here" {
                break;
            }
        }
    }
}

#[tokio::test]
async fn a_chat_flood_sustained_above_the_rate_is_closed() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &["--rate-per-sec", "10", "--rate-burst", "10"]);
    let (id, white_token, _) = server.two_player_match("").await;
    let mut white = server.ws(&id, Some(&white_token)).await;
    view(white.next().await);
    // 20 chat messages a second against 10: half are dropped, never 200
    // in a row, but the flood goes on.
    let chat = ClientMessage::Chat {
        text: "spam".into(),
    }
    .to_json();
    let (close, after) = white
        .flood_until_closed(&chat, Duration::from_millis(50), Duration::from_secs(30))
        .await
        .expect("a sustained flood is closed");
    let close = close.expect("a close frame");
    assert_eq!(u16::from(close.code), 1008, "policy violation");
    assert_eq!(close.reason, "rate-limited");
    assert!(after >= Duration::from_secs(9), "closed after {after:?}");
}

#[tokio::test]
async fn a_spectators_chat_flood_is_closed_like_a_players() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &["--rate-per-sec", "1", "--rate-burst", "2"]);
    let (id, _, _) = server.two_player_match("").await;
    let mut watcher = server.ws(&id, None).await;
    view(watcher.next().await);
    // Far above the rate: 200 dropped in a row close the connection.
    let chat = ClientMessage::Chat {
        text: "spam".into(),
    }
    .to_json();
    let (close, _) = watcher
        .flood_until_closed(&chat, Duration::from_millis(1), Duration::from_secs(20))
        .await
        .expect("a spectator's flood is closed");
    let close = close.expect("a close frame");
    assert_eq!(u16::from(close.code), 1008, "policy violation");
    assert_eq!(close.reason, "rate-limited");
}

#[tokio::test]
async fn legal_moves_are_never_dropped_by_the_flood_guard_but_refused_ones_pay() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &["--rate-per-sec", "1", "--rate-burst", "2"]);
    let (id, white_token, black_token) = server.two_player_match("").await;
    let mut white = server.ws(&id, Some(&white_token)).await;
    view(white.next().await);
    // Talk spends the bucket...
    for k in 0..3 {
        white
            .send(&ClientMessage::Chat {
                text: format!("hi {k}"),
            })
            .await;
    }
    assert_eq!(white.next_error().await, "rate-limited");
    // ...but a legal shot right after is played, not dropped.
    white.send(&shot(4, 0.0, 2.0)).await;
    white.next_of("shot-played").await;
    // Refused moves are junk: they pay into debt, and a connection that
    // keeps sending them is closed.
    let mut black = server.ws(&id, Some(&black_token)).await;
    view(black.next().await);
    for _ in 0..20 {
        black.send(&shot(12, 0.0, -2.0)).await;
        tokio::time::sleep(Duration::from_millis(5)).await;
    }
    assert_eq!(black.next_error().await, "not-your-turn");
    assert!(
        black.closes().await,
        "a flood of refused moves closes the connection"
    );
}

#[tokio::test]
async fn simulate_gives_the_servers_bits_and_refuses_hostile_requests() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(
        dir.path(),
        &["--simulate-per-sec", "1", "--simulate-burst", "8"],
    );
    let mut rng = game::noise::SplitMix64::new(4);
    for _ in 0..3 {
        let req = game::simulate::random_request(&mut rng);
        let (status, body) = server
            .http(
                "POST",
                "/api/simulate",
                &serde_json::to_string(&req).unwrap(),
            )
            .await;
        assert_eq!(status, 200, "{body}");
        let native = serde_json::to_string(&req.run().unwrap()).unwrap();
        assert_eq!(body, native, "the same bits as the server's own simulation");
    }
    let code = |body: &str| -> String {
        let v: serde_json::Value = serde_json::from_str(body).unwrap();
        v["code"].as_str().unwrap_or_default().to_string()
    };
    let opening = r#""board":[{"id":0,"pos":[0.02,0.02]},{"id":8,"pos":[0.02,0.30]}]"#;
    for (body, status, expected) in [
        ("{", 400, "bad-json"),
        (
            r#"{"board":[],"piece":0,"velocity":[0,1],"oops":1}"#,
            400,
            "bad-message",
        ),
        (
            &format!(r#"{{{opening},"piece":0,"velocity":[0,1e400]}}"#) as &str,
            400,
            "not-finite",
        ),
        (
            r#"{"board":[{"id":0,"pos":[0.02,0.02]},{"id":8,"pos":[0.021,0.02]}],"piece":0,"velocity":[0,1]}"#,
            400,
            "bad-board",
        ),
        (
            &format!(r#"{{{opening},"piece":0,"velocity":[0,9]}}"#),
            400,
            "too-fast",
        ),
    ] {
        let (s, b) = server.http("POST", "/api/simulate", body).await;
        assert_eq!((s, code(&b)), (status, expected.to_string()), "{body}: {b}");
    }
    // The address has spent its burst: refused until it refills.
    let (s, b) = server.http("POST", "/api/simulate", "{}").await;
    assert_eq!((s, code(&b)), (429, "rate-limited".to_string()));
}

#[tokio::test]
async fn behind_a_trusted_proxy_each_forwarded_client_has_its_own_limit_and_spoofing_does_not_help()
{
    // One match creation per address, refilling only after ~1000 s.
    let limits = ["--create-per-sec", "0.001", "--create-burst", "1"];
    let dir = tempfile::tempdir().unwrap();
    let mut flags = limits.to_vec();
    flags.extend(["--trusted-proxy", "127.0.0.0/8"]);
    let proxied = Server::start(dir.path(), &flags);
    let create = |server: &Server, header: &str| {
        let (addr, header) = (server.addr.clone(), header.to_string());
        async move {
            common::http_with(&addr, "POST", "/api/matches", &header, "{}")
                .await
                .0
        }
    };
    // Two clients behind the proxy: one creation each.
    assert_eq!(
        create(&proxied, "X-Forwarded-For: 198.51.100.1\r\n").await,
        201
    );
    assert_eq!(
        create(&proxied, "Forwarded: for=198.51.100.2\r\n").await,
        201
    );
    assert_eq!(
        create(&proxied, "X-Forwarded-For: 198.51.100.1\r\n").await,
        429
    );
    // A client's own spoofed entry left of the proxy's does not change who it is.
    assert_eq!(
        create(&proxied, "X-Forwarded-For: 203.0.113.5, 198.51.100.1\r\n").await,
        429
    );
    // One IPv6 client is one /64, whatever address it picks in it.
    assert_eq!(
        create(&proxied, "Forwarded: for=\"[2001:db8:0:1::1]\"\r\n").await,
        201
    );
    assert_eq!(
        create(&proxied, "Forwarded: for=\"[2001:db8:0:1::2]\"\r\n").await,
        429
    );
    // Without the setting the headers are not believed: one address for all.
    let dir = tempfile::tempdir().unwrap();
    let direct = Server::start(dir.path(), &limits);
    assert_eq!(
        create(&direct, "X-Forwarded-For: 198.51.100.1\r\n").await,
        201
    );
    assert_eq!(
        create(&direct, "X-Forwarded-For: 198.51.100.2\r\n").await,
        429
    );
}

#[tokio::test]
async fn limits_on_matches_and_connections_hold() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(
        dir.path(),
        &["--max-matches", "1", "--max-connections", "2"],
    );
    let (id, _) = server.create("{}").await;
    let (status, body) = server.http("POST", "/api/matches", "{}").await;
    assert_eq!(status, 503);
    assert!(body.contains(r#""code":"server-busy""#), "{body}");
    let mut a = server.ws(&id, None).await;
    let mut b = server.ws(&id, None).await;
    view(a.next().await);
    view(b.next().await);
    assert!(Client::try_connect(&server.addr, &id, None).await.is_err());
    drop(a);
    tokio::time::sleep(Duration::from_millis(300)).await;
    let mut c = server.ws(&id, None).await;
    view(c.next().await);
}

#[tokio::test]
async fn bad_http_requests_get_error_bodies_with_stable_codes() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &[]);
    let cases = [
        ("POST", "/api/matches", "{", 400, "bad-json"),
        (
            "POST",
            "/api/matches",
            r#"{"colour":"red"}"#,
            400,
            "bad-message",
        ),
        (
            "POST",
            "/api/matches",
            r#"{"config":{"mu":-1}}"#,
            400,
            "bad-config",
        ),
        (
            "POST",
            "/api/matches",
            r#"{"opponent":"bot","bot_level":"godlike"}"#,
            400,
            "bad-message",
        ),
        (
            "POST",
            "/api/matches",
            r#"{"turn_seconds":0}"#,
            400,
            "bad-config",
        ),
        (
            "POST",
            "/api/matches/deadbeefdeadbeef/join",
            "{}",
            404,
            "no-such-match",
        ),
        (
            "GET",
            "/api/matches/deadbeefdeadbeef/record",
            "",
            404,
            "no-such-match",
        ),
        (
            "GET",
            "/api/matches?status=sideways",
            "",
            400,
            "bad-message",
        ),
    ];
    for (method, path, body, status, code) in cases {
        let (got, text) = server.http(method, path, body).await;
        assert_eq!(got, status, "{method} {path} {body}: {text}");
        assert!(
            text.contains(&format!(r#""code":"{code}""#)),
            "{method} {path} {body}: {text}"
        );
    }
    let (id, _, _) = server.two_player_match("").await;
    let (status, text) = server
        .http("POST", &format!("/api/matches/{id}/join"), "{}")
        .await;
    assert_eq!((status, text.contains("match-full")), (409, true), "{text}");
    let (status, text) = server
        .http("GET", &format!("/api/matches/{id}/record"), "")
        .await;
    assert_eq!(
        (status, text.contains("match-not-over")),
        (409, true),
        "{text}"
    );
}
