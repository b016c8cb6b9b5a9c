//! The random numbers of tests and tools: the one small generator that
//! builds preset layouts (`presets::box_of_discs`), the lab's
//! hostile and benchmark scenes, the batches of the root-solver benchmarks
//! and the random cases of the engine's own tests.
//!
//! Hand-written on purpose, with no random-number crate behind it: what it
//! generates must stay the same forever. A layout or a hostile scene is
//! named by its seed in records, charts and pinned test results; a crate's
//! stream may change between its versions (and has, for the popular ones),
//! which would silently turn every such seed into another scene.
//!
//! Three recurrences are kept, because seeds in use are pinned to each
//! ([`Algorithm`]); every draw ([`Rng::unit`], [`Rng::range`], ...) is the
//! same arithmetic on top of any of them. Not for the game's noise (its own
//! generators, chosen for replays and fairness) nor for anything secret.

use glam::DVec2;

/// The recurrence a stream follows. Each is pinned by seeds in use; none
/// may change.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Algorithm {
    /// SplitMix64 (Steele, Lea and Flood): the lab's hostile scenes and
    /// the root-solver benchmarks.
    SplitMix64,
    /// xorshift64* (Marsaglia's shifts 12, 25, 27 and Vigna's multiplier):
    /// the preset layouts and the engine's lattice tests.
    XorShift64Star,
    /// Plain xorshift64 (shifts 13, 7, 17): the lab's random boxes and the
    /// root solver's random polynomials. A state of zero stays zero.
    XorShift64,
}

/// A deterministic stream of random numbers.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rng {
    state: u64,
    algorithm: Algorithm,
}

/// The golden-ratio increment of SplitMix64, also the seed scrambler of
/// some callers (`seed * GOLDEN | 1`: an odd, well-spread xorshift state).
pub const GOLDEN: u64 = 0x9E37_79B9_7F4A_7C15;

impl Rng {
    /// A SplitMix64 stream from its raw `state`.
    pub const fn splitmix64(state: u64) -> Rng {
        Rng {
            state,
            algorithm: Algorithm::SplitMix64,
        }
    }

    /// An xorshift64* stream from its raw `state` (not zero).
    pub const fn xorshift64_star(state: u64) -> Rng {
        Rng {
            state,
            algorithm: Algorithm::XorShift64Star,
        }
    }

    /// An xorshift64 stream from its raw `state` (not zero).
    pub const fn xorshift64(state: u64) -> Rng {
        Rng {
            state,
            algorithm: Algorithm::XorShift64,
        }
    }

    /// Which recurrence this stream follows.
    pub fn algorithm(&self) -> Algorithm {
        self.algorithm
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        match self.algorithm {
            Algorithm::SplitMix64 => {
                self.state = self.state.wrapping_add(GOLDEN);
                let mut z = self.state;
                z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
                z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
                z ^ (z >> 31)
            }
            Algorithm::XorShift64Star => {
                self.state ^= self.state >> 12;
                self.state ^= self.state << 25;
                self.state ^= self.state >> 27;
                self.state.wrapping_mul(0x2545_F491_4F6C_DD1D)
            }
            Algorithm::XorShift64 => {
                self.state ^= self.state << 13;
                self.state ^= self.state >> 7;
                self.state ^= self.state << 17;
                self.state
            }
        }
    }

    /// Uniform in `[0, 1)`: the top 53 bits of the next draw.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `[-1, 1)`: the top 53 bits of the next draw.
    pub fn symmetric(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// Log-uniform in `[lo, hi]` (both > 0).
    pub fn log_range(&mut self, lo: f64, hi: f64) -> f64 {
        (lo.ln() + (hi.ln() - lo.ln()) * self.unit()).exp()
    }

    /// Below `n` (0 for `n` = 0), by remainder: slightly uneven for an `n`
    /// far from a power of two, which no caller minds.
    pub fn below(&mut self, n: u64) -> u64 {
        self.next_u64() % n.max(1)
    }

    /// `true` with probability `p`.
    pub fn chance(&mut self, p: f64) -> bool {
        self.unit() < p
    }

    /// A unit vector at a random angle.
    pub fn direction(&mut self) -> DVec2 {
        let a = self.range(0.0, std::f64::consts::TAU);
        DVec2::new(a.cos(), a.sin())
    }
}

#[cfg(test)]
mod tests {
    //! The expected values come from an independent model of the copies
    //! this module replaced (Python integers, masked to 64 bits): each
    //! stream in use stays the same, bit for bit.
    use super::*;

