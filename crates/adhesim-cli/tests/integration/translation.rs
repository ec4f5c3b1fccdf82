//! End-to-end tests of the roll / slide / translate protocols and of `adhesim study`
//! (docs/friction.md): the files a translation run writes, errors naming the keys at
//! fault, the frictionless controls of the paper's Sect. 3, and tiny studies.

use std::path::{Path, PathBuf};
use std::process::Output;

use crate::common;
mod coupled;
mod force_control;
mod layer;
mod mixity;
mod press;
mod shear;
use common::{adhesim, assert_fails_with, column, read_csv, read_json, repo, run_with_sets, stderr, write};

/// Runs a scenario file of the repository with overrides; returns (out dir, summary).
fn run_scenario(dir: &Path, name: &str, sets: &[&str]) -> (PathBuf, serde_json::Value) {
    let out = dir.join(name.replace(".toml", ""));
    let output = run_with_sets(&repo().join("scenarios").join(name), &out, sets);
    assert!(output.status.success(), "{name}: {}", stderr(&output));
    let summary = read_json(&out.join("summary.json"));
    (out, summary)
}

#[test]
fn roll_run_writes_curve_summary_and_plots() {
    let dir = tempfile::tempdir().unwrap();
    let (out, summary) = run_scenario(
        dir.path(),
        "fig6.toml",
        &[
            "grid.n=32",
            "protocol.approach_steps=15",
            "protocol.steps=16",
            "analysis.gamma_approach=1.6e-5",
            "analysis.gamma_pulloff=2.4e-5",
        ],
    );
    let (header, rows) = read_csv(&out.join("curve.csv"));
    assert_eq!(rows.len(), 31);
    let phase = column(&header, &rows, "phase");
    assert_eq!(phase.iter().filter(|p| *p == "approach").count(), 15);
    assert_eq!(phase.iter().filter(|p| *p == "roll").count(), 16);
    let x: Vec<f64> = column(&header, &rows, "x").iter().map(|v| v.parse().unwrap()).collect();
    let f_t: Vec<f64> = column(&header, &rows, "force_tangential")
        .iter()
        .map(|v| v.parse().unwrap())
        .collect();
    // 2 wavelengths of λ = 0.05 in 16 steps, monotone.
    assert!((x[30] - 0.1).abs() < 1e-12, "x_end = {}", x[30]);
    assert!(x[15..].windows(2).all(|w| w[1] > w[0]));
    assert!(f_t[..15].iter().all(|&f| f == 0.0), "approach has no tangential force");
    assert!(f_t[15..].iter().any(|&f| f != 0.0));
    for name in ["force_tangential_before_change", "half_width"] {
        assert!(header.iter().any(|h| h == name), "{name} missing");
    }
    let results = &summary["results"];
    assert_eq!(results["kind"], "roll");
    for key in [
        "mean_tangential_force",
        "mean_tangential_force_work",
        "tangential_force_fluctuation",
        "mean_normal_force",
        "contact_half_width",
        "real_contact_area",
        "compactness",
        "dissipation_per_distance",
        "eq12_prediction",
        "eq12_ratio",
        "gamma3",
        "gamma3_half_width",
        "boundary_scale",
    ] {
        assert!(results[key].is_number(), "results.{key} = {}", results[key]);
    }
    // γ3 is fitted against the contact radius (farthest element, as γ1 and γ2 are), which is
    // never below the half-width; at a given normal force a larger radius means a larger γ
    // in the JKR relation, so the two fits are ordered.
    assert!(results["contact_radius"].as_f64().unwrap() >= results["contact_half_width"].as_f64().unwrap());
    assert!(results["gamma3"].as_f64().unwrap() >= results["gamma3_half_width"].as_f64().unwrap());
    // Eq. 12 with the given γ1, γ2: 2a(γ2 − γ1).
    let a = results["contact_half_width"].as_f64().unwrap();
    let expected = 2.0 * a * (2.4e-5 - 1.6e-5);
    assert!((results["eq12_prediction"].as_f64().unwrap() - expected).abs() < 1e-12 * expected.abs().max(1.0));
    // Sliding-only entries are null for a roll.
    assert!(results["friction_eq16"].is_null());
    assert!(results["pull_off_depth"].is_null());
    assert_eq!(summary["inputs"]["protocol"]["kind"], "roll");
    for file in ["force_distance.png", "force_distance.svg", "contact_snapshots.png"] {
        assert!(out.join("plots").join(file).is_file(), "{file}");
    }
    assert!(out.join("snapshots/max_depth.png").is_file());
}

