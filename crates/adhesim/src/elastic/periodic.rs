use super::spectral::SpectralConvolution;
use super::ElasticOperator;
use crate::grid::Grid;
use crate::material::ElasticMaterial;
use std::f64::consts::TAU;
use std::ops::Range;

/// Number of aliases |m|, |n| ≤ this kept in the element-consistent kernel: reproduces
/// Love's near-field coefficient differences to 1e-5 (docs/physics.md §1b).
pub(super) const ALIASES: i32 = 40;

/// Fourier multiplier used by the periodic operator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PeriodicKernel {
    /// K̂(q) = Σ_{m,n} 2·S(q+G_mn)/(E*|q+G_mn|), S the element's sinc² form factor:
    /// uniform pressure on square elements, collocated at centres, consistent with the
    /// free operator's Love coefficients (and so with the detachment stress σ_c).
    ElementConsistent,
    /// Stanley & Kato (1997) K̂(q) = 2/(E*|q|): exact for band-limited pressure fields.
    Continuous,
}

/// Periodic half-space (periods Lx = NxΔx and Ly = NyΔy) as a Fourier multiplier.
///
/// Stanley & Kato (1997), "An FFT-based method for rough surface contact",
/// *J. Tribol.* 119, 481–485, doi:10.1115/1.2833523; element-consistent aliasing as in
/// docs/physics.md §1b. K̂(0) = 0: the mean displacement of a periodic half-space is
/// undefined, so displacement control here controls the mean gap.
pub struct PeriodicOperator {
    grid: Grid,
    contact_modulus: f64,
    self_compliance: f64,
    engine: SpectralConvolution,
    /// The same kernel in single precision, for [`ElasticOperator::apply_single`].
    single: SpectralConvolution<f32>,
    applications: u64,
}

/// sin t / t, its series near 0: the form factor of a uniform element.
pub(super) fn sinc(t: f64) -> f64 {
    if t.abs() < 1e-8 {
        1.0 - t * t / 6.0
    } else {
        t.sin() / t
    }
}

impl PeriodicOperator {
    /// Plans the transforms and computes the kernel spectrum.
    pub fn new(grid: Grid, material: ElasticMaterial, kernel: PeriodicKernel) -> Self {
        Self::with_compliance_factor(grid, material, kernel, |_| 1.0)
    }

    /// The same operator for a body whose Fourier compliance is the half-space's 2/(E*|Q|)
    /// times `factor(|Q|)`: each alias term is multiplied by the factor at its own
    /// wavenumber |q + G| (an elastic layer, `super::layer`). A factor of exactly 1 gives
    /// the bits of [`new`](Self::new) (a product with 1.0 is exact).
    pub(crate) fn with_compliance_factor(
        grid: Grid,
        material: ElasticMaterial,
        kernel: PeriodicKernel,
        factor: impl Fn(f64) -> f64 + Sync,
    ) -> Self {
        let (nx, ny) = (grid.nx(), grid.ny());
        let modulus = material.contact_modulus();
        let mut engine = SpectralConvolution::<f64>::planned((nx, ny), (nx, ny));
        let aliases: Vec<i32> = match kernel {
            PeriodicKernel::ElementConsistent => (-ALIASES..=ALIASES).collect(),
            PeriodicKernel::Continuous => vec![0],
        };
        // Per-axis tables: shifted wavenumbers q + 2πm/Δ and form factors sinc((q+G)Δ/2),
        // for the wave `index` of an axis of n elements of side `delta` and period `size`.
        let table = |index: usize, n: usize, delta: f64, size: f64| -> Vec<(f64, f64)> {
            let k = if index <= n / 2 {
                index as f64
            } else {
                index as f64 - n as f64
            };
            let q = TAU * k / size;
            aliases
                .iter()
                .map(|&m| {
                    let shifted = q + TAU * m as f64 / delta;
                    let form = match kernel {
                        PeriodicKernel::ElementConsistent => sinc(0.5 * shifted * delta),
                        PeriodicKernel::Continuous => 1.0,
                    };
                    (shifted * shifted, form)
                })
                .collect()
        };
        let columns = nx / 2 + 1;
        // K̂ is even in q_y: evaluate rows 0..=Ny/2 once (in parallel), mirror the rest.
        let half_rows = ny / 2 + 1;
        let x_tables: Vec<Vec<(f64, f64)>> = (0..columns)
            .map(|index| table(index, nx, grid.dx(), grid.size_x()))
            .collect();
        let y_tables: Vec<Vec<(f64, f64)>> = (0..half_rows)
            .map(|index| table(index, ny, grid.dy(), grid.size_y()))
            .collect();
        let normalisation = 1.0 / (nx as f64 * ny as f64);
        let mut half = vec![0.0; half_rows * columns];
        {
            use rayon::prelude::*;
            half.par_chunks_mut(columns).enumerate().for_each(|(row, out)| {
                for (column, value) in out.iter_mut().enumerate() {
                    if row == 0 && column == 0 {
                        continue;
                    }
                    let mut sum = 0.0;
                    for &(qx2, sx) in &x_tables[column] {
                        for &(qy2, sy) in &y_tables[row] {
                            let wavenumber = (qx2 + qy2).sqrt();
                            sum += sx * sy * factor(wavenumber) / wavenumber;
                        }
                    }
                    *value = 2.0 * sum / modulus * normalisation;
                }
            });
        }
        engine.set_kernel_spectrum(|row, column| {
            let row = if row > ny / 2 { ny - row } else { row };
            half[row * columns + column]
        });
        let mut operator = Self {
            grid,
            contact_modulus: modulus,
            self_compliance: 0.0,
            single: engine.to_single(),
            engine,
            applications: 0,
        };
        let mut unit = vec![0.0; grid.len()];
        let centre = (ny / 2) * nx + nx / 2;
        unit[centre] = 1.0;
        let mut response = vec![0.0; grid.len()];
        operator.apply(&unit, &mut response);
        operator.self_compliance = response[centre];
        operator.applications = 0;
        operator
    }
}

impl ElasticOperator for PeriodicOperator {
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
    fn apply_single_rows(
        &mut self,
        pressure: &[f64],
        displacement: &mut [f64],
        input_rows: Range<usize>,
        output_rows: Range<usize>,
    ) {
        self.single
            .convolve_rows(pressure, displacement, input_rows, output_rows);
        self.applications += 1;
    }
    fn self_compliance(&self) -> f64 {
        self.self_compliance
    }
    fn applications(&self) -> u64 {
        self.applications
    }
}
