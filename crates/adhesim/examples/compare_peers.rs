//! adhesim's side of the peer comparison in `bench/compare/` (BENCHMARKS.md §How do we
//! compare with the peers): the same three problems the Python drivers give ASPHER, Tamaas
//! and ContactMechanics, timed and printed as one JSON object on stdout.
//!
//! `cargo run --release -p adhesim --example compare_peers -- [options]`
//!
//! Options (all optional):
//! - `--sizes 256,512,1024`: grids of the Hertz solve (a) and the operator timing (b);
//! - `--repeats 3`: timed runs per entry (each one cold: new operator, new state);
//! - `--tolerance 1e-10`: `CcgParams::tolerance`, Σ|p_new − p_old|/Σ|p| between iterations;
//! - `--solver nested|ccg`: the Hertz solver (default `nested`: `NestedActiveSet`, the
//!   default non-adhesive solver of `adhesim run`, to a relative residual of
//!   `--nested-tolerance 1e-10`; its setup includes the coarse levels);
//! - `--adhesive-n 128`, `--steps-per-unit 20`, `--max-depth 3`: the adhesive cycle (c)
//!   on an N×N free grid of side 1 with a_JKR = N/4 elements, depth steps of
//!   |d_JKR|/steps-per-unit up to max-depth·|d_JKR| and back until contact is lost;
//! - `--skip-hertz`, `--skip-operator`, `--skip-adhesive`.
//!
//! Threads: rayon's global pool, so `RAYON_NUM_THREADS` sets them.
//!
//! It asserts the accuracy it reports (Hertz force within 0.5 %, pull-off force within the
//! first-order mesh error) but is not run by `cargo test`: it exists for its timings, takes
//! seconds to minutes, and its checks are those of the `hertz_indent` and `jkr_pull_off`
//! examples, which are.
//! Problem (a): rigid paraboloid R = 1 on E* = 1, free half-space, square of side 1 with
//! N×N elements, depth d = (1/4)²/R (contact radius 1/4 = N/4 elements), displacement
//! control, cold start; error against Hertz F = (4/3)E*√R d^{3/2}.
use adhesim::analysis::reference::{Hertz, Jkr};
use adhesim::{
    AdhesiveParams, AdhesiveSolver, Boundary, Ccg, CcgParams, ContactState, Control, ElasticMaterial, ElasticOperator,
    FreeOperator, Grid, IndentPulloff, NestedActiveSet, NestedParams, NormalSolver, Problem, Profile, Sphere,
};
use std::time::Instant;

struct Options {
    sizes: Vec<usize>,
    repeats: usize,
    tolerance: f64,
    nested: bool,
    nested_tolerance: f64,
    adhesive_n: usize,
    steps_per_unit: f64,
    max_depth: f64,
    hertz: bool,
    operator: bool,
    adhesive: bool,
}

fn parse() -> Options {
    let mut options = Options {
        sizes: vec![256, 512, 1024],
        repeats: 3,
        tolerance: CcgParams::default().tolerance,
        nested: true,
        nested_tolerance: NestedParams::default().relative_tolerance,
        adhesive_n: 128,
        steps_per_unit: 20.0,
        max_depth: 3.0,
        hertz: true,
        operator: true,
        adhesive: true,
    };
    let mut args = std::env::args().skip(1);
    while let Some(flag) = args.next() {
        let mut value = || args.next().unwrap_or_else(|| panic!("{flag} needs a value"));
        match flag.as_str() {
            "--sizes" => {
                options.sizes = value()
                    .split(',')
                    .map(|s| s.trim().parse().expect("sizes as integers"))
                    .collect()
            }
            "--repeats" => options.repeats = value().parse().expect("repeats"),
            "--tolerance" => options.tolerance = value().parse().expect("tolerance"),
            "--nested-tolerance" => options.nested_tolerance = value().parse().expect("nested tolerance"),
            "--solver" => {
                options.nested = match value().as_str() {
                    "nested" => true,
                    "ccg" => false,
                    other => panic!("--solver must be nested or ccg, got {other}"),
                }
            }
            "--adhesive-n" => options.adhesive_n = value().parse().expect("adhesive N"),
            "--steps-per-unit" => options.steps_per_unit = value().parse().expect("steps per unit"),
            "--max-depth" => options.max_depth = value().parse().expect("max depth"),
            "--skip-hertz" => options.hertz = false,
            "--skip-operator" => options.operator = false,
            "--skip-adhesive" => options.adhesive = false,
            other => panic!("unknown option {other}"),
        }
    }
    assert!(options.repeats >= 1, "at least one repeat");
    options
}

