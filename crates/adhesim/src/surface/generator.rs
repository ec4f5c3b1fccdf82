use super::random::Xoshiro256;
use super::{positive, SurfaceError};
use crate::elastic::planner;
use crate::geometry::{GeometryError, RoughBase, RoughProfile, Topography};
use crate::grid::{Boundary, Grid};
use num_complex::Complex;
use std::f64::consts::TAU;

/// Side of the periodic patch on which a free-grid surface is generated, in grid sides:
/// the cut-out window then carries wavelengths up to twice its own side and is not
/// periodic (its opposite edges do not match).
pub const DEFAULT_PATCH_FACTOR: usize = 2;

/// Which rms value fixes the amplitude of the spectrum (exactly one of the two).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RmsTarget {
    /// Root-mean-square height h_rms (about the mean plane).
    Height(f64),
    /// Root-mean-square slope h'_rms = ⟨|∇h|²⟩^½.
    Slope(f64),
}

/// How the Fourier amplitudes are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Amplitudes {
    /// |H(q)| exactly √C(q) with a uniformly random phase: every map has the requested
    /// rms (to rounding, on the periodic patch) and the target spectrum mode by mode.
    #[default]
    RandomPhase,
    /// Complex Gaussian H(q) (Rayleigh modulus, uniform phase) with ⟨|H|²⟩ ∝ C(q): a
    /// Gaussian random field whose rms and spectrum match the request on average.
    /// (SurfaceTopography multiplies a normal deviate by a random phase instead; the
    /// mean square, hence the expected spectrum, is the same.)
    Filtered,
}

/// Parameters of a random self-affine surface (see the [module docs](super)).
///
/// Wavelengths are in the grid's length unit; q = 2π/λ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SelfAffine {
    /// Hurst exponent H ∈ (0, 1]: C(q) ∝ q^(−2−2H).
    pub hurst: f64,
    /// The rms height or rms slope the surface must have.
    pub target: RmsTarget,
    /// Roll-off wavelength λ_r = 2π/q_r: the spectrum is flat at wavevectors below q_r.
    /// `None`: no plateau (the power law runs down to the lowest mode, 2π over the patch).
    pub rolloff_wavelength: Option<f64>,
    /// Short-wavelength cutoff λ_s = 2π/q_s: no modes above q_s. `None`: the grid's
    /// Nyquist wavelength 2Δ (q_s = π/Δ).
    pub cutoff_wavelength: Option<f64>,
    /// Exact amplitudes or Gaussian ones.
    pub amplitudes: Amplitudes,
    /// On a free grid, the surface is generated periodic on a square `patch_factor` times
    /// the grid's side (same spacing) and its first N×N samples are kept (default
    /// [`DEFAULT_PATCH_FACTOR`]). Ignored on periodic grids.
    pub patch_factor: usize,
}

/// A generated height map with the spectrum it was drawn from.
#[derive(Debug, Clone, PartialEq)]
pub struct RoughSurface {
    /// Heights at the element centres of the grid, row-major; zero mean on the patch.
    pub heights: Vec<f64>,
    /// The grid the heights are sampled on.
    pub grid: Grid,
    /// Prefactor C₀ of C(q) = C₀·q^(−2−2H) (unit: length^(2−2H)).
    pub prefactor: f64,
    /// Hurst exponent.
    pub hurst: f64,
    /// Roll-off wavevector q_r (0 when there is no plateau).
    pub rolloff_wavevector: f64,
    /// Cutoff wavevector q_s.
    pub cutoff_wavevector: f64,
    /// Side of the periodic patch the surface was drawn on (the grid's side when periodic).
    pub patch_size: f64,
}

impl RoughSurface {
    /// The target spectrum C(q) the surface was drawn from.
    pub fn target_psd(&self, wavevector: f64) -> f64 {
        let exponent = -2.0 - 2.0 * self.hurst;
        if wavevector.is_nan() || wavevector <= 0.0 || wavevector > self.cutoff_wavevector * (1.0 + 1e-12) {
            0.0
        } else {
            self.prefactor * wavevector.max(self.rolloff_wavevector).powf(exponent)
        }
    }

