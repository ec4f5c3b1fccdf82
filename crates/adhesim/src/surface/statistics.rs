use super::map::{forward_transform, HeightMap};
use super::SurfaceError;
use crate::grid::{Boundary, Grid};
use std::f64::consts::{PI, TAU};

/// The three rms values of a height map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceStatistics {
    /// [`rms_height`].
    pub rms_height: f64,
    /// [`rms_slope`].
    pub rms_slope: f64,
    /// [`rms_curvature`].
    pub rms_curvature: f64,
}

/// One radial bin of an isotropic power spectrum.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PsdBin {
    /// Lower and upper edge of the bin (wavevector, 1/length).
    pub edges: (f64, f64),
    /// Mean |q| of the modes in the bin.
    pub wavevector: f64,
    /// Mean C(q) of the modes in the bin (length⁴).
    pub psd: f64,
    /// Number of lattice modes in the bin (±q counted separately).
    pub modes: usize,
}

fn check(grid: &Grid, heights: &[f64]) -> Result<(), SurfaceError> {
    if heights.len() != grid.len() {
        return Err(SurfaceError::SizeMismatch {
            expected: grid.len(),
            got: heights.len(),
        });
    }
    if let Some(index) = heights.iter().position(|h| !h.is_finite()) {
        return Err(SurfaceError::NonFiniteHeight {
            index,
            row: index / grid.nx(),
            column: index % grid.nx(),
            value: heights[index],
        });
    }
    Ok(())
}

/// A rectangular grid's heights as a [`HeightMap`]: the grid functions below hand
/// rectangles to it (SurfaceTopography's stencils with Δx and Δy, the spectral sums with
/// q = 2π(k_x/L_x, k_y/L_y)); square grids keep their own forms, bit for bit as before.
fn rectangle<'a>(grid: &Grid, heights: &'a [f64]) -> Option<Result<HeightMap<'a>, SurfaceError>> {
    (!grid.is_square()).then(|| {
        HeightMap::new(
            (grid.nx(), grid.ny()),
            (grid.dx(), grid.dy()),
            heights,
            None,
            grid.boundary() == Boundary::Periodic,
        )
    })
}

/// A statistic of a map too small for its stencil.
fn too_small(grid: &Grid) -> SurfaceError {
    SurfaceError::TooSmall(grid.nx().min(grid.ny()))
}

fn mean(values: &[f64]) -> f64 {
    values.iter().sum::<f64>() / values.len() as f64
}

/// Root-mean-square height about the mean, ⟨(h − h̄)²⟩^½.
pub fn rms_height(grid: &Grid, heights: &[f64]) -> Result<f64, SurfaceError> {
    check(grid, heights)?;
    let average = mean(heights);
    Ok((heights.iter().map(|h| (h - average).powi(2)).sum::<f64>() / heights.len() as f64).sqrt())
}

/// Root-mean-square slope h'_rms = ⟨(∂h/∂x)² + (∂h/∂y)²⟩^½.
///
/// Periodic grid: the spectral derivative, by Parseval h'_rms² = (1/N⁴)·Σ_q |q|²·|H(q)|²
/// over every lattice mode (the Nyquist modes with their |q|), the same sum the generator
/// normalises. Free grid: [`rms_slope_finite_differences`].
pub fn rms_slope(grid: &Grid, heights: &[f64]) -> Result<f64, SurfaceError> {
    check(grid, heights)?;
    if let Some(map) = rectangle(grid, heights) {
        let map = map?;
        return match grid.boundary() {
            Boundary::Periodic => map.spectral_slope_and_curvature().map(|(slope, _)| slope),
            Boundary::Free => map.rms_slope_finite_differences(),
        }
        .ok_or_else(|| too_small(grid));
    }
    match grid.boundary() {
        Boundary::Periodic => Ok(spectral_moment(grid, heights, 1).sqrt()),
        Boundary::Free => rms_slope_finite_differences(grid, heights),
    }
}

