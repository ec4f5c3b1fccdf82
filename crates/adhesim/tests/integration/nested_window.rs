//! The contact window of `NestedActiveSet` (docs/history.md §2026-11-23: the non-adhesive
//! whole run): pre-solving each level on the contact's bounding box must give the solution
//! of the whole grid. Both runs
//! converge to a relative residual of 1e-10 on the same set, so their forces agree far
//! below the 1e-8 asserted here (the two differ only in the rounding of their transforms
//! and in where their CG iterations stopped inside the tolerance); the sets must be equal.

use adhesim::{
    Boundary, ContactState, ElasticMaterial, FreeOperator, Grid, NestedActiveSet, NestedParams, Profile, Sphere,
};

fn solvers(grid: Grid, material: ElasticMaterial) -> (NestedActiveSet, NestedActiveSet) {
    let whole = NestedParams {
        contact_window: false,
        ..NestedParams::default()
    };
    (
        NestedActiveSet::new(grid, material, NestedParams::default()),
        NestedActiveSet::new(grid, material, whole),
    )
}

/// Solves at each depth in turn (warm starts between them) with and without the window
/// and compares set and force at every depth; returns the window applications per depth.
fn compare(grid: Grid, heights: &[f64], depths: &[f64]) -> Vec<u64> {
    let material = ElasticMaterial::new(1.0).unwrap();
    let mut operator = FreeOperator::new(grid, material);
    let (mut windowed, mut whole) = solvers(grid, material);
    let (mut windowed_state, mut whole_state) = (ContactState::new(&grid), ContactState::new(&grid));
    let mut window_applications = Vec::new();
    for &depth in depths {
        let a = windowed
            .solve(&mut operator, heights, depth, &mut windowed_state)
            .unwrap();
        let b = whole.solve(&mut operator, heights, depth, &mut whole_state).unwrap();
        assert_eq!(whole.window_applications(), 0, "the option turns the window off");
        assert_eq!(windowed_state.contact, whole_state.contact, "depth {depth}");
        assert!(a.contact_elements > 0);
        assert!((a.force / b.force - 1.0).abs() < 1e-8, "depth {depth}: {a:?} vs {b:?}");
        assert!(a.residual <= 1e-10);
        window_applications.push(windowed.window_applications());
    }
    window_applications
}

#[test]
fn window_gives_the_whole_grid_solution_for_a_centred_sphere() {
    // N = 128, L = 1: a = 16Δ, then (warm, loading) a = 40Δ, which outgrows the first
    // window and its margin. A cold a = 56Δ needs windows above 3/4 of the grid on every
    // level: none is used.
    let grid = Grid::new(128, 1.0, Boundary::Free).unwrap();
    let heights = Sphere::new(1.0).unwrap().heights(&grid);
    let depth = |a: f64| (a / 128.0).powi(2);
    let applications = compare(grid, &heights, &[depth(16.0), depth(40.0)]);
    assert!(applications.iter().all(|&a| a > 0), "{applications:?}");
    assert_eq!(compare(grid, &heights, &[depth(56.0)]), [0]);
}

#[test]
fn window_at_the_grid_edge_gives_the_whole_grid_solution() {
    // A sphere centred near a corner: the window is moved inside the grid and the contact
    // touches the grid's edge, where the window has no open side.
    let n = 96;
    let grid = Grid::new(n, 1.0, Boundary::Free).unwrap();
    let heights: Vec<f64> = (0..grid.len())
        .map(|k| {
            let (x, y) = grid.centre(k);
            ((x - 0.44).powi(2) + (y + 0.47).powi(2)) / 2.0
        })
        .collect();
    let applications = compare(grid, &heights, &[(10.0f64 / 96.0).powi(2), (14.0f64 / 96.0).powi(2)]);
    assert!(applications.iter().all(|&a| a > 0), "{applications:?}");
}
