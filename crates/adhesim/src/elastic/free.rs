use super::influence::love_coefficient;
use super::spectral::SpectralConvolution;
use super::ElasticOperator;
use crate::grid::Grid;
use crate::material::ElasticMaterial;

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
        let wrap = |i: usize| -> Option<f64> {
            match i {
                i if i < n => Some(i as f64),
                i if i == n => None,
                i => Some(i as f64 - padded as f64),
            }
        };
        let engine = SpectralConvolution::new(n, padded, |i, j| match (wrap(i), wrap(j)) {
            (Some(m), Some(l)) => love_coefficient(l * delta, m * delta, delta, modulus),
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
