//! A person's first game, in a real browser: the server serves the web
//! client; headless Chromium loads it, the app draws its lobby (a
//! screenshot shows it is not blank), "vs computer (easy)" is clicked, and
//! one of the player's pieces is pulled back with the mouse and let go —
//! the server's API then counts the shot. The player resigns, opens the
//! replay and scrubs it, then opens the sandbox and plays its break.
//! A second scenario opens the game at phone size (390x844 at a
//! device-pixel ratio of 3), at a device-pixel ratio of 2 and at full HD,
//! and checks from the client's own layout report that every control is
//! inside the window, none overlap and each is at least 44 px tall: on the
//! lobby, the rules, the leaderboard (both tabs), the account screen signed
//! out and signed in, the lobby signed in and the player's page (with the
//! server's real answers, empty or not) — signing in on the way with a key
//! pasted into the account screen — then on the match, where it pulls a
//! back-row piece to the window's edge and reads full power, and at phone
//! size shoots a second time with a finger (touch events); then the
//! end-of-match screen, the replay and the sandbox.
//! Screenshots and logs are left in
//! the artifacts folder (`target/e2e-artifacts` or `$CHAPAEV_E2E_ARTIFACTS`).

use e2e::browser::{self, centre, click_button, click_seen, shoot, state_until, Driver};
use e2e::process::Server;
use e2e::{api, artifacts_dir, layout, picture, E2eError, Result};
use fantoccini::Client;
use serde_json::Value;
use std::path::Path;
use std::time::{Duration, Instant};

/// What each scenario starts with: the browser's programs, the artifacts
/// folder, a scratch folder, the server and the browser driver.
struct Setup {
    programs: browser::Programs,
    artifacts: std::path::PathBuf,
    scratch: tempfile::TempDir,
    server: Server,
    driver: Driver,
}

/// Starts the server and the driver, their logs named with `tag`; `None`
/// where this machine has no browser.
fn setup(tag: &str) -> Option<Setup> {
    let programs = browser::find_programs().unwrap_or_else(|e| panic!("{e}"))?;
    let artifacts = artifacts_dir().unwrap_or_else(|e| panic!("{e}"));
    let scratch = tempfile::tempdir().unwrap();
    let server = Server::start(
        Path::new(env!("CARGO_BIN_EXE_e2e-server")),
        &scratch.path().join("data"),
        &artifacts.join(format!("server{tag}.log")),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let driver = Driver::start(&programs, &artifacts.join(format!("chromedriver{tag}.log")))
        .unwrap_or_else(|e| panic!("{e}"));
    Some(Setup {
        programs,
        artifacts,
        scratch,
        server,
        driver,
    })
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_player_opens_the_page_shoots_against_the_easy_bot_resigns_scrubs_the_replay_and_plays_the_sandbox(
) {
    let Some(Setup {
        programs,
        artifacts,
        scratch,
        server,
        driver,
    }) = setup("")
    else {
        return;
    };
    let client = driver
        .session(&programs, &scratch.path().join("profile"))
        .await
        .unwrap_or_else(|e| panic!("{e}"));

    let outcome = play(&client, &server, &artifacts).await;
    if outcome.is_err() {
        // What the page showed when it went wrong.
        let _ = browser::screenshot(&client, &artifacts.join("failure.png")).await;
        if let Ok(state) = browser::eval(&client, browser::APP_STATE).await {
            eprintln!("e2e: chapaev_state at the failure: {state}");
        }
    }
    let _ = client.close().await;
    drop(driver);
    drop(server);
    if let Err(e) = outcome {
        panic!(
            "{e}\n(screenshots and the server's and chromedriver's logs are in {})",
            artifacts.display()
        );
    }
}

/// Two strangers press Quick match in two browsers, each signed in to an
/// account of its own: the first waits (the wait shows its clock and a
/// Cancel), and the server pairs them into one match, whose page both open
/// in opposite seats.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn two_browsers_pressing_quick_match_are_paired_into_one_match() {
    let Some(Setup {
        programs,
        artifacts,
        scratch,
        server,
        driver,
    }) = setup("-quick")
    else {
        return;
    };
    let mut clients = Vec::new();
    for who in ["a", "b"] {
        let c = driver
            .session(&programs, &scratch.path().join(format!("profile-{who}")))
            .await
            .unwrap_or_else(|e| panic!("{e}"));
        clients.push(c);
    }
    let outcome = quick_match(&clients[0], &clients[1], &server, &artifacts).await;
    if outcome.is_err() {
        for (i, c) in clients.iter().enumerate() {
            let _ = browser::screenshot(c, &artifacts.join(format!("quick-failure-{i}.png"))).await;
            if let Ok(state) = browser::eval(c, browser::APP_STATE).await {
                eprintln!("e2e: browser {i}'s chapaev_state at the failure: {state}");
            }
        }
    }
    for c in clients {
        let _ = c.close().await;
    }
    drop(driver);
    drop(server);
    if let Err(e) = outcome {
        panic!("{e}\n(screenshots and logs are in {})", artifacts.display());
    }
}

async fn quick_match(a: &Client, b: &Client, server: &Server, artifacts: &Path) -> Result<()> {
    for (client, name) in [(a, "Stranger_a"), (b, "Stranger_b")] {
        sign_in_by_storage(client, server, name).await?;
    }
    click_button(a, "quick-match").await?;
    let waiting = state_until(a, "the first player's wait", 15, |s| {
        s["screen"] == "quick-match"
            && s["seeking"] == true
            && s["buttons"]["quick-cancel"].is_array()
    })
    .await?;
    eprintln!("e2e: waiting: {}", waiting["status"]);
    browser::screenshot(a, &artifacts.join("quick-1-waiting.png")).await?;
    click_button(b, "quick-match").await?;
    let on_match =
        |s: &Value| s["screen"] == "play" && s["match_id"].is_string() && !s["seat"].is_null();
    let first = state_until(a, "the first player's match", 20, on_match).await?;
    let second = state_until(b, "the second player's match", 20, on_match).await?;
    if first["match_id"] != second["match_id"] || first["seat"] == second["seat"] {
        return Err(E2eError::Check(format!(
            "not one match in two seats: {} {} and {} {}",
            first["match_id"], first["seat"], second["match_id"], second["seat"]
        )));
    }
    eprintln!(
        "e2e: paired into {} ({} and {})",
        first["match_id"], first["seat"], second["seat"]
    );
    browser::screenshot(b, &artifacts.join("quick-2-paired.png")).await?;
    Ok(())
}

/// Opens the game in `client` signed in to a new account `name` (made
/// through the API, its key put where the page keeps it).
async fn sign_in_by_storage(client: &Client, server: &Server, name: &str) -> Result<()> {
    let (status, made) = api::post_json(
        &server.addr,
        "/api/accounts",
        &serde_json::json!({ "name": name, "bot": false }),
    )
    .await?;
    let key = made["key"]
        .as_str()
        .filter(|_| status == 201)
        .ok_or_else(|| E2eError::Check(format!("POST /api/accounts: {status} {made}")))?;
    client.goto(&server.url("/")).await?;
    browser::eval(
        client,
        &format!(
            "localStorage.setItem('chapaev.account.key', {}); \
             localStorage.setItem('chapaev.account.name', {}); return true;",
            serde_json::json!(key),
            serde_json::json!(name)
        ),
    )
    .await?;
    client.refresh().await?;
    state_until(client, "the lobby, signed in", 30, |s| {
        s["screen"] == "lobby" && s["signed_in"] == name
    })
    .await?;
    Ok(())
}

/// The page can be installed: it links its web-app manifest (which names
/// its icons), and its service worker registers, takes control of the
/// page and caches the page and this build's wasm, so it opens offline.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_page_links_its_manifest_and_its_service_worker_caches_the_wasm() {
    let Some(Setup {
        programs,
        artifacts,
        scratch,
        server,
        driver,
    }) = setup("-install")
    else {
        return;
    };
    let client = driver
        .session(&programs, &scratch.path().join("profile"))
        .await
        .unwrap_or_else(|e| panic!("{e}"));
    let outcome = installable(&client, &server).await;
    let _ = client.close().await;
    drop(driver);
    drop(server);
    if let Err(e) = outcome {
        panic!("{e}\n(logs are in {})", artifacts.display());
    }
}

