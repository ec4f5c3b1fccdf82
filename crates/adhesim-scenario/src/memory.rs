//! The memory a run may use (`docs/reliability.md`, "Scenario inputs and resources"): the
//! smallest of the limits a user or a scheduler sets and of what the machine has free,
//! read before anything grid-sized is allocated. A scheduler (Slurm, a container) states
//! its limit in the cgroup, `prlimit`/`ulimit -v` in RLIMIT_AS; `MemAvailable` alone missed
//! both, and a run beyond them aborted mid-way instead of being refused.

use anyhow::{bail, Result};

/// Environment variable that states the memory available in bytes, instead of the limits
/// read from the system (a limit the system does not show; tests).
pub const MEMORY_VARIABLE: &str = "ADHESIM_MEMORY_AVAILABLE";

/// The memory a run may use and the limit that sets it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MemoryLimit {
    /// Bytes the run may allocate.
    pub bytes: u64,
    /// What sets it, for messages: `the address-space limit RLIMIT_AS of 1.9 GiB, less 0.1 GiB in use`.
    pub source: String,
    /// This is the address-space limit that the option lifting the memory guard leaves
    /// ([`memory_limit`]): raising it is then the only way past it.
    pub survives_lifting: bool,
}

impl std::fmt::Display for MemoryLimit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} of memory available ({})", gibibytes(self.bytes), self.source)
    }
}

/// `1.5 GiB` (the unit of the grid guard's messages).
pub fn gibibytes(bytes: u64) -> String {
    format!("{:.1} GiB", bytes as f64 / (1u64 << 30) as f64)
}

/// `1.5 GiB`, `12.0 MiB` below a GiB, `900 bytes` below a MiB (an object's arrays, a
/// frame, a reference curve: often far below a GiB).
pub fn bytes_text(bytes: u64) -> String {
    if bytes >= 1 << 30 {
        format!("{:.1} GiB", bytes as f64 / (1u64 << 30) as f64)
    } else if bytes >= 1 << 20 {
        format!("{:.1} MiB", bytes as f64 / (1u64 << 20) as f64)
    } else {
        format!("{bytes} bytes")
    }
}

/// The texts of the system files the limits come from (`None`: not there).
#[derive(Debug, Default, Clone)]
pub struct SystemMemoryFiles {
    /// `/proc/meminfo`.
    pub meminfo: Option<String>,
    /// `/proc/self/limits`.
    pub limits: Option<String>,
    /// `/proc/self/status` (the `VmSize` already mapped counts against RLIMIT_AS).
    pub status: Option<String>,
    /// The cgroup's limit: v2 `memory.max` or v1 `memory.limit_in_bytes`.
    pub cgroup_max: Option<String>,
    /// The cgroup's usage: v2 `memory.current` or v1 `memory.usage_in_bytes`.
    pub cgroup_current: Option<String>,
}

impl SystemMemoryFiles {
    /// Reads the files of this process (Linux; elsewhere every one is `None`).
    pub fn read() -> Self {
        let read = |path: &str| std::fs::read_to_string(path).ok();
        let (cgroup_max, cgroup_current) = read_cgroup(read("/proc/self/cgroup").as_deref());
        Self {
            meminfo: read("/proc/meminfo"),
            limits: read("/proc/self/limits"),
            status: read("/proc/self/status"),
            cgroup_max,
            cgroup_current,
        }
    }

    /// RLIMIT_AS less the address space in use (`None`: unlimited). Unlike the other limits,
    /// no swap or lazy allocator gets past it: an allocation beyond it fails at once, and
    /// Rust's allocations abort the process (`--allow-large` still checks it).
    pub fn address_space(&self) -> Option<MemoryLimit> {
        let limit = self.limits.as_deref().and_then(address_space_limit)?;
        let in_use = self
            .status
            .as_deref()
            .and_then(|t| kilobyte_line(t, "VmSize:"))
            .unwrap_or(0);
        Some(MemoryLimit {
            survives_lifting: false,
            bytes: limit.saturating_sub(in_use),
            source: format!(
                "the address-space limit RLIMIT_AS of {}, less {} in use",
                gibibytes(limit),
                gibibytes(in_use)
            ),
        })
    }

