//! Writes the golden records of the current physics version: whole matches
//! between the bots, played in process through the arena, covering the
//! variety of play (the standard and the default rules, other rule
//! variants and another board, noise on and off, the pie rule taken and
//! declined, resignation, passed turns, forfeits, every level), into
//! `game/tests/golden/physics-N/`, where `game`'s own tests replay them bit
//! for bit from then on.
//!
//! It runs only when asked (`--ignored`) with `CHAPAEV_BLESS_GOLDEN=1`. It
//! refuses to bless anything while a golden record of the current version
//! no longer replays (that needs a new physics version, not new files),
//! and it never rewrites a file that exists: it adds the missing ones. To
//! replace one, delete it first.

use bots::{by_name, play_match, ArenaLimits, Ask, Bot, Context, Decision, Level};
use game::golden::{folder_name, GoldenRecord, BLESS_VAR, WHAT_TO_DO};
use game::{
    Config, ForfeitReason, MatchRecord, MatchResult, NoiseConfig, Replay, Shot, Side,
    PHYSICS_VERSION,
};
use std::path::{Path, PathBuf};

/// Where the golden records live.
fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../game/tests/golden")
}

/// A bot with its pie-rule decision fixed.
struct PieChoice<B> {
    inner: B,
    swap: bool,
}

impl<B: Bot> Bot for PieChoice<B> {
    fn decide(&mut self, ctx: &Context) -> Decision {
        match ctx.ask() {
            Some(Ask::Pie) => Decision::Pie { swap: self.swap },
            _ => self.inner.decide(ctx),
        }
    }
}

/// A bot that resigns on its shooting turn number `at` (counting from 0).
struct Resigns<B> {
    inner: B,
    at: u32,
    seen: u32,
}

impl<B: Bot> Bot for Resigns<B> {
    fn decide(&mut self, ctx: &Context) -> Decision {
        if ctx.ask() == Some(Ask::Shoot) {
            self.seen += 1;
            if self.seen > self.at {
                return Decision::Resign;
            }
        }
        self.inner.decide(ctx)
    }
}

/// A bot that, on the turns listed (counting its own shooting turns from
/// 0), sends a shot the game refuses (an enemy piece), so the turn clock
/// runs out and passes its turn.
struct Dawdles<B> {
    inner: B,
    turns: Vec<u32>,
    seen: u32,
}

impl<B: Bot> Bot for Dawdles<B> {
    fn decide(&mut self, ctx: &Context) -> Decision {
        if ctx.ask() != Some(Ask::Shoot) {
            return self.inner.decide(ctx);
        }
        let turn = self.seen;
        self.seen += 1;
        let enemy = ctx.view.board.of(ctx.me.opponent()).next();
        match enemy {
            Some(p) if self.turns.contains(&turn) => {
                match Shot::new(p.id, glam::DVec2::new(0.0, 1.0), ctx.config()) {
                    Ok(shot) => Decision::Shot(shot),
                    Err(_) => self.inner.decide(ctx),
                }
            }
            _ => self.inner.decide(ctx),
        }
    }
}

/// A seat's player.
fn named(name: &str, seed: u64) -> Box<dyn Bot> {
    by_name(name, seed).unwrap_or_else(|| panic!("no bot {name}"))
}

/// One golden match.
struct Scenario {
    name: &'static str,
    /// The rules, in words.
    rules: &'static str,
    config: Config,
    seed: u64,
    /// The bots' names, in words.
    players: &'static str,
    first: Box<dyn Bot>,
    second: Box<dyn Bot>,
    /// Shots after which the arena stops the match.
    max_shots: u32,
    /// Whether the loser of the match walks away once the arena stops it
    /// unfinished (a forfeit for abandoning, as the server records it).
    abandon: Option<Side>,
}

fn standard() -> Config {
    Config::standard()
}

fn with(f: impl FnOnce(&mut Config)) -> Config {
    let mut c = Config::default();
    f(&mut c);
    c
}

