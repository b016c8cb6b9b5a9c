//! The sandbox's controls, drawn where [`layout`] puts them and applied to
//! the [`State`]: the toolbar (the lobby, the tools, walls or edges, the
//! side panel's button on a phone, export and import, and the language
//! switch where the row has room for it), the side panel
//! (the presets, gravity, what new discs are made of, the selected body)
//! and the playback bar (rewind, play, the speeds and the time slider).
//! Every control is finger-sized.

use super::format::{num, speed_label};
use super::layout::{self, NewDiscs, Row};
use super::presets::{Kind, MAX_GALPERIN};
use super::sim::SPEEDS;
use super::state::State;
use super::tools::{Tool, TOOLS};
use crate::i18n::t;
use crate::platform;
use crate::route::Route;
use crate::ui::{self, colors, Ui};
use ::glam::DVec2;
use engine::{Action, LineKind, Scene};
use macroquad::prelude::Rect;

/// The toolbar of the layout `a`; the route to take, if one was asked.
pub fn toolbar(s: &mut State, ui: &mut Ui, a: &layout::Areas) -> Option<Route> {
    // (name, label, selected), in the order of [`layout::toolbar`].
    let mut items: Vec<(String, String, bool)> = vec![("lobby".into(), t!("lobby"), false)];
    for tool in TOOLS {
        let label = match tool {
            Tool::Select => t!("sandbox-tool-select"),
            Tool::Velocity => t!("sandbox-tool-velocity"),
            Tool::Disc => t!("sandbox-tool-disc"),
            Tool::Point => t!("sandbox-tool-point"),
            Tool::Line(LineKind::Line) => t!("sandbox-tool-line"),
            Tool::Line(LineKind::Ray) => t!("sandbox-tool-ray"),
            Tool::Line(LineKind::Segment) => t!("sandbox-tool-segment"),
            Tool::Delete => t!("sandbox-tool-delete"),
        };
        items.push((format!("tool-{}", tool.name()), label, s.tool == tool));
    }
    let sensor = if s.sensor {
        t!("sandbox-edge")
    } else {
        t!("sandbox-wall")
    };
    items.push(("sensor".into(), sensor, s.sensor));
    if a.compact {
        items.push(("panel".into(), t!("sandbox-panel"), s.panel_open));
    }
    items.push(("export".into(), t!("sandbox-export"), false));
    items.push(("import".into(), t!("sandbox-import"), false));
    if let Some(r) = layout::language(a) {
        crate::i18n::switch(ui, r, true);
    }
    if let Some(r) = layout::tools_button(a) {
        if ui.button_styled("menu", &t!("sandbox-menu"), r, true, s.tools_open) {
            s.toggle_tools();
        }
    }
    if s.tools_open {
        // The menu over the world: the tools (set in rows of one width,
        // one label size) and the speeds.
        ui::panel(a.side);
        let (_, speeds) = layout::menu(a);
        speed_buttons(s, ui, &speeds);
    }
    let mut go = None;
    for ((name, label, selected), r) in items.iter().zip(layout::toolbar(a)) {
        let in_sight = !a.tight || s.tools_open || name == "lobby" || name == "panel";
        if !in_sight || !ui.button_styled(name, label, r, true, *selected) {
            continue;
        }
        if a.tight && name != "panel" && name != "lobby" && name != "sensor" {
            // A choice made in the menu closes it.
            s.tools_open = false;
        }
        match name.as_str() {
            "lobby" => go = Some(Route::Lobby),
            "sensor" => s.toggle_sensor(),
            "panel" => s.toggle_panel(),
            "import" => {
                platform::request_file();
                s.await_file();
            }
            "export" => match platform::save_file("scene.json", &s.sim.export()) {
                Ok(m) => s.say(t!("sandbox-exported", done = m, t = num(s.sim.t)), false),
                Err(e) => s.say(e, true),
            },
            tool => {
                if let Some(t) = TOOLS.iter().find(|t| format!("tool-{}", t.name()) == tool) {
                    s.tool = *t;
                }
            }
        }
    }
    go
}

