//! Non-adhesive contact against Hertz and the flat punch.

#![allow(clippy::needless_range_loop)]
use adhesim::analysis::reference::{FlatPunchReference, Hertz};
use adhesim::{
    Boundary, Ccg, CcgParams, ContactState, Control, ElasticMaterial, FlatPunch, FreeOperator, Grid, Profile, Sphere,
};

/// Hertz, free boundary, a = √(Rd) = 32Δ on a 128² grid. Tolerances (docs/validation.md §2):
/// force within 0.5 % (the prototype's discretisation error at a = 32Δ is ~1e-4), contact
/// radius within one element (staircase boundary), pressure within 2 % of p0 away from the edge
/// (r < 0.9a, where the square-root edge is resolved by several elements).
#[test]
fn hertz_displacement_control() {
    let n = 128;
    let delta = 1.0 / n as f64;
    let radius = 1.0;
    let a = 32.0 * delta;
    let depth = a * a / radius;
    let grid = Grid::new(n, 1.0, Boundary::Free).unwrap();
    let material = ElasticMaterial::new(1.0).unwrap();
    let mut operator = FreeOperator::new(grid, material);
    let sphere = Sphere::new(radius).unwrap();
    let heights = sphere.heights(&grid);
    let mut state = ContactState::new(&grid);
    let report = Ccg::new(CcgParams::default())
        .solve(&mut operator, &heights, Control::Displacement(depth), &mut state)
        .unwrap();
    let hertz = Hertz {
        radius,
        contact_modulus: 1.0,
    };
    let force_error = report.force / hertz.force(depth) - 1.0;
    assert!(force_error.abs() < 5e-3, "force error {force_error}");
    let contact_radius = state.contact_radius(&grid, (0.0, 0.0));
    assert!((contact_radius - a).abs() <= delta, "radius {contact_radius} vs {a}");
    let p0 = hertz.pressure(depth, 0.0);
    for k in 0..grid.len() {
        let (x, y) = grid.centre(k);
        let r = x.hypot(y);
        if r < 0.9 * a {
            let error = (state.pressure[k] - hertz.pressure(depth, r)).abs() / p0;
            assert!(error < 0.02, "pressure error {error} at r/a = {}", r / a);
        }
    }
    assert!(report.iterations > 1);
}

/// Load control reaches the requested load to 1e-8 relative (the iteration rescales p to
/// the load), and the depth it finds reproduces Hertz's to the same 0.5 % as the force.
#[test]
fn hertz_load_control_and_warm_start() {
    let n = 128;
    let grid = Grid::new(n, 1.0, Boundary::Free).unwrap();
    let material = ElasticMaterial::new(1.0).unwrap();
    let mut operator = FreeOperator::new(grid, material);
    let heights = Sphere::new(1.0).unwrap().heights(&grid);
    let hertz = Hertz {
        radius: 1.0,
        contact_modulus: 1.0,
    };
    let load = hertz.force((32.0f64 / 128.0).powi(2));
    let mut solver = Ccg::new(CcgParams::default());
    let mut state = ContactState::new(&grid);
    let report = solver
        .solve(&mut operator, &heights, Control::Load(load), &mut state)
        .unwrap();
    assert!((report.force / load - 1.0).abs() < 1e-8, "{report:?} vs {load}");
    let depth_error = report.depth / hertz.depth_for_force(load) - 1.0;
    assert!(depth_error.abs() < 5e-3, "depth error {depth_error}");
    // A warm start at the solution converges in fewer iterations than the cold start.
    let warm = solver
        .solve(&mut operator, &heights, Control::Load(load), &mut state)
        .unwrap();
    assert!(
        warm.iterations < report.iterations,
        "{} vs {}",
        warm.iterations,
        report.iterations
    );
    assert!(solver
        .solve(&mut operator, &heights, Control::Load(-1.0), &mut state)
        .is_err());
}

