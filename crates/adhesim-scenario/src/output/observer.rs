//! The observer of a run into a folder: writes `curve.csv` rows as the steps come, the
//! snapshot fields (`snapshots/*.npy`, `fields.npz`), hands the contact maps to the
//! [`RunPictures`] it was given (the command line draws them; Python runs without), drives
//! a [`RunProgress`], times the phases and watches for contact at the domain border.

use super::checkpoint::CheckpointPolicy;
use super::curve_csv::CurveCsv;
use super::fields::FieldsRecorder;
use super::observer_state::{Bits, ObserverState};
use super::timings::PhaseTimings;
use crate::{CurveColumns, RunOutcome, SnapshotFields, SnapshotPlan, ValidScenario};
use adhesim::{Grid, Observer, ProtocolCheckpoint, StepRecord, StepView};
use anyhow::{Context, Result};
use std::collections::BTreeSet;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The contact sets of one step kept for a composite picture: (step, contact, previous
/// contact).
pub type CapturedStep = (usize, Vec<bool>, Vec<bool>);

/// The pictures of a run folder. The scenario crate draws nothing: the command line
/// implements this with its figure builder (contact maps, force curves); a run without
/// pictures (Python's `adhesim.run`) writes every other file alike.
pub trait RunPictures: Sync {
    /// Writes the contact map of one step (`contact` against `previous`) as a PNG at `path`.
    fn contact_map(&self, path: &Path, grid: &Grid, contact: &[bool], previous: &[bool]) -> Result<()>;
    /// Writes the stick/slip/open map of a shift step of a shear as a PNG at `path`.
    fn slip_map(&self, path: &Path, grid: &Grid, status: &[adhesim::SlipStatus]) -> Result<()>;
    /// Writes the figures of a finished run into `dir` (`plots/`); returns their names
    /// relative to the run folder.
    fn figures(
        &self,
        scenario: &ValidScenario,
        outcome: &RunOutcome,
        captured: &[CapturedStep],
        dir: &Path,
    ) -> Result<Vec<String>>;
}

/// Shows the progress of a run (the command line's bar, Python's callback). An error from
/// [`RunProgress::step`] stops the run after that step (Ctrl-C in Python).
pub trait RunProgress {
    /// A step has been solved and its outputs written.
    fn step(&mut self, _record: &StepRecord) -> Result<()> {
        Ok(())
    }
    /// A warning for the user (also kept in `summary.json`).
    fn warning(&mut self, _message: &str) {}
    /// The run has ended.
    fn finish(&mut self) {}
}

/// No progress shown.
impl RunProgress for () {}

/// No progress shown; warnings printed on stderr, one `warning: ...` line each (a sweep
/// case run where no bar is drawn, as in Python's `adhesim.sweep`).
pub struct WarningsOnStderr;

impl RunProgress for WarningsOnStderr {
    fn warning(&mut self, message: &str) {
        eprintln!("warning: {message}");
    }
}

/// Writes the outputs of each step.
pub struct RunObserver<'a> {
    csv: CurveCsv,
    grid: Grid,
    snapshots: PathBuf,
    plan: SnapshotPlan,
    jump_snapshots: usize,
    progress: &'a mut dyn RunProgress,
    pictures: Option<&'a dyn RunPictures>,
    largest: (usize, usize, Vec<bool>),
    last_in_contact: Option<(usize, Vec<bool>, Vec<bool>)>,
    /// Warnings for the summary (also printed to stderr).
    pub warnings: Vec<String>,
    border_warned: bool,
    /// The first I/O error; the protocol is stopped when it happens.
    pub error: Option<anyhow::Error>,
    /// Snapshot files written, relative to the output folder.
    pub snapshot_files: Vec<String>,
    /// Steps whose contact sets are kept in `captured` (see [`RunObserver::capture`]).
    capture_steps: BTreeSet<usize>,
    /// (step, contact, previous contact) of the captured steps, in step order.
    pub captured: Vec<(usize, Vec<bool>, Vec<bool>)>,
    /// Solver and output wall time per phase.
    pub timings: PhaseTimings,
    /// `fields.npz` of the snapshot steps (crate::output::fields), when set.
    pub fields: Option<FieldsRecorder>,
    /// The snapshot fields once written (for Python's in-memory result).
    pub written_fields: Option<SnapshotFields>,
    /// Mid-run checkpoints, when on ([`RunObserver::enable_checkpoints`]).
    checkpoints: Option<Checkpoints>,
    /// Every element in contact at some step, when kept ([`RunObserver::track_touched`]).
    touched: Option<Vec<bool>>,
}

