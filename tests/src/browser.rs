//! Headless Chromium over WebDriver: finding Debian's `chromium` and
//! `chromedriver` (or failing with what to install, unless
//! `CHAPAEV_SKIP_BROWSER=1`), starting chromedriver on a free port, a
//! session with software WebGL (SwiftShader) in a fresh profile, and the
//! page-level helpers the scenarios use: evaluating JavaScript, polling for
//! a condition, clicking and dragging with the mouse, dragging a finger
//! (touch events), pasting text, screenshots.

use crate::process::{free_port, wait_for_port, Guard};
use crate::{E2eError, Result};
use fantoccini::actions::{InputSource, MouseActions, PointerAction, MOUSE_BUTTON_LEFT};
use fantoccini::{Client, ClientBuilder};
use serde_json::{json, Value};
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The variable that lets a machine without Chromium skip browser tests.
pub const SKIP_VAR: &str = "CHAPAEV_SKIP_BROWSER";

/// Chromium's flags: headless, sandbox-free (containers, root), no network
/// chatter, WebGL in software, a fixed window.
pub const CHROME_ARGS: &[&str] = &[
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
    "--window-size=1024,720",
];

/// The two programs, found.
#[derive(Debug, Clone)]
pub struct Programs {
    pub chromium: PathBuf,
    pub chromedriver: PathBuf,
}

/// Finds Chromium and chromedriver (`$CHROMIUM`, `$CHROMEDRIVER`, else
/// `/usr/bin/…`, else the `PATH`). `Ok(None)`: `CHAPAEV_SKIP_BROWSER=1`
/// says to skip (a loud message on standard error, past the test harness's
/// capture, says so); missing programs without it are an error saying what
/// to install.
pub fn find_programs() -> Result<Option<Programs>> {
    if std::env::var_os(SKIP_VAR).is_some_and(|v| !v.is_empty() && v != "0") {
        let bar = "!".repeat(72);
        let _ = writeln!(
            std::io::stderr(),
            "{bar}\n!! SKIPPED: the browser end-to-end test ({SKIP_VAR} is set).\n\
             !! Nothing was checked in a browser. It needs Chromium and chromedriver:\n\
             !!     apt-get install chromium chromium-driver\n{bar}"
        );
        return Ok(None);
    }
    let chromium = find(
        "CHROMIUM",
        &["chromium", "chromium-browser", "google-chrome"],
    );
    let chromedriver = find("CHROMEDRIVER", &["chromedriver"]);
    if let (Some(chromium), Some(chromedriver)) = (&chromium, &chromedriver) {
        return Ok(Some(Programs {
            chromium: chromium.clone(),
            chromedriver: chromedriver.clone(),
        }));
    }
    let missing = [("chromium", &chromium), ("chromedriver", &chromedriver)]
        .iter()
        .filter(|(_, p)| p.is_none())
        .map(|(n, _)| *n)
        .collect::<Vec<_>>()
        .join(" and ");
    Err(E2eError::Setup(format!(
        "{missing} not found: the browser end-to-end test needs Chromium and its WebDriver; \
         install them with `apt-get install chromium chromium-driver` (CI does), or set \
         {SKIP_VAR}=1 to skip this test on purpose"
    )))
}

fn find(var: &str, names: &[&str]) -> Option<PathBuf> {
    if let Some(p) = std::env::var_os(var).filter(|p| !p.is_empty()) {
        // An explicit choice: that program or none.
        return Some(PathBuf::from(p)).filter(|p| p.is_file());
    }
    let path = std::env::var_os("PATH").unwrap_or_default();
    names.iter().find_map(|name| {
        std::iter::once(PathBuf::from("/usr/bin"))
            .chain(std::env::split_paths(&path))
            .map(|dir| dir.join(name))
            .find(|p| p.is_file())
    })
}

/// chromedriver, running; killed (with the browsers it started) on drop.
pub struct Driver {
    pub guard: Guard,
    pub url: String,
}

