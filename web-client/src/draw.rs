//! Drawing the world: the wooden board, shaded checkers, plain discs,
//! lines and points for the sandbox, and the small effects (a hit ring, a
//! piece falling off the edge).

use crate::viewport::Viewport;
use ::glam::DVec2;
use engine::obstacle::{Line, LineKind};
use game::Side;
use macroquad::prelude::*;

const WOOD_LIGHT: Color = Color::new(0.87, 0.72, 0.50, 1.0);
const WOOD_DARK: Color = Color::new(0.62, 0.40, 0.22, 1.0);
const FRAME: Color = Color::new(0.36, 0.22, 0.12, 1.0);

/// Draws the 8x8 board of `size` metres, its frame and the file and rank
/// letters.
pub fn board(v: &Viewport, size: f64) {
    let sq = size / 8.0;
    let a = v.to_screen(DVec2::ZERO);
    let b = v.to_screen(DVec2::splat(size));
    let (x0, y0) = (a.x.min(b.x), a.y.min(b.y));
    let side = (a.x - b.x).abs();
    let frame = side * 0.045;
    draw_rectangle(
        x0 - frame + 5.0,
        y0 - frame + 7.0,
        side + 2.0 * frame,
        side + 2.0 * frame,
        Color::new(0.0, 0.0, 0.0, 0.35),
    );
    draw_rectangle(
        x0 - frame,
        y0 - frame,
        side + 2.0 * frame,
        side + 2.0 * frame,
        FRAME,
    );
    for file in 0..8 {
        for rank in 0..8 {
            let p = v.to_screen(DVec2::new(file as f64 * sq, rank as f64 * sq));
            let q = v.to_screen(DVec2::new((file + 1) as f64 * sq, (rank + 1) as f64 * sq));
            let (x, y) = (p.x.min(q.x), p.y.min(q.y));
            let w = (p.x - q.x).abs();
            let dark = (file + rank) % 2 == 0;
            let c = if dark { WOOD_DARK } else { WOOD_LIGHT };
            draw_rectangle(x, y, w, w, c);
            // A few grain lines per square, fixed per square so they do not shimmer.
            let seed = (file * 8 + rank) as f32;
            for k in 0..3 {
                let t = ((seed * 0.37 + k as f32 * 0.29).fract() * 0.8 + 0.1) * w;
                let grain = Color::new(0.0, 0.0, 0.0, if dark { 0.07 } else { 0.05 });
                draw_line(x, y + t, x + w, y + t + w * 0.04, 1.0, grain);
            }
        }
    }
    // The files and ranks in the frame, where it is wide enough to hold
    // them at a readable size (a small board goes without).
    let label = (frame * 0.7).clamp(crate::ui::MIN_TEXT, 16.0);
    if frame < 14.0 {
        return;
    }
    for i in 0..8u8 {
        let f = v.to_screen(DVec2::new((i as f64 + 0.5) * sq, 0.0));
        let files = (b'a' + i) as char;
        let s = files.to_string();
        let dy = if v.flipped {
            -frame * 0.35
        } else {
            frame * 0.75
        };
        crate::ui::draw_at_baseline(&s, f.x - label * 0.3, f.y + dy, label, WOOD_LIGHT);
        let r = v.to_screen(DVec2::new(0.0, (i as f64 + 0.5) * sq));
        let dx = if v.flipped { frame * 0.3 } else { -frame * 0.7 };
        crate::ui::draw_at_baseline(
            &(i + 1).to_string(),
            r.x + dx,
            r.y + label * 0.3,
            label,
            WOOD_LIGHT,
        );
    }
}

/// Colours of a checker of `side`: base, rim, highlight.
fn checker_colors(side: Side) -> (Color, Color, Color) {
    match side {
        Side::White => (
            Color::new(0.96, 0.93, 0.85, 1.0),
            Color::new(0.78, 0.72, 0.62, 1.0),
            Color::new(1.0, 1.0, 1.0, 0.85),
        ),
        Side::Black => (
            Color::new(0.16, 0.13, 0.12, 1.0),
            Color::new(0.05, 0.04, 0.04, 1.0),
            Color::new(0.55, 0.50, 0.48, 0.7),
        ),
    }
}

fn faded(c: Color, alpha: f32) -> Color {
    Color::new(c.r, c.g, c.b, c.a * alpha)
}

/// A shaded checker at screen point `c` with radius `r` (pixels).
pub fn checker(c: Vec2, r: f32, side: Side, alpha: f32) {
    let (base, rim, hi) = checker_colors(side);
    draw_circle(
        c.x + r * 0.12,
        c.y + r * 0.18,
        r,
        faded(Color::new(0.0, 0.0, 0.0, 0.35), alpha),
    );
    draw_circle(c.x, c.y, r, faded(rim, alpha));
    draw_circle(c.x - r * 0.04, c.y - r * 0.05, r * 0.88, faded(base, alpha));
    draw_circle_lines(
        c.x,
        c.y,
        r * 0.62,
        (r * 0.07).max(1.0),
        faded(rim, alpha * 0.8),
    );
    draw_circle(
        c.x - r * 0.35,
        c.y - r * 0.38,
        r * 0.22,
        faded(hi, alpha * 0.6),
    );
}

