//! The leaderboard: the people's or the bots' rated accounts, best first
//! (`GET /api/leaderboard`), in two tabs; each name opens the account's
//! page. As many rows as the window holds, each a finger-sized button.

use crate::account;
use crate::api::{Api, Pending, Profile};
use crate::i18n::t;
use crate::route::Route;
use crate::screen::Screen;
use crate::ui::{self, colors, Ui};
use macroquad::prelude::*;

/// How many accounts to ask for.
const LIMIT: usize = 50;

pub struct Leaderboard {
    bots: bool,
    rows: Vec<Profile>,
    pending: Option<Pending<Vec<Profile>>>,
    /// The list has come (an empty one included).
    loaded: bool,
    message: Option<String>,
}

impl Leaderboard {
    pub fn new(api: &Api, bots: bool) -> Leaderboard {
        Leaderboard {
            bots,
            rows: Vec::new(),
            pending: Some(api.leaderboard(bots, LIMIT)),
            loaded: false,
            message: None,
        }
    }

    fn poll(&mut self) {
        if let Some(p) = &mut self.pending {
            if let Some(r) = p.poll() {
                self.pending = None;
                self.loaded = true;
                match r {
                    Ok(rows) => self.rows = rows,
                    Err(e) => self.message = Some(e),
                }
            }
        }
    }
}

impl Screen for Leaderboard {
    fn frame(&mut self, ui: &mut Ui, _dt: f64) -> Option<Route> {
        self.poll();
        let mut go = None;
        let (w, h) = crate::scale::size().into();
        let pad = if w < 600.0 { 12.0 } else { 20.0 };
        let col = (w - 2.0 * pad).min(720.0);
        let x0 = (w - col) / 2.0;
        let gap = 8.0;
        let mut y = 12.0;
        if ui.button("lobby", &t!("lobby"), Rect::new(x0, y, 96.0, ui::TOUCH)) {
            go = Some(Route::Lobby);
        }
        // The title between the lobby's button and the language switch,
        // smaller (down to 12 units) where that is narrow.
        let lang_w = if w < 600.0 { 48.0 } else { 110.0 };
        let room = x0 + col - lang_w - 8.0 - (x0 + 108.0);
        ui::text_in(
            &t!("leaderboard"),
            x0 + 108.0,
            y + 9.0,
            24.0,
            room,
            colors::ACCENT,
        );
        crate::i18n::switch_top(ui, x0 + col, y);
        y += ui::TOUCH + 12.0;
        let tab_w = (col - gap) / 2.0;
        for (k, (name, label, bots)) in [
            ("tab-people", t!("leaderboard-people"), false),
            ("tab-bots", t!("leaderboard-bots"), true),
        ]
        .into_iter()
        .enumerate()
        {
            let r = Rect::new(x0 + k as f32 * (tab_w + gap), y, tab_w, ui::TOUCH);
            if ui.button_styled(name, &label, r, true, self.bots == bots) && self.bots != bots {
                go = Some(Route::Leaderboard { bots });
            }
        }
        y += ui::TOUCH + 12.0;
        let area = Rect::new(x0, y, col, h - y - 12.0);
        ui::panel(area);
        let _inside = ui::bounds(area);
        let mut ry = area.y + 10.0;
        if self.rows.is_empty() {
            let text = if let Some(m) = &self.message {
                m.clone()
            } else if self.loaded {
                t!("leaderboard-empty")
            } else {
                t!("loading")
            };
            // In as many lines as the list's width takes.
            for (i, line) in crate::help::wrap(&text, 16.0, area.w - 20.0)
                .iter()
                .enumerate()
            {
                let y = ry + 4.0 + i as f32 * 20.0;
                ui::text(line, area.x + 10.0, y, 16.0, colors::MUTED);
            }
        }
        let name_w = (area.w * 0.5).min(260.0);
        for (k, p) in self.rows.iter().enumerate() {
            if ry + ui::TOUCH > area.y + area.h - 6.0 {
                break;
            }
            let rank = format!("{}.", k + 1);
            ui::text(&rank, area.x + 10.0, ry + 12.0, 16.0, colors::MUTED);
            let r = Rect::new(area.x + 48.0, ry, name_w, ui::TOUCH);
            if ui.button(&format!("player-{k}"), &p.name, r) {
                go = Some(Route::Account {
                    name: p.name.clone(),
                });
            }
            let facts = format!(
                "{} · {}",
                account::profile_rating(p),
                t!("games-count", count = p.games)
            );
            let tx = r.x + r.w + 12.0;
            let room = area.x + area.w - tx - 8.0;
            if ui::text_width(&facts, 14.0) <= room {
                ui::text_in(&facts, tx, ry + 12.0, 16.0, room, colors::TEXT);
            } else {
                // A narrow list: the rating above the games.
                let rating = account::profile_rating(p);
                let games = t!("games-count", count = p.games);
                ui::text_in(&rating, tx, ry + 3.0, 14.0, room, colors::TEXT);
                ui::text_in(&games, tx, ry + 23.0, 14.0, room, colors::MUTED);
            }
            ry += ui::TOUCH + 6.0;
        }
        go
    }

    fn name(&self) -> &'static str {
        "leaderboard"
    }

    fn report(&self) -> serde_json::Map<String, serde_json::Value> {
        let mut m = serde_json::Map::new();
        m.insert("bots".into(), self.bots.into());
        m.insert("loaded".into(), self.loaded.into());
        m.insert("rows".into(), self.rows.len().into());
        m
    }
}
