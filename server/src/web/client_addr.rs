//! Who a request comes from, as every per-address limit counts it.
//!
//! The client address is the TCP peer, unless that peer is one of the
//! reverse proxies the operator trusts (`--trusted-proxy`): then it is
//! read from what the proxies say they forwarded for (`Forwarded`, RFC
//! 7239, or else `X-Forwarded-For`), walking the hops from the right and
//! stopping at the first that is not a trusted proxy. A client can write
//! anything into those headers, but only to the left of what a trusted
//! proxy appends, so the walk never reaches its inventions; and a header
//! from a peer that is not trusted is ignored altogether.
//!
//! The limits then count by the address's [`LimitKey`] ([`limit_key`]).

use crate::limit_key::LimitKey;
use actix_web::{web, HttpRequest};
use ipnet::IpNet;
use std::net::{IpAddr, Ipv6Addr};

/// The networks whose peers are trusted to say whom they forwarded for.
#[derive(Clone, Debug, Default)]
pub struct TrustedProxies(Vec<IpNet>);

impl TrustedProxies {
    /// Trusts every address in `nets`.
    pub fn new(nets: Vec<IpNet>) -> TrustedProxies {
        TrustedProxies(nets)
    }

    fn trusts(&self, ip: IpAddr) -> bool {
        let ip = ip.to_canonical();
        self.0.iter().any(|n| n.contains(&ip))
    }

    /// The client's address behind `peer`: `peer` itself unless it is
    /// trusted, else the right-most of `hops` (the forwarded-for chain,
    /// client first) that is not a trusted proxy; a hop that names no
    /// address (`unknown`, an obfuscated name, junk) ends the walk at the
    /// trusted proxy that reported it.
    pub fn resolve(&self, peer: IpAddr, hops: &[Option<IpAddr>]) -> IpAddr {
        let mut client = peer.to_canonical();
        if !self.trusts(client) {
            return client;
        }
        for hop in hops.iter().rev() {
            match hop {
                Some(ip) => {
                    client = ip.to_canonical();
                    if !self.trusts(client) {
                        return client;
                    }
                }
                None => return client,
            }
        }
        client
    }
}

/// One node of a forwarded-for chain: an address, bare or with a port
/// (`192.0.2.1`, `192.0.2.1:4711`, `[2001:db8::1]:4711`, `2001:db8::1`),
/// optionally quoted; `None` for anything else.
fn node(text: &str) -> Option<IpAddr> {
    let text = text.trim().trim_matches('"');
    if let Some(rest) = text.strip_prefix('[') {
        let (inside, _) = rest.split_once(']')?;
        return inside.parse::<Ipv6Addr>().ok().map(IpAddr::V6);
    }
    if let Ok(ip) = text.parse::<IpAddr>() {
        return Some(ip);
    }
    let (host, port) = text.rsplit_once(':')?;
    port.parse::<u16>().ok()?;
    host.parse::<std::net::Ipv4Addr>().ok().map(IpAddr::V4)
}

/// The `for=` of each element of `Forwarded` header values, in order.
fn forwarded_hops<'a>(values: impl Iterator<Item = &'a str>) -> Vec<Option<IpAddr>> {
    values
        .flat_map(|v| v.split(','))
        .map(|element| {
            element.split(';').find_map(|pair| {
                let (name, value) = pair.split_once('=')?;
                name.trim()
                    .eq_ignore_ascii_case("for")
                    .then(|| node(value))?
            })
        })
        .collect()
}

/// The addresses of `X-Forwarded-For` header values, in order.
fn x_forwarded_for_hops<'a>(values: impl Iterator<Item = &'a str>) -> Vec<Option<IpAddr>> {
    values.flat_map(|v| v.split(',')).map(node).collect()
}

/// The forwarded-for chain of `req`: its `Forwarded` headers if it has
/// any, else its `X-Forwarded-For` headers (unreadable values count as
/// hops without an address).
fn hops(req: &HttpRequest) -> Vec<Option<IpAddr>> {
    let values = |name: &str| {
        req.headers()
            .get_all(name)
            .map(|v| v.to_str().ok())
            .collect::<Vec<_>>()
    };
    let forwarded = values("forwarded");
    if !forwarded.is_empty() {
        if forwarded.iter().any(Option::is_none) {
            return vec![None];
        }
        return forwarded_hops(forwarded.into_iter().flatten());
    }
    let xff = values("x-forwarded-for");
    if xff.iter().any(Option::is_none) {
        return vec![None];
    }
    x_forwarded_for_hops(xff.into_iter().flatten())
}

