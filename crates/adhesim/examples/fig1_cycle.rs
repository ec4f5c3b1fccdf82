//! The paper's Fig. 1 cycle (wavy sphere, α = 1, to 15|d_JKR| and back) at grid size N,
//! with the solver's performance counters: the case of the adhesive step's speed goal
//! (BENCHMARKS.md §How fast is a run of each kind › The paper's Fig. 1 cycle at N = 512).
//!
//! `cargo run --release -p adhesim --example fig1_cycle -- [N] [approach steps] [curve.csv]`
//!
//! Prints wall time, FFT pairs, solves and CG iterations per step and, if a path is
//! given, writes depth, force and contact size per step (to compare solver options).
//! `ADHESIM_RELATIVE_TOLERANCE=1e-9` overrides the CG's relative tolerance;
//! `ADHESIM_REFERENCE_RULE=1` runs the reference rule (every fixed-set solve converged,
//! no certified early stops; docs/fast-step.md) to compare work and results;
//! `ADHESIM_PREDICTED_GROWTH=1` turns predicted-subset growth on, `0` off (default: the
//! solver's `Auto`, on from 512², docs/fast-step.md §3); `ADHESIM_RING_LAYERS=2` attaches
//! two layers of elements per trial ring (`AdhesiveParams::trial_ring_layers`) and
//! `ADHESIM_ATTACHMENT=penetration` attaches by penetration only
//! (`Attachment::PenetrationOnly`): different rules, whose physics cost is measured in
//! BENCHMARKS.md §What did not pay.
use adhesim::analysis::curve::{analyse_indentation, CurveAnalysisOptions};
use adhesim::analysis::reference::Jkr;
use adhesim::solver::{Attachment, PredictedGrowth};
use adhesim::Phase;
use adhesim::{
    AdhesiveParams, AdhesiveSolver, Boundary, ElasticMaterial, FreeOperator, Grid, IndentPulloff, NormalSolver,
    Problem, Profile, StepRecord, WavySphere,
};
use std::io::Write;

/// CPU time (user + system) of this process so far, from /proc (0 where unavailable).
fn process_cpu_seconds() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return 0.0;
    };
    // Fields after the command name (which ends with ')'): utime and stime are 14 and 15.
    let fields: Vec<&str> = stat
        .rsplit_once(')')
        .map_or(vec![], |(_, rest)| rest.split_whitespace().collect());
    let ticks: f64 = [11, 12]
        .iter()
        .filter_map(|&i| fields.get(i)?.parse::<f64>().ok())
        .sum();
    ticks / 100.0
}

