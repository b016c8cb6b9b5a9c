//! The lobby: your name (or, signed in, your account with its rating and
//! whether new matches are rated), a match against the computer (easy,
//! medium, hard or adaptive) or a friend (a link to send), joining by id, the way to
//! the leaderboard, and the server's open, live and finished matches — with
//! the seats' ratings and rated matches marked — to join, watch or replay.
//! A match this server cannot play (another physics version) offers no
//! Join or Watch. The lists refresh every few seconds.

mod layout;

use crate::account::{self, Account};
use crate::api::{token_key, Api, Opponent, Pending, Profile, SeatGrant, Summary};
use crate::route::Route;
use crate::screen::Screen;
use crate::ui::{self, colors, Ui};
use crate::{draw, platform};
use game::Side;
use macroquad::prelude::*;

/// Seconds between refreshes of the match lists.
const REFRESH_SECONDS: f64 = 5.0;
const NAME_KEY: &str = "chapaev.name";
const RATED_KEY: &str = "chapaev.rated";

/// One of the three lists.
struct List {
    status: &'static str,
    title: &'static str,
    action: &'static str,
    items: Vec<Summary>,
    pending: Option<Pending<Vec<Summary>>>,
}

pub struct Lobby {
    api: Api,
    name: String,
    join_id: String,
    creating: Option<Pending<SeatGrant>>,
    lists: [List; 3],
    refreshed: f64,
    now: f64,
    message: Option<String>,
    /// The rules are open over the lobby.
    help: bool,
    /// The account this browser is signed in to, its profile once fetched.
    account: Option<Account>,
    profile: Option<Profile>,
    fetching_profile: Option<Pending<Profile>>,
    /// New matches are rated (signed in only).
    rated: bool,
}

impl Lobby {
    pub fn new(api: Api) -> Lobby {
        let list = |status, title, action| List {
            status,
            title,
            action,
            items: Vec::new(),
            pending: None,
        };
        let account = account::signed_in();
        let fetching_profile = account.as_ref().map(|a| api.me(&a.key));
        Lobby {
            account,
            profile: None,
            fetching_profile,
            rated: platform::storage_get(RATED_KEY).as_deref() != Some("off"),
            api,
            name: platform::storage_get(NAME_KEY).unwrap_or_default(),
            join_id: String::new(),
            creating: None,
            lists: [
                list("open", "Waiting for an opponent", "Join"),
                list("live", "Being played", "Watch"),
                list("finished", "Finished", "Replay"),
            ],
            refreshed: f64::NEG_INFINITY,
            now: 0.0,
            message: None,
            help: false,
        }
    }

    /// The name to play under.
    pub fn player_name(&self) -> String {
        clean_name(&self.name)
    }

    fn create(&mut self, opponent: Opponent) {
        if self.creating.is_none() {
            platform::storage_set(NAME_KEY, self.name.trim());
            let rated = self.rated && self.account.is_some();
            self.creating = Some(self.api.create(&self.player_name(), opponent, rated));
            self.message = Some("creating the match...".into());
        }
    }

    fn poll(&mut self) -> Option<Route> {
        if let Some(p) = &mut self.fetching_profile {
            if let Some(r) = p.poll() {
                let refused = p.status() == Some(401);
                self.fetching_profile = None;
                match r {
                    Ok(profile) => self.profile = Some(profile),
                    // The key proves nothing any more: forget it.
                    Err(e) if refused => {
                        account::sign_out();
                        self.account = None;
                        self.api.key = None;
                        self.message = Some(format!("signed out: {e}"));
                    }
                    Err(e) => self.message = Some(e),
                }
            }
        }
        if self.now - self.refreshed > REFRESH_SECONDS {
            self.refreshed = self.now;
            for l in &mut self.lists {
                if l.pending.is_none() {
                    l.pending = Some(self.api.list(l.status, 8));
                }
            }
        }
        for l in &mut self.lists {
            if let Some(p) = &mut l.pending {
                if let Some(r) = p.poll() {
                    l.pending = None;
                    match r {
                        Ok(items) => l.items = items,
                        Err(e) => self.message = Some(e),
                    }
                }
            }
        }
        let p = self.creating.as_mut()?;
        let r = p.poll()?;
        self.creating = None;
        match r {
            Ok(grant) => {
                platform::storage_set(&token_key(&grant.match_id), &grant.token);
                Some(Route::Play {
                    match_id: grant.match_id,
                })
            }
            Err(e) => {
                self.message = Some(e);
                None
            }
        }
    }
}

