//! The smooth sphere with a Maugis–Dugdale cohesive zone against Maugis (1992): R = E* = 1,
//! γ0 = 1e-4, σ0 from the Maugis parameter λ (docs/validation.md §10).
//!
//! The pull-off error is a first-order mesh error of the zone's edge (an element carries
//! σ0 or nothing): measured at λ = 1 +7.6 %, +3.8 %, +1.6 % for 5.4, 10.8, 21.7 elements
//! across the zone at pull-off. The fast tests run grids whose measured error is well
//! inside the tolerances; the slow ones (`#[ignore]`) check λ = 1 and the mesh
//! convergence: `cargo test --release -p adhesim --test integration validation_maugis:: -- --ignored`.

use adhesim::analysis::reference::{cohesive_stress_for, MaugisDugdale};
use adhesim::{
    Boundary, CohesiveParams, CohesiveSolver, Dugdale, ElasticMaterial, FreeOperator, Grid, IndentPulloff,
    NormalSolver, Phase, Problem, Profile, ProtocolSummary, Sphere, StepRecord,
};

const WORK_OF_ADHESION: f64 = 1e-4;

/// Indents to 2e-3 and pulls off in steps of 2e-5 on an N×N free grid of side `size`.
fn run(lambda: f64, n: usize, size: f64, depth_step: f64) -> (ProtocolSummary, Vec<StepRecord>, MaugisDugdale) {
    let sigma = cohesive_stress_for(1.0, 1.0, WORK_OF_ADHESION, lambda);
    let model = MaugisDugdale {
        radius: 1.0,
        contact_modulus: 1.0,
        work_of_adhesion: WORK_OF_ADHESION,
        cohesive_stress: sigma,
    };
    let grid = Grid::new(n, size, Boundary::Free).unwrap();
    let material = ElasticMaterial::new(1.0).unwrap();
    let operator = FreeOperator::new(grid, material);
    let heights = Sphere::new(1.0).unwrap().heights(&grid);
    let law = Dugdale::new(sigma, vec![WORK_OF_ADHESION; grid.len()]);
    let solver = CohesiveSolver::new(grid, material, Box::new(law), CohesiveParams::default());
    let mut solver = NormalSolver::Cohesive(Box::new(solver));
    let protocol = IndentPulloff {
        start_depth: 0.0,
        max_depth: 2e-3,
        depth_step,
        max_retract_steps: 100_000,
        jump_force_threshold: 0.0,
    };
    let mut records = Vec::new();
    let mut problem = Problem::new(Box::new(operator), heights).unwrap();
    let summary = protocol.run(&mut problem, &mut solver, &mut records).unwrap();
    assert!(!summary.touches_border, "the domain holds the contact");
    (summary, records, model)
}

/// Relative error of the largest adhesive force against Maugis.
fn pull_off_error(lambda: f64, n: usize, size: f64) -> f64 {
    let (summary, _, model) = run(lambda, n, size, 2e-5);
    summary.max_adhesive_force / model.max_adhesive_force() - 1.0
}

/// λ = 0.3 within the 3 % on a coarse grid (N = 64, Δ = 7.0e-3, 13.5 elements
/// across the zone at pull-off; measured +1.66 %), λ = 0.1 within its 5 % (N = 64,
/// measured +0.51 %: the zone is wide, 20 elements). Under a second each.
#[test]
fn pull_off_matches_maugis_on_coarse_grids() {
    let error = pull_off_error(0.3, 64, 0.45);
    assert!(error.abs() < 0.03, "λ = 0.3: {:+.2} %", 100.0 * error);
    let error = pull_off_error(0.1, 64, 0.67);
    assert!(error.abs() < 0.05, "λ = 0.1: {:+.2} %", 100.0 * error);
}

