//! The shapes every HTTP answer shares: a refusal as a JSON error with its
//! status, a JSON body, a JSON request body read (empty reads as `{}`),
//! actix-web's own 413 given the same JSON body, the host a request was
//! addressed to, and the per-address limit on creating matches.

use crate::refusal::{HttpStatus, Refusal};
use crate::web::ratelimit::AddressLimiter;
use actix_web::http::StatusCode;
use actix_web::{HttpRequest, HttpResponse};
use game::protocol::ErrorCode;
use serde::{Deserialize, Serialize};
use tracing::error;

/// The per-address limit on creating matches (`POST /api/matches` and
/// `POST /api/exhibitions` share it).
#[derive(Debug)]
pub struct Creations(pub AddressLimiter);

impl Creations {
    /// Refuses a creation from this request's address past the limit.
    pub(crate) fn check(&self, req: &HttpRequest) -> Result<(), Refusal> {
        self.0
            .check(req, "too many matches created from this address; slow down")
    }
}

/// Gives a `413 Payload Too Large` that actix-web produced itself (a body
/// over the limit, refused before any handler ran) the JSON error body every
/// other refusal has; a 413 that already is JSON passes unchanged.
pub(crate) fn too_large_as_json<B>(
    res: actix_web::dev::ServiceResponse<B>,
    limit: usize,
) -> actix_web::Result<actix_web::middleware::ErrorHandlerResponse<B>> {
    use actix_web::middleware::ErrorHandlerResponse;
    let json = res
        .response()
        .headers()
        .get(actix_web::http::header::CONTENT_TYPE)
        .is_some_and(|v| v.as_bytes().starts_with(b"application/json"));
    if json {
        return Ok(ErrorHandlerResponse::Response(res.map_into_left_body()));
    }
    let (req, _) = res.into_parts();
    let body = refused(&Refusal::new(
        ErrorCode::MessageTooLarge,
        format!("bodies are at most {limit} bytes"),
    ));
    Ok(ErrorHandlerResponse::Response(
        actix_web::dev::ServiceResponse::new(req, body).map_into_right_body(),
    ))
}

/// A refusal as an HTTP error response with a JSON body.
pub(crate) fn refused(r: &Refusal) -> HttpResponse {
    let status = StatusCode::from_u16(r.http_status()).unwrap_or(StatusCode::BAD_REQUEST);
    HttpResponse::build(status)
        .content_type("application/json")
        .body(r.to_message().to_json())
}

pub(crate) fn json<T: Serialize>(status: StatusCode, body: &T) -> HttpResponse {
    match serde_json::to_string(body) {
        Ok(text) => HttpResponse::build(status)
            .content_type("application/json")
            .body(text),
        Err(e) => {
            error!(error = %e, "serialising a response failed");
            refused(&Refusal::internal())
        }
    }
}

/// Reads a JSON body (an empty body reads as `{}`).
pub(crate) fn read_body<T: for<'de> Deserialize<'de>>(bytes: &[u8]) -> Result<T, Refusal> {
    let text = if bytes.iter().all(u8::is_ascii_whitespace) {
        &b"{}"[..]
    } else {
        bytes
    };
    game::protocol::read(text).map_err(|e| Refusal::new(e.code, e.message))
}

/// The host (and port) the request was addressed to, as the examples on
/// the API page should name it: the `Host` header when it is a plain host
/// name or address, else `localhost:8080`.
pub(crate) fn public_host(req: &HttpRequest) -> String {
    let info = req.connection_info();
    let host = info.host();
    let plain = !host.is_empty()
        && host.len() <= 255
        && host
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '.' | '-' | ':' | '[' | ']'));
    if plain {
        host.to_string()
    } else {
        "localhost:8080".to_string()
    }
}
