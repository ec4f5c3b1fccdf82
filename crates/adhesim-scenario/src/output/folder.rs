//! Output folders that never put a user's files at risk (docs/reliability.md, "Outputs
//! and folders"): the marker of a run folder, the clearing of a previous run's outputs,
//! and the advisory lock of a sweep or study folder.

use anyhow::{anyhow, bail, Context, Result};
use std::path::{Path, PathBuf};

/// The file that marks a folder as an adhesim run folder.
pub const RUN_MARKER: &str = ".adhesim-run";

/// What a run writes into its folder: cleared before a new run, so that no output of the
/// previous run (e.g. its snapshots) is mixed with the new one.
const RUN_OUTPUTS: [&str; 9] = [
    "curve.csv",
    "curve.csv.partial",
    "summary.json",
    "plots",
    "snapshots",
    "fields.npz",
    "fields.npz.partial",
    "fields.nc",
    "fields.nc.partial",
];

/// Makes `out` ready for a run: creates it, or, when it exists and is not empty, requires
/// the run marker (or `force`) and removes the previous run's outputs; then writes the
/// marker (with the results revision), before any output.
pub fn prepare_run_folder(out: &Path, force: bool) -> Result<()> {
    if out.exists() {
        if !out.is_dir() {
            bail!("--out {} exists and is not a folder", out.display());
        }
        let mut entries =
            std::fs::read_dir(out).with_context(|| format!("cannot read output folder {}", out.display()))?;
        let empty = entries.next().is_none();
        if !empty && !out.join(RUN_MARKER).is_file() && !force {
            bail!(
                "output folder {} is not empty and is not an adhesim run folder (no {RUN_MARKER}); \
                 choose another --out, or pass --force to write into it (its curve.csv, summary.json, \
                 plots/ and snapshots/ are then replaced)",
                out.display()
            );
        }
        for name in RUN_OUTPUTS {
            let path = out.join(name);
            let removed = match std::fs::symlink_metadata(&path) {
                Err(_) => Ok(()),
                Ok(meta) if meta.is_dir() => std::fs::remove_dir_all(&path),
                Ok(_) => std::fs::remove_file(&path),
            };
            removed.with_context(|| format!("cannot remove the previous run's {}", path.display()))?;
        }
    } else {
        std::fs::create_dir_all(out).with_context(|| format!("cannot create output folder {}", out.display()))?;
    }
    write_run_marker(out)
}

/// Writes `out/.adhesim-run`: the results revision and version that wrote the folder.
pub fn write_run_marker(out: &Path) -> Result<()> {
    let path = out.join(RUN_MARKER);
    let text = format!(
        "adhesim run folder\nresults_revision = {}\nadhesim_version = {}\n",
        adhesim::RESULTS_REVISION,
        env!("CARGO_PKG_VERSION")
    );
    std::fs::write(&path, text).with_context(|| format!("cannot write {}", path.display()))
}

/// The name of this machine (for lock files), or `unknown`.
fn host_name() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .or_else(|_| std::fs::read_to_string("/etc/hostname"))
        .map(|s| s.trim().to_string())
        .ok()
        .filter(|s| !s.is_empty())
        .or_else(|| std::env::var("HOSTNAME").ok())
        .unwrap_or_else(|| "unknown".into())
}

/// Whether process `pid` of this machine is alive; `None` where this cannot be told
/// (no `/proc`).
pub(crate) fn process_alive(pid: u32) -> Option<bool> {
    if !Path::new("/proc/self").exists() {
        return None;
    }
    Some(Path::new("/proc").join(pid.to_string()).exists())
}

/// The owner recorded in a lock file.
struct Owner {
    pid: u32,
    host: String,
}

fn read_owner(path: &Path) -> Option<Owner> {
    let text = crate::files::read_own_text(path, "lock", 4096).ok()?;
    let field = |name: &str| {
        text.lines()
            .find_map(|l| l.strip_prefix(name).and_then(|r| r.strip_prefix(" = ")))
            .map(|v| v.trim().to_string())
    };
    Some(Owner {
        pid: field("pid")?.parse().ok()?,
        host: field("host")?,
    })
}

/// An advisory lock on a sweep or study folder (or on one shard of a sweep), held until
/// dropped: the file `DIR/.adhesim-lock[-shard-I-of-N]` with the owner's pid and host.
/// A lock whose process is dead on this host is stale and taken over with a message.
pub struct FolderLock {
    path: PathBuf,
}

/// Which cases a lock covers: shard `I` of `N` (all cases: 0 of 1).
#[derive(Clone, Copy)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

impl Shard {
    pub const ALL: Shard = Shard { index: 0, count: 1 };

    fn file_name(self) -> String {
        if self.count == 1 {
            ".adhesim-lock".into()
        } else {
            format!(".adhesim-lock-shard-{}-of-{}", self.index, self.count)
        }
    }

    fn parse(name: &str) -> Option<Shard> {
        if name == ".adhesim-lock" {
            return Some(Shard::ALL);
        }
        let (index, count) = name.strip_prefix(".adhesim-lock-shard-")?.split_once("-of-")?;
        Some(Shard {
            index: index.parse().ok()?,
            count: count.parse().ok()?,
        })
    }

    /// Whether two shards share a case: k ≡ i (mod n) and k ≡ i' (mod n') have a
    /// common solution iff i ≡ i' (mod gcd(n, n')).
    fn overlaps(self, other: Shard) -> bool {
        let (mut a, mut b) = (self.count, other.count);
        while b != 0 {
            (a, b) = (b, a % b);
        }
        a == 0 || self.index % a == other.index % a
    }
}

