//! End-to-end tests of the checks of what inputs imply and of the resource guards
//! (`docs/reliability.md`, "Scenario inputs and resources"). Each case ran into the OOM
//! killer, aborted, ran for hours or was accepted silently before those guards.

use std::path::Path;
use std::process::{Command, Output};

use crate::common;
use common::{assert_fails_with, npy_bytes, read_json, stderr, write, BIN};

fn adhesim(args: &[&str], memory: Option<&str>) -> Output {
    let mut command = Command::new(BIN);
    command.args(args);
    match memory {
        Some(bytes) => command.env("ADHESIM_MEMORY_AVAILABLE", bytes),
        None => command.env_remove("ADHESIM_MEMORY_AVAILABLE"),
    };
    command.output().expect("binary runs")
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

fn run(text: &str, extra: &[&str], memory: Option<&str>) -> (tempfile::TempDir, Output) {
    let temp = tempfile::tempdir().unwrap();
    let path = write(temp.path(), "scenario.toml", text);
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
    // E* = γ = 1e60: every JKR scale is ordinary, but the single-precision FFTs overflow;
    // this ran and failed with "solver produced a non-finite value" (printed twice).
    let (temp, output) = run(
        JKR,
        &[
            "--set",
            "material.contact_modulus=1e60",
            "--set",
            "adhesion.work_of_adhesion=1e60",
        ],
        None,
    );
    assert_fails_with(
        &output,
        &[
            "the stiffness E*/Δ = ",
            "material.contact_modulus = 1e60",
            "grid.size = 0.5",
        ],
    );
    assert_eq!(
        stderr(&output).matches("single-precision").count(),
        1,
        "{}",
        stderr(&output)
    );
    assert!(!temp.path().join("out").exists(), "nothing written for a refused run");
}

#[test]
fn a_roll_beyond_the_domain_is_refused() {
    // scenarios/fig6.toml: L = 0.4, a ≈ 0.077 at 5|d_JKR|; 50 λ = 2.5 is far off the grid.
    // This exited 0 with zero forces and no warning.
    let fig6 = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios/fig6.toml");
    let text = std::fs::read_to_string(fig6).unwrap();
    let (temp, output) = run(&text, &["--set", "protocol.distance=50"], None);
    assert_fails_with(
        &output,
        &[
            "protocol.distance = 50 carries the contact off the grid",
            "grid.size/2 = 2.0000e-1",
        ],
    );
    assert!(!temp.path().join("out").exists(), "nothing written for a refused run");
}

#[test]
fn zero_threads_are_refused() {
    let (temp, output) = run(JKR, &["--threads", "0"], None);
    assert_fails_with(&output, &["--threads must be >= 1, got 0"]);
    assert!(!temp.path().join("out").exists(), "nothing written for a refused run");
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
    let summary: serde_json::Value = read_json(&temp.path().join("out/summary.json"));
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

/// A sweep whose `--jobs` concurrent cases of its largest grid need more than the memory
/// available is refused before any case allocates (first robustness audit,
/// docs/reliability.md: a sweep of large grids ran into the OOM killer). grid.n = 1024
/// (free) is estimated at 0.41 GiB per run.
#[test]
fn a_sweep_whose_concurrent_cases_exceed_the_memory_is_refused() {
    let temp = tempfile::tempdir().unwrap();
    let sweep = "[scenario]\ngrid = { n = 16, size = 0.5 }\nmaterial = { contact_modulus = 1.0 }\nadhesion = { work_of_adhesion = 0.001 }\nindenter = { shape = \"sphere\", radius = 1.0 }\nprotocol = { kind = \"indent_pulloff\", max_depth = 2.0, depth_unit = \"jkr\", steps = 5 }\n[vary]\n\"grid.n\" = [16, 1024]\n";
    let path = temp.path().join("sweep.toml");
    std::fs::write(&path, sweep).unwrap();
    let out = temp.path().join("out");
    let sweep = |jobs: &str, memory: &str| {
        adhesim(
            &[
                "sweep",
                path.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
                "--jobs",
                jobs,
            ],
            Some(memory),
        )
    };
    // Two at a time need 0.8 GiB; 0.6 GB are available.
    let output = sweep("2", "600000000");
    assert_fails_with(
        &output,
        &[
            "grid.n = 1024 needs about 0.8 GiB (2 concurrent runs of 0.4 GiB each)",
            "0.6 GiB",
            "--jobs",
        ],
    );
    assert!(!out.join("cases").exists(), "no case started");
    // One at a time still needs more than 0.3 GB.
    let output = sweep("1", "300000000");
    assert_fails_with(
        &output,
        &[
            "grid.n = 1024 needs about 0.4 GiB, more than the 0.3 GiB",
            "--allow-large",
        ],
    );
}

const TOPOGRAPHY: &str = r#"
[grid]
n = 16
size = 0.8
[material]
contact_modulus = 1.0
[adhesion]
work_of_adhesion = 0.001
[indenter]
shape = "topography"
file = "FILE"
spacing = 0.05
[protocol]
kind = "indent_pulloff"
max_depth = 0.01
steps = 8
"#;

fn run_in(dir: &Path, text: &str, out: &str) -> Output {
    let path = write(dir, "scenario.toml", text);
    let out = dir.join(out);
    adhesim(
        &["run", path.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"],
        None,
    )
}

#[test]
fn topographies_are_read_in_every_format_and_a_lying_header_is_an_error() {
    let temp = tempfile::tempdir().unwrap();
    let (rows, columns) = (24, 20);
    let heights: Vec<f64> = (0..rows * columns)
        .map(|k| {
            let (i, j) = (k / columns, k % columns);
            let x = (j as f64 - columns as f64 / 2.0 + 0.5) * 0.05;
            let y = (i as f64 - rows as f64 / 2.0 + 0.5) * 0.05;
            (x * x + y * y) / 2.0 + 0.001 * ((i * 7 + j * 3) % 5) as f64
        })
        .collect();
    std::fs::write(temp.path().join("bump.npy"), npy_bytes((rows, columns), &heights)).unwrap();
    let ascii: String = heights
        .chunks(columns)
        .map(|row| row.iter().map(|h| format!("{h:e}")).collect::<Vec<_>>().join(" ") + "\n")
        .collect();
    std::fs::write(temp.path().join("bump.txt"), ascii).unwrap();
    let npy = run_in(temp.path(), &TOPOGRAPHY.replace("FILE", "bump.npy"), "npy");
    assert!(npy.status.success(), "{}", stderr(&npy));
    let txt = run_in(temp.path(), &TOPOGRAPHY.replace("FILE", "bump.txt"), "txt");
    assert!(txt.status.success(), "{}", stderr(&txt));
    // The same heights through two readers: the same curve, byte for byte.
    let curve = |folder: &str| std::fs::read(temp.path().join(folder).join("curve.csv")).unwrap();
    assert_eq!(curve("npy"), curve("txt"));
    // Without indenter.spacing a file that records none is an error naming the key.
    let no_spacing = TOPOGRAPHY.replace("FILE", "bump.npy").replace("spacing = 0.05\n", "");
    assert_fails_with(
        &run_in(temp.path(), &no_spacing, "none"),
        &["indenter.file", "indenter.spacing"],
    );
    // A 64-byte file whose header claims 10⁶ × 10⁶ elements aborted on allocation.
    std::fs::write(
        temp.path().join("huge.npy"),
        npy_bytes((1_000_000, 1_000_000), &[0.0; 8]),
    )
    .unwrap();
    let huge = run_in(temp.path(), &TOPOGRAPHY.replace("FILE", "huge.npy"), "huge");
    assert_fails_with(&huge, &["indenter.file", "huge.npy", "1000000"]);
    // A NaN in the map is refused, not filled silently.
    let mut holed = heights.clone();
    holed[5] = f64::NAN;
    std::fs::write(temp.path().join("holed.npy"), npy_bytes((rows, columns), &holed)).unwrap();
    let holed = run_in(temp.path(), &TOPOGRAPHY.replace("FILE", "holed.npy"), "holed");
    assert_fails_with(&holed, &["indenter.file", "holed.npy", "1 of 480 points are invalid"]);
}

/// An adhesion map (`adhesion.field.file`) is checked like a height map: a header lying
/// about its size, a map of another size than the grid, and negative or NaN values are
/// errors naming the key and the file, before the run.
#[test]
fn a_bad_adhesion_map_is_an_error_naming_the_key() {
    let temp = tempfile::tempdir().unwrap();
    let map_scenario = |file: &str| {
        JKR.replace(
            "work_of_adhesion = 0.001",
            &format!("work_of_adhesion = 0.001\nfield = {{ kind = \"map\", file = \"{file}\" }}"),
        )
    };
    let n = 32;
    let mut values = vec![1.0; n * n];
    std::fs::write(temp.path().join("good.npy"), npy_bytes((n, n), &values)).unwrap();
    let good = run_in(temp.path(), &map_scenario("good.npy"), "good");
    assert!(good.status.success(), "{}", stderr(&good));
    std::fs::write(
        temp.path().join("huge.npy"),
        npy_bytes((1_000_000, 1_000_000), &[1.0; 8]),
    )
    .unwrap();
    std::fs::write(temp.path().join("small.npy"), npy_bytes((16, 16), &values[..256])).unwrap();
    values[40] = -0.5;
    std::fs::write(temp.path().join("negative.npy"), npy_bytes((n, n), &values)).unwrap();
    values[40] = f64::NAN;
    std::fs::write(temp.path().join("nan.npy"), npy_bytes((n, n), &values)).unwrap();
    for (file, fragment) in [
        ("huge.npy", "1000000"),
        ("small.npy", "the map is 16×16, the grid is 32×32"),
        ("negative.npy", "-0.5"),
        ("nan.npy", "NaN"),
    ] {
        let out = format!("out-{file}");
        let output = run_in(temp.path(), &map_scenario(file), &out);
        assert_fails_with(&output, &["adhesion.field.file", file, fragment]);
        assert!(!temp.path().join(out).exists(), "nothing written for a refused run");
    }
}

/// Second robustness audit (docs/reliability.md): map values that keep γ finite and ≥ 0 but put
/// one element's critical stress σ_c outside the solver's single-precision range (1e296
/// overflowed mid-run; 1e-303 ended in a "did not converge" whose residual was below its
/// tolerance) are refused before the run, naming the element, its γ and the map.
#[test]
fn adhesion_maps_beyond_single_precision_are_refused_naming_the_element() {
    let temp = tempfile::tempdir().unwrap();
    let n = 32;
    for (name, value) in [("strong.npy", 1e296), ("faint.npy", 1e-303)] {
        let mut values = vec![1.0; n * n];
        values[40] = value;
        std::fs::write(temp.path().join(name), npy_bytes((n, n), &values)).unwrap();
        let scenario = JKR.replace(
            "work_of_adhesion = 0.001",
            &format!("work_of_adhesion = 0.001\nfield = {{ kind = \"map\", file = \"{name}\" }}"),
        );
        let out = format!("out-{name}");
        let output = run_in(temp.path(), &scenario, &out);
        let gamma = format!("γ = {:e}", 0.001 * value);
        assert_fails_with(
            &output,
            &[
                "the critical stress σ_c",
                "(element 40, ",
                &gamma,
                "single-precision",
                "adhesion.field",
            ],
        );
        assert!(!temp.path().join(out).exists(), "nothing written for a refused run");
    }
}
