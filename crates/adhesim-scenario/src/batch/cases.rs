//! Case folders: `DIR/cases/<id>/` with a `done` marker (`hash = …`, `status = ok|error`),
//! computed in `DIR/tmp/<id>.<pid>/` and renamed into place when finished.

use super::{pool::catch_panic, BatchCase};
use anyhow::{Context, Result};
use std::path::Path;

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
    let Ok(text) = std::fs::read_to_string(folder.join("done")) else {
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

/// Removes `TEMP_ROOT/<id>.*`: what killed runs of the case left.
pub(super) fn remove_temp_folders(temp_root: &Path, id: &str) {
    let Ok(entries) = std::fs::read_dir(temp_root) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        if name.strip_prefix(id).is_some_and(|rest| rest.starts_with('.')) {
            let _ = std::fs::remove_dir_all(entry.path());
        }
    }
}

/// Runs one case into a temporary folder and renames it into place. `Ok(Some(message))`
/// is a failed case (recorded in its folder's `error.txt`); `Err` is a failure of the
/// batch itself (the output folder cannot be written).
pub fn run_case<C: BatchCase>(dir: &Path, case: &C) -> Result<Option<String>> {
    let id = case.id();
    let temp = dir.join("tmp").join(format!("{id}.{}", std::process::id()));
    if temp.exists() {
        std::fs::remove_dir_all(&temp).with_context(|| format!("cannot remove {}", temp.display()))?;
    }
    std::fs::create_dir_all(&temp).with_context(|| format!("cannot create {}", temp.display()))?;
    case.describe(&temp)?;
    let failure = catch_panic(|| case.run(&temp))
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

/// 64-bit FNV-1a (stable across platforms and Rust versions, unlike `DefaultHasher`).
pub fn fnv1a(text: &str) -> u64 {
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for byte in text.bytes() {
        hash ^= u64::from(byte);
        hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
    }
    hash
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv1a_is_the_standard_hash() {
        assert_eq!(fnv1a(""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a("a"), 0xaf63_dc4c_8601_ec8c);
    }
}
