//! A live match, played or watched: the screen that ties its parts
//! together — the connection, the match state it feeds ([`state`]), the
//! board and the slingshot ([`board`]), the side panel ([`panel`]), the
//! end-of-match screen ([`end_screen`]), all placed by [`layout`] — and
//! what the panel's and the end screen's buttons do.
//!
//! In a wide window the panel stands to the right of the board; in a tall
//! one (a phone held upright) the board takes the full width at the top
//! and the panel lies below it. A player who opens an invitation link
//! without a name is asked for one before taking the seat.
//!
//! A match against the computer may also be played offline, in this page
//! ([`crate::local_match`]): the same screen, fed by the page's own
//! session through the same [`Channel`]. The computer answers on the
//! page's only thread, so it is asked only after the frame that says it is
//! thinking has been drawn and the last shot's film has played; the page
//! pauses for as long as it decides (the state report's `think_ms`).

pub mod board;
pub mod end_screen;
pub mod layout;
pub mod panel;
pub mod state;

use crate::api::{token_key, Api, Pending, SeatGrant, SocketAt};
use crate::channel::Channel;
use crate::connection::{Connection, Link};
use crate::highlight;
use crate::i18n::t;
use crate::local_match::LocalMatch;
use crate::platform;
use crate::route::{ws_origin, Route};
use crate::screen::Screen;
use crate::ui::{self, colors, Ui};
use crate::viewport::Viewport;
use board::{Drag, TURN_CUE};
use game::protocol::ClientMessage;
use game::token::SeatToken;
use game::{Phase, PieceId};
use macroquad::prelude::*;
use state::{MatchState, Mute};

/// Most chat lines the panel shows.
const CHAT_SHOWN: usize = 6;

/// How the screen came to the match.
enum Setup {
    /// Opened from an invitation link by a player without a name: asking
    /// for one before taking the seat.
    Naming(String),
    /// Taking the empty seat first.
    Joining(Pending<SeatGrant>),
    /// Connected (or connecting) with a token, or watching without one.
    Live,
    /// Could not take the seat.
    Refused(String),
}

pub struct Play {
    api: Api,
    match_id: String,
    name: String,
    token: Option<String>,
    setup: Setup,
    /// Asking the page's node where the match's socket is (on a cluster,
    /// the node that plays it), before connecting.
    locating: Option<Pending<SocketAt>>,
    conn: Option<Channel>,
    /// The computer's level of a match played in this page, offline.
    offline: Option<bots::Level>,
    /// The offline computer's question was shown as pending in the last
    /// frame drawn: it may think now.
    think_shown: bool,
    /// How long the offline computer's decisions took, in milliseconds
    /// of the page's clock (the last one, the longest) and how many.
    think_ms: Option<(f64, f64)>,
    thinks: u32,
    /// The match as this page follows it.
    state: MatchState,
    chat_draft: String,
    /// The chat's menu (quick phrases, mute switches) is open.
    chat_menu: bool,
    /// Whose chat this page hides.
    mute: Mute,
    drag: Option<Drag>,
    confirm_resign: bool,
    /// "Lobby" was pressed while the match is on: asking before leaving.
    confirm_leave: bool,
    /// The panel's status line this frame (for the test report).
    status: String,
    /// The rules are open over the board.
    help: bool,
    /// Where the pieces were drawn this frame (for the test report).
    drawn: Vec<(PieceId, Vec2, f32)>,
    /// The slingshot's power and the meter's rectangle while aiming.
    aiming: Option<(f64, Rect)>,
    /// The board's map this frame (the slingshot reads the pointer with it).
    viewport: Option<Viewport>,
    /// The end-of-match screen was closed.
    end_closed: bool,
    /// Sounds (and a phone's buzz on a hit) on: on by default, the
    /// player's choice remembered by the browser.
    sound: bool,
    /// Whether it was the player's turn last frame, and since when it is.
    was_my_turn: bool,
    turn_since: f64,
}

const SOUND_KEY: &str = "chapaev.sound";

/// Whether the player has sound on (the default) or turned it off.
pub(crate) fn sound_on() -> bool {
    platform::storage_get(SOUND_KEY).as_deref() != Some("off")
}
const NAME_KEY: &str = "chapaev.name";
/// The match this browser left while it was on (the lobby offers the way back).
pub const LEFT_KEY: &str = "chapaev.left-match";

