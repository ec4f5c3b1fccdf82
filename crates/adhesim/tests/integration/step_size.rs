//! The adhesive step's result must not depend on how finely the approach is cut: under
//! continuous loading an element that failed its closure test is re-tested as soon as the
//! contact around it grows, so banning it for the rest of a finite step makes the contact
//! lag (the solver's `retry_after_growth`). Here the same approach is driven with a coarse
//! and a 4× finer depth step, and the states at the common depths are compared.

use adhesim::{
    AdhesiveParams, AdhesiveSolver, Boundary, ContactState, ElasticMaterial, FreeOperator, Grid, Profile, WavySphere,
};

/// Contact-element counts and normal forces at every `stride`-th depth of `steps` equal
/// steps from first touch to `max_depth` (wavy sphere of Fig. 1's kind, α ≈ 1.2).
fn approach(steps: usize, stride: usize, params: AdhesiveParams) -> Vec<(usize, f64)> {
    let grid = Grid::new(64, 0.4, Boundary::Free).unwrap();
    let mut operator = FreeOperator::new(grid, ElasticMaterial::new(1.0).unwrap());
    let heights = WavySphere::new(1.0, 6e-4, 0.025, 0.0).unwrap().heights(&grid);
    let start = heights.iter().cloned().fold(f64::INFINITY, f64::min);
    let max_depth = 4e-3;
    let mut solver = AdhesiveSolver::new(grid, 1.0, vec![1e-4; grid.len()], params);
    let mut state = ContactState::new(&grid);
    let mut samples = Vec::new();
    for step in 1..=steps {
        let depth = start + (max_depth - start) * step as f64 / steps as f64;
        let report = solver.step(&mut operator, &heights, depth, &mut state).unwrap();
        if step % stride == 0 {
            samples.push((state.contact_elements(), report.force));
        }
    }
    samples
}

/// Largest relative difference in contact size between two sampled approaches.
fn largest_size_difference(coarse: &[(usize, f64)], fine: &[(usize, f64)]) -> f64 {
    coarse
        .iter()
        .zip(fine)
        .map(|(a, b)| (a.0 as f64 - b.0 as f64).abs() / b.0.max(1) as f64)
        .fold(0.0, f64::max)
}

/// Tolerance: the same contact set sizes exactly (on a monotone approach with every failed
/// element retried after growth, the state reached does not depend on the path's cut; here
/// the coarse step crosses up to 72 elements of growth at once), forces to 1e-6 of the
/// largest (CG tolerance). Without retries the coarse contact lags by up to 19 %.
#[test]
fn approach_does_not_depend_on_the_step_size() {
    let coarse = approach(20, 1, AdhesiveParams::default());
    let fine = approach(80, 4, AdhesiveParams::default());
    let force_scale = fine.iter().map(|s| s.1.abs()).fold(0.0, f64::max);
    let size_difference = largest_size_difference(&coarse, &fine);
    assert_eq!(size_difference, 0.0, "contact sizes differ by {size_difference}");
    for (a, b) in coarse.iter().zip(&fine) {
        assert!((a.1 - b.1).abs() < 1e-6 * force_scale, "forces {} vs {}", a.1, b.1);
    }
    let without_retries = AdhesiveParams {
        retry_after_growth: false,
        ..AdhesiveParams::default()
    };
    let lagging = largest_size_difference(&approach(20, 1, without_retries), &approach(80, 4, without_retries));
    assert!(
        lagging > 0.05,
        "without retries the coarse contact lags: {lagging} vs {size_difference}"
    );
}
