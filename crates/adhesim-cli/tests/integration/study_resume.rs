//! Long studies: `adhesim study` killed (SIGKILL) in the middle of a roll goes on from the
//! roll's mid-run checkpoint ("resumed case ... at step k" on stderr), with the roll's
//! curve.csv and the study's tables of an uninterrupted study (docs/sweeps.md, "Resuming a
//! case mid-run"); `--tables-only` writes the interim tables of the α whose runs are done.

use std::path::{Path, PathBuf};
use std::time::Duration;

use crate::common;
use common::{adhesim, kill_after_checkpoint, repo, stderr, write};

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
    let checkpoint = || roll_folder(&killed.join("tmp")).is_some_and(|p| p.join("checkpoint.json").exists());
    kill_after_checkpoint(&args, checkpoint, Duration::from_secs(300), Duration::from_millis(50));
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

/// `--tables-only` with one roll of the second α missing: runs nothing, and writes the
/// first α's rows exactly as the whole study wrote them (wall seconds aside), without the
/// second α; study.json names it. With no α complete it writes no tables.
#[test]
fn tables_only_writes_the_alphas_whose_runs_are_done() {
    let dir = tempfile::tempdir().unwrap();
    let study = write(
        dir.path(),
        "rolling.toml",
        &format!(
            "kind = \"rolling\"\nbase = \"{}\"\nalphas = [0.8, 1.2]\ndepths = [3, 5]\n\
             set = [\"grid.n=32\", \"protocol.approach_steps=10\", \"protocol.steps=8\"]\n\
             [normal]\nmax_depth = 5.0\nsteps = 20\n",
            repo().join("scenarios").join("fig6.toml").display()
        ),
    );
    let out = dir.path().join("r");
    let run = |extra: &[&str]| {
        let mut args = vec![
            "study",
            "rolling",
            study.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let output = adhesim(&args);
        assert!(output.status.success(), "{}", stderr(&output));
        output
    };
    run(&["--quiet"]);
    let whole = table_without_wall(&out);
    let whole_alphas = std::fs::read_to_string(out.join("alphas.csv")).unwrap();
    let cases = out.join("cases");
    let victim = std::fs::read_dir(&cases)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .find(|p| p.to_string_lossy().contains("case-1-1-"))
        .unwrap();
    std::fs::remove_dir_all(&victim).unwrap();
    let output = run(&["--tables-only"]);
    assert!(!victim.exists(), "--tables-only ran a run");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("interim") && stdout.contains("1.2"), "{stdout}");
    let interim = table_without_wall(&out);
    assert_eq!(interim.len(), 3, "a header and the two rolls of α = 0.8");
    assert_eq!(interim[..], whole[..3]);
    let alphas = std::fs::read_to_string(out.join("alphas.csv")).unwrap();
    let lines: Vec<&str> = alphas.lines().collect();
    assert_eq!(lines.len(), 2);
    let strip = |l: &str| {
        l.split(',')
            .enumerate()
            .filter(|(k, _)| *k != 4)
            .map(|(_, v)| v.to_string())
            .collect::<Vec<_>>()
    };
    let whole_lines: Vec<&str> = whole_alphas.lines().collect();
    assert!(
        whole_lines[0].split(',').nth(4) == Some("normal_wall_seconds"),
        "{}",
        whole_lines[0]
    );
    assert_eq!(strip(lines[1]), strip(whole_lines[1]));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("study.json")).unwrap()).unwrap();
    assert_eq!(json["unfinished_alphas"], serde_json::json!([1.2]));

    // No α complete: no tables.
    for entry in std::fs::read_dir(&cases).unwrap().flatten() {
        if entry.file_name().to_string_lossy().starts_with("case-0-0-") {
            std::fs::remove_dir_all(entry.path()).unwrap();
        }
    }
    for file in ["table.csv", "alphas.csv", "study.json"] {
        std::fs::remove_file(out.join(file)).unwrap();
    }
    let output = run(&["--tables-only"]);
    assert!(stderr(&output).contains("no tables written"), "{}", stderr(&output));
    assert!(!out.join("table.csv").exists());
}
