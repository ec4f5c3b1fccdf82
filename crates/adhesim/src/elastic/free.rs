use super::influence::{love_coefficient, love_primitive};
use super::spectral::SpectralConvolution;
use super::ElasticOperator;
use crate::grid::Grid;
use crate::material::ElasticMaterial;
use rayon::prelude::*;

/// K(±lΔ, ±mΔ) for 0 ≤ m, l < N, bit for bit what [`love_coefficient`] gives at each
/// signed offset, with the four primitives Φ(lΔ ± s, mΔ ± s) evaluated once per pair
/// m ≤ l. Φ is odd in each argument and symmetric under exchange, bitwise
/// ([`love_primitive`]), so each of the eight images of an offset is the same four values
/// with signs, summed in the order `love_coefficient` sums them.
/// Returns `[sign_m][sign_l][m * n + l]` with sign index 0 for + and 1 for −.
fn love_images(n: usize, delta: f64, modulus: f64) -> [[Vec<f64>; 2]; 2] {
    let mut images: [[Vec<f64>; 2]; 2] = Default::default();
    for row in images.iter_mut() {
        for table in row.iter_mut() {
            *table = vec![0.0; n * n];
        }
    }
    let s = 0.5 * delta;
    let scale = std::f64::consts::PI * modulus;
    // Per pair m ≤ l: (primitives [x+s or x−s][y+s or y−s] at x = lΔ, y = mΔ).
    let primitives: Vec<[[f64; 2]; 2]> = (0..n * n)
        .into_par_iter()
        .map(|k| {
            let (m, l) = (k / n, k % n);
            if l < m {
                return [[0.0; 2]; 2];
            }
            let (x, y) = (l as f64 * delta, m as f64 * delta);
            [
                [love_primitive(x + s, y + s), love_primitive(x + s, y - s)],
                [love_primitive(x - s, y + s), love_primitive(x - s, y - s)],
            ]
        })
        .collect();
    // Φ(σ_x·x ± s, σ_y·y ± s) from the stored values: for σ = −1, ±s turns into ∓s and
    // the sign comes out.
    let corner = |p: &[[f64; 2]; 2], sign_x: usize, dx: usize, sign_y: usize, dy: usize| {
        let value = p[dx ^ sign_x][dy ^ sign_y];
        if sign_x ^ sign_y == 1 {
            -value
        } else {
            value
        }
    };
    for m in 0..n {
        for l in 0..n {
            let swapped = l < m;
            let p = if swapped {
                &primitives[l * n + m]
            } else {
                &primitives[m * n + l]
            };
            for (sign_m, row) in images.iter_mut().enumerate() {
                for (sign_l, table) in row.iter_mut().enumerate() {
                    // Exchange maps Φ(x±s, y∓s) to the stored Φ(y∓s, x±s).
                    let term = |dx: usize, dy: usize| {
                        if swapped {
                            corner(p, sign_m, dy, sign_l, dx)
                        } else {
                            corner(p, sign_l, dx, sign_m, dy)
                        }
                    };
                    table[m * n + l] = (term(0, 0) - term(0, 1) - term(1, 0) + term(1, 1)) / scale;
                }
            }
        }
    }
    images
}

/// Non-periodic half-space by discrete convolution and FFT (DC-FFT).
///
/// Liu, Wang & Liu (2000), "A versatile method of discrete convolution and FFT (DC-FFT)
/// for contact analyses", *Wear* 243, 101–111, doi:10.1016/S0043-1648(00)00427-0.
/// Love's exact coefficients K(mΔ, nΔ), |m|,|n| < N, are wrapped into a 2N×2N array and
/// the pressure is zero-padded, so the cyclic convolution equals the exact linear one.
pub struct FreeOperator {
    grid: Grid,
    contact_modulus: f64,
    self_compliance: f64,
    engine: SpectralConvolution,
    /// The same kernel in single precision, for [`ElasticOperator::apply_single`].
    single: SpectralConvolution<f32>,
    applications: u64,
}

impl FreeOperator {
    /// Plans the transforms and computes the kernel spectrum for `grid` and `material`.
    pub fn new(grid: Grid, material: ElasticMaterial) -> Self {
        let n = grid.n();
        let padded = 2 * n;
        let delta = grid.element_size();
        let modulus = material.contact_modulus();
        // (|offset| in elements, sign index) for a wrapped index; row n of the padded array
        // is zero.
        let wrap = |i: usize| -> Option<(usize, usize)> {
            match i {
                i if i < n => Some((i, 0)),
                i if i == n => None,
                i => Some((padded - i, 1)),
            }
        };
        let images = love_images(n, delta, modulus);
        let engine = SpectralConvolution::new(n, padded, |i, j| match (wrap(i), wrap(j)) {
            (Some((m, sign_m)), Some((l, sign_l))) => images[sign_m][sign_l][m * n + l],
            _ => 0.0,
        });
        Self {
            grid,
            contact_modulus: modulus,
            self_compliance: love_coefficient(0.0, 0.0, delta, modulus),
            single: engine.to_single(),
            engine,
            applications: 0,
        }
    }
}

impl ElasticOperator for FreeOperator {
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
    fn self_compliance(&self) -> f64 {
        self.self_compliance
    }
    fn applications(&self) -> u64 {
        self.applications
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn octant_images_have_the_bits_of_direct_evaluation() {
        // Every signed offset of the padded kernel, against a direct evaluation.
        let (n, delta, modulus) = (12, 0.013, 2.5);
        let images = love_images(n, delta, modulus);
        for m in -(n as i64 - 1)..n as i64 {
            for l in -(n as i64 - 1)..n as i64 {
                let direct = love_coefficient(l as f64 * delta, m as f64 * delta, delta, modulus);
                let (sign_m, sign_l) = (usize::from(m < 0), usize::from(l < 0));
                let tabulated = images[sign_m][sign_l][m.unsigned_abs() as usize * n + l.unsigned_abs() as usize];
                assert_eq!(tabulated.to_bits(), direct.to_bits(), "offset ({l}, {m})");
            }
        }
    }
}
