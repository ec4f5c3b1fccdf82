//! Helpers shared by the integration tests of the `adhesim` binary: where it and the
//! repository's inputs are, running it, checking how it failed, writing inputs and reading
//! its CSV and JSON outputs.

// Each test file is its own crate and uses only some of these.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The `adhesim` binary under test.
pub const BIN: &str = env!("CARGO_BIN_EXE_adhesim");

/// The repository root.
pub fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The repository's `scenarios/`.
pub fn scenarios_dir() -> PathBuf {
    repo().join("scenarios")
}

/// The repository's `sweeps/`.
pub fn sweeps_dir() -> PathBuf {
    repo().join("sweeps")
}

/// Runs `adhesim ARGS` to the end.
pub fn adhesim(args: &[&str]) -> Output {
    Command::new(BIN).args(args).output().expect("binary runs")
}

/// Runs `adhesim run SCENARIO --out OUT --quiet EXTRA…` to the end.
pub fn run_quiet(scenario: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "run",
        scenario.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ];
    args.extend_from_slice(extra);
    adhesim(&args)
}

/// Runs `adhesim run SCENARIO --out OUT --quiet --set S…`, one `--set` per override in
/// `sets`, to the end.
pub fn run_with_sets(scenario: &Path, out: &Path, sets: &[&str]) -> Output {
    let mut extra = Vec::with_capacity(2 * sets.len());
    for set in sets {
        extra.extend(["--set", set]);
    }
    run_quiet(scenario, out, &extra)
}

/// [`run_with_sets`], which must succeed: curve.csv's header and rows.
pub fn curve_with_sets(scenario: &Path, out: &Path, sets: &[&str]) -> (Vec<String>, Vec<Vec<String>>) {
    let output = run_with_sets(scenario, out, sets);
    assert!(
        output.status.success(),
        "{} {sets:?}: {}",
        scenario.display(),
        stderr(&output)
    );
    read_csv(&out.join("curve.csv"))
}

/// The command's stderr as text.
pub fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// The command succeeded (else its stderr is shown).
pub fn assert_ok(output: &Output) {
    assert!(output.status.success(), "failed: {}", stderr(output));
}

/// Failed with exit status 1 (an error, not a panic or a usage error) and a message
/// containing every fragment.
pub fn assert_fails_with(output: &Output, fragments: &[&str]) {
    let message = stderr(output);
    assert!(!output.status.success(), "expected failure, stderr: {message}");
    assert!(!message.contains("panicked"), "panic: {message}");
    assert_eq!(output.status.code(), Some(1), "stderr: {message}");
    for fragment in fragments {
        assert!(message.contains(fragment), "`{fragment}` missing from: {message}");
    }
}

/// Writes `DIR/NAME` and returns its path.
pub fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// The header and the rows of a CSV file.
pub fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let mut reader = csv::Reader::from_path(path).unwrap();
    let header = reader.headers().unwrap().iter().map(String::from).collect();
    let rows = reader
        .records()
        .map(|r| r.unwrap().iter().map(String::from).collect())
        .collect();
    (header, rows)
}

/// The cells of column `name`.
pub fn column(header: &[String], rows: &[Vec<String>], name: &str) -> Vec<String> {
    let i = header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name} in {header:?}"));
    rows.iter().map(|r| r[i].clone()).collect()
}

/// The cells of column `name` as numbers.
pub fn column_values(header: &[String], rows: &[Vec<String>], name: &str) -> Vec<f64> {
    column(header, rows, name)
        .iter()
        .map(|v| {
            v.parse::<f64>()
                .unwrap_or_else(|_| panic!("column {name}: `{v}` is not a number"))
        })
        .collect()
}

/// A JSON file (e.g. `summary.json`).
pub fn read_json(path: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{} is not JSON: {e}", path.display()))
}

/// `adhesim experiment synth` of `frames` frames of 320×240 into `dir`.
pub fn synth_experiment(dir: &Path, frames: usize) {
    let out = adhesim(&[
        "experiment",
        "synth",
        "--out",
        dir.to_str().unwrap(),
        "--frames",
        &frames.to_string(),
        "--width",
        "320",
        "--height",
        "240",
        "--quiet",
    ]);
    assert!(
        out.status.success(),
        "synth failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// A 2-D little-endian f64 `.npy` file claiming `shape` and holding `values`.
pub fn npy_bytes(shape: (usize, usize), values: &[f64]) -> Vec<u8> {
    let mut header = format!(
        "{{'descr': '<f8', 'fortran_order': False, 'shape': ({}, {}), }}",
        shape.0, shape.1
    );
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend_from_slice(&(header.len() as u16).to_le_bytes());
    bytes.extend_from_slice(header.as_bytes());
    for v in values {
        bytes.extend_from_slice(&v.to_le_bytes());
    }
    bytes
}

/// Runs `adhesim ARGS` and kills it (SIGKILL) `settle` after `checkpoint` first finds a
/// mid-run checkpoint (within `limit`; the command must not end before).
pub fn kill_after_checkpoint(
    args: &[String],
    checkpoint: impl Fn() -> bool,
    limit: std::time::Duration,
    settle: std::time::Duration,
) {
    use std::time::{Duration, Instant};
    let mut child = Command::new(BIN)
        .args(args)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while !checkpoint() {
        assert!(start.elapsed() < limit, "no checkpoint written");
        assert!(child.try_wait().unwrap().is_none(), "the run ended before a checkpoint");
        std::thread::sleep(Duration::from_millis(2));
    }
    std::thread::sleep(settle);
    child.kill().unwrap();
    child.wait().unwrap();
}
