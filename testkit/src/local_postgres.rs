//! A throwaway PostgreSQL server on loopback, for the tests that run the
//! store, the server and a cluster of nodes against PostgreSQL: `initdb`
//! into a fresh folder, then `postgres` on a free port, with its socket in
//! that folder. It is started from the machine's own PostgreSQL binaries
//! (found on `PATH`, under `/usr/lib/postgresql/*/bin`, or in
//! `CHAPAEV_PG_BIN`); run as root, it runs as the `postgres` user, since
//! PostgreSQL refuses root. It stops (and its folder goes) when the
//! [`LocalPostgres`] is dropped, and, should the process that started it
//! die first, when that process ends (the kernel's parent-death signal).
//! A test of what survives a database restart stops it and starts it
//! again on the same folder and port ([`LocalPostgres::stop`],
//! [`LocalPostgres::start_again`]).

use crate::process::{command, free_port, start_for_process};
use crate::skip::{self, Service};
use std::path::{Path, PathBuf};
use std::process::{Child, Stdio};
use std::time::{Duration, Instant};

/// Why no local PostgreSQL could be started.
#[derive(Debug, thiserror::Error)]
pub enum LocalPostgresError {
    #[error(
        "PostgreSQL's initdb was not found (install the postgresql package, or set CHAPAEV_PG_BIN)"
    )]
    NotInstalled,
    #[error("{0}: {1}")]
    Io(&'static str, #[source] std::io::Error),
    #[error("initdb failed: {0}")]
    Initdb(String),
    #[error("PostgreSQL did not accept connections within {0:?} (its log: {1})")]
    NotReady(Duration, String),
    #[error("running as root, but there is no `postgres` user to run PostgreSQL as")]
    NoUser,
}

/// A PostgreSQL server this process started (see the module's
/// documentation).
pub struct LocalPostgres {
    child: Child,
    /// Whether `child` was stopped ([`LocalPostgres::stop`]).
    stopped: bool,
    port: u16,
    /// Where its programs are, and whom it runs as.
    bin: PathBuf,
    user: Option<(u32, u32)>,
    /// Removed on drop.
    dir: tempfile::TempDir,
}

/// The folder with `initdb` and `postgres`.
fn bin_dir() -> Option<PathBuf> {
    if let Some(dir) = std::env::var_os("CHAPAEV_PG_BIN") {
        return Some(PathBuf::from(dir));
    }
    if let Some(path) = std::env::var_os("PATH") {
        for dir in std::env::split_paths(&path) {
            let initdb = dir.join("initdb");
            if initdb.exists() {
                // Debian links initdb into PATH but not postgres: use the
                // folder the link points to.
                let real = std::fs::canonicalize(&initdb).ok()?;
                return real.parent().map(Path::to_path_buf);
            }
        }
    }
    let mut versions: Vec<PathBuf> = std::fs::read_dir("/usr/lib/postgresql")
        .ok()?
        .filter_map(|e| e.ok())
        .map(|e| e.path().join("bin"))
        .filter(|p| p.join("initdb").exists())
        .collect();
    versions.sort();
    versions.pop()
}

/// The user id and group id to run PostgreSQL as: `postgres`'s when this
/// process is root, else none (run as ourselves).
fn run_as() -> Result<Option<(u32, u32)>, LocalPostgresError> {
    // SAFETY: geteuid has no preconditions.
    if unsafe { libc::geteuid() } != 0 {
        return Ok(None);
    }
    let passwd = std::fs::read_to_string("/etc/passwd")
        .map_err(|e| LocalPostgresError::Io("/etc/passwd", e))?;
    passwd
        .lines()
        .map(|l| l.split(':').collect::<Vec<_>>())
        .find(|f| f.first() == Some(&"postgres") && f.len() > 3)
        .and_then(|f| Some((f[2].parse().ok()?, f[3].parse().ok()?)))
        .map(Some)
        .ok_or(LocalPostgresError::NoUser)
}

