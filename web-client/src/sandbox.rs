//! The offline physics sandbox (the thesis's single-player mode): place,
//! edit and delete discs, points and lines on an exact event-driven engine;
//! give a disc a velocity by dragging an arrow; set gravity and friction;
//! play, pause, rewind, scrub and change speed (slow motion included);
//! export and import the scene file; watch a statistics panel; and load
//! the presets — Galperin's billiard with its live count of the digits of
//! pi, a box of discs in Brownian motion, and the Chapaev break. Pan by
//! dragging empty space (or with the middle or right button), zoom with
//! the wheel.
//!
//! This module owns the screen: layout, input routing, drawing and the
//! panels. Every control is finger-sized; a window narrower than a
//! desktop's (a phone) gets the compact layout: the tools wrap in rows
//! above the world, the playback bar takes two rows below it, and the side
//! panel opens over the world with the "Panel" button. The logic lives in submodules: [`sim`] (the model and its
//! playback), [`tools`] (the editing state machine), [`presets`] (the
//! ready-made scenes).

pub mod presets;
pub mod sim;
pub mod tools;

use crate::draw;
use crate::platform;
use crate::route::Route;
use crate::screen::Screen;
use crate::ui::{self, colors, Ui};
use crate::viewport::Viewport;
use ::glam::DVec2;
use engine::{Action, BodyId, BodySpec, EndReason, LineKind, Scene};
use macroquad::prelude::*;
use presets::{DiscTemplate, Kind, MAX_GALPERIN};
use sim::{Sim, Tally, SPEEDS};
use tools::{Button, Gesture, Make, Tool, TOOLS};

/// Event budget per frame: adapted to keep a frame's computing near
/// [`COMPUTE_MS`], between these bounds.
const MIN_BUDGET: u64 = 2_000;
const MAX_BUDGET: u64 = 400_000;
const COMPUTE_MS: f64 = 20.0;

/// Height of the toolbar and the playback bar; width of the side panel.
const TOP: f32 = 56.0;
const BOTTOM: f32 = 60.0;
const SIDE: f32 = 262.0;
/// The narrowest window the desktop layout fits (narrower ones get the
/// compact layout).
const MIN_WIDTH: f32 = 1000.0;
/// Gap between controls.
const GAP: f32 = 4.0;
/// The compact toolbar's buttons: Lobby, the tools, Wall/Edge, Panel,
/// Import, Export (about 70 units each).
const TOOLBAR_BUTTONS: usize = TOOLS.len() + 5;

/// Height of a row of the side panel (a finger-sized control and a gap).
const ROW: f32 = ui::TOUCH + GAP;

/// Width the statistics panel takes from the world area (with margins).
const STATS_W: f32 = 248.0;

/// How long a message stays, seconds.
const MESSAGE_SECS: f64 = 7.0;

/// The sandbox screen.
pub struct Sandbox {
    sim: Sim,
    kind: Kind,
    /// Draw the 8x8 board of this size (the break).
    board: Option<f64>,
    view: Viewport,
    /// The view needs fitting to the scene (on the next frame, when the
    /// screen size is known).
    refit: bool,
    tool: Tool,
    /// New lines are sensors (edges discs fall off) instead of walls.
    sensor: bool,
    template: DiscTemplate,
    selected: Option<BodyId>,
    gesture: Option<(Gesture, Button)>,
    last_pointer: Vec2,
    galperin_n: u32,
    /// Gravity being dragged on its slider (applied on release).
    g_edit: Option<f64>,
    message: Option<(String, bool, f64)>,
    waiting_file: bool,
    budget: u64,
    compute_ms: f64,
    frame_ms: f64,
    clock: f64,
    tally: Tally,
    /// The side panel is open over the world (compact layout only).
    panel_open: bool,
}

impl Sandbox {
    /// Opens with the preset named by `?preset=` in the address, else the
    /// Chapaev break, paused at its start.
    pub fn new() -> Sandbox {
        let kind = preset_in(&platform::location()).unwrap_or(Kind::Break);
        let preset = presets::build(kind);
        let sim = match Sim::new(preset.scene.clone()) {
            Ok(sim) => sim,
            // The presets are valid scenes (tested); this is only a fallback.
            Err(_) => Sim::new(Scene::default()).unwrap_or_else(|_| unreachable!()),
        };
        let mut s = Sandbox {
            sim,
            kind: preset.kind,
            board: preset.board,
            view: Viewport {
                centre: DVec2::ZERO,
                anchor: vec2(0.0, 0.0),
                scale: 100.0,
                flipped: false,
            },
            refit: true,
            tool: Tool::Select,
            sensor: false,
            template: preset.template,
            selected: preset.follow,
            gesture: None,
            last_pointer: vec2(0.0, 0.0),
            galperin_n: 3,
            g_edit: None,
            message: None,
            waiting_file: false,
            budget: 50_000,
            compute_ms: 0.0,
            frame_ms: 0.0,
            clock: 0.0,
            tally: Tally::default(),
            panel_open: false,
        };
        if let Kind::Galperin(n) = kind {
            s.galperin_n = n;
        }
        s.sim.playing = platform::location().contains("play=1");
        s.say(hint(kind), false);
        s
    }

    fn say(&mut self, text: impl Into<String>, error: bool) {
        self.message = Some((text.into(), error, self.clock));
    }

