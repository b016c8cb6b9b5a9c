//! The rules every screen's layout keeps, checked on the rectangles the app
//! publishes (`window.chapaev_state.buttons`, CSS pixels): every control
//! lies inside the window, no two overlap, and each is tall enough for a
//! finger.

use serde_json::Value;

/// A control's rectangle, CSS pixels from the window's top-left.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Control<'a> {
    pub name: &'a str,
    pub x: f64,
    pub y: f64,
    pub w: f64,
    pub h: f64,
}

/// Pixels of slack for rounding.
const SLACK: f64 = 0.5;

/// The controls in a state report's `buttons`; an entry that is not an
/// `[x, y, w, h]` array is itself a fault.
pub fn controls(buttons: &Value) -> Result<Vec<Control<'_>>, String> {
    let map = buttons
        .as_object()
        .ok_or_else(|| format!("buttons is not an object: {buttons}"))?;
    map.iter()
        .map(|(name, r)| {
            let n = |i: usize| r[i].as_f64();
            match (n(0), n(1), n(2), n(3)) {
                (Some(x), Some(y), Some(w), Some(h)) => Ok(Control { name, x, y, w, h }),
                _ => Err(format!("{name} is not an [x, y, w, h] rectangle: {r}")),
            }
        })
        .collect()
}

/// Every way the controls break the rules in a `width` x `height` window,
/// as sentences (empty: none). `min_height` is the finger-sized minimum
/// (0 to skip that rule).
pub fn faults(controls: &[Control], width: f64, height: f64, min_height: f64) -> Vec<String> {
    let mut out = Vec::new();
    for c in controls {
        if c.x < -SLACK || c.y < -SLACK || c.x + c.w > width + SLACK || c.y + c.h > height + SLACK {
            out.push(format!(
                "{} at [{:.0}, {:.0}, {:.0}, {:.0}] is not inside the {width:.0}x{height:.0} window",
                c.name, c.x, c.y, c.w, c.h
            ));
        }
        if c.h + SLACK < min_height {
            out.push(format!(
                "{} is {:.1} px tall, less than {min_height:.0}",
                c.name, c.h
            ));
        }
    }
    for (i, a) in controls.iter().enumerate() {
        for b in &controls[i + 1..] {
            if let Some((dx, dy)) = overlap(a, b) {
                out.push(format!(
                    "{} and {} overlap ({dx:.0}x{dy:.0} px)",
                    a.name, b.name
                ));
            }
        }
    }
    out
}

/// How far `a` and `b` overlap (width, height), beyond rounding; `None`
/// when they do not.
pub fn overlap(a: &Control, b: &Control) -> Option<(f64, f64)> {
    let dx = (a.x + a.w).min(b.x + b.w) - a.x.max(b.x);
    let dy = (a.y + a.h).min(b.y + b.h) - a.y.max(b.y);
    (dx > SLACK && dy > SLACK).then_some((dx, dy))
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn controls_side_by_side_inside_the_window_pass() {
        let b = json!({"a": [0, 0, 100, 44], "b": [100, 0, 100, 44]});
        let c = controls(&b).unwrap();
        assert!(faults(&c, 200.0, 44.0, 44.0).is_empty());
    }

    #[test]
    fn a_control_off_screen_overlapping_or_too_short_is_named() {
        let b = json!({"off": [380, 0, 40, 44], "one": [0, 50, 60, 30], "two": [30, 60, 60, 44]});
        let f = faults(&controls(&b).unwrap(), 390.0, 844.0, 44.0);
        assert!(f.iter().any(|s| s.starts_with("off at")), "{f:?}");
        assert!(
            f.iter().any(|s| s.starts_with("one is 30.0 px tall")),
            "{f:?}"
        );
        assert!(
            f.iter().any(|s| s.starts_with("one and two overlap")),
            "{f:?}"
        );
        assert_eq!(f.len(), 3, "{f:?}");
    }

    #[test]
    fn a_malformed_rectangle_is_a_fault() {
        assert!(controls(&json!({"x": [1, 2]})).is_err());
    }
}
