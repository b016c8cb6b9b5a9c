//! The layout unit: every screen lays itself out in units that are CSS
//! pixels on a phone or a laptop and grow with a large window, so the
//! interface fills a 1920x1080 screen instead of staying a small island.
//!
//! macroquad draws at device pixels (`high_dpi`), so a screen with a
//! device-pixel ratio of 3 is sharp; on top of that a camera maps layout
//! units to CSS pixels by the window's zoom ([`zoom_for`]). Text is
//! rasterised at its final size (see `ui::text`), the pointer is read back
//! in layout units, and the browser test receives rectangles in CSS pixels
//! ([`css`]).

use macroquad::prelude::*;
use std::cell::Cell;

/// The window size (CSS pixels) the interface was designed for; larger
/// windows zoom it.
pub const DESIGN: (f32, f32) = (1100.0, 760.0);
/// The most the interface is zoomed.
pub const MAX_ZOOM: f32 = 2.0;

thread_local! {
    static ZOOM: Cell<f32> = const { Cell::new(1.0) };
}

/// How much a window of `w` x `h` CSS pixels zooms the interface: 1 up to
/// the design size, then with the window's shorter proportion, at most
/// [`MAX_ZOOM`]. Never below 1: every screen lays itself out for a
/// narrow window (a phone) rather than being zoomed out to fit.
pub fn zoom_for(w: f32, h: f32) -> f32 {
    let z = (w / DESIGN.0).min(h / DESIGN.1);
    if !z.is_finite() {
        return 1.0;
    }
    z.clamp(1.0, MAX_ZOOM)
}

/// Starts a frame: measures the window and sets the camera that maps
/// layout units to the screen.
pub fn begin_frame() {
    let (w, h) = (screen_width(), screen_height());
    let zoom = zoom_for(w, h);
    ZOOM.with(|z| z.set(zoom));
    let (lw, lh) = (w / zoom, h / zoom);
    set_camera(&Camera2D {
        target: vec2(lw / 2.0, lh / 2.0),
        zoom: vec2(2.0 / lw.max(1.0), 2.0 / lh.max(1.0)),
        ..Default::default()
    });
}

/// The window's current zoom (CSS pixels per layout unit).
pub fn zoom() -> f32 {
    ZOOM.with(Cell::get)
}

/// The window in layout units.
pub fn size() -> Vec2 {
    vec2(screen_width(), screen_height()) / zoom()
}

/// The pointer in layout units.
pub fn pointer() -> Vec2 {
    let (x, y) = mouse_position();
    vec2(x, y) / zoom()
}

/// A rectangle in layout units as CSS pixels from the window's top-left.
pub fn css(r: Rect) -> Rect {
    let z = zoom();
    Rect::new(r.x * z, r.y * z, r.w * z, r.h * z)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn phones_and_laptops_are_not_zoomed() {
        assert_eq!(zoom_for(390.0, 844.0), 1.0);
        assert_eq!(zoom_for(1024.0, 720.0), 1.0);
    }

    #[test]
    fn a_full_hd_window_zooms_with_its_shorter_proportion() {
        let z = zoom_for(1920.0, 1080.0);
        assert!((z - 1080.0 / 760.0).abs() < 1e-4, "{z}");
        assert_eq!(zoom_for(8000.0, 5000.0), MAX_ZOOM);
        assert_eq!(zoom_for(f32::NAN, 1.0), 1.0);
    }
}
