//! Smooth sphere against JKR: indentation and pull-off on a free half-space.
//!
//! `cargo run --release -p adhesim --example jkr_pull_off -- [a_JKR/Δ] [d_max/|d_JKR|] [steps per |d_JKR|]`
//!
//! Checks what it prints, with tolerances set by the first-order mesh error ε = 1.4Δ/a_JKR
//! of the pull-off force (docs/physics.md §4; docs/validation.md §3 measures it):
//! |F_min|/|F_JKR| − 1 within ±50 % of ε; the JKR force along the retraction
//! (d ≥ 0.5|d_JKR|) and approach (d ≥ 2|d_JKR|) within 1.5ε·|F_JKR| (measured ≤ 0.9ε from
//! a_JKR/Δ = 8 to 128); the final jump within (3ε + 2 depth steps)·|d_JKR| of
//! −9^{1/3}|d_JKR| (measured ≤ 2.7ε; the jump is seen at step granularity); and the energy
//! balance ∮F dd = Σ released energy to 1e-4 relative, the force
//! being linear in d on each fixed-set stretch so that the trapezoid rule with the force
//! before each change is exact up to the CG tolerance (measured 3e-6 at a_JKR/Δ = 16).
//! `cargo test --release -p adhesim --example jkr_pull_off` runs it at a_JKR/Δ = 8 (about
//! a second). `ADHESIM_RING_LAYERS=2` attaches two layers of elements per trial ring
//! (`AdhesiveParams::trial_ring_layers`; BENCHMARKS.md §What did not pay measures what it
//! changes).
#![allow(clippy::needless_range_loop)]
use adhesim::analysis::reference::Jkr;
use adhesim::{
    AdhesiveParams, AdhesiveSolver, Boundary, ElasticMaterial, FreeOperator, Grid, IndentPulloff, NormalSolver,
    Problem, Profile, ProtocolSummary, Sphere, StepRecord,
};

fn main() {
    let args: Vec<f64> = std::env::args().skip(1).map(|a| a.parse().expect("numbers")).collect();
    let resolution = args.first().copied().unwrap_or(16.0);
    let max_depth_jkr = args.get(1).copied().unwrap_or(3.0);
    let steps_per_unit = args.get(2).copied().unwrap_or(50.0);
    run(resolution, max_depth_jkr, steps_per_unit);
}

/// Indents to `max_depth_jkr`·|d_JKR| and pulls off at a_JKR/Δ = `resolution`; prints and
/// checks the curve against JKR.
fn run(resolution: f64, max_depth_jkr: f64, steps_per_unit: f64) {
    let (radius, modulus) = (1.0, 1.0);
    // choose γ so that a_JKR = 0.05 R
    let a_jkr: f64 = 0.05;
    let gamma = a_jkr.powi(3) * 8.0 * modulus / (9.0 * std::f64::consts::PI * radius * radius);
    let jkr = Jkr {
        radius,
        contact_modulus: modulus,
        work_of_adhesion: gamma,
    };
    let delta = a_jkr / resolution;
    let reach = jkr.radius_at_depth(max_depth_jkr * jkr.critical_depth().abs()).unwrap();
    let n = ((2.3 * reach / delta).ceil() as usize).next_power_of_two().max(16);
    let grid = Grid::new(n, n as f64 * delta, Boundary::Free).unwrap();
    let material = ElasticMaterial::new(modulus).unwrap();
    let operator = FreeOperator::new(grid, material);
    let heights = Sphere::new(radius).unwrap().heights(&grid);
    let d_jkr = jkr.critical_depth().abs();
    let mut solver = NormalSolver::Adhesive(Box::new(AdhesiveSolver::new(
        grid,
        modulus,
        vec![gamma; grid.len()],
        AdhesiveParams {
            relative_tolerance: std::env::var("ADHESIM_RTOL")
                .map(|v| v.parse().unwrap())
                .unwrap_or(1e-9),
            carry_bans_when_retracting: std::env::var_os("ADHESIM_EXACT_RINGS").is_none(),
            trial_ring_layers: std::env::var("ADHESIM_RING_LAYERS")
                .map_or(AdhesiveParams::default().trial_ring_layers, |v| {
                    v.parse().expect("ADHESIM_RING_LAYERS as a whole number ≥ 1")
                }),
            ..AdhesiveParams::default()
        },
    )));
    let protocol = IndentPulloff {
        start_depth: 0.0,
        max_depth: max_depth_jkr * d_jkr,
        depth_step: d_jkr / steps_per_unit,
        max_retract_steps: 100_000,
        jump_force_threshold: 1e-3 * jkr.critical_force().abs(),
    };
    let mut records: Vec<StepRecord> = Vec::new();
    let start = std::time::Instant::now();
    let mut problem = Problem::new(Box::new(operator), heights).expect("a valid problem");
    let summary = protocol.run(&mut problem, &mut solver, &mut records).unwrap();
    let f_jkr = jkr.critical_force().abs();
    println!(
        "N = {n}, a_JKR/Δ = {resolution}, steps = {}, wall {:.2} s",
        summary.steps,
        start.elapsed().as_secs_f64()
    );
    println!(
        "|F_min|/|F_JKR| = {:.4} at d/|d_JKR| = {:.3}; final jump after d/|d_JKR| = {:.3}; dissipated = {:.4e}; jumps = {}",
        summary.max_adhesive_force / f_jkr,
        summary.depth_at_max_adhesive_force / d_jkr,
        summary.pull_off_depth.unwrap_or(f64::NAN) / d_jkr,
        summary.dissipated_energy,
        summary.jumps
    );
    println!(
        "solves/step = {:.1}, CG iterations/step = {:.1}, FFT pairs/step = {:.1}",
        summary.solves as f64 / summary.steps as f64,
        summary.cg_iterations as f64 / summary.steps as f64,
        summary.operator_applications as f64 / summary.steps as f64
    );
    if std::env::var_os("ADHESIM_VERBOSE").is_some() {
        for r in records.iter().step_by(10) {
            println!(
                "{:?} d={:.3} solves={} cg={} att={} det={}",
                r.phase.unwrap(),
                r.depth / d_jkr,
                r.report.solves,
                r.report.cg_iterations,
                r.report.attached,
                r.report.detached
            );
        }
    }
    check_against_jkr(&records, &summary, &jkr, resolution, max_depth_jkr, steps_per_unit);
}

