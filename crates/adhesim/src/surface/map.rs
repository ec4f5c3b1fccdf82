//! Statistics of a measured height map: a rectangle of `nx × ny` points with its own spacings
//! `dx`, `dy` and points that may hold no data (a validity mask), as instruments record
//! them. The finite-difference forms are SurfaceTopography's (`rms_height_from_area`,
//! `rms_gradient`, `rms_curvature_from_area`, version 1.27) stencil for stencil, so the two
//! agree to rounding on the same valid map; the spectral forms are the Parseval sums of a
//! periodic map, as [`super::rms_slope`] on a periodic grid.

use super::{PsdBin, SurfaceError};
use crate::elastic::planner;
use num_complex::Complex;
use std::f64::consts::{PI, TAU};

/// A height map on a rectangular grid: `heights[iy * nx + ix]` at `x = ix·dx`, `y = iy·dy`.
/// Points that are `false` in `valid` hold no data: every statistic leaves them out (their
/// height is never read).
#[derive(Debug, Clone, Copy)]
pub struct HeightMap<'a> {
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    heights: &'a [f64],
    valid: Option<&'a [bool]>,
    periodic: bool,
}

/// Which definition a slope or curvature follows, for labels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Derivative {
    /// Finite differences (SurfaceTopography's stencils).
    FiniteDifferences,
    /// Exact derivatives of the map's Fourier series (periodic, fully valid maps).
    Spectral,
}

impl<'a> HeightMap<'a> {
    /// Checks that the sizes match, the spacings are positive and every valid height is
    /// finite, and that at least one point is valid.
    pub fn new(
        (nx, ny): (usize, usize),
        (dx, dy): (f64, f64),
        heights: &'a [f64],
        valid: Option<&'a [bool]>,
        periodic: bool,
    ) -> Result<Self, SurfaceError> {
        super::positive("dx", dx)?;
        super::positive("dy", dy)?;
        let expected = nx.saturating_mul(ny);
        if heights.len() != expected {
            return Err(SurfaceError::SizeMismatch {
                expected,
                got: heights.len(),
            });
        }
        if let Some(mask) = valid {
            if mask.len() != expected {
                return Err(SurfaceError::SizeMismatch {
                    expected,
                    got: mask.len(),
                });
            }
        }
        let map = Self {
            nx,
            ny,
            dx,
            dy,
            heights,
            valid,
            periodic,
        };
        if let Some(index) = (0..expected).find(|&k| map.is_valid(k) && !heights[k].is_finite()) {
            return Err(SurfaceError::NonFiniteHeight {
                index,
                row: index / nx,
                column: index % nx,
                value: heights[index],
            });
        }
        if map.valid_count() == 0 {
            return Err(SurfaceError::NoValidPoint);
        }
        Ok(map)
    }

    fn is_valid(&self, k: usize) -> bool {
        self.valid.is_none_or(|mask| mask[k])
    }

    /// Points that hold data.
    pub fn valid_count(&self) -> usize {
        self.valid
            .map_or(self.heights.len(), |mask| mask.iter().filter(|&&v| v).count())
    }

    fn mean(&self) -> f64 {
        let sum: f64 = (0..self.heights.len())
            .filter(|&k| self.is_valid(k))
            .map(|k| self.heights[k])
            .sum();
        sum / self.valid_count() as f64
    }

    /// rms height about the mean of the valid points, ⟨(h − h̄)²⟩^½ over the valid points
    /// (SurfaceTopography's `rms_height_from_area`, which drops masked points).
    pub fn rms_height(&self) -> f64 {
        let mean = self.mean();
        let sum: f64 = (0..self.heights.len())
            .filter(|&k| self.is_valid(k))
            .map(|k| (self.heights[k] - mean).powi(2))
            .sum();
        (sum / self.valid_count() as f64).sqrt()
    }

    /// Index of the point `steps` away along x and y, wrapping on a periodic map; `None`
    /// past the edge of a free map.
    fn offset(&self, ix: usize, iy: usize, step_x: isize, step_y: isize) -> Option<usize> {
        let shift = |i: usize, step: isize, n: usize| -> Option<usize> {
            let j = i as isize + step;
            if self.periodic {
                Some(j.rem_euclid(n as isize) as usize)
            } else {
                (0..n as isize).contains(&j).then_some(j as usize)
            }
        };
        Some(shift(iy, step_y, self.ny)? * self.nx + shift(ix, step_x, self.nx)?)
    }