impl Driver {
    /// Starts chromedriver on a free port, its log (and the browser's
    /// standard error) in `log`.
    pub fn start(programs: &Programs, log: &Path) -> Result<Driver> {
        let port = free_port()?;
        let io = |source| E2eError::Io {
            what: format!("creating {}", log.display()),
            source,
        };
        let out = std::fs::File::create(log).map_err(io)?;
        let err = out.try_clone().map_err(io)?;
        let mut cmd = Command::new(&programs.chromedriver);
        cmd.arg(format!("--port={port}"))
            .arg("--enable-chrome-logs")
            .stdin(Stdio::null())
            .stdout(out)
            .stderr(err);
        let mut guard = Guard::spawn("chromedriver", cmd)?;
        wait_for_port(&mut guard, port, Duration::from_secs(20))?;
        Ok(Driver {
            guard,
            url: format!("http://127.0.0.1:{port}"),
        })
    }

    /// A new browser session in a fresh profile folder `profile`.
    pub async fn session(&self, programs: &Programs, profile: &Path) -> Result<Client> {
        self.session_with(programs, profile, &[]).await
    }

    /// A new browser session with Chromium flags of its own added (a
    /// window size, `--force-device-scale-factor=3`).
    pub async fn session_with(
        &self,
        programs: &Programs,
        profile: &Path,
        extra: &[String],
    ) -> Result<Client> {
        let mut args: Vec<String> = CHROME_ARGS.iter().map(|a| a.to_string()).collect();
        args.extend(extra.iter().cloned());
        args.push(format!("--user-data-dir={}", profile.display()));
        args.push("--enable-logging=stderr".into());
        let caps = json!({
            "browserName": "chrome",
            "goog:chromeOptions": {
                "binary": programs.chromium,
                "args": args,
            },
        });
        let Value::Object(caps) = caps else {
            unreachable!("a JSON object literal")
        };
        let connector = hyper_util::client::legacy::connect::HttpConnector::new();
        Ok(ClientBuilder::new(connector)
            .capabilities(caps)
            .connect(&self.url)
            .await?)
    }
}

/// Resizes the window so the page's viewport is `width` x `height` CSS
/// pixels (`--window-size` sets the window, browser frame included).
pub async fn fit_viewport(client: &Client, width: u32, height: u32) -> Result<(u32, u32)> {
    let inner = || async {
        let v = eval(client, "return [window.innerWidth, window.innerHeight];").await?;
        let n = |i: usize| v[i].as_u64().and_then(|n| u32::try_from(n).ok());
        match (n(0), n(1)) {
            (Some(w), Some(h)) => Ok((w, h)),
            _ => Err(E2eError::Check(format!("window size unreadable: {v}"))),
        }
    };
    let (iw, ih) = inner().await?;
    if (iw, ih) != (width, height) {
        let (ow, oh) = client.get_window_size().await?;
        let grow = |outer: u64, want: u32, have: u32| {
            u32::try_from(outer).unwrap_or(want) + want.saturating_sub(have)
                - have.saturating_sub(want)
        };
        client
            .set_window_size(grow(ow, width, iw), grow(oh, height, ih))
            .await?;
    }
    inner().await
}

/// Evaluates `script` (a function body: `return …`) in the page.
pub async fn eval(client: &Client, script: &str) -> Result<Value> {
    Ok(client.execute(script, vec![]).await?)
}

/// Polls `script` every `every` until `done` accepts its value (returned),
/// or fails after `within` showing the last value.
pub async fn poll(
    client: &Client,
    what: &str,
    script: &str,
    within: Duration,
    every: Duration,
    mut done: impl FnMut(&Value) -> bool,
) -> Result<Value> {
    let start = Instant::now();
    loop {
        let value = eval(client, script).await?;
        if done(&value) {
            return Ok(value);
        }
        if start.elapsed() > within {
            return Err(E2eError::Timeout {
                what: what.to_string(),
                seconds: within.as_secs(),
                last: value.to_string(),
            });
        }
        tokio::time::sleep(every).await;
    }
}

fn mouse() -> MouseActions {
    MouseActions::new("mouse".to_string())
}

fn move_to(x: f64, y: f64, ms: u64) -> PointerAction {
    PointerAction::MoveTo {
        duration: Some(Duration::from_millis(ms)),
        x: x.round(),
        y: y.round(),
    }
}

