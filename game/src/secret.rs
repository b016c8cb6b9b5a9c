//! The match's noise secret and its public commitment.
//!
//! Every match of the current record format draws its execution noise from
//! a 256-bit [`NoiseSecret`] that only the server knows while the match is
//! played. Before the first shot the server publishes the secret's
//! [`NoiseCommitment`] — the SHA-256 of its 32 bytes, as 64 lowercase hex
//! digits — in the match's state and in the listing; when the match is
//! over the record reveals the secret itself, as 64 lowercase hex digits.
//! Anyone can then check, in any language, that the revealed secret is the
//! one committed to (hash it) and that every shot's noise came from it
//! ([`crate::verify`]). The secret never appears in `Debug` output, so it
//! cannot reach a log by accident.
//!
//! A secret is 32 bytes from the operating system's generator on a server
//! (which makes it unguessable). Local games that must be reproducible
//! from a number — tournaments, tests — derive it from a public seed
//! ([`NoiseSecret::from_seed`]): anyone who knows that seed knows the
//! noise, which is exactly what a seeded local game is for.

use serde::{Deserialize, Deserializer, Serialize, Serializer};
use sha2::{Digest, Sha256};
use std::fmt;

/// The number of bytes in a secret (256 bits).
pub const SECRET_BYTES: usize = 32;

/// Text that is not 64 hexadecimal digits.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum HexError {
    #[error("expected 64 lowercase hexadecimal digits, got {0} characters")]
    Length(usize),
    #[error("expected lowercase hexadecimal digits: {0}")]
    Digits(#[from] hex::FromHexError),
    #[error("expected lowercase hexadecimal digits, got uppercase ones")]
    Uppercase,
}

/// Reads 64 lowercase hex digits.
fn from_hex(text: &str) -> Result<[u8; 32], HexError> {
    if text.len() != 2 * SECRET_BYTES {
        return Err(HexError::Length(text.chars().count()));
    }
    if text.bytes().any(|b| b.is_ascii_uppercase()) {
        return Err(HexError::Uppercase);
    }
    let mut out = [0u8; SECRET_BYTES];
    hex::decode_to_slice(text, &mut out)?;
    Ok(out)
}

/// The secret a match's noise is drawn from.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct NoiseSecret([u8; SECRET_BYTES]);

impl NoiseSecret {
    /// A secret of these bytes (a server fills them from the operating
    /// system's generator).
    pub const fn from_bytes(bytes: [u8; SECRET_BYTES]) -> NoiseSecret {
        NoiseSecret(bytes)
    }

    /// A secret derived from a public 64-bit seed, for local games that
    /// must be reproducible from a number (tournaments, tests): the
    /// SHA-256 of `"chapaev noise secret from seed"` followed by the seed's
    /// eight bytes, little-endian. Never for a live match: whoever knows
    /// the seed knows the noise.
    pub fn from_seed(seed: u64) -> NoiseSecret {
        let mut h = Sha256::new();
        h.update(b"chapaev noise secret from seed");
        h.update(seed.to_le_bytes());
        NoiseSecret(h.finalize().into())
    }

    /// The secret's bytes (the ChaCha20 key).
    pub fn bytes(&self) -> &[u8; SECRET_BYTES] {
        &self.0
    }

    /// The public commitment to this secret.
    pub fn commitment(&self) -> NoiseCommitment {
        NoiseCommitment(Sha256::digest(self.0).into())
    }

    /// The secret as 64 lowercase hex digits (how records reveal it and
    /// stores keep it).
    pub fn to_hex(&self) -> String {
        hex::encode(self.0)
    }

    /// Reads [`NoiseSecret::to_hex`]'s form back.
    pub fn from_hex(text: &str) -> Result<NoiseSecret, HexError> {
        from_hex(text).map(NoiseSecret)
    }
}

impl fmt::Debug for NoiseSecret {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("NoiseSecret(<secret>)")
    }
}

/// The SHA-256 of a [`NoiseSecret`]'s bytes: published before the first
/// shot, it binds the server to the secret it reveals at the end.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct NoiseCommitment([u8; 32]);

