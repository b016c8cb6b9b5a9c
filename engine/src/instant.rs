//! One instant up to rounding: when two event times are the same moment.
//!
//! Events computed from different pairs of bodies land on times that differ
//! in their last few bits even where the physics has them simultaneous. The
//! event loop (`world`) counts such events as one instant (what its
//! livelock guards in `limits` watch), and the pushing contacts
//! (`push`) take a bounce due within that rounding as no bounce at
//! all. Both read the one test here, so they agree on what an instant is.

/// Whether `t` is the same instant as `t0` up to rounding: within about a
/// thousand units in the last place of the later time.
pub(crate) fn same_instant(t0: f64, t: f64) -> bool {
    t - t0 <= 2.5e-13 * t.abs().max(t0.abs())
}

#[cfg(test)]
mod tests {
    use super::same_instant;

    #[test]
    fn times_a_few_units_in_the_last_place_apart_are_one_instant() {
        let t: f64 = 1.0;
        let later = f64::from_bits(t.to_bits() + 8);
        assert!(same_instant(t, later));
        assert!(same_instant(t, t));
    }

    #[test]
    fn times_a_microsecond_apart_are_two_instants() {
        assert!(!same_instant(1.0, 1.0 + 1e-6));
    }
}
