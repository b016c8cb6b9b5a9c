//! The WebSocket endpoint `/ws?match=ID`. The client's first message is a
//! `hello` carrying the seat token (none: a spectator); the token never
//! travels in the URL, which proxies and browsers write down. A session
//! admits the connection to its match room once the hello has come
//! (answering `welcome`), forwards everything the room sends (the full
//! `match-state` first), and reads the client's
//! messages: it refuses oversized frames, malformed JSON, unknown messages
//! and floods (a token bucket per connection) itself, with an `error` of a
//! stable code, and passes every match message to the room. Moves are
//! never dropped by the flood guard: they pay only when the room refuses
//! them, and a connection whose refused moves run the bucket bankrupt is
//! closed. A connection
//! that stops answering pings, floods on after warnings, or cannot keep up
//! with the match is closed.
//!
//! Every write to the socket has a deadline (`--write-timeout-ms`): a client
//! that stops reading fills the kernel's buffers and then the session's
//! queue, and a write that cannot finish in time ends the session. Closing
//! politely would need yet another write, so the server then shuts the TCP
//! connection down itself ([`on_connect`] keeps a handle on each socket);
//! the same happens to a connection the room dropped for not keeping up
//! once its last messages cannot be flushed in time. Either way the socket,
//! its connection count and its address's count are released within about
//! one write timeout. Each client address holds at most
//! `--max-connections-per-address` connections; past it (or past the global
//! `--max-connections`) the upgrade is refused with HTTP 503 `server-busy`.

use crate::play::hub::{AddressGuard, Hub, RoomHandle};
use crate::play::room::{Claim, Command};
use crate::refusal::{HttpStatus, Refusal};
use crate::web::ratelimit::TokenBucket;
use actix_web::{web, HttpRequest, HttpResponse};
use actix_ws::{AggregatedMessage, CloseCode, CloseReason, ProtocolError, Session};
use game::protocol::{ClientMessage, ErrorCode, ServerMessage, PROTOCOL_VERSION};
use game::token::SeatToken;
use serde::Deserialize;
use std::future::Future;
use std::sync::Arc;
use std::time::{Duration, Instant};
use tracing::debug;

/// How often the server pings a quiet connection.
pub(crate) const PING_EVERY: Duration = Duration::from_secs(15);
/// A connection silent this long (no pong either) is closed.
pub(crate) const SILENT_FOR: Duration = Duration::from_secs(45);
/// Dropped messages in a row after which a flooding connection is closed.
pub(crate) const FLOOD_CLOSE_AFTER: u32 = 200;

/// How long a new connection has to say hello.
pub(crate) const HELLO_WITHIN: Duration = Duration::from_secs(10);

/// The query of `/ws`.
#[derive(Debug, Deserialize)]
pub struct WsQuery {
    #[serde(rename = "match")]
    pub match_id: String,
    /// Only read to refuse it: the token belongs in the hello.
    token: Option<String>,
}

/// Counts an open connection for as long as it lives.
struct ConnectionGuard(std::sync::Arc<crate::metrics::Metrics>);

impl Drop for ConnectionGuard {
    fn drop(&mut self) {
        self.0.connection_closed();
    }
}

/// What identifies a connection's TCP socket, kept in the connection's
/// data by [`on_connect`], so that a session stuck on a client that
/// stopped reading can shut the connection down. No descriptor is held
/// (that would double each connection's descriptors): the number, and the
/// addresses that prove a descriptor of that number is still this socket.
#[derive(Clone, Debug)]
pub struct ConnSocket(Arc<SocketId>);

#[derive(Debug)]
struct SocketId {
    #[cfg(unix)]
    fd: std::os::fd::RawFd,
    local: std::net::SocketAddr,
    peer: std::net::SocketAddr,
}

