//! Polonsky & Keer (1999)'s constrained conjugate gradients under load control on a
//! periodic strip contact (docs/validation.md §13). The heights are y-independent (a 1-D
//! profile), so every element of a row of the strip has bitwise the same gap (a power-of-two
//! FFT of a y-uniform field is exact). When the active set shrinks to one row, the mean-free
//! gap g − ḡ on it is zero, but a plainly rounded mean left it a uniform vector of rounding
//! size; along a uniform vector the load-constrained curvature Σ(r − r̄)t vanishes too, so
//! the step τ = Σg·t / Σ(r − r̄)t was rounding over rounding (4e16 on the case below),
//! wiped the pressure, and the cold restart retraced the same path forever (NotConverged).
//! The profile is the one the exponential cohesive law handed to CCG at N = 128
//! (docs/validation.md §13): z + K(−t) near its pull-off, a flattened bottom.

use adhesim::{Boundary, Ccg, CcgParams, ContactState, Control, ElasticMaterial, Grid, HalfSpace, SolveReport};

/// The mean-gap control of the failing cohesive step (tests/data/strip_profile.txt).
const STRIP_DEPTH: f64 = -2.431217913521752e-4;

/// The 128 heights of one row (every row is the same).
fn profile() -> Vec<f64> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/strip_profile.txt");
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|line| !line.starts_with('#'))
        .map(|line| line.trim().parse().unwrap())
        .collect()
}

/// A periodic 128 × `rows` cell of square elements (Δ = 1/128) carrying the profile.
fn strip(rows: usize) -> (Grid, Vec<f64>) {
    let profile = profile();
    let nx = profile.len();
    let grid = Grid::rectangular(nx, rows, 1.0, rows as f64 / nx as f64, Boundary::Periodic).unwrap();
    let heights = (0..grid.len()).map(|k| profile[k % nx]).collect();
    (grid, heights)
}

/// Converged solves here take 9 to 27 iterations (measured, the mean-gap solve's secant
/// steps together); 1000 leaves a wide margin and keeps the former endless cycle (11
/// iterations a turn) quick to fail.
fn ccg() -> Ccg {
    Ccg::new(CcgParams {
        max_iterations: 1000,
        ..CcgParams::default()
    })
}

/// The solution is a contact state: total load as asked, p ≥ 0, g = u + z − d ≥ 0 with
/// d the reported depth, g = 0 where p > 0. Gap tolerance 1e-10 of the height range (the
/// solver's depth tolerance; measured ≤ 2.4e-13 of the range here, Σp|g| ≤ 1.2e-13 of
/// range·Σp, load error ≤ 1.8e-15).
fn assert_contact_state(heights: &[f64], grid: &Grid, state: &ContactState, report: &SolveReport, load: f64) {
    let lowest = heights.iter().cloned().fold(f64::INFINITY, f64::min);
    let highest = heights.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let tolerance = 1e-10 * (highest - lowest);
    // Σp is rescaled to the load each iteration: equal up to the rounding of a sum.
    let force = state.force(grid.element_area());
    assert!((force - load).abs() <= 1e-12 * load, "load {load:e}: force {force:e}");
    assert!((report.force - load).abs() <= 1e-12 * load);
    let (mut complementarity, mut total) = (0.0, 0.0);
    for (k, &z) in heights.iter().enumerate() {
        let (p, gap) = (state.pressure[k], state.displacement[k] + z - report.depth);
        assert!(p >= 0.0, "load {load:e}: element {k} pressure {p:e}");
        assert!(gap >= -tolerance, "load {load:e}: element {k} gap {gap:e}");
        assert_eq!(state.contact[k], p > 0.0);
        if p > 0.0 {
            assert!(
                gap.abs() <= tolerance,
                "load {load:e}: element {k} in contact at gap {gap:e}"
            );
        }
        complementarity += p * gap.abs();
        total += p;
    }
    assert!(
        complementarity <= tolerance * total,
        "load {load:e}: Σp|g| {complementarity:e}"
    );
}

/// Load control on a 128 × 16 cell over three decades of load, through contacts one to
/// several rows wide: before the fix 10 of these 100 loads cycled without end.
#[test]
fn load_controlled_ccg_converges_on_a_strip_one_row_wide() {
    let (grid, heights) = strip(16);
    let mut operator = HalfSpace::new(grid, ElasticMaterial::new(1.0).unwrap());
    let mut solver = ccg();
    let mut one_row = 0;
    for i in 0..100 {
        let load = 1e-8 * 1e3f64.powf(i as f64 / 99.0);
        let mut state = ContactState::new(&grid);
        let report = solver
            .solve(&mut operator, &heights, Control::Load(load), &mut state)
            .unwrap_or_else(|e| panic!("load {load:e}: {e}"));
        assert_contact_state(&heights, &grid, &state, &report, load);
        if report.contact_elements == grid.ny() {
            one_row += 1;
        }
    }
    // The case in question: contacts of a single row are among the solutions.
    assert!(one_row > 10, "{one_row} one-row contacts");
}

/// The instance of docs/validation.md §13: the mean-gap solve of the cohesive step on the
/// 128 × 128 cell (its secant iteration on the load passes through one-row contacts) reaches
/// the depth within the solver's depth tolerance, 1e-10 of max(height range, |d|).
#[test]
fn mean_gap_solve_of_the_strip_profile_converges() {
    let (grid, heights) = strip(128);
    let mut operator = HalfSpace::new(grid, ElasticMaterial::new(1.0).unwrap());
    let mut state = ContactState::new(&grid);
    let report = ccg()
        .solve(&mut operator, &heights, Control::Displacement(STRIP_DEPTH), &mut state)
        .unwrap();
    let load = report.force;
    assert!(load > 0.0 && report.contact_elements == grid.ny(), "{report:?}");
    assert_contact_state(&heights, &grid, &state, &report, load);
    let lowest = heights.iter().cloned().fold(f64::INFINITY, f64::min);
    let highest = heights.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let reached = (0..grid.len())
        .filter(|&k| state.contact[k])
        .map(|k| state.displacement[k] + heights[k])
        .sum::<f64>()
        / report.contact_elements as f64;
    let scale = (highest - lowest).max(STRIP_DEPTH.abs());
    assert!((reached - STRIP_DEPTH).abs() <= 1e-10 * scale, "depth {reached:e}");
}
