//! `adhesim.sweep` on the scenario crate's sweep engine (`adhesim_scenario::sweep`,
//! `adhesim_scenario::batch`): the same plan, case folders, `done` markers, resume and
//! `table.csv` as `adhesim sweep`, with the command line's runner and figures
//! (`adhesim_figures::run_figures::run_sweep_case`), so a case folder is the same whoever
//! ran it.
//!
//! The parent process opens the folder ([`_sweep_open`]: plan, lock, `sweep.json`) and
//! lists the cases to do; each case is then a picklable unit, the folder and the case
//! index, that any process runs with [`_sweep_run_case`] (a `concurrent.futures`
//! executor's worker, a Dask worker); the parent rebuilds `table.csv` at the end.

use adhesim_scenario::batch::{self, case_state, Batch, CaseState};
use adhesim_scenario::output::checkpoint::CheckpointPolicy;
use adhesim_scenario::output::folder::Shard;
use adhesim_scenario::sweep::{self, plan, Plan, SweepCase};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::{Path, PathBuf};

use crate::convert::engine_error as value_error;

/// A sweep folder held open (locked) by the parent process of a Python sweep.
#[pyclass(name = "_SweepFolder", module = "adhesim._adhesim")]
pub struct SweepFolder {
    dir: PathBuf,
    plan: Plan,
    /// The folder lock; `None` once closed.
    batch: Option<Batch>,
}

/// The sweep's cases as batch cases run by the figures crate's runner (the command line's).
fn sweep_cases(plan: &Plan) -> Vec<SweepCase<'_>> {
    plan.cases
        .iter()
        .map(|case| SweepCase {
            plan,
            case,
            runner: &adhesim_figures::run_figures::run_sweep_case,
        })
        .collect()
}

/// Opens (creating) the sweep folder `out` for the sweep of `scenario_text` with the
/// tables of `sweep_text` (`vary`, `zip`, `random`, `set`, `derived`, as in a sweep
/// file): builds and checks the plan, takes the folder's lock and writes `sweep.json`
/// (refused where `out` holds another sweep). `base` resolves the scenario's relative
/// paths; `series` labels the table's rows. With `checkpoint_seconds` > 0, killed runs
/// that left a mid-run checkpoint are kept for their cases to go on from (see
/// [`SweepFolder::pending`] and [`_sweep_run_case`]); with 0 they are discarded.
#[pyfunction]
#[pyo3(signature = (out, sweep_text, scenario_text, origin, base, series, check_memory, jobs, checkpoint_seconds=0.0))]
#[allow(clippy::too_many_arguments)]
pub fn _sweep_open(
    out: PathBuf,
    sweep_text: &str,
    scenario_text: &str,
    origin: &str,
    base: PathBuf,
    series: &str,
    check_memory: bool,
    jobs: usize,
    checkpoint_seconds: f64,
) -> PyResult<SweepFolder> {
    let mut sweep_table = adhesim_scenario::parse_toml(sweep_text, "the sweep's arguments")
        .map_err(|e| crate::convert::scenario_error(&e, ""))?;
    let scenario =
        adhesim_scenario::parse_toml(scenario_text, origin).map_err(|e| crate::convert::scenario_error(&e, ""))?;
    sweep_table.insert("scenario".into(), toml::Value::Table(scenario));
    sweep_table.insert("series".into(), toml::Value::String(series.into()));
    let text = toml::to_string(&sweep_table).map_err(|e| PyValueError::new_err(format!("sweep: {e}")))?;
    let plan = plan::from_text(&text, origin, &base, series).map_err(value_error)?;
    // allow_large=True (no `check_memory`) still checks RLIMIT_AS, which nothing gets past.
    if let Some(limit) =
        adhesim_scenario::memory_limit((!check_memory).then_some("allow_large=True")).map_err(value_error)?
    {
        let context = if check_memory {
            "refused before allocating"
        } else {
            "refused before allocating, even with allow_large=True"
        };
        sweep::check_memory(&plan, jobs, &limit, "allow_large=True").map_err(|e| value_error(e.context(context)))?;
    }
    let mut batch = Batch::open(&out, Shard::ALL).map_err(value_error)?;
    // Each case runs through `_sweep_run_case`, with mid-run checkpoints every
    // `checkpoint_seconds` (docs/sweeps.md, "Resuming a case mid-run").
    batch
        .set_checkpoint_seconds(checkpoint_seconds)
        .map_err(|e| value_error(e.context("checkpoint_every")))?;
    sweep::write_plan(&out, &plan).map_err(value_error)?;
    Ok(SweepFolder {
        dir: out,
        plan,
        batch: Some(batch),
    })
}

