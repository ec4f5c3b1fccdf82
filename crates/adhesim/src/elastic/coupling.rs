//! The normal–tangential coupling of a half-space at ν < 1/2 (`friction.coupling = "full"`).
//!
//! A tangential point force Q_x at the origin moves the surface normally, and a normal
//! point force P tangentially (Johnson, *Contact Mechanics*, 1985, §3.2, with z and u_z
//! into the body, p > 0 compressive):
//!
//! u_z = +c·Q_x·x/r²,   u_x = −c·P·x/r²,   c = (1 − 2ν)/(4πG)
//!
//! (Boussinesq's surface is drawn in towards the load; Betti's reciprocity then fixes the
//! sign of Cerruti's normal term.) So K_xz = −K_zx, K_zx being odd in x, and the coupled
//! 3×3 operator is symmetric. Integrated over a Δx × Δy element with the primitive
//! ∫∫ s/r² = [½ t ln r² + s·atan(t/s)] over its four corners (docs/physics.md §8.1).

mod transform;

use super::cerruti::ShearMaterial;
use super::layer_coupling::{layer_coupling_coefficients, layer_coupling_compliance};
use super::tangential::{check_material, padded_offset, ShearBody, TangentialOperatorError};
use super::tangential_periodic::alias_tables;
use super::ElasticLayer;
use crate::grid::{Boundary, Grid};
use num_complex::Complex;
use rayon::prelude::*;
use transform::Transform2d;

/// ½ t ln(s² + t²) + s·atan(t/s): ∂_s∂_t of it is s/(s² + t²); 0 where s = t = 0.
fn odd_primitive(s: f64, t: f64) -> f64 {
    let squared = s * s + t * t;
    let logarithm = if t == 0.0 { 0.0 } else { 0.5 * t * squared.ln() };
    let angle = if s == 0.0 { 0.0 } else { s * (t / s).atan() };
    logarithm + angle
}

/// (K_zx, K_zy) of a Δx × Δy element at offset (ξ, η) from its centre: the normal surface
/// displacement (into the body) per unit uniform shear traction q_x, q_y on the element.
/// The tangential displacement per unit pressure is their negative.
pub fn coupling_rectangle(xi: f64, eta: f64, element_x: f64, element_y: f64, material: ShearMaterial) -> (f64, f64) {
    let (a, b) = (0.5 * element_x, 0.5 * element_y);
    let scale = (1.0 - 2.0 * material.poisson_ratio) / (4.0 * std::f64::consts::PI * material.shear_modulus);
    let corners = |xi: f64, eta: f64, a: f64, b: f64| {
        odd_primitive(xi + a, eta + b) - odd_primitive(xi + a, eta - b) - odd_primitive(xi - a, eta + b)
            + odd_primitive(xi - a, eta - b)
    };
    // K_zy is K_zx with the axes exchanged.
    (scale * corners(xi, eta, a, b), scale * corners(eta, xi, b, a))
}

/// The coupling operator: u_z = K_zx∗q_x + K_zy∗q_y (the normal displacement of shear
/// tractions) and (u_x, u_y) = −(K_zx∗p, K_zy∗p) (the tangential displacement of a
/// pressure). On a free grid by DC-FFT with [`coupling_rectangle`]'s exact element
/// coefficients; on a periodic grid as the Fourier multiplier
/// K̂_zx(Q) = −i(1 − 2ν)Q_x/(2GQ²) summed over the element's aliases with its form factor,
/// as the periodic tangential operator's, with K̂(0) = 0. [`for_body`](Self::for_body)
/// builds a bonded layer's instead (`layer_coupling`), which couples at ν = 1/2 too.
pub struct CouplingOperator {
    grid: Grid,
    transform: Transform2d,
    /// K̂_zx and K̂_zy, normalised, laid out as the transform's spectra.
    spectra: [Vec<Complex<f64>>; 2],
    /// Two spectra of work space.
    work: [Vec<Complex<f64>>; 2],
    transforms: u64,
}

impl CouplingOperator {
    /// Plans the transforms and computes the two kernel spectra.
    pub fn new(grid: Grid, material: ShearMaterial) -> Result<Self, TangentialOperatorError> {
        check_material(material)?;
        Ok(Self::build(grid, material.into()))
    }

    /// The coupling of `body`: the half-space's, or a bonded layer's (checked as
    /// [`super::TangentialOperator::on_layer`] checks it), which does not vanish at ν = 1/2.
    pub fn for_body(grid: Grid, body: ShearBody) -> Result<Self, TangentialOperatorError> {
        // The tangential operator's checks of the layer, without its spectra.
        if let Some(layer) = body.layer {
            super::tangential::check_layer(&grid, body.material, &layer)?;
        } else {
            check_material(body.material)?;
        }
        Ok(Self::build(grid, body))
    }

    fn build(grid: Grid, body: ShearBody) -> Self {
        let ShearBody { material, layer } = body;
        let (nx, ny) = (grid.nx(), grid.ny());
        let padded = match grid.boundary() {
            Boundary::Free => (2 * nx, 2 * ny),
            Boundary::Periodic => (nx, ny),
        };
        let transform = Transform2d::new((nx, ny), padded);
        let spectra = match grid.boundary() {
            Boundary::Free => free_spectra(&grid, material, layer.as_ref()),
            Boundary::Periodic => periodic_spectra(&grid, material, layer.as_ref()),
        };
        let len = transform.spectrum_len();
        Self {
            grid,
            transform,
            spectra,
            work: [vec![Complex::default(); len], vec![Complex::default(); len]],
            transforms: 0,
        }
    }

