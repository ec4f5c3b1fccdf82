//! `adhesim run` for protocol kinds roll / slide / translate (docs/friction.md): runs the
//! library's [`Translation`](adhesim::Translation), writes `curve.csv` and snapshots
//! through the run observer, the force–distance figure (Fig. 6a), a strip of consecutive
//! contact maps (Figs. 6b, 9) and `summary.json` with [`TranslationResults`].

use crate::scenario::{Scenario, TranslationSetup};
use crate::summary::{self, TranslationInputs, TranslationResults};
use crate::{output, tangential_plots, RunOptions};
use adhesim::{
    AdhesiveParams, AdhesiveSolver, HalfSpace, NormalSolver, Profile, ProtocolError, StepRecord, TranslationSummary,
};
use anyhow::{anyhow, Result};
use std::path::Path;
use std::time::Instant;

/// Consecutive steps shown in the snapshot strip by default.
const STRIP_FRAMES: usize = 4;

/// The normal solver of a scenario (adhesive where γ0 > 0).
pub fn normal_solver(scenario: &Scenario) -> NormalSolver {
    if scenario.gamma0 > 0.0 {
        NormalSolver::Adhesive(Box::new(AdhesiveSolver::new(
            scenario.grid,
            scenario.material.contact_modulus(),
            scenario.gamma.clone(),
            AdhesiveParams::default(),
        )))
    } else {
        adhesim::protocol::non_adhesive_solver(scenario.grid, scenario.material)
    }
}

/// Runs a translation without writing anything (for studies): the library summary, the
/// step records and the analysed results.
pub fn run_in_memory(scenario: &Scenario) -> Result<(TranslationSummary, Vec<StepRecord>, TranslationResults)> {
    let setup = setup(scenario)?;
    let mut operator = HalfSpace::new(scenario.grid, scenario.material);
    let mut solver = normal_solver(scenario);
    let mut records: Vec<StepRecord> = Vec::new();
    let summary = setup
        .protocol
        .run(&mut operator, &setup.contact, &mut solver, &mut records)
        .map_err(|e| anyhow!(e))?;
    let results = analyse(scenario, &setup, &summary, &records);
    Ok((summary, records, results))
}

fn setup(scenario: &Scenario) -> Result<TranslationSetup> {
    scenario
        .translation
        .ok_or_else(|| anyhow!("protocol.kind = \"indent_pulloff\" is not a translation"))
}

fn analyse(
    scenario: &Scenario,
    setup: &TranslationSetup,
    summary: &TranslationSummary,
    records: &[StepRecord],
) -> TranslationResults {
    TranslationResults::new(
        summary,
        &TranslationInputs {
            kinematics: setup.contact.kinematics(),
            records,
            stationary_from: setup.protocol.stationary_from,
            distance: setup.protocol.distance,
            jkr: scenario.jkr,
            work_of_adhesion: scenario.gamma0,
            radius: scenario.indenter.radius_of_curvature().unwrap_or(f64::NAN),
            contact_modulus: scenario.material.contact_modulus(),
            gammas: setup.gammas,
            tau0: setup.tau0,
        },
    )
}

