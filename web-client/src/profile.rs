//! An account's page: its profile (rating, rated games, person or bot),
//! its rating over time as a small line chart (`.../history`) and its
//! matches (`.../matches`), each finished one with a Replay button. What
//! the server does not answer shows as "—".

use crate::account;
use crate::api::{Api, HistoryPoint, Pending, Profile as Account, Summary};
use crate::i18n::t;
use crate::route::Route;
use crate::screen::Screen;
use crate::ui::{self, colors, Ui};
use macroquad::prelude::*;

/// How many of the account's matches to list.
const MATCHES: usize = 20;

/// Something asked of the server: on its way, come, or not to be had.
enum Answer<T> {
    Waiting(Pending<T>),
    Got(T),
    Failed(String),
}

impl<T> Answer<T> {
    fn poll(&mut self) {
        if let Answer::Waiting(p) = self {
            if let Some(r) = p.poll() {
                *self = match r {
                    Ok(v) => Answer::Got(v),
                    Err(e) => Answer::Failed(e),
                };
            }
        }
    }

    fn got(&self) -> Option<&T> {
        match self {
            Answer::Got(v) => Some(v),
            _ => None,
        }
    }
}

pub struct Profile {
    name: String,
    account: Answer<Account>,
    history: Answer<Vec<HistoryPoint>>,
    matches: Answer<Vec<Summary>>,
}

impl Profile {
    pub fn new(api: &Api, name: String) -> Profile {
        Profile {
            account: Answer::Waiting(api.account(&name)),
            history: Answer::Waiting(api.history(&name)),
            matches: Answer::Waiting(api.account_matches(&name, MATCHES)),
            name,
        }
    }
}

impl Screen for Profile {
    fn frame(&mut self, ui: &mut Ui, _dt: f64) -> Option<Route> {
        self.account.poll();
        self.history.poll();
        self.matches.poll();
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
        if ui.button(
            "leaderboard",
            &t!("leaderboard"),
            Rect::new(x0 + 96.0 + gap, y, 140.0, ui::TOUCH),
        ) {
            go = Some(Route::Leaderboard {
                bots: self.account.got().is_some_and(|a| a.bot),
            });
        }
        crate::i18n::switch_top(ui, x0 + col, y);
        y += ui::TOUCH + 16.0;
        ui::text(&ui::fit(&self.name, 26.0, col), x0, y, 26.0, colors::ACCENT);
        y += 34.0;
        let facts = match &self.account {
            Answer::Got(a) => t!(
                "profile-facts",
                kind = if a.bot { "bot" } else { "person" },
                rating = account::profile_rating(a),
                deviation = a.deviation.round() as i64,
                games = a.games
            ),
            Answer::Waiting(_) => t!("loading"),
            Answer::Failed(e) => e.clone(),
        };
        ui::text(&ui::fit(&facts, 16.0, col), x0, y, 16.0, colors::TEXT);
        y += 30.0;
        ui::text(&t!("profile-rating-over-time"), x0, y, 17.0, colors::ACCENT);
        y += 24.0;
        let chart_h = if w < 600.0 { 150.0 } else { 180.0 };
        let chart = Rect::new(x0, y, col, chart_h);
        match &self.history {
            Answer::Got(points) => {
                let values: Vec<f64> = points.iter().map(|p| p.rating).collect();
                crate::chart::draw(&values, chart);
            }
            Answer::Waiting(_) | Answer::Failed(_) => {
                ui::panel(chart);
                ui::text("—", x0 + 12.0, y + chart_h / 2.0 - 8.0, 16.0, colors::MUTED);
            }
        }
        y += chart_h + 16.0;
        ui::text(&t!("profile-matches"), x0, y, 17.0, colors::ACCENT);
        y += 26.0;
        let area = Rect::new(x0, y, col, h - y - 12.0);
        ui::panel(area);
        let mut ry = area.y + 8.0;
        let button_w = 90.0;
        let text_w = area.w - button_w - 28.0;
        match &self.matches {
            Answer::Got(list) if !list.is_empty() => {
                for (k, s) in list.iter().enumerate() {
                    if ry + ui::TOUCH > area.y + area.h - 4.0 {
                        break;
                    }
                    let (names, facts) = crate::lobby::describe(s);
                    ui::text(
                        &ui::fit(&names, 15.0, text_w),
                        area.x + 10.0,
                        ry + 3.0,
                        15.0,
                        colors::TEXT,
                    );
                    ui::text(
                        &ui::fit(&facts, 13.0, text_w),
                        area.x + 10.0,
                        ry + 24.0,
                        13.0,
                        colors::MUTED,
                    );
                    if s.result.is_some() {
                        let r =
                            Rect::new(area.x + area.w - button_w - 8.0, ry, button_w, ui::TOUCH);
                        if ui.button(&format!("match-{k}"), &t!("replay"), r) {
                            go = Some(Route::Replay {
                                match_id: s.match_id.clone(),
                            });
                        }
                    }
                    ry += ui::TOUCH + 6.0;
                }
            }
            Answer::Got(_) => {
                ui::text(
                    &t!("profile-no-matches"),
                    area.x + 10.0,
                    ry + 4.0,
                    16.0,
                    colors::MUTED,
                );
            }
            Answer::Waiting(_) | Answer::Failed(_) => {
                ui::text("—", area.x + 10.0, ry + 4.0, 16.0, colors::MUTED);
            }
        }
        go
    }

    fn name(&self) -> &'static str {
        "profile"
    }

    fn report(&self) -> serde_json::Map<String, serde_json::Value> {
        let mut m = serde_json::Map::new();
        m.insert("account".into(), self.name.clone().into());
        m.insert(
            "loaded".into(),
            (!matches!(self.account, Answer::Waiting(_))
                && !matches!(self.history, Answer::Waiting(_))
                && !matches!(self.matches, Answer::Waiting(_)))
            .into(),
        );
        m.insert(
            "rating".into(),
            self.account.got().map(account::profile_rating).into(),
        );
        m.insert("history".into(), self.history.got().map(Vec::len).into());
        m.insert("matches".into(), self.matches.got().map(Vec::len).into());
        m
    }
}
