//! The loop that pumps one WebSocket, shared by a match's socket
//! ([`crate::web::ws`]) and the lobby's event stream
//! ([`crate::web::stream`]). It owns everything about the socket itself:
//! frames read with the size cap (one oversized message is refused with
//! `message-too-large` and closes the connection), text only (a binary
//! frame is refused with `bad-message`), the opening `hello` within
//! [`HELLO_WITHIN`], pings every [`PING_EVERY`] and the close of a
//! connection silent for [`SILENT_FOR`], the per-connection token bucket
//! (a dropped message is answered `rate-limited` once per run of drops;
//! [`FLOOD_CLOSE_AFTER`] drops in a row, or a drop after
//! [`FLOOD_SUSTAINED_FOR`] above the rate, close the connection), every
//! write under the write timeout (one that cannot finish ends the session
//! as stuck), the outbound queue, JSON decoding with a typed refusal, the
//! close codes and reasons, and the counting of refused messages.
//!
//! What differs between the endpoints is theirs, behind three small
//! traits: a [`Door`] turns the first message into an open connection, an
//! [`Endpoint`] handles each message after it, and an [`Outbox`] is the
//! queue of what the connection is to be sent.

use crate::config::Limits;
use crate::metrics::Metrics;
use crate::refusal::Refusal;
use crate::web::ratelimit::TokenBucket;
use actix_ws::{AggregatedMessage, CloseCode, CloseReason, ProtocolError, Session};
use bytestring::ByteString;
use game::protocol::ErrorCode;
use serde::de::DeserializeOwned;
use std::future::Future;
use std::time::{Duration, Instant};
use tracing::debug;

/// How often the server pings a quiet connection.
pub(crate) const PING_EVERY: Duration = Duration::from_secs(15);
/// A connection silent this long (no pong either) is closed.
pub(crate) const SILENT_FOR: Duration = Duration::from_secs(45);
/// Dropped messages in a row after which a flooding connection is closed.
pub(crate) const FLOOD_CLOSE_AFTER: u32 = 200;
/// How long a connection may keep sending above the sustained rate (from
/// its first dropped message, until it pauses long enough for its bucket
/// to refill in full): a message dropped after that closes it. A flood
/// just over the rate drops too few messages in a row to be closed by
/// [`FLOOD_CLOSE_AFTER`], and is closed by this instead.
pub(crate) const FLOOD_SUSTAINED_FOR: Duration = Duration::from_secs(10);
/// How long a new connection has to say hello.
pub(crate) const HELLO_WITHIN: Duration = Duration::from_secs(10);

/// Why an endpoint did not take a message (or its opening).
#[derive(Debug, thiserror::Error)]
pub(crate) enum Error {
    /// The message is refused: the pump counts it, answers this `error`
    /// and reads on (during the opening: answers it and closes).
    #[error(transparent)]
    Refused(#[from] Refusal),
    /// The socket, or what the endpoint serves, is gone: the session ends
    /// at once, without a close frame, as stuck.
    #[error("the connection is gone")]
    Gone,
}

/// The writing end of a connection, as a [`Door`] sees it while opening.
pub(crate) struct Writer {
    session: Session,
    write_timeout: Duration,
}

impl Writer {
    /// Writes one text message within the write timeout; [`Error::Gone`]
    /// when it cannot.
    pub(crate) async fn say(&mut self, text: impl Into<ByteString>) -> Result<(), Error> {
        if timely(self.write_timeout, self.session.text(text)).await {
            Ok(())
        } else {
            Err(Error::Gone)
        }
    }

    async fn refuse(&mut self, r: &Refusal) -> Result<(), Error> {
        self.say(refusal_text(r)).await
    }

    async fn pong(&mut self, payload: &[u8]) -> bool {
        timely(self.write_timeout, self.session.pong(payload)).await
    }

    async fn ping(&mut self) -> bool {
        timely(self.write_timeout, self.session.ping(b"")).await
    }