    /// The heights as an indenter profile of the grid's spacing (shifted so that the
    /// lowest height is zero, as [`Topography::new`] does). An indenter touches first where
    /// its height is lowest, i.e. at the valleys of h: negate the heights to press the
    /// peaks (for a Gaussian surface both are statistically the same). A `Topography` is
    /// centred on the middle of its samples, half an element off the grid's element
    /// centres on an even grid, so on the grid it was drawn on it interpolates between
    /// samples and leaves the first row and column off the map (height +∞): to press the
    /// surface onto that grid use [`Self::to_rough_profile`].
    pub fn to_topography(&self) -> Result<Topography, GeometryError> {
        let grid = &self.grid;
        if grid.dx() != grid.dy() {
            return Err(GeometryError::Topography(format!(
                "a topography has one spacing; the grid's elements are {} × {}",
                grid.dx(),
                grid.dy()
            )));
        }
        Topography::new(self.heights.clone(), grid.ny(), grid.nx(), grid.dx())
    }

    /// The surface on a base shape, peaks towards the half-space (`rough_flat` with
    /// [`RoughBase::Flat`], `rough_sphere` with [`RoughBase::Sphere`]), sampled exactly at
    /// the element centres of the grid it was drawn on: see [`RoughProfile`].
    pub fn to_rough_profile(&self, base: RoughBase) -> Result<RoughProfile, GeometryError> {
        RoughProfile::new(base, self.heights.clone(), &self.grid)
    }
}

impl SelfAffine {
    /// A surface of Hurst exponent `hurst` with the given rms, no roll-off, cutoff at the
    /// grid's Nyquist, random-phase amplitudes and the default free-grid patch.
    pub fn new(hurst: f64, target: RmsTarget) -> Self {
        Self {
            hurst,
            target,
            rolloff_wavelength: None,
            cutoff_wavelength: None,
            amplitudes: Amplitudes::RandomPhase,
            patch_factor: DEFAULT_PATCH_FACTOR,
        }
    }

    /// Sets the roll-off wavelength λ_r.
    pub fn with_rolloff_wavelength(mut self, wavelength: f64) -> Self {
        self.rolloff_wavelength = Some(wavelength);
        self
    }

    /// Sets the cutoff wavelength λ_s.
    pub fn with_cutoff_wavelength(mut self, wavelength: f64) -> Self {
        self.cutoff_wavelength = Some(wavelength);
        self
    }

    /// Sets the amplitude mode.
    pub fn with_amplitudes(mut self, amplitudes: Amplitudes) -> Self {
        self.amplitudes = amplitudes;
        self
    }

    /// Sets the free-grid patch factor.
    pub fn with_patch_factor(mut self, factor: usize) -> Self {
        self.patch_factor = factor;
        self
    }

    /// Checks the parameters against `grid` without generating anything.
    pub fn validate(&self, grid: &Grid) -> Result<(), SurfaceError> {
        self.plan(&enclosing_square(grid)?).map(|_| ())
    }

    /// Patch size (points, side) and the band (q_r, q_s) in patch index units
    /// k = q·L_patch/2π, after validating every parameter.
    fn plan(&self, grid: &Grid) -> Result<Plan, SurfaceError> {
        if !(self.hurst.is_finite() && self.hurst > 0.0 && self.hurst <= 1.0) {
            return Err(SurfaceError::Hurst(self.hurst));
        }
        match self.target {
            RmsTarget::Height(value) => positive("rms_height", value)?,
            RmsTarget::Slope(value) => positive("rms_slope", value)?,
        };
        let factor = match grid.boundary() {
            Boundary::Periodic => 1,
            Boundary::Free if self.patch_factor == 0 => return Err(SurfaceError::PatchFactor(0)),
            Boundary::Free => self.patch_factor,
        };
        let points = factor * grid.nx();
        let patch = grid.size_x() * factor as f64;
        let spacing = grid.dx();
        let cutoff = match self.cutoff_wavelength {
            Some(wavelength) => {
                positive("cutoff_wavelength", wavelength)?;
                if wavelength < 2.0 * spacing * (1.0 - 1e-12) {
                    return Err(SurfaceError::CutoffBelowNyquist {
                        cutoff: wavelength,
                        nyquist: 2.0 * spacing,
                    });
                }
                patch / wavelength
            }
            None => points as f64 / 2.0,
        };
        let rolloff = match self.rolloff_wavelength {
            Some(wavelength) => {
                positive("rolloff_wavelength", wavelength)?;
                let cutoff_wavelength = patch / cutoff;
                if wavelength <= cutoff_wavelength {
                    return Err(SurfaceError::RolloffNotBelowCutoff {
                        rolloff: wavelength,
                        cutoff: cutoff_wavelength,
                    });
                }
                patch / wavelength
            }
            None => 0.0,
        };
        if cutoff * (1.0 + 1e-12) < 1.0 {
            return Err(SurfaceError::EmptyBand {
                cutoff: patch / cutoff,
                patch,
            });
        }
        Ok(Plan {
            points,
            patch,
            rolloff,
            cutoff,
        })
    }

