//! Checked conversions between Python values and the library's types, and the mapping of
//! library errors to Python exceptions. Every message names the argument and its value.

use numpy::{dtype, PyArray1, PyArray2, PyArrayDescrMethods, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;

pyo3::create_exception!(
    _adhesim,
    SolveError,
    pyo3::exceptions::PyRuntimeError,
    "A solver did not converge (iteration or round limit reached, or a non-finite value appeared). The message states the iterations and the residual reached."
);

pyo3::create_exception!(
    _adhesim,
    ScenarioError,
    pyo3::exceptions::PyValueError,
    "A scenario that cannot be read or run (a ValueError). `key` is the dotted key at fault (None when the error is not about one key), `value` its value as written, `requirement` what it must satisfy (None where unknown), `kind` one of syntax, unknown_key, missing_key, invalid_value, file, resources. A sweep's own tables (adhesim.sweep's vary, zip, random, derived; a sweep file) name their key as the sweep file's TOML dotted key: random.seed, random.cases, vary.alpha, zip.\"grid.n\", random.\"grid.size\".min, derived.alpha; a case's value of a scenario key keeps the scenario key (grid.n)."
);

/// The scenario crate's typed error as `adhesim.ScenarioError` (a `ValueError`) with
/// `.key`, `.value`, `.requirement` and `.kind`; `hint` is appended to the message.
pub fn scenario_error(error: &adhesim_scenario::ScenarioError, hint: &str) -> PyErr {
    let exception = ScenarioError::new_err(format!("{}{hint}", error.message()));
    Python::attach(|py| {
        let value = exception.value(py);
        let fields = [
            ("key", error.key.clone()),
            ("value", error.value.clone()),
            ("requirement", error.requirement.clone()),
            ("kind", Some(error.kind.name().to_string())),
        ];
        for (name, field) in fields {
            if let Err(failure) = value.setattr(name, field) {
                return failure;
            }
        }
        exception.clone_ref(py)
    })
}

/// An error of the sweep engine or the run folder: `adhesim.ScenarioError` where a
/// scenario key is at fault (a sweep case's bad value), else `ValueError`; the message is
/// the chain on one line.
pub fn engine_error(error: anyhow::Error) -> PyErr {
    match adhesim_scenario::ScenarioError::find(&error) {
        Some(typed) => scenario_error(&typed, ""),
        None => PyValueError::new_err(adhesim_scenario::error_text::error_line(error.chain())),
    }
}

/// Maps a library solve error to `ValueError` (bad input) or `adhesim.SolveError`
/// (non-convergence).
pub fn solve_error(error: adhesim::SolveError) -> PyErr {
    use adhesim::SolveError as E;
    match error {
        // A depth past full contact of a periodic cell is an impossible request, not a
        // failure to converge.
        E::SizeMismatch { .. } | E::InvalidLoad(_) | E::PeriodicUnsupported { .. } | E::BeyondFullContact { .. } => {
            PyValueError::new_err(error.to_string())
        }
        E::NotConverged { .. } | E::TooManyRounds { .. } | E::NonFinite { .. } | E::NotPositiveDefinite { .. } => {
            SolveError::new_err(error.to_string())
        }
    }
}

/// `ValueError` with the library's message.
pub fn value_error(error: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(error.to_string())
}

/// A finite, strictly positive float, or `ValueError` naming `name`.
pub fn positive(name: &str, value: f64) -> PyResult<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(PyValueError::new_err(format!(
            "{name} must be finite and > 0, got {value}"
        )))
    }
}

/// A finite, non-negative float, or `ValueError` naming `name`.
pub fn non_negative(name: &str, value: f64) -> PyResult<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(PyValueError::new_err(format!(
            "{name} must be finite and >= 0, got {value}"
        )))
    }
}

/// A finite float, or `ValueError` naming `name`.
pub fn finite(name: &str, value: f64) -> PyResult<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(PyValueError::new_err(format!("{name} must be finite, got {value}")))
    }
}

/// An integer ≥ `minimum` as usize (Python ints may be negative: a `ValueError`, not an
/// `OverflowError`, names the argument).
pub fn count(name: &str, value: i64, minimum: usize) -> PyResult<usize> {
    match usize::try_from(value) {
        Ok(v) if v >= minimum => Ok(v),
        _ => Err(PyValueError::new_err(format!(
            "{name} must be an integer >= {minimum}, got {value}"
        ))),
    }
}

