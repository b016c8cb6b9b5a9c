//! The example bots in other languages (`bots/examples/*`) play a whole
//! match against a built-in level on the real server (`e2e-server`,
//! built-in bots without their delay), each in a section of its own.

use e2e::process::{Guard, Server};
use e2e::{api, artifacts_dir, js};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// No example match runs longer.
const MATCH_LIMIT: Duration = Duration::from_secs(300);

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

/// Waits for `guard`'s process to exit; its exit status.
fn wait(guard: &mut Guard, limit: Duration, what: &str, log: &Path) -> String {
    let start = Instant::now();
    loop {
        if let Some(status) = guard.exited() {
            return status;
        }
        if start.elapsed() > limit {
            panic!(
                "{what} did not finish within {limit:?}; its log, {}:\n{}",
                log.display(),
                js::tail(&std::fs::read_to_string(log).unwrap_or_default(), 3000)
            );
        }
        std::thread::sleep(Duration::from_millis(100));
    }
}

// ---- JavaScript: bots/examples/node ---------------------------------------

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
    let artifacts = artifacts_dir().unwrap();
    let (out_path, err_path) = (
        artifacts.join("example-bots-node.out"),
        artifacts.join("example-bots-node.err"),
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
    let mut bot = Guard::spawn("node example bot", cmd).unwrap_or_else(|e| panic!("{e}"));
    let status = tokio::task::block_in_place(|| {
        wait(&mut bot, MATCH_LIMIT, "the node bot's match", &err_path)
    });
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
    eprintln!(
        "node bot: {report} after {shots} shots of its own in {:.1} s",
        start.elapsed().as_secs_f64()
    );
    assert!(shots > 0, "the bot shot");
    assert!(
        !stderr.contains("refused:"),
        "no move refused:\n{}",
        js::tail(&stderr, 3000)
    );

    let id = report["match_id"].as_str().expect("a match id");
    let (code, summary) = api::get_json(&server.addr, &format!("/api/matches/{id}"))
        .await
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(code, 200, "{summary}");
    assert_eq!(summary["status"], "finished", "{summary}");
    assert!(summary["result"].is_object(), "a result: {summary}");
    assert_eq!(
        summary["result"], report["result"],
        "the bot saw the stored result"
    );
}
