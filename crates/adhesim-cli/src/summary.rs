//! `summary.json`: the scenario crate builds its content ([`adhesim_scenario::Summary`]:
//! inputs, derived, results, performance, warnings); the CLI adds the observer's phase
//! timings and writes the file atomically.

use crate::output::RunObserver;
use adhesim_scenario::{Counters, Performance, PhaseTimes, Summary};
use anyhow::{Context, Result};
use std::path::Path;

/// Counters of a run, with the per-step averages and the observer's phase timings.
pub fn performance(wall_seconds: f64, counters: &Counters, observer: &RunObserver) -> Performance {
    let timings = &observer.timings;
    let times = PhaseTimes {
        phase_seconds: timings.phase_seconds.clone(),
        phase_steps: timings.phase_steps.clone(),
        output_seconds: timings.output_seconds,
    };
    Performance::new(wall_seconds, counters, times)
}

/// Writes `summary.json` atomically.
pub fn write(path: &Path, summary: &Summary<'_>) -> Result<()> {
    let text = summary
        .to_json()
        .with_context(|| format!("cannot write {}", path.display()))?;
    adhesim_scenario::batch::write_atomically(path, text.as_bytes())
}
