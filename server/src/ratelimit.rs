//! A per-connection token bucket: `rate` messages a second sustained, up to
//! `burst` at once. A message that finds the bucket empty is dropped and
//! answered with `rate-limited`; a connection that keeps flooding is closed.

use std::time::Instant;

/// A token bucket.
#[derive(Clone, Debug)]
pub struct TokenBucket {
    rate: f64,
    burst: f64,
    tokens: f64,
    last: Instant,
    /// Messages dropped since the bucket last had a token to spare.
    pub dropped_in_a_row: u32,
}

impl TokenBucket {
    pub fn new(rate: f64, burst: f64, now: Instant) -> TokenBucket {
        let burst = burst.max(1.0);
        TokenBucket {
            rate: rate.max(0.0),
            burst,
            tokens: burst,
            last: now,
            dropped_in_a_row: 0,
        }
    }

    /// Takes a token for one message; `false`: drop it.
    pub fn take(&mut self, now: Instant) -> bool {
        let dt = now.saturating_duration_since(self.last).as_secs_f64();
        self.last = now;
        self.tokens = (self.tokens + dt * self.rate).min(self.burst);
        if self.tokens >= 1.0 {
            self.tokens -= 1.0;
            self.dropped_in_a_row = 0;
            true
        } else {
            self.dropped_in_a_row += 1;
            false
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn a_burst_passes_then_the_rate_refills() {
        let t0 = Instant::now();
        let mut b = TokenBucket::new(10.0, 5.0, t0);
        assert!((0..5).all(|_| b.take(t0)));
        assert!(!b.take(t0));
        assert_eq!(b.dropped_in_a_row, 1);
        assert!(b.take(t0 + Duration::from_millis(100)));
        assert_eq!(b.dropped_in_a_row, 0);
        assert!(!b.take(t0 + Duration::from_millis(100)));
        // Refills no higher than the burst.
        let later = t0 + Duration::from_secs(60);
        assert!((0..5).all(|_| b.take(later)));
        assert!(!b.take(later));
    }
}