/// A name the server accepts: trimmed, at most 40 characters, `Player` if empty.
pub fn clean_name(n: &str) -> String {
    let n: String = n
        .trim()
        .chars()
        .filter(|c| !c.is_control())
        .take(40)
        .collect();
    if n.is_empty() {
        "Player".to_string()
    } else {
        n
    }
}

/// The name this browser last played under.
pub fn saved_name() -> String {
    clean_name(&platform::storage_get(NAME_KEY).unwrap_or_default())
}

/// A match in two lines: who plays whom (with their ratings where the
/// seats have them), then how it stands.
pub fn describe(s: &Summary) -> (String, String) {
    let first = account::with_rating(s.first.as_deref().unwrap_or("?"), s.first_rating);
    let second = match (&s.second, &s.bot) {
        (_, Some(level)) => account::with_rating(&format!("computer ({level})"), s.second_rating),
        (Some(n), None) => account::with_rating(n, s.second_rating),
        (None, None) => "...".to_string(),
    };
    let mut facts = Vec::new();
    if s.rated {
        facts.push("rated".to_string());
    }
    if !s.playable {
        facts.push("not playable here".to_string());
    }
    match s.result {
        Some(r) => match r.winner() {
            Some(Side::White) => facts.push("White won".to_string()),
            Some(Side::Black) => facts.push("Black won".to_string()),
            None => facts.push("drawn".to_string()),
        },
        None if s.second.is_none() && s.bot.is_none() => facts.push("waiting".to_string()),
        None => {}
    }
    facts.push(crate::story::count(s.shots, "shot"));
    (format!("{first} vs {second}"), facts.join(" · "))
}