/// A solver given too few iterations says so instead of returning a wrong answer.
#[test]
fn non_convergence_is_an_error() {
    let grid = Grid::new(64, 1.0, Boundary::Free).unwrap();
    let mut operator = FreeOperator::new(grid, ElasticMaterial::new(1.0).unwrap());
    let heights = Sphere::new(1.0).unwrap().heights(&grid);
    let mut state = ContactState::new(&grid);
    let result = Ccg::new(CcgParams {
        tolerance: 1e-12,
        max_iterations: 3,
        ..CcgParams::default()
    })
    .solve(&mut operator, &heights, Control::Displacement(0.01), &mut state);
    // The error states the displacement residual on the contact set, absolute and
    // relative to ‖d − z‖ there: after 3 iterations from a cold start it is far from 0
    // but finite, and the relative value is the absolute one over a length of order d.
    match result {
        Err(adhesim::SolveError::NotConverged {
            iterations: 3,
            absolute_residual,
            relative_residual,
            ..
        }) => {
            assert!(
                absolute_residual.is_finite() && absolute_residual > 0.0,
                "{absolute_residual}"
            );
            assert!(
                relative_residual.is_finite() && relative_residual > 1e-12,
                "{relative_residual}"
            );
        }
        other => panic!("expected NotConverged after 3 iterations, got {other:?}"),
    }
}

/// Flat circular punch of radius a = 24Δ: stiffness F/d within 2 % of 2E*a (docs/validation.md
/// §2; the staircase face and the edge singularity cost ~1 % at this resolution).
#[test]
fn flat_punch_stiffness() {
    let n = 64;
    let delta = 1.0 / n as f64;
    let a = 24.0 * delta;
    let grid = Grid::new(n, 1.0, Boundary::Free).unwrap();
    let mut operator = FreeOperator::new(grid, ElasticMaterial::new(1.0).unwrap());
    let heights = FlatPunch::new(a).unwrap().heights(&grid);
    let mut state = ContactState::new(&grid);
    let depth = 1e-3;
    let report = Ccg::new(CcgParams::default())
        .solve(&mut operator, &heights, Control::Displacement(depth), &mut state)
        .unwrap();
    let reference = FlatPunchReference {
        radius: a,
        contact_modulus: 1.0,
    };
    let error = report.force / depth / reference.stiffness() - 1.0;
    assert!(error.abs() < 0.02, "stiffness error {error}");
}

/// The nested-grid active-set solver on the Hertz case of `hertz_displacement_control`:
/// the same contact set as CCG and the same force to 1e-7 relative (both are converged far
/// below that: CCG to a pressure change of 1e-10, the active set to a residual of 1e-10),
/// hence the same 0.5 % agreement with Hertz, with fewer fine-grid FFT pairs. A warm start
/// at the solution needs one round; a periodic grid is refused with a clear error.
#[test]
fn nested_active_set_matches_ccg_and_hertz() {
    use adhesim::{NestedActiveSet, NestedParams, PeriodicKernel, PeriodicOperator, SolveError};
    let n = 128;
    let grid = Grid::new(n, 1.0, Boundary::Free).unwrap();
    let material = ElasticMaterial::new(1.0).unwrap();
    let mut operator = FreeOperator::new(grid, material);
    let heights = Sphere::new(1.0).unwrap().heights(&grid);
    let depth = (32.0f64 / 128.0).powi(2);
    let mut reference = ContactState::new(&grid);
    let ccg = Ccg::new(CcgParams::default())
        .solve(&mut operator, &heights, Control::Displacement(depth), &mut reference)
        .unwrap();
    let mut solver = NestedActiveSet::new(grid, material, NestedParams::default());
    assert_eq!(solver.coarse_levels(), 2, "128 → 64 → 32");
    let mut state = ContactState::new(&grid);
    let report = solver.solve(&mut operator, &heights, depth, &mut state).unwrap();
    assert_eq!(state.contact, reference.contact);
    assert!(
        (report.force / ccg.force - 1.0).abs() < 1e-7,
        "{} vs {}",
        report.force,
        ccg.force
    );
    let hertz = Hertz {
        radius: 1.0,
        contact_modulus: 1.0,
    };
    assert!((report.force / hertz.force(depth) - 1.0).abs() < 5e-3);
    assert!(report.residual <= 1e-10);
    assert!(
        report.operator_applications < ccg.operator_applications / 2,
        "{} vs {}",
        report.operator_applications,
        ccg.operator_applications
    );
    assert!(solver.coarse_applications() > 0);
    let warm = solver.solve(&mut operator, &heights, depth, &mut state).unwrap();
    assert!(warm.operator_applications <= 2, "{warm:?}");
    assert!((warm.force / report.force - 1.0).abs() < 1e-9);

    let periodic = Grid::new(32, 1.0, Boundary::Periodic).unwrap();
    let mut periodic_operator = PeriodicOperator::new(periodic, material, PeriodicKernel::ElementConsistent);
    let mut periodic_solver = NestedActiveSet::new(periodic, material, NestedParams::default());
    let error = periodic_solver
        .solve(
            &mut periodic_operator,
            &Sphere::new(1.0).unwrap().heights(&periodic),
            0.01,
            &mut ContactState::new(&periodic),
        )
        .unwrap_err();
    assert!(matches!(error, SolveError::PeriodicUnsupported { .. }), "{error}");
}

