//! Immediate-mode widgets drawn with macroquad: buttons, labels, a text
//! field, a slider and panels, in one palette.
//!
//! A screen calls the widgets every frame; a button answers `true` on the
//! frame it is clicked (pressed and released inside it, so a drag that
//! starts on the board never clicks a button). Every button drawn is
//! remembered by name with its rectangle, so the app can tell whether the
//! pointer is over a control and publish the layout to the browser test.
//!
//! Text is drawn in DejaVu Sans (a subset of Latin-1, Russian Cyrillic
//! and a little punctuation, about 22 kB, embedded): macroquad's own pixel font has a
//! dotted zero that reads as an eight. Sizes are layout units; the glyphs
//! are rasterised at the size they finally take on the screen.

use crate::{platform, scale};
use macroquad::prelude::*;
use std::collections::BTreeMap;

/// The smallest height of a control a finger can hit (CSS pixels).
pub const TOUCH: f32 = 44.0;

thread_local! {
    static FONT: Option<Font> =
        load_ttf_font_from_bytes(include_bytes!("../assets/DejaVuSans-subset.ttf")).ok();
}

/// The parameters that draw `size`-unit text crisply at the window's zoom.
fn params(font: Option<&Font>, size: f32, color: Color) -> TextParams<'_> {
    let zoom = scale::zoom();
    let px = (size * zoom).round().clamp(1.0, 400.0);
    TextParams {
        font,
        font_size: px as u16,
        font_scale: size / px,
        color,
        ..Default::default()
    }
}

thread_local! {
    /// The glyphs (character, rasterised size) already in the font's atlas.
    static CACHED: std::cell::RefCell<std::collections::HashSet<(char, u16)>> =
        std::cell::RefCell::new(std::collections::HashSet::new());
}

/// Puts the glyphs of `s` at `p`'s size into the atlas before anything
/// draws them. A new glyph can grow the atlas, which replaces its texture:
/// the shapes queued earlier in the frame are drawn first, so none of them
/// binds the deleted texture (Chromium's "glBindTexture called with an
/// already deleted texture").
fn cache_glyphs(font: Option<&Font>, s: &str, p: &TextParams) {
    let Some(font) = font else { return };
    let px = (f32::from(p.font_size) * screen_dpi_scale()).ceil() as u16;
    let missing: Vec<char> = CACHED.with(|c| {
        let mut cached = c.borrow_mut();
        let mut missing: Vec<char> = s
            .chars()
            .filter(|ch| !cached.contains(&(*ch, px)))
            .collect();
        missing.sort_unstable();
        missing.dedup();
        for ch in &missing {
            cached.insert((*ch, px));
        }
        missing
    });
    if !missing.is_empty() {
        // SAFETY: flushing macroquad's queued draw calls from the frame
        // loop, the only thread that draws, between two draw calls.
        unsafe { get_internal_gl() }.flush();
        font.populate_font_cache(&missing, px);
    }
}

/// The smallest text size (layout units, which are CSS pixels on a
/// phone) a screen draws: a text drawn smaller is reported
/// ([`Ui::small_texts`]) as a layout to fix.
pub const MIN_TEXT: f32 = 12.0;

thread_local! {
    /// The rectangles the text drawn now must stay in (innermost last;
    /// the window when empty): see [`bounds`].
    static BOUNDS: std::cell::RefCell<Vec<Rect>> = const { std::cell::RefCell::new(Vec::new()) };
    /// The texts drawn since [`Ui::begin`] below [`MIN_TEXT`], with their
    /// sizes.
    static SMALL_TEXTS: std::cell::RefCell<BTreeMap<String, f32>> =
        const { std::cell::RefCell::new(BTreeMap::new()) };
}

/// Keeps the text drawn while it lives inside a rectangle (a panel, a
/// row of a list): a text that runs out of it is reported as cut, as
/// one [`fit`] had to cut is.
#[must_use = "the bounds hold while the guard lives"]
pub struct Bounds(());

