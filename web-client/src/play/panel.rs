//! What the side panel says and offers, and drawing it: the heading (who
//! you play, the match, the connection), both players with their pieces
//! left and rows, the round and shot, whose turn it is with the clock, the
//! shot log, the buttons the moment allows (the pie decision only to
//! Black's seat, the invitation link while the second seat is empty,
//! resign, rematch, replay, lobby, rules, sound) and the chat. The content
//! is worked out from the match state without drawing ([`content`]), the
//! places from [`super::layout::panel`].
//!
//! Every button has a fixed slot ([`Slot`]), so no button moves when the
//! log grows or the match ends, and none takes the place of the one a
//! finger just pressed: Resign's confirmation, and the rematch after it,
//! stand in other slots than Resign.

use super::layout::{self, PanelLayout, PanelSpec};
use super::state::{phrase_text, MatchState, Mute, LOG_LINES};
use crate::draw;
use crate::i18n::t;
use crate::story::{side_key, side_name};
use crate::ui::{self, colors, Ui};
use game::protocol::{Phrase, MAX_CHAT_CHARS};
use game::{MatchResult, Phase, Seat, Side, WinReason};
use macroquad::prelude::{draw_rectangle, draw_rectangle_lines, vec2, Color, Rect};

/// A line of text and how it shows.
#[derive(Clone, Debug, PartialEq)]
pub struct Line {
    pub text: String,
    pub size: f32,
    pub color: Color,
}

fn line(text: impl Into<String>, size: f32, color: Color) -> Line {
    Line {
        text: text.into(),
        size,
        color,
    }
}

/// One player's row.
#[derive(Clone, Debug, PartialEq)]
pub struct Player {
    pub side: Side,
    /// The name, with " (you)" for this page's seat.
    pub name: String,
    /// Pieces left, of 8.
    pub left: usize,
    /// The row the side stands on, counted from its own edge.
    pub row: u8,
    /// Whether it is this side's turn.
    pub turn: bool,
}

/// A button: its name (what pressing it does), label, whether it can be
/// pressed and its slot.
#[derive(Clone, Debug, PartialEq)]
pub struct Button {
    pub name: &'static str,
    pub label: String,
    pub enabled: bool,
    pub slot: Slot,
}

/// The fixed places of the panel's buttons, in reading order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Slot {
    Lobby,
    Rules,
    Sound,
    /// Resign while the match is on, the replay once it is over.
    Resign,
    /// The first of a question's answers: swap seats, really resign, copy
    /// the invitation. Left empty once the match is over, so a second tap
    /// on "Really resign" hits nothing.
    First,
    /// The second answer: keep, play on; the rematch once the match is over.
    Second,
}

/// How many slots there are.
pub const SLOTS: usize = 6;

fn button(slot: Slot, name: &'static str, label: impl Into<String>, enabled: bool) -> Button {
    Button {
        name,
        label: label.into(),
        enabled,
        slot,
    }
}

/// What the screen knows beside the match state.
#[derive(Clone, Debug)]
pub struct Context<'a> {
    pub match_id: &'a str,
    /// The connection's status line and its colour.
    pub link: (String, Color),
    /// Whether the panel is compact ([`layout::compact`]).
    pub compact: bool,
    /// Whether the player may aim now.
    pub my_turn: bool,
    /// Resign was pressed once and waits to be confirmed.
    pub confirm_resign: bool,
    pub sound: bool,
}

/// Everything the panel shows, top to bottom.
#[derive(Clone, Debug, PartialEq)]
pub struct Content {
    pub head: Vec<Line>,
    /// Both players, once the match is known.
    pub players: Option<[Player; 2]>,
    /// The round, the status and (in a full panel) the clock: always the
    /// same lines, so nothing below them moves.
    pub body: Vec<Line>,
    /// One line above the buttons (empty when there is nothing to say).
    pub hints: Vec<Line>,
    pub buttons: Vec<Button>,
    /// The newest lines of the shot log, shown in their own area below the
    /// buttons, and how many lines that area holds.
    pub log: Vec<Line>,
    pub log_lines: usize,
    /// Whether this page may chat (once the match is known: players and
    /// spectators alike).
    pub chat_field: bool,
}

