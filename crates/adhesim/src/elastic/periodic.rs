use super::spectral::SpectralConvolution;
use super::ElasticOperator;
use crate::grid::Grid;
use crate::material::ElasticMaterial;
use std::f64::consts::TAU;
use std::ops::Range;

/// Number of aliases |m|, |n| ≤ this kept in the element-consistent kernel: reproduces
/// Love's near-field coefficient differences to 1e-5 (docs/physics.md §1b).
const ALIASES: i32 = 40;

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

/// Periodic half-space (period L = NΔ in x and y) as a Fourier multiplier.
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

fn sinc(t: f64) -> f64 {
    if t.abs() < 1e-8 {
        1.0 - t * t / 6.0
    } else {
        t.sin() / t
    }
}

impl PeriodicOperator {
    /// Plans the transforms and computes the kernel spectrum.
    pub fn new(grid: Grid, material: ElasticMaterial, kernel: PeriodicKernel) -> Self {
        let n = grid.n();
        let delta = grid.element_size();
        let modulus = material.contact_modulus();
        let mut engine = SpectralConvolution::<f64>::planned(n, n);
        let frequency = |index: usize| -> f64 {
            let k = if index <= n / 2 {
                index as f64
            } else {
                index as f64 - n as f64
            };
            TAU * k / grid.size()
        };
        let aliases: Vec<i32> = match kernel {
            PeriodicKernel::ElementConsistent => (-ALIASES..=ALIASES).collect(),
            PeriodicKernel::Continuous => vec![0],
        };
        // Per-axis tables: shifted wavenumbers q + 2πm/Δ and form factors sinc((q+G)Δ/2).
        let table = |index: usize| -> Vec<(f64, f64)> {
            let q = frequency(index);
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
        let tables: Vec<Vec<(f64, f64)>> = (0..n).map(table).collect();
        let normalisation = 1.0 / (n as f64 * n as f64);
        // K̂ is even in q_y: evaluate rows 0..=N/2 once (in parallel), mirror the rest.
        let half_rows = n / 2 + 1;
        let columns = n / 2 + 1;
        let mut half = vec![0.0; half_rows * columns];
        {
            use rayon::prelude::*;
            half.par_chunks_mut(columns).enumerate().for_each(|(row, out)| {
                for (column, value) in out.iter_mut().enumerate() {
                    if row == 0 && column == 0 {
                        continue;
                    }
                    let mut sum = 0.0;
                    for &(qx2, sx) in &tables[column] {
                        for &(qy2, sy) in &tables[row] {
                            sum += sx * sy / (qx2 + qy2).sqrt();
                        }
                    }
                    *value = 2.0 * sum / modulus * normalisation;
                }
            });
        }
        engine.set_kernel_spectrum(|row, column| {
            let row = if row > n / 2 { n - row } else { row };
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
        unit[(n / 2) * n + n / 2] = 1.0;
        let mut response = vec![0.0; grid.len()];
        operator.apply(&unit, &mut response);
        operator.self_compliance = response[(n / 2) * n + n / 2];
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
