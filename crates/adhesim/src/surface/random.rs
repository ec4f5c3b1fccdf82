//! A seeded random stream that is bit-identical on every platform.
//!
//! xoshiro256** (Blackman & Vigna (2021), "Scrambled linear pseudorandom number
//! generators", *ACM Trans. Math. Softw.* 47, 36, doi:10.1145/3460772) seeded through
//! SplitMix64, as its authors recommend. Uniform deviates use the top 53 bits (exact), and
//! the Gaussian and unit-circle deviates of Marsaglia's polar method use only +, ×, ÷ and
//! √ (all correctly rounded by IEEE 754) plus the logarithm below, written out in those
//! operations: no platform `libm` enters the stream, so a seed gives the same numbers
//! on every machine and compiler.

use std::f64::consts::LN_2;

/// xoshiro256** state.
#[derive(Debug, Clone)]
pub(crate) struct Xoshiro256 {
    state: [u64; 4],
}

impl Xoshiro256 {
    /// The generator for `seed`: the four state words are consecutive SplitMix64 outputs.
    pub(crate) fn new(seed: u64) -> Self {
        let mut mix = seed;
        let mut next = || {
            mix = mix.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = mix;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^ (z >> 31)
        };
        Self {
            state: [next(), next(), next(), next()],
        }
    }

    /// The next 64 random bits.
    pub(crate) fn next_u64(&mut self) -> u64 {
        let s = &mut self.state;
        let result = s[1].wrapping_mul(5).rotate_left(7).wrapping_mul(9);
        let t = s[1] << 17;
        s[2] ^= s[0];
        s[3] ^= s[1];
        s[1] ^= s[2];
        s[0] ^= s[3];
        s[2] ^= t;
        s[3] = s[3].rotate_left(45);
        result
    }

    /// Uniform on [−1, 1) with 53 random bits (exactly representable).
    fn symmetric_uniform(&mut self) -> f64 {
        let unit = (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
        2.0 * unit - 1.0
    }

    /// A point (u, v) uniform in the unit disk minus a tiny core, with s = u² + v².
    fn disk_point(&mut self) -> (f64, f64, f64) {
        loop {
            let (u, v) = (self.symmetric_uniform(), self.symmetric_uniform());
            let s = u * u + v * v;
            // The core s < 1e-300 is rejected so that 1/√s and ln s stay finite.
            if s < 1.0 && s > 1e-300 {
                return (u, v, s);
            }
        }
    }

    /// A uniformly distributed point (cos φ, sin φ) on the unit circle.
    pub(crate) fn unit_phase(&mut self) -> (f64, f64) {
        let (u, v, s) = self.disk_point();
        let inverse_radius = 1.0 / s.sqrt();
        (u * inverse_radius, v * inverse_radius)
    }

    /// Two independent standard normal deviates (Marsaglia's polar method).
    pub(crate) fn normal_pair(&mut self) -> (f64, f64) {
        let (u, v, s) = self.disk_point();
        let factor = (-2.0 * ln(s) / s).sqrt();
        (u * factor, v * factor)
    }
}

/// Natural logarithm of a positive finite `x` from IEEE basic operations only: x = m·2^e
/// with m ∈ [1/√2, √2), ln m = 2 atanh z, z = (m − 1)/(m + 1), |z| ≤ 0.172, by 14 terms of
/// its odd series (truncation < 1e-20 relative).
pub(crate) fn ln(x: f64) -> f64 {
    debug_assert!(x > 0.0 && x.is_finite());
    let (mut mantissa, mut exponent) = (x, 0i32);
    // Bring subnormals into the normal range first.
    if mantissa < f64::MIN_POSITIVE {
        mantissa *= (1u64 << 54) as f64;
        exponent -= 54;
    }
    let bits = mantissa.to_bits();
    exponent += ((bits >> 52) & 0x7ff) as i32 - 1023;
    mantissa = f64::from_bits((bits & 0x000f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000);
    if mantissa > std::f64::consts::SQRT_2 {
        mantissa *= 0.5;
        exponent += 1;
    }
    let z = (mantissa - 1.0) / (mantissa + 1.0);
    let z2 = z * z;
    let mut series = 0.0;
    for k in (0..14).rev() {
        series = series * z2 + 1.0 / (2 * k + 1) as f64;
    }
    2.0 * z * series + exponent as f64 * LN_2
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn logarithm_matches_std_to_rounding() {
        use std::f64::consts::{FRAC_1_SQRT_2, SQRT_2};
        // both sides of the √2 fold of the mantissa, subnormals, extremes
        let samples = [
            1e-300,
            1e-10,
            0.1,
            0.5,
            FRAC_1_SQRT_2,
            1.0,
            SQRT_2,
            SQRT_2 * (1.0 + 1e-15),
            2.0,
            3.5,
            1e10,
            5e-324,
        ];
        for &x in &samples {
            let (mine, reference) = (ln(x), x.ln());
            assert!(
                (mine - reference).abs() <= 4.0 * f64::EPSILON * reference.abs().max(1.0),
                "ln({x}) = {mine} vs {reference}"
            );
        }
    }

    /// The first outputs of xoshiro256** for SplitMix64-seeded state 0, pinned: they guard
    /// the stream (and every generated surface) against an accidental change. The values
    /// were reproduced by an independent re-statement of both algorithms in Python, whose
    /// first SplitMix64 output for seed 0 is the published 0xE220A8397B1DCDAF.
    #[test]
    fn stream_is_pinned() {
        let mut rng = Xoshiro256::new(0);
        let first: Vec<u64> = (0..3).map(|_| rng.next_u64()).collect();
        let mut again = Xoshiro256::new(0);
        assert_eq!(first, (0..3).map(|_| again.next_u64()).collect::<Vec<_>>());
        assert_ne!(first[0], first[1]);
        assert_eq!(first, PINNED.to_vec());
    }
    const PINNED: [u64; 3] = [11091344671253066420, 13793997310169335082, 1900383378846508768];

    #[test]
    fn normal_deviates_have_unit_variance() {
        let mut rng = Xoshiro256::new(7);
        let count = 200_000;
        let (mut sum, mut square) = (0.0, 0.0);
        for _ in 0..count / 2 {
            let (a, b) = rng.normal_pair();
            sum += a + b;
            square += a * a + b * b;
        }
        let mean = sum / count as f64;
        let variance = square / count as f64 - mean * mean;
        // standard errors: 1/√n = 0.0022 for the mean, √(2/n) = 0.0032 for the variance
        assert!(mean.abs() < 0.01, "mean {mean}");
        assert!((variance - 1.0).abs() < 0.015, "variance {variance}");
        let (c, s) = rng.unit_phase();
        assert!((c * c + s * s - 1.0).abs() < 1e-15);
    }
}
