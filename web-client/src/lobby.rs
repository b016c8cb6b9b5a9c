//! The lobby: your name, a match against the computer (easy, medium or
//! hard) or a friend (a link to send), joining by id, and the server's open, live
//! and finished matches to join, watch or replay. The lists refresh every
//! few seconds.

use crate::api::{token_key, Api, Opponent, Pending, SeatGrant, Summary};
use crate::route::Route;
use crate::screen::Screen;
use crate::ui::{self, colors, Ui};
use crate::{draw, platform};
use game::Side;
use macroquad::prelude::*;

/// Seconds between refreshes of the match lists.
const REFRESH_SECONDS: f64 = 5.0;
const NAME_KEY: &str = "chapaev.name";

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
        Lobby {
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
            self.creating = Some(self.api.create(&self.player_name(), opponent));
            self.message = Some("creating the match...".into());
        }
    }

    fn poll(&mut self) -> Option<Route> {
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
fn clean_name(n: &str) -> String {
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

fn describe(s: &Summary) -> String {
    let first = s.first.as_deref().unwrap_or("?");
    let second = match (&s.second, &s.bot) {
        (_, Some(level)) => format!("computer ({level})"),
        (Some(n), None) => n.clone(),
        (None, None) => "...".to_string(),
    };
    let mut d = format!("{first} vs {second}");
    if let Some(r) = s.result.and_then(|r| r.winner()) {
        let w = if r == Side::White { "White" } else { "Black" };
        d.push_str(&format!(" · {w} won"));
    }
    if s.shots > 0 {
        d.push_str(&format!(" · {} shots", s.shots));
    }
    d
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
}

impl Lobby {
    /// The lobby itself (drawn under the rules when they are open).
    fn lists_and_controls(&mut self, ui: &mut Ui) -> Option<Route> {
        let mut go = self.poll();
        let (w, h) = (screen_width(), screen_height());
        let col = (w - 40.0).min(980.0);
        let x0 = (w - col) / 2.0;
        let mut y = 24.0;
        // The title, with two checkers for a logo.
        draw::checker(vec2(x0 + 22.0, y + 22.0), 20.0, Side::White, 1.0);
        draw::checker(vec2(x0 + 52.0, y + 30.0), 20.0, Side::Black, 1.0);
        ui::text("Chapaev online", x0 + 86.0, y, 40.0, colors::ACCENT);
        ui::text(
            "flick your checkers, knock theirs off the board",
            x0 + 88.0,
            y + 42.0,
            18.0,
            colors::MUTED,
        );
        if ui.button(
            "help",
            "How to play",
            Rect::new(x0 + col - 140.0, y + 6.0, 140.0, 34.0),
        ) {
            self.help = true;
        }
        y += 86.0;
        ui::text("Your name", x0, y + 8.0, 18.0, colors::TEXT);
        ui.text_field(
            "name",
            &mut self.name,
            Rect::new(x0 + 100.0, y, 260.0, 34.0),
            "Player",
            40,
        );
        y += 52.0;
        let bw = ((col - 32.0) / 5.0).min(200.0);
        let b = |i: f32| Rect::new(x0 + i * (bw + 8.0), y, bw, 48.0);
        if ui.button("vs-computer-easy", "Computer: easy", b(0.0)) {
            self.create(Opponent::Bot("easy"));
        }
        if ui.button("vs-computer-medium", "Computer: medium", b(1.0)) {
            self.create(Opponent::Bot("medium"));
        }
        if ui.button("vs-computer-hard", "Computer: hard", b(2.0)) {
            self.create(Opponent::Bot("hard"));
        }
        if ui.button("vs-person", "A friend (link)", b(3.0)) {
            self.create(Opponent::Person);
        }
        if ui.button("sandbox", "Physics sandbox", b(4.0)) {
            go = Some(Route::Sandbox);
        }
        y += 62.0;
        ui::text("Join by id", x0, y + 8.0, 18.0, colors::TEXT);
        let field = Rect::new(x0 + 100.0, y, 260.0, 34.0);
        let entered = ui.text_field("join-id-field", &mut self.join_id, field, "match id", 64);
        let id = self.join_id.trim().to_string();
        let ok = !id.is_empty() && id.chars().all(|c| c.is_ascii_alphanumeric());
        if (ui.button_styled(
            "join-id",
            "Join",
            Rect::new(x0 + 370.0, y, 90.0, 34.0),
            ok,
            false,
        ) || entered)
            && ok
        {
            platform::storage_set(NAME_KEY, self.name.trim());
            go = Some(Route::Join { match_id: id });
        }
        if let Some(m) = &self.message {
            ui::text(m, x0 + 480.0, y + 8.0, 16.0, colors::MUTED);
        }
        y += 54.0;
        ui::text(
            "Writing a bot? The HTTP and WebSocket protocol is described at /api",
            x0,
            h - 20.0,
            14.0,
            colors::MUTED,
        );
        // The three lists side by side (or stacked on a narrow screen).
        let narrow = col < 700.0;
        let lw = if narrow { col } else { (col - 24.0) / 3.0 };
        let top = y;
        for (i, l) in self.lists.iter().enumerate() {
            let (lx, mut ly) = if narrow {
                (x0, top + i as f32 * ((h - top - 24.0) / 3.0))
            } else {
                (x0 + i as f32 * (lw + 12.0), top)
            };
            let lh = if narrow {
                (h - top - 24.0) / 3.0 - 8.0
            } else {
                h - top - 36.0
            };
            ui::panel(Rect::new(lx, ly, lw, lh));
            ui::text(l.title, lx + 10.0, ly + 8.0, 20.0, colors::ACCENT);
            ly += 36.0;
            if l.items.is_empty() {
                ui::text("none yet", lx + 10.0, ly, 16.0, colors::MUTED);
            }
            for (k, s) in l.items.iter().enumerate() {
                if ly + 30.0 > top + lh {
                    break;
                }
                let text: String = describe(s)
                    .chars()
                    .take(((lw - 98.0) / 6.8).max(8.0) as usize)
                    .collect();
                ui::text(&text, lx + 10.0, ly + 6.0, 15.0, colors::TEXT);
                let name = format!("{}-{k}", l.status);
                if ui.button(&name, l.action, Rect::new(lx + lw - 78.0, ly, 68.0, 26.0)) {
                    let match_id = s.match_id.clone();
                    go = Some(match l.status {
                        "open" => Route::Join { match_id },
                        "live" => Route::Watch { match_id },
                        _ => Route::Replay { match_id },
                    });
                }
                ly += 32.0;
            }
        }
        go
    }
}
