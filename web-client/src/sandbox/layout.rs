//! Where everything of the sandbox goes, as pure functions from the
//! window's size (and whether a body's controls show) to rectangles in
//! layout units: the world, the toolbar, the side panel and the playback
//! bar; every button of the toolbar, the side panel and the bar; the
//! overlays over the world; and the view that fits a scene into the
//! world. A window narrower than a desktop's (a phone) gets the compact
//! layout: held upright, the tools wrap in rows above the world, the
//! playback bar takes three rows below it and the side panel opens over the
//! world; held sideways (wider than tall), where height is short, the
//! tools stand in columns down the left edge, the bar lies below the world
//! right of them, and the side panel opens over the world's right part in
//! two columns. A phone too small for that (the world would be under
//! [`MIN_WORLD`] sideways, or the tools would take four rows upright) gets
//! the tight layout: the lobby, *Tools*, *Panel* and the language switch
//! stand alone (one column at the left sideways, one row at the top
//! upright), the tools and the speeds open in a menu over the world, and
//! the bar takes one row. Nothing here draws, so all of it is tested
//! natively.

use super::sim::SPEEDS;
use super::tools::TOOLS;
use crate::ui::TOUCH;
use crate::viewport::Viewport;
use ::glam::DVec2;
use engine::Scene;
use macroquad::prelude::{vec2, Rect};

/// Height of the toolbar and the playback bar; width of the side panel.
const TOP: f32 = 56.0;
const BOTTOM: f32 = 60.0;
const SIDE: f32 = 262.0;
/// The narrowest window the desktop layout fits (narrower ones get the
/// compact layout).
const MIN_WIDTH: f32 = 1000.0;
/// The width from which a desktop's playback bar takes wider buttons.
const WIDE: f32 = 1200.0;
/// Gap between controls.
pub const GAP: f32 = 4.0;
/// The compact toolbar's buttons: Lobby, the tools, Wall/Edge, Panel,
/// Import, Export (about 70 units each).
const TOOLBAR_BUTTONS: usize = TOOLS.len() + 5;

/// Height of a row of the side panel (a finger-sized control and a gap).
const ROW: f32 = TOUCH + GAP;

/// Width the statistics panel takes from the world area (with margins).
pub const STATS_W: f32 = 248.0;

/// Where a slider of a side panel row starts, right of its label.
const SLIDER_AT: f32 = 118.0;

/// Width of a button of the sideways layout's columns of tools (room for
/// "Скорость" at 12 units and more).
const RAIL_BUTTON: f32 = 78.0;
/// Width of a button of the tight layout's column.
const TIGHT_BUTTON: f32 = 72.0;

/// Width of a column of the side panel in two columns.
const SIDE_COLUMN: f32 = 236.0;
/// The narrowest column of a side panel in two columns.
const SIDE_COLUMN_MIN: f32 = 228.0;

/// The smallest world the sideways layout leaves (layout units): a window
/// whose columns of tools would leave less gets the tight layout.
pub const MIN_WORLD: (f32, f32) = (480.0, 220.0);

/// The controls the tight layout keeps in sight: the lobby, *Tools* (the
/// menu), *Panel* and the language switch.
const TIGHT_SLOTS: usize = 4;

/// The screen's parts in a window.
#[derive(Clone, Copy, Debug)]
pub struct Areas {
    /// The window's size.
    pub w: f32,
    pub h: f32,
    /// The compact (phone) layout.
    pub compact: bool,
    /// The compact layout of a window wider than tall (a phone on its
    /// side): the tools in columns at the left.
    pub sideways: bool,
    /// The layout of a phone too small for the compact one: the tools
    /// and the speeds in a menu over the world, the bar in one row.
    pub tight: bool,
    /// Heights of the toolbar's and the playback bar's bands.
    pub top: f32,
    pub bottom: f32,
    /// Where the scene shows.
    pub world: Rect,
    /// The side panel (over the world in the compact layout, and over
    /// the bar too when sideways).
    pub side: Rect,
    /// The playback bar.
    pub bar: Rect,
}

/// The parts of a `w` x `h` window.
pub fn areas(w: f32, h: f32) -> Areas {
    let compact = w < MIN_WIDTH;
    if compact && w > h {
        let mut rail = rail_width(h);
        let mut bottom = 2.0 * (TOUCH + GAP) + 12.0;
        let roomy =
            w - rail >= MIN_WORLD.0 && h - bottom >= MIN_WORLD.1 && speed_rows(w - rail - 4.0) == 1;
        if !roomy {
            // One column of four, and the bar in one row.
            rail = 8.0 + TIGHT_BUTTON + 8.0;
            bottom = TOUCH + GAP + 8.0;
        }
        let world = Rect::new(rail, 0.0, w - rail, h - bottom);
        // Two columns at the right, the window's height (over the bar,
        // which hides while the panel is open).
        let side_w = (2.0 * SIDE_COLUMN).min(world.w - 8.0);
        return Areas {
            w,
            h,
            compact,
            sideways: true,
            tight: !roomy,
            top: 0.0,
            bottom,
            world,
            side: Rect::new(w - side_w - 4.0, 4.0, side_w, h - 8.0),
            bar: Rect::new(rail, h - bottom, w - rail - 4.0, bottom - 4.0),
        };
    }
    if compact && toolbar_rows(w) > 3.0 {
        // One row of four at the top, the bar in one row; the panel and
        // the menu open over the world and the bar.
        let (top, bottom) = (6.0 + TOUCH + GAP + 2.0, TOUCH + GAP + 8.0);
        return Areas {
            w,
            h,
            compact,
            sideways: false,
            tight: true,
            top,
            bottom,
            world: Rect::new(0.0, top, w, h - top - bottom),
            side: Rect::new(4.0, top, w - 8.0, h - top - 4.0),
            bar: Rect::new(4.0, h - bottom, w - 8.0, bottom - 4.0),
        };
    }
    let (top, bottom) = if compact {
        let rows = toolbar_rows(w);
        // The bar's speeds in one or two rows of their own.
        let speeds = speed_rows(w - 8.0) as f32;
        (
            6.0 + rows * (TOUCH + GAP) + 2.0,
            (1.0 + speeds) * (TOUCH + GAP) + 12.0,
        )
    } else {
        (TOP, BOTTOM)
    };
    let world = if compact {
        Rect::new(0.0, top, w, h - top - bottom)
    } else {
        Rect::new(0.0, top, w - SIDE - 8.0, h - top - bottom)
    };
    let side = if compact {
        Rect::new(4.0, top, w - 8.0, h - top - bottom - 4.0)
    } else {
        Rect::new(w - SIDE - 4.0, top, SIDE, h - top - bottom - 4.0)
    };
    let bar = Rect::new(4.0, h - bottom, w - 8.0, bottom - 4.0);
    Areas {
        w,
        h,
        compact,
        sideways: false,
        tight: false,
        top,
        bottom,
        world,
        side,
        bar,
    }
}

