//! The two periodic runs that used to fail mid-run ("solver produced a non-finite
//! value"), through `adhesim run`: a rough flat whose first contact is one element (now
//! solved: the CG restarts when the previous gap norm vanishes), and the Hertz scenario
//! driven past full contact of its periodic cell (now refused before the run, naming the
//! key and the depth at which the whole cell touches: docs/physics.md §1b).
//!
//! `cargo test --release -p adhesim-cli --test integration periodic_runs::`

use crate::common;

use common::*;

const ROUGH_FLAT: &str = r#"
[grid]
n = 256
size = 1.0
boundary = "periodic"
[material]
contact_modulus = 1.0
[adhesion]
work_of_adhesion = 0.0
[indenter]
shape = "rough_flat"
[roughness]
hurst = 0.3
rms_height = 0.01
seed = 7
mode = "random_phase"
[protocol]
kind = "indent_pulloff"
max_depth = 1e-3
depth_unit = "length"
steps = 2
"#;

/// The issue's rough flat runs to the end: every force finite, compressive while the
/// indenter is below first contact, zero once it has left.
#[test]
fn periodic_rough_flat_with_a_one_element_contact_runs_to_the_end() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = write(dir.path(), "rough_flat.toml", ROUGH_FLAT);
    let out = dir.path().join("out");
    let output = adhesim(&[
        "run",
        scenario.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert_ok(&output);
    let (header, rows) = read_csv(&out.join("curve.csv"));
    let depths = column_values(&header, &rows, "d");
    let forces = column_values(&header, &rows, "force_normal");
    assert!(rows.len() >= 4, "{rows:?}");
    for (depth, force) in depths.iter().zip(&forces) {
        assert!(force.is_finite() && *force >= 0.0, "d = {depth}: F = {force}");
        assert_eq!(*force > 0.0, *depth > 0.0, "d = {depth}: F = {force}");
    }
}

/// hertz.toml on a periodic grid: its max_depth 0.01 lies beyond the cell's full contact
/// (mean(z) = L²/12 = 0.0075 for L = 0.3, R = 1), refused before the run with the key and
/// that depth; at 0.0075, 1.5e-5 short of the n = 32 cell's full contact (7.5146e-3), the
/// run goes to the end with all but a few corner elements in contact at the deepest step.
#[test]
fn periodic_hertz_past_full_contact_is_refused_and_below_it_runs() {
    let hertz = scenarios_dir().join("hertz.toml");
    let dir = tempfile::tempdir().unwrap();
    for n in ["16", "32", "64"] {
        let out = dir.path().join(format!("refused{n}"));
        let output = adhesim(&[
            "run",
            hertz.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
            "--set",
            "grid.boundary=\"periodic\"",
            "--set",
            &format!("grid.n={n}"),
        ]);
        assert_fails_with(&output, &["protocol.max_depth = 0.01", "beyond full contact", "7.5"]);
        assert!(!out.join("curve.csv").exists(), "n = {n}: refused before the run");
    }
    let out = dir.path().join("ran");
    let output = adhesim(&[
        "run",
        hertz.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
        "--set",
        "grid.boundary=\"periodic\"",
        "--set",
        "grid.n=32",
        "--set",
        "protocol.max_depth=0.0075",
    ]);
    assert_ok(&output);
    let (header, rows) = read_csv(&out.join("curve.csv"));
    let elements = column_values(&header, &rows, "n_contact");
    let forces = column_values(&header, &rows, "force_normal");
    assert!(forces.iter().all(|f| f.is_finite() && *f >= 0.0));
    let largest = elements.iter().copied().fold(0.0, f64::max);
    assert!(
        largest >= 0.95 * (32 * 32) as f64 && largest < (32 * 32) as f64,
        "{largest} elements"
    );
}