/// A ring around a checker (the selected or shootable piece).
pub fn halo(c: Vec2, r: f32, color: Color) {
    draw_circle_lines(c.x, c.y, r * 1.18, (r * 0.12).max(2.0), color);
}

/// An expanding, fading ring where something hit; `progress` runs 0..1.
pub fn hit_ring(c: Vec2, r: f32, progress: f32) {
    let k = progress.clamp(0.0, 1.0);
    draw_circle_lines(
        c.x,
        c.y,
        r * (0.3 + 1.2 * k),
        (r * 0.15 * (1.0 - k)).max(1.0),
        Color::new(1.0, 0.95, 0.7, 0.8 * (1.0 - k)),
    );
}

/// A plain disc for the sandbox, tinted by its id.
pub fn disc(c: Vec2, r: f32, id: u64, selected: bool) {
    let hue = (id.wrapping_mul(0x9E37_79B9) % 360) as f32 / 360.0;
    let base = hsl(hue, 0.55, 0.55);
    draw_circle(
        c.x + r * 0.1,
        c.y + r * 0.15,
        r,
        Color::new(0.0, 0.0, 0.0, 0.3),
    );
    draw_circle(c.x, c.y, r, base);
    draw_circle(
        c.x - r * 0.3,
        c.y - r * 0.3,
        r * 0.3,
        Color::new(1.0, 1.0, 1.0, 0.35),
    );
    if selected {
        halo(c, r, crate::ui::colors::ACCENT);
    }
}

fn hsl(h: f32, s: f32, l: f32) -> Color {
    macroquad::color::hsl_to_rgb(h, s, l)
}

/// A line, ray or segment of the sandbox (clipped to a long extent).
pub fn line(v: &Viewport, l: &Line, color: Color, width: f32) {
    let dir = l.b - l.a;
    let far = 1e3 / v.scale.max(1e-9) * 10.0 + dir.length() * 10.0;
    let unit = dir.normalize_or_zero();
    let (p, q) = match l.kind {
        LineKind::Segment => (l.a, l.b),
        LineKind::Ray => (l.a, l.a + unit * far),
        LineKind::Line => (l.a - unit * far, l.a + unit * far),
    };
    let (p, q) = (v.to_screen(p), v.to_screen(q));
    draw_line(p.x, p.y, q.x, q.y, width, color);
    let a = v.to_screen(l.a);
    draw_circle(a.x, a.y, width, color);
    if l.kind == LineKind::Segment {
        draw_circle(q.x, q.y, width, color);
    }
}

/// A fixed point obstacle.
pub fn point(c: Vec2, color: Color) {
    draw_circle(c.x, c.y, 4.0, color);
    draw_circle_lines(c.x, c.y, 6.0, 1.0, color);
}

/// Everything of one moment of a shot: pieces, pieces dropping off the
/// edge, hit rings; `halo_of` may ring a piece in a colour.
pub fn frame(
    v: &Viewport,
    radius: f64,
    f: &crate::clip::Frame,
    halo_of: impl Fn(game::PieceId) -> Option<Color>,
) {
    let r = v.px(radius);
    for &(piece, pos, k) in &f.falling {
        let c = v.to_screen(pos);
        let shrink = 1.0 - 0.55 * k;
        checker(
            c + vec2(0.0, r * k * 0.8),
            r * shrink,
            piece.side(),
            1.0 - k,
        );
    }
    for &(piece, pos) in &f.pieces {
        let c = v.to_screen(pos);
        checker(c, r, piece.side(), 1.0);
        if let Some(color) = halo_of(piece) {
            halo(c, r, color);
        }
    }
    for &(at, k) in &f.hits {
        hit_ring(v.to_screen(at), r, k);
    }
}

/// An arrow from `from` to `to` (pixels), at most 300 px long.
pub fn arrow(from: Vec2, to: Vec2, color: Color, width: f32) {
    let d = to - from;
    let len = d.length();
    if len < 1.0 {
        return;
    }
    let to = if len > 300.0 {
        from + d * (300.0 / len)
    } else {
        to
    };
    let dir = (to - from).normalize();
    let side = vec2(-dir.y, dir.x);
    let head = (6.0 + width * 2.0).min(len * 0.5);
    draw_line(from.x, from.y, to.x, to.y, width, color);
    let a = to - dir * head + side * head * 0.5;
    let b = to - dir * head - side * head * 0.5;
    draw_triangle(to, a, b, color);
}
