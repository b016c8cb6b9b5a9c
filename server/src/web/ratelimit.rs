//! A per-connection token bucket: `rate` messages a second sustained, up to
//! `burst` at once. A message that finds the bucket empty is dropped and
//! answered with `rate-limited`; a connection that keeps flooding is closed.
//! Moves are never dropped: a move pays only once the match refuses it
//! ([`TokenBucket::charge`]), so the bucket limits junk, not play.
//! [`AddressLimiter`] keeps a bucket per client address (simulations,
//! match creation, accounts), in a bounded table that newcomers can
//! always enter.

use crate::limit_key::LimitKey;
use crate::refusal::Refusal;
use actix_web::HttpRequest;
use game::protocol::ErrorCode;
use std::collections::HashMap;
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
    /// When the current run over the limit began: the first drop since the
    /// bucket was last full.
    over_since: Option<Instant>,
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
            over_since: None,
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
        if self.tokens >= self.burst {
            // Quiet long enough to refill in full: any run over the limit ended.
            self.over_since = None;
        }
        if self.tokens >= 1.0 {
            self.tokens -= 1.0;
            self.dropped_in_a_row = 0;
            true
        } else {
            self.dropped_in_a_row += 1;
            self.over_since.get_or_insert(now);
            false
        }
    }

    /// How long the sender has kept above the sustained rate: since the
    /// first message dropped after the bucket was last full (zero when
    /// none was). Slowing down to the rate does not end the run; pausing
    /// until the bucket is full again does.
    pub fn over_limit_for(&self, now: Instant) -> Duration {
        self.over_since
            .map_or(Duration::ZERO, |since| now.saturating_duration_since(since))
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

/// Client addresses remembered at most; past it, buckets idle long
/// enough to be full again are forgotten (a full bucket is the same as no
/// bucket), and if that is not enough, the longest idle ones.
const MAX_ADDRESSES: usize = 10_000;

/// A token bucket per client address ([`LimitKey`]: an IPv6 client's /64).
/// The table is bounded, and a newcomer always gets a bucket: when it is
/// full, the longest idle entries make room (a forgotten address starts
/// again with a full burst, which is the price of never locking out
/// newcomers).
#[derive(Debug)]
pub struct AddressLimiter {
    rate: f64,
    burst: f64,
    capacity: usize,
    buckets: Mutex<HashMap<LimitKey, TokenBucket>>,
}

impl AddressLimiter {
    /// `rate` requests a second sustained per address, `burst` at once.
    pub fn new(rate: f64, burst: f64) -> AddressLimiter {
        AddressLimiter::with_capacity(rate, burst, MAX_ADDRESSES)
    }

    /// The same, remembering at most `capacity` addresses (at least one).
    fn with_capacity(rate: f64, burst: f64, capacity: usize) -> AddressLimiter {
        AddressLimiter {
            rate,
            burst,
            capacity: capacity.max(1),
            buckets: Mutex::new(HashMap::new()),
        }
    }

    /// Takes a token for `req`'s client address, or refuses it with
    /// `rate-limited` and `message`.
    pub fn check(&self, req: &HttpRequest, message: &str) -> Result<(), Refusal> {
        if self.take(crate::web::client_addr::limit_key(req), Instant::now()) {
            Ok(())
        } else {
            Err(Refusal::new(ErrorCode::RateLimited, message))
        }
    }

    /// Takes a token for one request from `key`; `false`: refuse it.
    pub fn take(&self, key: LimitKey, now: Instant) -> bool {
        let mut buckets = self
            .buckets
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        if buckets.len() >= self.capacity && !buckets.contains_key(&key) {
            // A bucket idle for the time it takes to refill is full again.
            let refill = Duration::from_secs_f64(self.burst / self.rate.max(1e-9));
            buckets.retain(|_, b| now.saturating_duration_since(b.last_used()) < refill);
            if buckets.len() >= self.capacity {
                // Still full: forget the longest idle eighth at once, so
                // that the sort is paid once per many newcomers.
                let mut idle: Vec<(Instant, LimitKey)> =
                    buckets.iter().map(|(k, b)| (b.last_used(), *k)).collect();
                idle.sort_unstable_by_key(|(last, _)| *last);
                let forget = (buckets.len() + 1 - self.capacity).max(self.capacity / 8);
                for (_, k) in idle.into_iter().take(forget) {
                    buckets.remove(&k);
                }
            }
        }
        buckets
            .entry(key)
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

    fn key(s: &str) -> LimitKey {
        LimitKey::of(s.parse().unwrap())
    }

    #[test]
    fn each_address_has_its_own_bucket() {
        let limiter = AddressLimiter::new(1.0, 2.0);
        let now = Instant::now();
        let a = key("10.0.0.1");
        let b = key("10.0.0.2");
        assert!(limiter.take(a, now) && limiter.take(a, now));
        assert!(!limiter.take(a, now));
        assert!(limiter.take(b, now));
        assert!(limiter.take(a, now + Duration::from_secs(1)));
    }

    #[test]
    fn one_ipv6_client_shares_one_bucket_across_its_64() {
        let limiter = AddressLimiter::new(1.0, 2.0);
        let now = Instant::now();
        assert!(limiter.take(key("2001:db8:0:1::1"), now));
        assert!(limiter.take(key("2001:db8:0:1::2"), now));
        assert!(!limiter.take(key("2001:db8:0:1:ffff::3"), now));
        assert!(limiter.take(key("2001:db8:0:2::1"), now));
    }

    #[test]
    fn a_full_table_forgets_its_longest_idle_entries_instead_of_refusing_newcomers() {
        // One token per minute: nothing refills during the test.
        let limiter = AddressLimiter::with_capacity(1.0 / 60.0, 1.0, 8);
        let t0 = Instant::now();
        let at = |s: u64| t0 + Duration::from_secs(s);
        for i in 0..8u64 {
            assert!(limiter.take(key(&format!("10.0.0.{i}")), at(i)));
        }
        // A newcomer gets through; the longest idle entry (10.0.0.0) made room.
        assert!(limiter.take(key("192.0.2.1"), at(8)));
        // 10.0.0.7, used lately, keeps its empty bucket: still refused.
        assert!(!limiter.take(key("10.0.0.7"), at(9)));
        // 10.0.0.0 was forgotten: it starts afresh.
        assert!(limiter.take(key("10.0.0.0"), at(10)));
        // A thousand newcomers all get their request through, and the
        // table stays bounded.
        for i in 0..1000u64 {
            let newcomer = key(&format!("2001:db8:{i:x}::1"));
            assert!(limiter.take(newcomer, at(11)), "newcomer {i}");
            let held = limiter.buckets.lock().unwrap().len();
            assert!(held <= 8, "{held} entries");
        }
    }
}
