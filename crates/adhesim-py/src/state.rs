//! The contact state: the fields of a configuration and the warm start of the next solve.

use crate::convert::{elements, field, fits_in_memory};
use crate::grid::{describe, Grid};
use crate::views::Cached;
use numpy::PyArray2;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// Fields of a contact configuration on a grid; also the warm start of the next solve or
/// step (pass the same object again). Starts with no contact and no load.
///
/// The fields (`pressure`, `displacement`, `contact`, `gap`) are read-only float64 (bool
/// for `contact`) arrays of shape (n, n), [row = y, column = x]: two accesses between
/// solves return the same array (no copy), and writing into it raises ValueError. A solve
/// or step on the state makes new arrays; arrays taken before keep their values (use
/// `numpy.array(state.pressure)` for a writeable copy).
///
/// Parameters
/// ----------
/// grid : Grid
///     The grid the fields live on.
///
/// Raises
/// ------
/// MemoryError
///     The fields exceed the memory available.
#[pyclass(module = "adhesim._adhesim")]
pub struct ContactState {
    /// The library's state: change it only through [`ContactState::fields_mut`].
    inner: adhesim::ContactState,
    pub grid: adhesim::Grid,
    /// Heights and depth of the last solve or step (for the gap).
    pub last_heights: Vec<f64>,
    pub last_depth: Option<f64>,
    views: StateViews,
}

/// The read-only arrays handed out since the last change (crate::views).
#[derive(Default)]
struct StateViews {
    pressure: Cached<f64>,
    displacement: Cached<f64>,
    contact: Cached<bool>,
    gap: Cached<f64>,
}

impl ContactState {
    pub fn fresh(grid: adhesim::Grid) -> Self {
        Self {
            inner: adhesim::ContactState::new(&grid),
            grid,
            last_heights: Vec::new(),
            last_depth: None,
            views: StateViews::default(),
        }
    }

    /// The library's state, read only.
    pub fn fields(&self) -> &adhesim::ContactState {
        &self.inner
    }

    /// The library's state to change (a solve or step): forgets the arrays handed out, so
    /// the next access to a field gives the new values.
    pub fn fields_mut(&mut self) -> &mut adhesim::ContactState {
        self.views = StateViews::default();
        &mut self.inner
    }

    /// `ValueError` unless the state lives on `grid`.
    pub fn check_grid(&self, grid: &adhesim::Grid) -> PyResult<()> {
        if &self.grid == grid {
            Ok(())
        } else {
            Err(PyValueError::new_err(format!(
                "state is for {}; the solver's grid is {}",
                describe(&self.grid),
                describe(grid)
            )))
        }
    }

    /// Remembers the heights and depth the state was solved for.
    pub fn record(&mut self, heights: &[f64], depth: f64) {
        self.last_heights.clear();
        self.last_heights.extend_from_slice(heights);
        self.last_depth = Some(depth);
        self.views.gap.clear();
    }
}

#[pymethods]
impl ContactState {
    #[new]
    fn new(#[pyo3(from_py_with = crate::grid::grid_argument)] grid: Grid) -> PyResult<Self> {
        // Pressure, displacement, contact and the recorded heights, with numpy's copies.
        fits_in_memory(
            &format!("ContactState({})", describe(&grid.inner)),
            elements(&grid.inner) * 40,
        )?;
        Ok(Self::fresh(grid.inner))
    }

