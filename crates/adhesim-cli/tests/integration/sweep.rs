//! End-to-end tests of `adhesim sweep`: resuming after SIGKILL (whole cases, and a case
//! from its mid-run checkpoint), shards + merge, bad sweep files, and the JKR fits of a
//! smooth-sphere run.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::common;
use common::{
    adhesim, assert_fails_with, assert_ok, kill_after_checkpoint, read_json, scenarios_dir, stderr, sweeps_dir, write,
    BIN,
};

/// Eight cases of a few tenths of a second each (64×64 grid).
const SLOW_SWEEP: &str = r#"
series = "kill-test"

[scenario]
grid = { n = 64, size = 0.8 }
material = { contact_modulus = 1.0 }
adhesion = { work_of_adhesion = 6.16850275068085e-4 }
indenter = { shape = "wavy_sphere", radius = 1.0, amplitude = 0.0025, wavelength = 0.05 }
protocol = { kind = "indent_pulloff", max_depth = 8.0, depth_unit = "jkr", steps = 40 }

[vary]
alpha = [0.4, 0.6, 0.8, 1.0, 1.3, 1.7, 2.2, 3.0]
"#;

fn finished_cases(dir: &Path) -> Vec<String> {
    let mut ids: Vec<String> = std::fs::read_dir(dir.join("cases"))
        .map(|entries| {
            entries
                .flatten()
                .filter(|e| e.path().join("done").exists())
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    ids.sort();
    ids
}

#[test]
fn sweep_killed_and_restarted_gives_the_uninterrupted_table() {
    let temp = tempfile::tempdir().unwrap();
    let sweep = write(temp.path(), "slow.toml", SLOW_SWEEP);
    let sweep = sweep.to_str().unwrap();

    // Uninterrupted reference, two cases at a time.
    let reference = temp.path().join("reference");
    let reference_s = reference.to_str().unwrap();
    assert_ok(&adhesim(&[
        "sweep",
        sweep,
        "--out",
        reference_s,
        "--jobs",
        "2",
        "--threads",
        "1",
        "--quiet",
    ]));
    let expected = std::fs::read(reference.join("table.csv")).unwrap();
    assert_eq!(finished_cases(&reference).len(), 8);

    // Killed (SIGKILL) as soon as one case is finished, then restarted.
    let killed = temp.path().join("killed");
    let killed_s = killed.to_str().unwrap();
    let args = [
        "sweep",
        sweep,
        "--out",
        killed_s,
        "--jobs",
        "1",
        "--threads",
        "1",
        "--quiet",
    ];
    let mut child = Command::new(BIN)
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while finished_cases(&killed).is_empty() {
        assert!(start.elapsed() < Duration::from_secs(120), "no case finished");
        if child.try_wait().unwrap().is_some() {
            break;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let before = finished_cases(&killed);
    assert!(!before.is_empty());
    let first_summary = std::fs::read(killed.join("cases").join(&before[0]).join("summary.json")).unwrap();
    if before.len() < 8 {
        assert!(!killed.join("table.csv").exists() || std::fs::read(killed.join("table.csv")).unwrap() != expected);
    }

    let output = adhesim(&args);
    assert_ok(&output);
    let after = finished_cases(&killed);
    assert_eq!(after.len(), 8);
    for id in &before {
        assert!(after.contains(id), "finished case {id} lost");
    }
    // Not redone: the summary (with its wall time) is the one written before the kill.
    let again = std::fs::read(killed.join("cases").join(&before[0]).join("summary.json")).unwrap();
    assert_eq!(first_summary, again, "finished case {} was redone", before[0]);
    assert_eq!(
        String::from_utf8(std::fs::read(killed.join("table.csv")).unwrap()).unwrap(),
        String::from_utf8(expected).unwrap()
    );
    // Nothing left in the temporary folder of this (single) shard.
    assert_eq!(std::fs::read_dir(killed.join("tmp")).unwrap().count(), 0);
    assert!(killed.join("plots/fig3_master.png").exists());
}

#[test]
fn three_shards_merged_give_the_single_run_table() {
    let temp = tempfile::tempdir().unwrap();
    let sweep = sweeps_dir().join("tiny.toml");
    let sweep = sweep.to_str().unwrap();
    let single = temp.path().join("single");
    assert_ok(&adhesim(&[
        "sweep",
        sweep,
        "--out",
        single.to_str().unwrap(),
        "--quiet",
    ]));
    let expected = std::fs::read_to_string(single.join("table.csv")).unwrap();
    assert_eq!(expected.lines().count(), 7, "{expected}");

    let sharded = temp.path().join("sharded");
    let sharded_s = sharded.to_str().unwrap();
    for shard in ["2/3", "0/3", "1/3"] {
        assert_ok(&adhesim(&[
            "sweep", sweep, "--out", sharded_s, "--shard", shard, "--jobs", "1", "--quiet",
        ]));
    }
    // A shard runs only its own cases.
    let partial = temp.path().join("partial");
    assert_ok(&adhesim(&[
        "sweep",
        sweep,
        "--out",
        partial.to_str().unwrap(),
        "--shard",
        "1/3",
        "--quiet",
    ]));
    let ids = finished_cases(&partial);
    assert_eq!(
        ids,
        ["0001", "0004"]
            .iter()
            .map(|p| {
                finished_cases(&single)
                    .into_iter()
                    .find(|id| id.starts_with(p))
                    .unwrap()
            })
            .collect::<Vec<_>>()
    );

    std::fs::remove_file(sharded.join("table.csv")).unwrap();
    assert_ok(&adhesim(&["sweep", "merge", sharded_s, "--quiet"]));
    assert_eq!(std::fs::read_to_string(sharded.join("table.csv")).unwrap(), expected);
    assert_ok(&adhesim(&[
        "sweep",
        sweep,
        "--out",
        sharded_s,
        "--merge-only",
        "--quiet",
    ]));
    assert_eq!(std::fs::read_to_string(sharded.join("table.csv")).unwrap(), expected);

    // `plot master` redraws from tables (two tables: two series).
    let plots = temp.path().join("figs");
    let table = single.join("table.csv");
    let table2 = sharded.join("table.csv");
    assert_ok(&adhesim(&[
        "plot",
        "master",
        table.to_str().unwrap(),
        table2.to_str().unwrap(),
        "--out",
        plots.to_str().unwrap(),
    ]));
    for name in [
        "fig3_master.svg",
        "fig3_master.png",
        "fig5_master.png",
        "force_radius_cases.png",
    ] {
        assert!(plots.join(name).exists(), "{name} missing");
    }
    // --no-area leaves out the area-radius fits (the default draws them: the tiny cases
    // have them); --join adds one line per series and panel: one series (both tables are
    // the tiny sweep's, series "tiny") × 3 panels.
    let svg = |dir: &Path| std::fs::read_to_string(dir.join("fig3_master.svg")).unwrap();
    let polylines = |text: &str| text.matches("<polyline").count();
    let mut drawn = Vec::new();
    for (name, flags) in [
        ("no_area", &["--no-area"][..]),
        ("joined", &["--no-area", "--join"][..]),
    ] {
        let dir = temp.path().join(name);
        let mut args = vec!["plot", "master", table.to_str().unwrap(), table2.to_str().unwrap()];
        args.extend(flags);
        args.extend(["--out", dir.to_str().unwrap()]);
        assert_ok(&adhesim(&args));
        drawn.push(svg(&dir));
    }
    assert!(svg(&plots).contains("√(A/π)"));
    assert!(!drawn[0].contains("√(A/π)") && !drawn[1].contains("√(A/π)"));
    assert_eq!(polylines(&drawn[1]), polylines(&drawn[0]) + 3);
}

#[test]
fn bad_sweep_files_name_the_key() {
    let temp = tempfile::tempdir().unwrap();
    let base = std::fs::read_to_string(sweeps_dir().join("tiny.toml")).unwrap();
    let scenario = &base[base.find("[scenario]").unwrap()..base.find("[vary]").unwrap()];
    let cases: [(&str, &[&str]); 9] = [
        (
            "[vary]\n\"indenter.amplitud\" = [1e-4, 2e-4]\n",
            &["indenter.amplitud", "unknown key"],
        ),
        ("[vary]\n\"nosuch.key\" = [1, 2]\n", &["nosuch"]),
        (
            "[zip]\n\"grid.n\" = [32, 40]\n\"grid.size\" = [0.8, 0.9, 1.0]\n",
            &["zip.\"grid.size\" has 3", "zip.\"grid.n\" has 2", "equal lengths"],
        ),
        (
            "[random]\nseed = 1\ncases = 3\n\"material.contact_modulus\" = { min = 2.0, max = 1.0 }\n",
            &["random.\"material.contact_modulus\"", "min (2) > max (1)"],
        ),
        (
            "[random]\nseed = 1\ncases = 3\n\"material.contact_modulus\" = { min = 0.0, max = 1.0, scale = \"log\" }\n",
            &["random.\"material.contact_modulus\"", "min > 0"],
        ),
        (
            "[vary]\n\"indenter.radius\" = [1.0, -1.0]\n",
            &["indenter.radius = -1.0", "indenter.radius must be > 0, got -1"],
        ),
        (
            "[vary]\n\"grid.n\" = [32]\n[zip]\n\"grid.n\" = [40]\n",
            &["grid.n", "more than once"],
        ),
        (
            "[vary]\nmaugis_parameter = [1.5]\n",
            &["maugis_parameter = 1.5", "adhesion.law is not set"],
        ),
        (
            "[set]\n\"adhesion.law\" = \"dugdale\"\n[vary]\nmaugis_parameter = [1.5, -2.0]\n",
            &["maugis_parameter must be a finite number > 0, got -2"],
        ),
    ];
    for (k, (tail, fragments)) in cases.iter().enumerate() {
        let path = write(temp.path(), &format!("bad{k}.toml"), &format!("{scenario}{tail}"));
        let out = temp.path().join(format!("out{k}"));
        let output = adhesim(&["sweep", path.to_str().unwrap(), "--out", out.to_str().unwrap()]);
        assert_fails_with(&output, fragments);
        assert!(!out.exists(), "a bad sweep file must not create {}", out.display());
    }
    let output = adhesim(&[
        "sweep",
        sweeps_dir().join("tiny.toml").to_str().unwrap(),
        "--shard",
        "3/3",
    ]);
    assert_fails_with(&output, &["--shard", "3/3"]);
}

#[test]
fn smooth_sphere_fits_recover_the_work_of_adhesion() {
    let temp = tempfile::tempdir().unwrap();
    let scenario = scenarios_dir().join("jkr.toml");
    let out = temp.path().join("jkr");
    assert_ok(&adhesim(&[
        "run",
        scenario.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
        "--set",
        "grid.n=64",
        "--set",
        "protocol.steps=40",
    ]));
    let summary: serde_json::Value = read_json(&out.join("summary.json"));
    let results = &summary["results"];
    for key in ["gamma_approach_norm", "gamma_pulloff_norm"] {
        let value = results[key].as_f64().unwrap();
        assert!((value - 1.0).abs() < 0.1, "{key} = {value}");
    }
    let g0 = summary["inputs"]["adhesion"]["work_of_adhesion"].as_f64().unwrap();
    let g1 = results["gamma_approach"].as_f64().unwrap();
    let g2 = results["gamma_pulloff"].as_f64().unwrap();
    assert!((g1 / g0 - 1.0).abs() < 0.1 && (g2 / g0 - 1.0).abs() < 0.1);
    let q = results["boundary_friction"].as_f64().unwrap();
    assert!((q - 0.5 * (g2 - g1)).abs() < 1e-15);
    for key in [
        "gamma_approach_residual",
        "adhesive_force_ratio",
        "compactness_at_max_depth",
        "pinned_steps",
    ] {
        assert!(results[key].is_number(), "{key} = {}", results[key]);
    }
    assert!(out.join("plots/force_radius.svg").exists());
}

/// A folder finished by an older results revision (simulated by rewriting the case hashes
/// that revision would have produced) is not refused as "a different sweep": its cases
/// are redone under the current revision, and the table is rebuilt from them.
#[test]
fn cases_of_an_older_results_revision_are_redone() {
    let temp = tempfile::tempdir().unwrap();
    let out = temp.path().join("tiny");
    let out_s = out.to_str().unwrap();
    let sweep = sweeps_dir().join("tiny.toml");
    let args = [
        "sweep",
        sweep.to_str().unwrap(),
        "--out",
        out_s,
        "--jobs",
        "2",
        "--threads",
        "1",
        "--quiet",
    ];
    assert_ok(&adhesim(&args));
    let cases = finished_cases(&out);
    assert!(!cases.is_empty());
    let marker = out.join("cases").join(&cases[0]).join("done");
    let current = std::fs::read_to_string(&marker).unwrap();
    let hash = current
        .lines()
        .find_map(|l| l.strip_prefix("hash = "))
        .unwrap()
        .trim()
        .to_string();
    let old_hash = "0123456789abcdef";
    std::fs::write(&marker, current.replace(&hash, old_hash)).unwrap();
    let plan = std::fs::read_to_string(out.join("sweep.json")).unwrap();
    std::fs::write(out.join("sweep.json"), plan.replace(&hash, old_hash)).unwrap();
    let summary = out.join("cases").join(&cases[0]).join("summary.json");
    std::fs::write(&summary, "stale").unwrap();

    assert_ok(&adhesim(&args));
    assert_eq!(std::fs::read_to_string(&marker).unwrap(), current);
    assert_ne!(
        std::fs::read_to_string(&summary).unwrap(),
        "stale",
        "the old case was not redone"
    );
}

/// One case of a second or two (64×64 grid, 60 approach steps).
const ONE_CASE_SWEEP: &str = r#"
series = "checkpoint-test"

[scenario]
grid = { n = 64, size = 0.8 }
material = { contact_modulus = 1.0 }
adhesion = { work_of_adhesion = 6.16850275068085e-4 }
indenter = { shape = "wavy_sphere", radius = 1.0, amplitude = 0.0025, wavelength = 0.05 }
protocol = { kind = "indent_pulloff", max_depth = 8.0, depth_unit = "jkr", steps = 60 }
output = { snapshot_steps = [10, 70] }

[vary]
alpha = [1.0]
"#;

/// Every file of a case folder (by path relative to it), summary.json without its
/// `performance` section (wall times).
fn case_folder_files(folder: &Path) -> Vec<(String, Vec<u8>)> {
    adhesim_scenario::output::folder::comparable_files(folder).unwrap()
}

/// A case killed (SIGKILL) mid-run after a checkpoint goes on from it when the sweep is
/// run again ("resumed case ... at step k" on stderr), and its folder (curve.csv,
/// summary.json but `performance`, fields.npz, snapshots, plots) is byte-identical to an
/// uninterrupted run's.
#[test]
fn a_case_killed_mid_run_resumes_from_its_checkpoint() {
    let temp = tempfile::tempdir().unwrap();
    let sweep = write(temp.path(), "one.toml", ONE_CASE_SWEEP);
    let sweep = sweep.to_str().unwrap();
    let run = |out: &Path| {
        let mut args: Vec<String> = [
            "sweep",
            sweep,
            "--out",
            out.to_str().unwrap(),
            "--jobs",
            "1",
            "--threads",
            "1",
        ]
        .map(String::from)
        .to_vec();
        args.extend(["--quiet", "--checkpoint-every", "0.05"].map(String::from));
        args
    };
    let reference = temp.path().join("reference");
    let args = run(&reference);
    assert_ok(&adhesim(&args.iter().map(String::as_str).collect::<Vec<_>>()));
    let [id] = &finished_cases(&reference)[..] else {
        panic!("one case")
    };
    let expected = case_folder_files(&reference.join("cases").join(id));
    assert!(!expected.iter().any(|(name, _)| name.contains("checkpoint")));

    let killed = temp.path().join("killed");
    let args = run(&killed);
    let checkpoint = || -> Option<std::path::PathBuf> {
        let entries = std::fs::read_dir(killed.join("tmp")).ok()?;
        entries
            .flatten()
            .map(|e| e.path().join("checkpoint.json"))
            .find(|p| p.exists())
    };
    kill_after_checkpoint(
        &args,
        || checkpoint().is_some(),
        Duration::from_secs(120),
        Duration::from_millis(100),
    );
    if !finished_cases(&killed).is_empty() {
        // The case finished before the kill (a very fast machine): nothing to resume.
        return;
    }
    assert!(checkpoint().is_some());
    let output = adhesim(&args.iter().map(String::as_str).collect::<Vec<_>>());
    assert_ok(&output);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains(&format!("resumed case {id} at step ")), "{stderr}");
    let resumed = case_folder_files(&killed.join("cases").join(id));
    let names = |files: &[(String, Vec<u8>)]| files.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>();
    assert_eq!(names(&resumed), names(&expected));
    for ((name, a), (_, b)) in resumed.iter().zip(&expected) {
        assert!(a == b, "{name} differs from the uninterrupted run's");
    }
    assert_eq!(std::fs::read_dir(killed.join("tmp")).unwrap().count(), 0);
}

/// The sweep's bar counted whole cases only (`0/3 cases` until the first case ended): on a
/// terminal (the pseudo-terminal of util-linux `script`) a second line counts the steps of
/// the running cases; the progress goes to stderr only, so the outputs equal those of a
/// sweep without a terminal byte for byte.
#[cfg(target_os = "linux")]
#[test]
fn sweep_progress_counts_the_steps_of_running_cases() {
    let temp = tempfile::tempdir().unwrap();
    let text = SLOW_SWEEP.replace("[0.4, 0.6, 0.8, 1.0, 1.3, 1.7, 2.2, 3.0]", "[0.4, 1.0, 3.0]");
    let sweep = write(temp.path(), "three.toml", &text);
    let (quiet, shown) = (temp.path().join("quiet"), temp.path().join("shown"));
    let args = |out: &Path| format!("sweep {} --out {} --jobs 1 --threads 1", sweep.display(), out.display());
    let piped = Command::new(BIN).args(args(&quiet).split(' ')).output().unwrap();
    assert_ok(&piped);
    assert!(!stderr(&piped).contains("steps of"), "no bar without a terminal");
    let typescript = temp.path().join("typescript");
    let status = Command::new("script")
        .args(["-q", "-e", "-c", &format!("{BIN} {}", args(&shown))])
        .arg(&typescript)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .status()
        .expect("util-linux `script` runs (a pseudo-terminal for the bar)");
    assert!(status.success());
    let drawn = String::from_utf8_lossy(&std::fs::read(&typescript).unwrap()).into_owned();
    assert!(
        drawn.contains("cases (eta") && drawn.contains("steps of 1 running case"),
        "{drawn}"
    );
    // Steps done out of planned: a case's approach and as many back (80) known from its start.
    let counts: Vec<(u64, u64)> = drawn
        .split(" steps of")
        .filter_map(|before| {
            let (done, planned) = before.rsplit(' ').next()?.split_once('/')?;
            Some((done.parse().ok()?, planned.parse().ok()?))
        })
        .collect();
    assert!(
        counts.iter().any(|&(done, planned)| done < planned && planned >= 80),
        "{counts:?}"
    );
    assert_eq!(
        std::fs::read(quiet.join("table.csv")).unwrap(),
        std::fs::read(shown.join("table.csv")).unwrap()
    );
    for case in std::fs::read_dir(quiet.join("cases")).unwrap() {
        let id = case.unwrap().file_name();
        let curve = |dir: &Path| std::fs::read(dir.join("cases").join(&id).join("curve.csv")).unwrap();
        assert_eq!(curve(&quiet), curve(&shown), "{id:?}");
    }
}
