//! Where everything of the match screen goes, as pure functions from
//! sizes and counts to rectangles (layout units): the board's and the
//! panel's areas in the window, every line, player, button and the chat
//! within the panel, the end-of-match box over the board, the power meter
//! beside the pointer and the boxes asking for a name. Nothing here draws,
//! so all of it is tested natively.

use crate::ui::TOUCH;
use macroquad::prelude::{Rect, Vec2};

/// Room between buttons.
const GAP: f32 = 8.0;
/// A player's row in the panel, and how far the next one starts below.
const PLAYER_H: f32 = 36.0;
const PLAYER_STEP: f32 = 40.0;
/// A chat line's height.
const CHAT_LINE: f32 = 18.0;
/// The chat's send button's width (room for "Отправить" at a size near
/// its neighbours': a row's labels share the smallest size).
const SEND_W: f32 = 96.0;
/// The width of the chat's button that opens the quick phrases.
const PHRASES_W: f32 = 84.0;

/// The board's and the panel's areas in a `w` x `h` window: side by side
/// when it is wide, the board on top at full width when it is tall.
pub fn split(w: f32, h: f32) -> (Rect, Rect) {
    if w >= h * 1.1 {
        let pw = (w * 0.32).clamp(270.0, 380.0);
        (
            Rect::new(0.0, 0.0, w - pw, h),
            Rect::new(w - pw, 0.0, pw, h),
        )
    } else {
        // The panel keeps 300 units at least (a small phone's board gives
        // them up), room for its lines, buttons and shot log.
        let bh = w.min(h * 0.56).min(h - 300.0);
        (Rect::new(0.0, 0.0, w, bh), Rect::new(0.0, bh, w, h - bh))
    }
}

/// Whether the panel in `area` is compact (a tall window's lower part, or
/// a short one): the title is left out, the players stand side by side,
/// the clock ends the status line and fewer log lines show.
pub fn compact(area: Rect) -> bool {
    area.w > area.h * 0.75 || area.h < 560.0
}

/// What the panel holds, in order from the top: the heading lines' text
/// sizes, whether the players' rows follow (only once the match is known;
/// without it a single button to the lobby), the lines below them, hint
/// lines above the buttons, the buttons' slots, the shot log's lines (its
/// own area below the buttons, so the buttons never move as it grows), the
/// chat lines there are and whether the chat's field shows (for a seated
/// player).
#[derive(Clone, Debug, Default)]
pub struct PanelSpec {
    pub head: Vec<f32>,
    pub players: bool,
    pub body: Vec<f32>,
    pub hints: Vec<f32>,
    pub buttons: usize,
    pub log: usize,
    pub chat: usize,
    pub chat_field: bool,
}

/// Where the panel's parts go. A text line's rectangle is its top-left
/// corner, the width it may take and its text size as height.
#[derive(Clone, Debug, Default)]
pub struct PanelLayout {
    pub head: Vec<Rect>,
    pub players: Vec<Rect>,
    pub body: Vec<Rect>,
    pub hints: Vec<Rect>,
    pub buttons: Vec<Rect>,
    pub log: Vec<Rect>,
    pub chat: Vec<Rect>,
    /// The chat's row: its text field, the quick phrases' button and Send.
    pub chat_field: Option<ChatRow>,
}

/// The chat's row at the panel's foot.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChatRow {
    pub field: Rect,
    /// Opens (and closes) the quick phrases and the mute switches.
    pub phrases: Rect,
    pub send: Rect,
}

#[cfg(test)]
impl PanelLayout {
    /// Every rectangle laid out.
    pub fn all(&self) -> Vec<Rect> {
        let mut all: Vec<Rect> = [
            &self.head,
            &self.players,
            &self.body,
            &self.hints,
            &self.buttons,
            &self.log,
            &self.chat,
        ]
        .into_iter()
        .flatten()
        .copied()
        .collect();
        if let Some(row) = self.chat_field {
            all.extend([row.field, row.phrases, row.send]);
        }
        all
    }
}

/// Lines of the given text sizes from `y` down, each `size + 5` below the
/// last.
fn lines(sizes: &[f32], x: f32, w: f32, y: &mut f32) -> Vec<Rect> {
    sizes
        .iter()
        .map(|&size| {
            let r = Rect::new(x, *y, w, size);
            *y += size + 5.0;
            r
        })
        .collect()
}

