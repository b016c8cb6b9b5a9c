//! Cross-site requests refused: a page on another site must not create,
//! join or play matches in its visitor's browser. Browsers name the page's
//! origin in an `Origin` header on every POST and WebSocket opening; the
//! server accepts its own origin (the scheme and the `Host` the request was
//! sent to), any listed with `--allowed-origins` (a proxy's public address,
//! say), on a node of a cluster the origins of its live nodes' public URLs
//! (`--public-url`: a page one node served opens its match's socket on the
//! node that plays it), and requests without the header (bots, curl: no
//! browser, no visitor to abuse). Reads (`GET`, but the WebSocket) are not
//! checked: a foreign page cannot read their answers anyway.

use crate::play::hub::Hub;
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

/// The origin (scheme, host and port, lower case) of a URL such as
/// `https://Play.example/n/node-1`: `https://play.example`.
fn origin_of(url: &str) -> Option<String> {
    let url = url.trim().to_ascii_lowercase();
    let (scheme, rest) = url.split_once("://")?;
    if scheme != "http" && scheme != "https" {
        return None;
    }
    let authority = rest.split(['/', '?', '#']).next().unwrap_or_default();
    (!authority.is_empty()).then(|| format!("{scheme}://{authority}"))
}

/// Whether `origin` is that of one of the cluster's public URLs `urls`.
fn of_the_cluster(origin: &str, urls: &[String]) -> bool {
    let Some(origin) = origin_of(origin) else {
        return false;
    };
    urls.iter()
        .any(|u| origin_of(u).as_deref() == Some(origin.as_str()))
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
        let origin = header(header::ORIGIN).map(str::to_string);
        let mut allowed = match req.app_data::<web::Data<Origins>>() {
            Some(origins) => origins.allows(origin.as_deref(), header(header::HOST)),
            None => true,
        };
        if let (false, Some(origin), Some(hub)) =
            (allowed, &origin, req.app_data::<web::Data<Hub>>())
        {
            allowed = of_the_cluster(origin, &hub.cluster_urls().await);
        }
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

    #[test]
    fn a_page_of_another_node_of_the_cluster_is_allowed_by_its_public_urls_origin() {
        let urls = [
            "https://Play.example/n/node-1".to_string(),
            "http://10.0.0.5:8080".to_string(),
        ];
        assert!(of_the_cluster("https://play.example", &urls));
        assert!(of_the_cluster("http://10.0.0.5:8080/", &urls));
        assert!(!of_the_cluster("http://play.example", &urls));
        assert!(!of_the_cluster("http://10.0.0.5:8081", &urls));
        assert!(!of_the_cluster("null", &urls));
        assert!(!of_the_cluster("https://play.example.evil", &urls));
        assert_eq!(origin_of("ftp://x"), None);
        assert_eq!(origin_of("https://"), None);
    }
}
