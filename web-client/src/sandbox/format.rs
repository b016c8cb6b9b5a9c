//! How the sandbox writes numbers on screen: lengths, times and masses to
//! about four significant digits, and the playback speeds as `2x`.
//! Shared by the panels, the overlays and the world's grid label.

/// A number with about four significant digits.
pub fn num(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else if !x.is_finite() {
        "inf".into()
    } else if x.abs() >= 1e5 || x.abs() < 1e-3 {
        format!("{x:.3e}")
    } else if x.abs() >= 100.0 {
        format!("{x:.1}")
    } else if x.abs() >= 1.0 {
        format!("{x:.3}")
    } else {
        format!("{x:.4}")
    }
}

/// `1x`, `0.1x`, `-2x`.
pub fn speed_label(s: f64) -> String {
    format!("{s}x")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_keep_about_four_significant_digits() {
        assert_eq!(num(0.0), "0");
        assert_eq!(num(f64::INFINITY), "inf");
        assert_eq!(num(1234.567), "1234.6");
        assert_eq!(num(4.56789), "4.568");
        assert_eq!(num(0.0123456), "0.0123");
        assert_eq!(num(2e-4), "2.000e-4");
        assert_eq!(speed_label(-2.0), "-2x");
    }
}