/// Text drawn until the guard is dropped must stay inside `r` (and the
/// window): what runs out of it is reported among the cut texts.
pub fn bounds(r: Rect) -> Bounds {
    BOUNDS.with(|b| b.borrow_mut().push(r));
    Bounds(())
}

impl Drop for Bounds {
    fn drop(&mut self) {
        BOUNDS.with(|b| b.borrow_mut().pop());
    }
}

/// Whether a text `width` wide at `size` with its baseline at `(x, y)`
/// lies inside `r` (half a unit's slack for rounding; the glyphs rise
/// 0.8 of the size above the baseline and fall 0.2 below).
fn text_inside(x: f32, y: f32, width: f32, size: f32, r: Rect) -> bool {
    const SLACK: f32 = 0.5;
    x >= r.x - SLACK
        && x + width <= r.x + r.w + SLACK
        && y - 0.8 * size >= r.y - SLACK
        && y + 0.2 * size <= r.y + r.h + SLACK
}

/// Draws `s` with its baseline at `(x, y)`. A text that runs out of the
/// window or of the [`bounds`] it is drawn in is reported as cut, and one
/// smaller than [`MIN_TEXT`] as small.
pub fn draw_at_baseline(s: &str, x: f32, y: f32, size: f32, color: Color) {
    let width = FONT.with(|f| {
        let p = params(f.as_ref(), size, color);
        cache_glyphs(f.as_ref(), s, &p);
        draw_text_ex(s, x, y, p).width
    });
    if s.trim().is_empty() {
        return;
    }
    let window = Rect::new(0.0, 0.0, scale::size().x, scale::size().y);
    let within = BOUNDS
        .with(|b| b.borrow().last().copied())
        .unwrap_or(window);
    if !text_inside(x, y, width, size, window) || !text_inside(x, y, width, size, within) {
        CUT_TEXTS.with(|c| c.borrow_mut().insert(s.to_string()));
    }
    if size < MIN_TEXT - 0.01 {
        SMALL_TEXTS.with(|t| t.borrow_mut().insert(s.to_string(), size));
    }
}

/// The size of `s` at `size` units.
pub fn measure(s: &str, size: f32) -> TextDimensions {
    FONT.with(|f| {
        let p = params(f.as_ref(), size, WHITE);
        cache_glyphs(f.as_ref(), s, &p);
        measure_text(s, p.font, p.font_size, p.font_scale)
    })
}

/// The palette.
pub mod colors {
    use macroquad::prelude::Color;
    pub const BACKGROUND: Color = Color::new(0.16, 0.12, 0.09, 1.0);
    pub const PANEL: Color = Color::new(0.23, 0.17, 0.13, 1.0);
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
    /// The characters typed and the Backspaces pressed this frame, in the
    /// order they came (several can land in one frame).
    pub typed: Vec<Typed>,
    pub enter: bool,
    /// Text pasted this frame (Ctrl+V or the browser's paste event).
    pub paste: Option<String>,
    /// Whether a pointer resting over a button lights it: a mouse's does,
    /// a finger's does not (a touch screen's pointer stays where the last
    /// tap lifted, and would keep that button lit).
    pub hover: bool,
}

/// One keyboard edit of a text field.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Typed {
    Char(char),
    /// Backspace, held keys' repeats included.
    Backspace,
}

/// Collects the keyboard's edits in the order miniquad delivered them.
/// (macroquad's `get_char_pressed` hands the frame's characters out newest
/// first and `is_key_pressed` sees one Backspace a frame, so neither keeps
/// a fast typist's text.)
#[derive(Default)]
struct Typing(Vec<Typed>);

impl macroquad::miniquad::EventHandler for Typing {
    fn update(&mut self) {}
    fn draw(&mut self) {}
    fn char_event(&mut self, c: char, _mods: macroquad::miniquad::KeyMods, _repeat: bool) {
        if !c.is_control() {
            self.0.push(Typed::Char(c));
        }
    }
    fn key_down_event(&mut self, key: KeyCode, _mods: macroquad::miniquad::KeyMods, _repeat: bool) {
        if key == KeyCode::Backspace {
            self.0.push(Typed::Backspace);
        }
    }
}

