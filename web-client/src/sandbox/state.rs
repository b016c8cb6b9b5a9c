//! The sandbox's state without drawing, input devices or the browser: the
//! simulation ([`Sim`]) and the preset it came from, the view, the tool in
//! hand and the gesture in progress, the selection, what new discs and
//! lines are made of, the message shown, the side panel's state and the
//! frame's event budget. Every change the screen's controls, keys and
//! pointer make is a method here, so the transitions are tested natively;
//! the screen reads the rest back to draw it.

use super::layout::fit;
use super::presets::{self, DiscTemplate, Kind};
use super::sim::{Sim, Tally};
use super::tools::{self, Button, Gesture, Make, Tool};
use crate::i18n::t;
use crate::viewport::Viewport;
use ::glam::DVec2;
use engine::{Action, BodyId, BodySpec, Scene};
use macroquad::prelude::{vec2, Rect, Vec2};

/// Event budget per frame: adapted to keep a frame's computing near
/// [`COMPUTE_MS`], between these bounds.
const MIN_BUDGET: u64 = 2_000;
const MAX_BUDGET: u64 = 400_000;
const COMPUTE_MS: f64 = 20.0;

/// The sandbox as it stands.
pub struct State {
    pub sim: Sim,
    pub kind: Kind,
    /// Draw the 8x8 board of this size (the break).
    pub board: Option<f64>,
    pub view: Viewport,
    /// The view needs fitting to the scene (on the next frame, when the
    /// screen size is known).
    pub refit: bool,
    pub tool: Tool,
    /// New lines are sensors (edges discs fall off) instead of walls.
    pub sensor: bool,
    pub template: DiscTemplate,
    pub selected: Option<BodyId>,
    pub gesture: Option<(Gesture, Button)>,
    pub last_pointer: Vec2,
    pub galperin_n: u32,
    /// Gravity being dragged on its slider (applied on release).
    pub g_edit: Option<f64>,
    /// The message, whether it is an error, and when it was said.
    pub message: Option<(String, bool, f64)>,
    pub waiting_file: bool,
    pub budget: u64,
    pub compute_ms: f64,
    pub frame_ms: f64,
    /// Seconds since the screen opened.
    pub clock: f64,
    pub tally: Tally,
    /// The side panel is open over the world (compact layout only).
    pub panel_open: bool,
    /// The tight layout's menu of tools and speeds is open over the world.
    pub tools_open: bool,
}

impl State {
    /// Opens with the preset named by `?preset=` in `address`, else the
    /// Chapaev break, paused at its start (playing with `play=1`).
    pub fn from_address(address: &str) -> State {
        let kind = preset_in(address).unwrap_or(Kind::Break);
        let preset = presets::build(kind);
        let sim = match Sim::new(preset.scene.clone()) {
            Ok(sim) => sim,
            // The presets are valid scenes (tested); this is only a fallback.
            Err(_) => Sim::new(Scene::default()).unwrap_or_else(|_| unreachable!()),
        };
        let mut s = State {
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
            tools_open: false,
        };
        if let Kind::Galperin(n) = kind {
            s.galperin_n = n;
        }
        s.sim.playing = address.contains("play=1");
        s.say(hint(kind), false);
        s
    }

    /// Shows `text` (in red if an `error`) for a while.
    pub fn say(&mut self, text: impl Into<String>, error: bool) {
        self.message = Some((text.into(), error, self.clock));
    }

    /// A new frame `dt` seconds after the last.
    pub fn tick(&mut self, dt: f64) {
        self.clock += dt;
        self.frame_ms = 0.9 * self.frame_ms + 0.1 * dt * 1000.0;
    }

    /// Adapts the event budget to a frame whose computing took `took`
    /// milliseconds, while the chain is behind the time shown.
    pub fn adapt_budget(&mut self, took: f64) {
        if self.sim.behind {
            self.compute_ms = 0.8 * self.compute_ms + 0.2 * took;
            if took < COMPUTE_MS * 0.5 {
                self.budget = (self.budget * 2).min(MAX_BUDGET);
            } else if took > COMPUTE_MS {
                self.budget = (self.budget / 2).max(MIN_BUDGET);
            }
        }
    }

