//! The rough-sphere study's limits (docs/rough-spheres.md): a sphere carrying a random
//! self-affine roughness of vanishing amplitude detaches like the smooth JKR sphere, and its
//! rough-sphere parameter diverges as the roughness vanishes.
//!
//! `cargo test --release -p adhesim --test integration rough_sphere_limit::` (about a second)

use crate::common;

use adhesim::analysis::johnson::rough_sphere_parameter;
use adhesim::surface::{rms_height, rms_slope};
use adhesim::{
    AdhesiveParams, AdhesiveSolver, ElasticMaterial, FreeOperator, IndentPulloff, NormalSolver, Problem, Profile,
    RmsTarget, RoughBase, SelfAffine, Sphere,
};
use common::JkrCase;

/// At a_JKR/Δ = 16 a rough sphere with rms slope 1e-6 (h_rms ≈ 1e-5 |d_JKR|, the study's
/// band λ_s = a_JKR/2.6 … λ_r = 1.5 a_JKR) pulls off at |F_min|/|F_JKR| − 1 within ±50 % of
/// the first-order lattice error 1.4Δ/a_JKR, the tolerance `validation_jkr`'s smooth-sphere
/// test uses at this resolution (docs/physics.md §4: the detachment criterion converges to
/// JKR at first order from above), and within 1 % of the smooth sphere on the same grid
/// (a roughness of 1e-5 |d_JKR| cannot move the contact front by an element).
#[test]
fn vanishing_roughness_detaches_like_the_smooth_jkr_sphere() {
    let resolution = 16.0;
    let case = JkrCase::new(resolution, 2.0);
    let a_jkr = case.jkr.critical_radius();
    let surface = SelfAffine::new(0.8, RmsTarget::Slope(1e-6))
        .with_rolloff_wavelength(1.5 * a_jkr)
        .with_cutoff_wavelength(a_jkr / 2.6)
        .generate(&case.grid, 1)
        .unwrap();
    let h_rms = rms_height(&case.grid, &surface.heights).unwrap();
    let d_jkr = case.jkr.critical_depth().abs();
    assert!(h_rms > 0.0 && h_rms < 1e-4 * d_jkr, "h_rms = {h_rms:e}");
    let parameter = rough_sphere_parameter(
        h_rms,
        rms_slope(&case.grid, &surface.heights).unwrap(),
        case.jkr.work_of_adhesion,
        1.0,
    )
    .unwrap();
    assert!(
        parameter > 1e3,
        "α_r = {parameter} must be huge for a vanishing roughness"
    );

    let rough = surface
        .to_rough_profile(RoughBase::Sphere(Sphere::new(1.0).unwrap()))
        .unwrap()
        .heights(&case.grid);
    let operator = FreeOperator::new(case.grid, ElasticMaterial::new(1.0).unwrap());
    let mut solver = NormalSolver::Adhesive(Box::new(AdhesiveSolver::new(
        case.grid,
        1.0,
        vec![case.jkr.work_of_adhesion; case.grid.len()],
        AdhesiveParams::default(),
    )));
    let protocol = IndentPulloff {
        start_depth: 0.0,
        max_depth: 2.0 * d_jkr,
        depth_step: d_jkr / 40.0,
        max_retract_steps: 100_000,
        jump_force_threshold: 0.0,
    };
    let mut records = Vec::new();
    let mut problem = Problem::new(Box::new(operator), rough.clone()).unwrap();
    let summary = protocol.run(&mut problem, &mut solver, &mut records).unwrap();
    let rough_ratio = summary.max_adhesive_force / case.jkr.critical_force().abs();
    let expected = 1.4 / resolution;
    let error = rough_ratio - 1.0;
    assert!(
        error > 0.5 * expected && error < 1.5 * expected,
        "|F_min|/|F_JKR| − 1 = {error:.4}, expected ≈ {expected:.4}"
    );
    let (smooth, _) = case.run(2.0, 40.0);
    let smooth_ratio = smooth.max_adhesive_force / case.jkr.critical_force().abs();
    assert!(
        (rough_ratio / smooth_ratio - 1.0).abs() < 0.01,
        "rough {rough_ratio:.4} vs smooth {smooth_ratio:.4}"
    );
}
