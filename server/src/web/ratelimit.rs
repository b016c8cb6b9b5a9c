//! A per-connection token bucket: `rate` messages a second sustained, up to
//! `burst` at once. A message that finds the bucket empty is dropped and
//! answered with `rate-limited`; a connection that keeps flooding is closed.
//! Moves are never dropped: a move pays only once the match refuses it
//! ([`TokenBucket::charge`]), so the bucket limits junk, not play.
//! [`AddressLimiter`] keeps a bucket per client address (simulations,
//! match creation).

use crate::refusal::Refusal;
use actix_web::HttpRequest;
use game::protocol::ErrorCode;
use std::collections::HashMap;
use std::net::IpAddr;
use std::sync::Mutex;
use std::time::{Duration, Instant};

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

/// The client address of a request (the TCP peer; `0.0.0.0` when unknown),
/// which the per-address limits count by.
pub fn client_ip(req: &HttpRequest) -> IpAddr {
    req.peer_addr()
        .map(|a| a.ip())
        .unwrap_or(IpAddr::from([0, 0, 0, 0]))
}

/// Addresses remembered at most; past it, buckets idle for a while are
/// forgotten (a full bucket is the same as no bucket).
const MAX_ADDRESSES: usize = 10_000;

/// A token bucket per client address.
#[derive(Debug)]
pub struct AddressLimiter {
    rate: f64,
    burst: f64,
    buckets: Mutex<HashMap<IpAddr, TokenBucket>>,
}

impl AddressLimiter {
    /// `rate` requests a second sustained per address, `burst` at once.
    pub fn new(rate: f64, burst: f64) -> AddressLimiter {
        AddressLimiter {
            rate,
            burst,
            buckets: Mutex::new(HashMap::new()),
        }
    }

    /// Takes a token for `req`'s client address, or refuses it with
    /// `rate-limited` and `message`.
    pub fn check(&self, req: &HttpRequest, message: &str) -> Result<(), Refusal> {
        if self.take(client_ip(req), Instant::now()) {
            Ok(())
        } else {
            Err(Refusal::new(ErrorCode::RateLimited, message))
        }
    }

    /// Takes a token for one request from `addr`; `false`: refuse it.
    pub fn take(&self, addr: IpAddr, now: Instant) -> bool {
        let mut buckets = self
            .buckets
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        if buckets.len() >= MAX_ADDRESSES && !buckets.contains_key(&addr) {
            // A bucket idle for the time it takes to refill is full again.
            let refill = Duration::from_secs_f64(self.burst / self.rate.max(1e-9));
            buckets.retain(|_, b| now.saturating_duration_since(b.last_used()) < refill);
            if buckets.len() >= MAX_ADDRESSES {
                return false;
            }
        }
        buckets
            .entry(addr)
            .or_insert_with(|| TokenBucket::new(self.rate, self.burst, now))
            .take(now)
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

    #[test]
    fn each_address_has_its_own_bucket() {
        let limiter = AddressLimiter::new(1.0, 2.0);
        let now = Instant::now();
        let a = IpAddr::from([10, 0, 0, 1]);
        let b = IpAddr::from([10, 0, 0, 2]);
        assert!(limiter.take(a, now) && limiter.take(a, now));
        assert!(!limiter.take(a, now));
        assert!(limiter.take(b, now));
        assert!(limiter.take(a, now + Duration::from_secs(1)));
    }
}
