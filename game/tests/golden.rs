//! The golden records in `tests/golden/physics-N/`: whole matches played by
//! earlier builds (bots of every level, the standard and other rules), each
//! replayed here under its own physics version and checked bit for bit —
//! every number of every shot's outcome, the verdicts, the board each shot
//! left and the match as it ended. A failure means this build changed what
//! a shot does; the message says what to do about it.

use game::golden::{folder_name, GoldenRecord, BLESS_VAR, WHAT_TO_DO};
use game::{PhysicsVersion, RecordedMove, PHYSICS_VERSION};
use std::path::{Path, PathBuf};

fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden")
}

/// Every golden file, with the physics version its folder names.
fn golden_files() -> Vec<(u32, PathBuf)> {
    let mut files = Vec::new();
    let folders = std::fs::read_dir(golden_dir()).expect("tests/golden/ exists");
    for folder in folders {
        let folder = folder.unwrap().path();
        let name = folder.file_name().unwrap().to_string_lossy().to_string();
        let version: u32 = name
            .strip_prefix("physics-")
            .and_then(|v| v.parse().ok())
            .unwrap_or_else(|| panic!("tests/golden/{name}: not a physics-N folder"));
        for file in std::fs::read_dir(&folder).unwrap() {
            let path = file.unwrap().path();
            if path.extension().is_some_and(|x| x == "json") {
                files.push((version, path));
            }
        }
    }
    files.sort();
    files
}

fn load(path: &Path) -> GoldenRecord {
    let text = std::fs::read_to_string(path).unwrap();
    GoldenRecord::from_json(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn every_golden_record_replays_bit_for_bit_under_its_own_physics_version() {
    let files = golden_files();
    assert!(!files.is_empty(), "no golden records in tests/golden/");
    let mut failures = Vec::new();
    for (version, path) in &files {
        let golden = load(path);
        assert_eq!(
            golden.record.physics,
            *version,
            "{}: a record of physics {} in the folder of physics {version}",
            path.display(),
            golden.record.physics
        );
        if let Err(e) = golden.check() {
            failures.push(format!("{}: {e}", path.display()));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} golden records do not replay:\n{}\n\n{WHAT_TO_DO}",
        failures.len(),
        files.len(),
        failures.join("\n")
    );
    if std::env::var_os(BLESS_VAR).is_some() {
        eprintln!(
            "{BLESS_VAR} is set, but golden records are played by bots and written by \
             `cargo test -p bots --test golden -- --ignored`; this test only checks them."
        );
    }
}

#[test]
fn the_physics_versions_with_golden_records_are_exactly_those_this_build_plays() {
    let versions: std::collections::BTreeSet<u32> =
        golden_files().into_iter().map(|(v, _)| v).collect();
    let playable: std::collections::BTreeSet<u32> =
        PhysicsVersion::ALL.iter().map(|v| v.number()).collect();
    assert_eq!(
        versions,
        playable,
        "every physics version this build plays needs golden records (tests/golden/{}/ for \
         the current one: {BLESS_VAR}=1 cargo test -p bots --test golden -- --ignored), and \
         the golden records of every older version must stay, replaying under that version",
        folder_name(PHYSICS_VERSION)
    );
}

#[test]
fn the_golden_records_of_the_current_version_cover_the_variety_of_play() {
    let current: Vec<GoldenRecord> = golden_files()
        .into_iter()
        .filter(|(v, _)| *v == PHYSICS_VERSION)
        .map(|(_, p)| load(&p))
        .collect();
    let any = |f: &dyn Fn(&GoldenRecord) -> bool| current.iter().any(f);
    let moved = |g: &GoldenRecord, f: &dyn Fn(&RecordedMove) -> bool| g.record.moves.iter().any(f);
    let standard = game::Config::standard();
    let default = game::Config::default();
    assert!(any(&|g| g.record.config == standard), "the standard rules");
    assert!(any(&|g| g.record.config == default), "the default rules");
    assert!(
        any(&|g| g.record.config.variants.noise.is_none()),
        "noise off"
    );
    assert!(
        any(&|g| g.record.config.variants.noise.is_some()),
        "noise on"
    );
    assert!(
        any(&|g| g.record.config.variants.quick_match),
        "a quick match"
    );
    assert!(
        any(&|g| g.record.config.variants.two_row_advance),
        "two-row advance"
    );
    assert!(
        any(&|g| g.record.config.square != default.square),
        "another board"
    );
    for swap in [true, false] {
        assert!(
            any(&|g| moved(g, &|m| *m == RecordedMove::Pie { swap })),
            "the pie rule with swap {swap}"
        );
    }
    for kind in ["resign", "pass", "forfeit"] {
        assert!(
            any(&|g| moved(g, &|m| serde_json::json!(m)["move"] == kind)),
            "a {kind}"
        );
    }
    assert!(
        any(&|g| g
            .record
            .shots()
            .any(|s| s.round_end.is_some_and(|r| r.next_rows.is_some()))),
        "a round won with the match going on"
    );
    let won_by = |g: &GoldenRecord| match g.end.phase {
        game::Phase::Over {
            result: game::MatchResult::Won { reason, .. },
        } => Some(reason),
        _ => None,
    };
    for reason in [
        game::WinReason::FarEdge,
        game::WinReason::QuickMatch,
        game::WinReason::Resignation,
        game::WinReason::Timeouts,
        game::WinReason::Abandoned,
    ] {
        assert!(
            any(&|g| won_by(g) == Some(reason)),
            "a match won by {reason:?}"
        );
    }
    let shots: usize = current.iter().map(|g| g.rests.len()).sum();
    assert!(shots >= 200, "only {shots} shots");
}
