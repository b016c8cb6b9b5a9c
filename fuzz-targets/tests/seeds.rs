//! The seed corpus kept in `fuzz/corpus/<target>/`, written here so each
//! seed says what it is: real matches as a client sends them, the turn
//! clock, the store failing, a built-in bot, spectators and bad tokens; the
//! engine's example scenes and a few made to reach its corners; real match
//! records and damaged ones. The files must be exactly these (the fuzzers'
//! own finds are not kept; crash inputs go to `fuzz/artifacts/`):
//! `CHAPAEV_BLESS=1 cargo test -p fuzz-targets seeds` writes them again.

use fuzz_targets::script::{Decided, Op, Rules, Said, Script, Second, Token};
use game::protocol::ClientMessage;
use game::record::{MatchRecord, RecordedMove};
use game::{Config, Game, Phase, Seat, Shot, Variants};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

fn corpus(target: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../fuzz/corpus")
        .join(target)
}

/// The shot a plain aiming player takes: the own piece nearest to an
/// opponent's, straight at it, at `power` of the fastest shot.
fn aimed_shot(game: &Game, power: f64) -> Option<(Seat, Shot)> {
    let side = game.to_shoot()?;
    let board = game.board();
    let (from, to) = board
        .of(side)
        .flat_map(|p| board.of(side.opponent()).map(move |q| (p, q)))
        .min_by(|(a, b), (c, d)| {
            (a.pos - b.pos)
                .length()
                .total_cmp(&(c.pos - d.pos).length())
        })?;
    let velocity = (to.pos - from.pos).normalize() * game.config().max_speed * power;
    let shot = Shot::new(from.id, velocity, game.config()).ok()?;
    Some((game.seat_of(side), shot))
}

/// A match played out by aiming players, at most `shots` shots: the
/// messages each seat sent, and the game.
fn real_match(config: Config, seed: u64, shots: usize) -> (Vec<(Seat, ClientMessage)>, Game) {
    let mut game = Game::new(config, seed).expect("a playable config");
    let mut said = Vec::new();
    for n in 0..shots {
        if game.phase() == Phase::PieDecision {
            game.decide_pie(game::Side::Black, true)
                .expect("a pie decision");
            said.push((Seat::Second, ClientMessage::PieDecision { swap: true }));
            continue;
        }
        let power = [0.9, 0.6, 1.0, 0.75][n % 4];
        let Some((seat, shot)) = aimed_shot(&game, power) else {
            break;
        };
        game.play(game.side_of(seat), shot).expect("a legal shot");
        said.push((
            seat,
            ClientMessage::Shot {
                piece: shot.piece(),
                velocity: shot.velocity(),
            },
        ));
    }
    (said, game)
}

/// The frames of a real match between two connected players (the first
/// connection holds the first seat, the second the second).
fn match_frames(rules: Rules, config: Config, shots: usize) -> Script {
    let (said, _) = real_match(config, 7, shots);
    let mut ops = vec![
        Op::Connect {
            token: Token::First,
        },
        Op::Connect {
            token: Token::Second,
        },
    ];
    for (seat, msg) in said {
        ops.push(Op::Frame {
            conn: seat.index() as u8,
            bytes: msg.to_json().into_bytes(),
        });
        ops.push(Op::Wait { step: 20 });
    }
    ops.push(Op::Frame {
        conn: 0,
        bytes: br#"{"type":"offer-rematch"}"#.to_vec(),
    });
    ops.push(Op::Frame {
        conn: 1,
        bytes: br#"{"type":"accept-rematch"}"#.to_vec(),
    });
    ops.push(Op::RematchAnswer { created: true });
    Script {
        rules,
        second: Second::Person,
        seed: 7,
        ops,
    }
}

fn say(conn: u8, said: Said) -> Op {
    Op::Say { conn, said }
}

fn frame(conn: u8, text: &[u8]) -> Op {
    Op::Frame {
        conn,
        bytes: text.to_vec(),
    }
}

/// White's e-piece straight up the board at full power (knocks Black's off).
const KNOCK: Said = Said::Shot {
    piece: 4,
    vx: 0,
    vy: 120,
};
/// A gentle White shot that hits nothing.
const NUDGE: Said = Said::Shot {
    piece: 0,
    vx: 0,
    vy: 30,
};
/// A gentle Black shot that hits nothing.
const BLACK_NUDGE: Said = Said::Shot {
    piece: 15,
    vx: 0,
    vy: -30,
};