/// `[a, b, c]` with full precision.
fn list(values: &[f64]) -> String {
    let items: Vec<String> = values.iter().map(|v| format!("{v:e}")).collect();
    format!("[{}]", items.join(", "))
}

fn hertz_entry(n: usize, options: &Options) -> String {
    let grid = Grid::new(n, 1.0, Boundary::Free).expect("grid");
    let material = ElasticMaterial::new(1.0).expect("modulus");
    let heights = Sphere::new(1.0).expect("radius").heights(&grid);
    let depth = 0.25f64.powi(2);
    let hertz = Hertz {
        radius: 1.0,
        contact_modulus: 1.0,
    };
    let (mut setup, mut solve) = (Vec::new(), Vec::new());
    let mut last = None;
    for _ in 0..options.repeats {
        let start = Instant::now();
        let mut operator = FreeOperator::new(grid, material);
        let mut nested = options.nested.then(|| {
            NestedActiveSet::new(
                grid,
                material,
                NestedParams {
                    relative_tolerance: options.nested_tolerance,
                    ..NestedParams::default()
                },
            )
        });
        setup.push(start.elapsed().as_secs_f64());
        let mut state = ContactState::new(&grid);
        let start = Instant::now();
        let report = match nested.as_mut() {
            Some(solver) => solver.solve(&mut operator, &heights, depth, &mut state),
            None => Ccg::new(CcgParams {
                tolerance: options.tolerance,
                ..CcgParams::default()
            })
            .solve(&mut operator, &heights, Control::Displacement(depth), &mut state),
        }
        .expect("Hertz solve converged");
        solve.push(start.elapsed().as_secs_f64());
        last = Some(report);
    }
    let report = last.expect("one repeat");
    let reference = hertz.force(depth);
    // 0.5 %: the bound of tests/integration/validation_hertz.rs for a contact of 32 elements
    // in radius (here N/4; measured 1.3e-4 at N = 64).
    assert!(
        (report.force / reference - 1.0).abs() < 5e-3,
        "Hertz force error {:.2e} at N = {n}",
        report.force / reference - 1.0
    );
    format!(
        "{{\"n\": {n}, \"setup_s\": {}, \"solve_s\": {}, \"iterations\": {}, \"operator_applications\": {}, \
         \"force\": {:e}, \"force_hertz\": {reference:e}, \"rel_force_error\": {:e}, \"contact_elements\": {}}}",
        list(&setup),
        list(&solve),
        report.iterations,
        report.operator_applications,
        report.force,
        report.force / reference - 1.0,
        report.contact_elements
    )
}

fn operator_entry(n: usize, options: &Options) -> String {
    let grid = Grid::new(n, 1.0, Boundary::Free).expect("grid");
    let mut operator = FreeOperator::new(grid, ElasticMaterial::new(1.0).expect("modulus"));
    let pressure: Vec<f64> = (0..grid.len()).map(|k| ((k * 31) % 17) as f64).collect();
    let mut displacement = vec![0.0; grid.len()];
    operator.apply(&pressure, &mut displacement); // warm-up
    let start = Instant::now();
    operator.apply(&pressure, &mut displacement);
    let once = start.elapsed().as_secs_f64();
    // enough applications per repeat for ~0.3 s
    let count = ((0.3 / once.max(1e-6)).ceil() as usize).clamp(1, 1000);
    let mut per_application = Vec::new();
    for _ in 0..options.repeats {
        let start = Instant::now();
        for _ in 0..count {
            operator.apply(&pressure, &mut displacement);
        }
        per_application.push(start.elapsed().as_secs_f64() / count as f64);
    }
    format!(
        "{{\"n\": {n}, \"apply_s\": {}, \"applications_per_repeat\": {count}}}",
        list(&per_application)
    )
}

