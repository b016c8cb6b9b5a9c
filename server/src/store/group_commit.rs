//! Group commit, for either backend: a room queues its move
//! ([`GroupCommit::submit`]) and waits for its [`MoveWrite`]
//! (asynchronously; [`MoveWrite::wait`] blocks), and the store's writer
//! thread takes every queued move and hands them to the backend's
//! [`BatchWriter`], which writes them in one transaction (one disk sync for
//! all), each move in its own savepoint so that one bad move fails alone.
//! Each writer then gets its own result. Under load this turns one sync
//! per move into one per batch, and no game thread ever blocks on the
//! disk. Dropping the [`GroupCommit`] writes what is queued and stops the
//! thread.

use super::{AfterMove, Status, StoreError};
use crate::metrics::Histogram;
use game::rating::Score;
use game::{RecordedMove, Seat};
use prometheus_client::metrics::counter::Counter;
use prometheus_client::registry::Registry;
use std::sync::{Arc, Condvar, Mutex};
use std::time::Instant;
use tokio::sync::oneshot;

/// A move waiting to be written.
pub struct QueuedMove {
    pub id: String,
    pub index: i64,
    /// The move's JSON.
    pub body: String,
    pub status: &'static str,
    pub shots: i64,
    /// The result's JSON, once the match is over.
    pub result: Option<String>,
    /// For a finished match: the first seat's score, which rates a rated
    /// match in the move's own transaction.
    pub score: Option<Score>,
}

impl QueuedMove {
    /// Move number `index` of match `id` and its row update, serialised.
    pub fn new(
        id: &str,
        index: usize,
        m: &RecordedMove,
        after: &AfterMove<'_>,
    ) -> Result<QueuedMove, StoreError> {
        Ok(QueuedMove {
            id: id.to_string(),
            index: index as i64,
            body: serde_json::to_string(m)?,
            status: after.status.as_str(),
            shots: after.shots as i64,
            result: after.result.map(serde_json::to_string).transpose()?,
            score: match (after.status, after.winner) {
                (Status::Finished, Some(Seat::First)) => Some(Score::Win),
                (Status::Finished, Some(Seat::Second)) => Some(Score::Loss),
                (Status::Finished, None) => Some(Score::Draw),
                _ => None,
            },
        })
    }
}

/// What a backend does with a batch of moves.
pub trait BatchWriter: Send + 'static {
    /// Writes `batch` in one transaction, each move (with its match row and,
    /// for a rated match's last move, the ratings) undone alone if it
    /// fails; one result per move, in order. If the transaction itself
    /// fails, every move's result is an error.
    fn write(&mut self, batch: &[QueuedMove]) -> Vec<Result<(), StoreError>>;

    /// Runs after each batch's writers have their answers, on the writer
    /// thread (SQLite empties an overgrown log file here). Does nothing by
    /// default.
    fn after_batch(&mut self) {}
}

/// Where a queued move's writer waits for its result.
type Answer = oneshot::Sender<Result<(), StoreError>>;

/// A queued move's write: wait for it to learn whether the move is stored.
#[must_use = "a move is only stored once its write has completed"]
pub struct MoveWrite(oneshot::Receiver<Result<(), StoreError>>);

impl MoveWrite {
    /// Waits (asynchronously) until the move is committed or has failed.
    pub async fn done(self) -> Result<(), StoreError> {
        self.0
            .await
            .map_err(|_| StoreError::GroupCommit("the store closed first".into()))?
    }

    /// Blocks the thread until the move is committed or has failed (not
    /// from inside an async task: use [`MoveWrite::done`] there).
    pub fn wait(self) -> Result<(), StoreError> {
        self.0
            .blocking_recv()
            .map_err(|_| StoreError::GroupCommit("the store closed first".into()))?
    }
}

/// Moves waiting for the next group commit.
#[derive(Default)]
struct Queue {
    moves: Vec<(QueuedMove, Answer)>,
    closing: bool,
}

/// What the submitters and the writer thread share.
#[derive(Default)]
struct Shared {
    queue: Mutex<Queue>,
    /// Signalled when a move is queued or the store closes.
    wake: Condvar,
    /// How long each group commit took, from taking the batch to its
    /// answers (writes, commit, sync).
    commits: Histogram,
    /// Moves written by those commits.
    moves_committed: Counter,
}

/// The queue and the writer thread.
pub struct GroupCommit {
    shared: Arc<Shared>,
    writer: Option<std::thread::JoinHandle<()>>,
}

impl GroupCommit {
    /// Starts the writer thread, which writes through `backend`.
    pub fn start(backend: impl BatchWriter) -> Result<GroupCommit, StoreError> {
        let shared = Arc::new(Shared::default());
        let writer = {
            let shared = shared.clone();
            std::thread::Builder::new()
                .name("store-writer".into())
                .spawn(move || write_loop(&shared, backend))
                .map_err(|e| StoreError::Thread("writer", e))?
        };
        Ok(GroupCommit {
            shared,
            writer: Some(writer),
        })
    }

    /// Queues a move for the next group commit.
    pub fn submit(
        &self,
        id: &str,
        index: usize,
        m: &RecordedMove,
        after: &AfterMove<'_>,
    ) -> Result<MoveWrite, StoreError> {
        let queued = QueuedMove::new(id, index, m, after)?;
        let (done, answer) = oneshot::channel();
        let mut queue = self.shared.queue.lock().map_err(|_| StoreError::Poisoned)?;
        if queue.closing {
            return Err(StoreError::GroupCommit("the store is closing".into()));
        }
        queue.moves.push((queued, done));
        drop(queue);
        self.shared.wake.notify_one();
        Ok(MoveWrite(answer))
    }

    /// Registers the group commits (count and duration) and the moves
    /// they wrote in `registry`.
    pub fn register_metrics(&self, registry: &mut Registry) {
        registry.register(
            "chapaev_store_moves_committed",
            "Moves handed to group commits",
            self.shared.moves_committed.clone(),
        );
        self.shared.commits.register(
            registry,
            "chapaev_store_commit_seconds",
            "Time of each group commit: the batch's writes, the commit and its sync",
        );
    }
}

impl Drop for GroupCommit {
    /// Writes what is still queued, then stops the writer thread.
    fn drop(&mut self) {
        if let Ok(mut queue) = self.shared.queue.lock() {
            queue.closing = true;
        }
        self.shared.wake.notify_one();
        if let Some(writer) = self.writer.take() {
            let _ = writer.join();
        }
    }
}

/// The writer thread: waits for queued moves and commits each batch, until
/// the store closes with nothing left to write.
fn write_loop(shared: &Shared, mut backend: impl BatchWriter) {
    loop {
        let batch = {
            let Ok(mut queue) = shared.queue.lock() else {
                return;
            };
            while queue.moves.is_empty() && !queue.closing {
                queue = match shared.wake.wait(queue) {
                    Ok(q) => q,
                    Err(_) => return,
                };
            }
            if queue.moves.is_empty() {
                return;
            }
            std::mem::take(&mut queue.moves)
        };
        let started = Instant::now();
        let (moves, answers): (Vec<QueuedMove>, Vec<Answer>) = batch.into_iter().unzip();
        let mut results = backend.write(&moves);
        // A backend that answered short fails the rest rather than leave
        // their writers waiting.
        results.resize_with(moves.len(), || {
            Err(StoreError::GroupCommit("no answer for this move".into()))
        });
        shared.commits.observe(started.elapsed());
        shared.moves_committed.inc_by(moves.len() as u64);
        for (done, result) in answers.into_iter().zip(results) {
            let _ = done.send(result);
        }
        backend.after_batch();
    }
}