    /// Closes with `reason`; `true` when the close could not be written
    /// in time (the socket is stuck).
    async fn close(self, reason: Option<CloseReason>) -> bool {
        !timely(self.write_timeout, self.session.close(reason)).await
    }
}

/// What a connection is to be sent: the queue its endpoint fills.
pub(crate) trait Outbox {
    /// The next text to write, in order; `None` once the queue is closed
    /// (the connection then closes with [`Endpoint::outbox_closed`]).
    /// It races the socket's reads, so it must be cancel-safe: a call
    /// dropped before it finished loses nothing.
    async fn next(&mut self) -> Option<ByteString>;
}

/// How a connection opens: its first message, the hello, turned into an
/// open [`Endpoint`] and its [`Outbox`].
pub(crate) trait Door {
    /// The messages the client sends (decoded from JSON by the pump).
    type Message: DeserializeOwned;
    /// What the open connection's messages go to.
    type Endpoint: Endpoint<Message = Self::Message>;
    /// What the open connection is sent.
    type Outbox: Outbox;

    /// Opens the connection with its first message, which should be the
    /// hello, writing whatever must come before the outbox's first message
    /// (the `welcome`) through `writer`. [`Error::Refused`]: the pump
    /// counts the refusal, answers it and closes with `policy`;
    /// [`Error::Gone`]: a write did not finish, and `open` has undone what
    /// it opened.
    async fn open(
        self,
        hello: Self::Message,
        writer: &mut Writer,
    ) -> Result<(Self::Endpoint, Self::Outbox), Error>;

    /// The refusal (`no-hello`) of a connection that did not open with a
    /// text message in time; `why` says what came instead (or that nothing
    /// did). The pump answers it and closes with `policy`.
    fn no_hello(&self, why: &str) -> Refusal {
        Refusal::new(
            ErrorCode::NoHello,
            format!("{why}: a connection opens with a hello"),
        )
    }
}

/// What an open connection's messages go to.
pub(crate) trait Endpoint {
    /// The messages the client sends (decoded from JSON by the pump).
    type Message;

    /// The close code of a connection closed for an oversized message (or
    /// hello).
    const OVERSIZE_CLOSE: CloseCode = CloseCode::Size;
    /// The text of the `rate-limited` warning, sent on the first message
    /// of each run the flood guard drops.
    const SLOW_DOWN: &'static str = "too many messages; this one was dropped, slow down";

    /// Handles one message, already past the flood guard. An
    /// [`Error::Refused`] is counted and answered, and the connection reads
    /// on; [`Error::Gone`] ends the session at once.
    async fn on_message(&mut self, msg: Self::Message) -> Result<(), Error>;

    /// Whether `msg` passes the flood guard without a token, paying later
    /// (through [`Endpoint::debt`]) only if it turns out to be junk. Such a
    /// message closes the connection instead once the bucket is bankrupt.
    /// Default: none does.
    fn pays_later(&self, _msg: &Self::Message) -> bool {
        false
    }

    /// How many messages let through by [`Endpoint::pays_later`] turned
    /// out to be junk since the last call: they are charged to the bucket
    /// before each message is admitted. Default: none.
    fn debt(&mut self) -> u32 {
        0
    }

    /// Called at each ping with how long ago the outbox (or this hook)
    /// last gave the connection a message; what it returns is written
    /// (a keep-alive), and counts as such a message. Default: nothing.
    fn on_quiet(&mut self, _quiet: Duration) -> Option<ByteString> {
        None
    }

    /// Why the connection closes when its outbox is closed. Default:
    /// `going-away`, "the server closed this connection".
    fn outbox_closed(&self) -> CloseReason {
        CloseReason {
            code: CloseCode::Away,
            description: Some("the server closed this connection".into()),
        }
    }