impl ConnSocket {
    /// Shuts the TCP connection down both ways: the HTTP server's pending
    /// writes fail, it drops the connection, and the client sees it close.
    /// It duplicates the descriptor first and checks that the duplicate is
    /// the same connection (same local and peer address), so a number the
    /// HTTP server closed and reused meanwhile is left alone.
    fn shut_down(&self) {
        #[cfg(unix)]
        {
            use std::os::fd::{FromRawFd, OwnedFd};
            // SAFETY: dup(2) of any number is sound: a closed one fails
            // with EBADF, an open one gives a new descriptor...
            let dup = unsafe { libc::dup(self.0.fd) };
            if dup < 0 {
                return;
            }
            // ... which nobody else owns: it is closed when this drops.
            let stream = std::net::TcpStream::from(unsafe { OwnedFd::from_raw_fd(dup) });
            let same = stream.local_addr().ok() == Some(self.0.local)
                && stream.peer_addr().ok() == Some(self.0.peer);
            if same {
                let _ = stream.shutdown(std::net::Shutdown::Both);
            }
        }
    }
}

/// For [`actix_web::HttpServer::on_connect`]: keeps a [`ConnSocket`] of
/// each TCP connection.
pub fn on_connect(conn: &dyn std::any::Any, data: &mut actix_web::dev::Extensions) {
    #[cfg(unix)]
    if let Some(tcp) = conn.downcast_ref::<actix_web::rt::net::TcpStream>() {
        use std::os::fd::AsRawFd;
        match (tcp.local_addr(), tcp.peer_addr()) {
            (Ok(local), Ok(peer)) => {
                data.insert(ConnSocket(Arc::new(SocketId {
                    fd: tcp.as_raw_fd(),
                    local,
                    peer,
                })));
            }
            _ => debug!("a connection without addresses cannot be shut down if stuck"),
        }
    }
    #[cfg(not(unix))]
    let _ = (conn, data);
}

/// Whether a WebSocket read failed on the size limit: one frame above it
/// (`Overflow`), or a message fragmented into continuation frames that add
/// up to more (actix-ws reports that one only as an I/O error with this
/// text, having no variant of its own for it).
pub(crate) fn too_large(e: &ProtocolError) -> bool {
    match e {
        ProtocolError::Overflow => true,
        ProtocolError::Io(io) => io.to_string().contains("maximum continuation size"),
        _ => false,
    }
}

/// Writes within the write timeout; `false`: the socket is gone or stuck.
pub(crate) async fn timely<E>(limit: Duration, write: impl Future<Output = Result<(), E>>) -> bool {
    matches!(tokio::time::timeout(limit, write).await, Ok(Ok(())))
}

pub(crate) fn http_refusal(r: &Refusal) -> HttpResponse {
    let status = actix_web::http::StatusCode::from_u16(r.http_status())
        .unwrap_or(actix_web::http::StatusCode::BAD_REQUEST);
    HttpResponse::build(status)
        .content_type("application/json")
        .body(r.to_message().to_json())
}

/// `GET /ws`: upgrades to a WebSocket session.
pub async fn handler(
    req: HttpRequest,
    body: web::Payload,
    hub: web::Data<Hub>,
) -> Result<HttpResponse, actix_web::Error> {
    let query = match web::Query::<WsQuery>::from_query(req.query_string()) {
        Ok(q) => q.into_inner(),
        Err(e) => {
            return Ok(http_refusal(&Refusal::new(
                ErrorCode::BadMessage,
                format!("expected /ws?match=ID: {e}"),
            )))
        }
    };
    if query.token.is_some() {
        return Ok(http_refusal(&Refusal::new(
            ErrorCode::BadMessage,
            "the seat token goes in the hello message, never in the URL \
             (URLs end up in logs); connect to /ws?match=ID",
        )));
    }
    let admitted = match admit(&req, &hub) {
        Ok(a) => a,
        Err(r) => return Ok(http_refusal(&r)),
    };
    let browser = crate::web::auth::from_browser(&req);
    let (response, session, stream) = actix_ws::handle(&req, body)?;
    let hub = hub.get_ref().clone();
    actix_web::rt::spawn(async move {
        let stuck = run(hub.clone(), query, browser, session, stream).await;
        admitted.release(&hub, stuck).await;
    });
    Ok(response)
}

/// A WebSocket connection counted against the server's and its address's
/// limits for as long as it lives.
pub(crate) struct Admitted {
    guards: (ConnectionGuard, AddressGuard),
    socket: Option<ConnSocket>,
}