impl Play {
    /// Plays (with the token this browser holds) or watches `match_id`;
    /// `join` takes the empty seat first.
    pub fn new(api: Api, match_id: String, name: String, join: bool, watch: bool) -> Play {
        let token = if watch {
            None
        } else {
            platform::storage_get(&token_key(&match_id))
        };
        // A signed-in player joins under the account's name: nothing to ask.
        let named = api.key.is_some()
            || platform::storage_get(NAME_KEY).is_some_and(|n| !n.trim().is_empty());
        let setup = if join && token.is_none() && !named {
            Setup::Naming(String::new())
        } else if join && token.is_none() {
            Setup::Joining(api.join(&match_id, &name))
        } else {
            Setup::Live
        };
        let mut p = Play::with(api, match_id, name, token, setup);
        if matches!(p.setup, Setup::Live) {
            p.connect();
        }
        p
    }

    /// The screen for `match_id`, not yet connected.
    fn with(api: Api, match_id: String, name: String, token: Option<String>, setup: Setup) -> Play {
        Play {
            api,
            match_id,
            name,
            token,
            setup,
            locating: None,
            conn: None,
            offline: None,
            think_shown: false,
            think_ms: None,
            thinks: 0,
            state: MatchState::default(),
            chat_draft: String::new(),
            chat_menu: false,
            mute: Mute::default(),
            drag: None,
            confirm_resign: false,
            confirm_leave: false,
            status: String::new(),
            help: false,
            drawn: Vec::new(),
            viewport: None,
            aiming: None,
            end_closed: false,
            sound: sound_on(),
            was_my_turn: false,
            turn_since: 0.0,
        }
    }

    /// A match against `level` played in this page, offline: casual, never
    /// rated, its noise secret and the computer's seed drawn here.
    pub fn offline(api: Api, level: bots::Level, name: String) -> Play {
        let mut p = Play::with(api, "offline".to_string(), name, None, Setup::Live);
        let mut secret = [0u8; 32];
        for chunk in secret.chunks_mut(8) {
            chunk.copy_from_slice(&platform::random_u64().to_le_bytes());
        }
        let secret = game::NoiseSecret::from_bytes(secret);
        match LocalMatch::new(level, &p.name, secret, platform::random_u64(), 0.0) {
            Ok(m) => p.conn = Some(Channel::Local(Box::new(m))),
            Err(e) => p.setup = Setup::Refused(e.to_string()),
        }
        p.offline = Some(level);
        p
    }

    /// Asks where the match's socket is; [`Play::connected_to`] opens it.
    fn connect(&mut self) {
        self.locating = Some(self.api.socket(&self.match_id));
    }

    /// Opens the socket `direct` (another node's; none: this page's
    /// node's), falling back on this page's node.
    fn connected_to(&mut self, direct: Option<String>) {
        let own = format!("{}/ws?match={}", ws_origin(&self.api.origin), self.match_id);
        let token = self.token.clone().map(SeatToken::new);
        self.conn = Some(Channel::Server(Connection::open_preferring(
            direct,
            own,
            self.name.clone(),
            token,
        )));
    }

    fn connected(&self) -> bool {
        self.conn.as_ref().is_some_and(Channel::is_open)
    }

    /// Whether the player may aim now.
    fn my_turn(&self) -> bool {
        self.state.may_aim(self.connected())
    }

    fn send(&mut self, m: ClientMessage) -> bool {
        let sent = self.conn.as_mut().is_some_and(|c| c.send(&m));
        if !sent {
            self.state.notify(t!("play-not-connected-retry"));
        }
        sent
    }

    /// Takes what the server said; where to go when a rematch started.
    fn receive(&mut self, m: game::protocol::ServerMessage) -> Option<Route> {
        let match_id = self.state.receive(m)?;
        if let Some(t) = &self.token {
            platform::storage_set(&token_key(&match_id), t);
            return Some(Route::Play { match_id });
        }
        Some(Route::Watch { match_id })
    }

    /// Shows queued announcements, with their sounds if sound is on.
    fn advance(&mut self, dt: f64) {
        for s in self.state.advance(dt) {
            if self.sound {
                platform::play_sound(s);
            }
        }
    }