    fn load_preset(&mut self, kind: Kind) {
        let p = presets::build(kind);
        match Sim::new(p.scene) {
            Ok(sim) => {
                self.sim = sim;
                self.kind = p.kind;
                self.board = p.board;
                self.template = p.template;
                self.selected = p.follow;
                self.gesture = None;
                self.refit = true;
                self.say(hint(p.kind), false);
            }
            Err(e) => self.say(format!("preset failed: {e}"), true),
        }
    }

    fn import(&mut self, text: &str) {
        match Sim::import(text) {
            Ok(sim) => {
                let n = sim.scene().bodies.len();
                self.sim = sim;
                self.kind = Kind::Imported;
                self.board = None;
                self.selected = None;
                self.gesture = None;
                self.refit = true;
                self.say(format!("imported a scene of {n} bodies"), false);
            }
            Err(e) => self.say(format!("import refused, scene unchanged: {e}"), true),
        }
    }

    /// Applies an edit at the time shown, reporting a refusal.
    fn edit(&mut self, action: Action) {
        let added = match &action {
            Action::AddBody { body } => Some(body.id),
            _ => None,
        };
        let removed = match &action {
            Action::RemoveBody { id } => Some(*id),
            _ => None,
        };
        match self.sim.edit(action) {
            Ok(()) => {
                if added.is_some() {
                    self.selected = added;
                }
                if removed.is_some() && removed == self.selected {
                    self.selected = None;
                }
            }
            Err(e) => self.say(format!("refused: {e}"), true),
        }
    }

    fn selected_body(&self, scene: &Scene) -> Option<BodySpec> {
        let id = self.selected?;
        scene.bodies.iter().find(|b| b.id == id).copied()
    }

    fn update_selected(&mut self, scene: &Scene, change: impl Fn(&mut BodySpec)) {
        if let Some(mut b) = self.selected_body(scene) {
            change(&mut b);
            self.edit(Action::UpdateBody { body: b });
        }
    }

    // ---- input --------------------------------------------------------

    fn keys(&mut self, scene: &Scene) {
        if is_key_pressed(KeyCode::Space) {
            self.toggle_play();
        }
        if is_key_pressed(KeyCode::Home) {
            self.sim.playing = false;
            let start = self.sim.start();
            self.sim.seek(start);
        }
        if is_key_pressed(KeyCode::Escape) {
            self.tool = Tool::Select;
            self.gesture = None;
        }
        if is_key_pressed(KeyCode::Delete) || is_key_pressed(KeyCode::Backspace) {
            if let Some(b) = self.selected_body(scene) {
                self.sim.playing = false;
                self.edit(Action::RemoveBody { id: b.id });
            }
        }
    }

    fn toggle_play(&mut self) {
        if self.sim.playing {
            self.sim.playing = false;
        } else {
            self.sim.play();
        }
    }

    fn world_input(&mut self, ui: &Ui, area: Rect, scene: &Scene) {
        let p = ui.input.pointer;
        let inside = area.contains(p);
        if inside && ui.input.wheel != 0.0 && self.gesture.is_none() {
            self.view
                .zoom_about(p, 1.15f64.powf(ui.input.wheel.signum() as f64));
        }
        if self.gesture.is_none() && inside && !ui.captured() {
            let button = if ui.input.pressed {
                Some(Button::Primary)
            } else if ui.input.alt_pressed {
                Some(Button::Secondary)
            } else if is_mouse_button_pressed(MouseButton::Middle) {
                Some(Button::Middle)
            } else {
                None
            };
            if let Some(button) = button {
                let w = self.view.to_world(p);
                let hit = tools::pick(scene, w, 8.0 / self.view.scale);
                let (g, select) = tools::press(self.tool, button, hit, w, scene);
                if let Some(s) = select {
                    self.selected = s;
                }
                if g != Gesture::Pan {
                    self.sim.playing = false;
                }
                self.gesture = Some((g, button));
                self.last_pointer = p;
            }
        }
        if let Some((g, button)) = self.gesture {
            let down = match button {
                Button::Primary => ui.input.down,
                Button::Secondary => is_mouse_button_down(MouseButton::Right),
                Button::Middle => is_mouse_button_down(MouseButton::Middle),
            };
            if g == Gesture::Pan {
                self.view.pan(p - self.last_pointer);
            }
            let g = tools::drag(g, self.view.to_world(p));
            self.last_pointer = p;
            if down {
                self.gesture = Some((g, button));
            } else {
                self.gesture = None;
                // The scene may have moved on while playing: act on the
                // state at the time shown now.
                let now = self.sim.scene();
                let make = Make {
                    disc: self.template,
                    sensor: self.sensor,
                    slop: 3.0 / self.view.scale,
                };
                if let Some(action) = tools::release(g, &now, &make) {
                    self.edit(action);
                }
            }
        }
    }

    // ---- drawing the world --------------------------------------------

