//! Starting a service's process for tests: as the right user, tied to the
//! thread that started it (the kernel's parent-death signal stops it if
//! the test process dies first), on a free loopback port, and once per
//! test process however many tests ask for it.

use std::path::PathBuf;
use std::process::Command;

/// A command that runs as `user` (uid, gid; if any) and gets SIGTERM when
/// the thread of this process that spawned it ends.
pub fn command(program: PathBuf, user: Option<(u32, u32)>) -> Command {
    use std::os::unix::process::CommandExt;
    let mut cmd = Command::new(program);
    // SAFETY: only async-signal-safe calls between fork and exec.
    unsafe {
        cmd.pre_exec(move || {
            if let Some((uid, gid)) = user {
                if libc::setgid(gid) != 0 || libc::setuid(uid) != 0 {
                    return Err(std::io::Error::last_os_error());
                }
            }
            // After the credentials change, which clears it.
            libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGTERM);
            Ok(())
        });
    }
    cmd
}

/// A port on loopback nobody listens on now.
pub fn free_port() -> std::io::Result<u16> {
    let l = std::net::TcpListener::bind("127.0.0.1:0")?;
    Ok(l.local_addr()?.port())
}

/// Starts a service once per process, from a thread parked for good (the
/// service's parent-death signal is tied to the thread that started it),
/// and keeps the outcome in `cell`.
pub fn start_for_process<T: Send + Sync + 'static>(
    cell: &'static std::sync::OnceLock<Result<T, String>>,
    thread: &str,
    start: fn() -> Result<T, String>,
) -> &'static Result<T, String> {
    cell.get_or_init(|| {
        let (tx, rx) = std::sync::mpsc::channel();
        let spawned = std::thread::Builder::new()
            .name(thread.into())
            .spawn(move || {
                let _ = tx.send(start());
                loop {
                    std::thread::park();
                }
            });
        match spawned {
            Ok(_) => rx.recv().map_err(|e| e.to_string()).and_then(|r| r),
            Err(e) => Err(e.to_string()),
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_free_port_can_be_listened_on() {
        let port = free_port().unwrap();
        assert_ne!(port, 0);
        std::net::TcpListener::bind(("127.0.0.1", port)).unwrap();
    }

    #[test]
    fn a_service_is_started_once_per_process_and_its_outcome_kept() {
        use std::sync::atomic::{AtomicU32, Ordering};
        static STARTS: AtomicU32 = AtomicU32::new(0);
        static CELL: std::sync::OnceLock<Result<u32, String>> = std::sync::OnceLock::new();
        fn start() -> Result<u32, String> {
            Ok(STARTS.fetch_add(1, Ordering::SeqCst) + 7)
        }
        let first = start_for_process(&CELL, "test-service", start);
        let again = start_for_process(&CELL, "test-service", start);
        assert_eq!((first, again), (&Ok(7), &Ok(7)));
        assert_eq!(STARTS.load(Ordering::SeqCst), 1);
    }

    #[test]
    fn a_service_that_cannot_start_keeps_its_reason() {
        static CELL: std::sync::OnceLock<Result<u32, String>> = std::sync::OnceLock::new();
        let r = start_for_process(&CELL, "test-missing", || Err("not installed".into()));
        assert_eq!(r, &Err("not installed".to_string()));
    }
}