/// Where and when checkpoints are written, and the records they need.
struct Checkpoints {
    folder: PathBuf,
    policy: CheckpointPolicy,
    last: Instant,
    records: Vec<StepRecord>,
    warned: bool,
}

/// The phase names of the timings (`Phase::name`, or "unknown").
fn phase_name(name: &str) -> &'static str {
    [
        adhesim::Phase::Approach,
        adhesim::Phase::Retract,
        adhesim::Phase::Roll,
        adhesim::Phase::Slide,
    ]
    .iter()
    .map(|p| p.name())
    .find(|&p| p == name)
    .unwrap_or("unknown")
}

impl<'a> RunObserver<'a> {
    /// Creates `curve.csv` (with its header) and `snapshots/` in `out`; contact maps are
    /// drawn by `pictures` (none without).
    pub fn new(
        out: &Path,
        grid: Grid,
        columns: CurveColumns,
        plan: SnapshotPlan,
        progress: &'a mut dyn RunProgress,
        pictures: Option<&'a dyn RunPictures>,
    ) -> Result<Self> {
        let snapshots = out.join("snapshots");
        std::fs::create_dir_all(&snapshots).with_context(|| format!("cannot create {}", snapshots.display()))?;
        let csv = CurveCsv::create(&out.join("curve.csv"), columns)?;
        Ok(Self {
            csv,
            grid,
            snapshots,
            plan,
            jump_snapshots: 0,
            progress,
            pictures,
            largest: (0, 0, Vec::new()),
            last_in_contact: None,
            warnings: Vec::new(),
            border_warned: false,
            error: None,
            snapshot_files: Vec::new(),
            capture_steps: BTreeSet::new(),
            captured: Vec::new(),
            timings: PhaseTimings::new(),
            fields: None,
            written_fields: None,
            checkpoints: None,
            touched: None,
        })
    }

    /// Writes a checkpoint into `folder` every `policy.every` of wall time (every protocol,
    /// on solvers that support them; docs/sweeps.md, "Resuming a case mid-run").
    pub fn enable_checkpoints(&mut self, folder: &Path, policy: &CheckpointPolicy) {
        self.checkpoints = Some(Checkpoints {
            folder: folder.to_path_buf(),
            policy: policy.clone(),
            last: Instant::now(),
            records: Vec::new(),
            warned: false,
        });
    }

    /// Keeps the elements the run touches (in contact at some step), for the γ map of the
    /// next impression (`adhesion.first_contact_factor`).
    pub fn track_touched(&mut self) {
        self.touched = Some(vec![false; self.grid.len()]);
    }

    /// The state a checkpoint keeps.
    fn state(&self) -> ObserverState {
        let bits = |b: &Vec<bool>| Bits(b.clone());
        ObserverState {
            jump_snapshots: self.jump_snapshots,
            largest: (self.largest.0, self.largest.1, bits(&self.largest.2)),
            last_in_contact: self.last_in_contact.as_ref().map(|(s, c, p)| (*s, bits(c), bits(p))),
            warnings: self.warnings.clone(),
            border_warned: self.border_warned,
            snapshot_files: self.snapshot_files.clone(),
            captured: self.captured.iter().map(|(s, c, p)| (*s, bits(c), bits(p))).collect(),
            phase_seconds: self
                .timings
                .phase_seconds
                .iter()
                .map(|(k, v)| (k.to_string(), *v))
                .collect(),
            phase_steps: self
                .timings
                .phase_steps
                .iter()
                .map(|(k, v)| (k.to_string(), *v))
                .collect(),
            output_seconds: self.timings.output_seconds,
            fields: self.fields.as_ref().map(|f| f.recorder().clone()),
            touched: self.touched.as_ref().map(bits),
        }
    }

