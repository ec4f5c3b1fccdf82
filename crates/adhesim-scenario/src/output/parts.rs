//! The parts a run's observer is composed of ([`super::observer::RunObserver`]), each an
//! [`Observer`] of its own that any caller can compose with the library's pairs and
//! triples: the contact sets kept for composite pictures, the elements touched, the
//! border watch, the progress, and the adapter that turns an output which can fail into
//! an observer that stops the run at its first error.

use super::observer::{CapturedStep, RunProgress};
use super::observer_state::{Bits, ObserverState};
use crate::SnapshotRecorder;
use adhesim::{Observer, StepRecord, StepView};
use anyhow::Result;
use std::collections::BTreeSet;
use std::ops::ControlFlow;

/// An output written at every step that can fail (a file, a progress that was cancelled).
pub trait StepWriter {
    /// Writes the outputs of one step.
    fn write_step(&mut self, view: &StepView<'_>) -> Result<()>;
}

/// A [`StepWriter`] as an observer: its first error is kept in `error` and stops the run.
pub struct Writes<W> {
    /// The output.
    pub output: W,
    /// The first error, after which the output saw no more steps.
    pub error: Option<anyhow::Error>,
}

impl<W> Writes<W> {
    /// `output`, no error yet.
    pub fn new(output: W) -> Self {
        Self { output, error: None }
    }
}

impl<W: StepWriter> Observer for Writes<W> {
    fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()> {
        if self.error.is_some() {
            return ControlFlow::Break(());
        }
        match self.output.write_step(&view) {
            Ok(()) => ControlFlow::Continue(()),
            Err(error) => {
                self.error = Some(error);
                ControlFlow::Break(())
            }
        }
    }
}

/// A run's progress told of every step (an error from it, such as Ctrl-C in Python,
/// stops the run).
pub struct ProgressSteps<'a>(pub &'a mut dyn RunProgress);

impl StepWriter for ProgressSteps<'_> {
    fn write_step(&mut self, view: &StepView<'_>) -> Result<()> {
        self.0.step(view.record)
    }
}

impl StepWriter for super::curve_csv::CurveCsv {
    fn write_step(&mut self, view: &StepView<'_>) -> Result<()> {
        self.write(view.record)
    }
}

/// The snapshot fields of the chosen steps, kept for `fields.npz`.
impl Observer for super::fields::FieldsRecorder {
    fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()> {
        self.observe(&view);
        ControlFlow::Continue(())
    }
}

/// The snapshot fields of the chosen steps, kept in memory.
impl Observer for SnapshotRecorder {
    fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()> {
        self.observe(&view);
        ControlFlow::Continue(())
    }
}

/// The contact sets of chosen steps, kept in memory for composite pictures (the
/// consecutive sliding snapshots of the paper's Fig. 9).
#[derive(Default)]
pub struct CapturedSteps {
    steps: BTreeSet<usize>,
    /// (step, contact, previous contact) of the captured steps, in step order.
    pub sets: Vec<CapturedStep>,
}

impl CapturedSteps {
    /// Keeps the contact sets of `steps`.
    pub fn new(steps: impl IntoIterator<Item = usize>) -> Self {
        Self {
            steps: steps.into_iter().collect(),
            sets: Vec::new(),
        }
    }

    pub(super) fn save(&self, state: &mut ObserverState) {
        state.captured = self
            .sets
            .iter()
            .map(|(s, c, p)| (*s, Bits(c.clone()), Bits(p.clone())))
            .collect();
    }

    pub(super) fn restore(&mut self, state: &mut ObserverState) {
        self.sets = std::mem::take(&mut state.captured)
            .into_iter()
            .map(|(s, c, p)| (s, c.0, p.0))
            .collect();
    }
}

impl Observer for CapturedSteps {
    fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()> {
        let step = view.record.step;
        if self.steps.contains(&step) {
            self.sets
                .push((step, view.state.contact.clone(), view.previous_contact.to_vec()));
        }
        ControlFlow::Continue(())
    }
}

/// Every element in contact at some step (the γ map of the next impression,
/// `adhesion.first_contact_factor`).
pub struct TouchedElements {
    /// Whether each element has been in contact.
    pub touched: Vec<bool>,
}

impl TouchedElements {
    /// None touched yet, on a grid of `elements`.
    pub fn new(elements: usize) -> Self {
        Self {
            touched: vec![false; elements],
        }
    }

    pub(super) fn save(&self, state: &mut ObserverState) {
        state.touched = Some(Bits(self.touched.clone()));
    }

    pub(super) fn restore(&mut self, state: &mut ObserverState) {
        if let Some(kept) = state.touched.take() {
            self.touched = kept.0;
        }
    }
}

impl Observer for TouchedElements {
    fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()> {
        for (t, &c) in self.touched.iter_mut().zip(&view.state.contact) {
            *t |= c;
        }
        ControlFlow::Continue(())
    }
}

/// Watches for contact on the border of a free grid: one warning, at the first step
/// that has it.
#[derive(Default)]
pub struct BorderWatch {
    /// The warnings raised (at most one).
    pub warnings: Vec<String>,
    warned: bool,
}

impl BorderWatch {
    /// The warning of `record`, when it is the first step touching the border.
    pub fn watch(&mut self, record: &StepRecord) -> Option<&str> {
        if !record.touches_border || self.warned {
            return None;
        }
        self.warned = true;
        self.warnings.push(crate::border_warning(record.step, record.depth));
        self.warnings.last().map(String::as_str)
    }

    pub(super) fn save(&self, state: &mut ObserverState) {
        state.warnings = self.warnings.clone();
        state.border_warned = self.warned;
    }

    pub(super) fn restore(&mut self, state: &mut ObserverState) {
        self.warnings = std::mem::take(&mut state.warnings);
        self.warned = state.border_warned;
    }
}

impl Observer for BorderWatch {
    fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()> {
        self.watch(view.record);
        ControlFlow::Continue(())
    }
}
