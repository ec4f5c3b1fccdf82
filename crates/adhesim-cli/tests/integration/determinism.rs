//! The same scenario gives a bit-identical curve.csv on 1 and 2 threads (docs/validation.md
//! §6): FFT rows and columns are transformed independently of how rayon splits them and all
//! reductions are sequential.

use std::path::Path;
use std::process::Command;

use crate::common;
use common::{scenarios_dir, BIN};

fn run(scenario: &Path, out: &Path, threads: &str) -> Vec<u8> {
    let status = Command::new(BIN)
        .args([
            "run",
            scenario.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ])
        .args(["--threads", threads, "--set", "grid.n=48", "--set", "protocol.steps=40"])
        .status()
        .expect("adhesim runs");
    assert!(status.success());
    std::fs::read(out.join("curve.csv")).expect("curve.csv")
}

#[test]
fn curve_is_identical_on_one_and_two_threads() {
    let scenario = scenarios_dir().join("fig1.toml");
    let folder = tempfile::tempdir().unwrap();
    let single = run(&scenario, &folder.path().join("one"), "1");
    let double = run(&scenario, &folder.path().join("two"), "2");
    assert!(single.len() > 1000, "curve.csv has rows");
    assert!(single == double, "curve.csv differs between 1 and 2 threads");
}
