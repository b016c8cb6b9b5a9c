//! Chapaev online in the browser: the lobby, live play against people or
//! the server's bots (rated for a signed-in player), the replay viewer,
//! the leaderboard and players' pages, matches against the computer played
//! offline in the page (no server needed), and the offline physics sandbox,
//! drawn with macroquad and compiled to `wasm32-unknown-unknown` (the
//! server embeds the build and serves it at `/`). The same code runs on
//! the desktop against `CHAPAEV_SERVER` (default `http://127.0.0.1:8080`).

mod account;
mod aim;
mod api;
mod channel;
mod chart;
mod clip;
mod connection;
mod draw;
mod help;
mod highlight;
mod i18n;
mod leaderboard;
mod lobby;
mod local_match;
mod pace;
mod platform;
mod play;
mod profile;
mod quick_match;
mod replay;
mod route;
mod sandbox;
mod scale;
mod screen;
mod sign_in;
mod story;
#[cfg(test)]
mod test_geometry;
mod timeline;
mod ui;
mod viewport;

use macroquad::prelude::*;
use route::Route;
use screen::Screen;
use ui::{Input, Ui};

fn conf() -> macroquad::conf::Conf {
    macroquad::conf::Conf {
        miniquad_conf: Conf {
            window_title: i18n::text("app-title", &[]),
            window_width: 1024,
            window_height: 720,
            high_dpi: true,
            sample_count: 4,
            platform: miniquad::conf::Platform {
                blocking_event_loop: pace::BLOCKING,
                ..Default::default()
            },
            ..Default::default()
        },
        // In the browser's waiting loop, every input wakes a frame at once
        // (macroquad's own triggers; the rest are in `js/chapaev.js`).
        update_on: Some(pace::wake_on_input()),
        ..Default::default()
    }
}

/// Opens the screen for `route`.
fn open(route: &Route) -> Box<dyn Screen> {
    let signed_in = account::signed_in();
    let api = api::Api {
        origin: route::origin(&platform::location()),
        key: signed_in.as_ref().map(|a| a.key.clone()),
    };
    // A signed-in player plays under the account's name.
    let name = signed_in.map_or_else(lobby::saved_name, |a| a.name);
    match route {
        Route::Lobby => Box::new(lobby::Lobby::new(api)),
        Route::QuickMatch { rated } => Box::new(quick_match::QuickMatch::new(api, name, *rated)),
        Route::Play { match_id } => {
            Box::new(play::Play::new(api, match_id.clone(), name, false, false))
        }
        Route::Join { match_id } => {
            Box::new(play::Play::new(api, match_id.clone(), name, true, false))
        }
        Route::Watch { match_id } => {
            Box::new(play::Play::new(api, match_id.clone(), name, false, true))
        }
        Route::Replay { match_id } => Box::new(replay::Replay::new(api, match_id.clone())),
        Route::Sandbox => Box::new(sandbox::Sandbox::new()),
        Route::Offline { level } => Box::new(play::Play::offline(api, *level, name)),
        Route::SignIn => Box::new(sign_in::SignIn::new(api)),
        Route::Leaderboard { bots } => Box::new(leaderboard::Leaderboard::new(&api, *bots)),
        Route::Account { name } => Box::new(profile::Profile::new(&api, name.clone())),
    }
}

#[macroquad::main(conf)]
async fn main() {
    // The computer levels' deadlines read the page's clock (std's panics
    // in the browser).
    bots::clock::set_source(get_time);
    let mut route = Route::parse(&platform::location());
    let mut screen = open(&route);
    platform::set_hash(&route.hash());
    let mut ui = Ui::default();
    let mut ready = false;
    let mut pace = pace::Pace::default();
    // Time spent in our own frame code (update and draw calls), averaged.
    let mut work_ms = 0.0f64;
    // Frames drawn so far: the end-to-end test waits for one after its input.
    let mut frames: u64 = 0;
    loop {
        frames += 1;
        let started = get_time();
        clear_background(ui::colors::BACKGROUND);
        scale::begin_frame();
        ui.begin(Input::read());
        let dt = pace.step(get_frame_time() as f64);
        let next = screen.frame(&mut ui, dt);
        ui.end();
        let mut state = screen.report();
        state.insert("screen".into(), screen.name().into());
        state.insert("buttons".into(), ui.layout());
        state.insert("labels".into(), ui.labels());
        state.insert("cut".into(), ui.cut());
        state.insert("label_sizes".into(), ui.label_sizes());
        state.insert("cut_texts".into(), ui.cut_texts());
        state.insert("small_texts".into(), ui.small_texts());
        state.insert("hovered".into(), ui.hovered().into());
        state.insert("lang".into(), i18n::current().code().into());
        state
            .entry("animating")
            .or_insert_with(|| screen.animating().into());
        state.insert("fps".into(), get_fps().into());
        state.insert("work_ms".into(), work_ms.into());
        state.insert("frame".into(), frames.into());
        platform::report(&serde_json::Value::Object(state).to_string());
        let starting = !ready;
        if starting {
            platform::set_ready();
            ready = true;
        }
        // Follow the address bar (back button, edited links) and the screen's wishes.
        let from_address = Route::parse(&platform::location());
        let changed = next.is_some() || from_address != route;
        if let Some(r) = next {
            route = r;
            platform::set_hash(&route.hash());
            screen = open(&route);
        } else if from_address != route {
            route = from_address;
            screen = open(&route);
        }
        work_ms = 0.95 * work_ms + 0.05 * (get_time() - started) * 1000.0;
        pace.end_frame(get_time(), starting || changed || screen.animating());
        next_frame().await
    }
}
