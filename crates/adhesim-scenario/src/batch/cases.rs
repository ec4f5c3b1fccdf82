//! Case folders: `DIR/cases/<id>/` with a `done` marker (`hash = …`, `status = ok|error`),
//! computed in `DIR/tmp/<id>.<pid>/` and renamed into place when finished.

use super::{pool::catch_panic, BatchCase};
use crate::hash::fnv1a;
use crate::output::checkpoint::{read_header, CheckpointPolicy, CHECKPOINT_FILE};
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};

/// What a case folder's `done` marker says.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CaseState {
    Missing,
    Finished {
        ok: bool,
    },
    /// A folder without a valid marker, or from a different case (another hash).
    Broken,
}

/// Reads `DIR/cases/<id>/done` against the case's `hash`.
pub fn case_state(dir: &Path, id: &str, hash: &str) -> CaseState {
    let folder = dir.join("cases").join(id);
    if !folder.exists() {
        return CaseState::Missing;
    }
    let Ok(text) = crate::files::read_own_text(&folder.join("done"), "case marker", 4096) else {
        return CaseState::Broken;
    };
    let field = |name: &str| {
        text.lines()
            .find_map(|l| l.strip_prefix(name).and_then(|r| r.strip_prefix(" = ")))
            .map(str::trim)
    };
    match (field("hash"), field("status")) {
        (Some(found), Some(status)) if found == hash => CaseState::Finished { ok: status == "ok" },
        _ => CaseState::Broken,
    }
}

/// The folders `TEMP_ROOT/<id>.<pid>`: what runs of the case left, with their pids.
fn temp_folders(temp_root: &Path, id: &str) -> Vec<(PathBuf, Option<u32>)> {
    let Ok(entries) = std::fs::read_dir(temp_root) else {
        return Vec::new();
    };
    let mut found: Vec<_> = entries
        .flatten()
        .filter_map(|entry| {
            let name = entry.file_name().to_string_lossy().into_owned();
            let rest = name.strip_prefix(id)?.strip_prefix('.')?;
            Some((entry.path(), rest.parse().ok()))
        })
        .collect();
    found.sort();
    found
}

/// Removes `TEMP_ROOT/<id>.*` (what killed runs of the case left) but `keep`.
pub(super) fn remove_temp_folders(temp_root: &Path, id: &str, keep: Option<&Path>) {
    for (path, _) in temp_folders(temp_root, id) {
        if Some(path.as_path()) != keep {
            let _ = std::fs::remove_dir_all(path);
        }
    }
}

/// The temporary folder of a killed run of the case (its process is gone) holding a
/// checkpoint of this case (`hash`) by this build, with the most steps done: the case goes
/// on from it ("resumed case X at step k" on stderr). A checkpoint that cannot be continued
/// gets a one-line warning naming the file and why (its folder is then removed as any).
pub(super) fn resumable_temp_folder(temp_root: &Path, id: &str, hash: &str) -> Option<PathBuf> {
    let mut best: Option<(PathBuf, usize)> = None;
    for (path, pid) in temp_folders(temp_root, id) {
        let file = path.join(CHECKPOINT_FILE);
        let alive = pid.and_then(crate::output::folder::process_alive);
        if !file.exists() || alive == Some(true) || pid.is_none() {
            continue;
        }
        let header = read_header(&file).and_then(|header| match header.mismatch(hash) {
            Some(why) => Err(anyhow::anyhow!(why)),
            None => Ok(header),
        });
        match header {
            Ok(header) if best.as_ref().is_none_or(|(_, steps)| header.steps_done > *steps) => {
                best = Some((path, header.steps_done));
            }
            Ok(_) => {}
            Err(why) => eprintln!(
                "warning: checkpoint {} not used: {why:#}; case {id} restarts from scratch",
                file.display()
            ),
        }
    }
    let (path, steps) = best?;
    eprintln!(
        "resumed case {id} at step {steps} (from {})",
        path.join(CHECKPOINT_FILE).display()
    );
    Some(path)
}

/// Runs one case into a temporary folder and renames it into place. `Ok(Some(message))`
/// is a failed case (recorded in its folder's `error.txt`); `Err` is a failure of the
/// batch itself (the output folder cannot be written).
///
/// With `policy`, the run writes mid-run checkpoints into its folder; `resume` is the
/// folder of a killed run with a checkpoint to continue from, adopted (renamed to this
/// process's folder) instead of a new one.
pub fn run_case<C: BatchCase>(
    dir: &Path,
    case: &C,
    policy: Option<&CheckpointPolicy>,
    resume: Option<&Path>,
) -> Result<Option<String>> {
    let id = case.id();
    let temp = dir.join("tmp").join(format!("{id}.{}", std::process::id()));
    let adopt = resume.filter(|folder| folder.is_dir());
    if temp.exists() && adopt != Some(temp.as_path()) {
        std::fs::remove_dir_all(&temp).with_context(|| format!("cannot remove {}", temp.display()))?;
    }
    if let Some(folder) = adopt.filter(|folder| *folder != temp) {
        std::fs::rename(folder, &temp)
            .with_context(|| format!("cannot move {} to {}", folder.display(), temp.display()))?;
    }
    std::fs::create_dir_all(&temp).with_context(|| format!("cannot create {}", temp.display()))?;
    case.describe(&temp)?;
    let failure = catch_panic(|| match policy {
        Some(policy) => case.run_checkpointed(&temp, policy),
        None => case.run(&temp),
    })
    .err()
    .map(|error| crate::error_text::error_line(error.chain()));
    if let Some(message) = &failure {
        std::fs::write(temp.join("error.txt"), format!("{message}\n"))?;
    }
    let status = if failure.is_none() { "ok" } else { "error" };
    std::fs::write(
        temp.join("done"),
        format!("hash = {}\nstatus = {status}\n", case.hash()),
    )?;
    let target = dir.join("cases").join(id);
    if target.exists() {
        if matches!(case_state(dir, id, case.hash()), CaseState::Finished { .. }) {
            // Someone else (a concurrent run of the same shard) finished it first.
            std::fs::remove_dir_all(&temp)?;
            return Ok(failure);
        }
        std::fs::remove_dir_all(&target).with_context(|| format!("cannot remove {}", target.display()))?;
    }
    std::fs::rename(&temp, &target)
        .with_context(|| format!("cannot move {} to {}", temp.display(), target.display()))?;
    Ok(failure)
}

/// Hash of the results a scenario gives: its text and the library's
/// [`adhesim::RESULTS_REVISION`] (a cached case from an older algorithm is redone).
pub fn results_hash(scenario_text: &str) -> u64 {
    fnv1a(&format!(
        "{scenario_text}\nresults revision {}",
        adhesim::RESULTS_REVISION
    ))
}
