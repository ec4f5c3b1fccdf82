//! Wall time per phase of a run (moved from the command line's `output.rs`).

use std::collections::BTreeMap;
use std::time::Instant;

/// Wall time per phase: the solver's (time between steps, without the output) and the
/// output's own.
pub struct PhaseTimings {
    /// Solver wall time per phase.
    pub phase_seconds: BTreeMap<&'static str, f64>,
    /// Steps per phase.
    pub phase_steps: BTreeMap<&'static str, usize>,
    /// Wall time spent writing curve.csv rows and snapshots.
    pub output_seconds: f64,
    last_tick: Instant,
}

impl Default for PhaseTimings {
    fn default() -> Self {
        Self::new()
    }
}

impl PhaseTimings {
    pub fn new() -> Self {
        Self {
            phase_seconds: BTreeMap::new(),
            phase_steps: BTreeMap::new(),
            output_seconds: 0.0,
            last_tick: Instant::now(),
        }
    }

    /// A step of `phase` has been solved (since the last tick).
    pub fn solver_step(&mut self, phase: &'static str) {
        *self.phase_seconds.entry(phase).or_default() += self.last_tick.elapsed().as_secs_f64();
        *self.phase_steps.entry(phase).or_default() += 1;
    }

    /// The output of a step, begun at `start`, is written.
    pub fn output_done(&mut self, start: Instant) {
        self.output_seconds += start.elapsed().as_secs_f64();
        self.last_tick = Instant::now();
    }
}
