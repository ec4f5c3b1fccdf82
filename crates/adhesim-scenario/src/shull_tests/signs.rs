//! Bonded layers of ν = 0 and ν = −0.3 against the axisymmetric reference
//! (docs/validation.md §18.2): JKR pull-off at ν = 0 (its non-adhesive sphere and punch are
//! in shull_tests/bases.rs), and at ν = −0.3 the non-adhesive sphere and punch and the JKR
//! pull-off, with the same checks and tolerances as Shull's bonded incompressible layer.
//!
//! At ν < 0 (κ = 3 − 4ν > 3) the bonded factor's denominator κ cosh 2s + 2s² + (1 + κ²)/2
//! stays positive on the real axis, its nearest zero lies further from it than at ν = 1/2
//! (kt = 1.60i at ν = −0.3, 0.74i at 1/2), and 1 − f still decays as e^{−2s}: the library's
//! kernel and the reference take ν = −0.3 as they take ν ≥ 0 (the factor itself:
//! shull_tests/factor.rs).
//!
//! The default run keeps ν = −0.3's sphere and punch (6 s on one core) and its pull-off at
//! a/h ≈ 2, the largest layer effect (5 s); the six pull-offs at 128² and at 256² are
//! ignored tests.

use super::{
    assert_the_error_falls_with_the_spacing, assert_the_pull_off_carries_the_half_space_error,
    sphere_and_punch_against_the_reference, LayerKind, KINDS, PULL_OFF_THICKNESSES, THICKNESSES,
};

/// The bonded layer of ν = 0.
const BONDED_AT_ZERO: LayerKind = KINDS[4];
/// The bonded auxetic layer of ν = −0.3.
const BONDED_AUXETIC: LayerKind = KINDS[5];

#[test]
fn a_sphere_and_a_punch_on_a_bonded_layer_of_negative_poisson_ratio_are_the_axisymmetric_solution() {
    sphere_and_punch_against_the_reference(BONDED_AUXETIC, &THICKNESSES.map(Some));
}

#[test]
fn a_jkr_sphere_on_a_thin_bonded_layer_of_negative_poisson_ratio_pulls_off_at_the_axisymmetric_force() {
    assert_the_pull_off_carries_the_half_space_error(BONDED_AUXETIC, &PULL_OFF_THICKNESSES[2..]);
}

/// ν = 0 and −0.3 bonded at a/h ≈ 0.5, 1, 2, as the bonded layer of ν = 0.3. About 30 s on
/// one core:
/// `cargo test --release -p adhesim-scenario shull_tests -- --ignored --nocapture`.
#[test]
#[ignore]
fn jkr_spheres_on_bonded_layers_of_zero_and_negative_poisson_ratio_pull_off_at_the_axisymmetric_force() {
    for kind in [BONDED_AT_ZERO, BONDED_AUXETIC] {
        assert_the_pull_off_carries_the_half_space_error(kind, &PULL_OFF_THICKNESSES);
    }
}

/// The same at twice the resolution, as Shull's layer. About 170 s on 2 cores beside the
/// test above:
/// `cargo test --release -p adhesim-scenario shull_tests -- --ignored --nocapture`.
#[test]
#[ignore]
fn jkr_spheres_on_bonded_layers_of_zero_and_negative_poisson_ratio_pull_off_at_the_axisymmetric_force_at_twice_the_resolution(
) {
    let cases = PULL_OFF_THICKNESSES.map(Some);
    for kind in [BONDED_AT_ZERO, BONDED_AUXETIC] {
        assert_the_error_falls_with_the_spacing(kind, &cases);
    }
}
