//! One-call runs of a scenario (`adhesim.run`): the scenario crate's reading, validation
//! and run pipeline (`adhesim_scenario::run`), the same `curve.csv` columns and
//! `summary.json` content as the command line, with the GIL released during the run, the
//! progress callback run between steps and Python's signal handlers on the calling thread
//! while the steps run on a pool.

use crate::pool::run_watching_signals;
use adhesim::StepRecord;
use adhesim::{Observer, StepView};
use adhesim_scenario::output::folder::prepare_run_folder;
use adhesim_scenario::output::observer::RunProgress;
use adhesim_scenario::output::parts::BorderWatch;
use adhesim_scenario::output::run::{performance, run_into_folder, FolderRunOptions};
use adhesim_scenario::output::timings::Timed;
use adhesim_scenario::{
    CurveCell, CurveColumns, CurveKind, RunOutcome, SnapshotFields, SnapshotPlan, SnapshotRecorder, ValidScenario,
};
use numpy::{PyArray1, PyArray2};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Instant;

/// Between steps, with the GIL: the progress callback `progress(step, total)`, and a stop
/// when the calling thread's signal handlers raised (Ctrl-C; [`run_watching_signals`]);
/// the first exception stops the run.
struct PythonProgress {
    progress: Option<Py<PyAny>>,
    expected_steps: usize,
    /// The callback's exception that stopped the run.
    error: Option<PyErr>,
    /// Set when a signal handler raised on the calling thread.
    interrupted: Arc<AtomicBool>,
}

impl PythonProgress {
    fn between_steps(&mut self, step: usize) -> ControlFlow<()> {
        if self.interrupted.load(Ordering::SeqCst) {
            return ControlFlow::Break(());
        }
        let total = self.expected_steps.max(step + 1);
        // Signals are not checked here: the steps run on a pool thread, where Python runs
        // no handler; the calling thread runs them ([`run_watching_signals`]).
        let Some(callback) = &self.progress else {
            return ControlFlow::Continue(());
        };
        let result = Python::attach(|py| callback.call1(py, (step + 1, total)).map(drop));
        match result {
            Ok(()) => ControlFlow::Continue(()),
            Err(error) => {
                self.error = Some(error);
                ControlFlow::Break(())
            }
        }
    }
}

/// The progress of a run into a folder (the scenario crate's observer writes the files).
impl RunProgress for PythonProgress {
    fn step(&mut self, record: &StepRecord) -> anyhow::Result<()> {
        match self.between_steps(record.step) {
            ControlFlow::Continue(()) => Ok(()),
            ControlFlow::Break(()) => Err(anyhow::anyhow!("stopped by Python")),
        }
    }
}

/// The progress between steps as an observer (the first Python exception stops the run).
impl Observer for PythonProgress {
    fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()> {
        self.between_steps(view.record.step)
    }
}

/// Reads, overrides and validates a scenario, refusing before any allocation one whose
/// memory estimate exceeds the memory this process may use (where `check_memory`: the
/// smallest of RLIMIT_AS, the cgroup's limit and `MemAvailable`, or
/// `ADHESIM_MEMORY_AVAILABLE`; else RLIMIT_AS alone); errors become `ValueError` with the scenario crate's
/// message (it names the key and the value, or the file).
fn load(
    text: &str,
    origin: &str,
    base: &std::path::Path,
    overrides: &[String],
    check_memory: bool,
) -> PyResult<ValidScenario> {
    // allow_large=True (no `check_memory`) still checks RLIMIT_AS, which nothing gets past.
    let limit = adhesim_scenario::memory_limit((!check_memory).then_some("allow_large=True"))
        .map_err(|e| PyValueError::new_err(format!("{e:#}")))?;
    adhesim_scenario::load_within(text, origin, base, overrides, limit.as_ref()).map_err(|e| {
        let hint = if e.kind == adhesim_scenario::ErrorKind::Resources && check_memory {
            " (refused before allocating; pass allow_large=True to run anyway)"
        } else {
            ""
        };
        crate::convert::scenario_error(&e, hint)
    })
}

