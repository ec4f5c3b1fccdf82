//! The runs of a study (one indent_pulloff run per α for rolling, and the roll / slide
//! cases) as cases of the batch engine: each finished run is the folder
//! `<out>/cases/<name>-<hash>/` holding `record.json` (its results and wall time), so that
//! a killed study resumes where it stopped. The hash covers the exact scenario it ran (base
//! after `set`, plus the run's overrides) and the library's results revision.

use adhesim::StepRecord;
use adhesim_scenario::batch::{results_hash, Batch, BatchCase};
use adhesim_scenario::output::checkpoint::CheckpointPolicy;
use adhesim_scenario::output::observer::RunProgress;
use adhesim_scenario::output::run::{run_into_folder, FolderRunOptions};
use adhesim_scenario::{RunResults, TranslationResults, ValidScenario};
use anyhow::{bail, Context, Result};
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::time::{Duration, Instant};

/// The file of a finished run's results in its case folder.
const RECORD: &str = "record.json";

/// Part of a rolling case's hash: rolls from before γ3 was fitted against the contact
/// radius (they hold the half-width fit under `gamma3`) are redone, not misread.
pub const ROLLING_ANALYSIS: &str = "gamma3 against the contact radius, gamma3_half_width";

/// What a run computes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RunKind {
    /// The indent_pulloff run of an α: γ1, γ2 for Eq. 12.
    Normal,
    /// A roll or slide case.
    Translation,
}

/// One run of a study.
pub struct StudyRun {
    pub id: String,
    hash: String,
    /// How progress lines and failures name the run.
    pub what: String,
    /// Print a progress line on stderr now and then while the run goes on.
    pub progress: bool,
    pub kind: RunKind,
    /// Index of its α in the study file.
    pub alpha_index: usize,
    /// d/|d_JKR| (translation runs).
    pub depth: f64,
    /// Substrate angle (sliding runs).
    pub angle: Option<f64>,
    scenario: ValidScenario,
}

impl StudyRun {
    /// The run `name` of the scenario `table` with `changes` applied (`key`: the changes and
    /// anything else its results depend on).
    pub fn new(name: &str, table: &toml::Table, key: &[String], scenario: ValidScenario, kind: RunKind) -> Self {
        let hash = format!("{:016x}", results_hash(&format!("{table}\n{}", key.join("\n"))));
        Self {
            id: format!("{name}-{hash}"),
            hash,
            what: String::new(),
            progress: false,
            kind,
            alpha_index: 0,
            depth: 0.0,
            angle: None,
            scenario,
        }
    }
}

impl BatchCase for StudyRun {
    fn id(&self) -> &str {
        &self.id
    }

    fn hash(&self) -> &str {
        &self.hash
    }

    fn run(&self, folder: &Path) -> Result<()> {
        self.run_with(folder, None)
    }

    fn run_checkpointed(&self, folder: &Path, policy: &CheckpointPolicy) -> Result<()> {
        self.run_with(folder, Some(policy))
    }
}

impl StudyRun {
    /// Runs the scenario into the case folder through the output layer of `adhesim run`
    /// (curve.csv, summary.json, fields.npz; no pictures), with mid-run checkpoints by
    /// `policy` when given, then writes the study's record of it.
    fn run_with(&self, folder: &Path, policy: Option<&CheckpointPolicy>) -> Result<()> {
        let start = Instant::now();
        let options = FolderRunOptions {
            pictures: None,
            netcdf: false,
            checkpoint: policy,
        };
        let mut heartbeat = Heartbeat {
            what: &self.what,
            steps: self.scenario.expected_steps(),
            last: Instant::now(),
        };
        let progress: &mut dyn RunProgress = if self.progress { &mut heartbeat } else { &mut () };
        let results = run_into_folder(&self.scenario, folder, options, progress)?
            .outcome
            .results;
        let wall_seconds = start.elapsed().as_secs_f64();
        let text = match (self.kind, results) {
            (RunKind::Normal, RunResults::Indentation(results)) => serde_json::to_string_pretty(&NormalRecord {
                gamma_approach: results.fits.gamma_approach,
                gamma_pulloff: results.fits.gamma_pulloff,
                wall_seconds,
            })?,
            (RunKind::Translation, RunResults::Translation(results)) => {
                serde_json::to_string_pretty(&CaseRecord { results, wall_seconds })?
            }
            (RunKind::Normal, RunResults::Translation(_)) => {
                bail!("the normal run of a study must be protocol.kind = \"indent_pulloff\"")
            }
            (RunKind::Translation, RunResults::Indentation(_)) => {
                bail!("protocol.kind = \"indent_pulloff\" is not a translation")
            }
            (_, RunResults::Shear(_)) => bail!("protocol.kind = \"shear\" is not a run of a study"),
        };
        let path = folder.join(RECORD);
        std::fs::write(&path, text + "\n").with_context(|| format!("cannot write {}", path.display()))
    }
}