/// The place of the tight layout's control `i` (of [`TIGHT_SLOTS`]): down
/// the left edge sideways, along the top upright.
fn tight_slot(a: &Areas, i: usize) -> Rect {
    if a.sideways {
        return Rect::new(8.0, 6.0 + i as f32 * (TOUCH + GAP), TIGHT_BUTTON, TOUCH);
    }
    let n = TIGHT_SLOTS as f32;
    let bw = (a.w - 16.0 - GAP * (n - 1.0)) / n;
    Rect::new(8.0 + i as f32 * (bw + GAP), 6.0, bw, TOUCH)
}

/// The tight layout's *Tools*, which opens the menu of tools and speeds.
pub fn tools_button(a: &Areas) -> Option<Rect> {
    a.tight.then(|| tight_slot(a, 1))
}

/// The menu of the tight layout (in the side panel's place): the tools,
/// Wall/Edge, Export and Import in rows of four (three where four would
/// be under 90 units wide), in the order of
/// [`toolbar`] (without Lobby and Panel), and the speeds (one per
/// [`SPEEDS`]) in two rows of their own below.
pub fn menu(a: &Areas) -> (Vec<Rect>, Vec<Rect>) {
    let r = a.side;
    let items = TOOLS.len() + 3;
    let width = |per_row: usize| (r.w - 16.0 - GAP * (per_row - 1) as f32) / per_row as f32;
    let per_row = if width(4) >= 90.0 { 4 } else { 3 };
    let bw = width(per_row);
    let slot = |i: usize, per_row: usize, bw: f32, top: f32| {
        let (c, row) = ((i % per_row) as f32, (i / per_row) as f32);
        Rect::new(
            r.x + 8.0 + c * (bw + GAP),
            top + row * (TOUCH + GAP),
            bw,
            TOUCH,
        )
    };
    let tools = (0..items)
        .map(|i| slot(i, per_row, bw, r.y + 8.0))
        .collect();
    let rows = items.div_ceil(per_row) as f32;
    let top = r.y + 8.0 + rows * (TOUCH + GAP) + 8.0;
    let per_row = SPEEDS.len().div_ceil(2);
    let sw = (r.w - 16.0 - GAP * (per_row - 1) as f32) / per_row as f32;
    let speeds = (0..SPEEDS.len())
        .map(|i| slot(i, per_row, sw, top))
        .collect();
    (tools, speeds)
}

/// The columns of tools of the sideways layout in a window `h` tall:
/// as few as hold the toolbar's buttons and the language switch, in rows
/// of finger-sized buttons from the top.
fn rail_columns(h: f32) -> (usize, usize) {
    let slots = TOOLBAR_BUTTONS + 1;
    let fit = (((h - 6.0) / (TOUCH + GAP)).floor() as usize).max(1);
    let columns = slots.div_ceil(fit);
    (columns, slots.div_ceil(columns))
}

/// Width the columns of tools take in a window `h` tall (with margins).
fn rail_width(h: f32) -> f32 {
    let (columns, _) = rail_columns(h);
    8.0 + columns as f32 * RAIL_BUTTON + (columns - 1) as f32 * GAP + 8.0
}

/// The place of slot `i` of the sideways layout's columns of tools, row
/// by row.
fn rail_slot(h: f32, i: usize) -> Rect {
    let (columns, _) = rail_columns(h);
    let (c, r) = ((i % columns) as f32, (i / columns) as f32);
    Rect::new(
        8.0 + c * (RAIL_BUTTON + GAP),
        6.0 + r * (TOUCH + GAP),
        RAIL_BUTTON,
        TOUCH,
    )
}

/// How many buttons a row of the compact toolbar holds in a window `w`
/// units wide (at least 4, about 70 units each).
fn toolbar_per_row(w: f32) -> usize {
    (((w - 16.0) / 70.0).floor() as usize).clamp(4, TOOLBAR_BUTTONS)
}

/// The rows the compact toolbar takes in a window `w` units wide.
fn toolbar_rows(w: f32) -> f32 {
    TOOLBAR_BUTTONS.div_ceil(toolbar_per_row(w)) as f32
}

