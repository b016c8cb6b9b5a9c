//! Geometry the layout tests share: whether two rectangles overlap and
//! whether one lies inside another (with a thousandth of a unit's slack
//! for rounding), the window sizes every screen is checked at, and the
//! width of a text in the client's own font (DejaVu Sans, measured as
//! macroquad measures it: the sum of the glyphs' advances at the size).

use macroquad::prelude::Rect;

/// Phones upright and on their side (layout units).
pub const PHONES: [(f32, f32); 3] = [(390.0, 844.0), (412.0, 915.0), (844.0, 390.0)];

/// Whether `a` and `b` share any area (touching edges do not count).
pub fn overlap(a: Rect, b: Rect) -> bool {
    a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h
}

/// Whether `inner` lies within `outer`.
pub fn inside(inner: Rect, outer: Rect) -> bool {
    inner.x >= outer.x - 1e-3
        && inner.y >= outer.y - 1e-3
        && inner.x + inner.w <= outer.x + outer.w + 1e-3
        && inner.y + inner.h <= outer.y + outer.h + 1e-3
}

thread_local! {
    static FONT: fontdue::Font = fontdue::Font::from_bytes(
        include_bytes!("../assets/DejaVuSans-subset.ttf").as_slice(),
        fontdue::FontSettings::default(),
    )
    .expect("the embedded font parses");
}

/// The width of `s` at `size` units in the client's font at a zoom of 1
/// (as `ui::text_width` measures it in a browser window of that size).
pub fn font_width(s: &str, size: f32) -> f32 {
    let px = size.round().max(1.0);
    FONT.with(|f| {
        s.chars()
            .map(|c| f.metrics(c, px).advance_width * size / px)
            .sum()
    })
}
