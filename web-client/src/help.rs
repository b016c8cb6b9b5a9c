//! "How to play": the rules of Chapaev and the controls, as a panel any
//! screen can open over itself.

use crate::ui::{self, colors, Ui};
use macroquad::prelude::*;

/// The rules and controls, a paragraph per line.
pub const RULES: [&str; 9] = [
    "Each side has eight checkers on its own row. White shoots first.",
    "Your turn: press one of your checkers, drag back like a slingshot and let go.",
    "The farther you pull, the harder the flick (see the arrow and the meter); drag back onto the checker to cancel.",
    "A checker whose centre leaves the board is out.",
    "Knock off enemy checkers without losing your own and you shoot again; otherwise the turn passes.",
    "When only one colour is left the round is won: the winner's row moves a row closer to the other side and the winner starts the next round.",
    "When the rows meet, the winner pushes the loser back. A row that reaches the far edge wins the match.",
    "Each turn has a clock: run out and the turn passes; three times in a row and the match is lost.",
    "A dropped connection keeps your seat: the game reconnects by itself.",
];

/// Words of `text` wrapped to lines at most `width` pixels wide.
fn wrap(text: &str, size: f32, width: f32) -> Vec<String> {
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
    let wrapped: Vec<Vec<String>> = RULES.iter().map(|r| wrap(r, size, text_w)).collect();
    let lines: usize = wrapped.iter().map(Vec::len).sum();
    let ph = (90.0 + lines as f32 * (size + 4.0) + RULES.len() as f32 * 8.0 + 64.0).min(h - 20.0);
    let r = Rect::new((w - pw) / 2.0, (h - ph) / 2.0, pw, ph);
    ui::panel(r);
    ui::text(
        "How to play Chapaev",
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
        r.x + r.w - 120.0,
        r.y + r.h - ui::TOUCH - 12.0,
        100.0,
        ui::TOUCH,
    );
    ui.button("help-close", "Got it", close) || is_key_pressed(KeyCode::Escape)
}