    /// rms gradient ⟨(∂h/∂x)² + (∂h/∂y)²⟩^½ from forward differences
    /// (h[ix+1, iy] − h[ix, iy])/dx and (h[ix, iy+1] − h[ix, iy])/dy taken at the same point:
    /// SurfaceTopography's `rms_gradient`, which on a free map averages over the
    /// (nx − 1)(ny − 1) points that have both forward neighbours (wrapping around, nx·ny
    /// points, on a periodic map). A point counts where it and both neighbours are valid.
    /// `None` when no point has both differences (a map of one row or column).
    pub fn rms_slope_finite_differences(&self) -> Option<f64> {
        let (mut sum, mut count) = (0.0, 0usize);
        for iy in 0..self.ny {
            for ix in 0..self.nx {
                let k = iy * self.nx + ix;
                let (Some(kx), Some(ky)) = (self.offset(ix, iy, 1, 0), self.offset(ix, iy, 0, 1)) else {
                    continue;
                };
                if !(self.is_valid(k) && self.is_valid(kx) && self.is_valid(ky)) {
                    continue;
                }
                let slope_x = (self.heights[kx] - self.heights[k]) / self.dx;
                let slope_y = (self.heights[ky] - self.heights[k]) / self.dy;
                sum += slope_x * slope_x + slope_y * slope_y;
                count += 1;
            }
        }
        (count > 0).then(|| (sum / count as f64).sqrt())
    }

    /// rms mean curvature ⟨(∇²h/2)²⟩^½ from the five-point Laplacian with the true spacings,
    /// (h[ix±1] − 2h)/dx² + (h[iy±1] − 2h)/dy², on the (nx − 2)(ny − 2) interior points of
    /// a free map (every point of a periodic one): SurfaceTopography's
    /// `rms_curvature_from_area`. A point counts where its five stencil points are valid.
    /// `None` when no point has a full stencil (fewer than 3 points along a side).
    pub fn rms_curvature_finite_differences(&self) -> Option<f64> {
        let (mut sum, mut count) = (0.0, 0usize);
        for iy in 0..self.ny {
            for ix in 0..self.nx {
                let k = iy * self.nx + ix;
                let neighbours = [(-1, 0), (1, 0), (0, -1), (0, 1)].map(|(sx, sy)| self.offset(ix, iy, sx, sy));
                let [Some(west), Some(east), Some(south), Some(north)] = neighbours else {
                    continue;
                };
                if ![k, west, east, south, north].iter().all(|&p| self.is_valid(p)) {
                    continue;
                }
                let h = &self.heights;
                let laplacian = (h[west] + h[east] - 2.0 * h[k]) / (self.dx * self.dx)
                    + (h[south] + h[north] - 2.0 * h[k]) / (self.dy * self.dy);
                sum += laplacian * laplacian;
                count += 1;
            }
        }
        (count > 0).then(|| (sum / count as f64).sqrt() / 2.0)
    }

    /// Spectral rms slope and rms mean curvature of a periodic map with every point valid:
    /// h'_rms² = (1/N²)·Σ_q |q|²·|H(q)|² and κ_rms² = (1/N²)·Σ_q (|q|²/2)²·|H(q)|² over every
    /// lattice mode q = 2π(k_x/L_x, k_y/L_y) (N = nx·ny; the Nyquist modes with their |q|).
    /// `None` for a free map (its edges do not match, and the jump would be differentiated)
    /// or one with invalid points.
    pub fn spectral_slope_and_curvature(&self) -> Option<(f64, f64)> {
        if !self.periodic || self.valid_count() != self.heights.len() {
            return None;
        }
        let spectrum = forward_transform(self.heights, self.nx, self.ny);
        let columns = self.nx / 2 + 1;
        let (qx0, qy0) = (TAU / (self.nx as f64 * self.dx), TAU / (self.ny as f64 * self.dy));
        let (mut slope, mut curvature) = (0.0, 0.0);
        for row in 0..self.ny {
            let ky = signed_index(row, self.ny);
            for column in 0..columns {
                let multiplicity = if column == 0 || 2 * column == self.nx { 1.0 } else { 2.0 };
                let q2 = (qx0 * column as f64).powi(2) + (qy0 * ky).powi(2);
                let power = multiplicity * spectrum[row * columns + column].norm_sqr();
                slope += q2 * power;
                curvature += q2 * q2 / 4.0 * power;
            }
        }
        let n2 = (self.heights.len() as f64).powi(2);
        Some(((slope / n2).sqrt(), (curvature / n2).sqrt()))
    }

