//! Output folders never put a user's files at risk (docs/reliability.md, "Outputs and
//! folders"): `--out` refuses an unrelated non-empty folder, a re-run clears the previous
//! run's outputs, `curve.csv` only ever appears whole, a sweep folder is locked against a
//! second command, and a sweep with failed cases exits non-zero with their count.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::common;
use common::{
    adhesim, assert_fails_with, assert_ok, npy_bytes, read_json, run_quiet, scenarios_dir, stderr, write, BIN,
};

/// A Hertz indentation of a few milliseconds (16×16 grid).
const SMALL: &str = r#"
grid = { n = 16, size = 0.3 }
material = { contact_modulus = 1.0 }
adhesion = { work_of_adhesion = 0.0 }
indenter = { shape = "sphere", radius = 1.0 }
protocol = { kind = "indent_pulloff", max_depth = 0.01, steps = 6 }
"#;

/// A child process killed and reaped when dropped, also when an assertion fails.
struct Reaped(std::process::Child);

impl Reaped {
    fn spawn(command: &mut Command) -> Self {
        Self(command.spawn().expect("spawns"))
    }

    fn id(&self) -> u32 {
        self.0.id()
    }

    fn stop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

impl Drop for Reaped {
    fn drop(&mut self) {
        self.stop();
    }
}

fn names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .map(|entries| {
            entries
                .flatten()
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    names.sort();
    names
}

#[test]
fn out_refuses_an_unrelated_folder_unless_forced() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = write(dir.path(), "s.toml", SMALL);
    let mine = dir.path().join("my-data");
    std::fs::create_dir(&mine).unwrap();
    write(&mine, "curve.csv", "my own measurements\n");
    write(&mine, "notes.txt", "keep me\n");
    let output = run_quiet(&scenario, &mine, &[]);
    assert_fails_with(
        &output,
        &[mine.to_str().unwrap(), "not an adhesim run folder", "--force"],
    );
    assert_eq!(
        std::fs::read_to_string(mine.join("curve.csv")).unwrap(),
        "my own measurements\n"
    );
    assert_eq!(names(&mine), ["curve.csv", "notes.txt"]);

    // Forced: the run's outputs replace the user's curve.csv, other files stay.
    assert_ok(&run_quiet(&scenario, &mine, &["--force"]));
    assert!(std::fs::read_to_string(mine.join("curve.csv"))
        .unwrap()
        .starts_with("step,"));
    assert_eq!(std::fs::read_to_string(mine.join("notes.txt")).unwrap(), "keep me\n");
    assert!(mine.join(".adhesim-run").is_file());

    // An empty folder, or a missing one, is fine without --force.
    let empty = dir.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    assert_ok(&run_quiet(&scenario, &empty, &[]));
    assert_ok(&run_quiet(&scenario, &dir.path().join("new/nested"), &[]));
}

#[test]
fn rerun_clears_the_previous_outputs_and_leaves_no_temporary_file() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = write(dir.path(), "s.toml", SMALL);
    let out = dir.path().join("out");
    assert_ok(&run_quiet(&scenario, &out, &["--set", "output.snapshot_every=1"]));
    let marker = std::fs::read_to_string(out.join(".adhesim-run")).unwrap();
    assert!(
        marker.contains(&format!("results_revision = {}", adhesim::RESULTS_REVISION)),
        "marker: {marker}"
    );
    let first = names(&out.join("snapshots"));
    assert!(
        first.iter().filter(|n| n.starts_with("step_")).count() >= 6,
        "{first:?}"
    );
    write(&out.join("plots"), "stale.png", "old");

    // Fewer steps, no periodic snapshots: nothing of the first run may remain.
    assert_ok(&run_quiet(&scenario, &out, &["--set", "protocol.steps=3"]));
    let second = names(&out.join("snapshots"));
    assert!(
        second.iter().all(|n| !n.starts_with("step_")),
        "old snapshots left: {second:?}"
    );
    assert!(!out.join("plots/stale.png").exists());
    let rows = std::fs::read_to_string(out.join("curve.csv")).unwrap().lines().count();
    let summary: serde_json::Value = read_json(&out.join("summary.json"));
    assert_eq!(rows - 1, summary["performance"]["steps"].as_u64().unwrap() as usize);
    let leftovers: Vec<String> = names(&out)
        .into_iter()
        .filter(|n| n.ends_with(".tmp") || n.ends_with(".partial"))
        .collect();
    assert!(leftovers.is_empty(), "temporary files left: {leftovers:?}");
}

