//! End-to-end tests of the `adhesim` binary: bad inputs fail cleanly with the key and value
//! named, runs write the contract's files (docs/output.md), every scenario in
//! `scenarios/` runs on a coarse grid, and `reference jkr` reproduces F_JKR.

use std::path::PathBuf;
use std::process::Output;

use crate::common;
use common::{
    adhesim, assert_fails_with, column_values, read_csv, read_json, run_with_sets, scenarios_dir, stderr, write,
};

const HERTZ: &str = r#"
[grid]
n = 32
size = 0.3

[material]
contact_modulus = 1.0

[adhesion]
work_of_adhesion = 0.0

[indenter]
shape = "sphere"
radius = 1.0

[protocol]
kind = "indent_pulloff"
max_depth = 0.01
steps = 10
"#;

fn run_text(text: &str, extra: &[&str]) -> (tempfile::TempDir, Output) {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "s.toml", text);
    let out = dir.path().join("out");
    let mut args = vec!["run", path.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"];
    args.extend_from_slice(extra);
    let output = adhesim(&args);
    (dir, output)
}

#[test]
fn negative_radius_names_key_and_value() {
    let (_dir, output) = run_text(&HERTZ.replace("radius = 1.0", "radius = -1.0"), &[]);
    assert_fails_with(&output, &["indenter.radius must be > 0, got -1"]);
    // the same through an override
    let (_dir, output) = run_text(HERTZ, &["--set", "indenter.radius=-1"]);
    assert_fails_with(&output, &["indenter.radius must be > 0, got -1"]);
}

#[test]
fn zero_grid_names_key_and_value() {
    let (_dir, output) = run_text(&HERTZ.replace("n = 32", "n = 0"), &[]);
    assert_fails_with(&output, &["grid.n must be >= 2, got 0"]);
    let (_dir, output) = run_text(HERTZ, &["--set", "grid.n=-5"]);
    assert_fails_with(&output, &["grid.n must be >= 2, got -5"]);
    let (_dir, output) = run_text(HERTZ, &["--set", "grid.size=0"]);
    assert_fails_with(&output, &["grid.size must be > 0, got 0"]);
}

#[test]
fn unknown_keys_are_named() {
    let (_dir, output) = run_text(&HERTZ.replace("radius = 1.0", "radiuss = 1.0"), &[]);
    assert_fails_with(&output, &["unknown key `indenter.radiuss`"]);
    let (_dir, output) = run_text(&format!("{HERTZ}\n[numerics]\nfoo = 1\n"), &[]);
    assert_fails_with(&output, &["unknown key `numerics`"]);
    let (_dir, output) = run_text(&format!("{HERTZ}\n[solver]\nfoo = 1\n"), &[]);
    assert_fails_with(
        &output,
        &["unknown key `solver.foo` (expected `predicted_growth` or `contact_window`)"],
    );
    let (_dir, output) = run_text(
        HERTZ,
        &[
            "--set",
            "adhesion.field={ kind = \"quadratic\", ratio_edge_to_centre = 2.0, bogus = 1 }",
        ],
    );
    assert_fails_with(&output, &["adhesion.field.bogus"]);
}

#[test]
fn wrong_types_and_values_are_named() {
    let (_dir, output) = run_text(HERTZ, &["--set", "grid.size=\"big\""]);
    assert_fails_with(&output, &["grid.size", "big"]);
    let (_dir, output) = run_text(HERTZ, &["--set", "indenter.shape=cube"]);
    assert_fails_with(&output, &["indenter.shape", "cube"]);
    let (_dir, output) = run_text(HERTZ, &["--set", "protocol.depth_unit=\"jkr\""]);
    assert_fails_with(&output, &["protocol.depth_unit", "work_of_adhesion"]);
    let (_dir, output) = run_text(HERTZ, &["--set", "indenter.amplitude=0.1"]);
    assert_fails_with(
        &output,
        &["unknown key `indenter.amplitude` for indenter.shape = \"sphere\" (expected `radius`)"],
    );
    let (_dir, output) = run_text(&HERTZ.replace("radius = 1.0", ""), &[]);
    assert_fails_with(
        &output,
        &["missing key `indenter.radius` (needed by indenter.shape = \"sphere\")"],
    );
    let (_dir, output) = run_text(HERTZ, &["--set", "nonsense"]);
    assert_fails_with(&output, &["KEY=VALUE", "nonsense"]);
}