/// `adhesim run` of a roll / slide / translate scenario into `out` (which exists).
pub fn run(scenario: Scenario, out: &Path, options: &RunOptions) -> Result<()> {
    let setup = setup(&scenario)?;
    let start = Instant::now();
    let grid = scenario.grid;
    let mut operator = HalfSpace::new(grid, scenario.material);
    let mut solver = normal_solver(&scenario);
    let protocol = setup.protocol;
    let forward_end = protocol.approach_steps + protocol.steps;
    let o = &scenario.file.output;
    let mut chosen: std::collections::BTreeSet<usize> = o.snapshot_steps.iter().map(|&s| s as usize).collect();
    if chosen.is_empty() && o.snapshot_every == 0 {
        // The end of the forward stroke.
        chosen.insert(forward_end - 1);
    }
    let strip: Vec<usize> = if o.snapshot_steps.is_empty() {
        // Consecutive steps in the middle of the stationary part.
        let first = protocol.approach_steps
            + ((protocol.stationary_from + 0.5 * (1.0 - protocol.stationary_from)) * protocol.steps as f64) as usize;
        (first..first + STRIP_FRAMES).filter(|&s| s < forward_end).collect()
    } else {
        o.snapshot_steps.iter().map(|&s| s as usize).take(8).collect()
    };
    let plan = output::SnapshotPlan {
        chosen,
        every: o.snapshot_every as usize,
        jump_elements: o.jump_snapshot_elements as usize,
        max_jump_snapshots: o.max_snapshots as usize,
        max_depth_step: protocol.approach_steps - 1,
    };
    let expected = forward_end + if protocol.return_stroke { protocol.steps } else { 0 };
    let mut observer = output::RunObserver::new(out, grid, scenario.jkr, plan, expected, options.quiet)?;
    observer.capture(strip.iter().copied());
    let outcome = protocol.run(&mut operator, &setup.contact, &mut solver, &mut observer);
    observer.finish()?;
    let library_summary = match outcome {
        Ok(summary) => summary,
        Err(ProtocolError::Interrupted(step)) => {
            let cause = observer.error.take().unwrap_or_else(|| anyhow!("interrupted"));
            return Err(cause.context(format!("run stopped at step {step}")));
        }
        Err(error) => {
            return Err(anyhow!(error).context(format!(
                "run failed; {} holds the steps done",
                out.join("curve.csv").display()
            )))
        }
    };
    let results = analyse(&scenario, &setup, &library_summary, &observer.records);
    let plots = out.join("plots");
    let stationary_start = protocol.stationary_from * protocol.distance;
    let charts = tangential_plots::force_distance(
        &observer.records,
        scenario.jkr,
        setup.wavelength,
        (
            library_summary.mean_tangential_force,
            library_summary.mean_tangential_force_work,
        ),
        stationary_start,
    );
    let mut plot_files = tangential_plots::write_panels(&plots, "force_distance", &charts)?;
    if !observer.captured.is_empty() {
        let frames: Vec<(Vec<bool>, Vec<bool>, f64)> = observer
            .captured
            .iter()
            .map(|(step, contact, previous)| {
                let offset = observer.records.get(*step).map_or(0.0, |r| r.offset);
                (contact.clone(), previous.clone(), offset)
            })
            .collect();
        tangential_plots::write_snapshot_strip(&plots.join("contact_snapshots.png"), &grid, &frames)?;
        plot_files.push("plots/contact_snapshots.png".into());
    }
    let wall_seconds = start.elapsed().as_secs_f64();
    let mut warnings = observer.warnings.clone();
    if library_summary.touches_border && warnings.is_empty() {
        warnings.push("contact reached the domain border: the domain is too small, enlarge grid.size".into());
    }
    let moving_steps = library_summary.steps - protocol.approach_steps;
    let summary = summary::Summary {
        adhesim_version: env!("CARGO_PKG_VERSION"),
        inputs: &scenario.file,
        derived: &scenario.derived,
        results: results.clone(),
        performance: summary::Performance::new(
            wall_seconds,
            library_summary.cg_iterations,
            library_summary.operator_applications,
            library_summary.solves,
            library_summary.steps,
            &observer,
        ),
        warnings,
    };
    summary::write(&out.join("summary.json"), &summary)?;
    if !options.quiet {
        println!(
            "adhesim: {} {} steps ({} moving) in {:.1} s",
            setup.kind.name(),
            library_summary.steps,
            moving_steps,
            wall_seconds
        );
        let force = scenario.jkr.map_or(1.0, |j| j.critical_force().abs());
        let unit = if scenario.jkr.is_some() { " |F_JKR|" } else { "" };
        println!(
            "  mean F_T = {:.4}{unit} (per step), {:.4}{unit} (work), fluctuation {:.4}{unit}, mean F_N = {:.4}{unit}",
            library_summary.mean_tangential_force / force,
            library_summary.mean_tangential_force_work / force,
            library_summary.tangential_force_fluctuation / force,
            library_summary.mean_normal_force / force,
        );
        if let (Some(p), Some(r)) = (results.eq12_prediction, results.eq12_ratio) {
            println!("  Eq. 12: 2a(γ2−γ1) = {:.4}{unit}, F_T / 2a(γ2−γ1) = {r:.3}", p / force);
        }
        println!(
            "  half-width a = {:.4e}, compactness A/(πa²) = {:.3}, jumps = {}",
            results.contact_half_width, results.compactness, results.jumps
        );
        println!("outputs in {}/", out.display());
        println!("  summary.json, curve.csv");
        println!("  {}", plot_files.join(", "));
    }
    Ok(())
}
