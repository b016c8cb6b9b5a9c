//! End-to-end test support: the real server binary on a free port with a
//! temporary data folder, the tools' HTTP client and a WebSocket client.
#![allow(dead_code)]

// The HTTP client shared with the server's tools (not in the server library).
#[path = "../../tools/loopback.rs"]
mod loopback;

pub mod cluster;
pub mod modules;

use futures_util::{SinkExt, StreamExt};
use game::protocol::{ClientMessage, ServerMessage};
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::Duration;
use tokio::net::TcpStream;
use tokio_tungstenite::tungstenite::Message;
use tokio_tungstenite::{MaybeTlsStream, WebSocketStream};

/// A running server process.
pub struct Server {
    child: Child,
    pub addr: String,
    pub dir: PathBuf,
    /// Its log (stderr), shown when a test fails.
    log: PathBuf,
}

impl Server {
    /// The server's open file descriptors (Linux).
    pub fn descriptors(&self) -> usize {
        std::fs::read_dir(format!("/proc/{}/fd", self.child.id()))
            .map(|d| d.count())
            .unwrap_or(0)
    }

    /// Starts the server binary on `dir` with extra flags; waits until it listens.
    pub fn start(dir: &Path, extra: &[&str]) -> Server {
        Server::start_on(dir, "127.0.0.1:0", extra)
    }

    /// [`Server::start`] listening on `addr`.
    pub fn start_on(dir: &Path, addr: &str, extra: &[&str]) -> Server {
        let log_path = dir.join(format!(
            "server-{}.log",
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .unwrap()
                .as_nanos()
        ));
        let log = std::fs::File::create(&log_path).unwrap();
        let mut child = Command::new(env!("CARGO_BIN_EXE_server"))
            .args([
                "--addr",
                addr,
                "--bot-delay-ms",
                "0",
                "--log",
                "info,server=debug",
            ])
            .arg("--data-dir")
            .arg(dir.join("data"))
            .args(extra)
            .stdout(Stdio::piped())
            .stderr(log)
            .spawn()
            .expect("the server binary starts");
        let stdout = child.stdout.take().unwrap();
        let mut line = String::new();
        BufReader::new(stdout).read_line(&mut line).unwrap();
        let addr = line
            .trim()
            .strip_prefix("listening on http://")
            .unwrap_or_else(|| panic!("unexpected first line {line:?}"))
            .to_string();
        Server {
            child,
            addr,
            dir: dir.to_path_buf(),
            log: log_path,
        }
    }

    /// Sends the process `signal` (a name `kill` knows: `STOP`, `CONT`).
    pub fn signal(&self, signal: &str) {
        let pid = self.child.id().to_string();
        let sent = Command::new("kill")
            .args([&format!("-{signal}"), &pid])
            .status()
            .unwrap();
        assert!(sent.success(), "kill -{signal} {pid}");
    }

    /// Whether the process still runs.
    pub fn running(&mut self) -> bool {
        matches!(self.child.try_wait(), Ok(None))
    }

    /// SIGKILL: no chance to clean up.
    pub fn kill(&mut self) {
        self.child.kill().unwrap();
        self.child.wait().unwrap();
    }

    /// SIGTERM, then waits for the exit; returns whether it exited cleanly.
    pub fn terminate(&mut self) -> bool {
        let pid = self.child.id().to_string();
        Command::new("kill").args(["-TERM", &pid]).status().unwrap();
        for _ in 0..200 {
            if let Some(status) = self.child.try_wait().unwrap() {
                return status.success();
            }
            std::thread::sleep(Duration::from_millis(50));
        }
        panic!("the server did not stop within 10 s of SIGTERM");
    }

    pub async fn http(&self, method: &str, path: &str, body: &str) -> (u16, String) {
        http(&self.addr, method, path, body).await
    }

    /// Creates a match; returns (match id, token).
    pub async fn create(&self, body: &str) -> (String, String) {
        let (status, text) = self.http("POST", "/api/matches", body).await;
        assert_eq!(status, 201, "{text}");
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        (
            v["match_id"].as_str().unwrap().to_string(),
            v["token"].as_str().unwrap().to_string(),
        )
    }

    /// Joins the second seat; returns its token.
    pub async fn join(&self, id: &str) -> String {
        let (status, text) = self
            .http(
                "POST",
                &format!("/api/matches/{id}/join"),
                r#"{"name":"Anka"}"#,
            )
            .await;
        assert_eq!(status, 200, "{text}");
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        v["token"].as_str().unwrap().to_string()
    }

