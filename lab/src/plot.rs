//! SVG charts with `plotters` (SVG backend only): log–log scatter and line
//! charts of named series, the one shape every chart here needs. Values
//! that a log axis cannot show (zero, negative, NaN) are clamped to the
//! axis floor given by the caller, and the caption says so.

use crate::LabError;
use plotters::prelude::*;
use std::path::Path;

/// How a series is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Style {
    /// Markers only.
    Points,
    /// Markers joined by a line (in the given order).
    Line,
}

/// One named series.
#[derive(Clone, Debug)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub style: Style,
}

/// Axis titles, floors and the chart title.
#[derive(Clone, Debug)]
pub struct Axes<'a> {
    pub title: &'a str,
    pub x: &'a str,
    pub y: &'a str,
    /// Smallest value shown on y (smaller ones are drawn on it).
    pub y_floor: f64,
}

const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

fn plot_err(path: &Path, e: impl std::fmt::Display) -> LabError {
    LabError::Plot {
        path: path.display().to_string(),
        message: e.to_string(),
    }
}

/// The decade range `[10^floor(log lo), 10^ceil(log hi)]` of positive values.
fn decades(vals: impl Iterator<Item = f64>, floor: f64) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in vals {
        let v = if v.is_finite() && v > floor { v } else { floor };
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return (floor.max(1e-300), 1.0);
    }
    let lo = 10f64.powf(lo.log10().floor());
    let mut hi = 10f64.powf(hi.log10().ceil());
    if hi <= lo {
        hi = lo * 10.0;
    }
    (lo, hi)
}

/// Draws `series` on log–log axes into the SVG file `path`.
pub fn log_log(path: &Path, axes: &Axes, series: &[Series]) -> Result<(), LabError> {
    let root = SVGBackend::new(path, (900, 600)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_err(path, e))?;
    let all = || series.iter().flat_map(|s| s.points.iter());
    let (x0, x1) = decades(all().map(|p| p.0), 1e-300);
    let (y0, y1) = decades(all().map(|p| p.1), axes.y_floor);
    let mut chart = ChartBuilder::on(&root)
        .caption(axes.title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
        .map_err(|e| plot_err(path, e))?;
    chart
        .configure_mesh()
        .x_desc(axes.x)
        .y_desc(axes.y)
        .x_label_formatter(&|v| format!("{v:.0e}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .draw()
        .map_err(|e| plot_err(path, e))?;
    let clamp = |(x, y): (f64, f64)| {
        let y = if y.is_finite() && y > axes.y_floor {
            y
        } else {
            axes.y_floor
        };
        (x, y)
    };
    for (k, s) in series.iter().enumerate() {
        let color = PALETTE[k % PALETTE.len()];
        let pts: Vec<(f64, f64)> = s
            .points
            .iter()
            .copied()
            .filter(|p| p.0.is_finite() && p.0 > 0.0)
            .map(clamp)
            .collect();
        if s.style == Style::Line {
            chart
                .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
                .map_err(|e| plot_err(path, e))?;
        }
        let marker = k % 3;
        chart
            .draw_series(
                pts.iter()
                    .map(move |&p| -> DynElement<SVGBackend, (f64, f64)> {
                        match marker {
                            0 => Circle::new(p, 5, color.filled()).into_dyn(),
                            1 => TriangleMarker::new(p, 6, color.filled()).into_dyn(),
                            _ => Cross::new(p, 5, color.stroke_width(2)).into_dyn(),
                        }
                    }),
            )
            .map_err(|e| plot_err(path, e))?
            .label(s.name.as_str())
            .legend(move |(x, y)| Circle::new((x + 10, y), 5, color.filled()));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(|e| plot_err(path, e))?;
    root.present().map_err(|e| plot_err(path, e))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_an_svg_with_every_series_name() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.svg");
        let series = vec![
            Series {
                name: "alpha".into(),
                points: vec![(1e-6, 1e-3), (1e-3, 0.0)],
                style: Style::Line,
            },
            Series {
                name: "beta".into(),
                points: vec![(1e-2, 1e-12)],
                style: Style::Points,
            },
        ];
        let axes = Axes {
            title: "t",
            x: "x",
            y: "y",
            y_floor: 1e-17,
        };
        log_log(&path, &axes, &series).unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        assert!(svg.starts_with("<svg") && svg.contains("alpha") && svg.contains("beta"));
    }
}
