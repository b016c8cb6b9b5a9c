//! A live match, played or watched: the connection, the announcements
//! queued and animated in order from their exact films, the slingshot for
//! the player whose turn it is, and the side panel (players, round, rows,
//! pieces left, the turn clock, the pie decision, resign, rematch, chat,
//! the invitation link).

use crate::aim::{Aim, Slingshot};
use crate::api::{token_key, Api, Pending, SeatGrant};
use crate::clip::{Clip, Frame};
use crate::connection::{Connection, Link};
use crate::route::{ws_origin, Route};
use crate::screen::Screen;
use crate::ui::{self, colors, Ui};
use crate::viewport::Viewport;
use crate::{draw, platform};
use ::glam::DVec2;
use game::protocol::{ClientMessage, Players, ServerMessage, MAX_CHAT_CHARS};
use game::token::SeatToken;
use game::{MatchResult, MatchView, Phase, PieceId, Seat, Side, WinReason};
use macroquad::prelude::*;
use std::collections::VecDeque;

/// How the screen came to the match.
enum Setup {
    /// Taking the empty seat first.
    Joining(Pending<SeatGrant>),
    /// Connected (or connecting) with a token, or watching without one.
    Live,
    /// Could not take the seat.
    Refused(String),
}

/// A drag in progress from one of the player's pieces.
struct Drag {
    piece: PieceId,
    from: DVec2,
    pointer: DVec2,
}

pub struct Play {
    api: Api,
    match_id: String,
    name: String,
    token: Option<String>,
    setup: Setup,
    conn: Option<Connection>,
    you: Option<Seat>,
    players: Players,
    view: Option<MatchView>,
    /// Announcements not yet shown, in the order they came.
    queue: VecDeque<ServerMessage>,
    /// The shot being animated and its time.
    playing: Option<(Clip, f64)>,
    clock: Option<(Seat, Side, f64)>,
    chat: VecDeque<String>,
    chat_draft: String,
    notice: Option<(String, f64)>,
    drag: Option<Drag>,
    /// A shot was sent; waiting for the server's answer.
    awaiting: bool,
    confirm_resign: bool,
    /// The rules are open over the board.
    help: bool,
    rematch_offer: Option<Seat>,
    now: f64,
    /// Where the pieces were drawn this frame (for the test report).
    drawn: Vec<(PieceId, Vec2, f32)>,
}

const CHAT_LINES: usize = 6;

fn side_name(s: Side) -> &'static str {
    match s {
        Side::White => "White",
        Side::Black => "Black",
    }
}

impl Play {
    /// Plays (with the token this browser holds) or watches `match_id`;
    /// `join` takes the empty seat first.
    pub fn new(api: Api, match_id: String, name: String, join: bool, watch: bool) -> Play {
        let token = if watch {
            None
        } else {
            platform::storage_get(&token_key(&match_id))
        };
        let setup = if join && token.is_none() {
            Setup::Joining(api.join(&match_id, &name))
        } else {
            Setup::Live
        };
        let mut p = Play {
            api,
            match_id,
            name,
            token,
            setup,
            conn: None,
            you: None,
            players: Players::default(),
            view: None,
            queue: VecDeque::new(),
            playing: None,
            clock: None,
            chat: VecDeque::new(),
            chat_draft: String::new(),
            notice: None,
            drag: None,
            awaiting: false,
            confirm_resign: false,
            help: false,
            rematch_offer: None,
            now: 0.0,
            drawn: Vec::new(),
        };
        if matches!(p.setup, Setup::Live) {
            p.connect();
        }
        p
    }

    fn connect(&mut self) {
        let url = format!("{}/ws?match={}", ws_origin(&self.api.origin), self.match_id);
        let token = self.token.clone().map(SeatToken::new);
        self.conn = Some(Connection::open(url, self.name.clone(), token));
    }

    fn notify(&mut self, text: impl Into<String>) {
        self.notice = Some((text.into(), self.now + 5.0));
    }

    fn my_side(&self) -> Option<Side> {
        let v = self.view.as_ref()?;
        self.you.map(|s| s.side(v.swapped))
    }

    fn name_of(&self, seat: Seat) -> String {
        let n = match seat {
            Seat::First => &self.players.first,
            Seat::Second => &self.players.second,
        };
        n.clone().unwrap_or_else(|| "(waiting)".into())
    }

