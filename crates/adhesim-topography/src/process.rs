//! Processing of measured maps: mean-plane detrending and resampling onto a simulation grid.

use std::fmt;

use rustfft::num_complex::Complex;
use rustfft::FftPlanner;

use crate::bytes::MAX_POINTS;
use crate::{Topography, TopographyError};

/// How [`Topography::resample_with`] interpolates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ResampleMethod {
    /// Spectral when the target is finer than the measurement in both directions, bilinear
    /// otherwise.
    Auto,
    /// Bilinear interpolation between the four surrounding measured points.
    Bilinear,
    /// Zero padding in Fourier space (the map is taken as periodic with period
    /// `nx·dx` × `ny·dy`), then bilinear between the refined points, which is exact where a
    /// target point falls on one (target spacing dividing the period).
    Spectral,
}

/// The target grid is coarser than the measurement: wavelengths between the two spacings are
/// lost or aliased. The caller decides whether to warn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Undersampling {
    pub measured_dx: f64,
    pub measured_dy: f64,
    pub target_dx: f64,
    pub target_dy: f64,
}

impl fmt::Display for Undersampling {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "the grid spacing {:.4e} m × {:.4e} m is coarser than the measurement's {:.4e} m × {:.4e} m \
             (by {:.3} × {:.3}): roughness on scales below the grid spacing is not resolved",
            self.target_dx,
            self.target_dy,
            self.measured_dx,
            self.measured_dy,
            self.target_dx / self.measured_dx,
            self.target_dy / self.measured_dy
        )
    }
}

/// A resampled map, the method used and, when the target undersamples the measurement, by how
/// much.
#[derive(Clone, Debug, PartialEq)]
pub struct Resampled {
    pub topography: Topography,
    pub method: ResampleMethod,
    pub undersampling: Option<Undersampling>,
}

/// Relative slack on grid extents and spacings (rounding of spacings read from files).
const GRID_TOLERANCE: f64 = 1e-9;

impl Topography {
    /// Subtracts the least-squares plane `a + b·x + c·y` fitted to the valid points and
    /// returns `(a, b, c)` (metres, and slopes). Invalid points are set to 0, the mean of the
    /// detrended valid heights. A map inconsistent with its sizes (a hand-built
    /// [`Topography`]) or without a finite valid point is an error.
    pub fn detrend_mean_plane(&mut self) -> Result<(f64, f64, f64), TopographyError> {
        self.check_consistent()?;
        let valid = |i: usize| self.mask.as_ref().is_none_or(|m| m[i]);
        // Centred coordinates keep the normal equations well conditioned.
        let (mut n, mut sx, mut sy) = (0.0, 0.0, 0.0);
        for iy in 0..self.ny {
            for ix in 0..self.nx {
                if valid(iy * self.nx + ix) {
                    n += 1.0;
                    sx += ix as f64;
                    sy += iy as f64;
                }
            }
        }
        let (cx, cy) = (sx / n, sy / n);
        let mut m = [[0.0f64; 3]; 3];
        let mut rhs = [0.0f64; 3];
        for iy in 0..self.ny {
            for ix in 0..self.nx {
                let i = iy * self.nx + ix;
                if !valid(i) {
                    continue;
                }
                let basis = [1.0, ix as f64 - cx, iy as f64 - cy];
                for r in 0..3 {
                    rhs[r] += basis[r] * self.heights[i];
                    for c in 0..3 {
                        m[r][c] += basis[r] * basis[c];
                    }
                }
            }
        }
        let [mean, slope_ix, slope_iy] = solve3(m, rhs);
        for iy in 0..self.ny {
            for ix in 0..self.nx {
                let i = iy * self.nx + ix;
                self.heights[i] = if valid(i) {
                    self.heights[i] - (mean + slope_ix * (ix as f64 - cx) + slope_iy * (iy as f64 - cy))
                } else {
                    0.0
                };
            }
        }
        let (b, c) = (slope_ix / self.dx, slope_iy / self.dy);
        // The plane in the map's own coordinates x = x_offset + ix·dx.
        let a = mean - slope_ix * cx - slope_iy * cy - b * self.x_offset - c * self.y_offset;
        Ok((a, b, c))
    }