    fn draw_world(&self, area: Rect, scene: &Scene) {
        let v = &self.view;
        match self.board {
            Some(size) => draw::board(v, size),
            None => grid(v, area),
        }
        for l in &scene.lines {
            if self.board.is_some_and(|size| on_board_edge(l, size)) {
                continue;
            }
            if l.sensor {
                draw::line(v, l, Color::new(0.45, 0.75, 0.40, 0.55), 1.5);
            } else {
                draw::line(v, l, colors::TEXT, 2.5);
            }
        }
        for q in &scene.points {
            draw::point(v.to_screen(q.pos), colors::ACCENT);
        }
        if let Some(id) = self.selected {
            self.trail(id);
        }
        for b in &scene.bodies {
            let c = v.to_screen(b.pos);
            let r = v.px(b.radius).max(1.5);
            let selected = self.selected == Some(b.id);
            match (self.board, presets::checker_side(b.id)) {
                (Some(_), Some(side)) => {
                    draw::checker(c, r, side, 1.0);
                    if selected {
                        draw::halo(c, r, colors::ACCENT);
                    }
                }
                _ => draw::disc(c, r, b.id.0, selected),
            }
        }
        self.hit_rings();
        if !self.sim.playing {
            let few = scene.bodies.len() <= 40;
            for b in &scene.bodies {
                if b.vel != DVec2::ZERO && (few || self.selected == Some(b.id)) {
                    let from = v.to_screen(b.pos);
                    let to = v.to_screen(b.pos + tools::arrow_of(b.vel));
                    draw::arrow(from, to, Color::new(0.55, 0.85, 1.0, 0.8), 2.0);
                }
            }
        }
        self.gesture_preview(scene);
    }

    /// The path of body `id` over the last 30 s of model time.
    fn trail(&self, id: BodyId) {
        let t = self.sim.t;
        let from = (t - 30.0).max(self.sim.start());
        if t <= from || t.is_nan() {
            return;
        }
        const N: usize = 300;
        let mut last: Option<Vec2> = None;
        for k in 0..=N {
            let tk = from + (t - from) * k as f64 / N as f64;
            let here = self
                .sim
                .model
                .body_at(id, tk)
                .map(|b| self.view.to_screen(b.pos));
            if let (Some(a), Some(b)) = (last, here) {
                let alpha = 0.15 + 0.6 * k as f32 / N as f32;
                draw_line(a.x, a.y, b.x, b.y, 2.0, Color::new(0.93, 0.66, 0.25, alpha));
            }
            last = here;
        }
    }

    /// Expanding rings where collisions just happened.
    fn hit_rings(&self) {
        let window = 0.3 * self.sim.speed.abs().max(1e-3);
        let t = self.sim.t;
        for e in self.sim.recent_events(t - window, t, 40) {
            if !e.kind.is_collision() {
                continue;
            }
            let mut at = DVec2::ZERO;
            let mut n = 0.0;
            let mut r: f64 = 0.0;
            for id in e.kind.bodies() {
                if let Some(b) = self.sim.model.body_at(id, e.t) {
                    at += b.pos;
                    n += 1.0;
                    r = r.max(b.radius);
                }
            }
            if n > 0.0 {
                let c = self.view.to_screen(at / n);
                let progress = ((t - e.t) / window) as f32;
                draw::hit_ring(c, self.view.px(r).max(8.0), progress);
            }
        }
    }

    fn gesture_preview(&self, scene: &Scene) {
        let v = &self.view;
        let Some((g, _)) = self.gesture else {
            return;
        };
        let find = |id| scene.bodies.iter().find(|b| b.id == id);
        match g {
            Gesture::Move { id, offset, to } => {
                if let Some(b) = find(id) {
                    let c = v.to_screen(to + offset);
                    let r = v.px(b.radius);
                    draw_circle(c.x, c.y, r, Color::new(1.0, 0.95, 0.8, 0.35));
                    draw_circle_lines(c.x, c.y, r, 1.5, colors::ACCENT);
                }
            }
            Gesture::Aim { id, to } => {
                if let Some(b) = find(id) {
                    let from = v.to_screen(b.pos);
                    let tip = v.to_screen(to);
                    draw::arrow(from, tip, colors::ACCENT, 3.0);
                    let speed = tools::velocity_from_drag(to - b.pos).length();
                    ui::text(
                        &format!("{speed:.2} m/s"),
                        tip.x + 10.0,
                        tip.y - 10.0,
                        18.0,
                        colors::ACCENT,
                    );
                }
            }
            Gesture::Draw { kind, a, b } => {
                if (b - a).length() > 0.0 {
                    let line = engine::Line {
                        a,
                        b,
                        kind,
                        sensor: self.sensor,
                    };
                    draw::line(v, &line, colors::ACCENT, 2.0);
                }
            }
            Gesture::Place { disc: true, at } => {
                let c = v.to_screen(at);
                draw_circle_lines(c.x, c.y, v.px(self.template.radius), 1.5, colors::ACCENT);
            }
            Gesture::Place { disc: false, at } => draw::point(v.to_screen(at), colors::ACCENT),
            Gesture::Pan | Gesture::Delete(_) => {}
        }
    }

    // ---- overlays -----------------------------------------------------

    fn stats_panel(&self, area: Rect, scene: &Scene) {
        let tally = &self.tally;
        let r = Rect::new(area.x + 8.0, area.y + 8.0, 232.0, 265.0);
        ui::panel(r);
        let mut y = r.y + 8.0;
        let mut row = |label: &str, value: String, color: Color| {
            ui::text(label, r.x + 10.0, y, 16.0, colors::MUTED);
            ui::text(&value, r.x + 128.0, y, 16.0, color);
            y += 19.0;
        };
        let end = match self.sim.end() {
            Some(e) if e.reason == EndReason::Rest => "end (rest)".to_string(),
            Some(e) if e.reason == EndReason::Free => "end (free)".to_string(),
            _ => format!("{} s", num(self.sim.computed_to())),
        };
        row("time", format!("{} s", num(self.sim.t)), colors::TEXT);
        row("speed", speed_label(self.sim.speed), colors::TEXT);
        row("computed to", end, colors::TEXT);
        row("events", tally.physical().to_string(), colors::TEXT);
        row("  body-body", tally.body_body.to_string(), colors::TEXT);
        row("  body-line", tally.body_line.to_string(), colors::TEXT);
        row("  body-point", tally.body_point.to_string(), colors::TEXT);
        row("  stops", tally.stops.to_string(), colors::TEXT);
        row("  fell off", tally.exits.to_string(), colors::TEXT);
        row("edits", tally.actions.to_string(), colors::TEXT);
        row("bodies", scene.bodies.len().to_string(), colors::TEXT);
        row(
            "lines, points",
            format!("{}, {}", scene.lines.len(), scene.points.len()),
            colors::TEXT,
        );
        row("frame", format!("{:.1} ms", self.frame_ms), colors::TEXT);
        if self.sim.behind {
            row(
                "computing",
                format!("{:.0} ms/frame", self.compute_ms),
                colors::ACCENT,
            );
        }
    }

