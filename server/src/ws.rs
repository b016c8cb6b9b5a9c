//! The WebSocket endpoint `/ws?match=ID&token=T` (no token: a spectator).
//! A session admits the connection to its match room, forwards everything
//! the room sends (the full `match-state` first), and reads the client's
//! messages: it refuses oversized frames, malformed JSON, unknown messages
//! and floods (a token bucket per connection) itself, with an `error` of a
//! stable code, and passes every match message to the room. Moves are
//! never dropped by the flood guard: they pay only when the room refuses
//! them, and a connection whose refused moves run the bucket bankrupt is
//! closed. A connection
//! that stops answering pings, floods on after warnings, or cannot keep up
//! with the match is closed.

use crate::hub::{Hub, RoomHandle};
use crate::ratelimit::TokenBucket;
use crate::refusal::{HttpStatus, Refusal};
use crate::room::Command;
use actix_web::{web, HttpRequest, HttpResponse};
use actix_ws::{AggregatedMessage, CloseCode, CloseReason, ProtocolError, Session};
use game::protocol::{ClientMessage, ErrorCode, ServerMessage, PROTOCOL_VERSION};
use serde::Deserialize;
use std::time::{Duration, Instant};
use tracing::debug;

/// How often the server pings a quiet connection.
const PING_EVERY: Duration = Duration::from_secs(15);
/// A connection silent this long (no pong either) is closed.
const SILENT_FOR: Duration = Duration::from_secs(45);
/// Dropped messages in a row after which a flooding connection is closed.
const FLOOD_CLOSE_AFTER: u32 = 200;

/// The query of `/ws`.
#[derive(Debug, Deserialize)]
pub struct WsQuery {
    #[serde(rename = "match")]
    pub match_id: String,
    pub token: Option<String>,
}

/// Counts an open connection for as long as it lives.
struct ConnectionGuard(std::sync::Arc<crate::metrics::Metrics>);

impl Drop for ConnectionGuard {
    fn drop(&mut self) {
        self.0.connection_closed();
    }
}

fn http_refusal(r: &Refusal) -> HttpResponse {
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
                format!("expected /ws?match=ID[&token=T]: {e}"),
            )))
        }
    };
    let metrics = hub.metrics().clone();
    metrics.connection_opened();
    let guard = ConnectionGuard(metrics.clone());
    if metrics.connections() > hub.limits().max_connections as i64 {
        return Ok(http_refusal(&Refusal::new(
            ErrorCode::ServerBusy,
            "the server holds as many connections as it can; try later",
        )));
    }
    let (response, session, stream) = actix_ws::handle(&req, body)?;
    let hub = hub.get_ref().clone();
    actix_web::rt::spawn(async move {
        let _guard = guard;
        run(hub, query, session, stream).await;
    });
    Ok(response)
}

async fn send(session: &mut Session, msg: &ServerMessage) -> bool {
    session.text(msg.to_json()).await.is_ok()
}

async fn run(hub: Hub, query: WsQuery, mut session: Session, stream: actix_ws::MessageStream) {
    let limits = hub.limits().clone();
    let mut stream = stream
        .max_frame_size(limits.max_message_bytes)
        .aggregate_continuations()
        .max_continuation_size(limits.max_message_bytes);
    let (room, connected) = match hub.connect(&query.match_id, query.token).await {
        Ok(c) => c,
        Err(r) => {
            hub.metrics().refused();
            let _ = send(&mut session, &r.to_message()).await;
            let reason = CloseReason {
                code: CloseCode::Policy,
                description: Some(r.code.as_str().into()),
            };
            let _ = session.close(Some(reason)).await;
            return;
        }
    };
    let conn = connected.conn;
    let mut rx = connected.rx;
    let refused = connected.refused;
    let mut refused_seen = 0u32;
    let mut bucket = TokenBucket::new(limits.rate_per_sec, limits.rate_burst, Instant::now());
    let mut ping = tokio::time::interval(PING_EVERY);
    let mut last_heard = Instant::now();
    let reason: Option<CloseReason> = loop {
        tokio::select! {
            out = rx.recv() => match out {
                Some(text) => {
                    if session.text(&*text).await.is_err() {
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
                        if session.pong(&b).await.is_err() {
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
                            if let Some(r) = flooded(&hub, &mut session, &bucket).await {
                                break Some(r);
                            }
                            continue;
                        }
                        if !handle_message(&hub, &room, conn, &mut session, parsed).await {
                            break None;
                        }
                    }
                    Some(Ok(AggregatedMessage::Binary(_))) => {
                        if !bucket.take(Instant::now()) {
                            if let Some(r) = flooded(&hub, &mut session, &bucket).await {
                                break Some(r);
                            }
                            continue;
                        }
                        hub.metrics().refused();
                        let r = Refusal::new(ErrorCode::BadMessage, "messages are JSON text frames");
                        if !send(&mut session, &r.to_message()).await {
                            break None;
                        }
                    }
                    Some(Err(ProtocolError::Overflow)) => {
                        hub.metrics().refused();
                        let r = Refusal::new(
                            ErrorCode::MessageTooLarge,
                            format!("messages are at most {} bytes", limits.max_message_bytes),
                        );
                        let _ = send(&mut session, &r.to_message()).await;
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
                if session.ping(b"").await.is_err() {
                    break None;
                }
            }
        }
    };
    let _ = room.tx.send(Command::Disconnect { conn }).await;
    let _ = session.close(reason).await;
}

/// Answers a dropped message; closes a connection that floods on.
async fn flooded(hub: &Hub, session: &mut Session, bucket: &TokenBucket) -> Option<CloseReason> {
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
        if !send(session, &r.to_message()).await {
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
    parsed: Result<ClientMessage, game::protocol::ProtocolError>,
) -> bool {
    match parsed {
        Err(e) => {
            hub.metrics().refused();
            send(session, &e.to_message()).await
        }
        Ok(ClientMessage::Hello { protocol, .. }) => {
            if protocol == PROTOCOL_VERSION {
                send(
                    session,
                    &ServerMessage::Welcome {
                        protocol: PROTOCOL_VERSION,
                    },
                )
                .await
            } else {
                hub.metrics().refused();
                let r = Refusal::new(
                    ErrorCode::UnsupportedProtocol,
                    format!("this server speaks protocol {PROTOCOL_VERSION}"),
                );
                send(session, &r.to_message()).await
            }
        }
        Ok(msg) => room.tx.send(Command::message(conn, msg)).await.is_ok(),
    }
}