    /// Checks what the readers guarantee, for maps built by hand: sizes match the data,
    /// positive spacings, finite heights, at least one valid point.
    pub fn check_consistent(&self) -> Result<(), TopographyError> {
        let count = self.nx.checked_mul(self.ny).filter(|&n| n > 0 && n <= MAX_POINTS);
        let why = if count != Some(self.heights.len()) {
            Some(format!(
                "{} heights for {} × {} points",
                self.heights.len(),
                self.nx,
                self.ny
            ))
        } else if self.mask.as_ref().is_some_and(|m| m.len() != self.heights.len()) {
            Some("the mask and the heights differ in length".to_string())
        } else if !(self.dx > 0.0 && self.dy > 0.0 && self.dx.is_finite() && self.dy.is_finite()) {
            Some(format!("spacing {} × {} m is not positive", self.dx, self.dy))
        } else if self.heights.iter().any(|h| !h.is_finite()) {
            Some("a height is not finite".to_string())
        } else if self.mask.as_ref().is_some_and(|m| !m.iter().any(|&v| v)) {
            Some("no point is valid".to_string())
        } else {
            None
        };
        match why {
            Some(why) => Err(TopographyError::InvalidArgument {
                name: "topography",
                value: format!("channel {:?}", self.channel),
                why,
            }),
            None => Ok(()),
        }
    }

    /// Resamples onto `nx × ny` points of spacing `dx × dy` (metres) starting at the first
    /// measured point, with [`ResampleMethod::Auto`].
    pub fn resample_to(&self, nx: usize, ny: usize, dx: f64, dy: f64) -> Result<Resampled, TopographyError> {
        self.resample_with(nx, ny, dx, dy, ResampleMethod::Auto)
    }

    /// Resamples onto `nx × ny` points of spacing `dx × dy` with the given method. The target
    /// must lie inside the measurement (bilinear: `(nx−1)·dx ≤ (nx_m−1)·dx_m`; spectral, which
    /// takes the map as periodic: `nx·dx ≤ nx_m·dx_m`), else an error names the sizes.
    pub fn resample_with(
        &self,
        nx: usize,
        ny: usize,
        dx: f64,
        dy: f64,
        method: ResampleMethod,
    ) -> Result<Resampled, TopographyError> {
        self.check_consistent()?;
        check_target(nx, ny, dx, dy)?;
        let finer = dx < self.dx && dy < self.dy;
        let method = match method {
            ResampleMethod::Auto if finer => ResampleMethod::Spectral,
            ResampleMethod::Auto => ResampleMethod::Bilinear,
            other => other,
        };
        let periodic = method == ResampleMethod::Spectral;
        let (extent_x, extent_y) = if periodic {
            (self.nx as f64 * self.dx, self.ny as f64 * self.dy)
        } else {
            ((self.nx - 1) as f64 * self.dx, (self.ny - 1) as f64 * self.dy)
        };
        let (need_x, need_y) = if periodic {
            (nx as f64 * dx, ny as f64 * dy)
        } else {
            ((nx - 1) as f64 * dx, (ny - 1) as f64 * dy)
        };
        if need_x > extent_x * (1.0 + GRID_TOLERANCE) || need_y > extent_y * (1.0 + GRID_TOLERANCE) {
            return Err(TopographyError::InvalidArgument {
                name: "resampling grid",
                value: format!("{nx} × {ny} points of {dx:e} m × {dy:e} m"),
                why: format!(
                    "it spans {need_x:e} m × {need_y:e} m, more than the measurement's {extent_x:e} m × {extent_y:e} m ({} method)",
                    if periodic { "spectral" } else { "bilinear" }
                ),
            });
        }
        let undersampling =
            (dx > self.dx * (1.0 + GRID_TOLERANCE) || dy > self.dy * (1.0 + GRID_TOLERANCE)).then_some(Undersampling {
                measured_dx: self.dx,
                measured_dy: self.dy,
                target_dx: dx,
                target_dy: dy,
            });
        let heights = if periodic {
            let (rx, ry) = (
                refined_count(self.nx, self.dx, dx)?,
                refined_count(self.ny, self.dy, dy)?,
            );
            let refined = spectral_upsample(&self.heights, self.nx, self.ny, rx, ry);
            let (sx, sy) = (extent_x / rx as f64, extent_y / ry as f64);
            sample_grid(&refined, rx, ry, sx, sy, true, nx, ny, dx, dy)
        } else {
            sample_grid(&self.heights, self.nx, self.ny, self.dx, self.dy, false, nx, ny, dx, dy)
        };
        let mask = self.mask.as_ref().map(|mask| {
            // Nearest measured point decides validity.
            let mut out = Vec::with_capacity(nx * ny);
            for iy in 0..ny {
                for ix in 0..nx {
                    let mx = ((ix as f64 * dx / self.dx).round() as usize) % self.nx;
                    let my = ((iy as f64 * dy / self.dy).round() as usize) % self.ny;
                    out.push(mask[my * self.nx + mx]);
                }
            }
            out
        });
        let mut topography = self.clone();
        topography.nx = nx;
        topography.ny = ny;
        topography.dx = dx;
        topography.dy = dy;
        topography.heights = heights;
        topography.mask = mask.filter(|m| m.iter().any(|&v| !v));
        Ok(Resampled {
            topography,
            method,
            undersampling,
        })
    }
}