    /// The smallest of the limits the texts state; `None` where none is stated.
    pub fn limit(&self) -> Option<MemoryLimit> {
        let mut candidates = Vec::new();
        if let Some(bytes) = self.meminfo.as_deref().and_then(|t| kilobyte_line(t, "MemAvailable:")) {
            candidates.push(MemoryLimit {
                survives_lifting: false,
                bytes,
                source: "MemAvailable of /proc/meminfo".to_string(),
            });
        }
        candidates.extend(self.address_space());
        if let Some(limit) = self.cgroup_max.as_deref().and_then(cgroup_bytes) {
            let in_use = self.cgroup_current.as_deref().and_then(cgroup_bytes).unwrap_or(0);
            candidates.push(MemoryLimit {
                survives_lifting: false,
                bytes: limit.saturating_sub(in_use),
                source: format!(
                    "the cgroup memory limit of {}, less {} in use",
                    gibibytes(limit),
                    gibibytes(in_use)
                ),
            });
        }
        candidates.into_iter().min_by_key(|c| c.bytes)
    }
}

/// The cgroup files of this process from `/proc/self/cgroup`: v2 (`0::/PATH`, files under
/// /sys/fs/cgroup/PATH) or v1 (`N:...memory...:/PATH`, under /sys/fs/cgroup/memory/PATH);
/// inside a container the path may not exist, then the cgroup root's files are read.
fn read_cgroup(membership: Option<&str>) -> (Option<String>, Option<String>) {
    let read = |path: String| std::fs::read_to_string(path).ok();
    let lines: Vec<&str> = membership.map(|t| t.lines().collect()).unwrap_or_default();
    let v1 = lines.iter().find_map(|line| {
        let mut parts = line.splitn(3, ':');
        let (_, controllers, path) = (parts.next()?, parts.next()?, parts.next()?);
        controllers.split(',').any(|c| c == "memory").then_some(path)
    });
    if let Some(path) = v1 {
        for folder in [
            format!("/sys/fs/cgroup/memory{path}"),
            "/sys/fs/cgroup/memory".to_string(),
        ] {
            if let Some(max) = read(format!("{folder}/memory.limit_in_bytes")) {
                return (Some(max), read(format!("{folder}/memory.usage_in_bytes")));
            }
        }
    }
    let v2 = lines.iter().find_map(|line| line.strip_prefix("0::")).unwrap_or("/");
    for folder in [format!("/sys/fs/cgroup{v2}"), "/sys/fs/cgroup".to_string()] {
        if let Some(max) = read(format!("{}/memory.max", folder.trim_end_matches('/'))) {
            return (
                Some(max),
                read(format!("{}/memory.current", folder.trim_end_matches('/'))),
            );
        }
    }
    (None, None)
}

/// The `KEY   123456 kB` line of a /proc text, in bytes.
fn kilobyte_line(text: &str, key: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with(key))?;
    let kilobytes: u64 = line[key.len()..].split_whitespace().next()?.parse().ok()?;
    kilobytes.checked_mul(1024)
}

/// The soft limit of `Max address space` in `/proc/self/limits` (bytes; `None`: unlimited).
fn address_space_limit(text: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with("Max address space"))?;
    line["Max address space".len()..]
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

/// A cgroup limit or usage in bytes; `max` (v2) and v1's "unlimited" (a page-rounded
/// i64::MAX) are no limit.
fn cgroup_bytes(text: &str) -> Option<u64> {
    let bytes: u64 = text.trim().parse().ok()?;
    (bytes < 1 << 62).then_some(bytes)
}

/// The memory a run may use: [`MEMORY_VARIABLE`] where set (a value that is not a number
/// of bytes is an error), else the smallest of RLIMIT_AS (less the address space in use),
/// the cgroup's `memory.max` (less its usage) and `MemAvailable`; `None` where the system
/// states none of them (not Linux): then no memory guard applies.
pub fn memory_available() -> Result<Option<MemoryLimit>> {
    if let Ok(value) = std::env::var(MEMORY_VARIABLE) {
        return match value.trim().parse::<u64>() {
            Ok(bytes) => Ok(Some(MemoryLimit {
                survives_lifting: false,
                bytes,
                source: format!("{MEMORY_VARIABLE} = {bytes}"),
            })),
            Err(_) => bail!("{MEMORY_VARIABLE} must be a number of bytes, got `{value}`"),
        };
    }
    Ok(SystemMemoryFiles::read().limit())
}