    /// Isotropic PSD C(q) = A/N²·|H(q)|² (A = L_x·L_y, N = nx·ny) of the valid heights minus
    /// their mean, in `bins` logarithmic bins from 2π/max(L_x, L_y) to min(π/dx, π/dy).
    /// Invalid points enter as zero (no power); a free map is multiplied by the separable
    /// Hann window of [`super::isotropic_psd`]. The window and the mask are compensated by
    /// scaling so that Σ_q C(q)/A equals the variance of the valid heights for a map whose
    /// power is spread evenly over it: s² = N / Σ_valid w².
    pub fn isotropic_psd(&self, bins: usize) -> Result<Vec<PsdBin>, SurfaceError> {
        if bins == 0 {
            return Err(SurfaceError::NoBins);
        }
        if bins > super::MAX_PSD_BINS {
            return Err(SurfaceError::TooManyBins(bins));
        }
        let (nx, ny) = (self.nx, self.ny);
        let hann = |n: usize| -> Vec<f64> {
            (0..n)
                .map(|j| {
                    if self.periodic {
                        1.0
                    } else {
                        (PI * (j as f64 + 0.5) / n as f64).sin().powi(2)
                    }
                })
                .collect()
        };
        let (window_x, window_y) = (hann(nx), hann(ny));
        let mean = self.mean();
        let mut weight_sum = 0.0;
        let mut centred = vec![0.0; nx * ny];
        for iy in 0..ny {
            for ix in 0..nx {
                let k = iy * nx + ix;
                if self.is_valid(k) {
                    let w = window_x[ix] * window_y[iy];
                    centred[k] = (self.heights[k] - mean) * w;
                    weight_sum += w * w;
                }
            }
        }
        let scale2 = (nx * ny) as f64 / weight_sum;
        let spectrum = forward_transform(&centred, nx, ny);
        let columns = nx / 2 + 1;
        let (lx, ly) = (nx as f64 * self.dx, ny as f64 * self.dy);
        let (qx0, qy0) = (TAU / lx, TAU / ly);
        let lowest = TAU / lx.max(ly);
        let highest = (PI / self.dx).min(PI / self.dy);
        let log_span = (highest / lowest).ln().max(f64::MIN_POSITIVE);
        let normalisation = scale2 * lx * ly / ((nx * ny) as f64).powi(2);
        let mut sums = vec![(0.0, 0.0, 0usize); bins];
        for row in 0..ny {
            let ky = signed_index(row, ny);
            for column in 0..columns {
                let q = ((qx0 * column as f64).powi(2) + (qy0 * ky).powi(2)).sqrt();
                if q < lowest * (1.0 - 1e-12) || q > highest * (1.0 + 1e-12) {
                    continue;
                }
                let position = ((q / lowest).ln() / log_span * bins as f64).floor();
                let bin = (position.max(0.0) as usize).min(bins - 1);
                let multiplicity = if column == 0 || 2 * column == nx { 1 } else { 2 };
                let power = normalisation * spectrum[row * columns + column].norm_sqr();
                let entry = &mut sums[bin];
                entry.0 += multiplicity as f64 * q;
                entry.1 += multiplicity as f64 * power;
                entry.2 += multiplicity;
            }
        }
        let edge = |b: usize| lowest * (log_span * b as f64 / bins as f64).exp();
        Ok(sums
            .iter()
            .enumerate()
            .filter(|(_, entry)| entry.2 > 0)
            .map(|(bin, &(sum_q, sum_power, modes))| PsdBin {
                edges: (edge(bin), edge(bin + 1)),
                wavevector: sum_q / modes as f64,
                psd: sum_power / modes as f64,
                modes,
            })
            .collect())
    }
}

/// The wavenumber index of DFT row `row` of `n`: 0..=n/2, then negative.
fn signed_index(row: usize, n: usize) -> f64 {
    if row <= n / 2 {
        row as f64
    } else {
        row as f64 - n as f64
    }
}

/// Half spectrum H(q) = Σ_x h(x)·e^(−iq·x) of an `nx × ny` row-major map: `ny` rows of
/// `nx/2 + 1` columns (also the square grids' statistics, nx = ny).
pub(super) fn forward_transform(heights: &[f64], nx: usize, ny: usize) -> Vec<Complex<f64>> {
    let columns = nx / 2 + 1;
    let row_fft = planner::real_forward::<f64>(nx);
    let mut spectrum = vec![Complex::new(0.0, 0.0); ny * columns];
    let mut input = vec![0.0; nx];
    let mut scratch = row_fft.make_scratch_vec();
    for row in 0..ny {
        input.copy_from_slice(&heights[row * nx..(row + 1) * nx]);
        row_fft
            .process_with_scratch(
                &mut input,
                &mut spectrum[row * columns..(row + 1) * columns],
                &mut scratch,
            )
            .expect("buffer lengths match the plan");
    }
    let column_fft = planner::complex_forward::<f64>(ny);
    let mut buffer = vec![Complex::new(0.0, 0.0); ny];
    let mut column_scratch = vec![Complex::new(0.0, 0.0); column_fft.get_inplace_scratch_len()];
    for column in 0..columns {
        for row in 0..ny {
            buffer[row] = spectrum[row * columns + column];
        }
        column_fft.process_with_scratch(&mut buffer, &mut column_scratch);
        for row in 0..ny {
            spectrum[row * columns + column] = buffer[row];
        }
    }
    spectrum
}