thread_local! {
    /// Our subscription to macroquad's queue of input events.
    static SUBSCRIBER: usize = macroquad::input::utils::register_input_subscriber();
}

/// This frame's edits, in order.
fn typed() -> Vec<Typed> {
    let mut typing = Typing::default();
    SUBSCRIBER.with(|&id| macroquad::input::utils::repeat_all_miniquad_input(&mut typing, id));
    typing.0
}

/// `value` after the `typed` edits in order, at most `max` characters.
pub fn edit(value: &mut String, typed: &[Typed], max: usize) {
    for t in typed {
        match *t {
            Typed::Char(c) if value.chars().count() < max => value.push(c),
            Typed::Char(_) => {}
            Typed::Backspace => {
                value.pop();
            }
        }
    }
}

impl Input {
    /// Reads this frame's input from macroquad (touch arrives as mouse).
    pub fn read() -> Input {
        // The characters are read from the subscription; macroquad's own
        // queue is emptied so it cannot grow.
        while get_char_pressed().is_some() {}
        Input {
            pointer: scale::pointer(),
            pressed: is_mouse_button_pressed(MouseButton::Left),
            down: is_mouse_button_down(MouseButton::Left),
            released: is_mouse_button_released(MouseButton::Left),
            alt_pressed: is_mouse_button_pressed(MouseButton::Right),
            wheel: mouse_wheel().1,
            typed: typed(),
            enter: is_key_pressed(KeyCode::Enter) || is_key_pressed(KeyCode::KpEnter),
            paste: platform::pasted(),
            hover: !platform::coarse_pointer(),
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
    /// The labels of the buttons drawn this frame, by name.
    labels: BTreeMap<String, String>,
    /// The buttons whose label did not fit whole this frame.
    cut: std::collections::BTreeSet<String>,
    /// The text field with the keyboard focus.
    focus: Option<String>,
    /// Whether a widget took this frame's press.
    captured: bool,
    /// Inside [`Ui::without_input`]: a modal covers what is drawn, so no
    /// native text input may be laid over it.
    covered: bool,
    /// The button drawn lit by the pointer resting over it this frame.
    hovered: Option<String>,
    /// Inside [`Ui::even_labels`]: the size no label may start above.
    label_cap: Option<f32>,
    /// Each button's label this frame: the size it would take alone, and
    /// the size drawn (by name).
    sizes: BTreeMap<String, (f32, f32)>,
    /// Each button's rectangle and the one size of its group, from the
    /// last frame ([`even_groups`]).
    groups: Vec<(Rect, f32)>,
}

/// Draws `text` with its top-left corner near `(x, y)` at `size` pixels.
pub fn text(s: &str, x: f32, y: f32, size: f32, color: Color) {
    draw_at_baseline(s, x, y + size * 0.8, size, color);
}

/// Draws `text` centred in `r`.
pub fn text_centred(s: &str, r: Rect, size: f32, color: Color) {
    let m = measure(s, size);
    draw_at_baseline(
        s,
        r.x + (r.w - m.width) / 2.0,
        r.y + (r.h + size * 0.72) / 2.0,
        size,
        color,
    );
}

/// Width of `s` at `size` pixels.
pub fn text_width(s: &str, size: f32) -> f32 {
    measure(s, size).width
}

/// Draws `s` at `(x, y)` in at most `width` units: at `size`, smaller
/// (down to [`MIN_TEXT`]) where it is too wide, and cut with an ellipsis only
/// below that.
pub fn text_in(s: &str, x: f32, y: f32, size: f32, width: f32, color: Color) {
    let mut sz = size;
    while sz > MIN_TEXT && text_width(s, sz) > width {
        sz = (sz - 1.0).max(MIN_TEXT);
    }
    // The smaller text stays on the line the full size would take.
    text(&fit(s, sz, width), x, y + (size - sz) * 0.5, sz, color);
}

thread_local! {
    /// The texts [`fit`] had to cut since [`Ui::begin`] (for the test
    /// report: a text a screen shows cut is a layout to fix).
    static CUT_TEXTS: std::cell::RefCell<std::collections::BTreeSet<String>> =
        const { std::cell::RefCell::new(std::collections::BTreeSet::new()) };
}

/// `s` cut (with an ellipsis) to at most `width` units at `size`.
pub fn fit(s: &str, size: f32, width: f32) -> String {
    if text_width(s, size) <= width {
        return s.to_string();
    }
    CUT_TEXTS.with(|c| c.borrow_mut().insert(s.to_string()));
    let mut cut: String = s.to_string();
    while !cut.is_empty() {
        cut.pop();
        let candidate = format!("{}…", cut.trim_end());
        if text_width(&candidate, size) <= width {
            return candidate;
        }
    }
    String::new()
}

/// The words of `label` in two lines as even as can be, split at a space.
pub fn split_in_two(label: &str) -> Option<(&str, &str)> {
    let half = label.chars().count() / 2;
    label
        .char_indices()
        .filter(|(_, c)| *c == ' ')
        .min_by_key(|(i, _)| label[..*i].chars().count().abs_diff(half))
        .map(|(i, _)| (label[..i].trim_end(), label[i + 1..].trim_start()))
}

/// How a button's label is set in its button.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Setting {
    /// One line at this size.
    Line(f32),
    /// Two lines (split at a space) at this size.
    Lines(f32),
}

impl Setting {
    fn size(self) -> f32 {
        match self {
            Setting::Line(s) | Setting::Lines(s) => s,
        }
    }
}

/// How `label` is set in a button of `r`, no larger than `cap`: one line,
/// smaller as needed down to [`MIN_TEXT`]; a label still too wide, or
/// one that would read under [`READABLE`] on one line while two lines
/// read larger, takes two lines where the button is finger-tall;
/// whatever is left too wide ends with an ellipsis (down to 10 units).
/// `width` measures a text at a size.
fn setting(label: &str, r: Rect, cap: f32, width: impl Fn(&str, f32) -> f32) -> Setting {
    let room = label_room(r);
    let fits = |s: &str, size: f32| width(s, size) <= room;
    let mut size = label_start(r).min(cap);
    while size > MIN_TEXT && !fits(label, size) {
        size = (size - 1.0).max(MIN_TEXT);
    }
    let line_fits = fits(label, size);
    if r.h >= 40.0 && (!line_fits || size < READABLE) {
        if let Some((a, b)) = split_in_two(label) {
            let two = |size: f32| fits(a, size) && fits(b, size);
            let mut small = (r.h * 0.34).clamp(10.0, 16.0).min(cap.max(10.0));
            while small > 10.0 && !two(small) {
                small = (small - 1.0).max(10.0);
            }
            if !line_fits || (two(small) && small > size) {
                return Setting::Lines(small);
            }
        }
    }
    while size > 10.0 && !fits(label, size) {
        size = (size - 1.0).max(10.0);
    }
    Setting::Line(size)
}

/// The size a label is readable at on a phone: one that would be smaller
/// on one line takes two where they read larger.
const READABLE: f32 = 13.0;

/// Draws a button's `label` in `r` as [`setting`] sets it, so no label
/// ever runs past its button. Whether the label shows whole, and its size.
fn label_in(label: &str, r: Rect, color: Color, cap: f32) -> (bool, f32) {
    let room = label_room(r);
    let fits = |s: &str, size: f32| text_width(s, size) <= room;
    let set = setting(label, r, cap, text_width);
    match (set, split_in_two(label)) {
        (Setting::Lines(small), Some((a, b))) => {
            let line = small * 1.1;
            let top = Rect::new(r.x, r.y + r.h / 2.0 - line, r.w, line);
            let bottom = Rect::new(r.x, r.y + r.h / 2.0, r.w, line);
            text_centred(&fit(a, small, room), top, small, color);
            text_centred(&fit(b, small, room), bottom, small, color);
            (fits(a, small) && fits(b, small), small)
        }
        (set, _) => {
            let size = set.size();
            text_centred(&fit(label, size, room), r, size, color);
            (fits(label, size), size)
        }
    }
}

/// The groups of buttons drawn in a frame, from each button's rectangle
/// and the size its label would take alone: buttons of one height whose
/// tops are level form a row, buttons of one width whose left edges are
/// level a column, and rows and columns that share a button one group (a
/// grid of buttons is one group). Each button's rectangle with its
/// group's size, the smallest of the group's.
fn even_groups(buttons: &[(Rect, f32)]) -> Vec<(Rect, f32)> {
    let n = buttons.len();
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for i in 0..n {
        for j in i + 1..n {
            let (a, b) = (buttons[i].0, buttons[j].0);
            if same_row(a, b) || same_column(a, b) {
                let (ri, rj) = (root(&mut parent, i), root(&mut parent, j));
                parent[ri] = rj;
            }
        }
    }
    let mut size = vec![f32::INFINITY; n];
    for (i, (_, alone)) in buttons.iter().enumerate() {
        let r = root(&mut parent, i);
        size[r] = size[r].min(*alone);
    }
    (0..n)
        .map(|i| (buttons[i].0, size[root(&mut parent, i)]))
        .collect()
}

/// The size each of `buttons` (label, rectangle) draws its label at when
/// they are drawn in one frame: its group's ([`even_groups`]), with
/// `width` measuring a text at a size. For the screens' layout tests.
#[cfg(test)]
pub fn group_label_sizes(buttons: &[(&str, Rect)], width: impl Fn(&str, f32) -> f32) -> Vec<f32> {
    let alone: Vec<(Rect, f32)> = buttons
        .iter()
        .map(|(label, r)| (*r, setting(label, *r, f32::INFINITY, &width).size()))
        .collect();
    even_groups(&alone)
        .iter()
        .zip(buttons)
        .map(|((r, group), (label, _))| setting(label, *r, *group, &width).size())
        .collect()
}

/// Whether `a` and `b` stand in one row (level tops, one height, to a
/// tenth of a unit).
fn same_row(a: Rect, b: Rect) -> bool {
    (a.y - b.y).abs() < 0.1 && (a.h - b.h).abs() < 0.1
}

/// Whether `a` and `b` stand in one column (level left edges, one width
/// and one height, to a tenth of a unit).
fn same_column(a: Rect, b: Rect) -> bool {
    (a.x - b.x).abs() < 0.1 && (a.w - b.w).abs() < 0.1 && (a.h - b.h).abs() < 0.1
}

/// The size the group of a button at `r` takes (from `groups`, the last
/// frame's): that of the button drawn there, else that of its row or
/// column; none (infinite) for a button new there.
fn group_size(groups: &[(Rect, f32)], r: Rect) -> f32 {
    let same = |a: Rect| (a.x - r.x).abs() < 0.1 && (a.w - r.w).abs() < 0.1 && same_row(a, r);
    groups
        .iter()
        .find(|(a, _)| same(*a))
        .or_else(|| {
            groups
                .iter()
                .find(|(a, _)| same_row(*a, r) || same_column(*a, r))
        })
        .map_or(f32::INFINITY, |(_, size)| *size)
}

/// The width a button of `r` gives its label: a narrow button (the
/// sandbox's speeds on a phone) keeps less margin.
fn label_room(r: Rect) -> f32 {
    r.w - if r.w < 60.0 { 4.0 } else { 10.0 }
}

/// The size a label in a button of `r` starts at, before it shrinks to fit.
fn label_start(r: Rect) -> f32 {
    (r.h * 0.45).clamp(12.0, 20.0)
}

/// The one size for the labels of a row of buttons the size of `r`: the
/// largest (from [`label_start`] down to 12 units) at which every one of
/// `labels` fits one line, as `width(label, size)` measures it. Drawn at
/// it, a row whose longest label must shrink shrinks all of them alike,
/// instead of one label smaller than its neighbours.
fn even_size<S: AsRef<str>>(labels: &[S], r: Rect, width: impl Fn(&str, f32) -> f32) -> f32 {
    let room = label_room(r);
    let mut size = label_start(r);
    while size > 12.0 && labels.iter().any(|l| width(l.as_ref(), size) > room) {
        size -= 1.0;
    }
    size.max(12.0)
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
        // The groups of the last frame set this frame's sizes.
        let drawn: Vec<(Rect, f32)> = self
            .buttons
            .iter()
            .filter_map(|(name, r)| Some((*r, self.sizes.get(name)?.0)))
            .collect();
        self.groups = even_groups(&drawn);
        self.buttons.clear();
        self.labels.clear();
        self.cut.clear();
        self.sizes.clear();
        CUT_TEXTS.with(|c| c.borrow_mut().clear());
        SMALL_TEXTS.with(|t| t.borrow_mut().clear());
        BOUNDS.with(|b| b.borrow_mut().clear());
        self.captured = false;
        self.hovered = None;
        // Native inputs not laid over a field last frame go away.
        platform::field_sweep();
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
        let covered = std::mem::replace(&mut self.covered, true);
        let r = f(self);
        self.covered = covered;
        self.input = input;
        r
    }

