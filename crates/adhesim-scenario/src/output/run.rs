//! A run into a folder, the one pipeline of `adhesim run`, of every sweep case and of
//! Python's `adhesim.run(out=...)`: the run marker, the observer's `curve.csv`, snapshots
//! and field files, the pictures (when given), then `summary.json` with the phase timings,
//! written atomically. The folder is new, or made ready by
//! [`super::folder::prepare_run_folder`].

use super::checkpoint::{self, CheckpointPolicy};
use super::folder;
use super::observer::{RunObserver, RunPictures, RunProgress};
use super::timings::PhaseTimings;
use crate::{
    Performance, PhaseTimes, ProtocolSetup, RunOutcome, SnapshotFields, SnapshotPlan, SnapshotRecorder, Summary,
    ValidScenario,
};
use adhesim::ProtocolError;
use anyhow::{anyhow, Context, Result};
use std::path::Path;
use std::time::Instant;

/// Consecutive steps shown in the snapshot strip of a translation by default.
const STRIP_FRAMES: usize = 4;

/// What a run into a folder writes besides `curve.csv`, `summary.json` and `fields.npz`.
#[derive(Clone, Copy, Default)]
pub struct FolderRunOptions<'a> {
    /// Contact maps and figures; none without (the scenario crate draws nothing).
    pub pictures: Option<&'a dyn RunPictures>,
    /// Also `fields.nc` (NetCDF-3) beside `fields.npz`.
    pub netcdf: bool,
    /// Mid-run checkpoints into the folder, and continuing from the one found there (a
    /// case of the batch engine; docs/sweeps.md, "Resuming a case mid-run"); none without.
    pub checkpoint: Option<&'a CheckpointPolicy>,
}

/// What a finished run into a folder gives back.
pub struct FolderRun {
    /// The run's records, results and counters.
    pub outcome: RunOutcome,
    /// The text of `summary.json` as written.
    pub summary_json: String,
    /// The snapshot fields written to `fields.npz`.
    pub fields: SnapshotFields,
    /// Contact-map files written, relative to the folder.
    pub snapshot_files: Vec<String>,
    /// Figure files written, relative to the folder.
    pub plot_files: Vec<String>,
    /// Wall time of the run, figures included.
    pub wall_seconds: f64,
}

/// Runs a validated scenario into `out`: the marker, `curve.csv`, snapshots, field files,
/// pictures, `summary.json`. A solver failure or an interruption is an error naming the
/// step; `curve.csv.partial` then holds the steps done (no `curve.csv`, no `fields.npz`).
pub fn run_into_folder(
    scenario: &ValidScenario,
    out: &Path,
    options: FolderRunOptions<'_>,
    progress: &mut dyn RunProgress,
) -> Result<FolderRun> {
    std::fs::create_dir_all(out).with_context(|| format!("cannot create output folder {}", out.display()))?;
    folder::write_run_marker(out)?;
    let start = Instant::now();
    let resume = options
        .checkpoint
        .and_then(|policy| take_checkpoint(scenario, out, policy));
    let mut observer = RunObserver::new(
        out,
        scenario.grid,
        crate::curve::CurveColumns::of(scenario),
        SnapshotPlan::new(scenario),
        progress,
        options.pictures,
    )?;
    observer.capture(strip_steps(scenario));
    observer.fields = Some(super::fields::FieldsRecorder::new(
        SnapshotRecorder::new(SnapshotPlan::new(scenario)),
        options.netcdf,
    ));
    if let Some(policy) = options.checkpoint {
        observer.enable_checkpoints(out, policy);
    }
    if scenario.first_contact_factor.is_some() {
        observer.track_touched();
    }
    let resume = match resume {
        Some(body) => {
            observer.restore(body.observer, &body.records)?;
            Some(crate::Resume {
                protocol: body.protocol,
                records: body.records,
            })
        }
        None => None,
    };
    let outcome = crate::run_from(scenario, &mut observer, resume);
    if options.checkpoint.is_some() {
        // A finished (or failed) run is not continued: its folder holds no checkpoint.
        checkpoint::remove(out);
    }
    observer.finish(scenario, outcome.is_ok())?;
    let outcome = match outcome {
        Ok(outcome) => outcome,
        Err(ProtocolError::Interrupted(step)) => {
            let cause = observer.take_error().unwrap_or_else(|| anyhow!("interrupted"));
            return Err(cause.context(format!("run stopped at step {step}")));
        }
        Err(error) => {
            // One message, not an error chain: `ProtocolError::Solve` shows its source in its
            // own text, so `{:#}` (here, in sweep's error.txt) would print it twice.
            return Err(anyhow!(protocol_error_line(scenario, &error)).context(format!(
                "run failed; {} holds the steps done",
                out.join("curve.csv.partial").display()
            )));
        }
    };
    let plot_files = match options.pictures {
        Some(pictures) => pictures.figures(scenario, &outcome, &observer.captured.sets, &out.join("plots"))?,
        None => Vec::new(),
    };
    let wall_seconds = start.elapsed().as_secs_f64();
    let performance = performance(wall_seconds, &outcome, &observer.timings);
    let summary = Summary::new(scenario, &outcome, performance, &observer.border.warnings);
    let path = out.join("summary.json");
    let summary_json = summary
        .to_json()
        .with_context(|| format!("cannot write {}", path.display()))?;
    super::write_through_temp(&path, summary_json.as_bytes(), true)?;
    let fields = observer
        .written_fields
        .take()
        .ok_or_else(|| anyhow!("the snapshot fields of {} were not written", out.display()))?;
    Ok(FolderRun {
        outcome,
        summary_json,
        fields,
        snapshot_files: observer.take_snapshot_files(),
        plot_files,
        wall_seconds,
    })
}