/// `TypeError` (or `ValueError` for an int beyond the type's range) naming the argument
/// `name`, its value and the `expected` type: pyo3's own message ("'str' object cannot be
/// interpreted as an integer", "int too big to convert") named no argument.
fn argument_error(value: &Bound<'_, PyAny>, name: &str, expected: &str) -> PyErr {
    if value.is_instance_of::<pyo3::types::PyInt>() {
        PyValueError::new_err(format!(
            "{name} = {} is out of range: a 64-bit integer holds up to {}",
            repr_of(value),
            i64::MAX
        ))
    } else {
        PyTypeError::new_err(format!("{name} must be {expected}, got {}", described(value)))
    }
}

/// Python's `repr` of a value ("?" where it fails).
fn repr_of(value: &Bound<'_, PyAny>) -> String {
    value.repr().map_or_else(|_| "?".to_string(), |r| r.to_string())
}

/// "type repr", as the messages print a value they refuse: `str 'a'`.
pub fn described(value: &Bound<'_, PyAny>) -> String {
    let type_name = value
        .get_type()
        .name()
        .map_or_else(|_| "?".to_string(), |n| n.to_string());
    format!("{type_name} {}", repr_of(value))
}

/// An integer argument (a Python int or an integer numpy scalar), or an error naming `name`.
pub fn int_argument(value: &Bound<'_, PyAny>, name: &str) -> PyResult<i64> {
    if value.is_instance_of::<pyo3::types::PyBool>() {
        return Err(argument_error(value, name, "an integer"));
    }
    value
        .extract::<i64>()
        .map_err(|_| argument_error(value, name, "an integer"))
}

/// A float argument (a Python float or int, or a numpy scalar), or a `TypeError` naming
/// `name`.
pub fn float_argument(value: &Bound<'_, PyAny>, name: &str) -> PyResult<f64> {
    if value.is_instance_of::<pyo3::types::PyBool>() || value.is_instance_of::<pyo3::types::PyString>() {
        return Err(argument_error(value, name, "a number"));
    }
    value
        .extract::<f64>()
        .map_err(|_| argument_error(value, name, "a number"))
}

/// `value` as a float64 numpy array: itself where it is one, else `numpy.asarray(value,
/// dtype=numpy.float64)` (numpy's array_like convention: float32, integers, nested lists),
/// a `TypeError` naming `name` where that fails or would drop an imaginary part.
pub fn as_float64<'py>(value: &Bound<'py, PyAny>, name: &str) -> PyResult<Bound<'py, PyAny>> {
    let py = value.py();
    if let Ok(untyped) = value.cast::<PyUntypedArray>() {
        if untyped.dtype().is_equiv_to(&dtype::<f64>(py)) {
            return Ok(value.clone());
        }
    }
    let numpy = py.import("numpy")?;
    let type_name = value.get_type().name()?;
    if numpy.call_method1("iscomplexobj", (value,))?.is_truthy()? {
        return Err(PyTypeError::new_err(format!(
            "{name} must be real numbers (array_like of floats), got complex values in a {type_name}"
        )));
    }
    let kwargs = pyo3::types::PyDict::new(py);
    kwargs.set_item("dtype", numpy.getattr("float64")?)?;
    numpy.call_method("asarray", (value,), Some(&kwargs)).map_err(|e| {
        PyTypeError::new_err(format!(
            "{name} must be array_like of floats (a numpy array or nested lists), got {type_name}: {e}"
        ))
    })
}

