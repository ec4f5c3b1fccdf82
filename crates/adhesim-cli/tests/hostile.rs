//! The second robustness audit: the reproducers of the probe of 1,418 hostile inputs
//! (`docs/reliability.md`, "Defects and tests"). Each one aborted, hung, named the wrong key
//! or exited 0 with a wrong result before its fix.

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

mod common;
use common::{adhesim, assert_fails_with, npy_bytes, read_json, scenarios_dir, stderr, write, BIN};

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

/// `prlimit --as=2000000000 adhesim run scenarios/hertz.toml --set grid.n=2500` aborted after
/// 26 s: the guard read only MemAvailable. Now RLIMIT_AS (here set by the shell's
/// `ulimit -v`, in KiB) is read too and the grid is refused before the run.
#[test]
fn an_address_space_limit_refuses_a_large_grid_before_the_run() {
    let out = tempfile::tempdir().unwrap();
    let command = format!(
        "ulimit -v 1953125 && exec '{BIN}' run '{}' --set grid.n=2500 --out '{}' --quiet",
        hertz(),
        out.path().join("run").display()
    );
    let output = Command::new("sh")
        .args(["-c", &command])
        .env_remove("ADHESIM_MEMORY_AVAILABLE")
        .output()
        .unwrap();
    assert_fails_with(&output, &["grid.n = 2500 needs about", "of memory", "RLIMIT_AS"]);
    assert!(!out.path().join("run").join("curve.csv").exists());
}

/// A FIFO given as an input file blocked forever; a folder said only "Is a directory".
#[cfg(unix)]
#[test]
fn inputs_that_are_not_regular_files_are_refused_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("scenario.toml");
    assert!(Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let fifo = fifo.to_str().unwrap();
    let limit = Duration::from_secs(30);
    let output = adhesim_within(&["run", fifo, "--out", dir.path().join("o").to_str().unwrap()], limit);
    assert_fails_with(&output, &["scenario: ", "is a FIFO (named pipe), not a regular file"]);
    let output = adhesim_within(&["sweep", fifo, "--out", dir.path().join("s").to_str().unwrap()], limit);
    assert_fails_with(&output, &["sweep file: ", "is a FIFO"]);
    let output = adhesim_within(&["topography", fifo, "--spacing", "1"], limit);
    assert_fails_with(&output, &["is a FIFO"]);
    let folder = dir.path().to_str().unwrap();
    let output = adhesim_within(&["run", folder], limit);
    assert_fails_with(&output, &["scenario: ", "is a folder, not a regular file"]);
    // A height map named by a scenario key.
    let scenario = std::fs::read_to_string(hertz()).unwrap().replace(
        "shape = \"sphere\"\nradius = 1.0",
        "shape = \"topography\"\nfile = \"scenario.toml\"\nspacing = 0.01",
    );
    let path = write(dir.path(), "map.toml", &scenario);
    let output = adhesim_within(&["run", path.to_str().unwrap(), "--out", folder], limit);
    assert_fails_with(&output, &["indenter.file: ", "is a FIFO"]);
}

/// An experiment's `forces.path` naming a folder said only "Is a directory".
#[test]
fn an_experiment_log_that_is_a_folder_is_named_with_its_key() {
    let dir = tempfile::tempdir().unwrap();
    common::synth_experiment(dir.path(), 3);
    std::fs::remove_file(dir.path().join("log.csv")).unwrap();
    std::fs::create_dir(dir.path().join("log.csv")).unwrap();
    let spec = dir.path().join("experiment.toml");
    let output = adhesim(&[
        "experiment",
        spec.to_str().unwrap(),
        "--out",
        dir.path().join("o").to_str().unwrap(),
    ]);
    assert_fails_with(&output, &["forces.path: ", "log.csv is a folder, not a regular file"]);
}

