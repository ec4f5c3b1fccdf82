//! The one batch engine of `sweep` and `study`: a plan is a list of cases (each with an id,
//! a hash of what its results depend on, and a way to run it into a folder); the engine
//! runs them on a worker pool with panic capture, stores each finished case atomically as
//! `DIR/cases/<id>/` with a `done` marker (hash and status), resumes from the finished
//! cases, runs one shard of them, and counts the failures for a non-zero exit.
//!
//! A case is computed in `DIR/tmp/<id>.<pid>/` and renamed into place once its marker is
//! written, so a killed batch leaves whole case folders or none; a folder whose marker is
//! missing or holds another hash (another scenario, or an older
//! [`adhesim::RESULTS_REVISION`]) is redone.

mod cases;
#[cfg(test)]
mod checkpoint_tests;
mod pool;
#[cfg(test)]
mod tests;

pub use crate::hash::fnv1a;
use crate::output::checkpoint::CheckpointPolicy;
use crate::output::folder::{FolderLock, Shard};
use anyhow::{anyhow, bail, Context, Result};
pub use cases::{case_state, results_hash, run_case, CaseState};
use std::path::{Path, PathBuf};

/// One case of a batch.
pub trait BatchCase: Sync {
    /// The case's folder name under `DIR/cases/`.
    fn id(&self) -> &str;
    /// Hash of everything its results depend on (scenario and results revision), kept in
    /// the `done` marker: a finished folder with another hash is redone.
    fn hash(&self) -> &str;
    /// Writes the files that describe the case into its folder before it runs; an error
    /// here is a failure of the batch (the folder cannot be written), not of the case.
    fn describe(&self, _folder: &Path) -> Result<()> {
        Ok(())
    }
    /// Runs the case, writing its outputs into `folder`; an error or a panic is a failure
    /// of this case (kept in its `error.txt`), not of the batch.
    fn run(&self, folder: &Path) -> Result<()>;
    /// As [`run`](Self::run), writing mid-run checkpoints into `folder` by `policy` and
    /// continuing from the one found there (docs/sweeps.md, "Resuming a case mid-run"). Default: a case
    /// without checkpoints runs as [`run`](Self::run).
    fn run_checkpointed(&self, folder: &Path, _policy: &CheckpointPolicy) -> Result<()> {
        self.run(folder)
    }
}

/// Wall time between two mid-case checkpoints unless set ([`Batch::set_checkpoint_seconds`]).
pub const DEFAULT_CHECKPOINT_SECONDS: f64 = 600.0;

/// A batch folder, locked (for its shard) while this value lives: a second command on the
/// same cases is refused, not interleaved.
pub struct Batch {
    dir: PathBuf,
    shard: Shard,
    /// Seconds between mid-case checkpoints (0: none, and no case is continued).
    checkpoint_seconds: f64,
    _lock: FolderLock,
}

/// The cases of this shard sorted by what the folder holds for them.
pub struct Pending<'a, C> {
    /// Cases to run now (missing, broken, of another hash, or failed and retried).
    pub todo: Vec<&'a C>,
    /// Cases finished earlier (successfully, or failed and kept).
    pub finished: Vec<&'a C>,
    /// Ids of the cases that failed earlier and are kept (not retried).
    pub kept_failures: Vec<String>,
    /// Cases of this shard.
    pub selected: usize,
    /// Temporary folders of killed runs with a checkpoint to continue from, by case id.
    pub resumable: std::collections::HashMap<String, PathBuf>,
}

/// What [`Batch::execute`] did.
pub struct Outcome {
    pub selected: usize,
    pub ran: usize,
    pub skipped: usize,
    /// Ids of the cases that failed in this run.
    pub failed_now: Vec<String>,
    pub kept_failures: Vec<String>,
}

impl Batch {
    /// Takes the lock of `shard` in `dir` (created if missing).
    pub fn open(dir: &Path, shard: Shard) -> Result<Self> {
        let lock = FolderLock::acquire(dir, shard)?;
        Ok(Self {
            dir: dir.to_path_buf(),
            shard,
            checkpoint_seconds: DEFAULT_CHECKPOINT_SECONDS,
            _lock: lock,
        })
    }

    /// Writes a checkpoint of each running case every `seconds` of wall time (0: none, and
    /// killed cases restart from scratch); an error for a negative or non-finite value.
    pub fn set_checkpoint_seconds(&mut self, seconds: f64) -> Result<()> {
        CheckpointPolicy::every_seconds(seconds, "")?;
        self.checkpoint_seconds = seconds;
        Ok(())
    }

    /// The checkpoint policy of `case` (none when checkpoints are off).
    fn checkpoint_policy(&self, case: &dyn BatchCase) -> Option<CheckpointPolicy> {
        CheckpointPolicy::every_seconds(self.checkpoint_seconds, case.hash())
            .ok()
            .flatten()
    }

