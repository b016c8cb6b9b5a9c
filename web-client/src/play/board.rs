//! The board of a live match and the slingshot on it: the board fitted
//! into its area (White's side at the bottom unless this page plays
//! Black), its frame glowing when the turn comes, the pieces at the moment
//! shown, the "your turn" cue, and the drag from one of the player's
//! pieces with its arrow and power meter that ends in a shot.

use super::layout::meter_rect;
use crate::aim::{self, Aim, Slingshot};
use crate::clip::Frame;
use crate::draw;
use crate::i18n::t;
use crate::ui::{self, colors, Ui};
use crate::viewport::Viewport;
use ::glam::DVec2;
use game::{MatchView, PieceId, Side};
use macroquad::prelude::*;

/// How long the "your turn" cue shows after the turn comes, in seconds.
pub const TURN_CUE: f64 = 1.6;

/// A drag in progress from one of the player's pieces.
pub struct Drag {
    pub piece: PieceId,
    from: DVec2,
    pointer: DVec2,
}

/// The board as this frame shows it.
pub struct Shown {
    /// The board's map (the slingshot reads the pointer with it).
    pub viewport: Viewport,
    /// Where each piece was drawn, and its radius on the screen.
    pub drawn: Vec<(PieceId, Vec2, f32)>,
}

/// Draws the board of `v` in `area` at `frame`, seen from `mine`'s side;
/// `can_aim` lights the player's pieces (and `dragging` the one pulled),
/// `since_turn` is how long ago the turn came (its cue), `now` the clock.
#[allow(clippy::too_many_arguments)]
pub fn show(
    v: &MatchView,
    frame: &Frame,
    area: Rect,
    mine: Option<Side>,
    can_aim: bool,
    dragging: Option<PieceId>,
    since_turn: f64,
    now: f64,
) -> Shown {
    let flipped = mine == Some(Side::Black);
    let vp = Viewport::fit_square(
        v.config.board_size(),
        area,
        area.w.min(area.h) * 0.06,
        flipped,
    );
    // Your turn: the board's frame glows for a moment, then stays lit.
    if can_aim {
        let a = vp.to_screen(DVec2::ZERO);
        let b = vp.to_screen(DVec2::splat(v.config.board_size()));
        let (x0, y0) = (a.x.min(b.x), a.y.min(b.y));
        let side = (a.x - b.x).abs();
        let pad = side * 0.045 + 5.0;
        let fresh = (1.0 - since_turn as f32 / 1.5).max(0.0);
        let pulse = 0.35 + 0.65 * fresh * (0.5 + 0.5 * (now as f32 * 9.0).sin());
        draw_rectangle_lines(
            x0 - pad,
            y0 - pad,
            side + 2.0 * pad,
            side + 2.0 * pad,
            4.0,
            Color::new(0.45, 0.85, 0.40, pulse),
        );
    }
    draw::board(&vp, v.config.board_size());
    draw::frame(&vp, v.config.piece_radius, frame, |p| {
        if dragging == Some(p) {
            Some(colors::ACCENT)
        } else if can_aim && Some(p.side()) == mine {
            Some(Color::new(0.93, 0.66, 0.25, 0.45))
        } else {
            None
        }
    });
    let r = vp.px(v.config.piece_radius);
    let drawn = frame
        .pieces
        .iter()
        .map(|&(p, pos)| (p, vp.to_screen(pos), r))
        .collect();
    if can_aim && since_turn < TURN_CUE {
        let msg = Rect::new(
            area.x + area.w / 2.0 - 80.0,
            area.y + area.h / 2.0 - 24.0,
            160.0,
            48.0,
        );
        let k = ((TURN_CUE - since_turn) as f32).min(1.0);
        draw_rectangle(
            msg.x,
            msg.y,
            msg.w,
            msg.h,
            Color::new(0.0, 0.0, 0.0, 0.6 * k),
        );
        ui::text_centred(
            &t!("board-your-turn"),
            msg,
            24.0,
            Color::new(0.55, 0.95, 0.5, k),
        );
    }
    Shown {
        viewport: vp,
        drawn,
    }
}