    /// The board and the pieces (drawn first: the panel covers what slides
    /// off the board towards it).
    fn board(&mut self, area: Rect) {
        let Some(v) = &self.state.view else {
            self.viewport = None;
            ui::text_centred(&t!("play-connecting-match"), area, 22.0, colors::MUTED);
            return;
        };
        let shown = board::show(
            v,
            &self.state.current_frame(),
            area,
            self.state.my_side(),
            self.my_turn(),
            self.drag.as_ref().map(|d| d.piece),
            self.state.now - self.turn_since,
            self.state.now,
        );
        self.viewport = Some(shown.viewport);
        self.drawn = shown.drawn;
    }

    /// The slingshot, while it is the player's turn; a shot released is sent.
    fn aim(&mut self, ui: &mut Ui) {
        self.aiming = None;
        let (Some(vp), Some(v)) = (self.viewport, self.state.view.clone()) else {
            return;
        };
        if !self.my_turn() {
            self.drag = None;
            return;
        }
        let sling = board::sling(ui, vp, &v, self.state.my_side(), &mut self.drag);
        self.aiming = sling.aiming;
        if let Some((piece, velocity)) = sling.shot {
            if self.send(ClientMessage::Shot { piece, velocity }) {
                self.state.awaiting = true;
            }
        }
    }

    /// The connection's status line and its colour.
    fn link(&self) -> (String, Color) {
        if self.locating.is_some() {
            return (t!("play-link-connecting"), colors::MUTED);
        }
        match self.conn.as_ref().map(Channel::link) {
            Some(Link::Open) => (t!("play-link-open"), colors::GOOD),
            Some(Link::Connecting) => (t!("play-link-connecting"), colors::MUTED),
            Some(Link::Retrying { at, attempt }) => (
                t!(
                    "play-link-retrying",
                    seconds = (at - self.state.now).max(0.0).round(),
                    attempt = attempt
                ),
                colors::DANGER,
            ),
            Some(Link::Failed(why)) => (t!("play-link-failed", why = why.as_str()), colors::DANGER),
            Some(Link::Offline) if self.computer_thinking() => {
                (t!("play-link-offline-thinking"), colors::ACCENT)
            }
            Some(Link::Offline) => (t!("play-link-offline"), colors::MUTED),
            None => (t!("play-link-none"), colors::MUTED),
        }
    }

    /// The side panel in `area`, and what its buttons do.
    fn panel(&mut self, ui: &mut Ui, area: Rect) -> Option<Route> {
        let id = match self.offline {
            Some(_) => t!("play-offline-id"),
            None => self.match_id.clone(),
        };
        let cx = panel::Context {
            match_id: &id,
            link: self.link(),
            compact: layout::compact(area),
            my_turn: self.my_turn(),
            confirm_resign: self.confirm_resign,
            sound: self.sound,
        };
        let content = panel::content(&self.state, &cx);
        self.status = content
            .body
            .get(1)
            .map(|l| l.text.clone())
            .unwrap_or_default();
        let lines = self.state.chat_shown(self.mute, CHAT_SHOWN);
        let chat = panel::Chat {
            lines: &lines,
            draft: &mut self.chat_draft,
            menu: self.chat_menu,
            mute: self.mute,
            seated: self.state.you.is_some(),
        };
        let pressed = panel::show(ui, area, &content, chat);
        let mut go = None;
        for name in pressed.buttons {
            go = go.or(self.press(name));
        }
        if let Some(text) = pressed.chat {
            self.send(ClientMessage::Chat { text });
        }
        if let Some(phrase) = pressed.phrase {
            self.send(ClientMessage::Phrase { phrase });
            self.chat_menu = false;
        }
        go
    }

