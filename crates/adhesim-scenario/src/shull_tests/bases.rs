//! ν = 0.3 (and, without adhesion, 0) on a bonded base and ν = 1/2 and 0.3 on a
//! frictionless one against the axisymmetric reference (docs/validation.md §18.2): the same
//! checks as Shull's bonded incompressible layer, with the same tolerances. The pull-off at
//! ν = 0 and the bonded layer of ν = −0.3 are in shull_tests/signs.rs.
//!
//! On a frictionless base the layer factor does not depend on ν (shull_tests/factor.rs), so
//! at a fixed E* the operator, the reference and every run are the same for every ν: a
//! sphere on the frictionless layer at ν = 0.3 and 1/2 must agree bit for bit, and the
//! comparisons are run at ν = 1/2.

use super::{
    assert_the_error_falls_with_the_spacing, assert_the_pull_off_carries_the_half_space_error, operator, press,
    sphere_and_punch_against_the_reference, LayerKind, KINDS, PULL_OFF_THICKNESSES, SPACING, THICKNESSES,
};
use adhesim::LayerBase;

#[test]
fn a_sphere_and_a_punch_on_compressible_and_frictionless_layers_are_the_axisymmetric_solution() {
    for kind in &KINDS[1..3] {
        sphere_and_punch_against_the_reference(*kind, &THICKNESSES.map(Some));
    }
    // ν = 0 on a bonded base, the most compressible layer of non-negative ν: the same checks.
    sphere_and_punch_against_the_reference(KINDS[4], &THICKNESSES.map(Some));
    // ν = 0.3 on a frictionless base: the operator is ν = 1/2's, bit for bit (64², a = 16Δ).
    let sphere = adhesim::Sphere::new(1.0).unwrap();
    let frictionless = |poisson_ratio| LayerKind {
        poisson_ratio,
        base: LayerBase::Frictionless,
    };
    let depth = (16.0 * SPACING).powi(2);
    let [compressible, incompressible] =
        [0.3, 0.5].map(|nu| press(&mut operator(64, Some(0.25), frictionless(nu)), &sphere, depth));
    assert_eq!(compressible, incompressible);
}

/// The thinnest of the layers (a/h ≈ 2, where the layer departs most from the half-space)
/// in the default run; the three in `…_at_every_thickness`.
#[test]
fn a_jkr_sphere_on_a_compressible_bonded_layer_pulls_off_at_the_axisymmetric_force() {
    assert_the_pull_off_carries_the_half_space_error(KINDS[1], &PULL_OFF_THICKNESSES[2..]);
}

#[test]
fn a_jkr_sphere_on_a_layer_on_a_frictionless_base_pulls_off_at_the_axisymmetric_force() {
    assert_the_pull_off_carries_the_half_space_error(KINDS[2], &PULL_OFF_THICKNESSES[2..]);
}

#[test]
#[ignore = "about 20 s: cargo test --release -p adhesim-scenario shull_tests -- --ignored"]
fn jkr_spheres_on_compressible_and_frictionless_layers_pull_off_at_the_axisymmetric_force_at_every_thickness() {
    for kind in &KINDS[1..3] {
        assert_the_pull_off_carries_the_half_space_error(*kind, &PULL_OFF_THICKNESSES);
    }
}

/// ν = 0.3 bonded and ν = 1/2 frictionless at twice the resolution, as Shull's layer. About
/// 140 s on 2 cores:
/// `cargo test --release -p adhesim-scenario shull_tests -- --ignored --nocapture`.
#[test]
#[ignore]
fn jkr_spheres_on_compressible_and_frictionless_layers_pull_off_at_the_axisymmetric_force_at_twice_the_resolution() {
    let cases = PULL_OFF_THICKNESSES.map(Some);
    for kind in &KINDS[1..3] {
        assert_the_error_falls_with_the_spacing(*kind, &cases);
    }
}
