//! A throwaway Redis server on loopback, for the tests of several server
//! nodes: `redis-server` (from the machine's packages) on a free port,
//! keeping nothing on disk. It stops when dropped, or when the process
//! that started it ends ([`crate::process`]). A test of what survives a
//! Redis restart stops it and starts it again on the same port
//! ([`LocalRedis::stop`], [`LocalRedis::start_again`]).

use crate::process::{command, free_port, start_for_process};
use crate::skip::{self, Service};
use std::path::PathBuf;
use std::process::{Child, Stdio};
use std::time::{Duration, Instant};

/// Why no local Redis could be started.
#[derive(Debug, thiserror::Error)]
pub enum LocalRedisError {
    #[error("redis-server was not found on PATH (install the redis-server package)")]
    NotInstalled,
    #[error("finding a free port: {0}")]
    Port(#[source] std::io::Error),
    #[error("starting redis-server: {0}")]
    Io(#[source] std::io::Error),
    #[error("redis-server did not answer within {0:?}")]
    NotReady(Duration),
}

/// A Redis server this process started.
pub struct LocalRedis {
    /// `None` while stopped.
    child: Option<Child>,
    port: u16,
}

fn redis_server() -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .map(|d| d.join("redis-server"))
        .find(|p| p.exists())
}

impl LocalRedis {
    /// Starts `redis-server` on a free loopback port; returns once it
    /// answers.
    pub fn start() -> Result<LocalRedis, LocalRedisError> {
        let port = free_port().map_err(LocalRedisError::Port)?;
        Ok(LocalRedis {
            child: Some(spawn(port)?),
            port,
        })
    }

    /// Stops it at once (SIGKILL: it keeps nothing, so a clean stop is no
    /// different); every client's connection breaks.
    pub fn stop(&mut self) {
        if let Some(mut child) = self.child.take() {
            let _ = child.kill();
            let _ = child.wait();
        }
    }

    /// Starts it again, empty, on the same port (after [`LocalRedis::stop`];
    /// a running server is stopped first); returns once it answers.
    pub fn start_again(&mut self) -> Result<(), LocalRedisError> {
        self.stop();
        self.child = Some(spawn(self.port)?);
        Ok(())
    }

    /// Its URL.
    pub fn url(&self) -> String {
        format!("redis://127.0.0.1:{}", self.port)
    }
}

/// Starts `redis-server` on `port`; returns once it answers.
fn spawn(port: u16) -> Result<Child, LocalRedisError> {
    let bin = redis_server().ok_or(LocalRedisError::NotInstalled)?;
    let mut child = command(bin, None)
        .args(["--port", &port.to_string(), "--bind", "127.0.0.1"])
        .args(["--save", "", "--appendonly", "no", "--daemonize", "no"])
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .map_err(LocalRedisError::Io)?;
    let started = Instant::now();
    let within = Duration::from_secs(20);
    while started.elapsed() < within {
        if std::net::TcpStream::connect(("127.0.0.1", port)).is_ok() {
            return Ok(child);
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let _ = child.kill();
    let _ = child.wait();
    Err(LocalRedisError::NotReady(within))
}

impl Drop for LocalRedis {
    fn drop(&mut self) {
        self.stop();
    }
}

/// The process-wide local Redis the tests share, started on first use
/// from a thread that lives as long as the process. `None` when this
/// machine has no Redis: test `test` is then skipped, with a line on
/// stderr that says so, or fails where `CHAPAEV_REQUIRE_REDIS` is set
/// ([`crate::skip`]).
pub fn shared(test: &str) -> Option<&'static LocalRedis> {
    static SHARED: std::sync::OnceLock<Result<LocalRedis, String>> = std::sync::OnceLock::new();
    let started = start_for_process(&SHARED, "local-redis", || {
        LocalRedis::start().map_err(|e| e.to_string())
    });
    match started {
        Ok(r) => Some(r),
        Err(e) => {
            skip::without(test, Service::Redis, e);
            None
        }
    }
}