/// Largest |F − F_Maugis(d)| along the retraction from the deepest point to Maugis' largest
/// adhesive force, relative to that force (beyond it the branch steepens to its vertical
/// tangent, where a shift of the jump-off depth changes the force without bound).
fn branch_error(records: &[StepRecord], model: &MaugisDugdale) -> f64 {
    let end = model.at_max_adhesive_force().depth;
    records
        .iter()
        .filter(|r| r.phase == Some(Phase::Retract) && r.depth >= end)
        .map(|r| (r.force_normal - model.force_at_depth(r.depth).unwrap()).abs())
        .fold(0.0, f64::max)
        / model.max_adhesive_force()
}

/// The force–approach curve: the retraction follows Maugis' displacement-controlled branch
/// within the 3 % of the pull-off force at λ = 0.3 on the coarse grid (measured
/// 2.25 % at N = 64, 0.83 % at N = 128: the same first-order mesh error as the pull-off).
#[test]
fn retraction_follows_the_maugis_branch() {
    let (_, records, model) = run(0.3, 64, 0.45, 2e-5);
    let error = branch_error(&records, &model);
    assert!(error < 0.03, "λ = 0.3: {:.2} %", 100.0 * error);
}

/// Energy balance: the work of the indenter over the cycle equals the booked dissipation.
/// Along a step the tractions are fixed, so the force moves on one piece from the end
/// of a step to the force before change of the next; the trapezoid rule on those pairs is
/// exact while the contact set of the compressive part does not change either (the
/// nested solve converges to 1e-10): measured 1.1e-6 relative at λ = 0.3, N = 64 with
/// steps of 2e-5; the bound 1e-4 leaves room for other step sizes.
#[test]
fn dissipation_balances_the_work_over_a_cycle() {
    let (summary, records, _) = run(0.3, 64, 0.45, 2e-5);
    let mut work = 0.5 * records[0].report.force_before_change * records[0].depth;
    for pair in records.windows(2) {
        work += 0.5 * (pair[0].force_normal + pair[1].report.force_before_change) * (pair[1].depth - pair[0].depth);
    }
    // ∮F dd (approach up, retraction down) is the energy the cycle lost.
    assert!(summary.dissipated_energy > 0.0);
    let mismatch = (work - summary.dissipated_energy) / summary.dissipated_energy;
    assert!(
        mismatch.abs() < 0.01,
        "work {work:e}, dissipated {:e}",
        summary.dissipated_energy
    );
    assert!(summary.jumps > 0);
}

/// λ = 1 within the 3 % at N = 256 (Δ = 1.2e-3, 22 elements across the zone;
/// measured +1.65 %, about 20 s on 2 cores), and the retraction branch within 3 % of the
/// pull-off force (measured 1.65 %, largest at the pull-off point).
#[test]
#[ignore = "20 s: cargo test --release -p adhesim --test integration validation_maugis:: -- --ignored"]
fn pull_off_matches_maugis_at_lambda_one() {
    let (summary, records, model) = run(1.0, 256, 0.31, 2e-5);
    let error = summary.max_adhesive_force / model.max_adhesive_force() - 1.0;
    assert!(error.abs() < 0.03, "λ = 1: {:+.2} %", 100.0 * error);
    let error = branch_error(&records, &model);
    assert!(error < 0.03, "λ = 1 branch: {:.2} %", 100.0 * error);
}

/// Mesh convergence at λ = 1: halving Δ at least nearly halves the error (first order,
/// measured ratios 2.0 and 2.3), and the error keeps its sign (an element whose centre
/// lies in the zone carries σ0 over its whole area).
#[test]
#[ignore = "25 s: cargo test --release -p adhesim --test integration validation_maugis:: -- --ignored"]
fn pull_off_converges_at_first_order() {
    let errors: Vec<f64> = [64, 128, 256].iter().map(|&n| pull_off_error(1.0, n, 0.31)).collect();
    for pair in errors.windows(2) {
        assert!(pair[1] > 0.0 && pair[1] < 0.6 * pair[0], "{errors:?}");
    }
}