fn scenarios() -> Vec<Scenario> {
    let quick_noisy = with(|c| {
        c.variants.quick_match = true;
        c.variants.noise = Some(NoiseConfig {
            angle_sigma: 0.05,
            speed_sigma: 0.1,
        });
    });
    let two_rows = with(|c| {
        c.variants.two_row_advance = true;
        c.variants.pie_rule = true;
        c.variants.noise = Some(game::config::STANDARD_NOISE);
    });
    let other_board = with(|c| {
        c.square = 0.05;
        c.piece_radius = 0.018;
        c.piece_mass = 0.008;
        c.mu = 0.22;
        c.restitution = 0.8;
        c.max_speed = 2.5;
        c.variants.quick_match = true;
        c.variants.noise = Some(NoiseConfig {
            angle_sigma: 0.02,
            speed_sigma: 0.04,
        });
    });
    vec![
        Scenario {
            name: "standard-sealed-noise-greedy-vs-greedy",
            rules: "standard (noise, pie rule), record format 4: ChaCha20 noise from a committed secret",
            config: standard(),
            seed: 0x5EED_0C4A,
            players: "greedy vs greedy",
            first: by_name("greedy", 31).unwrap(),
            second: by_name("greedy", 32).unwrap(),
            max_shots: 60,
            abandon: Some(Side::Black),
        },
        Scenario {
            name: "standard-hard-vs-medium",
            rules: "standard (noise, pie rule)",
            config: standard(),
            seed: 0x5EED_0001,
            players: "hard vs medium",
            first: Level::Hard.bot(11),
            second: Level::Medium.bot(12),
            max_shots: 60,
            abandon: None,
        },
        Scenario {
            name: "standard-pie-taken",
            rules: "standard (noise, pie rule), Black takes White's side",
            config: standard(),
            seed: 0x5EED_0002,
            players: "medium vs easy",
            first: Level::Medium.bot(21),
            second: Box::new(PieChoice {
                inner: Level::Easy.bot(22),
                swap: true,
            }),
            max_shots: 60,
            abandon: None,
        },
        Scenario {
            name: "standard-pie-declined-resigned",
            rules: "standard (noise, pie rule), Black keeps its side",
            config: standard(),
            seed: 0x5EED_0003,
            players: "easy vs medium, medium resigns on its 6th turn",
            first: Level::Easy.bot(31),
            second: Box::new(PieChoice {
                inner: Resigns {
                    inner: Level::Medium.bot(32),
                    at: 5,
                    seen: 0,
                },
                swap: false,
            }),
            max_shots: 60,
            abandon: None,
        },
        Scenario {
            name: "standard-rows-apart-greedy-vs-greedy",
            rules: "standard (noise, pie rule, rows kept two ranks apart), played to its end",
            config: standard(),
            seed: 0x5EED_000B,
            players: "greedy vs greedy",
            first: named("greedy", 111),
            second: named("greedy", 112),
            max_shots: 400,
            abandon: None,
        },
        Scenario {
            name: "casual-greedy-vs-random",
            rules: "casual (the defaults: no noise, no pie rule)",
            config: Config::default(),
            seed: 0x5EED_0004,
            players: "greedy vs random",
            first: named("greedy", 41),
            second: named("random", 42),
            max_shots: 60,
            abandon: None,
        },
        Scenario {
            name: "casual-greedy-vs-search-passes",
            rules: "casual (the defaults), turns passed on the clock",
            config: Config::default(),
            seed: 0x5EED_0005,
            players: "greedy vs search, greedy lets its clock run out on its 1st and 3rd turns",
            first: Box::new(Dawdles {
                inner: named("greedy", 51),
                turns: vec![0, 2],
                seen: 0,
            }),
            second: named("search", 52),
            max_shots: 50,
            abandon: None,
        },
        Scenario {
            name: "standard-forfeit-on-timeouts",
            rules: "standard (noise, pie rule), a side forfeits on the clock",
            config: standard(),
            seed: 0x5EED_0006,
            players: "random vs medium, random stops answering after its third turn",
            first: Box::new(Dawdles {
                inner: named("random", 61),
                turns: (3..40).collect(),
                seen: 0,
            }),
            second: Level::Medium.bot(62),
            max_shots: 60,
            abandon: None,
        },
        Scenario {
            name: "casual-hard-vs-easy",
            rules: "casual (the defaults): only the levels' own hands miss",
            config: Config::default(),
            seed: 0x5EED_000A,
            players: "hard vs easy",
            first: Level::Hard.bot(101),
            second: Level::Easy.bot(102),
            max_shots: 60,
            abandon: None,
        },
        Scenario {
            name: "quick-noisy-easy-vs-easy",
            rules: "quick match (one round) with strong noise",
            config: quick_noisy,
            seed: 0x5EED_0007,
            players: "easy vs easy",
            first: Level::Easy.bot(71),
            second: Level::Easy.bot(72),
            max_shots: 60,
            abandon: None,
        },
        Scenario {
            name: "two-row-advance-hard-vs-hard",
            rules: "two-row advance, pie rule and the standard noise",
            config: two_rows,
            seed: 0x5EED_0008,
            players: "hard vs hard",
            first: Level::Hard.bot(81),
            second: Level::Hard.bot(82),
            max_shots: 60,
            abandon: None,
        },
        Scenario {
            name: "other-board-medium-vs-search-abandoned",
            rules: "quick match on a bigger, slicker board with its own noise",
            config: other_board,
            seed: 0x5EED_0009,
            players: "medium vs search, stopped after 6 shots and abandoned by Black",
            first: Level::Medium.bot(91),
            second: named("search", 92),
            max_shots: 6,
            abandon: Some(Side::Black),
        },
    ]
}