async fn installable(client: &Client, server: &Server) -> Result<()> {
    client.goto(&server.url("/")).await?;
    state_until(client, "the lobby", 30, |s| s["screen"] == "lobby").await?;
    let manifest = browser::eval(
        client,
        "const l = document.querySelector('link[rel=manifest]');
         if (!l) return null;
         return fetch(l.href).then(r => r.json());",
    )
    .await?;
    let icons = manifest["icons"].as_array().map_or(0, Vec::len);
    if manifest["start_url"] != "/" || icons < 2 {
        return Err(E2eError::Check(format!("the manifest: {manifest}")));
    }
    browser::poll(
        client,
        "the service worker in control",
        "return !!(navigator.serviceWorker && navigator.serviceWorker.controller);",
        Duration::from_secs(30),
        Duration::from_millis(200),
        |v| v == true,
    )
    .await?;
    let cached = browser::eval(
        client,
        "return caches.keys().then(async (keys) => {
             const urls = [];
             for (const k of keys) {
                 for (const r of await (await caches.open(k)).keys()) urls.push(new URL(r.url).pathname);
             }
             return urls;
         });",
    )
    .await?;
    let has = |path: &str| cached.as_array().into_iter().flatten().any(|u| u == path);
    if !(has("/") && has("/chapaev.wasm") && has("/chapaev.js")) {
        return Err(E2eError::Check(format!("cached: {cached}")));
    }
    eprintln!("e2e: the service worker cached {cached}");
    Ok(())
}

/// One window the layout scenario runs in.
struct Window {
    name: &'static str,
    width: u32,
    height: u32,
    dpr: u32,
}

const WINDOWS: [Window; 3] = [
    Window {
        name: "phone",
        width: 390,
        height: 844,
        dpr: 3,
    },
    Window {
        name: "sharp",
        width: 1024,
        height: 720,
        dpr: 2,
    },
    Window {
        name: "fullhd",
        width: 1920,
        height: 1080,
        dpr: 1,
    },
];

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn on_a_phone_a_sharp_screen_and_full_hd_every_control_fits_and_the_slingshot_reaches_full_power(
) {
    let Some(Setup {
        programs,
        artifacts,
        scratch,
        server,
        driver,
    }) = setup("-layout")
    else {
        return;
    };
    let mut failures = Vec::new();
    for window in &WINDOWS {
        let extra = [
            format!("--window-size={},{}", window.width, window.height),
            format!("--force-device-scale-factor={}", window.dpr),
        ];
        let profile = scratch.path().join(format!("profile-{}", window.name));
        let client = match driver.session_with(&programs, &profile, &extra).await {
            Ok(c) => c,
            Err(e) => panic!("{e}"),
        };
        let outcome = layouts(&client, &server, &artifacts, window).await;
        if let Err(e) = outcome {
            let _ = browser::screenshot(
                &client,
                &artifacts.join(format!("failure-{}.png", window.name)),
            )
            .await;
            if let Ok(state) = browser::eval(&client, browser::APP_STATE).await {
                eprintln!("e2e: chapaev_state at the failure: {state}");
            }
            failures.push(format!("{}: {e}", window.name));
        }
        let _ = client.close().await;
    }
    drop(driver);
    drop(server);
    assert!(
        failures.is_empty(),
        "{}\n(screenshots and logs are in {})",
        failures.join("\n"),
        artifacts.display()
    );
}

/// Checks the layout the app reports now: inside the window, no overlaps,
/// finger-sized where `finger`; saves a screenshot as `shot`.
async fn check_layout(
    client: &Client,
    artifacts: &Path,
    shot: &str,
    state: &Value,
    finger: bool,
) -> Result<()> {
    let size = browser::eval(client, "return [window.innerWidth, window.innerHeight];").await?;
    let (w, h) = (
        size[0].as_f64().unwrap_or(0.0),
        size[1].as_f64().unwrap_or(0.0),
    );
    let controls = layout::controls(&state["buttons"]).map_err(E2eError::Check)?;
    let faults = layout::faults(&controls, w, h, if finger { 44.0 } else { 0.0 });
    let png = browser::screenshot(client, &artifacts.join(shot)).await?;
    picture::stats(&png)?.check_drawn(shot, 8, 0.001)?;
    eprintln!(
        "e2e: {shot}: {} controls in {w}x{h}, {} faults",
        controls.len(),
        faults.len()
    );
    if faults.is_empty() {
        Ok(())
    } else {
        Err(E2eError::Check(format!(
            "{shot} (screen {}): {}",
            state["screen"],
            faults.join("; ")
        )))
    }
}

async fn layouts(
    client: &Client,
    server: &Server,
    artifacts: &Path,
    window: &Window,
) -> Result<()> {
    let (w, h) = browser::fit_viewport(client, window.width, window.height).await?;
    let dpr = browser::eval(client, "return window.devicePixelRatio;").await?;
    eprintln!(
        "e2e: {} viewport {w}x{h} at a device-pixel ratio of {dpr}",
        window.name
    );
    client.goto(&server.url("/")).await?;
    let name = window.name;
    // The lobby, with the server's lists filled in.
    let lobby = state_until(client, "the lobby", 30, |s| {
        s["screen"] == "lobby" && s["buttons"]["vs-computer-easy"].is_array()
    })
    .await?;
    // The canvas is drawn at device pixels.
    let canvas = browser::eval(
        client,
        "const c = document.querySelector('#glcanvas'); return [c.width, c.clientWidth];",
    )
    .await?;
    let (pixels, css) = (
        canvas[0].as_f64().unwrap_or(0.0),
        canvas[1].as_f64().unwrap_or(1.0),
    );
    let ratio = dpr.as_f64().unwrap_or(1.0);
    if (pixels / css - ratio).abs() > 0.05 {
        return Err(E2eError::Check(format!(
            "the canvas is {pixels} pixels wide for {css} CSS pixels at a device-pixel ratio of {ratio}"
        )));
    }
    check_layout(
        client,
        artifacts,
        &format!("layout-{name}-1-lobby.png"),
        &lobby,
        true,
    )
    .await?;
    // The rules over the lobby.
    click_button(client, "help").await?;
    let help = state_until(client, "the rules", 5, |s| {
        s["buttons"]["help-close"].is_array()
    })
    .await?;
    let close = &help["buttons"]["help-close"];
    let only_close = serde_json::json!({ "help-close": close });
    check_layout(
        client,
        artifacts,
        &format!("layout-{name}-2-rules.png"),
        &serde_json::json!({"buttons": only_close, "screen": "lobby"}),
        true,
    )
    .await?;
    click_button(client, "help-close").await?;
    accounts(client, server, artifacts, name).await?;

    // A match against the easy computer.
    click_button(client, "vs-computer-easy").await?;
    let play = state_until(client, "our turn on the play screen", 30, |s| {
        s["screen"] == "play" && s["my_turn"] == true && s["animating"] == false
    })
    .await?;
    check_layout(
        client,
        artifacts,
        &format!("layout-{name}-3-play.png"),
        &play,
        true,
    )
    .await?;
    // Full power from a back-row piece: pull it straight down to the
    // window's bottom edge; the meter stays inside the window.
    let piece = play["pieces"]
        .as_array()
        .into_iter()
        .flatten()
        .filter(|p| p["mine"] == true)
        .filter_map(|p| Some((p["x"].as_f64()?, p["y"].as_f64()?)))
        .max_by(|a, b| a.1.total_cmp(&b.1).then(b.0.total_cmp(&a.0)))
        .ok_or_else(|| E2eError::Check(format!("no piece of ours: {}", play["pieces"])))?;
    let edge = (piece.0, f64::from(h) - 2.0);
    browser::press_and_move(client, piece, edge, 10).await?;
    let aiming = browser::eval(client, browser::APP_STATE).await?;
    let _ = browser::screenshot(client, &artifacts.join(format!("layout-{name}-4-aim.png"))).await;
    browser::release(client).await?;
    let power = aiming["aim_power"].as_f64().unwrap_or(0.0);
    eprintln!("e2e: {name}: pulled from {piece:?} to {edge:?}: power {power:.3}");
    if power < 0.999 {
        return Err(E2eError::Check(format!(
            "a pull from the back row to the window's edge gave {:.0} % of full power: {aiming}",
            power * 100.0
        )));
    }
    let meter = serde_json::json!({ "meter": aiming["meter"] });
    let meter = layout::controls(&meter).map_err(E2eError::Check)?;
    let off = layout::faults(&meter, f64::from(w), f64::from(h), 0.0);
    if !off.is_empty() {
        return Err(E2eError::Check(format!(
            "the power meter: {}",
            off.join("; ")
        )));
    }
    // The shot is played.
    state_until(client, "the shot counted", 20, |s| {
        s["shots"].as_u64().is_some_and(|n| n >= 1)
    })
    .await?;
    if name == "phone" {
        shoot_by_touch(client, h).await?;
    }
    // Then resign: the end-of-match screen.
    click_button(client, "resign").await?;
    click_button(client, "resign-yes").await?;
    let end = state_until(client, "the end-of-match screen", 30, |s| {
        s["buttons"]["end-replay"].is_array() && s["animating"] == false
    })
    .await?;
    check_layout(
        client,
        artifacts,
        &format!("layout-{name}-5-end.png"),
        &end,
        true,
    )
    .await?;
    click_button(client, "end-replay").await?;
    let replay = state_until(client, "the replay loaded", 20, |s| {
        s["screen"] == "replay" && s["shots"].as_u64().is_some_and(|n| n >= 1)
    })
    .await?;
    check_layout(
        client,
        artifacts,
        &format!("layout-{name}-6-replay.png"),
        &replay,
        true,
    )
    .await?;
    click_button(client, "lobby").await?;
    click_button(client, "sandbox").await?;
    let sandbox = state_until(client, "the sandbox", 10, |s| {
        s["screen"] == "sandbox" && s["bodies"].as_u64().is_some_and(|n| n > 0)
    })
    .await?;
    check_layout(
        client,
        artifacts,
        &format!("layout-{name}-7-sandbox.png"),
        &sandbox,
        true,
    )
    .await?;
    // On a phone the side panel opens over the world.
    if name == "phone" {
        click_button(client, "panel").await?;
        let panel = state_until(client, "the sandbox's panel open", 10, |s| {
            s["panel_open"] == true && s["buttons"]["preset-break"].is_array()
        })
        .await?;
        check_layout(
            client,
            artifacts,
            &format!("layout-{name}-8-sandbox-panel.png"),
            &panel,
            true,
        )
        .await?;
    }
    Ok(())
}

