//! Quick match (`#/quick`, `#/quick/rated`): a stranger to play. The
//! screen opens the account's event stream (`/api/stream`), seeks a match
//! of the kind asked (rated against a similar rating, or casual), shows
//! the wait with its clock and a Cancel, and once the server pairs two
//! seekers takes the seat it hands over and opens the match. After
//! [`seek::OFFER_COMPUTER_AFTER`] seconds (or at once without an account,
//! since only accounts are paired) it offers the adaptive computer level
//! instead. What the wait means is decided in [`seek`]; this module owns
//! the stream's socket, the request for a computer match and the drawing.

pub mod seek;

use crate::api::{Api, Opponent, Pending, SeatGrant};
use crate::i18n::t;
use crate::platform::{Socket, SocketState};
use crate::route::{ws_origin, Route};
use crate::screen::Screen;
use crate::ui::{self, colors, Ui};
use game::stream::StreamServerMessage;
use macroquad::prelude::*;
use seek::{Phase, Seek};

pub struct QuickMatch {
    api: Api,
    /// The name a computer match is played under.
    name: String,
    seek: Seek,
    socket: Option<Socket>,
    /// The computer match asked for instead.
    creating: Option<Pending<SeatGrant>>,
    message: Option<String>,
}

impl QuickMatch {
    /// Starts looking for a rated or casual match for the signed-in
    /// player (`api.key`); without an account it only offers the computer.
    pub fn new(api: Api, name: String, rated: bool) -> QuickMatch {
        let mut seek = Seek::new(rated);
        let socket = if api.key.is_some() {
            Some(Socket::open(&stream_url(&api)))
        } else {
            seek.refuse(t!("quick-sign-in-first"));
            None
        };
        QuickMatch {
            api,
            name,
            seek,
            socket,
            creating: None,
            message: None,
        }
    }

    /// Drives the stream: opens it again when due, says hello and seeks
    /// once open, hands the server's messages to the wait.
    fn poll_stream(&mut self, dt: f64) {
        if self.seek.tick(dt) {
            self.socket = Some(Socket::open(&stream_url(&self.api)));
        }
        let Some(socket) = &self.socket else {
            return;
        };
        while let Some(text) = socket.recv() {
            if let Ok(msg) = StreamServerMessage::from_json(&text) {
                self.seek.heard(msg);
            }
        }
        match socket.state() {
            SocketState::Open if self.seek.phase == Phase::Connecting => {
                let key = self.api.key.clone().unwrap_or_default();
                for m in self.seek.opened(&key) {
                    socket.send(&m.to_json());
                }
            }
            SocketState::Closed => {
                self.socket = None;
                self.seek.closed();
            }
            _ => {}
        }
    }

    /// Withdraws the seek and closes the stream.
    fn stop(&mut self) {
        if let Some(socket) = self.socket.take() {
            if self.seek.phase == Phase::Waiting {
                socket.send(&self.seek.cancel().to_json());
            }
        }
    }
}

fn stream_url(api: &Api) -> String {
    format!("{}/api/stream", ws_origin(&api.origin))
}

/// Where the screen's parts go in a `w` x `h` window: the panel, then in
/// it the status line's top, Cancel, the computer and Sign in.
struct Places {
    panel: Rect,
    status_y: f32,
    cancel: Rect,
    computer: Rect,
    sign_in: Rect,
}

fn places(w: f32, h: f32) -> Places {
    let pw = (w - 24.0).min(520.0);
    let ph = 340.0f32.min(h - 24.0);
    let panel = Rect::new((w - pw) / 2.0, ((h - ph) / 2.0).min(120.0), pw, ph);
    let (x, bw) = (panel.x + 16.0, pw - 32.0);
    // The status and the hint take up to two lines each above the buttons.
    let row = |i: f32| Rect::new(x, panel.y + 144.0 + i * (ui::TOUCH + 12.0), bw, ui::TOUCH);
    Places {
        panel,
        status_y: panel.y + 54.0,
        cancel: row(0.0),
        computer: row(1.0),
        sign_in: row(2.0),
    }
}