/// Counts a WebSocket connection about to be upgraded, or the answer that
/// refuses it (`server-busy`: too many connections, in all or from its
/// address).
pub(crate) fn admit(req: &HttpRequest, hub: &Hub) -> Result<Admitted, Refusal> {
    let metrics = hub.metrics().clone();
    metrics.connection_opened();
    let guard = ConnectionGuard(metrics.clone());
    if metrics.connections() > hub.limits().max_connections as i64 {
        return Err(Refusal::new(
            ErrorCode::ServerBusy,
            "the server holds as many connections as it can; try later",
        ));
    }
    let addr = crate::web::ratelimit::client_ip(req);
    let Some(address_guard) = hub.admit_address(addr) else {
        return Err(Refusal::new(
            ErrorCode::ServerBusy,
            "this address holds as many connections as it may; try later",
        ));
    };
    Ok(Admitted {
        guards: (guard, address_guard),
        socket: req.conn_data::<ConnSocket>().cloned(),
    })
}

impl Admitted {
    /// After the session: see [`release`].
    pub(crate) async fn release(self, hub: &Hub, stuck: bool) {
        if let Some(socket) = self.socket {
            release(hub, socket, stuck, self.guards).await;
        }
    }
}

/// After a session: a socket whose writes got stuck is shut down at once;
/// otherwise the HTTP server gets one write timeout to flush the last
/// messages and close it, and is cut off after that. The connection counts
/// drop when the socket is gone.
async fn release(
    hub: &Hub,
    socket: ConnSocket,
    stuck: bool,
    guards: (ConnectionGuard, AddressGuard),
) {
    if !stuck {
        let deadline = tokio::time::Instant::now() + hub.limits().write_timeout;
        // The HTTP server holds the other handle until it drops the connection.
        while Arc::strong_count(&socket.0) > 1 && tokio::time::Instant::now() < deadline {
            tokio::time::sleep(Duration::from_millis(50)).await;
        }
        if Arc::strong_count(&socket.0) == 1 {
            drop(guards);
            return;
        }
    }
    debug!("shutting down a connection that does not take what is written to it");
    socket.shut_down();
    drop(guards);
}

async fn send(session: &mut Session, limit: Duration, msg: &ServerMessage) -> bool {
    timely(limit, session.text(msg.to_json())).await
}

