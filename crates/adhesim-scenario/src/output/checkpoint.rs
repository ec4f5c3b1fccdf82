//! Mid-case checkpoints of a run into a folder (docs/sweeps.md, "Resuming a case
//! mid-run"; the file is in docs/output.md, "A sweep"): every `every` of wall time an
//! indentation writes
//! `checkpoint.json` into its folder, atomically (a temporary sibling, fsync, rename). It
//! holds the protocol's and the solver's state after the last step, the records so far and
//! the output observer's state, so that a run continued from it writes the files of the
//! uninterrupted run byte for byte (the `performance` timings excepted).
//!
//! The file is two lines of JSON: a short header (format, adhesim version, results
//! revision, the case's hash, steps done), read alone to decide whether a killed case's
//! folder is continued, then the body.

use super::observer::ObserverState;
use adhesim::{ProtocolCheckpoint, StepRecord};
use anyhow::{anyhow, bail, Context, Result};
use serde::{Deserialize, Serialize};
use std::io::BufRead;
use std::path::Path;
use std::time::Duration;

/// The checkpoint's file name in a run folder.
pub const CHECKPOINT_FILE: &str = "checkpoint.json";

/// The version of the file's layout (2: the protocol's state is tagged `Indentation` or
/// `Translation`).
const FORMAT: &str = "adhesim-checkpoint-2";

/// When a run writes checkpoints, and for which case.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckpointPolicy {
    /// Wall time between two checkpoints (> 0).
    pub every: Duration,
    /// The case's hash (its scenario and the results revision): a checkpoint of another
    /// hash is not continued.
    pub case_hash: String,
}

impl CheckpointPolicy {
    /// Every `seconds` of wall time; `None` for 0 (checkpoints off). An error for a
    /// negative or non-finite interval.
    pub fn every_seconds(seconds: f64, case_hash: &str) -> Result<Option<Self>> {
        if !(seconds.is_finite() && seconds >= 0.0) {
            bail!("the checkpoint interval must be a number of seconds >= 0 (0: off), got {seconds}");
        }
        Ok((seconds > 0.0).then(|| Self {
            every: Duration::from_secs_f64(seconds),
            case_hash: case_hash.to_string(),
        }))
    }
}

/// The first line of `checkpoint.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CheckpointHeader {
    pub format: String,
    pub adhesim_version: String,
    pub results_revision: u32,
    pub case_hash: String,
    /// Steps done: the run goes on with this step number.
    pub steps_done: usize,
}

impl CheckpointHeader {
    fn current(case_hash: &str, steps_done: usize) -> Self {
        Self {
            format: FORMAT.to_string(),
            adhesim_version: env!("CARGO_PKG_VERSION").to_string(),
            results_revision: adhesim::RESULTS_REVISION,
            case_hash: case_hash.to_string(),
            steps_done,
        }
    }

    /// Why a run of the case with `case_hash` by this build cannot continue from it.
    pub fn mismatch(&self, case_hash: &str) -> Option<String> {
        let current = Self::current(case_hash, self.steps_done);
        if self.format != current.format {
            Some(format!("its format is `{}`, not `{FORMAT}`", self.format))
        } else if self.adhesim_version != current.adhesim_version {
            Some(format!(
                "it was written by adhesim {}, this is {}",
                self.adhesim_version, current.adhesim_version
            ))
        } else if self.results_revision != current.results_revision {
            Some(format!(
                "it is of results revision {}, this build's is {}",
                self.results_revision, current.results_revision
            ))
        } else if self.case_hash != case_hash {
            Some(format!(
                "it is of another scenario (hash {}, the case's is {case_hash})",
                self.case_hash
            ))
        } else {
            None
        }
    }
}

/// Reads the header line of the checkpoint at `path`.
pub fn read_header(path: &Path) -> Result<CheckpointHeader> {
    let file = std::fs::File::open(path).with_context(|| "cannot open it".to_string())?;
    let mut line = String::new();
    std::io::BufReader::new(file)
        .read_line(&mut line)
        .context("cannot read it")?;
    serde_json::from_str(&line).map_err(|error| anyhow!("its header is not valid ({error})"))
}

#[derive(Serialize)]
struct BodyRef<'a> {
    protocol: &'a ProtocolCheckpoint,
    records: &'a [StepRecord],
    observer: &'a ObserverState,
}

/// The second line of `checkpoint.json`.
#[derive(Deserialize)]
pub(crate) struct Body {
    pub protocol: ProtocolCheckpoint,
    pub records: Vec<StepRecord>,
    pub observer: ObserverState,
}

/// Writes `folder/checkpoint.json` atomically and durably.
pub(crate) fn write(
    folder: &Path,
    policy: &CheckpointPolicy,
    protocol: &ProtocolCheckpoint,
    records: &[StepRecord],
    observer: &ObserverState,
) -> Result<()> {
    let header = CheckpointHeader::current(&policy.case_hash, protocol.steps_done());
    let mut bytes = serde_json::to_vec(&header)?;
    bytes.push(b'\n');
    serde_json::to_writer(
        &mut bytes,
        &BodyRef {
            protocol,
            records,
            observer,
        },
    )?;
    bytes.push(b'\n');
    super::write_through_temp(&folder.join(CHECKPOINT_FILE), &bytes, true)
}

/// Reads `folder/checkpoint.json` of `policy`'s case: `Ok(None)` without one, an error
/// saying why one cannot be continued (its header, its body, or a size that is not the
/// grid's: `elements`).
pub(crate) fn read(folder: &Path, policy: &CheckpointPolicy, elements: usize) -> Result<Option<Body>> {
    let path = folder.join(CHECKPOINT_FILE);
    if !path.exists() {
        return Ok(None);
    }
    let header = read_header(&path)?;
    if let Some(why) = header.mismatch(&policy.case_hash) {
        bail!(why);
    }
    let text = std::fs::read_to_string(&path).context("cannot read it")?;
    let body = text
        .split_once('\n')
        .map(|(_, body)| body)
        .ok_or_else(|| anyhow!("it has no body"))?;
    let body: Body = serde_json::from_str(body).map_err(|error| anyhow!("its body is not valid ({error})"))?;
    let steps = body.protocol.steps_done();
    if steps != header.steps_done || body.records.len() != steps {
        bail!(
            "its header says {} steps, its body holds {} records after step {steps}",
            header.steps_done,
            body.records.len()
        );
    }
    if body.protocol.state().pressure.len() != elements || !body.observer.fits(elements) {
        bail!(
            "it is of {} elements, the grid has {elements}",
            body.protocol.state().pressure.len()
        );
    }
    Ok(Some(body))
}

/// Removes the checkpoint of a run folder and the temporary files of checkpoints that a
/// killed run left half written.
pub(crate) fn remove(folder: &Path) {
    let _ = std::fs::remove_file(folder.join(CHECKPOINT_FILE));
    if let Ok(entries) = std::fs::read_dir(folder) {
        for entry in entries.flatten() {
            let name = entry.file_name().to_string_lossy().into_owned();
            if name.starts_with(&format!(".{CHECKPOINT_FILE}.")) && name.ends_with(".tmp") {
                let _ = std::fs::remove_file(entry.path());
            }
        }
    }
}