/// The widths of the desktop toolbar's buttons in a window `w` units
/// wide: Lobby, a tool, Wall/Edge, Export and Import. The row shares one
/// label size, set by its most cramped label ("Скорость"), so the buttons
/// widen with the window from 1044 units (where the language switch
/// first fits between Wall/Edge and Import) to 1216 (a 1280 x 800
/// browser window), the room they take growing more slowly than the
/// window's, so the switch keeps its place.
fn toolbar_widths(w: f32) -> (f32, f32, f32, f32) {
    let k = ((w - 1044.0) / 172.0).clamp(0.0, 1.0);
    let grow = |from: f32, to: f32| from + (to - from) * k;
    (
        grow(70.0, 83.0),
        grow(74.0, 93.0),
        grow(58.0, 64.0),
        grow(74.0, 83.0),
    )
}

/// The toolbar's buttons in the window of `a`, in order: Lobby, the tools
/// (as [`TOOLS`]), Wall/Edge, Panel (compact only), Export, Import. On a
/// desktop they stand in one row, Export and Import at the right; in the
/// compact layout they wrap in rows of equal width, or, sideways, fill
/// the columns at the left row by row.
pub fn toolbar(a: &Areas) -> Vec<Rect> {
    let (w, compact) = (a.w, a.compact);
    if a.tight {
        // Lobby and Panel in sight, the rest in the menu.
        let (mut menu, _) = menu(a);
        let mut rects = vec![tight_slot(a, 0)];
        let rest = menu.split_off(TOOLS.len() + 1);
        rects.extend(menu);
        rects.push(tight_slot(a, 2));
        rects.extend(rest);
        return rects;
    }
    if a.sideways {
        return (0..TOOLBAR_BUTTONS).map(|i| rail_slot(a.h, i)).collect();
    }
    let (h, y) = (TOUCH, 6.0);
    if compact {
        let per_row = toolbar_per_row(w);
        let bw = (w - 16.0 - GAP * (per_row - 1) as f32) / per_row as f32;
        return (0..TOOLBAR_BUTTONS)
            .map(|i| {
                let (c, r) = ((i % per_row) as f32, (i / per_row) as f32);
                Rect::new(8.0 + c * (bw + GAP), y + r * (h + GAP), bw, h)
            })
            .collect();
    }
    let (lobby_w, tool_w, wall_w, file_w) = toolbar_widths(w);
    let mut rects = Vec::with_capacity(TOOLBAR_BUTTONS - 1);
    // Lobby, set apart from the tools.
    let mut x = 8.0;
    rects.push(Rect::new(x, y, lobby_w, h));
    x += lobby_w + 14.0;
    for i in 0..TOOLS.len() {
        rects.push(Rect::new(x, y, tool_w, h));
        // The last tool (Delete) is set apart from Wall/Edge.
        x += tool_w + if i + 1 == TOOLS.len() { 14.0 } else { GAP };
    }
    rects.push(Rect::new(x, y, wall_w, h));
    // Export, then Import left of it, at the right.
    let mut right = w - 8.0;
    for _ in 0..2 {
        right -= file_w;
        rects.push(Rect::new(right, y, file_w, h));
        right -= GAP;
    }
    rects
}

/// The language switch in the toolbar, where there is room for it: a
/// spare place at the end of the compact toolbar's last row (sideways:
/// the place after the last button), or the room between Wall/Edge and
/// Import on a desktop wide enough (`None` else).
pub fn language(a: &Areas) -> Option<Rect> {
    let (w, compact) = (a.w, a.compact);
    if a.tight {
        return Some(tight_slot(a, 3));
    }
    if a.sideways {
        return Some(rail_slot(a.h, TOOLBAR_BUTTONS));
    }
    let (h, y, lw) = (TOUCH, 6.0, 52.0);
    if compact {
        let per_row = toolbar_per_row(w);
        if TOOLBAR_BUTTONS.is_multiple_of(per_row) {
            return None;
        }
        let bw = (w - 16.0 - GAP * (per_row - 1) as f32) / per_row as f32;
        let (c, r) = (
            (TOOLBAR_BUTTONS % per_row) as f32,
            (TOOLBAR_BUTTONS / per_row) as f32,
        );
        return Some(Rect::new(8.0 + c * (bw + GAP), y + r * (h + GAP), bw, h));
    }
    let t = toolbar(a);
    let wall_end = t[TOOLS.len() + 1].right();
    let import = t[t.len() - 1].x;
    (import - wall_end - 2.0 * 14.0 >= lw).then(|| Rect::new(import - 14.0 - lw, y, lw, h))
}

/// The playback bar's controls.
#[derive(Clone, Debug)]
pub struct Playback {
    pub rewind: Rect,
    pub play: Rect,
    /// One per [`SPEEDS`], in order.
    pub speeds: Vec<Rect>,
    /// The time slider.
    pub slider: Rect,
    /// The time's text: its left, its top and the width it may take.
    pub time: (f32, f32, f32),
}

/// The narrowest a speed button of the compact bar may be before the
/// speeds take two rows ("0.01x" fits it at 13 units).
const SPEED_MIN_W: f32 = 42.0;

/// The width of each of `per_row` buttons in a row of the bar `bar_w`
/// wide.
fn speed_width(bar_w: f32, per_row: usize) -> f32 {
    (bar_w - 16.0 - GAP * (per_row - 1) as f32) / per_row as f32
}

/// The rows the compact bar `bar_w` wide gives its speeds: one where each
/// is [`SPEED_MIN_W`] wide or more, else two.
fn speed_rows(bar_w: f32) -> usize {
    if speed_width(bar_w, SPEEDS.len()) >= SPEED_MIN_W {
        1
    } else {
        2
    }
}

/// How the playback bar is laid out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bar {
    /// One row, the speeds in it (a desktop).
    Wide,
    /// Rewind, play and the slider in one row, the speeds in one or two
    /// rows below (a phone).
    Compact,
    /// Rewind, play and the slider only: the speeds are in the menu.
    Short,
}

impl Bar {
    /// The bar of the layout `a`.
    pub fn of(a: &Areas) -> Bar {
        if a.tight {
            Bar::Short
        } else if a.compact {
            Bar::Compact
        } else {
            Bar::Wide
        }
    }
}

