//! The account event stream through the real server: the welcome's full
//! picture, challenges (refused, made, accepted once, played with the
//! seat tokens the stream hands over, finished with the new rating), the
//! ladder pairing a bot with a computer level, a challenge to a hosted bot
//! (accepted at once, its seat played by the server, and after a restart
//! in the middle of that match, not paired on the ladder until it ends),
//! and hostile openings (a wrong key, a bot's key from a web page) refused
//! with a stable code.

mod common;

use common::{Client, Server};
use futures_util::{SinkExt, StreamExt};
use game::protocol::{ClientMessage, ErrorCode, PROTOCOL_VERSION};
use game::stream::{StreamClientMessage, StreamServerMessage};
use game::token::SeatToken;
use std::time::Duration;
use tokio::net::TcpStream;
use tokio_tungstenite::tungstenite::client::IntoClientRequest;
use tokio_tungstenite::tungstenite::Message;
use tokio_tungstenite::{MaybeTlsStream, WebSocketStream};

type Ws = WebSocketStream<MaybeTlsStream<TcpStream>>;

async fn account(s: &Server, name: &str, bot: bool) -> String {
    let body = format!(r#"{{"name":"{name}","bot":{bot}}}"#);
    let (status, text) = s.http("POST", "/api/accounts", &body).await;
    assert_eq!(status, 201, "{text}");
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["key"].as_str().unwrap().to_string()
}

struct Stream {
    ws: Ws,
}

impl Stream {
    /// Opens a stream (with extra request headers) and says hello with `key`.
    async fn open_with(addr: &str, key: &str, headers: &[(&'static str, &str)]) -> Stream {
        let mut req = format!("ws://{addr}/api/stream")
            .into_client_request()
            .unwrap();
        for (name, value) in headers {
            req.headers_mut().insert(*name, value.parse().unwrap());
        }
        let (ws, _) = tokio_tungstenite::connect_async(req).await.unwrap();
        let mut s = Stream { ws };
        s.send(&StreamClientMessage::Hello {
            protocol: PROTOCOL_VERSION,
            key: SeatToken::new(key),
        })
        .await;
        s
    }

    async fn open(addr: &str, key: &str) -> Stream {
        Stream::open_with(addr, key, &[]).await
    }

    async fn send(&mut self, m: &StreamClientMessage) {
        self.ws.send(Message::text(m.to_json())).await.unwrap();
    }

    /// The next message (skipping keep-alives), within 10 s.
    async fn next(&mut self) -> StreamServerMessage {
        loop {
            let frame = tokio::time::timeout(Duration::from_secs(10), self.ws.next())
                .await
                .expect("a stream message in time")
                .expect("the stream is open")
                .unwrap();
            if let Message::Text(t) = frame {
                let m = StreamServerMessage::from_json(&t).unwrap();
                if m != StreamServerMessage::KeepAlive {
                    return m;
                }
            }
        }
    }

    async fn error(&mut self) -> ErrorCode {
        match self.next().await {
            StreamServerMessage::Error { code, .. } => code,
            other => panic!("expected an error, got {other:?}"),
        }
    }
}

fn hello_with_key(key: &str) -> ClientMessage {
    ClientMessage::Hello {
        protocol: PROTOCOL_VERSION,
        name: "by key".into(),
        token: None,
        key: Some(SeatToken::new(key)),
    }
}

fn challenge_id(m: StreamServerMessage) -> String {
    match m {
        StreamServerMessage::Challenge { challenge } => challenge.id,
        other => panic!("expected a challenge, got {other:?}"),
    }
}

/// (match id, token) of a match-start.
fn started(m: StreamServerMessage) -> (String, String, String) {
    match m {
        StreamServerMessage::MatchStart {
            match_id,
            token,
            opponent,
            rated,
            ..
        } => {
            assert!(rated);
            (match_id, token.expose().to_string(), opponent)
        }
        other => panic!("expected a match start, got {other:?}"),
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_challenge_is_accepted_once_played_with_the_streamed_tokens_and_rated() {
    let dir = tempfile::tempdir().unwrap();
    let s = Server::start(dir.path(), &[]);
    let furmanov = account(&s, "Furmanov", true).await;
    let anka = account(&s, "Anka", false).await;

    let mut f = Stream::open(&s.addr, &furmanov).await;
    match f.next().await {
        StreamServerMessage::Welcome {
            account,
            bot,
            rating,
            matches,
            challenges,
            ..
        } => {
            assert_eq!((account.as_str(), bot, rating), ("Furmanov", true, 1500));
            assert!(matches.is_empty() && challenges.is_empty());
        }
        other => panic!("{other:?}"),
    }
    let mut a = Stream::open(&s.addr, &anka).await;
    a.next().await;

    let to = |who: &str| StreamClientMessage::Challenge {
        to: who.into(),
        rated: true,
        rules: None,
        turn_seconds: Some(30),
        color: None,
    };
    a.send(&to("nobody")).await;
    assert_eq!(a.error().await, ErrorCode::NoSuchAccount);
    a.send(&to("anka")).await;
    assert_eq!(a.error().await, ErrorCode::SameAccount);
    a.send(&StreamClientMessage::Ladder { join: true }).await;
    assert_eq!(
        a.error().await,
        ErrorCode::BadMessage,
        "people do not ladder"
    );
    a.send(&to("furmanov")).await;
    let id = challenge_id(a.next().await);
    assert_eq!(challenge_id(f.next().await), id);

    f.send(&StreamClientMessage::Accept {
        challenge: id.clone(),
    })
    .await;
    let (match_id, f_token, opponent) = started(f.next().await);
    assert_eq!(opponent, "Anka");
    let (same, a_token, _) = started(a.next().await);
    assert_eq!(same, match_id);
    f.send(&StreamClientMessage::Accept { challenge: id }).await;
    assert_eq!(f.error().await, ErrorCode::NoSuchChallenge, "accepted once");

    // The streamed tokens hold the seats; a resignation ends the match and
    // each stream hears of it with its new rating.
    // Anka's seat is also hers with her account key instead of the token
    // (a restarted process takes its matches back so); another account's
    // key holds no seat here.
    assert!(!a_token.is_empty());
    let mut by_key = Client::connect_silent(&s.addr, &match_id).await.unwrap();
    by_key.send(&hello_with_key(&anka)).await;
    match by_key.next().await {
        game::protocol::ServerMessage::Welcome { .. } => {}
        other => panic!("{other:?}"),
    }
    let state = by_key.next_of("match-state").await;
    assert!(
        matches!(
            state,
            game::protocol::ServerMessage::MatchState { you: Some(_), .. }
        ),
        "{state:?}"
    );
    let stranger = account(&s, "Petka", false).await;
    let mut wrong = Client::connect_silent(&s.addr, &match_id).await.unwrap();
    wrong.send(&hello_with_key(&stranger)).await;
    assert_eq!(wrong.next_error().await, "bad-key");

    let mut fm = Client::connect(&s.addr, &match_id, Some(&f_token)).await;
    fm.send(&ClientMessage::Resign).await;
    for stream in [&mut f, &mut a] {
        match stream.next().await {
            StreamServerMessage::MatchFinish {
                match_id: m,
                rating: Some(r),
                ..
            } => {
                assert_eq!(m, match_id);
                assert_ne!(r, 1500);
            }
            other => panic!("{other:?}"),
        }
    }

    // A reopened stream's welcome shows no match left to play.
    let mut again = Stream::open(&s.addr, &anka).await;
    match again.next().await {
        StreamServerMessage::Welcome { matches, .. } => assert!(matches.is_empty()),
        other => panic!("{other:?}"),
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_ladder_pairs_an_online_bot_with_a_computer_level_in_a_rated_match() {
    let dir = tempfile::tempdir().unwrap();
    let s = Server::start(dir.path(), &["--ladder-seconds", "1"]);
    let key = account(&s, "Chapaev", true).await;
    let mut c = Stream::open(&s.addr, &key).await;
    c.next().await;
    c.send(&StreamClientMessage::Ladder { join: true }).await;
    let (match_id, token, opponent) = started(c.next().await);
    assert!(opponent.starts_with("computer-"), "{opponent}");
    let (_, text) = s.http("GET", &format!("/api/matches/{match_id}"), "").await;
    let summary: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(summary["rated"], true, "{text}");
    // Still playing it: the next rounds pair it with nobody else.
    tokio::time::sleep(Duration::from_millis(2500)).await;
    let mut m = Client::connect(&s.addr, &match_id, Some(&token)).await;
    m.send(&ClientMessage::Resign).await;
    assert!(matches!(
        c.next().await,
        StreamServerMessage::MatchFinish { rating: Some(r), .. } if r < 1500
    ));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_stream_with_a_wrong_key_or_a_bot_key_from_a_web_page_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let s = Server::start(dir.path(), &[]);
    let bot = account(&s, "Furmanov", true).await;
    let mut wrong = Stream::open(&s.addr, "0123456789abcdef0123456789abcdef").await;
    assert_eq!(wrong.error().await, ErrorCode::BadKey);
    let page = [("sec-fetch-site", "same-origin")];
    let mut from_page = Stream::open_with(&s.addr, &bot, &page).await;
    assert_eq!(from_page.error().await, ErrorCode::BotKeyInBrowser);
    // A bad first message.
    let (ws, _) = tokio_tungstenite::connect_async(format!("ws://{}/api/stream", s.addr))
        .await
        .unwrap();
    let mut junk = Stream { ws };
    junk.ws
        .send(Message::text("{\"type\":\"ladder\",\"join\":true}"))
        .await
        .unwrap();
    assert_eq!(junk.error().await, ErrorCode::NoHello);
}

/// Uploads `module` as the bot's (`key`) active one; its hash.
async fn upload(s: &Server, key: &str, module: Vec<u8>) -> String {
    let url = format!("http://{}/api/accounts/me/module", s.addr);
    let bearer = format!("Bearer {key}");
    let (status, text) = tokio::task::spawn_blocking(move || {
        ureq::put(&url)
            .set("Authorization", &bearer)
            .send_bytes(&module)
            .map(|a| (a.status(), a.into_string().unwrap_or_default()))
            .unwrap_or_else(|e| panic!("{e}"))
    })
    .await
    .unwrap();
    assert_eq!(status, 201, "{text}");
    common::modules::json(&text)["hash"]
        .as_str()
        .unwrap()
        .to_string()
}

/// The ids of the matches `account` played, newest first.
async fn match_ids(s: &Server, account: &str) -> Vec<String> {
    let (status, text) = s
        .http("GET", &format!("/api/accounts/{account}/matches"), "")
        .await;
    assert_eq!(status, 200, "{text}");
    let listed: serde_json::Value = serde_json::from_str(&text).unwrap();
    listed
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["match_id"].as_str().unwrap().to_string())
        .collect()
}

/// A module that resigns at every decision, its bytes (so its hash) its
/// own for each `k`.
fn resigning_version(k: u32) -> Vec<u8> {
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

/// `DELETE`s the bot's (`key`) version `hash`: the status and the code.
async fn delete_version(s: &Server, key: &str, hash: &str) -> (u16, String) {
    let path = format!("/api/accounts/me/modules/{hash}");
    let (status, text) = common::modules::as_key(s, "DELETE", &path, key, "").await;
    let code = match status {
        204 => String::new(),
        _ => common::modules::json(&text)["code"]
            .as_str()
            .unwrap_or_default()
            .to_string(),
    };
    (status, code)
}

/// `challenger` challenges the hosted bot "Wasm" to a rated match,
/// playing White; the bot accepts at once: the new match's id, the
/// challenger's token and the opponent's name.
async fn challenge_wasm_as_white(challenger: &mut Stream) -> (String, String, String) {
    challenger
        .send(&StreamClientMessage::Challenge {
            to: "wasm".into(),
            rated: true,
            rules: None,
            turn_seconds: None,
            color: Some(game::Side::White),
        })
        .await;
    started(challenger.next().await)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_hosted_bot_mid_match_at_a_restart_keeps_its_version_and_is_not_paired_until_the_match_ends(
) {
    let dir = tempfile::tempdir().unwrap();
    // No ladder round yet: the bot plays only the challenge.
    let mut s = Server::start(dir.path(), &["--ladder-seconds", "600"]);
    let bot = account(&s, "Wasm", true).await;
    let v1 = upload(&s, &bot, resigning_version(1)).await;
    let key = account(&s, "Anka", false).await;
    let mut anka = Stream::open(&s.addr, &key).await;
    anka.next().await;
    // The lobby reads the hosted bots at most 5 s apart.
    tokio::time::sleep(Duration::from_millis(5500)).await;
    // Anka moves first, and does not yet: the match waits on her.
    let (match_id, token, _) = challenge_wasm_as_white(&mut anka).await;
    drop(anka);
    // Another version made active; the one the match plays with stays.
    let v2 = upload(&s, &bot, resigning_version(2)).await;
    assert_ne!(v1, v2);
    assert_eq!(
        delete_version(&s, &bot, &v1).await,
        (409, "module-in-use".to_string())
    );
    s.kill();
    // Back with a ladder round every second, and computer levels idle:
    // the bot, whose match resumes, is not paired.
    let s = Server::start(dir.path(), &["--ladder-seconds", "1"]);
    tokio::time::sleep(Duration::from_secs(4)).await;
    assert_eq!(match_ids(&s, "Wasm").await, std::slice::from_ref(&match_id));
    // Its seat is played by v1, from the store: it resigns at once.
    let mut m = Client::connect(&s.addr, &match_id, Some(&token)).await;
    m.send(&common::shot(4, 0.0, 2.0)).await;
    m.next_of("match-over").await;
    let (_, text) = s
        .http("GET", &format!("/api/matches/{match_id}/record"), "")
        .await;
    let record = game::MatchRecord::from_json(&text).unwrap();
    assert_eq!(record.hosted, Some([None, Some(v1.clone())]));
    assert!(matches!(
        record.moves.last(),
        Some(game::RecordedMove::Resign {
            side: game::Side::Black
        })
    ));
    // The match over, the version may go, and the ladder pairs the bot.
    assert_eq!(delete_version(&s, &bot, &v1).await, (204, String::new()));
    let deadline = std::time::Instant::now() + Duration::from_secs(20);
    while match_ids(&s, "Wasm").await.len() < 2 {
        assert!(
            std::time::Instant::now() < deadline,
            "not paired after its match"
        );
        tokio::time::sleep(Duration::from_millis(200)).await;
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_challenge_to_a_hosted_bot_is_accepted_at_once_and_the_server_plays_its_seat() {
    let dir = tempfile::tempdir().unwrap();
    let s = Server::start(dir.path(), &["--ladder-seconds", "1"]);
    let bot = account(&s, "Wasm", true).await;
    upload(&s, &bot, resigning_version(0)).await;
    let key = account(&s, "Anka", false).await;
    let mut anka = Stream::open(&s.addr, &key).await;
    anka.next().await;
    // The lobby reads the hosted bots every ladder round.
    tokio::time::sleep(Duration::from_millis(2500)).await;
    let (match_id, token, opponent) = challenge_wasm_as_white(&mut anka).await;
    assert_eq!(opponent, "Wasm");
    let mut m = Client::connect(&s.addr, &match_id, Some(&token)).await;
    m.send(&common::shot(4, 0.0, 2.0)).await;
    // The module resigns at its first decision: Anka wins, rated.
    assert!(matches!(
        anka.next().await,
        StreamServerMessage::MatchFinish { rating: Some(r), .. } if r > 1500
    ));
    let (_, text) = s
        .http("GET", &format!("/api/matches/{match_id}/record"), "")
        .await;
    let record = game::MatchRecord::from_json(&text).unwrap();
    assert!(record
        .hosted
        .is_some_and(|h| h[0].is_none() && h[1].is_some()));
}
