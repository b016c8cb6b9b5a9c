//! Execution noise, bit-identical on every platform.
//!
//! As in computational pool tournaments, a shot is played not exactly as
//! aimed: its direction is turned by a Gaussian angle and its speed scaled
//! by a Gaussian factor. The draws come from the match's [`NoiseKey`] and
//! the shot's number, so a replay reproduces them. Everything here uses only
//! `+ - * /`, `sqrt` and integer operations — all exactly specified, and so
//! identical natively and in wasm — never the platform's `sin`, `cos` or
//! `ln`, whose last bits differ between libms.
//!
//! Two schemes ([`NoiseScheme`]) turn a key into draws:
//! - **`chacha20`**, every match of record format 4 on: the key is the
//!   match's 256-bit [`NoiseSecret`]. Shot `n`'s draw takes the first 16
//!   bytes of the ChaCha20 keystream (20 rounds, key = the secret's 32
//!   bytes, 64-bit nonce = `n` little-endian, 64-bit block counter from 0,
//!   as in Bernstein's original ChaCha and `rand_chacha`) as two
//!   little-endian `u64`s. Without the secret nothing about one shot's
//!   draw tells anything about another's: ChaCha20 is a cipher.
//! - **`splitmix64`**, records of formats 1–3 only: SplitMix64 from a
//!   64-bit seed. Its output can be inverted, so one public shot gave the
//!   seed away; it is kept so that old records replay bit for bit.
//!
//! Either way the two `u64`s `a, b` become two standard normal numbers by
//! Box–Muller with our own polynomial `ln` and `sin_cos` (accurate to a few
//! ulps, deterministic always): `u1 = 1 - (a >> 11) / 2^53`, `u2 = (b >>
//! 11) / 2^53`, `r = sqrt(-2 ln u1)`, angle draw `r cos(2 pi u2)`, speed draw
//! `r sin(2 pi u2)`.
//!
//! Hand-written on purpose, where a crate exists for each piece (`rand_distr`
//! for normal draws, `libm` for `ln`, `sin`, `cos`): every match ever
//! recorded must replay bit for bit, and a crate's next version may change
//! its stream or its last bits. Only the ChaCha20 keystream comes from a
//! crate (`rand_chacha`), because ChaCha20's output is fixed by its
//! specification.

use crate::config::NoiseConfig;
use crate::secret::NoiseSecret;
use glam::DVec2;
use rand_chacha::rand_core::{RngCore, SeedableRng};
use rand_chacha::ChaCha20Rng;
use serde::{Deserialize, Serialize};
use std::f64::consts::{FRAC_PI_2, LN_2, SQRT_2, TAU};

