//! Wall time per phase of a run (moved from the command line's `output.rs`).

use adhesim::{Observer, ProtocolCheckpoint, StepView};
use std::collections::BTreeMap;
use std::ops::ControlFlow;
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

impl PhaseTimings {
    /// Puts the timings into a checkpoint's state.
    pub(super) fn save(&self, state: &mut super::observer_state::ObserverState) {
        state.phase_seconds = named(&self.phase_seconds);
        state.phase_steps = named(&self.phase_steps);
        state.output_seconds = self.output_seconds;
    }

    /// Continues with the timings of a checkpoint's state; `phase` names its phases.
    pub(super) fn restore(
        &mut self,
        state: &super::observer_state::ObserverState,
        phase: impl Fn(&str) -> &'static str,
    ) {
        self.phase_seconds = state.phase_seconds.iter().map(|(k, v)| (phase(k), *v)).collect();
        self.phase_steps = state.phase_steps.iter().map(|(k, v)| (phase(k), *v)).collect();
        self.output_seconds = state.output_seconds;
    }
}

/// A map by phase with owned names (as a checkpoint keeps it).
fn named<T: Copy>(map: &BTreeMap<&'static str, T>) -> BTreeMap<String, T> {
    map.iter().map(|(k, v)| (k.to_string(), *v)).collect()
}

/// An observer timed by phase: the wall time between steps is the solver's, the time the
/// observer takes over a step is the output's.
pub struct Timed<O> {
    /// The observer timed.
    pub observer: O,
    /// Its timings.
    pub timings: PhaseTimings,
}

impl<O> Timed<O> {
    /// `observer`, its clock started now.
    pub fn new(observer: O) -> Self {
        Self {
            observer,
            timings: PhaseTimings::new(),
        }
    }
}

impl<O: Observer> Observer for Timed<O> {
    fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()> {
        self.timings
            .solver_step(view.record.phase.map_or("unknown", |p| p.name()));
        let output_start = Instant::now();
        let flow = self.observer.on_step(view);
        self.timings.output_done(output_start);
        flow
    }

    fn wants_checkpoint(&mut self) -> bool {
        self.observer.wants_checkpoint()
    }

    fn on_checkpoint(&mut self, checkpoint: ProtocolCheckpoint) -> ControlFlow<()> {
        self.observer.on_checkpoint(checkpoint)
    }
}