    /// Fits the view to the scene in `world` if it asked for it (the
    /// compact layout, without a statistics panel, leaves no room for it).
    pub fn refit_in(&mut self, scene: &Scene, world: Rect, stats_w: f32) {
        if self.refit {
            self.view = fit(scene, self.board, world, stats_w);
            self.refit = false;
        }
    }

    pub fn load_preset(&mut self, kind: Kind) {
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
            Err(e) => self.say(t!("sandbox-preset-failed", error = e.to_string()), true),
        }
    }

    /// Galperin's billiard for `n` digits.
    pub fn galperin(&mut self, n: u32) {
        self.galperin_n = n;
        self.load_preset(Kind::Galperin(n));
    }

    /// Replaces the scene with an exported one, or says why not.
    pub fn import(&mut self, text: &str) {
        match Sim::import(text) {
            Ok(sim) => {
                let n = sim.scene().bodies.len();
                self.sim = sim;
                self.kind = Kind::Imported;
                self.board = None;
                self.selected = None;
                self.gesture = None;
                self.refit = true;
                self.say(t!("sandbox-imported", bodies = n), false);
            }
            Err(e) => self.say(t!("sandbox-import-refused", error = e.to_string()), true),
        }
    }

    /// Applies an edit at the time shown, reporting a refusal.
    pub fn edit(&mut self, action: Action) {
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
            Err(e) => self.say(t!("sandbox-refused", error = e.to_string()), true),
        }
    }

    /// The selected body as it is in `scene`, if it is there.
    pub fn selected_body(&self, scene: &Scene) -> Option<BodySpec> {
        let id = self.selected?;
        scene.bodies.iter().find(|b| b.id == id).copied()
    }

    /// Edits the selected body with `change`.
    pub fn update_selected(&mut self, scene: &Scene, change: impl Fn(&mut BodySpec)) {
        if let Some(mut b) = self.selected_body(scene) {
            change(&mut b);
            self.edit(Action::UpdateBody { body: b });
        }
    }

    /// Deletes the selected body (pausing first).
    pub fn delete_selected(&mut self, scene: &Scene) {
        if let Some(b) = self.selected_body(scene) {
            self.sim.playing = false;
            self.edit(Action::RemoveBody { id: b.id });
        }
    }

    pub fn toggle_play(&mut self) {
        if self.sim.playing {
            self.sim.playing = false;
        } else {
            self.sim.play();
        }
    }

    /// Pauses at the start.
    pub fn rewind(&mut self) {
        self.sim.playing = false;
        let start = self.sim.start();
        self.sim.seek(start);
    }

    /// Plays at speed `s` from now on; a backward speed away from the
    /// start plays at once.
    pub fn set_speed(&mut self, s: f64) {
        self.sim.speed = s;
        if s < 0.0 && self.sim.t > self.sim.start() {
            self.sim.playing = true;
        }
    }

    /// The time slider moved to `t`: pauses there.
    pub fn scrub(&mut self, t: f64) {
        if t != self.sim.t {
            self.sim.playing = false;
            self.sim.seek(t);
        }
    }

    /// The time slider's range: from the start to as far as the chain is
    /// computed (a little past the time shown while it grows).
    pub fn time_range(&self) -> (f64, f64) {
        let start = self.sim.start();
        let computed = self.sim.computed_to();
        let last = self.sim.model.events().last().map_or(start, |e| e.t);
        let hi = if computed.is_finite() {
            computed
        } else {
            last.max(self.sim.t) + 0.5
        }
        .max(start + 1e-9);
        (start, hi)
    }

    /// Back to the Select tool, dropping the gesture.
    pub fn escape(&mut self) {
        self.tool = Tool::Select;
        self.gesture = None;
    }

    /// New lines become edges instead of walls, or back.
    pub fn toggle_sensor(&mut self) {
        self.sensor = !self.sensor;
        self.say(
            if self.sensor {
                t!("sandbox-lines-are-edges")
            } else {
                t!("sandbox-lines-are-walls")
            },
            false,
        );
    }

    /// Opens or closes the side panel over the world, dropping the gesture.
    pub fn toggle_panel(&mut self) {
        self.panel_open = !self.panel_open;
        self.tools_open = false;
        self.gesture = None;
    }

    /// Opens or closes the tight layout's menu of tools and speeds over
    /// the world (closing the side panel), dropping the gesture.
    pub fn toggle_tools(&mut self) {
        self.tools_open = !self.tools_open;
        self.panel_open = false;
        self.gesture = None;
    }

    /// Waits for the file the browser was asked to pick.
    pub fn await_file(&mut self) {
        self.waiting_file = true;
        self.say(t!("sandbox-choose-file"), false);
    }

    /// The gravity slider shows `shown` and was moved to `g` while the
    /// pointer is `down`: the new value waits for the release.
    pub fn drag_gravity(&mut self, shown: f64, g: f64, down: bool, scene: &Scene) {
        if g != shown {
            self.g_edit = Some((g * 100.0).round() / 100.0);
        }
        if let Some(g) = self.g_edit {
            if !down {
                self.g_edit = None;
                if g != scene.g {
                    self.edit(Action::SetGravity { g });
                }
            }
        }
    }

    /// A press of `button` at screen point `p` over the world showing
    /// `scene`: starts a gesture with the tool in hand (anything but a pan
    /// pauses) and may change the selection.
    pub fn press(&mut self, button: Button, p: Vec2, scene: &Scene) {
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

    /// The pointer is at screen point `p`, its button still `down` or
    /// released: pans or drags the gesture, and on release applies what
    /// it makes.
    pub fn pointer(&mut self, p: Vec2, down: bool) {
        let Some((g, button)) = self.gesture else {
            return;
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

/// The preset named by a `preset=` parameter in an address, if any.
fn preset_in(address: &str) -> Option<Kind> {
    let (_, rest) = address.split_once("preset=")?;
    let name = rest.split(['&', '#', '/']).next()?;
    Kind::parse(name)
}

/// What to tell the user when a preset opens.
fn hint(kind: Kind) -> String {
    match kind {
        Kind::Galperin(_) => t!("sandbox-hint-galperin"),
        Kind::Brownian => t!("sandbox-hint-brownian"),
        Kind::Break => t!("sandbox-hint-break"),
        Kind::Empty | Kind::Imported => t!("sandbox-hint-empty"),
    }
}

#[cfg(test)]
mod tests {
    use super::super::format::{num, speed_label};
    use super::*;
    use macroquad::prelude::Rect;

    /// An empty table (four walls, no discs) fitted to a desktop's world.
    fn empty_table() -> State {
        let mut s = State::from_address("http://x/?preset=empty#/sandbox");
        let scene = s.sim.scene();
        s.refit_in(&scene, Rect::new(0.0, 56.0, 750.0, 600.0), 0.0);
        s
    }

    /// A click (press and release in place) at screen point `p`.
    fn click(s: &mut State, button: Button, p: Vec2) {
        let scene = s.sim.scene();
        s.press(button, p, &scene);
        s.pointer(p, false);
    }

    /// A drag from screen point `a` to `b`.
    fn drag(s: &mut State, button: Button, a: Vec2, b: Vec2) {
        let scene = s.sim.scene();
        s.press(button, a, &scene);
        s.pointer((a + b) / 2.0, true);
        s.pointer(b, false);
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

    #[test]
    fn it_opens_on_the_break_paused_or_the_preset_asked_for_playing() {
        let s = State::from_address("http://x/#/sandbox");
        assert_eq!(s.kind, Kind::Break);
        assert!(s.board.is_some() && !s.sim.playing && s.refit);
        assert_eq!(s.message.as_ref().unwrap().0, hint(Kind::Break));
        let s = State::from_address("http://x/?preset=galperin4&play=1#/sandbox");
        assert_eq!((s.kind, s.galperin_n), (Kind::Galperin(4), 4));
        assert!(s.sim.playing);
    }

    #[test]
    fn a_click_with_the_disc_tool_places_a_disc_selects_it_and_pauses() {
        let mut s = empty_table();
        s.sim.playing = true;
        s.tool = Tool::Disc;
        let at = s.view.to_screen(DVec2::new(0.5, 0.5));
        click(&mut s, Button::Primary, at);
        let scene = s.sim.scene();
        assert_eq!(scene.bodies.len(), 1);
        let b = scene.bodies[0];
        assert_eq!(s.selected, Some(b.id));
        assert!((b.pos - DVec2::new(0.5, 0.5)).length() < 0.01);
        assert_eq!(b.radius, s.template.radius);
        assert!(!s.sim.playing && s.gesture.is_none());
    }

    #[test]
    fn dragging_a_body_with_select_moves_it_and_a_right_drag_aims_it() {
        let mut s = empty_table();
        s.tool = Tool::Disc;
        let at = s.view.to_screen(DVec2::new(0.3, 0.3));
        click(&mut s, Button::Primary, at);
        let id = s.selected.unwrap();
        s.tool = Tool::Select;
        let from = s.view.to_screen(DVec2::new(0.3, 0.3));
        let to = s.view.to_screen(DVec2::new(0.6, 0.4));
        drag(&mut s, Button::Primary, from, to);
        let b = s.selected_body(&s.sim.scene()).unwrap();
        assert_eq!(b.id, id);
        assert!((b.pos - DVec2::new(0.6, 0.4)).length() < 0.01, "{}", b.pos);
        let aim = s.view.to_screen(DVec2::new(0.7, 0.4));
        drag(&mut s, Button::Secondary, to, aim);
        let b = s.selected_body(&s.sim.scene()).unwrap();
        assert!((b.vel - tools::velocity_from_drag(DVec2::new(0.1, 0.0))).length() < 0.05);
    }

    #[test]
    fn dragging_empty_space_pans_the_view_without_pausing_and_clears_the_selection() {
        let mut s = empty_table();
        s.selected = Some(BodyId(7));
        s.sim.playing = true;
        let centre = s.view.centre;
        let a = s.view.to_screen(DVec2::new(0.9, 0.9));
        drag(&mut s, Button::Primary, a, a + vec2(100.0, 0.0));
        assert!(s.sim.playing);
        assert_eq!(s.selected, None);
        assert!((s.view.centre.x - (centre.x - 100.0 / s.view.scale)).abs() < 1e-9);
        assert_eq!(s.sim.scene().bodies.len(), 0);
    }

    #[test]
    fn deleting_the_selected_body_clears_the_selection_and_a_refused_edit_says_why() {
        let mut s = empty_table();
        s.tool = Tool::Disc;
        let at = s.view.to_screen(DVec2::new(0.5, 0.5));
        click(&mut s, Button::Primary, at);
        let placed = s.sim.scene();
        // Another disc on top of the first is refused; nothing changes.
        let at = s.view.to_screen(DVec2::new(0.7, 0.7));
        click(&mut s, Button::Primary, at);
        let two = s.sim.scene();
        let first = placed.bodies[0];
        s.edit(Action::AddBody {
            body: BodySpec {
                id: BodyId(99),
                ..first
            },
        });
        let (text, error, _) = s.message.clone().unwrap();
        assert!(error && text.starts_with("refused:"), "{text}");
        assert_eq!(s.sim.scene(), two);
        s.delete_selected(&two);
        assert_eq!(s.selected, None);
        assert_eq!(s.sim.scene().bodies, placed.bodies);
    }

    #[test]
    fn play_rewind_and_the_speeds_move_the_time_shown() {
        let mut s = State::from_address("http://x/?preset=galperin3#/sandbox");
        s.toggle_play();
        assert!(s.sim.playing);
        s.sim.advance(0.5, 10_000);
        assert!(s.sim.t > 0.0);
        s.toggle_play();
        assert!(!s.sim.playing);
        // A backward speed away from the start plays at once.
        s.set_speed(-1.0);
        assert!(s.sim.playing && s.sim.speed == -1.0);
        s.rewind();
        assert!(!s.sim.playing);
        assert_eq!(s.sim.t, s.sim.start());
        s.set_speed(-2.0);
        assert!(!s.sim.playing, "nothing to play back at the start");
        let (start, hi) = s.time_range();
        assert!(start < hi);
        s.sim.playing = true;
        s.scrub(s.sim.t);
        assert!(s.sim.playing, "the slider left alone changes nothing");
        s.scrub((start + hi) / 2.0);
        assert!(!s.sim.playing);
        assert_eq!(s.sim.t, (start + hi) / 2.0);
    }

    #[test]
    fn presets_and_imports_replace_the_scene_and_a_bad_import_keeps_it() {
        let mut s = empty_table();
        s.load_preset(Kind::Brownian);
        assert_eq!(s.kind, Kind::Brownian);
        assert_eq!(s.selected, Some(BodyId(presets::BROWNIAN_ID)));
        assert!(s.refit && s.board.is_none());
        s.galperin(5);
        assert_eq!((s.kind, s.galperin_n), (Kind::Galperin(5), 5));
        let exported = s.sim.export();
        let before = s.sim.scene();
        s.import("{ not json");
        assert!(s.message.as_ref().unwrap().1);
        assert_eq!(s.sim.scene(), before);
        s.load_preset(Kind::Break);
        s.refit = false;
        s.import(&exported);
        assert_eq!((s.kind, s.board, s.selected), (Kind::Imported, None, None));
        assert!(s.refit && !s.message.as_ref().unwrap().1);
        assert_eq!(s.sim.scene(), before);
    }

    #[test]
    fn gravity_changes_only_when_its_slider_is_let_go() {
        let mut s = empty_table();
        let scene = s.sim.scene();
        s.drag_gravity(scene.g, 3.456, true, &scene);
        assert_eq!(s.g_edit, Some(3.46));
        assert_eq!(s.sim.scene().g, scene.g);
        s.drag_gravity(3.46, 3.46, false, &scene);
        assert_eq!(s.g_edit, None);
        assert_eq!(s.sim.scene().g, 3.46);
    }

    #[test]
    fn the_event_budget_doubles_when_quick_and_halves_when_slow_within_bounds() {
        let mut s = empty_table();
        s.adapt_budget(1.0);
        assert_eq!(s.budget, 50_000, "only while the chain is behind");
        s.sim.behind = true;
        s.adapt_budget(1.0);
        assert_eq!(s.budget, 100_000);
        s.adapt_budget(15.0);
        assert_eq!(s.budget, 100_000);
        for _ in 0..20 {
            s.adapt_budget(50.0);
        }
        assert_eq!(s.budget, MIN_BUDGET);
        for _ in 0..20 {
            s.adapt_budget(0.0);
        }
        assert_eq!(s.budget, MAX_BUDGET);
    }

    #[test]
    fn escape_the_panel_and_the_wall_switch_drop_the_gesture_or_say_what_changed() {
        let mut s = empty_table();
        s.tool = Tool::Delete;
        let scene = s.sim.scene();
        s.press(Button::Middle, vec2(300.0, 300.0), &scene);
        assert!(s.gesture.is_some());
        s.toggle_panel();
        assert!(s.panel_open && s.gesture.is_none());
        s.press(Button::Middle, vec2(300.0, 300.0), &scene);
        s.toggle_tools();
        assert!(s.tools_open && !s.panel_open && s.gesture.is_none());
        s.toggle_panel();
        assert!(s.panel_open && !s.tools_open);
        s.press(Button::Middle, vec2(300.0, 300.0), &scene);
        s.escape();
        assert_eq!((s.tool, s.gesture), (Tool::Select, None));
        s.toggle_sensor();
        assert!(s.sensor && s.message.as_ref().unwrap().0.contains("edges"));
        s.await_file();
        assert!(s.waiting_file);
    }
}
