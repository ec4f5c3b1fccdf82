//! One non-adhesive Hertz solve from a cold start, compared with the closed form.
//!
//! `cargo run --release -p adhesim --example hertz_indent -- [N]`
//!
//! R = E* = 1 on a free grid of side 1, depth (1/4)², so the contact radius is N/4 elements.
//! Both non-adhesive solvers must give the Hertz force within 0.5 % (the bound of
//! tests/integration/validation_hertz.rs at 32 elements; measured 1.3e-4 at N = 64) and the
//! contact radius within one element. `cargo test --release -p adhesim --example hertz_indent` runs
//! it at N = 64 (a fraction of a second).
use adhesim::analysis::reference::Hertz;
use adhesim::{
    Boundary, Ccg, CcgParams, ContactState, Control, ElasticMaterial, FreeOperator, Grid, NestedActiveSet,
    NestedParams, Profile, Sphere,
};

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .map_or(512, |a| a.parse().expect("N as a number"));
    run(n);
}

/// Solves at N×N, prints and checks both solvers against Hertz.
fn run(n: usize) {
    let grid = Grid::new(n, 1.0, Boundary::Free).expect("grid");
    let start = std::time::Instant::now();
    let mut operator = FreeOperator::new(grid, ElasticMaterial::new(1.0).expect("modulus"));
    let setup = start.elapsed().as_secs_f64();
    let heights = Sphere::new(1.0).expect("radius").heights(&grid);
    let depth = 0.25f64.powi(2); // contact radius L/4 = N/4 elements
    let start = std::time::Instant::now();
    let mut nested = NestedActiveSet::new(
        grid,
        ElasticMaterial::new(1.0).expect("modulus"),
        NestedParams::default(),
    );
    let nested_setup = start.elapsed().as_secs_f64();
    let hertz = Hertz {
        radius: 1.0,
        contact_modulus: 1.0,
    };
    let mut state = ContactState::new(&grid);
    let start = std::time::Instant::now();
    let report = nested
        .solve(&mut operator, &heights, depth, &mut state)
        .expect("converged");
    let solve = start.elapsed().as_secs_f64();
    let nested_force = report.force;
    check("nested active set", &grid, &state, nested_force, &hertz, depth);
    println!(
        "nested active set: setup {nested_setup:.3} s (+ operator {setup:.3} s), solve {solve:.3} s, {} CG iterations, {} FFT pairs (+ {} on {} coarse levels), force error {:.2e}, contact radius {:.1} elements",
        report.iterations,
        report.operator_applications,
        nested.coarse_applications(),
        nested.coarse_levels(),
        report.force / hertz.force(depth) - 1.0,
        state.contact_radius(&grid, (0.0, 0.0)) / grid.dx(),
    );
    let mut state = ContactState::new(&grid);
    let start = std::time::Instant::now();
    let report = Ccg::new(CcgParams::default())
        .solve(&mut operator, &heights, Control::Displacement(depth), &mut state)
        .expect("converged");
    let solve = start.elapsed().as_secs_f64();
    println!(
        "Polonsky–Keer CCG, N = {n}: setup {setup:.3} s, solve {solve:.3} s, {} iterations, {} FFT pairs, force error {:.2e}, contact radius {:.1} elements (Hertz {:.1})",
        report.iterations,
        report.operator_applications,
        report.force / hertz.force(depth) - 1.0,
        state.contact_radius(&grid, (0.0, 0.0)) / grid.dx(),
        hertz.contact_radius(depth) / grid.dx()
    );
    check("CCG", &grid, &state, report.force, &hertz, depth);
    // Both are converged far below the discretisation error (CCG to a pressure change of
    // 1e-10, the active set to a residual of 1e-10): the same force to 1e-7.
    assert!((report.force / nested_force - 1.0).abs() < 1e-7, "CCG vs nested");
}

fn check(solver: &str, grid: &Grid, state: &ContactState, force: f64, hertz: &Hertz, depth: f64) {
    let force_error = force / hertz.force(depth) - 1.0;
    assert!(
        force_error.abs() < 5e-3,
        "{solver}: force error {force_error:.2e} > 0.5 %"
    );
    let radius_error = state.contact_radius(grid, (0.0, 0.0)) - hertz.contact_radius(depth);
    assert!(
        radius_error.abs() <= grid.dx(),
        "{solver}: contact radius off by {:.2} elements",
        radius_error / grid.dx()
    );
}

#[cfg(test)]
mod tests {
    #[test]
    fn hertz_at_n64() {
        super::run(64);
    }
}