impl Content {
    /// The layout's spec for this content with `chat` lines of chat.
    pub fn spec(&self, chat: usize) -> PanelSpec {
        PanelSpec {
            head: self.head.iter().map(|l| l.size).collect(),
            players: self.players.is_some(),
            body: self.body.iter().map(|l| l.size).collect(),
            hints: self.hints.iter().map(|l| l.size).collect(),
            buttons: if self.players.is_some() {
                SLOTS
            } else {
                self.buttons.len()
            },
            log: self.log_lines,
            chat,
            chat_field: self.chat_field,
        }
    }
}

/// The panel's content for the match state `s`.
pub fn content(s: &MatchState, cx: &Context) -> Content {
    let compact = cx.compact;
    let role = match s.my_side() {
        Some(side) => t!("play-you-play", side = side_key(side)),
        None => t!("play-watching"),
    };
    let mut head = Vec::new();
    if compact {
        head.push(line(format!("{role} · {}", cx.link.0), 15.0, cx.link.1));
    } else {
        head.push(line(t!("play-heading"), 26.0, colors::ACCENT));
        head.push(line(
            t!("play-role-match", role = role, id = cx.match_id),
            15.0,
            colors::MUTED,
        ));
        head.push(line(cx.link.0.clone(), 15.0, cx.link.1));
    }
    let Some(v) = &s.view else {
        return Content {
            head,
            players: None,
            body: Vec::new(),
            hints: Vec::new(),
            buttons: vec![button(Slot::Lobby, "lobby", t!("play-back-to-lobby"), true)],
            log: Vec::new(),
            log_lines: 0,
            chat_field: false,
        };
    };
    let player = |side: Side| {
        let seat = Seat::of(side, v.swapped);
        let you = Some(seat) == s.you;
        // Rows count from the side's own edge.
        let rank = v.rows.rank(side);
        Player {
            side,
            name: if you {
                t!("play-name-you", name = s.name_of(seat))
            } else {
                s.name_of(seat)
            },
            // Counted on the board at rest: a shot's losses show once
            // its film has run.
            left: v
                .board
                .pieces()
                .iter()
                .filter(|p| p.id.side() == side)
                .count(),
            row: if side == Side::White {
                rank + 1
            } else {
                8 - rank
            },
            turn: v.to_shoot() == Some(side) && s.playing.is_none(),
        }
    };
    let players = [player(Side::White), player(Side::Black)];
    let over = matches!(v.phase, Phase::Over { .. });
    // A friend's match waits for the friend before anyone shoots.
    let waiting = s.you.is_some() && !s.both_seated() && !over;
    let busy = s.busy();
    let mut body = Vec::new();
    let shots = if over && !busy {
        t!("play-round-shots", round = v.round, shots = v.shots)
    } else {
        t!("play-round-shot", round = v.round, shot = v.shots + 1)
    };
    body.push(line(shots, 16.0, colors::TEXT));
    // Whose turn, and the clock.
    let status = match v.phase {
        Phase::Over { result } => result_text(result, s.my_side()),
        Phase::PieDecision => t!("play-pie-decides"),
        Phase::Shooting if waiting => t!("play-waiting-friend"),
        Phase::Shooting if busy => "...".to_string(),
        Phase::Shooting if s.awaiting => t!("play-shooting"),
        Phase::Shooting if cx.my_turn => t!("play-your-turn"),
        Phase::Shooting => t!("play-side-to-shoot", side = side_key(v.turn)),
    };
    let status_color = if cx.my_turn {
        colors::GOOD
    } else {
        colors::ACCENT
    };
    let clock = match (s.clock, v.phase) {
        (Some((_, _, deadline)), Phase::Shooting) => {
            let left = (deadline - s.now).max(0.0);
            Some((
                format!("{}:{:02}", (left / 60.0) as u32, left as u32 % 60),
                left < 10.0,
            ))
        }
        _ => None,
    };
    match (&clock, compact) {
        // In a compact panel the clock ends the status line.
        (Some((c, _)), true) => body.push(line(format!("{status} · {c}"), 17.0, status_color)),
        _ => body.push(line(status, 17.0, status_color)),
    }
    if !compact {
        // The clock's line is kept while there is no clock.
        let (text, color) = match &clock {
            Some((c, true)) => (t!("play-clock", time = c.as_str()), colors::DANGER),
            Some((c, false)) => (t!("play-clock", time = c.as_str()), colors::TEXT),
            None => (String::new(), colors::TEXT),
        };
        body.push(line(text, 16.0, color));
    }
    // The shot log, in its own area.
    let log_lines = if compact { 2 } else { LOG_LINES };
    let log = s
        .log
        .iter()
        .skip(s.log.len().saturating_sub(log_lines))
        .map(|l| line(l.clone(), 14.0, colors::MUTED))
        .collect();
    let mut hint = String::new();
    let mut buttons = Vec::new();
    buttons.push(button(Slot::Lobby, "lobby", t!("lobby"), true));
    buttons.push(button(Slot::Rules, "help", t!("rules-short"), true));
    let sound = if cx.sound {
        t!("play-sound-on")
    } else {
        t!("play-sound-off")
    };
    buttons.push(button(Slot::Sound, "sound", sound, true));
    if s.you.is_some() && !over {
        // Pressed again while its question is open, Resign does nothing.
        let label = if cx.confirm_resign {
            t!("play-resign-asking")
        } else {
            t!("play-resign")
        };
        buttons.push(button(Slot::Resign, "resign", label, !cx.confirm_resign));
    }
    if over {
        buttons.push(button(
            Slot::Resign,
            "replay",
            t!("play-watch-replay"),
            true,
        ));
    }
    if over && s.you.is_some() {
        let (label, enabled) = s.rematch_label();
        buttons.push(button(Slot::Second, "rematch", label, enabled));
    } else if s.you.is_some() && cx.confirm_resign {
        buttons.push(button(
            Slot::First,
            "resign-yes",
            t!("play-resign-yes"),
            true,
        ));
        buttons.push(button(
            Slot::Second,
            "resign-no",
            t!("play-resign-no"),
            true,
        ));
    } else if v.phase == Phase::PieDecision && s.my_side() == Some(Side::Black) {
        // Pie rule: Black's seat decides.
        buttons.push(button(Slot::First, "pie-swap", t!("play-pie-swap"), true));
        buttons.push(button(Slot::Second, "pie-keep", t!("play-pie-keep"), true));
    } else if waiting {
        // Invite: a seat is empty.
        hint = t!("play-invite-hint", id = cx.match_id);
        buttons.push(button(Slot::First, "copy-link", t!("play-copy-link"), true));
    }
    buttons.sort_by_key(|b| b.slot);
    Content {
        head,
        players: Some(players),
        body,
        hints: vec![line(hint, 14.0, colors::MUTED)],
        buttons,
        log,
        log_lines,
        chat_field: true,
    }
}

