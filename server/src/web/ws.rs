//! The WebSocket endpoint `/ws?match=ID`. On a node of a cluster, a
//! client that adds `&follow=1` is answered `307` to the node that plays
//! its match when that node has a public URL (`--public-url`), instead of
//! being relayed to it; a browser, whose WebSocket cannot follow a
//! redirect, asks `GET /api/matches/ID/socket` ([`socket`]) for that
//! node's socket first and opens it itself. The client's first message is a
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
use crate::play::room::{Claim, Command, Inbox};
use crate::refusal::{HttpStatus, Refusal};
use crate::web::pump;
use actix_web::{web, HttpRequest, HttpResponse};
use actix_ws::{CloseCode, CloseReason, Session};
use bytestring::ByteString;
use game::protocol::{ClientMessage, ErrorCode, ServerMessage, PROTOCOL_VERSION};
use game::token::SeatToken;
use serde::Deserialize;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::Arc;
use std::time::Duration;
use tracing::debug;

/// The query of `/ws`.
#[derive(Debug, Deserialize)]
pub struct WsQuery {
    #[serde(rename = "match")]
    pub match_id: String,
    /// Only read to refuse it: the token belongs in the hello.
    token: Option<String>,
    /// Present (any value): the client follows a `307` to the node that
    /// plays the match (a node of a cluster sends it there when it knows
    /// that node's public URL; otherwise it relays, as for every client).
    follow: Option<String>,
}

/// The answer sending a client that follows redirects to the node that
/// plays its match: `307` to that node's `/ws` for the match (`base` is
/// its public URL, `http` becoming `ws` and `https` `wss`), still asking
/// to be sent on should the match have moved again.
fn sent_to(base: &str, match_id: &str) -> HttpResponse {
    let location = format!("{}&follow=1", socket_url(base, match_id));
    HttpResponse::TemporaryRedirect()
        .insert_header((actix_web::http::header::LOCATION, location))
        .insert_header((actix_web::http::header::CACHE_CONTROL, "no-store"))
        .finish()
}

/// The socket of match `match_id` on the node whose public URL is `base`
/// (`http` becoming `ws` and `https` `wss`).
fn socket_url(base: &str, match_id: &str) -> String {
    let ws = match base.strip_prefix("https://") {
        Some(rest) => format!("wss://{rest}"),
        None => format!("ws://{}", base.strip_prefix("http://").unwrap_or(base)),
    };
    format!("{ws}/ws?match={match_id}")
}

/// The answer of [`socket`].
#[derive(Debug, serde::Serialize)]
struct SocketAt {
    match_id: String,
    /// The owner's socket, or `None`: connect to this node's `/ws`.
    url: Option<String>,
}

