//! The store's cost per move: process CPU time (user + system, every
//! thread: the writer, the checkpointer) over the moves written, with moves
//! of real matches submitted `group` at a time (one group commit each), on
//! a store on disk with the server's default sync. Prints the median of
//! several rounds; CPU time, not wall time, so hypervisor steal and the
//! disk's latency do not blur it.
//!
//! `cargo bench -p server --bench store_writes`

use game::golden::GoldenRecord;
use game::session::Status;
use game::Config;
use server::config::SyncMode;
use server::store::{AfterMove, SqliteStore, Store, StoredMatch, StoredSeat};
use std::time::Duration;

const MATCHES: usize = 200;
const ROUNDS: usize = 3;

fn cpu_time() -> Duration {
    let mut usage = std::mem::MaybeUninit::<libc::rusage>::zeroed();
    // SAFETY: getrusage fills the struct it is given.
    let usage = unsafe {
        libc::getrusage(libc::RUSAGE_SELF, usage.as_mut_ptr());
        usage.assume_init()
    };
    let tv = |t: libc::timeval| Duration::new(t.tv_sec as u64, t.tv_usec as u32 * 1_000);
    tv(usage.ru_utime) + tv(usage.ru_stime)
}

fn main() {
    let golden = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../game/tests/golden/physics-1/standard-hard-vs-medium.json");
    let text = std::fs::read_to_string(&golden).expect("a golden record to take moves from");
    let record = GoldenRecord::from_json(&text)
        .expect("a readable golden record")
        .record;
    let moves = record.moves;
    for group in [1, 4, 16] {
        let mut per_move = Vec::new();
        for _ in 0..ROUNDS {
            let dir = tempfile::tempdir().expect("a scratch folder");
            let store = SqliteStore::open(dir.path(), SyncMode::Full).expect("a store");
            let ids: Vec<String> = (0..MATCHES).map(|i| format!("m{i:015}")).collect();
            for id in &ids {
                store
                    .create(&StoredMatch {
                        id: id.clone(),
                        created_at: 0,
                        config: Config::default(),
                        seed: 7,
                        physics: 1,
                        status: Status::Live,
                        bot: None,
                        turn_seconds: 30,
                        seats: [StoredSeat::default(), StoredSeat::default()],
                        rematch_of: None,
                        rated: false,
                    })
                    .expect("a match row");
            }
            let before = cpu_time();
            let mut written = 0;
            // Each match plays its moves in turn, `group` matches at once.
            for (index, mv) in moves.iter().enumerate().take(10) {
                for chunk in ids.chunks(group) {
                    let waits: Vec<_> = chunk
                        .iter()
                        .map(|id| {
                            let after = AfterMove {
                                status: Status::Live,
                                shots: index as u32 + 1,
                                result: None,
                                winner: None,
                            };
                            store.submit_move(id, index, mv, &after).expect("queued")
                        })
                        .collect();
                    for w in waits {
                        w.wait().expect("stored");
                        written += 1;
                    }
                }
            }
            per_move.push((cpu_time() - before).as_secs_f64() * 1e6 / written as f64);
        }
        per_move.sort_by(f64::total_cmp);
        println!(
            "store_writes group={group:>2}: {:.1} µs CPU per move (median of {ROUNDS}; min {:.1}, max {:.1})",
            per_move[ROUNDS / 2],
            per_move[0],
            per_move[ROUNDS - 1]
        );
    }
}