/// Runs one session; `true` when it ended on a write that could not finish
/// in time (the socket is stuck).
async fn run(
    hub: Hub,
    query: WsQuery,
    browser: bool,
    mut session: Session,
    stream: actix_ws::MessageStream,
) -> bool {
    let limits = hub.limits().clone();
    let wt = limits.write_timeout;
    let mut stream = stream
        .max_frame_size(limits.max_message_bytes)
        .aggregate_continuations()
        .max_continuation_size(limits.max_message_bytes);
    let claim = match hello(&mut stream, &mut session, wt).await {
        Opening::Hello(Some(token), _) => Ok(Claim::Token(token)),
        Opening::Hello(None, Some(key)) => account_claim(&hub, key, browser).await,
        Opening::Hello(None, None) => Ok(Claim::Watch),
        Opening::Stuck => return true,
        Opening::Refused(r, code) => {
            hub.metrics().refused();
            if !send(&mut session, wt, &r.to_message()).await {
                return true;
            }
            let reason = CloseReason {
                code,
                description: Some(r.code.as_str().into()),
            };
            return !timely(wt, session.close(Some(reason))).await;
        }
    };
    let connected = match claim {
        Ok(claim) => hub.connect_as(&query.match_id, claim).await,
        Err(r) => Err(r),
    };
    let (room, connected) = match connected {
        Ok(c) => c,
        Err(r) => {
            hub.metrics().refused();
            if !send(&mut session, wt, &r.to_message()).await {
                return true;
            }
            let reason = CloseReason {
                code: CloseCode::Policy,
                description: Some(r.code.as_str().into()),
            };
            return !timely(wt, session.close(Some(reason))).await;
        }
    };
    // Before the room's first message (the match state) is forwarded.
    let welcome = ServerMessage::Welcome {
        protocol: PROTOCOL_VERSION,
    };
    if !send(&mut session, wt, &welcome).await {
        let _ = room
            .tx
            .send(Command::Disconnect {
                conn: connected.conn,
            })
            .await;
        return true;
    }
    let conn = connected.conn;
    let mut rx = connected.rx;
    let refused = connected.refused;
    let mut refused_seen = 0u32;
    let mut bucket = TokenBucket::new(limits.rate_per_sec, limits.rate_burst, Instant::now());
    let mut ping = tokio::time::interval(PING_EVERY);
    let mut last_heard = Instant::now();
    // Set when a write did not finish in time.
    let mut stuck = false;
    let reason: Option<CloseReason> = loop {
        tokio::select! {
            out = rx.recv() => match out {
                Some(text) => {
                    if !timely(wt, session.text(text)).await {
                        stuck = true;
                        break None;
                    }
                }
                None => break Some(CloseReason {
                    code: CloseCode::Away,
                    description: Some("the match closed this connection".into()),
                }),
            },
            frame = stream.recv() => {
                last_heard = Instant::now();
                match frame {
                    None | Some(Ok(AggregatedMessage::Close(_))) => break None,
                    Some(Ok(AggregatedMessage::Ping(b))) => {
                        if !timely(wt, session.pong(&b)).await {
                            stuck = true;
                            break None;
                        }
                    }
                    Some(Ok(AggregatedMessage::Pong(_))) => {}
                    Some(Ok(AggregatedMessage::Text(text))) => {
                        // Moves the match refused since the last message
                        // are charged now: junk pays, legal play does not.
                        let now = Instant::now();
                        let count = refused.load(std::sync::atomic::Ordering::Relaxed);
                        bucket.charge(count.wrapping_sub(refused_seen), now);
                        refused_seen = count;
                        let parsed = ClientMessage::from_json(&text);
                        let play = matches!(&parsed, Ok(m) if m.is_move());
                        if play && bucket.bankrupt() {
                            break Some(CloseReason {
                                code: CloseCode::Policy,
                                description: Some("rate-limited".into()),
                            });
                        }
                        if !play && !bucket.take(now) {
                            if let Some(r) = flooded(&hub, &mut session, wt, &bucket).await {
                                break Some(r);
                            }
                            continue;
                        }
                        if !handle_message(&hub, &room, conn, &mut session, wt, parsed).await {
                            stuck = true;
                            break None;
                        }
                    }
                    Some(Ok(AggregatedMessage::Binary(_))) => {
                        if !bucket.take(Instant::now()) {
                            if let Some(r) = flooded(&hub, &mut session, wt, &bucket).await {
                                break Some(r);
                            }
                            continue;
                        }
                        hub.metrics().refused();
                        let r = Refusal::new(ErrorCode::BadMessage, "messages are JSON text frames");
                        if !send(&mut session, wt, &r.to_message()).await {
                            stuck = true;
                            break None;
                        }
                    }
                    Some(Err(e)) if too_large(&e) => {
                        hub.metrics().refused();
                        let r = Refusal::new(
                            ErrorCode::MessageTooLarge,
                            format!("messages are at most {} bytes", limits.max_message_bytes),
                        );
                        if !send(&mut session, wt, &r.to_message()).await {
                            stuck = true;
                        }
                        break Some(CloseReason {
                            code: CloseCode::Size,
                            description: Some(r.code.as_str().into()),
                        });
                    }
                    Some(Err(e)) => {
                        debug!(error = %e, "websocket protocol error");
                        break Some(CloseReason {
                            code: CloseCode::Protocol,
                            description: None,
                        });
                    }
                }
            }
            _ = ping.tick() => {
                if last_heard.elapsed() > SILENT_FOR {
                    break Some(CloseReason {
                        code: CloseCode::Away,
                        description: Some("no answer to pings".into()),
                    });
                }
                if !timely(wt, session.ping(b"")).await {
                    stuck = true;
                    break None;
                }
            }
        }
    };
    let _ = room.tx.send(Command::Disconnect { conn }).await;
    if stuck {
        return true;
    }
    !timely(wt, session.close(reason)).await
}

/// The seat the account that `key` proves holds (a bot's key from a web
/// page is refused).
async fn account_claim(hub: &Hub, key: SeatToken, browser: bool) -> Result<Claim, Refusal> {
    let account = crate::web::auth::account_of_key(hub, key, browser).await?;
    Ok(Claim::Account(account.name))
}

