//! The tangential half-space operator: shear tractions → tangential surface displacements.

use super::cerruti::{cerruti_rectangle, CerrutiCoefficients, ShearMaterial};
use super::spectral::SpectralConvolution;
use super::tangential_periodic::periodic_spectra;
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
pub struct TangentialOperator {
    grid: Grid,
    material: ShearMaterial,
    xx: SpectralConvolution,
    yy: SpectralConvolution,
    /// The spectrum of K_xy; None at ν = 0, where the cross coefficient vanishes.
    xy: Option<Vec<f64>>,
    self_compliance: f64,
    transforms: u64,
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
        let nu = material.poisson_ratio;
        if grid.boundary() == Boundary::Periodic {
            let (xx, yy, xy) = periodic_spectra(&grid, material);
            let mut operator = Self {
                grid,
                material,
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
        let engine = |component: fn(CerrutiCoefficients) -> f64| {
            SpectralConvolution::new((nx, ny), (2 * nx, 2 * ny), |i, row: &mut [f64]| {
                let eta = wrap(i, ny);
                for (j, entry) in row.iter_mut().enumerate() {
                    *entry = match (eta, wrap(j, nx)) {
                        (Some(eta), Some(xi)) => component(cerruti_rectangle(xi * dx, eta * dy, dx, dy, material)),
                        _ => 0.0,
                    };
                }
            })
        };
        let xx = engine(|c| c.xx);
        let yy = engine(|c| c.yy);
        let xy = (nu != 0.0).then(|| engine(|c| c.xy).into_kernel());
        Ok(Self {
            grid,
            material,
            xx,
            yy,
            xy,
            self_compliance: cerruti_rectangle(0.0, 0.0, dx, dy, material).xx,
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
