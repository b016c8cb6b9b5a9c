//! The store's read connections: a few read-only SQLite connections to the
//! store's file, beside the writer's own. In write-ahead-log mode a reader
//! sees the last committed state and never waits for the writer, so match
//! listings, summaries and loads are not held up behind a group commit's
//! sync (as they were when every query shared the writer's connection).
//! A read takes whichever connection is free, and waits for one only when
//! all are busy.

use rusqlite::{Connection, OpenFlags};
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, MutexGuard, TryLockError};
use std::time::Duration;

/// How many read connections a store on disk opens.
pub const READERS: usize = 4;

/// A fixed set of read-only connections.
pub struct Readers {
    conns: Vec<Mutex<Connection>>,
    /// Where the next search for a free connection starts.
    next: AtomicUsize,
}

/// A read connection's lock was poisoned by a panic.
#[derive(Debug, thiserror::Error)]
#[error("a read connection was poisoned")]
pub struct Poisoned;

impl Readers {
    /// Opens `count` read-only connections to the database at `path`
    /// (which the writer has already put in log mode).
    pub fn open(path: &Path, count: usize) -> Result<Readers, rusqlite::Error> {
        let flags = OpenFlags::SQLITE_OPEN_READ_ONLY | OpenFlags::SQLITE_OPEN_NO_MUTEX;
        let conns = (0..count.max(1))
            .map(|_| {
                let conn = Connection::open_with_flags(path, flags)?;
                conn.busy_timeout(Duration::from_secs(5))?;
                Ok(Mutex::new(conn))
            })
            .collect::<Result<_, rusqlite::Error>>()?;
        Ok(Readers {
            conns,
            next: AtomicUsize::new(0),
        })
    }

    /// A free connection, or (all busy) the next one once it is free.
    pub fn get(&self) -> Result<MutexGuard<'_, Connection>, Poisoned> {
        let n = self.conns.len();
        let start = self.next.fetch_add(1, Ordering::Relaxed);
        for k in 0..n {
            match self.conns[(start + k) % n].try_lock() {
                Ok(guard) => return Ok(guard),
                Err(TryLockError::WouldBlock) => continue,
                Err(TryLockError::Poisoned(_)) => return Err(Poisoned),
            }
        }
        self.conns[start % n].lock().map_err(|_| Poisoned)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn readers_see_what_the_writer_committed_and_cannot_write() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("db.sqlite3");
        let writer = Connection::open(&path).unwrap();
        writer.pragma_update(None, "journal_mode", "WAL").unwrap();
        writer.execute_batch("CREATE TABLE t (x INTEGER)").unwrap();
        let readers = Readers::open(&path, 2).unwrap();
        writer.execute("INSERT INTO t VALUES (7)", []).unwrap();
        let a = readers.get().unwrap();
        // The first is held: the second is handed out, not waited for.
        let b = readers.get().unwrap();
        let x: i64 = b.query_row("SELECT x FROM t", [], |r| r.get(0)).unwrap();
        assert_eq!(x, 7);
        assert!(a.execute("INSERT INTO t VALUES (8)", []).is_err());
    }
}