#[pymethods]
impl SweepFolder {
    /// The cases in order: dicts of `index`, `id` and `values` (varied key → table cell).
    fn cases<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        let mut list = Vec::with_capacity(self.plan.cases.len());
        for case in &self.plan.cases {
            let dict = PyDict::new(py);
            dict.set_item("index", case.index)?;
            dict.set_item("id", &case.id)?;
            let values = PyDict::new(py);
            for (key, value) in self.plan.keys.iter().zip(&case.values) {
                values.set_item(key, value)?;
            }
            dict.set_item("values", values)?;
            list.push(dict);
        }
        Ok(list)
    }

    /// The cases still to run (missing, broken, of another hash; failed ones too with
    /// `retry_failed`): (index, the folder of a killed run with a checkpoint to go on from,
    /// or None); removes what other killed runs of them left.
    fn pending(&self, retry_failed: bool) -> PyResult<Vec<(usize, Option<PathBuf>)>> {
        let batch = self.batch()?;
        let cases = sweep_cases(&self.plan);
        let mut pending = batch.pending(&cases, retry_failed).map_err(value_error)?;
        let todo: Vec<(usize, String)> = pending.todo.iter().map(|c| (c.case.index, c.case.id.clone())).collect();
        Ok(todo
            .into_iter()
            .map(|(index, id)| (index, pending.resumable.remove(&id)))
            .collect())
    }

    /// Rebuilds `table.csv` and the master-curve plots from the finished case folders;
    /// returns (path of table.csv, ids of the cases that finished with an error).
    fn finish(&self, py: Python<'_>) -> PyResult<(PathBuf, Vec<String>)> {
        self.batch()?;
        let (summary, _plots) = py
            .detach(|| adhesim_figures::master_plots::sweep_table_and_plots(&self.dir, &self.plan))
            .map_err(value_error)?;
        let failed = self
            .plan
            .cases
            .iter()
            .filter(|case| case_state(&self.dir, &case.id, &case.hash) == CaseState::Finished { ok: false })
            .map(|case| case.id.clone())
            .collect();
        Ok((summary.path, failed))
    }

    /// Releases the folder's lock.
    fn close(&mut self) {
        self.batch = None;
    }
}

impl SweepFolder {
    fn batch(&self) -> PyResult<&Batch> {
        self.batch
            .as_ref()
            .ok_or_else(|| PyValueError::new_err(format!("the sweep folder {} is closed", self.dir.display())))
    }
}

/// Runs case `index` of the sweep in `out` (opened by `_sweep_open`) into
/// `out/cases/<id>/`, computed in `out/tmp/` and renamed into place with its `done`
/// marker; a case already finished there is not run again. With `checkpoint_seconds` > 0
/// the run writes a mid-run checkpoint that often, and goes on from the one in `resume`
/// (the folder of a killed run that `pending` named). Returns (ran, error message of a
/// failed case or None). The GIL is released while it runs.
#[pyfunction]
#[pyo3(signature = (out, index, checkpoint_seconds=0.0, resume=None, threads=None))]
pub fn _sweep_run_case(
    py: Python<'_>,
    out: PathBuf,
    index: usize,
    checkpoint_seconds: f64,
    resume: Option<PathBuf>,
    threads: Option<usize>,
) -> PyResult<(bool, Option<String>)> {
    let plan = sweep::read_plan(&out).map_err(value_error)?;
    let Some(case) = plan.cases.get(index) else {
        return Err(PyValueError::new_err(format!(
            "case index {index}: the sweep in {} has {} cases",
            out.display(),
            plan.cases.len()
        )));
    };
    if let CaseState::Finished { ok } = case_state(&out, &case.id, &case.hash) {
        let message = (!ok).then(|| error_text(&out, &case.id));
        return Ok((false, message));
    }
    let policy = CheckpointPolicy::every_seconds(checkpoint_seconds, &case.hash)
        .map_err(|e| value_error(e.context("checkpoint_every")))?;
    let sweep_case = SweepCase {
        plan: &plan,
        case,
        runner: &adhesim_figures::run_figures::run_sweep_case,
    };
    // A pool of its own or the process's, never rayon's global one (crate::pool).
    let pool = crate::pool::run_pool(py, threads)?;
    let failure = py
        .detach(|| pool.install(|| batch::run_case(&out, &sweep_case, policy.as_ref(), resume.as_deref())))
        .map_err(|e| value_error(e.context(format!("case {}", case.id))))?;
    Ok((true, failure))
}

/// The `error.txt` of a failed case (its message), or a note that it is missing.
fn error_text(out: &Path, id: &str) -> String {
    let path = out.join("cases").join(id).join("error.txt");
    adhesim_scenario::read_own_text(&path, "error.txt", u64::MAX)
        .map(|text| text.trim_end().to_string())
        .unwrap_or_else(|_| format!("failed (no {})", path.display()))
}