/// Unloading (BENCHMARKS.md §What did not pay, warm starts on unloads): from a = 32Δ at N = 128
/// to half the depth (a = 22.6Δ) and to zero. The default cold restart and the warm start
/// (`warm_unload`) must agree to 1e-7 (both converge to a relative residual of 1e-10) and with
/// Hertz to 0.5 % (the bound of the loading test; a = 22.6Δ still resolves the edge to ~2e-4);
/// at zero depth the cold restart finds no contact with a handful of fine applications instead
/// of a warm descent from thousands of elements.
#[test]
fn nested_unload_cold_restart_matches_warm_start_and_hertz() {
    use adhesim::{NestedActiveSet, NestedParams};
    let grid = Grid::new(128, 1.0, Boundary::Free).unwrap();
    let material = ElasticMaterial::new(1.0).unwrap();
    let mut operator = FreeOperator::new(grid, material);
    let heights = Sphere::new(1.0).unwrap().heights(&grid);
    let depth = (32.0f64 / 128.0).powi(2);
    let hertz = Hertz {
        radius: 1.0,
        contact_modulus: 1.0,
    };
    let mut cold_solver = NestedActiveSet::new(grid, material, NestedParams::default());
    let warm_params = NestedParams {
        warm_unload: true,
        ..NestedParams::default()
    };
    let mut warm_solver = NestedActiveSet::new(grid, material, warm_params);
    let mut loaded = ContactState::new(&grid);
    cold_solver.solve(&mut operator, &heights, depth, &mut loaded).unwrap();
    warm_solver
        .solve(&mut operator, &heights, depth, &mut loaded.clone())
        .unwrap();

    let (mut cold, mut warm) = (loaded.clone(), loaded.clone());
    let cold_half = cold_solver
        .solve(&mut operator, &heights, 0.5 * depth, &mut cold)
        .unwrap();
    let warm_half = warm_solver
        .solve(&mut operator, &heights, 0.5 * depth, &mut warm)
        .unwrap();
    assert!(
        cold_solver.coarse_applications() > 0,
        "the unload restarts with the coarse levels"
    );
    assert_eq!(warm_solver.coarse_applications(), 0, "the warm unload keeps its state");
    assert_eq!(cold.contact, warm.contact);
    assert!(
        (cold_half.force / warm_half.force - 1.0).abs() < 1e-7,
        "{cold_half:?} {warm_half:?}"
    );
    assert!((cold_half.force / hertz.force(0.5 * depth) - 1.0).abs() < 5e-3);

    let (mut cold, mut warm) = (loaded.clone(), loaded.clone());
    cold_solver.solve(&mut operator, &heights, depth, &mut cold).unwrap();
    warm_solver.solve(&mut operator, &heights, depth, &mut warm).unwrap();
    let cold_zero = cold_solver.solve(&mut operator, &heights, 0.0, &mut cold).unwrap();
    let warm_zero = warm_solver.solve(&mut operator, &heights, 0.0, &mut warm).unwrap();
    assert_eq!((cold_zero.contact_elements, warm_zero.contact_elements), (0, 0));
    assert_eq!((cold_zero.force, warm_zero.force), (0.0, 0.0));
    assert!(
        cold_zero.operator_applications < warm_zero.operator_applications,
        "{cold_zero:?} vs {warm_zero:?}"
    );
}
