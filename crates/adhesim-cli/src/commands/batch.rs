//! What `sweep` and `study` share to run many cases: the worker pool, panic capture (a
//! panicking case is an error of that case, not of the batch) and atomic writes (a killed
//! batch leaves whole files or none, so that it resumes from what is finished).

use anyhow::{anyhow, Context, Result};
use std::path::Path;

/// A pool of `jobs` worker threads for the cases.
pub fn worker_pool(jobs: usize) -> Result<rayon::ThreadPool> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .build()
        .context("cannot set up the thread pool")
}

/// Runs one case; a panic becomes an error `panic: MESSAGE`.
pub fn catch_panic<T>(case: impl FnOnce() -> Result<T>) -> Result<T> {
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(case)) {
        Ok(result) => result,
        Err(panic) => Err(anyhow!("{}", panic_message(panic.as_ref()))),
    }
}

/// `panic: MESSAGE` of a caught panic payload.
pub fn panic_message(panic: &(dyn std::any::Any + Send)) -> String {
    format!(
        "panic: {}",
        panic
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default()
    )
}

/// Writes a file through a temporary sibling and a rename, so readers never see half of it
/// (a full disk leaves the previous file or none, and an error naming the path).
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<()> {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let temp = path.with_file_name(format!(".{name}.{}.tmp", std::process::id()));
    let written = std::fs::File::create(&temp).and_then(|mut file| {
        use std::io::Write;
        file.write_all(bytes)?;
        file.sync_all()
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