#[test]
fn slide_run_evaluates_the_friction_law() {
    let dir = tempfile::tempdir().unwrap();
    let (_, summary) = run_scenario(
        dir.path(),
        "fig9.toml",
        &["grid.n=32", "protocol.approach_steps=10", "protocol.steps=10"],
    );
    let r = &summary["results"];
    assert_eq!(r["kind"], "slide");
    let f_b = r["mean_tangential_force"].as_f64().unwrap();
    let area = r["real_contact_area"].as_f64().unwrap();
    let tau0 = 1e-4;
    let f = r["friction_eq16"].as_f64().unwrap();
    assert!((f - (f_b + area * tau0)).abs() <= 1e-12 * f.abs().max(1e-30));
    assert!((r["tau_mean"].as_f64().unwrap() - f / area).abs() < 1e-9 * tau0);
    assert!(r["tau_mean_eq18"].is_number());
    assert!(r["eq12_prediction"].is_null());
    assert_eq!(summary["inputs"]["protocol"]["substrate_angle"], 30.0);
}

fn fails(sets: &[&str], base: &str) -> Output {
    let dir = tempfile::tempdir().unwrap();
    run_with_sets(&repo().join("scenarios").join(base), &dir.path().join("x"), sets)
}

#[test]
fn bad_translation_scenarios_name_the_key() {
    let cases: &[(&[&str], &str, &[&str])] = &[
        (&["protocol.depth=-5"], "fig6.toml", &["protocol.depth must exceed"]),
        (
            &["protocol.max_depth=3"],
            "fig6.toml",
            &["protocol.max_depth", "protocol.depth"],
        ),
        (&["protocol.steps=0"], "fig6.toml", &["protocol.steps", "got 0"]),
        (
            &["protocol.approach_steps=-2"],
            "fig6.toml",
            &["protocol.approach_steps", "-2"],
        ),
        (
            &["protocol.distance=0"],
            "fig6.toml",
            &["protocol.distance must be > 0"],
        ),
        (
            &["protocol.stationary_from=1.5"],
            "fig6.toml",
            &["protocol.stationary_from", "1.5"],
        ),
        (
            &["protocol.substrate_angle=10"],
            "fig6.toml",
            &["protocol.substrate_angle", "slide"],
        ),
        (
            &["protocol.substrate_angle=\"x\""],
            "fig9.toml",
            &["protocol.substrate_angle"],
        ),
        (
            &["protocol.distance_unit=\"furlong\""],
            "fig6.toml",
            &["protocol.distance_unit"],
        ),
        (&["protocol.speed=1"], "fig6.toml", &["unknown key `protocol.speed`"]),
        (
            &["analysis.gamma_approach=1e-5"],
            "fig6.toml",
            &["analysis.gamma_pulloff"],
        ),
        (&["analysis.tau0=-1"], "fig9.toml", &["analysis.tau0 must be >= 0"]),
        (&["analysis.mu=1"], "fig9.toml", &["analysis.mu"]),
        (
            &["indenter.shape=\"flat_punch\"", "indenter.amplitude=0"],
            "fig6.toml",
            &["indenter."],
        ),
        (
            &["protocol.distance=1"],
            "hertz.toml",
            &["protocol.distance", "indent_pulloff"],
        ),
        (&["analysis.tau0=1"], "hertz.toml", &["[analysis]"]),
    ];
    for (sets, base, fragments) in cases {
        assert_fails_with(&fails(sets, base), fragments);
    }
    // A punch cannot roll: the message names the shape key.
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(repo().join("scenarios/fig6.toml"))
        .unwrap()
        .replace("shape = \"wavy_sphere\"", "shape = \"flat_punch\"")
        .replace("amplitude = 5.627e-4      # α = 0.8\n", "")
        .replace("wavelength = 0.05\n", "")
        .replace("angle = 0.0\n", "")
        .replace("distance_unit = \"wavelength\"", "distance_unit = \"length\"");
    let path = dir.path().join("punch.toml");
    std::fs::write(&path, text).unwrap();
    let output = adhesim(&[
        "run",
        path.to_str().unwrap(),
        "--quiet",
        "--out",
        dir.path().join("o").to_str().unwrap(),
    ]);
    assert_fails_with(&output, &["protocol.kind = \"roll\"", "indenter.shape", "flat_punch"]);
    // Wavelength units need a wavy indenter.
    let sphere = std::fs::read_to_string(repo().join("scenarios/fig6.toml"))
        .unwrap()
        .replace("shape = \"wavy_sphere\"", "shape = \"sphere\"")
        .replace("amplitude = 5.627e-4      # α = 0.8\n", "")
        .replace("wavelength = 0.05\n", "")
        .replace("angle = 0.0\n", "");
    let path = dir.path().join("sphere.toml");
    std::fs::write(&path, sphere).unwrap();
    let output = adhesim(&[
        "run",
        path.to_str().unwrap(),
        "--quiet",
        "--out",
        dir.path().join("s").to_str().unwrap(),
    ]);
    assert_fails_with(&output, &["protocol.distance_unit = \"wavelength\""]);
}