    /// Whether the player may aim now.
    fn my_turn(&self) -> bool {
        let Some(v) = &self.view else { return false };
        self.playing.is_none()
            && self.queue.is_empty()
            && !self.awaiting
            && self.conn.as_ref().is_some_and(Connection::is_open)
            && self.my_side().is_some()
            && v.to_shoot() == self.my_side()
    }

    /// Takes what the server said.
    fn receive(&mut self, m: ServerMessage) -> Option<Route> {
        match m {
            ServerMessage::MatchState {
                you, players, view, ..
            } => {
                // The full state supersedes anything not yet shown.
                self.you = you;
                self.players = players;
                self.view = Some(view);
                self.queue.clear();
                self.playing = None;
                self.awaiting = false;
            }
            m @ (ServerMessage::ShotPlayed { .. }
            | ServerMessage::PieDecided { .. }
            | ServerMessage::TurnPassed { .. }
            | ServerMessage::MatchOver { .. }) => {
                if matches!(m, ServerMessage::ShotPlayed { .. }) {
                    self.awaiting = false;
                }
                self.queue.push_back(m);
            }
            ServerMessage::RematchOffered { by } => {
                self.rematch_offer = Some(by);
                if Some(by) != self.you {
                    self.notify(format!("{} offers a rematch", self.name_of(by)));
                }
            }
            ServerMessage::RematchStarted { match_id } => {
                if let Some(t) = &self.token {
                    platform::storage_set(&token_key(&match_id), t);
                    return Some(Route::Play { match_id });
                }
                return Some(Route::Watch { match_id });
            }
            ServerMessage::Chat { name, text, .. } => {
                self.chat.push_back(format!("{name}: {text}"));
                while self.chat.len() > CHAT_LINES {
                    self.chat.pop_front();
                }
            }
            ServerMessage::Error { code, message } => {
                self.awaiting = false;
                self.notify(format!("{message} ({code})"));
            }
            ServerMessage::PlayerJoined { seat, name } => {
                match seat {
                    Seat::First => self.players.first = Some(name.clone()),
                    Seat::Second => self.players.second = Some(name.clone()),
                }
                self.notify(format!("{name} joined"));
            }
            ServerMessage::PlayerLeft { seat, grace_ms } => {
                let n = self.name_of(seat);
                self.notify(format!(
                    "{n} lost the connection; the seat is kept for {} s",
                    grace_ms / 1000
                ));
            }
            ServerMessage::PlayerBack { seat } => {
                let n = self.name_of(seat);
                self.notify(format!("{n} is back"));
            }
            ServerMessage::Clock {
                seat,
                side,
                remaining_ms,
            } => self.clock = Some((seat, side, self.now + remaining_ms as f64 / 1000.0)),
            ServerMessage::TurnTimedOut { seat, strikes } => {
                let n = self.name_of(seat);
                self.notify(format!("{n} ran out of time ({strikes} of 3)"));
            }
            ServerMessage::Forfeited { seat, .. } => {
                let n = self.name_of(seat);
                self.notify(format!("{n} forfeited"));
            }
            ServerMessage::Welcome { .. } | ServerMessage::MatchCreated { .. } => {}
        }
        None
    }

    /// Shows queued announcements in order, animating shots.
    fn advance(&mut self, dt: f64) {
        // Catch up faster when several shots are waiting.
        let speed = if self.queue.len() > 1 { 3.0 } else { 1.0 };
        if let Some((clip, t)) = &mut self.playing {
            *t += dt * speed;
            if *t >= clip.duration() {
                if let Some(v) = &self.view {
                    self.view = Some(v.after_shot(&clip.outcome, &clip.film));
                }
                self.playing = None;
            }
        }
        while self.playing.is_none() {
            let Some(m) = self.queue.pop_front() else {
                break;
            };
            match m {
                ServerMessage::ShotPlayed { outcome, film, .. } => {
                    self.playing = Some((Clip::new(outcome, film), 0.0));
                }
                ServerMessage::PieDecided { swap } => {
                    if let Some(v) = &self.view {
                        self.view = Some(v.after_pie(swap));
                    }
                }
                ServerMessage::TurnPassed { .. } => {
                    if let Some(v) = &self.view {
                        self.view = Some(v.after_pass());
                    }
                }
                ServerMessage::MatchOver { result, .. } => {
                    if let Some(v) = &self.view {
                        self.view = Some(v.after_result(result));
                    }
                }
                _ => {}
            }
        }
    }