/// The result as the viewer reads it.
pub fn result_text(r: MatchResult, me: Option<Side>) -> String {
    match r {
        MatchResult::Draw => t!("end-drawn"),
        MatchResult::Won { side, reason } => {
            let how = match reason {
                WinReason::FarEdge => "far-edge",
                WinReason::QuickMatch => "quick",
                WinReason::Resignation => "resignation",
                WinReason::Timeouts => "timeouts",
                WinReason::Abandoned => "abandoned",
            };
            let viewer = match me {
                Some(m) if m == side => "won",
                Some(_) => "lost",
                None => "watching",
            };
            t!(
                "play-result",
                viewer = viewer,
                side = side_name(side),
                how = how
            )
        }
    }
}

/// What the player did in the panel this frame.
#[derive(Debug, Default)]
pub struct Pressed {
    /// The buttons pressed, by name.
    pub buttons: Vec<&'static str>,
    /// A chat line to send.
    pub chat: Option<String>,
    /// A quick phrase to send.
    pub phrase: Option<Phrase>,
}

/// The chat as the panel shows it.
pub struct Chat<'a> {
    /// The lines to show, oldest first (the newest that fit show).
    pub lines: &'a [String],
    /// What the chat's field holds.
    pub draft: &'a mut String,
    /// Whether the menu of quick phrases and mute switches is open.
    pub menu: bool,
    pub mute: Mute,
    /// Whether this page holds a seat (the mute switch names the
    /// opponent) or watches (it names the players).
    pub seated: bool,
}