    /// Sorts this shard's cases (those whose position modulo the shard count is the
    /// shard's index) into finished and to do; removes the leftovers of killed runs of
    /// the cases to do and their broken folders. Failed cases are redone with
    /// `retry_failed`, otherwise kept.
    pub fn pending<'a, C: BatchCase>(&self, cases: &'a [C], retry_failed: bool) -> Result<Pending<'a, C>> {
        let temp_root = self.dir.join("tmp");
        std::fs::create_dir_all(self.dir.join("cases"))
            .and_then(|()| std::fs::create_dir_all(&temp_root))
            .with_context(|| format!("cannot create {}/cases and tmp", self.dir.display()))?;
        let mut pending = Pending {
            todo: Vec::new(),
            finished: Vec::new(),
            kept_failures: Vec::new(),
            selected: 0,
            resumable: std::collections::HashMap::new(),
        };
        let shard = self.shard;
        for case in cases.iter().skip(shard.index).step_by(shard.count) {
            pending.selected += 1;
            // Leftovers of a killed run of this case (only this shard's cases: other
            // shards may be running in the same folder), but the folder of a killed run
            // that left a checkpoint of this case, when the case is to be done.
            let state = case_state(&self.dir, case.id(), case.hash());
            let resumable = match (state, self.checkpoint_seconds > 0.0) {
                (CaseState::Finished { ok: true }, _) | (_, false) => None,
                (CaseState::Finished { ok: false }, true) if !retry_failed => None,
                _ => cases::resumable_temp_folder(&temp_root, case.id(), case.hash()),
            };
            cases::remove_temp_folders(&temp_root, case.id(), resumable.as_deref());
            if let Some(folder) = resumable {
                pending.resumable.insert(case.id().to_string(), folder);
            }
            match state {
                CaseState::Finished { ok: true } => pending.finished.push(case),
                CaseState::Finished { ok: false } if !retry_failed => {
                    pending.finished.push(case);
                    pending.kept_failures.push(case.id().to_string());
                }
                CaseState::Broken | CaseState::Finished { .. } => {
                    let folder = self.dir.join("cases").join(case.id());
                    std::fs::remove_dir_all(&folder).with_context(|| format!("cannot remove {}", folder.display()))?;
                    pending.todo.push(case);
                }
                CaseState::Missing => pending.todo.push(case),
            }
        }
        Ok(pending)
    }

    /// Runs the cases to do on `jobs` workers, each with a rayon pool of `threads` threads
    /// for the FFTs of its case; `finished(case, failure)` is called as each one ends.
    /// An `Err` is a failure of the batch itself (a folder that cannot be written): the
    /// workers stop taking cases and the cases finished so far are kept.
    pub fn execute<C: BatchCase>(
        &self,
        pending: Pending<'_, C>,
        jobs: usize,
        threads: usize,
        finished: &(dyn Fn(&C, Option<&str>) + Sync),
    ) -> Result<Outcome> {
        let failures = std::sync::Mutex::new(Vec::new());
        pool::for_each(&pending.todo, jobs, threads, |case| {
            let policy = self.checkpoint_policy(*case);
            let resume = pending.resumable.get(case.id()).map(PathBuf::as_path);
            let failure = cases::run_case(&self.dir, *case, policy.as_ref(), resume)
                .with_context(|| format!("case {}", case.id()))?;
            if failure.is_some() {
                failures.lock().expect("lock").push(case.id().to_string());
            }
            finished(case, failure.as_deref());
            Ok(())
        })?;
        Ok(Outcome {
            selected: pending.selected,
            ran: pending.todo.len(),
            skipped: pending.finished.len(),
            failed_now: failures.into_inner().expect("lock"),
            kept_failures: pending.kept_failures,
        })
    }

    /// The folder of a finished case.
    pub fn case_folder(&self, id: &str) -> PathBuf {
        self.dir.join("cases").join(id)
    }
}

impl Outcome {
    /// The batch's exit: an error counting the failed cases of this run (and those kept
    /// from an earlier run), so that a script notices; Ok when none failed. `noun` names
    /// the cases (`cases`, `study runs`).
    pub fn failure_status(&self, dir: &Path, noun: &str) -> Result<()> {
        let (failed_now, kept) = (&self.failed_now, &self.kept_failures);
        let total = failed_now.len() + kept.len();
        if total == 0 {
            return Ok(());
        }
        let list = |ids: &[String]| {
            let mut text = ids.iter().take(10).cloned().collect::<Vec<_>>().join(", ");
            if ids.len() > 10 {
                text.push_str(", ...");
            }
            text
        };
        let mut message = format!("{total} of {} {noun} failed", self.selected);
        if !failed_now.is_empty() {
            message.push_str(&format!("; {} in this run: {}", failed_now.len(), list(failed_now)));
        }
        if !kept.is_empty() {
            message.push_str(&format!(
                "; {} failed earlier and were kept (--retry-failed redoes them): {}",
                kept.len(),
                list(kept)
            ));
        }
        bail!(
            "{message} (each case's error is in {}/cases/<id>/error.txt)",
            dir.display()
        )
    }
}

/// Parses `--shard I/N` with 0 <= I < N (no option: all cases).
pub fn parse_shard(text: Option<&str>) -> Result<Shard> {
    let Some(text) = text else { return Ok(Shard::ALL) };
    let bad = || anyhow!("--shard expects I/N with 0 <= I < N (e.g. 0/4), got `{text}`");
    let (i, n) = text.split_once('/').ok_or_else(bad)?;
    let i: usize = i.trim().parse().map_err(|_| bad())?;
    let n: usize = n.trim().parse().map_err(|_| bad())?;
    if n == 0 || i >= n {
        return Err(bad());
    }
    Ok(Shard { index: i, count: n })
}

/// Writes a file through a temporary sibling and a rename, so readers never see half of it
/// (a full disk leaves the previous file or none, and an error naming the path).
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<()> {
    crate::output::write_through_temp(path, bytes, true)
}
