//! Input files must be regular files (`docs/reliability.md`, "Scenario inputs and
//! resources"): opening a FIFO blocks until a writer comes, forever in a batch job; a
//! device streams without end; a folder fails with a bare "Is a directory". Each is
//! refused by name before it is opened. A regular file is read whole, so one larger than
//! the memory a run may use ([`crate::memory_available`]) is refused by name too.

use crate::error::{ErrorKind, ScenarioError};
use anyhow::{bail, Context, Result};
use std::io::Read;
use std::path::Path;

/// Refuses, naming `what` (a key, `scenario`, `sweep file`) and the path, a path that is
/// not a regular file (symbolic links are followed), or one larger than the memory
/// available (it is read whole). A missing file passes: the reader that opens it names it
/// with the system's reason.
pub fn check_regular_file(path: &Path, what: &str) -> Result<()> {
    let Ok(metadata) = std::fs::metadata(path) else {
        return Ok(());
    };
    let kind = metadata.file_type();
    if kind.is_file() {
        // An unreadable limit (a malformed ADHESIM_MEMORY_AVAILABLE) is reported by the
        // memory guard of the run, not here.
        if let Some(limit) = crate::memory_available().ok().flatten() {
            if metadata.len() > limit.bytes {
                let error = ScenarioError::new(
                    ErrorKind::Resources,
                    format!(
                        "{what}: {} is {}, more than the {} of memory available ({}); it is read whole",
                        path.display(),
                        crate::memory::bytes_text(metadata.len()),
                        crate::memory::bytes_text(limit.bytes),
                        limit.source
                    ),
                )
                .with_value(path.display().to_string())
                .with_requirement("a file that fits in memory");
                bail!(if what.contains('.') {
                    error.with_key(what)
                } else {
                    error
                });
            }
        }
        return Ok(());
    }
    let name = if kind.is_dir() {
        "a folder"
    } else {
        special_file_kind(&kind)
    };
    let error = ScenarioError::new(
        ErrorKind::File,
        format!("{what}: {} is {name}, not a regular file", path.display()),
    )
    .with_value(path.display().to_string())
    .with_requirement("a regular file");
    // `what` is a dotted scenario key, or a word (`scenario`, `sweep file`) for the file itself.
    bail!(if what.contains('.') {
        error.with_key(what)
    } else {
        error
    })
}

#[cfg(unix)]
fn special_file_kind(kind: &std::fs::FileType) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    if kind.is_fifo() {
        "a FIFO (named pipe)"
    } else if kind.is_char_device() || kind.is_block_device() {
        "a device"
    } else if kind.is_socket() {
        "a socket"
    } else {
        "not a file"
    }
}

#[cfg(not(unix))]
fn special_file_kind(_: &std::fs::FileType) -> &'static str {
    "not a file"
}

/// The text of the regular file `path`; errors name `what` and the path
/// (`cannot read scenario PATH: No such file or directory`).
pub fn read_input_text(path: &Path, what: &str) -> Result<String> {
    check_regular_file(path, what)?;
    std::fs::read_to_string(path).with_context(|| format!("cannot read {what} {}", path.display()))
}

/// The bytes of a file the program wrote itself and reads back (a checkpoint, a case's
/// `done` marker, a lock): refused, naming `what` and the path, unless it is a regular
/// file (a FIFO put in its place blocked the next command; a link to /dev/zero read
/// without end) of at most `max_bytes` (checked while reading too: a file that grows is
/// cut off, not read on).
pub fn read_own_file(path: &Path, what: &str, max_bytes: u64) -> Result<Vec<u8>> {
    check_regular_file(path, what)?;
    let file = std::fs::File::open(path).with_context(|| format!("cannot open {what} {}", path.display()))?;
    let mut bytes = Vec::new();
    file.take(max_bytes.saturating_add(1))
        .read_to_end(&mut bytes)
        .with_context(|| format!("cannot read {what} {}", path.display()))?;
    if bytes.len() as u64 > max_bytes {
        bail!(
            "{what}: {} is larger than the {max_bytes} bytes such a file can have",
            path.display()
        );
    }
    Ok(bytes)
}

/// [`read_own_file`] as text.
pub fn read_own_text(path: &Path, what: &str, max_bytes: u64) -> Result<String> {
    String::from_utf8(read_own_file(path, what, max_bytes)?)
        .map_err(|_| anyhow::anyhow!("{what}: {} is not text (UTF-8)", path.display()))
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;

    #[test]
    fn folders_fifos_and_devices_are_refused_by_name() {
        let dir = std::env::temp_dir().join(format!("adhesim-files-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let error = read_input_text(&dir, "scenario").unwrap_err().to_string();
        assert!(
            error.starts_with("scenario: ") && error.contains("is a folder"),
            "{error}"
        );
        let error = check_regular_file(Path::new("/dev/zero"), "indenter.file")
            .unwrap_err()
            .to_string();
        assert!(error.contains("indenter.file: /dev/zero is a device"), "{error}");
        let fifo = dir.join("pipe");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if made.is_ok_and(|s| s.success()) {
            let error = read_input_text(&fifo, "forces.path").unwrap_err().to_string();
            assert!(error.contains("is a FIFO"), "{error}");
        }
        let file = dir.join("a.toml");
        std::fs::write(&file, "x = 1").unwrap();
        assert_eq!(read_input_text(&file, "scenario").unwrap(), "x = 1");
        assert_eq!(read_own_file(&file, "marker", 5).unwrap(), b"x = 1");
        let error = read_own_file(&file, "marker", 4).unwrap_err().to_string();
        assert!(
            error.contains("marker: ") && error.contains("larger than the 4 bytes"),
            "{error}"
        );
        let error = read_own_file(Path::new("/dev/zero"), "checkpoint", 1 << 20)
            .unwrap_err()
            .to_string();
        assert!(error.contains("checkpoint: /dev/zero is a device"), "{error}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