/// The chat menu's buttons: each quick phrase, then the mute switches,
/// as (name, label).
pub fn menu_buttons(chat: &Chat) -> Vec<(String, String)> {
    let mut b: Vec<(String, String)> = Phrase::ALL
        .iter()
        .map(|p| (format!("phrase-{}", p.code()), phrase_text(*p)))
        .collect();
    let players = match (chat.seated, chat.mute.players) {
        (true, false) => t!("chat-mute-opponent"),
        (true, true) => t!("chat-unmute-opponent"),
        (false, false) => t!("chat-mute-players"),
        (false, true) => t!("chat-unmute-players"),
    };
    let spectators = if chat.mute.spectators {
        t!("chat-unmute-spectators")
    } else {
        t!("chat-mute-spectators")
    };
    b.push(("mute-players".into(), players));
    b.push(("mute-spectators".into(), spectators));
    b
}

/// Draws the panel in `area` with its content and the newest chat lines
/// that fit, the chat field editing the draft, and the chat's menu over
/// the panel while it is open (the panel under it takes no press).
pub fn show(ui: &mut Ui, area: Rect, c: &Content, chat: Chat) -> Pressed {
    ui::panel(area);
    // Every text of the panel stays in it.
    let _inside = ui::bounds(area);
    let l: PanelLayout = layout::panel(area, &c.spec(chat.lines.len()));
    let mut pressed = if chat.menu {
        ui.without_input(|ui| body(ui, c, &l, chat.lines))
    } else {
        body(ui, c, &l, chat.lines)
    };
    let Some(row) = l.chat_field else {
        return pressed;
    };
    if chat.menu {
        let items = menu_buttons(&chat);
        let (menu, rects) = layout::chat_menu(area, &row, items.len());
        draw_rectangle(menu.x, menu.y, menu.w, menu.h, colors::PANEL);
        draw_rectangle_lines(menu.x, menu.y, menu.w, menu.h, 1.5, colors::ACCENT);
        for ((name, label), r) in items.iter().zip(rects) {
            let on = match name.as_str() {
                "mute-players" => chat.mute.players,
                "mute-spectators" => chat.mute.spectators,
                _ => false,
            };
            if ui.button_styled(name, label, r, true, on) {
                match name.as_str() {
                    "mute-players" => pressed.buttons.push("mute-players"),
                    "mute-spectators" => pressed.buttons.push("mute-spectators"),
                    other => {
                        pressed.phrase = other.strip_prefix("phrase-").and_then(Phrase::from_code);
                    }
                }
            }
        }
    }
    let entered = ui.text_field(
        "chat",
        chat.draft,
        row.field,
        &t!("play-chat-placeholder"),
        MAX_CHAT_CHARS,
    );
    let label = if chat.menu {
        t!("chat-close")
    } else {
        t!("chat-phrases")
    };
    if ui.button_styled("chat-phrases", &label, row.phrases, true, chat.menu) {
        pressed.buttons.push("chat-phrases");
    }
    let send = ui.button("chat-send", &t!("play-chat-send"), row.send);
    if (entered || send) && !chat.draft.trim().is_empty() {
        pressed.chat = Some(std::mem::take(chat.draft));
    }
    pressed
}