    /// The buttons drawn this frame, as `{"name": [x, y, w, h]}` in CSS
    /// pixels from the window's top-left.
    pub fn layout(&self) -> serde_json::Value {
        serde_json::Value::Object(
            self.buttons
                .iter()
                .map(|(k, r)| {
                    let r = scale::css(*r);
                    (k.clone(), serde_json::json!([r.x, r.y, r.w, r.h]))
                })
                .collect(),
        )
    }

    /// The labels of the buttons drawn this frame, as `{"name": "label"}`.
    pub fn labels(&self) -> serde_json::Value {
        serde_json::Value::Object(
            self.labels
                .iter()
                .map(|(k, v)| (k.clone(), v.clone().into()))
                .collect(),
        )
    }

    /// Runs `f`, which draws a row of buttons the size of `r` labelled
    /// `labels`, with every label at one size ([`even_size`]).
    pub fn even_labels<S: AsRef<str>, R>(
        &mut self,
        labels: &[S],
        r: Rect,
        f: impl FnOnce(&mut Ui) -> R,
    ) -> R {
        let cap = even_size(labels, r, text_width);
        let outer = self.label_cap.replace(cap);
        let out = f(self);
        self.label_cap = outer;
        out
    }

    /// The button lit by a resting pointer this frame, if any.
    pub fn hovered(&self) -> Option<&str> {
        self.hovered.as_deref()
    }