/// A run killed mid-way leaves its steps in `curve.csv.partial` and no `curve.csv`: a
/// file named `curve.csv` is always a whole run (a full disk or a kill cannot cut it).
#[test]
fn a_killed_run_never_leaves_a_cut_curve_csv() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = write(
        dir.path(),
        "s.toml",
        &SMALL
            .replace("n = 16", "n = 128")
            .replace("steps = 6", "steps = 100000")
            .replace("max_depth = 0.01", "max_depth = 0.02"),
    );
    let out = dir.path().join("out");
    let mut child = Reaped::spawn(
        Command::new(BIN)
            .args([
                "run",
                scenario.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
                "--quiet",
            ])
            .stdout(Stdio::null())
            .stderr(Stdio::null()),
    );
    let partial = out.join("curve.csv.partial");
    let start = Instant::now();
    while std::fs::read_to_string(&partial).map_or(0, |t| t.lines().count()) < 3 {
        assert!(start.elapsed() < Duration::from_secs(60), "no rows written");
        assert!(
            child.0.try_wait().unwrap().is_none(),
            "the run ended too early for the test"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    child.stop();
    assert!(!out.join("curve.csv").exists(), "a killed run left a curve.csv");
    let text = std::fs::read_to_string(&partial).unwrap();
    assert!(text.lines().count() >= 3);
}

/// A write that fails mid-run (a full disk; here the file-size limit of `ulimit -f`, with
/// SIGXFSZ ignored so that the write returns EFBIG as a full disk returns ENOSPC): the
/// error names the file, the exit status is 1, and no `curve.csv` is left cut mid-line.
#[test]
fn a_failed_write_names_the_file_and_leaves_no_cut_curve_csv() {
    let dir = tempfile::tempdir().unwrap();
    // 300 steps of ~130 bytes: curve.csv.partial passes the 4 KiB limit mid-run.
    let scenario = write(dir.path(), "s.toml", &SMALL.replace("steps = 6", "steps = 300"));
    let out = dir.path().join("out");
    let script = format!(
        "trap '' XFSZ; ulimit -f 8; exec '{BIN}' run '{}' --out '{}' --quiet",
        scenario.display(),
        out.display()
    );
    let output = Command::new("sh").args(["-c", &script]).output().unwrap();
    assert_eq!(output.status.code(), Some(1), "{}", stderr(&output));
    let partial = out.join("curve.csv.partial");
    assert_fails_with(&output, &["cannot write", &partial.display().to_string()]);
    assert!(!out.join("curve.csv").exists(), "a failed write left a curve.csv");
    assert!(!out.join("summary.json").exists(), "a failed run left a summary.json");
}

fn host_name() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .unwrap()
        .trim()
        .to_string()
}

const SWEEP: &str = r#"
series = "safe"

[scenario]
grid = { n = 16, size = 0.3 }
material = { contact_modulus = 1.0 }
adhesion = { work_of_adhesion = 0.0 }
indenter = { shape = "sphere", radius = 1.0 }
protocol = { kind = "indent_pulloff", max_depth = 0.01, steps = 6 }

[vary]
"indenter.radius" = [1.0, 2.0]
"#;