    /// The grid the operator acts on.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// Writes u_z = K_zx∗q_x + K_zy∗q_y: the normal displacement (into the body) of the
    /// shear tractions (q_x, q_y) on the body.
    pub fn normal_from_shear(&mut self, traction: [&[f64]; 2], normal: &mut [f64]) {
        let [first, second] = &mut self.work;
        self.transform.forward(traction[0], first);
        self.transform.forward(traction[1], second);
        let [zx, zy] = &self.spectra;
        first
            .par_iter_mut()
            .zip(second.par_iter())
            .zip(zx.par_iter().zip(zy.par_iter()))
            .for_each(|((u, &q_y), (&k_x, &k_y))| *u = *u * k_x + q_y * k_y);
        self.transform.inverse(first, normal);
        self.transforms += 2;
    }

    /// Writes (u_x, u_y) = −(K_zx∗p, K_zy∗p): the tangential displacement of the pressure p.
    pub fn shear_from_normal(&mut self, pressure: &[f64], displacement: [&mut [f64]; 2]) {
        let [first, second] = &mut self.work;
        self.transform.forward(pressure, first);
        let [zx, zy] = &self.spectra;
        second
            .par_iter_mut()
            .zip(first.par_iter_mut())
            .zip(zx.par_iter().zip(zy.par_iter()))
            .for_each(|((y, x), (&k_x, &k_y))| {
                *y = -*x * k_y;
                *x = -*x * k_x;
            });
        let [ux, uy] = displacement;
        self.transform.inverse(first, ux);
        self.transform.inverse(second, uy);
        self.transforms += 2;
    }

    /// Forward + inverse transform pairs done so far (two per application).
    pub fn transform_pairs(&self) -> u64 {
        self.transforms
    }
}

/// The spectra of the free grid's element coefficients on the 2N-periodic padded grid
/// (the offset N, which no pair of data elements has, set to zero); on a layer its
/// coefficients (`layer_coupling`), K_zx odd in x and K_zy odd in y.
fn free_spectra(grid: &Grid, material: ShearMaterial, layer: Option<&ElasticLayer>) -> [Vec<Complex<f64>>; 2] {
    let (nx, ny) = (grid.nx(), grid.ny());
    let (dx, dy) = (grid.dx(), grid.dy());
    let (px, py) = (2 * nx, 2 * ny);
    let wrap = padded_offset;
    let layer_table = layer.map(|layer| layer_coupling_coefficients(grid, material, layer));
    let coefficient = |xi: f64, eta: f64| match &layer_table {
        None => coupling_rectangle(xi * dx, eta * dy, dx, dy, material),
        Some(table) => {
            let (zx, zy) = table[eta.abs() as usize * nx + xi.abs() as usize];
            (xi.signum() * zx, eta.signum() * zy)
        }
    };
    let mut kernels = [vec![0.0; px * py], vec![0.0; px * py]];
    for row in 0..py {
        for column in 0..px {
            if let (Some(eta), Some(xi)) = (wrap(row, ny), wrap(column, nx)) {
                let (zx, zy) = coefficient(xi, eta);
                kernels[0][row * px + column] = zx;
                kernels[1][row * px + column] = zy;
            }
        }
    }
    let mut transform = Transform2d::new((px, py), (px, py));
    let normalisation = 1.0 / (px * py) as f64;
    kernels.map(|kernel| {
        let mut spectrum = vec![Complex::default(); transform.spectrum_len()];
        transform.forward(&kernel, &mut spectrum);
        spectrum.iter_mut().for_each(|value| *value *= normalisation);
        spectrum
    })
}

/// K̂_zx and K̂_zy of a periodic grid (see [`CouplingOperator`]), normalised by 1/(NxNy).
/// Each is odd in its own wavenumber, so zero on its Nyquist line of an even grid, where
/// the wave and its alias coincide. On a layer each alias carries 2h(Qt)/(1 − 2ν) of the
/// half-space's term, written as h(Qt)/G over the scale 1/G.
fn periodic_spectra(grid: &Grid, material: ShearMaterial, layer: Option<&ElasticLayer>) -> [Vec<Complex<f64>>; 2] {
    let (nx, ny) = (grid.nx(), grid.ny());
    let (g, nu) = (material.shear_modulus, material.poisson_ratio);
    let columns = nx / 2 + 1;
    let (x_tables, y_tables) = alias_tables(grid);
    let scale = match layer {
        None => (1.0 - 2.0 * nu) / (2.0 * g * nx as f64 * ny as f64),
        Some(_) => 1.0 / (g * nx as f64 * ny as f64),
    };
    let entry = |column: usize, row: usize| -> [Complex<f64>; 2] {
        if row == 0 && column == 0 {
            return [Complex::default(); 2];
        }
        let mut sums = [0.0; 2];
        for &(qx, sx) in &x_tables[column] {
            for &(qy, sy) in &y_tables[row] {
                let squared = qx * qx + qy * qy;
                let weight = match layer {
                    None => sx * sy / squared,
                    Some(layer) => {
                        sx * sy / squared * layer_coupling_compliance(squared.sqrt() * layer.thickness(), nu)
                    }
                };
                sums[0] += weight * qx;
                sums[1] += weight * qy;
            }
        }
        if nx % 2 == 0 && column == nx / 2 {
            sums[0] = 0.0;
        }
        if ny % 2 == 0 && row == ny / 2 {
            sums[1] = 0.0;
        }
        sums.map(|sum| Complex::new(0.0, -scale * sum))
    };
    let values: Vec<[Complex<f64>; 2]> = (0..columns * ny)
        .into_par_iter()
        .map(|k| entry(k / ny, k % ny))
        .collect();
    [0, 1].map(|component| values.iter().map(|value| value[component]).collect())
}

#[cfg(test)]
mod tests;
