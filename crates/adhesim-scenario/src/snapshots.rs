//! The snapshot steps of a run and their contact fields, shared by the command line
//! (`snapshots/`, `fields.npz`) and the Python package (`RunResult.snapshots`,
//! `adhesim.run(out=...)`): which steps the scenario's `[output]` keeps
//! ([`SnapshotPlan`]) and the fields of those steps as the run goes
//! ([`SnapshotRecorder`], one [`FieldSnapshot`] a step). The named arrays of `fields.npz`
//! built from them are `snapshot_fields.rs`'s.

use crate::{ProtocolSetup, ValidScenario};
use adhesim::StepView;
use std::collections::BTreeSet;

/// Which steps get a snapshot, from the scenario's `[output]`.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct SnapshotPlan {
    /// Steps chosen by `output.snapshot_steps` (for a translation without chosen steps:
    /// the end of the forward stroke); they get a PNG, `.npy` fields and fields.
    pub chosen: BTreeSet<usize>,
    /// Every k-th step is chosen too (`output.snapshot_every`; 0 = off).
    pub every: usize,
    /// Jump steps with at least this many attached + detached elements get a PNG.
    pub jump_elements: usize,
    /// At most this many jump PNGs (`output.max_snapshots`).
    pub max_jump_snapshots: usize,
    /// The last approach step (the deepest indentation), `max_depth`.
    pub max_depth_step: usize,
}

impl SnapshotPlan {
    /// The plan of a scenario's `[output]`.
    pub fn new(scenario: &ValidScenario) -> Self {
        let output = &scenario.file.output;
        let mut chosen: BTreeSet<usize> = output.snapshot_steps.iter().map(|&s| s as usize).collect();
        let forward_end = match scenario.protocol_setup() {
            ProtocolSetup::Translation(setup) => Some(setup.protocol.approach_steps + setup.protocol.steps - 1),
            ProtocolSetup::Shear(setup) => Some(setup.protocol.approach_steps + setup.protocol.steps - 1),
            ProtocolSetup::Indentation(_) => None,
        };
        if let Some(step) = forward_end {
            if chosen.is_empty() && output.snapshot_every == 0 {
                // The end of the forward stroke.
                chosen.insert(step);
            }
        }
        Self {
            chosen,
            every: output.snapshot_every as usize,
            jump_elements: output.jump_snapshot_elements as usize,
            max_jump_snapshots: output.max_snapshots as usize,
            max_depth_step: scenario.approach_steps.saturating_sub(1),
        }
    }

    /// A chosen step (`snapshot_steps`, `snapshot_every`): `step_SSSSSS.png` and `.npy`.
    pub fn is_chosen(&self, step: usize) -> bool {
        self.chosen.contains(&step) || step.checked_rem(self.every) == Some(0)
    }

    /// A step whose fields are kept whatever happens after it: chosen, or the deepest.
    pub fn keeps_fields(&self, step: usize) -> bool {
        self.is_chosen(step) || step == self.max_depth_step
    }

    /// The name of a chosen step's files, `step_SSSSSS`.
    pub fn step_name(step: usize) -> String {
        format!("step_{step:06}")
    }
}

/// The fields of one step, row-major (n, n): row i is y, column j is x.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FieldSnapshot {
    /// Step number (as in `curve.csv`).
    pub step: usize,
    /// Indentation depth d.
    pub depth: f64,
    /// Lateral position X of the indenter axis (0 for indentation).
    pub offset: f64,
    /// Pressure p (> 0 compressive).
    pub pressure: Vec<f64>,
    /// Normal displacement u (> 0 into the body).
    pub displacement: Vec<f64>,
    /// The contact set.
    #[serde(with = "adhesim::bit_string")]
    pub contact: Vec<bool>,
    /// The tangential fields of a shear's shift step.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shear: Option<adhesim::ShearFields>,
}

impl FieldSnapshot {
    fn of(view: &StepView<'_>) -> Self {
        Self {
            step: view.record.step,
            depth: view.record.depth,
            offset: view.record.offset,
            pressure: view.state.pressure.clone(),
            displacement: view.state.displacement.clone(),
            contact: view.state.contact.clone(),
            shear: view.shear.cloned(),
        }
    }

    fn copy_from(&mut self, view: &StepView<'_>) {
        self.step = view.record.step;
        self.depth = view.record.depth;
        self.offset = view.record.offset;
        self.pressure.copy_from_slice(&view.state.pressure);
        self.displacement.copy_from_slice(&view.state.displacement);
        self.contact.copy_from_slice(&view.state.contact);
        match (&mut self.shear, view.shear) {
            (Some(kept), Some(fields)) => kept.clone_from(fields),
            (kept, fields) => *kept = fields.cloned(),
        }
    }
}

/// Collects the fields of the snapshot steps as a run goes: the steps the plan keeps, the
/// last step in contact (`pull_off`) and the step of the largest contact (the first of
/// them on a tie), each once. Two buffers are reused for the last two; jump steps get no
/// fields (their number would make memory grow with the run).
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct SnapshotRecorder {
    plan: SnapshotPlan,
    kept: Vec<FieldSnapshot>,
    last_in_contact: Option<FieldSnapshot>,
    largest: Option<(usize, FieldSnapshot)>,
}

impl SnapshotRecorder {
    /// A recorder following `plan`.
    pub fn new(plan: SnapshotPlan) -> Self {
        Self {
            plan,
            kept: Vec::new(),
            last_in_contact: None,
            largest: None,
        }
    }

    /// The plan it follows.
    pub fn plan(&self) -> &SnapshotPlan {
        &self.plan
    }

    /// Sees a step (every step of the run, in order).
    pub fn observe(&mut self, view: &StepView<'_>) {
        let step = view.record.step;
        if self.plan.keeps_fields(step) && self.kept.last().is_none_or(|s| s.step != step) {
            self.kept.push(FieldSnapshot::of(view));
        }
        let elements = view.record.contact_elements;
        if elements == 0 {
            return;
        }
        match &mut self.last_in_contact {
            Some(snapshot) => snapshot.copy_from(view),
            None => self.last_in_contact = Some(FieldSnapshot::of(view)),
        }
        match &mut self.largest {
            Some((largest, snapshot)) if elements > *largest => {
                *largest = elements;
                snapshot.copy_from(view);
            }
            Some(_) => {}
            None => self.largest = Some((elements, FieldSnapshot::of(view))),
        }
    }

    /// Whether every field kept has `elements` values (a recorder read from a checkpoint).
    pub(crate) fn fits(&self, elements: usize) -> bool {
        let fits = |s: &FieldSnapshot| {
            s.pressure.len() == elements && s.displacement.len() == elements && s.contact.len() == elements
        };
        self.kept.iter().all(fits) && self.last_in_contact.iter().all(fits) && self.largest.iter().all(|(_, s)| fits(s))
    }

    /// The snapshots so far, by step, each step once (also after a run stopped early).
    pub fn take_snapshots(&mut self) -> Vec<FieldSnapshot> {
        let mut snapshots = std::mem::take(&mut self.kept);
        snapshots.extend(self.last_in_contact.take());
        snapshots.extend(self.largest.take().map(|(_, s)| s));
        snapshots.sort_by_key(|s| s.step);
        snapshots.dedup_by_key(|s| s.step);
        snapshots
    }
}
