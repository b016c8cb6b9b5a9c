//! Bots on a real server: the `bots` runner ([`bots::runner`]) plays over
//! the documented HTTP + WebSocket protocol against the real server
//! process (`e2e-server`, built-in bots without their delay): two runners
//! play each other to the end and agree with the stored record; a runner
//! beats (or loses to) a built-in level; a runner survives the server
//! being killed and started again mid-match; a runner whose shot is
//! refused keeps the refusal in its report and plays on; a bot account
//! online on the event stream is paired on the ladder, plays its rated
//! match to the end and is rated.

use bots::runner::{CreateMatch, Opponent, RunReport, Runner, RunnerOptions};
use bots::{by_name, Bot, Context, Decision};
use e2e::process::{free_port, Server};
use e2e::{api, artifacts_dir};
use game::protocol::ErrorCode;
use game::{Config, MatchRecord, Replay, Shot};
use std::path::Path;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::Arc;
use std::time::Duration;

/// No test here runs longer.
const MATCH_LIMIT: Duration = Duration::from_secs(60);

fn start(data: &Path, addr: &str, log: &str) -> Server {
    let log = artifacts_dir()
        .unwrap_or_else(|e| panic!("{e}"))
        .join(format!("bots-{log}.log"));
    Server::start_with(
        Path::new(env!("CARGO_BIN_EXE_e2e-server")),
        data,
        &log,
        addr,
        &["--bot-delay-ms", "0"],
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

fn runner(server: &Server, name: &str) -> Runner {
    Runner::new(&server.url(""))
        .unwrap()
        .with_options(RunnerOptions {
            name: name.into(),
            ..RunnerOptions::default()
        })
}

async fn play<B: Bot + 'static>(
    runner: &Runner,
    grant: &bots::SeatGrant,
    bot: B,
) -> (RunReport, B) {
    tokio::time::timeout(MATCH_LIMIT, runner.play(grant, bot))
        .await
        .unwrap_or_else(|_| panic!("the match was not over within {MATCH_LIMIT:?}"))
        .unwrap_or_else(|e| panic!("{e}"))
}

/// The finished match's record from the API, replayed.
async fn replayed(server: &Server, id: &str) -> Replay {
    let (status, json) = api::get_json(&server.addr, &format!("/api/matches/{id}/record"))
        .await
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(status, 200, "{json}");
    let record: MatchRecord = serde_json::from_value(json).unwrap();
    Replay::new(record).unwrap()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn two_runners_play_each_other_to_the_end_and_agree_with_the_stored_record() {
    let scratch = tempfile::tempdir().unwrap();
    let server = start(&scratch.path().join("data"), "127.0.0.1:0", "two-runners");
    let (a, b) = (runner(&server, "greedy"), runner(&server, "random"));
    let mut create = CreateMatch::open(Config::standard());
    create.turn_seconds = Some(10);
    let first = a.create(&create).await.unwrap();
    let second = b.join(&first.match_id, Some("random")).await.unwrap();
    assert_eq!(second.match_id, first.match_id);
    // Before the first shot the listing publishes the noise commitment.
    let (status, summary) =
        api::get_json(&server.addr, &format!("/api/matches/{}", first.match_id))
            .await
            .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(status, 200, "{summary}");
    let committed = summary["noise_commitment"]
        .as_str()
        .unwrap_or_default()
        .to_string();
    assert_eq!(committed.len(), 64, "{summary}");
    let ((ra, _), (rb, _)) = tokio::join!(
        play(&a, &first, by_name("greedy", 1).unwrap()),
        play(&b, &second, by_name("random", 2).unwrap()),
    );
    eprintln!(
        "{} shots; {:?}; errors {:?} / {:?}",
        ra.shots, ra.result, ra.errors, rb.errors
    );
    let result = ra.result.expect("a result");
    assert_eq!(rb.result, Some(result), "both seats saw the same end");
    assert_eq!(ra.shots, rb.shots);
    assert_eq!(ra.my_shots + rb.my_shots, ra.shots);
    assert_ne!(ra.side, rb.side);
    assert_eq!(ra.score().unwrap() + rb.score().unwrap(), 1.0);
    assert!(ra.errors.is_empty() && rb.errors.is_empty());
    let replay = replayed(&server, &first.match_id).await;
    assert_eq!(replay.game().result(), Some(result));
    assert_eq!(replay.game().shots(), ra.shots);
    assert_eq!(ra.record.as_ref(), Some(replay.game().record()));
    // The record reveals the secret of that very commitment, and verifies.
    let verified = game::verify(replay.record()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(verified.commitment.to_hex(), committed);
    assert_eq!(verified.shots, ra.shots as usize);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_runner_plays_a_whole_match_against_a_built_in_level() {
    let scratch = tempfile::tempdir().unwrap();
    let server = start(&scratch.path().join("data"), "127.0.0.1:0", "against-level");
    let r = runner(&server, "greedy");
    let mut create = CreateMatch::against("easy", Config::standard());
    create.turn_seconds = Some(10);
    let grant = r.create(&create).await.unwrap();
    let (report, _) = play(&r, &grant, by_name("greedy", 3).unwrap()).await;
    eprintln!("{} shots; {:?}", report.shots, report.result);
    let result = report.result.expect("a result");
    assert!(report.my_shots > 0);
    assert_eq!(report.reconnects, 0);
    assert!(report.errors.is_empty(), "{:?}", report.errors);
    let replay = replayed(&server, &grant.match_id).await;
    assert_eq!(replay.game().result(), Some(result));
}

/// A bot counting its decisions, slow for the first few (so the test can
/// stop the server mid-match).
struct Counting<B> {
    inner: B,
    decided: Arc<AtomicU32>,
    slow_for: u32,
}

impl<B: Bot> Bot for Counting<B> {
    fn decide(&mut self, ctx: &Context) -> Decision {
        if self.decided.load(Ordering::SeqCst) < self.slow_for {
            std::thread::sleep(Duration::from_millis(150));
        }
        let d = self.inner.decide(ctx);
        self.decided.fetch_add(1, Ordering::SeqCst);
        d
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_runner_reconnects_after_the_server_is_killed_and_restarted_mid_match() {
    let scratch = tempfile::tempdir().unwrap();
    let data = scratch.path().join("data");
    let addr = format!("127.0.0.1:{}", free_port().unwrap());
    let server = start(&data, &addr, "restart-1");
    let r = runner(&server, "greedy");
    let mut create = CreateMatch::against("easy", Config::default());
    create.turn_seconds = Some(10);
    let grant = r.create(&create).await.unwrap();
    let decided = Arc::new(AtomicU32::new(0));
    let bot = Counting {
        inner: by_name("greedy", 4).unwrap(),
        decided: decided.clone(),
        slow_for: 6,
    };
    let playing = {
        let (r, grant) = (r.clone(), grant.clone());
        tokio::spawn(async move { play(&r, &grant, bot).await })
    };
    let waited = std::time::Instant::now();
    while decided.load(Ordering::SeqCst) < 3 {
        assert!(
            waited.elapsed() < Duration::from_secs(20),
            "the bot never decided three times"
        );
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
    let (_, before) = api::get_json(&server.addr, &format!("/api/matches/{}", grant.match_id))
        .await
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(before["status"], "live", "{before}");
    server.kill();
    tokio::time::sleep(Duration::from_millis(300)).await;
    let server = start(&data, &addr, "restart-2");
    let (report, bot) = playing.await.unwrap();
    eprintln!(
        "{} shots, {} reconnects; {:?}",
        report.shots, report.reconnects, report.result
    );
    assert!(report.reconnects >= 1, "{report:?}");
    let result = report.result.expect("a result");
    assert!(bot.decided.load(Ordering::SeqCst) > 3);
    let replay = replayed(&server, &grant.match_id).await;
    assert_eq!(replay.game().result(), Some(result));
    assert!(replay.game().shots() >= 3);
}

/// Flicks the enemy's piece on its first turn, then plays like `inner`.
struct IllegalFirst<B> {
    inner: B,
    tried: bool,
}

impl<B: Bot> Bot for IllegalFirst<B> {
    fn decide(&mut self, ctx: &Context) -> Decision {
        let d = self.inner.decide(ctx);
        if self.tried {
            return d;
        }
        let Decision::Shot(mine) = d else { return d };
        let Some(theirs) = ctx.view.board.of(ctx.me.opponent()).next() else {
            return d;
        };
        self.tried = true;
        match Shot::new(theirs.id, mine.velocity(), ctx.config()) {
            Ok(shot) => Decision::Shot(shot),
            Err(_) => d,
        }
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_refused_shot_is_reported_with_its_code_and_the_match_plays_on_to_its_end() {
    let scratch = tempfile::tempdir().unwrap();
    let server = start(&scratch.path().join("data"), "127.0.0.1:0", "refused");
    let r = runner(&server, "cheat");
    let create = CreateMatch {
        name: Some("cheat".into()),
        opponent: Opponent::Level("easy".into()),
        config: Config::default(),
        turn_seconds: Some(2),
        seed: None,
    };
    // A refused shot loses that turn, and a computer that knocks a piece
    // off shoots again: now and then it sweeps the match before our second
    // turn, so that match cannot show us playing on. Another one can.
    let mut attempt = 0;
    let (grant, report) = loop {
        attempt += 1;
        let grant = r.create(&create).await.unwrap();
        let bot = IllegalFirst {
            inner: by_name("greedy", 5).unwrap(),
            tried: false,
        };
        let (report, bot) = play(&r, &grant, bot).await;
        eprintln!(
            "{} shots; {:?}; errors {:?}",
            report.shots, report.result, report.errors
        );
        assert!(bot.tried);
        let codes: Vec<ErrorCode> = report.errors.iter().map(|e| e.code).collect();
        assert_eq!(
            codes,
            [ErrorCode::NotYourPiece],
            "refused once, never sent again"
        );
        assert!(report.result.is_some());
        assert!(report.sent > report.my_shots, "the refused shot was sent");
        if report.my_shots > 0 || attempt == 3 {
            break (grant, report);
        }
        eprintln!("the computer swept match {attempt} before our second turn; another");
    };
    assert!(report.my_shots > 0, "it played on after the refusal");
    let replay = replayed(&server, &grant.match_id).await;
    assert_eq!(replay.game().result(), report.result);
}

#[test]
fn a_tournament_against_a_running_server_plays_every_game_there_and_leaves_the_records() {
    let scratch = tempfile::tempdir().unwrap();
    let server = start(&scratch.path().join("data"), "127.0.0.1:0", "tournament");
    let settings = bots::tournament::TournamentSettings {
        bots: vec!["random".into(), "easy".into()],
        games: 2,
        seed: 1,
        config: Config::standard(),
        sprt: None,
        limits: bots::ArenaLimits::default(),
        progress: false,
        server: Some(server.url("")),
    };
    let report = bots::tournament::run(&settings).unwrap_or_else(|e| panic!("{e}"));
    let games = &report.pairings[0].games;
    assert_eq!(games.len(), 2);
    assert_eq!(report.pairings[0].wdl.games(), 2);
    let rt = tokio::runtime::Runtime::new().unwrap();
    let (status, list) = rt
        .block_on(api::get_json(&server.addr, "/api/matches?status=finished"))
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(status, 200);
    let finished = list["matches"].as_array().unwrap();
    assert_eq!(finished.len(), 2, "{list}");
    for g in games {
        // Each game's record is the server's, and replays to its result.
        let replay = Replay::new(g.record.clone()).unwrap();
        assert!(replay.game().is_over());
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_online_bot_is_paired_on_the_ladder_plays_to_the_end_and_is_rated() {
    let scratch = tempfile::tempdir().unwrap();
    let log = artifacts_dir()
        .unwrap_or_else(|e| panic!("{e}"))
        .join("bots-ladder.log");
    let server = Server::start_with(
        Path::new(env!("CARGO_BIN_EXE_e2e-server")),
        &scratch.path().join("data"),
        &log,
        "127.0.0.1:0",
        &[
            "--bot-delay-ms",
            "0",
            "--bot-think-ms",
            "50",
            "--ladder-seconds",
            "1",
        ],
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let body = serde_json::json!({"name": "RandomBot", "bot": true});
    let (status, made) = api::post_json(&server.addr, "/api/accounts", &body)
        .await
        .unwrap();
    assert_eq!(status, 201, "{made}");
    let key = made["key"].as_str().unwrap().to_string();
    let options = bots::online::OnlineOptions {
        ladder: true,
        max_matches: 1,
        stop_after: Some(1),
    };
    let online = bots::online::Online::new(
        runner(&server, "RandomBot"),
        &key,
        |n| by_name("random", n).unwrap(),
        options,
    );
    let report = tokio::time::timeout(MATCH_LIMIT, online.run())
        .await
        .unwrap_or_else(|_| panic!("no ladder match played within {MATCH_LIMIT:?}"))
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((report.finished, report.failed), (1, 0), "{report:?}");
    assert!(report.rating.is_some(), "{report:?}");
    let (_, profile) = api::get_json(&server.addr, "/api/accounts/randombot")
        .await
        .unwrap();
    assert_eq!(profile["games"], 1, "{profile}");
    assert_eq!(profile["rating"].as_i64(), report.rating, "{profile}");
}