/// Rewind, play, the speeds and the time slider in the bar `r`: one row
/// on a desktop; two or three in the compact layout (the speeds in one
/// or two below); one without the speeds in the tight layout.
pub fn playback(r: Rect, bar: Bar) -> Playback {
    let h = TOUCH;
    let y = r.y + 6.0;
    let mut x = r.x + 8.0;
    let rewind = Rect::new(x, y, h, h);
    x += h + GAP;
    // Wider where the bar is (the row shares one label size, set by its
    // speeds' "-0.1x" and "0.25x").
    let (play_w, speed_w) = if r.w >= WIDE {
        (84.0, 56.0)
    } else {
        (70.0, 44.0)
    };
    let play = Rect::new(x, y, play_w, h);
    // Room for the slider's knob beside Play.
    x += play_w + 24.0;
    let speeds = match bar {
        Bar::Wide => {
            let mut sx = x;
            let speeds = SPEEDS
                .iter()
                .map(|_| {
                    let s = Rect::new(sx, y, speed_w, h);
                    sx += speed_w + GAP / 2.0;
                    s
                })
                .collect();
            x = sx + 24.0;
            speeds
        }
        Bar::Compact => {
            // In two rows of five where one would be too narrow for
            // "0.01x" to read at a phone's size.
            let per_row = SPEEDS.len().div_ceil(speed_rows(r.w));
            let sw = speed_width(r.w, per_row);
            (0..SPEEDS.len())
                .map(|i| {
                    let (c, row) = ((i % per_row) as f32, (i / per_row) as f32);
                    Rect::new(
                        r.x + 8.0 + c * (sw + GAP),
                        y + (1.0 + row) * (h + GAP),
                        sw,
                        h,
                    )
                })
                .collect()
        }
        Bar::Short => Vec::new(),
    };
    let label_w = match bar {
        Bar::Wide => 120.0,
        Bar::Compact => 96.0,
        Bar::Short => 84.0,
    };
    let slider = Rect::new(x, y, (r.x + r.w - label_w - 16.0 - x).max(40.0), h);
    Playback {
        rewind,
        play,
        speeds,
        slider,
        time: (slider.x + slider.w + 12.0, y + 13.0, label_w),
    }
}

/// A stepper's or a slider's row of the side panel: the label at its
/// left, the control at its right.
pub type Row = Rect;

/// A stepper row's `-` and `+` buttons.
pub fn stepper_buttons(row: Row) -> (Rect, Rect) {
    let h = TOUCH;
    (
        Rect::new(row.x + row.w - 2.0 * h - GAP, row.y, h, h),
        Rect::new(row.x + row.w - h, row.y, h, h),
    )
}

/// A slider row's slider, right of its label.
pub fn slider_of(row: Row) -> Rect {
    Rect::new(row.x + SLIDER_AT, row.y, row.w - SLIDER_AT, TOUCH)
}

/// The controls of new discs.
#[derive(Clone, Copy, Debug)]
pub struct NewDiscs {
    /// The heading's top.
    pub heading: f32,
    /// Stepper rows.
    pub radius: Row,
    pub mass: Row,
    /// Slider rows.
    pub mu: Row,
    pub e: Row,
}

/// The selected body's controls.
#[derive(Clone, Copy, Debug)]
pub struct BodyControls {
    /// Its position and speed's line's top.
    pub info: f32,
    /// Stepper rows.
    pub radius: Row,
    pub mass: Row,
    pub mu: Row,
    pub e: Row,
    pub stop: Rect,
    pub delete: Rect,
}

/// The side panel's parts.
#[derive(Clone, Copy, Debug)]
pub struct SidePanel {
    /// The text's left edge.
    pub x: f32,
    /// The left edge of the new discs' and the selection's text (a second
    /// column's in a panel wide enough for two).
    pub x2: f32,
    /// The presets' heading's top and their buttons.
    pub presets: f32,
    pub galperin: Rect,
    pub galperin_less: Rect,
    pub galperin_more: Rect,
    pub brownian: Rect,
    pub chapaev: Rect,
    pub empty: Rect,
    pub fit: Rect,
    /// The world's heading's top and the gravity's slider row.
    pub world: f32,
    pub gravity: Row,
    /// Whether the world's heading and gravity show (a short panel in one
    /// column gives their place to a body's controls).
    pub world_shown: bool,
    /// The controls of new discs, unless a body's replace them.
    pub new_discs: Option<NewDiscs>,
    /// The selection's heading's top (and its help lines below).
    pub selection: f32,
    /// The selected body's controls, when one is in the scene.
    pub body: Option<BodyControls>,
}

