//! The world's clock: where the zero of its working time lies.
//!
//! A time held in one `f64` resolves about 2.2e-16 of its magnitude: 4.4e-16 s
//! at t = 3 s. Galperin's billiard at nine digits hits every 1.8e-16 s there,
//! at ten digits every 1.8e-18 s, so in absolute time its events fall onto
//! one number and the positions computed at them are off by a fraction of
//! the gap the light disc crosses. From the seventh revision the world
//! therefore computes every time as seconds since an origin of its own, the
//! [`Clock`], and moves that origin up to the latest event once [`RUN`]
//! events in a row have each come closer to the one before than [`REBASE`]
//! of the working time (finitely closer: events at one instant move
//! nothing). Every pending time and every trajectory's start is then
//! re-expressed from the new origin (trajectories already run on their own
//! clocks, so only their start and stop times change). The origin itself
//! is a double-double, the exact sum of the moves, so the absolute time of
//! an event is known to far below an `f64`'s rounding, and is rounded once
//! when it is reported.
//!
//! What a move costs in exactness: the start of a trajectory that began
//! well before the new origin is re-rounded, by at most half a unit in the
//! last place of its working time (what its absolute time carried anyway),
//! so its absolute start as shown can change by a unit in the last place
//! though no event touched it. The trigger is chosen so that no scene but
//! a sustained run of events far closer together than the time resolves
//! (a light disc rattling between a wall and a heavy one) ever moves it.
//!
//! Before the seventh revision the origin never moves, and every conversion
//! here is the identity: old computations keep their bits.

/// Events closer together than this fraction of the working time, [`RUN`]
/// in a row, move the origin (see [`Clock::moves_for`]): between moves an
/// event's time carries a rounding of at most `2^-52 / REBASE` (about
/// 2.4e-7) of the gap between events. At t = 1 s that is a gap below a
/// nanosecond.
pub(crate) const REBASE: f64 = 1.0 / (1u64 << 30) as f64;

/// See [`REBASE`]: a few close events in a row (a disc touching two
/// things nearly at once) move nothing.
pub(crate) const RUN: u32 = 64;

/// The origin of a world's working time: an absolute time as the unevaluated
/// sum `hi + lo` (a double-double), whether it ever moved from zero, and the
/// close events in a row so far (see [`RUN`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Clock {
    hi: f64,
    lo: f64,
    moved: bool,
    close: u32,
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
        if self.moved && t.is_finite() {
            // Rounded as the origin moved there would be: an event's time
            // is the start, after the move, of the trajectories it began.
            self.plus(t).0
        } else {
            t
        }
    }

    /// Whether the absolute time of working time `t` may lie beyond
    /// `bound > 0`: `false` only where both `t` and the origin lie below a
    /// quarter of it, so that their sum, rounded, cannot reach it. Lets a
    /// check against a far horizon skip the exact sum on every event.
    #[inline(always)]
    pub(crate) fn may_pass(&self, t: f64, bound: f64) -> bool {
        !(t < 0.25 * bound && self.hi < 0.25 * bound)
    }

    /// The absolute time of working time zero, rounded: what the rounding
    /// of an absolute time is judged from (`push::next_within_rounding`).
    /// Zero while the origin is at zero.
    #[inline(always)]
    pub(crate) fn origin(&self) -> f64 {
        self.hi
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

    /// Whether an event at working time `t`, `gap` after the one before it
    /// (`same`: at one instant with it), should move the origin up to it:
    /// it ends a run of [`RUN`] events each finitely closer to the one
    /// before than [`REBASE`] of the working time.
    #[inline(always)]
    pub(crate) fn moves_for(&mut self, gap: f64, t: f64, same: bool) -> bool {
        if same || !(gap > 0.0 && gap < REBASE * t.abs()) {
            self.close = 0;
            return false;
        }
        self.close += 1;
        if self.close < RUN {
            return false;
        }
        self.close = 0;
        true
    }

    /// The origin moved forward by `by`: the double-double sum, normalised
    /// (`hi` the sum rounded).
    #[inline]
    fn plus(&self, by: f64) -> (f64, f64) {
        // Knuth's two-sum: s + err == hi + by exactly.
        let s = self.hi + by;
        let b = s - self.hi;
        let err = (self.hi - (s - b)) + (by - b);
        let lo = self.lo + err;
        let hi = s + lo;
        (hi, lo - (hi - s))
    }

    /// Moves the origin forward by `by` seconds of working time, exactly
    /// (to the double-double's 106 bits).
    pub(crate) fn advance(&mut self, by: f64) {
        (self.hi, self.lo) = self.plus(by);
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
    fn only_a_run_of_events_finitely_closer_than_the_rebase_fraction_moves_the_origin() {
        let mut c = Clock::default();
        let moves = |c: &mut Clock, gap: f64, same: bool| {
            (0..RUN).filter(|_| c.moves_for(gap, 3.2, same)).count()
        };
        assert_eq!(moves(&mut c, 1e-18, false), 1, "a run of close events");
        assert_eq!(moves(&mut c, 0.0, false), 0, "simultaneous events");
        assert_eq!(moves(&mut c, 1e-18, true), 0, "one instant");
        assert_eq!(moves(&mut c, 1e-3, false), 0, "game-like spacing");
        for _ in 0..RUN - 1 {
            assert!(!c.moves_for(1e-18, 3.2, false));
        }
        assert!(!c.moves_for(1e-3, 3.2, false), "a wide gap ends the run");
        assert!(!c.moves_for(1e-18, 3.2, false));
    }

    #[test]
    fn a_time_far_below_the_bound_never_passes_it_whatever_the_origin() {
        let bound = 1e150;
        let mut c = Clock::default();
        assert!(!c.may_pass(3.2, bound));
        assert!(c.may_pass(0.3 * bound, bound));
        assert!(c.may_pass(f64::NAN, bound));
        c.advance(0.2 * bound);
        // Both below a quarter: the exact sum stays below the bound.
        let t = 0.2499 * bound;
        assert!(!c.may_pass(t, bound));
        assert!(c.absolute(t) < bound);
        c.advance(0.1 * bound);
        assert!(c.may_pass(1.0, bound));
        for t in [0.0, 0.5 * bound, 0.7 * bound] {
            // Where it may, the exact check decides; where it says no, the
            // exact sum agrees.
            assert!(c.may_pass(t, bound) || c.absolute(t) <= bound);
        }
    }

    #[test]
    fn an_event_time_is_the_origin_moved_to_it() {
        let mut c = Clock::default();
        c.advance(3.2);
        c.advance(1.3e-17);
        let t = 7.7e-17;
        let shown = c.absolute(t);
        c.advance(t);
        assert_eq!(c.absolute(0.0), shown);
    }
}