/// The material of new discs.
fn new_disc_controls(s: &mut State, ui: &mut Ui, x: f32, d: NewDiscs) {
    ui::text(&t!("sandbox-new-discs"), x, d.heading, 15.0, colors::MUTED);
    let t = s.template;
    let radius = t!("sandbox-radius", value = num(t.radius));
    if let Some(f) = stepper(ui, "new-radius", &radius, d.radius) {
        s.template.radius = (t.radius * f).clamp(1e-4, 1e3);
    }
    if let Some(f) = stepper(
        ui,
        "new-mass",
        &t!("sandbox-mass", value = num(t.mass)),
        d.mass,
    ) {
        s.template.mass = (t.mass * f * f).clamp(1e-6, 1e12);
    }
    s.template.mu = unit_slider(ui, "new-mu", "mu", t.mu, d.mu);
    s.template.restitution = unit_slider(ui, "new-e", "e", t.restitution, d.e);
}

/// The side panel in `r` over the scene shown.
pub fn side_panel(s: &mut State, ui: &mut Ui, r: Rect, scene: &Scene) {
    ui::panel(r);
    // Every text of the panel stays in it.
    let _inside = ui::bounds(r);
    // The presets and the world's controls, which stand where they do
    // whatever is selected (a preset may change the selection).
    let top = layout::side_panel(r, false);
    let x = top.x;
    let heading = |t: &str, y: f32| ui::text(t, x, y, 17.0, colors::ACCENT);

    heading(&t!("sandbox-presets"), top.presets);
    let n = s.galperin_n;
    if ui.button_styled(
        "preset-galperin",
        &t!("sandbox-galperin", n = n),
        top.galperin,
        true,
        s.kind == Kind::Galperin(n),
    ) {
        s.load_preset(Kind::Galperin(n));
    }
    if ui.button_styled("galperin-less", "-", top.galperin_less, n > 1, false) {
        s.galperin(n - 1);
    }
    if ui.button_styled(
        "galperin-more",
        "+",
        top.galperin_more,
        n < MAX_GALPERIN,
        false,
    ) {
        s.galperin(n + 1);
    }
    let presets = [
        (
            "preset-brownian",
            t!("sandbox-brownian"),
            top.brownian,
            Kind::Brownian,
        ),
        (
            "preset-break",
            t!("sandbox-break"),
            top.chapaev,
            Kind::Break,
        ),
        ("preset-empty", t!("sandbox-empty"), top.empty, Kind::Empty),
    ];
    for (name, label, rect, kind) in presets {
        if ui.button_styled(name, &label, rect, true, s.kind == kind) {
            s.load_preset(kind);
        }
    }
    if ui.button("fit", &t!("sandbox-fit"), top.fit) {
        s.refit = true;
    }

    let l = layout::side_panel(r, s.selected_body(scene).is_some());
    if l.world_shown {
        heading(&t!("sandbox-world"), top.world);
        let g_now = s.g_edit.unwrap_or(scene.g);
        let row = top.gravity;
        ui::text(
            &t!("sandbox-gravity", g = format!("{g_now:.2}")),
            x,
            row.y + 4.0,
            16.0,
            colors::TEXT,
        );
        let g = ui.slider("gravity", g_now, 0.0, 20.0, layout::slider_of(row));
        s.drag_gravity(g_now, g, ui.input.down, scene);
    }

    // The new discs and the selection (a second column's, if two).
    let x = l.x2;
    let heading = |t: &str, y: f32| ui::text(t, x, y, 17.0, colors::ACCENT);
    if let Some(d) = l.new_discs {
        new_disc_controls(s, ui, x, d);
    }

    match (s.selected, s.selected_body(scene).zip(l.body)) {
        (Some(_), Some((b, c))) => {
            heading(&t!("sandbox-body", id = b.id.0), l.selection);
            ui::text(
                &t!(
                    "sandbox-body-at",
                    x = num(b.pos.x),
                    y = num(b.pos.y),
                    v = num(b.vel.length())
                ),
                x,
                c.info,
                15.0,
                colors::TEXT,
            );
            let radius = t!("sandbox-radius", value = num(b.radius));
            if let Some(f) = stepper(ui, "body-radius", &radius, c.radius) {
                s.update_selected(scene, |b| b.radius *= f);
            }
            if let Some(f) = stepper(
                ui,
                "body-mass",
                &t!("sandbox-mass", value = num(b.mass)),
                c.mass,
            ) {
                s.update_selected(scene, |b| b.mass *= f * f);
            }
            if let Some(f) = stepper(ui, "body-mu", &format!("mu {:.2}", b.mu), c.mu) {
                let step = if f > 1.0 { 0.05 } else { -0.05 };
                s.update_selected(scene, |b| {
                    b.mu = ((b.mu + step) * 100.0).round().max(0.0) / 100.0
                });
            }
            if let Some(f) = stepper(ui, "body-e", &format!("e {:.2}", b.restitution), c.e) {
                let step = if f > 1.0 { 0.1 } else { -0.1 };
                s.update_selected(scene, |b| {
                    b.restitution = ((b.restitution + step) * 10.0).round().clamp(0.0, 10.0) / 10.0
                });
            }
            if ui.button("body-stop", &t!("sandbox-stop-it"), c.stop) {
                s.edit(Action::SetVelocity {
                    id: b.id,
                    vel: DVec2::ZERO,
                });
            }
            if ui.button("body-delete", &t!("sandbox-tool-delete"), c.delete) {
                s.edit(Action::RemoveBody { id: b.id });
            }
        }
        (Some(id), None) => {
            heading(&t!("sandbox-body", id = id.0), l.selection);
            ui::text(
                &t!("sandbox-body-absent"),
                x,
                l.selection + 22.0,
                15.0,
                colors::MUTED,
            );
        }
        (None, _) => {
            heading(&t!("sandbox-selection"), l.selection);
            let lines: Vec<String> = [
                t!("sandbox-help-1"),
                t!("sandbox-help-2"),
                t!("sandbox-help-3"),
                t!("sandbox-help-4"),
            ]
            .iter()
            .flat_map(|p| crate::help::wrap(p, 15.0, r.x + r.w - x - 8.0))
            .collect();
            for (k, line) in lines.iter().enumerate() {
                let ly = l.selection + 22.0 + 18.0 * k as f32;
                // As many as the panel holds.
                if ly + 18.0 > r.y + r.h {
                    break;
                }
                ui::text(line, x, ly, 15.0, colors::MUTED);
            }
        }
    }
}