    /// Draws the surface for `seed` on `grid`.
    ///
    /// The random numbers are drawn sequentially, one (or, after rejections, a few) per
    /// mode of the half spectrum in row-major order, from a seeded xoshiro256** stream
    /// that is bit-identical on every platform; nothing depends on threads, so the heights
    /// are identical for any rayon pool. The phases depend only on the seed and the patch
    /// size: surfaces with the same seed and grid but another H, rms or band are the same
    /// realisation with another spectrum.
    ///
    /// On a free rectangular grid of square elements the surface is drawn on the square
    /// grid of the longer side (same spacing, so the same realisation as that square
    /// grid's) and its first Nx columns of its first Ny rows are kept.
    pub fn generate(&self, grid: &Grid, seed: u64) -> Result<RoughSurface, SurfaceError> {
        let square = enclosing_square(grid)?;
        let mut surface = self.generate_square(&square, seed)?;
        if square != *grid {
            let (nx, ny, n) = (grid.nx(), grid.ny(), square.nx());
            for row in 0..ny {
                surface.heights.copy_within(row * n..row * n + nx, row * nx);
            }
            surface.heights.truncate(nx * ny);
            surface.grid = *grid;
        }
        Ok(surface)
    }

    fn generate_square(&self, grid: &Grid, seed: u64) -> Result<RoughSurface, SurfaceError> {
        let plan = self.plan(grid)?;
        let m = plan.points;
        let columns = m / 2 + 1;
        let exponent = -2.0 - 2.0 * self.hurst;
        // Shape s(k) = C(q)/C₀ in patch index units (the 2π/L factors go into C₀ below).
        let shape = |row: usize, column: usize| -> f64 {
            let ky = if row <= m / 2 {
                row as f64
            } else {
                row as f64 - m as f64
            };
            let k = (ky * ky + (column * column) as f64).sqrt();
            if k == 0.0 || k > plan.cutoff * (1.0 + 1e-12) {
                0.0
            } else {
                k.max(plan.rolloff).powf(exponent)
            }
        };
        // Full-spectrum sums Σ s and Σ k²·s: half-spectrum columns other than 0 and the
        // Nyquist column stand for two modes (k and −k).
        let weight = |column: usize| if column == 0 || 2 * column == m { 1.0 } else { 2.0 };
        let (mut sum, mut sum_k2) = (0.0, 0.0);
        for row in 0..m {
            let ky = if row <= m / 2 {
                row as f64
            } else {
                row as f64 - m as f64
            };
            for column in 0..columns {
                let value = weight(column) * shape(row, column);
                sum += value;
                sum_k2 += value * (ky * ky + (column * column) as f64);
            }
        }
        let wavenumber = TAU / plan.patch;
        let area = plan.patch * plan.patch;
        // h_rms² = C₀'·Σs/A, h'_rms² = C₀'·(2π/L)²·Σk²s/A, with C(q) = C₀'·s(k).
        let scaled_prefactor = match self.target {
            RmsTarget::Height(rms) => rms * rms * area / sum,
            RmsTarget::Slope(rms) => rms * rms * area / (sum_k2 * wavenumber * wavenumber),
        };
        if !(sum > 0.0 && scaled_prefactor.is_finite()) {
            return Err(SurfaceError::EmptyBand {
                cutoff: plan.patch / plan.cutoff,
                patch: plan.patch,
            });
        }
        // |H(q)| = M²·√(C(q)/A), C(q) = C₀'·s(k).
        let amplitude_scale = (m * m) as f64 * (scaled_prefactor / area).sqrt();
        let mut spectrum = vec![Complex::new(0.0, 0.0); m * columns];
        let mut rng = Xoshiro256::new(seed);
        for row in 0..m {
            for column in 0..columns {
                let draw = match self.amplitudes {
                    Amplitudes::RandomPhase => {
                        let (c, s) = rng.unit_phase();
                        Complex::new(c, s)
                    }
                    Amplitudes::Filtered => {
                        let (a, b) = rng.normal_pair();
                        Complex::new(a, b) * std::f64::consts::FRAC_1_SQRT_2
                    }
                };
                spectrum[row * columns + column] = draw * (amplitude_scale * shape(row, column).sqrt());
            }
        }
        enforce_hermitian(&mut spectrum, m, self.amplitudes);
        let mut patch_heights = inverse_transform(&mut spectrum, m);
        let n = grid.nx();
        let heights = if m == n {
            patch_heights
        } else {
            for row in 0..n {
                patch_heights.copy_within(row * m..row * m + n, row * n);
            }
            patch_heights.truncate(n * n);
            patch_heights
        };
        Ok(RoughSurface {
            heights,
            grid: *grid,
            prefactor: scaled_prefactor * wavenumber.powf(-exponent),
            hurst: self.hurst,
            rolloff_wavevector: plan.rolloff * wavenumber,
            cutoff_wavevector: plan.cutoff * wavenumber,
            patch_size: plan.patch,
        })
    }
}

