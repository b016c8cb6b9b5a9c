//! The panels drawn over the sandbox's world: the statistics (time, speed,
//! how far the chain is computed, the events by kind, the scene's size,
//! the frame's time), Galperin's counter of collisions against the digits
//! of pi, and the message line that fades after a few seconds. They read
//! the [`State`] and change nothing; [`layout`] places them.

use super::format::{num, speed_label};
use super::layout;
use super::state::State;
use crate::i18n::t;
use crate::ui::{self, colors};
use engine::{EndReason, Scene};
use macroquad::prelude::*;

/// How long a message stays, seconds.
const MESSAGE_SECS: f64 = 7.0;

/// The statistics panel over the world `area`.
pub fn stats(s: &State, area: Rect, scene: &Scene) {
    let tally = &s.tally;
    let r = layout::stats(area);
    ui::panel(r);
    let _inside = ui::bounds(r);
    let mut y = r.y + 8.0;
    let mut row = |label: String, value: String, color: Color| {
        ui::text(
            &ui::fit(&label, 16.0, 114.0),
            r.x + 10.0,
            y,
            16.0,
            colors::MUTED,
        );
        ui::text(&value, r.x + 128.0, y, 16.0, color);
        y += 19.0;
    };
    let end = match s.sim.end() {
        Some(e) if e.reason == EndReason::Rest => t!("stats-end-rest"),
        Some(e) if e.reason == EndReason::Free => t!("stats-end-free"),
        _ => t!("stats-seconds", t = num(s.sim.computed_to())),
    };
    let sub = |id: &str| format!("  {}", crate::i18n::text(id, &[]));
    row(
        t!("stats-time"),
        t!("stats-seconds", t = num(s.sim.t)),
        colors::TEXT,
    );
    row(t!("stats-speed"), speed_label(s.sim.speed), colors::TEXT);
    row(t!("stats-computed-to"), end, colors::TEXT);
    row(
        t!("stats-events"),
        tally.physical().to_string(),
        colors::TEXT,
    );
    row(
        sub("stats-body-body"),
        tally.body_body.to_string(),
        colors::TEXT,
    );
    row(
        sub("stats-body-line"),
        tally.body_line.to_string(),
        colors::TEXT,
    );
    row(
        sub("stats-body-point"),
        tally.body_point.to_string(),
        colors::TEXT,
    );
    row(sub("stats-stops"), tally.stops.to_string(), colors::TEXT);
    row(sub("stats-fell-off"), tally.exits.to_string(), colors::TEXT);
    row(t!("stats-edits"), tally.actions.to_string(), colors::TEXT);
    row(
        t!("stats-bodies"),
        scene.bodies.len().to_string(),
        colors::TEXT,
    );
    row(
        t!("stats-lines-points"),
        format!("{}, {}", scene.lines.len(), scene.points.len()),
        colors::TEXT,
    );
    row(
        t!("stats-frame"),
        t!("stats-ms", ms = format!("{:.1}", s.frame_ms)),
        colors::TEXT,
    );
    if s.sim.behind {
        row(
            t!("stats-computing"),
            t!("stats-ms-per-frame", ms = format!("{:.0}", s.compute_ms)),
            colors::ACCENT,
        );
    }
}

/// Galperin's counter: collisions so far against the digits of pi.
pub fn galperin(s: &State, area: Rect, n: u32) {
    let count = s.tally.body_body + s.tally.body_line;
    let target = engine::presets::pi_digits(n);
    let r = layout::galperin_counter(area);
    ui::panel(r);
    let _inside = ui::bounds(r);
    ui::text(
        &t!("galperin-collisions"),
        r.x + 12.0,
        r.y + 8.0,
        16.0,
        colors::MUTED,
    );
    let done = count == target && s.sim.end().is_some_and(|e| e.reason == EndReason::Free);
    let color = if done { colors::GOOD } else { colors::ACCENT };
    ui::text(&count.to_string(), r.x + 12.0, r.y + 26.0, 44.0, color);
    let digits = target.to_string();
    let pi = format!("{}.{}", &digits[..1], &digits[1..]);
    ui::text_in(
        &t!("galperin-pi", n = n, pi = pi),
        r.x + 12.0,
        r.y + 70.0,
        18.0,
        r.w - 20.0,
        colors::TEXT,
    );
    let ratio = t!("galperin-ratio", power = n - 1);
    let line = if done {
        format!("{ratio} {}", t!("galperin-done"))
    } else {
        ratio
    };
    ui::text_in(
        &line,
        r.x + 12.0,
        r.y + 90.0,
        15.0,
        r.w - 20.0,
        colors::MUTED,
    );
}

/// The message at the bottom of the world `area`, fading in its last
/// second.
pub fn message(s: &State, area: Rect) {
    let Some((text, error, since)) = &s.message else {
        return;
    };
    let age = s.clock - since;
    if age > MESSAGE_SECS {
        return;
    }
    let alpha = (1.0 - ((age - MESSAGE_SECS + 1.0).max(0.0))) as f32;
    // In as many lines as the world's width needs (smaller, down to 12
    // units, rather than more than three).
    let room = area.w - 36.0;
    let mut size: f32 = 17.0;
    let mut lines = crate::help::wrap(text, size, room);
    while size > 12.0 && lines.len() > 3 {
        size -= 1.0;
        lines = crate::help::wrap(text, size, room);
    }
    let widest = lines
        .iter()
        .map(|l| ui::text_width(l, size))
        .fold(0.0, f32::max);
    let r = layout::message(area, widest, lines.len(), size);
    draw_rectangle(
        r.x,
        r.y,
        r.w,
        r.h,
        Color::new(0.1, 0.07, 0.05, 0.85 * alpha),
    );
    let c = if *error { colors::DANGER } else { colors::TEXT };
    for (i, line) in lines.iter().enumerate() {
        ui::text(
            &ui::fit(line, size, room),
            r.x + 10.0,
            r.y + 6.0 + i as f32 * layout::line_step(size),
            size,
            Color::new(c.r, c.g, c.b, alpha),
        );
    }
}