/// The memory limit for a run: [`memory_available`], or, where `lifted_by` names the
/// option that lifts the memory guard (`--allow-large`, `allow_large=True`), only
/// RLIMIT_AS: swap or a lazy allocator may let a run fit beyond the other limits, but
/// nothing gets past that one, and a run beyond it aborts in an allocation.
pub fn memory_limit(lifted_by: Option<&str>) -> Result<Option<MemoryLimit>> {
    match lifted_by {
        None => memory_available(),
        Some(option) => Ok(SystemMemoryFiles::read().address_space().map(|limit| MemoryLimit {
            source: format!("{}, which {option} does not lift", limit.source),
            survives_lifting: true,
            ..limit
        })),
    }
}

/// Bytes per bin of an isotropic PSD, an upper estimate: its sums and bins (64 bytes) and
/// what is written, drawn or returned to Python of them (`adhesim topography --bins`,
/// `adhesim.surface.psd(bins=)`).
pub const PSD_BYTES_PER_BIN: u128 = 128;

/// Refuses, naming `what` and both sizes, an allocation of `bytes` beyond `limit`.
pub fn check_allocation(what: &str, bytes: u128, limit: &MemoryLimit) -> Result<()> {
    if bytes > u128::from(limit.bytes) {
        let need = u64::try_from(bytes).map_or_else(|_| format!("{bytes} bytes"), bytes_text);
        bail!(
            "{what} would need about {need} of memory, more than the {} of memory available ({})",
            bytes_text(limit.bytes),
            limit.source
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const MEMINFO: &str = "MemTotal:       16314264 kB\nMemFree:         1000000 kB\nMemAvailable:    8000000 kB\n";
    const LIMITS: &str = "Limit                     Soft Limit           Hard Limit           Units     \nMax stack size            8388608              unlimited            bytes     \nMax address space         2000000000           unlimited            bytes     \n";

    #[test]
    fn the_smallest_limit_wins_and_is_named() {
        let files = SystemMemoryFiles {
            meminfo: Some(MEMINFO.to_string()),
            ..Default::default()
        };
        assert_eq!(files.limit().unwrap().bytes, 8_000_000 * 1024);
        let files = SystemMemoryFiles {
            limits: Some(LIMITS.to_string()),
            status: Some("Name: adhesim\nVmSize:    100000 kB\n".to_string()),
            ..files
        };
        let limit = files.limit().unwrap();
        assert_eq!(limit.bytes, 2_000_000_000 - 100_000 * 1024);
        assert!(limit.source.contains("RLIMIT_AS"), "{limit}");
        let files = SystemMemoryFiles {
            cgroup_max: Some("1073741824\n".to_string()),
            cgroup_current: Some("73741824\n".to_string()),
            ..files
        };
        let limit = files.limit().unwrap();
        assert_eq!(limit.bytes, 1_000_000_000);
        assert!(limit.source.contains("cgroup"), "{limit}");
    }

    #[test]
    fn unlimited_limits_are_no_limit() {
        let files = SystemMemoryFiles {
            limits: Some(LIMITS.replace("2000000000  ", "unlimited   ")),
            cgroup_max: Some("max\n".to_string()),
            ..Default::default()
        };
        assert_eq!(files.limit(), None);
        let v1_unlimited = SystemMemoryFiles {
            cgroup_max: Some("9223372036854771712\n".to_string()),
            ..Default::default()
        };
        assert_eq!(v1_unlimited.limit(), None);
        assert_eq!(kilobyte_line("MemAvailable: lots kB\n", "MemAvailable:"), None);
    }

    #[test]
    fn an_allocation_beyond_the_limit_names_what_and_the_limit() {
        let limit = MemoryLimit {
            survives_lifting: false,
            bytes: 1 << 30,
            source: "test".to_string(),
        };
        assert!(check_allocation("x", 1 << 29, &limit).is_ok());
        let error = check_allocation("HalfSpace(Grid(n=100000))", u128::MAX, &limit)
            .unwrap_err()
            .to_string();
        assert!(
            error.contains("HalfSpace(Grid(n=100000))") && error.contains("1.0 GiB of memory available"),
            "{error}"
        );
    }
}