fn per_step_over_scale(summary: &serde_json::Value) -> f64 {
    let r = &summary["results"];
    r["mean_tangential_force"].as_f64().unwrap() / r["boundary_scale"].as_f64().unwrap()
}

/// Paper Sect. 3: translating the whole rough profile over a smooth half-space is
/// frictionless (translation invariance), and so is rolling a smooth sphere; the per-step
/// mean F_T is below 2 % of the boundary-friction scale 2a·γ0, while rolling the same
/// rough sphere (α = 0.6) gives more than 5 % of it. (Measured at these settings:
/// translate 0.3 %, smooth roll < 1 %, rough roll ≈ 8 %.)
#[test]
fn frictionless_controls_through_the_cli() {
    let dir = tempfile::tempdir().unwrap();
    // α = 0.6, depth 3·|d_JKR|, as in the library's validation test.
    let rough = ["indenter.amplitude=7.5e-4", "protocol.depth=3"];
    let (_, translate) = run_scenario(dir.path(), "fig6_translate_control.toml", &rough);
    let ratio = per_step_over_scale(&translate);
    assert!(ratio.abs() < 0.02, "translate: F_T/(2aγ0) = {ratio:.4}");
    assert_eq!(translate["results"]["kind"], "translate");

    let smooth_dir = dir.path().join("smooth");
    std::fs::create_dir_all(&smooth_dir).unwrap();
    let (_, smooth) = run_scenario(&smooth_dir, "fig6.toml", &["indenter.amplitude=0", "protocol.depth=3"]);
    let ratio = per_step_over_scale(&smooth);
    assert!(ratio.abs() < 0.02, "smooth roll: F_T/(2aγ0) = {ratio:.4}");

    let rough_dir = dir.path().join("rough");
    std::fs::create_dir_all(&rough_dir).unwrap();
    let (_, roll) = run_scenario(&rough_dir, "fig6.toml", &rough);
    let ratio = per_step_over_scale(&roll);
    assert!(ratio > 0.05, "rough roll: F_T/(2aγ0) = {ratio:.4}");
}

/// `adhesim study KIND FILE --out OUT EXTRA...`.
fn study(kind: &str, file: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut args = vec!["study", kind, file.to_str().unwrap(), "--out", out.to_str().unwrap()];
    args.extend_from_slice(extra);
    adhesim(&args)
}

