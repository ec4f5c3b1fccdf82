//! `summary.json`: inputs echoed, derived quantities, results, performance, warnings.

use crate::scenario::{Derived, ScenarioFile};
use adhesim::ProtocolSummary;
use anyhow::{Context, Result};
use serde::Serialize;
use std::path::Path;

/// Results of an indentation / pull-off run. Entries that do not apply (fits not yet
/// available, tangential quantities of a normal protocol) are null.
#[derive(Debug, Serialize)]
pub struct Results {
    pub max_adhesive_force: f64,
    pub pull_off_depth: Option<f64>,
    pub depth_at_max_adhesive_force: Option<f64>,
    pub gamma_approach: Option<f64>,
    pub gamma_pulloff: Option<f64>,
    pub boundary_friction: Option<f64>,
    pub dissipated_energy: f64,
    pub jumps: usize,
    pub mean_tangential_force: Option<f64>,
    pub border_contact: bool,
    pub largest_contact_elements: usize,
    pub largest_contact_step: usize,
}

impl Results {
    pub fn from_protocol(summary: &ProtocolSummary) -> Self {
        Self {
            max_adhesive_force: summary.max_adhesive_force,
            pull_off_depth: summary.pull_off_depth,
            depth_at_max_adhesive_force: (summary.max_adhesive_force > 0.0)
                .then_some(summary.depth_at_max_adhesive_force),
            gamma_approach: None,
            gamma_pulloff: None,
            boundary_friction: None,
            dissipated_energy: summary.dissipated_energy,
            jumps: summary.jumps,
            mean_tangential_force: None,
            border_contact: summary.touches_border,
            largest_contact_elements: summary.largest_contact.0,
            largest_contact_step: summary.largest_contact.1,
        }
    }
}

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
}

#[derive(Debug, Serialize)]
pub struct Summary<'a> {
    pub adhesim_version: &'static str,
    pub inputs: &'a ScenarioFile,
    pub derived: &'a Derived,
    pub results: Results,
    pub performance: Performance,
    pub warnings: Vec<String>,
}

/// Writes `summary.json` with null for non-finite numbers (JSON has no NaN).
pub fn write(path: &Path, summary: &Summary<'_>) -> Result<()> {
    let text = serde_json::to_string_pretty(summary)?;
    std::fs::write(path, text + "\n").with_context(|| format!("cannot write {}", path.display()))
}
