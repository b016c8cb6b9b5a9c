//! The map between world metres and screen pixels: a centre, a scale and
//! an optional half turn (so a player's own side is always at the bottom),
//! with panning and zooming about a point for the sandbox.
//!
//! World `y` points up (away from White), screen `y` points down.

use glam::DVec2;
use macroquad::prelude::{vec2, Rect, Vec2};

/// World-to-screen transform.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Viewport {
    /// The world point shown at `anchor`.
    pub centre: DVec2,
    /// Where on the screen `centre` appears.
    pub anchor: Vec2,
    /// Pixels per metre.
    pub scale: f64,
    /// Turned half a turn (Black's view of the board).
    pub flipped: bool,
}

impl Viewport {
    /// Fits the square `[0, size]²` into `area` with a margin, turned if
    /// `flipped`.
    pub fn fit_square(size: f64, area: Rect, margin: f32, flipped: bool) -> Viewport {
        let side = (area.w.min(area.h) - 2.0 * margin).max(10.0);
        Viewport {
            centre: DVec2::splat(size / 2.0),
            anchor: vec2(area.x + area.w / 2.0, area.y + area.h / 2.0),
            scale: side as f64 / size,
            flipped,
        }
    }

    /// Screen position of world point `p`.
    pub fn to_screen(self, p: DVec2) -> Vec2 {
        let d = self.turn(p - self.centre) * self.scale;
        vec2(self.anchor.x + d.x as f32, self.anchor.y - d.y as f32)
    }

    /// World point under screen position `s`.
    pub fn to_world(self, s: Vec2) -> DVec2 {
        let d = DVec2::new((s.x - self.anchor.x) as f64, (self.anchor.y - s.y) as f64);
        self.centre + self.turn(d / self.scale)
    }

    /// A world length in pixels.
    pub fn px(&self, metres: f64) -> f32 {
        (metres * self.scale) as f32
    }

    fn turn(&self, d: DVec2) -> DVec2 {
        if self.flipped {
            -d
        } else {
            d
        }
    }

    /// Moves the view by a screen-space drag of `delta` pixels.
    pub fn pan(&mut self, delta: Vec2) {
        let d = DVec2::new(-delta.x as f64, delta.y as f64) / self.scale;
        self.centre += self.turn(d);
    }

    /// Zooms by `factor` keeping the world point under `at` in place.
    pub fn zoom_about(&mut self, at: Vec2, factor: f64) {
        let fixed = self.to_world(at);
        self.scale = (self.scale * factor).clamp(1.0, 1e7);
        let moved = self.to_world(at);
        self.centre += fixed - moved;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn world_and_screen_round_trip_both_ways_up() {
        for flipped in [false, true] {
            let v = Viewport::fit_square(0.32, Rect::new(0.0, 0.0, 800.0, 600.0), 20.0, flipped);
            for p in [
                DVec2::new(0.0, 0.0),
                DVec2::new(0.3, 0.1),
                DVec2::new(0.16, 0.16),
            ] {
                let back = v.to_world(v.to_screen(p));
                assert!((back - p).length() < 1e-6, "{p} came back as {back}");
            }
        }
    }

    #[test]
    fn whites_back_row_is_at_the_bottom_unless_flipped() {
        let area = Rect::new(0.0, 0.0, 800.0, 600.0);
        let v = Viewport::fit_square(0.32, area, 20.0, false);
        assert!(v.to_screen(DVec2::new(0.16, 0.0)).y > v.to_screen(DVec2::new(0.16, 0.32)).y);
        let f = Viewport::fit_square(0.32, area, 20.0, true);
        assert!(f.to_screen(DVec2::new(0.16, 0.0)).y < f.to_screen(DVec2::new(0.16, 0.32)).y);
        // The square fills the short side less the margins.
        assert!((v.px(0.32) - 560.0).abs() < 1e-3);
    }

    #[test]
    fn zooming_keeps_the_point_under_the_pointer() {
        let mut v = Viewport::fit_square(1.0, Rect::new(0.0, 0.0, 500.0, 500.0), 0.0, false);
        let at = vec2(120.0, 340.0);
        let before = v.to_world(at);
        v.zoom_about(at, 2.5);
        assert!((v.to_world(at) - before).length() < 1e-9);
        v.pan(vec2(30.0, -10.0));
        let moved = v.to_screen(before);
        assert!((moved - (at + vec2(30.0, -10.0))).length() < 1e-3);
    }
}
