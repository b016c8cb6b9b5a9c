//! The clock a bot's deadline ([`crate::Context::deadline`]) and a
//! search's time budget are read on. Natively it is
//! [`std::time::Instant`]. In the browser (`wasm32-unknown-unknown`)
//! std's clock panics, and this crate reaches no JavaScript of its own, so
//! the page hands it a clock once ([`set_source`]: seconds from any
//! fixed start, such as the page's own timer): [`PageInstant`], read
//! through it. Until a page sets one, its time stands still: a deadline
//! never passes, and a search does exactly its fixed work (its samples),
//! which is then its whole budget.

use std::ops::Add;
use std::sync::OnceLock;
use std::time::Duration;

/// The instant type bots read: the platform's own clock natively, the
/// page's in the browser.
#[cfg(not(target_arch = "wasm32"))]
pub type Instant = std::time::Instant;

/// The instant type bots read: the platform's own clock natively, the
/// page's in the browser.
#[cfg(target_arch = "wasm32")]
pub type Instant = PageInstant;

/// The page's clock: seconds since the start of the source's choosing.
static SOURCE: OnceLock<fn() -> f64> = OnceLock::new();

/// Sets the page's clock (seconds since a fixed start, never going back);
/// `false` if one was set already (the first stays).
pub fn set_source(now: fn() -> f64) -> bool {
    SOURCE.set(now).is_ok()
}

/// An instant on the page's clock ([`set_source`]); without one, always
/// the same instant.
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub struct PageInstant(f64);

impl PageInstant {
    /// Now, on the page's clock.
    pub fn now() -> PageInstant {
        let secs = SOURCE.get().map_or(0.0, |now| now());
        PageInstant(if secs.is_finite() { secs } else { 0.0 })
    }

    /// Time from `earlier` to this instant (zero if `earlier` is later).
    pub fn saturating_duration_since(&self, earlier: PageInstant) -> Duration {
        Duration::try_from_secs_f64(self.0 - earlier.0).unwrap_or(Duration::ZERO)
    }

    /// Time since this instant.
    pub fn elapsed(&self) -> Duration {
        PageInstant::now().saturating_duration_since(*self)
    }
}

impl Add<Duration> for PageInstant {
    type Output = PageInstant;
    fn add(self, d: Duration) -> PageInstant {
        PageInstant(self.0 + d.as_secs_f64())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn page_instants_measure_the_time_between_them_and_never_go_negative() {
        let a = PageInstant(10.0);
        let b = a + Duration::from_millis(1500);
        assert_eq!(b.saturating_duration_since(a), Duration::from_millis(1500));
        assert_eq!(a.saturating_duration_since(b), Duration::ZERO);
        assert_eq!(
            PageInstant(f64::NAN).saturating_duration_since(a),
            Duration::ZERO
        );
    }

    #[test]
    fn the_page_clock_reads_the_source_it_was_given_and_keeps_the_first() {
        fn twelve() -> f64 {
            12.5
        }
        fn other() -> f64 {
            99.0
        }
        // This test is the only one in the crate that sets a source.
        assert!(set_source(twelve));
        assert!(!set_source(other));
        assert_eq!(PageInstant::now(), PageInstant(12.5));
        assert_eq!(PageInstant(12.0).elapsed(), Duration::from_millis(500));
    }
}
