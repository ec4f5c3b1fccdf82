//! The content of `summary.json` (docs/output.md): inputs echoed, derived quantities,
//! results, performance, warnings. Built here once, so that the command line and the
//! Python package report the same run the same way; the caller writes the text.

use crate::model::{Derived, ScenarioFile, ValidScenario};
use crate::pipeline::RunOutcome;
use crate::results::RunResults;
use adhesim::{Phase, RunCounters, StepRecord};
use anyhow::{Context, Result};
use serde::Serialize;
use std::collections::BTreeMap;

/// Counters and wall times of a run (the only part of `summary.json` that differs between
/// two runs of the same scenario).
#[derive(Debug, Clone, Serialize)]
pub struct Performance {
    pub wall_seconds: f64,
    /// CG iterations summed over all solves.
    pub solver_iterations: usize,
    /// Forward + inverse FFT pairs (elastic operator applications).
    pub fft_pairs: u64,
    /// Of those, the adhesive CG's pairs on contact windows (transforms of twice a
    /// window's side instead of twice the grid's; docs/physics.md §3.2).
    pub window_fft_pairs: u64,
    /// The CG preconditioner's applications, not in `fft_pairs`: unpadded transform pairs
    /// of the solved grid's own size (the whole grid, a window or a nested level).
    pub preconditioner_fft_pairs: u64,
    pub solves: usize,
    pub steps: usize,
    pub threads: usize,
    /// Averages per quasi-static step.
    pub fft_pairs_per_step: f64,
    pub solves_per_step: f64,
    pub cg_iterations_per_solve: f64,
    /// Solver wall time and steps per phase (approach, retract, roll, slide).
    pub phase_seconds: BTreeMap<&'static str, f64>,
    pub phase_steps: BTreeMap<&'static str, usize>,
    /// Wall time of writing outputs (curve rows, snapshots) during the run.
    pub output_seconds: f64,
}

/// Solver and output wall time per phase, as an observer measured them.
#[derive(Debug, Clone, Default)]
pub struct PhaseTimes {
    /// Solver wall time per phase.
    pub phase_seconds: BTreeMap<&'static str, f64>,
    /// Steps per phase.
    pub phase_steps: BTreeMap<&'static str, usize>,
    /// Wall time spent on the outputs of the steps.
    pub output_seconds: f64,
}

impl Performance {
    /// Counters of a run, with the per-step averages, the threads of rayon's pool and
    /// the observer's phase timings.
    pub fn new(wall_seconds: f64, counters: &RunCounters, times: PhaseTimes) -> Self {
        let RunCounters {
            steps,
            solves,
            cg_iterations: solver_iterations,
            operator_applications: fft_pairs,
            window_applications: window_fft_pairs,
            preconditioner_applications: preconditioner_fft_pairs,
            ..
        } = *counters;
        let per = |value: f64, count: usize| if count > 0 { value / count as f64 } else { 0.0 };
        Self {
            wall_seconds,
            solver_iterations,
            fft_pairs,
            window_fft_pairs,
            preconditioner_fft_pairs,
            solves,
            steps,
            threads: rayon::current_num_threads(),
            fft_pairs_per_step: per(fft_pairs as f64, steps),
            solves_per_step: per(solves as f64, steps),
            cg_iterations_per_solve: per(solver_iterations as f64, solves),
            phase_seconds: times.phase_seconds,
            phase_steps: times.phase_steps,
            output_seconds: times.output_seconds,
        }
    }
}

/// The whole `summary.json`.
#[derive(Debug, Serialize)]
pub struct Summary<'a> {
    pub adhesim_version: &'static str,
    pub inputs: &'a ScenarioFile,
    pub derived: &'a Derived,
    pub results: &'a RunResults,
    pub performance: Performance,
    pub warnings: Vec<String>,
}

impl<'a> Summary<'a> {
    /// The summary of a finished run. `run_warnings` are those an observer raised during
    /// the run ([`border_warning`]); the scenario's resolution warnings come first.
    pub fn new(
        scenario: &'a ValidScenario,
        outcome: &'a RunOutcome,
        performance: Performance,
        run_warnings: &[String],
    ) -> Self {
        let mut warnings = scenario.warnings.clone();
        warnings.extend(run_warnings.iter().cloned());
        if outcome.report.counters().touches_border && run_warnings.is_empty() {
            warnings.push("contact reached the domain border: the domain is too small, enlarge grid.size".into());
        }
        warnings.extend(lost_contact_warning(&outcome.records));
        warnings.extend(crate::guards::unresolved_contact_warning(&outcome.records));
        warnings.extend(crate::cohesive::dugdale_pinning_estimate(scenario, &outcome.results));
        Self {
            adhesim_version: env!("CARGO_PKG_VERSION"),
            inputs: &scenario.file,
            derived: &scenario.derived,
            results: &outcome.results,
            performance,
            warnings,
        }
    }

    /// The text of `summary.json`: pretty JSON with a final newline, null for
    /// non-finite numbers (JSON has no NaN).
    pub fn to_json(&self) -> Result<String> {
        let text = serde_json::to_string_pretty(self).context("cannot serialise summary.json")?;
        Ok(text + "\n")
    }
}

/// The warning of the first step whose contact reached the border of a free grid.
pub fn border_warning(step: usize, depth: f64) -> String {
    format!(
        "contact reached the domain border at step {step} (d = {depth:.6e}): the domain is too small, enlarge grid.size"
    )
}

/// A roll, slide or translation whose contact is lost during the travel (it left the grid
/// or came off): the zero forces of those steps are not those of a rolling contact, and
/// the means of `summary.json` include them (docs/reliability.md).
pub fn lost_contact_warning(records: &[StepRecord]) -> Option<String> {
    let travel: Vec<&StepRecord> = records
        .iter()
        .filter(|r| matches!(r.phase, Some(Phase::Roll | Phase::Slide)))
        .collect();
    let lost: Vec<&&StepRecord> = travel.iter().filter(|r| r.contact_elements == 0).collect();
    let first = lost.first()?;
    Some(format!(
        "the contact was lost in {} of {} travel steps (first at step {}, X = {:.4e}): those steps have zero force and the means in summary.json include them; lower protocol.distance, raise protocol.depth, or enlarge grid.size",
        lost.len(),
        travel.len(),
        first.step,
        first.offset
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn travel_step(step: usize, offset: f64, contact_elements: usize) -> StepRecord {
        StepRecord {
            step,
            phase: Some(Phase::Roll),
            offset,
            contact_elements,
            ..StepRecord::default()
        }
    }

    /// First robustness audit (docs/reliability.md): a roll whose contact left the grid exited 0 with zero force, no warning.
    #[test]
    fn a_travel_that_loses_the_contact_is_reported() {
        let approach = StepRecord {
            phase: Some(Phase::Approach),
            contact_elements: 0,
            ..StepRecord::default()
        };
        let mut records = vec![approach, travel_step(1, 0.1, 12), travel_step(2, 0.2, 3)];
        assert_eq!(lost_contact_warning(&records), None);
        records.extend([travel_step(3, 0.3, 0), travel_step(4, 0.4, 0)]);
        let warning = lost_contact_warning(&records).unwrap();
        assert!(
            warning.starts_with("the contact was lost in 2 of 4 travel steps (first at step 3, X = 3.0000e-1)"),
            "{warning}"
        );
    }
}
