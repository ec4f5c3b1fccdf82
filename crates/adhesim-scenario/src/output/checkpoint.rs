//! Mid-case checkpoints of a run into a folder (docs/sweeps.md, "Resuming a case
//! mid-run"; the file is in docs/output.md, "A sweep"): every `every` of wall time an
//! indentation writes
//! `checkpoint.json` into its folder, atomically (a temporary sibling, fsync, rename). It
//! holds the protocol's and the solver's state after the last step, the records so far and
//! the output observer's state, so that a run continued from it writes the files of the
//! uninterrupted run byte for byte (the `performance` timings excepted).
//!
//! The file is two lines of JSON: a short header (format, adhesim version, results
//! revision, the case's hash, steps done, checksum), read alone to decide whether a killed
//! case's folder is continued, then the body. The checksum (64-bit FNV-1a) covers the
//! header's fields, the case's hash (its scenario) among them, and the body's bytes: a
//! checkpoint edited, cut or taken from another case is never continued, the case restarts
//! from scratch with a warning naming the file.

use super::observer_state::ObserverState;
use crate::hash::fnv1a;
use adhesim::{ProtocolCheckpoint, StepRecord};
use anyhow::{anyhow, bail, Context, Result};
use serde::{Deserialize, Serialize};
use std::io::{BufRead, Read};
use std::path::Path;
use std::time::Duration;

/// The checkpoint's file name in a run folder.
pub const CHECKPOINT_FILE: &str = "checkpoint.json";

/// The version of the file's layout (2: the protocol's state is tagged `Indentation` or
/// `Translation`; 3: the header carries the checksum).
const FORMAT: &str = "adhesim-checkpoint-3";

/// The longest interval between two checkpoints, in seconds (about 32 years; `Duration`
/// holds up to 1.8e19 s, and a value beyond it panicked). 0 turns checkpoints off.
pub const MAX_CHECKPOINT_SECONDS: f64 = 1e9;

/// The longest header line read (it is about 200 bytes).
const MAX_HEADER_BYTES: u64 = 64 << 10;

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
        if !(seconds.is_finite() && (0.0..=MAX_CHECKPOINT_SECONDS).contains(&seconds)) {
            bail!(
                "the checkpoint interval must be a number of seconds from 0 (off) to {MAX_CHECKPOINT_SECONDS:e}, got {seconds:e}"
            );
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
    /// FNV-1a of the fields above and the body line, 16 hex digits ([`Self::checksum_of`]);
    /// empty in files of an older format.
    #[serde(default)]
    pub checksum: String,
}

impl CheckpointHeader {
    fn current(case_hash: &str, steps_done: usize) -> Self {
        Self {
            format: FORMAT.to_string(),
            adhesim_version: env!("CARGO_PKG_VERSION").to_string(),
            results_revision: adhesim::RESULTS_REVISION,
            case_hash: case_hash.to_string(),
            steps_done,
            checksum: String::new(),
        }
    }

    /// The checksum of this header's fields (but the checksum) and the body line `body`
    /// (without its line end).
    fn checksum_of(&self, body: &str) -> String {
        let text = format!(
            "{}\n{}\n{}\n{}\n{}\n{body}",
            self.format, self.adhesim_version, self.results_revision, self.case_hash, self.steps_done
        );
        format!("{:016x}", fnv1a(&text))
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

/// Reads the header line of the checkpoint at `path` (a regular file: a FIFO put in its
/// place blocked the next sweep, a link to /dev/zero read without end).
pub fn read_header(path: &Path) -> Result<CheckpointHeader> {
    crate::files::check_regular_file(path, "checkpoint")?;
    let file = std::fs::File::open(path).with_context(|| "cannot open it".to_string())?;
    let mut line = String::new();
    std::io::BufReader::new(file.take(MAX_HEADER_BYTES))
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
    let body = serde_json::to_string(&BodyRef {
        protocol,
        records,
        observer,
    })?;
    let mut header = CheckpointHeader::current(&policy.case_hash, protocol.steps_done());
    header.checksum = header.checksum_of(&body);
    let mut bytes = serde_json::to_vec(&header)?;
    bytes.push(b'\n');
    bytes.extend_from_slice(body.as_bytes());
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
    let bytes = crate::files::read_own_file(&path, "checkpoint", u64::MAX)?;
    let text = String::from_utf8(bytes).map_err(|_| anyhow!("it is not text"))?;
    let body = text
        .split_once('\n')
        .map(|(_, body)| body)
        .ok_or_else(|| anyhow!("it has no body"))?;
    let body = body.strip_suffix('\n').unwrap_or(body);
    if header.checksum != header.checksum_of(body) {
        bail!("its checksum does not match its content (the file was changed or cut after it was written)");
    }
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

/// The checkpoint file `text` moved to the case `case_hash` with a valid checksum: for
/// tests of the checks behind the checksum (another grid, another protocol).
#[cfg(test)]
pub(crate) fn resigned(text: &str, case_hash: &str) -> String {
    let (header, body) = text.split_once('\n').expect("a header line");
    let body = body.strip_suffix('\n').unwrap_or(body);
    let mut header: CheckpointHeader = serde_json::from_str(header).expect("a header");
    header.case_hash = case_hash.to_string();
    header.checksum = header.checksum_of(body);
    format!("{}\n{body}\n", serde_json::to_string(&header).expect("JSON"))
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