    /// Galperin's counter: collisions so far against the digits of pi.
    fn galperin_panel(&self, area: Rect, n: u32) {
        let count = self.tally.body_body + self.tally.body_line;
        let target = engine::presets::pi_digits(n);
        let w = 330.0;
        let r = Rect::new(area.x + area.w - w - 8.0, area.y + 8.0, w, 112.0);
        ui::panel(r);
        ui::text("collisions", r.x + 12.0, r.y + 8.0, 16.0, colors::MUTED);
        let done = count == target && self.sim.end().is_some_and(|e| e.reason == EndReason::Free);
        let color = if done { colors::GOOD } else { colors::ACCENT };
        ui::text(&count.to_string(), r.x + 12.0, r.y + 26.0, 44.0, color);
        let digits = target.to_string();
        let pi = format!("{}.{}", &digits[..1], &digits[1..]);
        ui::text(
            &format!("pi to {n} digits: {pi}"),
            r.x + 12.0,
            r.y + 70.0,
            18.0,
            colors::TEXT,
        );
        let ratio = format!("mass ratio 100^{} ", n - 1);
        let status = if done { "all done" } else { "" };
        ui::text(
            &format!("{ratio}{status}"),
            r.x + 12.0,
            r.y + 90.0,
            15.0,
            colors::MUTED,
        );
    }

    fn message_line(&self, area: Rect) {
        let Some((text, error, since)) = &self.message else {
            return;
        };
        let age = self.clock - since;
        if age > MESSAGE_SECS {
            return;
        }
        let alpha = (1.0 - ((age - MESSAGE_SECS + 1.0).max(0.0))) as f32;
        let size = 17.0;
        let w = ui::text_width(text, size).min(area.w - 24.0) + 20.0;
        let r = Rect::new(area.x + 8.0, area.y + area.h - 36.0, w, 28.0);
        draw_rectangle(
            r.x,
            r.y,
            r.w,
            r.h,
            Color::new(0.1, 0.07, 0.05, 0.85 * alpha),
        );
        let c = if *error { colors::DANGER } else { colors::TEXT };
        ui::text(
            &ui::fit(text, size, area.w - 24.0),
            r.x + 10.0,
            r.y + 6.0,
            size,
            Color::new(c.r, c.g, c.b, alpha),
        );
    }

    // ---- controls -----------------------------------------------------

    /// The toolbar: one row on a desktop; in the compact layout the
    /// buttons wrap in rows of equal width, with "Panel" among them.
    fn toolbar(&mut self, ui: &mut Ui, w: f32, compact: bool) -> Option<Route> {
        let h = ui::TOUCH;
        let y = 6.0;
        // (name, label, width on a desktop (0: at the right), selected).
        let mut items: Vec<(String, &str, f32, bool)> =
            vec![("lobby".into(), "Lobby", 70.0, false)];
        for tool in TOOLS {
            let label = match tool {
                Tool::Select => "Select",
                Tool::Velocity => "Velocity",
                Tool::Disc => "Disc",
                Tool::Point => "Point",
                Tool::Line(LineKind::Line) => "Line",
                Tool::Line(LineKind::Ray) => "Ray",
                Tool::Line(LineKind::Segment) => "Segment",
                Tool::Delete => "Delete",
            };
            items.push((
                format!("tool-{}", tool.name()),
                label,
                74.0,
                self.tool == tool,
            ));
        }
        let sensor = if self.sensor { "Edge" } else { "Wall" };
        items.push(("sensor".into(), sensor, 58.0, self.sensor));
        if compact {
            items.push(("panel".into(), "Panel", 0.0, self.panel_open));
        }
        items.push(("export".into(), "Export", 0.0, false));
        items.push(("import".into(), "Import", 0.0, false));
        let rects: Vec<Rect> = if compact {
            let per_row = toolbar_per_row(w);
            let bw = (w - 16.0 - GAP * (per_row - 1) as f32) / per_row as f32;
            (0..items.len())
                .map(|i| {
                    let (c, r) = ((i % per_row) as f32, (i / per_row) as f32);
                    Rect::new(8.0 + c * (bw + GAP), y + r * (h + GAP), bw, h)
                })
                .collect()
        } else {
            let mut x = 8.0;
            let mut right = w - 8.0;
            items
                .iter()
                .map(|(name, _, bw, _)| {
                    if *bw == 0.0 {
                        right -= 74.0;
                        let r = Rect::new(right, y, 74.0, h);
                        right -= GAP;
                        r
                    } else {
                        let r = Rect::new(x, y, *bw, h);
                        let after = if name == "lobby" || name == "tool-delete" {
                            14.0
                        } else {
                            GAP
                        };
                        x += bw + after;
                        r
                    }
                })
                .collect()
        };
        let mut go = None;
        for ((name, label, _, selected), r) in items.iter().zip(rects) {
            if !ui.button_styled(name, label, r, true, *selected) {
                continue;
            }
            match name.as_str() {
                "lobby" => go = Some(Route::Lobby),
                "sensor" => {
                    self.sensor = !self.sensor;
                    self.say(
                        if self.sensor {
                            "new lines are edges: a disc whose centre crosses one falls off"
                        } else {
                            "new lines are walls: discs bounce off them"
                        },
                        false,
                    );
                }
                "panel" => {
                    self.panel_open = !self.panel_open;
                    self.gesture = None;
                }
                "import" => {
                    platform::request_file();
                    self.waiting_file = true;
                    self.say("choose a scene file (JSON)", false);
                }
                "export" => match platform::save_file("scene.json", &self.sim.export()) {
                    Ok(m) => self.say(
                        format!("{m} (the scene at t = {} s)", num(self.sim.t)),
                        false,
                    ),
                    Err(e) => self.say(e, true),
                },
                tool => {
                    if let Some(t) = TOOLS.iter().find(|t| format!("tool-{}", t.name()) == tool) {
                        self.tool = *t;
                    }
                }
            }
        }
        go
    }

