//! The tangential operator of a half-space or a bonded layer: shear tractions →
//! tangential surface displacements.

use super::cerruti::{cerruti_rectangle, CerrutiCoefficients, ShearMaterial};
use super::layer_shear::layer_shear_coefficients;
use super::spectral::SpectralConvolution;
use super::tangential_periodic::periodic_spectra;
use super::{ElasticLayer, LayerBase, LayerError};
use crate::grid::{Boundary, Grid};
use thiserror::Error;

/// Why a tangential operator cannot be built.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum TangentialOperatorError {
    /// G must be finite and positive, ν in (−1, 1/2].
    #[error("shear modulus must be finite and > 0 and Poisson's ratio in (-1, 0.5], got G = {shear_modulus}, ν = {poisson_ratio}")]
    InvalidMaterial {
        /// G.
        shear_modulus: f64,
        /// ν.
        poisson_ratio: f64,
    },
    /// A layer on a frictionless base slides on it under a tangential load.
    #[error("a layer on a frictionless base carries no tangential load (it slides on its base): use a bonded base")]
    LayerSlidesOnBase,
    /// The layer's ν must be the material's.
    #[error("the layer's Poisson's ratio {layer} differs from the material's {material}")]
    LayerPoissonRatio {
        /// ν of the layer.
        layer: f64,
        /// ν of the material.
        material: f64,
    },
    /// The layer cannot be resolved on the grid.
    #[error(transparent)]
    Layer(#[from] LayerError),
}

/// The tangential half-space: u_x = K_xx∗q_x + K_xy∗q_y, u_y = K_xy∗q_x + K_yy∗q_y. On a
/// free grid by DC-FFT (Liu, Wang & Liu 2000) with Cerruti's exact element coefficients
/// ([`cerruti_rectangle`]), each a linear convolution made cyclic by zero padding; on a
/// periodic grid as Cerruti's Fourier multiplier summed over the element's aliases
/// (`tangential_periodic`), with K̂(0) = 0: the shift is then the indenter's relative to
/// the surface's mean displacement, as a periodic depth is relative to the mean gap.
///
/// Goodman's approximation: the normal displacement of a shear traction and the
/// tangential displacement of a pressure, both ∝ (1 − 2ν), are left out (exact at
/// ν = 1/2, docs/physics.md §8.1).
///
/// [`on_layer`](Self::on_layer) builds the same operator for an elastic layer bonded to a
/// rigid base: Cerruti's coefficients plus the layer's correction on free grids, the
/// layer's Fourier compliance in the alias sum on periodic ones (`layer_shear`).
pub struct TangentialOperator {
    grid: Grid,
    material: ShearMaterial,
    layer: Option<ElasticLayer>,
    xx: SpectralConvolution,
    yy: SpectralConvolution,
    /// The spectrum of K_xy; None on a half-space at ν = 0, where the cross coefficient
    /// vanishes.
    xy: Option<Vec<f64>>,
    self_compliance: f64,
    transforms: u64,
}

/// The body a tangential operator is built for: its G and ν, as a half-space or as an
/// elastic layer bonded to a rigid base.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShearBody {
    /// G and ν.
    pub material: ShearMaterial,
    /// The layer (None: the half-space).
    pub layer: Option<ElasticLayer>,
}

impl From<ShearMaterial> for ShearBody {
    fn from(material: ShearMaterial) -> Self {
        Self { material, layer: None }
    }
}

/// G finite and positive, ν in (−1, 1/2]: what the tangential and coupling operators take.
pub(super) fn check_material(material: ShearMaterial) -> Result<(), TangentialOperatorError> {
    let (g, nu) = (material.shear_modulus, material.poisson_ratio);
    if g.is_finite() && g > 0.0 && nu > -1.0 && nu <= 0.5 {
        Ok(())
    } else {
        Err(TangentialOperatorError::InvalidMaterial {
            shear_modulus: g,
            poisson_ratio: nu,
        })
    }
}

/// What the tangential and coupling operators of a layer take: a valid material, a bonded
/// base, the material's ν, and on a free grid at least 1/16 of an element of thickness.
pub(super) fn check_layer(
    grid: &Grid,
    material: ShearMaterial,
    layer: &ElasticLayer,
) -> Result<(), TangentialOperatorError> {
    check_material(material)?;
    if layer.base() != LayerBase::Bonded {
        return Err(TangentialOperatorError::LayerSlidesOnBase);
    }
    if layer.poisson_ratio() != material.poisson_ratio {
        return Err(TangentialOperatorError::LayerPoissonRatio {
            layer: layer.poisson_ratio(),
            material: material.poisson_ratio,
        });
    }
    Ok(layer.check_resolved(grid)?)
}

