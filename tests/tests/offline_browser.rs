//! The computer, played offline in a real browser: the server serves the
//! web client once (its service worker caches the page and the wasm), then
//! the server's process is killed. The page, reloaded, opens from the
//! cache; its lobby finds the server out of reach and says so. "Offline vs
//! computer" with the hard level starts a match played in the page; the
//! player shoots (pulling a piece back with the mouse) until the computer
//! has answered at least once, and its decision's time on the page's clock
//! is printed (the client's `think_ms`). Back in the lobby, "Computer:
//! easy" — the button that asks the server — falls back to an offline
//! match too. Screenshots of the offline lobby, of the hard match after
//! the computer's answer and of the fallback match are left in the
//! artifacts folder (`target/e2e-artifacts` or
//! `$CHAPAEV_E2E_ARTIFACTS`). Skipped, saying so, without a browser.

use e2e::browser::{self, click_button, shoot, state_until, Driver};
use e2e::process::Server;
use e2e::{artifacts_dir, picture, E2eError, Result};
use fantoccini::Client;
use std::path::Path;
use std::time::Duration;

const STATE: &str = "return window.chapaev_state || null;";

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn with_the_server_gone_the_cached_page_plays_the_computer_offline_and_it_answers() {
    let Some(programs) = browser::find_programs().unwrap_or_else(|e| panic!("{e}")) else {
        eprintln!("skipped: no Chromium and chromedriver on this machine");
        return;
    };
    let artifacts = artifacts_dir().unwrap_or_else(|e| panic!("{e}"));
    let scratch = tempfile::tempdir().unwrap();
    let server = Server::start(
        Path::new(env!("CARGO_BIN_EXE_e2e-server")),
        &scratch.path().join("data"),
        &artifacts.join("server-offline.log"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let driver = Driver::start(&programs, &artifacts.join("chromedriver-offline.log"))
        .unwrap_or_else(|e| panic!("{e}"));
    let client = driver
        .session(&programs, &scratch.path().join("profile"))
        .await
        .unwrap_or_else(|e| panic!("{e}"));
    let outcome = offline(&client, server, &artifacts).await;
    if outcome.is_err() {
        let _ = browser::screenshot(&client, &artifacts.join("offline-failure.png")).await;
        if let Ok(state) = browser::eval(&client, STATE).await {
            eprintln!("e2e: chapaev_state at the failure: {state}");
        }
    }
    let _ = client.close().await;
    drop(driver);
    if let Err(e) = outcome {
        panic!("{e}\n(screenshots and logs are in {})", artifacts.display());
    }
}

async fn offline(client: &Client, server: Server, artifacts: &Path) -> Result<()> {
    client.goto(&server.url("/")).await?;
    state_until(client, "the lobby", 30, |s| s["screen"] == "lobby").await?;
    browser::poll(
        client,
        "the service worker in control",
        "return !!(navigator.serviceWorker && navigator.serviceWorker.controller);",
        Duration::from_secs(30),
        Duration::from_millis(200),
        |v| v == true,
    )
    .await?;
    // The server's process is killed: nothing answers on its port.
    drop(server);
    client.refresh().await?;
    let lobby = state_until(client, "the lobby, the server out of reach", 30, |s| {
        s["screen"] == "lobby" && s["offline"] == true
    })
    .await?;
    eprintln!("e2e: the lobby says: {}", lobby["message"]);
    let shot = browser::screenshot(client, &artifacts.join("offline-1-lobby.png")).await?;
    picture::stats(&shot)?.check_drawn("offline lobby", 8, 0.01)?;

    // The explicit choice, at the strongest fixed level.
    click_button(client, "offline").await?;
    let dialog = state_until(client, "the offline levels", 10, |s| {
        s["buttons"]["offline-hard"].is_array()
    })
    .await?;
    if dialog["cut_texts"]
        .as_array()
        .is_some_and(|c| !c.is_empty())
    {
        return Err(E2eError::Check(format!("cut: {}", dialog["cut_texts"])));
    }
    click_button(client, "offline-hard").await?;
    until_the_computer_answers(client, "hard").await?;
    let shot = browser::screenshot(client, &artifacts.join("offline-2-hard.png")).await?;
    picture::stats(&shot)?.check_drawn("offline match (hard)", 8, 0.01)?;
    // More of its decisions, for the figure: until the turn comes back,
    // its fourth decision, the end or 20 s, whichever comes first.
    let more = state_until(client, "more decisions", 20, |s| {
        s["thinks"].as_u64() >= Some(4)
            || s["end_screen"] == true
            || (s["my_turn"] == true && s["animating"] == false)
    })
    .await;
    let s = match more {
        Ok(s) => s,
        Err(_) => browser::eval(client, STATE).await?,
    };
    eprintln!(
        "e2e: offline hard: {} decisions, the longest {} ms of the page's clock",
        s["thinks"], s["think_ms_longest"]
    );

    // The lobby's own button, which would ask the server, falls back.
    browser::eval(client, "location.hash = '#/'; return true;").await?;
    state_until(client, "the lobby again", 15, |s| s["screen"] == "lobby").await?;
    click_button(client, "vs-computer-easy").await?;
    let play = state_until(client, "an offline match against easy", 15, |s| {
        s["screen"] == "play" && s["my_turn"] == true
    })
    .await?;
    if play["offline"] != "easy" {
        return Err(E2eError::Check(format!(
            "the lobby's button did not fall back: {}",
            play["offline"]
        )));
    }
    let shot = browser::screenshot(client, &artifacts.join("offline-3-fallback.png")).await?;
    picture::stats(&shot)?.check_drawn("offline match (easy)", 8, 0.01)?;
    Ok(())
}

/// On the offline match against `level`, shoots whenever it is our turn
/// until the computer has answered at least once (twelve shots at most).
async fn until_the_computer_answers(client: &Client, level: &str) -> Result<()> {
    let mut fired = 0;
    loop {
        let s = state_until(client, "our turn or the computer's answer", 30, |s| {
            s["screen"] == "play"
                && (s["thinks"].as_u64() > Some(0)
                    || (s["my_turn"] == true && s["animating"] == false))
        })
        .await?;
        if s["offline"] != level {
            return Err(E2eError::Check(format!(
                "not an offline match against {level}: {}",
                s["offline"]
            )));
        }
        if s["thinks"].as_u64() > Some(0) {
            eprintln!(
                "e2e: offline {level}: the computer answered after {fired} shots of ours; \
                 {} decisions, the last {} ms, the longest {} ms of the page's clock; \
                 status: {}",
                s["thinks"], s["think_ms"], s["think_ms_longest"], s["status"]
            );
            return Ok(());
        }
        if fired == 12 {
            return Err(E2eError::Check(format!(
                "the computer never answered in {fired} shots"
            )));
        }
        shoot(client, &s).await?;
        fired += 1;
        let before = s["shots"].as_u64().unwrap_or(0);
        state_until(client, "our shot played", 15, |t| {
            t["shots"].as_u64().is_some_and(|n| n > before)
        })
        .await?;
    }
}
