//! Immediate-mode widgets drawn with macroquad: buttons, labels, a text
//! field, a slider and panels, in one palette.
//!
//! A screen calls the widgets every frame; a button answers `true` on the
//! frame it is clicked (pressed and released inside it, so a drag that
//! starts on the board never clicks a button). Every button drawn is
//! remembered by name with its rectangle, so the app can tell whether the
//! pointer is over a control and publish the layout to the browser test.

use macroquad::prelude::*;
use std::collections::BTreeMap;

/// The palette.
pub mod colors {
    use macroquad::prelude::Color;
    pub const BACKGROUND: Color = Color::new(0.16, 0.12, 0.09, 1.0);
    pub const PANEL: Color = Color::new(0.23, 0.17, 0.13, 0.94);
    pub const TEXT: Color = Color::new(0.95, 0.90, 0.80, 1.0);
    pub const MUTED: Color = Color::new(0.72, 0.65, 0.55, 1.0);
    pub const ACCENT: Color = Color::new(0.93, 0.66, 0.25, 1.0);
    pub const BUTTON: Color = Color::new(0.40, 0.27, 0.17, 1.0);
    pub const BUTTON_HOT: Color = Color::new(0.52, 0.36, 0.22, 1.0);
    pub const BUTTON_OFF: Color = Color::new(0.30, 0.25, 0.21, 1.0);
    pub const DANGER: Color = Color::new(0.80, 0.30, 0.25, 1.0);
    pub const GOOD: Color = Color::new(0.45, 0.75, 0.40, 1.0);
}

/// The pointer and keyboard as one frame saw them.
#[derive(Clone, Debug, Default)]
pub struct Input {
    pub pointer: Vec2,
    pub pressed: bool,
    pub down: bool,
    pub released: bool,
    /// Secondary (right) button pressed this frame.
    pub alt_pressed: bool,
    pub wheel: f32,
    pub chars: Vec<char>,
    pub backspace: bool,
    pub enter: bool,
}

impl Input {
    /// Reads this frame's input from macroquad (touch arrives as mouse).
    pub fn read() -> Input {
        let (x, y) = mouse_position();
        let mut chars = Vec::new();
        while let Some(c) = get_char_pressed() {
            if !c.is_control() {
                chars.push(c);
            }
        }
        Input {
            pointer: vec2(x, y),
            pressed: is_mouse_button_pressed(MouseButton::Left),
            down: is_mouse_button_down(MouseButton::Left),
            released: is_mouse_button_released(MouseButton::Left),
            alt_pressed: is_mouse_button_pressed(MouseButton::Right),
            wheel: mouse_wheel().1,
            chars,
            backspace: is_key_pressed(KeyCode::Backspace),
            enter: is_key_pressed(KeyCode::Enter) || is_key_pressed(KeyCode::KpEnter),
        }
    }
}

/// Widget state kept across frames.
#[derive(Default)]
pub struct Ui {
    pub input: Input,
    /// Where the current press started (a click needs press and release
    /// inside the same button).
    press_at: Option<Vec2>,
    /// Buttons drawn this frame, by name.
    buttons: BTreeMap<String, Rect>,
    /// The text field with the keyboard focus.
    focus: Option<String>,
    /// Whether a widget took this frame's press.
    captured: bool,
}

/// Draws `text` with its top-left corner near `(x, y)` at `size` pixels.
pub fn text(s: &str, x: f32, y: f32, size: f32, color: Color) {
    draw_text(s, x, y + size * 0.75, size, color);
}

/// Draws `text` centred in `r`.
pub fn text_centred(s: &str, r: Rect, size: f32, color: Color) {
    let m = measure_text(s, None, size as u16, 1.0);
    draw_text(
        s,
        r.x + (r.w - m.width) / 2.0,
        r.y + (r.h + m.offset_y * 0.8) / 2.0,
        size,
        color,
    );
}

/// Width of `s` at `size` pixels.
pub fn text_width(s: &str, size: f32) -> f32 {
    measure_text(s, None, size as u16, 1.0).width
}

/// Draws a rounded-looking panel.
pub fn panel(r: Rect) {
    draw_rectangle(r.x, r.y, r.w, r.h, colors::PANEL);
    draw_rectangle_lines(r.x, r.y, r.w, r.h, 1.5, Color::new(0.45, 0.33, 0.24, 1.0));
}

impl Ui {
    /// Starts a frame with fresh input.
    pub fn begin(&mut self, input: Input) {
        if input.pressed {
            self.press_at = Some(input.pointer);
        }
        self.input = input;
        self.buttons.clear();
        self.captured = false;
    }

    /// Ends the frame (forgets a finished press).
    pub fn end(&mut self) {
        if self.input.released || !self.input.down {
            self.press_at = None;
        }
        if self.input.pressed && !self.captured {
            self.focus = None;
        }
    }

