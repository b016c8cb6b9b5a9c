//! The example bots of `bots/examples/`, each in its own language, play a
//! whole match against a built-in level on the real server process
//! (`e2e-server`), over nothing but the documented HTTP + WebSocket
//! protocol; the server's API then says the match finished with a result.

use e2e::process::{Guard, Server};
use e2e::python::{repo_root, venv_python};
use e2e::{api, artifacts_dir, js};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The real server, built-in bots without their delay and with a short
/// think cap.
fn start_server(data: &Path, log: &str) -> Server {
    let log = artifacts_dir()
        .unwrap_or_else(|e| panic!("{e}"))
        .join(format!("example-bots-{log}.log"));
    Server::start_with(
        Path::new(env!("CARGO_BIN_EXE_e2e-server")),
        data,
        &log,
        "127.0.0.1:0",
        &["--bot-delay-ms", "0", "--bot-think-ms", "200"],
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

/// Waits for the bot process to exit (killing it, group and all, after
/// `limit`); its exit status.
async fn finish(mut bot: Guard, limit: Duration) -> String {
    let start = Instant::now();
    loop {
        if let Some(status) = bot.exited() {
            return status;
        }
        if start.elapsed() > limit {
            drop(bot);
            panic!("the bot did not finish its match within {limit:?}");
        }
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
}

/// The finished match's summary from the API: status `finished` and a result.
async fn assert_finished(server: &Server, match_id: &str) -> serde_json::Value {
    let (status, summary) = api::get_json(&server.addr, &format!("/api/matches/{match_id}"))
        .await
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(status, 200, "{summary}");
    assert_eq!(summary["status"], "finished", "{summary}");
    assert!(!summary["result"].is_null(), "a result: {summary}");
    assert!(summary["shots"].as_u64().unwrap_or(0) > 0, "{summary}");
    summary
}

// ===== Python: bots/examples/python/bot.py =====

/// No Python example match runs longer.
const PYTHON_MATCH_LIMIT: Duration = Duration::from_secs(240);

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_python_example_bot_plays_a_whole_match_against_a_level() {
    let Some(python) = venv_python().unwrap_or_else(|e| panic!("{e}")) else {
        return;
    };
    let scratch = tempfile::tempdir().unwrap();
    let server = start_server(&scratch.path().join("data"), "python");
    let artifacts = artifacts_dir().unwrap_or_else(|e| panic!("{e}"));
    let out_path = artifacts.join("example-bot-python.out");
    let err_path = artifacts.join("example-bot-python.err");
    let mut cmd = Command::new(&python);
    cmd.arg(repo_root().join("bots/examples/python/bot.py"))
        .args([
            "--server",
            &server.url(""),
            "--level",
            "easy",
            "--rules",
            "standard",
        ])
        .args(["--turn-seconds", "30", "--budget", "1.0", "--seed", "7"])
        .stdin(Stdio::null())
        .stdout(std::fs::File::create(&out_path).unwrap())
        .stderr(std::fs::File::create(&err_path).unwrap());
    let start = Instant::now();
    let bot = Guard::spawn("python example bot", cmd).unwrap_or_else(|e| panic!("{e}"));
    let status = finish(bot, PYTHON_MATCH_LIMIT).await;
    let out = std::fs::read_to_string(&out_path).unwrap();
    let err = std::fs::read_to_string(&err_path).unwrap();
    let tail: String = err
        .lines()
        .rev()
        .take(15)
        .collect::<Vec<_>>()
        .into_iter()
        .rev()
        .collect::<Vec<_>>()
        .join("\n");
    assert!(
        status.contains("exit status: 0"),
        "the bot exited {status}; stderr ends:\n{tail}"
    );
    let lines: Vec<serde_json::Value> = out
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{e}: {l}")))
        .collect();
    assert_eq!(lines.len(), 2, "the match id, then the result: {out}");
    let match_id = lines[0]["match_id"]
        .as_str()
        .expect("a match id")
        .to_string();
    assert_eq!(lines[1]["match_id"], match_id.as_str());
    let summary = assert_finished(&server, &match_id).await;
    assert_eq!(summary["bot"], "easy", "{summary}");
    assert_eq!(
        lines[1]["result"], summary["result"],
        "the bot saw the server's result"
    );
    eprintln!(
        "python example bot: {} shots in {:.1} s, result {}",
        summary["shots"],
        start.elapsed().as_secs_f64(),
        summary["result"]
    );
}

// ===== JavaScript: bots/examples/node/bot.mjs =====

/// No Node example match runs longer.
const NODE_MATCH_LIMIT: Duration = Duration::from_secs(300);

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_node_example_bot_plays_a_whole_match_against_a_level() {
    if !js::ready_or_skip("node example bot") {
        return;
    }
    js::build_package().unwrap_or_else(|e| panic!("{e}"));
    let dir = js::workspace().join("bots/examples/node");
    js::npm_install(&dir).unwrap_or_else(|e| panic!("{e}"));

    let scratch = tempfile::tempdir().unwrap();
    let server = start_server(&scratch.path().join("data"), "node");
    let artifacts = artifacts_dir().unwrap_or_else(|e| panic!("{e}"));
    let (out_path, err_path) = (
        artifacts.join("example-bot-node.out"),
        artifacts.join("example-bot-node.err"),
    );
    let mut cmd = Command::new("node");
    cmd.arg("bot.mjs")
        .args(["--server", &server.url("")])
        .args(["--level", "easy", "--rules", "standard", "--samples", "2"])
        .current_dir(&dir)
        .stdin(Stdio::null())
        .stdout(std::fs::File::create(&out_path).unwrap())
        .stderr(std::fs::File::create(&err_path).unwrap());
    let start = Instant::now();
    let bot = Guard::spawn("node example bot", cmd).unwrap_or_else(|e| panic!("{e}"));
    let status = finish(bot, NODE_MATCH_LIMIT).await;
    let stderr = std::fs::read_to_string(&err_path).unwrap_or_default();
    assert!(
        status.contains("exit status: 0"),
        "the bot exited with {status}:\n{}",
        js::tail(&stderr, 3000)
    );
    let stdout = std::fs::read_to_string(&out_path).unwrap();
    let last = stdout.lines().last().unwrap_or_default();
    let report: serde_json::Value = serde_json::from_str(last)
        .unwrap_or_else(|e| panic!("the bot's last line is not JSON ({e}): {last:?}"));
    let shots = stderr.lines().filter(|l| l.contains(" shoots ")).count();
    assert!(shots > 0, "the bot shot");
    assert!(
        !stderr.contains("refused:"),
        "no move refused:\n{}",
        js::tail(&stderr, 3000)
    );
    let id = report["match_id"].as_str().expect("a match id");
    let summary = assert_finished(&server, id).await;
    assert_eq!(
        summary["result"], report["result"],
        "the bot saw the stored result"
    );
    eprintln!(
        "node example bot: {shots} shots of its own in {:.1} s, result {}",
        start.elapsed().as_secs_f64(),
        summary["result"]
    );
}
