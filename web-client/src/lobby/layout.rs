//! Where the lobby's parts go, as a pure function of the window's size
//! (layout units): the centred column, the title row with the rules
//! button, the account row, the grid of matches to start, the join-by-id
//! row, the message, the footer and the three match lists (side by side
//! on a wide screen, stacked on a narrow one). Nothing here draws, so it
//! is tested natively.
//!
//! The matches to start stand in a grid: two columns on a phone, four on
//! a wide screen. The grid shares one label size (the smallest its labels
//! fit at), so eight buttons in one row would shrink every label to the
//! size of the longest ("Компьютер: адаптивный") in an eighth of the
//! column; four to a row leave room for it at a size that reads easily.
//! The last, "Offline vs computer", takes a row of its own, the column's
//! full width.
//!
//! A window too short for the column (a small phone on its side) sets it
//! in two: the title, the join row and the lists at the left, the
//! buttons of the title row, the account row and the matches to start at
//! the right; a short phone upright leaves out the footer so its lists
//! keep room for their headings and a line.

use crate::ui::TOUCH;
use macroquad::prelude::Rect;

/// Room between controls.
pub const GAP: f32 = 8.0;
/// How many matches there are to start.
pub const CHOICES: usize = 9;

/// The lobby's places.
#[derive(Clone, Debug)]
pub struct Layout {
    /// The column's left edge and width.
    pub x0: f32,
    pub col: f32,
    /// A narrow column (a phone): smaller title, a grid of two columns
    /// (four on a wide screen), stacked lists.
    pub narrow: bool,
    /// The title row's top.
    pub title_y: f32,
    /// The rules button beside the title.
    pub help: Rect,
    /// The language switch beside the rules button.
    pub lang: Rect,
    /// The logo's checkers' radius.
    pub logo: f32,
    /// Whether the tagline has its lines under the title (a short phone
    /// upright gives them to the lists).
    pub tagline: bool,
    /// The account row's left edge, top and width, and the width of its
    /// label.
    pub account_x: f32,
    pub account_y: f32,
    pub account_w: f32,
    pub label_w: f32,
    /// The matches to start.
    pub choices: [Rect; CHOICES],
    /// The join-by-id row: its field and button.
    pub join_field: Rect,
    pub join: Rect,
    /// Where a message goes: its text's left, top and width.
    pub message: (f32, f32, f32),
    /// The footer line's top, where there is room for it.
    pub footer_y: Option<f32>,
    /// The open, live and finished lists.
    pub lists: [Rect; 3],
}

