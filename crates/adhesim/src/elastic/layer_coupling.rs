//! The normal–tangential coupling of an elastic layer bonded to a rigid base
//! (`friction.coupling = "full"` on a layer; docs/physics.md §9.5). Unlike the
//! half-space's, it does not vanish at ν = 1/2: a thin incompressible layer sheared by τ
//! carries a flux t²τ/(2G) sideways and its surface rises by (t²/(2G))∇·τ.
//!
//! In the convention of [`super::CouplingOperator`] (u_z into the body),
//! K̂_zx(k) = −i (k_x/k)·h(kt)/(Gk) with [`layer_coupling_compliance`] h, which is the
//! half-space's (1 − 2ν)/2 for kt → ∞. In real space the layer's excess over the
//! half-space's x(1 − 2ν)/(4πGr²) is (x/r)·d₁(r/t)/(2πGt), d₁(ρ) = ∫₀^∞ c₁(s) J₁(sρ) ds,
//! c₁ = h − (1 − 2ν)/2 (the n = 1 term of the plane wave, times −i·i = 1).

use super::bessel::Bessel;
use super::cerruti::ShearMaterial;
use super::coupling::coupling_rectangle;
use super::layer::{bonded_denominator, element_integrals, PointCorrection, SCREENED_KT};
use super::layer_tables::TableKey;
use super::ElasticLayer;
use crate::grid::Grid;
use std::f64::consts::PI;

/// h(s) = −[s² − (1 − 2ν)κ sinh² s] / (κ cosh 2s + 2s² + (1 + κ²)/2), s = kt, κ = 3 − 4ν:
/// the bonded layer's coupling over 1/(Gk) in the operators' sign convention (the plane
/// layer problem of docs/physics.md §9.1 under a shear wave; checked against Navier's
/// equations in the tests). → (1 − 2ν)/2 for s → ∞ (the half-space's); at ν = 1/2 it is
/// −s²/(cosh 2s + 2s² + 1) < 0: the layer bulges away from a pressure where a compressible
/// half-space is drawn towards it.
pub(super) fn layer_coupling_compliance(kt: f64, poisson_ratio: f64) -> f64 {
    let half_space = 0.5 * (1.0 - 2.0 * poisson_ratio);
    if kt >= SCREENED_KT {
        return half_space;
    }
    if kt <= 0.0 {
        return 0.0;
    }
    let kappa = 3.0 - 4.0 * poisson_ratio;
    -(kt * kt - (1.0 - 2.0 * poisson_ratio) * kappa * kt.sinh().powi(2)) / bonded_denominator(kt, kappa)
}

/// s·(h(s) − (1 − 2ν)/2), the integrand of the coupling's table (J₁(x)/x).
pub(super) fn coupling_table_integrand(nu: f64) -> impl Fn(f64) -> f64 {
    let half_space = 0.5 * (1.0 - 2.0 * nu);
    move |s| s * (layer_coupling_compliance(s, nu) - half_space)
}

/// (K_zx, K_zy) of the bonded layer at offsets (lΔx, mΔy), 0 ≤ l < Nx, 0 ≤ m < Ny
/// (`[m * Nx + l]`): the half-space's [`coupling_rectangle`] plus the layer's excess
/// integrated over the element, zero where the whole element lies beyond 60t. K_zx is odd
/// in l and even in m, K_zy the other way round. The excess is tabulated as
/// e(ρ) = d₁(ρ)/ρ = ∫ c₁(s)·s·[J₁(sρ)/(sρ)] ds (even and smooth at ρ = 0), so that the
/// point excess is (x, y)·e(r/t)/(2πGt²), and −(1 − 2ν)/(2ρ²) beyond the table.
pub(super) fn layer_coupling_coefficients(
    grid: &Grid,
    material: ShearMaterial,
    layer: &ElasticLayer,
) -> Vec<(f64, f64)> {
    let (nx, dx, dy) = (grid.nx(), grid.dx(), grid.dy());
    let t = layer.thickness();
    let nu = material.poisson_ratio;
    let half_space = 0.5 * (1.0 - 2.0 * nu);
    let excess = PointCorrection::tabulate(
        TableKey::Coupling {
            poisson_ratio_bits: nu.to_bits(),
        },
        coupling_table_integrand(nu),
        Bessel::J1OverX,
        (-half_space, 2),
    );
    let scale = 1.0 / (2.0 * PI * material.shear_modulus * t * t);
    let sums = element_integrals(grid, t, |x, y| {
        let e = excess.value(x.hypot(y) / t);
        [x * e, y * e]
    });
    sums.iter()
        .enumerate()
        .map(|(k, sum)| match sum {
            Some([zx, zy]) => {
                let (xi, eta) = ((k % nx) as f64 * dx, (k / nx) as f64 * dy);
                let (half_zx, half_zy) = coupling_rectangle(xi, eta, dx, dy, material);
                (half_zx + scale * zx, half_zy + scale * zy)
            }
            None => (0.0, 0.0),
        })
        .collect()
}

#[cfg(test)]
mod tests;