    /// Called once the connection stops reading, however it ended, before
    /// the close frame is written. Default: nothing.
    async fn on_close(&mut self) {}
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

/// The `error` message of a refusal, as both endpoints send it.
fn refusal_text(r: &Refusal) -> String {
    r.to_message().to_json()
}

/// A client message decoded, or its typed refusal (`bad-json`,
/// `not-finite`, `bad-message`).
fn decode<M: DeserializeOwned>(text: &str) -> Result<M, Refusal> {
    game::protocol::read(text.as_bytes()).map_err(|e| Refusal::new(e.code, e.message))
}

/// What the flood guard does with one message.
#[derive(Debug, PartialEq, Eq)]
enum Admission {
    /// Handle it.
    Pass,
    /// Drop it (counted as refused); `warn`: the first of a run of drops,
    /// answered `rate-limited`.
    Drop { warn: bool },
    /// Drop it (counted) and close the connection: it floods on.
    Flooded,
    /// Close the connection: it pays later, but its junk has run the
    /// bucket bankrupt.
    Bankrupt,
}

/// The flood guard's decision on one message at `now`, after the debt was
/// charged: messages that pay later pass unless the bucket is bankrupt;
/// others take a token or are dropped, and a long enough run of drops, or
/// a drop after [`FLOOD_SUSTAINED_FOR`] over the limit, closes the
/// connection.
fn admit(bucket: &mut TokenBucket, pays_later: bool, now: Instant) -> Admission {
    if pays_later {
        return if bucket.bankrupt() {
            Admission::Bankrupt
        } else {
            Admission::Pass
        };
    }
    if bucket.take(now) {
        Admission::Pass
    } else if bucket.dropped_in_a_row >= FLOOD_CLOSE_AFTER
        || bucket.over_limit_for(now) >= FLOOD_SUSTAINED_FOR
    {
        Admission::Flooded
    } else {
        Admission::Drop {
            warn: bucket.dropped_in_a_row == 1,
        }
    }
}

fn rate_limited() -> CloseReason {
    CloseReason {
        code: CloseCode::Policy,
        description: Some("rate-limited".into()),
    }
}

/// Runs one connection through `door`, then its endpoint, until it ends;
/// `true` when it ended on a write that could not finish in time (the
/// socket is stuck, and should be shut down).
pub(crate) async fn serve<D: Door>(
    door: D,
    limits: &Limits,
    metrics: &Metrics,
    session: Session,
    stream: actix_ws::MessageStream,
) -> bool {
    let mut stream = stream
        .max_frame_size(limits.max_message_bytes)
        .aggregate_continuations()
        .max_continuation_size(limits.max_message_bytes);
    let mut writer = Writer {
        session,
        write_timeout: limits.write_timeout,
    };
    let oversize = <D::Endpoint as Endpoint>::OVERSIZE_CLOSE;
    // The first message, or why the connection is refused (and the code
    // it is closed with).
    let deadline = tokio::time::Instant::now() + HELLO_WITHIN;
    let first = loop {
        let frame = match tokio::time::timeout_at(deadline, stream.recv()).await {
            Err(_) => break Err((door.no_hello("no hello within 10 s"), CloseCode::Policy)),
            Ok(frame) => frame,
        };
        match frame {
            None | Some(Ok(AggregatedMessage::Close(_))) => return false,
            Some(Ok(AggregatedMessage::Ping(b))) => {
                if !writer.pong(&b).await {
                    return true;
                }
            }
            Some(Ok(AggregatedMessage::Pong(_))) => {}
            Some(Ok(AggregatedMessage::Text(text))) => {
                break decode::<D::Message>(&text).map_err(|r| (r, CloseCode::Policy))
            }
            Some(Ok(AggregatedMessage::Binary(_))) => {
                break Err((
                    door.no_hello("messages are JSON text frames"),
                    CloseCode::Policy,
                ))
            }
            Some(Err(e)) if too_large(&e) => {
                break Err((
                    Refusal::new(ErrorCode::MessageTooLarge, "the hello is too large"),
                    oversize,
                ))
            }
            Some(Err(_)) => return false,
        }
    };
    let opened = match first {
        Ok(hello) => match door.open(hello, &mut writer).await {
            Ok(opened) => Ok(opened),
            Err(Error::Refused(r)) => Err((r, CloseCode::Policy)),
            Err(Error::Gone) => return true,
        },
        Err(refused) => Err(refused),
    };
    let (mut endpoint, mut outbox) = match opened {
        Ok(opened) => opened,
        Err((r, code)) => {
            metrics.refused();
            if writer.refuse(&r).await.is_err() {
                return true;
            }
            return writer
                .close(Some(CloseReason {
                    code,
                    description: Some(r.code.as_str().into()),
                }))
                .await;
        }
    };
    let mut bucket = TokenBucket::new(limits.rate_per_sec, limits.rate_burst, Instant::now());
    let mut ping = tokio::time::interval(PING_EVERY);
    let mut last_heard = Instant::now();
    let mut last_said = Instant::now();
    // Set when a write did not finish in time (or the endpoint is gone).
    let mut stuck = false;
    let reason: Option<CloseReason> = loop {
        tokio::select! {
            out = outbox.next() => match out {
                Some(text) => {
                    last_said = Instant::now();
                    if writer.say(text).await.is_err() {
                        stuck = true;
                        break None;
                    }
                }
                None => break Some(endpoint.outbox_closed()),
            },
            frame = stream.recv() => {
                last_heard = Instant::now();
                let text = match frame {
                    None | Some(Ok(AggregatedMessage::Close(_))) => break None,
                    Some(Ok(AggregatedMessage::Ping(b))) => {
                        if !writer.pong(&b).await {
                            stuck = true;
                            break None;
                        }
                        continue;
                    }
                    Some(Ok(AggregatedMessage::Pong(_))) => continue,
                    Some(Ok(AggregatedMessage::Text(text))) => Some(text),
                    Some(Ok(AggregatedMessage::Binary(_))) => None,
                    Some(Err(e)) if too_large(&e) => {
                        metrics.refused();
                        let r = Refusal::new(
                            ErrorCode::MessageTooLarge,
                            format!("messages are at most {} bytes", limits.max_message_bytes),
                        );
                        if writer.refuse(&r).await.is_err() {
                            stuck = true;
                        }
                        break Some(CloseReason {
                            code: oversize,
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
                };
                // Junk let through earlier is charged now, before this
                // message is admitted.
                let now = Instant::now();
                bucket.charge(endpoint.debt(), now);
                let decoded = match text {
                    Some(text) => decode::<D::Message>(&text),
                    None => Err(Refusal::new(
                        ErrorCode::BadMessage,
                        "messages are JSON text frames",
                    )),
                };
                let pays_later = matches!(&decoded, Ok(m) if endpoint.pays_later(m));
                match admit(&mut bucket, pays_later, now) {
                    Admission::Pass => {}
                    Admission::Bankrupt => break Some(rate_limited()),
                    Admission::Flooded => {
                        metrics.refused();
                        break Some(rate_limited());
                    }
                    Admission::Drop { warn } => {
                        metrics.refused();
                        let slow_down = Refusal::new(
                            ErrorCode::RateLimited,
                            <D::Endpoint as Endpoint>::SLOW_DOWN,
                        );
                        if warn && writer.refuse(&slow_down).await.is_err() {
                            stuck = true;
                            break None;
                        }
                        continue;
                    }
                }
                let handled = match decoded {
                    Ok(msg) => endpoint.on_message(msg).await,
                    Err(r) => Err(Error::Refused(r)),
                };
                match handled {
                    Ok(()) => {}
                    Err(Error::Refused(r)) => {
                        metrics.refused();
                        if writer.refuse(&r).await.is_err() {
                            stuck = true;
                            break None;
                        }
                    }
                    Err(Error::Gone) => {
                        stuck = true;
                        break None;
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
                if !writer.ping().await {
                    stuck = true;
                    break None;
                }
                if let Some(text) = endpoint.on_quiet(last_said.elapsed()) {
                    last_said = Instant::now();
                    if writer.say(text).await.is_err() {
                        stuck = true;
                        break None;
                    }
                }
            }
        }
    };
    endpoint.on_close().await;
    if stuck {
        return true;
    }
    writer.close(reason).await
}

#[cfg(test)]
mod tests {
    use super::*;
    use actix_web::test::TestRequest;
    use actix_web::FromRequest;
    use game::stream::StreamServerMessage;
    use serde_json::{json, Value};
    use std::cell::RefCell;
    use std::rc::Rc;

    #[test]
    fn a_burst_passes_then_one_warning_then_silent_drops_then_a_flood_closes() {
        let t0 = Instant::now();
        let mut bucket = TokenBucket::new(0.0, 2.0, t0);
        assert_eq!(admit(&mut bucket, false, t0), Admission::Pass);
        assert_eq!(admit(&mut bucket, false, t0), Admission::Pass);
        assert_eq!(
            admit(&mut bucket, false, t0),
            Admission::Drop { warn: true }
        );
        for _ in 2..FLOOD_CLOSE_AFTER {
            assert_eq!(
                admit(&mut bucket, false, t0),
                Admission::Drop { warn: false }
            );
        }
        assert_eq!(admit(&mut bucket, false, t0), Admission::Flooded);
    }

    /// Sends at `per_sec` for `seconds` (simulated time); when the
    /// connection is closed, how long after the start.
    fn flood(per_sec: u32, seconds: u32, pause_every: Option<(u32, u32)>) -> Option<Duration> {
        let t0 = Instant::now();
        let mut bucket = TokenBucket::new(10.0, 10.0, t0);
        let step = Duration::from_secs(1) / per_sec;
        let mut at = Duration::ZERO;
        for k in 0..per_sec * seconds {
            if let Some((every, pause)) = pause_every {
                if k > 0 && k % every == 0 {
                    at += Duration::from_secs(pause.into());
                }
            }
            if admit(&mut bucket, false, t0 + at) == Admission::Flooded {
                return Some(at);
            }
            at += step;
        }
        None
    }

    #[test]
    fn a_flood_sustained_just_above_the_rate_is_closed_after_the_grace() {
        // 12 messages a second against 10: two dropped a second, never
        // 200 in a row, but over the limit for good.
        // The burst of 10 drains at 2 a second: the first drop comes at
        // about 5 s, the close 10 s later.
        let closed = flood(12, 30, None).expect("closed");
        assert!(
            closed >= FLOOD_SUSTAINED_FOR + Duration::from_secs(4),
            "{closed:?}"
        );
        assert!(
            closed < FLOOD_SUSTAINED_FOR + Duration::from_secs(7),
            "{closed:?}"
        );
        // Exactly at the rate: nothing is dropped, nothing closed.
        assert_eq!(flood(10, 30, None), None);
    }

    #[test]
    fn bursts_over_the_limit_with_pauses_between_are_never_closed() {
        // 20 at 40 a second (half dropped), then 2 s of silence, for 60 s.
        assert_eq!(flood(40, 60, Some((20, 2))), None);
    }

    #[test]
    fn messages_that_pay_later_pass_an_empty_bucket_until_their_debt_bankrupts_it() {
        let t0 = Instant::now();
        let mut bucket = TokenBucket::new(0.0, 2.0, t0);
        while bucket.take(t0) {}
        assert_eq!(admit(&mut bucket, true, t0), Admission::Pass);
        bucket.charge(10, t0);
        assert_eq!(admit(&mut bucket, true, t0), Admission::Bankrupt);
    }

    #[test]
    fn malformed_json_is_refused_with_its_typed_code() {
        let bad = decode::<Value>("{").unwrap_err();
        assert_eq!(bad.code, ErrorCode::BadJson);
        let wrong = decode::<game::protocol::ClientMessage>(r#"{"type":"nope"}"#).unwrap_err();
        assert_eq!(wrong.code, ErrorCode::BadMessage);
    }

    #[test]
    fn a_refusal_reads_the_same_on_the_match_socket_and_the_event_stream() {
        let r = Refusal::new(ErrorCode::RateLimited, "slow down");
        assert_eq!(refusal_text(&r), StreamServerMessage::refused(&r).to_json());
    }

    /// Opens on any first message; refuses `{"refuse":true}`, keeps the
    /// rest; `{"move":..}` pays later.
    struct TestDoor(Rc<RefCell<Vec<Value>>>);

    struct TestEndpoint(Rc<RefCell<Vec<Value>>>);

    /// An outbox that never has anything.
    struct Silent;

    impl Outbox for Silent {
        async fn next(&mut self) -> Option<ByteString> {
            std::future::pending().await
        }
    }

    impl Door for TestDoor {
        type Message = Value;
        type Endpoint = TestEndpoint;
        type Outbox = Silent;

        async fn open(
            self,
            hello: Value,
            writer: &mut Writer,
        ) -> Result<(TestEndpoint, Silent), Error> {
            if hello != json!("hello") {
                return Err(self.no_hello("not a hello").into());
            }
            writer.say("welcome").await?;
            Ok((TestEndpoint(self.0), Silent))
        }
    }

    impl Endpoint for TestEndpoint {
        type Message = Value;

        async fn on_message(&mut self, msg: Value) -> Result<(), Error> {
            if msg == json!({"refuse": true}) {
                return Err(Refusal::new(ErrorCode::BadMessage, "refused").into());
            }
            self.0.borrow_mut().push(msg);
            Ok(())
        }

        fn pays_later(&self, msg: &Value) -> bool {
            msg.get("move").is_some()
        }
    }

    /// A masked client frame (a zero mask: the payload as it is).
    fn frame(opcode: u8, payload: &[u8]) -> Vec<u8> {
        let mut f = vec![0x80 | opcode];
        if payload.len() < 126 {
            f.push(0x80 | payload.len() as u8);
        } else {
            f.push(0x80 | 126);
            f.extend_from_slice(&(payload.len() as u16).to_be_bytes());
        }
        f.extend_from_slice(&[0; 4]);
        f.extend_from_slice(payload);
        f
    }

    fn text(s: &str) -> Vec<u8> {
        frame(0x1, s.as_bytes())
    }

    /// What the server wrote, frame by frame: texts as they are, a close as
    /// `close CODE REASON`; pings left out.
    fn written(mut bytes: &[u8]) -> Vec<String> {
        let mut out = Vec::new();
        while bytes.len() >= 2 {
            let opcode = bytes[0] & 0x0f;
            let (len, head) = match bytes[1] & 0x7f {
                126 => (usize::from(u16::from_be_bytes([bytes[2], bytes[3]])), 4),
                127 => panic!("no test writes that much"),
                n => (usize::from(n), 2),
            };
            let payload = &bytes[head..head + len];
            bytes = &bytes[head + len..];
            match opcode {
                0x1 => out.push(String::from_utf8(payload.to_vec()).unwrap()),
                0x8 if payload.is_empty() => out.push("close".to_string()),
                0x8 => out.push(format!(
                    "close {} {}",
                    u16::from_be_bytes([payload[0], payload[1]]),
                    String::from_utf8_lossy(&payload[2..])
                )),
                _ => {}
            }
        }
        out
    }

    fn code_of(json: &str) -> String {
        let v: Value = serde_json::from_str(json).unwrap();
        assert_eq!(v["type"], "error", "{json}");
        v["code"].as_str().unwrap().to_string()
    }

    fn refused_count(metrics: &Metrics) -> u64 {
        let rendered = metrics.render();
        let line = rendered
            .lines()
            .find(|l| l.starts_with("chapaev_refused_messages_total "))
            .unwrap();
        line.rsplit(' ').next().unwrap().parse().unwrap()
    }

    struct Served {
        stuck: bool,
        written: Vec<String>,
        kept: Vec<Value>,
        refused: u64,
    }

    /// Pumps a connection whose client sent `frames`, each in a read of
    /// its own, and then went away (its input ends), through [`TestDoor`].
    async fn serve_frames(limits: Limits, frames: Vec<Vec<u8>>) -> Served {
        // One frame per poll, as from a socket (actix-ws reports a size
        // error ahead of the frames read with it).
        let reads = futures_util::stream::unfold(frames.into_iter(), |mut frames| async move {
            tokio::task::yield_now().await;
            let chunk = frames.next()?;
            Some((
                Ok::<_, actix_web::error::PayloadError>(actix_web::web::Bytes::from(chunk)),
                frames,
            ))
        });
        let reads: std::pin::Pin<
            Box<dyn futures_util::Stream<Item = Result<_, actix_web::error::PayloadError>>>,
        > = Box::pin(reads);
        let (req, _) = TestRequest::get()
            .insert_header(("upgrade", "websocket"))
            .insert_header(("connection", "upgrade"))
            .insert_header(("sec-websocket-version", "13"))
            .insert_header(("sec-websocket-key", "dGhlIHNhbXBsZSBub25jZQ=="))
            .to_http_parts();
        let mut payload = actix_web::dev::Payload::from(reads);
        let body = actix_web::web::Payload::from_request(&req, &mut payload)
            .await
            .unwrap();
        let (response, session, stream) = actix_ws::handle(&req, body).unwrap();
        let kept = Rc::new(RefCell::new(Vec::new()));
        let metrics = Metrics::default();
        let door = TestDoor(kept.clone());
        let (stuck, bytes) = tokio::join!(
            serve(door, &limits, &metrics, session, stream),
            actix_web::body::to_bytes(response.into_body())
        );
        let kept = kept.borrow().clone();
        Served {
            stuck,
            written: written(&bytes.unwrap()),
            kept,
            refused: refused_count(&metrics),
        }
    }

    #[actix_web::test]
    async fn messages_after_the_hello_reach_the_endpoint_and_refusals_are_answered() {
        let mut frames = vec![text(r#""hello""#)];
        frames.push(text(r#"{"n":1}"#));
        frames.push(text(r#"{"refuse":true}"#));
        frames.push(text("{"));
        frames.push(frame(0x2, b"\x01"));
        frames.push(text(r#"{"n":2}"#));
        let served = serve_frames(Limits::default(), frames).await;
        assert!(!served.stuck);
        assert_eq!(served.kept, vec![json!({"n":1}), json!({"n":2})]);
        let (last, rest) = served.written.split_last().unwrap();
        assert_eq!(rest[0], "welcome");
        let codes: Vec<String> = rest[1..].iter().map(|t| code_of(t)).collect();
        assert_eq!(codes, ["bad-message", "bad-json", "bad-message"]);
        // The client's input ended: a plain close.
        assert_eq!(last, "close");
        assert_eq!(served.refused, 3);
    }

    #[actix_web::test]
    async fn an_oversized_message_is_refused_and_closes_with_the_size_code() {
        let limits = Limits {
            max_message_bytes: 64,
            ..Limits::default()
        };
        let mut frames = vec![text(r#""hello""#)];
        frames.push(text(&format!("\"{}\"", "x".repeat(100))));
        frames.push(text(r#"{"n":1}"#));
        let served = serve_frames(limits, frames).await;
        assert!(served.kept.is_empty(), "{:?}", served.written);
        assert_eq!(code_of(&served.written[1]), "message-too-large");
        assert_eq!(served.written[2], "close 1009 message-too-large");
        assert_eq!(served.refused, 1);
    }

    #[actix_web::test]
    async fn a_flood_is_warned_once_then_closed_rate_limited() {
        let limits = Limits {
            rate_per_sec: 0.0,
            rate_burst: 1.0,
            ..Limits::default()
        };
        let mut frames = vec![text(r#""hello""#)];
        for n in 0..=FLOOD_CLOSE_AFTER + 5 {
            frames.push(text(&format!(r#"{{"n":{n}}}"#)));
        }
        let served = serve_frames(limits, frames).await;
        assert_eq!(served.kept, vec![json!({"n":0})]);
        assert_eq!(served.written.len(), 3, "{:?}", served.written);
        assert_eq!(code_of(&served.written[1]), "rate-limited");
        assert_eq!(served.written[2], "close 1008 rate-limited");
        assert_eq!(served.refused, u64::from(FLOOD_CLOSE_AFTER));
    }

    #[actix_web::test]
    async fn messages_that_pay_later_pass_an_empty_bucket() {
        let limits = Limits {
            rate_per_sec: 0.0,
            rate_burst: 1.0,
            ..Limits::default()
        };
        let mut frames = vec![text(r#""hello""#)];
        // Takes the only token.
        frames.push(text(r#"{"n":0}"#));
        for n in 0..5 {
            frames.push(text(&format!(r#"{{"move":{n}}}"#)));
        }
        let served = serve_frames(limits, frames).await;
        assert_eq!(served.kept.len(), 6);
        assert_eq!(served.refused, 0);
    }

    #[actix_web::test]
    async fn a_connection_that_does_not_open_with_a_text_hello_is_refused_no_hello() {
        let served = serve_frames(Limits::default(), vec![frame(0x2, b"\x01")]).await;
        assert_eq!(code_of(&served.written[0]), "no-hello");
        assert_eq!(served.written[1], "close 1008 no-hello");
        let served = serve_frames(Limits::default(), vec![text(r#""bye""#)]).await;
        assert_eq!(code_of(&served.written[0]), "no-hello");
        assert_eq!(served.refused, 1);
    }
}