/// What the slingshot came to this frame.
#[derive(Default)]
pub struct Sling {
    /// The power and the meter's rectangle while aiming.
    pub aiming: Option<(f64, Rect)>,
    /// A shot released: the piece and its velocity.
    pub shot: Option<(PieceId, DVec2)>,
}

/// The slingshot for `mine` on `v`'s board mapped by `vp`: takes presses
/// the panel left, draws the pull, the arrow and the power meter (kept
/// inside the window), releases the shot.
pub fn sling(
    ui: &Ui,
    vp: Viewport,
    v: &MatchView,
    mine: Option<Side>,
    drag: &mut Option<Drag>,
) -> Sling {
    let mut out = Sling::default();
    let input = &ui.input;
    let pointer = vp.to_world(input.pointer);
    if input.pressed && !ui.captured() && drag.is_none() {
        let grab = v.config.piece_radius * 1.4;
        let hit = v
            .board
            .pieces()
            .iter()
            .filter(|p| Some(p.id.side()) == mine)
            .map(|p| (p, (p.pos - pointer).length()))
            .filter(|(_, d)| *d <= grab)
            .min_by(|a, b| a.1.total_cmp(&b.1));
        if let Some((p, _)) = hit {
            *drag = Some(Drag {
                piece: p.id,
                from: p.pos,
                pointer,
            });
        }
    }
    let Some(d) = drag else { return out };
    d.pointer = pointer;
    // The window in world metres: the pull's reach ends at its edge.
    let window = crate::scale::size();
    let (c0, c1) = (vp.to_world(vec2(0.0, 0.0)), vp.to_world(window));
    let room = aim::room_along(d.from, d.pointer - d.from, c0.min(c1), c0.max(c1));
    let sling = Slingshot {
        radius: v.config.piece_radius,
        full_pull: aim::full_pull(v.config.square, v.config.piece_radius, room),
        max_speed: v.config.max_speed,
    };
    let aim = sling.aim(d.from, d.pointer);
    let c = vp.to_screen(d.from);
    let p = input.pointer;
    draw_line(c.x, c.y, p.x, p.y, 2.0, Color::new(0.9, 0.8, 0.6, 0.6));
    match aim {
        Aim::Shoot { velocity, power } => {
            // The arrow: where the piece would go, as long as a full-power shot's first 3 squares.
            let dir = velocity / velocity.length();
            let tip = vp.to_screen(d.from + dir * v.config.square * (0.8 + 3.2 * power));
            let col = Color::new(1.0, 0.85 - 0.6 * power as f32, 0.25, 0.95);
            draw::arrow(c, tip, col, 5.0);
            // The power meter beside the pointer, inside the window.
            let meter = meter_rect(p, window);
            out.aiming = Some((
                power,
                Rect::new(meter.x - 4.0, meter.y - 4.0, 62.0, meter.h + 8.0),
            ));
            draw_rectangle(
                meter.x - 4.0,
                meter.y - 4.0,
                62.0,
                meter.h + 8.0,
                Color::new(0.0, 0.0, 0.0, 0.55),
            );
            draw_rectangle(
                meter.x,
                meter.y,
                meter.w,
                meter.h,
                Color::new(1.0, 1.0, 1.0, 0.12),
            );
            let h = meter.h * power as f32;
            draw_rectangle(meter.x, meter.y + meter.h - h, meter.w, h, col);
            ui::text(
                &format!("{:.0}%", power * 100.0),
                meter.x + meter.w + 4.0,
                meter.y + meter.h / 2.0 - 8.0,
                15.0,
                colors::TEXT,
            );
        }
        Aim::Cancel => {
            let msg = t!("board-release-to-cancel");
            let tw = ui::text_width(&msg, 16.0);
            let x = (p.x + 14.0).min(window.x - tw - 6.0).max(4.0);
            let y = (p.y - 30.0).clamp(4.0, window.y - 24.0);
            ui::text(&msg, x, y, 16.0, colors::MUTED);
        }
    }
    if ui.input.released || !ui.input.down {
        let piece = d.piece;
        *drag = None;
        if let Aim::Shoot { velocity, .. } = aim {
            out.shot = Some((piece, velocity));
        }
    }
    out
}
