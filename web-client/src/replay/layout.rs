//! Where the replay's parts go, as pure functions from the window's size
//! to rectangles in layout units: the buttons of the top row, the room of
//! the title and the heading, the board and the control bar (the timeline
//! and its clock, the shot jumps with play/pause, the speeds). A wide
//! window has the heading above the board and one row of controls below
//! it; a narrow one (a phone upright) three rows of controls below; a
//! short one wider than tall (a phone on its side) the board at the left
//! and everything else in a column at its right. Nothing here draws, so
//! all of it is tested natively.

use crate::ui::TOUCH;
use macroquad::prelude::Rect;

/// The speeds offered: backwards, slow motion down to a tenth, fast.
pub const SPEEDS: [f64; 7] = [-1.0, 0.1, 0.25, 0.5, 1.0, 2.0, 4.0];
/// The speeds where a row has no room for all of them at a readable
/// size: backwards, the best shots' slow motion, and forwards.
pub const FEWER_SPEEDS: [f64; 5] = [-1.0, 0.25, 1.0, 2.0, 4.0];

/// The narrowest a speed button may be before the row offers
/// [`FEWER_SPEEDS`] ("0.25x" fits it at 14 units).
const SPEED_MIN_W: f32 = 44.0;
/// The room the clock's text takes beside the timeline (narrow layouts).
const CLOCK_W: f32 = 92.0;
/// The width of the column right of the board in the sideways layout (at
/// least room for five speeds whose "0.25x" reads at 13.8 units).
const COLUMN: (f32, f32) = (262.0, 420.0);

/// How the replay is laid out in a window.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// The heading above the board, one row of controls below it.
    Wide,
    /// A phone upright: three rows of controls below the board.
    Narrow,
    /// A phone on its side: the board at the left, a column at its right.
    Side,
}

/// The layout of a `w` x `h` window.
pub fn mode(w: f32, h: f32) -> Mode {
    if w >= 930.0 {
        Mode::Wide
    } else if w > h && h < 520.0 {
        Mode::Side
    } else {
        Mode::Narrow
    }
}

/// The top row's buttons and the room for the title and the heading.
#[derive(Clone, Copy, Debug)]
pub struct Top {
    pub lobby: Rect,
    pub lang: Rect,
    /// The language switch says "EN"/"RU" rather than its whole name.
    pub short_lang: bool,
    /// The title's left, top and width (its lines go down from there).
    pub title: Rect,
    /// Where the heading may go below the title (its left, width and the
    /// lowest its lines may reach; its top follows the title).
    pub heading: Rect,
}

/// The top row and the text's room in a `w` x `h` window.
pub fn top(w: f32, h: f32) -> Top {
    let m = mode(w, h);
    let lobby = Rect::new(w - 98.0, 8.0, 90.0, TOUCH);
    let short_lang = m != Mode::Wide;
    let lang_w = if short_lang { 48.0 } else { 110.0 };
    let lang = Rect::new(lobby.x - 8.0 - lang_w, lobby.y, lang_w, TOUCH);
    match m {
        Mode::Side => {
            let x = column_x(w, h) + 8.0;
            let text = Rect::new(x, lobby.y + lobby.h + 6.0, w - x - 8.0, 0.0);
            let bottom = controls(w, h).panel.y - 4.0;
            Top {
                lobby,
                lang,
                short_lang,
                title: text,
                heading: Rect::new(x, text.y, text.w, bottom - text.y),
            }
        }
        _ => Top {
            lobby,
            lang,
            short_lang,
            // Beside the buttons.
            title: Rect::new(12.0, 8.0, lang.x - 20.0, 0.0),
            heading: if m == Mode::Narrow {
                Rect::new(12.0, 8.0, w - 24.0, h)
            } else {
                Rect::new(12.0, 8.0, lang.x - 20.0, h)
            },
        },
    }
}

/// The left edge of the sideways layout's column.
fn column_x(w: f32, h: f32) -> f32 {
    w - (w - h).clamp(COLUMN.0, COLUMN.1)
}

/// The control bar's parts.
#[derive(Clone, Debug)]
pub struct Controls {
    /// The bar's panel.
    pub panel: Rect,
    /// The timeline.
    pub track: Rect,
    /// The clock's text: its left, its top, the width it may take (its
    /// height is its size).
    pub clock: Rect,
    /// Previous shot, play/pause, next shot.
    pub previous: Rect,
    pub play: Rect,
    pub next: Rect,
    /// The speeds offered ([`SPEEDS`], or [`FEWER_SPEEDS`] where a row
    /// has no room for all) and their buttons.
    pub speeds: &'static [f64],
    pub speed_buttons: Vec<Rect>,
}

