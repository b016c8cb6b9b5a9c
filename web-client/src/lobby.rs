//! The lobby: your name (or, signed in, your account with its rating and
//! whether new matches are rated), a quick match against a stranger, a
//! match against the computer (easy,
//! medium, hard or adaptive) or a friend (a link to send), joining by id, the way to
//! the leaderboard, and the server's open, live and finished matches — with
//! the seats' ratings and rated matches marked — to join, watch or replay.
//! A match this server cannot play (another physics version) offers no
//! Join or Watch. The lists refresh every few seconds.
//!
//! The computer can also be played offline, in the page
//! ([`crate::local_match`]): by choice ("Offline vs computer" and a level),
//! and by itself whenever the server is out of reach — the lists got no
//! answer (the page was opened offline, or the server is down), or the
//! match against the computer could not be created for that reason.
//!
//! This module owns the screen: it starts the requests and feeds their
//! answers to the [`state`] (the lists, the account, the message and the
//! rest the lobby keeps), keeps the browser's storage, and draws the
//! controls and the lists where [`layout`] puts them.

mod layout;
pub mod state;

use crate::account;
use crate::api::{token_key, Api, Opponent, Pending, Profile, SeatGrant, Summary};
use crate::i18n::{self, t};
use crate::route::Route;
use crate::screen::Screen;
use crate::ui::{self, colors, Ui};
use crate::{draw, platform};
use bots::Level;
use game::Side;
use macroquad::prelude::*;
pub use state::{clean_name, describe};
use state::{offered, LobbyState, MatchList};

const NAME_KEY: &str = "chapaev.name";
const RATED_KEY: &str = "chapaev.rated";

pub struct Lobby {
    api: Api,
    /// Everything but the requests in flight.
    s: LobbyState,
    creating: Option<Pending<SeatGrant>>,
    /// The lists' requests in flight, one per list.
    listing: [Option<Pending<Vec<Summary>>>; 3],
    fetching_profile: Option<Pending<Profile>>,
    /// A question over the lobby, if one is open.
    dialog: Option<Dialog>,
    /// The level of the match against the computer being created (played
    /// offline instead should the server be out of reach).
    creating_level: Option<Level>,
}

/// The questions the lobby asks over itself.
#[derive(Clone, Debug, PartialEq)]
enum Dialog {
    /// The player left this match while it was on: offer the way back.
    Return(String),
    /// "Sign out" was pressed: the key is the only way into the account.
    SignOut,
    /// "Offline vs computer" was pressed: which level.
    Offline,
}

impl Lobby {
    pub fn new(api: Api) -> Lobby {
        let account = account::signed_in();
        let fetching_profile = account.as_ref().map(|a| api.me(&a.key));
        let rated = platform::storage_get(RATED_KEY).as_deref() != Some("off");
        let name = platform::storage_get(NAME_KEY).unwrap_or_default();
        Lobby {
            s: LobbyState::new(name, account, rated),
            fetching_profile,
            api,
            creating: None,
            listing: [None, None, None],
            creating_level: None,
            dialog: platform::storage_get(crate::play::LEFT_KEY)
                .filter(|id| crate::route::valid_id(id))
                .map(Dialog::Return),
        }
    }

    /// A match against `level`: on the server, or here when the server is
    /// out of reach.
    fn computer(&mut self, level: Level) -> Option<Route> {
        if self.s.offline {
            platform::storage_set(NAME_KEY, self.s.name.trim());
            return Some(Route::Offline { level });
        }
        if self.creating.is_none() {
            self.creating_level = Some(level);
        }
        self.create(Opponent::Bot(level.as_str()));
        None
    }

    fn create(&mut self, opponent: Opponent) {
        if self.creating.is_none() {
            platform::storage_set(NAME_KEY, self.s.name.trim());
            let rated = self.s.rated_request();
            let name = self.s.player_name();
            self.creating = Some(self.api.create(&name, opponent, rated));
            self.s.creating();
        }
    }

