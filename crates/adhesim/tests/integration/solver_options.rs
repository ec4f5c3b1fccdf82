//! Speed-ups of the adhesive step must not change results: carried bans during
//! retraction, the preconditioner and the looser relative CG tolerance (1e-6 instead of
//! 1e-9; the front criterion decides) give the same curves as the plain algorithm of the
//! docs/physics.md §2.4 (same contact sets; forces equal to the CG tolerance). The default
//! also stops solves on certified decisions and releases certified elements without a
//! solve (docs/fast-step.md); the plain algorithm is the reference rule.

use adhesim::{
    AdhesiveParams, AdhesiveSolver, Boundary, ElasticMaterial, FreeOperator, Grid, IndentPulloff, NormalSolver,
    Problem, Profile, StepRecord, WavySphere,
};

fn cycle(amplitude: f64, params: AdhesiveParams) -> Vec<StepRecord> {
    let grid = Grid::new(48, 0.3, Boundary::Free).unwrap();
    let operator = FreeOperator::new(grid, ElasticMaterial::new(1.0).unwrap());
    let heights = WavySphere::new(1.0, amplitude, 0.025, 0.0).unwrap().heights(&grid);
    let start = heights.iter().cloned().fold(f64::INFINITY, f64::min);
    let mut solver = NormalSolver::Adhesive(Box::new(AdhesiveSolver::new(grid, 1.0, vec![2e-5; grid.len()], params)));
    let protocol = IndentPulloff {
        start_depth: start,
        max_depth: 3e-3,
        depth_step: 5e-5,
        max_retract_steps: 10_000,
        jump_force_threshold: 0.0,
    };
    let mut records = Vec::new();
    let mut problem = Problem::new(Box::new(operator), heights).unwrap();
    protocol.run(&mut problem, &mut solver, &mut records).unwrap();
    records
}

/// Tolerance: forces agree to 1e-6 of the force scale (each solve is converged to a
/// point-wise residual of 1e-4·σ_c·K(0,0); different warm starts give different round-off),
/// and the contact-set sizes agree exactly.
fn assert_same(reference: &[StepRecord], candidate: &[StepRecord]) {
    assert_eq!(reference.len(), candidate.len());
    let scale = reference.iter().map(|r| r.force_normal.abs()).fold(0.0, f64::max);
    for (a, b) in reference.iter().zip(candidate) {
        assert_eq!(a.contact_elements, b.contact_elements, "step {}", a.step);
        assert!(
            (a.force_normal - b.force_normal).abs() < 1e-6 * scale,
            "step {}: force {:e} vs {:e} (scale {scale:e})",
            a.step,
            a.force_normal,
            b.force_normal
        );
    }
}

#[test]
fn speed_ups_leave_curves_unchanged() {
    for amplitude in [0.0, 3e-4, 1e-3] {
        let plain = cycle(
            amplitude,
            AdhesiveParams {
                carry_bans_when_retracting: false,
                preconditioned: false,
                relative_tolerance: 1e-9,
                reference_rule: true,
                ..AdhesiveParams::default()
            },
        );
        let fast = cycle(amplitude, AdhesiveParams::default());
        assert_same(&plain, &fast);
        let plain_solves: usize = plain.iter().map(|r| r.report.solves).sum();
        let fast_solves: usize = fast.iter().map(|r| r.report.solves).sum();
        assert!(
            fast_solves < plain_solves,
            "h = {amplitude}: {fast_solves} vs {plain_solves}"
        );
    }
}