/// The widths of the wide bar's buttons in a window `w` units wide: a
/// shot jump, play/pause and a speed. The bar's row of buttons shares
/// one label size, set by the most cramped of them ("Пред. щелчок",
/// "0.25x"), so a wide window (1200 units and more) gives them the room
/// it has; the wide bar's controls then end 1126 units from the left.
pub fn bar_widths(w: f32) -> (f32, f32, f32) {
    if w >= 1200.0 {
        (160.0, 90.0, 72.0)
    } else {
        (116.0, 80.0, 56.0)
    }
}

/// `n` buttons of one width in a row from `x`, `width` wide in all, at
/// `y`, `gap` apart.
fn row(x: f32, y: f32, width: f32, n: usize, gap: f32) -> Vec<Rect> {
    let bw = (width - gap * (n - 1) as f32) / n as f32;
    (0..n)
        .map(|i| Rect::new(x + i as f32 * (bw + gap), y, bw, TOUCH))
        .collect()
}

/// The speeds a row `width` wide offers, and their buttons.
fn speed_row(x: f32, y: f32, width: f32, gap: f32) -> (&'static [f64], Vec<Rect>) {
    let all = row(x, y, width, SPEEDS.len(), gap);
    if all[0].w >= SPEED_MIN_W {
        (&SPEEDS, all)
    } else {
        (&FEWER_SPEEDS, row(x, y, width, FEWER_SPEEDS.len(), gap))
    }
}

/// The control bar of a `w` x `h` window.
pub fn controls(w: f32, h: f32) -> Controls {
    match mode(w, h) {
        Mode::Wide => {
            let panel = Rect::new(0.0, h - 118.0, w, 118.0);
            let track = Rect::new(20.0, panel.y + 8.0, w - 40.0, TOUCH);
            let y = panel.y + 60.0;
            let (jump_w, play_w, speed_w) = bar_widths(w);
            let previous = Rect::new(20.0, y, jump_w, TOUCH);
            let play = Rect::new(previous.right() + 8.0, y, play_w, TOUCH);
            let next = Rect::new(play.right() + 8.0, y, jump_w, TOUCH);
            let clock = Rect::new(next.right() + 12.0, y + 13.0, 112.0, 17.0);
            let speed_buttons = (0..SPEEDS.len())
                .map(|i| {
                    let x = clock.x - 4.0 + 120.0 + i as f32 * (speed_w + 8.0);
                    Rect::new(x, y, speed_w, TOUCH)
                })
                .collect();
            Controls {
                panel,
                track,
                clock,
                previous,
                play,
                next,
                speeds: &SPEEDS,
                speed_buttons,
            }
        }
        m => {
            // Three rows: the timeline and its clock, the jumps with
            // play/pause, the speeds.
            let (x, width) = if m == Mode::Side {
                let x = column_x(w, h);
                (x, w - x)
            } else {
                (0.0, w)
            };
            let panel = Rect::new(x, h - 164.0, width, 164.0);
            let (left, room) = (x + 10.0, width - 20.0);
            let track = Rect::new(left, panel.y + 6.0, room - CLOCK_W - 6.0, TOUCH);
            let clock = Rect::new(track.right() + 6.0, track.y + 14.0, CLOCK_W, 15.0);
            let jumps = row(left, panel.y + 58.0, room, 3, 8.0);
            let (speeds, speed_buttons) = speed_row(left, panel.y + 110.0, room, 6.0);
            Controls {
                panel,
                track,
                clock,
                previous: jumps[0],
                play: jumps[1],
                next: jumps[2],
                speeds,
                speed_buttons,
            }
        }
    }
}

/// The board's area once the heading above it ends at `head_h` (the
/// whole height left of the column in the sideways layout).
pub fn board(w: f32, h: f32, head_h: f32) -> Rect {
    let c = controls(w, h);
    match mode(w, h) {
        Mode::Side => Rect::new(0.0, 0.0, c.panel.x, h),
        _ => Rect::new(0.0, head_h, w, c.panel.y - head_h),
    }
}

