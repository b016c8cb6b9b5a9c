//! The JavaScript binding gives the very bits of native Rust: the
//! `chapaev` package (`bots/js`, built by `bots/js/build.sh`) run in Node
//! on 10,000 random simulation requests agrees with `SimulateRequest::run`
//! on every number of every answer; hostile requests are refused with the
//! wire code; the seeded functions (noise draws, random requests) and the
//! film's scenes match their Rust originals.
//!
//! Without `node` these fail with what to install, unless
//! `CHAPAEV_SKIP_BINDINGS=1`.

use e2e::js;
use e2e::same_bits;
use game::noise::{NoiseDraw, SplitMix64};
use game::simulate::random_request;
use game::{Config, Film, PieceId, SimulateRequest, Simulation};
use glam::DVec2;
use std::ffi::OsStr;
use std::io::Write;
use std::time::Instant;

/// Cases compared bit for bit.
const CASES: usize = 10_000;
/// The seed they are drawn from.
const SEED: u64 = 0x00C4_A9AE_5EED;

/// Runs `same_bits.mjs` on `requests` (JSON lines); its answer lines.
fn run_same_bits(requests: &[String]) -> Vec<String> {
    let mut file = tempfile::NamedTempFile::new().unwrap();
    for r in requests {
        writeln!(file, "{r}").unwrap();
    }
    file.flush().unwrap();
    let out = js::node(&[OsStr::new("tests/same_bits.mjs"), file.path().as_os_str()])
        .unwrap_or_else(|e| panic!("{e}"));
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(str::to_string)
        .collect()
}

#[test]
fn ten_thousand_random_requests_give_the_same_bits_in_node_as_natively() {
    if !js::ready_or_skip("same bits") {
        return;
    }
    js::build_package().unwrap_or_else(|e| panic!("{e}"));
    let mut rng = SplitMix64::new(SEED);
    let requests: Vec<SimulateRequest> = (0..CASES)
        .map(|k| {
            let mut r = random_request(&mut rng);
            // Every 100th with its film: thousands more numbers to agree on.
            r.film = k % 100 == 0;
            r
        })
        .collect();
    let lines: Vec<String> = requests
        .iter()
        .map(|r| serde_json::to_string(r).unwrap())
        .collect();

    let start = Instant::now();
    let answers = run_same_bits(&lines);
    let node_s = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let tally =
        same_bits::check("node", SEED, &requests, &answers).unwrap_or_else(|e| panic!("{e}"));
    let native_s = start.elapsed().as_secs_f64();
    eprintln!("{CASES} requests: node {node_s:.2} s (start, wasm and JSON included), native and the comparison {native_s:.2} s");
    assert_eq!(tally.errors, 0, "random requests are all valid");
}

