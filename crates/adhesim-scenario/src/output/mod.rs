//! The output layer of a run, shared by `adhesim run`, `sweep`, `study` and the Python
//! package: the run folder (marker, clearing, locks), `curve.csv`, the phase timings and
//! the field files, each written whole or not at all.

pub mod checkpoint;
pub mod curve_csv;
pub mod fields;
pub mod folder;
pub mod observer;
mod observer_state;
pub mod parts;
pub mod run;
pub mod snapshot_maps;
pub mod timings;

use anyhow::{anyhow, Context, Result};
use std::io::Write;
use std::path::Path;

/// Writes `bytes` to a temporary sibling of `path`, checked through its flush (and synced
/// to disk where `durable`: the batch engine's markers and tables), then renames it into
/// place; a failed write removes the temporary file and names both.
pub fn write_through_temp(path: &Path, bytes: &[u8], durable: bool) -> Result<()> {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let temp = path.with_file_name(format!(".{name}.{}.tmp", std::process::id()));
    let written = std::fs::File::create(&temp).and_then(|mut file| {
        file.write_all(bytes)?;
        if durable {
            file.sync_all()
        } else {
            file.flush()
        }
    });
    if let Err(error) = written {
        let _ = std::fs::remove_file(&temp);
        return Err(anyhow!(error).context(format!(
            "cannot write {} (through the temporary file {})",
            path.display(),
            temp.display()
        )));
    }
    std::fs::rename(&temp, path).with_context(|| format!("cannot write {}", path.display()))
}
