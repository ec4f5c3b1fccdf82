//! Argument extractors named after their parameter, for `#[pyo3(from_py_with = …)]`.
//!
//! pyo3's own conversion errors name neither the argument nor the value ("must be real
//! number, not str"; the argument's name is only a note, which Python < 3.11 drops). Each
//! function here is named after the parameter it converts, so its error reads
//! "tolerance must be a number, got str 'a'" whatever the Python version.

use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::PyClass;

use crate::convert::{described, float_argument, int_argument};

/// One extractor per name: `fn name(value) -> PyResult<$output>` calling `$convert(value,
/// "name")`.
macro_rules! named {
    ($output:ty, $convert:path; $($name:ident),* $(,)?) => {
        $(
            pub fn $name(value: &Bound<'_, PyAny>) -> PyResult<$output> {
                $convert(value, stringify!($name))
            }
        )*
    };
}

/// A Python float or int (or numpy scalar).
pub mod number {
    use super::*;
    named!(f64, float_argument;
        tolerance, relative_tolerance, front_tolerance, depth, work_of_adhesion, radius, contact_modulus,
        amplitude, wavelength, angle_degrees);
}

/// A number, or None.
pub mod optional_number {
    use super::*;
    named!(Option<f64>, super::optional_float; depth, load, worst_first_fraction);
}

/// A Python int (or integer numpy scalar); the solvers check its range.
pub mod integer {
    use super::*;
    named!(i64, int_argument; max_iterations, max_cg_iterations, max_rounds, coarsest);
}

/// A str.
pub mod text {
    use super::*;
    named!(String, super::text_argument; attachment);
}

/// A str, or None.
pub mod optional_text {
    use super::*;
    named!(Option<String>, super::optional_text; boundary);
}

/// True or False (or a numpy bool); 1, 0 and "yes" are refused.
pub mod flag {
    use super::*;
    named!(bool, super::bool_argument; preconditioned, carry_bans_when_retracting, retry_after_growth);
}

/// A pair of numbers, as (x, y) or (E, ν).
pub mod pair {
    use super::*;
    named!((f64, f64), super::pair_argument; centre, first, second, semi_axes);
}

/// `value` as an instance of `T`, or a `TypeError` naming `name`, the value and `expected`.
pub(crate) fn instance<'py, T: PyClass>(
    value: &Bound<'py, PyAny>,
    name: &str,
    expected: &str,
) -> PyResult<Bound<'py, T>> {
    match value.cast::<T>() {
        Ok(bound) => Ok(bound.clone()),
        Err(_) => Err(PyTypeError::new_err(format!(
            "{name} must be {expected}, got {}",
            described(value)
        ))),
    }
}

/// None, or what `convert` makes of the value.
fn optional<T>(
    value: &Bound<'_, PyAny>,
    name: &str,
    convert: fn(&Bound<'_, PyAny>, &str) -> PyResult<T>,
) -> PyResult<Option<T>> {
    if value.is_none() {
        Ok(None)
    } else {
        convert(value, name).map(Some)
    }
}

fn optional_float(value: &Bound<'_, PyAny>, name: &str) -> PyResult<Option<f64>> {
    optional(value, name, float_argument)
}

fn text_argument(value: &Bound<'_, PyAny>, name: &str) -> PyResult<String> {
    value
        .extract::<String>()
        .map_err(|_| PyTypeError::new_err(format!("{name} must be a str, got {}", described(value))))
}

fn optional_text(value: &Bound<'_, PyAny>, name: &str) -> PyResult<Option<String>> {
    optional(value, name, text_argument)
}

fn bool_argument(value: &Bound<'_, PyAny>, name: &str) -> PyResult<bool> {
    value
        .extract::<bool>()
        .map_err(|_| PyTypeError::new_err(format!("{name} must be True or False, got {}", described(value))))
}

/// Two numbers from a tuple, list or array of length 2.
fn pair_argument(value: &Bound<'_, PyAny>, name: &str) -> PyResult<(f64, f64)> {
    let is_text = value.is_instance_of::<pyo3::types::PyString>() || value.is_instance_of::<pyo3::types::PyBytes>();
    let items: Option<Vec<Bound<'_, PyAny>>> = if is_text {
        None
    } else {
        value
            .try_iter()
            .ok()
            .and_then(|items| items.collect::<PyResult<Vec<_>>>().ok())
    };
    match items.as_deref() {
        Some([first, second]) => Ok((
            float_argument(first, &format!("{name}[0]"))?,
            float_argument(second, &format!("{name}[1]"))?,
        )),
        Some(other) => Err(PyValueError::new_err(format!(
            "{name} must be a pair of numbers, got {} of length {}",
            described(value),
            other.len()
        ))),
        None => Err(PyTypeError::new_err(format!(
            "{name} must be a pair of numbers, got {}",
            described(value)
        ))),
    }
}
