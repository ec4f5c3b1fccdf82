use super::spectral::SpectralConvolution;
use crate::grid::Grid;
use std::f64::consts::TAU;

/// Approximate inverse of the half-space compliance, r ↦ F⁻¹[(E*/2)·√(|q|² + q0²)·F r]
/// on the unpadded Nx×Ny grid (q0 = 2π/max(Lx, Ly) keeps the mean mode invertible).
///
/// The compliance is ≈ 2/(E*|q|) in Fourier space, so this stiffness multiplier clusters
/// the spectrum of the compliance restricted to a contact set: the |q| spectral
/// preconditioner used for half-space conjugate gradients (e.g. Bazrafshan, de Rooij &
/// Schipper, *Tribol. Int.* 2017; the ASPHER code). One application is an N×N real FFT
/// pair in single precision, about a sixth of the zero-padded operator's cost.
pub struct SpectralPreconditioner {
    engine: SpectralConvolution<f32>,
}

impl SpectralPreconditioner {
    /// Plans the transforms for `grid` and contact modulus E*.
    pub fn new(grid: &Grid, contact_modulus: f64) -> Self {
        let (nx, ny) = (grid.nx(), grid.ny());
        // Single precision: an approximate inverse gains nothing from f64.
        let mut engine = SpectralConvolution::<f32>::planned((nx, ny), (nx, ny));
        let frequency = |index: usize, n: usize, size: f64| -> f64 {
            let k = if index <= n / 2 {
                index as f64
            } else {
                index as f64 - n as f64
            };
            TAU * k / size
        };
        // q0: the lowest wavenumber of the longer side.
        let lowest = TAU / grid.size_x().max(grid.size_y());
        let normalisation = 1.0 / (nx as f64 * ny as f64);
        engine.set_kernel_spectrum(|row, column| {
            let (qy, qx) = (frequency(row, ny, grid.size_y()), frequency(column, nx, grid.size_x()));
            0.5 * contact_modulus * (qx * qx + qy * qy + lowest * lowest).sqrt() * normalisation
        });
        Self { engine }
    }

    /// Writes the preconditioned field.
    pub fn apply(&mut self, field: &[f64], result: &mut [f64]) {
        self.engine.convolve(field, result);
    }

    /// As [`apply`](Self::apply) for a field that vanishes outside `rows`, written on
    /// `rows` only (other rows of `result` are left as they are): the bits of `apply` there.
    pub fn apply_rows(&mut self, field: &[f64], result: &mut [f64], rows: std::ops::Range<usize>) {
        self.engine.convolve_rows(field, result, rows.clone(), rows);
    }
}
