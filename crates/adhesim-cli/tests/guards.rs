//! End-to-end tests of the checks of what inputs imply and of the resource guards
//! (`docs/reliability.md`, "Scenario inputs and resources"). Each case ran into the OOM
//! killer, aborted, ran for hours or was accepted silently before those guards.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_adhesim");

fn adhesim(args: &[&str], memory: Option<&str>) -> Output {
    let mut command = Command::new(BIN);
    command.args(args);
    match memory {
        Some(bytes) => command.env("ADHESIM_MEMORY_AVAILABLE", bytes),
        None => command.env_remove("ADHESIM_MEMORY_AVAILABLE"),
    };
    command.output().expect("binary runs")
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

fn assert_fails_with(output: &Output, fragments: &[&str]) {
    let message = stderr(output);
    assert!(!output.status.success(), "expected failure, stderr: {message}");
    assert!(!message.contains("panicked"), "panic: {message}");
    assert_eq!(output.status.code(), Some(1), "stderr: {message}");
    for fragment in fragments {
        assert!(message.contains(fragment), "`{fragment}` missing from: {message}");
    }
}

const JKR: &str = r#"
[grid]
n = 32
size = 0.5
[material]
contact_modulus = 1.0
[adhesion]
work_of_adhesion = 0.001
[indenter]
shape = "sphere"
radius = 1.0
[protocol]
kind = "indent_pulloff"
max_depth = 2.0
depth_unit = "jkr"
steps = 10
"#;

fn scenario(dir: &Path, text: &str) -> PathBuf {
    let path = dir.join("scenario.toml");
    std::fs::write(&path, text).unwrap();
    path
}

fn run(text: &str, extra: &[&str], memory: Option<&str>) -> (tempfile::TempDir, Output) {
    let temp = tempfile::tempdir().unwrap();
    let path = scenario(temp.path(), text);
    let out = temp.path().join("out");
    let mut args = vec!["run", path.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"];
    args.extend_from_slice(extra);
    let output = adhesim(&args, memory);
    (temp, output)
}

#[test]
fn a_grid_beyond_the_memory_available_is_refused_unless_allowed() {
    // 4 GiB available; grid.n = 16384 needs ~100 GiB: refused before allocating.
    let four_gib = (4u64 << 30).to_string();
    let (temp, output) = run(JKR, &["--set", "grid.n=16384"], Some(&four_gib));
    assert_fails_with(&output, &["grid.n = 16384 needs about", "4.0 GiB", "--allow-large"]);
    assert!(!temp.path().join("out").exists(), "nothing written for a refused run");
    let (_, output) = run(JKR, &[], Some("not-a-number"));
    assert_fails_with(&output, &["ADHESIM_MEMORY_AVAILABLE", "not-a-number"]);
    // With --allow-large the same small limit does not stop a small run.
    let (_, output) = run(JKR, &["--allow-large"], Some("1000"));
    assert!(output.status.success(), "{}", stderr(&output));
}

#[test]
fn extreme_inputs_blame_the_key_responsible() {
    let (_, output) = run(JKR, &["--set", "material.contact_modulus=1e300"], None);
    assert_fails_with(&output, &["material.contact_modulus = 1e300", "d_JKR"]);
    let (_, output) = run(JKR, &["--set", "protocol.steps=10000000"], None);
    assert_fails_with(&output, &["protocol.steps must be in 1..=1000000, got 10000000"]);
}

#[test]
fn too_many_threads_are_clamped_with_a_warning() {
    let (temp, output) = run(JKR, &["--threads", "1000"], None);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(
        stderr(&output).contains("--threads 1000 exceeds the"),
        "{}",
        stderr(&output)
    );
    assert!(temp.path().join("out/summary.json").exists());
}

#[test]
fn resolution_warnings_reach_stderr_and_the_summary() {
    // Δ = 0.5/32 = 0.0156; λ = 0.02 spans 1.28 elements.
    let wavy = JKR.replace(
        "shape = \"sphere\"\nradius = 1.0",
        "shape = \"wavy_sphere\"\nradius = 1.0\namplitude = 1e-5\nwavelength = 0.02",
    );
    let (temp, output) = run(&wavy, &[], None);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(
        stderr(&output).contains("warning: the waviness wavelength"),
        "{}",
        stderr(&output)
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(temp.path().join("out/summary.json")).unwrap()).unwrap();
    let warnings = summary["warnings"].as_array().unwrap();
    assert!(
        warnings.iter().any(|w| w.as_str().unwrap().contains("1.28 elements")),
        "{warnings:?}"
    );
}

#[test]
fn reference_points_are_capped() {
    let output = adhesim(&["reference", "hertz", "--points", "100000000000"], None);
    assert_fails_with(&output, &["--points must be in 2..=10000000, got 100000000000"]);
}

#[test]
fn sweeps_with_too_many_cases_are_refused_before_they_are_built() {
    let temp = tempfile::tempdir().unwrap();
    let base = "[scenario]\ngrid = { n = 16, size = 0.5 }\nmaterial = { contact_modulus = 1.0 }\nadhesion = { work_of_adhesion = 0.001 }\nindenter = { shape = \"sphere\", radius = 1.0 }\nprotocol = { kind = \"indent_pulloff\", max_depth = 2.0, depth_unit = \"jkr\", steps = 5 }\n";
    let random = format!(
        "{base}[random]\nseed = 1\ncases = 100000000\n\"material.contact_modulus\" = {{ min = 1.0, max = 2.0 }}\n"
    );
    let values: Vec<String> = (0..1000).map(|k| format!("{}", 1.0 + k as f64 * 1e-3)).collect();
    let list = values.join(", ");
    let vary = format!("{base}[vary]\n\"material.contact_modulus\" = [{list}]\n\"indenter.radius\" = [{list}]\n");
    for (name, text, fragment) in [
        ("random.toml", random, "random.cases must be <= 100000"),
        ("vary.toml", vary, "1000000 cases"),
    ] {
        let path = temp.path().join(name);
        std::fs::write(&path, text).unwrap();
        let out = temp.path().join(format!("out-{name}"));
        let output = adhesim(&["sweep", path.to_str().unwrap(), "--out", out.to_str().unwrap()], None);
        assert_fails_with(&output, &[fragment]);
        // Refused from the counts (the message gives the product), nothing created.
        assert!(!out.exists());
    }
}