/// The speed buttons at `rects` (one per [`SPEEDS`]), their labels at one
/// size ("0.01x" as large as "1x" can be).
fn speed_buttons(s: &mut State, ui: &mut Ui, rects: &[Rect]) {
    let labels: Vec<String> = SPEEDS.iter().map(|&v| speed_label(v)).collect();
    if let Some(&first) = rects.first() {
        ui.even_labels(&labels, first, |ui| {
            for ((&speed, rect), label) in SPEEDS.iter().zip(rects).zip(&labels) {
                let name = format!("speed-{speed}");
                let selected = s.sim.speed == speed;
                if ui.button_styled(&name, label, *rect, true, selected) {
                    s.set_speed(speed);
                }
            }
        });
    }
}

/// The playback bar in `r`: rewind, play, the speeds (unless they are in
/// the tight layout's menu) and the time slider.
pub fn playback_bar(s: &mut State, ui: &mut Ui, r: Rect, bar: layout::Bar) {
    ui::panel(r);
    let l = layout::playback(r, bar);
    if ui.button("rewind", "|<", l.rewind) {
        s.rewind();
    }
    let label = if s.sim.playing {
        t!("replay-pause")
    } else {
        t!("replay-play")
    };
    if ui.button_styled("play", &label, l.play, true, s.sim.playing) {
        s.toggle_play();
    }
    speed_buttons(s, ui, &l.speeds);
    let (start, hi) = s.time_range();
    let t = ui.slider("time", s.sim.t, start, hi, l.slider);
    s.scrub(t);
    let (tx, ty, tw) = l.time;
    ui::text_in(
        &t!("sandbox-time", t = num(s.sim.t)),
        tx,
        ty,
        17.0,
        tw,
        colors::TEXT,
    );
}

/// A labelled slider over `[0, 1]` in `row`: the value shown and returned
/// to two decimals.
fn unit_slider(ui: &mut Ui, id: &str, label: &str, value: f64, row: Row) -> f64 {
    ui::text(
        &format!("{label} {value:.2}"),
        row.x,
        row.y + 4.0,
        16.0,
        colors::TEXT,
    );
    let v = ui.slider(id, value, 0.0, 1.0, layout::slider_of(row));
    (v * 100.0).round() / 100.0
}

/// A `-` / `+` pair with a label in `row`; the factor 1/1.25 or 1.25 when
/// clicked.
fn stepper(ui: &mut Ui, name: &str, label: &str, row: Row) -> Option<f64> {
    let (less, more) = layout::stepper_buttons(row);
    ui::text_in(
        label,
        row.x,
        row.y + 13.0,
        16.0,
        less.x - row.x - 4.0,
        colors::TEXT,
    );
    let less = ui.button(&format!("{name}-less"), "-", less);
    let more = ui.button(&format!("{name}-more"), "+", more);
    if less {
        Some(1.0 / 1.25)
    } else if more {
        Some(1.25)
    } else {
        None
    }
}
