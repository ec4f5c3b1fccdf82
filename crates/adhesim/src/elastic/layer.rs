//! An elastic layer of finite thickness t on a rigid base, loaded by normal pressure on
//! its free surface by a rigid frictionless indenter: pressure → normal surface
//! displacement (docs/physics.md, "Elastic layer of finite thickness").
//!
//! The Fourier compliance is the half-space's 2/(E*k) times [`layer_compliance_factor`]
//! of kt. A periodic grid uses it inside the element-consistent alias sum of
//! [`PeriodicOperator`]; a free grid uses Love's coefficients plus the layer's correction
//! to Boussinesq's point kernel, a Hankel transform tabulated once in r/t and integrated
//! over each element, in the DC-FFT convolution of [`super::FreeOperator`].

use super::bessel::Bessel;
use super::influence::love_rectangle;
use super::layer_tables::{table, TableKey, TABLE_RANGE, TABLE_ROWS, TABLE_STEP};
use super::periodic::{PeriodicKernel, PeriodicOperator};
use super::spectral::SpectralConvolution;
use super::ElasticOperator;
use crate::grid::{Boundary, Grid};
use crate::material::ElasticMaterial;
use rayon::prelude::*;
use std::f64::consts::PI;
use std::ops::Range;
use std::sync::Arc;
use thiserror::Error;

/// How the layer is held by the rigid base.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum LayerBase {
    /// Bonded: no displacement at the base (u = 0 there).
    Bonded,
    /// Frictionless: no normal displacement and no shear traction at the base.
    Frictionless,
}

/// Errors for invalid layer parameters.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum LayerError {
    /// The thickness must be finite and positive.
    #[error("layer thickness must be finite and > 0, got {0}")]
    InvalidThickness(f64),
    /// Poisson's ratio must lie in (−1, 0.5].
    #[error("Poisson's ratio of the layer must lie in (-1, 0.5], got {0}")]
    InvalidPoissonRatio(f64),
    /// A free grid's element quadrature resolves layers down to a sixteenth of an element.
    #[error(
        "layer thickness {thickness} is below 1/16 of the element size {element}: the free grid cannot resolve it"
    )]
    ThinnerThanElements {
        /// The layer thickness.
        thickness: f64,
        /// The larger element side.
        element: f64,
    },
}

/// An elastic layer: thickness t, Poisson's ratio ν and the base it rests on. Its contact
/// modulus E* = E/(1 − ν²) is the [`ElasticMaterial`]'s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElasticLayer {
    thickness: f64,
    poisson_ratio: f64,
    base: LayerBase,
}

impl ElasticLayer {
    /// A layer of `thickness` (> 0, finite) and `poisson_ratio` in (−1, 0.5].
    pub fn new(thickness: f64, poisson_ratio: f64, base: LayerBase) -> Result<Self, LayerError> {
        if !(thickness.is_finite() && thickness > 0.0) {
            return Err(LayerError::InvalidThickness(thickness));
        }
        if !(poisson_ratio > -1.0 && poisson_ratio <= 0.5) {
            return Err(LayerError::InvalidPoissonRatio(poisson_ratio));
        }
        Ok(Self {
            thickness,
            poisson_ratio,
            base,
        })
    }

    /// The thickness t.
    pub fn thickness(&self) -> f64 {
        self.thickness
    }

    /// Poisson's ratio ν.
    pub fn poisson_ratio(&self) -> f64 {
        self.poisson_ratio
    }

    /// The base.
    pub fn base(&self) -> LayerBase {
        self.base
    }

    /// On a free grid the element quadrature resolves the layer down to a sixteenth of an
    /// element; periodic grids take any thickness.
    pub(super) fn check_resolved(&self, grid: &Grid) -> Result<(), LayerError> {
        let element = grid.dx().max(grid.dy());
        if grid.boundary() == Boundary::Free && self.thickness < element / 16.0 {
            return Err(LayerError::ThinnerThanElements {
                thickness: self.thickness,
                element,
            });
        }
        Ok(())
    }