/// Wall time between two progress lines of a running run.
const HEARTBEAT: Duration = Duration::from_secs(60);

/// A line on stderr at most once a minute while a run goes on (a slide of a
/// paper-resolution study takes half an hour): the run and its step.
struct Heartbeat<'a> {
    what: &'a str,
    /// Steps the protocol will report (an estimate for an indentation).
    steps: usize,
    last: Instant,
}

impl RunProgress for Heartbeat<'_> {
    fn step(&mut self, record: &StepRecord) -> Result<()> {
        if self.last.elapsed() >= HEARTBEAT {
            eprintln!("  {}: step {} of about {}", self.what, record.step + 1, self.steps);
            self.last = Instant::now();
        }
        Ok(())
    }
}

/// A run finished by an adhesim older than the batch engine, kept as `<out>/cache/<id>.json`
/// (the same id: the same scenario and results revision).
struct CachedRun<'a> {
    run: &'a StudyRun,
    record: String,
}

impl BatchCase for CachedRun<'_> {
    fn id(&self) -> &str {
        &self.run.id
    }

    fn hash(&self) -> &str {
        &self.run.hash
    }

    fn run(&self, folder: &Path) -> Result<()> {
        let path = folder.join(RECORD);
        std::fs::write(&path, &self.record).with_context(|| format!("cannot write {}", path.display()))
    }
}

/// Moves the readable runs of an old `<out>/cache/` into case folders (atomically, by the
/// batch engine), so that a study begun before the batch engine resumes instead of
/// recomputing them; returns how many. The old files are left in place.
pub fn adopt_old_cache(out: &Path, runs: &[StudyRun], batch: &Batch) -> Result<usize> {
    let cache = out.join("cache");
    if !cache.is_dir() {
        return Ok(0);
    }
    let cached: Vec<CachedRun> = runs
        .iter()
        .filter_map(|run| {
            let path = cache.join(format!("{}.json", run.id));
            let record = adhesim_scenario::read_own_text(&path, "study record", u64::MAX).ok()?;
            let readable = match run.kind {
                RunKind::Normal => serde_json::from_str::<NormalRecord>(&record).is_ok(),
                RunKind::Translation => serde_json::from_str::<CaseRecord>(&record).is_ok(),
            };
            readable.then_some(CachedRun { run, record })
        })
        .collect();
    let pending = batch.pending(&cached, true)?;
    let adopted = pending.todo.len();
    batch.execute(pending, 1, 1, &|_, _| {})?;
    Ok(adopted)
}

/// The record of a finished run in its case folder.
pub fn load<T: for<'de> Deserialize<'de>>(folder: &Path) -> Result<T> {
    let path = folder.join(RECORD);
    let text = adhesim_scenario::read_own_text(&path, "study record", u64::MAX)?;
    serde_json::from_str(&text).with_context(|| {
        format!(
            "{} is not a study run's record (delete its folder to redo the run)",
            path.display()
        )
    })
}

/// A normal run's record: γ1, γ2 and its wall time.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct NormalRecord {
    pub gamma_approach: Option<f64>,
    pub gamma_pulloff: Option<f64>,
    pub wall_seconds: f64,
}

/// A translation run's record.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct CaseRecord {
    pub results: TranslationResults,
    pub wall_seconds: f64,
}