/// The side panel in `r`, with the selected body's controls if `body`.
/// Without the room for both (a panel under 720 tall), a body's controls
/// replace those of new discs. A panel wide enough for two columns (the
/// sideways layout's) has the presets and the world in the first, the
/// new discs and the selection in the second.
pub fn side_panel(r: Rect, body: bool) -> SidePanel {
    let two = r.w >= 2.0 * SIDE_COLUMN_MIN - 1e-3;
    let column = if two { r.w / 2.0 } else { r.w };
    let x = r.x + 10.0;
    let w = column - 20.0;
    let h = TOUCH;
    let row = |y: f32| Rect::new(x, y, w, h);
    let mut y = r.y + 8.0;
    let presets = y;
    y += 22.0;
    let galperin = Rect::new(x, y, w - 2.0 * (h + GAP), h);
    let (galperin_less, galperin_more) = stepper_buttons(row(y));
    y += h + 4.0;
    let half = (w - 4.0) / 2.0;
    let brownian = Rect::new(x, y, half, h);
    let chapaev = Rect::new(x + half + 4.0, y, half, h);
    y += h + 4.0;
    let empty = Rect::new(x, y, half, h);
    let fit = Rect::new(x + half + 4.0, y, half, h);
    y += h + 12.0;
    let world = y;
    y += 22.0;
    let gravity = row(y);
    y += ROW;
    let x2 = if two { x + column } else { x };
    if two {
        y = r.y + 8.0;
    }
    let row = |y: f32| Rect::new(x2, y, w, h);
    let compact = r.h < 720.0;
    // A panel in one column too short for the world's row and a body's
    // controls too: the body's take the world's place.
    let world_shown = !(!two && r.h < 540.0 && body);
    if !world_shown {
        y = world;
    }
    let new_discs = (!(compact && body)).then(|| {
        let heading = y;
        y += 18.0;
        let d = NewDiscs {
            heading,
            radius: row(y),
            mass: row(y + ROW),
            mu: row(y + 2.0 * ROW),
            e: row(y + 3.0 * ROW),
        };
        y += 4.0 * ROW + 6.0;
        d
    });
    let selection = y;
    let body = body.then(|| {
        let info = y + 22.0;
        let y = info + 20.0;
        let buttons = y + 4.0 * ROW + 2.0;
        BodyControls {
            info,
            radius: row(y),
            mass: row(y + ROW),
            mu: row(y + 2.0 * ROW),
            e: row(y + 3.0 * ROW),
            stop: Rect::new(x2, buttons, half, h),
            delete: Rect::new(x2 + half + 4.0, buttons, half, h),
        }
    });
    SidePanel {
        x,
        x2,
        presets,
        galperin,
        galperin_less,
        galperin_more,
        brownian,
        chapaev,
        empty,
        fit,
        world,
        gravity,
        world_shown,
        new_discs,
        selection,
        body,
    }
}

/// The statistics panel over the world's top left corner.
pub fn stats(world: Rect) -> Rect {
    Rect::new(world.x + 8.0, world.y + 8.0, 232.0, 265.0)
}

/// Galperin's counter over the world's top right corner (narrower in a
/// narrow world).
pub fn galperin_counter(world: Rect) -> Rect {
    let w = (world.w - 16.0).min(330.0);
    Rect::new(world.x + world.w - w - 8.0, world.y + 8.0, w, 112.0)
}

/// From one line of the message to the next, at `size`.
pub fn line_step(size: f32) -> f32 {
    size + 3.0
}

/// The message's box at the world's bottom for `lines` lines of text at
/// `size`, the widest `text_w` wide.
pub fn message(world: Rect, text_w: f32, lines: usize, size: f32) -> Rect {
    let w = text_w.min(world.w - 36.0) + 20.0;
    let h = 8.0 + lines.max(1) as f32 * line_step(size);
    Rect::new(world.x + 8.0, world.y + world.h - 8.0 - h, w, h)
}

/// A view that shows the whole scene (and the board) in `area`, leaving
/// `stats_w` on its left for the statistics panel.
pub fn fit(scene: &Scene, board: Option<f64>, area: Rect, stats_w: f32) -> Viewport {
    let mut lo = DVec2::splat(f64::INFINITY);
    let mut hi = DVec2::splat(f64::NEG_INFINITY);
    let mut take = |p: DVec2, r: f64| {
        if p.is_finite() {
            lo = lo.min(p - DVec2::splat(r));
            hi = hi.max(p + DVec2::splat(r));
        }
    };
    for b in &scene.bodies {
        take(b.pos, b.radius);
    }
    for q in &scene.points {
        take(q.pos, 0.0);
    }
    for l in &scene.lines {
        take(l.a, 0.0);
        take(l.b, 0.0);
    }
    if let Some(size) = board {
        take(DVec2::ZERO, size * 0.06);
        take(DVec2::splat(size), size * 0.06);
    }
    if !(lo.x <= hi.x && lo.y <= hi.y) {
        lo = DVec2::splat(-1.0);
        hi = DVec2::splat(1.0);
    }
    let size = (hi - lo).max(DVec2::splat(0.05));
    // Leave room for the statistics panel on the left of the world area.
    let left = stats_w.min(area.w * 0.4);
    let usable = Rect::new(area.x + left, area.y, area.w - left, area.h - 40.0);
    let scale = (usable.w as f64 / size.x).min(usable.h as f64 / size.y) * 0.9;
    Viewport {
        centre: (lo + hi) / 2.0,
        anchor: vec2(usable.x + usable.w / 2.0, usable.y + usable.h / 2.0),
        scale: scale.clamp(1.0, 1e7),
        flipped: false,
    }
}

#[cfg(test)]
mod tests {
    use super::super::presets::{self, Kind};
    use super::*;
    use crate::test_geometry::{inside, overlap, PHONES};

    const DESKTOPS: [(f32, f32); 2] = [(1280.0, 720.0), (1920.0, 1080.0)];
    /// Phones on their side besides [`PHONES`]' (a small one, a tall one).
    const SIDEWAYS: [(f32, f32); 2] = [(568.0, 320.0), (915.0, 412.0)];
    /// The smallest phone (an iPhone SE) upright and on its side.
    const SMALL: [(f32, f32); 2] = [(320.0, 568.0), (568.0, 320.0)];

    fn apart(what: &str, rects: &[Rect]) {
        for (i, a) in rects.iter().enumerate() {
            for b in &rects[i + 1..] {
                assert!(!overlap(*a, *b), "{what}: {a:?} overlaps {b:?}");
            }
        }
    }