    /// C_layer(k)/C_halfspace(k) at wavenumber k.
    pub fn compliance_factor(&self, wavenumber: f64) -> f64 {
        layer_compliance_factor(wavenumber * self.thickness, self.poisson_ratio, self.base)
    }
}

/// Beyond this kt the factor is 1 in double precision: 1 − f < 1e-18 for both bases and
/// every ν in (−1, 0.5] (1 − f ≈ 2(2s² + (1 + κ²)/2)e^{−2s}/κ, s = kt).
pub(super) const SCREENED_KT: f64 = 25.0;

/// C_layer(k)/C_halfspace(k): the surface compliance of an elastic layer of thickness t on
/// a rigid base under a normal pressure wave of wavenumber k (zero shear traction on the
/// surface), over the half-space's 2/(E*k); a function of s = kt and ν (κ = 3 − 4ν):
///
/// bonded:       f = (κ sinh 2s − 2s) / (κ cosh 2s + 2s² + (1 + κ²)/2)
/// frictionless: f = (cosh 2s − 1) / (sinh 2s + 2s)
///
/// The plane-strain layer solution of Westergaard and Burmister as collected in Johnson
/// (1985), *Contact Mechanics*, §5.9 (Cambridge University Press,
/// doi:10.1017/CBO9781139171731), and Chen & Engel (1972), *Int. J. Solids Struct.* 8,
/// 1257–1281, doi:10.1016/0020-7683(72)90079-3; re-derived from Navier's equations for
/// docs/physics.md. Finite for every ν up to exactly 1/2 (κ = 1, no 0/0): the numerator's
/// cancellation at small s is removed by writing it (κ − 1) sinh 2s + (sinh 2s − 2s).
/// Limits: f → 1 for s → ∞; bonded f → 4s(κ − 1)/(1 + κ)² (uniaxial strain) and at
/// κ = 1 f → 2s³/3 (C = t³k²/(3G)); frictionless f → s/2 (C = t/E*). `kt` ≥ 0; f(0) = 0.
///
/// # Example
/// ```
/// use adhesim::elastic::layer_compliance_factor;
/// use adhesim::LayerBase;
///
/// // Short waves do not feel the base; long ones on a thin bonded incompressible layer see
/// // the lubrication compliance t³k²/(3G): the half-space's 2/(E*k) times (2/3)(kt)³ at
/// // ν = 1/2 (E* = 4G).
/// assert_eq!(layer_compliance_factor(30.0, 0.5, LayerBase::Bonded), 1.0);
/// let kt = 1e-3;
/// let factor = layer_compliance_factor(kt, 0.5, LayerBase::Bonded);
/// assert!((factor / (2.0 / 3.0 * kt * kt * kt) - 1.0).abs() < 1e-3);
/// // A frictionless base is softer than a bonded one.
/// assert!(layer_compliance_factor(1.0, 0.3, LayerBase::Frictionless) > layer_compliance_factor(1.0, 0.3, LayerBase::Bonded));
/// ```
pub fn layer_compliance_factor(kt: f64, poisson_ratio: f64, base: LayerBase) -> f64 {
    if kt >= SCREENED_KT {
        return 1.0;
    }
    if kt <= 0.0 {
        return 0.0;
    }
    let double = 2.0 * kt;
    match base {
        LayerBase::Bonded => {
            let kappa = 3.0 - 4.0 * poisson_ratio;
            let numerator = (kappa - 1.0) * double.sinh() + sinh_minus_argument(double);
            numerator / bonded_denominator(kt, kappa)
        }
        LayerBase::Frictionless => {
            // cosh 2s − 1 = 2 sinh² s, without cancellation.
            2.0 * kt.sinh().powi(2) / (double.sinh() + double)
        }
    }
}