impl NoiseCommitment {
    /// As 64 lowercase hex digits (how the protocol and records carry it).
    pub fn to_hex(&self) -> String {
        hex::encode(self.0)
    }

    /// Reads [`NoiseCommitment::to_hex`]'s form back.
    pub fn from_hex(text: &str) -> Result<NoiseCommitment, HexError> {
        from_hex(text).map(NoiseCommitment)
    }

    /// Whether `secret` is the secret committed to.
    pub fn opens_to(&self, secret: &NoiseSecret) -> bool {
        secret.commitment() == *self
    }
}

impl fmt::Debug for NoiseCommitment {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "NoiseCommitment({})", self.to_hex())
    }
}

impl fmt::Display for NoiseCommitment {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.to_hex())
    }
}

/// Both travel as lowercase hex strings.
macro_rules! hex_serde {
    ($ty:ty, $what:literal) => {
        impl Serialize for $ty {
            fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.serialize_str(&self.to_hex())
            }
        }
        impl<'de> Deserialize<'de> for $ty {
            fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                let text = String::deserialize(d)?;
                <$ty>::from_hex(&text)
                    .map_err(|e| serde::de::Error::custom(format!("{}: {e}", $what)))
            }
        }
        impl schemars::JsonSchema for $ty {
            fn schema_name() -> std::borrow::Cow<'static, str> {
                stringify!($ty).into()
            }
            fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
                schemars::json_schema!({
                    "type": "string",
                    "pattern": "^[0-9a-f]{64}$",
                    "description": $what
                })
            }
        }
    };
}
hex_serde!(
    NoiseSecret,
    "the match's noise secret: 32 bytes as lowercase hex"
);
hex_serde!(
    NoiseCommitment,
    "SHA-256 of the noise secret's 32 bytes, as lowercase hex"
);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_commitment_is_the_sha256_of_the_secrets_bytes_in_lowercase_hex() {
        // SHA-256 of 32 zero bytes, as any sha256sum computes it.
        let zero = NoiseSecret::from_bytes([0; 32]);
        assert_eq!(
            zero.commitment().to_hex(),
            "66687aadf862bd776c8fc18b8e9f8e20089714856ee233b3902a591d0d5f2925"
        );
        assert!(zero.commitment().opens_to(&zero));
        assert!(!zero
            .commitment()
            .opens_to(&NoiseSecret::from_bytes([1; 32])));
    }

    #[test]
    fn secrets_and_commitments_round_trip_through_hex_and_json() {
        let s = NoiseSecret::from_seed(42);
        assert_eq!(NoiseSecret::from_hex(&s.to_hex()), Ok(s));
        let json = serde_json::to_string(&s.commitment()).unwrap();
        assert_eq!(json, format!("\"{}\"", s.commitment().to_hex()));
        let back: NoiseCommitment = serde_json::from_str(&json).unwrap();
        assert_eq!(back, s.commitment());
    }

    #[test]
    fn malformed_hex_is_refused_with_a_clear_error() {
        assert_eq!(NoiseSecret::from_hex("ab"), Err(HexError::Length(2)));
        assert_eq!(
            NoiseSecret::from_hex(&"AB".repeat(32)),
            Err(HexError::Uppercase)
        );
        assert!(matches!(
            NoiseSecret::from_hex(&"zz".repeat(32)),
            Err(HexError::Digits(_))
        ));
        let err = serde_json::from_str::<NoiseSecret>("\"12\"").unwrap_err();
        assert!(err.to_string().contains("64 lowercase"), "{err}");
    }

    #[test]
    fn a_secret_never_prints_itself() {
        let s = NoiseSecret::from_seed(1);
        assert_eq!(format!("{s:?}"), "NoiseSecret(<secret>)");
    }

    #[test]
    fn secrets_from_different_seeds_differ() {
        assert_ne!(NoiseSecret::from_seed(1), NoiseSecret::from_seed(2));
        assert_eq!(NoiseSecret::from_seed(7), NoiseSecret::from_seed(7));
    }
}
