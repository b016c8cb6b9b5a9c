//! Bots from outside the process in whole matches: the starter
//! WebAssembly bot (built from `bots/wasm-starter` for wasm32) run as the
//! server hosts it, a hostile module beside it, and a program speaking
//! JSON lines.

use bots::hosted_bot::HostedBot;
use bots::program::ProgramBot;
use bots::{by_name, play_match, ArenaLimits};
use game::{Config, MatchResult, NoiseSecret, Side};
use hosted::{BotModule, Limits};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;

/// The workspace's target folder (this test's temporary folder is in it).
fn target_dir() -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR"))
        .parent()
        .expect("the temporary folder is inside the target folder")
        .to_path_buf()
}

/// The starter bot's module, built for wasm32 as its author would.
fn starter() -> Arc<BotModule> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let target = target_dir();
    let status = Command::new(env!("CARGO"))
        .args(["build", "-p", "chapaev-starter-bot", "--release"])
        .args(["--target", "wasm32-unknown-unknown", "--target-dir"])
        .arg(&target)
        .current_dir(&root)
        .status()
        .expect("cargo runs");
    assert!(
        status.success(),
        "building the starter bot failed (it needs `rustup target add wasm32-unknown-unknown`)"
    );
    let wasm = target.join("wasm32-unknown-unknown/release/chapaev_starter_bot.wasm");
    let bytes = std::fs::read(&wasm).expect("the starter's wasm was built");
    Arc::new(BotModule::load(&bytes, &Limits::default()).expect("the starter bot loads"))
}

/// The AssemblyScript starter's module, built with npm as its author
/// would (`npm ci && npm run build`), or `None` (said out loud) where npm
/// is not installed.
fn assemblyscript_starter() -> Option<Arc<BotModule>> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("wasm-starter-as");
    if Command::new("npm").arg("--version").output().is_err() {
        eprintln!("skipped: npm is not installed, so the AssemblyScript starter cannot be built");
        return None;
    }
    let npm = |args: &[&str]| {
        let status = Command::new("npm")
            .args(args)
            .current_dir(&dir)
            .status()
            .expect("npm runs");
        assert!(status.success(), "npm {args:?} failed in {}", dir.display());
    };
    if !dir.join("node_modules/.bin/asc").exists() {
        npm(&["ci", "--no-audit", "--no-fund"]);
    }
    npm(&["run", "build"]);
    let bytes =
        std::fs::read(dir.join("build/starter.wasm")).expect("the starter's wasm was built");
    Some(Arc::new(
        BotModule::load(&bytes, &Limits::default()).expect("the AssemblyScript starter loads"),
    ))
}

/// Plays `module` as White against the greedy bot from `seed`, twice, and
/// checks the match ends, the bot never failed, and the second match is
/// the first bit for bit.
fn plays_a_whole_match_reproducibly(module: Arc<BotModule>, seed: u64) {
    let play = || {
        let mut hosted = HostedBot::new(module.clone(), NoiseSecret::from_seed(seed));
        let mut greedy = by_name("greedy", 1).unwrap();
        let report = play_match(
            Config::standard(),
            seed,
            &mut hosted,
            &mut greedy,
            &ArenaLimits::default(),
        )
        .unwrap();
        (report, hosted.usage().clone())
    };
    let (first, usage) = play();
    assert!(first.result.is_some(), "finished in {} shots", first.shots);
    assert!(usage.failures.is_empty(), "{:?}", usage.failures);
    assert!(usage.decisions > 0 && usage.shots > 0, "{usage:?}");
    assert_eq!(first.timeouts, 0);
    let replay = game::Replay::new(first.record.clone()).unwrap();
    assert_eq!(replay.game().result(), first.result);
    // The same seed: the same noise, the same random streams, the same match.
    let (again, usage_again) = play();
    assert_eq!(
        serde_json::to_string(&again.record).unwrap(),
        serde_json::to_string(&first.record).unwrap()
    );
    assert_eq!(usage_again, usage);
}

#[test]
fn the_starter_bot_plays_a_whole_match_and_its_seed_replays_it_bit_for_bit() {
    plays_a_whole_match_reproducibly(starter(), 5);
}