/// sinh x − x without cancellation: its Taylor series below |x| = 1.
pub(super) fn sinh_minus_argument(x: f64) -> f64 {
    if x.abs() >= 1.0 {
        return x.sinh() - x;
    }
    let square = x * x;
    let mut term = x * square / 6.0;
    let mut sum = term;
    let mut n = 3.0;
    while term.abs() > 1e-18 * sum.abs() {
        term *= square / ((n + 1.0) * (n + 2.0));
        sum += term;
        n += 2.0;
    }
    sum
}

/// The denominator κ cosh 2s + 2s² + (1 + κ²)/2 (s = kt, κ = 3 − 4ν) shared by the bonded
/// layer's normal, tangential and coupling compliances.
pub(super) fn bonded_denominator(kt: f64, kappa: f64) -> f64 {
    kappa * (2.0 * kt).cosh() + 2.0 * kt * kt + 0.5 * (1.0 + kappa * kappa)
}

/// Gauss–Legendre nodes on [−1, 1] (positive half) and weights, 4 points.
const GAUSS4_NODES: [f64; 2] = [0.339_981_043_584_856_3, 0.861_136_311_594_052_6];
const GAUSS4_WEIGHTS: [f64; 2] = [0.652_145_154_862_546_1, 0.347_854_845_137_453_9];
/// 8 points.
const GAUSS8_NODES: [f64; 4] = [
    0.183_434_642_495_649_8,
    0.525_532_409_916_329,
    0.796_666_477_413_626_7,
    0.960_289_856_497_536_3,
];
const GAUSS8_WEIGHTS: [f64; 4] = [
    0.362_683_783_378_362,
    0.313_706_645_877_887_3,
    0.222_381_034_453_374_5,
    0.101_228_536_290_376_3,
];

/// Panel width in s of the Hankel quadrature: J0(sρ) has period 2π/ρ ≥ 0.1 in s.
const PANEL: f64 = 0.05;

/// The layer's point-load kernel minus Boussinesq's, D(r) = d(r/t)/(πE*t), with
/// d(ρ) = ∫0^∞ (f(s) − 1) J0(sρ) ds (the 2-D inverse transform of the radial compliance
/// difference (2/(E*k))(f(kt) − 1)), tabulated on ρ = jh. The integrand decays as e^{−2s}
/// and is cut at s = 25 (below 1e-18); 8-point Gauss–Legendre on panels of 0.05. The
/// tangential kernels ([`super::layer_shear`]) tabulate their own integrands the same way.
pub(super) struct PointCorrection {
    values: Arc<[f64]>,
    /// d(ρ)·ρ^`far_power` beyond the table, where the layer carries nothing and D is minus
    /// the half-space's point kernel.
    far: f64,
    far_power: i32,
}

impl PointCorrection {
    fn new(layer: &ElasticLayer) -> Self {
        let (poisson_ratio, base) = (layer.poisson_ratio, layer.base);
        let key = TableKey::Normal {
            poisson_ratio_bits: poisson_ratio.to_bits(),
            base,
        };
        Self::tabulate(key, normal_table_integrand(poisson_ratio, base), Bessel::J0, (-1.0, 1))
    }

    /// d(ρ) = ∫0^25 `integrand`(s)·`bessel`(sρ) ds on the table, and c/ρ^n beyond it,
    /// (c, n) = `far`; `bessel` must be even (the table reflects at 0).
    /// The Bessel values of one row come from [`Bessel::fill`] (the series side by side). A
    /// table is computed once per `key` in a process ([`super::layer_tables`]): `key` must
    /// name every parameter `integrand` depends on.
    pub(super) fn tabulate(key: TableKey, integrand: impl Fn(f64) -> f64, bessel: Bessel, far: (f64, i32)) -> Self {
        Self {
            values: table(key, || Self::compute(integrand, bessel)),
            far: far.0,
            far_power: far.1,
        }
    }

    /// The table's values, d(ρ) at ρ = jh.
    fn compute(integrand: impl Fn(f64) -> f64, bessel: Bessel) -> Vec<f64> {
        Self::compute_rows(integrand, bessel, 1)
    }

