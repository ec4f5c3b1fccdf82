//! Resource guards of the command line (`docs/reliability.md`, "Scenario inputs and
//! resources"): the memory available to a run and the thread count.

/// Environment variable that states the memory available in bytes, instead of
/// `/proc/meminfo` (a container whose limit /proc does not show; tests).
pub const MEMORY_VARIABLE: &str = "ADHESIM_MEMORY_AVAILABLE";

/// The memory available in bytes: [`MEMORY_VARIABLE`] where set, else `MemAvailable` of
/// `/proc/meminfo`; `None` where neither is there (not Linux): then no memory guard applies.
pub fn available_memory() -> anyhow::Result<Option<u64>> {
    if let Ok(value) = std::env::var(MEMORY_VARIABLE) {
        return match value.trim().parse::<u64>() {
            Ok(bytes) => Ok(Some(bytes)),
            Err(_) => anyhow::bail!("{MEMORY_VARIABLE} must be a number of bytes, got `{value}`"),
        };
    }
    Ok(std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|text| parse_mem_available(&text)))
}

/// The `MemAvailable:   123456 kB` line of a `/proc/meminfo` text, in bytes.
fn parse_mem_available(text: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kilobytes: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kilobytes.checked_mul(1024)
}

/// The memory limit for a run: `None` (no check) with `--allow-large`.
pub fn memory_limit(allow_large: bool) -> anyhow::Result<Option<u64>> {
    if allow_large {
        Ok(None)
    } else {
        available_memory()
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mem_available_is_read_in_bytes() {
        let text = "MemTotal:       16314264 kB\nMemFree:         1000000 kB\nMemAvailable:    8000000 kB\n";
        assert_eq!(parse_mem_available(text), Some(8_000_000 * 1024));
        assert_eq!(parse_mem_available("MemTotal: 1 kB\n"), None);
        assert_eq!(parse_mem_available("MemAvailable: lots kB\n"), None);
    }

    #[test]
    fn thread_counts_are_clamped_to_the_cores() {
        assert_eq!(clamp_threads(1_000).unwrap(), cores());
        assert_eq!(clamp_threads(1).unwrap(), 1);
        assert!(clamp_threads(0).is_err());
    }
}
