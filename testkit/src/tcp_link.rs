//! A TCP link a test can cut: a forwarder on a free loopback port that
//! passes every connection through to a service's port, until the test
//! cuts it. Then every connection through it breaks and new ones are
//! closed as soon as they open, as if the network between one client and
//! the service failed, while the service itself (and every other client
//! of it) goes on. Restoring it lets new connections through again.
//!
//! Plain threads, two per connection: a test's handful of connections.

use std::io::{Read, Write};
use std::net::{Shutdown, TcpListener, TcpStream};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Duration;

/// What the forwarder's threads share.
#[derive(Default)]
struct Shared {
    /// Cut: connections are closed as they open.
    cut: AtomicBool,
    /// The link is dropped: the acceptor ends.
    ended: AtomicBool,
    /// Both ends of every connection passed through (shut down on a cut).
    open: Mutex<Vec<TcpStream>>,
}

impl Shared {
    fn close_all(&self) {
        let mut open = self.open.lock().unwrap_or_else(PoisonError::into_inner);
        for s in open.drain(..) {
            let _ = s.shutdown(Shutdown::Both);
        }
    }
}

/// A forwarder to one service port (see the module's documentation).
pub struct TcpLink {
    port: u16,
    shared: Arc<Shared>,
}

impl TcpLink {
    /// Forwards a new loopback port to `127.0.0.1:target`.
    pub fn start(target: u16) -> std::io::Result<TcpLink> {
        let listener = TcpListener::bind("127.0.0.1:0")?;
        let port = listener.local_addr()?.port();
        listener.set_nonblocking(true)?;
        let shared = Arc::new(Shared::default());
        let s = shared.clone();
        std::thread::Builder::new()
            .name("tcp-link".into())
            .spawn(move || accept(listener, target, s))?;
        Ok(TcpLink { port, shared })
    }

    /// The port to connect to instead of the service's.
    pub fn port(&self) -> u16 {
        self.port
    }

    /// Breaks every connection through the link, and closes new ones as
    /// they open, until [`TcpLink::restore`].
    pub fn cut(&self) {
        self.shared.cut.store(true, Ordering::SeqCst);
        self.shared.close_all();
    }

    /// Lets new connections through again.
    pub fn restore(&self) {
        self.shared.cut.store(false, Ordering::SeqCst);
    }
}

impl Drop for TcpLink {
    fn drop(&mut self) {
        self.shared.ended.store(true, Ordering::SeqCst);
        self.shared.cut.store(true, Ordering::SeqCst);
        self.shared.close_all();
    }
}

/// Accepts connections until the link is dropped; passes each through
/// unless the link is cut.
fn accept(listener: TcpListener, target: u16, shared: Arc<Shared>) {
    while !shared.ended.load(Ordering::SeqCst) {
        let client = match listener.accept() {
            Ok((client, _)) => client,
            Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => {
                std::thread::sleep(Duration::from_millis(10));
                continue;
            }
            Err(_) => continue,
        };
        if shared.cut.load(Ordering::SeqCst) {
            let _ = client.shutdown(Shutdown::Both);
            continue;
        }
        let _ = pass_through(client, target, &shared);
    }
}

/// Connects `client` to the service and copies both ways on two threads.
fn pass_through(client: TcpStream, target: u16, shared: &Arc<Shared>) -> std::io::Result<()> {
    client.set_nonblocking(false)?;
    let service = TcpStream::connect(("127.0.0.1", target))?;
    let _ = client.set_nodelay(true);
    let _ = service.set_nodelay(true);
    {
        let mut open = shared.open.lock().unwrap_or_else(PoisonError::into_inner);
        open.push(client.try_clone()?);
        open.push(service.try_clone()?);
    }
    let (c2, s2) = (client.try_clone()?, service.try_clone()?);
    std::thread::Builder::new()
        .name("tcp-link-up".into())
        .spawn(move || copy(client, service))?;
    std::thread::Builder::new()
        .name("tcp-link-down".into())
        .spawn(move || copy(s2, c2))?;
    Ok(())
}

/// Copies `from` to `to` until either ends; then closes both.
fn copy(mut from: TcpStream, mut to: TcpStream) {
    let mut buf = [0u8; 16 * 1024];
    loop {
        match from.read(&mut buf) {
            Ok(0) | Err(_) => break,
            Ok(n) => {
                if to.write_all(&buf[..n]).is_err() {
                    break;
                }
            }
        }
    }
    let _ = from.shutdown(Shutdown::Both);
    let _ = to.shutdown(Shutdown::Both);
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::BufRead;

    /// An echo server on a free port: each connection's lines come back.
    fn echo() -> u16 {
        let listener = TcpListener::bind("127.0.0.1:0").unwrap();
        let port = listener.local_addr().unwrap().port();
        std::thread::spawn(move || {
            for conn in listener.incoming().flatten() {
                std::thread::spawn(move || {
                    let mut w = conn.try_clone().unwrap();
                    for line in std::io::BufReader::new(conn).lines() {
                        let Ok(line) = line else { break };
                        if writeln!(w, "{line}").is_err() {
                            break;
                        }
                    }
                });
            }
        });
        port
    }

    /// Sends a line through `port`; the line that came back, if any.
    fn round_trip(conn: &mut TcpStream, text: &str) -> Option<String> {
        conn.set_read_timeout(Some(Duration::from_secs(5))).ok()?;
        writeln!(conn, "{text}").ok()?;
        let mut line = String::new();
        let n = std::io::BufReader::new(conn.try_clone().ok()?)
            .read_line(&mut line)
            .ok()?;
        (n > 0).then(|| line.trim_end().to_string())
    }

    #[test]
    fn a_link_passes_connections_through_until_cut_and_again_once_restored() {
        let link = TcpLink::start(echo()).unwrap();
        let mut before = TcpStream::connect(("127.0.0.1", link.port())).unwrap();
        assert_eq!(round_trip(&mut before, "one").as_deref(), Some("one"));
        link.cut();
        assert_eq!(round_trip(&mut before, "two"), None, "the open one broke");
        let mut during = TcpStream::connect(("127.0.0.1", link.port())).unwrap();
        assert_eq!(
            round_trip(&mut during, "three"),
            None,
            "a new one is closed"
        );
        link.restore();
        let mut after = TcpStream::connect(("127.0.0.1", link.port())).unwrap();
        assert_eq!(round_trip(&mut after, "four").as_deref(), Some("four"));
    }
}