    /// Every button of the side panel.
    fn side_buttons(p: &SidePanel) -> Vec<Rect> {
        let mut all = vec![
            p.galperin,
            p.galperin_less,
            p.galperin_more,
            p.brownian,
            p.chapaev,
            p.empty,
            p.fit,
        ];
        if p.world_shown {
            all.push(slider_of(p.gravity));
        }
        if let Some(d) = p.new_discs {
            let (a, b) = stepper_buttons(d.radius);
            let (c, e) = stepper_buttons(d.mass);
            all.extend([a, b, c, e, slider_of(d.mu), slider_of(d.e)]);
        }
        if let Some(b) = p.body {
            for row in [b.radius, b.mass, b.mu, b.e] {
                let (less, more) = stepper_buttons(row);
                all.extend([less, more]);
            }
            all.extend([b.stop, b.delete]);
        }
        all
    }

    #[test]
    fn the_fitted_view_shows_every_body_on_a_desktop_and_a_phone() {
        let desktop = (Rect::new(0.0, 56.0, 750.0, 600.0), STATS_W);
        let phone = (Rect::new(0.0, 152.0, 390.0, 584.0), 0.0);
        for (area, stats_w) in [desktop, phone] {
            for kind in [Kind::Galperin(4), Kind::Brownian, Kind::Break] {
                let p = presets::build(kind);
                let v = fit(&p.scene, p.board, area, stats_w);
                for b in &p.scene.bodies {
                    let s = v.to_screen(b.pos);
                    assert!(area.contains(s), "{kind:?} in {area:?}: {s} outside");
                }
            }
        }
    }

    /// The size the labels of one row of `buttons` (label, rectangle)
    /// share, measured in the client's font.
    fn row_size(buttons: &[(String, Rect)]) -> f32 {
        let buttons: Vec<(&str, Rect)> = buttons.iter().map(|(l, r)| (l.as_str(), *r)).collect();
        let sizes = crate::ui::group_label_sizes(&buttons, crate::test_geometry::font_width);
        sizes.iter().copied().fold(f32::INFINITY, f32::min)
    }

    #[test]
    fn the_toolbar_and_the_playback_bar_read_at_a_comfortable_size_on_a_desktop_in_both_languages()
    {
        use crate::i18n::{message_in, Lang};
        // A 1280 x 800 browser window, in layout units.
        let z = crate::scale::zoom_for(1280.0, 800.0);
        let (w, h) = (1280.0 / z, 800.0 / z);
        let a = areas(w, h);
        assert!(!a.compact);
        for lang in [Lang::En, Lang::Ru] {
            let text = |id: &str| message_in(lang, id).expect("the message exists");
            let mut labels: Vec<String> = std::iter::once("lobby".to_string())
                .chain(TOOLS.map(|t| format!("sandbox-tool-{}", t.name())))
                .chain(["sandbox-wall", "sandbox-export", "sandbox-import"].map(String::from))
                .map(|id| text(&id))
                .collect();
            let mut rects = toolbar(&a);
            if let Some(lang_r) = language(&a) {
                labels.push(lang.other().code().to_uppercase());
                rects.push(lang_r);
            }
            let bar: Vec<(String, Rect)> = labels.into_iter().zip(rects).collect();
            let top = row_size(&bar);
            let p = playback(a.bar, Bar::Wide);
            let mut row = vec![("|<".to_string(), p.rewind), (text("replay-pause"), p.play)];
            row.extend(
                SPEEDS
                    .iter()
                    .map(|s| crate::sandbox::format::speed_label(*s))
                    .zip(p.speeds),
            );
            let bottom = row_size(&row);
            eprintln!("sandbox {w}x{h} {lang:?}: toolbar at {top}, playback at {bottom}");
            assert!(top >= 16.0 && bottom >= 16.0, "{lang:?}: {top}, {bottom}");
        }
    }

    #[test]
    fn the_compact_toolbar_takes_three_rows_on_a_phone_and_one_on_a_wide_window() {
        assert_eq!(toolbar_rows(390.0), 3.0);
        assert_eq!(toolbar_rows(999.0), 1.0);
        assert_eq!(toolbar_rows(200.0), 4.0);
    }

    #[test]
    fn the_language_switch_takes_a_free_place_in_the_toolbar() {
        for (w, compact) in [
            (390.0, true),
            (412.0, true),
            (768.0, true),
            (1280.0, false),
            (1920.0, false),
        ] {
            let a = areas(w, 900.0);
            assert_eq!(a.compact, compact);
            let lang = language(&a).expect("room for the switch");
            assert!(inside(lang, Rect::new(0.0, 0.0, w, 200.0)), "{w}: {lang:?}");
            assert!(lang.h >= TOUCH);
            for r in toolbar(&a) {
                assert!(!overlap(lang, r), "{w}: {lang:?} overlaps {r:?}");
            }
        }
        // No room: a desktop at its narrowest.
        assert_eq!(language(&areas(1000.0, 900.0)), None);
        // Wider buttons on a wider window leave the switch its place.
        for w in (1044..=1400).step_by(2) {
            let a = areas(w as f32, 900.0);
            let lang = language(&a).unwrap_or_else(|| panic!("{w}: no room for the switch"));
            for r in toolbar(&a) {
                assert!(!overlap(lang, r), "{w}: {lang:?} overlaps {r:?}");
            }
        }
    }

    #[test]
    fn a_wide_window_sets_the_side_panel_right_of_the_world_between_the_bars() {
        for (w, h) in DESKTOPS {
            let a = areas(w, h);
            assert!(!a.compact, "{w}x{h}");
            assert_eq!((a.top, a.bottom), (TOP, BOTTOM));
            assert_eq!((a.world.x, a.world.y), (0.0, TOP));
            assert!(a.world.x + a.world.w < a.side.x, "{w}x{h}");
            assert_eq!(a.side.w, SIDE);
            assert!(a.bar.y >= a.world.y + a.world.h, "{w}x{h}");
            // One row of tools, Export and Import at the right.
            let t = toolbar(&a);
            assert_eq!(t.len(), TOOLBAR_BUTTONS - 1);
            assert!(t.iter().all(|r| r.y == 6.0));
            assert_eq!(t[t.len() - 2].x + t[t.len() - 2].w, w - 8.0);
        }
    }

