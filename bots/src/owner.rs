//! Connecting to a match's socket on the node that plays it. On a server
//! of several nodes, a client asking one node for a match another node
//! plays is either relayed there or, when it adds `follow=1` to its
//! `/ws?match=ID` URL and the owner has a public URL, answered `307` with
//! the owner's socket. [`connect`] asks so and follows: at most
//! [`MAX_HOPS`] times, and should the node it is sent to not answer (it
//! died, or cannot be reached from here) it goes back to the URL it was
//! given without `follow`, so that node relays. A single server ignores
//! `follow`.

use tokio::net::TcpStream;
use tokio_tungstenite::tungstenite::{self, http::StatusCode};
use tokio_tungstenite::{MaybeTlsStream, WebSocketStream};

/// How many `307`s [`connect`] follows (a match moving again meanwhile
/// may send it on once more).
pub const MAX_HOPS: usize = 3;

/// An open match socket.
pub type Socket = WebSocketStream<MaybeTlsStream<TcpStream>>;

/// `url` asking to be sent to the node that plays its match (unchanged
/// if it asks already).
pub fn following(url: &str) -> String {
    if url.contains("follow=") {
        url.to_string()
    } else if url.contains('?') {
        format!("{url}&follow=1")
    } else {
        format!("{url}?follow=1")
    }
}

/// Where a `307` (or another redirect) sends the client, if it is one.
fn sent_to(e: &tungstenite::Error) -> Option<String> {
    let tungstenite::Error::Http(response) = e else {
        return None;
    };
    if !matches!(
        response.status(),
        StatusCode::TEMPORARY_REDIRECT | StatusCode::PERMANENT_REDIRECT | StatusCode::FOUND
    ) {
        return None;
    }
    let location = response.headers().get("location")?.to_str().ok()?;
    (location.starts_with("ws://") || location.starts_with("wss://")).then(|| location.to_string())
}

/// Connects to the match socket `url` (`ws://host/ws?match=ID`) on the
/// node that plays the match (see the module's documentation): the
/// socket, and the URL it was opened on. `nodelay` turns Nagle's
/// algorithm off.
pub async fn connect(url: &str, nodelay: bool) -> Result<(Socket, String), tungstenite::Error> {
    let open = |u: String| async move {
        tokio_tungstenite::connect_async_with_config(u.as_str(), None, nodelay)
            .await
            .map(|(ws, _)| (ws, u))
    };
    let mut at = following(url);
    for hop in 0..=MAX_HOPS {
        match open(at.clone()).await {
            Ok(found) => return Ok(found),
            Err(e) => match sent_to(&e) {
                Some(next) if hop < MAX_HOPS => at = next,
                // Too many hops: relayed by the node first asked.
                Some(_) => break,
                // The first node refused: that is the answer.
                None if hop == 0 => return Err(e),
                // The node sent to does not answer: back to the first,
                // which relays.
                None => break,
            },
        }
    }
    open(url.to_string()).await
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_match_url_asks_to_follow_once() {
        assert_eq!(
            following("ws://a:1/ws?match=m"),
            "ws://a:1/ws?match=m&follow=1"
        );
        assert_eq!(
            following("ws://a:1/ws?match=m&follow=1"),
            "ws://a:1/ws?match=m&follow=1"
        );
        assert_eq!(following("ws://a:1/ws"), "ws://a:1/ws?follow=1");
    }

    #[test]
    fn only_a_redirect_to_a_socket_sends_the_client_on() {
        let redirect = |status: u16, location: &str| {
            tungstenite::Error::Http(
                tungstenite::http::Response::builder()
                    .status(status)
                    .header("location", location)
                    .body(None)
                    .unwrap(),
            )
        };
        assert_eq!(
            sent_to(&redirect(307, "wss://b/n/2/ws?match=m&follow=1")).as_deref(),
            Some("wss://b/n/2/ws?match=m&follow=1")
        );
        assert_eq!(sent_to(&redirect(307, "https://b/ws?match=m")), None);
        assert_eq!(sent_to(&redirect(503, "ws://b/ws?match=m")), None);
    }
}