    /// What a panel or end-screen button does.
    fn press(&mut self, name: &str) -> Option<Route> {
        match name {
            "pie-swap" => {
                self.send(ClientMessage::PieDecision { swap: true });
            }
            "pie-keep" => {
                self.send(ClientMessage::PieDecision { swap: false });
            }
            "replay" | "end-replay" | "copy-link" if self.offline.is_some() => {
                self.state.notify(t!("play-offline-not-kept"));
            }
            "rematch" | "end-rematch" => {
                if let Some(level) = self.offline {
                    return Some(Route::Offline { level });
                }
                self.send(if self.state.rematch_is_theirs() {
                    ClientMessage::AcceptRematch
                } else {
                    ClientMessage::OfferRematch
                });
            }
            "leave-yes" if self.offline.is_some() => return Some(Route::Lobby),
            "copy-link" => {
                let link = format!("{}/#/join/{}", self.api.origin, self.match_id);
                platform::copy_text(&link);
                self.state.notify(t!("play-link-copied", link = link));
            }
            "resign" => self.confirm_resign = true,
            "resign-yes" => {
                self.send(ClientMessage::Resign);
                self.confirm_resign = false;
            }
            "resign-no" => self.confirm_resign = false,
            "replay" | "end-replay" => {
                return Some(Route::Replay {
                    match_id: self.match_id.clone(),
                })
            }
            "lobby" | "end-lobby" if self.seated_and_on() => self.confirm_leave = true,
            "lobby" | "end-lobby" => return Some(Route::Lobby),
            "leave-yes" => {
                platform::storage_set(LEFT_KEY, &self.match_id);
                return Some(Route::Lobby);
            }
            "leave-no" => self.confirm_leave = false,
            "help" => self.help = true,
            "sound" => {
                self.sound = !self.sound;
                platform::storage_set(SOUND_KEY, if self.sound { "on" } else { "off" });
                if self.sound {
                    platform::play_sound(platform::Sound::YourTurn);
                }
            }
            "end-close" => self.end_closed = true,
            "chat-phrases" => self.chat_menu = !self.chat_menu,
            "mute-players" => self.mute.players = !self.mute.players,
            "mute-spectators" => self.mute.spectators = !self.mute.spectators,
            _ => {}
        }
        None
    }

    /// Whether the offline computer has a question pending.
    fn computer_thinking(&self) -> bool {
        self.conn
            .as_ref()
            .and_then(Channel::local)
            .is_some_and(LocalMatch::thinking)
    }

    /// The offline computer's move, once the frame that says it thinks has
    /// been drawn with the last shot's film over; timed on the page's clock.
    fn computer_moves(&mut self) {
        let ready = self.think_shown && !self.state.busy();
        self.think_shown = false;
        let Some(local) = self.conn.as_mut().and_then(Channel::local_mut) else {
            return;
        };
        if ready && local.thinking() {
            let started = get_time();
            local.think();
            let ms = (get_time() - started) * 1000.0;
            let longest = self.think_ms.map_or(ms, |(_, l)| l.max(ms));
            self.think_ms = Some((ms, longest));
            self.thinks += 1;
        }
    }

    /// Whether this page holds a seat in a match still being played.
    fn seated_and_on(&self) -> bool {
        self.state.you.is_some()
            && self
                .state
                .view
                .as_ref()
                .is_some_and(|v| !matches!(v.phase, Phase::Over { .. }))
    }

    /// The question before leaving a match that goes on without the player.
    fn leave_dialog(&mut self, ui: &mut Ui) -> Option<Route> {
        let box_ = layout::dialog(crate::scale::size(), 190.0);
        ui::panel(box_);
        let (x, w) = (box_.x + 16.0, box_.w - 32.0);
        ui::text(
            &ui::fit(&t!("play-leave-title"), 21.0, w),
            x,
            box_.y + 14.0,
            21.0,
            colors::ACCENT,
        );
        for (i, l) in crate::help::wrap_lines(&t!("play-leave-body"), 16.0, w, 2)
            .iter()
            .enumerate()
        {
            let y = box_.y + 50.0 + i as f32 * 22.0;
            ui::text(&ui::fit(l, 16.0, w), x, y, 16.0, colors::TEXT);
        }
        let (stay, leave) = layout::dialog_buttons(box_, 126.0);
        if ui.button("leave-no", &t!("play-leave-no"), stay) {
            return self.press("leave-no");
        }
        if ui.button("leave-yes", &t!("play-leave-yes"), leave) {
            return self.press("leave-yes");
        }
        None
    }

    /// The end-of-match screen over the board, once everything announced
    /// is shown and until it is closed.
    fn end_screen(&mut self, ui: &mut Ui, area: Rect) -> Option<Route> {
        let v = self.state.view.as_ref()?;
        let Phase::Over { result } = v.phase else {
            return None;
        };
        if self.end_closed || self.state.busy() {
            return None;
        }
        let words = end_screen::words(result, self.state.my_side(), &self.state.score(), v);
        let rematch = self.state.you.map(|_| self.state.rematch_label());
        let mut go = None;
        let rematch = rematch.as_ref().map(|(l, e)| (l.as_str(), *e));
        for name in end_screen::show(ui, area, &words, rematch) {
            go = go.or(self.press(name));
        }
        go
    }
}

