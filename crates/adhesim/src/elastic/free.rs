use super::influence::love_coefficient;
use super::spectral::SpectralConvolution;
use super::ElasticOperator;
use crate::grid::Grid;
use crate::material::ElasticMaterial;
use rayon::prelude::*;

/// K(lΔ, mΔ) for 0 ≤ m, l < N at `[m * n + l]`. K(ξ,η) = K(±ξ,±η) = K(η,ξ) holds bitwise
/// for [`love_coefficient`], so each coefficient is evaluated once (l ≥ m) and mirrored:
/// an eighth of the evaluations of the 2N×2N padded kernel, with the same bits.
fn love_quadrant(n: usize, delta: f64, modulus: f64) -> Vec<f64> {
    let mut quadrant = vec![0.0; n * n];
    quadrant.par_chunks_mut(n).enumerate().for_each(|(m, row)| {
        for (l, value) in row.iter_mut().enumerate().skip(m) {
            *value = love_coefficient(l as f64 * delta, m as f64 * delta, delta, modulus);
        }
    });
    for m in 0..n {
        for l in 0..m {
            quadrant[m * n + l] = quadrant[l * n + m];
        }
    }
    quadrant
}

/// Non-periodic half-space by discrete convolution and FFT (DC-FFT).
///
/// Liu, Wang & Liu (2000), "A versatile method of discrete convolution and FFT (DC-FFT)
/// for contact analyses", *Wear* 243, 101–111, doi:10.1016/S0043-1648(00)00427-0.
/// Love's exact coefficients K(mΔ, nΔ), |m|,|n| < N, are wrapped into a 2N×2N array and
/// the pressure is zero-padded, so the cyclic convolution equals the exact linear one.
pub struct FreeOperator {
    grid: Grid,
    contact_modulus: f64,
    self_compliance: f64,
    engine: SpectralConvolution,
    /// The same kernel in single precision, for [`ElasticOperator::apply_single`].
    single: SpectralConvolution<f32>,
    applications: u64,
}

impl FreeOperator {
    /// Plans the transforms and computes the kernel spectrum for `grid` and `material`.
    pub fn new(grid: Grid, material: ElasticMaterial) -> Self {
        let n = grid.n();
        let padded = 2 * n;
        let delta = grid.element_size();
        let modulus = material.contact_modulus();
        // |offset| in elements for a wrapped index; the row n of the padded array is zero.
        let wrap = |i: usize| -> Option<usize> {
            match i {
                i if i < n => Some(i),
                i if i == n => None,
                i => Some(padded - i),
            }
        };
        let quadrant = love_quadrant(n, delta, modulus);
        let engine = SpectralConvolution::new(n, padded, |i, j| match (wrap(i), wrap(j)) {
            (Some(m), Some(l)) => quadrant[m * n + l],
            _ => 0.0,
        });
        Self {
            grid,
            contact_modulus: modulus,
            self_compliance: love_coefficient(0.0, 0.0, delta, modulus),
            single: engine.to_single(),
            engine,
            applications: 0,
        }
    }
}

impl ElasticOperator for FreeOperator {
    fn grid(&self) -> &Grid {
        &self.grid
    }
    fn contact_modulus(&self) -> f64 {
        self.contact_modulus
    }
    fn apply(&mut self, pressure: &[f64], displacement: &mut [f64]) {
        self.engine.convolve(pressure, displacement);
        self.applications += 1;
    }
    fn apply_single(&mut self, pressure: &[f64], displacement: &mut [f64]) {
        self.single.convolve(pressure, displacement);
        self.applications += 1;
    }
    fn self_compliance(&self) -> f64 {
        self.self_compliance
    }
    fn applications(&self) -> u64 {
        self.applications
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mirrored_quadrant_has_the_bits_of_direct_evaluation() {
        // Every signed offset of the padded kernel, against a direct evaluation.
        let (n, delta, modulus) = (12, 0.013, 2.5);
        let quadrant = love_quadrant(n, delta, modulus);
        for m in -(n as i64 - 1)..n as i64 {
            for l in -(n as i64 - 1)..n as i64 {
                let direct = love_coefficient(l as f64 * delta, m as f64 * delta, delta, modulus);
                let mirrored = quadrant[m.unsigned_abs() as usize * n + l.unsigned_abs() as usize];
                assert_eq!(mirrored.to_bits(), direct.to_bits(), "offset ({l}, {m})");
            }
        }
    }
}
