//! The match WebSocket that keeps itself up: it opens, says hello, hands
//! over every server message, and when the connection drops it reconnects
//! with the same seat token after a growing pause (the server answers a
//! reconnect with the full match state, so nothing else is needed). A
//! refusal that reconnecting cannot fix (a wrong token, no such match)
//! stops it. On a cluster it may open the socket of the node that plays
//! the match directly (a browser's socket cannot follow the server's
//! redirect there); a direct socket that does not open (that node gone, or
//! out of reach) gives way to the page's own node for good, which relays.

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
    /// No server: the match is played in this page ([`crate::channel`]).
    Offline,
}

/// A self-healing match connection.
pub struct Connection {
    url: String,
    /// The page's own node's socket, while `url` is another node's.
    fallback: Option<String>,
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
    /// Opens `direct` (the socket of the node that plays the match) when
    /// there is one, else `own` (`ws://.../ws?match=..`, the page's node's),
    /// which also takes over should `direct` fail to open; and says hello
    /// as `name` with the seat token (none: to watch).
    pub fn open_preferring(
        direct: Option<String>,
        own: String,
        name: String,
        token: Option<SeatToken>,
    ) -> Connection {
        let (url, fallback) = match direct {
            Some(direct) if direct != own => (direct, Some(own)),
            _ => (own, None),
        };
        Connection {
            socket: Some(Socket::open(&url)),
            url,
            fallback,
            name,
            token,
            link: Link::Connecting,
            attempt: 0,
            fatal: None,
        }
    }

    /// The socket's address, as last opened.
    pub fn url(&self) -> &str {
        &self.url
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
            (SocketState::Closed, Link::Connecting)
                if self.fatal.is_none() && self.fallback.is_some() =>
            {
                // The other node's socket did not open: the page's own
                // node, at once.
                self.url = self.fallback.take().unwrap_or_default();
                self.socket = Some(Socket::open(&self.url));
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

#[cfg(test)]
mod tests {
    use super::*;
    use std::net::TcpListener;
    use std::time::{Duration, Instant};

    /// Polls `c` until it is open (at most 5 s).
    fn until_open(c: &mut Connection) {
        let start = Instant::now();
        while !c.is_open() {
            assert!(start.elapsed() < Duration::from_secs(5), "{:?}", c.link());
            c.poll(start.elapsed().as_secs_f64());
            std::thread::sleep(Duration::from_millis(5));
        }
    }

    /// A socket that takes one connection and hands back its first frame.
    fn one_socket() -> (String, std::thread::JoinHandle<String>) {
        let listener = TcpListener::bind("127.0.0.1:0").unwrap();
        let url = format!("ws://{}/ws?match=m1", listener.local_addr().unwrap());
        let first = std::thread::spawn(move || {
            let (stream, _) = listener.accept().unwrap();
            let mut ws = tungstenite::accept(stream).unwrap();
            ws.read().unwrap().into_text().unwrap().to_string()
        });
        (url, first)
    }

    #[test]
    fn a_direct_socket_that_does_not_open_gives_way_to_the_pages_own_node() {
        let (own, hello) = one_socket();
        // A port nobody listens on any more.
        let gone = TcpListener::bind("127.0.0.1:0")
            .unwrap()
            .local_addr()
            .unwrap();
        let direct = format!("ws://{gone}/ws?match=m1");
        let mut c = Connection::open_preferring(Some(direct), own.clone(), "Petka".into(), None);
        until_open(&mut c);
        assert_eq!(c.url(), own);
        assert!(hello.join().unwrap().contains(r#""type":"hello""#));
    }

    #[test]
    fn a_direct_socket_that_opens_is_used_and_the_own_node_is_left_alone() {
        let (direct, hello) = one_socket();
        let own = "ws://127.0.0.1:9/ws?match=m1".to_string();
        let mut c = Connection::open_preferring(Some(direct.clone()), own, "Petka".into(), None);
        until_open(&mut c);
        assert_eq!(c.url(), direct);
        assert!(hello.join().unwrap().contains("Petka"));
    }
}