    /// The size each button's label was drawn at this frame, as
    /// `{"name": size}` in layout units.
    pub fn label_sizes(&self) -> serde_json::Value {
        serde_json::Value::Object(
            self.sizes
                .iter()
                .map(|(k, (_, drawn))| (k.clone(), f64::from(*drawn).into()))
                .collect(),
        )
    }

    /// The texts cut to fit this frame (buttons' labels and the rest).
    pub fn cut_texts(&self) -> serde_json::Value {
        CUT_TEXTS.with(|c| c.borrow().iter().cloned().collect::<Vec<_>>().into())
    }

    /// The texts drawn this frame below [`MIN_TEXT`], as `{"text": size}`
    /// in layout units.
    pub fn small_texts(&self) -> serde_json::Value {
        SMALL_TEXTS.with(|t| {
            serde_json::Value::Object(
                t.borrow()
                    .iter()
                    .map(|(k, v)| (k.clone(), f64::from(*v).into()))
                    .collect(),
            )
        })
    }

    /// The names of the buttons whose label was cut this frame.
    pub fn cut(&self) -> serde_json::Value {
        self.cut.iter().cloned().collect::<Vec<_>>().into()
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
        let lit = hot && !held && (self.input.hover || self.input.down);
        if lit {
            self.hovered = Some(name.to_string());
        }
        let color = if !enabled {
            colors::BUTTON_OFF
        } else if selected || held {
            colors::ACCENT
        } else if lit {
            colors::BUTTON_HOT
        } else {
            colors::BUTTON
        };
        draw_rectangle(r.x, r.y + 2.0, r.w, r.h, Color::new(0.0, 0.0, 0.0, 0.35));
        draw_rectangle(r.x, r.y, r.w, r.h, color);
        draw_rectangle_lines(r.x, r.y, r.w, r.h, 1.0, Color::new(1.0, 0.9, 0.7, 0.25));
        let tc = if !enabled {
            colors::MUTED
        } else if selected || held {
            colors::BACKGROUND
        } else {
            colors::TEXT
        };
        self.labels.insert(name.to_string(), label.to_string());
        // As large as its group allows (the smallest size of the group's
        // labels last frame), within an even row's cap.
        let alone = setting(label, r, f32::INFINITY, text_width).size();
        let group = group_size(&self.groups, r);
        let cap = group.min(self.label_cap.unwrap_or(f32::INFINITY));
        let (whole, drawn) = label_in(label, r, tc, cap);
        if !whole {
            self.cut.insert(name.to_string());
        }
        self.sizes.insert(name.to_string(), (alone, drawn));
        if hot && self.input.pressed {
            self.captured = true;
        }
        enabled && hot && self.input.released && self.press_at.is_some_and(|p| r.contains(p))
    }

