//! Limits of the machine and of the inputs' sizes: address space, memory, file size,
//! step counts and durations, each refused or reported by name before it can abort a run.

use super::*;

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

/// `--allow-large` skipped every memory check, so under `ulimit -v` the run aborted in an
/// allocation ("memory allocation of N bytes failed", SIGABRT), and `experiment synth` of
/// 16000 × 16000 frames the same. RLIMIT_AS, which neither swap nor a lazy allocator gets
/// past, is now checked with the flag too, and synth checks its frames' memory first: each
/// an error naming the flag or size and the limit, exit status 1.
#[test]
fn an_address_space_limit_is_a_named_error_under_allow_large_and_synth() {
    let out = tempfile::tempdir().unwrap();
    let limited = |args: String| {
        Command::new("sh")
            .args(["-c", &format!("ulimit -v 1953125 && exec '{BIN}' {args}")])
            .env_remove("ADHESIM_MEMORY_AVAILABLE")
            .output()
            .unwrap()
    };
    let run = out.path().join("run");
    let output = limited(format!(
        "run '{}' --set grid.n=2500 --out '{}' --quiet --allow-large",
        hertz(),
        run.display()
    ));
    assert_fails_with(
        &output,
        &[
            "even with --allow-large",
            "grid.n = 2500 needs about",
            "RLIMIT_AS",
            "which --allow-large does not lift): lower grid.n or raise the limit",
        ],
    );
    assert!(!run.join("curve.csv").exists());
    let synth = out.path().join("synth");
    let output = limited(format!(
        "experiment synth --out '{}' --frames 2 --width 16000 --height 16000 --quiet",
        synth.display()
    ));
    assert_fails_with(&output, &["--width 16000 --height 16000", "of memory", "RLIMIT_AS"]);
}