/// Runs a scenario given as TOML text (see `adhesim.run`, which prepares the arguments).
///
/// `check_memory` refuses a scenario whose memory estimate exceeds the memory available,
/// as the command line does. With `out`, the run goes into that folder through the
/// scenario crate's run into a folder (the command line's pipeline, without figures):
/// the folder is made ready as `adhesim run --out` does (`force` as `--force`). Returns a
/// dict: `columns` (list of (name, numpy array) in `curve.csv` order), `csv` (the text of
/// `curve.csv`), `summary` (the text of `summary.json`), `snapshots` (list of dicts of the
/// selected steps' fields).
#[pyfunction]
#[pyo3(signature = (text, origin, base, overrides, progress = None, check_memory = false, out = None, force = false, threads = None))]
#[allow(clippy::too_many_arguments)]
pub fn _run_scenario<'py>(
    py: Python<'py>,
    text: &str,
    origin: &str,
    base: PathBuf,
    overrides: Vec<String>,
    progress: Option<Py<PyAny>>,
    check_memory: bool,
    out: Option<PathBuf>,
    force: bool,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let scenario = load(text, origin, &base, &overrides, check_memory)?;
    let pool = crate::pool::run_pool(py, threads)?;
    let progress = PythonProgress {
        progress,
        expected_steps: scenario.expected_steps(),
        error: None,
        interrupted: Arc::new(AtomicBool::new(false)),
    };
    let (outcome, summary, fields) = match out {
        Some(out) => run_in_folder(py, &pool, &scenario, &out, force, progress)?,
        None => run_in_memory(py, &pool, &scenario, progress)?,
    };
    let columns = CurveColumns::of(&scenario);
    let result = PyDict::new(py);
    result.set_item("columns", curve_arrays(py, &columns, &outcome.records)?)?;
    result.set_item("csv", curve_text(&columns, &outcome.records))?;
    result.set_item("summary", summary)?;
    let plan = SnapshotPlan::new(&scenario);
    result.set_item("snapshots", snapshot_dicts(py, &plan, &fields)?)?;
    result.set_item("fields", RunFields(fields))?;
    Ok(result)
}

/// A run in memory: (outcome, summary.json text, snapshot fields).
fn run_in_memory(
    py: Python<'_>,
    pool: &rayon::ThreadPool,
    scenario: &ValidScenario,
    progress: PythonProgress,
) -> PyResult<(RunOutcome, String, SnapshotFields)> {
    let start = Instant::now();
    // The observer of an in-memory run: the snapshot fields (as in `fields.npz`), the
    // border warning and the progress, timed by phase as the command line's run is.
    let mut observer = Timed::new((
        SnapshotRecorder::new(SnapshotPlan::new(scenario)),
        BorderWatch::default(),
        progress,
    ));
    let interrupted = Arc::clone(&observer.observer.2.interrupted);
    let (outcome, raised) = run_watching_signals(py, pool, &interrupted, || {
        adhesim_scenario::run(scenario, &mut observer)
    });
    let Timed {
        observer: (mut recorder, border, mut progress),
        timings,
    } = observer;
    let outcome = match (outcome, raised.or_else(|| progress.error.take())) {
        (_, Some(error)) => return Err(error),
        (Ok(outcome), None) => outcome,
        (Err(error), None) => {
            return Err(crate::convert::SolveError::new_err(format!(
                "run failed: {}",
                adhesim_scenario::output::run::protocol_error_line(scenario, &error)
            )))
        }
    };
    let performance = performance(start.elapsed().as_secs_f64(), &outcome, &timings);
    let summary = adhesim_scenario::Summary::new(scenario, &outcome, performance, &border.warnings);
    let summary = summary.to_json().map_err(|e| PyValueError::new_err(format!("{e:#}")))?;
    let fields = SnapshotFields::new(scenario, recorder.take_snapshots());
    Ok((outcome, summary, fields))
}

/// A run into the folder `out` by the scenario crate's pipeline (marker, curve.csv,
/// snapshots/*.npy, fields.npz, summary.json; no figures): (outcome, summary.json text,
/// snapshot fields).
fn run_in_folder(
    py: Python<'_>,
    pool: &rayon::ThreadPool,
    scenario: &ValidScenario,
    out: &Path,
    force: bool,
    mut progress: PythonProgress,
) -> PyResult<(RunOutcome, String, SnapshotFields)> {
    prepare_run_folder(out, force).map_err(|e| {
        PyValueError::new_err(format!(
            "{} (in Python: out=..., force=True)",
            adhesim_scenario::error_text::error_line(e.chain())
        ))
    })?;
    let interrupted = Arc::clone(&progress.interrupted);
    let (done, raised) = run_watching_signals(py, pool, &interrupted, || {
        run_into_folder(scenario, out, FolderRunOptions::default(), &mut progress)
    });
    match (done, raised.or_else(|| progress.error.take())) {
        (_, Some(error)) => Err(error),
        (Ok(done), None) => Ok((done.outcome, done.summary_json, done.fields)),
        (Err(error), None) => Err(crate::convert::SolveError::new_err(
            adhesim_scenario::error_text::error_line(error.chain()),
        )),
    }
}