/// Root-mean-square slope from forward differences (h_{j+1} − h_j)/Δ along x and y, each
/// averaged over its own N(N − 1) pairs (wrapping around, N² pairs, on a periodic grid):
/// SurfaceTopography's `rms_gradient`. First order: a mode of wavevector q is seen with
/// slope 2 sin(qΔ/2)/Δ instead of q (−10 % at half the Nyquist wavevector, −36 % at it).
pub fn rms_slope_finite_differences(grid: &Grid, heights: &[f64]) -> Result<f64, SurfaceError> {
    check(grid, heights)?;
    if let Some(map) = rectangle(grid, heights) {
        return map?.rms_slope_finite_differences().ok_or_else(|| too_small(grid));
    }
    let n = grid.nx();
    let periodic = grid.boundary() == Boundary::Periodic;
    let spacing = grid.dx();
    let (mut sum_x, mut sum_y, mut count) = (0.0, 0.0, 0usize);
    let last = if periodic { n } else { n - 1 };
    for row in 0..n {
        for column in 0..last {
            let next = (column + 1) % n;
            sum_x += (heights[row * n + next] - heights[row * n + column]).powi(2);
            // the same pair along y, transposed: rows `column` and `next` at column `row`
            sum_y += (heights[next * n + row] - heights[column * n + row]).powi(2);
            count += 1;
        }
    }
    Ok(((sum_x + sum_y) / count as f64).sqrt() / spacing)
}

/// Root-mean-square mean curvature ⟨(∇²h/2)²⟩^½ (small slopes), as SurfaceTopography's
/// `rms_curvature_from_area`.
///
/// Periodic grid: spectral, (1/N⁴)·Σ_q (|q|²/2)²·|H(q)|². Free grid: the five-point
/// Laplacian on the (N − 2)² interior samples (second order; needs N ≥ 3).
pub fn rms_curvature(grid: &Grid, heights: &[f64]) -> Result<f64, SurfaceError> {
    check(grid, heights)?;
    if let Some(map) = rectangle(grid, heights) {
        let map = map?;
        return match grid.boundary() {
            Boundary::Periodic => map.spectral_slope_and_curvature().map(|(_, curvature)| curvature),
            Boundary::Free => map.rms_curvature_finite_differences(),
        }
        .ok_or_else(|| too_small(grid));
    }
    if grid.boundary() == Boundary::Periodic {
        return Ok(spectral_moment(grid, heights, 2).sqrt() / 2.0);
    }
    let n = grid.nx();
    if n < 3 {
        return Err(SurfaceError::TooSmall(n));
    }
    let spacing = grid.dx();
    let mut sum = 0.0;
    for row in 1..n - 1 {
        for column in 1..n - 1 {
            let k = row * n + column;
            let laplacian = heights[k - 1] + heights[k + 1] + heights[k - n] + heights[k + n] - 4.0 * heights[k];
            sum += laplacian * laplacian;
        }
    }
    Ok((sum / ((n - 2) * (n - 2)) as f64).sqrt() / (2.0 * spacing * spacing))
}

/// All three rms values.
pub fn statistics(grid: &Grid, heights: &[f64]) -> Result<SurfaceStatistics, SurfaceError> {
    Ok(SurfaceStatistics {
        rms_height: rms_height(grid, heights)?,
        rms_slope: rms_slope(grid, heights)?,
        rms_curvature: rms_curvature(grid, heights)?,
    })
}