/// The panel's parts in `area`. Buttons are two to a row (three in a wide
/// compact panel, or a short one as wide as a small phone); the chat sits at the bottom, as many of its lines as
/// fit between the buttons and its field.
pub fn panel(area: Rect, spec: &PanelSpec) -> PanelLayout {
    let compact = compact(area);
    let x = area.x + 12.0;
    let w = area.w - 24.0;
    let bottom = area.y + area.h - 8.0;
    let mut y = area.y + 10.0;
    let mut l = PanelLayout {
        head: lines(&spec.head, x, w, &mut y),
        ..PanelLayout::default()
    };
    y += 4.0;
    if !spec.players {
        l.buttons = (0..spec.buttons.min(1))
            .map(|_| Rect::new(x, y, w, TOUCH))
            .collect();
        return l;
    }
    let half = (w - GAP) / 2.0;
    for i in 0..2 {
        if compact {
            l.players
                .push(Rect::new(x + i as f32 * (half + GAP), y, half, PLAYER_H));
        } else {
            l.players.push(Rect::new(x, y, w, PLAYER_H));
            y += PLAYER_STEP;
        }
    }
    if compact {
        y += PLAYER_STEP;
    }
    l.body = lines(&spec.body, x, w, &mut y);
    y += 2.0;
    l.hints = lines(&spec.hints, x, w, &mut y);
    // Three to a row in a wide compact panel, and in a short one wide
    // enough (the smallest phone upright), so its buttons stay in it.
    let three = w > 520.0 || (area.h < 300.0 && w > 280.0);
    let per_row = if compact && three { 3 } else { 2 };
    let bw = (w - GAP * (per_row - 1) as f32) / per_row as f32;
    l.buttons = (0..spec.buttons)
        .map(|i| {
            let (c, r) = ((i % per_row) as f32, (i / per_row) as f32);
            Rect::new(x + c * (bw + GAP), y + r * (TOUCH + GAP), bw, TOUCH)
        })
        .collect();
    y += spec.buttons.div_ceil(per_row) as f32 * (TOUCH + GAP) + 4.0;
    l.log = lines(&vec![14.0; spec.log], x, w, &mut y);
    // As many of the log's lines as the panel holds.
    l.log.retain(|r| r.y + r.h <= bottom);
    // The chat above its field (spectators read it, without a field).
    let field_y = bottom - TOUCH;
    let chat_bottom = if spec.chat_field {
        field_y - 4.0
    } else {
        bottom
    };
    let fit = ((chat_bottom - y) / CHAT_LINE).floor().max(0.0) as usize;
    let shown = spec.chat.min(fit);
    let top = chat_bottom - shown as f32 * CHAT_LINE;
    l.chat = (0..shown)
        .map(|i| Rect::new(x, top + i as f32 * CHAT_LINE, w, 14.0))
        .collect();
    if spec.chat_field && field_y >= y {
        let phrases_x = x + w - SEND_W - GAP - PHRASES_W;
        l.chat_field = Some(ChatRow {
            field: Rect::new(x, field_y, phrases_x - GAP - x, TOUCH),
            phrases: Rect::new(phrases_x, field_y, PHRASES_W, TOUCH),
            send: Rect::new(x + w - SEND_W, field_y, SEND_W, TOUCH),
        });
    }
    l
}

/// The chat's menu, opened over the panel `area` just above the chat's
/// `row`: its box and `items` buttons in it, two to a row (three in a
/// wide panel), in reading order. It covers what lies under it, so the
/// panel's own buttons take no press while it is open.
pub fn chat_menu(area: Rect, row: &ChatRow, items: usize) -> (Rect, Vec<Rect>) {
    let x = area.x + 12.0;
    let w = area.w - 24.0;
    let per_row = if w > 520.0 { 3 } else { 2 };
    let rows = items.div_ceil(per_row);
    let bw = (w - GAP * (per_row - 1) as f32) / per_row as f32;
    let h = rows as f32 * (TOUCH + GAP) - GAP + 16.0;
    let top = (row.field.y - 6.0 - h).max(area.y);
    let buttons = (0..items)
        .map(|i| {
            let (c, r) = ((i % per_row) as f32, (i / per_row) as f32);
            Rect::new(x + c * (bw + GAP), top + 8.0 + r * (TOUCH + GAP), bw, TOUCH)
        })
        .collect();
    (Rect::new(area.x + 4.0, top, area.w - 8.0, h), buttons)
}