#[test]
fn the_assemblyscript_starter_plays_a_whole_match_and_its_seed_replays_it_bit_for_bit() {
    if let Some(module) = assemblyscript_starter() {
        plays_a_whole_match_reproducibly(module, 6);
    }
}

#[test]
fn a_looping_bot_times_out_and_forfeits_while_a_match_beside_it_plays_on() {
    let looping = wat::parse_str(
        r#"(module
            (memory (export "memory") 2)
            (func (export "chapaev_alloc") (param i32) (result i32) i32.const 65536)
            (func (export "chapaev_decide") (param i32 i32) (result i64) (loop br 0) i64.const 0))"#,
    )
    .unwrap();
    let limits = Limits {
        fuel_per_decision: 5_000_000,
        ..Limits::default()
    };
    let looping = Arc::new(BotModule::load(&looping, &limits).unwrap());
    let good = starter();
    let beside = std::thread::spawn(move || {
        let mut hosted = HostedBot::new(good, NoiseSecret::from_seed(8));
        let mut random = by_name("random", 2).unwrap();
        play_match(
            Config::standard(),
            8,
            &mut random,
            &mut hosted,
            &ArenaLimits::default(),
        )
        .map(|r| (r.result, hosted.usage().failures.len()))
    });
    let mut spinner = HostedBot::new(looping, NoiseSecret::from_seed(7));
    let mut greedy = by_name("greedy", 1).unwrap();
    let r = play_match(
        Config::default(),
        7,
        &mut spinner,
        &mut greedy,
        &ArenaLimits::default(),
    )
    .unwrap();
    // Every White turn passes on the clock; Black wins (on the board, or
    // when three timeouts forfeit).
    assert_eq!(
        r.result.as_ref().and_then(MatchResult::winner),
        Some(Side::Black)
    );
    assert!(r.timeouts >= 1, "{} timeouts", r.timeouts);
    let failures = &spinner.usage().failures;
    assert!(
        !failures.is_empty() && failures.iter().all(|f| f.contains("out of fuel")),
        "{failures:?}"
    );
    let (result, failures) = beside
        .join()
        .expect("the other match did not panic")
        .unwrap();
    assert!(result.is_some());
    assert_eq!(failures, 0);
}

/// A bot in Python with nothing but the standard library: its first piece
/// straight at the nearest enemy, nearly full power; keeps its side.
const PYTHON_BOT: &str = r#"
import json, math, sys
for line in sys.stdin:
    r = json.loads(line)
    me, v = r["me"], r["view"]
    if v["phase"]["phase"] == "pie-decision":
        print(json.dumps({"type": "pie-decision", "swap": False}), flush=True)
        continue
    mine = [p for p in v["board"] if (p["id"] < 8) == (me == "white")]
    theirs = [p for p in v["board"] if (p["id"] < 8) != (me == "white")]
    a = mine[0]
    b = min(theirs, key=lambda p: math.dist(p["pos"], a["pos"]))
    dx, dy = b["pos"][0] - a["pos"][0], b["pos"][1] - a["pos"][1]
    n = math.hypot(dx, dy)
    s = 0.9 * v["config"]["max_speed"]
    print(json.dumps({"type": "shot", "piece": a["id"], "velocity": [dx / n * s, dy / n * s]}), flush=True)
"#;

#[test]
fn a_program_speaking_json_lines_plays_a_whole_match() {
    if Command::new("python3").arg("--version").output().is_err() {
        eprintln!("skipped: python3 is not installed");
        return;
    }
    let script = Path::new(env!("CARGO_TARGET_TMPDIR")).join("jsonl_bot.py");
    std::fs::write(&script, PYTHON_BOT).unwrap();
    let mut program = ProgramBot::spawn(&format!("python3 {}", script.display())).unwrap();
    let mut random = by_name("random", 3).unwrap();
    let r = play_match(
        Config::standard(),
        11,
        &mut program,
        &mut random,
        &ArenaLimits::default(),
    )
    .unwrap();
    assert!(r.result.is_some(), "{} shots", r.shots);
    assert_eq!(program.last_error, None);
    assert_eq!(r.timeouts, 0);
}

#[test]
fn a_program_that_is_not_there_is_a_clear_error() {
    let err = ProgramBot::spawn("/nonexistent/bot --stdio").err().unwrap();
    assert!(err.to_string().contains("/nonexistent/bot"), "{err}");
}