/// Copies an array_like of shape `(n, n)` into `buffer` as float64 in row-major order
/// (row i = y, column j = x): float64 arrays as they are, other dtypes and nested lists
/// through [`as_float64`]. Refuses what numpy cannot make floats of (`TypeError`) and other
/// shapes (`ValueError`), naming the argument and the expected shape. `+inf` is allowed
/// where `allow_infinity` (heights: no surface there); NaN and −inf never are.
pub fn read_field(
    value: &Bound<'_, PyAny>,
    name: &str,
    grid: &adhesim::Grid,
    allow_infinity: bool,
    buffer: &mut Vec<f64>,
) -> PyResult<()> {
    let (n, rows) = (grid.nx(), grid.ny());
    let value = &as_float64(value, name)?;
    let untyped = value.cast::<PyUntypedArray>()?;
    if untyped.shape() != [rows, n] {
        let elements = if grid.nx() == grid.ny() {
            "the grid's n × n elements"
        } else {
            "the grid's ny rows × nx columns"
        };
        return Err(PyValueError::new_err(format!(
            "{name} must have shape ({rows}, {n}) ({elements}), got shape {:?}",
            untyped.shape()
        )));
    }
    let array = value.cast::<PyArray2<f64>>()?;
    let readonly = array
        .try_readonly()
        .map_err(|e| PyValueError::new_err(format!("{name}: {e}")))?;
    buffer.clear();
    buffer.extend(readonly.as_array().iter().copied());
    if let Some(k) = buffer
        .iter()
        .position(|v| v.is_nan() || *v == f64::NEG_INFINITY || (!allow_infinity && v.is_infinite()))
    {
        let allowed = if allow_infinity {
            "finite or +inf (no surface)"
        } else {
            "finite"
        };
        return Err(PyValueError::new_err(format!(
            "{name}[{}, {}] must be {allowed}, got {}",
            k / n,
            k % n,
            buffer[k]
        )));
    }
    Ok(())
}

/// A row-major field as a new `(ny, nx)` numpy array (rows along y).
pub fn field<'py, T: numpy::Element + Copy>(
    py: Python<'py>,
    values: &[T],
    grid: &adhesim::Grid,
) -> PyResult<Bound<'py, PyArray2<T>>> {
    PyArray1::from_slice(py, values).reshape([grid.ny(), grid.nx()])
}

/// Reads a 1-D array_like (any strides, any real dtype, a list) into a Vec of float64.
pub fn read_vector(value: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<f64>> {
    let value = &as_float64(value, name)?;
    let untyped = value.cast::<PyUntypedArray>()?;
    if untyped.ndim() != 1 {
        return Err(PyValueError::new_err(format!(
            "{name} must be 1-D, got shape {:?}",
            untyped.shape()
        )));
    }
    let array = value.cast::<PyArray1<f64>>()?;
    let readonly = array
        .try_readonly()
        .map_err(|e| PyValueError::new_err(format!("{name}: {e}")))?;
    Ok(readonly.as_array().iter().copied().collect())
}

/// `MemoryError` where `bytes` (what `what` would allocate) exceed the memory this process
/// may use: the smallest of RLIMIT_AS, the cgroup's limit and `MemAvailable`, or
/// `ADHESIM_MEMORY_AVAILABLE` (`adhesim_scenario::memory_available`). Without it a grid of
/// 10⁵ elements per side aborted the interpreter on allocation.
pub fn fits_in_memory(what: &str, bytes: u128) -> PyResult<()> {
    let limit = adhesim_scenario::memory_available().map_err(value_error)?;
    match limit {
        Some(limit) => adhesim_scenario::memory::check_allocation(what, bytes, &limit)
            .map_err(|e| pyo3::exceptions::PyMemoryError::new_err(e.to_string())),
        None => Ok(()),
    }
}

/// Elements of `grid`, N², as u128 (sizes in bytes are computed without overflow).
pub fn elements(grid: &adhesim::Grid) -> u128 {
    grid.nx() as u128 * grid.ny() as u128
}

/// Bytes of a half-space operator and the solvers on it, an upper estimate as the scenario
/// crate's `memory_estimate`: three complex half spectra and two real buffers on the padded
/// grid (2N per side free, N periodic) and 32 f64 fields of N².
pub fn half_space_bytes(grid: &adhesim::Grid) -> u128 {
    let (nx, ny) = (grid.nx() as u128, grid.ny() as u128);
    let (padded_x, padded_y) = match grid.boundary() {
        adhesim::Boundary::Free => (2 * nx, 2 * ny),
        adhesim::Boundary::Periodic => (nx, ny),
    };
    3 * padded_y * (padded_x / 2 + 1) * 16 + 2 * padded_x * padded_y * 8 + 32 * nx * ny * 8
}