#[test]
fn malformed_toml_and_missing_files_fail_cleanly() {
    let (_dir, output) = run_text("[grid\nn = 3\n", &[]);
    assert_fails_with(&output, &["malformed TOML", "line 1"]);
    let output = adhesim(&["run", "/nonexistent/scenario.toml", "--quiet"]);
    assert_fails_with(&output, &["cannot read scenario", "/nonexistent/scenario.toml"]);
    let topography = r#"
[grid]
n = 16
size = 1.0
[material]
contact_modulus = 1.0
[adhesion]
work_of_adhesion = 0.0
[indenter]
shape = "topography"
file = "missing.npy"
spacing = 0.1
[protocol]
kind = "indent_pulloff"
max_depth = 0.01
steps = 5
"#;
    let (_dir, output) = run_text(topography, &[]);
    assert_fails_with(&output, &["indenter.file", "missing.npy"]);
}

#[test]
fn hertz_run_writes_the_contract() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("hertz");
    let scenario = scenarios_dir().join("hertz.toml");
    let output = adhesim(&[
        "run",
        scenario.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));

    let (header, rows) = read_csv(&out.join("curve.csv"));
    for name in [
        "step",
        "phase",
        "d",
        "x",
        "force_normal",
        "force_tangential",
        "area",
        "radius",
        "n_contact",
        "dissipated_energy",
        "attached",
        "detached",
        "jumped",
        "step_dissipated_energy",
        "solves",
        "cg_iterations",
        "fft_pairs",
    ] {
        assert!(header.iter().any(|h| h == name), "column {name} missing: {header:?}");
    }
    // γ0 = 0: no JKR normalisation
    assert!(!header.iter().any(|h| h == "d_norm"));
    assert!(rows.len() > 20);
    for row in &rows {
        for cell in row {
            let lower = cell.to_ascii_lowercase();
            assert!(!lower.contains("nan") && !lower.contains("inf"), "bad cell {cell}");
        }
    }
    let phase = header.iter().position(|h| h == "phase").unwrap();
    assert_eq!(rows[0][phase], "approach");
    assert_eq!(rows.last().unwrap()[phase], "retract");
    // At the deepest step the force matches Hertz within the discretisation error
    // (a = 0.1 = 21 elements: a few per cent).
    let d = column_values(&header, &rows, "d");
    let force = column_values(&header, &rows, "force_normal");
    let deepest = d
        .iter()
        .cloned()
        .enumerate()
        .fold((0, f64::MIN), |m, (i, x)| if x > m.1 { (i, x) } else { m })
        .0;
    let hertz = 4.0 / 3.0 * d[deepest].powf(1.5);
    assert!(
        (force[deepest] / hertz - 1.0).abs() < 0.03,
        "F = {}, Hertz {hertz}",
        force[deepest]
    );

    let summary: serde_json::Value = read_json(&out.join("summary.json"));
    for key in [
        "f_jkr",
        "d_jkr",
        "a_jkr",
        "johnson_parameter",
        "element_size",
        "critical_stress",
    ] {
        assert!(summary["derived"].get(key).is_some(), "derived.{key} missing");
    }
    assert!(summary["derived"]["f_jkr"].is_null());
    assert!(summary["derived"]["johnson_parameter"].is_null());
    for key in [
        "max_adhesive_force",
        "pull_off_depth",
        "gamma_approach",
        "gamma_pulloff",
        "boundary_friction",
        "dissipated_energy",
        "jumps",
        "mean_tangential_force",
        "border_contact",
    ] {
        assert!(summary["results"].get(key).is_some(), "results.{key} missing");
    }
    assert!(summary["results"]["gamma_approach"].is_null());
    assert!(summary["results"]["mean_tangential_force"].is_null());
    assert_eq!(summary["results"]["border_contact"], false);
    for key in [
        "wall_seconds",
        "solver_iterations",
        "fft_pairs",
        "solves",
        "steps",
        "threads",
    ] {
        assert!(summary["performance"][key].is_number(), "performance.{key} missing");
    }
    assert_eq!(summary["inputs"]["indenter"]["shape"], "sphere");
    assert_eq!(summary["warnings"].as_array().unwrap().len(), 0);

    for name in ["force_depth", "force_radius"] {
        for ext in ["png", "svg"] {
            let path = out.join("plots").join(format!("{name}.{ext}"));
            assert!(
                std::fs::metadata(&path).map(|m| m.len() > 1000).unwrap_or(false),
                "{path:?}"
            );
        }
    }
    for name in ["largest_contact.png", "max_depth.png", "pull_off.png"] {
        assert!(out.join("snapshots").join(name).exists(), "snapshot {name}");
    }
}