/// The account screens, each checked: the leaderboard's two tabs, the
/// account screen signed out; then signing in with the key of an account
/// made through the API, pasted into the account screen; the lobby and the
/// account screen signed in, the player's page; and signing out again.
async fn accounts(client: &Client, server: &Server, artifacts: &Path, window: &str) -> Result<()> {
    click_button(client, "leaderboard").await?;
    let people = state_until(client, "the people's leaderboard", 15, |s| {
        s["screen"] == "leaderboard" && s["bots"] == false && s["loaded"] == true
    })
    .await?;
    let shot = |n: &str| format!("layout-{window}-2{n}.png");
    check_layout(client, artifacts, &shot("a-leaderboard"), &people, true).await?;
    click_button(client, "tab-bots").await?;
    let bots = state_until(client, "the bots' leaderboard", 15, |s| {
        s["screen"] == "leaderboard" && s["bots"] == true && s["loaded"] == true
    })
    .await?;
    check_layout(client, artifacts, &shot("b-leaderboard-bots"), &bots, true).await?;
    click_button(client, "lobby").await?;
    click_button(client, "sign-in").await?;
    let signed_out = state_until(client, "the account screen, signed out", 10, |s| {
        s["screen"] == "account" && s["buttons"]["account-use-key"].is_array()
    })
    .await?;
    check_layout(client, artifacts, &shot("c-sign-in"), &signed_out, true).await?;
    // An account made elsewhere; its key pasted here.
    let account = format!("e2e-{window}");
    let (status, made) = api::post_json(
        &server.addr,
        "/api/accounts",
        &serde_json::json!({ "name": account, "bot": false }),
    )
    .await?;
    let key = made["key"]
        .as_str()
        .filter(|_| status == 201)
        .ok_or_else(|| E2eError::Check(format!("POST /api/accounts: {status} {made}")))?
        .to_string();
    click_button(client, "account-key").await?;
    browser::paste(client, &key).await?;
    click_button(client, "account-use-key").await?;
    let lobby = state_until(client, "the lobby, signed in with its rating", 15, |s| {
        s["screen"] == "lobby" && s["signed_in"] == account.as_str() && s["rating"] == "1500?"
    })
    .await?;
    check_layout(client, artifacts, &shot("d-lobby-signed-in"), &lobby, true).await?;
    click_button(client, "account").await?;
    state_until(client, "the account screen, signed in", 10, |s| {
        s["screen"] == "account" && s["signed_in"] == account.as_str()
    })
    .await?;
    click_button(client, "export-key").await?;
    let exported = state_until(client, "the key exported", 10, |s| {
        s["message"].as_str().is_some_and(|m| m.contains("copied"))
    })
    .await?;
    check_layout(client, artifacts, &shot("e-account"), &exported, true).await?;
    click_button(client, "account-page").await?;
    let page = state_until(
        client,
        "the player's page with the server's answers",
        15,
        |s| s["screen"] == "profile" && s["loaded"] == true && s["rating"] == "1500?",
    )
    .await?;
    eprintln!(
        "e2e: {window}: {account}'s page: history {}, matches {}",
        page["history"], page["matches"]
    );
    check_layout(client, artifacts, &shot("f-player"), &page, true).await?;
    click_button(client, "lobby").await?;
    click_button(client, "sign-out").await?;
    click_button(client, "sign-out-yes").await?;
    state_until(client, "the lobby, signed out", 10, |s| {
        s["screen"] == "lobby" && s["signed_in"].is_null() && s["buttons"]["sign-in"].is_array()
    })
    .await?;
    Ok(())
}

/// On our turn again, a finger pulls the piece nearest the middle down
/// (touch events, as a phone sends them) and lets go: the client's report
/// counts one more shot.
async fn shoot_by_touch(client: &Client, height: u32) -> Result<()> {
    let ready = state_until(client, "our turn again, nothing moving", 60, |s| {
        s["my_turn"] == true && s["animating"] == false
    })
    .await?;
    let before = ready["shots"].as_u64().unwrap_or(0);
    let width = browser::eval(client, "return window.innerWidth;")
        .await?
        .as_f64()
        .unwrap_or(390.0);
    let bottom = f64::from(height) - 2.0;
    let piece = ready["pieces"]
        .as_array()
        .into_iter()
        .flatten()
        .filter(|p| p["mine"] == true)
        .filter_map(|p| Some((p["x"].as_f64()?, p["y"].as_f64()?)))
        .filter(|&(_, y)| y + 40.0 < bottom)
        .min_by(|a, b| {
            let off = |p: &(f64, f64)| (p.0 - width / 2.0).abs();
            off(a).total_cmp(&off(b))
        })
        .ok_or_else(|| {
            E2eError::Check(format!("no piece of ours to touch: {}", ready["pieces"]))
        })?;
    let to = (piece.0, (piece.1 + 80.0).min(bottom));
    eprintln!("e2e: a finger pulls the piece at {piece:?} to {to:?}");
    browser::touch_drag(client, piece, to, 8).await?;
    state_until(client, "the touch shot counted", 20, |s| {
        s["shots"].as_u64().is_some_and(|n| n > before)
    })
    .await?;
    Ok(())
}

