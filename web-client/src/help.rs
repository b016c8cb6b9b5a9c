//! "How to play": the rules of Chapaev and the controls, as a panel any
//! screen can open over itself.

use crate::i18n::t;
use crate::ui::{self, colors, Ui};
use macroquad::prelude::*;

/// The rules and controls, a paragraph each.
pub fn rules() -> [String; 9] {
    [
        t!("rules-1"),
        t!("rules-2"),
        t!("rules-3"),
        t!("rules-4"),
        t!("rules-5"),
        t!("rules-6"),
        t!("rules-7"),
        t!("rules-8"),
        t!("rules-9"),
    ]
}

/// `text` wrapped to at most `lines` lines `width` wide at `size`, the
/// last one cut with an ellipsis if the text is longer.
pub fn wrap_lines(text: &str, size: f32, width: f32, lines: usize) -> Vec<String> {
    let mut wrapped = wrap(text, size, width);
    if wrapped.len() > lines {
        let rest = wrapped.split_off(lines.saturating_sub(1)).join(" ");
        wrapped.push(ui::fit(&rest, size, width));
    }
    wrapped
}

/// `text` in at most `lines` lines `width` wide: at `size`, or smaller
/// (down to [`ui::MIN_TEXT`]) where it takes more lines; only below that
/// is the last line cut. The size and the lines.
pub fn shrink_lines(text: &str, size: f32, width: f32, lines: usize) -> (f32, Vec<String>) {
    let mut size = size;
    while size > ui::MIN_TEXT && wrap(text, size, width).len() > lines {
        size = (size - 1.0).max(ui::MIN_TEXT);
    }
    (size, wrap_lines(text, size, width, lines))
}

/// Words of `text` wrapped to lines at most `width` pixels wide.
pub fn wrap(text: &str, size: f32, width: f32) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        let candidate = if line.is_empty() {
            word.to_string()
        } else {
            format!("{line} {word}")
        };
        if !line.is_empty() && ui::text_width(&candidate, size) > width {
            lines.push(std::mem::replace(&mut line, word.to_string()));
        } else {
            line = candidate;
        }
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}

thread_local! {
    /// The page of the rules shown (a window too small for all of them
    /// shows them a page at a time).
    static PAGE: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// The paragraphs of each page, in order, for paragraphs of `lines`
/// lines each, `step` units a line and 8 between paragraphs, on pages
/// `room` units tall: as many whole paragraphs as fit, and at least one.
fn pages(lines: &[usize], step: f32, room: f32) -> Vec<std::ops::Range<usize>> {
    let mut pages = Vec::new();
    let (mut first, mut used) = (0, 0.0);
    for (i, &n) in lines.iter().enumerate() {
        let tall = n as f32 * step + 8.0;
        if i > first && used + tall > room {
            pages.push(first..i);
            (first, used) = (i, 0.0);
        }
        used += tall;
    }
    if first < lines.len() {
        pages.push(first..lines.len());
    }
    pages
}

/// Draws the panel centred on the screen; `true` when it is closed. A
/// window too small for all the rules shows them a page at a time, with
/// `<` and `>` to turn the pages.
pub fn show(ui: &mut Ui) -> bool {
    let (w, h) = crate::scale::size().into();
    draw_rectangle(0.0, 0.0, w, h, Color::new(0.0, 0.0, 0.0, 0.55));
    let pw = (w - 24.0).min(640.0);
    let size = if w < 500.0 || h < 500.0 { 15.0 } else { 17.0 };
    let step = size + 4.0;
    let text_w = pw - 40.0;
    let rules = rules();
    let wrapped: Vec<Vec<String>> = rules.iter().map(|r| wrap(r, size, text_w)).collect();
    let counts: Vec<usize> = wrapped.iter().map(Vec::len).collect();
    let lines: usize = counts.iter().sum();
    let ph = (90.0 + lines as f32 * step + rules.len() as f32 * 8.0 + 64.0).min(h - 20.0);
    let r = Rect::new((w - pw) / 2.0, (h - ph) / 2.0, pw, ph);
    ui::panel(r);
    let _inside = ui::bounds(r);
    ui::text_in(
        &t!("help-title"),
        r.x + 20.0,
        r.y + 16.0,
        26.0,
        text_w,
        colors::ACCENT,
    );
    // The paragraphs between the title and the buttons.
    let room = ph - 60.0 - ui::TOUCH - 20.0;
    let pages = pages(&counts, step, room);
    let page = PAGE.with(|p| p.get()).min(pages.len().saturating_sub(1));
    let mut y = r.y + 60.0;
    for para in &wrapped[pages.get(page).cloned().unwrap_or(0..0)] {
        for l in para {
            ui::text(l, r.x + 20.0, y, size, colors::TEXT);
            y += step;
        }
        y += 8.0;
    }
    let by = r.y + r.h - ui::TOUCH - 12.0;
    let narrow = pw < 420.0;
    let close_w = if narrow { 96.0 } else { 120.0 };
    let close = Rect::new(r.x + r.w - 12.0 - close_w, by, close_w, ui::TOUCH);
    let lang_w = if narrow { 56.0 } else { 120.0 };
    let lang = Rect::new(r.x + 12.0, by, lang_w, ui::TOUCH);
    crate::i18n::switch(ui, lang, narrow);
    if pages.len() > 1 {
        let next = Rect::new(close.x - 8.0 - 44.0, by, 44.0, ui::TOUCH);
        let previous = Rect::new(next.x - 8.0 - 44.0, by, 44.0, ui::TOUCH);
        let last = pages.len() - 1;
        if ui.button_styled("help-previous", "<", previous, page > 0, false) {
            PAGE.with(|p| p.set(page.saturating_sub(1)));
        }
        if ui.button_styled("help-next", ">", next, page < last, false) {
            PAGE.with(|p| p.set((page + 1).min(last)));
        }
    }
    let closed =
        ui.button("help-close", &t!("help-close"), close) || is_key_pressed(KeyCode::Escape);
    if closed {
        PAGE.with(|p| p.set(0));
    }
    closed
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rules_fill_pages_with_whole_paragraphs_in_order_and_each_page_holds_one_at_least() {
        // Paragraphs of 2, 3, 1, 4 and 9 lines, 20 units a line.
        let lines = [2, 3, 1, 4, 9];
        assert_eq!(pages(&lines, 20.0, 1000.0), vec![0..5]);
        let p = pages(&lines, 20.0, 130.0);
        // 48 + 68 fit 130; 28 more does not; 28 + 88 do; the 9 lines
        // (188) take a page of their own though they overflow it.
        assert_eq!(p, vec![0..2, 2..4, 4..5]);
        assert_eq!(
            pages(&[], 20.0, 100.0),
            Vec::<std::ops::Range<usize>>::new()
        );
    }
}
