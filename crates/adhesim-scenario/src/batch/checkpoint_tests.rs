//! Mid-case checkpoints through the engine, on a real case (the Fig. 1 wavy sphere at
//! n = 40, scenarios/fig1.toml's kind): a case killed after a checkpoint (simulated: a
//! progress that panics after step k, so that nothing after it runs, as under SIGKILL, in a
//! temporary folder whose pid is not alive) is continued by the next batch from its
//! checkpoint and its folder is byte-identical to an uninterrupted run's (curve.csv,
//! fields.npz, the snapshot .npy files, summary.json but `performance`); a corrupt or
//! mismatched checkpoint is warned about and the case restarts, with the same files.

use super::*;
use crate::output::checkpoint::CHECKPOINT_FILE;
use crate::output::observer::RunProgress;
use crate::output::run::{run_into_folder, FolderRunOptions};
use adhesim::StepRecord;

const SCENARIO: &str = r#"
[grid]
n = 40
size = 0.25
boundary = "free"

[material]
contact_modulus = 1.0

[adhesion]
work_of_adhesion = 6.16850275068085e-4

[indenter]
shape = "wavy_sphere"
radius = 1.0
amplitude = 0.0025
wavelength = 0.05
angle = 0.0

[protocol]
kind = "indent_pulloff"
max_depth = 6.0
depth_unit = "jkr"
steps = 24

[output]
snapshot_steps = [3, 30]
jump_force_threshold = 0.01
"#;

/// A pid that is never alive (above any pid_max).
const DEAD_PID: u32 = 4_000_000_000;

/// A sweep-like case that runs the scenario into its folder without pictures.
struct RealCase {
    id: String,
    hash: String,
    text: String,
    /// The first step a run of the batch solved (0, or where it resumed).
    first_step: std::sync::Mutex<Option<usize>>,
}

fn real_case(text: &str) -> RealCase {
    RealCase {
        id: "wavy".into(),
        hash: format!("{:016x}", cases::results_hash(text)),
        text: text.into(),
        first_step: std::sync::Mutex::new(None),
    }
}

/// Notes the first step solved.
struct FirstStep<'a>(&'a std::sync::Mutex<Option<usize>>);

impl RunProgress for FirstStep<'_> {
    fn step(&mut self, record: &StepRecord) -> Result<()> {
        self.0.lock().unwrap().get_or_insert(record.step);
        Ok(())
    }
}

impl RealCase {
    fn run_with(&self, folder: &Path, policy: Option<&CheckpointPolicy>, progress: &mut dyn RunProgress) -> Result<()> {
        let scenario = crate::load(&self.text, "test case", Path::new("."), &[])?;
        let options = FolderRunOptions {
            pictures: None,
            netcdf: false,
            checkpoint: policy,
        };
        run_into_folder(&scenario, folder, options, progress)?;
        Ok(())
    }
}

impl BatchCase for RealCase {
    fn id(&self) -> &str {
        &self.id
    }
    fn hash(&self) -> &str {
        &self.hash
    }
    fn run(&self, folder: &Path) -> Result<()> {
        self.run_with(folder, None, &mut ())
    }
    fn run_checkpointed(&self, folder: &Path, policy: &CheckpointPolicy) -> Result<()> {
        self.run_with(folder, Some(policy), &mut FirstStep(&self.first_step))
    }
}

/// "Kills" the run after step `at`: a panic, so that nothing after it runs.
struct KillAfter(usize);

impl RunProgress for KillAfter {
    fn step(&mut self, record: &StepRecord) -> Result<()> {
        if record.step == self.0 {
            std::panic::panic_any("killed");
        }
        Ok(())
    }
}

/// A checkpoint after every step.
fn every_step(case: &RealCase) -> CheckpointPolicy {
    CheckpointPolicy::every_seconds(1e-9, &case.hash).unwrap().unwrap()
}

/// Runs the case in `dir/tmp/<id>.<DEAD_PID>/` until it is killed after step `at`.
fn killed_run(case: &RealCase, dir: &Path, at: usize) -> PathBuf {
    let folder = dir.join("tmp").join(format!("{}.{DEAD_PID}", case.id));
    std::fs::create_dir_all(&folder).unwrap();
    let policy = every_step(case);
    let killed = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        let _ = case.run_with(&folder, Some(&policy), &mut KillAfter(at));
    }));
    assert!(killed.is_err(), "the run was not killed at step {at}");
    folder
}