fn check_target(nx: usize, ny: usize, dx: f64, dy: f64) -> Result<(), TopographyError> {
    if nx < 1 || ny < 1 || nx.checked_mul(ny).is_none_or(|n| n > MAX_POINTS) {
        return Err(TopographyError::InvalidArgument {
            name: "resampling grid size",
            value: format!("{nx} × {ny}"),
            why: format!("needs 1 to {MAX_POINTS} points"),
        });
    }
    for (name, value) in [("resampling dx", dx), ("resampling dy", dy)] {
        if !(value.is_finite() && value > 0.0) {
            return Err(TopographyError::InvalidArgument {
                name,
                value: format!("{value}"),
                why: "must be a positive length in metres".into(),
            });
        }
    }
    Ok(())
}

/// Points of the refined periodic grid: the fewest whose spacing `n·spacing/count` is at most
/// `target` (exactly `target` when it divides the period).
fn refined_count(n: usize, spacing: f64, target: f64) -> Result<usize, TopographyError> {
    let ratio = n as f64 * spacing / target;
    let count = if (ratio - ratio.round()).abs() < GRID_TOLERANCE * ratio {
        ratio.round()
    } else {
        ratio.ceil()
    };
    let count = (count as usize).max(n);
    if count > MAX_POINTS {
        return Err(TopographyError::InvalidArgument {
            name: "resampling dx/dy",
            value: format!("{target:e}"),
            why: format!("refining {n} points to {count} exceeds {MAX_POINTS}"),
        });
    }
    Ok(count)
}

/// Samples `values` (`nx × ny`, spacing `sx × sy`) bilinearly at `tx × ty` points of spacing
/// `dx × dy`; `periodic` wraps past the last point, otherwise the last cell is extended by
/// the rounding slack only.
#[allow(clippy::too_many_arguments)]
fn sample_grid(
    values: &[f64],
    nx: usize,
    ny: usize,
    sx: f64,
    sy: f64,
    periodic: bool,
    tx: usize,
    ty: usize,
    dx: f64,
    dy: f64,
) -> Vec<f64> {
    let locate = |position: f64, n: usize| -> (usize, usize, f64) {
        if n == 1 {
            return (0, 0, 0.0);
        }
        if periodic {
            let cell = position.floor();
            let i0 = (cell as usize) % n;
            (i0, (i0 + 1) % n, position - cell)
        } else {
            let i0 = (position.floor() as usize).min(n - 2);
            (i0, i0 + 1, (position - i0 as f64).clamp(0.0, 1.0))
        }
    };
    let mut out = Vec::with_capacity(tx * ty);
    for iy in 0..ty {
        let (y0, y1, fy) = locate(iy as f64 * dy / sy, ny);
        for ix in 0..tx {
            let (x0, x1, fx) = locate(ix as f64 * dx / sx, nx);
            let at = |x: usize, y: usize| values[y * nx + x];
            out.push(
                (1.0 - fy) * ((1.0 - fx) * at(x0, y0) + fx * at(x1, y0))
                    + fy * ((1.0 - fx) * at(x0, y1) + fx * at(x1, y1)),
            );
        }
    }
    out
}

