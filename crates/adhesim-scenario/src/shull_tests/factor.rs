//! The layer factor f(kt) that the axisymmetric reference takes from the library
//! (`adhesim::elastic::layer_compliance_factor`), re-derived here for the ν and bases the
//! comparison runs, independently of the library's closed forms and of its RK4 shooting
//! (which does not reach ν = 1/2).
//!
//! A normal pressure wave p cos(kx) on the surface z = 0 of a layer 0 ≤ z ≤ t (z into the
//! layer) is a plane-strain problem, and the 3-D surface response to a pressure of
//! wavevector k is the same function of |k|t (isotropy), which is what the Hankel
//! representation of the reference uses. Papkovich–Neuber with a harmonic φ and a harmonic
//! ψ along z, 2G u = 4(1 − ν)ψ e_z − ∇(zψ + φ), with φ = Φ(z) cos kx, ψ = Ψ(z) cos kx and
//! Φ, Ψ combinations of e^{±kz}, gives (G = k = 1, κ = 3 − 4ν; u_x = U sin x,
//! u_z = W cos x, σ_zz ∝ cos x, σ_xz ∝ sin x)
//!
//!     2U = zΨ + Φ,                2W = κΨ − zΨ′ − Φ′,
//!     σ_zz = 2(1 − ν)Ψ′ − zΨ − Φ,  σ_xz = (1 − κ)Ψ/2 + zΨ′ + Φ′
//!
//! (λ∇·u = 2νΨ′ stays finite at ν = 1/2). The surface carries σ_zz = −p, σ_xz = 0; the
//! base z = t has U = W = 0 (bonded) or W = 0, σ_xz = 0 (frictionless). Four coefficients,
//! four conditions; f = W(0)/(p(1 − ν)), the half-space's 2/(E*k) being (1 − ν)/(Gk).

use super::axisymmetric::solve_linear;
use adhesim::LayerBase;

/// f(s) at s = kt from the Papkovich–Neuber solution above.
pub(super) fn papkovich_neuber_factor(s: f64, poisson_ratio: f64, base: LayerBase) -> f64 {
    let kappa = 3.0 - 4.0 * poisson_ratio;
    // Basis: (Φ, Ψ) = (e, 0) or (0, e) for e = e^{z − s} (e′ = e) and e = e^{−z} (e′ = −e).
    // Each column is (U, W, σ_zz, σ_xz) at depth z.
    let column = |index: usize, z: f64| -> [f64; 4] {
        let (e, de) = if index.is_multiple_of(2) {
            ((z - s).exp(), (z - s).exp())
        } else {
            ((-z).exp(), -(-z).exp())
        };
        let ((phi, dphi), (psi, dpsi)) = if index < 2 {
            ((e, de), (0.0, 0.0))
        } else {
            ((0.0, 0.0), (e, de))
        };
        [
            0.5 * (z * psi + phi),
            0.5 * (kappa * psi - z * dpsi - dphi),
            2.0 * (1.0 - poisson_ratio) * dpsi - z * psi - phi,
            0.5 * (1.0 - kappa) * psi + z * dpsi + dphi,
        ]
    };
    let surface: Vec<[f64; 4]> = (0..4).map(|i| column(i, 0.0)).collect();
    let bottom: Vec<[f64; 4]> = (0..4).map(|i| column(i, s)).collect();
    let (first, second) = match base {
        LayerBase::Bonded => (0, 1),
        LayerBase::Frictionless => (1, 3),
    };
    let matrix: Vec<Vec<f64>> = [(&surface, 2), (&surface, 3), (&bottom, first), (&bottom, second)]
        .iter()
        .map(|&(at, row)| at.iter().map(|c| c[row]).collect())
        .collect();
    let coefficients = solve_linear(&matrix, &[-1.0, 0.0, 0.0, 0.0]);
    let surface_w: f64 = surface.iter().zip(&coefficients).map(|(c, a)| c[1] * a).sum();
    surface_w / (1.0 - poisson_ratio)
}

/// The factor the reference integrates is the elastic layer's for every ν and base it is
/// run with (ν = 1/2 and 0.3, bonded and frictionless; ν = 0 and −0.3 as a margin): the
/// library's closed form against the Papkovich–Neuber solve at kt = 0.05–8, to 1e-10 (the
/// solve's round-off: its coefficients span e^{−kt} to 1, and κ cosh 2s cancels against the
/// numerator's κ sinh 2s to 1 − f ≈ e^{−2s}; measured 2e-13 or less). Both tend to 1 as
/// kt → ∞ (the half-space), and the frictionless factor does not depend on ν.
#[test]
fn the_reference_layer_factor_is_the_papkovich_neuber_solution_for_both_bases() {
    let mut worst: f64 = 0.0;
    for poisson_ratio in [0.5, 0.3, 0.0, -0.3] {
        for base in [LayerBase::Bonded, LayerBase::Frictionless] {
            for kt in [0.05, 0.2, 0.5, 1.0, 2.0, 4.0, 8.0] {
                let library = adhesim::elastic::layer_compliance_factor(kt, poisson_ratio, base);
                let derived = papkovich_neuber_factor(kt, poisson_ratio, base);
                worst = worst.max((library / derived - 1.0).abs());
                assert!(
                    (library / derived - 1.0).abs() < 1e-10,
                    "ν = {poisson_ratio}, {base:?}, kt = {kt}: {library} vs {derived}"
                );
            }
            let far = papkovich_neuber_factor(20.0, poisson_ratio, base);
            assert!(
                (far - 1.0).abs() < 1e-14,
                "ν = {poisson_ratio}, {base:?}: f(20) = {far}"
            );
        }
        let frictionless = papkovich_neuber_factor(1.0, poisson_ratio, LayerBase::Frictionless);
        let incompressible = papkovich_neuber_factor(1.0, 0.5, LayerBase::Frictionless);
        assert!((frictionless / incompressible - 1.0).abs() < 1e-12);
    }
    println!("layer factor against Papkovich–Neuber: largest relative difference {worst:.1e}");
}
