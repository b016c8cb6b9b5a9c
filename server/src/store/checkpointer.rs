//! The checkpointer: copies the store's write-ahead log back into the
//! database file on its own thread and its own SQLite connection, so that
//! no group commit ever waits for a checkpoint. Left to itself SQLite
//! checkpoints inside whichever commit pushes the log past 1000 pages:
//! that commit then writes and syncs a thousand pages, and every move
//! queued behind it waits (the p99 of the commit time). Here the writer's
//! connection has automatic checkpoints off and [nudges](Nudge::nudge)
//! this thread after each commit; the thread lets writes gather for a
//! moment, then runs passive checkpoints (they never block the writer)
//! until the log is fully copied, which lets the next commit start the log
//! over from its beginning, so the log file stays small.
//!
//! Under a steady stream of commits (thousands of moves a second) passive
//! checkpoints never catch the writer and the log never starts over; the
//! store's writer itself then empties it between two group commits
//! ([`crate::store`]), which no checkpoint on this thread could do: it
//! would starve waiting for a moment without a writer.

use crate::config::SyncMode;
use crate::store::StoreError;
use rusqlite::Connection;
use std::path::Path;
use std::sync::{Arc, Condvar, Mutex};
use std::time::Duration;
use tracing::warn;

/// How long writes gather before a checkpoint runs.
const GATHER: Duration = Duration::from_millis(200);
/// Passive checkpoints run back to back at most this many times per nudge:
/// each copies what the writer appended during the one before, so they
/// converge unless a reader holds an old snapshot.
const PASSES: usize = 8;

#[derive(Default)]
struct State {
    dirty: bool,
    closing: bool,
}

#[derive(Default)]
struct Signal {
    state: Mutex<State>,
    wake: Condvar,
}

/// The background checkpoint thread of one database file.
pub struct Checkpointer {
    signal: Arc<Signal>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Checkpointer {
    /// Opens a second connection to the database at `path` and starts the
    /// thread. `sync` is the store's: a checkpoint syncs the database file
    /// before the log may be reused.
    pub fn start(path: &Path, sync: SyncMode) -> Result<Checkpointer, StoreError> {
        let conn = Connection::open(path)?;
        // Reading the journal mode opens the database, so this connection
        // sees the log (until then a checkpoint finds nothing to copy).
        let mode: String = conn.query_row("PRAGMA journal_mode", [], |r| r.get(0))?;
        if !mode.eq_ignore_ascii_case("wal") {
            warn!(%mode, "the store is not in write-ahead-log mode; nothing to checkpoint");
        }
        conn.pragma_update(None, "synchronous", sync.pragma())?;
        conn.busy_timeout(Duration::from_secs(5))?;
        let signal = Arc::new(Signal::default());
        let thread = {
            let signal = signal.clone();
            std::thread::Builder::new()
                .name("checkpointer".into())
                .spawn(move || run(&conn, &signal))
                .map_err(|e| StoreError::Thread("checkpoint", e))?
        };
        Ok(Checkpointer {
            signal,
            thread: Some(thread),
        })
    }

    /// A handle that tells the thread the log has grown.
    pub fn nudger(&self) -> Nudge {
        Nudge(self.signal.clone())
    }
}

/// Tells a [`Checkpointer`] that the log has grown (cheap to clone; after
/// the checkpointer has stopped, nudging does nothing).
#[derive(Clone)]
pub struct Nudge(Arc<Signal>);

impl Nudge {
    pub fn nudge(&self) {
        if let Ok(mut state) = self.0.state.lock() {
            if !state.dirty {
                state.dirty = true;
                self.0.wake.notify_one();
            }
        }
    }
}

impl Drop for Checkpointer {
    /// Stops the thread (a checkpoint in progress finishes first).
    fn drop(&mut self) {
        if let Ok(mut state) = self.signal.state.lock() {
            state.closing = true;
        }
        self.signal.wake.notify_one();
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

fn run(conn: &Connection, signal: &Signal) {
    loop {
        {
            let Ok(mut state) = signal.state.lock() else {
                return;
            };
            while !state.dirty && !state.closing {
                state = match signal.wake.wait(state) {
                    Ok(s) => s,
                    Err(_) => return,
                };
            }
            if state.closing {
                return;
            }
            // Let more commits land in the log before copying it.
            state = match signal.wake.wait_timeout(state, GATHER) {
                Ok((s, _)) => s,
                Err(_) => return,
            };
            if state.closing {
                return;
            }
            state.dirty = false;
        }
        for _ in 0..PASSES {
            match passive(conn) {
                Ok(true) => break,
                Ok(false) => {}
                Err(e) => {
                    warn!(error = %e, "background checkpoint failed; the next one retries");
                    break;
                }
            }
        }
    }
}

/// One passive checkpoint; `true` if the whole log is now in the database.
fn passive(conn: &Connection) -> Result<bool, rusqlite::Error> {
    conn.query_row("PRAGMA wal_checkpoint(PASSIVE)", [], |row| {
        let (busy, log, copied): (i64, i64, i64) = (row.get(0)?, row.get(1)?, row.get(2)?);
        Ok(busy == 0 && copied >= log)
    })
}

#[cfg(test)]
mod tests {
    use crate::config::SyncMode;
    use crate::store::{AfterMove, SqliteStore, Status, Store, StoredMatch, StoredSeat};
    use game::{Config, RecordedMove, Side};
    use std::time::{Duration, Instant};

    #[test]
    fn the_checkpointer_copies_the_log_into_the_database_file_without_the_writer() {
        let dir = tempfile::tempdir().unwrap();
        let db = dir.path().join("chapaev.sqlite3");
        let store = SqliteStore::open(dir.path(), SyncMode::Normal).unwrap();
        store
            .create(&StoredMatch {
                id: "m".into(),
                created_at: 0,
                config: Config::default(),
                noise: game::NoiseKey::from(1),
                physics: game::PHYSICS_VERSION,
                status: Status::Live,
                bot: None,
                turn_seconds: 60,
                seats: [StoredSeat::default(), StoredSeat::default()],
                rematch_of: None,
                rated: false,
                seed: None,
            })
            .unwrap();
        let after = AfterMove {
            status: Status::Live,
            shots: 0,
            result: None,
            winner: None,
        };
        for k in 0..400 {
            let pass = RecordedMove::Pass { side: Side::White };
            store.append_move("m", k, &pass, &after).unwrap();
        }
        // The commits wrote only the log; the database file fills up when
        // the background thread has copied it (a few hundred ms).
        let size = || std::fs::metadata(&db).map(|m| m.len()).unwrap_or(0);
        let deadline = Instant::now() + Duration::from_secs(20);
        while size() < 16 * 1024 && Instant::now() < deadline {
            std::thread::sleep(Duration::from_millis(20));
        }
        assert!(
            size() >= 16 * 1024,
            "the database file holds the moves: {} bytes",
            size()
        );
        drop(store);
        let store = SqliteStore::open(dir.path(), SyncMode::Normal).unwrap();
        assert_eq!(store.moves("m").unwrap().len(), 400);
    }
}
