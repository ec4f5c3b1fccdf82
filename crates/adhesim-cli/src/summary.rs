//! `summary.json`: inputs echoed, derived quantities, results, performance, warnings.

use adhesim_scenario::{Counters, Derived, ScenarioFile};
use anyhow::{Context, Result};
use serde::Serialize;
use std::path::Path;

#[derive(Debug, Serialize)]
pub struct Performance {
    pub wall_seconds: f64,
    /// CG iterations summed over all solves.
    pub solver_iterations: usize,
    /// Forward + inverse FFT pairs (elastic operator applications).
    pub fft_pairs: u64,
    pub solves: usize,
    pub steps: usize,
    pub threads: usize,
    /// Averages per quasi-static step.
    pub fft_pairs_per_step: f64,
    pub solves_per_step: f64,
    pub cg_iterations_per_solve: f64,
    /// Solver wall time and steps per phase (approach, retract, roll, slide).
    pub phase_seconds: std::collections::BTreeMap<&'static str, f64>,
    pub phase_steps: std::collections::BTreeMap<&'static str, usize>,
    /// Wall time of writing curve.csv and snapshots during the run.
    pub output_seconds: f64,
}

impl Performance {
    /// Counters of a run, with the per-step averages and the observer's phase timings.
    pub fn new(wall_seconds: f64, counters: &Counters, observer: &crate::output::RunObserver) -> Self {
        let Counters {
            steps,
            solves,
            cg_iterations: solver_iterations,
            operator_applications: fft_pairs,
            ..
        } = *counters;
        let per = |value: f64, count: usize| if count > 0 { value / count as f64 } else { 0.0 };
        Self {
            wall_seconds,
            solver_iterations,
            fft_pairs,
            solves,
            steps,
            threads: rayon::current_num_threads(),
            fft_pairs_per_step: per(fft_pairs as f64, steps),
            solves_per_step: per(solves as f64, steps),
            cg_iterations_per_solve: per(solver_iterations as f64, solves),
            phase_seconds: observer.timings.phase_seconds.clone(),
            phase_steps: observer.timings.phase_steps.clone(),
            output_seconds: observer.timings.output_seconds,
        }
    }
}

/// The whole `summary.json`; `R` is the run's results (`adhesim_scenario::RunResults`).
#[derive(Debug, Serialize)]
pub struct Summary<'a, R> {
    pub adhesim_version: &'static str,
    pub inputs: &'a ScenarioFile,
    pub derived: &'a Derived,
    pub results: R,
    pub performance: Performance,
    pub warnings: Vec<String>,
}

/// Writes `summary.json` atomically, with null for non-finite numbers (JSON has no NaN).
pub fn write<R: Serialize>(path: &Path, summary: &Summary<'_, R>) -> Result<()> {
    let text = serde_json::to_string_pretty(summary).with_context(|| format!("cannot write {}", path.display()))?;
    crate::commands::batch::write_atomically(path, (text + "\n").as_bytes())
}