    /// The moment to draw: the animated shot, or the board at rest.
    fn current_frame(&self) -> Frame {
        match (&self.playing, &self.view) {
            (Some((clip, t)), _) => clip.frame(*t),
            (None, Some(v)) => Frame {
                pieces: v.board.pieces().iter().map(|p| (p.id, p.pos)).collect(),
                ..Frame::default()
            },
            _ => Frame::default(),
        }
    }

    fn send(&mut self, m: ClientMessage) -> bool {
        let sent = self.conn.as_ref().is_some_and(|c| c.send(&m));
        if !sent {
            self.notify("not connected; trying again");
        }
        sent
    }

    /// The board, the pieces and the slingshot.
    fn board(&mut self, ui: &mut Ui, area: Rect) {
        let Some(v) = self.view.clone() else {
            ui::text_centred("Connecting to the match...", area, 24.0, colors::MUTED);
            return;
        };
        let flipped = self.my_side() == Some(Side::Black);
        let vp = Viewport::fit_square(
            v.config.board_size(),
            area,
            area.w.min(area.h) * 0.06,
            flipped,
        );
        draw::board(&vp, v.config.board_size());
        let frame = self.current_frame();
        let mine = self.my_side();
        let can_aim = self.my_turn();
        let dragging = self.drag.as_ref().map(|d| d.piece);
        draw::frame(&vp, v.config.piece_radius, &frame, |p| {
            if dragging == Some(p) {
                Some(colors::ACCENT)
            } else if can_aim && Some(p.side()) == mine {
                Some(Color::new(0.93, 0.66, 0.25, 0.45))
            } else {
                None
            }
        });
        let r = vp.px(v.config.piece_radius);
        self.drawn = frame
            .pieces
            .iter()
            .map(|&(p, pos)| (p, vp.to_screen(pos), r))
            .collect();
        self.aim(ui, &vp, &v, can_aim);
    }

    fn aim(&mut self, ui: &mut Ui, vp: &Viewport, v: &MatchView, can_aim: bool) {
        if !can_aim {
            self.drag = None;
            return;
        }
        let input = &ui.input;
        let pointer = vp.to_world(input.pointer);
        let mine = self.my_side();
        if input.pressed && !ui.captured() && self.drag.is_none() {
            let grab = v.config.piece_radius * 1.4;
            let hit = v
                .board
                .pieces()
                .iter()
                .filter(|p| Some(p.id.side()) == mine)
                .map(|p| (p, (p.pos - pointer).length()))
                .filter(|(_, d)| *d <= grab)
                .min_by(|a, b| a.1.total_cmp(&b.1));
            if let Some((p, _)) = hit {
                self.drag = Some(Drag {
                    piece: p.id,
                    from: p.pos,
                    pointer,
                });
            }
        }
        let Some(drag) = &mut self.drag else { return };
        drag.pointer = pointer;
        let sling = Slingshot {
            radius: v.config.piece_radius,
            square: v.config.square,
            max_speed: v.config.max_speed,
        };
        let aim = sling.aim(drag.from, drag.pointer);
        let c = vp.to_screen(drag.from);
        let p = input.pointer;
        draw_line(c.x, c.y, p.x, p.y, 2.0, Color::new(0.9, 0.8, 0.6, 0.6));
        match aim {
            Aim::Shoot { velocity, power } => {
                // The arrow: where the piece would go, as long as a full-power shot's first 3 squares.
                let dir = velocity / velocity.length();
                let tip = vp.to_screen(drag.from + dir * v.config.square * (0.8 + 3.2 * power));
                let col = Color::new(1.0, 0.85 - 0.6 * power as f32, 0.25, 0.95);
                draw::arrow(c, tip, col, 5.0);
                // The power meter beside the pointer.
                let (mx, my) = (p.x + 18.0, p.y - 40.0);
                draw_rectangle(mx, my, 10.0, 60.0, Color::new(0.0, 0.0, 0.0, 0.5));
                let h = 60.0 * power as f32;
                draw_rectangle(mx, my + 60.0 - h, 10.0, h, col);
                ui::text(
                    &format!("{:.0}%", power * 100.0),
                    mx + 14.0,
                    my + 20.0,
                    16.0,
                    colors::TEXT,
                );
            }
            Aim::Cancel => {
                ui::text(
                    "release here to cancel",
                    p.x + 14.0,
                    p.y - 10.0,
                    16.0,
                    colors::MUTED,
                );
            }
        }
        if ui.input.released || !ui.input.down {
            let piece = drag.piece;
            self.drag = None;
            if let Aim::Shoot { velocity, .. } = aim {
                if self.send(ClientMessage::Shot { piece, velocity }) {
                    self.awaiting = true;
                }
            }
        }
    }