/// The panel above the chat's row: its lines, players, buttons, the shot
/// log and the chat's lines.
fn body(ui: &mut Ui, c: &Content, l: &PanelLayout, chat: &[String]) -> Pressed {
    // Smaller (down to 12 units) rather than cut.
    let text = |line: &Line, r: Rect| {
        ui::text_in(&line.text, r.x, r.y, line.size, r.w, line.color);
    };
    for (line, r) in c.head.iter().zip(&l.head) {
        text(line, *r);
    }
    for (p, r) in c.players.iter().flatten().zip(&l.players) {
        draw::checker(vec2(r.x + 9.0, r.y + 10.0), 8.0, p.side, 1.0);
        let color = if p.turn { colors::ACCENT } else { colors::TEXT };
        let count = format!("{}/8", p.left);
        let cw = ui::text_width(&count, 18.0);
        let row = t!("play-row-of", row = p.row);
        // The count beside the name, or (a name too long for that, in a
        // narrow panel) beside the row below it, the name taking the
        // whole width; the name smaller rather than cut.
        if ui::text_width(&p.name, 14.0) <= r.w - 30.0 - cw {
            ui::text_in(&p.name, r.x + 22.0, r.y, 18.0, r.w - 30.0 - cw, color);
            ui::text(&count, r.x + r.w - cw, r.y, 18.0, colors::TEXT);
            ui::text_in(
                &row,
                r.x + 22.0,
                r.y + 21.0,
                13.0,
                r.w - 22.0,
                colors::MUTED,
            );
        } else {
            // A name too long for the whole width even at the smallest
            // size ("компьютер (лёгкий)" in half a small phone's panel)
            // gives its second half to the line below, in the row's place.
            let room = r.w - 22.0;
            let (name, row) = match ui::split_in_two(&p.name) {
                Some((a, b)) if ui::text_width(&p.name, ui::MIN_TEXT) > room => {
                    (a.to_string(), b.to_string())
                }
                _ => (p.name.clone(), row),
            };
            ui::text_in(&name, r.x + 22.0, r.y, 18.0, room, color);
            let small = ui::text_width(&count, 13.0);
            ui::text(&count, r.x + r.w - small, r.y + 21.0, 13.0, colors::TEXT);
            let room = r.w - 30.0 - small;
            ui::text_in(&row, r.x + 22.0, r.y + 21.0, 13.0, room, colors::MUTED);
        }
    }
    for (line, r) in c.body.iter().zip(&l.body) {
        text(line, *r);
    }
    for (line, r) in c.hints.iter().zip(&l.hints) {
        text(line, *r);
    }
    let mut pressed = Pressed::default();
    for b in &c.buttons {
        let Some(r) = l.buttons.get(b.slot as usize) else {
            continue;
        };
        if ui.button_styled(b.name, &b.label, *r, b.enabled, false) {
            pressed.buttons.push(b.name);
        }
    }
    for (line, r) in c.log.iter().zip(&l.log) {
        text(line, *r);
    }
    // The chat of players and spectators, above its row.
    for (s, r) in chat.iter().skip(chat.len() - l.chat.len()).zip(&l.chat) {
        ui::text(&ui::fit(s, 14.0, r.w), r.x, r.y, 14.0, colors::TEXT);
    }
    pressed
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::play::state::tests::seated;
    use game::protocol::ServerMessage;

    fn cx(compact: bool) -> Context<'static> {
        Context {
            match_id: "m1",
            link: ("connected".into(), colors::GOOD),
            compact,
            my_turn: false,
            confirm_resign: false,
            sound: false,
        }
    }

    fn names(c: &Content) -> Vec<&'static str> {
        c.buttons.iter().map(|b| b.name).collect()
    }

    fn pie(you: Option<Seat>) -> MatchState {
        let mut s = seated(you);
        s.view.as_mut().unwrap().phase = Phase::PieDecision;
        s
    }

    #[test]
    fn the_pie_decision_is_offered_only_to_blacks_seat() {
        let black = content(&pie(Some(Seat::Second)), &cx(false));
        assert!(names(&black).ends_with(&["pie-swap", "pie-keep"]));
        for you in [Some(Seat::First), None] {
            let c = content(&pie(you), &cx(false));
            assert!(!names(&c).contains(&"pie-swap"), "{you:?}");
            assert_eq!(c.body[1].text, "Black decides: swap seats or not");
        }
        // After a swap, the second seat plays White and no longer decides.
        let mut swapped = pie(Some(Seat::Second));
        swapped.view.as_mut().unwrap().swapped = true;
        assert!(!names(&content(&swapped, &cx(false))).contains(&"pie-swap"));
    }

    #[test]
    fn a_spectator_gets_no_resign_or_rematch_but_the_chat() {
        let c = content(&seated(None), &cx(false));
        assert_eq!(names(&c), ["lobby", "help", "sound"]);
        assert!(c.chat_field);
        assert!(c.head[1].text.starts_with("Watching"));
    }

    #[test]
    fn the_chat_menu_offers_every_phrase_and_names_the_mute_switch_by_role() {
        let mut draft = String::new();
        let mut chat = Chat {
            lines: &[],
            draft: &mut draft,
            menu: true,
            mute: Mute::default(),
            seated: true,
        };
        let b = menu_buttons(&chat);
        assert_eq!(b.len(), Phrase::ALL.len() + 2);
        assert!(b
            .iter()
            .any(|(n, l)| n == "phrase-good-shot" && l == "Good shot!"));
        assert_eq!(b[b.len() - 2].1, "Mute opponent");
        chat.seated = false;
        chat.mute.players = true;
        chat.mute.spectators = true;
        let b = menu_buttons(&chat);
        assert_eq!(b[b.len() - 2].1, "Unmute players");
        assert_eq!(b[b.len() - 1].1, "Unmute spectators");
    }

    #[test]
    fn resigning_asks_to_be_confirmed() {
        let s = seated(Some(Seat::First));
        assert!(names(&content(&s, &cx(false))).contains(&"resign"));
        let confirm = Context {
            confirm_resign: true,
            ..cx(false)
        };
        let c = content(&s, &confirm);
        let n = names(&c);
        assert!(n.contains(&"resign-yes") && n.contains(&"resign-no"));
        // Resign stays where it was, pressed again it does nothing.
        let resign = c.buttons.iter().find(|b| b.name == "resign").unwrap();
        assert!(!resign.enabled);
    }

    #[test]
    fn the_first_seat_alone_is_asked_to_send_the_invitation() {
        let mut s = seated(Some(Seat::First));
        s.players.second = None;
        let c = content(&s, &cx(false));
        assert!(names(&c).contains(&"copy-link"));
        assert_eq!(c.hints.len(), 1);
        assert!(c.hints[0].text.contains("m1"), "{:?}", c.hints);
        assert_eq!(c.body[1].text, "Waiting for your friend to join");
        let mut other = seated(None);
        other.players.second = None;
        assert!(!names(&content(&other, &cx(false))).contains(&"copy-link"));
    }

    #[test]
    fn a_finished_match_offers_the_rematch_as_the_offers_stand() {
        let mut s = seated(Some(Seat::First));
        let result = MatchResult::Won {
            side: Side::White,
            reason: WinReason::Resignation,
        };
        s.view.as_mut().unwrap().phase = Phase::Over { result };
        let c = content(&s, &cx(false));
        assert_eq!(names(&c), ["lobby", "help", "sound", "replay", "rematch"]);
        assert_eq!(c.buttons[4].label, "Offer a rematch");
        assert_eq!(c.body[1].text, "You won: wins by resignation");
        s.receive(ServerMessage::RematchOffered { by: Seat::First });
        let c = content(&s, &cx(false));
        assert_eq!(
            (c.buttons[4].label.as_str(), c.buttons[4].enabled),
            ("Rematch offered...", false)
        );
    }

    #[test]
    fn the_player_whose_turn_it_is_reads_so_and_the_clock_runs() {
        let mut s = seated(Some(Seat::First));
        s.receive(ServerMessage::Clock {
            seat: Seat::First,
            side: Side::White,
            remaining_ms: 65_000,
        });
        let mine = Context {
            my_turn: true,
            ..cx(false)
        };
        let c = content(&s, &mine);
        assert_eq!(c.body[1].text, "Your turn: drag back from a piece");
        assert_eq!(c.body[2].text, "clock 1:05");
        // Compact: the clock ends the status line.
        let c = content(
            &s,
            &Context {
                compact: true,
                ..mine
            },
        );
        assert_eq!(c.body[1].text, "Your turn: drag back from a piece · 1:05");
        let p = c.players.unwrap();
        assert_eq!(
            (p[0].name.as_str(), p[0].left, p[0].turn),
            ("Anka (you)", 8, true)
        );
        assert_eq!(
            (p[1].name.as_str(), p[1].row, p[1].turn),
            ("Petka", 1, false)
        );
    }

    #[test]
    fn before_the_match_is_known_only_the_way_back_is_offered() {
        let s = MatchState::default();
        let c = content(&s, &cx(true));
        assert!(c.players.is_none());
        assert_eq!(names(&c), ["lobby"]);
        assert_eq!(c.head[0].text, "Watching · connected");
    }

    #[test]
    fn every_panel_content_fits_its_layout_on_a_desktop() {
        let (_, area) = layout::split(1100.0, 760.0);
        let c = content(&seated(Some(Seat::First)), &cx(layout::compact(area)));
        let l = layout::panel(area, &c.spec(6));
        assert_eq!(l.head.len(), c.head.len());
        assert_eq!(l.body.len(), c.body.len());
        assert_eq!(l.buttons.len(), SLOTS);
        assert_eq!(l.log.len(), c.log_lines);
        assert_eq!(l.chat.len(), 6);
    }

    fn slot_of(c: &Content, name: &str) -> Option<Slot> {
        c.buttons.iter().find(|b| b.name == name).map(|b| b.slot)
    }

    #[test]
    fn resigns_confirmation_and_the_rematch_never_take_resigns_place() {
        let s = seated(Some(Seat::First));
        let on = content(&s, &cx(false));
        let confirm = content(
            &s,
            &Context {
                confirm_resign: true,
                ..cx(false)
            },
        );
        let resign = slot_of(&on, "resign").unwrap();
        let yes = slot_of(&confirm, "resign-yes").unwrap();
        assert_ne!(yes, resign);
        let mut over = seated(Some(Seat::First));
        over.view.as_mut().unwrap().phase = Phase::Over {
            result: MatchResult::Won {
                side: Side::Black,
                reason: WinReason::Resignation,
            },
        };
        let over = content(&over, &cx(false));
        let rematch = slot_of(&over, "rematch").unwrap();
        assert!(rematch != resign && rematch != yes);
        // Nothing waits under the finger that pressed "Really resign".
        assert!(over.buttons.iter().all(|b| b.slot != yes));
    }

    #[test]
    fn the_buttons_keep_their_places_as_the_log_grows_and_the_match_ends() {
        for compact in [false, true] {
            let (_, area) = if compact {
                layout::split(390.0, 844.0)
            } else {
                layout::split(1280.0, 800.0)
            };
            let mut s = seated(Some(Seat::First));
            let first = content(&s, &cx(compact));
            for i in 0..6 {
                s.log.push_back(format!("shot {i}"));
            }
            let long = content(&s, &cx(compact));
            s.view.as_mut().unwrap().phase = Phase::Over {
                result: MatchResult::Draw,
            };
            let over = content(&s, &cx(compact));
            let place = |c: &Content, name: &str| {
                let l = layout::panel(area, &c.spec(3));
                l.buttons[slot_of(c, name).unwrap() as usize]
            };
            for name in ["lobby", "help", "sound"] {
                assert_eq!(place(&first, name), place(&long, name), "{name}");
                assert_eq!(place(&first, name), place(&over, name), "{name}");
            }
            assert_eq!(place(&first, "resign"), place(&long, "resign"));
            assert_eq!(long.log.len(), long.log_lines);
            assert_eq!(first.body.len(), long.body.len());
        }
    }
}