/// Forces against JKR on both branches, the loop area against the released energy, and the
/// pull-off and final jump against JKR within the first-order mesh error 1.4Δ/a_JKR ± 50 %.
fn check_against_jkr(
    records: &[StepRecord],
    summary: &ProtocolSummary,
    jkr: &Jkr,
    resolution: f64,
    max_depth_jkr: f64,
    steps_per_unit: f64,
) {
    let (d_jkr, f_jkr) = (jkr.critical_depth().abs(), jkr.critical_force().abs());
    let (mut worst_retract, mut worst_approach) = (0.0f64, 0.0f64);
    for r in records {
        let d = r.depth / d_jkr;
        if let Some(f) = jkr.force_at_depth(r.depth) {
            let error = (r.force_normal - f).abs() / f_jkr;
            match r.phase {
                Some(adhesim::Phase::Retract) if d >= 0.5 => worst_retract = worst_retract.max(error),
                Some(adhesim::Phase::Approach) if d >= 2.0 => worst_approach = worst_approach.max(error),
                _ => {}
            }
        }
    }
    println!("max |F − F_JKR|/|F_JKR|: retract (d ≥ 0.5) {worst_retract:.4}, approach (d ≥ 2) {worst_approach:.4}");
    let loop_area: f64 = records
        .windows(2)
        .map(|w| 0.5 * (w[0].force_normal + w[1].force_normal) * (w[1].depth - w[0].depth))
        .sum::<f64>()
        + 0.5 * records[0].force_normal * (records[0].depth - 0.0);
    let exact: f64 = records
        .windows(2)
        .map(|w| 0.5 * (w[0].force_normal + w[1].report.force_before_change) * (w[1].depth - w[0].depth))
        .sum::<f64>()
        + 0.5 * records[0].report.force_before_change * records[0].depth;
    let negative: f64 = records.iter().map(|r| r.report.dissipated_energy.min(0.0)).sum();
    let mut approach_signed = 0.0;
    for r in records {
        if let (Some(adhesim::Phase::Approach), Some(f)) = (r.phase, jkr.force_at_depth(r.depth)) {
            if r.depth / d_jkr >= 2.0 {
                approach_signed += (r.force_normal - f) / f_jkr;
            }
        }
    }
    println!(
        "loop area {loop_area:.5e} (exact trapezoid {exact:.5e}) vs dissipated {:.5e} (negative parts {negative:.3e}); mean approach F−F_JKR {approach_signed:.3}",
        summary.dissipated_energy
    );
    let mesh_error = 1.4 / resolution;
    let pull_off_error = summary.max_adhesive_force / f_jkr - 1.0;
    assert!(
        (0.5 * mesh_error..=1.5 * mesh_error).contains(&pull_off_error),
        "|F_min|/|F_JKR| − 1 = {pull_off_error:.4}, expected 1.4Δ/a_JKR = {mesh_error:.4} ± 50 %"
    );
    assert!(
        worst_retract < 1.5 * mesh_error,
        "retraction off JKR by {worst_retract:.4}|F_JKR|"
    );
    if max_depth_jkr >= 2.0 {
        assert!(
            worst_approach < 1.5 * mesh_error,
            "approach off JKR by {worst_approach:.4}|F_JKR|"
        );
    }
    let final_jump = summary.pull_off_depth.expect("contact was lost") / d_jkr;
    assert!(
        (final_jump + 9f64.cbrt()).abs() < 3.0 * mesh_error + 2.0 / steps_per_unit,
        "final jump at {final_jump:.3}|d_JKR|, JKR −2.080"
    );
    let balance = exact / summary.dissipated_energy - 1.0;
    assert!(balance.abs() < 1e-4, "∮F dd vs released energy: {balance:.2e}");
}

#[cfg(test)]
mod tests {
    #[test]
    fn jkr_cycle_at_eight_elements_per_contact_radius() {
        super::run(8.0, 3.0, 50.0);
    }
}