/// The `curve.csv` columns as numpy arrays: int64 counts and flags, float64 quantities,
/// str phases.
fn curve_arrays<'py>(
    py: Python<'py>,
    columns: &CurveColumns,
    records: &[adhesim::StepRecord],
) -> PyResult<Bound<'py, PyList>> {
    let list = PyList::empty(py);
    for (index, column) in columns.columns().iter().enumerate() {
        let cells = records.iter().map(|r| columns.cell(index, r));
        let array: Bound<'py, PyAny> = match column.kind {
            CurveKind::Float => PyArray1::from_iter(
                py,
                cells.map(|c| match c {
                    CurveCell::Float(v) => v,
                    _ => f64::NAN,
                }),
            )
            .into_any(),
            CurveKind::Integer => PyArray1::from_iter(
                py,
                cells.map(|c| match c {
                    CurveCell::Integer(v) => v as i64,
                    _ => -1,
                }),
            )
            .into_any(),
            CurveKind::Text => {
                let texts: Vec<String> = cells.map(|c| c.to_string()).collect();
                py.import("numpy")?.call_method1("array", (texts,))?
            }
        };
        list.append((column.name, array))?;
    }
    Ok(list)
}

/// The text of `curve.csv`, as the command line writes it (comma-separated, no cell
/// needs quoting, `\n` line ends).
fn curve_text(columns: &CurveColumns, records: &[adhesim::StepRecord]) -> String {
    use std::fmt::Write;
    let mut text = columns.names().collect::<Vec<_>>().join(",");
    text.push('\n');
    for record in records {
        for (k, cell) in columns.row(record).enumerate() {
            if k > 0 {
                text.push(',');
            }
            let _ = write!(text, "{cell}");
        }
        text.push('\n');
    }
    text
}

/// The snapshots as dicts of numpy arrays: pressure, displacement, gap = u + z − d (0
/// where the indenter has no surface), contact (bool), and `chosen` (the step is one of
/// `[output]`'s, with `.npy` files in `snapshots/`).
fn snapshot_dicts<'py>(py: Python<'py>, plan: &SnapshotPlan, fields: &SnapshotFields) -> PyResult<Bound<'py, PyList>> {
    let (nx, ny) = fields.counts();
    let list = PyList::empty(py);
    for (index, snapshot) in fields.snapshots().iter().enumerate() {
        let dict = PyDict::new(py);
        dict.set_item("step", snapshot.step)?;
        dict.set_item("depth", snapshot.depth)?;
        dict.set_item("offset", snapshot.offset)?;
        dict.set_item("pressure", shaped(py, &snapshot.pressure, (ny, nx))?)?;
        dict.set_item("displacement", shaped(py, &snapshot.displacement, (ny, nx))?)?;
        dict.set_item("gap", shaped(py, fields.gap(index), (ny, nx))?)?;
        dict.set_item("contact", shaped(py, &snapshot.contact, (ny, nx))?)?;
        dict.set_item("chosen", plan.is_chosen(snapshot.step))?;
        list.append(dict)?;
    }
    Ok(list)
}

/// A row-major field as a new (rows, columns) numpy array.
fn shaped<'py, T: numpy::Element + Copy>(
    py: Python<'py>,
    values: &[T],
    (rows, columns): (usize, usize),
) -> PyResult<Bound<'py, numpy::PyArray2<T>>> {
    use numpy::PyArrayMethods;
    numpy::PyArray1::from_slice(py, values).reshape([rows, columns])
}

/// The `fields.npz` arrays of a run (`adhesim.run` writes them into `out`).
#[pyclass(frozen, name = "_RunFields", module = "adhesim._adhesim")]
pub struct RunFields(SnapshotFields);

#[pymethods]
impl RunFields {
    /// Writes `fields.npz` to `path` (the command line's bytes for the same run).
    fn write_npz(&self, path: PathBuf) -> PyResult<()> {
        let shapes = self.0.shapes();
        adhesim_topography::write_npz(&path, &self.0.npz_arrays(&shapes))
            .map_err(|e| PyValueError::new_err(format!("cannot write {}: {e}", path.display())))
    }
}