/// The lobby in a `w` x `h` window; `message` whether a message shows
/// (on a narrow screen it takes a line above the lists).
pub fn layout(w: f32, h: f32, message: bool) -> Layout {
    if w > h && h < SHORT {
        return two_columns(w, h, message);
    }
    let pad = if w < 600.0 { 12.0 } else { 20.0 };
    let col = (w - 2.0 * pad).min(980.0);
    let x0 = (w - col) / 2.0;
    let narrow = col < 700.0;
    // A short phone upright (an iPhone SE's 568): the grid's rows closer,
    // the title without its tagline, so the lists keep a heading and a
    // line each.
    let tight = narrow && h < 640.0;
    let row = TOUCH;
    let title_y = if narrow { 10.0 } else { 24.0 };
    let help = if narrow {
        Rect::new(x0 + col - 84.0, title_y + 2.0, 84.0, row)
    } else {
        Rect::new(x0 + col - 150.0, title_y + 4.0, 150.0, row)
    };
    let lang = if narrow {
        Rect::new(help.x - GAP - 48.0, help.y, 48.0, row)
    } else {
        Rect::new(help.x - GAP - 110.0, help.y, 110.0, row)
    };
    let logo = if narrow { 14.0 } else { 20.0 };
    let account_y = title_y
        + match (narrow, tight) {
            (_, true) => 50.0,
            (true, false) => 62.0,
            (false, _) => 86.0,
        };
    let label_w = if narrow { 98.0 } else { 100.0 };
    let mut y = account_y + row + if tight { 6.0 } else { 12.0 };
    // The matches to start: a grid of four columns, or two on a phone.
    let per_row = if narrow { 2 } else { 4 };
    let bw = (col - GAP * (per_row - 1) as f32) / per_row as f32;
    let bh = if narrow { row } else { 52.0 };
    let row_gap = if tight { 4.0 } else { GAP };
    let choices = std::array::from_fn(|i| {
        let (c, r) = ((i % per_row) as f32, (i / per_row) as f32);
        if i + 1 == CHOICES && CHOICES % per_row == 1 {
            // Alone in its row: the full width.
            Rect::new(x0, y + r * (bh + row_gap), col, bh)
        } else {
            Rect::new(x0 + c * (bw + GAP), y + r * (bh + row_gap), bw, bh)
        }
    });
    y += CHOICES.div_ceil(per_row) as f32 * (bh + row_gap) + if tight { 2.0 } else { 6.0 };
    let join_w = 80.0;
    let field_w = (col - label_w - GAP - join_w).min(300.0);
    let join_field = Rect::new(x0 + label_w, y, field_w, row);
    let join = Rect::new(join_field.x + join_field.w + GAP, y, join_w, row);
    y += row + if tight { 6.0 } else { 10.0 };
    let message_at = if narrow {
        let at = (x0, y, col);
        if message {
            y += 22.0;
        }
        at
    } else {
        let mx = join.x + join.w + 16.0;
        (mx, join.y + 12.0, x0 + col - mx)
    };
    // The three lists side by side (or stacked on a narrow screen; one
    // too short for them and the footer goes without the footer).
    let top = y;
    let footer = !narrow || (h - 30.0 - top) / 3.0 - GAP >= LIST_MIN_H;
    let (bottom, gap) = if footer {
        (h - 30.0, GAP)
    } else {
        (h - 4.0, 4.0)
    };
    let lw = if narrow { col } else { (col - 24.0) / 3.0 };
    let lists = std::array::from_fn(|i| {
        if narrow {
            let lh = (bottom - top + gap) / 3.0;
            Rect::new(x0, top + i as f32 * lh, lw, lh - gap)
        } else {
            Rect::new(x0 + i as f32 * (lw + 12.0), top, lw, bottom - top)
        }
    });
    Layout {
        x0,
        col,
        narrow,
        title_y,
        help,
        lang,
        logo,
        tagline: !tight,
        account_x: x0,
        account_y,
        account_w: col,
        label_w,
        choices,
        join_field,
        join,
        message: message_at,
        footer_y: footer.then_some(h - 22.0),
        lists,
    }
}

/// Windows less tall than this, and wider than tall, get two columns.
const SHORT: f32 = 480.0;

/// The least height of a list: its heading and one line under it.
const LIST_MIN_H: f32 = 50.0;

