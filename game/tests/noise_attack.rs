//! The attack that broke the first noise scheme, kept as a regression test.
//!
//! Records of formats 1–3 drew each shot's noise with SplitMix64 from a
//! 64-bit match seed. A shot's `aimed` and `played` velocities are public
//! (the `shot-played` message, the film), and they give away the two
//! standard normal numbers of its draw, hence most of the 53-bit uniforms
//! behind them. SplitMix64's output function can be inverted, so a bot
//! that searched the few bits it could not read recovered the generator's
//! state and the match seed from one shot, then knew every later shot's
//! noise in advance. That attack is [`recover_seed`] below: it must still
//! break the old scheme (so it is a real attack, not a strawman), and it
//! must find nothing against the ChaCha20 secret of current matches.

use game::noise::{NoiseDraw, NoiseKey, SplitMix64};
use game::{Config, Game, NoiseSecret, PieceId, Shot, ShotOutcome, Side};
use glam::DVec2;

const GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;
const SHOT_MIX: u64 = 0xD1B5_4A32_D192_ED03;
const C1: u64 = 0xBF58_476D_1CE4_E5B9;
const C2: u64 = 0x94D0_49BB_1331_11EB;

/// The multiplicative inverse of odd `c` modulo 2^64 (Newton's iteration).
fn inverse(c: u64) -> u64 {
    let mut x = c;
    for _ in 0..6 {
        x = x.wrapping_mul(2u64.wrapping_sub(c.wrapping_mul(x)));
    }
    x
}

/// Undoes `x ^= x >> shift`.
fn unshift(mut y: u64, shift: u32) -> u64 {
    let mut x = y;
    while y != 0 {
        y >>= shift;
        x ^= y;
    }
    x
}

/// The inverse of SplitMix64's output function.
fn unmix(z: u64) -> u64 {
    let z = unshift(z, 31).wrapping_mul(inverse(C2));
    let z = unshift(z, 27).wrapping_mul(inverse(C1));
    unshift(z, 30)
}

/// SplitMix64's output function.
fn mix(z: u64) -> u64 {
    let z = (z ^ (z >> 30)).wrapping_mul(C1);
    let z = (z ^ (z >> 27)).wrapping_mul(C2);
    z ^ (z >> 31)
}

/// The seed of a match of the old scheme, from one public unclamped shot
/// and the public noise model, or `None`.
fn recover_seed(config: &Config, shot: &ShotOutcome) -> Option<u64> {
    let noise = config.variants.noise?;
    let (aimed, played) = (shot.aimed, shot.played);
    // The draw, read off the two velocities (to a few ulps).
    let turned = aimed.perp_dot(played).atan2(aimed.dot(played));
    let angle = turned / noise.angle_sigma;
    let speed = (played.length() / aimed.length() - 1.0) / noise.speed_sigma;
    // Box-Muller backwards: u1 = exp(-r^2 / 2) = 1 - (a >> 11) / 2^53 and
    // 2 pi u2 = atan2(speed, angle) with u2 = (b >> 11) / 2^53.
    let r2 = angle * angle + speed * speed;
    let scale = (1u64 << 53) as f64;
    let top = ((1.0 - (-r2 / 2.0).exp()) * scale).round() as i64;
    let turn = speed.atan2(angle).rem_euclid(std::f64::consts::TAU);
    let u2_top = (turn / std::f64::consts::TAU * scale).round() as i64;
    // What the velocities leave unread: a few ulps of each uniform, and
    // the 11 low bits of `a` that Box-Muller drops.
    const WINDOW: i64 = 1 << 10;
    for t in (top - WINDOW).max(0)..=top + WINDOW {
        for low in 0..1u64 << 11 {
            let a = ((t as u64) << 11) | low;
            // a = mix(inner + GAMMA), b = mix(inner + 2 GAMMA).
            let inner = unmix(a).wrapping_sub(GAMMA);
            let b = mix(inner.wrapping_add(GAMMA.wrapping_mul(2)));
            if ((b >> 11) as i64 - u2_top).abs() > WINDOW {
                continue;
            }
            let draw = NoiseDraw::sample(&mut SplitMix64::new(inner));
            let again = draw.apply(&noise, aimed, config.max_speed);
            if again.x.to_bits() == played.x.to_bits() && again.y.to_bits() == played.y.to_bits() {
                // inner = mix(seed ^ shot * SHOT_MIX + GAMMA).
                let mixed = unmix(inner).wrapping_sub(GAMMA);
                return Some(mixed ^ u64::from(shot.number).wrapping_mul(SHOT_MIX));
            }
        }
    }
    None
}

/// Shot 0 of a standard match keyed by `key`: White's e-piece up the
/// board at half power (far from the speed limit, so nothing is clamped).
fn first_shot(key: NoiseKey) -> (Config, ShotOutcome) {
    let config = Config::standard();
    let mut game = Game::new(config.clone(), key).unwrap();
    let piece = PieceId::new(Side::White, 4).unwrap();
    let shot = Shot::new(piece, DVec2::new(0.05, 1.0), &config).unwrap();
    (config, game.play(Side::White, shot).unwrap().outcome)
}

#[test]
fn the_attack_inverts_splitmix64_and_recovers_the_old_schemes_seed_from_one_shot() {
    assert_eq!(unmix(mix(0x0123_4567_89ab_cdef)), 0x0123_4567_89ab_cdef);
    for seed in [1u64, 0xDEAD_BEEF_0BAD_F00D, u64::MAX - 11] {
        let (config, shot) = first_shot(NoiseKey::SplitMix64(seed));
        assert_eq!(recover_seed(&config, &shot), Some(seed), "seed {seed:#x}");
        // With the seed every later shot's noise is known in advance.
        let key = NoiseKey::SplitMix64(recover_seed(&config, &shot).unwrap());
        assert_eq!(key.draw(1), NoiseKey::SplitMix64(seed).draw(1));
    }
}

#[test]
fn the_same_attack_finds_nothing_against_a_chacha20_secret() {
    for k in 0..3u8 {
        let secret = NoiseSecret::from_bytes([k.wrapping_mul(77).wrapping_add(1); 32]);
        let (config, shot) = first_shot(NoiseKey::ChaCha20(secret));
        assert_eq!(recover_seed(&config, &shot), None);
    }
    // Nor does a seed "recovered" any other way predict a ChaCha20 match:
    // a local game keyed by a number is not the server's secret.
    let (_, shot) = first_shot(NoiseKey::ChaCha20(NoiseSecret::from_bytes([9; 32])));
    let (_, guess) = first_shot(NoiseKey::from(9));
    assert_ne!(shot.played, guess.played);
}