/// How a connection's opening went.
enum Opening {
    /// It said hello in the protocol this server speaks, with this token.
    Hello(Option<SeatToken>, Option<SeatToken>),
    /// It must be refused with this, and closed with this code.
    Refused(Refusal, CloseCode),
    /// A write did not finish in time, or the client went away.
    Stuck,
}

/// Waits (at most [`HELLO_WITHIN`]) for the client's `hello`, answering
/// pings meanwhile. Anything else first is refused with `no-hello`.
async fn hello(
    stream: &mut actix_ws::AggregatedMessageStream,
    session: &mut Session,
    wt: Duration,
) -> Opening {
    let no_hello = |what: &str| {
        Opening::Refused(
            Refusal::new(
                ErrorCode::NoHello,
                format!(
                    "{what}: a connection opens with {{\"type\":\"hello\",\"protocol\":\
                     {PROTOCOL_VERSION},\"name\":...,\"token\":...}} (no token: watch)"
                ),
            ),
            CloseCode::Policy,
        )
    };
    let deadline = tokio::time::Instant::now() + HELLO_WITHIN;
    loop {
        let frame = match tokio::time::timeout_at(deadline, stream.recv()).await {
            Err(_) => return no_hello("no hello within 10 s"),
            Ok(frame) => frame,
        };
        match frame {
            None | Some(Ok(AggregatedMessage::Close(_))) => return Opening::Stuck,
            Some(Ok(AggregatedMessage::Ping(b))) => {
                if !timely(wt, session.pong(&b)).await {
                    return Opening::Stuck;
                }
            }
            Some(Ok(AggregatedMessage::Pong(_))) => {}
            Some(Ok(AggregatedMessage::Text(text))) => {
                return match ClientMessage::from_json(&text) {
                    Ok(ClientMessage::Hello {
                        protocol,
                        token,
                        key,
                        ..
                    }) if protocol == PROTOCOL_VERSION => Opening::Hello(token, key),
                    Ok(ClientMessage::Hello { .. }) => Opening::Refused(
                        Refusal::new(
                            ErrorCode::UnsupportedProtocol,
                            format!("this server speaks protocol {PROTOCOL_VERSION}"),
                        ),
                        CloseCode::Policy,
                    ),
                    Ok(_) => no_hello("the first message was not a hello"),
                    Err(e) => Opening::Refused(Refusal::new(e.code, e.message), CloseCode::Policy),
                }
            }
            Some(Ok(AggregatedMessage::Binary(_))) => {
                return no_hello("messages are JSON text frames")
            }
            Some(Err(e)) if too_large(&e) => {
                return Opening::Refused(
                    Refusal::new(ErrorCode::MessageTooLarge, "the hello is too large"),
                    CloseCode::Size,
                )
            }
            Some(Err(_)) => return Opening::Stuck,
        }
    }
}

/// Answers a dropped message; closes a connection that floods on.
async fn flooded(
    hub: &Hub,
    session: &mut Session,
    wt: Duration,
    bucket: &TokenBucket,
) -> Option<CloseReason> {
    hub.metrics().refused();
    let close = Some(CloseReason {
        code: CloseCode::Policy,
        description: Some("rate-limited".into()),
    });
    if bucket.dropped_in_a_row >= FLOOD_CLOSE_AFTER {
        return close;
    }
    // One warning per run of drops, not one per dropped message.
    if bucket.dropped_in_a_row == 1 {
        let r = Refusal::new(
            ErrorCode::RateLimited,
            "too many messages; this one was dropped, slow down",
        );
        if !send(session, wt, &r.to_message()).await {
            return close;
        }
    }
    None
}

/// Handles one text message as read; `false` if the session is gone.
async fn handle_message(
    hub: &Hub,
    room: &RoomHandle,
    conn: u64,
    session: &mut Session,
    wt: Duration,
    parsed: Result<ClientMessage, game::protocol::ProtocolError>,
) -> bool {
    match parsed {
        Err(e) => {
            hub.metrics().refused();
            send(session, wt, &e.to_message()).await
        }
        Ok(ClientMessage::Hello { .. }) => {
            hub.metrics().refused();
            let r = Refusal::new(
                ErrorCode::BadMessage,
                "hello is the first message of a connection, and only the first",
            );
            send(session, wt, &r.to_message()).await
        }
        Ok(msg) => room.tx.send(Command::message(conn, msg)).await.is_ok(),
    }
}