impl Screen for Play {
    fn frame(&mut self, ui: &mut Ui, dt: f64) -> Option<Route> {
        self.state.now += dt;
        if let Setup::Joining(p) = &mut self.setup {
            match p.poll() {
                Some(Ok(grant)) => {
                    platform::storage_set(&token_key(&grant.match_id), &grant.token);
                    return Some(Route::Play {
                        match_id: grant.match_id,
                    });
                }
                Some(Err(e)) => self.setup = Setup::Refused(e),
                None => {}
            }
        }
        let window = crate::scale::size();
        if let Setup::Naming(draft) = &mut self.setup {
            let box_ = layout::dialog(window, 200.0);
            ui::panel(box_);
            let (x, w) = (box_.x + 16.0, box_.w - 32.0);
            ui::text(
                &ui::fit(&t!("play-invited-title"), 21.0, w),
                x,
                box_.y + 14.0,
                21.0,
                colors::ACCENT,
            );
            ui::text(&t!("lobby-your-name"), x, box_.y + 48.0, 16.0, colors::TEXT);
            let field = Rect::new(x, box_.y + 72.0, w, ui::TOUCH);
            let entered = ui.text_field("join-name", draft, field, &t!("player-default-name"), 40);
            let (ok, watch) = layout::dialog_buttons(box_, 136.0);
            if ui.button("join-name-ok", &t!("play-take-seat"), ok) || entered {
                let name = crate::lobby::clean_name(draft);
                platform::storage_set(NAME_KEY, &name);
                self.setup = Setup::Joining(self.api.join(&self.match_id, &name));
                self.name = name;
            } else if ui.button("watch", &t!("play-just-watch"), watch) {
                return Some(Route::Watch {
                    match_id: self.match_id.clone(),
                });
            }
            return None;
        }
        if let Setup::Refused(why) = &self.setup {
            let box_ = layout::dialog(window, 190.0);
            ui::panel(box_);
            let (x, w) = (box_.x + 16.0, box_.w - 32.0);
            ui::text(
                &ui::fit(&t!("play-seat-refused"), 21.0, w),
                x,
                box_.y + 14.0,
                21.0,
                colors::ACCENT,
            );
            ui::text(&ui::fit(why, 15.0, w), x, box_.y + 50.0, 15.0, colors::TEXT);
            let (watch, lobby) = layout::dialog_buttons(box_, 126.0);
            if ui.button("watch", &t!("play-watch-instead"), watch) {
                return Some(Route::Watch {
                    match_id: self.match_id.clone(),
                });
            }
            if ui.button("lobby", &t!("lobby"), lobby) {
                return Some(Route::Lobby);
            }
            return None;
        }
        if let Some(answer) = self.locating.as_mut().and_then(Pending::poll) {
            // No answer (an older server, a fault): this page's node.
            self.locating = None;
            self.connected_to(answer.ok().and_then(|s| s.url));
        }
        let mut go = None;
        self.computer_moves();
        if let Some(c) = &mut self.conn {
            for m in c.poll(self.state.now) {
                if let Some(r) = self.receive(m) {
                    go = Some(r);
                }
            }
        }
        self.advance(dt);
        let (w, h) = (window.x, window.y);
        let (board, panel) = layout::split(w, h);
        // Your turn: a cue (and a sound, if on) when it comes.
        let my_turn = self.my_turn();
        if my_turn && !self.was_my_turn {
            self.turn_since = self.state.now;
            if self.sound {
                platform::play_sound(platform::Sound::YourTurn);
            }
        }
        self.was_my_turn = my_turn;
        // The board first (the panel covers what slides off it), then the
        // panel and the end screen, whose buttons take presses before the
        // slingshot does; with the rules open, nothing sees the pointer.
        self.board(board);
        let help = self.help;
        let nav = if self.confirm_leave {
            ui.without_input(|ui| {
                self.panel(ui, panel);
                self.end_screen(ui, board)
            });
            self.leave_dialog(ui)
        } else if help {
            ui.without_input(|ui| {
                let nav = self.panel(ui, panel);
                nav.or(self.end_screen(ui, board))
            })
        } else {
            let nav = self.panel(ui, panel);
            let nav = nav.or(self.end_screen(ui, board));
            self.aim(ui);
            nav
        };
        if help {
            self.help = !crate::help::show(ui);
        }
        // The instant replay of a shot worth seeing again, and its Skip.
        if self.state.replaying {
            let r = Rect::new(board.x + board.w - 128.0, board.y + 6.0, 120.0, ui::TOUCH);
            let label = t!("play-slow-motion", speed = highlight::SLOW);
            let label = ui::fit(&label, 17.0, r.x - board.x - 16.0);
            ui::text(&label, board.x + 10.0, board.y + 16.0, 17.0, colors::ACCENT);
            if !help && ui.button("skip-replay", &t!("play-skip-replay"), r) {
                self.state.skip_replay();
            }
        }
        if let Some((text, until)) = &self.state.notice {
            if self.state.now < *until {
                let shown = ui::fit(text, 16.0, board.w - 40.0);
                let tw = ui::text_width(&shown, 16.0) + 24.0;
                let r = Rect::new(board.x + (board.w - tw) / 2.0, board.y + 6.0, tw, 28.0);
                draw_rectangle(r.x, r.y, r.w, r.h, Color::new(0.0, 0.0, 0.0, 0.7));
                ui::text_centred(&shown, r, 16.0, colors::TEXT);
            }
        }
        // Drawn with the computer's question pending: it may answer next frame.
        self.think_shown = self.computer_thinking() && !self.state.busy();
        go.or(nav)
    }