/// Isotropic (radially averaged) power spectrum C(q) = A/N⁴·|H(q)|² of the map minus its
/// mean, in `bins` logarithmic bins between 2π/L and the Nyquist wavevector π/Δ (the
/// corner modes beyond π/Δ are left out; empty bins are omitted).
///
/// On a free grid the map is first multiplied by a separable Hann window
/// w = sin²(π(j + ½)/N)·sin²(π(i + ½)/N) rescaled to ⟨w²⟩ = 1, so that the jump between
/// opposite edges does not leak a q⁻⁴ tail into the spectrum while the total power is
/// kept (SurfaceTopography also windows non-periodic maps with a Hann window).
pub fn isotropic_psd(grid: &Grid, heights: &[f64], bins: usize) -> Result<Vec<PsdBin>, SurfaceError> {
    check(grid, heights)?;
    if bins == 0 {
        return Err(SurfaceError::NoBins);
    }
    if bins > super::MAX_PSD_BINS {
        return Err(SurfaceError::TooManyBins(bins));
    }
    if let Some(map) = rectangle(grid, heights) {
        return map?.isotropic_psd(bins);
    }
    let n = grid.nx();
    let average = mean(heights);
    let mut centred: Vec<f64> = heights.iter().map(|h| h - average).collect();
    if grid.boundary() == Boundary::Free {
        let window: Vec<f64> = (0..n)
            .map(|j| (PI * (j as f64 + 0.5) / n as f64).sin().powi(2))
            .collect();
        let mean_square = (window.iter().map(|w| w * w).sum::<f64>() / n as f64).powi(2);
        let scale = 1.0 / mean_square.sqrt();
        for (k, h) in centred.iter_mut().enumerate() {
            *h *= window[k / n] * window[k % n] * scale;
        }
    }
    let spectrum = forward_transform(&centred, n, n);
    let columns = n / 2 + 1;
    let wavenumber = TAU / grid.size_x();
    let area = grid.size_x() * grid.size_x();
    let normalisation = area / (n as f64).powi(4);
    let (lowest, highest) = (1.0f64, n as f64 / 2.0);
    let log_span = (highest / lowest).ln().max(f64::MIN_POSITIVE);
    let mut sums = vec![(0.0, 0.0, 0usize); bins];
    for row in 0..n {
        let ky = if row <= n / 2 {
            row as f64
        } else {
            row as f64 - n as f64
        };
        for column in 0..columns {
            let k = (ky * ky + (column * column) as f64).sqrt();
            if k < lowest * (1.0 - 1e-12) || k > highest * (1.0 + 1e-12) {
                continue;
            }
            let position = ((k / lowest).ln() / log_span * bins as f64).floor();
            let bin = (position.max(0.0) as usize).min(bins - 1);
            let multiplicity = if column == 0 || 2 * column == n { 1 } else { 2 };
            let power = normalisation * spectrum[row * columns + column].norm_sqr();
            let entry = &mut sums[bin];
            entry.0 += multiplicity as f64 * k;
            entry.1 += multiplicity as f64 * power;
            entry.2 += multiplicity;
        }
    }
    Ok(sums
        .iter()
        .enumerate()
        .filter(|(_, entry)| entry.2 > 0)
        .map(|(bin, &(sum_k, sum_power, modes))| {
            let edge = |b: usize| wavenumber * lowest * (log_span * b as f64 / bins as f64).exp();
            PsdBin {
                edges: (edge(bin), edge(bin + 1)),
                wavevector: wavenumber * sum_k / modes as f64,
                psd: sum_power / modes as f64,
                modes,
            }
        })
        .collect())
}