#[cfg(target_os = "linux")]
#[test]
fn a_locked_sweep_folder_is_refused_and_a_stale_lock_taken_over() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(dir.path(), "sweep.toml", SWEEP);
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    // A live process of this host holds the folder.
    let mut holder = Reaped::spawn(Command::new("sleep").arg("60"));
    let lock = out.join(".adhesim-lock");
    write(
        &out,
        ".adhesim-lock",
        &format!("pid = {}\nhost = {}\n", holder.id(), host_name()),
    );
    let sweep = |extra: &[&str]| {
        let mut args = vec![
            "sweep",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ];
        args.extend_from_slice(extra);
        adhesim(&args)
    };
    let output = sweep(&[]);
    assert_fails_with(&output, &[lock.to_str().unwrap(), &format!("pid {}", holder.id())]);
    assert!(!out.join("cases").exists(), "the refused sweep touched the folder");
    // A shard shares cases with the whole-folder lock; so does merge.
    assert_fails_with(
        &sweep(&["--shard", "1/2"]),
        &[".adhesim-lock", &format!("pid {}", holder.id())],
    );

    // The holder dies: its lock is stale, taken over with a message, released at the end.
    holder.stop();
    let output = sweep(&[]);
    assert_ok(&output);
    assert!(stderr(&output).contains("stale lock"), "stderr: {}", stderr(&output));
    assert!(!lock.exists(), "the lock was not released");
    assert_eq!(names(&out.join("cases")).len(), 2);
}

/// A lock whose owner cannot be checked (another host's, or one naming no owner) counts as
/// held: refused, with the advice to delete it if that process is gone; nothing touched.
#[test]
fn a_lock_of_another_host_or_without_owner_is_held() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(dir.path(), "sweep.toml", SWEEP);
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    let lock = out.join(".adhesim-lock");
    for (text, fragment) in [
        ("pid = 1\nhost = some-other-host\n", "held by pid 1 on some-other-host"),
        ("garbage", "names no owner"),
    ] {
        write(&out, ".adhesim-lock", text);
        let output = adhesim(&[
            "sweep",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ]);
        assert_fails_with(&output, &[lock.to_str().unwrap(), fragment, "delete the lock file if"]);
        assert_eq!(std::fs::read_to_string(&lock).unwrap(), text, "the lock was changed");
        assert!(!out.join("cases").exists(), "the refused sweep touched the folder");
    }
}

/// `--out` naming a file is an error naming it; the file is left as it was.
#[test]
fn out_naming_a_file_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = write(dir.path(), "s.toml", SMALL);
    let notes = write(dir.path(), "notes.txt", "mine");
    assert_fails_with(&run_quiet(&scenario, &notes, &[]), &[notes.to_str().unwrap()]);
    assert_fails_with(&run_quiet(&scenario, &notes, &["--force"]), &[notes.to_str().unwrap()]);
    assert_eq!(std::fs::read_to_string(&notes).unwrap(), "mine");
}

#[cfg(target_os = "linux")]
#[test]
fn shards_lock_only_their_own_cases() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(dir.path(), "sweep.toml", SWEEP);
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    let mut holder = Reaped::spawn(Command::new("sleep").arg("60"));
    write(
        &out,
        ".adhesim-lock-shard-0-of-2",
        &format!("pid = {}\nhost = {}\n", holder.id(), host_name()),
    );
    let sweep = |shard: &str| {
        adhesim(&[
            "sweep",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
            "--shard",
            shard,
        ])
    };
    // Shard 1/2 has other cases: it runs beside the holder of shard 0/2.
    assert_ok(&sweep("1/2"));
    // Shard 0/4 shares cases with 0/2 (k = 0, 4, ...): refused.
    assert_fails_with(&sweep("0/4"), &[".adhesim-lock-shard-0-of-2"]);
    holder.stop();
}

#[test]
fn a_sweep_with_failed_cases_exits_non_zero_with_the_count() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(dir.path(), "sweep.toml", SWEEP);
    let out = dir.path().join("out");
    let args = [
        "sweep",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ];
    assert_ok(&adhesim(&args));
    // A case recorded as failed (as a run that failed writes it) is kept on a re-run and
    // still makes the sweep fail, so that a cluster script notices.
    let case = names(&out.join("cases"))[1].clone();
    let done = out.join("cases").join(&case).join("done");
    let marker = std::fs::read_to_string(&done)
        .unwrap()
        .replace("status = ok", "status = error");
    std::fs::write(&done, marker).unwrap();
    let output = adhesim(&args);
    assert_fails_with(&output, &["1 of 2 cases failed", &case, "--retry-failed"]);
    // Redone, it succeeds.
    let mut retry = args.to_vec();
    retry.push("--retry-failed");
    assert_ok(&adhesim(&retry));
}

