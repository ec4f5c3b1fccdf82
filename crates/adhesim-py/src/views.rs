//! Read-only numpy arrays of the fields a Rust object holds (`ContactState.pressure`,
//! `AdhesiveSolver.critical_stress`, ...): one array per field, made on the first access
//! and returned again (the same object, no copy) until the owner's fields change; its
//! `flags.writeable` is False, so writing into it raises `ValueError`.
//!
//! A change of the fields (a solve or step on the state) drops the cached arrays: the next
//! access makes a new one, and arrays taken before keep the values they had (a snapshot
//! of the state at that time, never a view that changes under the caller).

use numpy::{Element, PyArray2};
use pyo3::prelude::*;
use std::sync::OnceLock;

/// The cached array of one field.
pub struct Cached<T>(OnceLock<Py<PyArray2<T>>>);

impl<T> Default for Cached<T> {
    fn default() -> Self {
        Self(OnceLock::new())
    }
}

impl<T: Element> Cached<T> {
    /// The cached array, or `make()`'s, marked read-only and kept.
    pub fn get<'py>(
        &self,
        py: Python<'py>,
        make: impl FnOnce() -> PyResult<Bound<'py, PyArray2<T>>>,
    ) -> PyResult<Bound<'py, PyArray2<T>>> {
        if let Some(array) = self.0.get() {
            return Ok(array.bind(py).clone());
        }
        let array = make()?;
        read_only(array.as_any())?;
        // Another thread may have set it meanwhile: every caller then gets that one.
        let kept = self.0.get_or_init(|| array.unbind());
        Ok(kept.bind(py).clone())
    }

    /// Forgets the array (the field changed); arrays handed out keep their values.
    pub fn clear(&mut self) {
        self.0.take();
    }
}

/// Sets `array.flags.writeable = False`.
pub fn read_only(array: &Bound<'_, PyAny>) -> PyResult<()> {
    array.getattr("flags")?.setattr("writeable", false)
}