/// (1/N⁴)·Σ_q |q|^(2·order)·|H(q)|² over every lattice mode (periodic maps).
fn spectral_moment(grid: &Grid, heights: &[f64], order: i32) -> f64 {
    let n = grid.nx();
    let spectrum = forward_transform(heights, n, n);
    let columns = n / 2 + 1;
    let wavenumber = TAU / grid.size_x();
    let mut sum = 0.0;
    for row in 0..n {
        let ky = if row <= n / 2 {
            row as f64
        } else {
            row as f64 - n as f64
        };
        for column in 0..columns {
            let multiplicity = if column == 0 || 2 * column == n { 1.0 } else { 2.0 };
            let q2 = wavenumber * wavenumber * (ky * ky + (column * column) as f64);
            sum += multiplicity * q2.powi(order) * spectrum[row * columns + column].norm_sqr();
        }
    }
    sum / (n as f64).powi(4)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// h = a·sin(2πk·x/L): h_rms = a/√2, h'_rms = a·q/√2, mean curvature rms a·q²/(2√2),
    /// exact (to rounding) for the spectral forms on a periodic grid; on a free grid the
    /// finite differences are within O((qΔ)²) (here qΔ = 2π·3/64 ≈ 0.29: 1 % and 2 %).
    #[test]
    fn sine_wave_statistics() {
        let (n, size, amplitude, k) = (64, 2.0, 0.3, 3.0);
        let q = TAU * k / size;
        for boundary in [Boundary::Periodic, Boundary::Free] {
            let grid = Grid::new(n, size, boundary).unwrap();
            let heights: Vec<f64> = (0..grid.len())
                .map(|i| amplitude * (q * grid.centre(i).0).sin())
                .collect();
            let stats = statistics(&grid, &heights).unwrap();
            let tolerance = if boundary == Boundary::Periodic { 1e-12 } else { 0.02 };
            let expect = |value: f64, exact: f64, name: &str| {
                assert!(
                    (value / exact - 1.0).abs() < tolerance,
                    "{boundary:?} {name}: {value} vs {exact}"
                )
            };
            expect(stats.rms_height, amplitude / 2f64.sqrt(), "height");
            expect(stats.rms_slope, amplitude * q / 2f64.sqrt(), "slope");
            expect(
                stats.rms_curvature,
                amplitude * q * q / (2.0 * 2f64.sqrt()),
                "curvature",
            );
            // forward differences: 2 sin(qΔ/2)/Δ exactly on the periodic grid
            let delta = grid.dx();
            let difference = rms_slope_finite_differences(&grid, &heights).unwrap();
            let exact = amplitude * 2.0 * (q * delta / 2.0).sin() / delta / 2f64.sqrt();
            let tolerance = if boundary == Boundary::Periodic { 1e-12 } else { 0.02 };
            assert!(
                (difference / exact - 1.0).abs() < tolerance,
                "{boundary:?}: {difference} vs {exact}"
            );
        }
    }

    /// The PSD of a single mode puts all the power h_rms² = a²/2 (times A: Σ_q C = A·h_rms²)
    /// in the bin holding |q| = 2πk/L, on the periodic grid.
    #[test]
    fn psd_of_a_single_mode() {
        let (n, size, amplitude) = (32, 1.0, 0.5);
        let grid = Grid::new(n, size, Boundary::Periodic).unwrap();
        let q = TAU * 4.0 / size;
        let heights: Vec<f64> = (0..grid.len())
            .map(|i| amplitude * (q * grid.centre(i).1).cos())
            .collect();
        let bins = isotropic_psd(&grid, &heights, 8).unwrap();
        let total: f64 = bins.iter().map(|b| b.psd * b.modes as f64).sum();
        assert!((total / (size * size) - amplitude * amplitude / 2.0).abs() < 1e-14);
        let holder = bins.iter().find(|b| b.edges.0 <= q && q < b.edges.1).unwrap();
        assert!((holder.psd * holder.modes as f64 / total - 1.0).abs() < 1e-12);
    }

    /// On a free grid the Hann window keeps the total power (⟨w²⟩ = 1: Σ_q C = A·h_rms²
    /// to the window's edge effects, here 1 %) and keeps the peak within one bin of the
    /// mode (the Hann main lobe spans ±2 modes; a 4.5-period wave is not periodic on the
    /// window, its power lands on k = 4 and 5).
    #[test]
    fn free_grid_psd_is_windowed() {
        let (n, size, amplitude) = (64, 1.0, 0.5);
        let grid = Grid::new(n, size, Boundary::Free).unwrap();
        let q = TAU * 4.5 / size;
        let heights: Vec<f64> = (0..grid.len())
            .map(|i| amplitude * (q * grid.centre(i).0).sin())
            .collect();
        let bins = isotropic_psd(&grid, &heights, 12).unwrap();
        let total: f64 = bins.iter().map(|b| b.psd * b.modes as f64).sum::<f64>() / (size * size);
        let variance = rms_height(&grid, &heights).unwrap().powi(2);
        assert!((total / variance - 1.0).abs() < 0.01, "{total} vs {variance}");
        let peak = bins.iter().max_by(|a, b| a.psd.total_cmp(&b.psd)).unwrap();
        let width = peak.edges.1 / peak.edges.0;
        assert!(peak.edges.0 <= q * width && q < peak.edges.1 * width, "{peak:?}");
    }

    #[test]
    fn bad_maps_are_named_errors() {
        let grid = Grid::new(4, 1.0, Boundary::Free).unwrap();
        assert_eq!(
            rms_height(&grid, &[0.0; 3]),
            Err(SurfaceError::SizeMismatch { expected: 16, got: 3 })
        );
        let mut heights = vec![0.0; 16];
        heights[6] = f64::NAN;
        let error = rms_slope(&grid, &heights).unwrap_err();
        assert!(matches!(
            error,
            SurfaceError::NonFiniteHeight {
                index: 6,
                row: 1,
                column: 2,
                ..
            }
        ));
        assert_eq!(isotropic_psd(&grid, &[0.0; 16], 0), Err(SurfaceError::NoBins));
        let tiny = Grid::new(2, 1.0, Boundary::Free).unwrap();
        assert_eq!(rms_curvature(&tiny, &[0.0; 4]), Err(SurfaceError::TooSmall(2)));
    }
}
