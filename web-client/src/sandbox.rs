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
//! This module owns the screen: it routes the keys, the pointer and the
//! browser's file to the [`state`], runs the frame's computing, and draws
//! in order the [`world`], the [`overlays`] and the [`controls`], all
//! placed by [`layout`]. Every control is finger-sized; a window narrower
//! than a desktop's (a phone) gets the compact layout: the tools wrap in
//! rows above the world, the playback bar takes two rows below it, and the
//! side panel opens over the world with the "Panel" button. The logic
//! lives in submodules: [`sim`] (the model and its playback), [`tools`]
//! (the editing state machine), [`presets`] (the ready-made scenes),
//! [`state`] (everything the screen keeps and every change to it).

pub mod controls;
pub mod format;
pub mod layout;
pub mod overlays;
pub mod presets;
pub mod sim;
pub mod state;
pub mod tools;
pub mod world;

use crate::platform;
use crate::route::Route;
use crate::screen::Screen;
use crate::ui::{colors, Ui};
use engine::Scene;
use layout::STATS_W;
use macroquad::prelude::*;
use presets::Kind;
use state::State;
use tools::Button;

/// The sandbox screen.
pub struct Sandbox {
    s: State,
}

impl Sandbox {
    /// Opens with the preset named by `?preset=` in the address, else the
    /// Chapaev break, paused at its start.
    pub fn new() -> Sandbox {
        Sandbox {
            s: State::from_address(&platform::location()),
        }
    }

    // ---- input --------------------------------------------------------

    fn keys(&mut self, scene: &Scene) {
        if is_key_pressed(KeyCode::Space) {
            self.s.toggle_play();
        }
        if is_key_pressed(KeyCode::Home) {
            self.s.rewind();
        }
        if is_key_pressed(KeyCode::Escape) {
            self.s.escape();
        }
        if is_key_pressed(KeyCode::Delete) || is_key_pressed(KeyCode::Backspace) {
            self.s.delete_selected(scene);
        }
    }

    fn world_input(&mut self, ui: &Ui, area: Rect, scene: &Scene) {
        let s = &mut self.s;
        let p = ui.input.pointer;
        let inside = area.contains(p);
        if inside && ui.input.wheel != 0.0 && s.gesture.is_none() {
            s.view
                .zoom_about(p, 1.15f64.powf(ui.input.wheel.signum() as f64));
        }
        if s.gesture.is_none() && inside && !ui.captured() {
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
                s.press(button, p, scene);
            }
        }
        if let Some((_, button)) = s.gesture {
            let down = match button {
                Button::Primary => ui.input.down,
                Button::Secondary => is_mouse_button_down(MouseButton::Right),
                Button::Middle => is_mouse_button_down(MouseButton::Middle),
            };
            s.pointer(p, down);
        }
    }
}

impl Default for Sandbox {
    fn default() -> Self {
        Sandbox::new()
    }
}

impl Screen for Sandbox {
    fn frame(&mut self, ui: &mut Ui, dt: f64) -> Option<Route> {
        self.s.tick(dt);
        let (w, h) = crate::scale::size().into();
        let areas = layout::areas(w, h);
        let layout::Areas {
            compact,
            sideways,
            tight,
            top,
            bottom,
            world,
            side,
            bar,
            ..
        } = areas;
        if !compact {
            self.s.panel_open = false;
        }
        if !tight {
            self.s.tools_open = false;
        }
        // Something open over the world takes its input.
        let covering = self.s.panel_open || self.s.tools_open;

        if self.s.waiting_file {
            if let Some(text) = platform::picked_file() {
                self.s.waiting_file = false;
                self.s.import(&text);
            }
        }

        // Play: extend the chain within the frame's event budget.
        let started = get_time();
        self.s.sim.advance(dt, self.s.budget);
        self.s.adapt_budget((get_time() - started) * 1000.0);

        let scene = self.s.sim.scene();
        // The compact layout has no statistics panel to leave room for.
        let left = if compact { 0.0 } else { STATS_W };
        self.s.refit_in(&scene, world, left);
        self.keys(&scene);
        if !covering {
            self.world_input(ui, world, &scene);
        }
        let scene = self.s.sim.scene();
        self.s.tally = self.s.sim.tally();

        // Sideways, the open panel covers the world's right part: the view
        // is drawn moved left, its centre in the middle of what is seen.
        let covered = if sideways && !tight && self.s.panel_open {
            (world.x + world.w - side.x).max(0.0)
        } else {
            0.0
        };
        self.s.view.anchor.x -= covered / 2.0;
        world::draw(&self.s, world, &scene);
        self.s.view.anchor.x += covered / 2.0;
        if !compact {
            overlays::stats(&self.s, world, &scene);
        }
        if let Kind::Galperin(n) = self.s.kind {
            overlays::galperin(&self.s, world, n);
        }
        overlays::message(&self.s, world);
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
        // Sideways, the tools' columns left of the world.
        draw_rectangle(0.0, 0.0, world.x, h, colors::BACKGROUND);
        let route = controls::toolbar(&mut self.s, ui, &areas);
        if !compact || self.s.panel_open {
            controls::side_panel(&mut self.s, ui, side, &scene);
        }
        // Sideways, and in the tight layout, the open panel (or menu)
        // takes the bar's place.
        if !((sideways || tight) && covering) {
            controls::playback_bar(&mut self.s, ui, bar, layout::Bar::of(&areas));
        }
        route
    }

    fn name(&self) -> &'static str {
        "sandbox"
    }

    fn report(&self) -> serde_json::Map<String, serde_json::Value> {
        let scene = self.s.sim.scene();
        let mut m = serde_json::Map::new();
        let t = &self.s.tally;
        m.insert("bodies".into(), scene.bodies.len().into());
        m.insert("lines".into(), scene.lines.len().into());
        m.insert("points".into(), scene.points.len().into());
        m.insert("t".into(), self.s.sim.t.into());
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
        m.insert("computed_to".into(), self.s.sim.computed_to().into());
        m.insert("playing".into(), self.s.sim.playing.into());
        m.insert("behind".into(), self.s.sim.behind.into());
        m.insert("speed".into(), self.s.sim.speed.into());
        m.insert("g".into(), scene.g.into());
        m.insert("tool".into(), self.s.tool.name().into());
        m.insert("preset".into(), self.s.kind.name().into());
        m.insert("selected".into(), self.s.selected.map(|b| b.0).into());
        m.insert("panel_open".into(), self.s.panel_open.into());
        m.insert("tools_open".into(), self.s.tools_open.into());
        // The world's rectangle, and the open panel's, in CSS pixels.
        let (w, h) = crate::scale::size().into();
        let a = layout::areas(w, h);
        let css = |r: Rect| {
            let r = crate::scale::css(r);
            serde_json::json!([r.x, r.y, r.w, r.h])
        };
        m.insert("world".into(), css(a.world));
        m.insert("tight".into(), a.tight.into());
        if a.compact && (self.s.panel_open || self.s.tools_open) {
            m.insert("side".into(), css(a.side));
        }
        if let Some((text, error, _)) = &self.s.message {
            m.insert("message".into(), text.clone().into());
            m.insert("error".into(), (*error).into());
        }
        m
    }

    fn animating(&self) -> bool {
        self.s.sim.playing || self.s.gesture.is_some()
    }
}