/// A case failing during its run (here a contact modulus whose forces overflow, refused by
/// the solver) counts as a failure of this run.
#[test]
fn a_case_failing_in_its_run_is_counted() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(
        dir.path(),
        "sweep.toml",
        &SWEEP.replace(
            "\"indenter.radius\" = [1.0, 2.0]",
            "\"material.contact_modulus\" = [1.0, 1e300]",
        ),
    );
    let out = dir.path().join("out");
    let output = adhesim(&[
        "sweep",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    let message = stderr(&output);
    assert!(!output.status.success(), "a failed case gave exit 0: {message}");
    assert!(!message.contains("panicked"), "panic: {message}");
    // Once validation refuses E* = 1e300 up front (docs/reliability.md) the sweep fails before
    // any case runs; either way it does not exit 0.
    if out.join("cases").exists() {
        assert!(message.contains("1 of 2 cases failed"), "stderr: {message}");
    }
}

#[cfg(target_os = "linux")]
#[test]
fn a_locked_study_folder_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let base = scenarios_dir().join("fig6.toml");
    let study = write(
        dir.path(),
        "rolling.toml",
        &format!(
            "kind = \"rolling\"\nbase = \"{}\"\nalphas = [0.8]\nset = [\"grid.n=16\"]\n",
            base.display()
        ),
    );
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    let mut holder = Reaped::spawn(Command::new("sleep").arg("60"));
    write(
        &out,
        ".adhesim-lock",
        &format!("pid = {}\nhost = {}\n", holder.id(), host_name()),
    );
    let output = adhesim(&[
        "study",
        "rolling",
        study.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert_fails_with(&output, &[".adhesim-lock", &format!("pid {}", holder.id())]);
    assert!(!out.join("table.csv").exists());
    holder.stop();
}

/// Second robustness audit (docs/reliability.md): a PNG that fails to write (the disk fills,
/// here a file-size limit of 64 KiB under `ulimit -f`, which the ~100 KiB height map of a 128²
/// map passes first) is named in the error, and neither it nor its temporary file is left; the
/// smaller files written before it are whole (the PSD's PNG has the bytes of an unlimited run).
#[cfg(target_os = "linux")]
#[test]
fn a_png_that_cannot_be_written_whole_is_named_and_not_left_cut() {
    let dir = tempfile::tempdir().unwrap();
    let n = 128;
    // white-noise heights: a map whose PNG barely compresses
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let heights: Vec<f64> = (0..n * n)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 1e-6
        })
        .collect();
    let map = dir.path().join("noise.npy");
    std::fs::write(&map, npy_bytes((n, n), &heights)).unwrap();
    let analyse = |out: &Path, limit: &str| {
        let script = format!(
            "trap '' XFSZ; {limit} exec '{BIN}' topography '{}' --spacing 1e-6 --height-unit m --out '{}'",
            map.display(),
            out.display()
        );
        Command::new("sh").args(["-c", &script]).output().unwrap()
    };
    let whole = dir.path().join("whole");
    let output = analyse(&whole, "");
    assert_ok(&output);
    let heights_png = std::fs::metadata(whole.join("heights.png")).unwrap().len();
    let psd_png = std::fs::metadata(whole.join("psd.png")).unwrap().len();
    assert!(
        psd_png < 64 * 1024 && heights_png > 64 * 1024,
        "{psd_png} and {heights_png} bytes"
    );

    let cut = dir.path().join("cut");
    // 128 blocks of 512 bytes (sh's unit)
    let output = analyse(&cut, "ulimit -f 128;");
    assert_eq!(output.status.code(), Some(1), "{}", stderr(&output));
    let target = cut.join("heights.png");
    assert_fails_with(&output, &["cannot write", &target.display().to_string()]);
    assert!(!target.exists(), "a failed write left heights.png");
    let leftovers: Vec<_> = std::fs::read_dir(&cut)
        .unwrap()
        .map(|entry| entry.unwrap().file_name().into_string().unwrap())
        .filter(|name| name.ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "temporary files left: {leftovers:?}");
    assert_eq!(
        std::fs::read(cut.join("psd.png")).unwrap(),
        std::fs::read(whole.join("psd.png")).unwrap()
    );
}
