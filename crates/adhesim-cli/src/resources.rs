//! Resource guards of the command line (`docs/reliability.md`, "Scenario inputs and
//! resources"): the memory available to a run and the thread count.

pub use adhesim_scenario::memory::{check_allocation, MemoryLimit};

/// The memory limit for a run ([`adhesim_scenario::memory_limit`]): with `--allow-large`
/// only RLIMIT_AS (`prlimit --as`, `ulimit -v`), which nothing gets past.
pub fn memory_limit(allow_large: bool) -> anyhow::Result<Option<MemoryLimit>> {
    adhesim_scenario::memory_limit(allow_large.then_some("--allow-large"))
}

/// Cores of this machine.
pub fn cores() -> usize {
    std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1)
}

/// `--threads N`: 0 is an error; more than the machine's cores only oversubscribes them
/// (a 0.2 s run took a minute with 1000 threads), so it is clamped with a warning.
pub fn clamp_threads(requested: usize) -> anyhow::Result<usize> {
    if requested == 0 {
        anyhow::bail!("--threads must be >= 1, got 0");
    }
    let cores = cores();
    if requested > cores {
        eprintln!("warning: --threads {requested} exceeds the {cores} cores of this machine; using {cores}");
        return Ok(cores);
    }
    Ok(requested)
}