/// The signed offset in elements of index `i` of a 2n-periodic padded axis (DC-FFT); the
/// index n, which no offset of the data window reaches, is None.
pub(super) fn padded_offset(i: usize, n: usize) -> Option<f64> {
    match i {
        i if i < n => Some(i as f64),
        i if i == n => None,
        i => Some(-((2 * n - i) as f64)),
    }
}

impl TangentialOperator {
    /// Plans the transforms and computes the three kernel spectra.
    pub fn new(grid: Grid, material: ShearMaterial) -> Result<Self, TangentialOperatorError> {
        check_material(material)?;
        Self::build(grid, material, None)
    }

    /// The operator of `layer` (bonded to its base; its ν must be `material`'s) instead of
    /// the half-space. On a free grid the layer must be at least 1/16 of an element thick.
    ///
    /// # Example
    /// ```
    /// use adhesim::{Boundary, ElasticLayer, Grid, LayerBase, ShearMaterial, TangentialOperator};
    ///
    /// // A uniform traction over a patch much wider than a thin layer shears it simply:
    /// // u = q·t/G in the middle of the patch (32t from its edges).
    /// let grid = Grid::new(64, 1.0, Boundary::Free)?;
    /// let material = ShearMaterial::from_contact_modulus(4.0, 0.5); // G = 1
    /// let layer = ElasticLayer::new(grid.dx(), 0.5, LayerBase::Bonded)?;
    /// let mut operator = TangentialOperator::on_layer(grid, material, layer)?;
    /// let qx = vec![1.0; grid.len()];
    /// let qy = vec![0.0; grid.len()];
    /// let (mut ux, mut uy) = (vec![0.0; grid.len()], vec![0.0; grid.len()]);
    /// operator.apply([&qx, &qy], [&mut ux, &mut uy]);
    /// let centre = 32 * 64 + 32;
    /// assert!((ux[centre] / layer.thickness() - 1.0).abs() < 1e-6);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn on_layer(grid: Grid, material: ShearMaterial, layer: ElasticLayer) -> Result<Self, TangentialOperatorError> {
        check_layer(&grid, material, &layer)?;
        Self::build(grid, material, Some(layer))
    }

    /// [`new`](Self::new) or [`on_layer`](Self::on_layer), as `body` says.
    pub fn for_body(grid: Grid, body: ShearBody) -> Result<Self, TangentialOperatorError> {
        match body.layer {
            None => Self::new(grid, body.material),
            Some(layer) => Self::on_layer(grid, body.material, layer),
        }
    }

    fn build(
        grid: Grid,
        material: ShearMaterial,
        layer: Option<ElasticLayer>,
    ) -> Result<Self, TangentialOperatorError> {
        let nu = material.poisson_ratio;
        if grid.boundary() == Boundary::Periodic {
            let (xx, yy, xy) = periodic_spectra(&grid, material, layer.as_ref());
            let mut operator = Self {
                grid,
                material,
                layer,
                xx,
                yy,
                xy,
                self_compliance: 0.0,
                transforms: 0,
            };
            // The diagonal of the periodic sum (the free one's less the images' and the
            // mean's share), read off the response to a unit traction.
            let n = grid.len();
            let centre = (grid.ny() / 2) * grid.nx() + grid.nx() / 2;
            let (mut unit, zero) = (vec![0.0; n], vec![0.0; n]);
            unit[centre] = 1.0;
            let (mut ux, mut uy) = (vec![0.0; n], vec![0.0; n]);
            operator.apply([&unit, &zero], [&mut ux, &mut uy]);
            operator.self_compliance = ux[centre];
            operator.transforms = 0;
            return Ok(operator);
        }
        let (nx, ny) = (grid.nx(), grid.ny());
        let (dx, dy) = (grid.dx(), grid.dy());
        let wrap = padded_offset;
        let layer_table = layer.map(|layer| layer_shear_coefficients(&grid, material, &layer));
        // The coefficients at a signed offset in elements: K_xx, K_yy even, K_xy odd.
        let coefficient = |xi: f64, eta: f64| match &layer_table {
            None => cerruti_rectangle(xi * dx, eta * dy, dx, dy, material),
            Some(table) => {
                let entry = table[eta.abs() as usize * nx + xi.abs() as usize];
                let sign = xi.signum() * eta.signum();
                CerrutiCoefficients {
                    xy: sign * entry.xy,
                    ..entry
                }
            }
        };
        let engine = |component: fn(CerrutiCoefficients) -> f64| {
            SpectralConvolution::new((nx, ny), (2 * nx, 2 * ny), |i, row: &mut [f64]| {
                let eta = wrap(i, ny);
                for (j, entry) in row.iter_mut().enumerate() {
                    *entry = match (eta, wrap(j, nx)) {
                        (Some(eta), Some(xi)) => component(coefficient(xi, eta)),
                        _ => 0.0,
                    };
                }
            })
        };
        let xx = engine(|c| c.xx);
        let yy = engine(|c| c.yy);
        // On a layer K_xy is not zero at ν = 0: the longitudinal and transverse factors differ.
        let xy = (nu != 0.0 || layer.is_some()).then(|| engine(|c| c.xy).into_kernel());
        Ok(Self {
            grid,
            material,
            layer,
            xx,
            yy,
            xy,
            self_compliance: coefficient(0.0, 0.0).xx,
            transforms: 0,
        })
    }

    /// The grid the operator acts on.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// G and ν of the half-space.
    pub fn material(&self) -> ShearMaterial {
        self.material
    }

    /// The layer the operator is built for (None: the half-space).
    pub fn layer(&self) -> Option<&ElasticLayer> {
        self.layer.as_ref()
    }

    /// K_xx(0,0): the tangential displacement of an element under its own unit traction
    /// along x.
    ///
    /// # Example
    /// ```
    /// use adhesim::{Boundary, Grid, ShearMaterial, TangentialOperator};
    ///
    /// // On a square element K_xx(0,0) = (2 − ν)Δ·asinh(1)/(πG) (docs/physics.md §8.1); a unit
    /// // traction on one element moves it by that much, and nothing across the shear there.
    /// let grid = Grid::new(16, 1.0, Boundary::Free)?;
    /// let material = ShearMaterial::from_contact_modulus(4.0, 0.5); // G = 1
    /// let mut operator = TangentialOperator::new(grid, material)?;
    /// let closed_form = 1.5 * grid.dx() * 1f64.asinh() / std::f64::consts::PI;
    /// assert!((operator.self_compliance() / closed_form - 1.0).abs() < 1e-12);
    /// let centre = 8 * 16 + 8;
    /// let mut qx = vec![0.0; grid.len()];
    /// qx[centre] = 1.0;
    /// let qy = vec![0.0; grid.len()];
    /// let (mut ux, mut uy) = (vec![0.0; grid.len()], vec![0.0; grid.len()]);
    /// operator.apply([&qx, &qy], [&mut ux, &mut uy]);
    /// assert!((ux[centre] / closed_form - 1.0).abs() < 1e-9);
    /// assert!(uy[centre].abs() < 1e-12 * closed_form);
    /// assert_eq!(operator.transform_pairs(), 2);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn self_compliance(&self) -> f64 {
        self.self_compliance
    }

    /// Writes (u_x, u_y) = K (q_x, q_y); each slice holds one value per element, row-major.
    ///
    /// # Panics
    /// If a slice length differs from the number of elements.
    pub fn apply(&mut self, traction: [&[f64]; 2], displacement: [&mut [f64]; 2]) {
        match &self.xy {
            Some(cross) => self.xx.convolve_pair(&mut self.yy, cross, traction, displacement),
            None => {
                let ([qx, qy], [ux, uy]) = (traction, displacement);
                self.xx.convolve(qx, ux);
                self.yy.convolve(qy, uy);
            }
        }
        self.transforms += 2;
    }

    /// Forward + inverse transform pairs done so far (two per application).
    pub fn transform_pairs(&self) -> u64 {
        self.transforms
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A direct O(N⁴) sum of the coefficients, the reference of the convolution.
    fn direct(grid: &Grid, material: ShearMaterial, qx: &[f64], qy: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let n = grid.len();
        let (mut ux, mut uy) = (vec![0.0; n], vec![0.0; n]);
        for target in 0..n {
            let (x, y) = grid.centre(target);
            for source in 0..n {
                let (xs, ys) = grid.centre(source);
                let c = cerruti_rectangle(x - xs, y - ys, grid.dx(), grid.dy(), material);
                ux[target] += c.xx * qx[source] + c.xy * qy[source];
                uy[target] += c.xy * qx[source] + c.yy * qy[source];
            }
        }
        (ux, uy)
    }

    #[test]
    fn convolution_equals_the_direct_sum_on_a_rectangular_grid() {
        // DC-FFT is exact up to round-off: 1e-12 of the largest displacement.
        let grid = Grid::rectangular(12, 9, 1.2, 0.72, Boundary::Free).unwrap();
        let material = ShearMaterial {
            shear_modulus: 0.8,
            poisson_ratio: 0.3,
        };
        let n = grid.len();
        let qx: Vec<f64> = (0..n).map(|k| ((k * 37 % 11) as f64 - 4.0) / 7.0).collect();
        let qy: Vec<f64> = (0..n).map(|k| ((k * 53 % 13) as f64 - 6.0) / 9.0).collect();
        let mut operator = TangentialOperator::new(grid, material).unwrap();
        let (mut ux, mut uy) = (vec![0.0; n], vec![0.0; n]);
        operator.apply([&qx, &qy], [&mut ux, &mut uy]);
        let (rx, ry) = direct(&grid, material, &qx, &qy);
        let scale = rx.iter().chain(&ry).fold(0.0f64, |m, v| m.max(v.abs()));
        for k in 0..n {
            assert!((ux[k] - rx[k]).abs() < 1e-12 * scale, "ux[{k}] {} vs {}", ux[k], rx[k]);
            assert!((uy[k] - ry[k]).abs() < 1e-12 * scale, "uy[{k}] {} vs {}", uy[k], ry[k]);
        }
        assert_eq!(operator.transform_pairs(), 2);
    }

    #[test]
    fn refuses_bad_constants() {
        let free = Grid::new(8, 1.0, Boundary::Free).unwrap();
        let bad = ShearMaterial {
            shear_modulus: 1.0,
            poisson_ratio: 0.6,
        };
        assert!(TangentialOperator::new(free, bad).is_err());
    }

    #[test]
    fn periodic_near_field_is_the_free_one() {
        // A unit traction q_x on one element of a 64² grid, ν = 0.3, Δx ≠ Δy: the periodic
        // response differs from the free grid's by the images' and the mean's share, smooth
        // over the element's neighbourhood (its gradient there is ~(Δ/L)² of the near
        // field's). So the differences of displacement between the element and its
        // neighbours, and the cross displacement u_y, agree to 1e-4 of the largest
        // difference (the alias sums' truncation at |m| ≤ 40 and the images' curvature).
        let material = ShearMaterial {
            shear_modulus: 1.0,
            poisson_ratio: 0.3,
        };
        let n = 64;
        let response = |boundary| {
            let grid = Grid::rectangular(n, n, 1.0, 0.75, boundary).unwrap();
            let mut operator = TangentialOperator::new(grid, material).unwrap();
            let centre = (n / 2) * n + n / 2;
            let (mut qx, qy) = (vec![0.0; n * n], vec![0.0; n * n]);
            qx[centre] = 1.0;
            let (mut ux, mut uy) = (vec![0.0; n * n], vec![0.0; n * n]);
            operator.apply([&qx, &qy], [&mut ux, &mut uy]);
            (ux, uy, centre, operator.self_compliance())
        };
        let (free_x, free_y, centre, _) = response(Boundary::Free);
        let (periodic_x, periodic_y, _, diagonal) = response(Boundary::Periodic);
        assert_eq!(diagonal, periodic_x[centre]);
        let scale = free_x[centre] - free_x[centre + 1];
        for offset in [1, n, n + 1, 2, 2 * n + 3] {
            for k in [centre + offset, centre - offset] {
                let free = free_x[centre] - free_x[k];
                let periodic = periodic_x[centre] - periodic_x[k];
                assert!(
                    (free - periodic).abs() < 1e-4 * scale,
                    "u_x at {k}: {periodic} vs {free}"
                );
                let (free, periodic) = (free_y[k] - free_y[centre], periodic_y[k] - periodic_y[centre]);
                assert!(
                    (free - periodic).abs() < 1e-4 * scale,
                    "u_y at {k}: {periodic} vs {free}"
                );
            }
        }
        // A uniform traction moves nothing: K̂(0) = 0.
        let grid = Grid::new(16, 1.0, Boundary::Periodic).unwrap();
        let mut operator = TangentialOperator::new(grid, material).unwrap();
        let (uniform, zero) = (vec![1.0; 256], vec![0.0; 256]);
        let (mut ux, mut uy) = (vec![0.0; 256], vec![0.0; 256]);
        operator.apply([&uniform, &zero], [&mut ux, &mut uy]);
        assert!(ux.iter().chain(&uy).all(|u| u.abs() < 1e-12), "{:?}", &ux[..4]);
    }
}