/// Runs the pending cases of `dir` with a checkpoint after every step: the resumable ones,
/// and the first step the case's run solved.
fn run_batch(case: &RealCase, dir: &Path) -> (Vec<String>, Option<usize>) {
    let mut batch = Batch::open(dir, Shard::ALL).unwrap();
    batch.set_checkpoint_seconds(1e-9).unwrap();
    let cases = [real_case(&case.text)];
    let pending = batch.pending(&cases, false).unwrap();
    let resumable: Vec<String> = pending.resumable.keys().cloned().collect();
    let outcome = batch.execute(pending, 1, 1, &|_, _| {}).unwrap();
    assert!(outcome.failed_now.is_empty(), "{:?}", outcome.failed_now);
    let first = *cases[0].first_step.lock().unwrap();
    (resumable, first)
}

/// The files of a finished case folder, by name; summary.json without `performance`
/// (its wall times differ).
fn case_files(dir: &Path, id: &str) -> Vec<(String, Vec<u8>)> {
    crate::output::folder::comparable_files(&dir.join("cases").join(id)).unwrap()
}

fn uninterrupted(case: &RealCase) -> (tempfile::TempDir, Vec<(String, Vec<u8>)>) {
    let dir = tempfile::tempdir().unwrap();
    assert_eq!(run_batch(case, dir.path()), (vec![], Some(0)));
    let files = case_files(dir.path(), &case.id);
    (dir, files)
}

fn names(files: &[(String, Vec<u8>)]) -> Vec<&str> {
    files.iter().map(|(n, _)| n.as_str()).collect()
}

fn assert_same(resumed: &[(String, Vec<u8>)], plain: &[(String, Vec<u8>)]) {
    assert_eq!(names(resumed), names(plain), "the same files");
    for ((name, a), (_, b)) in resumed.iter().zip(plain) {
        assert!(a == b, "{name} differs from the uninterrupted run's");
    }
}

/// Killed after step 12 (approach), run on to step 40 (retraction) and killed again, with
/// the step-12 checkpoint put back (the files of steps 13..40 are then ahead of it, as
/// when a run is killed between two checkpoints): the resumed case is byte-identical.
#[test]
fn a_killed_case_resumes_from_its_checkpoint_byte_identically() {
    let case = real_case(SCENARIO);
    let (_plain_dir, plain) = uninterrupted(&case);
    assert!(names(&plain).contains(&"curve.csv") && names(&plain).contains(&"fields.npz"));
    assert!(
        !names(&plain).contains(&CHECKPOINT_FILE),
        "a finished case holds no checkpoint"
    );
    let curve = String::from_utf8(plain.iter().find(|(n, _)| n == "curve.csv").unwrap().1.clone()).unwrap();
    assert!(curve.lines().count() > 45, "{} steps", curve.lines().count() - 1);
    let dir = tempfile::tempdir().unwrap();
    let folder = killed_run(&case, dir.path(), 12);
    let early = std::fs::read(folder.join(CHECKPOINT_FILE)).unwrap();
    killed_run(&case, dir.path(), 40);
    std::fs::write(folder.join(CHECKPOINT_FILE), early).unwrap();
    // Steps 0..=11 are not solved again: the run goes on with step 12.
    assert_eq!(
        run_batch(&case, dir.path()),
        (vec![case.id.clone()], Some(12)),
        "resumed"
    );
    assert!(!folder.exists(), "the killed run's folder was adopted");
    assert_same(&case_files(dir.path(), &case.id), &plain);
}

/// A Maugis–Dugdale smooth sphere (λ = 0.3, scenarios/cohesive/maugis_lambda0p3.toml at
/// n = 64 in steps of 1e-4): a cohesive law's solver and its nested compressive solver.
const DUGDALE: &str = r#"
[grid]
n = 64
size = 0.45
boundary = "free"

[material]
contact_modulus = 1.0

[adhesion]
work_of_adhesion = 1e-4
law = "dugdale"
cohesive_stress = 1.235285e-02

[indenter]
shape = "sphere"
radius = 1.0

[protocol]
kind = "indent_pulloff"
max_depth = 2e-3
step = 1e-4

[output]
snapshot_steps = [3, 25]
jump_force_threshold = 0.01
"#;

/// The cohesive case killed while reporting step 8 (approach) and step 25 (retraction),
/// each continued by the next batch from the checkpoint after the step before (the run goes
/// on with the killed step): byte-identical to the uninterrupted
/// run (cohesive runs now write checkpoints; before, a killed one restarted from scratch).
#[test]
fn a_killed_cohesive_case_resumes_from_its_checkpoint_byte_identically() {
    let case = real_case(DUGDALE);
    let (_plain_dir, plain) = uninterrupted(&case);
    let curve = String::from_utf8(plain.iter().find(|(n, _)| n == "curve.csv").unwrap().1.clone()).unwrap();
    assert!(curve.lines().count() > 30, "{} steps", curve.lines().count() - 1);
    assert_killed_runs_resume(&case, &[8, 25], &plain);
}

