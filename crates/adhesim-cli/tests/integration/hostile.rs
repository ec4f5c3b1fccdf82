//! The second robustness audit: the reproducers of the probe of 1,418 hostile inputs
//! (`docs/reliability.md`, "Defects and tests"). Each one aborted, hung, named the wrong key
//! or exited 0 with a wrong result before its fix.

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use crate::common;
use common::{adhesim, assert_fails_with, npy_bytes, read_json, run_quiet, scenarios_dir, stderr, write, BIN};

fn hertz() -> String {
    scenarios_dir().join("hertz.toml").to_str().unwrap().to_string()
}

/// Runs `adhesim ARGS`, failing the test (and killing the process) after `limit`: a hang
/// is a failure, not a stuck test suite.
fn adhesim_within(args: &[&str], limit: Duration) -> Output {
    let mut child = Command::new(BIN)
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("binary runs");
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > limit {
            child.kill().unwrap();
            panic!("adhesim {args:?} still running after {limit:?}: it hangs");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

/// Runs `adhesim ARGS` with `ADHESIM_MEMORY_AVAILABLE` = `bytes`.
fn adhesim_with_memory(args: &[&str], bytes: &str) -> Output {
    Command::new(BIN)
        .args(args)
        .env("ADHESIM_MEMORY_AVAILABLE", bytes)
        .output()
        .expect("binary runs")
}

// Reliability, third pass (a probe of 2,923 hostile inputs): one test per cause
// (`docs/reliability.md`, "Third pass").

/// A one-case sweep of `sweeps/tiny.toml`'s scenario (milliseconds).
const ONE_CASE: &str = r#"
series = "one"
[scenario]
grid = { n = 32, size = 0.8 }
material = { contact_modulus = 1.0 }
adhesion = { work_of_adhesion = 6.16850275068085e-4 }
indenter = { shape = "wavy_sphere", radius = 1.0, amplitude = 0.0025, wavelength = 0.1 }
protocol = { kind = "indent_pulloff", max_depth = 6.0, depth_unit = "jkr", steps = 12 }
[vary]
alpha = [1.0]
"#;

mod files;
mod limits;
mod values;