    fn poll(&mut self) -> Option<Route> {
        if let Some(p) = &mut self.fetching_profile {
            if let Some(r) = p.poll() {
                let refused = p.status() == Some(401);
                self.fetching_profile = None;
                if self.s.profile_answered(r, refused) {
                    // The key proves nothing any more: forget it.
                    account::sign_out();
                    self.api.key = None;
                }
            }
        }
        if self.s.refresh_due() {
            for (l, pending) in self.s.lists.iter().zip(&mut self.listing) {
                if pending.is_none() {
                    *pending = Some(self.api.list(l.status, 8));
                }
            }
        }
        for (i, pending) in self.listing.iter_mut().enumerate() {
            if let Some(p) = pending {
                if let Some(r) = p.poll() {
                    let status = p.status();
                    *pending = None;
                    self.s.listed(i, r);
                    self.s.heard(status);
                }
            }
        }
        let p = self.creating.as_mut()?;
        let r = p.poll()?;
        let status = p.status();
        self.creating = None;
        let level = self.creating_level.take();
        if r.is_err() && self.s.heard(status) {
            // No server to play the computer on: play it here.
            if let Some(level) = level {
                return Some(Route::Offline { level });
            }
        }
        let grant = self.s.created(r)?;
        Some(seated(&grant))
    }
}

/// Keeps the seat's token (so a reload keeps the seat) and leads to its match.
pub fn seated(grant: &SeatGrant) -> Route {
    platform::storage_set(&token_key(&grant.match_id), &grant.token);
    Route::Play {
        match_id: grant.match_id.clone(),
    }
}

/// The name this browser last played under.
pub fn saved_name() -> String {
    clean_name(&platform::storage_get(NAME_KEY).unwrap_or_default())
}

impl Screen for Lobby {
    fn frame(&mut self, ui: &mut Ui, dt: f64) -> Option<Route> {
        self.s.tick(dt);
        if let Some(d) = self.dialog.clone() {
            ui.without_input(|ui| self.lists_and_controls(ui));
            return self.dialog(ui, &d);
        }
        if self.s.help {
            ui.without_input(|ui| self.lists_and_controls(ui));
            self.s.help = !crate::help::show(ui);
            return None;
        }
        self.lists_and_controls(ui)
    }

    fn name(&self) -> &'static str {
        "lobby"
    }

    fn report(&self) -> serde_json::Map<String, serde_json::Value> {
        let mut m = serde_json::Map::new();
        m.insert(
            "signed_in".into(),
            self.s.account.as_ref().map(|a| a.name.clone()).into(),
        );
        m.insert(
            "rating".into(),
            self.s.profile.as_ref().map(account::profile_rating).into(),
        );
        m.insert("rated".into(), self.s.rated_request().into());
        m.insert("name".into(), self.s.name.clone().into());
        m.insert("offline".into(), self.s.offline.into());
        m.insert("message".into(), self.s.message.clone().into());
        m.insert(
            "dialog".into(),
            self.dialog.as_ref().map(|d| format!("{d:?}")).into(),
        );
        let listed: Vec<serde_json::Value> = self
            .s
            .lists
            .iter()
            .flat_map(|l| &l.items)
            .map(|s| {
                serde_json::json!({"match_id": s.match_id, "rated": s.rated,
                    "playable": s.playable, "names": describe(s).0})
            })
            .collect();
        m.insert("listed".into(), listed.into());
        m
    }
}