/// The case killed while reporting each step of `at`, each time continued by the next
/// batch from the checkpoint after the step before (the run goes on with the killed step):
/// byte-identical to the uninterrupted run's files `plain`.
fn assert_killed_runs_resume(case: &RealCase, at: &[usize], plain: &[(String, Vec<u8>)]) {
    for &at in at {
        let dir = tempfile::tempdir().unwrap();
        killed_run(case, dir.path(), at);
        assert_eq!(
            run_batch(case, dir.path()),
            (vec![case.id.clone()], Some(at)),
            "resumed at step {at}"
        );
        assert_same(&case_files(dir.path(), &case.id), plain);
    }
}

/// A checkpoint whose body is cut, one of another scenario, and one of another grid under
/// this case's header: each is warned about and the case restarts from scratch, with the
/// files of the uninterrupted run.
#[test]
fn a_corrupt_or_foreign_checkpoint_restarts_the_case() {
    let case = real_case(SCENARIO);
    let (_plain_dir, plain) = uninterrupted(&case);
    let coarse = real_case(&SCENARIO.replace("n = 40", "n = 32"));
    let coarse_dir = tempfile::tempdir().unwrap();
    let coarse_folder = killed_run(&coarse, coarse_dir.path(), 8);
    let coarse_text = std::fs::read_to_string(coarse_folder.join(CHECKPOINT_FILE)).unwrap();
    for damage in ["cut", "foreign", "grid"] {
        let dir = tempfile::tempdir().unwrap();
        let folder = killed_run(&case, dir.path(), 20);
        let path = folder.join(CHECKPOINT_FILE);
        let text = std::fs::read_to_string(&path).unwrap();
        let damaged = match damage {
            "cut" => text[..text.len() / 2].to_string(),
            "foreign" => text.replacen(&case.hash, "0123456789abcdef", 1),
            // Signed anew: the grid check behind the checksum.
            _ => crate::output::checkpoint::resigned(&coarse_text, &case.hash),
        };
        std::fs::write(&path, damaged).unwrap();
        let (resumable, first) = run_batch(&case, dir.path());
        // A cut body or another grid passes the header check (the run then restarts);
        // another hash does not.
        assert_eq!(resumable.is_empty(), damage == "foreign", "{damage}");
        assert_eq!(first, Some(0), "{damage}: restarted from scratch");
        assert_same(&case_files(dir.path(), &case.id), &plain);
    }
}

/// `text` with the number after the last `key` raised by one (still valid JSON).
fn bump_last_number(text: &str, key: &str) -> String {
    let at = text.rfind(key).unwrap_or_else(|| panic!("no {key}")) + key.len();
    let end = at + text[at..].find(|c: char| !c.is_ascii_digit()).unwrap();
    let number: u64 = text[at..end].parse().unwrap();
    format!("{}{}{}", &text[..at], number + 1, &text[end..])
}

/// Checkpoints that lie: a number edited in the body (the last record's contact count),
/// the header's step count edited, the file cut inside its body or after its header, and
/// another scenario's checkpoint of the same grid put in with this case's hash. Each one is
/// warned about and the case restarts from scratch, with the uninterrupted run's files.
/// Before the checksum, the edited body and the other scenario's checkpoint were continued
/// and changed the case's results without a word (an edited jump count reached summary.json
/// and table.csv).
#[test]
fn a_tampered_checkpoint_never_changes_the_results() {
    let case = real_case(SCENARIO);
    let (_plain_dir, plain) = uninterrupted(&case);
    let other = real_case(&SCENARIO.replace("work_of_adhesion = 6.16850275068085e-4", "work_of_adhesion = 7e-4"));
    let other_dir = tempfile::tempdir().unwrap();
    let other_folder = killed_run(&other, other_dir.path(), 20);
    let other_text = std::fs::read_to_string(other_folder.join(CHECKPOINT_FILE)).unwrap();
    for damage in ["body", "header", "cut", "header only", "another scenario"] {
        let dir = tempfile::tempdir().unwrap();
        let folder = killed_run(&case, dir.path(), 20);
        let path = folder.join(CHECKPOINT_FILE);
        let text = std::fs::read_to_string(&path).unwrap();
        let (header, body) = text.split_once('\n').unwrap();
        let damaged = match damage {
            "body" => format!("{header}\n{}", bump_last_number(body, "\"contact_elements\":")),
            "header" => format!("{}\n{body}", bump_last_number(header, "\"steps_done\":")),
            "cut" => text[..text.len() - 40].to_string(),
            "header only" => format!("{header}\n"),
            _ => other_text.replacen(&other.hash, &case.hash, 1),
        };
        assert_ne!(damaged, text, "{damage}");
        std::fs::write(&path, damaged).unwrap();
        let (_, first) = run_batch(&case, dir.path());
        assert_eq!(first, Some(0), "{damage}: restarted from scratch");
        assert_same(&case_files(dir.path(), &case.id), &plain);
    }
}