impl LocalPostgres {
    /// Initialises a cluster in a fresh folder and starts it; returns once
    /// it accepts connections.
    pub fn start() -> Result<LocalPostgres, LocalPostgresError> {
        let bin = bin_dir().ok_or(LocalPostgresError::NotInstalled)?;
        let user = run_as()?;
        let dir = tempfile::Builder::new()
            .prefix("chapaev-pg-")
            .tempdir()
            .map_err(|e| LocalPostgresError::Io("making its folder", e))?;
        let data = dir.path().join("data");
        std::fs::create_dir(&data).map_err(|e| LocalPostgresError::Io("making its folder", e))?;
        if let Some((uid, gid)) = user {
            for p in [dir.path(), &data] {
                std::os::unix::fs::chown(p, Some(uid), Some(gid))
                    .map_err(|e| LocalPostgresError::Io("giving its folder to postgres", e))?;
            }
        }
        let out = command(bin.join("initdb"), user)
            .args([
                "-A",
                "trust",
                "-U",
                "postgres",
                "-E",
                "UTF8",
                "--locale=C",
                "-D",
            ])
            .arg(&data)
            .stdin(Stdio::null())
            .output()
            .map_err(|e| LocalPostgresError::Io("running initdb", e))?;
        if !out.status.success() {
            return Err(LocalPostgresError::Initdb(
                String::from_utf8_lossy(&out.stderr).into_owned(),
            ));
        }
        let port = free_port().map_err(|e| LocalPostgresError::Io("finding a free port", e))?;
        let child = spawn(&bin, user, dir.path(), port)?;
        let mut pg = LocalPostgres {
            child,
            stopped: false,
            port,
            bin,
            user,
            dir,
        };
        pg.wait_ready(Duration::from_secs(60))?;
        Ok(pg)
    }

    /// A fast shutdown (SIGINT: open transactions are rolled back, every
    /// client's connection ends); returns once it has exited.
    pub fn stop(&mut self) {
        if self.stopped {
            return;
        }
        self.stopped = true;
        // SAFETY: signalling our own child by its id.
        unsafe {
            libc::kill(self.child.id() as libc::pid_t, libc::SIGINT);
        }
        let deadline = Instant::now() + Duration::from_secs(10);
        while Instant::now() < deadline {
            if let Ok(Some(_)) = self.child.try_wait() {
                return;
            }
            std::thread::sleep(Duration::from_millis(50));
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
    }

    /// Starts it again on the same folder (every database kept) and port,
    /// after [`LocalPostgres::stop`] (a running server is stopped first);
    /// returns once it accepts connections.
    pub fn start_again(&mut self) -> Result<(), LocalPostgresError> {
        self.stop();
        self.child = spawn(&self.bin, self.user, self.dir.path(), self.port)?;
        self.stopped = false;
        self.wait_ready(Duration::from_secs(60))
    }

    fn wait_ready(&mut self, within: Duration) -> Result<(), LocalPostgresError> {
        let started = Instant::now();
        loop {
            if postgres::Client::connect(&self.url("postgres"), postgres::NoTls).is_ok() {
                return Ok(());
            }
            let exited = matches!(self.child.try_wait(), Ok(Some(_)));
            if exited || started.elapsed() > within {
                let log = std::fs::read_to_string(self.dir.path().join("postgres.log"))
                    .unwrap_or_default();
                return Err(LocalPostgresError::NotReady(within, log));
            }
            std::thread::sleep(Duration::from_millis(100));
        }
    }

    /// The port it listens on (127.0.0.1).
    pub fn port(&self) -> u16 {
        self.port
    }

    /// The process id of the `postgres` server.
    pub fn pid(&self) -> u32 {
        self.child.id()
    }

    /// The URL of database `db` on it.
    pub fn url(&self, db: &str) -> String {
        format!("postgres://postgres@127.0.0.1:{}/{db}", self.port)
    }

    /// Creates a new, empty database and returns its URL.
    pub fn fresh_database(&self, db: &str) -> Result<String, postgres::Error> {
        let mut admin = postgres::Client::connect(&self.url("postgres"), postgres::NoTls)?;
        admin.batch_execute(&format!("CREATE DATABASE \"{db}\""))?;
        Ok(self.url(db))
    }
}

impl Drop for LocalPostgres {
    /// A fast shutdown, then the folder goes.
    fn drop(&mut self) {
        self.stop();
    }
}

/// Starts `postgres` on the data folder in `dir` (its log and socket
/// there too), on loopback `port`.
fn spawn(
    bin: &Path,
    user: Option<(u32, u32)>,
    dir: &Path,
    port: u16,
) -> Result<Child, LocalPostgresError> {
    let log_path = dir.join("postgres.log");
    let log = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(&log_path)
        .map_err(|e| LocalPostgresError::Io("opening its log", e))?;
    if let Some((uid, gid)) = user {
        let _ = std::os::unix::fs::chown(&log_path, Some(uid), Some(gid));
    }
    let err = log
        .try_clone()
        .map_err(|e| LocalPostgresError::Io("opening its log", e))?;
    command(bin.join("postgres"), user)
        .arg("-D")
        .arg(dir.join("data"))
        .args(["-p", &port.to_string(), "-c", "listen_addresses=127.0.0.1"])
        .args(["-c", "max_connections=200", "-k"])
        .arg(dir)
        .stdin(Stdio::null())
        .stdout(log)
        .stderr(err)
        .spawn()
        .map_err(|e| LocalPostgresError::Io("starting postgres", e))
}

/// The process-wide local PostgreSQL the tests share, started on first
/// use from a thread that lives as long as the process (so the
/// parent-death signal stops it only when the process ends). `None` when
/// this machine has no PostgreSQL: test `test` is then skipped, with a
/// line on stderr that says so, or fails where `CHAPAEV_REQUIRE_POSTGRES`
/// is set ([`crate::skip`]).
pub fn shared(test: &str) -> Option<&'static LocalPostgres> {
    static SHARED: std::sync::OnceLock<Result<LocalPostgres, String>> = std::sync::OnceLock::new();
    let started = start_for_process(&SHARED, "local-postgres", || {
        LocalPostgres::start().map_err(|e| e.to_string())
    });
    match started {
        Ok(pg) => {
            static CLEANUP: std::sync::Once = std::sync::Once::new();
            CLEANUP.call_once(|| {
                let _ = AT_EXIT.set((pg.pid(), pg.dir.path().to_path_buf()));
                // SAFETY: registers a plain function to run at exit.
                unsafe {
                    libc::atexit(stop_shared_at_exit);
                }
            });
            Some(pg)
        }
        Err(e) => {
            skip::without(test, Service::Postgres, e);
            None
        }
    }
}

