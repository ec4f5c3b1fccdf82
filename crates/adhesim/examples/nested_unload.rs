//! Warm against cold nested start of `NestedActiveSet` when a Hertz contact is unloaded:
//! the measurement behind `NestedParams::warm_unload` (BENCHMARKS.md §What did not pay,
//! warm starts on unloads).
//!
//! `cargo run --release -p adhesim --example nested_unload -- [N]`
//!
//! The Hertz case of `scenarios/hertz.toml` (R = E* = 1, L = 0.3, d = 0.01) is solved cold
//! at d, then unloaded to f·d for several f, once from the warm state (rule off) and once
//! from a cold nested start; f > 1 (loading) is measured too. The fraction of the warm set
//! inside {z < f·d} (where the new set must lie) is printed with the time and fine-grid
//! operator applications of each, and the forces must agree within 1e-7 relative (both are
//! converged to a relative residual of 1e-10).
use adhesim::{
    Boundary, ContactState, ElasticMaterial, FreeOperator, Grid, NestedActiveSet, NestedParams, Profile, Sphere,
};
use std::time::Instant;

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .map_or(512, |a| a.parse().expect("N as a number"));
    let grid = Grid::new(n, 0.3, Boundary::Free).expect("grid");
    let material = ElasticMaterial::new(1.0).expect("modulus");
    let mut operator = FreeOperator::new(grid, material);
    let heights = Sphere::new(1.0).expect("radius").heights(&grid);
    let depth = 0.01;
    let solver = |warm_unload: bool| {
        let params = NestedParams {
            warm_unload,
            ..NestedParams::default()
        };
        NestedActiveSet::new(grid, material, params)
    };
    let (mut warm_solver, mut cold_solver) = (solver(true), solver(false));
    let mut loaded = ContactState::new(&grid);
    warm_solver
        .solve(&mut operator, &heights, depth, &mut loaded)
        .expect("loading solve");
    let loaded_elements = loaded.contact_elements();
    println!("N = {n}: {loaded_elements} contact elements at d = {depth}");
    println!("| f = d'/d | warm set in z < d' | warm: time, fine applications | cold: time, fine (+ coarse) applications | force rel. diff |");
    println!("|---|---|---|---|---|");
    for fraction in [2.0, 1.5, 1.1, 0.9, 0.75, 0.6, 0.5, 0.4, 0.25, 0.1, 0.0] {
        let target = fraction * depth;
        let kept = (0..grid.len())
            .filter(|&k| loaded.contact[k] && heights[k] < target)
            .count() as f64
            / loaded_elements as f64;
        let mut warm = loaded.clone();
        // The previous solve was at d: re-solve there so each row starts from it.
        let mut again = loaded.clone();
        warm_solver
            .solve(&mut operator, &heights, depth, &mut again)
            .expect("re-solve at d");
        let start = Instant::now();
        let warm_report = warm_solver
            .solve(&mut operator, &heights, target, &mut warm)
            .expect("warm solve");
        let warm_time = start.elapsed().as_secs_f64();
        let mut cold = ContactState::new(&grid);
        let start = Instant::now();
        let cold_report = cold_solver
            .solve(&mut operator, &heights, target, &mut cold)
            .expect("cold solve");
        let cold_time = start.elapsed().as_secs_f64();
        let scale = warm_report
            .force
            .abs()
            .max(cold_report.force.abs())
            .max(f64::MIN_POSITIVE);
        let difference = (warm_report.force - cold_report.force).abs() / scale;
        println!(
            "| {fraction} | {kept:.3} | {:.3} s, {} | {:.3} s, {} (+ {}) | {difference:.1e} |",
            warm_time,
            warm_report.operator_applications,
            cold_time,
            cold_report.operator_applications,
            cold_solver.coarse_applications()
        );
        assert!(
            difference < 1e-7 || scale < 1e-300,
            "forces differ by {difference:e} at f = {fraction}"
        );
    }
}