    /// d(jh) for every `stride`-th row j of the table, each exactly as in the whole table.
    pub(super) fn compute_rows(integrand: impl Fn(f64) -> f64, bessel: Bessel, stride: usize) -> Vec<f64> {
        let panels = (SCREENED_KT / PANEL).round() as usize;
        let (mut nodes, mut weights) = (Vec::with_capacity(panels * 8), Vec::with_capacity(panels * 8));
        for panel in 0..panels {
            let centre = (panel as f64 + 0.5) * PANEL;
            for (&node, &weight) in GAUSS8_NODES.iter().zip(&GAUSS8_WEIGHTS) {
                for sign in [-1.0, 1.0] {
                    let s = centre + sign * node * 0.5 * PANEL;
                    nodes.push(s);
                    weights.push(0.5 * PANEL * weight * integrand(s));
                }
            }
        }
        (0..TABLE_ROWS)
            .into_par_iter()
            .step_by(stride)
            .map_init(
                || vec![0.0; nodes.len()],
                |row, j| {
                    let rho = j as f64 * TABLE_STEP;
                    bessel.fill(&nodes, rho, row);
                    weights.iter().zip(row.iter()).map(|(&w, &b)| w * b).sum()
                },
            )
            .collect()
    }

    /// d(ρ): cubic Lagrange interpolation (d is even: the stencil reflects at 0), c/ρ^n
    /// beyond the table.
    pub(super) fn value(&self, rho: f64) -> f64 {
        if rho >= TABLE_RANGE {
            return self.far / rho.powi(self.far_power);
        }
        let last = self.values.len() - 1;
        let position = rho / TABLE_STEP;
        let start = (position.floor() as i64 - 1).min(last as i64 - 3);
        let x = position - start as f64;
        let at = |j: i64| self.values[j.unsigned_abs() as usize];
        let (y0, y1, y2, y3) = (at(start), at(start + 1), at(start + 2), at(start + 3));
        // Lagrange on the nodes 0, 1, 2, 3 at x.
        let (a, b, c, d) = (x, x - 1.0, x - 2.0, x - 3.0);
        -y0 * b * c * d / 6.0 + y1 * a * c * d / 2.0 - y2 * a * b * d / 2.0 + y3 * a * b * c / 6.0
    }
}

/// The normal kernel's table integrand f(s) − 1 ([`layer_compliance_factor`] less the
/// half-space's).
pub(super) fn normal_table_integrand(poisson_ratio: f64, base: LayerBase) -> impl Fn(f64) -> f64 {
    move |s| layer_compliance_factor(s, poisson_ratio, base) - 1.0
}

/// K_layer at offset (lΔx, mΔy) for 0 ≤ l < Nx, 0 ≤ m < Ny (`[m * Nx + l]`): Love's
/// coefficient plus D integrated over the element ([`element_integrals`]). Zero where the
/// whole element lies beyond 60t: the exact value there is below 2e-20 of the kernel's
/// scale. K is even in l and in m.
fn layer_coefficients(grid: &Grid, modulus: f64, layer: &ElasticLayer) -> Vec<f64> {
    let (nx, dx, dy) = (grid.nx(), grid.dx(), grid.dy());
    let t = layer.thickness;
    let correction = PointCorrection::new(layer);
    let scale = 1.0 / (PI * modulus * t);
    let sums = element_integrals(grid, t, |x, y| [correction.value(x.hypot(y) / t)]);
    let mut table = vec![0.0; sums.len()];
    table.par_chunks_mut(nx).enumerate().for_each(|(m, row)| {
        for (l, value) in row.iter_mut().enumerate() {
            if let Some([sum]) = sums[m * nx + l] {
                let (xi, eta) = (l as f64 * dx, m as f64 * dy);
                *value = love_rectangle(xi, eta, dx, dy, modulus) + scale * sum;
            }
        }
    });
    table
}

