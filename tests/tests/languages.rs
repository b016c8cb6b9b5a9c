//! The interface in Russian and English, in a real browser: a Chromium
//! whose preferred language is Russian (`--lang=ru`, `--accept-lang=ru`)
//! opens the game in Russian (the client's report says `lang: "ru"`, the
//! page's `<html lang>` follows, the lobby's buttons read in Russian); the
//! language switch turns it to English and the choice survives a reload.
//! Every main screen (lobby, rules, leaderboard, account, quick match, play
//! against the computer, the end of the match, the replay, the sandbox) is
//! visited in both languages, at a laptop's and a phone's size, and on each
//! the client reports no button whose label had to be cut, no text cut
//! short (a title, a heading) and, in every row of buttons, one size for
//! all their labels, no text smaller than 12 CSS pixels (the client's
//! `small_texts`: a button's label or any other text) and every control
//! inside the window; each is saved as
//! a screenshot (`lobby-ru.png`, `lobby-en.png`, `lobby-ru-phone.png`, ...)
//! in the artifacts folder (`target/e2e-artifacts` or
//! `$CHAPAEV_E2E_ARTIFACTS`). The page's loader, shown before the game
//! has loaded, speaks the same language, and the computer's seat in a
//! match reads as the computer of its level in it. On a phone held
//! sideways (844 x 390 at three device pixels a CSS pixel) the sandbox
//! leaves the world most of the window, its side panel opens and closes
//! over it, and every control stays inside the window. The smallest
//! phone there is (an iPhone SE: 568 x 320 on its side, 320 x 568
//! upright, two device pixels a CSS pixel) gets the same tour, in
//! Russian on its side and in English upright, every screen with a
//! language switch (the lobby, the rules, the leaderboard, the account,
//! the replay, the sandbox) seen in the other language too, so each
//! screen is checked in both languages at that size; there the sandbox's
//! world is at least 480 x 220 CSS pixels sideways and 300 x 400 upright,
//! and its menu of tools and its side panel open over the world and
//! close again.

use e2e::browser::{self, click_button, state_until, Driver};
use e2e::process::Server;
use e2e::{artifacts_dir, picture, E2eError, Result};
use fantoccini::Client;
use serde_json::Value;
use std::path::Path;
use std::time::Duration;

const STATE: &str = "return window.chapaev_state || null;";

/// A window the tour runs in: its name in the screenshots' names, its
/// CSS size and device-pixel ratio.
struct Window {
    suffix: &'static str,
    width: u32,
    height: u32,
    dpr: u32,
}

const LAPTOP: Window = Window {
    suffix: "",
    width: 1280,
    height: 800,
    dpr: 1,
};

const PHONE: Window = Window {
    suffix: "-phone",
    width: 390,
    height: 844,
    dpr: 2,
};

const SIDEWAYS: Window = Window {
    suffix: "-sideways",
    width: 844,
    height: 390,
    dpr: 3,
};

/// The smallest phone on its side and upright.
const SMALL_SIDEWAYS: Window = Window {
    suffix: "-small-sideways",
    width: 568,
    height: 320,
    dpr: 2,
};

const SMALL_UPRIGHT: Window = Window {
    suffix: "-small",
    width: 320,
    height: 568,
    dpr: 2,
};

/// The smallest text a screen may show (CSS pixels; the client reports
/// any smaller one in `small_texts`, a button's label among them).
const MIN_TEXT: f64 = 12.0;

/// The smallest label of the replay's controls on a phone (CSS pixels).
const REPLAY_PHONE_TEXT: f64 = 13.0;

/// The smallest world the sandbox leaves on the smallest phone (CSS
/// pixels): on its side, and upright.
const SMALL_WORLD_SIDEWAYS: (f64, f64) = (480.0, 220.0);
const SMALL_WORLD_UPRIGHT: (f64, f64) = (300.0, 400.0);

