//! A live match, played or watched: the connection, the announcements
//! queued and animated in order from their exact films, the slingshot for
//! the player whose turn it is, the side panel (players, round, rows,
//! pieces left, the turn clock, the shot log, the pie decision, resign,
//! rematch, sound, chat, the invitation link) and the end-of-match screen.
//!
//! In a wide window the panel stands to the right of the board; in a tall
//! one (a phone held upright) the board takes the full width at the top
//! and the panel lies below it. A player who opens an invitation link
//! without a name is asked for one before taking the seat.

use crate::aim::{self, Aim, Slingshot};
use crate::api::{token_key, Api, Pending, SeatGrant};
use crate::clip::{Clip, Frame};
use crate::connection::{Connection, Link};
use crate::route::{ws_origin, Route};
use crate::screen::Screen;
use crate::story::{self, side_name, Score};
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

/// A drag in progress from one of the player's pieces.
struct Drag {
    piece: PieceId,
    from: DVec2,
    pointer: DVec2,
}

/// How long the "your turn" cue shows after the turn comes, in seconds.
const TURN_CUE: f64 = 1.6;

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
    /// The slingshot's power and the meter's rectangle while aiming.
    aiming: Option<(f64, Rect)>,
    /// The board's map this frame (the slingshot reads the pointer with it).
    viewport: Option<Viewport>,
    /// One line per shot shown, newest last.
    log: VecDeque<String>,
    /// The outcomes of the shots seen (the end screen's score).
    outcomes: Vec<game::ShotOutcome>,
    /// The whole match's score, from the record the server sent at its end.
    final_score: Option<Score>,
    /// The end-of-match screen was closed.
    end_closed: bool,
    /// Short sounds on (off by default; remembered by the browser).
    sound: bool,
    /// Whether it was the player's turn last frame, and since when it is.
    was_my_turn: bool,
    turn_since: f64,
}