/// Runs one case into `out` as `adhesim run` does, before its report: the scenario's
/// warnings, [`run_into_folder`], then the warnings on the finished run (contact lost, or
/// never resolved), each handed to `progress` (`summary.json` keeps those the run itself
/// raised). The runner of the command line's runs and sweep cases and, with
/// [`WarningsOnStderr`](super::observer::WarningsOnStderr), of Python's `adhesim.sweep`.
pub fn run_case(
    scenario: &ValidScenario,
    out: &Path,
    options: FolderRunOptions<'_>,
    progress: &mut dyn RunProgress,
) -> Result<FolderRun> {
    for warning in &scenario.warnings {
        progress.warning(warning);
    }
    let done = run_into_folder(scenario, out, options, progress)?;
    let records = &done.outcome.records;
    for warning in [
        crate::lost_contact_warning(records),
        crate::unresolved_contact_warning(records),
    ]
    .into_iter()
    .flatten()
    {
        progress.warning(&warning);
    }
    Ok(done)
}

/// A failed run's error on one line, naming the key of a limit the run reached: "contact
/// not lost …; raise the step limit" named no key.
pub fn protocol_error_line(scenario: &ValidScenario, error: &ProtocolError) -> String {
    let line = crate::error_text::error_line(anyhow::Chain::new(error));
    match error {
        ProtocolError::ContactNotLost { .. } if scenario.translation.is_none() => {
            format!("{line} (protocol.max_retract_steps = {})", scenario.max_retract_steps)
        }
        _ => line,
    }
}

/// The checkpoint in `out` to continue from, if it is this case's and readable; otherwise
/// a one-line warning naming the file and why, and the run starts from scratch (the
/// files of the checkpoint's run removed).
fn take_checkpoint(scenario: &ValidScenario, out: &Path, policy: &CheckpointPolicy) -> Option<checkpoint::Body> {
    // (The solver is only built to ask where a checkpoint is there.)
    let path = out.join(checkpoint::CHECKPOINT_FILE);
    let found = if path.exists() && scenario.normal_solver().supports_checkpoints() {
        checkpoint::read(out, policy, scenario.grid.len()).and_then(|body| match body {
            Some(body) if !of_this_protocol(scenario, &body.protocol) => {
                Err(anyhow!("it is of {}, this case is not", body.protocol.protocol_name()))
            }
            body => Ok(body),
        })
    } else {
        Ok(None)
    };
    match found {
        Ok(Some(body)) => Some(body),
        Ok(None) => {
            checkpoint::remove(out);
            None
        }
        Err(why) => {
            eprintln!(
                "warning: checkpoint {} not used: {why:#}; the case restarts from scratch",
                path.display()
            );
            checkpoint::remove(out);
            let _ = std::fs::remove_dir_all(out.join("snapshots"));
            None
        }
    }
}

/// Whether `checkpoint` is of the scenario's kind of protocol.
fn of_this_protocol(scenario: &ValidScenario, checkpoint: &adhesim::ProtocolCheckpoint) -> bool {
    matches!(
        (scenario.protocol_setup(), checkpoint),
        (
            ProtocolSetup::Indentation(_),
            adhesim::ProtocolCheckpoint::Indentation(_)
        ) | (
            ProtocolSetup::Translation(_),
            adhesim::ProtocolCheckpoint::Translation(_)
        )
    )
}

/// Counters of a run, with the per-step averages and the observer's phase timings.
pub fn performance(wall_seconds: f64, outcome: &RunOutcome, timings: &PhaseTimings) -> Performance {
    let times = PhaseTimes {
        phase_seconds: timings.phase_seconds.clone(),
        phase_steps: timings.phase_steps.clone(),
        output_seconds: timings.output_seconds,
    };
    Performance::new(wall_seconds, &outcome.report.counters(), times)
}

/// The steps whose contact sets the observer keeps for the snapshot strip of a
/// translation (paper Figs. 6b, 9): the chosen steps (at most 8), else consecutive steps
/// in the middle of the stationary part.
fn strip_steps(scenario: &ValidScenario) -> Vec<usize> {
    let o = &scenario.file.output;
    let ProtocolSetup::Translation(setup) = scenario.protocol_setup() else {
        return Vec::new();
    };
    let protocol = &setup.protocol;
    let forward_end = protocol.approach_steps + protocol.steps;
    if o.snapshot_steps.is_empty() {
        let first = protocol.approach_steps
            + ((protocol.stationary_from + 0.5 * (1.0 - protocol.stationary_from)) * protocol.steps as f64) as usize;
        (first..first + STRIP_FRAMES).filter(|&s| s < forward_end).collect()
    } else {
        o.snapshot_steps.iter().map(|&s| s as usize).take(8).collect()
    }
}
