//! An elastic layer bonded to a rigid base under shear tractions on its free surface:
//! shear tractions → tangential surface displacements, the layer's counterpart of
//! Cerruti's half-space (docs/physics.md, "The layer under shear").
//!
//! A traction wave of wavenumber k splits into a longitudinal part (along k), which
//! shears and stretches the layer in the plane of k and the normal, and a transverse part
//! (across k), an antiplane shear. Over the half-space's compliances (1 − ν)/(Gk) and
//! 1/(Gk) they carry the factors [`layer_longitudinal_factor`] and
//! [`layer_transverse_factor`]. As on the half-space, Goodman's approximation leaves out
//! the normal displacement of a shear traction; on a layer it does not vanish at ν = 1/2
//! ([`layer_coupling_ratio`] says how large it is).
//!
//! A frictionless base cannot hold a tangential load (the layer would slide on it), so only
//! a bonded base is taken.

use super::bessel::Bessel;
use super::cerruti::{cerruti_rectangle, CerrutiCoefficients, ShearMaterial};
use super::layer::{bonded_denominator, element_integrals, sinh_minus_argument, PointCorrection, SCREENED_KT};
use super::layer_tables::TableKey;
use super::{ElasticLayer, LayerBase};
use crate::grid::Grid;
use std::f64::consts::PI;

/// The longitudinal tangential compliance of a layer of thickness t bonded to a rigid
/// base over the half-space's (1 − ν)/(Gk), at s = kt (κ = 3 − 4ν):
///
/// f_L = (κ sinh 2s + 2s) / (κ cosh 2s + 2s² + (1 + κ²)/2)
///
/// the normal factor's ([`super::layer_compliance_factor`]) numerator with the sign of 2s
/// turned; derived from Navier's equations as that one (docs/physics.md). Limits: f_L → 1
/// for s → ∞; f_L → 4s/(1 + κ) for s → 0, i.e. the simple shear of the layer, C = t/G.
/// Finite for every ν in (−1, 1/2]; `kt` ≥ 0, f_L(0) = 0.
///
/// # Example
/// ```
/// use adhesim::elastic::layer_longitudinal_factor;
///
/// // Long waves shear a thin layer as a whole: C = (1 − ν)/(Gk)·f_L = t/G.
/// let (kt, nu) = (1e-4, 0.3);
/// let compliance_times_g_over_t = (1.0 - nu) * layer_longitudinal_factor(kt, nu) / kt;
/// assert!((compliance_times_g_over_t - 1.0).abs() < 1e-7);
/// assert_eq!(layer_longitudinal_factor(30.0, nu), 1.0);
/// ```
pub fn layer_longitudinal_factor(kt: f64, poisson_ratio: f64) -> f64 {
    if kt >= SCREENED_KT {
        return 1.0;
    }
    if kt <= 0.0 {
        return 0.0;
    }
    let kappa = 3.0 - 4.0 * poisson_ratio;
    let double = 2.0 * kt;
    (kappa * double.sinh() + double) / bonded_denominator(kt, kappa)
}

/// The transverse (antiplane) tangential compliance of a layer of thickness t bonded to a
/// rigid base over the half-space's 1/(Gk): tanh(kt). The antiplane displacement obeys
/// u'' = k²u across the layer with G u' = −q at the surface and u = 0 at the base, so
/// u(0) = q tanh(kt)/(Gk); → t/G for kt → 0 (simple shear).
pub fn layer_transverse_factor(kt: f64) -> f64 {
    kt.max(0.0).tanh()
}