/// Checkpoints off (0 s): a killed case's folder is discarded as before, and the
/// interval is checked.
#[test]
fn no_checkpoints_means_no_resume() {
    let case = real_case(SCENARIO);
    let dir = tempfile::tempdir().unwrap();
    let folder = killed_run(&case, dir.path(), 5);
    let mut batch = Batch::open(dir.path(), Shard::ALL).unwrap();
    assert!(batch.set_checkpoint_seconds(-1.0).is_err());
    assert!(batch.set_checkpoint_seconds(f64::NAN).is_err());
    // 1e300 s panicked in Duration::from_secs_f64 (any value from about 1.9e19).
    let error = batch.set_checkpoint_seconds(1e300).unwrap_err().to_string();
    assert!(error.contains("from 0 (off) to 1e9, got 1e300"), "{error}");
    batch.set_checkpoint_seconds(1e9).unwrap();
    batch.set_checkpoint_seconds(0.0).unwrap();
    let cases = [real_case(SCENARIO)];
    let pending = batch.pending(&cases, false).unwrap();
    assert!(pending.resumable.is_empty());
    assert!(!folder.exists(), "discarded");
}

/// A roll (scenarios/fig6.toml's kind at n = 40, 16 approach and 24 roll steps): the
/// translation protocols write checkpoints too.
const ROLL: &str = r#"
[grid]
n = 40
size = 0.4
boundary = "free"

[material]
contact_modulus = 1.0

[adhesion]
work_of_adhesion = 2e-5

[indenter]
shape = "wavy_sphere"
radius = 1.0
amplitude = 5.627e-4
wavelength = 0.05
angle = 0.0

[protocol]
kind = "roll"
depth = 5.0
depth_unit = "jkr"
approach_steps = 16
distance = 1.0
distance_unit = "wavelength"
steps = 24
stationary_from = 0.5

[output]
snapshot_steps = [3, 30]
jump_force_threshold = 0.01
"#;

/// The roll killed while reporting step 10 (approach), step 16 (its first rolling step)
/// and step 33 (the stationary part), each continued by the next batch from the checkpoint
/// after the step before: byte-identical to the uninterrupted run, the snapshot strip of
/// consecutive steps and the stationary means included (before, a killed translation
/// restarted from scratch).
#[test]
fn a_killed_roll_resumes_from_its_checkpoint_byte_identically() {
    let case = real_case(ROLL);
    let (_plain_dir, plain) = uninterrupted(&case);
    let curve = String::from_utf8(plain.iter().find(|(n, _)| n == "curve.csv").unwrap().1.clone()).unwrap();
    assert_eq!(curve.lines().count(), 41, "a header and 40 steps");
    assert_killed_runs_resume(&case, &[10, 16, 33], &plain);
}

/// The wavy sphere with `adhesion.first_contact_factor`, killed in its approach and in its
/// retraction: the elements touched before the kill come back from the checkpoint, so the
/// resumed folder's `first_contact_map.npy` is the uninterrupted run's, byte for byte.
#[test]
fn a_killed_case_resumes_its_first_contact_map_byte_identically() {
    let text = SCENARIO.replace(
        "work_of_adhesion = 6.16850275068085e-4",
        "work_of_adhesion = 6.16850275068085e-4\nfirst_contact_factor = 1.5",
    );
    let case = real_case(&text);
    let (_plain_dir, plain) = uninterrupted(&case);
    assert!(names(&plain).contains(&"first_contact_map.npy"), "{:?}", names(&plain));
    assert_killed_runs_resume(&case, &[12, 40], &plain);
}

/// An indentation's checkpoint put into a roll's folder (under the roll's header) is
/// warned about and the case restarts from scratch, with the uninterrupted run's files.
#[test]
fn a_checkpoint_of_another_protocol_restarts_the_case() {
    let case = real_case(ROLL);
    let (_plain_dir, plain) = uninterrupted(&case);
    let indentation = real_case(SCENARIO);
    let other_dir = tempfile::tempdir().unwrap();
    let other = killed_run(&indentation, other_dir.path(), 8);
    let text = std::fs::read_to_string(other.join(CHECKPOINT_FILE)).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let folder = killed_run(&case, dir.path(), 20);
    // Signed anew: the protocol check behind the checksum.
    std::fs::write(
        folder.join(CHECKPOINT_FILE),
        crate::output::checkpoint::resigned(&text, &case.hash),
    )
    .unwrap();
    let (resumable, first) = run_batch(&case, dir.path());
    assert_eq!(resumable, vec![case.id.clone()]);
    assert_eq!(first, Some(0), "restarted from scratch");
    assert_same(&case_files(dir.path(), &case.id), &plain);
}
