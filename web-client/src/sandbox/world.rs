//! Drawing the sandbox's world in its area: the grid or the board, the
//! lines and points, the discs (checkers on the board) with the selected
//! one's trail and its halo, the rings where collisions just happened, the
//! velocity arrows while paused and the preview of the gesture in
//! progress. It reads the [`State`] and changes nothing.

use super::format::num;
use super::presets;
use super::state::State;
use super::tools::{self, Gesture};
use crate::draw;
use crate::ui::{self, colors};
use crate::viewport::Viewport;
use ::glam::DVec2;
use engine::{BodyId, Scene};
use macroquad::prelude::*;

/// Draws the scene `scene` (the state's, at the time shown) in `area`.
pub fn draw(s: &State, area: Rect, scene: &Scene) {
    let v = &s.view;
    match s.board {
        Some(size) => draw::board(v, size),
        None => grid(v, area),
    }
    for l in &scene.lines {
        if s.board.is_some_and(|size| on_board_edge(l, size)) {
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
    if let Some(id) = s.selected {
        trail(s, id);
    }
    for b in &scene.bodies {
        let c = v.to_screen(b.pos);
        let r = v.px(b.radius).max(1.5);
        let selected = s.selected == Some(b.id);
        match (s.board, presets::checker_side(b.id)) {
            (Some(_), Some(side)) => {
                draw::checker(c, r, side, 1.0);
                if selected {
                    draw::halo(c, r, colors::ACCENT);
                }
            }
            _ => draw::disc(c, r, b.id.0, selected),
        }
    }
    hit_rings(s);
    if !s.sim.playing {
        let few = scene.bodies.len() <= 40;
        for b in &scene.bodies {
            if b.vel != DVec2::ZERO && (few || s.selected == Some(b.id)) {
                let from = v.to_screen(b.pos);
                let to = v.to_screen(b.pos + tools::arrow_of(b.vel));
                draw::arrow(from, to, Color::new(0.55, 0.85, 1.0, 0.8), 2.0);
            }
        }
    }
    gesture_preview(s, scene);
}

/// The path of body `id` over the last 30 s of model time.
fn trail(s: &State, id: BodyId) {
    let t = s.sim.t;
    let from = (t - 30.0).max(s.sim.start());
    if t <= from || t.is_nan() {
        return;
    }
    const N: usize = 300;
    let mut last: Option<Vec2> = None;
    for k in 0..=N {
        let tk = from + (t - from) * k as f64 / N as f64;
        let here = s.sim.model.body_at(id, tk).map(|b| s.view.to_screen(b.pos));
        if let (Some(a), Some(b)) = (last, here) {
            let alpha = 0.15 + 0.6 * k as f32 / N as f32;
            draw_line(a.x, a.y, b.x, b.y, 2.0, Color::new(0.93, 0.66, 0.25, alpha));
        }
        last = here;
    }
}

/// Expanding rings where collisions just happened.
fn hit_rings(s: &State) {
    let window = 0.3 * s.sim.speed.abs().max(1e-3);
    let t = s.sim.t;
    for e in s.sim.recent_events(t - window, t, 40) {
        if !e.kind.is_collision() {
            continue;
        }
        let mut at = DVec2::ZERO;
        let mut n = 0.0;
        let mut r: f64 = 0.0;
        for id in e.kind.bodies() {
            if let Some(b) = s.sim.model.body_at(id, e.t) {
                at += b.pos;
                n += 1.0;
                r = r.max(b.radius);
            }
        }
        if n > 0.0 {
            let c = s.view.to_screen(at / n);
            let progress = ((t - e.t) / window) as f32;
            draw::hit_ring(c, s.view.px(r).max(8.0), progress);
        }
    }
}

/// A preview of what the gesture in progress would make.
fn gesture_preview(s: &State, scene: &Scene) {
    let v = &s.view;
    let Some((g, _)) = s.gesture else {
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
                    &crate::i18n::t!("sandbox-speed", v = format!("{speed:.2}")),
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
                    sensor: s.sensor,
                };
                draw::line(v, &line, colors::ACCENT, 2.0);
            }
        }
        Gesture::Place { disc: true, at } => {
            let c = v.to_screen(at);
            draw_circle_lines(c.x, c.y, v.px(s.template.radius), 1.5, colors::ACCENT);
        }
        Gesture::Place { disc: false, at } => draw::point(v.to_screen(at), colors::ACCENT),
        Gesture::Pan | Gesture::Delete(_) => {}
    }
}

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
        &crate::i18n::t!("sandbox-grid", step = num(step)),
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

/// Whether `l` is one of the edges of the board `[0, size]^2` (drawn by
/// the board's frame already).
fn on_board_edge(l: &engine::Line, size: f64) -> bool {
    let edge = |x: f64| x.abs() < 1e-9 || (x - size).abs() < 1e-9;
    (l.a.x == l.b.x && edge(l.a.x)) || (l.a.y == l.b.y && edge(l.a.y))
}

#[cfg(test)]
mod tests {
    use super::*;

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
    fn only_lines_along_the_boards_edges_are_left_to_its_frame() {
        let line = |a: DVec2, b: DVec2| engine::Line {
            a,
            b,
            kind: engine::LineKind::Segment,
            sensor: true,
        };
        let size = 2.0;
        assert!(on_board_edge(
            &line(DVec2::ZERO, DVec2::new(0.0, 2.0)),
            size
        ));
        assert!(on_board_edge(
            &line(DVec2::new(0.0, 2.0), DVec2::new(2.0, 2.0)),
            size
        ));
        assert!(!on_board_edge(
            &line(DVec2::new(1.0, 0.0), DVec2::new(1.0, 2.0)),
            size
        ));
        assert!(!on_board_edge(
            &line(DVec2::ZERO, DVec2::new(2.0, 2.0)),
            size
        ));
    }
}
