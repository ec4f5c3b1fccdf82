//! The rayon pool the package's calls run on: the process's own, built again in a forked
//! child, never rayon's global one. A process forked from one whose global pool has run
//! (a fork-started `ProcessPoolExecutor`) inherits that pool without its threads, and a
//! call on it would wait for them forever.

use pyo3::exceptions::{PyUserWarning, PyValueError};
use pyo3::prelude::*;
use rayon::ThreadPool;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Arc, Mutex};
use std::time::Duration;

/// The pool of this process (by its id) and the id it was built in.
static PROCESS_POOL: Mutex<Option<(u32, Arc<ThreadPool>)>> = Mutex::new(None);

/// The process's pool, built on first use and again after a fork (as many threads as
/// rayon's global pool would have: `RAYON_NUM_THREADS`, else the cores).
fn process_pool() -> PyResult<Arc<ThreadPool>> {
    let id = std::process::id();
    let mut slot = PROCESS_POOL.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    if let Some((built_in, pool)) = slot.as_ref() {
        if *built_in == id {
            return Ok(Arc::clone(pool));
        }
    }
    let pool = Arc::new(
        rayon::ThreadPoolBuilder::new()
            .build()
            .map_err(|e| PyValueError::new_err(format!("cannot build a thread pool: {e}")))?,
    );
    // A pool inherited through a fork has no threads to stop: it is left, not dropped.
    if let Some(inherited) = slot.replace((id, Arc::clone(&pool))) {
        std::mem::forget(inherited);
    }
    Ok(pool)
}

/// Runs `work` with the GIL released on the process's pool.
pub fn detached<T: Send>(py: Python<'_>, work: impl FnOnce() -> T + Send) -> PyResult<T> {
    let pool = process_pool()?;
    Ok(py.detach(|| pool.install(work)))
}

/// The pool of a run: `threads` threads of its own (more than the cores this process may
/// use are clamped with a warning, as `--threads` is), or the process's pool.
pub fn run_pool(py: Python<'_>, threads: Option<usize>) -> PyResult<Arc<ThreadPool>> {
    let Some(requested) = threads else {
        return process_pool();
    };
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let threads = match requested {
        0 => return Err(PyValueError::new_err("threads must be >= 1, got 0")),
        requested if requested > cores => {
            let message =
                format!("threads = {requested} exceeds the {cores} cores this process may use; using {cores}");
            PyErr::warn(
                py,
                &py.get_type::<PyUserWarning>(),
                &std::ffi::CString::new(message)?,
                1,
            )?;
            cores
        }
        requested => requested,
    };
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map(Arc::new)
        .map_err(|e| PyValueError::new_err(format!("cannot build a thread pool of {threads} threads: {e}")))
}

/// Runs `work` on `pool` with the GIL released while the calling thread keeps Python's
/// signal handlers running: they run on the main thread only, and `work` runs on a pool
/// thread. They are run every 50 ms and when `work` ends; the first exception one raises
/// (KeyboardInterrupt) sets `interrupted`, which the run checks between steps, and is
/// returned beside `work`'s result.
pub fn run_watching_signals<T: Send>(
    py: Python<'_>,
    pool: &ThreadPool,
    interrupted: &AtomicBool,
    work: impl FnOnce() -> T + Send,
) -> (T, Option<PyErr>) {
    py.detach(|| {
        let (done, finished) = mpsc::channel();
        std::thread::scope(|scope| {
            let worker = scope.spawn(move || {
                let result = pool.install(work);
                let _ = done.send(());
                result
            });
            let mut raised = None;
            loop {
                let ended = finished.recv_timeout(Duration::from_millis(50)).is_ok() || worker.is_finished();
                if raised.is_none() {
                    if let Err(error) = Python::attach(|py| py.check_signals()) {
                        interrupted.store(true, Ordering::SeqCst);
                        raised = Some(error);
                    }
                }
                if ended {
                    break;
                }
            }
            let result = worker.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic));
            (result, raised)
        })
    })
}
