//! A 2-D real-to-complex transform with a complex kernel spectrum: the coupling kernels are
//! odd in one offset, so their spectra are imaginary, which the operators' engine
//! (`spectral.rs`, real even spectra only) does not take.

use super::super::planner;
use num_complex::Complex;
use rayon::prelude::*;
use realfft::{ComplexToReal, RealToComplex};
use rustfft::Fft;
use std::sync::Arc;

/// Forward and inverse transforms of Ny data rows of Nx values zero-padded to
/// padded_y × padded_x; spectra are column-major, `[column * padded_y + row]`, over the
/// padded_x/2 + 1 columns of the real transform.
pub(super) struct Transform2d {
    nx: usize,
    ny: usize,
    padded_x: usize,
    padded_y: usize,
    forward_rows: Arc<dyn RealToComplex<f64>>,
    inverse_rows: Arc<dyn ComplexToReal<f64>>,
    forward_columns: Arc<dyn Fft<f64>>,
    inverse_columns: Arc<dyn Fft<f64>>,
    /// Row spectra of the data rows, `[row * columns + column]`.
    rows: Vec<Complex<f64>>,
}

impl Transform2d {
    /// Plans the transforms (`data` = (Nx, Ny), `padded` = (padded_x, padded_y)).
    pub(super) fn new(data: (usize, usize), padded: (usize, usize)) -> Self {
        let ((nx, ny), (padded_x, padded_y)) = (data, padded);
        Self {
            nx,
            ny,
            padded_x,
            padded_y,
            forward_rows: planner::real_forward(padded_x),
            inverse_rows: planner::real_inverse(padded_x),
            forward_columns: planner::complex_forward(padded_y),
            inverse_columns: planner::complex_inverse(padded_y),
            rows: vec![Complex::default(); ny * (padded_x / 2 + 1)],
        }
    }

    /// Complex columns of a spectrum.
    pub(super) fn columns(&self) -> usize {
        self.padded_x / 2 + 1
    }

    /// Values of a spectrum.
    pub(super) fn spectrum_len(&self) -> usize {
        self.columns() * self.padded_y
    }

    /// `spectrum` = the transform of `input` (Nx·Ny values, row-major), zero outside it.
    pub(super) fn forward(&mut self, input: &[f64], spectrum: &mut [Complex<f64>]) {
        let (nx, columns, padded_y) = (self.nx, self.columns(), self.padded_y);
        assert_eq!(input.len(), nx * self.ny, "input field does not match the grid");
        assert_eq!(
            spectrum.len(),
            self.spectrum_len(),
            "spectrum does not match the transform"
        );
        let (forward_rows, padded_x) = (&self.forward_rows, self.padded_x);
        self.rows
            .par_chunks_mut(columns)
            .zip(input.par_chunks(nx))
            .for_each_init(
                || (vec![0.0; padded_x], forward_rows.make_scratch_vec()),
                |(real, scratch), (row, values)| {
                    real[..nx].copy_from_slice(values);
                    real[nx..].fill(0.0);
                    forward_rows
                        .process_with_scratch(real, row, scratch)
                        .expect("row transform sizes are planned");
                },
            );
        let (rows, ny, forward_columns) = (&self.rows, self.ny, &self.forward_columns);
        spectrum
            .par_chunks_mut(padded_y)
            .enumerate()
            .for_each(|(column, values)| {
                for (row, value) in values.iter_mut().enumerate() {
                    *value = if row < ny {
                        rows[row * columns + column]
                    } else {
                        Complex::default()
                    };
                }
                forward_columns.process(values);
            });
    }

    /// `output` (Nx·Ny values) = the data window of the inverse transform of `spectrum`
    /// (not normalised; `spectrum` is overwritten).
    pub(super) fn inverse(&mut self, spectrum: &mut [Complex<f64>], output: &mut [f64]) {
        let (nx, columns, padded_y) = (self.nx, self.columns(), self.padded_y);
        assert_eq!(output.len(), nx * self.ny, "output field does not match the grid");
        assert_eq!(
            spectrum.len(),
            self.spectrum_len(),
            "spectrum does not match the transform"
        );
        let inverse_columns = &self.inverse_columns;
        spectrum
            .par_chunks_mut(padded_y)
            .for_each(|values| inverse_columns.process(values));
        let (inverse_rows, padded_x) = (&self.inverse_rows, self.padded_x);
        let spectrum = &*spectrum;
        output.par_chunks_mut(nx).enumerate().for_each_init(
            || {
                (
                    vec![Complex::default(); columns],
                    vec![0.0; padded_x],
                    inverse_rows.make_scratch_vec(),
                )
            },
            |(row_spectrum, real, scratch), (row, values)| {
                for (column, value) in row_spectrum.iter_mut().enumerate() {
                    *value = spectrum[column * padded_y + row];
                }
                // The exact result is real: the imaginary parts of the zero and Nyquist
                // columns are rounding, which the real inverse must not see.
                row_spectrum[0].im = 0.0;
                if padded_x % 2 == 0 {
                    row_spectrum[columns - 1].im = 0.0;
                }
                inverse_rows
                    .process_with_scratch(row_spectrum, real, scratch)
                    .expect("row transform sizes are planned");
                values.copy_from_slice(&real[..nx]);
            },
        );
    }
}
