//! A whole match on one time axis: the shots one after another, each
//! followed by a short pause, so a replay can be scrubbed, played at any
//! speed (backwards too) and jumped shot by shot. Pure arithmetic over the
//! shots' durations.

/// Pause after each shot, in seconds.
pub const GAP: f64 = 0.8;

/// Where each shot starts on the match axis.
#[derive(Clone, Debug, PartialEq)]
pub struct Timeline {
    starts: Vec<f64>,
    total: f64,
}

impl Timeline {
    /// The axis of shots lasting `durations` seconds each.
    pub fn new(durations: impl IntoIterator<Item = f64>) -> Timeline {
        let mut starts = Vec::new();
        let mut at = 0.0;
        for d in durations {
            starts.push(at);
            at += d.max(0.0) + GAP;
        }
        Timeline { starts, total: at }
    }

    /// Length of the whole match.
    pub fn total(&self) -> f64 {
        self.total
    }

    pub fn shots(&self) -> usize {
        self.starts.len()
    }

    /// Where shot `n` starts.
    pub fn start(&self, n: usize) -> f64 {
        self.starts.get(n).copied().unwrap_or(self.total)
    }

    /// The shot shown at match time `t` and the time within it (which
    /// runs past the shot's end during its pause); `None` before any shot.
    pub fn locate(&self, t: f64) -> Option<(usize, f64)> {
        let n = self.starts.partition_point(|&s| s <= t);
        let n = n.checked_sub(1)?;
        Some((n, t - self.starts[n]))
    }

    /// The time after `dt` seconds of wall time at `speed`, clamped to the
    /// match.
    pub fn step(&self, t: f64, dt: f64, speed: f64) -> f64 {
        (t + dt * speed).clamp(0.0, self.total)
    }

    /// The start of the shot after the one at `t`.
    pub fn next_shot(&self, t: f64) -> f64 {
        let n = self.starts.partition_point(|&s| s <= t + 1e-9);
        self.start(n)
    }

    /// The start of the shot at `t`, or of the one before if `t` is at
    /// (or just after) its start.
    pub fn previous_shot(&self, t: f64) -> f64 {
        match self.locate(t) {
            Some((n, within)) if within > 0.3 => self.start(n),
            Some((n, _)) if n > 0 => self.start(n - 1),
            _ => 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shots_follow_each_other_with_a_pause() {
        let tl = Timeline::new([1.0, 2.0, 0.5]);
        assert_eq!(tl.shots(), 3);
        assert_eq!(tl.start(1), 1.0 + GAP);
        assert!((tl.total() - (3.5 + 3.0 * GAP)).abs() < 1e-12);
        assert_eq!(tl.locate(0.0), Some((0, 0.0)));
        let (n, within) = tl.locate(1.0 + GAP + 0.25).unwrap();
        assert_eq!(n, 1);
        assert!((within - 0.25).abs() < 1e-12);
        assert_eq!(tl.locate(tl.total()).map(|(n, _)| n), Some(2));
        assert_eq!(Timeline::new([]).locate(0.0), None);
    }

    #[test]
    fn playing_backwards_or_fast_stays_inside_the_match() {
        let tl = Timeline::new([1.0, 1.0]);
        assert_eq!(tl.step(0.5, 1.0, -2.0), 0.0);
        assert_eq!(tl.step(tl.total() - 0.1, 1.0, 4.0), tl.total());
        assert_eq!(tl.step(1.0, 0.25, -2.0), 0.5);
    }

    #[test]
    fn jumping_shot_by_shot() {
        let tl = Timeline::new([1.0, 1.0, 1.0]);
        assert_eq!(tl.next_shot(0.0), tl.start(1));
        assert_eq!(tl.next_shot(tl.start(1)), tl.start(2));
        assert_eq!(tl.next_shot(tl.start(2)), tl.total());
        assert_eq!(tl.previous_shot(tl.start(2) + 0.5), tl.start(2));
        assert_eq!(tl.previous_shot(tl.start(2)), tl.start(1));
        assert_eq!(tl.previous_shot(0.1), 0.0);
    }
}
