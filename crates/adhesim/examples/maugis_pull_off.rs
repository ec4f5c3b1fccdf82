//! Smooth sphere with a Maugis–Dugdale cohesive zone against Maugis' closed form
//! (docs/validation.md §10): R = E* = 1, γ0 = 1e-4.
//!
//! `cargo run --release -p adhesim --example maugis_pull_off -- λ N [size] [depth step] [max depth] [ccg]`
//!
//! Prints the largest adhesive force under displacement control and its error against
//! Maugis (1992), the operator applications, solves and wall time, and the energy balance
//! ∮F dd against the booked dissipation. The defaults of `size`, `depth step` and
//! `max depth` are those of the validation tests (`maugis_case` below).
use adhesim::analysis::reference::{cohesive_stress_for, MaugisDugdale};
use adhesim::{
    Acceleration, Boundary, CohesiveLaw, CohesiveParams, CohesiveSolver, Dugdale, ElasticMaterial, Exponential,
    FreeOperator, Grid, IndentPulloff, NormalSolver, Problem, Profile, Sphere, StepRecord,
};
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let number = |i: usize| args.get(i).map(|a| a.parse::<f64>().expect("a number"));
    let lambda = number(0).unwrap_or(1.0);
    let n = number(1).unwrap_or(128.0) as usize;
    let (default_size, default_step, default_max) = defaults(lambda);
    let size = number(2).unwrap_or(default_size);
    let step = number(3).unwrap_or(default_step);
    let max_depth = number(4).unwrap_or(default_max);
    let nested = args.get(5).map(|a| a != "ccg").unwrap_or(true);
    let gamma = 1e-4;
    let sigma = cohesive_stress_for(1.0, 1.0, gamma, lambda);
    let model = MaugisDugdale {
        radius: 1.0,
        contact_modulus: 1.0,
        work_of_adhesion: gamma,
        cohesive_stress: sigma,
    };
    let grid = Grid::new(n, size, Boundary::Free).unwrap();
    let material = ElasticMaterial::new(1.0).unwrap();
    let operator = FreeOperator::new(grid, material);
    let heights = Sphere::new(1.0).unwrap().heights(&grid);
    // ADHESIM_EXPONENTIAL_RANGE=ρ runs the exponential law of that range instead.
    let law: Box<dyn CohesiveLaw> = match std::env::var("ADHESIM_EXPONENTIAL_RANGE") {
        Ok(range) => Box::new(Exponential::new(range.parse().expect("ρ"), vec![gamma; grid.len()])),
        Err(_) => Box::new(Dugdale::new(sigma, vec![gamma; grid.len()])),
    };
    let params = CohesiveParams {
        nested,
        max_rounds: std::env::var("ADHESIM_MAX_ROUNDS")
            .map(|v| v.parse().expect("rounds"))
            .unwrap_or(CohesiveParams::default().max_rounds),
        // ADHESIM_ACCELERATION=plain: a smooth law's rounds without Anderson mixing.
        acceleration: match std::env::var("ADHESIM_ACCELERATION").as_deref() {
            Ok("plain") => Acceleration::Plain,
            _ => Acceleration::Anderson,
        },
        ..CohesiveParams::default()
    };
    let mut solver = NormalSolver::Cohesive(Box::new(CohesiveSolver::new(grid, material, law, params)));
    let protocol = IndentPulloff {
        start_depth: 0.0,
        max_depth,
        depth_step: step,
        max_retract_steps: 100_000,
        jump_force_threshold: 0.0,
    };
    let start = Instant::now();
    let mut records: Vec<StepRecord> = Vec::new();
    let mut problem = Problem::new(Box::new(operator), heights).expect("a valid problem");
    let summary = protocol.run(&mut problem, &mut solver, &mut records).unwrap();
    let seconds = start.elapsed().as_secs_f64();
    let mut costly: Vec<&StepRecord> = records.iter().collect();
    costly.sort_by_key(|r| std::cmp::Reverse(r.report.solves));
    for r in costly.iter().take(3) {
        println!(
            "step {} ({}) at depth {:.4e}: {} rounds, {} FFT pairs",
            r.step,
            r.phase.map(|p| p.name()).unwrap_or("-"),
            r.depth,
            r.report.solves,
            r.report.operator_applications
        );
    }
    let expected = model.max_adhesive_force();
    let at = model.at_max_adhesive_force();
    let mut area = 0.5 * records[0].force_normal * records[0].depth;
    for pair in records.windows(2) {
        area += 0.5 * (pair[0].force_normal + pair[1].force_normal) * (pair[1].depth - pair[0].depth);
    }
    println!(
        "λ {lambda}: σ0 {sigma:.4e}, δc {:.4e}, N {n}, Δ {:.4e}, zone at pull-off {:.4e} ({:.1} Δ), a {:.4e} ({:.1} Δ)",
        gamma / sigma,
        grid.dx(),
        at.zone_radius - at.contact_radius,
        (at.zone_radius - at.contact_radius) / grid.dx(),
        at.contact_radius,
        at.contact_radius / grid.dx(),
    );
    println!(
        "max adhesive force {:.6e} vs Maugis {:.6e}: error {:+.3} % (depth {:.4e} vs {:.4e})",
        summary.max_adhesive_force,
        expected,
        100.0 * (summary.max_adhesive_force / expected - 1.0),
        summary.depth_at_max_adhesive_force,
        at.depth,
    );
    // The retraction against Maugis' displacement-controlled branch, from the deepest
    // point to Maugis' largest adhesive force (beyond it the branch steepens towards the
    // vertical tangent, where a shift of the depth changes the force without bound).
    let branch_error = records
        .iter()
        .filter(|r| r.phase == Some(adhesim::Phase::Retract) && r.depth >= at.depth)
        .filter_map(|r| model.force_at_depth(r.depth).map(|f| (r.force_normal - f).abs()))
        .fold(0.0f64, f64::max);
    println!(
        "retraction branch to the largest adhesive force: max |F - F_Maugis(d)| = {:.3} % of it",
        100.0 * branch_error / expected
    );
    println!(
        "steps {}, solves {}, FFT pairs {}, jumps {}, {:.2} s; dissipated {:.4e}, loop area {:.4e}; border {}",
        summary.steps,
        summary.solves,
        summary.operator_applications,
        summary.jumps,
        seconds,
        summary.dissipated_energy,
        area,
        summary.touches_border
    );
}

/// Domain size, depth step and deepest indentation per λ: the domain holds the zone's
/// largest extent (≈ √(2Rδc) + a) with margin, the step resolves the pull-off depth
/// (≈ 2e-3) in about 100 steps.
pub fn defaults(lambda: f64) -> (f64, f64, f64) {
    let gamma: f64 = 1e-4;
    let sigma = cohesive_stress_for(1.0, 1.0, gamma, lambda);
    let reach = (2.0 * gamma / sigma).sqrt() + 0.06;
    (2.4 * reach, 2e-5, 2e-3)
}