/// `GET /api/matches/{id}/socket`: where a browser had better open its
/// socket for the match. On a node of a cluster, when another node plays
/// the match and has a public URL, that node's socket (`{"url":
/// "wss://.../ws?match=ID"}`, counted as a client routed there); otherwise
/// `{"url": null}`: this node's own `/ws` (it plays the match, takes it,
/// or relays to its owner). A malformed id is refused (`bad-message`).
pub async fn socket(hub: web::Data<Hub>, id: web::Path<String>) -> HttpResponse {
    let match_id = id.into_inner();
    if !crate::token::is_match_id(&match_id) {
        return http_refusal(&Refusal::new(
            ErrorCode::BadMessage,
            "a match id is 1 to 64 letters, digits and dashes",
        ));
    }
    let url = hub
        .route(&match_id)
        .await
        .map(|base| socket_url(&base, &match_id));
    let mut answer =
        crate::web::reply::json(actix_web::http::StatusCode::OK, &SocketAt { match_id, url });
    // The owner changes when a node stops: never cached.
    answer.headers_mut().insert(
        actix_web::http::header::CACHE_CONTROL,
        actix_web::http::header::HeaderValue::from_static("no-store"),
    );
    answer
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
    // Sent to the node that plays the match (before counting it: this
    // node holds no connection for it).
    if query.follow.is_some() {
        if let Some(base) = hub.route(&query.match_id).await {
            return Ok(sent_to(&base, &query.match_id));
        }
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
    let addr = crate::web::client_addr::limit_key(req);
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

/// Runs one session; `true` when it ended on a write that could not finish
/// in time (the socket is stuck).
async fn run(
    hub: Hub,
    query: WsQuery,
    browser: bool,
    session: Session,
    stream: actix_ws::MessageStream,
) -> bool {
    let limits = hub.limits().clone();
    let metrics = hub.metrics().clone();
    let door = MatchDoor {
        hub,
        match_id: query.match_id,
        browser,
    };
    pump::serve(door, &limits, &metrics, session, stream).await
}

/// How a match's socket opens: a `hello` with a seat token (a player), an
/// account key (the account's seat), or neither (a spectator), admitted to
/// the match's room and answered `welcome`.
struct MatchDoor {
    hub: Hub,
    match_id: String,
    browser: bool,
}

impl pump::Door for MatchDoor {
    type Message = ClientMessage;
    type Endpoint = MatchEndpoint;
    type Outbox = Inbox;

    async fn open(
        self,
        hello: ClientMessage,
        writer: &mut pump::Writer,
    ) -> Result<(MatchEndpoint, Inbox), pump::Error> {
        let claim = match hello {
            ClientMessage::Hello {
                protocol,
                token,
                key,
                name,
            } if protocol == PROTOCOL_VERSION => match (token, key) {
                (Some(token), _) => Claim::Token(token),
                (None, Some(key)) => account_claim(&self.hub, key, self.browser).await?,
                (None, None) => Claim::Watch(name),
            },
            ClientMessage::Hello { .. } => {
                return Err(Refusal::new(
                    ErrorCode::UnsupportedProtocol,
                    format!("this server speaks protocol {PROTOCOL_VERSION}"),
                )
                .into())
            }
            _ => return Err(self.no_hello("the first message was not a hello").into()),
        };
        let (room, connected) = self.hub.connect_as(&self.match_id, claim).await?;
        // Before the room's first message (the match state) is forwarded.
        let welcome = ServerMessage::Welcome {
            protocol: PROTOCOL_VERSION,
        };
        if let Err(gone) = writer.say(welcome.to_json()).await {
            let _ = room
                .tx
                .send(Command::Disconnect {
                    conn: connected.conn,
                })
                .await;
            return Err(gone);
        }
        let endpoint = MatchEndpoint {
            room,
            conn: connected.conn,
            refused: connected.refused,
            refused_seen: 0,
        };
        Ok((endpoint, connected.rx))
    }

    fn no_hello(&self, why: &str) -> Refusal {
        Refusal::new(
            ErrorCode::NoHello,
            format!(
                "{why}: a connection opens with {{\"type\":\"hello\",\"protocol\":\
                 {PROTOCOL_VERSION},\"name\":...,\"token\":...}} (no token: watch)"
            ),
        )
    }
}

/// The room's messages to this connection, as they come.
impl pump::Outbox for Inbox {
    async fn next(&mut self) -> Option<ByteString> {
        self.recv().await
    }
}

/// An open match connection: its messages go to the room. Moves pass the
/// flood guard free and pay only when the room refuses them.
struct MatchEndpoint {
    room: RoomHandle,
    conn: u64,
    /// How many of this connection's moves the room has refused...
    refused: Arc<AtomicU32>,
    /// ... of which this many are charged already.
    refused_seen: u32,
}

impl pump::Endpoint for MatchEndpoint {
    type Message = ClientMessage;

    async fn on_message(&mut self, msg: ClientMessage) -> Result<(), pump::Error> {
        if let ClientMessage::Hello { .. } = msg {
            return Err(Refusal::new(
                ErrorCode::BadMessage,
                "hello is the first message of a connection, and only the first",
            )
            .into());
        }
        let command = Command::message(self.conn, msg);
        self.room
            .tx
            .send(command)
            .await
            .map_err(|_| pump::Error::Gone)
    }

    fn pays_later(&self, msg: &ClientMessage) -> bool {
        msg.is_move()
    }

    fn debt(&mut self) -> u32 {
        let count = self.refused.load(Ordering::Relaxed);
        let debt = count.wrapping_sub(self.refused_seen);
        self.refused_seen = count;
        debt
    }

    fn outbox_closed(&self) -> CloseReason {
        CloseReason {
            code: CloseCode::Away,
            description: Some("the match closed this connection".into()),
        }
    }

    async fn on_close(&mut self) {
        let _ = self
            .room
            .tx
            .send(Command::Disconnect { conn: self.conn })
            .await;
    }
}

/// The seat the account that `key` proves holds (a bot's key from a web
/// page is refused).
async fn account_claim(hub: &Hub, key: SeatToken, browser: bool) -> Result<Claim, Refusal> {
    let account = crate::web::auth::account_of_key(hub, key, browser).await?;
    Ok(Claim::Account(account.name))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn location(r: &HttpResponse) -> &str {
        r.headers()
            .get(actix_web::http::header::LOCATION)
            .and_then(|v| v.to_str().ok())
            .unwrap_or_default()
    }

    #[test]
    fn a_client_is_sent_to_the_owners_socket_on_its_public_url_with_the_scheme_of_a_websocket() {
        let r = sent_to("https://play.example/n/node-1", "m123");
        assert_eq!(r.status(), actix_web::http::StatusCode::TEMPORARY_REDIRECT);
        assert_eq!(
            location(&r),
            "wss://play.example/n/node-1/ws?match=m123&follow=1"
        );
        let r = sent_to("http://10.0.0.5:8080", "m123");
        assert_eq!(location(&r), "ws://10.0.0.5:8080/ws?match=m123&follow=1");
    }

    #[test]
    fn a_browser_is_given_the_owners_socket_without_the_follow_flag() {
        assert_eq!(
            socket_url("https://play.example/n/node-1", "m123"),
            "wss://play.example/n/node-1/ws?match=m123"
        );
        assert_eq!(
            socket_url("http://10.0.0.5:8080", "m123"),
            "ws://10.0.0.5:8080/ws?match=m123"
        );
    }
}