/// ∫∫ `point`(x, y) over the element at offset (lΔx, mΔy) from the source element, for
/// 0 ≤ l < Nx, 0 ≤ m < Ny (`[m * Nx + l]`): Gauss–Legendre 4×4 on sub-squares of side
/// ≤ t/2 near the element, on the whole element from 8 elements on, where a layer's
/// correction is smooth on the scale of the distance. None where the whole element lies
/// beyond 60t, where the layer's kernel is below 2e-20 of its scale.
pub(super) fn element_integrals<const C: usize>(
    grid: &Grid,
    thickness: f64,
    point: impl Fn(f64, f64) -> [f64; C] + Sync,
) -> Vec<Option<[f64; C]>> {
    let (nx, ny, dx, dy) = (grid.nx(), grid.ny(), grid.dx(), grid.dy());
    let element = dx.max(dy);
    let near_divisions = ((2.0 * element / thickness).ceil() as usize).clamp(1, 32);
    let mut table = vec![None; nx * ny];
    table.par_chunks_mut(nx).enumerate().for_each(|(m, row)| {
        for (l, value) in row.iter_mut().enumerate() {
            let (xi, eta) = (l as f64 * dx, m as f64 * dy);
            let nearest = (xi - 0.5 * dx).max(0.0).hypot((eta - 0.5 * dy).max(0.0));
            if nearest > TABLE_RANGE * thickness {
                continue;
            }
            let divisions = if xi.hypot(eta) < 8.0 * element {
                near_divisions
            } else {
                1
            };
            let (hx, hy) = (dx / divisions as f64, dy / divisions as f64);
            let mut sum = [0.0; C];
            for a in 0..divisions {
                for b in 0..divisions {
                    let cx = -0.5 * dx + (a as f64 + 0.5) * hx;
                    let cy = -0.5 * dy + (b as f64 + 0.5) * hy;
                    for (i, &ni) in GAUSS4_NODES.iter().enumerate() {
                        for si in [-1.0, 1.0] {
                            for (j, &nj) in GAUSS4_NODES.iter().enumerate() {
                                for sj in [-1.0, 1.0] {
                                    let x = xi - (cx + 0.5 * si * ni * hx);
                                    let y = eta - (cy + 0.5 * sj * nj * hy);
                                    let weight = GAUSS4_WEIGHTS[i] * GAUSS4_WEIGHTS[j] * 0.25 * hx * hy;
                                    let values = point(x, y);
                                    for (total, value) in sum.iter_mut().zip(values) {
                                        *total += weight * value;
                                    }
                                }
                            }
                        }
                    }
                }
            }
            *value = Some(sum);
        }
    });
    table
}

/// The layer's operator on a free grid (DC-FFT) or a periodic one (Fourier multiplier).
enum LayerKernel {
    Periodic(PeriodicOperator),
    Free {
        engine: SpectralConvolution,
        /// Single-precision copy for [`ElasticOperator::apply_single`], made at first use.
        single: Option<SpectralConvolution<f32>>,
        self_compliance: f64,
        applications: u64,
    },
}

/// Surface compliance of an elastic layer on a rigid base ([`ElasticLayer`]), for a rigid
/// frictionless indenter.
///
/// Free grids: the discrete convolution and FFT of Liu, Wang & Liu (2000), *Wear* 243,
/// 101–111, doi:10.1016/S0043-1648(00)00427-0, with the exact element coefficients of the
/// layer: Love's (1929) half-space coefficient plus the layer's correction to Boussinesq,
/// whose Hankel transform is tabulated once (no periodic images, no truncation of the
/// grid: the coefficients are exact for any t, to ≈ 1e-8 of the self-compliance).
/// Periodic grids: the element-consistent alias sum of [`PeriodicOperator`] with each term
/// multiplied by the factor at its own wavenumber; as there, K̂(0) = 0 (the solvers'
/// mean-gap convention), which leaves out the layer's uniform compression C(0)·p̄
/// (zero for a bonded incompressible layer).
pub struct LayerOperator {
    grid: Grid,
    contact_modulus: f64,
    layer: ElasticLayer,
    kernel: LayerKernel,
}

