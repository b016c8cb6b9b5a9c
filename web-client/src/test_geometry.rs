//! Geometry the layout tests share: whether two rectangles overlap and
//! whether one lies inside another (with a thousandth of a unit's slack
//! for rounding), and the window sizes every screen is checked at.

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