/// How strongly a layer bonded to a rigid base couples normal and tangential loads at a
/// wavenumber k: |C_nt|/√(C_nn·C_tt), the compliances of the plane (longitudinal) problem
/// at s = kt, with Gk·C_nt = [s² − (1 − 2ν)κ sinh² s]/D (D the denominator of
/// [`layer_longitudinal_factor`]; derived as it and checked by integrating Navier's
/// equations). On a half-space it is the Dundurs-type constant (1 − 2ν)/(2(1 − ν)),
/// zero at ν = 1/2; on a thin incompressible layer it tends to √3/2, so Goodman's
/// approximation, which drops C_nt, is not exact on layers even for rubber. `kt` > 0.
///
/// # Example
/// ```
/// use adhesim::elastic::layer_coupling_ratio;
///
/// // Thick: the half-space's (1 − 2ν)/(2(1 − ν)) (0 for rubber); thin rubber: √3/2.
/// assert!((layer_coupling_ratio(20.0, 0.3) - 0.4 / 1.4).abs() < 1e-12);
/// assert!(layer_coupling_ratio(20.0, 0.5) < 1e-12);
/// assert!((layer_coupling_ratio(1e-3, 0.5) - 0.75f64.sqrt()).abs() < 1e-5);
/// ```
pub fn layer_coupling_ratio(kt: f64, poisson_ratio: f64) -> f64 {
    if kt >= SCREENED_KT {
        return (1.0 - 2.0 * poisson_ratio) / (2.0 * (1.0 - poisson_ratio));
    }
    let kappa = 3.0 - 4.0 * poisson_ratio;
    let double = 2.0 * kt;
    let normal_numerator = (kappa - 1.0) * double.sinh() + sinh_minus_argument(double);
    let tangential_numerator = kappa * double.sinh() + double;
    let coupling_numerator = kt * kt - (1.0 - 2.0 * poisson_ratio) * kappa * kt.sinh().powi(2);
    // C_nn, C_tt and C_nt share Gk/D; C_nn = (1 − ν)f, C_tt = (1 − ν)f_L.
    coupling_numerator.abs() / ((1.0 - poisson_ratio) * (normal_numerator * tangential_numerator).sqrt())
}

/// The Fourier compliance tensor of the bonded layer at wavevector (qx, qy) times G:
/// [xx, yy, xy], the longitudinal and transverse factors on the projections onto and
/// across the wavevector.
pub(super) fn layer_shear_multiplier(qx: f64, qy: f64, thickness: f64, poisson_ratio: f64) -> [f64; 3] {
    let squared = qx * qx + qy * qy;
    let wavenumber = squared.sqrt();
    let kt = wavenumber * thickness;
    let longitudinal = (1.0 - poisson_ratio) * layer_longitudinal_factor(kt, poisson_ratio);
    let transverse = layer_transverse_factor(kt);
    let (along_x, along_y) = (qx * qx / squared, qy * qy / squared);
    [
        (longitudinal * along_x + transverse * along_y) / wavenumber,
        (longitudinal * along_y + transverse * along_x) / wavenumber,
        (longitudinal - transverse) * qx * qy / squared / wavenumber,
    ]
}

/// (c_L, c_T) = ((1 − ν)(f_L − 1), tanh s − 1): the longitudinal and transverse excess of
/// the bonded layer's tangential compliance over Cerruti's at s = kt.
fn shear_excess(s: f64, nu: f64) -> (f64, f64) {
    let longitudinal = (1.0 - nu) * (layer_longitudinal_factor(s, nu) - 1.0);
    let transverse = layer_transverse_factor(s) - 1.0;
    (longitudinal, transverse)
}

/// c0 = (c_L + c_T)/2, the integrand of the isotropic table (J₀).
pub(super) fn isotropic_table_integrand(nu: f64) -> impl Fn(f64) -> f64 {
    move |s| {
        let (l, t) = shear_excess(s, nu);
        0.5 * (l + t)
    }
}

/// c2 = (c_L − c_T)/2, the integrand of the deviatoric table (J₂).
pub(super) fn deviatoric_table_integrand(nu: f64) -> impl Fn(f64) -> f64 {
    move |s| {
        let (l, t) = shear_excess(s, nu);
        0.5 * (l - t)
    }
}

