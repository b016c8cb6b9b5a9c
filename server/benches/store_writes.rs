//! The store's cost per move, on each backend: CPU time over the moves
//! written, with moves of real matches submitted `group` at a time (one
//! group commit each), with the server's default durability. Prints the
//! median of several rounds; CPU time, not wall time, so hypervisor steal
//! and the disk's latency do not blur it.
//!
//! - SQLite: a store on disk with `--sync full`; the process's CPU (user +
//!   system, every thread: the writer, the checkpointer).
//! - PostgreSQL (where the machine has it: a throwaway server from
//!   `local_services::local_postgres`): the process's CPU plus the database
//!   server's (the postmaster and its backends, from `/proc`), since the
//!   work happens there.
//!
//! `cargo bench -p server --bench store_writes`

use game::golden::GoldenRecord;
use game::session::Status;
use game::{Config, RecordedMove};
use server::config::SyncMode;
use server::store::{AfterMove, PostgresStore, SqliteStore, Store, StoredMatch, StoredSeat};
use std::time::Duration;

const MATCHES: usize = 200;
const ROUNDS: usize = 3;

/// This process's CPU time.
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

/// The CPU time of process `pid` and its children alive now, from `/proc`.
fn tree_cpu_time(pid: u32) -> Duration {
    // SAFETY: sysconf has no preconditions.
    let ticks = unsafe { libc::sysconf(libc::_SC_CLK_TCK) }.max(1) as f64;
    let mut total = 0u64;
    let Ok(entries) = std::fs::read_dir("/proc") else {
        return Duration::ZERO;
    };
    for entry in entries.flatten() {
        let Ok(stat) = std::fs::read_to_string(entry.path().join("stat")) else {
            continue;
        };
        // The fields after the command name, which is in parentheses.
        let Some(rest) = stat.rsplit_once(") ").map(|(_, r)| r) else {
            continue;
        };
        let fields: Vec<&str> = rest.split(' ').collect();
        let this = entry.file_name().to_string_lossy().parse::<u32>().ok();
        let parent = fields.get(1).and_then(|p| p.parse::<u32>().ok());
        if this == Some(pid) || parent == Some(pid) {
            let utime: u64 = fields.get(11).and_then(|v| v.parse().ok()).unwrap_or(0);
            let stime: u64 = fields.get(12).and_then(|v| v.parse().ok()).unwrap_or(0);
            total += utime + stime;
        }
    }
    Duration::from_secs_f64(total as f64 / ticks)
}

/// A fresh store, and the folder it lives in (if any), removed with it.
type Opened = (Box<dyn Store>, Option<tempfile::TempDir>);

/// A store to measure, and the CPU time to count for it.
struct Backend {
    name: &'static str,
    open: Box<dyn Fn() -> Opened>,
    cpu: Box<dyn Fn() -> Duration>,
}

fn backends() -> Vec<Backend> {
    let mut all = vec![Backend {
        name: "sqlite",
        open: Box::new(|| {
            let dir = tempfile::tempdir().expect("a scratch folder");
            let store = SqliteStore::open(dir.path(), SyncMode::Full).expect("a store");
            (Box::new(store), Some(dir))
        }),
        cpu: Box::new(cpu_time),
    }];
    if let Some(pg) = local_services::local_postgres::shared("store_writes") {
        let pid = pg.pid();
        all.push(Backend {
            name: "postgresql",
            open: Box::new(|| {
                let url = local_services::local_postgres::shared_database("store_writes")
                    .expect("a database");
                (
                    Box::new(PostgresStore::connect(&url).expect("a store")),
                    None,
                )
            }),
            cpu: Box::new(move || cpu_time() + tree_cpu_time(pid)),
        });
    }
    all
}

/// Median CPU per move, in µs, over the rounds: moves written `group` at
/// a time.
fn measure(backend: &Backend, moves: &[RecordedMove], group: usize) -> [f64; ROUNDS] {
    let mut per_move = [0.0; ROUNDS];
    for slot in per_move.iter_mut() {
        let (store, dir) = (backend.open)();
        let ids: Vec<String> = (0..MATCHES).map(|i| format!("m{i:015}")).collect();
        for id in &ids {
            store
                .create(&StoredMatch {
                    id: id.clone(),
                    created_at: 0,
                    config: Config::default(),
                    noise: game::NoiseKey::from(7),
                    physics: 1,
                    status: Status::Live,
                    bot: None,
                    turn_seconds: 30,
                    seats: [StoredSeat::default(), StoredSeat::default()],
                    rematch_of: None,
                    rated: false,
                    seed: None,
                })
                .expect("a match row");
        }
        let before = (backend.cpu)();
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
        *slot = ((backend.cpu)() - before).as_secs_f64() * 1e6 / written as f64;
        // The store (its writer thread) goes before its folder.
        drop(store);
        drop(dir);
    }
    per_move.sort_by(f64::total_cmp);
    per_move
}

fn main() {
    let golden = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../game/tests/golden/physics-1/standard-hard-vs-medium.json");
    let text = std::fs::read_to_string(&golden).expect("a golden record to take moves from");
    let moves = GoldenRecord::from_json(&text)
        .expect("a readable golden record")
        .record
        .moves;
    for backend in backends() {
        for group in [1, 4, 16] {
            let per_move = measure(&backend, &moves, group);
            println!(
                "store_writes {:>10} group={group:>2}: {:.1} µs CPU per move (median of {ROUNDS}; min {:.1}, max {:.1})",
                backend.name,
                per_move[ROUNDS / 2],
                per_move[0],
                per_move[ROUNDS - 1]
            );
        }
    }
}