    fn name(&self) -> &'static str {
        "play"
    }

    /// A shot playing, or the "your turn" cue pulsing.
    fn animating(&self) -> bool {
        self.state.playing.is_some()
            || self.state.now - self.turn_since < TURN_CUE
            || self.computer_thinking()
    }

    fn report(&self) -> serde_json::Map<String, serde_json::Value> {
        let mine = self.state.my_side();
        let pieces: Vec<_> = self
            .drawn
            .iter()
            .map(|(p, c, r)| {
                // CSS pixels, like the buttons.
                let z = crate::scale::zoom();
                serde_json::json!({"id": u8::from(*p), "x": c.x * z, "y": c.y * z, "r": r * z,
                    "mine": Some(p.side()) == mine})
            })
            .collect();
        let mut m = serde_json::Map::new();
        m.insert("match_id".into(), self.match_id.clone().into());
        m.insert(
            "seat".into(),
            serde_json::to_value(self.state.you).unwrap_or_default(),
        );
        m.insert("my_turn".into(), self.my_turn().into());
        m.insert("status".into(), self.status.clone().into());
        m.insert("animating".into(), self.state.busy().into());
        m.insert("sound".into(), self.sound.into());
        m.insert("replaying".into(), self.state.replaying.into());
        m.insert(
            "connected".into(),
            self.conn.as_ref().is_some_and(Channel::is_open).into(),
        );
        m.insert(
            "socket".into(),
            self.conn.as_ref().and_then(Channel::url).into(),
        );
        m.insert("offline".into(), self.offline.map(|l| l.as_str()).into());
        m.insert("thinking".into(), self.computer_thinking().into());
        m.insert("thinks".into(), self.thinks.into());
        if let Some((last, longest)) = self.think_ms {
            m.insert("think_ms".into(), last.into());
            m.insert("think_ms_longest".into(), longest.into());
        }
        m.insert(
            "shots".into(),
            self.state.view.as_ref().map_or(0, |v| v.shots).into(),
        );
        m.insert("pieces".into(), pieces.into());
        if let Some((power, meter)) = self.aiming {
            let r = crate::scale::css(meter);
            m.insert("aim_power".into(), power.into());
            m.insert("meter".into(), serde_json::json!([r.x, r.y, r.w, r.h]));
        }
        m.insert(
            "chat".into(),
            self.state.chat_shown(self.mute, CHAT_SHOWN).into(),
        );
        m.insert("chat_menu".into(), self.chat_menu.into());
        m.insert(
            "players".into(),
            serde_json::json!([
                self.state.name_of(game::Seat::First),
                self.state.name_of(game::Seat::Second)
            ]),
        );
        m.insert(
            "log".into(),
            self.state.log.iter().cloned().collect::<Vec<_>>().into(),
        );
        m.insert(
            "end_screen".into(),
            matches!(
                self.state.view.as_ref().map(|v| v.phase),
                Some(Phase::Over { .. })
            )
            .into(),
        );
        m
    }
}