/// A left click at (`x`, `y`) in CSS pixels from the viewport's top-left,
/// the button held for a few frames so a frame loop sees it.
pub async fn click(client: &Client, x: f64, y: f64) -> Result<()> {
    let actions = mouse()
        .then(move_to(x, y, 50))
        .pause(Duration::from_millis(50))
        .then(PointerAction::Down {
            button: MOUSE_BUTTON_LEFT,
        })
        .pause(Duration::from_millis(80))
        .then(PointerAction::Up {
            button: MOUSE_BUTTON_LEFT,
        });
    client.perform_actions(actions).await?;
    Ok(client.release_actions().await?)
}

/// The pointer pressed at `from` and moved to `to` in `steps` small moves
/// (a frame or two each), still held.
fn pressed_path(from: (f64, f64), to: (f64, f64), steps: u32) -> MouseActions {
    let mut actions = mouse()
        .then(move_to(from.0, from.1, 50))
        .pause(Duration::from_millis(50))
        .then(PointerAction::Down {
            button: MOUSE_BUTTON_LEFT,
        })
        .pause(Duration::from_millis(80));
    let steps = steps.max(1);
    for i in 1..=steps {
        let t = f64::from(i) / f64::from(steps);
        actions = actions.then(move_to(
            from.0 + (to.0 - from.0) * t,
            from.1 + (to.1 - from.1) * t,
            30,
        ));
    }
    actions
}

/// Presses at `from` and moves to `to` in `steps` small moves, holding the
/// button (finish with [`release`]), so the page can be read mid-drag.
pub async fn press_and_move(
    client: &Client,
    from: (f64, f64),
    to: (f64, f64),
    steps: u32,
) -> Result<()> {
    let actions = pressed_path(from, to, steps).pause(Duration::from_millis(150));
    Ok(client.perform_actions(actions).await?)
}

/// Lets go of the button [`press_and_move`] holds.
pub async fn release(client: &Client) -> Result<()> {
    let actions = mouse()
        .then(PointerAction::Up {
            button: MOUSE_BUTTON_LEFT,
        })
        .pause(Duration::from_millis(80));
    client.perform_actions(actions).await?;
    Ok(client.release_actions().await?)
}

/// Presses at `from`, moves to `to` in `steps` small moves (a frame or two
/// each), and releases there.
pub async fn drag(client: &Client, from: (f64, f64), to: (f64, f64), steps: u32) -> Result<()> {
    let actions = pressed_path(from, to, steps)
        .pause(Duration::from_millis(120))
        .then(PointerAction::Up {
            button: MOUSE_BUTTON_LEFT,
        });
    client.perform_actions(actions).await?;
    Ok(client.release_actions().await?)
}

/// Dispatches one touch event (`touchstart`, `touchmove` or `touchend`)
/// of one finger at (`x`, `y`) CSS pixels on the game's canvas, as a
/// phone's browser does.
async fn touch(client: &Client, kind: &str, x: f64, y: f64) -> Result<()> {
    const SCRIPT: &str = "const [kind, x, y] = arguments;
        const c = document.querySelector('#glcanvas');
        const t = new Touch({identifier: 1, target: c, clientX: x, clientY: y,
                             pageX: x, pageY: y, screenX: x, screenY: y});
        const down = kind === 'touchend' ? [] : [t];
        c.dispatchEvent(new TouchEvent(kind, {touches: down, targetTouches: down,
            changedTouches: [t], bubbles: true, cancelable: true}));
        return true;";
    client
        .execute(SCRIPT, vec![json!(kind), json!(x), json!(y)])
        .await?;
    Ok(())
}

/// A finger's tap at (`x`, `y`): put down, held a few frames, lifted.
pub async fn tap(client: &Client, x: f64, y: f64) -> Result<()> {
    touch(client, "touchstart", x, y).await?;
    tokio::time::sleep(Duration::from_millis(120)).await;
    touch(client, "touchend", x, y).await
}

/// A finger put down at `from`, slid to `to` in `steps` moves (a frame or
/// two each) and lifted there: touch events on the canvas.
pub async fn touch_drag(
    client: &Client,
    from: (f64, f64),
    to: (f64, f64),
    steps: u32,
) -> Result<()> {
    let frame = Duration::from_millis(40);
    touch(client, "touchstart", from.0, from.1).await?;
    tokio::time::sleep(frame * 2).await;
    let steps = steps.max(1);
    let mut at = from;
    for i in 1..=steps {
        let t = f64::from(i) / f64::from(steps);
        at = (from.0 + (to.0 - from.0) * t, from.1 + (to.1 - from.1) * t);
        touch(client, "touchmove", at.0, at.1).await?;
        tokio::time::sleep(frame).await;
    }
    tokio::time::sleep(frame * 3).await;
    touch(client, "touchend", at.0, at.1).await
}