impl Lobby {
    /// The row under the title: the name to play under and "Sign in", or
    /// the signed-in account (its page), "Rated" and "Sign out".
    fn account_row(
        &mut self,
        ui: &mut Ui,
        x0: f32,
        y: f32,
        col: f32,
        label_w: f32,
        narrow: bool,
    ) -> Option<Route> {
        let row = ui::TOUCH;
        let gap = 8.0;
        let Some(a) = self.s.account.clone() else {
            ui::text_in(
                &t!("lobby-your-name"),
                x0,
                y + 12.0,
                17.0,
                label_w - 6.0,
                colors::TEXT,
            );
            let sign_w = if narrow { 84.0 } else { 110.0 };
            let field_w = (col - label_w - gap - sign_w).min(260.0);
            let field = Rect::new(x0 + label_w, y, field_w, row);
            ui.text_field(
                "name",
                &mut self.s.name,
                field,
                &t!("player-default-name"),
                40,
            );
            let b = Rect::new(field.x + field.w + gap, y, sign_w, row);
            return ui
                .button("sign-in", &t!("sign-in"), b)
                .then_some(Route::SignIn);
        };
        let rating = self
            .s
            .profile
            .as_ref()
            .map_or_else(|| "—".to_string(), account::profile_rating);
        let (x, w) = if narrow {
            (x0, col)
        } else {
            ui::text_in(
                &t!("lobby-signed-in"),
                x0,
                y + 12.0,
                17.0,
                label_w - 6.0,
                colors::TEXT,
            );
            (x0 + label_w, (col - label_w).min(560.0))
        };
        let name_w = (w - 2.0 * gap) * 0.46;
        let other_w = (w - 2.0 * gap - name_w) / 2.0;
        let mut go = None;
        let label = format!("{} · {rating}", a.name);
        if ui.button("account", &label, Rect::new(x, y, name_w, row)) {
            go = Some(Route::SignIn);
        }
        let rated = Rect::new(x + name_w + gap, y, other_w, row);
        let label = if self.s.rated {
            t!("lobby-rated-on")
        } else {
            t!("lobby-rated-off")
        };
        if ui.button_styled("rated", &label, rated, true, self.s.rated) {
            let remembered = self.s.toggle_rated();
            platform::storage_set(RATED_KEY, remembered);
        }
        let out = Rect::new(rated.x + other_w + gap, y, other_w, row);
        if ui.button("sign-out", &t!("sign-out"), out) {
            self.dialog = Some(Dialog::SignOut);
        }
        go
    }

    /// The question `d` over the lobby, and what its buttons do.
    fn dialog(&mut self, ui: &mut Ui, d: &Dialog) -> Option<Route> {
        use crate::play::layout::{dialog, dialog_buttons};
        let (title, body, lines) = match d {
            Dialog::Return(_) => (t!("lobby-return-title"), t!("lobby-return-body"), 2),
            Dialog::SignOut => (t!("lobby-sign-out-title"), t!("lobby-sign-out-body"), 3),
            Dialog::Offline => (t!("lobby-offline-title"), t!("lobby-offline-body"), 3),
        };
        let h = match d {
            Dialog::Offline => 320.0,
            _ if lines == 2 => 190.0,
            _ => 268.0,
        };
        let box_ = dialog(crate::scale::size(), h);
        ui::panel(box_);
        let (x, w) = (box_.x + 16.0, box_.w - 32.0);
        ui::text(
            &ui::fit(&title, 21.0, w),
            x,
            box_.y + 14.0,
            21.0,
            colors::ACCENT,
        );
        let lines = crate::help::wrap_lines(&body, 16.0, w, lines);
        for (i, l) in lines.iter().enumerate() {
            let y = box_.y + 50.0 + i as f32 * 22.0;
            ui::text(&ui::fit(l, 16.0, w), x, y, 16.0, colors::TEXT);
        }
        match d {
            Dialog::Return(match_id) => {
                platform::storage_set(crate::play::LEFT_KEY, "");
                let (back, stay) = dialog_buttons(box_, h - 64.0);
                if ui.button("return-match", &t!("lobby-return-yes"), back) {
                    self.dialog = None;
                    return Some(Route::Play {
                        match_id: match_id.clone(),
                    });
                }
                if ui.button("return-no", &t!("lobby-return-no"), stay) {
                    self.dialog = None;
                }
            }
            Dialog::Offline => {
                let levels = [
                    ("offline-easy", t!("lobby-computer-easy"), Level::Easy),
                    ("offline-medium", t!("lobby-computer-medium"), Level::Medium),
                    ("offline-hard", t!("lobby-computer-hard"), Level::Hard),
                    (
                        "offline-adaptive",
                        t!("lobby-computer-adaptive"),
                        Level::Adaptive,
                    ),
                ];
                let rows = [
                    dialog_buttons(box_, h - 180.0),
                    dialog_buttons(box_, h - 124.0),
                ];
                let rects = [rows[0].0, rows[0].1, rows[1].0, rows[1].1];
                for ((name, label, level), r) in levels.into_iter().zip(rects) {
                    if ui.button(name, &label, r) {
                        self.dialog = None;
                        platform::storage_set(NAME_KEY, self.s.name.trim());
                        return Some(Route::Offline { level });
                    }
                }
                let (_, cancel) = dialog_buttons(box_, h - 64.0);
                if ui.button("offline-cancel", &t!("cancel"), cancel) {
                    self.dialog = None;
                }
            }
            Dialog::SignOut => {
                let copy = Rect::new(x, box_.y + h - 116.0, w, ui::TOUCH);
                if ui.button("sign-out-copy", &t!("copy-key"), copy) {
                    if let Some(a) = account::signed_in() {
                        platform::copy_text(&a.key);
                        self.s.message = Some(t!("key-copied"));
                    }
                }
                let (cancel, out) = dialog_buttons(box_, h - 64.0);
                if ui.button("sign-out-no", &t!("cancel"), cancel) {
                    self.dialog = None;
                }
                if ui.button("sign-out-yes", &t!("sign-out"), out) {
                    self.dialog = None;
                    account::sign_out();
                    self.s.signed_out();
                    self.api.key = None;
                }
            }
        }
        None
    }

