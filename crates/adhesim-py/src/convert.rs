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

/// Copies a float64 array of shape `(n, n)` into `buffer` in row-major order (row i = y,
/// column j = x). Refuses other types and dtypes (`TypeError`) and other shapes
/// (`ValueError`), naming the argument and the expected shape. `+inf` is allowed where
/// `allow_infinity` (heights: no surface there); NaN and −inf never are.
pub fn read_field(
    value: &Bound<'_, PyAny>,
    name: &str,
    n: usize,
    allow_infinity: bool,
    buffer: &mut Vec<f64>,
) -> PyResult<()> {
    let expected = format!("({n}, {n})");
    let Ok(untyped) = value.cast::<PyUntypedArray>() else {
        let type_name = value.get_type().name()?;
        return Err(PyTypeError::new_err(format!(
            "{name} must be a numpy.ndarray of dtype float64 and shape {expected}, got {type_name} (use numpy.asarray({name}, dtype=float))"
        )));
    };
    let descr = untyped.dtype();
    if !descr.is_equiv_to(&dtype::<f64>(value.py())) {
        return Err(PyTypeError::new_err(format!(
            "{name} must have dtype float64 and shape {expected}, got dtype {descr} with shape {:?} (use {name}.astype(float))",
            untyped.shape()
        )));
    }
    if untyped.shape() != [n, n] {
        return Err(PyValueError::new_err(format!(
            "{name} must have shape {expected} (the grid's n × n elements), got shape {:?}",
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

/// A row-major field as a new `(n, n)` numpy array.
pub fn field<'py, T: numpy::Element + Copy>(
    py: Python<'py>,
    values: &[T],
    n: usize,
) -> PyResult<Bound<'py, PyArray2<T>>> {
    PyArray1::from_slice(py, values).reshape([n, n])
}

/// Reads a 1-D float64 array (any strides) into a Vec.
pub fn read_vector(value: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<f64>> {
    let Ok(untyped) = value.cast::<PyUntypedArray>() else {
        let type_name = value.get_type().name()?;
        return Err(PyTypeError::new_err(format!(
            "{name} must be a 1-D numpy.ndarray of dtype float64, got {type_name}"
        )));
    };
    let descr = untyped.dtype();
    if !descr.is_equiv_to(&dtype::<f64>(value.py())) || untyped.ndim() != 1 {
        return Err(PyTypeError::new_err(format!(
            "{name} must be a 1-D numpy.ndarray of dtype float64, got dtype {descr} with shape {:?}",
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
    let n = grid.n() as u128;
    n * n
}

/// Bytes of a half-space operator and the solvers on it, an upper estimate as the scenario
/// crate's `memory_estimate`: three complex half spectra and two real buffers on the padded
/// grid (2N per side free, N periodic) and 32 f64 fields of N².
pub fn half_space_bytes(grid: &adhesim::Grid) -> u128 {
    let n = grid.n() as u128;
    let padded = match grid.boundary() {
        adhesim::Boundary::Free => 2 * n,
        adhesim::Boundary::Periodic => n,
    };
    3 * padded * (padded / 2 + 1) * 16 + 2 * padded * padded * 8 + 32 * n * n * 8
}
