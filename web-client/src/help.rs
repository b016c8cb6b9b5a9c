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

/// Draws the panel centred on the screen; `true` when it is closed.
pub fn show(ui: &mut Ui) -> bool {
    let (w, h) = crate::scale::size().into();
    draw_rectangle(0.0, 0.0, w, h, Color::new(0.0, 0.0, 0.0, 0.55));
    let pw = (w - 24.0).min(640.0);
    let size = if w < 500.0 { 15.0 } else { 17.0 };
    let text_w = pw - 40.0;
    let rules = rules();
    let wrapped: Vec<Vec<String>> = rules.iter().map(|r| wrap(r, size, text_w)).collect();
    let lines: usize = wrapped.iter().map(Vec::len).sum();
    let ph = (90.0 + lines as f32 * (size + 4.0) + rules.len() as f32 * 8.0 + 64.0).min(h - 20.0);
    let r = Rect::new((w - pw) / 2.0, (h - ph) / 2.0, pw, ph);
    ui::panel(r);
    ui::text(
        &ui::fit(&t!("help-title"), 26.0, text_w),
        r.x + 20.0,
        r.y + 16.0,
        26.0,
        colors::ACCENT,
    );
    let mut y = r.y + 60.0;
    for para in &wrapped {
        for l in para {
            ui::text(l, r.x + 20.0, y, size, colors::TEXT);
            y += size + 4.0;
        }
        y += 8.0;
    }
    let close = Rect::new(
        r.x + r.w - 140.0,
        r.y + r.h - ui::TOUCH - 12.0,
        120.0,
        ui::TOUCH,
    );
    let lang = Rect::new(r.x + 20.0, close.y, 120.0, ui::TOUCH);
    crate::i18n::switch(ui, lang, false);
    ui.button("help-close", &t!("help-close"), close) || is_key_pressed(KeyCode::Escape)
}
