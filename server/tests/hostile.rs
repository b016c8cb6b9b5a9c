//! Hostile clients cannot hold the server's resources: a client that stops
//! reading is dropped and its socket closed (so its connection counts are
//! released), one address cannot hold more than its share of connections,
//! and creating matches is limited per address while the limit on matches
//! in memory holds under concurrent requests.

mod common;

use common::{view, Client, Server};
use futures_util::{SinkExt, StreamExt};
use game::protocol::ClientMessage;
use std::time::{Duration, Instant};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::{TcpSocket, TcpStream};
use tokio_tungstenite::tungstenite::{self, Message};

/// Open WebSocket connections, as `/healthz` counts them.
async fn connections(server: &Server) -> i64 {
    let (status, body) = server.http("GET", "/healthz", "").await;
    assert_eq!(status, 200, "{body}");
    let v: serde_json::Value = serde_json::from_str(&body).unwrap();
    v["connections"].as_i64().unwrap()
}

/// The error code in a JSON error body.
fn code(body: &str) -> String {
    let v: serde_json::Value = serde_json::from_str(body).unwrap_or_default();
    v["code"].as_str().unwrap_or_default().to_string()
}

/// A WebSocket handshake on a socket with a tiny receive buffer, after which
/// the client never reads again.
async fn stalled_spectator(addr: &str, id: &str) -> TcpStream {
    let socket = TcpSocket::new_v4().unwrap();
    socket.set_recv_buffer_size(4096).unwrap();
    let mut s = socket.connect(addr.parse().unwrap()).await.unwrap();
    let req = format!(
        "GET /ws?match={id} HTTP/1.1\r\nHost: {addr}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n\
         Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n"
    );
    s.write_all(req.as_bytes()).await.unwrap();
    let mut head = Vec::new();
    let mut byte = [0u8; 1];
    while !head.ends_with(b"\r\n\r\n") {
        assert_eq!(s.read(&mut byte).await.unwrap(), 1, "the server answers");
        head.push(byte[0]);
    }
    let head = String::from_utf8_lossy(&head);
    assert!(head.starts_with("HTTP/1.1 101"), "{head}");
    // A spectator's hello, as one masked text frame (mask 0: plain bytes).
    let hello = br#"{"type":"hello","protocol":1,"name":"slow"}"#;
    let mut frame = vec![0x81, 0x80 | hello.len() as u8, 0, 0, 0, 0];
    frame.extend_from_slice(hello);
    s.write_all(&frame).await.unwrap();
    s
}

#[tokio::test]
async fn a_client_that_stops_reading_is_dropped_and_its_socket_closed_by_the_server() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(
        dir.path(),
        &[
            "--write-timeout-ms",
            "1000",
            "--outbound-queue",
            "128",
            "--rate-per-sec",
            "100000",
            "--rate-burst",
            "100000",
        ],
    );
    let (id, token) = server.create(r#"{"name":"Petka"}"#).await;
    let url = format!("ws://{}/ws?match={id}", server.addr);
    let (mut player, _) = tokio_tungstenite::connect_async(url).await.unwrap();
    let hello = ClientMessage::Hello {
        protocol: 1,
        name: "Petka".into(),
        token: Some(game::token::SeatToken::new(token)),
        key: None,
    };
    player.send(Message::Text(hello.to_json())).await.unwrap();
    let (mut says, mut hears) = player.split();
    // The player reads everything, so only the spectator falls behind.
    let reader = tokio::spawn(async move { while let Some(Ok(_)) = hears.next().await {} });
    let mut stalled = stalled_spectator(&server.addr, &id).await;
    assert_eq!(connections(&server).await, 2);

    let chat = ClientMessage::Chat {
        text: "ура! ".repeat(100),
    }
    .to_json();
    let started = Instant::now();
    let mut sent = 0;
    let released = loop {
        // In small batches: the player, who reads, keeps up.
        for _ in 0..20 {
            says.send(Message::Text(chat.clone())).await.unwrap();
        }
        sent += 20;
        if connections(&server).await == 1 {
            break true;
        }
        if started.elapsed() > Duration::from_secs(30) {
            break false;
        }
        tokio::time::sleep(Duration::from_millis(5)).await;
    };
    assert!(
        released,
        "the stalled connection is still counted after {sent} chats"
    );
    eprintln!("released after {sent} chats in {:?}", started.elapsed());

    // The server closed the socket: reading drains what was buffered, then ends.
    let mut buf = vec![0u8; 1 << 16];
    let closed = tokio::time::timeout(Duration::from_secs(10), async {
        loop {
            match stalled.read(&mut buf).await {
                Ok(0) | Err(_) => break,
                Ok(_) => {}
            }
        }
    })
    .await;
    assert!(closed.is_ok(), "the server closed the stalled socket");
    // The player was not hurt.
    says.send(Message::Text(
        r#"{"type":"chat","text":"still here"}"#.into(),
    ))
    .await
    .unwrap();
    assert_eq!(connections(&server).await, 1);
    drop(says);
    reader.abort();
}

