//! Mesh-refinement study of the smooth sphere against JKR; prints the markdown table of
//! docs/validation.md.
//!
//! `cargo run --release -p adhesim --example jkr_refinement -- 8 16 32 64 128`
//!
//! Each case: R = E* = 1, γ0 such that a_JKR = 0.05, indentation to 3|d_JKR| and pull-off
//! in steps of |d_JKR|/50 on a free grid holding the largest contact with a 15 % margin.
//! Every row is checked with the tolerances of the `jkr_pull_off` example, all set by the
//! first-order mesh error ε = 1.4Δ/a_JKR (docs/physics.md §4): pull-off error within ±50 %
//! of ε, retraction and approach within 1.5ε·|F_JKR| of JKR, final jump within
//! (3ε + 2 steps)·|d_JKR| of −9^{1/3}|d_JKR|. `cargo test --release -p adhesim --example
//! jkr_refinement` runs the row a_JKR/Δ = 8 (under a second); finer rows take from seconds
//! (32) to a quarter of an hour (128).
use adhesim::analysis::curve::{analyse_indentation, CurveAnalysisOptions};
use adhesim::analysis::reference::Jkr;
use adhesim::{
    AdhesiveParams, AdhesiveSolver, Boundary, ElasticMaterial, FreeOperator, Grid, IndentPulloff, NormalSolver, Phase,
    Problem, Profile, Sphere, StepRecord,
};

fn main() {
    let resolutions: Vec<f64> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("resolutions a_JKR/Δ as numbers"))
        .collect();
    let resolutions = if resolutions.is_empty() {
        vec![8.0, 16.0, 32.0]
    } else {
        resolutions
    };
    println!("| a_JKR/Δ | N | \\|F_min\\|/\\|F_JKR\\| | 1 + 1.4Δ/a_JKR | max retract error (d ≥ 0.5\\|d_JKR\\|) | max approach error (d ≥ 2\\|d_JKR\\|) | final jump d/\\|d_JKR\\| | γ1/γ0 | γ2/γ0 | steps | FFT pairs/step | wall s |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    for resolution in resolutions {
        row(resolution);
    }
}

/// Runs one resolution, prints its table row and checks it.
fn row(resolution: f64) {
    let a_jkr: f64 = 0.05;
    let gamma = a_jkr.powi(3) * 8.0 / (9.0 * std::f64::consts::PI);
    let jkr = Jkr {
        radius: 1.0,
        contact_modulus: 1.0,
        work_of_adhesion: gamma,
    };
    let (d_jkr, f_jkr) = (jkr.critical_depth().abs(), jkr.critical_force().abs());
    let delta = a_jkr / resolution;
    let reach = jkr.radius_at_depth(3.0 * d_jkr).unwrap();
    let n = ((2.3 * reach / delta).ceil() as usize).next_power_of_two().max(16);
    let grid = Grid::new(n, n as f64 * delta, Boundary::Free).unwrap();
    let operator = FreeOperator::new(grid, ElasticMaterial::new(1.0).unwrap());
    let heights = Sphere::new(1.0).unwrap().heights(&grid);
    let mut solver = NormalSolver::Adhesive(Box::new(AdhesiveSolver::new(
        grid,
        1.0,
        vec![gamma; grid.len()],
        AdhesiveParams::default(),
    )));
    let protocol = IndentPulloff {
        start_depth: 0.0,
        max_depth: 3.0 * d_jkr,
        depth_step: d_jkr / 50.0,
        max_retract_steps: 100_000,
        jump_force_threshold: 0.0,
    };
    let mut records: Vec<StepRecord> = Vec::new();
    let start = std::time::Instant::now();
    let mut problem = Problem::new(Box::new(operator), heights).expect("a valid problem");
    let summary = protocol.run(&mut problem, &mut solver, &mut records).unwrap();
    let wall = start.elapsed().as_secs_f64();
    let (mut retract, mut approach) = (0.0f64, 0.0f64);
    for r in &records {
        let d = r.depth / d_jkr;
        if let Some(f) = jkr.force_at_depth(r.depth) {
            let error = (r.force_normal - f).abs() / f_jkr;
            match r.phase {
                Some(Phase::Retract) if d >= 0.5 => retract = retract.max(error),
                Some(Phase::Approach) if d >= 2.0 => approach = approach.max(error),
                _ => {}
            }
        }
    }
    let analysis = analyse_indentation(
        &records,
        &CurveAnalysisOptions {
            radius: 1.0,
            contact_modulus: 1.0,
            work_of_adhesion: gamma,
            min_fit_radius: 0.5 * a_jkr,
        },
    );
    let ratio = |fit: Option<adhesim::analysis::fit::JkrFit>| fit.map_or(f64::NAN, |f| f.work_of_adhesion / gamma);
    println!(
        "| {resolution} | {n} | {:.4} | {:.4} | {retract:.4} | {approach:.4} | {:.3} | {:.4} | {:.4} | {} | {:.1} | {wall:.1} |",
        summary.max_adhesive_force / f_jkr,
        1.0 + 1.4 / resolution,
        summary.pull_off_depth.unwrap_or(f64::NAN) / d_jkr,
        ratio(analysis.gamma_approach),
        ratio(analysis.gamma_pulloff),
        summary.steps,
        summary.operator_applications as f64 / summary.steps as f64,
    );
    let mesh_error = 1.4 / resolution;
    let pull_off_error = summary.max_adhesive_force / f_jkr - 1.0;
    assert!(
        (0.5 * mesh_error..=1.5 * mesh_error).contains(&pull_off_error),
        "a_JKR/Δ = {resolution}: |F_min|/|F_JKR| − 1 = {pull_off_error:.4}, expected {mesh_error:.4} ± 50 %"
    );
    assert!(
        retract < 1.5 * mesh_error,
        "a_JKR/Δ = {resolution}: retraction off by {retract:.4}"
    );
    assert!(
        approach < 1.5 * mesh_error,
        "a_JKR/Δ = {resolution}: approach off by {approach:.4}"
    );
    let final_jump = summary.pull_off_depth.expect("contact was lost") / d_jkr;
    assert!(
        (final_jump + 9f64.cbrt()).abs() < 3.0 * mesh_error + 2.0 / 50.0,
        "a_JKR/Δ = {resolution}: final jump at {final_jump:.3}|d_JKR|"
    );
}

#[cfg(test)]
mod tests {
    #[test]
    fn coarsest_row() {
        super::row(8.0);
    }
}