async fn play(client: &Client, server: &Server, artifacts: &Path) -> Result<()> {
    // 1. The page loads and the app draws its first frame.
    let (w, h) = browser::fit_viewport(client, 1024, 720).await?;
    eprintln!("e2e: viewport {w}x{h}");
    let started = Instant::now();
    client.goto(&server.url("/")).await?;
    let ready = browser::poll(
        client,
        "window.chapaev_ready",
        "return window.chapaev_ready === true \
           ? (typeof window.chapaev_ready_ms === 'number' ? window.chapaev_ready_ms : performance.now()) \
           : null;",
        Duration::from_secs(30),
        Duration::from_millis(20),
        |v| v.is_number(),
    )
    .await?;
    let waited = started.elapsed();
    let ready_ms = ready.as_f64().unwrap_or(f64::NAN);
    eprintln!(
        "e2e: the app was ready {ready_ms:.0} ms after navigation start \
         ({:.0} ms after the test asked for the page)",
        waited.as_secs_f64() * 1000.0
    );
    std::fs::write(
        artifacts.join("timings.json"),
        format!(
            "{{\"ready_ms_since_navigation\":{ready_ms:.1},\"ready_ms_since_goto\":{:.1}}}\n",
            waited.as_secs_f64() * 1000.0
        ),
    )
    .map_err(|source| E2eError::Io {
        what: "writing timings.json".into(),
        source,
    })?;

    // 2. The lobby is drawn: WebGL works and the app draws something.
    tokio::time::sleep(Duration::from_millis(300)).await;
    let shot = browser::screenshot(client, &artifacts.join("01-lobby.png")).await?;
    let stats = picture::stats(&shot)?;
    eprintln!("e2e: lobby screenshot: {stats}");
    stats.check_drawn("lobby", 8, 0.001)?;

    // 3. "vs computer (easy)".
    let lobby = state_until(client, "the lobby's vs-computer-easy button", 10, |s| {
        s["screen"] == "lobby" && s["buttons"]["vs-computer-easy"].is_array()
    })
    .await?;
    let (x, y) = centre(&lobby["buttons"]["vs-computer-easy"])?;
    eprintln!("e2e: clicking vs-computer-easy at ({x:.0}, {y:.0})");
    click_seen(client, x, y).await?;

    // 4. The match is on, connected, and it is our turn.
    let play = state_until(
        client,
        "the play screen, connected, on our turn, nothing moving",
        30,
        |s| {
            s["screen"] == "play"
                && s["connected"] == true
                && s["my_turn"] == true
                && s["animating"] == false
        },
    )
    .await?;
    let match_id = play["match_id"]
        .as_str()
        .ok_or_else(|| E2eError::Check(format!("no match_id on the play screen: {play}")))?
        .to_string();
    eprintln!("e2e: playing match {match_id} as {}", play["seat"]);

    // 5. Pull one of our pieces straight down and let go: it shoots up the
    // board. 80 px, or as far as the window allows (at least 40).
    const PULL: f64 = 80.0;
    const MIN_PULL: f64 = 40.0;
    let height = browser::eval(client, "return window.innerHeight;")
        .await?
        .as_f64()
        .unwrap_or(720.0);
    let width = browser::eval(client, "return window.innerWidth;")
        .await?
        .as_f64()
        .unwrap_or(1024.0);
    let piece = play["pieces"]
        .as_array()
        .into_iter()
        .flatten()
        .filter(|p| p["mine"] == true)
        .filter_map(|p| Some((p["x"].as_f64()?, p["y"].as_f64()?)))
        .filter(|&(_, y)| y + MIN_PULL < height - 2.0)
        .min_by(|a, b| {
            let off = |p: &(f64, f64)| (p.0 - width / 2.0).abs();
            off(a).total_cmp(&off(b))
        })
        .ok_or_else(|| {
            E2eError::Check(format!(
                "no piece of ours with {MIN_PULL} px of room below it: {}",
                play["pieces"]
            ))
        })?;
    let pull = PULL.min(height - 2.0 - piece.1);
    eprintln!(
        "e2e: pulling the piece at ({:.0}, {:.0}) down {pull:.0} px",
        piece.0, piece.1
    );
    browser::drag(client, piece, (piece.0, piece.1 + pull), 8).await?;

    // While the shot animates: the frame rate the browser reaches and the
    // time our own frame code takes (reported, not asserted: timings belong
    // in benchmarks, and headless Chromium draws WebGL in software).
    let mut fps = Vec::new();
    let mut work = Vec::new();
    let sampling = Instant::now();
    while sampling.elapsed() < Duration::from_millis(1500) {
        let s = browser::eval(client, browser::APP_STATE).await?;
        if s["animating"] == true {
            fps.extend(s["fps"].as_f64());
            work.extend(s["work_ms"].as_f64());
        }
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
    };
    eprintln!(
        "e2e: while the shot animated: {} samples, median {:.0} fps, our frame code {:.2} ms",
        fps.len(),
        median(&mut fps),
        median(&mut work)
    );

    // 6. The server counts the shot.
    let start = Instant::now();
    let path = format!("/api/matches/{match_id}");
    loop {
        let (status, summary) = api::get_json(&server.addr, &path).await?;
        if status == 200 && summary["shots"].as_u64().is_some_and(|n| n >= 1) {
            eprintln!("e2e: the server counted the shot: {summary}");
            break;
        }
        if start.elapsed() > Duration::from_secs(15) {
            let state = browser::eval(client, browser::APP_STATE)
                .await
                .unwrap_or(Value::Null);
            return Err(E2eError::Timeout {
                what: format!("GET {path} to count a shot"),
                seconds: 15,
                last: format!("{status} {summary}; page state {state}"),
            });
        }
        tokio::time::sleep(Duration::from_millis(200)).await;
    }

    // 7. The board after the shot.
    tokio::time::sleep(Duration::from_millis(500)).await;
    let shot = browser::screenshot(client, &artifacts.join("02-after-shot.png")).await?;
    let stats = picture::stats(&shot)?;
    eprintln!("e2e: play screenshot: {stats}");
    stats.check_drawn("play", 8, 0.01)?;

    // 8. Resign (with its confirmation), then open the replay of the match.
    click_button(client, "resign").await?;
    click_button(client, "resign-yes").await?;
    click_button(client, "replay").await?;
    let replay = state_until(client, "the replay screen with the match loaded", 15, |s| {
        s["screen"] == "replay" && s["shots"].as_u64().is_some_and(|n| n >= 1)
    })
    .await?;
    eprintln!(
        "e2e: the replay holds {} shots over {:.1} s",
        replay["shots"], replay["total"]
    );
    // Scrub: clicking the middle of the timeline jumps there.
    let (x, y) = centre(&replay["buttons"]["timeline"])?;
    click_seen(client, x, y).await?;
    let total = replay["total"].as_f64().unwrap_or(0.0);
    state_until(
        client,
        "the replay's time near the middle after a click on the timeline",
        5,
        |s| {
            s["t"]
                .as_f64()
                .is_some_and(|t| (t - total / 2.0).abs() < total * 0.2 + 0.5)
        },
    )
    .await?;
    let shot = browser::screenshot(client, &artifacts.join("03-replay.png")).await?;
    picture::stats(&shot)?.check_drawn("replay", 8, 0.01)?;

    // 9. Back to the lobby and into the sandbox: its break plays and counts events.
    click_button(client, "lobby").await?;
    click_button(client, "sandbox").await?;
    let sandbox = state_until(client, "the sandbox with its bodies", 10, |s| {
        s["screen"] == "sandbox" && s["bodies"].as_u64().is_some_and(|n| n > 0)
    })
    .await?;
    eprintln!("e2e: the sandbox opened with {} bodies", sandbox["bodies"]);
    click_button(client, "play").await?;
    let played = state_until(client, "the sandbox's events after Play", 10, |s| {
        s["events"].as_u64().is_some_and(|n| n > 0)
    })
    .await?;
    eprintln!("e2e: the sandbox played {} events", played["events"]);
    let shot = browser::screenshot(client, &artifacts.join("04-sandbox.png")).await?;
    picture::stats(&shot)?.check_drawn("sandbox", 8, 0.01)?;
    Ok(())
}