/// What the match came to, in words.
fn ending(record: &MatchRecord) -> Result<String, game::ReplayError> {
    let replay = Replay::new(record.clone())?;
    let g = replay.game();
    let how = match g.result() {
        Some(MatchResult::Won { side, reason }) => {
            let reason = serde_json::json!(reason);
            format!("{side} won ({})", reason.as_str().unwrap_or("?"))
        }
        Some(MatchResult::Draw) => "a draw".to_string(),
        None => "stopped unfinished".to_string(),
    };
    let pie = record.moves.iter().find_map(|m| match m {
        game::RecordedMove::Pie { swap } => Some(*swap),
        _ => None,
    });
    let pie = match pie {
        Some(true) => ", the pie swapped the seats",
        Some(false) => ", the pie kept the seats",
        None => "",
    };
    Ok(format!(
        "{how} after {} shots in {} round(s){pie}",
        g.shots(),
        g.round()
    ))
}

/// Plays `s` and makes its golden record.
fn play(s: Scenario) -> GoldenRecord {
    let Scenario {
        name,
        rules,
        config,
        seed,
        players,
        mut first,
        mut second,
        max_shots,
        abandon,
    } = s;
    let limits = ArenaLimits {
        max_shots,
        ..ArenaLimits::default()
    };
    let report = play_match(config, seed, &mut first, &mut second, &limits)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let mut record = report.record;
    if let Some(side) = abandon {
        let replay = Replay::new(record).unwrap_or_else(|e| panic!("{name}: {e}"));
        let mut game = replay.game().clone();
        if !game.is_over() {
            game.forfeit(side, ForfeitReason::Abandoned)
                .unwrap_or_else(|e| panic!("{name}: {e}"));
        }
        record = game.record().clone();
    }
    let ending = ending(&record).unwrap_or_else(|e| panic!("{name}: {e}"));
    let about = format!("{name}: {rules}; {players}; {ending}");
    GoldenRecord::of(about, &record).unwrap_or_else(|e| panic!("{name}: {e}"))
}

#[test]
#[ignore = "writes game/tests/golden/: CHAPAEV_BLESS_GOLDEN=1 cargo test -p bots --test golden -- --ignored"]
fn blessing_adds_the_missing_golden_records_of_the_current_physics_version_only() {
    assert_eq!(
        std::env::var(BLESS_VAR).as_deref(),
        Ok("1"),
        "writing golden records takes {BLESS_VAR}=1"
    );
    let dir = golden_dir().join(folder_name(PHYSICS_VERSION));
    std::fs::create_dir_all(&dir).unwrap();
    // Every golden record of this version that exists must still hold:
    // new files are no cure for changed outcomes.
    let mut existing: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    existing.sort();
    for path in &existing {
        let text = std::fs::read_to_string(path).unwrap();
        let checked = GoldenRecord::from_json(&text).and_then(|g| g.check());
        if let Err(e) = checked {
            panic!(
                "refusing to bless: {} does not hold: {e}\n\n{WHAT_TO_DO}",
                path.display()
            );
        }
    }
    for s in scenarios() {
        let path = dir.join(format!("{}.json", s.name));
        if path.exists() {
            eprintln!("kept    {}", path.display());
            continue;
        }
        let golden = play(s);
        assert_eq!(golden.record.physics, PHYSICS_VERSION);
        golden.check().unwrap();
        let text = golden.to_json().unwrap();
        std::fs::write(&path, &text).unwrap();
        eprintln!(
            "written {} ({} moves, {} shots, {} bytes): {}",
            path.display(),
            golden.record.moves.len(),
            golden.rests.len(),
            text.len(),
            golden.about
        );
    }
}