impl LayerOperator {
    /// Plans the transforms and computes the kernel spectrum for `grid`, the contact
    /// modulus E* of `material` and `layer`.
    pub fn new(grid: Grid, material: ElasticMaterial, layer: ElasticLayer) -> Result<Self, LayerError> {
        let modulus = material.contact_modulus();
        let kernel = match grid.boundary() {
            Boundary::Periodic => LayerKernel::Periodic(PeriodicOperator::with_compliance_factor(
                grid,
                material,
                PeriodicKernel::ElementConsistent,
                |wavenumber| layer.compliance_factor(wavenumber),
            )),
            Boundary::Free => {
                layer.check_resolved(&grid)?;
                let (nx, ny) = (grid.nx(), grid.ny());
                let table = layer_coefficients(&grid, modulus, &layer);
                // Row i of the 2Ny × 2Nx padded kernel: offsets m = i (i < Ny), −(2Ny − i)
                // (i > Ny), zero row Ny; the same wrapping along the row.
                let engine = SpectralConvolution::new((nx, ny), (2 * nx, 2 * ny), |i, row| {
                    let m = match i {
                        i if i < ny => i,
                        i if i == ny => {
                            row.fill(0.0);
                            return;
                        }
                        i => 2 * ny - i,
                    };
                    for (j, entry) in row.iter_mut().enumerate() {
                        *entry = match j {
                            j if j < nx => table[m * nx + j],
                            j if j == nx => 0.0,
                            j => table[m * nx + 2 * nx - j],
                        };
                    }
                });
                LayerKernel::Free {
                    engine,
                    single: None,
                    self_compliance: table[0],
                    applications: 0,
                }
            }
        };
        Ok(Self {
            grid,
            contact_modulus: modulus,
            layer,
            kernel,
        })
    }

    /// The layer.
    pub fn layer(&self) -> &ElasticLayer {
        &self.layer
    }
}

impl ElasticOperator for LayerOperator {
    fn grid(&self) -> &Grid {
        &self.grid
    }
    fn contact_modulus(&self) -> f64 {
        self.contact_modulus
    }
    fn apply(&mut self, pressure: &[f64], displacement: &mut [f64]) {
        match &mut self.kernel {
            LayerKernel::Periodic(operator) => operator.apply(pressure, displacement),
            LayerKernel::Free {
                engine, applications, ..
            } => {
                engine.convolve(pressure, displacement);
                *applications += 1;
            }
        }
    }
    fn apply_single(&mut self, pressure: &[f64], displacement: &mut [f64]) {
        match &mut self.kernel {
            LayerKernel::Periodic(operator) => operator.apply_single(pressure, displacement),
            LayerKernel::Free {
                engine,
                single,
                applications,
                ..
            } => {
                single
                    .get_or_insert_with(|| engine.to_single())
                    .convolve(pressure, displacement);
                *applications += 1;
            }
        }
    }
    fn apply_single_rows(
        &mut self,
        pressure: &[f64],
        displacement: &mut [f64],
        input_rows: Range<usize>,
        output_rows: Range<usize>,
    ) {
        match &mut self.kernel {
            LayerKernel::Periodic(operator) => {
                operator.apply_single_rows(pressure, displacement, input_rows, output_rows)
            }
            LayerKernel::Free {
                engine,
                single,
                applications,
                ..
            } => {
                let single = single.get_or_insert_with(|| engine.to_single());
                single.convolve_rows(pressure, displacement, input_rows, output_rows);
                *applications += 1;
            }
        }
    }
    fn self_compliance(&self) -> f64 {
        match &self.kernel {
            LayerKernel::Periodic(operator) => operator.self_compliance(),
            LayerKernel::Free { self_compliance, .. } => *self_compliance,
        }
    }
    fn applications(&self) -> u64 {
        match &self.kernel {
            LayerKernel::Periodic(operator) => operator.applications(),
            LayerKernel::Free { applications, .. } => *applications,
        }
    }
}

#[cfg(test)]
pub(super) mod navier;
#[cfg(test)]
mod tests;