/// The square grid a surface for `grid` is drawn on: `grid` itself when square; for a
/// free rectangle of square elements, the square of its longer side. Periodic rectangles
/// and rectangular elements are refused (the generator's spectrum lives on a square
/// lattice of square cells).
fn enclosing_square(grid: &Grid) -> Result<Grid, SurfaceError> {
    if grid.is_square() {
        return Ok(*grid);
    }
    let refuse = || SurfaceError::RectangularGrid {
        nx: grid.nx(),
        ny: grid.ny(),
        size_x: grid.size_x(),
        size_y: grid.size_y(),
    };
    if grid.boundary() == Boundary::Periodic || grid.dx() != grid.dy() {
        return Err(refuse());
    }
    let square = if grid.nx() >= grid.ny() {
        Grid::new(grid.nx(), grid.size_x(), Boundary::Free)
    } else {
        Grid::new(grid.ny(), grid.size_y(), Boundary::Free)
    };
    square.map_err(|_| refuse())
}

struct Plan {
    points: usize,
    patch: f64,
    rolloff: f64,
    cutoff: f64,
}

/// Columns 0 and M/2 (M even) of the half spectrum hold modes whose conjugates are in the
/// same column: row M − r takes the conjugate of row r, and the self-conjugate modes
/// (rows 0 and M/2) become real with their modulus kept (random-phase: the sign of the
/// drawn cosine; filtered: the real part, a normal deviate of the same variance).
fn enforce_hermitian(spectrum: &mut [Complex<f64>], m: usize, amplitudes: Amplitudes) {
    let columns = m / 2 + 1;
    let mut self_conjugate_columns = vec![0];
    if m.is_multiple_of(2) {
        self_conjugate_columns.push(m / 2);
    }
    for &column in &self_conjugate_columns {
        for row in 1..m.div_ceil(2) {
            spectrum[(m - row) * columns + column] = spectrum[row * columns + column].conj();
        }
        let mut rows = vec![0];
        if m.is_multiple_of(2) {
            rows.push(m / 2);
        }
        for row in rows {
            let value = &mut spectrum[row * columns + column];
            *value = match amplitudes {
                Amplitudes::RandomPhase => Complex::new(value.norm().copysign(value.re), 0.0),
                Amplitudes::Filtered => Complex::new(value.re * std::f64::consts::SQRT_2, 0.0),
            };
        }
    }
}

/// h(x) = (1/M²)·Σ_q H(q)·e^(iq·x) from the half spectrum (rows complex, then each row
/// complex-to-real). Sequential: generation is done once per surface.
fn inverse_transform(spectrum: &mut [Complex<f64>], m: usize) -> Vec<f64> {
    let columns = m / 2 + 1;
    let column_fft = planner::complex_inverse::<f64>(m);
    let mut column_buffer = vec![Complex::new(0.0, 0.0); m];
    let mut scratch = vec![Complex::new(0.0, 0.0); column_fft.get_inplace_scratch_len()];
    for column in 0..columns {
        for row in 0..m {
            column_buffer[row] = spectrum[row * columns + column];
        }
        column_fft.process_with_scratch(&mut column_buffer, &mut scratch);
        for row in 0..m {
            spectrum[row * columns + column] = column_buffer[row];
        }
    }
    let row_fft = planner::real_inverse::<f64>(m);
    let mut heights = vec![0.0; m * m];
    let mut row_scratch = row_fft.make_scratch_vec();
    let normalisation = 1.0 / (m * m) as f64;
    for (row, out) in heights.chunks_exact_mut(m).enumerate() {
        let input = &mut spectrum[row * columns..(row + 1) * columns];
        // After the column pass these modes are real up to rounding; c2r needs them real.
        input[0].im = 0.0;
        if m.is_multiple_of(2) {
            input[columns - 1].im = 0.0;
        }
        row_fft
            .process_with_scratch(input, out, &mut row_scratch)
            .expect("buffer lengths match the plan and the edge modes are real");
        out.iter_mut().for_each(|h| *h *= normalisation);
    }
    heights
}
