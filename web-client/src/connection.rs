//! The match WebSocket that keeps itself up: it opens, says hello, hands
//! over every server message, and when the connection drops it reconnects
//! with the same seat token after a growing pause (the server answers a
//! reconnect with the full match state, so nothing else is needed). A
//! refusal that reconnecting cannot fix (a wrong token, no such match)
//! stops it.

use crate::platform::{Socket, SocketState};
use game::protocol::{ClientMessage, ErrorCode, ServerMessage, PROTOCOL_VERSION};
use game::token::SeatToken;

/// Pause before the first reconnect attempt, doubled each time up to
/// [`MAX_BACKOFF`].
pub const FIRST_BACKOFF: f64 = 0.5;
pub const MAX_BACKOFF: f64 = 5.0;

/// Where the connection stands, for the status line.
#[derive(Clone, Debug, PartialEq)]
pub enum Link {
    Connecting,
    Open,
    /// Dropped; trying again at the given clock time.
    Retrying {
        at: f64,
        attempt: u32,
    },
    /// Given up for this reason.
    Failed(String),
}

/// A self-healing match connection.
pub struct Connection {
    url: String,
    name: String,
    /// The seat token, said in each hello (none: watching).
    token: Option<SeatToken>,
    socket: Option<Socket>,
    link: Link,
    attempt: u32,
    /// A refusal seen on this connection that reconnecting cannot fix.
    fatal: Option<String>,
}

impl Connection {
    /// Opens `url` (`ws://.../ws?match=..`), saying hello as `name` with
    /// the seat token (none: to watch).
    pub fn open(url: String, name: String, token: Option<SeatToken>) -> Connection {
        Connection {
            socket: Some(Socket::open(&url)),
            url,
            name,
            token,
            link: Link::Connecting,
            attempt: 0,
            fatal: None,
        }
    }

    pub fn link(&self) -> &Link {
        &self.link
    }

    pub fn is_open(&self) -> bool {
        self.link == Link::Open
    }

    /// Sends a message; `false` if the connection is not open (the caller
    /// tells the player; nothing is queued behind their back).
    pub fn send(&self, m: &ClientMessage) -> bool {
        match (&self.socket, &self.link) {
            (Some(s), Link::Open) => s.send(&m.to_json()),
            _ => false,
        }
    }

    /// Drives the connection at clock time `now` (seconds) and returns the
    /// messages that arrived.
    pub fn poll(&mut self, now: f64) -> Vec<ServerMessage> {
        let mut out = Vec::new();
        if let Link::Retrying { at, .. } = self.link {
            if now >= at {
                self.socket = Some(Socket::open(&self.url));
                self.link = Link::Connecting;
            }
        }
        let Some(socket) = &self.socket else {
            return out;
        };
        // Messages that arrived before a close are still delivered.
        while let Some(text) = socket.recv() {
            match ServerMessage::from_json(&text) {
                Ok(m) => out.push(m),
                Err(e) => out.push(ServerMessage::Error {
                    code: ErrorCode::BadMessage,
                    message: crate::i18n::t!("api-unreadable-message", error = e.to_string()),
                }),
            }
        }
        let fatal = out.iter().find_map(|m| match m {
            ServerMessage::Error {
                code: ErrorCode::BadToken | ErrorCode::NoSuchMatch | ErrorCode::UnsupportedPhysics,
                message,
            } => Some(message.clone()),
            _ => None,
        });
        if fatal.is_some() {
            self.fatal = fatal;
        }
        match (socket.state(), &self.link) {
            (SocketState::Open, Link::Connecting) => {
                self.link = Link::Open;
                self.attempt = 0;
                let hello = ClientMessage::Hello {
                    protocol: PROTOCOL_VERSION,
                    name: self.name.clone(),
                    token: self.token.clone(),
                    key: None,
                };
                socket.send(&hello.to_json());
            }
            (SocketState::Closed, Link::Open | Link::Connecting) => {
                self.socket = None;
                self.link = match self.fatal.take() {
                    Some(reason) => Link::Failed(reason),
                    None => {
                        let pause =
                            (FIRST_BACKOFF * 2f64.powi(self.attempt as i32)).min(MAX_BACKOFF);
                        self.attempt += 1;
                        Link::Retrying {
                            at: now + pause,
                            attempt: self.attempt,
                        }
                    }
                };
            }
            _ => {}
        }
        out
    }
}
