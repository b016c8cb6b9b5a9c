//! A per-connection token bucket: `rate` messages a second sustained, up to
//! `burst` at once. A message that finds the bucket empty is dropped and
//! answered with `rate-limited`; a connection that keeps flooding is closed.
//! Moves are never dropped: a move pays only once the match refuses it
//! ([`TokenBucket::charge`]), so the bucket limits junk, not play.

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

    /// When a token was last asked for.
    pub fn last_used(&self) -> Instant {
        self.last
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

    /// Charges `n` messages already let through (moves the match then
    /// refused): the tokens may go into debt, down to minus the burst.
    pub fn charge(&mut self, n: u32, now: Instant) {
        let dt = now.saturating_duration_since(self.last).as_secs_f64();
        self.last = now;
        self.tokens =
            ((self.tokens + dt * self.rate).min(self.burst) - f64::from(n)).max(-self.burst);
    }

    /// Whether refused messages have run the bucket into its deepest debt:
    /// a whole burst of junk beyond the limit.
    pub fn bankrupt(&self) -> bool {
        self.tokens <= -self.burst
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

    #[test]
    fn refused_moves_run_the_bucket_into_debt_until_it_is_bankrupt() {
        let t0 = Instant::now();
        let mut b = TokenBucket::new(10.0, 5.0, t0);
        b.charge(7, t0);
        assert!(!b.bankrupt());
        assert!(!b.take(t0), "in debt: other messages are dropped");
        b.charge(100, t0);
        assert!(b.bankrupt());
        // The debt is paid back at the sustained rate.
        b.charge(0, t0 + Duration::from_secs(1));
        assert!(!b.bankrupt());
        assert!(b.take(t0 + Duration::from_millis(1700)));
    }
}
