//! Cross-site requests refused: a page on another site must not create,
//! join or play matches in its visitor's browser. Browsers name the page's
//! origin in an `Origin` header on every POST and WebSocket opening; the
//! server accepts its own origin (the scheme and the `Host` the request was
//! sent to), any listed with `--allowed-origins` (a proxy's public address,
//! say), and requests without the header (bots, curl: no browser, no
//! visitor to abuse). Reads (`GET`, but the WebSocket) are not checked: a
//! foreign page cannot read their answers anyway.

use crate::refusal::Refusal;
use crate::web::reply::refused;
use actix_web::body::MessageBody;
use actix_web::dev::{ServiceRequest, ServiceResponse};
use actix_web::http::{header, Method};
use actix_web::middleware::Next;
use actix_web::web;
use game::protocol::ErrorCode;

/// The origins allowed besides the server's own.
#[derive(Clone, Debug, Default)]
pub struct Origins {
    allowed: Vec<String>,
}

impl Origins {
    /// Origins such as `https://chapaev.example` (no trailing slash).
    pub fn new(allowed: &[String]) -> Origins {
        Origins {
            allowed: allowed
                .iter()
                .map(|o| o.trim().trim_end_matches('/').to_ascii_lowercase())
                .filter(|o| !o.is_empty())
                .collect(),
        }
    }

    /// Whether a request with these headers may act.
    pub fn allows(&self, origin: Option<&str>, host: Option<&str>) -> bool {
        let Some(origin) = origin else {
            return true;
        };
        let origin = origin.trim().trim_end_matches('/').to_ascii_lowercase();
        let authority = origin
            .strip_prefix("http://")
            .or_else(|| origin.strip_prefix("https://"));
        let own = match (authority, host) {
            (Some(a), Some(h)) => a == h.trim().to_ascii_lowercase(),
            _ => false,
        };
        own || self.allowed.contains(&origin)
    }
}

/// The middleware: refuses a POST or a WebSocket opening from a foreign
/// origin with `403 forbidden-origin`.
pub async fn check(
    req: ServiceRequest,
    next: Next<impl MessageBody + 'static>,
) -> Result<ServiceResponse<impl MessageBody>, actix_web::Error> {
    let checked = req.method() != Method::GET || req.path() == "/ws";
    if checked {
        let header = |name| {
            req.headers()
                .get(name)
                .and_then(|v: &header::HeaderValue| v.to_str().ok())
        };
        let allowed = match req.app_data::<web::Data<Origins>>() {
            Some(origins) => origins.allows(header(header::ORIGIN), header(header::HOST)),
            None => true,
        };
        if !allowed {
            let r = Refusal::new(
                ErrorCode::ForbiddenOrigin,
                "requests from another site's pages are refused",
            );
            return Ok(req.into_response(refused(&r)).map_into_right_body());
        }
    }
    next.call(req)
        .await
        .map(ServiceResponse::map_into_left_body)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_own_origin_a_listed_one_and_no_origin_are_allowed_and_nothing_else() {
        let o = Origins::new(&["https://chapaev.example/".to_string()]);
        let host = Some("127.0.0.1:8080");
        assert!(o.allows(None, host));
        assert!(o.allows(Some("http://127.0.0.1:8080"), host));
        assert!(o.allows(Some("https://Chapaev.example"), host));
        assert!(!o.allows(Some("http://evil.example"), host));
        assert!(!o.allows(Some("null"), host));
        assert!(!o.allows(Some("http://127.0.0.1:8081"), host));
        assert!(!o.allows(Some("http://127.0.0.1:8080"), None));
    }
}
