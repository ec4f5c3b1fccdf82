//! Files that are not what they seem (FIFOs, folders, closed pipes, partial outputs):
//! each named, none blocking, none left under a final name.

use super::*;

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

/// A run that fails after writing (here at its retraction step limit) leaves its rows in
/// `curve.csv.partial` and nothing under a final name: `law = "exponential"` with
/// `range = 5e-324` failed on fields.npz and left a `curve.csv` of NaN rows. The error
/// names the limit's key.
#[test]
fn a_failed_run_leaves_no_file_under_a_final_name() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    let jkr = scenarios_dir().join("jkr.toml");
    let output = run_quiet(
        &jkr,
        &out,
        &["--set", "grid.n=32", "--set", "protocol.max_retract_steps=1"],
    );
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

/// `adhesim experiment snyth` said only that the spec file `snyth` could not be read: a
/// missing spec named like a subcommand now gets clap's suggestion too.
#[test]
fn a_misspelt_subcommand_read_as_a_spec_file_is_suggested() {
    let dir = tempfile::tempdir().unwrap();
    let output = Command::new(BIN)
        .args(["experiment", "snyth"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert_fails_with(
        &output,
        &["experiment spec snyth: no such file", "did you mean `synth`?"],
    );
    // An unrelated name: the file is not there, and nothing is suggested.
    let output = Command::new(BIN)
        .args(["experiment", "spec.toml"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert_fails_with(&output, &["cannot read experiment spec spec.toml"]);
    assert!(!stderr(&output).contains("did you mean"), "{}", stderr(&output));
}