/// The client address of `req` (`0.0.0.0` when the peer is unknown),
/// behind the proxies the app trusts (a [`TrustedProxies`] in its data;
/// none trusted without one).
pub fn client_ip(req: &HttpRequest) -> IpAddr {
    let peer = req
        .peer_addr()
        .map(|a| a.ip())
        .unwrap_or(IpAddr::from([0, 0, 0, 0]));
    match req.app_data::<web::Data<TrustedProxies>>() {
        Some(trusted) => trusted.resolve(peer, &hops(req)),
        None => peer.to_canonical(),
    }
}

/// The key `req`'s client address counts under in the per-address limits.
pub fn limit_key(req: &HttpRequest) -> LimitKey {
    LimitKey::of(client_ip(req))
}

#[cfg(test)]
mod tests {
    use super::*;
    use actix_web::test::TestRequest;

    fn ip(s: &str) -> IpAddr {
        s.parse().unwrap()
    }

    fn trusting(nets: &[&str]) -> TrustedProxies {
        TrustedProxies::new(
            nets.iter()
                .map(|n| crate::config::parse_trusted_proxy(n).unwrap())
                .collect(),
        )
    }

    fn request(peer: &str, headers: &[(&str, &str)], trusted: &TrustedProxies) -> HttpRequest {
        let mut r = TestRequest::default()
            .peer_addr(std::net::SocketAddr::new(ip(peer), 40000))
            .app_data(web::Data::new(trusted.clone()));
        for (name, value) in headers {
            r = r.append_header((*name, *value));
        }
        r.to_http_request()
    }

    #[test]
    fn forwarding_headers_from_an_untrusted_peer_are_ignored() {
        let trusted = trusting(&["10.0.0.0/8"]);
        for headers in [
            [("x-forwarded-for", "198.51.100.7")],
            [("forwarded", "for=198.51.100.7")],
        ] {
            let req = request("203.0.113.9", &headers, &trusted);
            assert_eq!(client_ip(&req), ip("203.0.113.9"), "{headers:?}");
        }
        // Without any trusted proxy configured, the same.
        let req = request(
            "203.0.113.9",
            &[("x-forwarded-for", "198.51.100.7")],
            &TrustedProxies::default(),
        );
        assert_eq!(client_ip(&req), ip("203.0.113.9"));
    }

    #[test]
    fn behind_a_trusted_proxy_the_client_is_the_rightmost_untrusted_hop() {
        let trusted = trusting(&["10.0.0.0/8", "fd00::/8"]);
        // The client put a spoofed address first; the proxy appended the real one.
        let req = request(
            "10.1.2.3",
            &[("x-forwarded-for", "1.2.3.4, 198.51.100.7, 10.9.9.9")],
            &trusted,
        );
        assert_eq!(client_ip(&req), ip("198.51.100.7"));
        let req = request(
            "fd00::1",
            &[(
                "forwarded",
                "for=1.2.3.4, for=\"[2001:db8:cafe::17]:4711\";proto=https, for=10.0.0.2",
            )],
            &trusted,
        );
        assert_eq!(client_ip(&req), ip("2001:db8:cafe::17"));
        // Forwarded wins over X-Forwarded-For; several header lines chain in order.
        let req = request(
            "10.1.2.3",
            &[
                ("x-forwarded-for", "192.0.2.99"),
                ("forwarded", "for=192.0.2.1:5000"),
                ("forwarded", "for=10.0.0.7"),
            ],
            &trusted,
        );
        assert_eq!(client_ip(&req), ip("192.0.2.1"));
        // No header: the proxy itself.
        assert_eq!(
            client_ip(&request("10.1.2.3", &[], &trusted)),
            ip("10.1.2.3")
        );
    }

    #[test]
    fn an_unreadable_hop_stops_at_the_trusted_proxy_that_reported_it() {
        let trusted = trusting(&["10.0.0.0/8"]);
        for (name, value) in [
            ("forwarded", "for=198.51.100.7, for=unknown"),
            ("forwarded", "for=_hidden"),
            ("forwarded", "proto=https"),
            ("x-forwarded-for", "198.51.100.7, not-an-address"),
        ] {
            let req = request("10.0.0.5", &[(name, value)], &trusted);
            assert_eq!(client_ip(&req), ip("10.0.0.5"), "{value}");
        }
    }

    #[test]
    fn a_trusted_proxy_is_a_network_or_one_address() {
        let t = trusting(&["192.168.0.0/16", "2001:db8::5"]);
        assert!(t.trusts(ip("192.168.7.7")));
        assert!(t.trusts(ip("::ffff:192.168.7.7")));
        assert!(t.trusts(ip("2001:db8::5")));
        assert!(!t.trusts(ip("2001:db8::6")));
    }
}