    /// The material of new discs; returns where the next section starts.
    fn new_disc_controls(&mut self, ui: &mut Ui, x: f32, mut y: f32, w: f32) -> f32 {
        ui::text("New discs", x, y, 15.0, colors::MUTED);
        y += 18.0;
        let t = self.template;
        if let Some(f) = stepper(
            ui,
            "new-radius",
            &format!("radius {}", num(t.radius)),
            x,
            y,
            w,
        ) {
            self.template.radius = (t.radius * f).clamp(1e-4, 1e3);
        }
        y += ROW;
        if let Some(f) = stepper(ui, "new-mass", &format!("mass {}", num(t.mass)), x, y, w) {
            self.template.mass = (t.mass * f * f).clamp(1e-6, 1e12);
        }
        y += ROW;
        self.template.mu = unit_slider(ui, "new-mu", "mu", t.mu, x, y, w);
        y += ROW;
        self.template.restitution = unit_slider(ui, "new-e", "e", t.restitution, x, y, w);
        y += ROW + 6.0;
        y
    }

    fn side_panel(&mut self, ui: &mut Ui, r: Rect, scene: &Scene) {
        ui::panel(r);
        let x = r.x + 10.0;
        let w = r.w - 20.0;
        let mut y = r.y + 8.0;
        let h = ui::TOUCH;
        let heading = |s: &str, y: f32| ui::text(s, x, y, 17.0, colors::ACCENT);

        heading("Presets", y);
        y += 22.0;
        let n = self.galperin_n;
        if ui.button_styled(
            "preset-galperin",
            &format!("Galperin n={n}"),
            Rect::new(x, y, w - 2.0 * (h + GAP), h),
            true,
            self.kind == Kind::Galperin(n),
        ) {
            self.load_preset(Kind::Galperin(n));
        }
        if ui.button_styled(
            "galperin-less",
            "-",
            Rect::new(x + w - 2.0 * h - GAP, y, h, h),
            n > 1,
            false,
        ) {
            self.galperin_n = n - 1;
            self.load_preset(Kind::Galperin(n - 1));
        }
        if ui.button_styled(
            "galperin-more",
            "+",
            Rect::new(x + w - h, y, h, h),
            n < MAX_GALPERIN,
            false,
        ) {
            self.galperin_n = n + 1;
            self.load_preset(Kind::Galperin(n + 1));
        }
        y += h + 4.0;
        let half = (w - 4.0) / 2.0;
        if ui.button_styled(
            "preset-brownian",
            "Brownian box",
            Rect::new(x, y, half, h),
            true,
            self.kind == Kind::Brownian,
        ) {
            self.load_preset(Kind::Brownian);
        }
        if ui.button_styled(
            "preset-break",
            "Chapaev break",
            Rect::new(x + half + 4.0, y, half, h),
            true,
            self.kind == Kind::Break,
        ) {
            self.load_preset(Kind::Break);
        }
        y += h + 4.0;
        if ui.button_styled(
            "preset-empty",
            "Empty table",
            Rect::new(x, y, half, h),
            true,
            self.kind == Kind::Empty,
        ) {
            self.load_preset(Kind::Empty);
        }
        if ui.button("fit", "Fit view", Rect::new(x + half + 4.0, y, half, h)) {
            self.refit = true;
        }
        y += h + 12.0;

        heading("World", y);
        y += 22.0;
        let g_now = self.g_edit.unwrap_or(scene.g);
        ui::text(
            &format!("g = {g_now:.2} m/s2"),
            x,
            y + 4.0,
            16.0,
            colors::TEXT,
        );
        let g = ui.slider(
            "gravity",
            g_now,
            0.0,
            20.0,
            Rect::new(x + 118.0, y, w - 118.0, ui::TOUCH),
        );
        if g != g_now {
            self.g_edit = Some((g * 100.0).round() / 100.0);
        }
        if let Some(g) = self.g_edit {
            if !ui.input.down {
                self.g_edit = None;
                if g != scene.g {
                    self.edit(Action::SetGravity { g });
                }
            }
        }
        y += ROW;
        // Without the room for both, a selected body's controls replace
        // those of new discs.
        let compact = r.h < 720.0;
        if !(compact && self.selected_body(scene).is_some()) {
            y = self.new_disc_controls(ui, x, y, w);
        }

        match (self.selected, self.selected_body(scene)) {
            (Some(_), Some(b)) => {
                heading(&format!("Body {}", b.id.0), y);
                y += 22.0;
                ui::text(
                    &format!(
                        "at ({}, {})  |v| {} m/s",
                        num(b.pos.x),
                        num(b.pos.y),
                        num(b.vel.length())
                    ),
                    x,
                    y,
                    15.0,
                    colors::TEXT,
                );
                y += 20.0;
                if let Some(f) = stepper(
                    ui,
                    "body-radius",
                    &format!("radius {}", num(b.radius)),
                    x,
                    y,
                    w,
                ) {
                    self.update_selected(scene, |b| b.radius *= f);
                }
                y += ROW;
                if let Some(f) = stepper(ui, "body-mass", &format!("mass {}", num(b.mass)), x, y, w)
                {
                    self.update_selected(scene, |b| b.mass *= f * f);
                }
                y += ROW;
                if let Some(f) = stepper(ui, "body-mu", &format!("mu {:.2}", b.mu), x, y, w) {
                    let step = if f > 1.0 { 0.05 } else { -0.05 };
                    self.update_selected(scene, |b| {
                        b.mu = ((b.mu + step) * 100.0).round().max(0.0) / 100.0
                    });
                }
                y += ROW;
                if let Some(f) = stepper(ui, "body-e", &format!("e {:.2}", b.restitution), x, y, w)
                {
                    let step = if f > 1.0 { 0.1 } else { -0.1 };
                    self.update_selected(scene, |b| {
                        b.restitution =
                            ((b.restitution + step) * 10.0).round().clamp(0.0, 10.0) / 10.0
                    });
                }
                y += ROW + 2.0;
                if ui.button("body-stop", "Stop it", Rect::new(x, y, half, h)) {
                    self.edit(Action::SetVelocity {
                        id: b.id,
                        vel: DVec2::ZERO,
                    });
                }
                if ui.button(
                    "body-delete",
                    "Delete",
                    Rect::new(x + half + 4.0, y, half, h),
                ) {
                    self.edit(Action::RemoveBody { id: b.id });
                }
            }
            (Some(id), None) => {
                heading(&format!("Body {}", id.0), y);
                ui::text(
                    "not in the scene at this time",
                    x,
                    y + 22.0,
                    15.0,
                    colors::MUTED,
                );
            }
            (None, _) => {
                heading("Selection", y);
                for (k, line) in [
                    "Click a body to select it.",
                    "Drag it to move it; right-drag",
                    "(or the Velocity tool) to aim it.",
                    "Wheel: zoom.  Drag empty: pan.",
                    "Space: play/pause.  Del: delete.",
                ]
                .iter()
                .enumerate()
                {
                    let ly = y + 22.0 + 18.0 * k as f32;
                    // As many as the panel holds.
                    if ly + 18.0 > r.y + r.h {
                        break;
                    }
                    ui::text(line, x, ly, 15.0, colors::MUTED);
                }
            }
        }
    }