    #[test]
    fn a_tall_window_is_compact_the_world_full_width_the_panel_over_it() {
        for (w, h) in [(390.0, 844.0), (412.0, 915.0), (768.0, 1024.0)] {
            let a = areas(w, h);
            assert!(a.compact, "{w}x{h}");
            assert_eq!((a.world.x, a.world.w), (0.0, w));
            assert!(inside(a.side, a.world), "{w}x{h}");
            // The toolbar wraps in rows above the world, Panel among them.
            let t = toolbar(&a);
            assert_eq!(t.len(), TOOLBAR_BUTTONS);
            assert!(t.iter().any(|r| r.y > 6.0));
            assert!(t.iter().all(|r| r.y + r.h < a.world.y));
            // The speeds take the bar's second row.
            let p = playback(a.bar, Bar::Compact);
            assert!(p.speeds.iter().all(|s| s.y > p.play.y + p.play.h));
        }
        assert!(areas(999.0, 700.0).compact && !areas(1000.0, 700.0).compact);
    }

    /// The controls in sight while nothing is open over the world: the
    /// toolbar's (in the tight layout only Lobby, *Menu*, *Panel* and the
    /// language switch).
    fn in_sight(a: &Areas) -> Vec<Rect> {
        let mut tools = toolbar(a);
        if a.tight {
            tools = vec![tools[0], tools[TOOLS.len() + 2]];
        }
        tools.extend(language(a));
        tools.extend(tools_button(a));
        tools
    }

    #[test]
    fn every_control_is_inside_the_window_apart_and_finger_tall_at_phone_and_desktop_sizes() {
        for (w, h) in PHONES
            .into_iter()
            .chain(SIDEWAYS)
            .chain(SMALL)
            .chain(DESKTOPS)
        {
            let window = Rect::new(0.0, 0.0, w, h);
            let a = areas(w, h);
            for part in [a.world, a.side, a.bar] {
                assert!(inside(part, window), "{w}x{h}: {part:?}");
            }
            assert!(!overlap(a.world, a.bar), "{w}x{h}");
            assert!(a.compact || !overlap(a.world, a.side), "{w}x{h}");
            assert_eq!(a.sideways, a.compact && w > h, "{w}x{h}");
            let tools = in_sight(&a);
            let p = playback(a.bar, Bar::of(&a));
            let mut bar = vec![p.rewind, p.play, p.slider];
            bar.extend(&p.speeds);
            for r in tools.iter().chain(&bar) {
                assert!(inside(*r, window), "{w}x{h}: {r:?} outside");
                assert!(r.h >= TOUCH, "{w}x{h}: {r:?} is short");
                assert!(!overlap(*r, a.world), "{w}x{h}: {r:?} over the world");
            }
            for r in &bar {
                assert!(inside(*r, a.bar), "{w}x{h}: {r:?} outside the bar");
            }
            let (tx, _, tw) = p.time;
            assert!(tx + tw <= a.bar.x + a.bar.w + 1e-3, "{w}x{h}: the time");
            apart(&format!("{w}x{h} toolbar"), &tools);
            apart(&format!("{w}x{h} bar"), &bar);
        }
    }

    #[test]
    fn the_side_panels_controls_fit_it_apart_with_or_without_a_body() {
        for (w, h) in PHONES
            .into_iter()
            .chain(SIDEWAYS)
            .chain(SMALL)
            .chain(DESKTOPS)
        {
            let a = areas(w, h);
            for body in [false, true] {
                let p = side_panel(a.side, body);
                assert_eq!(p.body.is_some(), body);
                let all = side_buttons(&p);
                for r in &all {
                    assert!(inside(*r, a.side), "{w}x{h} {body}: {r:?} outside");
                    assert!(r.h >= TOUCH, "{w}x{h}: {r:?} is short");
                }
                apart(&format!("{w}x{h} side panel"), &all);
            }
        }
    }

    #[test]
    fn a_short_panel_swaps_the_new_disc_controls_for_the_bodys_and_a_tall_one_shows_both() {
        let short = side_panel(areas(1280.0, 720.0).side, true);
        assert!(short.new_discs.is_none() && short.body.is_some());
        let tall = side_panel(areas(1920.0, 1080.0).side, true);
        assert!(tall.new_discs.is_some() && tall.body.is_some());
        let nothing = side_panel(areas(1280.0, 720.0).side, false);
        assert!(nothing.new_discs.is_some() && nothing.body.is_none());
    }

    #[test]
    fn a_phone_on_its_side_has_its_tools_in_columns_at_the_left_and_a_world_600_wide() {
        let a = areas(844.0, 390.0);
        assert!(a.compact && a.sideways);
        // The world: most of the window, not a strip under two rows of
        // tools (it was 844 x 178, the panel over all of it).
        assert!(a.world.w >= 600.0 && a.world.h >= 270.0, "{:?}", a.world);
        let mut tools = toolbar(&a);
        assert_eq!(tools.len(), TOOLBAR_BUTTONS);
        tools.extend(language(&a));
        for r in &tools {
            assert!(r.x + r.w <= a.world.x, "{r:?} over the world");
            assert!(r.w >= 60.0 && r.h >= TOUCH, "{r:?}");
        }
        apart("sideways tools", &tools);
        // The panel: two columns at the right, the world's left part seen.
        let p = side_panel(a.side, true);
        assert!(p.x2 > p.x + 200.0, "{p:?}");
        assert!(a.side.x - a.world.x >= 180.0, "{:?}", a.side);
        for (w, h) in PHONES.into_iter().chain(SIDEWAYS) {
            let a = areas(w, h);
            assert_eq!(a.sideways, w > h, "{w}x{h}");
            let tools = toolbar(&a);
            assert!(tools.iter().all(|r| inside(*r, Rect::new(0.0, 0.0, w, h))));
        }
    }