#[test]
fn hostile_requests_are_refused_with_the_wire_code() {
    if !js::ready_or_skip("hostile requests") {
        return;
    }
    js::build_package().unwrap_or_else(|e| panic!("{e}"));
    let opening = r#""board":[{"id":0,"pos":[0.02,0.02]},{"id":4,"pos":[0.18,0.02]},{"id":12,"pos":[0.18,0.30]}]"#;
    let cases: &[(&str, String)] = &[
        ("too-fast", format!(r#"{{{opening},"piece":4,"velocity":[0,1e9]}}"#)),
        ("zero-speed", format!(r#"{{{opening},"piece":4,"velocity":[0,0]}}"#)),
        ("not-finite", format!(r#"{{{opening},"piece":4,"velocity":[1e999,0]}}"#)),
        (
            "not-finite",
            format!(r#"{{{opening},"piece":4,"velocity":[0,1],"noise":{{"angle":1e999,"speed":0}}}}"#),
        ),
        ("piece-off-board", format!(r#"{{{opening},"piece":5,"velocity":[0,1]}}"#)),
        (
            "bad-config",
            format!(r#"{{"config":{{"mu":-1}},{opening},"piece":4,"velocity":[0,1]}}"#),
        ),
        (
            "bad-board",
            r#"{"board":[{"id":0,"pos":[0.02,0.02]},{"id":0,"pos":[0.1,0.1]}],"piece":0,"velocity":[0,1]}"#.into(),
        ),
        (
            "bad-board",
            r#"{"board":[{"id":0,"pos":[0.02,0.02]},{"id":1,"pos":[0.03,0.02]}],"piece":0,"velocity":[0,1]}"#.into(),
        ),
        (
            "bad-board",
            r#"{"board":[{"id":0,"pos":[-1e999,0.02]}],"piece":0,"velocity":[0,1]}"#.into(),
        ),
        ("bad-board", r#"{"board":[{"id":0,"pos":[0.5,0.02]}],"piece":0,"velocity":[0,1]}"#.into()),
        ("bad-message", format!(r#"{{{opening},"piece":16,"velocity":[0,1]}}"#)),
        ("bad-message", format!(r#"{{{opening},"piece":4,"velocity":[null,1]}}"#)),
        ("bad-message", format!(r#"{{{opening},"piece":4,"velocity":"fast"}}"#)),
        ("bad-message", format!(r#"{{{opening},"velocity":[0,1]}}"#)),
        ("bad-message", r#"{"piece":4,"velocity":[0,1]}"#.into()),
        ("bad-message", "null".into()),
        ("bad-message", "[1,2,3]".into()),
        ("bad-message", r#""shot""#.into()),
    ];
    let lines: Vec<String> = cases.iter().map(|(_, l)| l.clone()).collect();
    let answers = run_same_bits(&lines);
    assert_eq!(answers.len(), cases.len());
    for ((code, request), answer) in cases.iter().zip(&answers) {
        let v: serde_json::Value = serde_json::from_str(answer).unwrap();
        assert_eq!(v["error"], *code, "{request} gave {answer}");
        // Natively the same, where serde_json can read the request at all.
        if let Ok(req) = serde_json::from_str::<SimulateRequest>(request) {
            assert_eq!(req.run().unwrap_err().code().as_str(), *code, "{request}");
        }
    }
}

/// The API script: hostile calls checked in JS (it exits non-zero on a
/// failed assertion), and the seeded functions' output compared here.
#[test]
fn the_whole_api_refuses_hostile_input_and_its_seeded_functions_match_rust() {
    if !js::ready_or_skip("api") {
        return;
    }
    js::build_package().unwrap_or_else(|e| panic!("{e}"));
    let out = js::node(&[OsStr::new("tests/api_check.mjs")]).unwrap_or_else(|e| panic!("{e}"));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();

    let big = 18_446_744_073_709_551_557u64;
    let mut rng = SplitMix64::new(big);
    let draws: Vec<NoiseDraw> = (0..1000).map(|_| NoiseDraw::sample(&mut rng)).collect();
    let got: Vec<NoiseDraw> = serde_json::from_value(v["noise"].clone()).unwrap();
    assert_eq!(json(&got), json(&draws), "noiseSample");

    let mut rng = SplitMix64::new(9);
    let reqs: Vec<SimulateRequest> = (0..50).map(|_| random_request(&mut rng)).collect();
    let got: Vec<SimulateRequest> = serde_json::from_value(v["requests"].clone()).unwrap();
    assert_eq!(json(&got), json(&reqs), "randomRequests");
    let got: SimulateRequest = serde_json::from_value(v["request"].clone()).unwrap();
    assert_eq!(
        got,
        random_request(&mut SplitMix64::new(9)),
        "randomRequest"
    );

    let mut rng = SplitMix64::new(big);
    let u64s: Vec<String> = (0..2).map(|_| rng.next_u64().to_string()).collect();
    let f64s = [rng.next_f64(), rng.next_f64()];
    assert_eq!(v["u64s"], serde_json::json!(u64s), "NoiseRng.nextU64");
    let got: [f64; 2] = serde_json::from_value(v["f64s"].clone()).unwrap();
    assert_eq!(
        got.map(f64::to_bits),
        f64s.map(f64::to_bits),
        "NoiseRng.nextF64"
    );

    let standard = Config::standard();
    let noise = standard.variants.noise.unwrap();
    let applied = NoiseDraw {
        angle: 1.5,
        speed: 2.5,
    }
    .apply(&noise, DVec2::new(0.3, -1.1), standard.max_speed);
    let got: DVec2 = serde_json::from_value(v["applied"].clone()).unwrap();
    assert_eq!(
        got.to_array().map(f64::to_bits),
        applied.to_array().map(f64::to_bits)
    );

    // The film and a scene in the middle of it, against the Rust film.
    let filmed: Simulation = serde_json::from_value(v["film"].clone()).unwrap();
    let film: &Film = filmed.film.as_ref().expect("a film");
    let t = filmed.duration / 3.0;
    let scene = film.scene_at(t);
    let want: Vec<serde_json::Value> = scene
        .bodies
        .iter()
        .map(|b| {
            serde_json::json!({"id": PieceId::from_body(b.id).unwrap(), "pos": b.pos, "vel": b.vel})
        })
        .collect();
    let want = serde_json::json!({"t": t, "pieces": want});
    // Re-read both through f64 so only bits, not spellings, are compared.
    let norm = |x: &serde_json::Value| {
        serde_json::to_string(&serde_json::from_value::<Moment>(x.clone()).unwrap()).unwrap()
    };
    assert_eq!(norm(&v["scene"]), norm(&want), "FilmPlayer.sceneAt");
}

#[derive(serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct Moment {
    t: f64,
    pieces: Vec<MovingPiece>,
}

#[derive(serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct MovingPiece {
    id: u8,
    pos: DVec2,
    vel: DVec2,
}

/// serde_json's text of `x`: two values with the same text have the same bits.
fn json<T: serde::Serialize>(x: &T) -> String {
    serde_json::to_string(x).unwrap()
}