fn main() {
    let mut args = std::env::args().skip(1);
    let n: usize = args.next().map_or(128, |a| a.parse().expect("N as a number"));
    let steps: usize = args.next().map_or(300, |a| a.parse().expect("steps as a number"));
    let curve_path = args.next();
    let work_of_adhesion = 6.168_502_750_680_85e-4;
    let grid = Grid::new(n, 0.8, Boundary::Free).expect("grid");
    let jkr = Jkr {
        radius: 1.0,
        contact_modulus: 1.0,
        work_of_adhesion,
    };
    let heights = WavySphere::new(1.0, 0.0025, 0.05, 0.0).expect("profile").heights(&grid);
    let start_depth = heights.iter().cloned().fold(f64::INFINITY, f64::min);
    let max_depth = 15.0 * jkr.critical_depth().abs();
    let operator = FreeOperator::new(grid, ElasticMaterial::new(1.0).expect("modulus"));
    let mut solver = NormalSolver::Adhesive(Box::new(AdhesiveSolver::new(
        grid,
        1.0,
        vec![work_of_adhesion; grid.len()],
        AdhesiveParams {
            relative_tolerance: std::env::var("ADHESIM_RELATIVE_TOLERANCE")
                .map_or(AdhesiveParams::default().relative_tolerance, |v| {
                    v.parse().expect("ADHESIM_RELATIVE_TOLERANCE as a number")
                }),
            reference_rule: std::env::var("ADHESIM_REFERENCE_RULE").is_ok_and(|v| v == "1"),
            predicted_growth: match std::env::var("ADHESIM_PREDICTED_GROWTH").as_deref() {
                Ok("1") => PredictedGrowth::On,
                Ok("0") => PredictedGrowth::Off,
                _ => PredictedGrowth::Auto,
            },
            attachment: match std::env::var("ADHESIM_ATTACHMENT").as_deref() {
                Ok("penetration") => Attachment::PenetrationOnly,
                _ => Attachment::Trial,
            },
            trial_ring_layers: std::env::var("ADHESIM_RING_LAYERS")
                .map_or(AdhesiveParams::default().trial_ring_layers, |v| {
                    v.parse().expect("ADHESIM_RING_LAYERS as a whole number ≥ 1")
                }),
            ..AdhesiveParams::default()
        },
    )));
    let protocol = IndentPulloff {
        start_depth,
        max_depth,
        depth_step: (max_depth - start_depth) / steps as f64,
        max_retract_steps: 100_000,
        jump_force_threshold: 0.0,
    };
    let mut records: Vec<StepRecord> = Vec::new();
    let cpu_start = process_cpu_seconds();
    let start = std::time::Instant::now();
    let mut problem = Problem::new(Box::new(operator), heights).expect("a valid problem");
    let summary = protocol.run(&mut problem, &mut solver, &mut records).expect("cycle");
    let wall = start.elapsed().as_secs_f64();
    let cpu = process_cpu_seconds() - cpu_start;
    let per_step = |total: f64| total / summary.steps as f64;
    println!(
        "N = {n}: {} steps in {wall:.1} s ({:.3} s/step), {:.1} FFT pairs/step, {:.2} solves/step, {:.2} CG iterations/solve, pull-off force {:.4} |F_JKR|",
        summary.steps,
        wall / summary.steps as f64,
        per_step(summary.operator_applications as f64),
        per_step(summary.solves as f64),
        summary.cg_iterations as f64 / summary.solves as f64,
        summary.max_adhesive_force / jkr.critical_force().abs()
    );
    // γ1, γ2 as `adhesim run` reports them (fits over a ≥ max(a_JKR/2, 2λ)).
    let analysis = analyse_indentation(
        &records,
        &CurveAnalysisOptions {
            radius: 1.0,
            contact_modulus: 1.0,
            work_of_adhesion,
            min_fit_radius: (0.5 * jkr.critical_radius()).max(2.0 * 0.05),
        },
    );
    let ratio =
        |fit: Option<adhesim::analysis::fit::JkrFit>| fit.map_or(f64::NAN, |f| f.work_of_adhesion / work_of_adhesion);
    println!(
        "  γ1/γ0 {:.4}, γ2/γ0 {:.4}",
        ratio(analysis.gamma_approach),
        ratio(analysis.gamma_pulloff)
    );
    print_phases(&records);
    if let NormalSolver::Adhesive(adhesive) = &solver {
        let (predicted, fallbacks) = adhesive.predicted_growth();
        println!(
            "  certified early stops: {} of {} solves; tie refinements {} ({} unresolved); rings grown through a predicted subset: {predicted} ({fallbacks} fell back to the exact peel), local replays {:.1} ms/step; CPU {cpu:.1} s ({:.2} cores)",
            adhesive.certified_stops(),
            summary.solves,
            adhesive.tie_refinements(),
            adhesive.unresolved_ties(),
            1e3 * adhesive.prediction_seconds() / summary.steps as f64,
            cpu / wall
        );
    }
    if let Some(path) = curve_path {
        write_curve(&path, &records);
    }
}

/// Counters per step of the approach and of the retraction apart.
fn print_phases(records: &[StepRecord]) {
    let approach = records.iter().filter(|r| r.phase == Some(Phase::Approach)).count();
    for (label, part) in [("approach", &records[..approach]), ("retraction", &records[approach..])] {
        let steps = part.len().max(1) as f64;
        let fft: u64 = part.iter().map(|r| r.report.operator_applications).sum();
        let solves: usize = part.iter().map(|r| r.report.solves).sum();
        let cg: usize = part.iter().map(|r| r.report.cg_iterations).sum();
        let rings: usize = part.iter().map(|r| r.report.attachment_rounds).sum();
        let attached: usize = part.iter().map(|r| r.report.attached).sum();
        println!(
            "  {label}: {} steps, {:.1} FFT pairs/step, {:.2} solves/step, {:.2} CG iterations/solve, {:.2} attachment rounds/step, {:.1} elements attached/step",
            part.len(),
            fft as f64 / steps,
            solves as f64 / steps,
            cg as f64 / solves.max(1) as f64,
            rings as f64 / steps,
            attached as f64 / steps
        );
    }
}

/// Depth, force, contact size and counters per step, to compare solver options.
fn write_curve(path: &str, records: &[StepRecord]) {
    let mut file = std::io::BufWriter::new(std::fs::File::create(path).expect("curve file"));
    writeln!(
        file,
        "step,depth,force_normal,contact_elements,radius,solves,cg_iterations,fft_pairs,attached,detached,attachment_rounds"
    )
    .expect("write");
    for r in records {
        writeln!(
            file,
            "{},{:e},{:e},{},{:e},{},{},{},{},{},{}",
            r.step,
            r.depth,
            r.force_normal,
            r.contact_elements,
            r.radius,
            r.report.solves,
            r.report.cg_iterations,
            r.report.operator_applications,
            r.report.attached,
            r.report.detached,
            r.report.attachment_rounds
        )
        .expect("write");
    }
}