// ---- The defects a player found, each at phone and desktop size.

/// The two windows the defects are checked in: a phone held upright and a
/// laptop.
const PLAYER_WINDOWS: [Window; 2] = [
    Window {
        name: "phone",
        width: 390,
        height: 844,
        dpr: 3,
    },
    Window {
        name: "desktop",
        width: 1280,
        height: 800,
        dpr: 1,
    },
];

/// A scenario run in one window: the page is open on the lobby.
type Scenario =
    for<'a> fn(
        &'a Client,
        &'a Server,
        &'a Path,
        &'a Window,
    ) -> std::pin::Pin<Box<dyn std::future::Future<Output = Result<()>> + Send + 'a>>;

/// Runs `scenario` in a fresh browser at each of [`PLAYER_WINDOWS`],
/// the page opened on the lobby first; fails with every window's failure.
async fn in_player_windows(tag: &str, scenario: Scenario) {
    let Some(Setup {
        programs,
        artifacts,
        scratch,
        server,
        driver,
    }) = setup(tag)
    else {
        return;
    };
    let mut failures = Vec::new();
    for window in &PLAYER_WINDOWS {
        let extra = [
            format!("--window-size={},{}", window.width, window.height),
            format!("--force-device-scale-factor={}", window.dpr),
        ];
        let profile = scratch.path().join(format!("profile{tag}-{}", window.name));
        let client = driver
            .session_with(&programs, &profile, &extra)
            .await
            .unwrap_or_else(|e| panic!("{e}"));
        let outcome = async {
            browser::fit_viewport(&client, window.width, window.height).await?;
            client.goto(&server.url("/")).await?;
            state_until(&client, "the lobby", 30, |s| {
                s["screen"] == "lobby" && s["buttons"]["vs-computer-easy"].is_array()
            })
            .await?;
            scenario(&client, &server, &artifacts, window).await
        }
        .await;
        if let Err(e) = outcome {
            let _ = browser::screenshot(
                &client,
                &artifacts.join(format!("failure{tag}-{}.png", window.name)),
            )
            .await;
            if let Ok(state) = browser::eval(&client, browser::APP_STATE).await {
                eprintln!("e2e: chapaev_state at the failure: {state}");
            }
            failures.push(format!("{}: {e}", window.name));
        }
        let _ = client.close().await;
    }
    drop(driver);
    drop(server);
    assert!(
        failures.is_empty(),
        "{}\n(screenshots and logs are in {})",
        failures.join("\n"),
        artifacts.display()
    );
}

/// Saves a screenshot of what the player sees now as `fixed-<name>-<window>.png`.
async fn snap(client: &Client, artifacts: &Path, name: &str, window: &Window) -> Result<()> {
    let shot = format!("fixed-{name}-{}.png", window.name);
    let png = browser::screenshot(client, &artifacts.join(&shot)).await?;
    picture::stats(&png)?.check_drawn(&shot, 8, 0.001)
}