#[test]
fn the_preconditioners_transforms_are_counted_apart() {
    // performance.preconditioner_fft_pairs: the CG applies its spectral preconditioner
    // before its first iteration and after every iteration but the last, once per
    // iteration. The JKR-type solver's CG iterations are all preconditioned, so the two
    // counts are equal (Fig. 1 at 64²); the nested non-adhesive solver's CG iterations count
    // its fine level and its windows only, while its coarse levels apply the preconditioner
    // too, so Hertz's count exceeds them.
    let dir = tempfile::tempdir().unwrap();
    let performance = |scenario: &str| {
        let out = dir.path().join(scenario.trim_end_matches(".toml"));
        let output = run_with_sets(&scenarios_dir().join(scenario), &out, &["grid.n=64"]);
        assert!(output.status.success(), "{}", stderr(&output));
        let summary = read_json(&out.join("summary.json"));
        let count = |key: &str| summary["performance"][key].as_u64().unwrap();
        (count("preconditioner_fft_pairs"), count("solver_iterations"))
    };
    let (preconditioner, iterations) = performance("fig1.toml");
    assert!(iterations > 0);
    assert_eq!(preconditioner, iterations);
    let (preconditioner, iterations) = performance("hertz.toml");
    assert!(
        preconditioner > iterations && iterations > 0,
        "{preconditioner} vs {iterations}"
    );
}

#[test]
fn contact_at_the_border_is_a_warning() {
    // a = 0.1 at d = 0.01, but the domain is only 0.16 wide.
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "small.toml", &HERTZ.replace("size = 0.3", "size = 0.16"));
    let out = dir.path().join("out");
    let output = adhesim(&["run", path.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"]);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(stderr(&output).contains("warning: contact reached the domain border"));
    let summary: serde_json::Value = read_json(&out.join("summary.json"));
    assert_eq!(summary["results"]["border_contact"], true);
    let warnings = summary["warnings"].as_array().unwrap();
    assert!(warnings.iter().any(|w| w.as_str().unwrap().contains("border")));
}

#[test]
fn every_scenario_runs_on_a_coarse_grid() {
    let dir = tempfile::tempdir().unwrap();
    let mut names: Vec<PathBuf> = std::fs::read_dir(scenarios_dir())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    names.sort();
    assert!(names.len() >= 11, "{names:?}");
    for scenario in names {
        let stem = scenario.file_stem().unwrap().to_str().unwrap().to_string();
        let out = dir.path().join(&stem);
        let output = adhesim(&[
            "run",
            scenario.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
            "--set",
            "grid.n=32",
            "--set",
            "protocol.steps=12",
        ]);
        assert!(output.status.success(), "{stem}: {}", stderr(&output));
        let summary: serde_json::Value = read_json(&out.join("summary.json"));
        assert_eq!(summary["inputs"]["grid"]["n"], 32, "{stem}");
        assert!(summary["performance"]["steps"].as_u64().unwrap() > 12, "{stem}");
        if stem == "fig1" || stem.starts_with("fig2") || stem.starts_with("fig4") {
            assert!(summary["derived"]["johnson_parameter"].is_number(), "{stem}");
            let (header, _) = read_csv(&out.join("curve.csv"));
            assert!(header.iter().any(|h| h == "force_norm"), "{stem}");
        }
    }
}

#[test]
fn reference_jkr_minimum_is_f_jkr() {
    let (radius, modulus, gamma) = (2.0, 1.5, 0.3);
    let output = adhesim(&[
        "reference",
        "jkr",
        "--radius",
        "2",
        "--contact-modulus",
        "1.5",
        "--work-of-adhesion",
        "0.3",
        "--points",
        "50",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let mut reader = csv::Reader::from_reader(output.stdout.as_slice());
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    let rows: Vec<Vec<String>> = reader
        .records()
        .map(|r| r.unwrap().iter().map(String::from).collect())
        .collect();
    let force = column_values(&header, &rows, "force");
    let minimum = force.iter().cloned().fold(f64::INFINITY, f64::min);
    let expected = -1.5 * std::f64::consts::PI * gamma * radius;
    assert!((minimum / expected - 1.0).abs() < 1e-9, "{minimum} vs {expected}");
    let _ = modulus;
    for kind in ["hertz", "flat-punch"] {
        let output = adhesim(&["reference", kind, "--points", "5"]);
        assert!(output.status.success(), "{kind}: {}", stderr(&output));
        assert_eq!(String::from_utf8_lossy(&output.stdout).lines().count(), 6, "{kind}");
    }
    assert_fails_with(&adhesim(&["reference", "jkr"]), &["--work-of-adhesion"]);
}

#[test]
fn help_names_the_default_and_overrides() {
    // `adhesim` without arguments runs scenarios/fig1.toml (about 40 s: too slow here).
    let output = adhesim(&["--help"]);
    assert!(output.status.success());
    assert!(String::from_utf8_lossy(&output.stdout).contains("default scenario"));
    let output = adhesim(&["run", "--help"]);
    assert!(String::from_utf8_lossy(&output.stdout).contains("--set"));
}