    /// The lobby itself (drawn under the rules when they are open).
    fn lists_and_controls(&mut self, ui: &mut Ui) -> Option<Route> {
        let mut go = self.poll();
        let (w, h) = crate::scale::size().into();
        let l = layout::layout(w, h, self.s.message.is_some());
        let (x0, col, narrow) = (l.x0, l.col, l.narrow);
        let gap = layout::GAP;
        let y = l.title_y;
        // The title, with two checkers for a logo, and the rules beside it.
        let help = l.help;
        let logo = l.logo;
        draw::checker(
            vec2(x0 + logo + 2.0, y + logo + 2.0),
            logo,
            Side::White,
            1.0,
        );
        draw::checker(
            vec2(x0 + logo * 2.6, y + logo * 1.5),
            logo,
            Side::Black,
            1.0,
        );
        let tx = x0 + logo * 4.2;
        let room = l.lang.x - tx - gap;
        let name = t!("app-title");
        let mut title = if narrow { 26.0 } else { 40.0 };
        while title > 16.0 && ui::text_width(&name, title) > room {
            title -= 1.0;
        }
        ui::text(&name, tx, y, title, colors::ACCENT);
        // The tagline: one line, or two on a phone, under the title.
        // Smaller (down to 12 units) rather than cut, and left out where
        // even that takes more lines.
        let lines = match (l.tagline, narrow) {
            (false, _) => 0,
            (true, true) => 2,
            (true, false) => 1,
        };
        let words = if narrow {
            t!("lobby-tagline-short")
        } else {
            t!("lobby-tagline")
        };
        let mut size: f32 = if narrow { 13.0 } else { 18.0 };
        while size > ui::MIN_TEXT && crate::help::wrap(&words, size, room).len() > lines {
            size -= 1.0;
        }
        let tagline = crate::help::wrap(&words, size, room);
        let tagline = if tagline.len() > lines {
            Vec::new()
        } else {
            tagline
        };
        for (i, line) in tagline.iter().enumerate() {
            let ly = y + title + 4.0 + i as f32 * (size + 2.0);
            ui::text(line, tx + 2.0, ly, size, colors::MUTED);
        }
        let rules = if narrow {
            t!("rules-short")
        } else {
            t!("how-to-play")
        };
        if ui.button("help", &rules, help) {
            self.s.help = true;
        }
        i18n::switch(ui, l.lang, narrow);
        let label_w = l.label_w;
        if let Some(r) =
            self.account_row(ui, l.account_x, l.account_y, l.account_w, label_w, narrow)
        {
            go = Some(r);
        }
        // The matches to start: a grid of four columns, or two on a phone.
        let choices: [(&str, String); layout::CHOICES] = [
            ("quick-match", t!("lobby-quick-match")),
            ("vs-computer-easy", t!("lobby-computer-easy")),
            ("vs-computer-medium", t!("lobby-computer-medium")),
            ("vs-computer-hard", t!("lobby-computer-hard")),
            ("vs-computer-adaptive", t!("lobby-computer-adaptive")),
            ("vs-person", t!("lobby-friend")),
            ("sandbox", t!("lobby-sandbox")),
            ("leaderboard", t!("leaderboard")),
            ("offline", t!("lobby-offline")),
        ];
        for ((name, label), rect) in choices.iter().zip(l.choices) {
            if ui.button(name, label, rect) {
                match *name {
                    "quick-match" => {
                        go = Some(Route::QuickMatch {
                            rated: self.s.rated_request(),
                        })
                    }
                    "vs-computer-easy" => go = self.computer(Level::Easy),
                    "vs-computer-medium" => go = self.computer(Level::Medium),
                    "vs-computer-hard" => go = self.computer(Level::Hard),
                    "vs-computer-adaptive" => go = self.computer(Level::Adaptive),
                    "vs-person" => self.create(Opponent::Person),
                    "sandbox" => go = Some(Route::Sandbox),
                    "offline" => self.dialog = Some(Dialog::Offline),
                    _ => go = Some(Route::Leaderboard { bots: false }),
                }
            }
        }
        let field = l.join_field;
        ui::text_in(
            &t!("lobby-join-by-id"),
            x0,
            field.y + 12.0,
            17.0,
            label_w - 6.0,
            colors::TEXT,
        );
        let entered = ui.text_field(
            "join-id-field",
            &mut self.s.join_id,
            field,
            &t!("lobby-match-id"),
            64,
        );
        let target = self.s.join_target();
        let pressed = ui.button_styled("join-id", &t!("join"), l.join, target.is_some(), false);
        if let Some(id) = target.filter(|_| pressed || entered) {
            go = Some(Route::Join { match_id: id });
        }
        if let Some(m) = &self.s.message {
            let (mx, my, mw) = l.message;
            let size = if narrow { 15.0 } else { 16.0 };
            ui::text(&ui::fit(m, size, mw), mx, my, size, colors::MUTED);
        }
        let footer = if narrow {
            t!("lobby-footer-short")
        } else {
            t!("lobby-footer")
        };
        if let Some(footer_y) = l.footer_y {
            ui::text(
                &ui::fit(&footer, 14.0, col),
                x0,
                footer_y,
                14.0,
                colors::MUTED,
            );
        }
        for (list_, area) in self.s.lists.iter().zip(l.lists) {
            if let Some(r) = list(ui, list_, area) {
                go = Some(r);
            }
        }
        if go.is_some() {
            platform::storage_set(NAME_KEY, self.s.name.trim());
        }
        go
    }
}

