//! What the per-address limits count by (connections per address, match
//! and account creations, simulations): an IPv4 address, or the /64
//! network of an IPv6 one — what one subscriber is handed, and can pick
//! any of its 2^64 addresses from. An IPv4 address mapped into IPv6
//! counts as the IPv4 address. Which address a request comes from is the
//! web layer's business (`web::client_addr`).

use std::net::{IpAddr, Ipv6Addr};

/// The key one client address counts under.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct LimitKey(IpAddr);

impl LimitKey {
    /// The key `ip` counts under.
    pub fn of(ip: IpAddr) -> LimitKey {
        match ip.to_canonical() {
            IpAddr::V4(v4) => LimitKey(IpAddr::V4(v4)),
            IpAddr::V6(v6) => {
                let network = u128::from(v6) & !((1u128 << 64) - 1);
                LimitKey(IpAddr::V6(Ipv6Addr::from(network)))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(s: &str) -> LimitKey {
        LimitKey::of(s.parse().unwrap())
    }

    #[test]
    fn ipv6_clients_are_counted_by_their_64_and_mapped_ipv4_as_ipv4() {
        assert_eq!(
            key("2001:db8:1:2:aaaa::1"),
            key("2001:db8:1:2:ffff:ffff:ffff:ffff")
        );
        assert_ne!(key("2001:db8:1:2::1"), key("2001:db8:1:3::1"));
        assert_eq!(key("::ffff:192.0.2.1"), key("192.0.2.1"));
        assert_ne!(key("192.0.2.1"), key("192.0.2.2"));
    }
}
