//! The periodic tangential half-space: Cerruti's surface compliance as a Fourier
//! multiplier, element-consistent as the periodic normal operator's.

use super::cerruti::ShearMaterial;
use super::layer_shear::layer_shear_multiplier;
use super::periodic::{sinc, ALIASES};
use super::spectral::SpectralConvolution;
use super::ElasticLayer;
use crate::grid::Grid;
use std::f64::consts::TAU;

/// The signed shifted wavenumbers q + 2πm/Δ (|m| ≤ `ALIASES`) of wave `index` of an axis of
/// `n` elements of width `delta` (length `size`), each with its element's form factor
/// sinc(qΔ/2).
fn alias_table(index: usize, n: usize, delta: f64, size: f64) -> Vec<(f64, f64)> {
    let k = if index <= n / 2 {
        index as f64
    } else {
        index as f64 - n as f64
    };
    let q = TAU * k / size;
    (-ALIASES..=ALIASES)
        .map(|m| {
            let shifted = q + TAU * m as f64 / delta;
            (shifted, sinc(0.5 * shifted * delta))
        })
        .collect()
}

/// The alias tables of a periodic grid's real-transform columns (x, Nx/2 + 1 waves) or
/// rows (y, Ny waves).
pub(super) type AliasTables = Vec<Vec<(f64, f64)>>;

/// [`alias_table`] of every column wave (x) and row wave (y) of `grid`.
pub(super) fn alias_tables(grid: &Grid) -> (AliasTables, AliasTables) {
    let (nx, ny) = (grid.nx(), grid.ny());
    let x_tables = (0..nx / 2 + 1)
        .map(|i| alias_table(i, nx, grid.dx(), grid.size_x()))
        .collect();
    let y_tables = (0..ny).map(|i| alias_table(i, ny, grid.dy(), grid.size_y())).collect();
    (x_tables, y_tables)
}

/// The three spectra of a periodic grid: K̂_xx, K̂_yy and K̂_xy (None at ν = 0), laid out
/// for [`SpectralConvolution`] with no padding.
///
/// Cerruti's surface displacements transform to K̂_xx(Q) = (1 − ν Q_x²/Q²)/(G Q),
/// K̂_yy(Q) = (1 − ν Q_y²/Q²)/(G Q) and K̂_xy(Q) = −ν Q_x Q_y/(G Q³) (docs/physics.md
/// §8.1); each is summed over the aliases Q = q + G_mn (|m|, |n| ≤ 40, as the periodic
/// normal operator's) with the element's form factor sinc(Q_xΔx/2)·sinc(Q_yΔy/2), so that
/// a uniform traction on each element, collocated at its centre, is what the operator
/// sees, as on the free grid. K̂(0) = 0: the mean
/// tangential displacement of a periodic half-space is undefined, so a shift here is
/// the indenter's relative to the surface's mean displacement. K̂_xy is odd in each
/// wavenumber and so zero on the Nyquist row and column of an even grid.
///
/// On a bonded `layer` each alias carries the layer's compliance tensor at its own
/// wavenumber instead (`layer_shear`); K̂(0) = 0 as on the half-space, which leaves out the
/// layer's uniform simple shear t·q̄/G (as the periodic normal operators leave out the
/// uniform compression), and K̂_xy is there at every ν.
pub(super) fn periodic_spectra(
    grid: &Grid,
    material: ShearMaterial,
    layer: Option<&ElasticLayer>,
) -> (SpectralConvolution, SpectralConvolution, Option<Vec<f64>>) {
    let (nx, ny) = (grid.nx(), grid.ny());
    let (g, nu) = (material.shear_modulus, material.poisson_ratio);
    let columns = nx / 2 + 1;
    let (x_tables, y_tables) = alias_tables(grid);
    let normalisation = 1.0 / (nx as f64 * ny as f64 * g);
    // [xx, yy, xy] at (row, column).
    let entry = |row: usize, column: usize| -> [f64; 3] {
        if row == 0 && column == 0 {
            return [0.0; 3];
        }
        let mut sums = [0.0; 3];
        for &(qx, sx) in &x_tables[column] {
            for &(qy, sy) in &y_tables[row] {
                match layer {
                    None => {
                        let squared = qx * qx + qy * qy;
                        let wavenumber = squared.sqrt();
                        let weight = sx * sy / wavenumber;
                        sums[0] += weight * (1.0 - nu * qx * qx / squared);
                        sums[1] += weight * (1.0 - nu * qy * qy / squared);
                        sums[2] -= weight * nu * qx * qy / squared;
                    }
                    Some(layer) => {
                        let multiplier = layer_shear_multiplier(qx, qy, layer.thickness(), nu);
                        for (sum, value) in sums.iter_mut().zip(multiplier) {
                            *sum += sx * sy * value;
                        }
                    }
                }
            }
        }
        let nyquist = (nx % 2 == 0 && column == nx / 2) || (ny % 2 == 0 && row == ny / 2);
        if nyquist {
            sums[2] = 0.0;
        }
        sums.map(|sum| sum * normalisation)
    };
    let values: Vec<[f64; 3]> = {
        use rayon::prelude::*;
        (0..ny * columns)
            .into_par_iter()
            .map(|k| entry(k / columns, k % columns))
            .collect()
    };
    let engine = |component: usize| {
        let mut engine = SpectralConvolution::planned((nx, ny), (nx, ny));
        engine.set_kernel_spectrum(|row, column| values[row * columns + column][component]);
        engine
    };
    let cross = (nu != 0.0 || layer.is_some()).then(|| engine(2).into_kernel());
    (engine(0), engine(1), cross)
}
