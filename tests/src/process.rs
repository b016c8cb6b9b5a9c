//! Child processes: the server and chromedriver are started in process
//! groups of their own and killed, group and all (the browser chromedriver
//! launched included), when their guard drops — whether the scenario
//! passed, failed or panicked; and a command run to its end whose exit
//! status is checked ([`run_to_end`]).

use crate::{E2eError, Result};
use std::io::{BufRead, BufReader};
use std::net::{Ipv4Addr, TcpListener, TcpStream};
use std::os::unix::process::CommandExt;
use std::path::Path;
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

/// A child process, killed with its whole process group on drop.
pub struct Guard {
    child: Child,
    name: String,
}

impl Guard {
    /// Spawns `cmd` in a new process group.
    pub fn spawn(name: &str, mut cmd: Command) -> Result<Guard> {
        cmd.process_group(0);
        let child = cmd.spawn().map_err(|source| E2eError::Io {
            what: format!("starting {name}"),
            source,
        })?;
        Ok(Guard {
            child,
            name: name.to_string(),
        })
    }

    pub fn id(&self) -> u32 {
        self.child.id()
    }

    /// Whether the process has exited (with how).
    pub fn exited(&mut self) -> Option<String> {
        match self.child.try_wait() {
            Ok(Some(status)) => Some(status.to_string()),
            Ok(None) => None,
            Err(e) => Some(e.to_string()),
        }
    }
}

impl Drop for Guard {
    fn drop(&mut self) {
        // The group's id is the leader's pid (process_group(0)).
        let group = format!("-{}", self.child.id());
        let _ = Command::new("kill")
            .args(["-KILL", "--", &group])
            .stderr(Stdio::null())
            .status();
        let _ = self.child.kill();
        let _ = self.child.wait();
        eprintln!("e2e: stopped {}", self.name);
    }
}

/// Runs `cmd` (described as `what`) to its end, its standard output
/// captured, and its standard error too unless the caller set it (to let
/// it through); its output, or unless it exited 0 an error saying so with
/// the end of its standard error.
pub fn run_to_end(what: &str, cmd: &mut Command) -> Result<Output> {
    let out = cmd.output().map_err(|source| E2eError::Io {
        what: format!("running {what}"),
        source,
    })?;
    if out.status.success() {
        return Ok(out);
    }
    Err(E2eError::Check(format!(
        "{what} failed ({}):\n{}",
        out.status,
        crate::js::tail(&String::from_utf8_lossy(&out.stderr), 4000)
    )))
}

/// A free TCP port on 127.0.0.1 (free when asked; taken by whoever binds first).
pub fn free_port() -> Result<u16> {
    let listener = TcpListener::bind((Ipv4Addr::LOCALHOST, 0)).map_err(|source| E2eError::Io {
        what: "finding a free port".into(),
        source,
    })?;
    listener
        .local_addr()
        .map(|a| a.port())
        .map_err(|source| E2eError::Io {
            what: "finding a free port".into(),
            source,
        })
}

/// Waits until something accepts connections on `port`.
pub fn wait_for_port(guard: &mut Guard, port: u16, within: Duration) -> Result<()> {
    let start = Instant::now();
    loop {
        if TcpStream::connect((Ipv4Addr::LOCALHOST, port)).is_ok() {
            return Ok(());
        }
        if let Some(status) = guard.exited() {
            return Err(E2eError::Setup(format!(
                "{} exited ({status}) before listening on port {port}",
                guard.name
            )));
        }
        if start.elapsed() > within {
            return Err(E2eError::Timeout {
                what: format!("{} to listen on port {port}", guard.name),
                seconds: within.as_secs(),
                last: "no connection".into(),
            });
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// The real server (`e2e-server`, the same code as `server`) on a free
/// port, its store in `data`, its log in `log`.
pub struct Server {
    pub guard: Guard,
    /// `127.0.0.1:PORT`.
    pub addr: String,
}

impl Server {
    pub fn start(binary: &Path, data: &Path, log: &Path) -> Result<Server> {
        Server::start_with(binary, data, log, "127.0.0.1:0", &[])
    }

    /// The server listening on `addr` (`127.0.0.1:0`: a free port; a fixed
    /// port to start it again where it was), with `extra` flags.
    pub fn start_with(
        binary: &Path,
        data: &Path,
        log: &Path,
        addr: &str,
        extra: &[&str],
    ) -> Result<Server> {
        let log_file = std::fs::File::create(log).map_err(|source| E2eError::Io {
            what: format!("creating {}", log.display()),
            source,
        })?;
        let mut cmd = Command::new(binary);
        cmd.args(["--addr", addr, "--log", "info,server=debug"])
            .arg("--data-dir")
            .arg(data)
            .args(extra)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(log_file);
        let mut guard = Guard::spawn("server", cmd)?;
        let stdout = guard
            .child
            .stdout
            .take()
            .ok_or_else(|| E2eError::Setup("the server's stdout is not piped".into()))?;
        // The server's one line on stdout: `listening on http://ADDR`.
        let mut line = String::new();
        BufReader::new(stdout)
            .read_line(&mut line)
            .map_err(|source| E2eError::Io {
                what: "reading the server's first line".into(),
                source,
            })?;
        let addr = line
            .trim()
            .strip_prefix("listening on http://")
            .ok_or_else(|| {
                E2eError::Setup(format!(
                    "the server did not start (first line {line:?}; log in {})",
                    log.display()
                ))
            })?
            .to_string();
        Ok(Server { guard, addr })
    }

    /// SIGKILL to the server's whole process group: no chance to clean up.
    pub fn kill(self) {
        drop(self.guard);
    }

    pub fn url(&self, path: &str) -> String {
        format!("http://{}{path}", self.addr)
    }
}