    /// Runs `f` with the pointer and keyboard hidden from it: a modal
    /// panel is open above what `f` draws.
    pub fn without_input<R>(&mut self, f: impl FnOnce(&mut Ui) -> R) -> R {
        let input = std::mem::take(&mut self.input);
        self.input.pointer = vec2(f32::NEG_INFINITY, f32::NEG_INFINITY);
        let r = f(self);
        self.input = input;
        r
    }

    /// The buttons drawn this frame, as `{"name": [x, y, w, h]}`.
    pub fn layout(&self) -> serde_json::Value {
        serde_json::Value::Object(
            self.buttons
                .iter()
                .map(|(k, r)| (k.clone(), serde_json::json!([r.x, r.y, r.w, r.h])))
                .collect(),
        )
    }

    /// A button; `true` on the frame it is clicked.
    pub fn button(&mut self, name: &str, label: &str, r: Rect) -> bool {
        self.button_styled(name, label, r, true, false)
    }

    /// A button that may be disabled or shown as selected.
    pub fn button_styled(
        &mut self,
        name: &str,
        label: &str,
        r: Rect,
        enabled: bool,
        selected: bool,
    ) -> bool {
        self.buttons.insert(name.to_string(), r);
        let hot = enabled && r.contains(self.input.pointer);
        let held = hot && self.input.down && self.press_at.is_some_and(|p| r.contains(p));
        let color = if !enabled {
            colors::BUTTON_OFF
        } else if selected || held {
            colors::ACCENT
        } else if hot {
            colors::BUTTON_HOT
        } else {
            colors::BUTTON
        };
        draw_rectangle(r.x, r.y + 2.0, r.w, r.h, Color::new(0.0, 0.0, 0.0, 0.35));
        draw_rectangle(r.x, r.y, r.w, r.h, color);
        draw_rectangle_lines(r.x, r.y, r.w, r.h, 1.0, Color::new(1.0, 0.9, 0.7, 0.25));
        let size = (r.h * 0.5).clamp(12.0, 22.0);
        let tc = if !enabled {
            colors::MUTED
        } else if selected || held {
            colors::BACKGROUND
        } else {
            colors::TEXT
        };
        text_centred(label, r, size, tc);
        if hot && self.input.pressed {
            self.captured = true;
        }
        enabled && hot && self.input.released && self.press_at.is_some_and(|p| r.contains(p))
    }

    /// A one-line text field editing `value` (at most `max` characters);
    /// `true` when Enter is pressed in it.
    pub fn text_field(
        &mut self,
        name: &str,
        value: &mut String,
        r: Rect,
        placeholder: &str,
        max: usize,
    ) -> bool {
        self.buttons.insert(name.to_string(), r);
        if self.input.pressed && r.contains(self.input.pointer) {
            self.focus = Some(name.to_string());
            self.captured = true;
        }
        let focused = self.focus.as_deref() == Some(name);
        let mut entered = false;
        if focused {
            for &c in &self.input.chars {
                if value.chars().count() < max {
                    value.push(c);
                }
            }
            if self.input.backspace {
                value.pop();
            }
            entered = self.input.enter;
        }
        draw_rectangle(r.x, r.y, r.w, r.h, Color::new(0.10, 0.08, 0.06, 1.0));
        let border = if focused {
            colors::ACCENT
        } else {
            Color::new(0.45, 0.33, 0.24, 1.0)
        };
        draw_rectangle_lines(r.x, r.y, r.w, r.h, 1.5, border);
        let size = (r.h * 0.55).clamp(12.0, 22.0);
        let (shown, color) = if value.is_empty() && !focused {
            (placeholder.to_string(), colors::MUTED)
        } else {
            (value.clone(), colors::TEXT)
        };
        let y = r.y + (r.h - size) / 2.0;
        text(&shown, r.x + 8.0, y, size, color);
        if focused && (get_time() * 2.0) as i64 % 2 == 0 {
            let x = r.x + 9.0 + text_width(value, size);
            draw_line(x, y, x, y + size, 1.5, colors::TEXT);
        }
        entered
    }

    /// A horizontal slider over `[lo, hi]`; returns the new value.
    pub fn slider(&mut self, name: &str, value: f64, lo: f64, hi: f64, r: Rect) -> f64 {
        self.buttons.insert(name.to_string(), r);
        let mut v = value;
        let grabbing = self.input.down && self.press_at.is_some_and(|p| r.contains(p));
        if grabbing {
            self.captured = true;
            let f = ((self.input.pointer.x - r.x) / r.w).clamp(0.0, 1.0) as f64;
            v = lo + f * (hi - lo);
        }
        let mid = r.y + r.h / 2.0;
        draw_rectangle(r.x, mid - 2.0, r.w, 4.0, colors::BUTTON_OFF);
        let f = ((v - lo) / (hi - lo)).clamp(0.0, 1.0) as f32;
        draw_rectangle(r.x, mid - 2.0, r.w * f, 4.0, colors::ACCENT);
        draw_circle(r.x + r.w * f, mid, r.h * 0.35, colors::TEXT);
        v
    }

    /// Whether a widget took this frame's press (so the board should not).
    pub fn captured(&self) -> bool {
        self.captured
    }
}
