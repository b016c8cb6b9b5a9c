//! `fingerprint`: one line per hostile scene with its event count, end and
//! a hash of every event (its time's bits, its kind) and of every disc's
//! trajectory after it (`Debug`, which tells -0.0 from +0.0), under the
//! latest revision unless another is named. Two builds of the engine that
//! compute the same bits print the same lines, so `diff` of two runs shows
//! any scene whose run changed at all (`revision-diff` compares two revisions of one build).
//! `cargo run --release -p lab --example fingerprint -- plastic-lines 0 10000`
//! (kind, first seed, scenes); an optional fourth argument names the
//! revision to run under (`r12`), so that older revisions' frozen results
//! can be checked too.

use engine::{Event, EventHandler, Limits, Revision, World, WorldConfig};
use lab::hostile::{Hostile, Kind, MAX_EVENTS};
use std::collections::hash_map::DefaultHasher;
use std::fmt::Write as _;
use std::hash::Hasher;
use std::process::ExitCode;

/// Hashes each event and the trajectories after it.
struct Fingerprint {
    hash: DefaultHasher,
    text: String,
}

impl EventHandler for Fingerprint {
    fn on_event(&mut self, world: &World, event: &Event) {
        self.text.clear();
        let _ = write!(self.text, "{:x} {:?}", event.t.to_bits(), event.kind);
        for b in world.bodies() {
            let _ = write!(self.text, " {:?} {:?}", b.id, b.trajectory);
        }
        self.hash.write(self.text.as_bytes());
    }
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (kind, seed, count, revision) = match args.as_slice() {
        [kind, seed, count] => (
            kind.as_str(),
            seed.as_str(),
            count.as_str(),
            Some(Revision::LATEST),
        ),
        [kind, seed, count, revision] => (
            kind.as_str(),
            seed.as_str(),
            count.as_str(),
            revision.parse().ok(),
        ),
        // Matches no kind: the usage below.
        _ => ("", "", "", None),
    };
    let parsed = Kind::ALL
        .into_iter()
        .find(|k| k.name() == kind)
        .zip(seed.parse::<u64>().ok())
        .zip(count.parse::<u64>().ok())
        .zip(revision);
    let Some((((kind, first), count), revision)) = parsed else {
        eprintln!("usage: fingerprint KIND FIRST_SEED COUNT [REVISION]");
        return ExitCode::FAILURE;
    };
    for seed in first..first.saturating_add(count) {
        let h = Hostile::generate(kind, seed);
        let config = WorldConfig {
            revision,
            ..WorldConfig::default()
        };
        let Ok(mut world) = World::new(&h.scene, config) else {
            println!("{} {seed} refused", kind.name());
            continue;
        };
        let limits = Limits {
            until: h.until,
            max_collisions: u64::MAX,
            max_events: MAX_EVENTS,
        };
        let mut print = Fingerprint {
            hash: DefaultHasher::new(),
            text: String::new(),
        };
        let end = world.run(&limits, &mut print);
        println!(
            "{} {seed} {} {:?} {:?} {:016x}",
            kind.name(),
            world.stats().events,
            end.reason,
            end.t,
            print.hash.finish()
        );
    }
    ExitCode::SUCCESS
}