    /// A person-vs-person match with both seats taken: (id, first token, second token).
    pub async fn two_player_match(&self, extra: &str) -> (String, String, String) {
        let (id, a) = self.create(&format!(r#"{{"name":"Petka"{extra}}}"#)).await;
        let b = self.join(&id).await;
        (id, a, b)
    }

    pub async fn ws(&self, id: &str, token: Option<&str>) -> Client {
        Client::connect(&self.addr, id, token).await
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
        // A failing test shows what the server said last (its folder,
        // and so its log, goes with the test).
        if std::thread::panicking() {
            let log = std::fs::read_to_string(&self.log).unwrap_or_default();
            let lines: Vec<&str> = log.lines().collect();
            let tail = &lines[lines.len().saturating_sub(60)..];
            eprintln!(
                "--- the last {} lines of the server on {} ---\n{}",
                tail.len(),
                self.addr,
                tail.join("\n")
            );
        }
    }
}

/// One HTTP request; returns the status and body.
pub async fn http(addr: &str, method: &str, path: &str, body: &str) -> (u16, String) {
    http_with(addr, method, path, "", body).await
}

/// An HTTP request with extra header lines (each ending in `\r\n`).
pub async fn http_with(
    addr: &str,
    method: &str,
    path: &str,
    headers: &str,
    body: &str,
) -> (u16, String) {
    let headers: Vec<(&str, &str)> = headers
        .split("\r\n")
        .filter(|line| !line.is_empty())
        .map(|line| {
            let (name, value) = line.split_once(':').expect("a header line");
            (name.trim(), value.trim())
        })
        .collect();
    loopback::request(addr, method, path, &headers, body)
        .await
        .unwrap_or_else(|e| panic!("no HTTP answer: {e}"))
}

/// A WebSocket client speaking the protocol.
pub struct Client {
    ws: WebSocketStream<MaybeTlsStream<TcpStream>>,
    /// Every text frame received and sent, as it travelled.
    pub received: Vec<String>,
    pub sent: Vec<String>,
    /// A message read while opening that was not the `welcome`.
    pending: Option<ServerMessage>,
}

impl Client {
    /// Connects and says hello with `token` (none: watch); the `welcome`
    /// is taken, anything else (a refusal) is left to read.
    pub async fn connect(addr: &str, id: &str, token: Option<&str>) -> Client {
        Client::try_connect(addr, id, token).await.unwrap()
    }

    pub async fn try_connect(
        addr: &str,
        id: &str,
        token: Option<&str>,
    ) -> Result<Client, tokio_tungstenite::tungstenite::Error> {
        let c = Client::connect_silent(addr, id).await?.hello(token).await;
        Ok(c)
    }

    /// Connects to the node that plays the match, asking `addr` first and
    /// following its `307` ([`bots::owner::connect`]), and says hello: the
    /// client, and the address of the node it ended on.
    pub async fn try_connect_following(
        addr: &str,
        id: &str,
        token: Option<&str>,
    ) -> Result<(Client, String), tokio_tungstenite::tungstenite::Error> {
        let (ws, url) = bots::owner::connect(&format!("ws://{addr}/ws?match={id}"), false).await?;
        let at = url
            .strip_prefix("ws://")
            .and_then(|u| u.split('/').next())
            .unwrap_or_default()
            .to_string();
        let c = Client::on(ws).hello(token).await;
        Ok((c, at))
    }

    /// Opens the socket `url` (`ws://host/ws?match=ID`) as a page of
    /// `origin` does (the `Origin` header a browser sends), and says hello
    /// with `token` (none: watch).
    pub async fn try_connect_from(
        url: &str,
        origin: &str,
        token: Option<&str>,
    ) -> Result<Client, tokio_tungstenite::tungstenite::Error> {
        use tokio_tungstenite::tungstenite::client::IntoClientRequest;
        let mut request = url.into_client_request()?;
        let origin = origin.parse().map_err(|_| {
            tokio_tungstenite::tungstenite::Error::Url(
                tokio_tungstenite::tungstenite::error::UrlError::UnableToConnect(origin.into()),
            )
        })?;
        request.headers_mut().insert("origin", origin);
        let (ws, _) = tokio_tungstenite::connect_async(request).await?;
        let c = Client::on(ws).hello(token).await;
        Ok(c)
    }

    /// Connects without saying anything.
    pub async fn connect_silent(
        addr: &str,
        id: &str,
    ) -> Result<Client, tokio_tungstenite::tungstenite::Error> {
        let (ws, _) =
            tokio_tungstenite::connect_async(format!("ws://{addr}/ws?match={id}")).await?;
        Ok(Client::on(ws))
    }

    /// A client on the open socket `ws`, nothing said yet.
    fn on(ws: WebSocketStream<MaybeTlsStream<TcpStream>>) -> Client {
        Client {
            ws,
            received: Vec::new(),
            sent: Vec::new(),
            pending: None,
        }
    }

    /// Says hello with `token` (none: watch); the `welcome` is taken,
    /// anything else (a refusal) is left to read.
    async fn hello(mut self, token: Option<&str>) -> Client {
        self.send(&ClientMessage::Hello {
            protocol: game::protocol::PROTOCOL_VERSION,
            name: "test".into(),
            token: token.map(game::token::SeatToken::new),
            key: None,
        })
        .await;
        match self.try_next().await {
            Some(ServerMessage::Welcome { .. }) => {}
            other => self.pending = other,
        }
        self
    }

    pub async fn send_text(&mut self, text: impl Into<String>) {
        let text = text.into();
        self.sent.push(text.clone());
        self.ws.send(Message::Text(text)).await.unwrap();
    }

    /// Sends `text` every `every` while reading what comes, until the
    /// server closes the connection (then its close frame, if one came, and
    /// how long the flood lasted) or `within` passes (`None`).
    pub async fn flood_until_closed(
        &mut self,
        text: &str,
        every: Duration,
        within: Duration,
    ) -> Option<(
        Option<tokio_tungstenite::tungstenite::protocol::CloseFrame<'static>>,
        Duration,
    )> {
        let start = tokio::time::Instant::now();
        let mut tick = tokio::time::interval(every);
        loop {
            tokio::select! {
                _ = tick.tick() => {
                    if start.elapsed() > within {
                        return None;
                    }
                    // A send may fail once the server has closed: the read says so.
                    let _ = self.ws.send(Message::Text(text.to_string())).await;
                }
                frame = self.ws.next() => match frame {
                    Some(Ok(Message::Close(close))) => {
                        return Some((close.map(|c| c.into_owned()), start.elapsed()))
                    }
                    None | Some(Err(_)) => return Some((None, start.elapsed())),
                    Some(Ok(_)) => {}
                },
            }
        }
    }

    /// Sends `text` as one message fragmented into frames of `chunk` bytes.
    pub async fn send_fragmented(&mut self, text: &str, chunk: usize) {
        use tokio_tungstenite::tungstenite::protocol::frame::coding::{Data, OpCode};
        use tokio_tungstenite::tungstenite::protocol::frame::Frame;
        let parts: Vec<&[u8]> = text.as_bytes().chunks(chunk).collect();
        for (k, part) in parts.iter().enumerate() {
            let opcode = if k == 0 { Data::Text } else { Data::Continue };
            let frame = Frame::message(part.to_vec(), OpCode::Data(opcode), k + 1 == parts.len());
            if self.ws.send(Message::Frame(frame)).await.is_err() {
                return;
            }
        }
    }

    pub async fn send(&mut self, m: &ClientMessage) {
        self.send_text(m.to_json()).await;
    }

    /// The next protocol message (`None`: the server closed the connection).
    pub async fn try_next(&mut self) -> Option<ServerMessage> {
        if let Some(m) = self.pending.take() {
            return Some(m);
        }
        loop {
            let frame = tokio::time::timeout(Duration::from_secs(15), self.ws.next())
                .await
                .expect("a message in time");
            match frame {
                Some(Ok(Message::Text(t))) => {
                    self.received.push(t.to_string());
                    return Some(ServerMessage::from_json(&t).unwrap());
                }
                Some(Ok(Message::Close(_))) | None | Some(Err(_)) => return None,
                Some(Ok(_)) => continue,
            }
        }
    }

    pub async fn next(&mut self) -> ServerMessage {
        self.try_next().await.expect("the connection is open")
    }

    /// The next message of type `kind` (kebab-case), skipping others.
    pub async fn next_of(&mut self, kind: &str) -> ServerMessage {
        loop {
            let m = self.next().await;
            if m.to_json().starts_with(&format!("{{\"type\":\"{kind}\"")) {
                return m;
            }
        }
    }

    /// The error code of the next `error` message.
    pub async fn next_error(&mut self) -> String {
        match self.next_of("error").await {
            ServerMessage::Error { code, .. } => code.as_str().to_string(),
            _ => unreachable!(),
        }
    }

    /// Whether the server closes the connection (skipping what comes before).
    pub async fn closes(&mut self) -> bool {
        for _ in 0..1000 {
            if self.try_next().await.is_none() {
                return true;
            }
        }
        false
    }
}

/// A shot message: piece number, velocity.
pub fn shot(piece: u8, vx: f64, vy: f64) -> ClientMessage {
    ClientMessage::Shot {
        piece: piece.try_into().unwrap(),
        velocity: glam::DVec2::new(vx, vy),
    }
}

/// The view in a `match-state` message.
pub fn view(m: ServerMessage) -> game::MatchView {
    match m {
        ServerMessage::MatchState { view, .. } => view,
        other => panic!("expected match-state, got {}", other.to_json()),
    }
}