/// The end-of-match box over the board.
#[derive(Clone, Copy, Debug)]
pub struct EndLayout {
    /// The box.
    pub r: Rect,
    /// Its text's left edge and width.
    pub x: f32,
    pub w: f32,
    pub rematch: Option<Rect>,
    pub replay: Rect,
    pub close: Rect,
}

/// The end-of-match box centred on the board `area`, with a rematch
/// button for a `seated` player.
pub fn end_screen(area: Rect, seated: bool) -> EndLayout {
    let pw = (area.w - 24.0).min(420.0);
    let ph = 150.0 + (TOUCH + GAP) * if seated { 2.0 } else { 1.0 } + GAP;
    let r = Rect::new(
        area.x + (area.w - pw) / 2.0,
        area.y + (area.h - ph) / 2.0,
        pw,
        ph,
    );
    let x = r.x + 16.0;
    let w = r.w - 32.0;
    let mut y = r.y + 138.0;
    let half = (w - GAP) / 2.0;
    let rematch = seated.then(|| {
        let b = Rect::new(x, y, w, TOUCH);
        y += TOUCH + GAP;
        b
    });
    EndLayout {
        r,
        x,
        w,
        rematch,
        replay: Rect::new(x, y, half, TOUCH),
        close: Rect::new(x + half + GAP, y, half, TOUCH),
    }
}

/// A box of height `h` centred in the window, at most 440 wide.
pub fn dialog(window: Vec2, h: f32) -> Rect {
    let bw = (window.x - 24.0).min(440.0);
    Rect::new((window.x - bw) / 2.0, (window.y - h) / 2.0, bw, h)
}

/// Two buttons side by side at `y` in a dialog `box_` (its text inset 16).
pub fn dialog_buttons(box_: Rect, y: f32) -> (Rect, Rect) {
    let (x, w) = (box_.x + 16.0, box_.w - 32.0);
    let half = (w - GAP) / 2.0;
    (
        Rect::new(x, box_.y + y, half, TOUCH),
        Rect::new(x + half + GAP, box_.y + y, half, TOUCH),
    )
}

