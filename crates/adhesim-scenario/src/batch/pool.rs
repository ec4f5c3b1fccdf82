//! The worker pool of a batch and its panic capture (a panicking case is an error of that
//! case, not of the batch).

use anyhow::{anyhow, Result};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// Calls `work` on every item from `jobs` worker threads, each inside its own rayon pool of
/// `threads` threads (the parallel FFTs of its item). The first error `work` returns stops
/// the workers from taking more items and is returned.
pub fn for_each<T: Sync>(
    items: &[T],
    jobs: usize,
    threads: usize,
    work: impl Fn(&T) -> Result<()> + Sync,
) -> Result<()> {
    let next = AtomicUsize::new(0);
    let fatal: Mutex<Option<anyhow::Error>> = Mutex::new(None);
    std::thread::scope(|scope| {
        for _ in 0..jobs.min(items.len()) {
            scope.spawn(|| {
                let pool = match rayon::ThreadPoolBuilder::new().num_threads(threads).build() {
                    Ok(pool) => pool,
                    Err(e) => {
                        *fatal.lock().expect("lock") = Some(anyhow!("cannot build a thread pool: {e}"));
                        return;
                    }
                };
                loop {
                    if fatal.lock().expect("lock").is_some() {
                        return;
                    }
                    let k = next.fetch_add(1, Ordering::SeqCst);
                    let Some(item) = items.get(k) else { return };
                    if let Err(error) = pool.install(|| work(item)) {
                        *fatal.lock().expect("lock") = Some(error);
                        return;
                    }
                }
            });
        }
    });
    match fatal.into_inner().expect("lock") {
        Some(error) => Err(error),
        None => Ok(()),
    }
}

/// Runs one case; a panic becomes an error `panic: MESSAGE`.
pub fn catch_panic<T>(case: impl FnOnce() -> Result<T>) -> Result<T> {
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(case)) {
        Ok(result) => result,
        Err(panic) => Err(anyhow!("{}", panic_message(panic.as_ref()))),
    }
}

/// `panic: MESSAGE` of a caught panic payload.
fn panic_message(panic: &(dyn std::any::Any + Send)) -> String {
    format!(
        "panic: {}",
        panic
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default()
    )
}