    /// Continues from a checkpoint: its state, and `curve.csv` rows of the `records` done.
    pub(crate) fn restore(&mut self, state: ObserverState, records: &[StepRecord]) -> Result<()> {
        for record in records {
            self.csv.write(record)?;
        }
        if let Some(checkpoints) = &mut self.checkpoints {
            checkpoints.records = records.to_vec();
        }
        self.jump_snapshots = state.jump_snapshots;
        self.largest = (state.largest.0, state.largest.1, state.largest.2 .0);
        self.last_in_contact = state.last_in_contact.map(|(s, c, p)| (s, c.0, p.0));
        self.warnings = state.warnings;
        self.border_warned = state.border_warned;
        self.snapshot_files = state.snapshot_files;
        self.captured = state.captured.into_iter().map(|(s, c, p)| (s, c.0, p.0)).collect();
        self.timings.phase_seconds = state.phase_seconds.iter().map(|(k, v)| (phase_name(k), *v)).collect();
        self.timings.phase_steps = state.phase_steps.iter().map(|(k, v)| (phase_name(k), *v)).collect();
        self.timings.output_seconds = state.output_seconds;
        if let (Some(fields), Some(recorder)) = (&mut self.fields, state.fields) {
            fields.restore(recorder);
        }
        if let (Some(touched), Some(kept)) = (&mut self.touched, state.touched) {
            *touched = kept.0;
        }
        Ok(())
    }

    /// Keeps the contact sets of these steps in memory (for composite pictures such as
    /// the consecutive sliding snapshots of the paper's Fig. 9).
    pub fn capture(&mut self, steps: impl IntoIterator<Item = usize>) {
        self.capture_steps.extend(steps);
    }

    fn snapshot(&mut self, name: &str, contact: &[bool], previous: &[bool]) -> Result<()> {
        let Some(pictures) = self.pictures else {
            return Ok(());
        };
        let path = self.snapshots.join(format!("{name}.png"));
        pictures.contact_map(&path, &self.grid, contact, previous)?;
        self.snapshot_files.push(format!("snapshots/{name}.png"));
        Ok(())
    }

    fn handle(&mut self, view: &StepView<'_>) -> Result<()> {
        let r = view.record;
        self.csv.write(r)?;
        let step = r.step;
        let n = (self.grid.ny(), self.grid.nx());
        let changed = r.report.attached + r.report.detached;
        if self.plan.is_chosen(step) {
            let name = SnapshotPlan::step_name(step);
            self.snapshot(&name, &view.state.contact, view.previous_contact)?;
            if let (Some(pictures), Some(shear)) = (self.pictures, view.shear) {
                pictures.slip_map(
                    &self.snapshots.join(format!("{name}_slip.png")),
                    &self.grid,
                    &shear.status,
                )?;
                self.snapshot_files.push(format!("snapshots/{name}_slip.png"));
            }
            write_field(
                &self.snapshots.join(format!("{name}_pressure.npy")),
                n,
                &view.state.pressure,
            )?;
            write_field(
                &self.snapshots.join(format!("{name}_displacement.npy")),
                n,
                &view.state.displacement,
            )?;
        }
        if r.jumped && changed >= self.plan.jump_elements && self.jump_snapshots < self.plan.max_jump_snapshots {
            self.jump_snapshots += 1;
            self.snapshot(&format!("jump_{step:06}"), &view.state.contact, view.previous_contact)?;
        }
        if step == self.plan.max_depth_step {
            self.snapshot("max_depth", &view.state.contact, view.previous_contact)?;
        }
        if let Some(fields) = &mut self.fields {
            fields.observe(view);
        }
        if self.capture_steps.contains(&step) {
            self.captured
                .push((step, view.state.contact.clone(), view.previous_contact.to_vec()));
        }
        if let Some(touched) = &mut self.touched {
            for (t, &c) in touched.iter_mut().zip(&view.state.contact) {
                *t |= c;
            }
        }
        if r.contact_elements > self.largest.0 {
            self.largest = (r.contact_elements, step, view.state.contact.clone());
        }
        if r.contact_elements > 0 {
            match &mut self.last_in_contact {
                Some((s, contact, previous)) => {
                    *s = step;
                    contact.copy_from_slice(&view.state.contact);
                    previous.copy_from_slice(view.previous_contact);
                }
                None => {
                    self.last_in_contact = Some((step, view.state.contact.clone(), view.previous_contact.to_vec()));
                }
            }
        }
        if r.touches_border && !self.border_warned {
            self.border_warned = true;
            let message = crate::border_warning(step, r.depth);
            self.progress.warning(&message);
            self.warnings.push(message);
        }
        self.progress.step(r)
    }