/// The grid and the indenter heights (ny, nx) a scenario presses, built exactly as its run
/// builds them (every `indenter.shape`: analytic, `topography` files, `rough_*` with their
/// `[roughness]`), without running it (see `adhesim.geometry.from_scenario`).
#[pyfunction]
pub fn _scenario_heights<'py>(
    py: Python<'py>,
    text: &str,
    origin: &str,
    base: PathBuf,
    overrides: Vec<String>,
) -> PyResult<(crate::grid::Grid, Bound<'py, PyArray2<f64>>)> {
    let scenario = load(text, origin, &base, &overrides, true)?;
    let heights = crate::convert::field(py, &scenario.heights, &scenario.grid)?;
    Ok((crate::grid::Grid { inner: scenario.grid }, heights))
}

/// Every column `curve.csv` can have, with its kind ("int", "float" or "str"), for
/// reading a run folder back (`adhesim.load`).
#[pyfunction]
pub fn _curve_column_kinds(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let dict = PyDict::new(py);
    for column in CurveColumns::every() {
        let kind = match column.kind {
            CurveKind::Integer => "int",
            CurveKind::Float => "float",
            CurveKind::Text => "str",
        };
        dict.set_item(column.name, kind)?;
    }
    Ok(dict)
}

/// A Python value as TOML text (for `--set`-style overrides and dict scenarios): bool,
/// int, float, str, list/tuple and dict (an inline table).
#[pyfunction]
pub fn _toml_value(value: &Bound<'_, PyAny>) -> PyResult<String> {
    Ok(to_toml(value, "value")?.to_string())
}

/// The text of an input file named by a Python argument (`what`: `scenario`), read as the
/// command line reads its inputs: a FIFO (it blocked forever), a device or a folder is
/// refused by name (`ValueError`), as is a file larger than the memory available; a
/// missing file is a `FileNotFoundError`.
#[pyfunction]
pub fn _read_input_text(path: PathBuf, what: &str) -> PyResult<String> {
    if !path.exists() {
        return Err(pyo3::exceptions::PyFileNotFoundError::new_err(format!(
            "{what}: {} does not exist",
            path.display()
        )));
    }
    adhesim_scenario::read_input_text(&path, what)
        .map_err(|e| PyValueError::new_err(adhesim_scenario::error_text::error_line(e.chain())))
}

/// A nested dict as the text of a TOML document.
#[pyfunction]
pub fn _toml_document(value: &Bound<'_, PyAny>) -> PyResult<String> {
    match to_toml(value, "scenario")? {
        toml::Value::Table(table) => Ok(table.to_string()),
        _ => Err(PyTypeError::new_err("scenario must be a dict")),
    }
}

/// Converts a Python value into a TOML value; `key` (the dotted key) names it in errors.
fn to_toml(value: &Bound<'_, PyAny>, key: &str) -> PyResult<toml::Value> {
    if value.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(value.extract()?));
    }
    if value.is_instance_of::<PyInt>() {
        return value
            .extract::<i64>()
            .map(toml::Value::Integer)
            .map_err(|_| PyValueError::new_err(format!("{key}: integer {value} does not fit in 64 bits")));
    }
    if value.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(value.extract()?));
    }
    if value.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(value.extract()?));
    }
    if let Ok(dict) = value.cast::<PyDict>() {
        let mut table = toml::Table::new();
        for (name, item) in dict.iter() {
            let Ok(name) = name.extract::<String>() else {
                return Err(PyTypeError::new_err(format!("{key}: keys must be str, got {name:?}")));
            };
            let item = to_toml(&item, &format!("{key}.{name}"))?;
            table.insert(name, item);
        }
        return Ok(toml::Value::Table(table));
    }
    if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() {
        let mut items = Vec::new();
        for (k, item) in value.try_iter()?.enumerate() {
            items.push(to_toml(&item?, &format!("{key}[{k}]"))?);
        }
        return Ok(toml::Value::Array(items));
    }
    // numpy scalars and other numbers: a float where Python can make one.
    if let Ok(number) = value.call_method0("__float__").and_then(|f| f.extract::<f64>()) {
        if value.hasattr("is_integer")? || value.hasattr("dtype")? {
            if let Ok(integer) = value.call_method0("__index__").and_then(|i| i.extract::<i64>()) {
                return Ok(toml::Value::Integer(integer));
            }
        }
        return Ok(toml::Value::Float(number));
    }
    let type_name = value.get_type().name()?;
    Err(PyTypeError::new_err(format!(
        "{key} must be a bool, int, float, str, list or dict, got {type_name}"
    )))
}