fn protocol_seeds() -> BTreeMap<String, Vec<u8>> {
    let connect = |token| Op::Connect { token };
    let scripts = [
        (
            "real-match-frames",
            match_frames(Rules::Casual, Config::default(), 40),
        ),
        (
            "real-quick-match-frames",
            match_frames(
                Rules::QuickMatch,
                Config {
                    variants: Variants {
                        quick_match: true,
                        ..Variants::default()
                    },
                    ..Config::default()
                },
                40,
            ),
        ),
        (
            "frames-refused-and-read",
            Script {
                rules: Rules::Casual,
                second: Second::Person,
                seed: 1,
                ops: vec![
                    connect(Token::First),
                    connect(Token::Second),
                    frame(0, b"{"),
                    frame(0, b"not json"),
                    frame(0, br#"{"type":"teleport"}"#),
                    frame(0, br#"{"type":"shot","piece":16,"velocity":[0,1]}"#),
                    frame(0, br#"{"type":"shot","piece":4,"velocity":[0,1e400]}"#),
                    frame(0, br#"{"type":"shot","piece":4,"velocity":[0,NaN]}"#),
                    frame(0, br#"{"type":"shot","piece":4,"velocity":[0,9.5]}"#),
                    frame(0, br#"{"type":"shot","piece":4,"velocity":[0,0]}"#),
                    frame(0, br#"{"type":"shot","piece":12,"velocity":[0,-1]}"#),
                    frame(1, br#"{"type":"shot","piece":12,"velocity":[0,-1]}"#),
                    frame(0, br#"{"type":"hello","protocol":1,"name":"Petka"}"#),
                    frame(0, br#"{"type":"create-match","config":{"square":0.05}}"#),
                    frame(0, br#"{"type":"join-match","match_id":"m1"}"#),
                    frame(0, br#"{"type":"watch","match_id":"m1"}"#),
                    frame(0, br#"{"type":"pie-decision","swap":true}"#),
                    frame(1, br#"{"type":"chat","text":"Vasily Ivanovich!"}"#),
                    frame(0, b"{\"type\":\"chat\",\"text\":\"\xff\xfe\"}"),
                    frame(0, br#"{"type":"shot","piece":4,"velocity":[0.0,2.0]}"#),
                    frame(0, br#"{"type":"shot","piece":3,"velocity":[-0.0,1.25e-3]}"#),
                    frame(1, br#"{"type":"resign"}"#),
                    frame(1, br#"{"type":"accept-rematch"}"#),
                    frame(0, br#"{"type":"offer-rematch"}"#),
                    frame(1, br#"{"type":"accept-rematch"}"#),
                    Op::RematchAnswer { created: false },
                ],
            },
        ),
        (
            "turn-clock-forfeit",
            Script {
                rules: Rules::Casual,
                second: Second::Person,
                seed: 2,
                ops: vec![
                    connect(Token::First),
                    connect(Token::Second),
                    say(0, NUDGE),
                    Op::Deadline,
                    Op::Deadline,
                    say(0, KNOCK),
                    Op::Deadline,
                    Op::Deadline,
                    Op::Deadline,
                    Op::Deadline,
                    Op::Deadline,
                    Op::Disconnect { conn: 0 },
                    Op::Disconnect { conn: 0 },
                    Op::Wait { step: 130 },
                    connect(Token::First),
                ],
            },
        ),
        (
            "abandoned-seat",
            Script {
                rules: Rules::Casual,
                second: Second::Person,
                seed: 3,
                ops: vec![
                    connect(Token::First),
                    connect(Token::Second),
                    connect(Token::None),
                    say(0, NUDGE),
                    Op::Disconnect { conn: 1 },
                    Op::Wait { step: 20 },
                    connect(Token::Second),
                    say(2, BLACK_NUDGE),
                    Op::Disconnect { conn: 2 },
                    Op::Deadline,
                    say(1, Said::OfferRematch),
                    say(0, Said::AcceptRematch),
                ],
            },
        ),
        (
            "bot-match",
            Script {
                rules: Rules::Standard,
                second: Second::Bot,
                seed: 4,
                ops: vec![
                    connect(Token::First),
                    say(0, NUDGE),
                    Op::Deadline,
                    Op::BotAnswer {
                        stale: 0,
                        decided: Decided::Pie { swap: false },
                    },
                    Op::Deadline,
                    Op::BotAnswer {
                        stale: 0,
                        decided: Decided::Shot {
                            piece: 12,
                            vx: 0,
                            vy: -110,
                        },
                    },
                    Op::BotAnswer {
                        stale: 0,
                        decided: Decided::Resign,
                    },
                    say(0, NUDGE),
                    Op::Deadline,
                    Op::BotAnswer {
                        stale: 0,
                        decided: Decided::Shot {
                            piece: 1,
                            vx: 0,
                            vy: 50,
                        },
                    },
                    Op::BotAnswer {
                        stale: 2,
                        decided: Decided::Resign,
                    },
                    say(0, Said::Resign),
                    say(0, Said::OfferRematch),
                    Op::RematchAnswer { created: false },
                ],
            },
        ),
        (
            "join-and-failed-writes",
            Script {
                rules: Rules::Casual,
                second: Second::Empty,
                seed: 5,
                ops: vec![
                    connect(Token::First),
                    connect(Token::Second),
                    say(0, KNOCK),
                    Op::FailNextWrite { reload: true },
                    Op::Join {
                        name: b"Anka".to_vec(),
                    },
                    Op::Join {
                        name: "Анка".as_bytes().to_vec(),
                    },
                    Op::Join {
                        name: b"late".to_vec(),
                    },
                    connect(Token::Second),
                    say(0, KNOCK),
                    Op::FailNextWrite { reload: true },
                    say(0, NUDGE),
                    say(0, NUDGE),
                    Op::FailNextWrite { reload: false },
                    say(1, Said::Resign),
                    say(0, Said::Resign),
                ],
            },
        ),
        (
            "pie-rule",
            Script {
                rules: Rules::TwoRowsAndPie,
                second: Second::Person,
                seed: 6,
                ops: vec![
                    connect(Token::First),
                    connect(Token::Second),
                    say(0, NUDGE),
                    say(0, Said::Pie { swap: true }),
                    say(1, NUDGE),
                    say(1, Said::Pie { swap: true }),
                    say(0, BLACK_NUDGE),
                    say(1, KNOCK),
                    Op::Deadline,
                    Op::Wait { step: 60 },
                ],
            },
        ),
        (
            "spectators-and-tokens",
            Script {
                rules: Rules::Casual,
                second: Second::Person,
                seed: 8,
                ops: vec![
                    connect(Token::Wrong),
                    connect(Token::Prefix),
                    connect(Token::None),
                    connect(Token::None),
                    connect(Token::First),
                    connect(Token::Second),
                    connect(Token::None),
                    say(2, Said::Chat { len: 500 }),
                    say(2, Said::Chat { len: 501 }),
                    say(0, Said::Chat { len: 3 }),
                    say(0, KNOCK),
                    say(4, Said::Resign),
                    say(2, Said::Hello),
                    Op::Disconnect { conn: 0 },
                    connect(Token::First),
                    say(3, KNOCK),
                ],
            },
        ),
        (
            "idle-close",
            Script {
                rules: Rules::Casual,
                second: Second::Empty,
                seed: 9,
                ops: vec![
                    Op::Wait { step: 130 },
                    connect(Token::First),
                    Op::Join {
                        name: b"Anka".to_vec(),
                    },
                ],
            },
        ),
    ];
    scripts
        .into_iter()
        .map(|(name, script)| (name.to_string(), script.encode()))
        .collect()
}

fn scene_seeds() -> BTreeMap<String, Vec<u8>> {
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("../engine/examples");
    let mut seeds = BTreeMap::new();
    for name in ["box", "break", "galperin"] {
        let path = examples.join(format!("{name}.json"));
        let text = std::fs::read(&path).expect("an engine example");
        seeds.insert(format!("example-{name}.json"), text);
    }
    let config = Config::default();
    let game = Game::new(config.clone(), 0).expect("the default config");
    let (_, shot) = aimed_shot(&game, 1.0).expect("an opening shot");
    let opening = game::physics::scene(&config, game.board(), shot.piece(), shot.velocity());
    seeds.insert(
        "game-opening-shot.json".into(),
        opening.to_json().into_bytes(),
    );
    let hand_written: [(&str, &str); 9] = [
        (
            "newtons-cradle.json",
            r#"{"g": 9.81, "bodies": [
  {"id": 1, "pos": [0.0, 0.0], "vel": [1.0, 0.0], "radius": 0.01, "mass": 0.01, "mu": 0.2},
  {"id": 2, "pos": [0.02, 0.0], "vel": [0.0, 0.0], "radius": 0.01, "mass": 0.01, "mu": 0.2},
  {"id": 3, "pos": [0.04, 0.0], "vel": [0.0, 0.0], "radius": 0.01, "mass": 0.01, "mu": 0.2},
  {"id": 4, "pos": [0.06, 0.0], "vel": [0.0, 0.0], "radius": 0.01, "mass": 0.01, "mu": 0.2}
]}"#,
        ),
        (
            "frictionless-box.json",
            r#"{"g": 9.81, "bodies": [
  {"id": 1, "pos": [0.5, 0.5], "vel": [1.3, 0.7], "radius": 0.05, "mass": 1, "mu": 0},
  {"id": 2, "pos": [0.2, 0.7], "vel": [-0.4, 2.1], "radius": 0.05, "mass": 2, "mu": 0}
], "lines": [
  {"a": [0, 0], "b": [1, 0], "kind": "segment"},
  {"a": [1, 0], "b": [1, 1], "kind": "segment"},
  {"a": [1, 1], "b": [0, 1], "kind": "segment"},
  {"a": [0, 1], "b": [0, 0], "kind": "segment"}
]}"#,
        ),
        (
            "points-rays-and-sensors.json",
            r#"{"g": 3.5, "t": 2.0, "bodies": [
  {"id": 7, "pos": [0.0, 0.0], "vel": [2.0, 0.1], "radius": 0.02, "mass": 0.005, "mu": 0.1, "restitution": 0.5},
  {"id": 9, "pos": [0.3, 0.05], "vel": [-1.0, 0.0], "radius": 0.03, "mass": 0.02, "mu": 0.4}
], "points": [{"pos": [0.6, 0.0]}], "lines": [
  {"a": [0.8, -1], "b": [0.8, 1], "kind": "ray"},
  {"a": [-1, 0.2], "b": [1, 0.2], "kind": "line"},
  {"a": [0.5, -1], "b": [0.5, 1], "kind": "line", "sensor": true}
]}"#,
        ),
        (
            "pushing-chain.json",
            r#"{"bodies": [
  {"id": 1, "pos": [0.0, 0.0], "vel": [0.5, 0.0], "radius": 0.016, "mass": 0.005, "mu": 0.1},
  {"id": 2, "pos": [0.032, 0.0], "vel": [0.5, 0.0], "radius": 0.016, "mass": 0.005, "mu": 0.3},
  {"id": 3, "pos": [0.064, 0.0], "vel": [0.5, 0.0], "radius": 0.016, "mass": 0.005, "mu": 0.6}
]}"#,
        ),
        (
            "overlapping.json",
            r#"{"bodies": [
  {"id": 1, "pos": [0, 0], "vel": [0, 0], "radius": 1, "mass": 1, "mu": 0.1},
  {"id": 2, "pos": [1, 0], "vel": [0, 0], "radius": 1, "mass": 1, "mu": 0.1}
]}"#,
        ),
        (
            "out-of-range.json",
            r#"{"bodies": [{"id": 1, "pos": [0, 1e400], "vel": [0, 0], "radius": 1, "mass": 1, "mu": 0.1}]}"#,
        ),
        (
            "huge-and-tiny.json",
            r#"{"g": 1e-300, "bodies": [
  {"id": 1, "pos": [-1e149, 0], "vel": [1e149, 1e-300], "radius": 1e-300, "mass": 1e300, "mu": 1e-300},
  {"id": 2, "pos": [1e149, 0], "vel": [-1e149, 0], "radius": 1e100, "mass": 1e-300, "mu": 1}
]}"#,
        ),
        (
            "near-the-bounds.json",
            r#"{"g": 1, "bodies": [
  {"id": 1, "pos": [-1e140, 0], "vel": [1e70, 0], "radius": 1e139, "mass": 1, "mu": 1},
  {"id": 2, "pos": [1e140, 0], "vel": [-1e70, 1e-300], "radius": 1e139, "mass": 2, "mu": 0.5},
  {"id": 3, "pos": [0, 1e145], "vel": [0, 0], "radius": 1e-100, "mass": 1e30, "mu": 0}
], "lines": [{"a": [-1e149, -1e149], "b": [1e149, -1e149], "kind": "line"}]}"#,
        ),
        ("unknown-field.json", r#"{"bodies": [], "wind": 3}"#),
    ];
    for (name, text) in hand_written {
        seeds.insert(name.into(), text.as_bytes().to_vec());
    }
    seeds
}

fn record_seeds() -> BTreeMap<String, Vec<u8>> {
    let mut seeds = BTreeMap::new();
    let mut put = |name: &str, text: String| {
        seeds.insert(format!("{name}.json"), text.into_bytes());
    };
    let (_, casual) = real_match(Config::default(), 11, 30);
    put("casual-match", casual.private_record().to_json());
    let (_, mut standard) = real_match(Config::standard(), 12, 6);
    if let Some(side) = standard.to_shoot() {
        standard.pass(side).expect("a pass");
    }
    if !standard.is_over() {
        standard
            .forfeit(game::Side::White, game::ForfeitReason::Timeouts)
            .expect("a forfeit");
    }
    put("standard-match-forfeited", standard.record().to_json());
    let quick = Config {
        variants: Variants {
            quick_match: true,
            two_row_advance: true,
            ..Variants::default()
        },
        ..Config::default()
    };
    let (_, quick) = real_match(quick, 13, 40);
    put("quick-match", quick.record().to_json());

    let mut v1: serde_json::Value = serde_json::from_str(
        &MatchRecord::new(
            Config::default(),
            &game::NoiseKey::SplitMix64(1),
            game::PhysicsVersion::CURRENT,
        )
        .to_json(),
    )
    .expect("json");
    v1["version"] = 1.into();
    v1["moves"] = serde_json::json!([{"move": "resign", "side": "black"}]);
    put("version-1-resigned", v1.to_string());

    let mut diverged = casual.private_record();
    if let Some(RecordedMove::Shot(first)) = diverged.moves.first_mut() {
        first.played.x = f64::from_bits(first.played.x.to_bits() ^ 1);
    }
    put("diverged", diverged.to_json());
    let key = game::NoiseKey::from(0);
    let mut illegal = MatchRecord::new(Config::default(), &key, game::PhysicsVersion::CURRENT);
    illegal.moves.push(RecordedMove::Pie { swap: true });
    put("sealed-not-revealed", illegal.to_json());
    illegal.reveal(&key);
    put("illegal-pie", illegal.to_json());
    put(
        "unplayable-config",
        r#"{"version": 2, "config": {"square": 0.04, "piece_radius": 0.03}, "seed": 0, "moves": []}"#.into(),
    );
    put(
        "unsupported-version",
        r#"{"version": 3, "config": {}, "seed": 0, "moves": []}"#.into(),
    );
    put(
        "no-version",
        r#"{"config": {}, "seed": 0, "moves": []}"#.into(),
    );
    seeds
}

/// Checks the corpus of `target` holds exactly `seeds`; with
/// `CHAPAEV_BLESS` set, writes it.
fn check_corpus(target: &str, seeds: BTreeMap<String, Vec<u8>>) {
    let dir = corpus(target);
    if std::env::var_os("CHAPAEV_BLESS").is_some() {
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("the corpus folder");
        for (name, bytes) in &seeds {
            std::fs::write(dir.join(name), bytes).expect("a seed written");
        }
    }
    let mut kept = BTreeMap::new();
    for entry in std::fs::read_dir(&dir)
        .expect("the corpus folder")
        .flatten()
    {
        let name = entry.file_name().to_string_lossy().into_owned();
        kept.insert(name, std::fs::read(entry.path()).expect("a seed"));
    }
    let stale: Vec<&String> = seeds
        .keys()
        .chain(kept.keys())
        .filter(|name| seeds.get(*name) != kept.get(*name))
        .collect();
    assert!(
        stale.is_empty(),
        "fuzz/corpus/{target} differs from its seeds at {stale:?}: \
         CHAPAEV_BLESS=1 cargo test -p fuzz-targets seeds"
    );
}

#[test]
fn the_protocol_session_seeds_are_the_scripts_written_here() {
    check_corpus("protocol_session", protocol_seeds());
}

#[test]
fn the_scene_json_seeds_are_the_engine_examples_and_the_scenes_written_here() {
    check_corpus("scene_json", scene_seeds());
}

#[test]
fn the_record_replay_seeds_are_the_records_written_here() {
    check_corpus("record_replay", record_seeds());
}

#[test]
fn the_real_match_seeds_are_played_to_the_end() {
    let (said, game) = real_match(Config::default(), 7, 40);
    assert!(said.len() > 5, "{} moves", said.len());
    assert!(game.shots() > 5);
    let (_, quick) = real_match(
        Config {
            variants: Variants {
                quick_match: true,
                ..Variants::default()
            },
            ..Config::default()
        },
        7,
        40,
    );
    assert!(quick.is_over(), "the quick match ends");
}