/// SplitMix64: a tiny, fast, well-mixed 64-bit generator.
#[derive(Clone, Debug)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// A generator started from `seed`.
    pub fn new(seed: u64) -> Self {
        SplitMix64(seed)
    }

    /// The generator for shot number `shot` of a match with seed `seed`
    /// (independent streams per shot, so replays can start anywhere).
    pub fn for_shot(seed: u64, shot: u32) -> Self {
        let mut mix = SplitMix64(seed ^ (shot as u64).wrapping_mul(0xD1B5_4A32_D192_ED03));
        SplitMix64(mix.next_u64())
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)`, 53 random bits.
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Two independent standard normal draws (Box–Muller).
    pub fn gaussian_pair(&mut self) -> (f64, f64) {
        let a = self.next_u64();
        let b = self.next_u64();
        gaussian_pair(a, b)
    }
}

/// Uniform in `[0, 1)` from the top 53 bits of `bits`.
fn unit(bits: u64) -> f64 {
    (bits >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// Two standard normal numbers from two uniform `u64`s (Box–Muller).
fn gaussian_pair(a: u64, b: u64) -> (f64, f64) {
    let u1 = 1.0 - unit(a); // (0, 1]: ln is finite
    let u2 = unit(b);
    let r = (-2.0 * ln(u1)).sqrt();
    let (s, c) = sin_cos(TAU * u2);
    (r * c, r * s)
}

/// How a match's key becomes its draws (recorded with the match).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum NoiseScheme {
    /// SplitMix64 from a 64-bit seed: records of formats 1–3.
    Splitmix64,
    /// ChaCha20 keyed by a 256-bit secret, the shot's number as the nonce.
    Chacha20,
}

impl NoiseScheme {
    /// The scheme's name, as records write it.
    pub fn as_str(self) -> &'static str {
        match self {
            NoiseScheme::Splitmix64 => "splitmix64",
            NoiseScheme::Chacha20 => "chacha20",
        }
    }
}

impl std::fmt::Display for NoiseScheme {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// What a match's execution noise is drawn from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum NoiseKey {
    /// The inverted-at-will seed of records of formats 1–3 (replays only).
    SplitMix64(u64),
    /// A secret, committed to before the first shot and revealed after the
    /// last.
    ChaCha20(NoiseSecret),
}

impl NoiseKey {
    /// The scheme this key draws with.
    pub fn scheme(&self) -> NoiseScheme {
        match self {
            NoiseKey::SplitMix64(_) => NoiseScheme::Splitmix64,
            NoiseKey::ChaCha20(_) => NoiseScheme::Chacha20,
        }
    }

    /// The two uniform `u64`s of shot number `shot`.
    pub fn words(&self, shot: u32) -> (u64, u64) {
        match self {
            NoiseKey::SplitMix64(seed) => {
                let mut rng = SplitMix64::for_shot(*seed, shot);
                let a = rng.next_u64();
                (a, rng.next_u64())
            }
            NoiseKey::ChaCha20(secret) => {
                let mut rng = ChaCha20Rng::from_seed(*secret.bytes());
                rng.set_stream(u64::from(shot));
                let a = rng.next_u64();
                (a, rng.next_u64())
            }
        }
    }

    /// The draw of shot number `shot`.
    pub fn draw(&self, shot: u32) -> NoiseDraw {
        let (a, b) = self.words(shot);
        let (angle, speed) = gaussian_pair(a, b);
        NoiseDraw { angle, speed }
    }
}

/// A bare number keys a reproducible local game: the secret derived from
/// it ([`NoiseSecret::from_seed`]), drawn with ChaCha20. Anyone who knows
/// the number knows the noise, so a server never keys a match this way.
impl From<u64> for NoiseKey {
    fn from(seed: u64) -> NoiseKey {
        NoiseKey::ChaCha20(NoiseSecret::from_seed(seed))
    }
}

impl From<NoiseSecret> for NoiseKey {
    fn from(secret: NoiseSecret) -> NoiseKey {
        NoiseKey::ChaCha20(secret)
    }
}

/// Natural logarithm of a positive finite `x`, deterministic everywhere
/// (`NaN` for anything else).
pub fn ln(x: f64) -> f64 {
    if x.is_nan() || x <= 0.0 || x == f64::INFINITY {
        return f64::NAN;
    }
    let (mut x, mut e) = (x, 0i64);
    if x < f64::MIN_POSITIVE {
        x *= (1u64 << 54) as f64; // exact: normalise a subnormal
        e -= 54;
    }
    let bits = x.to_bits();
    e += ((bits >> 52) & 0x7ff) as i64 - 1023;
    let mut m = f64::from_bits((bits & 0x000f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000);
    if m > SQRT_2 {
        m /= 2.0; // exact
        e += 1;
    }
    // ln m = 2 atanh z with |z| <= 0.1716 for m in [1/sqrt2, sqrt2].
    let z = (m - 1.0) / (m + 1.0);
    let z2 = z * z;
    let mut sum = 0.0;
    for k in (0..14).rev() {
        sum = sum * z2 + 1.0 / (2 * k + 1) as f64;
    }
    e as f64 * LN_2 + 2.0 * z * sum
}

/// `(sin x, cos x)`, deterministic everywhere: reduction to `|r| <= pi/4`
/// by quarter turns, then Taylor polynomials to degree 19.
pub fn sin_cos(x: f64) -> (f64, f64) {
    if !x.is_finite() {
        return (f64::NAN, f64::NAN);
    }
    // pi/2 split in two so that k * PIO2_HI is exact for moderate k.
    const PIO2_HI: f64 = 1.570_796_326_734_125_6;
    const PIO2_LO: f64 = 6.077_100_506_506_192e-11;
    let k = (x / FRAC_PI_2).round();
    let r = (x - k * PIO2_HI) - k * PIO2_LO;
    let r2 = r * r;
    let mut s = 1.0;
    let mut c = 1.0;
    for n in (1..=9).rev() {
        let n = n as f64;
        s = 1.0 - r2 / ((2.0 * n) * (2.0 * n + 1.0)) * s;
        c = 1.0 - r2 / ((2.0 * n - 1.0) * (2.0 * n)) * c;
    }
    let s = r * s;
    match (k as i64).rem_euclid(4) {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// `v` turned by `angle` radians counter-clockwise (deterministic).
pub fn rotate(v: DVec2, angle: f64) -> DVec2 {
    let (s, c) = sin_cos(angle);
    DVec2::new(v.x * c - v.y * s, v.x * s + v.y * c)
}

/// One draw of execution noise: two standard normal numbers, one turning
/// the direction and one scaling the speed. The server draws it from the
/// match's key and the shot's number ([`NoiseKey::draw`]); a bot that
/// wants to know how robust a candidate is draws its own from its own
/// generator ([`NoiseDraw::sample`]) and applies it with the very same
/// arithmetic ([`NoiseDraw::apply`]).
#[derive(
    Clone,
    Copy,
    Debug,
    Default,
    PartialEq,
    serde::Serialize,
    serde::Deserialize,
    schemars::JsonSchema,
)]
#[serde(deny_unknown_fields)]
pub struct NoiseDraw {
    /// Standard normal; the direction turns by `angle_sigma * angle` radians.
    pub angle: f64,
    /// Standard normal; the speed scales by `1 + speed_sigma * speed`.
    pub speed: f64,
}

impl NoiseDraw {
    /// No noise: the shot is played exactly as aimed.
    pub const NONE: NoiseDraw = NoiseDraw {
        angle: 0.0,
        speed: 0.0,
    };

    /// A draw from any generator.
    pub fn sample(rng: &mut SplitMix64) -> NoiseDraw {
        let (angle, speed) = rng.gaussian_pair();
        NoiseDraw { angle, speed }
    }

    /// The velocity played when `aimed` is shot with this draw under
    /// `noise`: turned by `angle_sigma * angle` radians, its speed scaled by
    /// `1 + speed_sigma * speed` and kept within `[0, max_speed]`.
    pub fn apply(&self, noise: &NoiseConfig, aimed: DVec2, max_speed: f64) -> DVec2 {
        let speed = aimed.length();
        if speed == 0.0 {
            return aimed;
        }
        let turned = rotate(aimed, noise.angle_sigma * self.angle);
        let new_speed = (speed * (1.0 + noise.speed_sigma * self.speed)).clamp(0.0, max_speed);
        turned * (new_speed / speed)
    }
}

/// The velocity actually played when `aimed` is shot as the match's shot
/// number `shot`: turned by `N(0, angle_sigma)` radians, its speed scaled by
/// `1 + N(0, speed_sigma)` and kept within `[0, max_speed]`.
pub fn perturb(
    noise: &NoiseConfig,
    key: &NoiseKey,
    shot: u32,
    aimed: DVec2,
    max_speed: f64,
) -> DVec2 {
    key.draw(shot).apply(noise, aimed, max_speed)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polynomial_sin_cos_matches_the_platform_to_a_few_ulps() {
        let mut rng = SplitMix64::new(1);
        for _ in 0..10_000 {
            let x = (rng.next_f64() - 0.5) * 40.0;
            let (s, c) = sin_cos(x);
            assert!((s - x.sin()).abs() < 4e-16, "sin {x}: {s} vs {}", x.sin());
            assert!((c - x.cos()).abs() < 4e-16, "cos {x}: {c} vs {}", x.cos());
        }
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
    }

    #[test]
    fn polynomial_ln_matches_the_platform_to_a_few_ulps() {
        let mut rng = SplitMix64::new(2);
        for _ in 0..10_000 {
            let x = rng.next_f64() * 1e3 + 1e-300;
            assert!((ln(x) - x.ln()).abs() <= 4.0 * f64::EPSILON * x.ln().abs().max(1.0));
        }
        assert_eq!(ln(1.0), 0.0);
        assert!((ln(5e-324) - 5e-324f64.ln()).abs() < 1e-12);
        assert!(ln(0.0).is_nan() && ln(-1.0).is_nan());
    }

    #[test]
    fn splitmix_gives_the_reference_sequence() {
        // Reference values of SplitMix64 seeded with 1234567.
        let mut rng = SplitMix64::new(1234567);
        assert_eq!(rng.next_u64(), 6457827717110365317);
        assert_eq!(rng.next_u64(), 3203168211198807973);
    }

    #[test]
    fn gaussian_draws_have_zero_mean_and_unit_variance() {
        let mut rng = SplitMix64::new(7);
        let n = 100_000;
        let (mut sum, mut sq) = (0.0, 0.0);
        for _ in 0..n / 2 {
            let (a, b) = rng.gaussian_pair();
            sum += a + b;
            sq += a * a + b * b;
        }
        let mean = sum / n as f64;
        let var = sq / n as f64 - mean * mean;
        assert!(mean.abs() < 0.02, "{mean}");
        assert!((var - 1.0).abs() < 0.02, "{var}");
    }

    #[test]
    fn the_same_seed_and_shot_give_the_same_noise_and_others_differ() {
        let n = NoiseConfig {
            angle_sigma: 0.05,
            speed_sigma: 0.05,
        };
        let v = DVec2::new(1.0, 0.5);
        let (k42, k43) = (NoiseKey::from(42), NoiseKey::from(43));
        let a = perturb(&n, &k42, 3, v, 2.0);
        assert_eq!(a.x.to_bits(), perturb(&n, &k42, 3, v, 2.0).x.to_bits());
        assert_ne!(a, perturb(&n, &k42, 4, v, 2.0));
        assert_ne!(a, perturb(&n, &k43, 3, v, 2.0));
        assert_ne!(a, v);
    }

    #[test]
    fn legacy_noise_is_pinned_to_exact_bits_on_every_platform() {
        // The same bits were obtained natively (x86_64) and in wasm32.
        let n = NoiseConfig {
            angle_sigma: 0.05,
            speed_sigma: 0.1,
        };
        let v = perturb(
            &n,
            &NoiseKey::SplitMix64(77),
            12,
            DVec2::new(0.3, -1.1),
            2.0,
        );
        assert_eq!(v.x.to_bits(), 0x3fcb_2991_1e59_207b);
        assert_eq!(v.y.to_bits(), 0xbfee_c0ab_cf47_1862);
    }

    #[test]
    fn chacha_words_are_the_published_keystream_with_the_shot_as_nonce() {
        // Bernstein's ChaCha20 with a zero key: the keystream of nonce 0
        // starts 76 b8 e0 ad a0 f1 3d 90 40 5d 6a e5 53 86 bd 28, and of
        // nonce 01 00 00 00 00 00 00 00 (1, little-endian) ef 3f df d6 c6
        // 15 78 fb f5 cf 35 bd 3d d3 3b 80 (draft-agl-tls-chacha20poly1305,
        // section 7). Each is read as two little-endian u64s.
        let key = NoiseKey::ChaCha20(NoiseSecret::from_bytes([0; 32]));
        assert_eq!(key.words(0), (0x903d_f1a0_ade0_b876, 0x28bd_8653_e56a_5d40));
        assert_eq!(key.words(1), (0xfb78_15c6_d6df_3fef, 0x803b_d33d_bd35_cff5));
    }

    #[test]
    fn chacha_noise_is_pinned_to_exact_bits_on_every_platform() {
        let n = NoiseConfig {
            angle_sigma: 0.05,
            speed_sigma: 0.1,
        };
        let key = NoiseKey::ChaCha20(NoiseSecret::from_bytes([7; 32]));
        let v = perturb(&n, &key, 12, DVec2::new(0.3, -1.1), 2.0);
        // wasm32 draws the same bits: the JS package's `verify` gives
        // native's draws bit for bit (tests/tests/verify_everywhere.rs).
        assert_eq!(v.x.to_bits(), 0x3fd3_a752_a502_f25e);
        assert_eq!(v.y.to_bits(), 0xbff2_1cdd_b381_1a42);
    }

    #[test]
    fn chacha_draws_are_standard_normal_and_uncorrelated_between_shots() {
        let key = NoiseKey::from(3);
        let n = 50_000u32;
        let (mut sum, mut sq, mut cross) = (0.0, 0.0, 0.0);
        let mut prev = key.draw(0);
        for shot in 1..=n {
            let d = key.draw(shot);
            sum += d.angle + d.speed;
            sq += d.angle * d.angle + d.speed * d.speed;
            cross += d.angle * prev.angle;
            prev = d;
        }
        let count = 2.0 * n as f64;
        assert!((sum / count).abs() < 0.015, "mean {}", sum / count);
        assert!((sq / count - 1.0).abs() < 0.02, "variance {}", sq / count);
        assert!((cross / n as f64).abs() < 0.02, "lag-1 correlation");
    }

    #[test]
    fn zero_sigmas_play_the_shot_exactly_as_aimed() {
        let n = NoiseConfig {
            angle_sigma: 0.0,
            speed_sigma: 0.0,
        };
        let v = DVec2::new(-0.3, 1.25);
        assert_eq!(perturb(&n, &NoiseKey::from(9), 0, v, 2.0), v);
    }

    #[test]
    fn noisy_speed_never_exceeds_the_maximum_and_rotation_keeps_length() {
        let n = NoiseConfig {
            angle_sigma: 0.3,
            speed_sigma: 0.5,
        };
        for shot in 0..1000 {
            let v = perturb(&n, &NoiseKey::from(5), shot, DVec2::new(0.0, 2.0), 2.0);
            assert!(v.length() <= 2.0 * (1.0 + 1e-15));
        }
        let r = rotate(DVec2::new(3.0, 4.0), 1.0);
        assert!((r.length() - 5.0).abs() < 1e-14);
        let q = rotate(DVec2::X, FRAC_PI_2);
        assert!(q.x.abs() < 1e-16 && (q.y - 1.0).abs() < 1e-16);
    }
}
