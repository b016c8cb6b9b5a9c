//! A hosted bot's randomness: one stream per decision, derived from the
//! match's noise secret with domain separation, so that a hosted match
//! replays exactly from its record (which reveals the secret) while the
//! bot learns nothing of the shot noise.
//!
//! The stream's key is the SHA-256 of the label [`DOMAIN`], the secret's
//! 32 bytes and the decision's request (its JSON, which names the side and
//! the whole public view); the stream is ChaCha20 under that key. The
//! match noise is ChaCha20 keyed by the secret itself: a bot would have to
//! invert SHA-256 to get from its stream to the noise.

use game::decide::DecideRequest;
use game::NoiseSecret;
use rand_chacha::rand_core::{RngCore, SeedableRng};
use rand_chacha::ChaCha20Rng;
use sha2::{Digest, Sha256};

/// The label that separates this use of the secret from every other.
pub const DOMAIN: &[u8] = b"chapaev hosted-bot randomness v1";

/// The key of one decision's random stream.
#[derive(Clone, Copy, PartialEq, Eq)]
pub struct DecisionSeed([u8; 32]);

impl DecisionSeed {
    /// The seed of the decision `request` in the match of `secret`.
    pub fn derive(secret: &NoiseSecret, request: &DecideRequest) -> DecisionSeed {
        let mut h = Sha256::new();
        h.update(DOMAIN);
        h.update(secret.bytes());
        h.update(request.to_json().as_bytes());
        DecisionSeed(h.finalize().into())
    }

    /// A seed of these bytes (tests).
    pub const fn from_bytes(bytes: [u8; 32]) -> DecisionSeed {
        DecisionSeed(bytes)
    }

    /// The stream.
    pub(crate) fn stream(&self) -> Stream {
        Stream(ChaCha20Rng::from_seed(self.0))
    }
}

impl std::fmt::Debug for DecisionSeed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("DecisionSeed(<secret>)")
    }
}

/// One decision's random stream.
pub(crate) struct Stream(ChaCha20Rng);

impl Stream {
    pub(crate) fn next_u64(&mut self) -> u64 {
        self.0.next_u64()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use game::{Config, Game, Side};

    fn request(me: Side) -> DecideRequest {
        DecideRequest {
            me,
            view: Game::new(Config::standard(), 1).unwrap().view(),
        }
    }

    #[test]
    fn the_stream_follows_from_secret_and_request_and_differs_from_the_match_noise() {
        let s = NoiseSecret::from_seed(9);
        let a = DecisionSeed::derive(&s, &request(Side::White));
        assert!(a == DecisionSeed::derive(&s, &request(Side::White)));
        assert!(a != DecisionSeed::derive(&s, &request(Side::Black)));
        assert!(a != DecisionSeed::derive(&NoiseSecret::from_seed(10), &request(Side::White)));
        // The noise of shot 0 is ChaCha20 under the secret itself, stream 0.
        let (noise, _) = game::NoiseKey::from(s).words(0);
        let mut plain = ChaCha20Rng::from_seed(*s.bytes());
        assert_eq!(plain.next_u64(), noise);
        assert_ne!(a.stream().next_u64(), noise);
    }
}