    /// A one-line text field editing `value` (at most `max` characters);
    /// `true` when Enter is pressed in it. On a touch screen a native input
    /// is laid over it ([`platform::field_place`]): a tap opens the phone's
    /// keyboard, and what is typed there comes back here.
    pub fn text_field(
        &mut self,
        name: &str,
        value: &mut String,
        r: Rect,
        placeholder: &str,
        max: usize,
    ) -> bool {
        self.buttons.insert(name.to_string(), r);
        let native = !self.covered && platform::coarse_pointer();
        let mut entered = false;
        if native {
            let c = scale::css(r);
            platform::field_place(name, [c.x, c.y, c.w, c.h], value, placeholder, max);
            if let Some(typed) = platform::field_take(name) {
                *value = typed
                    .chars()
                    .filter(|c| !c.is_control())
                    .take(max)
                    .collect();
            }
            let flags = platform::field_flags(name);
            if flags.focused {
                self.focus = Some(name.to_string());
            } else if self.focus.as_deref() == Some(name) {
                self.focus = None;
            }
            entered = flags.entered;
        } else if self.input.pressed && r.contains(self.input.pointer) {
            self.focus = Some(name.to_string());
            self.captured = true;
        }
        let focused = self.focus.as_deref() == Some(name);
        if focused && !native {
            edit(value, &self.input.typed, max);
            if let Some(pasted) = &self.input.paste {
                let room = max.saturating_sub(value.chars().count());
                value.extend(pasted.chars().filter(|c| !c.is_control()).take(room));
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
        let size = (r.h * 0.45).clamp(12.0, 20.0);
        let y = r.y + (r.h - size) / 2.0;
        if value.is_empty() && !focused {
            // The placeholder smaller (down to 12 units) rather than cut.
            text_in(placeholder, r.x + 8.0, y, size, r.w - 16.0, colors::MUTED);
        } else {
            text(
                &fit(value, size, r.w - 16.0),
                r.x + 8.0,
                y,
                size,
                colors::TEXT,
            );
        }
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

#[cfg(test)]
mod tests {
    use super::*;

    fn chars(s: &str) -> Vec<Typed> {
        s.chars().map(Typed::Char).collect()
    }

    #[test]
    fn a_long_label_splits_at_the_space_nearest_its_middle() {
        assert_eq!(
            split_in_two("Компьютер: адаптивный"),
            Some(("Компьютер:", "адаптивный"))
        );
        assert_eq!(
            split_in_two("Play the computer (adaptive)"),
            Some(("Play the computer", "(adaptive)"))
        );
        assert_eq!(split_in_two("Лидеры"), None);
    }

    #[test]
    fn a_row_of_labels_shrinks_evenly_to_its_longest() {
        // A font whose letters are 0.6 of its size wide.
        let width = |s: &str, size: f32| s.chars().count() as f32 * size * 0.6;
        let r = Rect::new(0.0, 0.0, 56.0, TOUCH);
        // "0.25x" needs a smaller size than "1x": the whole row takes it.
        let even = even_size(&["-1x", "0.1x", "0.25x", "1x"], r, width);
        assert!(width("0.25x", even) <= label_room(r));
        assert!(width("0.25x", even + 1.0) > label_room(r));
        assert!(even < label_start(r));
        // Labels that all fit keep the full size; one too long for any
        // size stops at the smallest.
        assert_eq!(even_size(&["1x", "2x"], r, width), label_start(r));
        assert_eq!(even_size(&["a label far too long"], r, width), 12.0);
    }

    #[test]
    fn the_buttons_of_a_row_or_a_grid_share_the_smallest_size_and_others_keep_theirs() {
        let width = |s: &str, size: f32| s.chars().count() as f32 * size * 0.6;
        let alone = |label: &str, r: Rect| setting(label, r, f32::INFINITY, width).size();
        // A 2 x 2 grid whose one long label is bottom right, and a button
        // elsewhere.
        let grid = [
            Rect::new(0.0, 10.0, 120.0, TOUCH),
            Rect::new(130.0, 10.0, 120.0, TOUCH),
            Rect::new(0.0, 60.0, 120.0, TOUCH),
            Rect::new(130.0, 60.0, 120.0, TOUCH),
        ];
        let apart = Rect::new(300.0, 200.0, 90.0, TOUCH);
        let labels = ["Lobby", "Rules", "Sound", "Computer: adaptive"];
        let mut drawn: Vec<(Rect, f32)> = grid
            .iter()
            .zip(labels)
            .map(|(r, l)| (*r, alone(l, *r)))
            .collect();
        drawn.push((apart, alone("Import", apart)));
        let long = alone("Computer: adaptive", grid[3]);
        assert!(long < alone("Lobby", grid[0]), "the long label shrinks");
        let groups = even_groups(&drawn);
        // The top left button shares no row or column with the long one,
        // but the grid is one group.
        for r in grid {
            assert_eq!(group_size(&groups, r), long, "{r:?}");
        }
        assert_eq!(group_size(&groups, apart), label_start(apart));
        assert_eq!(group_size(&[], apart), f32::INFINITY);
        // Drawn within the group's size, a short label matches the long one.
        assert_eq!(setting("Lobby", grid[0], long, width).size(), long);
        // A label set on two lines gives its group that smaller size.
        let narrow = Rect::new(0.0, 0.0, 60.0, TOUCH);
        let two = setting("Play the computer", narrow, f32::INFINITY, width);
        assert!(matches!(two, Setting::Lines(_)), "{two:?}");
    }

    #[test]
    fn keys_typed_in_one_frame_keep_their_order() {
        let mut v = String::new();
        edit(&mut v, &chars("abcdefgh"), 40);
        assert_eq!(v, "abcdefgh");
        let mut v = String::from("An");
        edit(&mut v, &chars("ka"), 40);
        assert_eq!(v, "Anka");
    }

    #[test]
    fn every_backspace_counts_in_its_place() {
        let mut v = String::from("Anak");
        let mut typed = vec![Typed::Backspace, Typed::Backspace];
        typed.extend(chars("ka"));
        typed.push(Typed::Backspace);
        typed.push(Typed::Char('a'));
        edit(&mut v, &typed, 40);
        assert_eq!(v, "Anka");
    }

    #[test]
    fn typing_stops_at_the_limit_and_backspace_on_empty_is_harmless() {
        let mut v = String::new();
        edit(&mut v, &[Typed::Backspace], 3);
        assert_eq!(v, "");
        edit(&mut v, &chars("abcdef"), 3);
        assert_eq!(v, "abc");
    }
}