impl Screen for QuickMatch {
    fn frame(&mut self, ui: &mut Ui, dt: f64) -> Option<Route> {
        self.poll_stream(dt);
        if let Phase::Paired { match_id, token } = &self.seek.phase {
            let grant = SeatGrant {
                match_id: match_id.clone(),
                token: token.expose().to_string(),
            };
            self.stop();
            return Some(crate::lobby::seated(&grant));
        }
        if let Some(p) = &mut self.creating {
            if let Some(r) = p.poll() {
                self.creating = None;
                match r {
                    Ok(grant) => {
                        self.stop();
                        return Some(crate::lobby::seated(&grant));
                    }
                    Err(e) => self.message = Some(e),
                }
            }
        }
        let (w, h) = crate::scale::size().into();
        let p = places(w, h);
        ui::panel(p.panel);
        let (x, tw) = (p.panel.x + 16.0, p.panel.w - 32.0);
        ui::text(
            &ui::fit(&t!("lobby-quick-match"), 26.0, tw),
            x,
            p.panel.y + 14.0,
            26.0,
            colors::ACCENT,
        );
        // The status and the hint in two lines each, smaller (down to 12
        // units) where a narrow panel needs it.
        let (size, status) = crate::help::shrink_lines(&self.seek.status(), 17.0, tw, 2);
        for (i, line) in status.iter().enumerate() {
            ui::text(line, x, p.status_y + i as f32 * 20.0, size, colors::TEXT);
        }
        let hint = match &self.message {
            Some(m) => m.clone(),
            None if self.seek.offer_computer() => t!("quick-nobody-yet"),
            None => t!("quick-next-person"),
        };
        let hint_y = p.status_y + 20.0 * status.len() as f32 + 4.0;
        let (size, hint) = crate::help::shrink_lines(&hint, 15.0, tw, 2);
        for (i, line) in hint.iter().enumerate() {
            ui::text(line, x, hint_y + i as f32 * 18.0, size, colors::MUTED);
        }
        let mut go = None;
        if ui.button("quick-cancel", &t!("cancel"), p.cancel) {
            self.stop();
            go = Some(Route::Lobby);
        }
        if self.seek.offer_computer() {
            let label = if self.creating.is_some() {
                t!("quick-starting")
            } else {
                t!("quick-play-computer")
            };
            let enabled = self.creating.is_none();
            if ui.button_styled("quick-computer", &label, p.computer, enabled, false) {
                self.creating = Some(self.api.create(
                    &self.name,
                    Opponent::Bot("adaptive"),
                    self.seek.rated && self.api.key.is_some(),
                ));
            }
        }
        if self.api.key.is_none() && ui.button("sign-in", &t!("sign-in"), p.sign_in) {
            go = Some(Route::SignIn);
        }
        go
    }

    fn name(&self) -> &'static str {
        "quick-match"
    }

    fn report(&self) -> serde_json::Map<String, serde_json::Value> {
        let mut m = serde_json::Map::new();
        m.insert("seeking".into(), (self.seek.phase == Phase::Waiting).into());
        m.insert("rated".into(), self.seek.rated.into());
        m.insert("waited".into(), self.seek.waited.into());
        m.insert("offer_computer".into(), self.seek.offer_computer().into());
        m.insert("status".into(), self.seek.status().into());
        m
    }

    fn animating(&self) -> bool {
        // The clock ticks; the heartbeat redraws it twice a second.
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_geometry::{inside, overlap, PHONES};

    #[test]
    fn the_wait_s_buttons_fit_every_window_without_overlapping() {
        for (w, h) in PHONES
            .into_iter()
            .chain([(1100.0, 760.0), (1920.0, 1080.0)])
        {
            let p = places(w, h);
            let window = Rect::new(0.0, 0.0, w, h);
            let buttons = [p.cancel, p.computer, p.sign_in];
            for (i, b) in buttons.iter().enumerate() {
                assert!(inside(*b, p.panel) && inside(*b, window), "{w}x{h}: {b:?}");
                assert!(b.h >= ui::TOUCH);
                assert!(
                    b.y > p.status_y + 80.0,
                    "below two lines of status and of hint"
                );
                for c in &buttons[i + 1..] {
                    assert!(!overlap(*b, *c), "{w}x{h}: {b:?} overlaps {c:?}");
                }
            }
        }
    }
}