fn adhesive_entry(options: &Options) -> String {
    let n = options.adhesive_n;
    let (radius, modulus) = (1.0, 1.0);
    let delta = 1.0 / n as f64;
    let a_jkr: f64 = 0.25; // N/4 elements
    let gamma = a_jkr.powi(3) * 8.0 * modulus / (9.0 * std::f64::consts::PI * radius * radius);
    let jkr = Jkr {
        radius,
        contact_modulus: modulus,
        work_of_adhesion: gamma,
    };
    let d_jkr = jkr.critical_depth().abs();
    let grid = Grid::new(n, 1.0, Boundary::Free).expect("grid");
    let material = ElasticMaterial::new(modulus).expect("modulus");
    let heights = Sphere::new(radius).expect("radius").heights(&grid);
    let params = AdhesiveParams::default();
    let protocol = IndentPulloff {
        start_depth: 0.0,
        max_depth: options.max_depth * d_jkr,
        depth_step: d_jkr / options.steps_per_unit,
        max_retract_steps: 100_000,
        jump_force_threshold: 1e-3 * jkr.critical_force().abs(),
    };
    let (mut setup, mut wall) = (Vec::new(), Vec::new());
    let mut last = None;
    for _ in 0..options.repeats {
        let start = Instant::now();
        let operator = FreeOperator::new(grid, material);
        let mut solver = NormalSolver::Adhesive(Box::new(AdhesiveSolver::new(
            grid,
            modulus,
            vec![gamma; grid.len()],
            params,
        )));
        setup.push(start.elapsed().as_secs_f64());
        let start = Instant::now();
        let mut problem = Problem::new(Box::new(operator), heights.clone()).expect("a valid problem");
        let summary = protocol
            .run(&mut problem, &mut solver, &mut ())
            .expect("load-unload cycle");
        wall.push(start.elapsed().as_secs_f64());
        last = Some(summary);
    }
    let summary = last.expect("one repeat");
    let f_jkr = jkr.critical_force();
    // Pull-off converges at first order from above: |F_min|/|F_JKR| − 1 within ±50 % of
    // 1.4Δ/a_JKR (docs/physics.md §4, the bound of the jkr_pull_off example).
    let mesh_error = 1.4 * delta / a_jkr;
    let pull_off_error = summary.max_adhesive_force / f_jkr.abs() - 1.0;
    assert!(
        (0.5 * mesh_error..=1.5 * mesh_error).contains(&pull_off_error),
        "|F_min|/|F_JKR| − 1 = {pull_off_error:.4}, expected {mesh_error:.4} ± 50 %"
    );
    assert!(!summary.touches_border, "the contact reached the border of the grid");
    format!(
        "{{\"n\": {n}, \"domain\": 1.0, \"a_jkr_over_delta\": {:e}, \"gamma\": {gamma:e}, \"d_jkr\": {d_jkr:e}, \
         \"max_depth\": {:e}, \"depth_step\": {:e}, \"setup_s\": {}, \"wall_s\": {}, \"steps\": {}, \
         \"solves\": {}, \"cg_iterations\": {}, \"operator_applications\": {}, \"pull_off_force\": {:e}, \
         \"f_jkr\": {f_jkr:e}, \"pull_off_over_f_jkr\": {:e}, \"pull_off_depth\": {}, \
         \"relative_tolerance\": {:e}, \"front_tolerance\": {:e}, \"touches_border\": {}}}",
        a_jkr / delta,
        protocol.max_depth,
        protocol.depth_step,
        list(&setup),
        list(&wall),
        summary.steps,
        summary.solves,
        summary.cg_iterations,
        summary.operator_applications,
        -summary.max_adhesive_force,
        -summary.max_adhesive_force / f_jkr,
        summary.pull_off_depth.map_or("null".to_string(), |d| format!("{d:e}")),
        params.relative_tolerance,
        params.front_tolerance,
        summary.touches_border
    )
}

fn main() {
    let options = parse();
    let mut parts = vec![
        "\"code\": \"adhesim\"".to_string(),
        format!("\"threads\": {}", rayon::current_num_threads()),
        format!("\"tolerance\": {:e}", options.tolerance),
        format!(
            "\"hertz_solver\": \"{}\"",
            if options.nested { "nested" } else { "ccg" }
        ),
        format!("\"nested_tolerance\": {:e}", options.nested_tolerance),
    ];
    if options.hertz {
        let entries: Vec<String> = options.sizes.iter().map(|&n| hertz_entry(n, &options)).collect();
        parts.push(format!("\"hertz\": [{}]", entries.join(", ")));
    }
    if options.operator {
        let entries: Vec<String> = options.sizes.iter().map(|&n| operator_entry(n, &options)).collect();
        parts.push(format!("\"operator\": [{}]", entries.join(", ")));
    }
    if options.adhesive {
        parts.push(format!("\"adhesive\": {}", adhesive_entry(&options)));
    }
    println!("{{{}}}", parts.join(", "));
}