    fn draws(mut rng: Rng, f: impl Fn(&mut Rng) -> u64) -> [u64; 3] {
        [f(&mut rng), f(&mut rng), f(&mut rng)]
    }

    #[test]
    fn splitmix64_gives_the_reference_sequence() {
        let mut rng = Rng::splitmix64(1234567);
        assert_eq!(rng.next_u64(), 6457827717110365317);
        assert_eq!(rng.next_u64(), 3203168211198807973);
    }

    #[test]
    fn splitmix64_keeps_the_root_benchmark_batch() {
        assert_eq!(
            draws(Rng::splitmix64(0x5EED), Rng::next_u64),
            [
                0x09f1_fd9d_03f0_a9b4,
                0x5532_7416_1bbf_8475,
                0x5d5b_ca46_96b3_43b3
            ]
        );
        assert_eq!(
            draws(Rng::splitmix64(0x5EED), |r| r.range(0.5, 2.0).to_bits()),
            [
                0x3fe1_dd5f_8d70_bd20,
                0x3fef_f975_c425_33e8,
                0x3ff0_c09a_f69e_20ce
            ]
        );
    }

    #[test]
    fn xorshift64_star_keeps_the_preset_layouts() {
        let state = 7u64.wrapping_mul(GOLDEN) | 1;
        assert_eq!(
            draws(Rng::xorshift64_star(state), Rng::next_u64),
            [
                0x671e_db9d_e9e9_afb7,
                0x67e5_3669_d5fb_6b34,
                0x974e_a030_4616_1d80
            ]
        );
        assert_eq!(
            draws(Rng::xorshift64_star(state), |r| r.symmetric().to_bits()),
            [
                0xbfc8_e124_6216_1658,
                0xbfc8_1ac9_962a_0498,
                0x3fc7_4ea0_3046_1618
            ]
        );
    }

    #[test]
    fn xorshift64_keeps_the_lab_boxes_and_the_solver_polynomials() {
        let state = 7u64.wrapping_mul(GOLDEN) | 1;
        assert_eq!(
            draws(Rng::xorshift64(state), Rng::next_u64),
            [
                0xf63f_752d_d400_329a,
                0xecce_e9dd_2109_d47f,
                0x7f59_6005_939f_3817
            ]
        );
        assert_eq!(
            draws(Rng::xorshift64(0x1234_5678_9abc_def0), Rng::next_u64),
            [
                0xfe80_0d65_69fa_1b4d,
                0x0ce7_c497_a6b0_9c3b,
                0x41df_b69a_11db_93c3
            ]
        );
        assert_eq!(
            draws(Rng::xorshift64(0x1234_5678_9abc_def0), |r| r
                .symmetric()
                .to_bits()),
            [
                0x3fef_a003_595a_7e86,
                0xbfec_c60e_da16_53da,
                0xbfdf_1024_b2f7_1238
            ]
        );
    }

    #[test]
    fn unit_and_symmetric_read_the_same_top_bits() {
        let (mut a, mut b) = (Rng::splitmix64(9), Rng::splitmix64(9));
        for _ in 0..1000 {
            let u = a.unit();
            assert!((0.0..1.0).contains(&u));
            assert_eq!(b.symmetric(), 2.0 * u - 1.0);
        }
    }

    #[test]
    fn below_stays_below_and_below_zero_is_zero() {
        let mut rng = Rng::xorshift64_star(5);
        assert!((0..1000).all(|_| rng.below(7) < 7));
        assert_eq!(rng.below(0), 0);
    }
}
