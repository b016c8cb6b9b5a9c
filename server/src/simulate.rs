//! `POST /api/simulate`: one shot simulated on any position with exactly
//! the server's physics and rules ([`game::simulate`]), for bots written in
//! a language without the JavaScript or Python package. The computation
//! runs on the blocking pool, and each client address has its own token
//! bucket ([`AddressLimiter`]), so one client cannot take the server's CPU.

use crate::http::refused;
use crate::ratelimit::TokenBucket;
use crate::refusal::Refusal;
use actix_web::{web, HttpRequest, HttpResponse};
use game::protocol::ErrorCode;
use game::SimulateRequest;
use std::collections::HashMap;
use std::net::IpAddr;
use std::sync::Mutex;
use std::time::{Duration, Instant};
use tracing::error;

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

/// `POST /api/simulate`.
pub async fn handler(
    limiter: web::Data<AddressLimiter>,
    req: HttpRequest,
    bytes: web::Bytes,
) -> HttpResponse {
    let addr = req
        .peer_addr()
        .map(|a| a.ip())
        .unwrap_or(IpAddr::from([0, 0, 0, 0]));
    if !limiter.take(addr, Instant::now()) {
        return refused(&Refusal::new(
            ErrorCode::RateLimited,
            "too many simulations from this address; slow down",
        ));
    }
    let request: SimulateRequest = match game::protocol::read(&bytes) {
        Ok(r) => r,
        Err(e) => return refused(&Refusal::new(e.code, e.message)),
    };
    match web::block(move || request.run()).await {
        Ok(Ok(sim)) => match serde_json::to_string(&sim) {
            Ok(text) => HttpResponse::Ok()
                .content_type("application/json")
                .body(text),
            Err(e) => {
                error!(error = %e, "serialising a simulation failed");
                refused(&Refusal::internal())
            }
        },
        Ok(Err(e)) => refused(&Refusal::new(e.code(), e.to_string())),
        Err(e) => {
            error!(error = %e, "a simulation's task failed");
            refused(&Refusal::internal())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