/// Where the power meter goes: beside the pointer, moved inside `window`.
pub fn meter_rect(pointer: Vec2, window: Vec2) -> Rect {
    let (w, h) = (12.0, 64.0);
    let mut x = pointer.x + 22.0;
    if x + 58.0 > window.x {
        x = pointer.x - 22.0 - 58.0;
    }
    let y = (pointer.y - h / 2.0).clamp(8.0, (window.y - h - 8.0).max(8.0));
    Rect::new(x.clamp(8.0, (window.x - 62.0).max(8.0)), y, w, h)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_geometry::{inside, overlap, PHONES};
    use macroquad::prelude::vec2;

    const DESKTOPS: [(f32, f32); 3] = [(1100.0, 760.0), (1280.0, 720.0), (1440.0, 900.0)];

    /// A seated player's panel during a match: as the screen fills it.
    fn playing(area: Rect, buttons: usize, chat: usize) -> PanelSpec {
        let c = compact(area);
        let head = if c {
            vec![15.0]
        } else {
            vec![26.0, 15.0, 15.0]
        };
        let mut body = vec![16.0, 17.0];
        if !c {
            body.push(16.0);
        }
        PanelSpec {
            head,
            players: true,
            body,
            hints: vec![14.0],
            buttons,
            log: if c { 2 } else { 4 },
            chat,
            chat_field: true,
        }
    }

    #[test]
    fn a_wide_window_puts_the_panel_right_of_the_board() {
        for (w, h) in DESKTOPS.into_iter().chain([(844.0, 390.0)]) {
            let (board, panel) = split(w, h);
            assert_eq!(board.x, 0.0);
            assert_eq!(panel.x, board.w, "{w}x{h}");
            assert_eq!((board.h, panel.h), (h, h));
            assert!((270.0..=380.0).contains(&panel.w));
        }
    }

    #[test]
    fn a_tall_window_puts_the_board_full_width_on_top_and_the_panel_below() {
        for (w, h) in [(390.0, 844.0), (412.0, 915.0), (768.0, 1024.0)] {
            let (board, panel) = split(w, h);
            assert_eq!((board.x, board.y, board.w), (0.0, 0.0, w));
            assert_eq!(panel.y, board.h, "{w}x{h}");
            assert_eq!((panel.w, panel.y + panel.h), (w, h));
            assert!(board.h <= w, "the board area is no taller than square");
        }
    }

    #[test]
    fn board_and_panel_share_the_window_without_overlapping() {
        for (w, h) in PHONES.into_iter().chain(DESKTOPS) {
            let (board, panel) = split(w, h);
            let window = Rect::new(0.0, 0.0, w, h);
            assert!(!overlap(board, panel), "{w}x{h}");
            assert!(inside(board, window) && inside(panel, window), "{w}x{h}");
        }
    }

    #[test]
    fn a_phones_panel_is_compact_and_a_desktops_is_not() {
        for (w, h) in PHONES {
            assert!(compact(split(w, h).1), "{w}x{h}");
        }
        for (w, h) in [(1100.0, 760.0), (1440.0, 900.0)] {
            assert!(!compact(split(w, h).1), "{w}x{h}");
        }
    }

    #[test]
    fn the_panels_parts_stay_inside_it_and_apart_at_phone_and_desktop_sizes() {
        // The smallest phone upright and on its side besides.
        let small = [(320.0, 568.0), (568.0, 320.0)];
        for (w, h) in PHONES.into_iter().chain(small).chain(DESKTOPS) {
            let (_, area) = split(w, h);
            // While shooting (resign, lobby, rules, sound) and at the end
            // (rematch, replay, lobby, rules, sound), with a full chat.
            for buttons in [6] {
                let l = panel(area, &playing(area, buttons, 6));
                assert_eq!(l.buttons.len(), buttons);
                let all = l.all();
                for (i, a) in all.iter().enumerate() {
                    assert!(inside(*a, area), "{w}x{h}: {a:?} outside {area:?}");
                    for b in &all[i + 1..] {
                        assert!(!overlap(*a, *b), "{w}x{h}: {a:?} overlaps {b:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn a_seated_player_always_gets_the_chat_field_on_a_desktop() {
        for (w, h) in DESKTOPS {
            let (_, area) = split(w, h);
            let l = panel(area, &playing(area, 5, 0));
            let row = l.chat_field.expect("a chat field");
            assert!((row.field.y + row.field.h - (area.y + area.h - 8.0)).abs() < 1e-3);
            assert!(row.field.x + row.field.w < row.phrases.x);
            assert!(row.phrases.x + row.phrases.w < row.send.x);
            assert!(row.field.w >= 120.0, "{w}x{h}: room to type");
        }
    }

    #[test]
    fn the_chat_menu_stands_above_the_chat_row_inside_the_panel_its_buttons_apart() {
        for (w, h) in PHONES.into_iter().chain(DESKTOPS).chain([(844.0, 390.0)]) {
            let (_, area) = split(w, h);
            let l = panel(area, &playing(area, 6, 6));
            let Some(row) = l.chat_field else {
                panic!("{w}x{h}: no chat row");
            };
            // The quick phrases and the two mute switches.
            let (menu, buttons) = chat_menu(area, &row, 10);
            assert!(inside(menu, area), "{w}x{h}: {menu:?} outside {area:?}");
            assert!(menu.y + menu.h <= row.field.y, "{w}x{h}: covers the row");
            for (i, a) in buttons.iter().enumerate() {
                assert!(inside(*a, menu), "{w}x{h}: {a:?} outside {menu:?}");
                assert!(a.h >= TOUCH);
                for b in &buttons[i + 1..] {
                    assert!(!overlap(*a, *b), "{w}x{h}: {a:?} overlaps {b:?}");
                }
            }
        }
    }

    #[test]
    fn the_chat_shows_only_the_lines_that_fit_above_its_field() {
        let area = Rect::new(0.0, 0.0, 300.0, 330.0);
        let l = panel(area, &playing(area, 4, 6));
        let last_button = l.buttons.last().unwrap();
        assert!(l.chat.len() < 6);
        for c in &l.chat {
            assert!(c.y >= last_button.y + last_button.h);
        }
    }

    #[test]
    fn a_compact_panel_sets_the_players_side_by_side_and_a_tall_one_stacks_them() {
        let (_, phone) = split(390.0, 844.0);
        let l = panel(phone, &playing(phone, 4, 0));
        assert_eq!(l.players[0].y, l.players[1].y);
        assert!(l.players[0].x + l.players[0].w < l.players[1].x);
        let (_, desk) = split(1100.0, 760.0);
        let l = panel(desk, &playing(desk, 4, 0));
        assert_eq!(l.players[0].x, l.players[1].x);
        assert!(l.players[0].y + l.players[0].h <= l.players[1].y);
    }

    #[test]
    fn a_wide_compact_panel_has_three_buttons_to_a_row() {
        let (_, area) = split(768.0, 1024.0);
        let l = panel(area, &playing(area, 6, 0));
        assert_eq!(l.buttons[0].y, l.buttons[2].y);
        assert!(l.buttons[3].y > l.buttons[0].y);
        let (_, phone) = split(390.0, 844.0);
        let l = panel(phone, &playing(phone, 6, 0));
        assert!(l.buttons[2].y > l.buttons[0].y);
    }

    #[test]
    fn before_the_match_is_known_the_panel_has_one_button_to_the_lobby() {
        let (_, area) = split(1100.0, 760.0);
        let spec = PanelSpec {
            head: vec![26.0, 15.0, 15.0],
            buttons: 1,
            ..PanelSpec::default()
        };
        let l = panel(area, &spec);
        assert!(l.players.is_empty() && l.chat_field.is_none());
        assert_eq!(l.buttons.len(), 1);
        assert!((l.buttons[0].w - (area.w - 24.0)).abs() < 1e-3);
        assert!(l.buttons[0].y > l.head[2].y + l.head[2].h);
    }

    #[test]
    fn the_end_screen_is_centred_on_the_board_with_its_buttons_inside() {
        for (w, h) in PHONES.into_iter().chain(DESKTOPS) {
            let (board, _) = split(w, h);
            for seated in [false, true] {
                let e = end_screen(board, seated);
                assert!(inside(e.r, board), "{w}x{h}");
                let centre = e.r.center();
                assert!((centre - board.center()).length() < 1e-3);
                assert_eq!(e.rematch.is_some(), seated);
                let buttons: Vec<Rect> = e.rematch.into_iter().chain([e.replay, e.close]).collect();
                for (i, b) in buttons.iter().enumerate() {
                    assert!(inside(*b, e.r), "{w}x{h}: {b:?}");
                    for c in &buttons[i + 1..] {
                        assert!(!overlap(*b, *c));
                    }
                }
            }
        }
    }

    #[test]
    fn the_dialogs_fit_a_phone_and_keep_their_width_on_a_desktop() {
        let d = dialog(vec2(360.0, 640.0), 200.0);
        assert_eq!((d.x, d.w), (12.0, 336.0));
        let d = dialog(vec2(1440.0, 900.0), 200.0);
        assert_eq!((d.w, d.y), (440.0, 350.0));
        let (a, b) = dialog_buttons(d, 136.0);
        assert!(inside(a, d) && inside(b, d) && !overlap(a, b));
    }

    #[test]
    fn the_power_meter_stays_inside_the_window() {
        let window = vec2(390.0, 844.0);
        for p in [vec2(0.0, 0.0), vec2(385.0, 840.0), vec2(200.0, 400.0)] {
            let m = meter_rect(p, window);
            let shown = Rect::new(m.x - 4.0, m.y - 4.0, 62.0, m.h + 8.0);
            assert!(
                inside(shown, Rect::new(0.0, 0.0, window.x, window.y)),
                "{p}"
            );
        }
        // Beside the pointer, on its right where there is room.
        assert!(meter_rect(vec2(100.0, 400.0), window).x > 100.0);
        assert!(meter_rect(vec2(380.0, 400.0), window).x < 380.0);
    }
}
