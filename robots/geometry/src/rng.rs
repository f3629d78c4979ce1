//! The one seeded generator behind every source of noise: SplitMix64 seeding a
//! xoshiro256** generator, with Box-Muller normals. Written out here so that the
//! bit stream is fixed by this file alone and cannot change with a dependency
//! upgrade; the tests pin both algorithms to known outputs.

/// SplitMix64 (Steele, Lea and Flood 2014): expands a seed into [`Rng`]'s state,
/// derives stream seeds, and is on its own the generator of test data that must
/// be the same on every machine.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SplitMix64(pub u64);

impl SplitMix64 {
    pub fn new(seed: u64) -> Self {
        SplitMix64(seed)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1) with 53 random bits.
    pub fn uniform(&mut self) -> f64 {
        unit(self.next_u64())
    }

    /// Uniform in [a, b).
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.uniform()
    }
}

/// The top 53 bits of `bits` as a fraction in [0, 1).
fn unit(bits: u64) -> f64 {
    (bits >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// Deterministic random source. Each noise source owns its own stream (see
/// [`Rng::fork`]) so that enabling one never shifts another's draws.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Rng {
    s: [u64; 4],
    /// Box-Muller yields normals in pairs; the second is kept for the next call.
    spare: Option<u64>,
}

impl Rng {
    pub fn new(seed: u64) -> Self {
        let mut st = SplitMix64::new(seed);
        let s = [st.next_u64(), st.next_u64(), st.next_u64(), st.next_u64()];
        Rng { s, spare: None }
    }

    /// An independent stream derived from this seed and a stream label.
    pub fn fork(seed: u64, stream: u64) -> Self {
        let mut st = SplitMix64::new(seed ^ stream.wrapping_mul(0xD1B5_4A32_D192_ED03));
        Rng::new(st.next_u64())
    }

    pub fn next_u64(&mut self) -> u64 {
        let result = self.s[1].wrapping_mul(5).rotate_left(7).wrapping_mul(9);
        let t = self.s[1] << 17;
        self.s[2] ^= self.s[0];
        self.s[3] ^= self.s[1];
        self.s[1] ^= self.s[2];
        self.s[0] ^= self.s[3];
        self.s[2] ^= t;
        self.s[3] = self.s[3].rotate_left(45);
        result
    }

    /// Uniform in [0, 1) with 53 random bits.
    pub fn uniform(&mut self) -> f64 {
        unit(self.next_u64())
    }

    /// Standard normal N(0, 1).
    pub fn normal(&mut self) -> f64 {
        if let Some(bits) = self.spare.take() {
            return f64::from_bits(bits);
        }
        // 1 - u keeps the logarithm's argument in (0, 1].
        let u1 = 1.0 - self.uniform();
        let u2 = self.uniform();
        let r = (-2.0 * u1.ln()).sqrt();
        let theta = std::f64::consts::TAU * u2;
        self.spare = Some((r * theta.sin()).to_bits());
        r * theta.cos()
    }

    /// N(0, sigma^2); a zero sigma draws nothing, so noise-free configs leave
    /// the stream untouched.
    pub fn gauss(&mut self, sigma: f64) -> f64 {
        if sigma == 0.0 {
            0.0
        } else {
            sigma * self.normal()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splitmix64_gives_the_reference_sequence() {
        // The first outputs of Vigna's splitmix64.c for the seed 1234567.
        let mut g = SplitMix64::new(1_234_567);
        let got: Vec<u64> = (0..5).map(|_| g.next_u64()).collect();
        assert_eq!(
            got,
            [
                6_457_827_717_110_365_317,
                3_203_168_211_198_807_973,
                9_817_491_932_198_370_423,
                4_593_380_528_125_082_431,
                16_408_922_859_458_223_821,
            ]
        );
    }

    #[test]
    fn xoshiro256starstar_gives_the_reference_sequence() {
        // From the state [1, 2, 3, 4], as rand_xoshiro's test of the reference code.
        let mut r = Rng {
            s: [1, 2, 3, 4],
            spare: None,
        };
        let got: Vec<u64> = (0..4).map(|_| r.next_u64()).collect();
        assert_eq!(got, [11_520, 0, 1_509_978_240, 1_215_971_899_390_074_240]);
    }

    #[test]
    fn a_seed_and_a_stream_pin_the_draws() {
        // What every simulated run's noise is drawn from: a change here changes
        // every trace of a noisy robot.
        let mut r = Rng::new(7);
        assert_eq!(r.next_u64(), PINNED_NEW_7);
        let mut f = Rng::fork(7, 2);
        assert_eq!(f.next_u64(), PINNED_FORK_7_2);
        let mut n = Rng::new(42);
        assert_eq!(n.normal().to_bits(), PINNED_NORMAL_42.0);
        assert_eq!(n.normal().to_bits(), PINNED_NORMAL_42.1);
        assert_eq!(SplitMix64::new(9).uniform().to_bits(), PINNED_UNIFORM_9);
    }

    const PINNED_NEW_7: u64 = 12_923_355_070_828_475_994;
    const PINNED_FORK_7_2: u64 = 14_222_987_149_082_099_752;
    const PINNED_NORMAL_42: (u64, u64) = (13_822_506_758_473_011_324, 4_598_868_084_635_917_274);
    const PINNED_UNIFORM_9: u64 = 4_604_321_396_663_242_252;

    #[test]
    fn same_seed_same_stream_and_forks_differ() {
        let mut a = Rng::new(7);
        let mut b = Rng::new(7);
        for _ in 0..100 {
            assert_eq!(a.next_u64(), b.next_u64());
        }
        let mut f1 = Rng::fork(7, 1);
        let mut f2 = Rng::fork(7, 2);
        assert_ne!(f1.next_u64(), f2.next_u64());
    }

    #[test]
    fn a_zero_sigma_draws_nothing() {
        let mut a = Rng::new(3);
        let b = a.clone();
        assert_eq!(a.gauss(0.0), 0.0);
        assert_eq!(a, b);
    }

    #[test]
    fn normals_have_unit_variance() {
        let mut r = Rng::new(42);
        let n = 20_000;
        let xs: Vec<f64> = (0..n).map(|_| r.normal()).collect();
        let mean = xs.iter().sum::<f64>() / n as f64;
        let var = xs.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n as f64;
        assert!(mean.abs() < 0.03, "mean {mean}");
        assert!((var - 1.0).abs() < 0.05, "var {var}");
    }

    #[test]
    fn uniforms_lie_in_the_half_open_unit_interval() {
        let mut r = Rng::new(1);
        let mut s = SplitMix64::new(1);
        for _ in 0..10_000 {
            let (a, b) = (r.uniform(), s.uniform());
            assert!((0.0..1.0).contains(&a) && (0.0..1.0).contains(&b));
        }
    }
}