/// A server and a chromedriver of the test's own (each test runs beside
/// the others), or `None` where the machine has no browser (said out loud
/// by `find_programs`).
struct Rig {
    programs: browser::Programs,
    artifacts: std::path::PathBuf,
    scratch: tempfile::TempDir,
    server: Server,
    driver: Driver,
}

fn rig(tag: &str) -> Option<Rig> {
    let programs = browser::find_programs().unwrap_or_else(|e| panic!("{e}"))?;
    let artifacts = artifacts_dir().unwrap_or_else(|e| panic!("{e}"));
    let scratch = tempfile::tempdir().unwrap();
    let server = Server::start(
        Path::new(env!("CARGO_BIN_EXE_e2e-server")),
        &scratch.path().join("data"),
        &artifacts.join(format!("server-languages{tag}.log")),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let driver = Driver::start(
        &programs,
        &artifacts.join(format!("chromedriver-languages{tag}.log")),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    Some(Rig {
        programs,
        artifacts,
        scratch,
        server,
        driver,
    })
}

impl Rig {
    /// A Russian browser in `window`.
    async fn russian(&self, window: &Window) -> Client {
        let extra = [
            "--lang=ru".to_string(),
            "--accept-lang=ru-RU,ru".to_string(),
            format!("--window-size={},{}", window.width, window.height),
            format!("--force-device-scale-factor={}", window.dpr),
        ];
        let profile = self
            .scratch
            .path()
            .join(format!("profile-languages{}", window.suffix));
        self.driver
            .session_with(&self.programs, &profile, &extra)
            .await
            .unwrap_or_else(|e| panic!("{e}"))
    }

    /// Fails the test with `outcome`'s error, a screenshot and the
    /// client's state, named for `window`.
    async fn finish(&self, client: Client, window: &Window, outcome: Result<()>) {
        if let Err(e) = &outcome {
            let _ = browser::screenshot(
                &client,
                &self
                    .artifacts
                    .join(format!("failure-languages{}.png", window.suffix)),
            )
            .await;
            if let Ok(state) = browser::eval(&client, STATE).await {
                eprintln!("e2e: chapaev_state at the failure: {state}");
            }
            let _ = client.close().await;
            panic!(
                "{}x{}: {e}\n(screenshots and logs are in {})",
                window.width,
                window.height,
                self.artifacts.display()
            );
        }
        let _ = client.close().await;
    }
}

/// The tour of every screen in `window`: both languages in full, or on
/// the smallest phone one language with each switchable screen seen in
/// the other too.
async fn tour_in(window: &Window) {
    let Some(rig) = rig(window.suffix) else {
        return;
    };
    let client = rig.russian(window).await;
    let started = std::time::Instant::now();
    let outcome = if window.suffix.starts_with("-small") {
        smallest_phone(&client, &rig.server, &rig.artifacts, window).await
    } else {
        both_languages(&client, &rig.server, &rig.artifacts, window).await
    };
    eprintln!(
        "e2e: the tours at {}x{} took {:.1} s",
        window.width,
        window.height,
        started.elapsed().as_secs_f64()
    );
    rig.finish(client, window, outcome).await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_russian_browser_gets_russian_the_switch_turns_it_to_english_and_a_reload_keeps_it() {
    tour_in(&LAPTOP).await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn on_a_phone_every_screen_reads_whole_and_even_in_both_languages() {
    tour_in(&PHONE).await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn on_the_smallest_phone_on_its_side_every_screen_reads_whole_and_even() {
    tour_in(&SMALL_SIDEWAYS).await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn on_the_smallest_phone_upright_every_screen_reads_whole_and_even() {
    tour_in(&SMALL_UPRIGHT).await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn on_a_phone_on_its_side_the_sandbox_leaves_the_world_most_of_the_window() {
    let Some(rig) = rig(SIDEWAYS.suffix) else {
        return;
    };
    let client = rig.russian(&SIDEWAYS).await;
    let outcome = sandbox_sideways(&client, &rig.server, &rig.artifacts).await;
    rig.finish(client, &SIDEWAYS, outcome).await;
}

/// Russian first (from the browser's preference), the tour; then the
/// switch to English, a reload, the tour again.
async fn both_languages(
    client: &Client,
    server: &Server,
    artifacts: &Path,
    window: &Window,
) -> Result<()> {
    browser::fit_viewport(client, window.width, window.height).await?;
    client.goto(&server.url("/")).await?;
    let preferred = browser::eval(client, "return navigator.languages.join(',');").await?;
    eprintln!("e2e: the browser prefers {preferred}");
    let lobby = lobby_in(client, "ru").await?;
    expect_label(&lobby, "vs-computer-easy", "Компьютер: лёгкий")?;
    expect_loader(client, "ru", "Загружается «Чапаев»…").await?;
    expect_label(
        &lobby,
        "lang",
        if short_switch(window) {
            "EN"
        } else {
            "English"
        },
    )?;
    expect_html_lang(client, "ru").await?;
    tour(client, artifacts, window, "ru").await?;

    // The switch, in the lobby: English at once, and after a reload.
    click_button(client, "lang").await?;
    let lobby = lobby_in(client, "en").await?;
    expect_label(&lobby, "vs-computer-easy", "Computer: easy")?;
    expect_html_lang(client, "en").await?;
    client.refresh().await?;
    let lobby = lobby_in(client, "en").await?;
    expect_label(&lobby, "vs-computer-easy", "Computer: easy")?;
    expect_label(
        &lobby,
        "lang",
        if short_switch(window) {
            "RU"
        } else {
            "Русский"
        },
    )?;
    expect_loader(client, "en", "Loading Chapaev…").await?;
    tour(client, artifacts, window, "en").await
}

/// The tour on the smallest phone: in Russian (the browser's language) on
/// its side, in English (switched to in the lobby) upright.
async fn smallest_phone(
    client: &Client,
    server: &Server,
    artifacts: &Path,
    window: &Window,
) -> Result<()> {
    browser::fit_viewport(client, window.width, window.height).await?;
    client.goto(&server.url("/")).await?;
    lobby_in(client, "ru").await?;
    let lang = if window.width < window.height {
        click_button(client, "lang").await?;
        lobby_in(client, "en").await?;
        "en"
    } else {
        "ru"
    };
    tour(client, artifacts, window, lang).await
}

/// On the smallest phone, the screen `name` shown in `lang` is switched to
/// the other language, checked as [`tour`] checks a screen and saved as
/// `<name>-<other><suffix>.png`, and switched back.
async fn in_the_other_language(
    client: &Client,
    artifacts: &Path,
    window: &Window,
    name: &str,
    lang: &str,
) -> Result<()> {
    if !window.suffix.starts_with("-small") {
        return Ok(());
    }
    let other = if lang == "ru" { "en" } else { "ru" };
    click_button(client, "lang").await?;
    let state = settle(client, other).await?;
    let file = format!("{name}-{other}{}.png", window.suffix);
    let png = browser::screenshot(client, &artifacts.join(&file)).await?;
    picture::stats(&png)?.check_drawn(&file, 8, 0.001)?;
    whole_and_even(&state, &file)?;
    inside_window(&state, &file, window)?;
    click_button(client, "lang").await?;
    settle(client, lang).await?;
    Ok(())
}

/// Whether the lobby's language switch reads "EN"/"RU" in `window` (a
/// phone's) rather than the language's whole name.
fn short_switch(window: &Window) -> bool {
    window.width < 600
}

/// Loads the page once more in a hidden frame and reads its loader as the
/// page has parsed (before the game's first frame takes it away): it
/// must speak `lang` (the language chosen before, else the browser's).
async fn expect_loader(client: &Client, lang: &str, words: &str) -> Result<()> {
    browser::eval(
        client,
        r#"window.loaderSeen = null;
           const f = document.createElement("iframe");
           f.style.cssText = "position:absolute;width:10px;height:10px;opacity:0";
           f.src = "/?loader";
           document.body.appendChild(f);
           window.loaderFrame = f;
           const look = setInterval(() => {
               const d = f.contentDocument;
               if (!d || d.URL === "about:blank" || d.readyState === "loading") return;
               const w = d.getElementById("loading-words");
               window.loaderSeen = w ? [d.documentElement.lang, w.textContent] : ["gone"];
               clearInterval(look);
           }, 1);
           return true;"#,
    )
    .await?;
    let seen = browser::poll(
        client,
        "the loader in a frame",
        "return window.loaderSeen;",
        Duration::from_secs(15),
        Duration::from_millis(50),
        |v| !v.is_null(),
    )
    .await?;
    browser::eval(client, "window.loaderFrame.remove(); return true;").await?;
    if seen[0] == lang && seen[1] == words {
        Ok(())
    } else {
        Err(E2eError::Check(format!(
            "the page's loader reads {seen}, not [{lang:?}, {words:?}]"
        )))
    }
}

/// Visits every main screen from the lobby, checking each shows `lang`
/// with no label cut, and saves its screenshot as `<screen>-<lang><suffix>.png`.
async fn tour(client: &Client, artifacts: &Path, window: &Window, lang: &str) -> Result<()> {
    let snap = |name: &'static str| async move {
        let state = settle(client, lang).await?;
        let file = format!("{name}-{lang}{}.png", window.suffix);
        let png = browser::screenshot(client, &artifacts.join(&file)).await?;
        picture::stats(&png)?.check_drawn(&file, 8, 0.001)?;
        whole_and_even(&state, &file)?;
        inside_window(&state, &file, window)?;
        Ok::<Value, E2eError>(state)
    };
    let other = |name: &'static str| in_the_other_language(client, artifacts, window, name, lang);
    snap("lobby").await?;
    other("lobby").await?;
    click_button(client, "help").await?;
    snap("help").await?;
    other("help").await?;
    click_button(client, "help-close").await?;

    click_button(client, "leaderboard").await?;
    state_until(client, "the leaderboard, loaded", 15, |s| {
        s["screen"] == "leaderboard" && s["loaded"] == true
    })
    .await?;
    snap("leaderboard").await?;
    other("leaderboard").await?;
    click_button(client, "lobby").await?;

    click_button(client, "sign-in").await?;
    state_until(client, "the account screen", 15, |s| {
        s["screen"] == "account"
    })
    .await?;
    snap("sign-in").await?;
    other("sign-in").await?;
    click_button(client, "lobby").await?;

    // Without an account the quick match offers the computer at once.
    click_button(client, "quick-match").await?;
    state_until(client, "the quick match's offer of the computer", 15, |s| {
        s["screen"] == "quick-match" && s["buttons"]["quick-computer"].is_array()
    })
    .await?;
    snap("quick-match").await?;
    click_button(client, "quick-cancel").await?;

    click_button(client, "vs-computer-easy").await?;
    state_until(
        client,
        "the match against the computer, on our turn",
        30,
        |s| s["screen"] == "play" && s["my_turn"] == true && s["animating"] == false,
    )
    .await?;
    let play = snap("play").await?;
    // The computer's seat reads as the computer of its level, in words of
    // the language shown (the server names it `bot (easy)`).
    let computer = if lang == "ru" {
        "компьютер (лёгкий)"
    } else {
        "computer (easy)"
    };
    if play["players"][1] != computer {
        return Err(E2eError::Check(format!(
            "the computer's seat reads {}, not {computer:?}",
            play["players"]
        )));
    }
    click_button(client, "resign").await?;
    click_button(client, "resign-yes").await?;
    state_until(client, "the end of the match", 15, |s| {
        s["buttons"]["end-replay"].is_array()
    })
    .await?;
    snap("end").await?;
    click_button(client, "end-replay").await?;
    let replay = state_until(client, "the replay, loaded, with its players", 15, |s| {
        s["screen"] == "replay" && s["buttons"]["timeline"].is_array() && s["players"].is_string()
    })
    .await?;
    // Who played whom, and the shot jumps in words.
    let players = replay["players"].as_str().unwrap_or_default();
    if !players.contains(computer) {
        return Err(E2eError::Check(format!(
            "the replay's players read {players:?}, without {computer:?}"
        )));
    }
    let previous = if lang == "ru" {
        "Пред. щелчок"
    } else {
        "Prev. shot"
    };
    expect_label(&replay, "previous-shot", previous)?;
    let replay = snap("replay").await?;
    other("replay").await?;
    // On a phone the replay's controls read at 13 px or more.
    if window.width < 600 {
        let sizes = replay["label_sizes"]
            .as_object()
            .cloned()
            .unwrap_or_default();
        if let Some((name, size)) = sizes
            .iter()
            .find(|(_, s)| s.as_f64().unwrap_or(0.0) < REPLAY_PHONE_TEXT)
        {
            return Err(E2eError::Check(format!(
                "replay{}: the {name} button's label is {size} px, under {REPLAY_PHONE_TEXT}",
                window.suffix
            )));
        }
    }
    click_button(client, "lobby").await?;

    click_button(client, "sandbox").await?;
    state_until(client, "the sandbox with its bodies", 15, |s| {
        s["screen"] == "sandbox" && s["bodies"].as_u64().is_some_and(|n| n > 0)
    })
    .await?;
    let sandbox = snap("sandbox").await?;
    other("sandbox").await?;
    if !sandbox["buttons"]["lang"].is_array() {
        return Err(E2eError::Check(format!(
            "no language switch in the sandbox's toolbar: {}",
            sandbox["buttons"]
        )));
    }
    let small = match window.suffix {
        "-small-sideways" => Some(SMALL_WORLD_SIDEWAYS),
        "-small" => Some(SMALL_WORLD_UPRIGHT),
        _ => None,
    };
    if let Some((min_w, min_h)) = small {
        let world = &sandbox["world"];
        let (ww, wh) = (
            world[2].as_f64().unwrap_or(0.0),
            world[3].as_f64().unwrap_or(0.0),
        );
        eprintln!(
            "e2e: the sandbox's world at {}x{}: {ww} x {wh} CSS pixels",
            window.width, window.height
        );
        if ww < min_w || wh < min_h {
            return Err(E2eError::Check(format!(
                "the sandbox's world is {ww} x {wh} at {}x{}, not at least {min_w} x {min_h}",
                window.width, window.height
            )));
        }
        // The menu of tools and speeds, then the side panel, over the
        // world; each closes again.
        for (button, shows, open) in [
            ("menu", "tool-disc", "tools_open"),
            ("panel", "preset-brownian", "panel_open"),
        ] {
            click_button(client, button).await?;
            let state = snap(if button == "menu" {
                "sandbox-menu"
            } else {
                "sandbox-panel"
            })
            .await?;
            if state[open] != true || !state["buttons"][shows].is_array() {
                return Err(E2eError::Check(format!(
                    "{button} did not open what it holds: {}",
                    state["buttons"]
                )));
            }
            click_button(client, button).await?;
            let closed = settle(client, lang).await?;
            if closed[open] != false || !closed["buttons"]["play"].is_array() {
                return Err(E2eError::Check(format!(
                    "{button} did not close, or the bar did not come back"
                )));
            }
        }
    }
    click_button(client, "lobby").await?;
    lobby_in(client, lang).await?;
    Ok(())
}

/// Checks that every control the screen `state` reports (saved as
/// `file`) lies inside `window`.
fn inside_window(state: &Value, file: &str, window: &Window) -> Result<()> {
    let buttons = state["buttons"].as_object().cloned().unwrap_or_default();
    let (w, h) = (f64::from(window.width), f64::from(window.height));
    for (name, r) in &buttons {
        let n = |i: usize| r[i].as_f64().unwrap_or(f64::NAN);
        if !(n(0) >= -0.01 && n(1) >= -0.01 && n(0) + n(2) <= w + 0.01 && n(1) + n(3) <= h + 0.01) {
            return Err(E2eError::Check(format!(
                "{file}: {name} {r} is outside the {w} x {h} window"
            )));
        }
    }
    Ok(())
}

/// Checks the screen `state` reports (saved as `file`): no button's label
/// cut, no other text cut short or running out of its panel or the
/// window, no text (a label or another) under [`MIN_TEXT`], and one label
/// size in each row of buttons (buttons of one height whose tops are
/// level).
fn whole_and_even(state: &Value, file: &str) -> Result<()> {
    let cut = state["cut"].as_array().cloned().unwrap_or_default();
    if !cut.is_empty() {
        return Err(E2eError::Check(format!(
            "{file}: labels cut on {}: {cut:?} (labels {})",
            state["screen"], state["labels"]
        )));
    }
    let texts = state["cut_texts"].as_array().cloned().unwrap_or_default();
    if !texts.is_empty() {
        return Err(E2eError::Check(format!(
            "{file}: texts cut short on {}: {texts:?}",
            state["screen"]
        )));
    }
    let small = state["small_texts"]
        .as_object()
        .cloned()
        .unwrap_or_default();
    if !small.is_empty() {
        return Err(E2eError::Check(format!(
            "{file}: texts under {MIN_TEXT} px on {}: {small:?}",
            state["screen"]
        )));
    }
    eprintln!(
        "e2e: {file}: label sizes {}, buttons {}",
        state["label_sizes"], state["buttons"]
    );
    // Each row by its top and height (tenths of a pixel), with its
    // buttons' names and label sizes.
    type Row = Vec<(String, f64)>;
    let mut rows: Vec<((f64, f64), Row)> = Vec::new();
    let sizes = state["label_sizes"]
        .as_object()
        .cloned()
        .unwrap_or_default();
    for (name, size) in &sizes {
        let rect = &state["buttons"][name];
        let (Some(y), Some(h), Some(size)) = (rect[1].as_f64(), rect[3].as_f64(), size.as_f64())
        else {
            continue;
        };
        let key = ((y * 10.0).round(), (h * 10.0).round());
        match rows.iter_mut().find(|(k, _)| *k == key) {
            Some((_, row)) => row.push((name.clone(), size)),
            None => rows.push((key, vec![(name.clone(), size)])),
        }
    }
    for (_, row) in &rows {
        if let Some((name, size)) = row.iter().find(|(_, s)| *s < MIN_TEXT - 0.01) {
            return Err(E2eError::Check(format!(
                "{file}: the {name} button's label is {size} px on {}, under {MIN_TEXT}",
                state["screen"]
            )));
        }
        if row.iter().any(|(_, s)| (s - row[0].1).abs() > 0.01) {
            return Err(E2eError::Check(format!(
                "{file}: one row of buttons on {} has labels of different sizes: {row:?}",
                state["screen"]
            )));
        }
    }
    Ok(())
}

/// The sandbox on a phone held sideways: the world takes most of the
/// window (at least 600 x 270 CSS pixels), every button stays inside the
/// window, the side panel opens over the world's right part and leaves
/// some of it in sight, and closes again.
async fn sandbox_sideways(client: &Client, server: &Server, artifacts: &Path) -> Result<()> {
    browser::fit_viewport(client, SIDEWAYS.width, SIDEWAYS.height).await?;
    client.goto(&server.url("/#/sandbox")).await?;
    state_until(client, "the sandbox with its bodies", 30, |s| {
        s["screen"] == "sandbox" && s["bodies"].as_u64().is_some_and(|n| n > 0)
    })
    .await?;
    let inside = |state: &Value, file: &str| -> Result<()> {
        let buttons = state["buttons"].as_object().cloned().unwrap_or_default();
        for (name, r) in &buttons {
            let n = |i: usize| r[i].as_f64().unwrap_or(f64::NAN);
            let (w, h) = (f64::from(SIDEWAYS.width), f64::from(SIDEWAYS.height));
            if !(n(0) >= -0.01
                && n(1) >= -0.01
                && n(0) + n(2) <= w + 0.01
                && n(1) + n(3) <= h + 0.01)
            {
                return Err(E2eError::Check(format!(
                    "{file}: {name} {r} is outside the window"
                )));
            }
        }
        whole_and_even(state, file)
    };
    let closed = settle(client, "ru").await?;
    let png = browser::screenshot(client, &artifacts.join("sandbox-ru-sideways.png")).await?;
    picture::stats(&png)?.check_drawn("sandbox-ru-sideways.png", 8, 0.001)?;
    inside(&closed, "sandbox-ru-sideways.png")?;
    let world = &closed["world"];
    let (ww, wh) = (
        world[2].as_f64().unwrap_or(0.0),
        world[3].as_f64().unwrap_or(0.0),
    );
    eprintln!("e2e: the sandbox's world on a phone held sideways: {ww} x {wh} CSS pixels");
    if ww < 600.0 || wh < 270.0 {
        return Err(E2eError::Check(format!(
            "the sandbox's world is {ww} x {wh} on a phone held sideways, not at least 600 x 270"
        )));
    }
    click_button(client, "panel").await?;
    let open = settle(client, "ru").await?;
    browser::screenshot(client, &artifacts.join("sandbox-panel-ru-sideways.png")).await?;
    inside(&open, "sandbox-panel-ru-sideways.png")?;
    let side = &open["side"];
    let seen = side[0].as_f64().unwrap_or(0.0) - world[0].as_f64().unwrap_or(0.0);
    if open["panel_open"] != true || !open["buttons"]["preset-brownian"].is_array() || seen < 150.0
    {
        return Err(E2eError::Check(format!(
            "the open panel ({side}) should show the presets and leave 150 px of the world ({world}) in sight"
        )));
    }
    click_button(client, "panel").await?;
    let again = settle(client, "ru").await?;
    if again["panel_open"] != false || !again["buttons"]["play"].is_array() {
        return Err(E2eError::Check(
            "the panel did not close, or the bar did not come back".into(),
        ));
    }
    Ok(())
}

/// Waits for the lobby drawn in `lang`.
async fn lobby_in(client: &Client, lang: &str) -> Result<Value> {
    state_until(client, &format!("the lobby in {lang}"), 30, |s| {
        s["screen"] == "lobby" && s["lang"] == lang && s["buttons"]["vs-computer-easy"].is_array()
    })
    .await
}

/// Lets the screen draw a few frames, then reads it: it must be in `lang`.
async fn settle(client: &Client, lang: &str) -> Result<Value> {
    tokio::time::sleep(Duration::from_millis(600)).await;
    let state = browser::eval(client, STATE).await?;
    if state["lang"] != lang {
        return Err(E2eError::Check(format!(
            "the {} screen is in {}, not {lang}",
            state["screen"], state["lang"]
        )));
    }
    Ok(state)
}

fn expect_label(state: &Value, button: &str, label: &str) -> Result<()> {
    if state["labels"][button] == label {
        Ok(())
    } else {
        Err(E2eError::Check(format!(
            "the {button} button reads {}, not {label:?}",
            state["labels"][button]
        )))
    }
}

async fn expect_html_lang(client: &Client, lang: &str) -> Result<()> {
    let html = browser::eval(client, "return document.documentElement.lang;").await?;
    if html == lang {
        Ok(())
    } else {
        Err(E2eError::Check(format!(
            "<html lang> is {html}, not {lang:?}"
        )))
    }
}
