//! The observer of a run into a folder, composed of its parts ([`super::parts`]): the
//! `curve.csv` rows as the steps come, the snapshots ([`SnapshotMaps`], whose contact maps
//! the [`RunPictures`] it was given draw: the command line's; Python runs without), the
//! snapshot fields (`fields.npz`), the contact sets kept for pictures, the elements
//! touched, the border watch and the [`RunProgress`], timed by phase, and the
//! checkpoints, which keep the state of every part.

use super::checkpoint::CheckpointPolicy;
use super::curve_csv::CurveCsv;
use super::fields::FieldsRecorder;
use super::observer_state::ObserverState;
use super::parts::{BorderWatch, CapturedSteps, ProgressSteps, TouchedElements, Writes};
use super::snapshot_maps::{write_field, SnapshotMaps};
use super::timings::PhaseTimings;
use crate::{CurveColumns, RunOutcome, SnapshotFields, SnapshotPlan, ValidScenario};
use adhesim::{Grid, Observer, ProtocolCheckpoint, StepRecord, StepView};
use anyhow::Result;
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

/// The observer of a run into a folder: its parts, each seeing every step in this order
/// until one fails, and the checkpoints that keep their state.
pub struct RunObserver<'a> {
    curve: Writes<CurveCsv>,
    maps: Writes<SnapshotMaps<'a>>,
    /// `fields.npz` of the snapshot steps (crate::output::fields), when set.
    pub fields: Option<FieldsRecorder>,
    /// The contact sets kept for composite pictures ([`RunObserver::capture`]).
    pub captured: CapturedSteps,
    /// Every element in contact at some step, when kept ([`RunObserver::track_touched`]).
    touched: Option<TouchedElements>,
    /// Contact at the border of a free grid (its warning, for the summary, is also handed
    /// to the progress).
    pub border: BorderWatch,
    progress: Writes<ProgressSteps<'a>>,
    /// Solver and output wall time per phase.
    pub timings: PhaseTimings,
    /// The snapshot fields once written (for Python's in-memory result).
    pub written_fields: Option<SnapshotFields>,
    /// Mid-run checkpoints, when on ([`RunObserver::enable_checkpoints`]).
    checkpoints: Option<Checkpoints>,
    grid: Grid,
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
        let maps = SnapshotMaps::new(out, grid, plan, pictures)?;
        let csv = CurveCsv::create(&out.join("curve.csv"), columns)?;
        Ok(Self {
            curve: Writes::new(csv),
            maps: Writes::new(maps),
            fields: None,
            captured: CapturedSteps::default(),
            touched: None,
            border: BorderWatch::default(),
            progress: Writes::new(ProgressSteps(progress)),
            timings: PhaseTimings::new(),
            written_fields: None,
            checkpoints: None,
            grid,
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
        self.touched = Some(TouchedElements::new(self.grid.len()));
    }

    /// Keeps the contact sets of these steps in memory (for composite pictures such as
    /// the consecutive sliding snapshots of the paper's Fig. 9).
    pub fn capture(&mut self, steps: impl IntoIterator<Item = usize>) {
        self.captured = CapturedSteps::new(steps);
    }

    /// Snapshot files written, relative to the output folder.
    pub fn take_snapshot_files(&mut self) -> Vec<String> {
        std::mem::take(&mut self.maps.output.snapshot_files)
    }

    /// The first error of a part (an I/O error, a cancelled progress), which stopped the
    /// run.
    pub fn take_error(&mut self) -> Option<anyhow::Error> {
        self.curve
            .error
            .take()
            .or_else(|| self.maps.error.take())
            .or_else(|| self.progress.error.take())
    }

    fn failed(&self) -> bool {
        self.curve.error.is_some() || self.maps.error.is_some() || self.progress.error.is_some()
    }

    /// The state a checkpoint keeps: each part's.
    fn state(&self) -> ObserverState {
        let mut state = ObserverState::default();
        self.maps.output.save(&mut state);
        self.border.save(&mut state);
        self.captured.save(&mut state);
        self.timings.save(&mut state);
        state.fields = self.fields.as_ref().map(|f| f.recorder().clone());
        if let Some(touched) = &self.touched {
            touched.save(&mut state);
        }
        state
    }

    /// Continues from a checkpoint: its state, and `curve.csv` rows of the `records` done.
    pub(crate) fn restore(&mut self, mut state: ObserverState, records: &[StepRecord]) -> Result<()> {
        for record in records {
            self.curve.output.write(record)?;
        }
        if let Some(checkpoints) = &mut self.checkpoints {
            checkpoints.records = records.to_vec();
        }
        self.maps.output.restore(&mut state);
        self.border.restore(&mut state);
        self.captured.restore(&mut state);
        self.timings.restore(&state, phase_name);
        if let (Some(fields), Some(recorder)) = (&mut self.fields, state.fields.take()) {
            fields.restore(recorder);
        }
        if let Some(touched) = &mut self.touched {
            touched.restore(&mut state);
        }
        Ok(())
    }

    /// Closes the progress bar; then, for a run that `succeeded`, writes the contact maps of
    /// the largest contact and of the last configuration before contact was lost,
    /// `fields.npz` of the snapshot steps of `scenario` (the one run), and last renames
    /// `curve.csv.partial` to `curve.csv`: a curve under its final name only when every
    /// output of the run was written. After a failed run or an I/O error the rows done
    /// stay in `curve.csv.partial` (a run failing in its fields left a `curve.csv` of NaN
    /// rows under its final name).
    pub fn finish(&mut self, scenario: &ValidScenario, succeeded: bool) -> Result<()> {
        self.progress.output.0.finish();
        if self.failed() || !succeeded {
            return Ok(());
        }
        self.maps.output.finish()?;
        let out = self.maps.output.folder().map(Path::to_path_buf);
        if let (Some(fields), Some(out)) = (&mut self.fields, &out) {
            self.written_fields = Some(fields.write(scenario, out)?);
        }
        if let (Some(touched), Some(factor), Some(out)) = (&self.touched, scenario.first_contact_factor, &out) {
            let map =
                crate::first_contact::next_impression_map(&scenario.gamma, scenario.gamma0, factor, &touched.touched);
            let shape = (self.grid.ny(), self.grid.nx());
            write_field(&out.join(crate::first_contact::FIRST_CONTACT_MAP), shape, &map)?;
        }
        self.curve.output.commit()
    }

    /// Every part sees the step; the border's warning goes to the progress before its
    /// step.
    fn handle(&mut self, view: StepView<'_>) -> ControlFlow<()> {
        (
            &mut self.curve,
            &mut self.maps,
            (&mut self.fields, &mut self.captured, &mut self.touched),
        )
            .on_step(view)?;
        if let Some(message) = self.border.watch(view.record) {
            self.progress.output.0.warning(message);
        }
        self.progress.on_step(view)
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
        let flow = self.handle(view);
        self.timings.output_done(output_start);
        flow
    }

    fn wants_checkpoint(&mut self) -> bool {
        !self.failed()
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
