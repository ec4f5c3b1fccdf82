//! Sweeps, one engine for `adhesim sweep` and Python's `adhesim.sweep`: the plan of a
//! sweep file (cases, pseudo-keys, hashes), its `sweep.json`, each case as a
//! [`BatchCase`] run into its folder, the memory check of a plan and `table.csv`.
//!
//! How a case's folder is filled is injected ([`CaseRunner`]): the command line's run with
//! its figures, so that a case folder is the same whoever runs it.

mod keys;
mod maugis;
pub mod plan;
pub mod table;

use crate::batch::{write_atomically, BatchCase};
use crate::memory::MemoryLimit;
use crate::output::checkpoint::CheckpointPolicy;
use crate::ValidScenario;
use anyhow::{bail, Context, Result};
pub use plan::{Case, Plan};
use std::path::Path;

/// Runs one case's validated scenario into its folder (curve.csv, summary.json, ...), with
/// mid-run checkpoints by the policy when given (continuing from the one in the folder).
pub type CaseRunner = dyn Fn(&ValidScenario, &Path, Option<&CheckpointPolicy>) -> Result<()> + Sync;

/// Refuses a plan whose largest grid, run `jobs` at a time, needs more memory than is
/// available (before any case allocates its FFT buffers). `lifting_option` is how the
/// caller lifts the guard (`--allow-large`, `allow_large=True`), for the hint.
pub fn check_memory(plan: &Plan, jobs: usize, limit: &MemoryLimit, lifting_option: &str) -> Result<()> {
    let mut largest: Option<(u64, &Case, crate::ScenarioFile)> = None;
    for case in &plan.cases {
        let table = crate::parse_toml(&case.scenario, &case.id)?;
        let file = crate::deserialize(&table)?;
        let estimate = file.memory_estimate();
        if largest.as_ref().is_none_or(|(e, _, _)| estimate > *e) {
            largest = Some((estimate, case, file));
        }
    }
    let Some((_, case, file)) = largest else { return Ok(()) };
    let runs = jobs.min(plan.cases.len()) as u64;
    let hint = match (limit.survives_lifting, runs > 1) {
        (true, true) => " (lower --jobs)".to_string(),
        (true, false) => String::new(),
        (false, true) => format!(" (pass {lifting_option} to run anyway, or lower --jobs)"),
        (false, false) => format!(" (pass {lifting_option} to run anyway)"),
    };
    file.check_memory(limit, runs)
        .with_context(|| format!("case {}{hint}", case.id))
}

/// Writes `DIR/sweep.json` (the plan), refusing a folder that holds another sweep.
pub fn write_plan(dir: &Path, plan: &Plan) -> Result<()> {
    std::fs::create_dir_all(dir.join("cases")).with_context(|| format!("cannot create {}", dir.display()))?;
    let path = dir.join("sweep.json");
    let text = serde_json::to_string_pretty(plan)? + "\n";
    let existing = match path.exists() {
        true => Some(crate::files::read_own_text(&path, "sweep.json", u64::MAX)?),
        false => None,
    };
    if let Some(existing) = existing {
        let same = serde_json::from_str::<Plan>(&existing)
            .map(|old| {
                // The same cases, whatever results revision hashed them: finished cases of
                // an older revision are then redone (their markers' hashes differ).
                let same_case = |a: &Case, b: &Case| {
                    (a.index, &a.id, &a.values, &a.scenario) == (b.index, &b.id, &b.values, &b.scenario)
                };
                old.keys == plan.keys
                    && old.cases.len() == plan.cases.len()
                    && old.cases.iter().zip(&plan.cases).all(|(a, b)| same_case(a, b))
            })
            .unwrap_or(false);
        if !same {
            bail!(
                "{} holds a different sweep (its sweep.json lists other cases); choose another --out or delete that folder",
                dir.display()
            );
        }
        if existing == text {
            return Ok(());
        }
    }
    write_atomically(&path, text.as_bytes())
}

/// Reads `DIR/sweep.json`.
pub fn read_plan(dir: &Path) -> Result<Plan> {
    let path = dir.join("sweep.json");
    let text = crate::files::read_own_text(&path, "sweep.json", u64::MAX)
        .with_context(|| format!("cannot read {} (is {} a sweep folder?)", path.display(), dir.display()))?;
    serde_json::from_str(&text).with_context(|| format!("{} is not a sweep plan", path.display()))
}

/// One case of a sweep, as the batch engine runs it: the case's scenario run into its
/// folder by `runner`, with `scenario.toml` and `case.json` beside the run's files.
pub struct SweepCase<'a> {
    pub plan: &'a Plan,
    pub case: &'a Case,
    pub runner: &'a CaseRunner,
}

impl BatchCase for SweepCase<'_> {
    fn id(&self) -> &str {
        &self.case.id
    }

    fn hash(&self) -> &str {
        &self.case.hash
    }

    fn describe(&self, folder: &Path) -> Result<()> {
        let (plan, case) = (self.plan, self.case);
        std::fs::write(folder.join("scenario.toml"), &case.scenario)
            .with_context(|| format!("cannot write {}", folder.display()))?;
        let values = plan.keys.iter().zip(&case.values);
        let case_info = serde_json::json!({
            "index": case.index,
            "id": case.id,
            "hash": case.hash,
            "series": plan.series,
            "values": values.map(|(k, v)| (k.clone(), serde_json::Value::String(v.clone()))).collect::<serde_json::Map<_, _>>(),
        });
        std::fs::write(
            folder.join("case.json"),
            serde_json::to_string_pretty(&case_info)? + "\n",
        )?;
        Ok(())
    }

    fn run(&self, folder: &Path) -> Result<()> {
        self.run_with(folder, None)
    }

    fn run_checkpointed(&self, folder: &Path, policy: &CheckpointPolicy) -> Result<()> {
        self.run_with(folder, Some(policy))
    }
}

impl SweepCase<'_> {
    fn run_with(&self, folder: &Path, policy: Option<&CheckpointPolicy>) -> Result<()> {
        let case = self.case;
        let scenario = crate::load(&case.scenario, &format!("case {}", case.id), &self.plan.base_dir, &[])?;
        (self.runner)(&scenario, folder, policy)
    }
}
