//! The JavaScript package works in a real browser with the very bits of
//! native Rust: headless Chromium loads the package's `web/` build (an ES
//! module and its wasm, served over HTTP like any site would), and
//! simulates random requests; every answer is compared with
//! `SimulateRequest::run`, number for number.
//!
//! Needs Debian's `chromium` and `chromium-driver` and `node` (as the
//! browser end-to-end test and the Node binding tests do); skipped with
//! `CHAPAEV_SKIP_BROWSER=1` or `CHAPAEV_SKIP_BINDINGS=1`.

use e2e::browser::{self, Driver};
use e2e::{artifacts_dir, js};
use game::noise::SplitMix64;
use game::simulate::random_request;
use game::Simulation;
use std::io::{BufRead, BufReader, Write};
use std::net::{TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// Requests compared in the browser.
const CASES: usize = 2_000;

/// The page: loads the package and says when it is ready.
const PAGE: &str = r#"<!doctype html><meta charset="utf-8"><title>chapaev in a browser</title>
<script type="module">
import init, { simulate } from "/web/chapaev_js.js";
await init();
window.chapaev_simulate = simulate;
window.chapaev_ready = true;
</script>"#;

/// Serves `root` (and the page at `/`) on a loopback port, one request per
/// connection, until the test ends.
fn serve(root: PathBuf) -> u16 {
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let port = listener.local_addr().unwrap().port();
    std::thread::spawn(move || {
        for stream in listener.incoming().flatten() {
            let _ = answer(&root, stream);
        }
    });
    port
}

fn answer(root: &Path, mut stream: TcpStream) -> std::io::Result<()> {
    let mut line = String::new();
    let mut reader = BufReader::new(stream.try_clone()?);
    reader.read_line(&mut line)?;
    // Skip the headers.
    loop {
        let mut h = String::new();
        if reader.read_line(&mut h)? == 0 || h == "\r\n" {
            break;
        }
    }
    let path = line.split_whitespace().nth(1).unwrap_or("/");
    let (status, kind, body) = if path == "/" {
        ("200 OK", "text/html", PAGE.as_bytes().to_vec())
    } else {
        let file = root.join(path.trim_start_matches('/'));
        let kind = match file.extension().and_then(|e| e.to_str()) {
            Some("js") | Some("mjs") => "text/javascript",
            Some("wasm") => "application/wasm",
            _ => "application/octet-stream",
        };
        match (path.contains(".."), std::fs::read(&file)) {
            (false, Ok(bytes)) => ("200 OK", kind, bytes),
            _ => ("404 Not Found", "text/plain", b"not found".to_vec()),
        }
    };
    write!(
        stream,
        "HTTP/1.1 {status}\r\nContent-Type: {kind}\r\nContent-Length: {}\r\nConnection: close\r\n\r\n",
        body.len()
    )?;
    stream.write_all(&body)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_js_package_gives_the_native_bits_in_a_real_browser() {
    if !js::ready_or_skip("the browser binding test") {
        return;
    }
    let Some(programs) = browser::find_programs().unwrap_or_else(|e| panic!("{e}")) else {
        return;
    };
    js::build_package().unwrap_or_else(|e| panic!("{e}"));
    let port = serve(js::package_dir().join("pkg"));
    let artifacts = artifacts_dir().unwrap_or_else(|e| panic!("{e}"));
    let scratch = tempfile::tempdir().unwrap();
    let driver = Driver::start(&programs, &artifacts.join("chromedriver-bindings.log"))
        .unwrap_or_else(|e| panic!("{e}"));
    let client = driver
        .session(&programs, &scratch.path().join("profile"))
        .await
        .unwrap_or_else(|e| panic!("{e}"));
    client
        .goto(&format!("http://127.0.0.1:{port}/"))
        .await
        .unwrap_or_else(|e| panic!("{e}"));
    browser::poll(
        &client,
        "the package to load in the page",
        "return window.chapaev_ready || null;",
        Duration::from_secs(30),
        Duration::from_millis(100),
        |v| v.as_bool() == Some(true),
    )
    .await
    .unwrap_or_else(|e| panic!("{e}"));

    let mut rng = SplitMix64::new(0xB0_55E5);
    let requests: Vec<_> = (0..CASES).map(|_| random_request(&mut rng)).collect();
    let args = vec![serde_json::to_value(&requests).unwrap()];
    let answers = client
        .execute(
            "return JSON.stringify(arguments[0].map((r) => { \
               try { return window.chapaev_simulate(r); } \
               catch (e) { return { error: e.code || String(e) }; } }));",
            args,
        )
        .await
        .unwrap_or_else(|e| panic!("{e}"));
    let _ = client.close().await;
    drop(driver);
    let answers: Vec<serde_json::Value> =
        serde_json::from_str(answers.as_str().expect("a JSON string")).unwrap();
    assert_eq!(answers.len(), CASES);
    for (k, (req, answer)) in requests.iter().zip(&answers).enumerate() {
        let native = serde_json::to_string(&req.run().unwrap()).unwrap();
        let browser: Simulation = serde_json::from_value(answer.clone())
            .unwrap_or_else(|e| panic!("request {k}: not a simulation ({e}): {answer}"));
        assert_eq!(
            serde_json::to_string(&browser).unwrap(),
            native,
            "request {k} differs: {}",
            serde_json::to_string(req).unwrap()
        );
    }
}
