//! Secrets and identifiers from the operating system's random source: seat
//! tokens (128 bits, hex; the server keeps only their hashes, see
//! [`game::token`]), match ids (64 bits, hex) and the noise secrets of
//! matches (256 bits, see [`game::secret`]).

/// The OS random source failed.
#[derive(Debug, thiserror::Error)]
#[error("the operating system's random source failed: {0}")]
pub struct RandomError(String);

fn random_bytes<const N: usize>() -> Result<[u8; N], RandomError> {
    let mut buf = [0u8; N];
    getrandom::fill(&mut buf).map_err(|e| RandomError(e.to_string()))?;
    Ok(buf)
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// A seat token: 128 random bits as 32 hex digits.
pub fn seat_token() -> Result<SeatToken, RandomError> {
    Ok(SeatToken::new(hex(&random_bytes::<16>()?)))
}

/// A match id: 64 random bits as 16 hex digits.
pub fn match_id() -> Result<String, RandomError> {
    Ok(hex(&random_bytes::<8>()?))
}

/// A match's noise secret: 256 random bits, committed to before the first
/// shot and revealed when the match is over.
pub fn noise_secret() -> Result<NoiseSecret, RandomError> {
    Ok(NoiseSecret::from_bytes(random_bytes::<32>()?))
}

/// 64 random bits, to seed a generator of the server's own (a computer
/// level's hand, the lobby's colour draws): never the match's noise.
pub fn seed() -> Result<u64, RandomError> {
    Ok(u64::from_le_bytes(random_bytes::<8>()?))
}

pub use game::token::{SeatToken, TokenHash};
use game::NoiseSecret;

/// Whether `s` looks like a match id (so junk never reaches the store).
pub fn is_match_id(s: &str) -> bool {
    !s.is_empty() && s.len() <= 64 && s.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'-')
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_carry_128_random_bits_and_differ() {
        let a = seat_token().unwrap();
        let b = seat_token().unwrap();
        assert_eq!(a.expose().len(), 32);
        assert!(a.expose().bytes().all(|c| c.is_ascii_hexdigit()));
        assert_ne!(a, b);
        assert_eq!(match_id().unwrap().len(), 16);
    }

    #[test]
    fn match_ids_are_short_and_plain() {
        assert!(is_match_id("0123abcd"));
        assert!(!is_match_id("../x"));
        assert!(!is_match_id(""));
    }
}