impl FolderLock {
    /// Takes the lock of `shard` in `dir` (created if missing). Refused, naming the lock
    /// file and its owner, while a live process holds this shard or one sharing cases.
    pub fn acquire(dir: &Path, shard: Shard) -> Result<Self> {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        let path = dir.join(shard.file_name());
        let host = host_name();
        let text = format!("pid = {}\nhost = {host}\n", std::process::id());
        for _ in 0..3 {
            match std::fs::OpenOptions::new().write(true).create_new(true).open(&path) {
                Ok(mut file) => {
                    use std::io::Write;
                    file.write_all(text.as_bytes())
                        .with_context(|| format!("cannot write lock file {}", path.display()))?;
                    let lock = Self { path };
                    // Another shard sharing cases may hold its own lock file.
                    lock.check_others(dir, shard, &host)?;
                    return Ok(lock);
                }
                Err(error) if error.kind() == std::io::ErrorKind::AlreadyExists => {
                    take_over_if_stale(&path, &host)?;
                }
                Err(error) => {
                    return Err(anyhow!(error).context(format!("cannot create lock file {}", path.display())));
                }
            }
        }
        bail!("cannot take the lock {} (it keeps reappearing)", path.display())
    }

    fn check_others(&self, dir: &Path, shard: Shard, host: &str) -> Result<()> {
        let entries = std::fs::read_dir(dir).with_context(|| format!("cannot read {}", dir.display()))?;
        for entry in entries.flatten() {
            let other_path = entry.path();
            if other_path == self.path {
                continue;
            }
            let name = entry.file_name().to_string_lossy().into_owned();
            let Some(other) = Shard::parse(&name) else { continue };
            if !shard.overlaps(other) {
                continue;
            }
            // An unreadable lock may be one being written: it counts as held.
            let owner = read_owner(&other_path).unwrap_or(Owner {
                pid: 0,
                host: "an unknown host".into(),
            });
            if owner.host == host && process_alive(owner.pid) == Some(false) {
                continue; // stale: ignored here, taken over by its own shard
            }
            bail!(
                "{} is in use: lock {} is held by pid {} on {} (running the same cases); \
                 wait for it, or delete the lock file if that process is gone",
                dir.display(),
                other_path.display(),
                owner.pid,
                owner.host
            );
        }
        Ok(())
    }
}

/// Removes the lock at `path` when its owner is a dead process of this host; otherwise
/// refuses, naming the lock and its owner.
fn take_over_if_stale(path: &Path, host: &str) -> Result<()> {
    let Some(owner) = read_owner(path) else {
        bail!(
            "{} exists but names no owner (pid, host): another command may be starting in this folder; \
             delete the lock file if none is",
            path.display()
        );
    };
    let dead = owner.host == host && process_alive(owner.pid) == Some(false);
    if !dead {
        bail!(
            "the folder is in use: lock {} is held by pid {} on {}; wait for that command, \
             or delete the lock file if that process is gone",
            path.display(),
            owner.pid,
            owner.host
        );
    }
    eprintln!(
        "note: taking over the stale lock {} (pid {} on {} is no longer running)",
        path.display(),
        owner.pid,
        owner.host
    );
    match std::fs::remove_file(path) {
        Ok(()) => Ok(()),
        Err(error) if error.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(error) => Err(anyhow!(error).context(format!("cannot remove the stale lock {}", path.display()))),
    }
}

impl Drop for FolderLock {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

/// The output folder of a command: `--out` if given, else `out/<file stem>`.
pub fn output_dir(out: Option<&Path>, input: &Path, what: &str) -> Result<PathBuf> {
    if let Some(out) = out {
        return Ok(out.to_path_buf());
    }
    let stem = input
        .file_stem()
        .ok_or_else(|| anyhow!("{what} path {} has no file name", input.display()))?;
    Ok(Path::new("out").join(stem))
}

/// Every file under a run or case folder, by its path relative to `folder`, sorted, with
/// summary.json's `performance` section (wall times and counters that differ between two
/// runs of the same case) removed: what "byte-identical outputs" compares, e.g. a case
/// resumed from a checkpoint against one run straight through.
pub fn comparable_files(folder: &Path) -> Result<Vec<(String, Vec<u8>)>> {
    let mut files = Vec::new();
    let mut stack = vec![folder.to_path_buf()];
    while let Some(current) = stack.pop() {
        let entries = std::fs::read_dir(&current).with_context(|| format!("cannot read {}", current.display()))?;
        for entry in entries {
            let path = entry
                .with_context(|| format!("cannot read {}", current.display()))?
                .path();
            if path.is_dir() {
                stack.push(path);
                continue;
            }
            let name = path.strip_prefix(folder)?.to_string_lossy().into_owned();
            let mut bytes = std::fs::read(&path).with_context(|| format!("cannot read {}", path.display()))?;
            if name == "summary.json" {
                let mut summary: serde_json::Value =
                    serde_json::from_slice(&bytes).with_context(|| format!("{} is not JSON", path.display()))?;
                if let Some(object) = summary.as_object_mut() {
                    object.remove("performance");
                }
                bytes = serde_json::to_vec_pretty(&summary)?;
            }
            files.push((name, bytes));
        }
    }
    files.sort();
    Ok(files)
}