    /// Closes the progress bar; then, for a run that `succeeded`, writes the contact maps of
    /// the largest contact and of the last configuration before contact was lost,
    /// `fields.npz` of the snapshot steps of `scenario` (the one run), and last renames
    /// `curve.csv.partial` to `curve.csv`: a curve under its final name only when every
    /// output of the run was written. After a failed run or an I/O error (in `error`) the
    /// rows done stay in `curve.csv.partial` (a run failing in its fields left a
    /// `curve.csv` of NaN rows under its final name).
    pub fn finish(&mut self, scenario: &ValidScenario, succeeded: bool) -> Result<()> {
        self.progress.finish();
        if self.error.is_some() || !succeeded {
            return Ok(());
        }
        if self.largest.0 > 0 {
            let contact = std::mem::take(&mut self.largest.2);
            // Shown without change colours: the map of the contact itself.
            self.snapshot("largest_contact", &contact, &contact)?;
        }
        if let Some((_, contact, previous)) = self.last_in_contact.take() {
            self.snapshot("pull_off", &contact, &previous)?;
        }
        if let (Some(fields), Some(out)) = (&mut self.fields, self.snapshots.parent()) {
            self.written_fields = Some(fields.write(scenario, out)?);
        }
        if let (Some(touched), Some(factor), Some(out)) =
            (&self.touched, scenario.first_contact_factor, self.snapshots.parent())
        {
            let map = crate::first_contact::next_impression_map(&scenario.gamma, scenario.gamma0, factor, touched);
            let shape = (self.grid.ny(), self.grid.nx());
            write_field(&out.join(crate::first_contact::FIRST_CONTACT_MAP), shape, &map)?;
        }
        self.csv.commit()
    }
}

impl Observer for RunObserver<'_> {
    fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()> {
        if let Some(checkpoints) = &mut self.checkpoints {
            checkpoints.records.push(*view.record);
        }
        self.timings
            .solver_step(view.record.phase.map_or("unknown", |p| p.name()));
        let output_start = Instant::now();
        let result = self.handle(&view);
        self.timings.output_done(output_start);
        match result {
            Ok(()) => ControlFlow::Continue(()),
            Err(error) => {
                self.error = Some(error);
                ControlFlow::Break(())
            }
        }
    }

    fn wants_checkpoint(&mut self) -> bool {
        self.error.is_none()
            && self
                .checkpoints
                .as_ref()
                .is_some_and(|c| c.last.elapsed() >= c.policy.every)
    }

    /// Writes the checkpoint; a failure to write it is a warning on stderr (once), not a
    /// failure of the run (the run goes on without).
    fn on_checkpoint(&mut self, checkpoint: ProtocolCheckpoint) -> ControlFlow<()> {
        let state = self.state();
        let Some(c) = &mut self.checkpoints else {
            return ControlFlow::Continue(());
        };
        match super::checkpoint::write(&c.folder, &c.policy, &checkpoint, &c.records, &state) {
            Ok(()) => {}
            Err(error) if !c.warned => {
                c.warned = true;
                eprintln!("warning: no checkpoint written: {error:#}");
            }
            Err(_) => {}
        }
        c.last = Instant::now();
        ControlFlow::Continue(())
    }
}

/// A field as an .npy array of `shape` = (rows, columns) = (Ny, Nx).
fn write_field(path: &Path, shape: (usize, usize), values: &[f64]) -> Result<()> {
    use ndarray_npy::WriteNpyExt;
    let array = ndarray::Array2::from_shape_vec(shape, values.to_vec())?;
    let file = File::create(path).with_context(|| format!("cannot create {}", path.display()))?;
    let mut writer = BufWriter::new(file);
    array
        .write_npy(&mut writer)
        .with_context(|| format!("cannot write {}", path.display()))?;
    writer.flush()?;
    Ok(())
}
