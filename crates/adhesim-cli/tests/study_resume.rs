//! `adhesim study` killed (SIGKILL) in the middle of a roll: the roll's run had written a
//! mid-run checkpoint, and the study run again goes on from it ("resumed case ... at step
//! k" on stderr), with the roll's curve.csv and the study's tables of an uninterrupted
//! study (docs/sweeps.md, "Resuming a case mid-run").

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

mod common;
use common::{adhesim, repo, stderr, write};

const BIN: &str = env!("CARGO_BIN_EXE_adhesim");

fn args(study: &Path, out: &Path) -> Vec<String> {
    let mut args: Vec<String> = [
        "study",
        "rolling",
        study.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]
    .map(String::from)
    .to_vec();
    args.extend(["--quiet", "--checkpoint-every", "0.05"].map(String::from));
    args
}

/// The folder of the roll (`case-…`) under `dir` (`cases/` or `tmp/`).
fn roll_folder(dir: &Path) -> Option<PathBuf> {
    std::fs::read_dir(dir)
        .ok()?
        .flatten()
        .map(|e| e.path())
        .find(|p| p.file_name().is_some_and(|n| n.to_string_lossy().starts_with("case-")))
}

/// The table without its last column (the runs' wall seconds).
fn table_without_wall(out: &Path) -> Vec<String> {
    std::fs::read_to_string(out.join("table.csv"))
        .unwrap()
        .lines()
        .map(|l| l.rsplit_once(',').map_or(l, |(head, _)| head).to_string())
        .collect()
}

#[test]
fn a_study_killed_mid_roll_resumes_from_the_checkpoint() {
    let dir = tempfile::tempdir().unwrap();
    let study = write(
        dir.path(),
        "rolling.toml",
        &format!(
            "kind = \"rolling\"\nbase = \"{}\"\nalphas = [0.8]\ndepths = [5]\n\
             set = [\"grid.n=48\", \"protocol.approach_steps=20\", \"protocol.steps=240\"]\n\
             [normal]\nmax_depth = 5.0\nsteps = 20\n",
            repo().join("scenarios").join("fig6.toml").display()
        ),
    );
    let reference = dir.path().join("reference");
    let output = adhesim(&args(&study, &reference).iter().map(String::as_str).collect::<Vec<_>>());
    assert!(output.status.success(), "{}", stderr(&output));
    let roll = roll_folder(&reference.join("cases")).expect("the roll's case folder");
    let expected_curve = std::fs::read(roll.join("curve.csv")).unwrap();
    assert!(
        !roll.join("checkpoint.json").exists(),
        "a finished run keeps no checkpoint"
    );

    let killed = dir.path().join("killed");
    let args = args(&study, &killed);
    let mut child = Command::new(BIN)
        .args(&args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let checkpoint = || {
        roll_folder(&killed.join("tmp"))
            .map(|p| p.join("checkpoint.json"))
            .filter(|p| p.exists())
    };
    let start = Instant::now();
    while checkpoint().is_none() {
        assert!(start.elapsed() < Duration::from_secs(300), "no checkpoint written");
        assert!(
            child.try_wait().unwrap().is_none(),
            "the study ended before a checkpoint"
        );
        std::thread::sleep(Duration::from_millis(2));
    }
    std::thread::sleep(Duration::from_millis(50));
    child.kill().unwrap();
    child.wait().unwrap();
    if roll_folder(&killed.join("cases")).is_some() {
        // The roll finished before the kill (a very fast machine): nothing to resume.
        return;
    }
    let output = adhesim(&args.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(output.status.success(), "{}", stderr(&output));
    let log = stderr(&output);
    assert!(log.contains("resumed case case-") && log.contains(" at step "), "{log}");
    let roll = roll_folder(&killed.join("cases")).expect("the roll's case folder");
    assert!(
        std::fs::read(roll.join("curve.csv")).unwrap() == expected_curve,
        "curve.csv differs"
    );
    assert_eq!(table_without_wall(&killed), table_without_wall(&reference));
}