    /// The side panel.
    fn panel(&mut self, ui: &mut Ui, area: Rect) -> Option<Route> {
        ui::panel(area);
        let x = area.x + 14.0;
        let w = area.w - 28.0;
        let mut y = area.y + 12.0;
        let line = |y: &mut f32, s: &str, size: f32, c: Color| {
            ui::text(s, x, *y, size, c);
            *y += size + 6.0;
        };
        line(&mut y, "Chapaev", 28.0, colors::ACCENT);
        let role = match self.my_side() {
            Some(s) => format!("You play {}", side_name(s)),
            None => "Watching".to_string(),
        };
        line(
            &mut y,
            &format!("{role} · match {}", self.match_id),
            16.0,
            colors::MUTED,
        );
        let link = match self.conn.as_ref().map(Connection::link) {
            Some(Link::Open) => ("connected".to_string(), colors::GOOD),
            Some(Link::Connecting) => ("connecting...".to_string(), colors::MUTED),
            Some(Link::Retrying { at, attempt }) => (
                format!(
                    "reconnecting in {:.0} s (try {attempt})",
                    (at - self.now).max(0.0)
                ),
                colors::DANGER,
            ),
            Some(Link::Failed(why)) => (format!("disconnected: {why}"), colors::DANGER),
            None => ("not connected".to_string(), colors::MUTED),
        };
        line(&mut y, &link.0, 16.0, link.1);
        y += 6.0;
        let Some(v) = self.view.clone() else {
            return ui
                .button("lobby", "Back to the lobby", Rect::new(x, y, w, 36.0))
                .then_some(Route::Lobby);
        };
        let frame = self.current_frame();
        for side in [Side::White, Side::Black] {
            let seat = Seat::of(side, v.swapped);
            let left = frame
                .pieces
                .iter()
                .filter(|(p, _)| p.side() == side)
                .count();
            let you = if Some(seat) == self.you { " (you)" } else { "" };
            let turn = v.to_shoot() == Some(side) && self.playing.is_none();
            draw::checker(vec2(x + 10.0, y + 11.0), 9.0, side, 1.0);
            let c = if turn { colors::ACCENT } else { colors::TEXT };
            ui::text(
                &format!("{}{you}", self.name_of(seat)),
                x + 26.0,
                y,
                20.0,
                c,
            );
            ui::text(&format!("{left}/8"), x + w - 40.0, y, 20.0, colors::TEXT);
            y += 24.0;
            // Rows count from the side's own edge.
            let rank = v.rows.rank(side);
            let row = if side == Side::White {
                rank + 1
            } else {
                8 - rank
            };
            ui::text(
                &format!("on row {row} of 8 from its edge"),
                x + 26.0,
                y,
                15.0,
                colors::MUTED,
            );
            y += 22.0;
        }
        line(
            &mut y,
            &format!("Round {} · shot {}", v.round, v.shots + 1),
            18.0,
            colors::TEXT,
        );
        // Whose turn, and the clock.
        let status = match v.phase {
            Phase::Over { result } => result_text(result, self.my_side()),
            Phase::PieDecision => "Black decides: swap seats or not".to_string(),
            Phase::Shooting if self.playing.is_some() || !self.queue.is_empty() => {
                "...".to_string()
            }
            Phase::Shooting if self.awaiting => "shooting...".to_string(),
            Phase::Shooting if self.my_turn() => "Your turn: drag back from a piece".to_string(),
            Phase::Shooting => format!("{} to shoot", side_name(v.turn)),
        };
        line(&mut y, &status, 18.0, colors::ACCENT);
        if let (Some((_, _, deadline)), Phase::Shooting) = (self.clock, v.phase) {
            let left = (deadline - self.now).max(0.0);
            let c = if left < 10.0 {
                colors::DANGER
            } else {
                colors::TEXT
            };
            line(
                &mut y,
                &format!("clock {}:{:02}", (left / 60.0) as u32, left as u32 % 60),
                18.0,
                c,
            );
        }
        y += 4.0;
        let mut go = None;
        let half = (w - 8.0) / 2.0;
        // Pie rule: Black's seat decides.
        if v.phase == Phase::PieDecision && self.my_side() == Some(Side::Black) {
            if ui.button("pie-swap", "Swap seats", Rect::new(x, y, half, 34.0)) {
                self.send(ClientMessage::PieDecision { swap: true });
            }
            if ui.button("pie-keep", "Keep", Rect::new(x + half + 8.0, y, half, 34.0)) {
                self.send(ClientMessage::PieDecision { swap: false });
            }
            y += 42.0;
        }
        // Invite: the second seat is empty.
        if self.players.second.is_none() && self.you == Some(Seat::First) {
            line(
                &mut y,
                "Waiting for an opponent: send them the link",
                15.0,
                colors::MUTED,
            );
            let link = format!("{}/#/join/{}", self.api.origin, self.match_id);
            if ui.button(
                "copy-link",
                "Copy invitation link",
                Rect::new(x, y, w, 34.0),
            ) {
                platform::copy_text(&link);
                self.notify(format!("copied {link}"));
            }
            y += 42.0;
        }
        let over = matches!(v.phase, Phase::Over { .. });
        if self.you.is_some() && !over {
            if self.confirm_resign {
                if ui.button("resign-yes", "Really resign", Rect::new(x, y, half, 34.0)) {
                    self.send(ClientMessage::Resign);
                    self.confirm_resign = false;
                }
                if ui.button(
                    "resign-no",
                    "Play on",
                    Rect::new(x + half + 8.0, y, half, 34.0),
                ) {
                    self.confirm_resign = false;
                }
            } else if ui.button("resign", "Resign", Rect::new(x, y, half, 34.0)) {
                self.confirm_resign = true;
            }
            y += 42.0;
        }
        if over {
            if self.you.is_some() {
                let theirs = self.rematch_offer.is_some_and(|s| Some(s) != self.you);
                let mine = self.rematch_offer.is_some() && !theirs;
                let label = if theirs {
                    "Accept the rematch"
                } else if mine {
                    "Rematch offered..."
                } else {
                    "Offer a rematch"
                };
                if ui.button_styled("rematch", label, Rect::new(x, y, w, 34.0), !mine, false) {
                    self.send(if theirs {
                        ClientMessage::AcceptRematch
                    } else {
                        ClientMessage::OfferRematch
                    });
                }
                y += 42.0;
            }
            if ui.button("replay", "Watch the replay", Rect::new(x, y, w, 34.0)) {
                go = Some(Route::Replay {
                    match_id: self.match_id.clone(),
                });
            }
            y += 42.0;
        }
        if ui.button("lobby", "Lobby", Rect::new(x, y, half, 34.0)) {
            go = Some(Route::Lobby);
        }
        if ui.button("help", "Rules", Rect::new(x + half + 8.0, y, half, 34.0)) {
            self.help = true;
        }
        y += 46.0;
        // Chat between the seats (spectators read it).
        let chat_top = y;
        for l in &self.chat {
            let shown: String = l.chars().take(60).collect();
            ui::text(&shown, x, y, 15.0, colors::TEXT);
            y += 19.0;
        }
        if self.you.is_some() {
            let y = y
                .max(chat_top + 19.0 * CHAT_LINES as f32)
                .min(area.y + area.h - 44.0);
            let field = Rect::new(x, y, w - 70.0, 32.0);
            let entered = ui.text_field(
                "chat",
                &mut self.chat_draft,
                field,
                "say something...",
                MAX_CHAT_CHARS,
            );
            let send = ui.button("chat-send", "Send", Rect::new(x + w - 62.0, y, 62.0, 32.0));
            if (entered || send) && !self.chat_draft.trim().is_empty() {
                let text = std::mem::take(&mut self.chat_draft);
                self.send(ClientMessage::Chat { text });
            }
        }
        go
    }
}

