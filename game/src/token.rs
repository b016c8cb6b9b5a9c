//! Seat tokens: the secret a player's client presents ([`SeatToken`]) and
//! the only form in which a server keeps it ([`TokenHash`], its SHA-256).
//!
//! A token is 128 random bits, so a plain hash is enough (nothing to guess
//! by brute force, nothing to stretch); a stolen database then holds no
//! token that could take a seat. Presented tokens are checked by hashing
//! them and comparing the hashes in constant time. Neither type prints its
//! secret in `Debug`, so a token never reaches a log by accident.

use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use std::fmt;
use subtle::ConstantTimeEq;

/// A seat token as a client presents it (in its `hello`).
#[derive(Clone, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(transparent)]
pub struct SeatToken(String);

impl SeatToken {
    /// Wraps a token (its text is not checked: a wrong one simply matches
    /// no seat).
    pub fn new(token: impl Into<String>) -> SeatToken {
        SeatToken(token.into())
    }

    /// The token's text, for the one answer that hands it to its owner.
    pub fn expose(&self) -> &str {
        &self.0
    }

    /// The hash a server keeps instead of the token.
    pub fn hash(&self) -> TokenHash {
        TokenHash::of(&self.0)
    }
}

impl fmt::Debug for SeatToken {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("SeatToken(<secret>)")
    }
}

/// The SHA-256 of a seat token.
#[derive(Clone, Copy, Eq)]
pub struct TokenHash([u8; 32]);

/// Stored text that is not a token hash.
#[derive(Debug, thiserror::Error)]
#[error("a token hash is 64 hexadecimal digits, not {0} characters of this")]
pub struct BadTokenHash(usize);

impl TokenHash {
    /// The hash of `token`'s text.
    pub fn of(token: &str) -> TokenHash {
        TokenHash(Sha256::digest(token.as_bytes()).into())
    }

    /// Whether `presented` is the token this is the hash of, in time that
    /// does not depend on where the hashes differ.
    pub fn matches(&self, presented: &SeatToken) -> bool {
        *self == presented.hash()
    }

    /// As 64 lower-case hexadecimal digits (how a store keeps it).
    pub fn to_hex(&self) -> String {
        self.0.iter().map(|b| format!("{b:02x}")).collect()
    }

    /// Reads [`TokenHash::to_hex`]'s form back.
    pub fn from_hex(hex: &str) -> Result<TokenHash, BadTokenHash> {
        let bad = || BadTokenHash(hex.len());
        if hex.len() != 64 || !hex.is_ascii() {
            return Err(bad());
        }
        let mut out = [0u8; 32];
        for (i, byte) in out.iter_mut().enumerate() {
            *byte = u8::from_str_radix(&hex[2 * i..2 * i + 2], 16).map_err(|_| bad())?;
        }
        Ok(TokenHash(out))
    }
}

/// Constant-time: equal hashes compare in the same time as ones that
/// differ in their first byte.
impl PartialEq for TokenHash {
    fn eq(&self, other: &TokenHash) -> bool {
        self.0.ct_eq(&other.0).into()
    }
}

impl fmt::Debug for TokenHash {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "TokenHash({}..)", &self.to_hex()[..8])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_token_matches_its_own_hash_and_no_other() {
        let token = SeatToken::new("540a0bf048fe73e1505aeb84de7f0fcd");
        let hash = token.hash();
        assert!(hash.matches(&token));
        assert!(!hash.matches(&SeatToken::new("540a0bf048fe73e1505aeb84de7f0fce")));
        assert!(!hash.matches(&SeatToken::new("")));
        assert_eq!(hash, TokenHash::of("540a0bf048fe73e1505aeb84de7f0fcd"));
    }

    #[test]
    fn the_hash_is_sha256_of_the_token_text() {
        // SHA-256("abc"), from FIPS 180-2's first example.
        assert_eq!(
            TokenHash::of("abc").to_hex(),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
    }

    #[test]
    fn a_hash_reads_back_from_its_hex_and_junk_is_refused() {
        let hash = TokenHash::of("t");
        assert_eq!(TokenHash::from_hex(&hash.to_hex()).unwrap(), hash);
        assert!(TokenHash::from_hex("t").is_err());
        assert!(TokenHash::from_hex(&"g".repeat(64)).is_err());
        assert!(TokenHash::from_hex(&"é".repeat(32)).is_err());
    }

    #[test]
    fn neither_form_prints_the_secret() {
        let token = SeatToken::new("supersecret");
        assert!(!format!("{token:?}").contains("supersecret"));
        let hash = token.hash();
        assert!(!format!("{hash:?}").contains(&hash.to_hex()));
    }
}