/// Types `keys` into the focused canvas in one go (one script, so every
/// key lands in the same frame), as the browser delivers a fast typist's
/// keys: `\u{8}` is Backspace, anything else a character.
async fn type_burst(client: &Client, keys: &str) -> Result<()> {
    const SCRIPT: &str = "const c = document.querySelector('#glcanvas');
        for (const k of arguments[0]) {
            if (k === '\\b') {
                c.dispatchEvent(new KeyboardEvent('keydown', {code: 'Backspace', key: 'Backspace', bubbles: true}));
                c.dispatchEvent(new KeyboardEvent('keyup', {code: 'Backspace', key: 'Backspace', bubbles: true}));
                continue;
            }
            const code = 'Key' + k.toUpperCase();
            c.dispatchEvent(new KeyboardEvent('keydown', {code, key: k, bubbles: true}));
            const press = new KeyboardEvent('keypress', {code, key: k, bubbles: true});
            Object.defineProperty(press, 'charCode', {get: () => k.charCodeAt(0)});
            c.dispatchEvent(press);
            c.dispatchEvent(new KeyboardEvent('keyup', {code, key: k, bubbles: true}));
        }
        return true;";
    client
        .execute(SCRIPT, vec![serde_json::json!(keys)])
        .await?;
    Ok(())
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn keys_typed_in_one_frame_keep_their_order_and_every_backspace_counts() {
    in_player_windows("-typing", |client, _server, artifacts, window| {
        Box::pin(async move {
            click_button(client, "name").await?;
            // Whatever the field held, 45 Backspaces empty it (it holds at
            // most 40); then "Anka", all in one frame.
            type_burst(client, &format!("{}Anka", "\u{8}".repeat(45))).await?;
            state_until(client, "the name typed as Anka", 10, |s| {
                s["name"] == "Anka"
            })
            .await?;
            type_burst(client, "abcdefgh\u{8}\u{8}gh").await?;
            state_until(client, "the name typed on in order", 10, |s| {
                s["name"] == "Ankaabcdefgh"
            })
            .await?;
            snap(client, artifacts, "typing", window).await
        })
    })
    .await;
}

/// Makes an account through the API and signs in with its key pasted into
/// the account screen; ends on the lobby, signed in. The account's name.
async fn sign_in_by_key(client: &Client, server: &Server, window: &Window) -> Result<String> {
    let account = format!("out-{}", window.name);
    let (status, made) = api::post_json(
        &server.addr,
        "/api/accounts",
        &serde_json::json!({ "name": account, "bot": false }),
    )
    .await?;
    let key = made["key"]
        .as_str()
        .filter(|_| status == 201)
        .ok_or_else(|| E2eError::Check(format!("POST /api/accounts: {status} {made}")))?
        .to_string();
    click_button(client, "sign-in").await?;
    click_button(client, "account-key").await?;
    browser::paste(client, &key).await?;
    click_button(client, "account-use-key").await?;
    state_until(client, "the lobby, signed in", 15, |s| {
        s["screen"] == "lobby" && s["signed_in"] == account.as_str()
    })
    .await?;
    Ok(account)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn signing_out_asks_first_and_offers_to_copy_the_key() {
    in_player_windows("-sign-out", |client, server, artifacts, window| {
        Box::pin(async move {
            let account = sign_in_by_key(client, server, window).await?;
            click_button(client, "sign-out").await?;
            state_until(client, "the question before signing out", 10, |s| {
                s["dialog"] == "SignOut"
                    && s["signed_in"] == account.as_str()
                    && s["buttons"]["sign-out-copy"].is_array()
            })
            .await?;
            snap(client, artifacts, "sign-out", window).await?;
            click_button(client, "sign-out-copy").await?;
            state_until(client, "the key copied, still signed in", 10, |s| {
                s["message"].as_str().is_some_and(|m| m.contains("copied"))
                    && s["signed_in"] == account.as_str()
            })
            .await?;
            click_button(client, "sign-out-no").await?;
            state_until(client, "still signed in after Cancel", 10, |s| {
                s["dialog"].is_null() && s["signed_in"] == account.as_str()
            })
            .await?;
            click_button(client, "sign-out").await?;
            click_button(client, "sign-out-yes").await?;
            state_until(client, "signed out after saying so", 10, |s| {
                s["signed_in"].is_null() && s["buttons"]["sign-in"].is_array()
            })
            .await?;
            Ok(())
        })
    })
    .await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_friends_match_waits_for_the_friend_before_anyone_aims() {
    in_player_windows("-friend", |client, server, artifacts, window| {
        Box::pin(async move {
            click_button(client, "vs-person").await?;
            let waiting = state_until(client, "the friend's match, connected", 30, |s| {
                s["screen"] == "play" && s["connected"] == true && s["animating"] == false
            })
            .await?;
            // Settle a moment: nothing may offer the turn.
            tokio::time::sleep(Duration::from_millis(600)).await;
            let s = browser::eval(client, browser::APP_STATE).await?;
            if s["my_turn"] != false
                || s["status"] != "Waiting for your friend to join"
                || !s["buttons"]["copy-link"].is_array()
            {
                return Err(E2eError::Check(format!(
                    "alone in a friend's match the page offers the turn or no link: {s}"
                )));
            }
            snap(client, artifacts, "friend-waiting", window).await?;
            // The friend takes the seat: now it is our turn.
            let id = waiting["match_id"].as_str().unwrap_or_default();
            let (status, joined) = api::post_json(
                &server.addr,
                &format!("/api/matches/{id}/join"),
                &serde_json::json!({ "name": "Petka" }),
            )
            .await?;
            if status != 200 && status != 201 {
                return Err(E2eError::Check(format!("join: {status} {joined}")));
            }
            state_until(client, "our turn once the friend joined", 15, |s| {
                s["my_turn"] == true
            })
            .await?;
            Ok(())
        })
    })
    .await;
}

/// Opens a match against the easy computer and waits for our turn.
async fn against_the_computer(client: &Client) -> Result<Value> {
    click_button(client, "vs-computer-easy").await?;
    state_until(client, "our turn against the computer", 30, |s| {
        s["screen"] == "play" && s["my_turn"] == true && s["animating"] == false
    })
    .await
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn leaving_a_match_mid_play_asks_first_and_the_lobby_offers_the_way_back() {
    in_player_windows("-leave", |client, _server, artifacts, window| {
        Box::pin(async move {
            let play = against_the_computer(client).await?;
            let id = play["match_id"].clone();
            click_button(client, "lobby").await?;
            state_until(client, "the question before leaving", 10, |s| {
                s["screen"] == "play" && s["buttons"]["leave-yes"].is_array()
            })
            .await?;
            snap(client, artifacts, "leave-warning", window).await?;
            click_button(client, "leave-no").await?;
            state_until(client, "still in the match after Stay", 10, |s| {
                s["screen"] == "play" && !s["buttons"]["leave-yes"].is_array()
            })
            .await?;
            click_button(client, "lobby").await?;
            click_button(client, "leave-yes").await?;
            state_until(client, "the lobby offering the way back", 15, |s| {
                s["screen"] == "lobby" && s["buttons"]["return-match"].is_array()
            })
            .await?;
            snap(client, artifacts, "lobby-return", window).await?;
            click_button(client, "return-match").await?;
            state_until(client, "back in the same match", 20, |s| {
                s["screen"] == "play" && s["match_id"] == id && s["connected"] == true
            })
            .await?;
            Ok(())
        })
    })
    .await;
}

/// Whether the rectangles `a` and `b` (`[x, y, w, h]`) overlap.
fn overlaps(a: &Value, b: &Value) -> bool {
    let (a, b) = (serde_json::json!({ "a": a }), serde_json::json!({ "b": b }));
    match (layout::controls(&a), layout::controls(&b)) {
        (Ok(a), Ok(b)) => layout::overlap(&a[0], &b[0]).is_some(),
        _ => false,
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_panels_buttons_keep_their_places_and_resigns_confirmation_stands_elsewhere() {
    in_player_windows("-panel", |client, _server, artifacts, window| {
        Box::pin(async move {
            let fixed = ["lobby", "help", "sound", "resign"];
            let at = |s: &Value, n: &str| s["buttons"][n].clone();
            let over = |s: &Value| s["end_screen"] == true;
            // Two shots each way: the log grows. The computer may sweep the
            // board and win round after round (the winner opens the next
            // one) before our third turn comes: then a new match.
            let mut attempt = 0;
            let (start, later) = loop {
                attempt += 1;
                let start = against_the_computer(client).await?;
                let mut swept = false;
                for round in 0..2 {
                    let ready = state_until(client, "our turn", 60, |s| {
                        (s["my_turn"] == true && s["animating"] == false) || over(s)
                    })
                    .await?;
                    if over(&ready) {
                        swept = true;
                        break;
                    }
                    shoot(client, &ready).await?;
                    state_until(client, "the shot counted", 30, |s| {
                        s["shots"].as_u64().is_some_and(|n| n > 2 * round)
                    })
                    .await?;
                }
                let later = if swept {
                    None
                } else {
                    let s = state_until(client, "a log of shots, our turn", 120, |s| {
                        (s["my_turn"] == true && s["log"].as_array().is_some_and(|l| l.len() >= 3))
                            || over(s)
                    })
                    .await?;
                    (!over(&s)).then_some(s)
                };
                match later {
                    Some(later) => break (start, later),
                    None if attempt < 3 => {
                        eprintln!("e2e: the computer won before our third turn; a new match");
                        click_button(client, "lobby").await?;
                        state_until(client, "the lobby", 15, |s| s["screen"] == "lobby").await?;
                    }
                    None => {
                        return Err(E2eError::Check(
                            "the computer won three matches before our third turn".into(),
                        ))
                    }
                }
            };
            for n in fixed {
                if at(&start, n) != at(&later, n) {
                    return Err(E2eError::Check(format!(
                        "{n} moved from {} to {} as the log grew to {}",
                        at(&start, n),
                        at(&later, n),
                        later["log"]
                    )));
                }
            }
            // A double tap on Resign: the second tap finds no confirmation
            // under the finger.
            let (x, y) = centre(&at(&start, "resign"))?;
            click_seen(client, x, y).await?;
            click_seen(client, x, y).await?;
            let asking = state_until(client, "Resign's question", 10, |s| {
                s["buttons"]["resign-yes"].is_array()
            })
            .await?;
            if overlaps(&at(&asking, "resign-yes"), &at(&start, "resign"))
                || asking["end_screen"] == true
            {
                return Err(E2eError::Check(format!(
                    "Resign's confirmation stands under Resign: {asking}"
                )));
            }
            snap(client, artifacts, "resign-question", window).await?;
            let yes = at(&asking, "resign-yes");
            click_button(client, "resign-yes").await?;
            let over = state_until(client, "the match over", 30, |s| {
                s["end_screen"] == true && s["buttons"]["rematch"].is_array()
            })
            .await?;
            for n in ["resign", "resign-yes"] {
                let was = if n == "resign" {
                    at(&start, n)
                } else {
                    yes.clone()
                };
                if overlaps(&at(&over, "rematch"), &was) {
                    return Err(E2eError::Check(format!(
                        "the rematch took {n}'s place: {}",
                        at(&over, "rematch")
                    )));
                }
            }
            for n in ["lobby", "help", "sound"] {
                if at(&start, n) != at(&over, n) {
                    return Err(E2eError::Check(format!(
                        "{n} moved at the match's end: {} to {}",
                        at(&start, n),
                        at(&over, n)
                    )));
                }
            }
            snap(client, artifacts, "panel-over", window).await
        })
    })
    .await;
}

/// What the page's synthesiser was asked to play so far, by kind.
async fn sounds_heard(client: &Client) -> Result<Vec<(String, f64)>> {
    let heard = browser::eval(client, "return window.chapaevSounds || [];").await?;
    Ok(heard
        .as_array()
        .into_iter()
        .flatten()
        .map(|s| {
            (
                s["kind"].as_str().unwrap_or_default().to_string(),
                s["loudness"].as_f64().unwrap_or(0.0),
            )
        })
        .collect())
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn shots_clack_as_their_pieces_meet_and_the_sound_button_silences_them_for_good() {
    in_player_windows("-sound", |client, _server, _artifacts, _window| {
        Box::pin(async move {
            let play = against_the_computer(client).await?;
            if play["sound"] != true {
                return Err(E2eError::Check(format!(
                    "sound is not on by default: {play}"
                )));
            }
            // Our shot, then the computer's, until a collision is heard.
            shoot(client, &play).await?;
            let start = Instant::now();
            let heard = loop {
                let heard = sounds_heard(client).await?;
                if heard.iter().any(|(k, _)| k == "clack") {
                    break heard;
                }
                if start.elapsed() > Duration::from_secs(60) {
                    return Err(E2eError::Check(format!(
                        "no clack within 60 s of shots: {heard:?}"
                    )));
                }
                let s = browser::eval(client, browser::APP_STATE).await?;
                if s["my_turn"] == true && s["animating"] == false {
                    shoot(client, &s).await?;
                }
                tokio::time::sleep(Duration::from_millis(200)).await;
            };
            let flicks = heard.iter().filter(|(k, _)| k == "flick").count();
            let clacks: Vec<f64> = heard
                .iter()
                .filter(|(k, _)| k == "clack")
                .map(|(_, l)| *l)
                .collect();
            if flicks == 0 || clacks.iter().any(|l| !(0.05..=1.0).contains(l)) {
                return Err(E2eError::Check(format!(
                    "flicks and clacks as loud as the hits: {heard:?}"
                )));
            }
            // Muted: the next shots are silent, and it stays so after a reload.
            click_button(client, "sound").await?;
            state_until(client, "sound off", 10, |s| s["sound"] == false).await?;
            client.refresh().await?;
            // The match may be over by now (a computer that knocks a piece
            // off shoots again, and sometimes sweeps the board): then a new one.
            let back = state_until(client, "the page again after the reload", 30, |s| {
                s["screen"] == "lobby"
                    || s["end_screen"] == true
                    || (s["screen"] == "play" && s["my_turn"] == true && s["animating"] == false)
            })
            .await?;
            let muted = if back["screen"] == "lobby" {
                against_the_computer(client).await?
            } else if back["end_screen"] == true {
                eprintln!("e2e: the computer ended the match; a new one, still muted");
                click_button(client, "lobby").await?;
                state_until(client, "the lobby", 15, |s| s["screen"] == "lobby").await?;
                against_the_computer(client).await?
            } else {
                back
            };
            if muted["sound"] != false {
                return Err(E2eError::Check(format!("the mute was forgotten: {muted}")));
            }
            browser::eval(client, "window.chapaevSounds.length = 0; return null;").await?;
            let shots = muted["shots"].as_u64().unwrap_or(0);
            shoot(client, &muted).await?;
            state_until(client, "our shot played and shown", 60, |s| {
                s["shots"].as_u64().unwrap_or(0) > shots && s["animating"] == false
            })
            .await?;
            let after = sounds_heard(client).await?;
            if !after.is_empty() {
                return Err(E2eError::Check(format!("muted, yet heard {after:?}")));
            }
            Ok(())
        })
    })
    .await;
}

/// The rectangle of the native input laid over the text field `name`, in
/// CSS pixels, once there is one (`None` after `secs` without one).
async fn native_input(client: &Client, name: &str, secs: u64) -> Result<Option<Value>> {
    let script = format!(
        r#"const el = document.querySelector('input[data-chapaev-field="{name}"]');
           if (!el) return null;
           const r = el.getBoundingClientRect();
           return [r.x, r.y, r.width, r.height];"#
    );
    let start = Instant::now();
    loop {
        let found = browser::eval(client, &script).await?;
        if !found.is_null() {
            return Ok(Some(found));
        }
        if start.elapsed() > Duration::from_secs(secs) {
            return Ok(None);
        }
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn on_a_touch_screen_a_text_field_is_a_real_input_that_takes_the_phones_typing() {
    in_player_windows("-input", |client, _server, _artifacts, window| {
        Box::pin(async move {
            state_until(client, "the lobby's name field", 30, |s| {
                s["screen"] == "lobby" && s["buttons"]["name"].is_array()
            })
            .await?;
            if window.name != "phone" {
                // A mouse and a keyboard: the canvas is typed into, no input.
                if let Some(r) = native_input(client, "name", 2).await? {
                    return Err(E2eError::Check(format!("a native input on a desktop: {r}")));
                }
                return Ok(());
            }
            // Headless Chromium has a fine pointer: make it a touch screen,
            // and note any use of the browser's prompt.
            browser::eval(
                client,
                r#"const real = window.matchMedia.bind(window);
                   window.matchMedia = (q) => q.includes("pointer: coarse") ? { matches: true } : real(q);
                   window.prompt = () => { window.chapaevPrompted = true; return null; };
                   return null;"#,
            )
            .await?;
            let rect = native_input(client, "name", 10)
                .await?
                .ok_or_else(|| E2eError::Check("no native input over the name field".into()))?;
            let s = browser::eval(client, browser::APP_STATE).await?;
            let field = &s["buttons"]["name"];
            let off = (0..4)
                .map(|i| (rect[i].as_f64().unwrap_or(f64::NAN) - field[i].as_f64().unwrap_or(0.0)).abs())
                .fold(0.0, f64::max);
            if off.is_nan() || off >= 1.5 {
                return Err(E2eError::Check(format!(
                    "the input {rect} is not over the field {field}"
                )));
            }
            let input = client
                .find(fantoccini::Locator::Css(r#"input[data-chapaev-field="name"]"#))
                .await?;
            input.click().await?;
            input.clear().await?;
            input.send_keys("Анка-2").await?;
            state_until(client, "the typed name in the client", 10, |s| s["name"] == "Анка-2")
                .await?;
            let focused = browser::eval(
                client,
                "return document.activeElement && document.activeElement.dataset.chapaevField;",
            )
            .await?;
            let prompted = browser::eval(client, "return window.chapaevPrompted || false;").await?;
            if focused != "name" || prompted != false {
                return Err(E2eError::Check(format!(
                    "focus {focused}, the browser's prompt used: {prompted}"
                )));
            }
            Ok(())
        })
    })
    .await;
}

// ---- The chat of a game: quick phrases, spectators, mute.

/// Presses the button `name` as this window's player does: a finger's tap
/// on the phone, a mouse click on the desktop; then waits for a frame
/// drawn after it.
async fn press(client: &Client, window: &Window, name: &str) -> Result<()> {
    if window.name != "phone" {
        return click_button(client, name).await;
    }
    let state = state_until(client, &format!("the {name} button"), 15, |s| {
        s["buttons"][name].is_array()
    })
    .await?;
    let (x, y) = centre(&state["buttons"][name])?;
    eprintln!("e2e: tapping {name} at ({x:.0}, {y:.0})");
    let after = state["frame"].as_u64().unwrap_or(0);
    browser::tap(client, x, y).await?;
    state_until(client, "a frame after the tap", 10, |s| {
        s["frame"].as_u64().is_some_and(|f| f > after)
    })
    .await?;
    Ok(())
}

/// Whether the page's chat shows a line equal to `line`.
fn chat_has(s: &Value, line: &str) -> bool {
    s["chat"]
        .as_array()
        .is_some_and(|lines| lines.iter().any(|l| l == line))
}

/// Opens a spectator's WebSocket on match `id` from the page (the name
/// `Furmanov`), which keeps every chat it reads in `window.spyChats`.
const SPECTATOR: &str = r#"const [id] = arguments;
    window.spyChats = [];
    const ws = new WebSocket(location.origin.replace(/^http/, "ws") + "/ws?match=" + id);
    window.spy = ws;
    ws.onopen = () => ws.send(JSON.stringify({type: "hello", protocol: 1, name: "Furmanov"}));
    ws.onmessage = (e) => {
        const m = JSON.parse(e.data);
        if (m.type === "welcome") window.spyReady = true;
        if (m.type === "chat") window.spyChats.push(m);
    };
    return true;"#;

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_match_chat_has_quick_phrases_spectators_and_a_mute_and_a_tap_leaves_nothing_lit() {
    in_player_windows("-chat", |client, _server, artifacts, window| {
        Box::pin(async move {
            if window.name == "phone" {
                // Headless Chromium has a fine pointer: make it a touch screen.
                browser::eval(
                    client,
                    r#"const real = window.matchMedia.bind(window);
                       window.matchMedia = (q) => q.includes("pointer: coarse") ? { matches: true } : real(q);
                       return null;"#,
                )
                .await?;
            }
            let play = against_the_computer(client).await?;
            let id = play["match_id"].as_str().unwrap_or_default().to_string();
            // A spectator talks: the player reads it, marked as a spectator's.
            client
                .execute(SPECTATOR, vec![serde_json::json!(id)])
                .await?;
            browser::poll(
                client,
                "the spectator connected",
                "return window.spyReady || false;",
                Duration::from_secs(10),
                Duration::from_millis(50),
                |v| v == true,
            )
            .await?;
            browser::eval(
                client,
                r#"window.spy.send(JSON.stringify({type: "chat", text: "hi from the stands"})); return true;"#,
            )
            .await?;
            let from_stands = "Furmanov (watching): hi from the stands";
            state_until(client, "the spectator's line in the chat", 10, |s| {
                chat_has(s, from_stands)
            })
            .await?;
            // One press opens the quick phrases, one sends "Good shot!".
            press(client, window, "chat-phrases").await?;
            let open = state_until(client, "the chat's menu", 10, |s| {
                s["chat_menu"] == true && s["buttons"]["phrase-good-shot"].is_array()
            })
            .await?;
            // A finger lifted leaves no button lit; a mouse resting on one lights it.
            let lit = &open["hovered"];
            let expected = if window.name == "phone" {
                Value::Null
            } else {
                Value::from("chat-phrases")
            };
            if open.get("hovered").is_none() || *lit != expected {
                return Err(E2eError::Check(format!(
                    "after pressing chat-phrases the lit button is {lit}, not {expected}"
                )));
            }
            snap(client, artifacts, "chat-phrases", window).await?;
            press(client, window, "phrase-good-shot").await?;
            let me = play["seat"].as_str().unwrap_or_default().to_string();
            state_until(client, "the phrase in the chat", 10, |s| {
                s["chat_menu"] == false
                    && s["chat"]
                        .as_array()
                        .is_some_and(|l| l.iter().any(|l| l.as_str().is_some_and(|l| l.ends_with(": Good shot!"))))
            })
            .await?;
            // The spectator got its code, for its own language.
            let heard = browser::eval(client, "return window.spyChats;").await?;
            let coded = heard.as_array().is_some_and(|chats| {
                chats
                    .iter()
                    .any(|c| c["phrase"] == "good-shot" && c["from"] == me.as_str())
            });
            if !coded {
                return Err(E2eError::Check(format!(
                    "the spectator did not hear the phrase by its code: {heard}"
                )));
            }
            // Muting the spectators hides their lines, said before and after.
            press(client, window, "chat-phrases").await?;
            press(client, window, "mute-spectators").await?;
            state_until(client, "the spectator's line hidden", 10, |s| {
                !chat_has(s, from_stands)
            })
            .await?;
            browser::eval(
                client,
                r#"window.spy.send(JSON.stringify({type: "chat", text: "still talking"})); return true;"#,
            )
            .await?;
            browser::poll(
                client,
                "the spectator's own echo",
                "return window.spyChats.some((c) => c.text === 'still talking');",
                Duration::from_secs(10),
                Duration::from_millis(50),
                |v| v == true,
            )
            .await?;
            tokio::time::sleep(Duration::from_millis(300)).await;
            let muted = browser::eval(client, browser::APP_STATE).await?;
            if muted["chat"]
                .as_array()
                .is_none_or(|l| l.iter().any(|l| l.as_str().is_some_and(|l| l.contains("still talking"))))
            {
                return Err(E2eError::Check(format!(
                    "a muted spectator still shows: {}",
                    muted["chat"]
                )));
            }
            snap(client, artifacts, "chat-muted", window).await?;
            Ok(())
        })
    })
    .await;
}

// ---- Figures: the first frame, cold and warm, and the frame rate of a shot.

/// Milliseconds from navigation start to the app's first frame
/// (`window.chapaev_ready_ms`, set by the page's plugin on that frame).
async fn first_frame_ms(client: &Client) -> Result<f64> {
    let ready = browser::poll(
        client,
        "the first frame",
        "return window.chapaev_ready === true ? window.chapaev_ready_ms : null;",
        Duration::from_secs(60),
        Duration::from_millis(10),
        |v| v.is_number(),
    )
    .await?;
    Ok(ready.as_f64().unwrap_or(f64::NAN))
}

/// Prints the figures the client's README quotes (they are measured, not
/// asserted: a loaded machine is slower, not wrong): the first frame of a
/// cold visit (a fresh profile, nothing cached) and of a warm one (the
/// page reloaded, its files in the browser's cache), then the frames drawn
/// per second while a shot animates, counted both by the app's own frame
/// counter and by the browser's `requestAnimationFrame`. Desktop size
/// (1280x800), headless Chromium with WebGL in software.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn figures_the_first_frame_cold_and_warm_and_the_frame_rate_while_a_shot_animates() {
    let Some(Setup {
        programs,
        artifacts,
        scratch,
        server,
        driver,
    }) = setup("-figures")
    else {
        return;
    };
    let extra = [
        "--window-size=1280,800".to_string(),
        "--force-device-scale-factor=1".to_string(),
    ];
    let client = driver
        .session_with(&programs, &scratch.path().join("profile-figures"), &extra)
        .await
        .unwrap_or_else(|e| panic!("{e}"));
    let outcome = async {
        browser::fit_viewport(&client, 1280, 800).await?;
        client.goto(&server.url("/")).await?;
        let cold = first_frame_ms(&client).await?;
        client.goto(&server.url("/?warm")).await?;
        let warm = first_frame_ms(&client).await?;
        eprintln!("e2e: FIGURE first frame: cold {cold:.0} ms, warm {warm:.0} ms after navigation start");
        state_until(&client, "the lobby", 30, |s| {
            s["screen"] == "lobby" && s["buttons"]["vs-computer-easy"].is_array()
        })
        .await?;
        let play = against_the_computer(&client).await?;
        // The browser's own frames, counted from now.
        browser::eval(
            &client,
            "window.rafCount = 0;
             const tick = () => { window.rafCount += 1; requestAnimationFrame(tick); };
             requestAnimationFrame(tick);
             return true;",
        )
        .await?;
        const COUNTS: &str = "const s = window.chapaev_state || {};
            return [s.frame || 0, window.rafCount, performance.now(), s.animating === true];";
        shoot(&client, &play).await?;
        let start = browser::poll(
            &client,
            "the shot animating",
            COUNTS,
            Duration::from_secs(10),
            Duration::from_millis(5),
            |v| v[3] == true,
        )
        .await?;
        let end = browser::poll(
            &client,
            "the shot's animation ended",
            COUNTS,
            Duration::from_secs(30),
            Duration::from_millis(20),
            |v| v[3] == false,
        )
        .await?;
        let n = |v: &Value, i: usize| v[i].as_f64().unwrap_or(f64::NAN);
        let secs = (n(&end, 2) - n(&start, 2)) / 1000.0;
        let app = (n(&end, 0) - n(&start, 0)) / secs;
        let raf = (n(&end, 1) - n(&start, 1)) / secs;
        eprintln!(
            "e2e: FIGURE while a shot animates ({secs:.2} s): {app:.1} app frames/s, {raf:.1} requestAnimationFrame/s"
        );
        std::fs::write(
            artifacts.join("figures.json"),
            format!(
                "{{\"first_frame_cold_ms\":{cold:.1},\"first_frame_warm_ms\":{warm:.1},\
                 \"shot_seconds\":{secs:.3},\"app_fps\":{app:.1},\"raf_fps\":{raf:.1}}}\n"
            ),
        )
        .map_err(|source| E2eError::Io {
            what: "writing figures.json".into(),
            source,
        })?;
        if !(app > 0.0 && raf > 0.0 && cold > 0.0 && warm > 0.0) {
            return Err(E2eError::Check(format!(
                "no figure: cold {cold}, warm {warm}, {app} and {raf} frames/s"
            )));
        }
        Ok(())
    }
    .await;
    let _ = client.close().await;
    drop(driver);
    drop(server);
    if let Err(e) = outcome {
        panic!("{e}\n(logs are in {})", artifacts.display());
    }
}