/// The lobby in two columns (a short window): the title, the join row,
/// "Offline vs computer", the message and the stacked lists at the left;
/// the rules, the language switch, the account row and the other matches
/// to start (two to a row) at the right. No footer, and no tagline where
/// the lists would lose their heading and line to it.
fn two_columns(w: f32, h: f32, message: bool) -> Layout {
    let pad = 12.0;
    let half = (w - 2.0 * pad - 12.0) / 2.0;
    let (x0, rx) = (pad, pad + half + 12.0);
    let row = TOUCH;
    let title_y = 6.0;
    let help = Rect::new(rx + half - 84.0, title_y, 84.0, row);
    let lang = Rect::new(help.x - GAP - 48.0, title_y, 48.0, row);
    let account_y = title_y + row + 6.0;
    let label_w = 98.0;
    let y = account_y + row + 8.0;
    let bw = (half - GAP) / 2.0;
    // The left column: under the title and its tagline (about 70 units,
    // or the title alone, about 40), the join row, "Offline vs computer",
    // the message and the lists.
    let under = |top: f32| top + (row + 8.0) + (row + 4.0) + if message { 22.0 } else { 0.0 };
    let tagline = (h - under(80.0)) / 3.0 - 4.0 >= LIST_MIN_H;
    let mut ly = if tagline { 80.0 } else { 44.0 };
    let offline = Rect::new(x0, ly + row + 8.0, half, row);
    let choices = std::array::from_fn(|i| {
        if i + 1 == CHOICES {
            return offline;
        }
        let (c, r) = ((i % 2) as f32, (i / 2) as f32);
        Rect::new(rx + c * (bw + GAP), y + r * (row + GAP), bw, row)
    });
    let join_w = 80.0;
    let join_field = Rect::new(x0 + label_w, ly, half - label_w - GAP - join_w, row);
    let join = Rect::new(join_field.x + join_field.w + GAP, ly, join_w, row);
    ly += (row + 8.0) + (row + 4.0);
    let message_at = (x0, ly, half);
    if message {
        ly += 22.0;
    }
    let gap = 4.0;
    let lh = (h - 4.0 - ly + gap) / 3.0;
    let lists = std::array::from_fn(|i| Rect::new(x0, ly + i as f32 * lh, half, lh - gap));
    Layout {
        x0,
        col: half,
        narrow: true,
        title_y,
        help,
        lang,
        logo: 14.0,
        tagline,
        account_x: rx,
        account_y,
        account_w: half,
        label_w,
        choices,
        join_field,
        join,
        message: message_at,
        footer_y: None,
        lists,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::i18n::{message_in, Lang};
    use crate::test_geometry::font_width;
    use crate::ui::group_label_sizes;

    /// The smallest label size of the lobby's main choices on a desktop.
    const COMFORTABLE: f32 = 16.0;

    const PHONES: [(f32, f32); 2] = [(390.0, 844.0), (412.0, 915.0)];
    /// The smallest phone upright and on its side, and a phone on its side.
    const SMALL: [(f32, f32); 3] = [(320.0, 568.0), (568.0, 320.0), (844.0, 390.0)];
    const DESKTOPS: [(f32, f32); 3] = [(1100.0, 760.0), (1280.0, 720.0), (1440.0, 900.0)];

    fn overlap(a: Rect, b: Rect) -> bool {
        a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h
    }

    fn inside(inner: Rect, w: f32, h: f32) -> bool {
        inner.x >= -1e-3
            && inner.y >= -1e-3
            && inner.x + inner.w <= w + 1e-3
            && inner.y + inner.h <= h + 1e-3
    }

    fn all(l: &Layout) -> Vec<Rect> {
        let mut v = vec![l.help, l.lang, l.join_field, l.join];
        v.extend(l.choices);
        v.extend(l.lists);
        v
    }

    #[test]
    fn a_phone_gets_a_narrow_lobby_with_stacked_lists() {
        for (w, h) in PHONES {
            let l = layout(w, h, false);
            assert!(l.narrow);
            assert_eq!(l.lists[0].x, l.lists[1].x);
            assert!(l.lists[0].y + l.lists[0].h <= l.lists[1].y);
            // Two matches to start to a row.
            assert_eq!(l.choices[0].y, l.choices[1].y);
            assert!(l.choices[2].y > l.choices[0].y);
        }
    }

    #[test]
    fn a_desktop_sets_the_lists_side_by_side_and_the_choices_in_two_rows_of_four_and_a_wide_one() {
        for (w, h) in DESKTOPS {
            let l = layout(w, h, false);
            assert!(!l.narrow);
            assert_eq!(l.lists[0].y, l.lists[2].y);
            assert!(l.lists[0].x + l.lists[0].w < l.lists[1].x);
            assert!(l.choices[..4].iter().all(|c| c.y == l.choices[0].y));
            assert!(l.choices[4..8].iter().all(|c| c.y == l.choices[4].y));
            assert!(l.choices[4].y > l.choices[0].y);
            assert_eq!(l.choices[4].x, l.choices[0].x);
            // "Offline vs computer" alone under them, the column's width.
            assert!(l.choices[8].y > l.choices[4].y);
            assert_eq!((l.choices[8].x, l.choices[8].w), (l.x0, l.col));
            assert!(l.col <= 980.0);
        }
    }

    /// The messages of the matches to start, in the lobby's order.
    const CHOICE_MESSAGES: [&str; CHOICES] = [
        "lobby-quick-match",
        "lobby-computer-easy",
        "lobby-computer-medium",
        "lobby-computer-hard",
        "lobby-computer-adaptive",
        "lobby-friend",
        "lobby-sandbox",
        "leaderboard",
        "lobby-offline",
    ];

    /// The size the matches to start share in a `w` x `h` window in
    /// `lang`, measured in the client's font.
    fn choice_label_size(w: f32, h: f32, lang: Lang) -> f32 {
        let l = layout(w, h, false);
        let labels: Vec<String> = CHOICE_MESSAGES
            .iter()
            .map(|id| message_in(lang, id).expect("the message exists"))
            .collect();
        let buttons: Vec<(&str, Rect)> = labels.iter().map(String::as_str).zip(l.choices).collect();
        let sizes = group_label_sizes(&buttons, font_width);
        // Every label shows whole at that size: on one line, or on two.
        for ((label, r), size) in buttons.iter().zip(&sizes) {
            let lines = match crate::ui::split_in_two(label) {
                Some((a, b)) if font_width(label, *size) > r.w => vec![a, b],
                _ => vec![*label],
            };
            assert!(
                lines.iter().all(|l| font_width(l, *size) <= r.w),
                "{w}x{h} {lang:?}: {label} runs past its button"
            );
        }
        // The grid shares one size; "Offline vs computer", alone in its
        // row, reads at least as large.
        let (grid, wide) = sizes.split_at(CHOICES - 1);
        assert!(grid.iter().all(|s| *s == grid[0]), "{sizes:?}");
        assert!(wide.iter().all(|s| *s >= grid[0]), "{sizes:?}");
        sizes[0]
    }

    #[test]
    fn the_matches_to_start_read_at_a_comfortable_size_on_a_desktop_in_both_languages() {
        // The bound for the desktop; a phone's two columns are as wide as
        // its buttons can be, and only have to stay legible.
        // A 1280 x 800 browser window, in layout units.
        let z = crate::scale::zoom_for(1280.0, 800.0);
        for (w, h) in DESKTOPS.into_iter().chain([(1280.0 / z, 800.0 / z)]) {
            for lang in [Lang::En, Lang::Ru] {
                let size = choice_label_size(w, h, lang);
                eprintln!("lobby {w}x{h} {lang:?}: the matches to start at {size} units");
                assert!(size >= COMFORTABLE, "{w}x{h} {lang:?}: {size}");
            }
        }
        for (w, h) in PHONES {
            for lang in [Lang::En, Lang::Ru] {
                let size = choice_label_size(w, h, lang);
                eprintln!("lobby {w}x{h} {lang:?}: the matches to start at {size} units");
                assert!(size >= 12.0, "{w}x{h} {lang:?}: {size}");
            }
        }
    }

    #[test]
    fn nothing_overlaps_and_everything_is_inside_the_window() {
        for (w, h) in PHONES.into_iter().chain(SMALL).chain(DESKTOPS) {
            for message in [false, true] {
                let l = layout(w, h, message);
                let mut rects = all(&l);
                // The account row's place (the name's field and Sign in).
                rects.push(Rect::new(
                    l.account_x + l.label_w,
                    l.account_y,
                    l.account_w - l.label_w,
                    TOUCH,
                ));
                for (i, a) in rects.iter().enumerate() {
                    assert!(inside(*a, w, h), "{w}x{h}: {a:?}");
                    for b in &rects[i + 1..] {
                        assert!(!overlap(*a, *b), "{w}x{h}: {a:?} overlaps {b:?}");
                    }
                }
                // The lists end above the footer, and hold their heading
                // and a line (without a message, which takes their room).
                for list in l.lists {
                    assert!(list.y + list.h <= l.footer_y.unwrap_or(h));
                    assert!(message || list.h >= LIST_MIN_H, "{w}x{h}: {list:?}");
                }
            }
        }
    }

    #[test]
    fn a_message_on_a_phone_takes_a_line_above_the_lists() {
        let (w, h) = PHONES[0];
        let without = layout(w, h, false);
        let with = layout(w, h, true);
        assert_eq!(with.lists[0].y, without.lists[0].y + 22.0);
        assert!(with.message.1 < with.lists[0].y);
        // On a desktop it stands beside the join button instead.
        let d = layout(1100.0, 760.0, true);
        assert!(d.message.0 > d.join.x + d.join.w);
        assert_eq!(d.lists[0].y, layout(1100.0, 760.0, false).lists[0].y);
    }
}
