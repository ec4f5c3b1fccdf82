//! An adhesive flat punch retracted to exactly the depth of its face (d = 0) while the face
//! is in contact (first robustness audit, docs/reliability.md: `scenarios/fig12_*.toml` with
//! `protocol.steps = 2` reached d = 0 on its second retraction step and failed with "solver did
//! not converge in 5000 iterations: residual 3e264": the fixed-set right-hand side d − z was 0
//! on the whole contact set, so the relative CG criterion asked for a residual of exactly 0).
//!
//! Closed form: on a fixed contact disc of radius a the force is Boussinesq's F = 2aE*d
//! (Johnson 1985, Sect. 3.8), linear in d and 0 at d = 0.

use adhesim::{
    AdhesiveParams, AdhesiveSolver, Boundary, ContactState, ElasticMaterial, FlatPunch, FreeOperator, Grid, Profile,
};

#[test]
fn punch_retracted_to_its_face_depth_carries_no_force() {
    let n = 32;
    let grid = Grid::new(n, 1.0, Boundary::Free).unwrap();
    let delta = grid.dx();
    let radius = 8.0 * delta;
    let contact_modulus = 1.0;
    let mut operator = FreeOperator::new(grid, ElasticMaterial::new(contact_modulus).unwrap());
    let heights = FlatPunch::new(radius).unwrap().heights(&grid);
    let face = heights.iter().filter(|h| h.is_finite()).count();
    // γ large enough that the face holds in tension at d = −step (Kendall's pull-off depth
    // √(2πaγ/E*) = 0.056 here, ten steps).
    let gamma = 1e-3;
    let mut solver = AdhesiveSolver::new(
        grid,
        contact_modulus,
        vec![gamma; grid.len()],
        AdhesiveParams::default(),
    );
    let mut state = ContactState::new(&grid);
    let step = 0.005;
    let mut forces = Vec::new();
    for depth in [step, 2.0 * step, step, 0.0, -step] {
        let report = solver
            .step(&mut operator, &heights, depth, &mut state)
            .unwrap_or_else(|e| panic!("step to d = {depth}: {e}"));
        assert_eq!(
            state.contact_elements(),
            face,
            "d = {depth}: the whole face stays in contact"
        );
        forces.push(report.force);
    }
    // d = 0: p = 0 exactly on the face (K_CC p = 0), so F = 0 exactly.
    assert_eq!(forces[3], 0.0);
    assert!(state.pressure.iter().all(|p| p.is_finite()));
    // On one contact set F is linear in d: F(−s) = −F(s) and F(2s) = 2F(s) up to the CG
    // tolerance (1e-6 relative).
    assert!(
        (forces[4] + forces[0]).abs() < 1e-5 * forces[0],
        "F(-s) = {:e}, F(s) = {:e}",
        forces[4],
        forces[0]
    );
    assert!((forces[1] - 2.0 * forces[0]).abs() < 1e-5 * forces[0]);
    // Boussinesq within 10 %: the staircase rim of an 8-element radius (docs/physics.md §4).
    let boussinesq = 2.0 * radius * contact_modulus * step;
    assert!(
        (forces[0] / boussinesq - 1.0).abs() < 0.1,
        "F(s)/(2aE*s) = {:.4}",
        forces[0] / boussinesq
    );
}