const CHAT_LINES: usize = 6;
const LOG_LINES: usize = 4;
const SOUND_KEY: &str = "chapaev.sound";
const NAME_KEY: &str = "chapaev.name";

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
            viewport: None,
            aiming: None,
            log: VecDeque::new(),
            outcomes: Vec::new(),
            final_score: None,
            end_closed: false,
            sound: platform::storage_get(SOUND_KEY).as_deref() == Some("on"),
            was_my_turn: false,
            turn_since: 0.0,
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
                    let line = story::shot_line(&outcome, self.my_side(), true);
                    self.log.push_back(line);
                    while self.log.len() > LOG_LINES {
                        self.log.pop_front();
                    }
                    if self.sound {
                        platform::beep(platform::Sound::Flick);
                        if !outcome.knocked_off.is_empty() {
                            platform::beep(platform::Sound::Fall);
                        }
                    }
                    self.outcomes.push(outcome.clone());
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
                ServerMessage::MatchOver { result, record } => {
                    // The last shot's line was written while the match
                    // went on: after a resignation or forfeit nobody
                    // shoots again.
                    let me = self.my_side();
                    if let (Some(o), Some(line)) = (self.outcomes.last(), self.log.back_mut()) {
                        *line = story::shot_line(o, me, false);
                    }
                    if let Some(v) = &self.view {
                        self.view = Some(v.after_result(result));
                    }
                    // The record has every shot, also those played before
                    // this page connected.
                    self.final_score = game::Replay::new(record)
                        .ok()
                        .map(|r| Score::of((0..r.shot_count()).filter_map(|n| r.outcome(n))));
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

    /// The board and the pieces (drawn first: the panel covers what slides
    /// off the board towards it).
    fn board(&mut self, area: Rect) {
        let Some(v) = self.view.clone() else {
            self.viewport = None;
            ui::text_centred("Connecting to the match...", area, 22.0, colors::MUTED);
            return;
        };
        let flipped = self.my_side() == Some(Side::Black);
        let vp = Viewport::fit_square(
            v.config.board_size(),
            area,
            area.w.min(area.h) * 0.06,
            flipped,
        );
        self.viewport = Some(vp);
        let can_aim = self.my_turn();
        // Your turn: the board's frame glows for a moment, then stays lit.
        if can_aim {
            let a = vp.to_screen(DVec2::ZERO);
            let b = vp.to_screen(DVec2::splat(v.config.board_size()));
            let (x0, y0) = (a.x.min(b.x), a.y.min(b.y));
            let side = (a.x - b.x).abs();
            let pad = side * 0.045 + 5.0;
            let fresh = (1.0 - (self.now - self.turn_since) as f32 / 1.5).max(0.0);
            let pulse = 0.35 + 0.65 * fresh * (0.5 + 0.5 * (self.now as f32 * 9.0).sin());
            draw_rectangle_lines(
                x0 - pad,
                y0 - pad,
                side + 2.0 * pad,
                side + 2.0 * pad,
                4.0,
                Color::new(0.45, 0.85, 0.40, pulse),
            );
        }
        draw::board(&vp, v.config.board_size());
        let frame = self.current_frame();
        let mine = self.my_side();
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
        if can_aim && self.now - self.turn_since < TURN_CUE {
            let msg = Rect::new(
                area.x + area.w / 2.0 - 80.0,
                area.y + area.h / 2.0 - 24.0,
                160.0,
                48.0,
            );
            let k = ((TURN_CUE - (self.now - self.turn_since)) as f32).min(1.0);
            draw_rectangle(
                msg.x,
                msg.y,
                msg.w,
                msg.h,
                Color::new(0.0, 0.0, 0.0, 0.6 * k),
            );
            ui::text_centred("Your turn", msg, 24.0, Color::new(0.55, 0.95, 0.5, k));
        }
    }

    /// The slingshot: takes presses the panel left, draws the pull, the
    /// arrow and the power meter (kept inside the window), shoots on release.
    fn aim(&mut self, ui: &mut Ui) {
        self.aiming = None;
        let (Some(vp), Some(v)) = (self.viewport, self.view.clone()) else {
            return;
        };
        if !self.my_turn() {
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
        // The window in world metres: the pull's reach ends at its edge.
        let window = crate::scale::size();
        let (c0, c1) = (vp.to_world(vec2(0.0, 0.0)), vp.to_world(window));
        let room = aim::room_along(drag.from, drag.pointer - drag.from, c0.min(c1), c0.max(c1));
        let sling = Slingshot {
            radius: v.config.piece_radius,
            full_pull: aim::full_pull(v.config.square, v.config.piece_radius, room),
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
                // The power meter beside the pointer, inside the window.
                let meter = meter_rect(p, window);
                self.aiming = Some((
                    power,
                    Rect::new(meter.x - 4.0, meter.y - 4.0, 62.0, meter.h + 8.0),
                ));
                draw_rectangle(
                    meter.x - 4.0,
                    meter.y - 4.0,
                    62.0,
                    meter.h + 8.0,
                    Color::new(0.0, 0.0, 0.0, 0.55),
                );
                draw_rectangle(
                    meter.x,
                    meter.y,
                    meter.w,
                    meter.h,
                    Color::new(1.0, 1.0, 1.0, 0.12),
                );
                let h = meter.h * power as f32;
                draw_rectangle(meter.x, meter.y + meter.h - h, meter.w, h, col);
                ui::text(
                    &format!("{:.0}%", power * 100.0),
                    meter.x + meter.w + 4.0,
                    meter.y + meter.h / 2.0 - 8.0,
                    15.0,
                    colors::TEXT,
                );
            }
            Aim::Cancel => {
                let msg = "release here to cancel";
                let tw = ui::text_width(msg, 16.0);
                let x = (p.x + 14.0).min(window.x - tw - 6.0).max(4.0);
                let y = (p.y - 30.0).clamp(4.0, window.y - 24.0);
                ui::text(msg, x, y, 16.0, colors::MUTED);
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

    /// The side panel; `compact` in a tall window's lower part.
    fn panel(&mut self, ui: &mut Ui, area: Rect) -> Option<Route> {
        ui::panel(area);
        let compact = area.w > area.h * 0.75 || area.h < 560.0;
        let x = area.x + 12.0;
        let w = area.w - 24.0;
        let bottom = area.y + area.h - 8.0;
        let mut y = area.y + 10.0;
        let row = ui::TOUCH;
        let gap = 8.0;
        let line = |y: &mut f32, s: &str, size: f32, c: Color| {
            ui::text(&ui::fit(s, size, w), x, *y, size, c);
            *y += size + 5.0;
        };
        let role = match self.my_side() {
            Some(s) => format!("You play {}", side_name(s)),
            None => "Watching".to_string(),
        };
        if !compact {
            line(&mut y, "Chapaev", 26.0, colors::ACCENT);
            line(
                &mut y,
                &format!("{role} · match {}", self.match_id),
                15.0,
                colors::MUTED,
            );
        }
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
        if compact {
            line(&mut y, &format!("{role} · {}", link.0), 15.0, link.1);
        } else {
            line(&mut y, &link.0, 15.0, link.1);
        }
        y += 4.0;
        let Some(v) = self.view.clone() else {
            return ui
                .button("lobby", "Back to the lobby", Rect::new(x, y, w, row))
                .then_some(Route::Lobby);
        };
        let frame = self.current_frame();
        let half = (w - gap) / 2.0;
        for (i, side) in [Side::White, Side::Black].into_iter().enumerate() {
            let seat = Seat::of(side, v.swapped);
            let left = frame
                .pieces
                .iter()
                .filter(|(p, _)| p.side() == side)
                .count();
            let you = if Some(seat) == self.you { " (you)" } else { "" };
            let turn = v.to_shoot() == Some(side) && self.playing.is_none();
            // Rows count from the side's own edge.
            let rank = v.rows.rank(side);
            let row_no = if side == Side::White {
                rank + 1
            } else {
                8 - rank
            };
            let (px, pw) = if compact {
                (x + i as f32 * (half + gap), half)
            } else {
                (x, w)
            };
            draw::checker(vec2(px + 9.0, y + 10.0), 8.0, side, 1.0);
            let c = if turn { colors::ACCENT } else { colors::TEXT };
            let count = format!("{left}/8");
            let cw = ui::text_width(&count, 18.0);
            ui::text(
                &ui::fit(
                    &format!("{}{you}", self.name_of(seat)),
                    18.0,
                    pw - 30.0 - cw,
                ),
                px + 22.0,
                y,
                18.0,
                c,
            );
            ui::text(&count, px + pw - cw, y, 18.0, colors::TEXT);
            ui::text(
                &format!("row {row_no} of 8"),
                px + 22.0,
                y + 21.0,
                13.0,
                colors::MUTED,
            );
            if !compact {
                y += 40.0;
            }
        }
        if compact {
            y += 40.0;
        }
        let over = matches!(v.phase, Phase::Over { .. });
        let busy = self.playing.is_some() || !self.queue.is_empty();
        let shots = if over && !busy {
            format!("Round {} · {}", v.round, story::count(v.shots, "shot"))
        } else {
            format!("Round {} · shot {}", v.round, v.shots + 1)
        };
        line(&mut y, &shots, 16.0, colors::TEXT);
        // Whose turn, and the clock.
        let status = match v.phase {
            Phase::Over { result } => result_text(result, self.my_side()),
            Phase::PieDecision => "Black decides: swap seats or not".to_string(),
            Phase::Shooting if busy => "...".to_string(),
            Phase::Shooting if self.awaiting => "shooting...".to_string(),
            Phase::Shooting if self.my_turn() => "Your turn: drag back from a piece".to_string(),
            Phase::Shooting => format!("{} to shoot", side_name(v.turn)),
        };
        let status_color = if self.my_turn() {
            colors::GOOD
        } else {
            colors::ACCENT
        };
        let clock = match (self.clock, v.phase) {
            (Some((_, _, deadline)), Phase::Shooting) => {
                let left = (deadline - self.now).max(0.0);
                Some((
                    format!("{}:{:02}", (left / 60.0) as u32, left as u32 % 60),
                    left < 10.0,
                ))
            }
            _ => None,
        };
        match (&clock, compact) {
            // In a compact panel the clock ends the status line.
            (Some((c, _)), true) => line(&mut y, &format!("{status} · {c}"), 17.0, status_color),
            _ => line(&mut y, &status, 17.0, status_color),
        }
        if let (Some((c, urgent)), false) = (&clock, compact) {
            let color = if *urgent {
                colors::DANGER
            } else {
                colors::TEXT
            };
            line(&mut y, &format!("clock {c}"), 16.0, color);
        }
        // The shot log.
        let log_lines = if compact { 2 } else { LOG_LINES };
        for l in self
            .log
            .iter()
            .skip(self.log.len().saturating_sub(log_lines))
        {
            line(&mut y, l, 14.0, colors::MUTED);
        }
        y += 2.0;
        let mut go = None;
        let mut buttons: Vec<(&str, String, bool)> = Vec::new();
        // Pie rule: Black's seat decides.
        if v.phase == Phase::PieDecision && self.my_side() == Some(Side::Black) {
            buttons.push(("pie-swap", "Swap seats".into(), true));
            buttons.push(("pie-keep", "Keep".into(), true));
        }
        // Invite: the second seat is empty.
        let inviting = self.players.second.is_none() && self.you == Some(Seat::First);
        if inviting {
            line(
                &mut y,
                "Waiting for an opponent: send them the link",
                14.0,
                colors::MUTED,
            );
            buttons.push(("copy-link", "Copy invitation link".into(), true));
        }
        if self.you.is_some() && !over {
            if self.confirm_resign {
                buttons.push(("resign-yes", "Really resign".into(), true));
                buttons.push(("resign-no", "Play on".into(), true));
            } else {
                buttons.push(("resign", "Resign".into(), true));
            }
        }
        if over {
            if self.you.is_some() {
                let (label, enabled) = self.rematch_label();
                buttons.push(("rematch", label.into(), enabled));
            }
            buttons.push(("replay", "Watch the replay".into(), true));
        }
        buttons.push(("lobby", "Lobby".into(), true));
        buttons.push(("help", "Rules".into(), true));
        let sound = if self.sound {
            "Sound: on"
        } else {
            "Sound: off"
        };
        buttons.push(("sound", sound.into(), true));
        // Two to a row (three in a wide compact panel).
        let per_row = if compact && w > 520.0 { 3 } else { 2 };
        let bw = (w - gap * (per_row - 1) as f32) / per_row as f32;
        for (i, (name, label, enabled)) in buttons.iter().enumerate() {
            let (c, r) = ((i % per_row) as f32, (i / per_row) as f32);
            let rect = Rect::new(x + c * (bw + gap), y + r * (row + gap), bw, row);
            if ui.button_styled(name, label, rect, *enabled, false) {
                go = go.or(self.press(name, &v));
            }
        }
        y += buttons.len().div_ceil(per_row) as f32 * (row + gap) + 4.0;
        // Chat between the seats (spectators read it), above its field.
        let field_y = bottom - row;
        let seated = self.you.is_some();
        let chat_bottom = if seated { field_y - 4.0 } else { bottom };
        let fit_lines = ((chat_bottom - y) / 18.0).floor().max(0.0) as usize;
        let shown = self.chat.len().min(fit_lines).min(CHAT_LINES);
        let mut cy = chat_bottom - shown as f32 * 18.0;
        for l in self.chat.iter().skip(self.chat.len() - shown) {
            ui::text(&ui::fit(l, 14.0, w), x, cy, 14.0, colors::TEXT);
            cy += 18.0;
        }
        if seated && field_y >= y {
            let field = Rect::new(x, field_y, w - 78.0, row);
            let entered = ui.text_field(
                "chat",
                &mut self.chat_draft,
                field,
                "say something...",
                MAX_CHAT_CHARS,
            );
            let send = ui.button(
                "chat-send",
                "Send",
                Rect::new(x + w - 70.0, field_y, 70.0, row),
            );
            if (entered || send) && !self.chat_draft.trim().is_empty() {
                let text = std::mem::take(&mut self.chat_draft);
                self.send(ClientMessage::Chat { text });
            }
        }
        go
    }

    /// The rematch button's label, and whether it can be pressed.
    fn rematch_label(&self) -> (&'static str, bool) {
        let theirs = self.rematch_offer.is_some_and(|s| Some(s) != self.you);
        let mine = self.rematch_offer.is_some() && !theirs;
        if theirs {
            ("Accept the rematch", true)
        } else if mine {
            ("Rematch offered...", false)
        } else {
            ("Offer a rematch", true)
        }
    }

    /// What a panel or end-screen button does.
    fn press(&mut self, name: &str, v: &MatchView) -> Option<Route> {
        let _ = v;
        match name {
            "pie-swap" => {
                self.send(ClientMessage::PieDecision { swap: true });
            }
            "pie-keep" => {
                self.send(ClientMessage::PieDecision { swap: false });
            }
            "copy-link" => {
                let link = format!("{}/#/join/{}", self.api.origin, self.match_id);
                platform::copy_text(&link);
                self.notify(format!("copied {link}"));
            }
            "resign" => self.confirm_resign = true,
            "resign-yes" => {
                self.send(ClientMessage::Resign);
                self.confirm_resign = false;
            }
            "resign-no" => self.confirm_resign = false,
            "rematch" | "end-rematch" => {
                let theirs = self.rematch_offer.is_some_and(|s| Some(s) != self.you);
                self.send(if theirs {
                    ClientMessage::AcceptRematch
                } else {
                    ClientMessage::OfferRematch
                });
            }
            "replay" | "end-replay" => {
                return Some(Route::Replay {
                    match_id: self.match_id.clone(),
                })
            }
            "lobby" | "end-lobby" => return Some(Route::Lobby),
            "help" => self.help = true,
            "sound" => {
                self.sound = !self.sound;
                platform::storage_set(SOUND_KEY, if self.sound { "on" } else { "off" });
                if self.sound {
                    platform::beep(platform::Sound::YourTurn);
                }
            }
            "end-close" => self.end_closed = true,
            _ => {}
        }
        None
    }

    /// The end-of-match screen over the board: the result, the rounds, the
    /// shots, and one press to a rematch, the replay or the lobby.
    fn end_screen(&mut self, ui: &mut Ui, area: Rect) -> Option<Route> {
        let v = self.view.clone()?;
        let Phase::Over { result } = v.phase else {
            return None;
        };
        if self.end_closed || self.playing.is_some() || !self.queue.is_empty() {
            return None;
        }
        let pw = (area.w - 24.0).min(420.0);
        let seated = self.you.is_some();
        let ph = 150.0 + (ui::TOUCH + 8.0) * if seated { 2.0 } else { 1.0 } + 8.0;
        let r = Rect::new(
            area.x + (area.w - pw) / 2.0,
            area.y + (area.h - ph) / 2.0,
            pw,
            ph,
        );
        draw_rectangle(
            r.x - 4.0,
            r.y - 4.0,
            r.w + 8.0,
            r.h + 8.0,
            Color::new(0.0, 0.0, 0.0, 0.45),
        );
        ui::panel(r);
        let x = r.x + 16.0;
        let w = r.w - 32.0;
        let (title, color) = match (result.winner(), self.my_side()) {
            (None, _) => ("Drawn".to_string(), colors::TEXT),
            (Some(wn), Some(me)) if wn == me => ("You won!".to_string(), colors::GOOD),
            (Some(_), Some(_)) => ("You lost".to_string(), colors::DANGER),
            (Some(wn), None) => (format!("{} won", side_name(wn)), colors::ACCENT),
        };
        ui::text(&title, x, r.y + 14.0, 30.0, color);
        ui::text(
            &ui::fit(&result_reason(result), 15.0, w),
            x,
            r.y + 54.0,
            15.0,
            colors::MUTED,
        );
        let score = self
            .final_score
            .clone()
            .unwrap_or_else(|| Score::of(&self.outcomes));
        ui::text(
            &ui::fit(&score.rounds_line(), 17.0, w),
            x,
            r.y + 80.0,
            17.0,
            colors::TEXT,
        );
        ui::text(
            &format!(
                "{} · {}",
                story::count(v.shots, "shot"),
                story::count(v.round, "round")
            ),
            x,
            r.y + 104.0,
            17.0,
            colors::TEXT,
        );
        let mut y = r.y + 138.0;
        let half = (w - 8.0) / 2.0;
        let mut go = None;
        let mut pressed = Vec::new();
        if seated {
            let (label, enabled) = self.rematch_label();
            if ui.button_styled(
                "end-rematch",
                label,
                Rect::new(x, y, w, ui::TOUCH),
                enabled,
                false,
            ) {
                pressed.push("end-rematch");
            }
            y += ui::TOUCH + 8.0;
        }
        if ui.button("end-replay", "Replay", Rect::new(x, y, half, ui::TOUCH)) {
            pressed.push("end-replay");
        }
        if ui.button(
            "end-close",
            "Close",
            Rect::new(x + half + 8.0, y, half, ui::TOUCH),
        ) {
            pressed.push("end-close");
        }
        for name in pressed {
            go = go.or(self.press(name, &v));
        }
        go
    }
}

/// Where the power meter goes: beside the pointer, moved inside `window`.
fn meter_rect(pointer: Vec2, window: Vec2) -> Rect {
    let (w, h) = (12.0, 64.0);
    let mut x = pointer.x + 22.0;
    if x + 58.0 > window.x {
        x = pointer.x - 22.0 - 58.0;
    }
    let y = (pointer.y - h / 2.0).clamp(8.0, (window.y - h - 8.0).max(8.0));
    Rect::new(x.clamp(8.0, (window.x - 62.0).max(8.0)), y, w, h)
}

/// The board's and the panel's areas in a `w` x `h` window: side by side
/// when it is wide, the board on top at full width when it is tall.
fn layout(w: f32, h: f32) -> (Rect, Rect) {
    if w >= h * 1.1 {
        let pw = (w * 0.32).clamp(270.0, 380.0);
        (
            Rect::new(0.0, 0.0, w - pw, h),
            Rect::new(w - pw, 0.0, pw, h),
        )
    } else {
        let bh = w.min(h * 0.56);
        (Rect::new(0.0, 0.0, w, bh), Rect::new(0.0, bh, w, h - bh))
    }
}

/// How the match was decided, in words for the end screen.
fn result_reason(r: MatchResult) -> String {
    match r {
        MatchResult::Draw => "Both sides' last pieces fell together".to_string(),
        MatchResult::Won { side, reason } => {
            let how = match reason {
                WinReason::FarEdge => "reached the far edge",
                WinReason::QuickMatch => "won the round",
                WinReason::Resignation => "won by resignation",
                WinReason::Timeouts => "won: the other side ran out of time three times",
                WinReason::Abandoned => "won: the other side left",
            };
            format!("{} {how}", side_name(side))
        }
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
        let window = crate::scale::size();
        if let Setup::Naming(draft) = &mut self.setup {
            let bw = (window.x - 24.0).min(440.0);
            let box_ = Rect::new((window.x - bw) / 2.0, (window.y - 200.0) / 2.0, bw, 200.0);
            ui::panel(box_);
            let (x, w) = (box_.x + 16.0, box_.w - 32.0);
            ui::text(
                "You are invited to a match",
                x,
                box_.y + 14.0,
                21.0,
                colors::ACCENT,
            );
            ui::text("Your name", x, box_.y + 48.0, 16.0, colors::TEXT);
            let field = Rect::new(x, box_.y + 72.0, w, ui::TOUCH);
            let entered = ui.text_field("join-name", draft, field, "Player", 40);
            let half = (w - 8.0) / 2.0;
            let b = Rect::new(x, box_.y + 136.0, half, ui::TOUCH);
            if ui.button("join-name-ok", "Take the seat", b) || entered {
                let name = crate::lobby::clean_name(draft);
                platform::storage_set(NAME_KEY, &name);
                self.setup = Setup::Joining(self.api.join(&self.match_id, &name));
                self.name = name;
            } else if ui.button(
                "watch",
                "Just watch",
                Rect::new(b.x + half + 8.0, b.y, half, b.h),
            ) {
                return Some(Route::Watch {
                    match_id: self.match_id.clone(),
                });
            }
            return None;
        }
        if let Setup::Refused(why) = &self.setup {
            let bw = (window.x - 24.0).min(440.0);
            let box_ = Rect::new((window.x - bw) / 2.0, (window.y - 190.0) / 2.0, bw, 190.0);
            ui::panel(box_);
            let (x, w) = (box_.x + 16.0, box_.w - 32.0);
            ui::text(
                "Could not take the seat",
                x,
                box_.y + 14.0,
                21.0,
                colors::ACCENT,
            );
            ui::text(&ui::fit(why, 15.0, w), x, box_.y + 50.0, 15.0, colors::TEXT);
            let half = (w - 8.0) / 2.0;
            let b = Rect::new(x, box_.y + 126.0, half, ui::TOUCH);
            if ui.button("watch", "Watch instead", b) {
                return Some(Route::Watch {
                    match_id: self.match_id.clone(),
                });
            }
            if ui.button(
                "lobby",
                "Lobby",
                Rect::new(b.x + half + 8.0, b.y, half, b.h),
            ) {
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
        let (w, h) = (window.x, window.y);
        let (board, panel) = layout(w, h);
        // Your turn: a cue (and a sound, if on) when it comes.
        let my_turn = self.my_turn();
        if my_turn && !self.was_my_turn {
            self.turn_since = self.now;
            if self.sound {
                platform::beep(platform::Sound::YourTurn);
            }
        }
        self.was_my_turn = my_turn;
        // The board first (the panel covers what slides off it), then the
        // panel and the end screen, whose buttons take presses before the
        // slingshot does; with the rules open, nothing sees the pointer.
        self.board(board);
        let help = self.help;
        let nav = if help {
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
        if let Some((text, until)) = &self.notice {
            if self.now < *until {
                let shown = ui::fit(text, 16.0, board.w - 40.0);
                let tw = ui::text_width(&shown, 16.0) + 24.0;
                let r = Rect::new(board.x + (board.w - tw) / 2.0, board.y + 6.0, tw, 28.0);
                draw_rectangle(r.x, r.y, r.w, r.h, Color::new(0.0, 0.0, 0.0, 0.7));
                ui::text_centred(&shown, r, 16.0, colors::TEXT);
            }
        }
        go.or(nav)
    }

    fn name(&self) -> &'static str {
        "play"
    }

    /// A shot playing, or the "your turn" cue pulsing.
    fn animating(&self) -> bool {
        self.playing.is_some() || self.now - self.turn_since < TURN_CUE
    }

    fn report(&self) -> serde_json::Map<String, serde_json::Value> {
        let mine = self.my_side();
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
        if let Some((power, meter)) = self.aiming {
            let r = crate::scale::css(meter);
            m.insert("aim_power".into(), power.into());
            m.insert("meter".into(), serde_json::json!([r.x, r.y, r.w, r.h]));
        }
        m.insert(
            "log".into(),
            self.log.iter().cloned().collect::<Vec<_>>().into(),
        );
        m.insert(
            "end_screen".into(),
            matches!(
                self.view.as_ref().map(|v| v.phase),
                Some(Phase::Over { .. })
            )
            .into(),
        );
        m
    }
}