/// The result as the viewer reads it.
fn result_text(r: MatchResult, me: Option<Side>) -> String {
    match r {
        MatchResult::Draw => "Drawn".to_string(),
        MatchResult::Won { side, reason } => {
            let how = match reason {
                WinReason::FarEdge => "reached the far edge",
                WinReason::QuickMatch => "won the round",
                WinReason::Resignation => "wins by resignation",
                WinReason::Timeouts => "wins: the other side ran out of time three times",
                WinReason::Abandoned => "wins: the other side left",
            };
            match me {
                Some(m) if m == side => format!("You won: {how}"),
                Some(_) => format!("You lost: {} {how}", side_name(side)),
                None => format!("{} {how}", side_name(side)),
            }
        }
    }
}

impl Screen for Play {
    fn frame(&mut self, ui: &mut Ui, dt: f64) -> Option<Route> {
        self.now += dt;
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
        if let Setup::Refused(why) = &self.setup {
            let area = Rect::new(0.0, 0.0, screen_width(), screen_height());
            let box_ = Rect::new(area.w / 2.0 - 220.0, area.h / 2.0 - 90.0, 440.0, 180.0);
            ui::panel(box_);
            ui::text(
                "Could not take the seat",
                box_.x + 16.0,
                box_.y + 14.0,
                22.0,
                colors::ACCENT,
            );
            ui::text(why, box_.x + 16.0, box_.y + 50.0, 16.0, colors::TEXT);
            let b = Rect::new(box_.x + 16.0, box_.y + 120.0, 190.0, 36.0);
            if ui.button("watch", "Watch instead", b) {
                return Some(Route::Watch {
                    match_id: self.match_id.clone(),
                });
            }
            if ui.button("lobby", "Lobby", Rect::new(b.x + 210.0, b.y, 190.0, 36.0)) {
                return Some(Route::Lobby);
            }
            return None;
        }
        let mut go = None;
        if let Some(c) = &mut self.conn {
            for m in c.poll(self.now) {
                if let Some(r) = self.receive(m) {
                    go = Some(r);
                }
            }
        }
        self.advance(dt);
        let (w, h) = (screen_width(), screen_height());
        let (board, panel) = if w >= h * 1.1 {
            let pw = (w * 0.32).clamp(260.0, 360.0);
            (
                Rect::new(0.0, 0.0, w - pw, h),
                Rect::new(w - pw, 0.0, pw, h),
            )
        } else {
            let bh = (h * 0.62).min(w);
            (Rect::new(0.0, 0.0, w, bh), Rect::new(0.0, bh, w, h - bh))
        };
        // The panel first, so its buttons take presses before the board does;
        // with the rules open, neither sees the pointer.
        let help = self.help;
        let nav = if help {
            ui.without_input(|ui| {
                let nav = self.panel(ui, panel);
                self.board(ui, board);
                nav
            })
        } else {
            let nav = self.panel(ui, panel);
            self.board(ui, board);
            nav
        };
        if help {
            self.help = !crate::help::show(ui);
        }
        if let Some((text, until)) = &self.notice {
            if self.now < *until {
                let tw = ui::text_width(text, 18.0) + 24.0;
                let r = Rect::new(board.x + (board.w - tw) / 2.0, board.y + 8.0, tw, 30.0);
                draw_rectangle(r.x, r.y, r.w, r.h, Color::new(0.0, 0.0, 0.0, 0.7));
                ui::text_centred(text, r, 18.0, colors::TEXT);
            }
        }
        go.or(nav)
    }

    fn name(&self) -> &'static str {
        "play"
    }

    fn animating(&self) -> bool {
        self.playing.is_some()
    }

    fn report(&self) -> serde_json::Map<String, serde_json::Value> {
        let mine = self.my_side();
        let pieces: Vec<_> = self
            .drawn
            .iter()
            .map(|(p, c, r)| {
                serde_json::json!({"id": u8::from(*p), "x": c.x, "y": c.y, "r": r,
                    "mine": Some(p.side()) == mine})
            })
            .collect();
        let mut m = serde_json::Map::new();
        m.insert("match_id".into(), self.match_id.clone().into());
        m.insert(
            "seat".into(),
            serde_json::to_value(self.you).unwrap_or_default(),
        );
        m.insert("my_turn".into(), self.my_turn().into());
        m.insert(
            "animating".into(),
            (self.playing.is_some() || !self.queue.is_empty()).into(),
        );
        m.insert(
            "connected".into(),
            self.conn.as_ref().is_some_and(Connection::is_open).into(),
        );
        m.insert(
            "shots".into(),
            self.view.as_ref().map_or(0, |v| v.shots).into(),
        );
        m.insert("pieces".into(), pieces.into());
        m
    }
}