impl Screen for Lobby {
    fn frame(&mut self, ui: &mut Ui, dt: f64) -> Option<Route> {
        self.now += dt;
        if self.help {
            ui.without_input(|ui| self.lists_and_controls(ui));
            self.help = !crate::help::show(ui);
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
            self.account.as_ref().map(|a| a.name.clone()).into(),
        );
        m.insert(
            "rating".into(),
            self.profile.as_ref().map(account::profile_rating).into(),
        );
        m.insert(
            "rated".into(),
            (self.rated && self.account.is_some()).into(),
        );
        let listed: Vec<serde_json::Value> = self
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
        let Some(a) = self.account.clone() else {
            ui::text("Your name", x0, y + 12.0, 17.0, colors::TEXT);
            let sign_w = if narrow { 84.0 } else { 110.0 };
            let field_w = (col - label_w - gap - sign_w).min(260.0);
            let field = Rect::new(x0 + label_w, y, field_w, row);
            ui.text_field("name", &mut self.name, field, "Player", 40);
            let b = Rect::new(field.x + field.w + gap, y, sign_w, row);
            return ui.button("sign-in", "Sign in", b).then_some(Route::SignIn);
        };
        let rating = self
            .profile
            .as_ref()
            .map_or_else(|| "—".to_string(), account::profile_rating);
        let (x, w) = if narrow {
            (x0, col)
        } else {
            ui::text("Signed in", x0, y + 12.0, 17.0, colors::TEXT);
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
        let label = if self.rated {
            "Rated: on"
        } else {
            "Rated: off"
        };
        if ui.button_styled("rated", label, rated, true, self.rated) {
            self.rated = !self.rated;
            platform::storage_set(RATED_KEY, if self.rated { "on" } else { "off" });
        }
        let out = Rect::new(rated.x + other_w + gap, y, other_w, row);
        if ui.button("sign-out", "Sign out", out) {
            account::sign_out();
            self.account = None;
            self.profile = None;
            self.api.key = None;
        }
        go
    }

    /// The lobby itself (drawn under the rules when they are open).
    fn lists_and_controls(&mut self, ui: &mut Ui) -> Option<Route> {
        let mut go = self.poll();
        let (w, h) = crate::scale::size().into();
        let l = layout::layout(w, h, self.message.is_some());
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
        let room = help.x - tx - gap;
        let mut title = if narrow { 26.0 } else { 40.0 };
        while title > 16.0 && ui::text_width("Chapaev online", title) > room {
            title -= 1.0;
        }
        ui::text("Chapaev online", tx, y, title, colors::ACCENT);
        ui::text(
            &ui::fit(
                "flick your checkers, knock theirs off the board",
                if narrow { 13.0 } else { 18.0 },
                room,
            ),
            tx + 2.0,
            y + title + 4.0,
            if narrow { 13.0 } else { 18.0 },
            colors::MUTED,
        );
        let rules = if narrow { "Rules" } else { "How to play" };
        if ui.button("help", rules, help) {
            self.help = true;
        }
        let label_w = l.label_w;
        if let Some(r) = self.account_row(ui, x0, l.account_y, col, label_w, narrow) {
            go = Some(r);
        }
        // The matches to start: one row, or a grid of two columns.
        let choices: [(&str, &str); 7] = [
            ("vs-computer-easy", "Computer: easy"),
            ("vs-computer-medium", "Computer: medium"),
            ("vs-computer-hard", "Computer: hard"),
            ("vs-computer-adaptive", "Computer: adaptive"),
            ("vs-person", "A friend (link)"),
            ("sandbox", "Physics sandbox"),
            ("leaderboard", "Leaderboard"),
        ];
        for ((i, (name, label)), rect) in choices.iter().enumerate().zip(l.choices) {
            if ui.button(name, label, rect) {
                match i {
                    0 => self.create(Opponent::Bot("easy")),
                    1 => self.create(Opponent::Bot("medium")),
                    2 => self.create(Opponent::Bot("hard")),
                    3 => self.create(Opponent::Bot("adaptive")),
                    4 => self.create(Opponent::Person),
                    5 => go = Some(Route::Sandbox),
                    _ => go = Some(Route::Leaderboard { bots: false }),
                }
            }
        }
        let field = l.join_field;
        ui::text("Join by id", x0, field.y + 12.0, 17.0, colors::TEXT);
        let entered = ui.text_field("join-id-field", &mut self.join_id, field, "match id", 64);
        let id = self.join_id.trim().to_string();
        let ok = !id.is_empty() && id.chars().all(|c| c.is_ascii_alphanumeric());
        if (ui.button_styled("join-id", "Join", l.join, ok, false) || entered) && ok {
            go = Some(Route::Join { match_id: id });
        }
        if let Some(m) = &self.message {
            let (mx, my, mw) = l.message;
            let size = if narrow { 15.0 } else { 16.0 };
            ui::text(&ui::fit(m, size, mw), mx, my, size, colors::MUTED);
        }
        let footer = if narrow {
            "Writing a bot? See /api"
        } else {
            "Writing a bot? The HTTP and WebSocket protocol is described at /api"
        };
        ui::text(footer, x0, l.footer_y, 14.0, colors::MUTED);
        for (list_, area) in self.lists.iter().zip(l.lists) {
            if let Some(r) = list(ui, list_, area) {
                go = Some(r);
            }
        }
        if go.is_some() {
            platform::storage_set(NAME_KEY, self.name.trim());
        }
        go
    }
}

/// Whether a match in the list of `status` gets its button: a match this
/// server cannot play (another physics version) is neither joined nor
/// watched, only replayed once finished.
fn offered(status: &str, s: &Summary) -> bool {
    s.playable || status == "finished"
}

/// One list of matches in `area`, as many rows as fit (each a
/// finger-sized button and two lines of description); where a click leads.
fn list(ui: &mut Ui, l: &List, area: Rect) -> Option<Route> {
    let mut go = None;
    ui::panel(area);
    ui::text(l.title, area.x + 10.0, area.y + 8.0, 19.0, colors::ACCENT);
    let mut y = area.y + 34.0;
    if l.items.is_empty() {
        ui::text("none yet", area.x + 10.0, y, 16.0, colors::MUTED);
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
        if offered && ui.button(&name, l.action, r) {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn summary(json: serde_json::Value) -> Summary {
        serde_json::from_value(json).expect("a summary")
    }

    #[test]
    fn a_rated_match_shows_each_seats_rating_and_is_marked_rated() {
        let s = summary(serde_json::json!({
            "match_id": "ab", "first": "Petka", "second": null, "bot": "hard", "shots": 2,
            "result": null, "rated": true,
            "first_rating": {"rating": 1523, "provisional": false},
            "second_rating": {"rating": 1500, "provisional": true}}));
        let (names, facts) = describe(&s);
        assert_eq!(names, "Petka (1523) vs computer (hard) (1500?)");
        assert_eq!(facts, "rated · 2 shots");
    }

    #[test]
    fn a_match_this_server_cannot_play_is_only_replayed() {
        let s = summary(serde_json::json!({
            "match_id": "ab", "first": "Anka", "second": "Petka", "bot": null, "shots": 0,
            "result": null, "playable": false}));
        assert!(!offered("open", &s) && !offered("live", &s));
        assert!(offered("finished", &s));
        assert_eq!(describe(&s).1, "not playable here · 0 shots");
        let playable = summary(serde_json::json!({
            "match_id": "ab", "first": "Anka", "second": null, "bot": null, "shots": 0,
            "result": null}));
        assert!(offered("open", &playable));
        assert_eq!(describe(&playable).0, "Anka vs ...");
    }
}