/// The best shots' buttons down the board's left edge (`n` of them),
/// below the heading's end `head_h`; none in the sideways layout, whose
/// board leaves no room beside it.
pub fn best(w: f32, h: f32, head_h: f32, n: usize) -> Vec<Rect> {
    let (top, bw) = match mode(w, h) {
        Mode::Side => return Vec::new(),
        Mode::Narrow => (head_h + 6.0, 112.0),
        Mode::Wide => (head_h + 28.0, 150.0),
    };
    (0..n)
        .map(|i| Rect::new(12.0, top + i as f32 * (TOUCH + 6.0), bw, TOUCH))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::i18n::{message_in, Lang};
    use crate::test_geometry::{font_width, inside, overlap, PHONES};

    /// Phones and the smallest one, upright and on its side.
    const SMALL: [(f32, f32); 2] = [(320.0, 568.0), (568.0, 320.0)];

    fn all(c: &Controls) -> Vec<Rect> {
        let mut v = vec![c.track, c.previous, c.play, c.next];
        v.extend(&c.speed_buttons);
        v
    }

    #[test]
    fn every_control_is_inside_the_window_apart_and_off_the_board_on_phones_and_desktops() {
        for (w, h) in PHONES
            .into_iter()
            .chain(SMALL)
            .chain([(1216.0, 760.0), (1024.0, 720.0)])
        {
            let window = Rect::new(0.0, 0.0, w, h);
            let c = controls(w, h);
            let t = top(w, h);
            let mut shown = all(&c);
            shown.extend([t.lobby, t.lang]);
            let board = board(w, h, 100.0);
            for (i, r) in shown.iter().enumerate() {
                assert!(inside(*r, window), "{w}x{h}: {r:?} outside");
                assert!(r.h >= TOUCH, "{w}x{h}: {r:?}");
                assert!(
                    !overlap(*r, board),
                    "{w}x{h}: {r:?} over the board {board:?}"
                );
                for s in &shown[i + 1..] {
                    assert!(!overlap(*r, *s), "{w}x{h}: {r:?} overlaps {s:?}");
                }
            }
            assert!(inside(c.clock, c.panel), "{w}x{h}: the clock");
            assert_eq!(c.speeds.len(), c.speed_buttons.len());
            for r in best(w, h, 100.0, 3) {
                assert!(inside(r, board), "{w}x{h}: a best shot {r:?}");
            }
        }
    }

    #[test]
    fn the_board_keeps_a_playable_size_on_the_smallest_phone() {
        for (w, h) in SMALL {
            // The heading of a narrow window ends about 140 units down.
            let b = board(w, h, 140.0);
            let side = b.w.min(b.h);
            eprintln!("replay {w}x{h}: the board's area {} x {}", b.w, b.h);
            assert!(side >= 220.0, "{w}x{h}: {b:?}");
        }
        assert_eq!(mode(568.0, 320.0), Mode::Side);
        assert_eq!(mode(320.0, 568.0), Mode::Narrow);
        assert_eq!(mode(1216.0, 760.0), Mode::Wide);
    }

    #[test]
    fn the_controls_read_at_13_units_or_more_on_every_phone_in_both_languages() {
        for (w, h) in PHONES.into_iter().chain(SMALL) {
            let c = controls(w, h);
            for lang in [Lang::En, Lang::Ru] {
                let text = |id: &str| message_in(lang, id).expect("the message exists");
                for play in ["replay-play", "replay-pause"] {
                    let mut labels = vec![
                        (text("replay-previous-shot"), c.previous),
                        (text(play), c.play),
                        (text("replay-next-shot"), c.next),
                    ];
                    labels.extend(
                        c.speeds
                            .iter()
                            .map(|s| format!("{s}x"))
                            .zip(c.speed_buttons.iter().copied()),
                    );
                    let buttons: Vec<(&str, Rect)> =
                        labels.iter().map(|(l, r)| (l.as_str(), *r)).collect();
                    let sizes = crate::ui::group_label_sizes(&buttons, font_width);
                    let least = sizes.iter().copied().fold(f32::INFINITY, f32::min);
                    eprintln!(
                        "replay {w}x{h} {lang:?} {play}: the jumps at {}, the speeds at {} ({} of them)",
                        sizes[0],
                        sizes[3],
                        c.speeds.len()
                    );
                    assert!(least >= 13.0, "{w}x{h} {lang:?}: {sizes:?}");
                }
            }
        }
    }
}