    /// Rewind, play, the speeds and the time slider: one row on a
    /// desktop; two in the compact layout (the speeds below).
    fn playback_bar(&mut self, ui: &mut Ui, r: Rect, compact: bool) {
        ui::panel(r);
        let h = ui::TOUCH;
        let y = r.y + 6.0;
        let mut x = r.x + 8.0;
        if ui.button("rewind", "|<", Rect::new(x, y, h, h)) {
            self.sim.playing = false;
            let start = self.sim.start();
            self.sim.seek(start);
        }
        x += h + GAP;
        let label = if self.sim.playing { "Pause" } else { "Play" };
        if ui.button_styled(
            "play",
            label,
            Rect::new(x, y, 70.0, h),
            true,
            self.sim.playing,
        ) {
            self.toggle_play();
        }
        // Room for the slider's knob beside Play.
        x += 70.0 + 24.0;
        let n = SPEEDS.len() as f32;
        let (mut sx, sy, sw) = if compact {
            let sw = (r.w - 16.0 - GAP / 2.0 * (n - 1.0)) / n;
            (r.x + 8.0, y + h + GAP, sw)
        } else {
            (x, y, 44.0)
        };
        for s in SPEEDS {
            let name = format!("speed-{s}");
            let selected = self.sim.speed == s;
            if ui.button_styled(
                &name,
                &speed_label(s),
                Rect::new(sx, sy, sw, h),
                true,
                selected,
            ) {
                self.sim.speed = s;
                if s < 0.0 && self.sim.t > self.sim.start() {
                    self.sim.playing = true;
                }
            }
            sx += sw + GAP / 2.0;
        }
        if !compact {
            x = sx + 24.0;
        }
        let label_w = if compact { 96.0 } else { 120.0 };
        let slider = Rect::new(x, y, (r.x + r.w - label_w - 16.0 - x).max(40.0), h);
        let start = self.sim.start();
        let computed = self.sim.computed_to();
        let last = self.sim.model.events().last().map_or(start, |e| e.t);
        let hi = if computed.is_finite() {
            computed
        } else {
            last.max(self.sim.t) + 0.5
        }
        .max(start + 1e-9);
        let t = ui.slider("time", self.sim.t, start, hi, slider);
        if t != self.sim.t {
            self.sim.playing = false;
            self.sim.seek(t);
        }
        ui::text(
            &ui::fit(&format!("t = {} s", num(self.sim.t)), 17.0, label_w),
            slider.x + slider.w + 12.0,
            y + 13.0,
            17.0,
            colors::TEXT,
        );
    }
}