    #[test]
    fn the_overlays_stay_inside_the_world_and_apart() {
        for (w, h) in PHONES.into_iter().chain(SMALL).chain(DESKTOPS) {
            let a = areas(w, h);
            let counter = galperin_counter(a.world);
            let msg = message(a.world, 300.0, 3, 17.0);
            let mut shown = vec![counter, msg];
            // The statistics panel shows in the desktop layout only.
            if !a.compact {
                shown.push(stats(a.world));
            }
            for r in &shown {
                assert!(inside(*r, a.world), "{w}x{h}: {r:?} outside");
            }
            apart(&format!("{w}x{h} overlays"), &shown);
        }
    }

    #[test]
    fn the_smallest_phone_gets_the_tight_layout_with_a_world_of_480_by_220_sideways_and_300_by_400_upright(
    ) {
        for (w, h) in SMALL {
            let a = areas(w, h);
            assert!(a.compact && a.tight, "{w}x{h}");
            let min = if a.sideways {
                MIN_WORLD
            } else {
                (300.0, 400.0)
            };
            eprintln!("sandbox {w}x{h}: the world {} x {}", a.world.w, a.world.h);
            assert!(
                a.world.w >= min.0 && a.world.h >= min.1,
                "{w}x{h}: {:?}",
                a.world
            );
            // In sight: four controls, apart and off the world.
            let shown = in_sight(&a);
            assert_eq!(shown.len(), TIGHT_SLOTS, "{w}x{h}");
            for r in &shown {
                assert!(!overlap(*r, a.world) && r.h >= TOUCH, "{w}x{h}: {r:?}");
            }
            apart(&format!("{w}x{h} in sight"), &shown);
            // The menu: the tools, Wall/Edge, Export, Import and the
            // speeds, inside the panel's place, apart.
            let (tools, speeds) = menu(&a);
            assert_eq!(tools.len(), TOOLS.len() + 3);
            assert_eq!(speeds.len(), SPEEDS.len());
            let all: Vec<Rect> = tools.iter().chain(&speeds).copied().collect();
            for r in &all {
                assert!(inside(*r, a.side), "{w}x{h}: {r:?} outside {:?}", a.side);
                assert!(r.h >= TOUCH && r.w >= 44.0, "{w}x{h}: {r:?}");
            }
            apart(&format!("{w}x{h} menu"), &all);
            // The bar: one row, no speeds.
            let p = playback(a.bar, Bar::of(&a));
            assert!(p.speeds.is_empty() && p.slider.w >= 60.0, "{w}x{h}: {p:?}");
        }
        // A phone on its side with room enough keeps its columns of tools.
        for (w, h) in [(844.0, 390.0), (915.0, 412.0), (667.0, 375.0)] {
            let a = areas(w, h);
            assert!(a.sideways && !a.tight, "{w}x{h}");
            assert!(a.world.w >= MIN_WORLD.0 && a.world.h >= MIN_WORLD.1);
        }
        assert!(!areas(390.0, 844.0).tight && !areas(375.0, 667.0).tight);
    }

    #[test]
    fn the_speeds_read_at_13_units_and_the_tools_at_12_or_more_on_every_phone_in_both_languages() {
        use crate::i18n::{message_in, Lang};
        let speeds: Vec<String> = SPEEDS
            .iter()
            .map(|s| crate::sandbox::format::speed_label(*s))
            .collect();
        for (w, h) in PHONES.into_iter().chain(SIDEWAYS).chain(SMALL) {
            let a = areas(w, h);
            let rects = if a.tight {
                menu(&a).1
            } else {
                playback(a.bar, Bar::of(&a)).speeds
            };
            let row: Vec<(String, Rect)> = speeds.iter().cloned().zip(rects).collect();
            let size = row_size(&row);
            for lang in [Lang::En, Lang::Ru] {
                let text = |id: &str| message_in(lang, id).expect("the message exists");
                let mut labels: Vec<String> = std::iter::once("lobby".to_string())
                    .chain(TOOLS.map(|t| format!("sandbox-tool-{}", t.name())))
                    .chain(["sandbox-wall", "sandbox-panel", "sandbox-export"].map(String::from))
                    .chain(std::iter::once("sandbox-import".to_string()))
                    .map(|id| text(&id))
                    .collect();
                let mut rects = toolbar(&a);
                if !a.compact {
                    // No Panel on a desktop.
                    labels.remove(TOOLS.len() + 2);
                }
                if let Some(r) = tools_button(&a) {
                    labels.push(text("sandbox-menu"));
                    rects.push(r);
                }
                let tools: Vec<(String, Rect)> = labels.into_iter().zip(rects).collect();
                let sizes: Vec<f32> = {
                    let b: Vec<(&str, Rect)> =
                        tools.iter().map(|(l, r)| (l.as_str(), *r)).collect();
                    crate::ui::group_label_sizes(&b, crate::test_geometry::font_width)
                };
                let least = sizes.iter().copied().fold(f32::INFINITY, f32::min);
                eprintln!("sandbox {w}x{h} {lang:?}: speeds at {size}, tools at {least}");
                assert!(size >= 13.0, "{w}x{h}: the speeds at {size}");
                assert!(least >= 12.0, "{w}x{h} {lang:?}: the tools at {sizes:?}");
            }
        }
    }
}