/// The layer's tangential point kernel minus Cerruti's, in the two radial functions of an
/// isotropic 2-D tensor kernel: D_αβ(r) = [δ_αβ d0(ρ) − (2r̂_α r̂_β − δ_αβ) d2(ρ)]/(2πGt),
/// ρ = r/t, with d_n(ρ) = ∫0^∞ c_n(s) J_n(sρ) ds and
/// c0 = [(1 − ν)(f_L − 1) + (tanh s − 1)]/2, c2 = [(1 − ν)(f_L − 1) − (tanh s − 1)]/2:
/// the inverse transform of the tensor's isotropic part (J0) and of its cos 2φ part (J2,
/// with i² = −1). Beyond the table the layer carries nothing and D is minus Cerruti's:
/// d0 = −(2 − ν)/(2ρ), d2 = ν/(2ρ).
pub(super) struct ShearCorrection {
    isotropic: PointCorrection,
    deviatoric: PointCorrection,
}

impl ShearCorrection {
    pub(super) fn new(layer: &ElasticLayer) -> Self {
        let nu = layer.poisson_ratio();
        let poisson_ratio_bits = nu.to_bits();
        let isotropic = PointCorrection::tabulate(
            TableKey::ShearIsotropic { poisson_ratio_bits },
            isotropic_table_integrand(nu),
            Bessel::J0,
            (-(2.0 - nu) / 2.0, 1),
        );
        let deviatoric = PointCorrection::tabulate(
            TableKey::ShearDeviatoric { poisson_ratio_bits },
            deviatoric_table_integrand(nu),
            Bessel::J2,
            (nu / 2.0, 1),
        );
        Self { isotropic, deviatoric }
    }

    /// [D_xx, D_yy, D_xy]·2πGt at (x, y) = (ρ cos θ, ρ sin θ)·t.
    pub(super) fn at(&self, x: f64, y: f64, thickness: f64) -> [f64; 3] {
        let r = x.hypot(y);
        let rho = r / thickness;
        let (d0, d2) = (self.isotropic.value(rho), self.deviatoric.value(rho));
        let (cos2, sin2) = ((x * x - y * y) / (r * r), 2.0 * x * y / (r * r));
        [d0 - cos2 * d2, d0 + cos2 * d2, -sin2 * d2]
    }
}

/// The bonded layer's tangential coefficients at offsets (lΔx, mΔy), 0 ≤ l < Nx,
/// 0 ≤ m < Ny (`[m * Nx + l]`): Cerruti's plus the correction integrated over the element,
/// zero where the whole element lies beyond 60t. K_xx and K_yy are even in l and m, K_xy
/// odd in each.
pub(super) fn layer_shear_coefficients(
    grid: &Grid,
    material: ShearMaterial,
    layer: &ElasticLayer,
) -> Vec<CerrutiCoefficients> {
    debug_assert_eq!(layer.base(), LayerBase::Bonded);
    let (nx, dx, dy) = (grid.nx(), grid.dx(), grid.dy());
    let t = layer.thickness();
    let correction = ShearCorrection::new(layer);
    let scale = 1.0 / (2.0 * PI * material.shear_modulus * t);
    let sums = element_integrals(grid, t, |x, y| correction.at(x, y, t));
    sums.iter()
        .enumerate()
        .map(|(k, sum)| match sum {
            Some([xx, yy, xy]) => {
                let (xi, eta) = ((k % nx) as f64 * dx, (k / nx) as f64 * dy);
                let half_space = cerruti_rectangle(xi, eta, dx, dy, material);
                CerrutiCoefficients {
                    xx: half_space.xx + scale * xx,
                    yy: half_space.yy + scale * yy,
                    xy: half_space.xy + scale * xy,
                }
            }
            None => CerrutiCoefficients {
                xx: 0.0,
                yy: 0.0,
                xy: 0.0,
            },
        })
        .collect()
}

#[cfg(test)]
mod tests;