impl Default for Sandbox {
    fn default() -> Self {
        Sandbox::new()
    }
}

impl Screen for Sandbox {
    fn frame(&mut self, ui: &mut Ui, dt: f64) -> Option<Route> {
        self.clock += dt;
        self.frame_ms = 0.9 * self.frame_ms + 0.1 * dt * 1000.0;
        let (w, h) = crate::scale::size().into();
        let compact = w < MIN_WIDTH;
        let (top, bottom) = if compact {
            let rows = toolbar_rows(w);
            (
                6.0 + rows * (ui::TOUCH + GAP) + 2.0,
                2.0 * (ui::TOUCH + GAP) + 12.0,
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
        if !compact {
            self.panel_open = false;
        }

        if self.waiting_file {
            if let Some(text) = platform::picked_file() {
                self.waiting_file = false;
                self.import(&text);
            }
        }

        // Play: extend the chain within the frame's event budget.
        let started = get_time();
        self.sim.advance(dt, self.budget);
        let took = (get_time() - started) * 1000.0;
        if self.sim.behind {
            self.compute_ms = 0.8 * self.compute_ms + 0.2 * took;
            if took < COMPUTE_MS * 0.5 {
                self.budget = (self.budget * 2).min(MAX_BUDGET);
            } else if took > COMPUTE_MS {
                self.budget = (self.budget / 2).max(MIN_BUDGET);
            }
        }

        let scene = self.sim.scene();
        if self.refit {
            // The compact layout has no statistics panel to leave room for.
            let left = if compact { 0.0 } else { STATS_W };
            self.view = fit(&scene, self.board, world, left);
            self.refit = false;
        }
        self.keys(&scene);
        if !self.panel_open {
            self.world_input(ui, world, &scene);
        }
        let scene = self.sim.scene();
        self.tally = self.sim.tally();

        self.draw_world(world, &scene);
        if !compact {
            self.stats_panel(world, &scene);
        }
        if let Kind::Galperin(n) = self.kind {
            self.galperin_panel(world, n);
        }
        self.message_line(world);
        // The world stays out of the bars and the side panel.
        draw_rectangle(0.0, 0.0, w, top - 2.0, colors::BACKGROUND);
        draw_rectangle(0.0, h - bottom - 4.0, w, bottom + 4.0, colors::BACKGROUND);
        draw_rectangle(
            world.x + world.w,
            top - 2.0,
            w - world.x - world.w,
            h,
            colors::BACKGROUND,
        );
        let route = self.toolbar(ui, w, compact);
        if !compact || self.panel_open {
            self.side_panel(ui, side, &scene);
        }
        self.playback_bar(ui, bar, compact);
        route
    }

    fn name(&self) -> &'static str {
        "sandbox"
    }

    fn report(&self) -> serde_json::Map<String, serde_json::Value> {
        let scene = self.sim.scene();
        let mut m = serde_json::Map::new();
        let t = &self.tally;
        m.insert("bodies".into(), scene.bodies.len().into());
        m.insert("lines".into(), scene.lines.len().into());
        m.insert("points".into(), scene.points.len().into());
        m.insert("t".into(), self.sim.t.into());
        m.insert("events".into(), t.upto.into());
        m.insert("collisions".into(), t.collisions().into());
        m.insert(
            "by_kind".into(),
            serde_json::json!({
                "body-body": t.body_body, "body-line": t.body_line,
                "body-point": t.body_point, "stop": t.stops,
                "region-exit": t.exits, "action": t.actions,
            }),
        );
        m.insert("computed_to".into(), self.sim.computed_to().into());
        m.insert("playing".into(), self.sim.playing.into());
        m.insert("behind".into(), self.sim.behind.into());
        m.insert("speed".into(), self.sim.speed.into());
        m.insert("g".into(), scene.g.into());
        m.insert("tool".into(), self.tool.name().into());
        m.insert("preset".into(), self.kind.name().into());
        m.insert("selected".into(), self.selected.map(|b| b.0).into());
        m.insert("panel_open".into(), self.panel_open.into());
        if let Some((text, error, _)) = &self.message {
            m.insert("message".into(), text.clone().into());
            m.insert("error".into(), (*error).into());
        }
        m
    }

    fn animating(&self) -> bool {
        self.sim.playing || self.gesture.is_some()
    }
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

/// A labelled slider over `[0, 1]` at `(x, y)`, `w` wide: the value shown
/// and returned to two decimals.
fn unit_slider(ui: &mut Ui, id: &str, label: &str, value: f64, x: f32, y: f32, w: f32) -> f64 {
    ui::text(
        &format!("{label} {value:.2}"),
        x,
        y + 4.0,
        16.0,
        colors::TEXT,
    );
    let v = ui.slider(
        id,
        value,
        0.0,
        1.0,
        Rect::new(x + 118.0, y, w - 118.0, ui::TOUCH),
    );
    (v * 100.0).round() / 100.0
}

/// A `-` / `+` pair with a label; the factor 1/1.25 or 1.25 when clicked.
fn stepper(ui: &mut Ui, name: &str, label: &str, x: f32, y: f32, w: f32) -> Option<f64> {
    let h = ui::TOUCH;
    ui::text(label, x, y + 13.0, 16.0, colors::TEXT);
    let less = ui.button(
        &format!("{name}-less"),
        "-",
        Rect::new(x + w - 2.0 * h - GAP, y, h, h),
    );
    let more = ui.button(&format!("{name}-more"), "+", Rect::new(x + w - h, y, h, h));
    if less {
        Some(1.0 / 1.25)
    } else if more {
        Some(1.25)
    } else {
        None
    }
}

/// A line with an arrow head, clamped to 300 pixels.
/// A faint metric grid (lines every 1, 2 or 5 times a power of ten metres,
/// at least 40 pixels apart) with its step written in the corner.
fn grid(v: &Viewport, area: Rect) {
    let step = grid_step(v.scale);
    let lo = v.to_world(vec2(area.x, area.y + area.h));
    let hi = v.to_world(vec2(area.x + area.w, area.y));
    let faint = Color::new(1.0, 0.9, 0.7, 0.05);
    let axis = Color::new(1.0, 0.9, 0.7, 0.14);
    let (i0, i1) = ((lo.x / step).floor() as i64, (hi.x / step).ceil() as i64);
    let (j0, j1) = ((lo.y / step).floor() as i64, (hi.y / step).ceil() as i64);
    if i1 - i0 > 400 || j1 - j0 > 400 {
        return;
    }
    for i in i0..=i1 {
        let x = v.to_screen(DVec2::new(i as f64 * step, 0.0)).x;
        let c = if i == 0 { axis } else { faint };
        draw_line(x, area.y, x, area.y + area.h, 1.0, c);
    }
    for j in j0..=j1 {
        let y = v.to_screen(DVec2::new(0.0, j as f64 * step)).y;
        let c = if j == 0 { axis } else { faint };
        draw_line(area.x, y, area.x + area.w, y, 1.0, c);
    }
    ui::text(
        &format!("grid {} m", num(step)),
        area.x + 10.0,
        area.y + area.h - 62.0,
        14.0,
        colors::MUTED,
    );
}

/// The grid step for a scale: the smallest 1, 2 or 5 times a power of ten
/// metres that is at least 40 pixels.
fn grid_step(scale: f64) -> f64 {
    let min = 40.0 / scale.max(1e-12);
    let p = 10f64.powf(min.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|k| k * p)
        .find(|s| *s >= min)
        .unwrap_or(10.0 * p)
}

/// A view that shows the whole scene (and the board) in `area`.
fn fit(scene: &Scene, board: Option<f64>, area: Rect, stats_w: f32) -> Viewport {
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

/// A number with about four significant digits.
fn num(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else if !x.is_finite() {
        "inf".into()
    } else if x.abs() >= 1e5 || x.abs() < 1e-3 {
        format!("{x:.3e}")
    } else if x.abs() >= 100.0 {
        format!("{x:.1}")
    } else if x.abs() >= 1.0 {
        format!("{x:.3}")
    } else {
        format!("{x:.4}")
    }
}

/// `1x`, `0.1x`, `-2x`.
fn speed_label(s: f64) -> String {
    format!("{s}x")
}

/// Whether `l` is one of the edges of the board `[0, size]^2` (drawn by
/// the board's frame already).
fn on_board_edge(l: &engine::Line, size: f64) -> bool {
    let edge = |x: f64| x.abs() < 1e-9 || (x - size).abs() < 1e-9;
    (l.a.x == l.b.x && edge(l.a.x)) || (l.a.y == l.b.y && edge(l.a.y))
}

/// The preset named by a `preset=` parameter in an address, if any.
fn preset_in(address: &str) -> Option<Kind> {
    let (_, rest) = address.split_once("preset=")?;
    let name = rest.split(['&', '#', '/']).next()?;
    Kind::parse(name)
}

/// What to tell the user when a preset opens.
fn hint(kind: Kind) -> &'static str {
    match kind {
        Kind::Galperin(_) => {
            "Galperin's billiard: press Play (try 0.1x or 0.01x) and count the collisions"
        }
        Kind::Brownian => "a heavy disc among light ones: press Play and watch its trail",
        Kind::Break => "the Chapaev break: press Play, or aim a checker with the right button",
        Kind::Empty | Kind::Imported => "place discs, points and lines with the tools above",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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

    #[test]
    fn the_compact_toolbar_takes_three_rows_on_a_phone_and_one_on_a_wide_window() {
        assert_eq!(toolbar_rows(390.0), 3.0);
        assert_eq!(toolbar_rows(999.0), 1.0);
        assert_eq!(toolbar_rows(200.0), 4.0);
    }

    #[test]
    fn grid_steps_are_round_and_at_least_forty_pixels() {
        for scale in [3.0, 100.0, 777.0, 2500.0, 1e5] {
            let s = grid_step(scale);
            assert!(s * scale >= 40.0 - 1e-9, "{scale}: {s}");
            assert!(s * scale < 40.0 * 5.0 + 1e-9, "{scale}: {s}");
        }
        assert_eq!(grid_step(100.0), 0.5);
    }

    #[test]
    fn the_address_may_name_a_preset() {
        assert_eq!(
            preset_in("http://x/?preset=brownian#/sandbox"),
            Some(Kind::Brownian)
        );
        assert_eq!(
            preset_in("http://x/?preset=galperin5#/sandbox"),
            Some(Kind::Galperin(5))
        );
        assert_eq!(preset_in("http://x/#/sandbox"), None);
        assert_eq!(num(0.5), "0.5000");
        assert_eq!(speed_label(0.01), "0.01x");
    }
}