/// `adhesim reference ... | head` printed "Broken pipe" and exited 1.
#[test]
fn reference_into_a_closed_pipe_ends_quietly() {
    let mut child = Command::new(BIN)
        .args(["reference", "hertz", "--points", "1000000"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut first)
        .unwrap();
    assert_eq!(first.trim(), "a,d,force");
    // The reader is dropped here: the pipe closes with most rows unwritten.
    let output = child.wait_with_output().unwrap();
    assert!(output.status.success(), "exit {:?}: {}", output.status, stderr(&output));
    assert_eq!(stderr(&output), "");
}

/// `adhesim sweep merge DIR | head -1` panicked ("failed printing to stdout: Broken pipe"):
/// the commands' reports go through `outln!`, which ignores a closed pipe.
#[test]
fn a_report_into_a_closed_pipe_ends_quietly() {
    let out = tempfile::tempdir().unwrap();
    let hertz = scenarios_dir().join("hertz.toml");
    let mut child = Command::new(BIN)
        .args(["run", hertz.to_str().unwrap(), "--out"])
        .arg(out.path().join("hertz"))
        .args(["--set", "grid.n=16"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // The reader goes before the run reports anything: every line meets a closed pipe.
    drop(child.stdout.take());
    let output = child.wait_with_output().unwrap();
    assert!(output.status.success(), "exit {:?}: {}", output.status, stderr(&output));
    assert!(!stderr(&output).contains("panicked"), "{}", stderr(&output));
    assert!(
        out.path().join("hertz/summary.json").is_file(),
        "the run's files are written"
    );
}

/// `adhesim reference` printed inf and NaN rows where the closed forms overflow.
#[test]
fn reference_prints_no_non_finite_rows() {
    let output = adhesim(&["reference", "hertz", "--radius", "1e300", "--max-radius", "1e300"]);
    assert_fails_with(&output, &["leaves double precision", "d = inf", "--radius 1e300"]);
    assert!(output.stdout.is_empty(), "nothing printed before the error");
    let output = adhesim(&["reference", "jkr", "--radius", "1e-300", "--work-of-adhesion", "1e300"]);
    assert_fails_with(
        &output,
        &["is not a usable number", "--radius 1e-300", "--work-of-adhesion 1e300"],
    );
}

/// Type errors were blamed on another key whose value the message happened to quote.
#[test]
fn type_errors_name_the_key_the_user_wrote() {
    let rough = scenarios_dir().join("rough_sphere.toml");
    let punch = scenarios_dir().join("fig12_homogeneous.toml");
    let ratio = scenarios_dir().join("fig12_ratio13.toml");
    let hertz = hertz();
    let cases: [(&Path, &str, &str); 7] = [
        (
            Path::new(&hertz),
            "protocol.steps=0.01",
            "protocol.steps = 0.01: invalid type",
        ),
        (
            Path::new(&hertz),
            "indenter.shape=nan",
            "indenter.shape = nan: invalid type",
        ),
        (&rough, "roughness.seed=nan", "roughness.seed = nan: invalid type"),
        (
            &punch,
            "indenter.semi_axes=[\"a\",\"b\"]",
            "indenter.semi_axes = [\"a\", \"b\"]: invalid type",
        ),
        (
            &punch,
            "indenter.semi_axes=[1,\"a\"]",
            "indenter.semi_axes = [1, \"a\"]: invalid type",
        ),
        (
            &ratio,
            "adhesion.work_of_adhesion=\"x\"",
            "adhesion.work_of_adhesion = \"x\": invalid type",
        ),
        (
            Path::new(&hertz),
            "protocol.max_depth={a = 1}",
            "protocol.max_depth = { a = 1 }: invalid type: map",
        ),
    ];
    for (scenario, set, expected) in cases {
        let output = adhesim(&["run", scenario.to_str().unwrap(), "--set", set]);
        assert_fails_with(&output, &[expected]);
    }
}

/// `topography any.npy --spacing 1e300` made the PSD plot's tick generation allocate without
/// bound; heights near 1e300 gave an rms height of inf with exit 0.
#[test]
fn absurd_topography_spacings_and_heights_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let heights: Vec<f64> = (0..256).map(|k| ((k * 37 % 101) as f64 - 50.0) * 1e-3).collect();
    let plain = dir.path().join("plain.npy");
    std::fs::write(&plain, npy_bytes((16, 16), &heights)).unwrap();
    let out = dir.path().join("out");
    let limit = Duration::from_secs(60);
    for spacing in ["1e300", "1e-300"] {
        let args = [
            "topography",
            plain.to_str().unwrap(),
            "--spacing",
            spacing,
            "--height-unit",
            "m",
            "--out",
            out.to_str().unwrap(),
        ];
        let output = adhesim_within(&args, limit);
        assert_fails_with(&output, &["plain.npy: spacing", "outside the floating-point range"]);
    }
    let huge: Vec<f64> = heights.iter().map(|h| h * 1e303).collect();
    let path = dir.path().join("huge.npy");
    std::fs::write(&path, npy_bytes((16, 16), &huge)).unwrap();
    let args = [
        "topography",
        path.to_str().unwrap(),
        "--spacing",
        "1",
        "--height-unit",
        "m",
        "--out",
        out.to_str().unwrap(),
    ];
    assert_fails_with(
        &adhesim_within(&args, limit),
        &["huge.npy: a height of", "beyond 1e150"],
    );
}

/// A sphere whose contact radius stays under an element gave 63× to 1981× the Hertz force
/// without a word; now a warning on stderr and in summary.json (Hertz and JKR).
#[test]
fn an_unresolved_contact_radius_is_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    for (name, extra) in [
        ("hertz", "adhesion.work_of_adhesion=0"),
        ("jkr", "adhesion.work_of_adhesion=1e-6"),
    ] {
        let out = dir.path().join(name);
        let args = [
            "run",
            &hertz(),
            "--set",
            "protocol.max_depth=1e-5",
            "--set",
            "grid.n=16",
            "--set",
            extra,
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ];
        let output = adhesim(&args);
        assert!(output.status.success(), "{}", stderr(&output));
        assert!(
            stderr(&output).contains("contact radius at the largest depth"),
            "{}",
            stderr(&output)
        );
        let summary = read_json(&out.join("summary.json"));
        let warnings = summary["warnings"].as_array().unwrap();
        let expected = if name == "hertz" {
            "the Hertz contact radius"
        } else {
            "the JKR contact radius"
        };
        assert!(
            warnings.iter().any(|w| w.as_str().unwrap().contains(expected)),
            "{warnings:?}"
        );
    }
    // The shipped Hertz scenario resolves its contact (a = 21 elements): no such warning.
    let output = adhesim(&[
        "run",
        &hertz(),
        "--out",
        dir.path().join("ok").to_str().unwrap(),
        "--quiet",
    ]);
    assert!(
        !stderr(&output).contains("contact radius at the largest depth"),
        "{}",
        stderr(&output)
    );
}

/// A sphere of radius 1e-300 and an rms height of 1e300 failed mid-run or with a message
/// about another key; now refused before the run, naming theirs.
#[test]
fn heights_beyond_the_solver_range_are_refused_naming_the_keys() {
    let output = adhesim(&["run", &hertz(), "--set", "indenter.radius=1e-300"]);
    assert_fails_with(&output, &["the indenter's heights span", "indenter.radius = 1e-300"]);
    let rough = scenarios_dir().join("rough_sphere.toml");
    for value in ["1e300", "1e-300"] {
        let output = adhesim(&[
            "run",
            rough.to_str().unwrap(),
            "--set",
            &format!("roughness.rms_height={value}"),
        ]);
        let expected = format!("roughness.rms_height = {value} lies outside the magnitudes 1e-150..1e150");
        assert_fails_with(&output, &[&expected]);
    }
}

/// Runs `adhesim ARGS` with `ADHESIM_MEMORY_AVAILABLE` = `bytes`.
fn adhesim_with_memory(args: &[&str], bytes: &str) -> Output {
    Command::new(BIN)
        .args(args)
        .env("ADHESIM_MEMORY_AVAILABLE", bytes)
        .output()
        .expect("binary runs")
}

/// The memory guard holds on every path that allocates by an input's size, not only `run`
/// and `sweep`: a study's runs, `topography SCENARIO`, an experiment's frames and
/// `reference --points`.
#[test]
fn every_command_checks_the_memory_limit() {
    let dir = tempfile::tempdir().unwrap();
    let out = |name: &str| dir.path().join(name).to_str().unwrap().to_string();
    let study = common::repo().join("sweeps/fig7_rolling.toml");
    let output = adhesim_with_memory(
        &[
            "study",
            "rolling",
            study.to_str().unwrap(),
            "--out",
            &out("study"),
            "--quiet",
        ],
        "1000000",
    );
    assert_fails_with(&output, &["needs about", "ADHESIM_MEMORY_AVAILABLE = 1000000"]);
    let rough = scenarios_dir().join("rough_sphere.toml");
    let output = adhesim_with_memory(
        &["topography", rough.to_str().unwrap(), "--out", &out("topo")],
        "1000000",
    );
    assert_fails_with(&output, &["needs about", "of memory"]);
    common::synth_experiment(dir.path(), 2);
    let spec = dir.path().join("experiment.toml");
    let output = adhesim_with_memory(&["experiment", spec.to_str().unwrap(), "--out", &out("exp")], "100000");
    assert_fails_with(&output, &["frames.path: frames of 320×240 pixels", "of memory"]);
    let output = adhesim_with_memory(&["reference", "hertz", "--points", "10000000"], "1000000");
    assert_fails_with(
        &output,
        &["--points 10000000 would need about 76.3 MiB of memory", "1000000 bytes"],
    );
    // The same commands pass within an ordinary limit.
    let output = adhesim_with_memory(&["reference", "hertz", "--points", "10"], "1000000");
    assert!(output.status.success(), "{}", stderr(&output));
}

/// Second robustness audit (docs/reliability.md): all lengths scaled by 1e-20 (inside the
/// documented window; γ scaled with them, E* kept). The normalised results must equal the
/// unscaled file's, and forces scale by 1e-40 (F ∝ γR), to the CG tolerance (relative residual
/// 1e-6: the two runs stop their solves at different roundings; measured 3e-9).
#[test]
fn lengths_scaled_by_1e_minus_20_give_the_same_normalised_results() {
    let temp = tempfile::tempdir().unwrap();
    let scenario = scenarios_dir().join("jkr.toml");
    let scenario = scenario.to_str().unwrap();
    let plain = temp.path().join("plain");
    let scaled = temp.path().join("scaled");
    let base = ["run", scenario, "--set", "grid.n=64", "--quiet", "--out"];
    let output = adhesim(&[&base[..], &[plain.to_str().unwrap()]].concat());
    assert!(output.status.success(), "{}", stderr(&output));
    let tiny = [
        "--set",
        "grid.size=0.25e-20",
        "--set",
        "indenter.radius=1e-20",
        "--set",
        "adhesion.work_of_adhesion=3.5367765131532306e-25",
    ];
    let output = adhesim(&[&base[..], &[scaled.to_str().unwrap()], &tiny[..]].concat());
    assert!(output.status.success(), "{}", stderr(&output));
    let plain = read_json(&plain.join("summary.json"))["results"].clone();
    let scaled = read_json(&scaled.join("summary.json"))["results"].clone();
    let value = |results: &serde_json::Value, key: &str| results[key].as_f64().unwrap();
    for (key, scale) in [
        ("gamma_approach_norm", 1.0),
        ("gamma_pulloff_norm", 1.0),
        ("adhesive_force_ratio", 1.0),
        ("max_adhesive_force", 1e-40),
        ("pull_off_depth", 1e-20),
    ] {
        let ratio = value(&scaled, key) / (scale * value(&plain, key));
        assert!((ratio - 1.0).abs() < 1e-6, "{key}: scaled/plain = {ratio}");
    }
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

/// `--checkpoint-every 1e300` (any value from about 1.9e19 s) panicked in
/// `Duration::from_secs_f64` ("cannot convert float seconds to Duration", exit 101), under
/// `sweep` and `study`: now an error naming the flag and the bound.
#[test]
fn a_checkpoint_interval_beyond_any_duration_is_an_error_naming_the_flag() {
    let dir = tempfile::tempdir().unwrap();
    let sweep = write(dir.path(), "one.toml", ONE_CASE);
    let out = dir.path().join("sweep");
    for value in ["1e300", "2e19", "inf", "-1"] {
        let output = adhesim(&[
            "sweep",
            sweep.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
            &format!("--checkpoint-every={value}"),
        ]);
        assert_fails_with(&output, &["--checkpoint-every", "from 0 (off) to 1e9"]);
    }
    let study = write(
        dir.path(),
        "rolling.toml",
        &format!(
            "kind = \"rolling\"\nbase = \"{}\"\nalphas = [0.8]\ndepths = [5]\n[normal]\nmax_depth = 5.0\nsteps = 20\n",
            scenarios_dir().join("fig6.toml").display()
        ),
    );
    let output = adhesim(&[
        "study",
        "rolling",
        study.to_str().unwrap(),
        "--out",
        dir.path().join("study").to_str().unwrap(),
        "--quiet",
        "--checkpoint-every",
        "1e300",
    ]);
    assert_fails_with(&output, &["--checkpoint-every", "got 1e300"]);
}

/// `adhesim topography p.npy --bins 4000000000` asked for 96 GB and died by SIGABRT: the
/// bins are capped (no map has more distinct wavevector magnitudes than the cap) and
/// checked against the memory available, the error naming `--bins`.
#[test]
fn psd_bins_are_capped_and_checked_against_the_memory() {
    let dir = tempfile::tempdir().unwrap();
    let values: Vec<f64> = (0..64).map(|i| (i as f64 * 0.7).sin()).collect();
    let map = dir.path().join("p.npy");
    std::fs::write(&map, npy_bytes((8, 8), &values)).unwrap();
    let topography = |bins: &str, memory: Option<&str>| {
        let mut command = Command::new(BIN);
        command.args([
            "topography",
            map.to_str().unwrap(),
            "--spacing",
            "1e-6",
            "--height-unit",
            "m",
            "--bins",
            bins,
            "--out",
            dir.path().join("t").to_str().unwrap(),
        ]);
        if let Some(bytes) = memory {
            command.env("ADHESIM_MEMORY_AVAILABLE", bytes);
        }
        command.output().unwrap()
    };
    let output = topography("4000000000", None);
    assert_fails_with(&output, &["--bins must be 2 … 1000000, got 4000000000"]);
    let output = topography("1000000", Some("10000000"));
    assert_fails_with(&output, &["--bins 1000000 would need about", "of memory available"]);
    let output = topography("30", Some("10000000"));
    assert!(output.status.success(), "{}", stderr(&output));
}

/// `ulimit -f 16` killed a run with SIGXFSZ (the signal's default action): the command now
/// ignores the signal, so the write fails with EFBIG and the run stops with the error
/// naming the file, as on a full disk, without a `curve.csv` under its final name. Unlike
/// `safe_outputs`' test, the shell does not ignore the signal for it.
#[cfg(unix)]
#[test]
fn a_file_size_limit_is_a_named_error_not_a_signal() {
    use std::os::unix::process::ExitStatusExt;
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    let command = format!(
        "trap - XFSZ; ulimit -f 8; exec '{BIN}' run '{}' --set protocol.steps=300 --out '{}' --quiet",
        hertz(),
        out.display()
    );
    let output = Command::new("sh").args(["-c", &command]).output().unwrap();
    assert_eq!(output.status.signal(), None, "killed by a signal: {}", stderr(&output));
    assert_fails_with(&output, &["cannot write", "curve.csv.partial", "File too large"]);
    assert!(!out.join("curve.csv").exists(), "a failed write left a curve.csv");
}

/// A FIFO named `checkpoint.json` in a killed case's tmp/ folder blocked the next sweep; a
/// checkpoint that is a link to /dev/zero was read without bound. Each is refused with a
/// warning naming the file, and the case runs from scratch.
#[cfg(unix)]
#[test]
fn a_checkpoint_that_is_not_a_regular_file_is_warned_about_not_read() {
    let dir = tempfile::tempdir().unwrap();
    let sweep = write(dir.path(), "one.toml", ONE_CASE);
    let out = dir.path().join("sweep");
    let args = [
        "sweep",
        sweep.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
        "--jobs",
        "1",
        "--checkpoint-every",
        "60",
    ];
    let output = adhesim_within(&args, Duration::from_secs(60));
    assert!(output.status.success(), "{}", stderr(&output));
    let case = std::fs::read_dir(out.join("cases"))
        .unwrap()
        .flatten()
        .next()
        .unwrap()
        .file_name()
        .to_string_lossy()
        .into_owned();
    for kind in ["fifo", "device"] {
        std::fs::remove_dir_all(out.join("cases").join(&case)).unwrap();
        // A pid above any pid_max: a killed run's folder.
        let killed = out.join("tmp").join(format!("{case}.4000000000"));
        std::fs::create_dir_all(&killed).unwrap();
        let checkpoint = killed.join("checkpoint.json");
        if kind == "fifo" {
            assert!(Command::new("mkfifo").arg(&checkpoint).status().unwrap().success());
        } else {
            std::os::unix::fs::symlink("/dev/zero", &checkpoint).unwrap();
        }
        let output = adhesim_within(&args, Duration::from_secs(60));
        assert!(output.status.success(), "{kind}: {}", stderr(&output));
        let log = stderr(&output);
        let expected = if kind == "fifo" { "is a FIFO" } else { "is a device" };
        assert!(
            log.contains("warning: checkpoint ")
                && log.contains(&checkpoint.display().to_string())
                && log.contains(expected)
                && log.contains("restarts from scratch"),
            "{kind}: {log}"
        );
        assert!(out.join("cases").join(&case).join("curve.csv").exists(), "{kind}");
    }
}

/// `law = "exponential"` with `range = 1e3` started its approach 6.9ρ above first contact
/// in steps the step cap did not count (about 3.5·10⁸ steps): refused before the run with
/// the estimate and the key to change.
#[test]
fn an_approach_beyond_the_step_cap_is_refused_before_the_run() {
    let scenario = scenarios_dir().join("cohesive").join("exponential_mu1.toml");
    let output = adhesim_within(
        &["run", scenario.to_str().unwrap(), "--set", "adhesion.range=1e3"],
        Duration::from_secs(60),
    );
    assert_fails_with(
        &output,
        &[
            "adhesion.range = 1000",
            "approach steps, more than the cap of 1000000",
            "choose a smaller adhesion.range or a larger depth step",
        ],
    );
}

/// A run that fails after writing (here at its retraction step limit) leaves its rows in
/// `curve.csv.partial` and nothing under a final name: `law = "exponential"` with
/// `range = 5e-324` failed on fields.npz and left a `curve.csv` of NaN rows. The error
/// names the limit's key.
#[test]
fn a_failed_run_leaves_no_file_under_a_final_name() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    let jkr = scenarios_dir().join("jkr.toml");
    let output = adhesim(&[
        "run",
        jkr.to_str().unwrap(),
        "--set",
        "grid.n=32",
        "--set",
        "protocol.max_retract_steps=1",
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert_fails_with(
        &output,
        &[
            "curve.csv.partial holds the steps done",
            "contact not lost after 1 retraction steps",
            "protocol.max_retract_steps = 1",
        ],
    );
    assert!(out.join("curve.csv.partial").exists());
    for name in ["curve.csv", "fields.npz", "summary.json"] {
        assert!(!out.join(name).exists(), "a failed run left {name}");
    }
    // The range that gave NaN rows is refused before the run, naming the key.
    let exponential = scenarios_dir().join("cohesive").join("exponential_mu1.toml");
    let output = adhesim(&[
        "run",
        exponential.to_str().unwrap(),
        "--set",
        "adhesion.range=5e-324",
        "--out",
        dir.path().join("nan").to_str().unwrap(),
    ]);
    assert_fails_with(&output, &["adhesion.range = 5e-324", "1e-150..1e150"]);
    assert!(!dir.path().join("nan").join("curve.csv").exists());
}

/// A grid size of 1e-310 was refused as "[grid]: grid element size size/n … Δ² = 0e0",
/// where every other message names `grid.size` and prints numbers as a person writes them.
#[test]
fn a_grid_of_subnormal_elements_is_named_as_grid_size_in_plain_numbers() {
    let output = adhesim(&["run", &hertz(), "--set", "grid.size=1e-310"]);
    assert_fails_with(
        &output,
        &[
            "grid.size = 1e-310 with grid.n = 64 makes elements of side 1.5625e-312 and area 0",
            "choose a grid.size commensurate with grid.n",
        ],
    );
    assert!(!stderr(&output).contains("0e0"), "{}", stderr(&output));
}

/// Degenerate law parameters: `cohesive_stress = 5e-324` gave F_ad = 0 (Dugdale) and
/// `range = 5e-324` NaN rows (exponential); refused before the run, naming the key.
#[test]
fn degenerate_law_parameters_are_refused_naming_the_key() {
    let dugdale = scenarios_dir().join("cohesive").join("maugis_lambda1.toml");
    let output = adhesim(&[
        "run",
        dugdale.to_str().unwrap(),
        "--set",
        "adhesion.cohesive_stress=5e-324",
    ]);
    assert_fails_with(&output, &["adhesion.cohesive_stress = 5e-324", "1e-150..1e150"]);
}

/// A sphere with `protocol.step = 1e6` |d_JKR| "ran" one step each way and reported a
/// dissipated energy of 57,198 without a word: warned on stderr and in summary.json.
#[test]
fn a_single_approach_step_is_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    let jkr = scenarios_dir().join("jkr.toml");
    let output = adhesim(&[
        "run",
        jkr.to_str().unwrap(),
        "--set",
        "grid.n=32",
        "--set",
        "protocol.steps=1",
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    let expected = "in 1 approach step of";
    assert!(stderr(&output).contains(expected), "{}", stderr(&output));
    if output.status.success() {
        let summary = read_json(&out.join("summary.json"));
        let warnings = summary["warnings"].as_array().unwrap();
        assert!(
            warnings.iter().any(|w| w.as_str().unwrap().contains(expected)),
            "{warnings:?}"
        );
    }
}

/// `plot master` drew NaN, inf, text and α ≤ 0 rows, and exited 0 with no figure when
/// every α was 0: each such row is an error naming the table, its line, the case and the
/// column; a table of good rows is drawn.
#[test]
fn plot_master_rejects_rows_it_cannot_draw() {
    let dir = tempfile::tempdir().unwrap();
    let header = "case,johnson_parameter,gamma_approach_norm,gamma_pulloff_norm,adhesive_force_ratio,status,series\n";
    let good = "0000-a,0.5,0.9,1.2,1.1,ok,s\n0001-b,1.0,0.8,1.4,1.2,ok,s\n";
    let out = dir.path().join("plots");
    let plot = |name: &str, rows: &str| {
        let table = write(dir.path(), name, &format!("{header}{good}{rows}"));
        adhesim(&[
            "plot",
            "master",
            table.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ])
    };
    for (row, column, value) in [
        ("0002-c,nan,0.8,1.4,1.2,ok,s\n", "johnson_parameter", "\"nan\""),
        ("0002-c,0,0.8,1.4,1.2,ok,s\n", "johnson_parameter", "\"0\""),
        ("0002-c,-1,0.8,1.4,1.2,ok,s\n", "johnson_parameter", "\"-1\""),
        ("0002-c,2.0,inf,1.4,1.2,ok,s\n", "gamma_approach_norm", "\"inf\""),
        ("0002-c,2.0,0.8,abc,1.2,ok,s\n", "gamma_pulloff_norm", "\"abc\""),
    ] {
        let output = plot("t.csv", row);
        let expected = format!("t.csv line 4 (case 0002-c): {column} = {value} cannot be drawn");
        assert_fails_with(&output, &[&expected]);
    }
    // A failed case's row is not drawn and not checked; an empty value is no value.
    let output = plot("t.csv", "0002-c,nan,,,,error,s\n0003-d,2.0,,1.3,,ok,s\n");
    assert!(output.status.success(), "{}", stderr(&output));
    // Every α 0: nothing to draw is an error, not exit 0 without a figure.
    let table = write(
        dir.path(),
        "zero.csv",
        &format!("{header}0000-a,0,0.9,1.2,1.1,error,s\n"),
    );
    let output = adhesim(&[
        "plot",
        "master",
        table.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_fails_with(&output, &["nothing to draw"]);
}

/// A topography indenter whose contact is below one element (a single low point of a
/// measured map) ran without a word: a warning on stderr and in summary.json.
#[test]
fn a_contact_of_one_element_on_a_map_is_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    let n = 16;
    let mut values = vec![1e-3; n * n];
    // Four points at 0: the element whose centre lies among them is the one lowest.
    for (row, column) in [
        (n / 2, n / 2),
        (n / 2, n / 2 - 1),
        (n / 2 - 1, n / 2),
        (n / 2 - 1, n / 2 - 1),
    ] {
        values[row * n + column] = 0.0;
    }
    std::fs::write(dir.path().join("spike.npy"), npy_bytes((n, n), &values)).unwrap();
    let scenario = format!(
        "[grid]\nn = {n}\nsize = 1.0\n[material]\ncontact_modulus = 1.0\n[adhesion]\nwork_of_adhesion = 0.0\n\
         [indenter]\nshape = \"topography\"\nfile = \"spike.npy\"\nspacing = {}\n\
         [protocol]\nkind = \"indent_pulloff\"\nmax_depth = 1e-5\ndepth_unit = \"length\"\nsteps = 4\n",
        1.0 / n as f64
    );
    let path = write(dir.path(), "spike.toml", &scenario);
    let out = dir.path().join("run");
    let output = adhesim(&["run", path.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let expected = "the contact never spanned more than 1 element";
    assert!(stderr(&output).contains(expected), "{}", stderr(&output));
    let summary = read_json(&out.join("summary.json"));
    assert!(
        summary["warnings"]
            .as_array()
            .unwrap()
            .iter()
            .any(|w| w.as_str().unwrap().contains(expected)),
        "{summary}"
    );
}

/// Type errors spoke Rust (`expected i64`, `floating point`): now in words.
#[test]
fn type_errors_name_types_in_words() {
    let output = adhesim(&["run", &hertz(), "--set", "protocol.steps=0.01"]);
    assert_fails_with(
        &output,
        &["protocol.steps = 0.01: invalid type: number `0.01`, expected an integer"],
    );
    let message = stderr(&output);
    assert!(
        !message.contains("i64") && !message.contains("floating point"),
        "{message}"
    );
    let output = adhesim(&["run", &hertz(), "--set", "indenter.radius=\"x\""]);
    assert_fails_with(&output, &["indenter.radius = \"x\": invalid type", "expected a number"]);
}
