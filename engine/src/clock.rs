//! The world's clock: where the zero of its working time lies.
//!
//! A time held in one `f64` resolves about 2.2e-16 of its magnitude: 4.4e-16 s
//! at t = 3 s. Galperin's billiard at nine digits hits every 1.8e-16 s there,
//! at ten digits every 1.8e-18 s, so in absolute time its events fall onto
//! one number and the positions computed at them are off by a fraction of
//! the gap the light disc crosses. From the seventh revision the world
//! therefore computes every time as seconds since an origin of its own, the
//! [`Clock`], and moves that origin up to the latest event whenever the
//! events come closer together than [`REBASE`] of the working time: every
//! pending time and every trajectory's start is then re-expressed from the
//! new origin (trajectories already run on their own clocks, so only their
//! start and stop times change). The origin itself is a double-double, the
//! exact sum of the moves, so the absolute time of an event is known to far
//! below an `f64`'s rounding, and is rounded once when it is reported.
//!
//! Before the seventh revision the origin never moves, and every conversion
//! here is the identity: old computations keep their bits.

/// Events closer together than this fraction of the working time move the
/// origin (see [`Clock::moves_for`]): after a move, an event's time carries
/// a rounding of at most `2^-52 / REBASE` (about 2.3e-10) of the gap
/// between events.
pub(crate) const REBASE: f64 = 1.0 / (1u64 << 20) as f64;

/// The origin of a world's working time: an absolute time as the unevaluated
/// sum `hi + lo` (a double-double), and whether it ever moved from zero.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Clock {
    hi: f64,
    lo: f64,
    moved: bool,
}

impl Clock {
    /// Whether the origin moved from zero, ever (only from the seventh
    /// revision).
    #[inline(always)]
    pub(crate) fn moved(&self) -> bool {
        self.moved
    }

    /// The absolute time of working time `t`, rounded once; `t` itself
    /// while the origin is at zero.
    #[inline(always)]
    pub(crate) fn absolute(&self, t: f64) -> f64 {
        if self.moved {
            self.hi + (self.lo + t)
        } else {
            t
        }
    }

    /// The working time of absolute time `t`; `t` itself while the origin is
    /// at zero.
    #[inline(always)]
    pub(crate) fn working(&self, t: f64) -> f64 {
        if self.moved {
            (t - self.hi) - self.lo
        } else {
            t
        }
    }

    /// Whether an event at working time `t`, `gap` after the one before it,
    /// should move the origin up to it: the events are finitely apart but
    /// closer than [`REBASE`] of the working time.
    #[inline(always)]
    pub(crate) fn moves_for(gap: f64, t: f64) -> bool {
        gap > 0.0 && gap < REBASE * t.abs()
    }

    /// Moves the origin forward by `by` seconds of working time, exactly
    /// (to the double-double's 106 bits).
    pub(crate) fn advance(&mut self, by: f64) {
        // Knuth's two-sum: s + err == hi + by exactly.
        let s = self.hi + by;
        let b = s - self.hi;
        let err = (self.hi - (s - b)) + (by - b);
        let lo = self.lo + err;
        // Renormalised, so that hi is the sum rounded.
        self.hi = s + lo;
        self.lo = lo - (self.hi - s);
        self.moved = true;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_unmoved_clock_changes_no_time() {
        let c = Clock::default();
        for t in [0.0, -0.0, 1e-300, 3.2, f64::INFINITY] {
            assert_eq!(c.absolute(t).to_bits(), t.to_bits());
            assert_eq!(c.working(t).to_bits(), t.to_bits());
        }
    }

    #[test]
    fn moves_smaller_than_the_rounding_of_the_time_add_up_exactly() {
        // A million moves of 1e-18 s from 3.2 s: in one f64 each would be
        // lost (the rounding at 3.2 is 4.4e-16 s).
        let mut c = Clock::default();
        c.advance(3.2);
        for _ in 0..1_000_000 {
            c.advance(1e-18);
        }
        let elapsed = (c.hi - 3.2) + c.lo;
        assert!((elapsed - 1e-12).abs() < 1e-22, "{elapsed:e}");
        assert_eq!(c.absolute(0.0), 3.2 + 1e-12);
    }

    #[test]
    fn working_time_inverts_absolute_time() {
        let mut c = Clock::default();
        c.advance(3.2);
        c.advance(1e-17);
        for t in [0.0, 1e-18, 2.5e-16, 0.7] {
            let back = c.working(c.absolute(t));
            assert!((back - t).abs() <= 4.5e-16, "{t:e}: {back:e}");
        }
        assert_eq!(c.absolute(f64::INFINITY), f64::INFINITY);
    }

    #[test]
    fn only_events_finitely_closer_than_the_rebase_fraction_move_the_origin() {
        assert!(Clock::moves_for(1e-18, 3.2));
        assert!(!Clock::moves_for(0.0, 3.2), "simultaneous events");
        assert!(!Clock::moves_for(1e-3, 3.2), "game-like spacing");
        assert!(!Clock::moves_for(1e-18, 0.0));
    }
}