/// Band-limited (trigonometric) interpolation of a periodic `nx × ny` map onto `rx × ry`
/// points by zero padding its discrete Fourier transform, rows first, then columns.
fn spectral_upsample(values: &[f64], nx: usize, ny: usize, rx: usize, ry: usize) -> Vec<f64> {
    let mut planner = FftPlanner::new();
    let rows = upsample_lines(values, nx, ny, rx, &mut planner);
    // Transpose so that columns become contiguous lines, upsample, transpose back.
    let mut columns = vec![0.0; rx * ny];
    for y in 0..ny {
        for x in 0..rx {
            columns[x * ny + y] = rows[y * rx + x];
        }
    }
    let refined_columns = upsample_lines(&columns, ny, rx, ry, &mut planner);
    let mut out = vec![0.0; rx * ry];
    for x in 0..rx {
        for y in 0..ry {
            out[y * rx + x] = refined_columns[x * ry + y];
        }
    }
    out
}

/// Upsamples each of `lines` contiguous lines of length `n` to length `m ≥ n`.
fn upsample_lines(values: &[f64], n: usize, lines: usize, m: usize, planner: &mut FftPlanner<f64>) -> Vec<f64> {
    let forward = planner.plan_fft_forward(n);
    let inverse = planner.plan_fft_inverse(m);
    let mut spectrum = vec![Complex::new(0.0, 0.0); n];
    let mut padded = vec![Complex::new(0.0, 0.0); m];
    let mut out = Vec::with_capacity(m * lines);
    let half = n / 2;
    for line in values.chunks_exact(n) {
        for (s, &v) in spectrum.iter_mut().zip(line) {
            *s = Complex::new(v, 0.0);
        }
        forward.process(&mut spectrum);
        padded.fill(Complex::new(0.0, 0.0));
        // Frequencies below Nyquist keep their place; an even length's Nyquist term is split
        // between +n/2 and −n/2 so the result stays real.
        for k in 0..n.div_ceil(2) {
            padded[k] = spectrum[k];
            if k > 0 {
                padded[m - k] = spectrum[n - k];
            }
        }
        if n.is_multiple_of(2) && n > 0 {
            if m == n {
                padded[half] = spectrum[half];
            } else {
                padded[half] = spectrum[half] * 0.5;
                padded[m - half] = spectrum[half] * 0.5;
            }
        }
        inverse.process(&mut padded);
        let scale = 1.0 / n as f64;
        out.extend(padded.iter().map(|c| c.re * scale));
    }
    out
}

/// Solves the symmetric 3×3 system by Gaussian elimination with partial pivoting; a singular
/// direction (a map one point wide) gets a zero coefficient.
fn solve3(mut m: [[f64; 3]; 3], mut rhs: [f64; 3]) -> [f64; 3] {
    let scale = m[0][0].abs().max(1.0);
    for col in 0..3 {
        let pivot = (col..3)
            .max_by(|&a, &b| m[a][col].abs().total_cmp(&m[b][col].abs()))
            .unwrap_or(col);
        m.swap(col, pivot);
        rhs.swap(col, pivot);
        if m[col][col].abs() <= 1e-12 * scale {
            continue;
        }
        for row in 0..3 {
            if row != col {
                let factor = m[row][col] / m[col][col];
                let pivot_row = m[col];
                for (value, p) in m[row].iter_mut().zip(pivot_row) {
                    *value -= factor * p;
                }
                rhs[row] -= factor * rhs[col];
            }
        }
    }
    let mut out = [0.0; 3];
    for i in 0..3 {
        if m[i][i].abs() > 1e-12 * scale {
            out[i] = rhs[i] / m[i][i];
        }
    }
    out
}