#[test]
fn tiny_rolling_study_writes_tables_and_figures_and_resumes() {
    let dir = tempfile::tempdir().unwrap();
    let scenarios = repo().join("scenarios");
    let rolling = write(
        dir.path(),
        "rolling.toml",
        &format!(
            "kind = \"rolling\"\nbase = \"{}\"\nalphas = [0.8, 1.2]\ndepths = [3, 5]\n\
             set = [\"grid.n=32\", \"protocol.approach_steps=10\", \"protocol.steps=8\"]\n\
             [normal]\nmax_depth = 5.0\nsteps = 20\n",
            scenarios.join("fig6.toml").display()
        ),
    );
    let out = dir.path().join("r");
    let output = study("rolling", &rolling, &out, &["--jobs", "2", "--quiet"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let (header, rows) = read_csv(&out.join("table.csv"));
    assert_eq!(rows.len(), 4);
    for name in [
        "alpha",
        "depth_norm",
        "mean_tangential_force_norm",
        "eq12_prediction_norm",
        "gamma3_norm",
        "gamma3_half_width_norm",
    ] {
        assert!(header.iter().any(|h| h == name), "{name}");
    }
    let (_, alphas) = read_csv(&out.join("alphas.csv"));
    assert_eq!(alphas.len(), 2);
    for file in ["fig7.png", "fig7_work.svg", "fig8.png"] {
        assert!(out.join("plots").join(file).is_file(), "{file}");
    }
    // Resuming: every finished run is a case folder with its `done` marker (4 rolls + 2
    // normal runs); a re-run reuses them all (nothing is recomputed) and writes the same
    // table. Removing one case folder (as if the study had been killed before it
    // finished) recomputes only that one.
    let cached: Vec<PathBuf> = std::fs::read_dir(out.join("cases"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("done").is_file() && p.join("record.json").is_file())
        .collect();
    assert_eq!(cached.len(), 6, "{cached:?}");
    let table = std::fs::read_to_string(out.join("table.csv")).unwrap();
    let victim = cached
        .iter()
        .find(|p| p.to_string_lossy().contains("case-1-1"))
        .unwrap();
    std::fs::remove_dir_all(victim).unwrap();
    let output = study("rolling", &rolling, &out, &[]);
    assert!(output.status.success(), "{}", stderr(&output));
    let log = stderr(&output);
    assert_eq!(log.matches("(finished earlier)").count(), 5, "{log}");
    let strip_wall = |text: &str| -> Vec<String> {
        // wall_seconds (last column) differs for the recomputed case
        text.lines()
            .map(|l| l.rsplit_once(',').map_or(l, |(head, _)| head).to_string())
            .collect()
    };
    let again = std::fs::read_to_string(out.join("table.csv")).unwrap();
    assert_eq!(strip_wall(&table), strip_wall(&again));
    // A study folder in the layout from before the batch engine (`cache/<id>.json`, no case
    // folders) resumes as well: its runs move into case folders and none is recomputed.
    std::fs::create_dir(out.join("cache")).unwrap();
    for entry in std::fs::read_dir(out.join("cases")).unwrap() {
        let folder = entry.unwrap().path();
        let id = folder.file_name().unwrap().to_string_lossy().into_owned();
        std::fs::rename(folder.join("record.json"), out.join("cache").join(format!("{id}.json"))).unwrap();
    }
    std::fs::remove_dir_all(out.join("cases")).unwrap();
    let output = study("rolling", &rolling, &out, &[]);
    assert!(output.status.success(), "{}", stderr(&output));
    let log = stderr(&output);
    assert!(log.contains("6 finished runs of"), "{log}");
    assert_eq!(log.matches("(finished earlier)").count(), 6, "{log}");
    assert_eq!(std::fs::read_to_string(out.join("table.csv")).unwrap(), again);
    // Shards: each runs its share of the runs; the one that finds all finished writes the
    // same table.
    let sharded = dir.path().join("sharded");
    for shard in ["0/2", "1/2"] {
        assert!(!sharded.join("table.csv").exists(), "a table before shard {shard}");
        let output = study("rolling", &rolling, &sharded, &["--shard", shard, "--quiet"]);
        assert!(output.status.success(), "{}", stderr(&output));
    }
    let table = std::fs::read_to_string(sharded.join("table.csv")).unwrap();
    assert_eq!(strip_wall(&table), strip_wall(&again));
}

#[test]
fn tiny_sliding_studies_average_over_angles_and_bad_studies_fail() {
    let dir = tempfile::tempdir().unwrap();
    let scenarios = repo().join("scenarios");
    let sliding = write(
        dir.path(),
        "sliding.toml",
        &format!(
            "kind = \"sliding\"\nbase = \"{}\"\nalphas = [0.5, 1.0]\n\
             set = [\"grid.n=32\", \"protocol.approach_steps=10\", \"protocol.steps=8\"]\n",
            scenarios.join("fig9.toml").display()
        ),
    );
    let out = dir.path().join("s");
    let output = study("sliding", &sliding, &out, &["--quiet"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let (_, rows) = read_csv(&out.join("table.csv"));
    assert_eq!(rows.len(), 2);
    for file in ["fig10a.png", "fig10b.svg"] {
        assert!(out.join("plots").join(file).is_file(), "{file}");
    }
    // Several substrate orientations: every case runs at each; the base's θ = 30° cases are
    // the ones above (reused from the cache), and the per-α standard error is the spread of
    // the cases' F_B/(2aγ0) over √n.
    let angled = write(
        dir.path(),
        "sliding_angles.toml",
        &format!(
            "kind = \"sliding\"\nbase = \"{}\"\nalphas = [0.5, 1.0]\nsubstrate_angles = [30, 45]\n\
             set = [\"grid.n=32\", \"protocol.approach_steps=10\", \"protocol.steps=8\"]\n",
            scenarios.join("fig9.toml").display()
        ),
    );
    let output = study("sliding", &angled, &out, &[]);
    assert!(output.status.success(), "{}", stderr(&output));
    assert_eq!(
        stderr(&output).matches("(finished earlier)").count(),
        2,
        "{}",
        stderr(&output)
    );
    let (header, rows) = read_csv(&out.join("table.csv"));
    assert_eq!(rows.len(), 4);
    let thetas = column(&header, &rows, "substrate_angle");
    assert_eq!(thetas, ["30.0", "45.0", "30.0", "45.0"]);
    let per_case: Vec<f64> = column(&header, &rows, "boundary_force_per_width_norm")
        .iter()
        .map(|v| v.parse().unwrap())
        .collect();
    let (alpha_header, alphas) = read_csv(&out.join("alphas.csv"));
    let sem: Vec<f64> = column(&alpha_header, &alphas, "boundary_force_per_width_sem")
        .iter()
        .map(|v| v.parse().unwrap())
        .collect();
    for (k, pair) in per_case.chunks(2).enumerate() {
        // two values: sample std / √2 = |difference| / 2
        let expected = (pair[0] - pair[1]).abs() / 2.0;
        assert!(
            (sem[k] - expected).abs() <= 1e-12 * expected + 1e-15,
            "{sem:?} vs {per_case:?}"
        );
    }
    let bad = write(
        dir.path(),
        "rolling_angles.toml",
        &format!(
            "kind = \"rolling\"\nbase = \"{}\"\nalphas = [0.8]\nsubstrate_angles = [30]\n",
            scenarios.join("fig6.toml").display()
        ),
    );
    let output = adhesim(&["study", "rolling", bad.to_str().unwrap(), "--quiet"]);
    assert_fails_with(&output, &["substrate_angles", "sliding"]);
    // The study kind must match the command.
    let output = adhesim(&["study", "rolling", sliding.to_str().unwrap(), "--quiet"]);
    assert_fails_with(&output, &["kind"]);
    // A rolling study needs a roll base scenario.
    let wrong = write(
        dir.path(),
        "wrong.toml",
        &format!(
            "kind = \"rolling\"\nbase = \"{}\"\nalphas = [1.0]\n",
            scenarios.join("fig9.toml").display()
        ),
    );
    let output = adhesim(&["study", "rolling", wrong.to_str().unwrap(), "--quiet"]);
    assert_fails_with(&output, &["protocol.kind = \"roll\""]);
}
