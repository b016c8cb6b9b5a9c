//! `POST /api/simulate`: one shot simulated on any position with exactly
//! the server's physics and rules ([`game::simulate`]), for bots written in
//! a language without the JavaScript or Python package. The computation
//! runs on the blocking pool, and each client address has its own token
//! bucket ([`AddressLimiter`]), so one client cannot take the server's CPU.

use crate::refusal::Refusal;
use crate::web::ratelimit::AddressLimiter;
use crate::web::reply::refused;
use actix_web::{web, HttpRequest, HttpResponse};
use game::SimulateRequest;
use tracing::error;

/// `POST /api/simulate`.
pub async fn handler(
    limiter: web::Data<AddressLimiter>,
    req: HttpRequest,
    bytes: web::Bytes,
) -> HttpResponse {
    if let Err(r) = limiter.check(&req, "too many simulations from this address; slow down") {
        return refused(&r);
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