/// Pastes `text` into the page as the browser's paste event carries it.
pub async fn paste(client: &Client, text: &str) -> Result<()> {
    const SCRIPT: &str = "const data = new DataTransfer();
        data.setData('text', arguments[0]);
        window.dispatchEvent(new ClipboardEvent('paste', {clipboardData: data}));
        return true;";
    client.execute(SCRIPT, vec![json!(text)]).await?;
    Ok(())
}

/// Takes a screenshot, writes it to `path`, returns the PNG.
pub async fn screenshot(client: &Client, path: &Path) -> Result<Vec<u8>> {
    let png = client.screenshot().await?;
    std::fs::write(path, &png).map_err(|source| E2eError::Io {
        what: format!("writing {}", path.display()),
        source,
    })?;
    Ok(png)
}

/// The script that reads the app's state (`window.chapaev_state`, refreshed
/// every frame).
pub const APP_STATE: &str = "return window.chapaev_state || null;";

/// Polls the app's state every 50 ms until `done` holds (at most `secs`
/// seconds).
pub async fn state_until(
    client: &Client,
    what: &str,
    secs: u64,
    done: impl FnMut(&Value) -> bool,
) -> Result<Value> {
    poll(
        client,
        what,
        APP_STATE,
        Duration::from_secs(secs),
        Duration::from_millis(50),
        done,
    )
    .await
}

/// Waits for the app's button `name` to be drawn, clicks its centre, and
/// waits for a frame drawn after the click.
pub async fn click_button(client: &Client, name: &str) -> Result<()> {
    let state = state_until(client, &format!("the {name} button"), 15, |s| {
        s["buttons"][name].is_array()
    })
    .await?;
    let (x, y) = centre(&state["buttons"][name])?;
    click_seen(client, x, y).await
}

/// Clicks at (`x`, `y`) and waits for a frame drawn after the click, so
/// the next step reads a page that has seen it. (The page draws only while
/// something changes: without this wait, a second click could reach it in
/// the same frame as the first.)
pub async fn click_seen(client: &Client, x: f64, y: f64) -> Result<()> {
    click(client, x, y).await?;
    let after = eval(client, APP_STATE).await?["frame"]
        .as_u64()
        .unwrap_or(0);
    state_until(client, "a frame after the click", 10, |s| {
        s["frame"].as_u64().is_some_and(|f| f > after)
    })
    .await?;
    Ok(())
}

/// The centre of an `[x, y, w, h]` rectangle from the app's state.
pub fn centre(rect: &Value) -> Result<(f64, f64)> {
    match (
        rect[0].as_f64(),
        rect[1].as_f64(),
        rect[2].as_f64(),
        rect[3].as_f64(),
    ) {
        (Some(x), Some(y), Some(w), Some(h)) => Ok((x + w / 2.0, y + h / 2.0)),
        _ => Err(E2eError::Check(format!("not a rectangle: {rect}"))),
    }
}

/// In a match (`play`: the app's state), pulls the piece of ours nearest
/// the middle of the window straight down and lets go.
pub async fn shoot(client: &Client, play: &Value) -> Result<()> {
    let size = eval(client, "return [window.innerWidth, window.innerHeight];").await?;
    let (Some(width), Some(height)) = (size[0].as_f64(), size[1].as_f64()) else {
        return Err(E2eError::Check(format!("not a window size: {size}")));
    };
    let piece = play["pieces"]
        .as_array()
        .into_iter()
        .flatten()
        .filter(|p| p["mine"] == true)
        .filter_map(|p| Some((p["x"].as_f64()?, p["y"].as_f64()?)))
        .filter(|&(_, y)| y + 40.0 < height - 2.0)
        .min_by(|a, b| {
            let off = |p: &(f64, f64)| (p.0 - width / 2.0).abs();
            off(a).total_cmp(&off(b))
        })
        .ok_or_else(|| E2eError::Check(format!("no piece of ours: {}", play["pieces"])))?;
    let to = (piece.0, (piece.1 + 80.0).min(height - 2.0));
    drag(client, piece, to, 8).await
}
