//! Random self-affine surfaces and the statistics of any height map.
//!
//! [`SelfAffine`] draws a Gaussian random surface with the isotropic power spectrum
//! C(q) = C₀·q^(−2−2H) between a roll-off wavevector q_r (plateau C₀·q_r^(−2−2H) below it)
//! and a short-wavelength cutoff q_s (zero above it), by Fourier filtering: Ramisetti et
//! al. (2011), *J. Phys.: Condens. Matter* 23, 215004, doi:10.1088/0953-8984/23/21/215004;
//! Jacobs, Junge & Pastewka (2017), "Quantitative characterization of surface topography
//! using spectral analysis", *Surf. Topogr.: Metrol. Prop.* 5, 013001,
//! doi:10.1088/2051-672X/aa51f8.
//!
//! ## Spectrum convention
//! The same discrete convention as SurfaceTopography's `fourier_synthesis`: for a map of
//! M×M samples on a square of area A = L², with discrete Fourier coefficients
//! H(q) = Σ_x h(x)·e^(−iq·x) (q on the lattice 2π/L·(k_x, k_y)),
//!
//! C(q) = A/M⁴ · |H(q)|²,   h_rms² = (1/A)·Σ_q C(q),   h'_rms² = (1/A)·Σ_q |q|²·C(q),
//!
//! sums over every lattice wavevector. The prefactor C₀ is fixed by the requested rms
//! through these discrete sums, plateau included (not by the continuum integral
//! h_rms² = (1/2π)∫q·C(q)dq), so in [`Amplitudes::RandomPhase`] mode the periodic map has
//! the requested rms height or rms slope to rounding. SurfaceTopography 1.27 does the
//! same, except that its self-conjugate modes ((N/2, 0), (0, N/2)) get half the power
//! (the real part of a random phase) where adhesim keeps the modulus with a random sign;
//! `bench/compare/surface_results.md` compares the two.
//!
//! ## Statistics
//! [`rms_height`], [`rms_slope`], [`rms_curvature`] and [`isotropic_psd`] take any height
//! map on a [`Grid`](crate::Grid): spectral derivatives (Parseval sums over the map's spectrum) on a
//! periodic grid, finite differences on a free one (see each function).
//!
//! [`HeightMap`] holds a measured map as instruments record it: a rectangle with its own
//! x and y spacings and invalid points. Its statistics leave the invalid points out and name
//! their definition (finite differences as SurfaceTopography 1.27, or spectral on a periodic
//! map); [`fill_invalid_harmonic`] fills invalid points as SurfaceTopography's
//! `interpolate_undefined_data` does.

mod fill;
mod generator;
mod map;
mod random;
mod statistics;
#[cfg(test)]
mod tests_map;

pub use fill::fill_invalid_harmonic;
pub use generator::{Amplitudes, RmsTarget, RoughSurface, SelfAffine, DEFAULT_PATCH_FACTOR};
pub use map::{Derivative, HeightMap};
pub use statistics::{
    isotropic_psd, rms_curvature, rms_height, rms_slope, rms_slope_finite_differences, statistics, PsdBin,
    SurfaceStatistics,
};

use thiserror::Error;

/// The most bins of an isotropic PSD. Its sums hold 24 bytes per bin, allocated before any
/// bin is filled (4·10⁹ bins asked for 96 GB and aborted); a map of 16384² points has
/// fewer than 12,000 distinct wavevector magnitudes, so bins beyond that stay empty.
pub const MAX_PSD_BINS: usize = 1_000_000;

/// Invalid generator parameters or height maps.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum SurfaceError {
    /// The Hurst exponent must lie in (0, 1].
    #[error("hurst must be finite and in (0, 1], got {0}")]
    Hurst(f64),
    /// A length, rms value or wavelength must be finite and positive.
    #[error("{name} must be finite and > 0, got {value}")]
    NotPositive {
        /// Parameter name.
        name: &'static str,
        /// Offending value.
        value: f64,
    },
    /// The roll-off wavelength must be longer than the cutoff wavelength (q_r < q_s).
    #[error(
        "rolloff_wavelength ({rolloff}) must be longer than cutoff_wavelength ({cutoff}): q_r = 2π/λ_r must be below q_s = 2π/λ_s"
    )]
    RolloffNotBelowCutoff {
        /// Roll-off wavelength λ_r.
        rolloff: f64,
        /// Cutoff wavelength λ_s.
        cutoff: f64,
    },
    /// The cutoff wavelength is shorter than two elements (above the grid's Nyquist).
    #[error("cutoff_wavelength {cutoff} is shorter than two elements (2Δ = {nyquist}): the grid cannot resolve it")]
    CutoffBelowNyquist {
        /// Cutoff wavelength asked for.
        cutoff: f64,
        /// The shortest resolvable wavelength 2Δ.
        nyquist: f64,
    },
    /// No Fourier mode of the (patch) lattice lies in the band, so nothing can be drawn.
    #[error("no Fourier mode lies below the cutoff wavelength {cutoff} on a patch of side {patch}")]
    EmptyBand {
        /// Cutoff wavelength λ_s.
        cutoff: f64,
        /// Side of the periodic patch.
        patch: f64,
    },
    /// The generator needs square elements, and a square grid when periodic.
    #[error(
        "a generated surface needs square elements (and, on a periodic grid, a square grid): the grid is {nx} × {ny} elements over {size_x} × {size_y}"
    )]
    RectangularGrid {
        /// Elements along x.
        nx: usize,
        /// Elements along y.
        ny: usize,
        /// Side along x.
        size_x: f64,
        /// Side along y.
        size_y: f64,
    },
    /// The free-grid patch factor must be at least 1.
    #[error("patch_factor must be >= 1, got {0}")]
    PatchFactor(usize),
    /// A height map does not match its grid.
    #[error("height map has {got} values, the grid has {expected} elements")]
    SizeMismatch {
        /// Elements of the grid.
        expected: usize,
        /// Values given.
        got: usize,
    },
    /// A height is NaN or infinite.
    #[error("height at index {index} (row {row}, column {column}) is not finite ({value})")]
    NonFiniteHeight {
        /// Flat index.
        index: usize,
        /// Row.
        row: usize,
        /// Column.
        column: usize,
        /// The value.
        value: f64,
    },
    /// An isotropic PSD needs at least one bin.
    #[error("psd bins must be >= 1, got 0")]
    NoBins,
    /// More bins than [`MAX_PSD_BINS`].
    #[error("psd bins must be at most {MAX_PSD_BINS}, got {0}")]
    TooManyBins(usize),
    /// A measured map without a single valid point.
    #[error("the height map has no valid point")]
    NoValidPoint,
    /// The harmonic filling did not reach its tolerance.
    #[error("the harmonic filling of invalid points did not converge (relative residual {residual:e})")]
    FillNotConverged {
        /// Relative residual reached.
        residual: f64,
    },
    /// Finite differences need at least 3 samples per side.
    #[error("curvature by finite differences needs at least 3×3 samples, got {0}×{0}")]
    TooSmall(usize),
}

pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64, SurfaceError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(SurfaceError::NotPositive { name, value })
    }
}