/// One list of matches in `area`, as many rows as fit (each a
/// finger-sized button and two lines of description); where a click leads.
fn list(ui: &mut Ui, l: &MatchList, area: Rect) -> Option<Route> {
    let mut go = None;
    ui::panel(area);
    let _inside = ui::bounds(area);
    ui::text(
        &ui::fit(&i18n::text(l.title, &[]), 19.0, area.w - 20.0),
        area.x + 10.0,
        area.y + 8.0,
        19.0,
        colors::ACCENT,
    );
    let mut y = area.y + 34.0;
    if l.items.is_empty() {
        ui::text(&t!("lobby-none-yet"), area.x + 10.0, y, 16.0, colors::MUTED);
    }
    let button_w = 76.0;
    let text_w = area.w - button_w - 28.0;
    for (k, s) in l.items.iter().enumerate() {
        if y + ui::TOUCH > area.y + area.h - 4.0 {
            break;
        }
        let (names, facts) = describe(s);
        ui::text(
            &ui::fit(&names, 15.0, text_w),
            area.x + 10.0,
            y + 3.0,
            15.0,
            colors::TEXT,
        );
        ui::text(
            &ui::fit(&facts, 13.0, text_w),
            area.x + 10.0,
            y + 24.0,
            13.0,
            colors::MUTED,
        );
        let offered = offered(l.status, s);
        let name = format!("{}-{k}", l.status);
        let r = Rect::new(area.x + area.w - button_w - 8.0, y, button_w, ui::TOUCH);
        if offered && ui.button(&name, &i18n::text(l.action, &[]), r) {
            let match_id = s.match_id.clone();
            go = Some(match l.status {
                "open" => Route::Join { match_id },
                "live" => Route::Watch { match_id },
                _ => Route::Replay { match_id },
            });
        }
        y += ui::TOUCH + 6.0;
    }
    go
}