    /// Pressure per element (> 0 compressive, < 0 tensile), shape (ny, nx), read-only.
    #[getter]
    fn pressure<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.views
            .pressure
            .get(py, || field(py, &self.inner.pressure, &self.grid))
    }

    /// Normal surface displacement u = K p (> 0 into the body), shape (ny, nx), read-only.
    #[getter]
    fn displacement<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.views
            .displacement
            .get(py, || field(py, &self.inner.displacement, &self.grid))
    }

    /// Contact mask (True in contact), shape (ny, nx), read-only.
    #[getter]
    fn contact<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<bool>>> {
        self.views
            .contact
            .get(py, || field(py, &self.inner.contact, &self.grid))
    }

    /// Gap g = z − d + u ≥ 0 (0 in contact) for the heights z and depth d of the last
    /// solve or step; +inf where the indenter has no surface. Read-only, shape (ny, nx).
    ///
    /// Raises
    /// ------
    /// ValueError
    ///     The state has not been solved yet.
    #[getter]
    fn gap<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let Some(depth) = self.last_depth else {
            return Err(PyValueError::new_err(
                "gap: the state has not been solved yet (no heights and depth)",
            ));
        };
        self.views.gap.get(py, || {
            let gap: Vec<f64> = self
                .last_heights
                .iter()
                .zip(&self.inner.displacement)
                .map(|(z, u)| z - depth + u)
                .collect();
            field(py, &gap, &self.grid)
        })
    }

    /// Depth d of the last solve or step (prescribed, or found under load control), or None.
    #[getter]
    fn depth(&self) -> Option<f64> {
        self.last_depth
    }

    /// Normal force F = Δ²·Σp (> 0 compressive).
    #[getter]
    fn force(&self) -> f64 {
        self.inner.force(self.grid.element_area())
    }

    /// Number of elements in contact.
    #[getter]
    fn contact_elements(&self) -> usize {
        self.inner.contact_elements()
    }

    /// Real contact area Δ²·|C|.
    #[getter]
    fn contact_area(&self) -> f64 {
        self.grid.element_area() * self.inner.contact_elements() as f64
    }

    /// Largest distance from `centre` to the centre of an element in contact (the
    /// paper's contact radius, Sect. 2.3).
    ///
    /// Parameters
    /// ----------
    /// centre : tuple of float, default (0.0, 0.0)
    ///     The point (x, y) the radius is measured from.
    ///
    /// Returns
    /// -------
    /// float
    ///     The radius; 0 without contact.
    ///
    /// Raises
    /// ------
    /// ValueError
    ///     A centre that is not finite (`(nan, 0)` returned 0).
    #[pyo3(signature = (centre = (0.0, 0.0)), text_signature = "($self, centre=(0.0, 0.0))")]
    fn contact_radius(&self, #[pyo3(from_py_with = crate::args::pair::centre)] centre: (f64, f64)) -> PyResult<f64> {
        if !(centre.0.is_finite() && centre.1.is_finite()) {
            return Err(PyValueError::new_err(format!(
                "centre must be a finite point (x, y), got ({}, {})",
                centre.0, centre.1
            )));
        }
        Ok(self.inner.contact_radius(&self.grid, centre))
    }

    /// The grid of the state.
    #[getter]
    fn grid(&self) -> Grid {
        Grid { inner: self.grid }
    }

    /// An independent copy (e.g. to branch a load path from a saved state).
    fn copy(&self) -> Self {
        Self {
            inner: self.inner.clone(),
            grid: self.grid,
            last_heights: self.last_heights.clone(),
            last_depth: self.last_depth,
            views: StateViews::default(),
        }
    }

    fn __repr__(&self) -> String {
        let depth = self.last_depth.map_or("None".to_string(), |d| format!("{d:?}"));
        format!(
            "ContactState(grid={}, depth={depth}, force={:e}, contact_elements={})",
            describe(&self.grid),
            self.inner.force(self.grid.element_area()),
            self.inner.contact_elements()
        )
    }
}

/// The `state` argument of a solve: an `adhesim.ContactState` or None.
pub fn state_argument(value: &Bound<'_, PyAny>) -> PyResult<Option<Py<ContactState>>> {
    if value.is_none() {
        return Ok(None);
    }
    Ok(Some(
        crate::args::instance::<ContactState>(value, "state", "an adhesim.ContactState or None")?.unbind(),
    ))
}

/// The `state` a step updates in place (None is refused).
pub fn contact_state_argument<'py>(value: &Bound<'py, PyAny>) -> PyResult<Bound<'py, ContactState>> {
    crate::args::instance::<ContactState>(value, "state", "an adhesim.ContactState")
}