#[tokio::test]
async fn connections_past_the_per_address_limit_are_refused_with_server_busy() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &["--max-connections-per-address", "2"]);
    let (id, _) = server.create("{}").await;
    let mut a = server.ws(&id, None).await;
    let mut b = server.ws(&id, None).await;
    view(a.next().await);
    view(b.next().await);
    let url = format!("ws://{}/ws?match={id}", server.addr);
    match tokio_tungstenite::connect_async(url.clone()).await {
        Err(tungstenite::Error::Http(response)) => {
            assert_eq!(response.status().as_u16(), 503);
            let body = String::from_utf8_lossy(response.body().as_deref().unwrap_or_default());
            assert_eq!(code(&body), "server-busy", "{body}");
        }
        Err(e) => panic!("expected HTTP 503, got {e}"),
        Ok(_) => panic!("a third connection from one address was let in"),
    }
    // A connection closed gives its place back.
    drop(a);
    let started = Instant::now();
    loop {
        if let Ok(mut c) = Client::try_connect(&server.addr, &id, None).await {
            view(c.next().await);
            break;
        }
        assert!(
            started.elapsed() < Duration::from_secs(5),
            "the place was never given back"
        );
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
}

#[tokio::test]
async fn concurrent_creations_never_pass_the_limit_on_matches() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(
        dir.path(),
        &[
            "--max-matches",
            "20",
            "--create-per-sec",
            "10000",
            "--create-burst",
            "10000",
        ],
    );
    let tasks: Vec<_> = (0..100)
        .map(|i| {
            let addr = server.addr.clone();
            tokio::spawn(async move {
                if i % 4 == 0 {
                    common::http(&addr, "POST", "/api/exhibitions", "{}").await
                } else {
                    common::http(&addr, "POST", "/api/matches", r#"{"name":"Petka"}"#).await
                }
            })
        })
        .collect();
    let (mut created, mut busy) = (0, 0);
    for t in tasks {
        let (status, body) = t.await.unwrap();
        match status {
            201 => created += 1,
            503 if code(&body) == "server-busy" => busy += 1,
            _ => panic!("unexpected answer {status} {body}"),
        }
    }
    assert_eq!((created, busy), (20, 80));
    let (_, body) = server.http("GET", "/healthz", "").await;
    let v: serde_json::Value = serde_json::from_str(&body).unwrap();
    assert_eq!(v["matches_in_memory"], 20);
}

#[tokio::test]
async fn creating_matches_is_rate_limited_per_address() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(
        dir.path(),
        &["--create-per-sec", "0.01", "--create-burst", "3"],
    );
    server.create("{}").await;
    server.create("{}").await;
    let (status, body) = server.http("POST", "/api/exhibitions", "{}").await;
    assert_eq!(status, 201, "{body}");
    for path in ["/api/matches", "/api/exhibitions"] {
        let (status, body) = server.http("POST", path, "{}").await;
        assert_eq!(
            (status, code(&body)),
            (429, "rate-limited".into()),
            "{path}"
        );
    }
    // Refused creations made nothing.
    let (_, body) = server.http("GET", "/healthz", "").await;
    let v: serde_json::Value = serde_json::from_str(&body).unwrap();
    assert_eq!(v["matches_in_memory"], 3);
}

#[tokio::test]
async fn a_connection_the_server_closes_is_released_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &[]);
    let (id, _) = server.create("{}").await;
    let mut thief = server.ws(&id, Some(&"0".repeat(32))).await;
    assert_eq!(thief.next_error().await, "bad-token");
    assert!(thief.closes().await);
    // Well within the 10 s write timeout: the closed socket is not held.
    let started = Instant::now();
    while connections(&server).await != 0 {
        assert!(
            started.elapsed() < Duration::from_secs(3),
            "a closed connection is still counted"
        );
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
}

#[tokio::test]
async fn each_connection_holds_one_descriptor_of_the_server() {
    let dir = tempfile::tempdir().unwrap();
    let server = Server::start(dir.path(), &[]);
    let (id, _) = server.create("{}").await;
    let mut first = server.ws(&id, None).await;
    view(first.next().await);
    let before = server.descriptors();
    let mut clients = Vec::new();
    for _ in 0..40 {
        let mut c = server.ws(&id, None).await;
        view(c.next().await);
        clients.push(c);
    }
    let grown = server.descriptors() - before;
    // One socket each (a few more for the runtime's own needs at most).
    assert!(
        (40..48).contains(&grown),
        "40 connections took {grown} descriptors"
    );
}
