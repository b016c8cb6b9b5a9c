//! A small line chart of a series over time (an account's rating after
//! each rated match): the values mapped into a rectangle with a margin of
//! range above and below, the line, its points, and the lowest and highest
//! values written at the left edge.

use crate::ui::{self, colors};
use macroquad::prelude::*;

/// Where the `values` (oldest first) fall in `area`: evenly spaced from
/// left to right, the highest value near the top. A single value sits in
/// the middle; values that are all equal lie on the middle line.
pub fn points(values: &[f64], area: Rect) -> Vec<Vec2> {
    let finite: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    let (lo, hi) = finite
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    let n = finite.len();
    finite
        .iter()
        .enumerate()
        .map(|(i, &v)| {
            let fx = if n > 1 {
                i as f32 / (n - 1) as f32
            } else {
                0.5
            };
            let fy = if hi > lo {
                ((v - lo) / (hi - lo)) as f32
            } else {
                0.5
            };
            vec2(area.x + fx * area.w, area.y + (1.0 - fy) * area.h)
        })
        .collect()
}

/// Draws the chart of `values` in `area` (a panel; "no rated games yet"
/// when there are none).
pub fn draw(values: &[f64], area: Rect) {
    ui::panel(area);
    let label_w = 48.0;
    let inner = Rect::new(
        area.x + label_w,
        area.y + 14.0,
        area.w - label_w - 14.0,
        area.h - 28.0,
    );
    let finite: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    if finite.is_empty() {
        ui::text(
            &crate::i18n::t!("chart-no-games"),
            area.x + 12.0,
            area.y + area.h / 2.0 - 8.0,
            15.0,
            colors::MUTED,
        );
        return;
    }
    let grid = Color::new(0.45, 0.33, 0.24, 1.0);
    draw_line(inner.x, inner.y, inner.x, inner.y + inner.h, 1.0, grid);
    draw_line(
        inner.x,
        inner.y + inner.h,
        inner.x + inner.w,
        inner.y + inner.h,
        1.0,
        grid,
    );
    let lo = finite.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = finite.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    ui::text(
        &format!("{}", hi.round() as i64),
        area.x + 6.0,
        inner.y - 6.0,
        13.0,
        colors::MUTED,
    );
    if hi > lo {
        ui::text(
            &format!("{}", lo.round() as i64),
            area.x + 6.0,
            inner.y + inner.h - 8.0,
            13.0,
            colors::MUTED,
        );
    }
    let ps = points(&finite, inner);
    for pair in ps.windows(2) {
        draw_line(
            pair[0].x,
            pair[0].y,
            pair[1].x,
            pair[1].y,
            2.0,
            colors::ACCENT,
        );
    }
    for p in &ps {
        draw_circle(p.x, p.y, 3.0, colors::TEXT);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_series_spans_the_area_highest_at_the_top() {
        let area = Rect::new(10.0, 20.0, 100.0, 50.0);
        let p = points(&[1500.0, 1600.0, 1550.0], area);
        assert_eq!(p.len(), 3);
        assert_eq!(p[0], vec2(10.0, 70.0));
        assert_eq!(p[1], vec2(60.0, 20.0));
        assert_eq!(p[2], vec2(110.0, 45.0));
    }

    #[test]
    fn one_value_or_equal_values_lie_on_the_middle_line_and_nan_is_left_out() {
        let area = Rect::new(0.0, 0.0, 100.0, 50.0);
        assert_eq!(points(&[1500.0], area), vec![vec2(50.0, 25.0)]);
        let p = points(&[1500.0, f64::NAN, 1500.0], area);
        assert_eq!(p, vec![vec2(0.0, 25.0), vec2(100.0, 25.0)]);
        assert!(points(&[], area).is_empty());
    }
}