/// The shared server's process id and folder, for [`stop_shared_at_exit`].
static AT_EXIT: std::sync::OnceLock<(u32, PathBuf)> = std::sync::OnceLock::new();

/// At the process's exit (statics are never dropped): a fast shutdown of
/// the shared server, then its folder goes.
extern "C" fn stop_shared_at_exit() {
    let Some((pid, dir)) = AT_EXIT.get() else {
        return;
    };
    // SAFETY: signalling the server this process started.
    unsafe {
        libc::kill(*pid as libc::pid_t, libc::SIGINT);
    }
    let deadline = Instant::now() + Duration::from_secs(10);
    // Gone once its pid file is (PostgreSQL removes it last).
    while dir.join("data/postmaster.pid").exists() && Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(20));
    }
    let _ = std::fs::remove_dir_all(dir);
}

/// A fresh database on the [`shared`] server, named after `test` and
/// unique in this process; `None` (test `test` skipped) as [`shared`].
pub fn shared_database(test: &str) -> Option<String> {
    use std::sync::atomic::{AtomicU32, Ordering};
    static NEXT: AtomicU32 = AtomicU32::new(0);
    let pg = shared(test)?;
    let n = NEXT.fetch_add(1, Ordering::Relaxed);
    // The test's name, cut short enough that the suffix (what makes the
    // name unique) fits PostgreSQL's 63 bytes.
    let test: String = test
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .take(40)
        .collect();
    let name = format!("{test}_{}_{n}", std::process::id());
    match pg.fresh_database(&name) {
        Ok(url) => Some(url),
        Err(e) => panic!("creating database {name}: {e}"),
    }
}
