//! Grid, material, the elastic half-space operator and the contact state.

use crate::convert::{count, elements, field, fits_in_memory, half_space_bytes, positive, read_field, value_error};
use crate::views::Cached;
use adhesim::{Boundary, ElasticOperator};
use numpy::{PyArray1, PyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// A grid of boundary elements: `Grid(n, size)` is n × n square elements covering a square
/// of side `size`; `Grid(nx, ny, size_x, size_y)` is nx columns (along x) and ny rows (along
/// y) of Δx × Δy elements covering size_x × size_y.
///
/// Δx = size_x/nx, Δy = size_y/ny. Fields are (ny, nx) arrays indexed [row, column]: row i is
/// the coordinate y, column j the coordinate x; element centres sit at (j − nx//2)·Δx,
/// (i − ny//2)·Δy, so the origin is the centre of element (ny//2, nx//2).
///
/// Args:
///     n, size: elements per side (integer ≥ 2) and side length L (> 0, any length unit);
///         or nx, ny, size_x, size_y.
///     boundary: "free" (one contact on an infinite half-space) or "periodic" (the
///         rectangle is one period of an infinite surface); positional after the sizes, or
///         a keyword.
///
/// Raises:
///     ValueError: a count < 2, a size not finite and > 0, an unknown boundary, or another
///         number of arguments.
#[pyclass(module = "adhesim._adhesim", frozen, eq, from_py_object)]
#[derive(Clone, Copy, PartialEq)]
pub struct Grid {
    pub inner: adhesim::Grid,
}

impl Grid {
    /// `ValueError` naming `what` unless the grid is square (n × n square elements).
    fn square(&self, what: &str) -> PyResult<()> {
        if self.inner.is_square() {
            Ok(())
        } else {
            Err(PyValueError::new_err(format!(
                "Grid.{what} is for square grids; {} has nx, ny, size_x, size_y, dx, dy",
                self.__repr__()
            )))
        }
    }
}

/// The centres (index − count//2)·spacing of one axis, as a numpy array.
fn axis<'py>(
    py: Python<'py>,
    what: &str,
    count: usize,
    centre: impl Fn(usize) -> f64,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    // The values and numpy's copy.
    fits_in_memory(what, count as u128 * 16)?;
    Ok(PyArray1::from_vec(py, (0..count).map(centre).collect()))
}

#[pymethods]
impl Grid {
    #[new]
    #[pyo3(signature = (*args, boundary = None))]
    fn new(args: &Bound<'_, pyo3::types::PyTuple>, boundary: Option<String>) -> PyResult<Self> {
        let mut values: Vec<Bound<'_, PyAny>> = args.iter().collect();
        // A string after the sizes is the boundary.
        let positional = match values.last() {
            Some(last) if matches!(values.len(), 3 | 5) && last.is_instance_of::<pyo3::types::PyString>() => {
                Some(values.pop().expect("an argument").extract::<String>()?)
            }
            _ => None,
        };
        let boundary = match (positional, boundary) {
            (Some(_), Some(_)) => return Err(PyValueError::new_err("boundary given twice")),
            (Some(name), None) | (None, Some(name)) => name,
            (None, None) => "free".to_string(),
        };
        let boundary = match boundary.as_str() {
            "free" => Boundary::Free,
            "periodic" => Boundary::Periodic,
            other => {
                return Err(PyValueError::new_err(format!(
                    "boundary must be 'free' or 'periodic', got {other:?}"
                )))
            }
        };
        let grid = match values.as_slice() {
            [n, size] => adhesim::Grid::new(
                count("n", n.extract()?, 2)?,
                positive("size", size.extract()?)?,
                boundary,
            ),
            [nx, ny, size_x, size_y] => adhesim::Grid::rectangular(
                count("nx", nx.extract()?, 2)?,
                count("ny", ny.extract()?, 2)?,
                positive("size_x", size_x.extract()?)?,
                positive("size_y", size_y.extract()?)?,
                boundary,
            ),
            other => {
                return Err(PyValueError::new_err(format!(
                    "Grid takes (n, size) or (nx, ny, size_x, size_y), then the boundary; got {} arguments",
                    other.len()
                )))
            }
        };
        Ok(Self {
            inner: grid.map_err(value_error)?,
        })
    }

    /// Elements per side, n (square grids).
    #[getter]
    fn n(&self) -> PyResult<usize> {
        self.square("n")?;
        Ok(self.inner.nx())
    }

    /// Elements along x (columns), nx.
    #[getter]
    fn nx(&self) -> usize {
        self.inner.nx()
    }

    /// Elements along y (rows), ny.
    #[getter]
    fn ny(&self) -> usize {
        self.inner.ny()
    }

    /// The fields' shape (ny, nx).
    #[getter]
    fn shape(&self) -> (usize, usize) {
        (self.inner.ny(), self.inner.nx())
    }

    /// Side length L of the square (square grids).
    #[getter]
    fn size(&self) -> PyResult<f64> {
        self.square("size")?;
        Ok(self.inner.size_x())
    }

    /// Side length along x.
    #[getter]
    fn size_x(&self) -> f64 {
        self.inner.size_x()
    }

    /// Side length along y.
    #[getter]
    fn size_y(&self) -> f64 {
        self.inner.size_y()
    }

    /// "free" or "periodic".
    #[getter]
    fn boundary(&self) -> &'static str {
        boundary_name(self.inner.boundary())
    }

    /// Element side Δ = L/n (square elements; see dx, dy).
    #[getter]
    fn element_size(&self) -> PyResult<f64> {
        if self.inner.dx() != self.inner.dy() {
            return Err(PyValueError::new_err(format!(
                "Grid.element_size is for square elements; {} has dx = {}, dy = {}",
                self.__repr__(),
                self.inner.dx(),
                self.inner.dy()
            )));
        }
        Ok(self.inner.dx())
    }

    /// Element side along x, Δx = size_x/nx.
    #[getter]
    fn dx(&self) -> f64 {
        self.inner.dx()
    }

    /// Element side along y, Δy = size_y/ny.
    #[getter]
    fn dy(&self) -> f64 {
        self.inner.dy()
    }

    /// Element area Δx·Δy (force = Δx·Δy·Σp).
    #[getter]
    fn element_area(&self) -> f64 {
        self.inner.element_area()
    }

    /// Centre coordinates of the columns (x) or rows (y) of a square grid: a 1-D array
    /// (j − n//2)·Δ.
    fn coordinates<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.square("coordinates()")?;
        let grid = self.inner;
        axis(py, &format!("{}.coordinates()", self.__repr__()), grid.nx(), |j| {
            grid.x(j)
        })
    }

    /// Centre coordinates of the columns: a 1-D array (j − nx//2)·Δx.
    fn x<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let grid = self.inner;
        axis(py, &format!("{}.x()", self.__repr__()), grid.nx(), |j| grid.x(j))
    }

    /// Centre coordinates of the rows: a 1-D array (i − ny//2)·Δy.
    fn y<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let grid = self.inner;
        axis(py, &format!("{}.y()", self.__repr__()), grid.ny(), |i| grid.y(i))
    }

    fn __repr__(&self) -> String {
        describe(&self.inner)
    }
}

/// `Grid(n=…, size=…, boundary=…)`, or with nx, ny, size_x, size_y for a rectangle.
pub fn describe(grid: &adhesim::Grid) -> String {
    if grid.is_square() {
        format!(
            "Grid(n={}, size={}, boundary={:?})",
            grid.nx(),
            grid.size_x(),
            boundary_name(grid.boundary())
        )
    } else {
        format!(
            "Grid(nx={}, ny={}, size_x={}, size_y={}, boundary={:?})",
            grid.nx(),
            grid.ny(),
            grid.size_x(),
            grid.size_y(),
            boundary_name(grid.boundary())
        )
    }
}

fn boundary_name(boundary: Boundary) -> &'static str {
    match boundary {
        Boundary::Free => "free",
        Boundary::Periodic => "periodic",
    }
}

/// Linear elastic half-space, characterised by its contact modulus E* = E/(1 − ν²)
/// (against a rigid indenter; units of pressure).
///
/// Raises:
///     ValueError: contact_modulus not finite and > 0.
#[pyclass(module = "adhesim._adhesim", frozen, from_py_object)]
#[derive(Clone, Copy)]
pub struct Material {
    pub inner: adhesim::ElasticMaterial,
}

#[pymethods]
impl Material {
    #[new]
    fn new(contact_modulus: f64) -> PyResult<Self> {
        positive("contact_modulus", contact_modulus)?;
        Ok(Self {
            inner: adhesim::ElasticMaterial::new(contact_modulus).map_err(value_error)?,
        })
    }

    /// E* = E/(1 − ν²) from Young's modulus E (> 0) and Poisson's ratio ν in (−1, 0.5].
    #[staticmethod]
    fn from_youngs_modulus(youngs_modulus: f64, poisson_ratio: f64) -> PyResult<Self> {
        Ok(Self {
            inner: adhesim::ElasticMaterial::from_youngs_modulus(youngs_modulus, poisson_ratio).map_err(value_error)?,
        })
    }

    /// Two elastic bodies, each (E, ν): 1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2.
    #[staticmethod]
    fn from_two_bodies(first: (f64, f64), second: (f64, f64)) -> PyResult<Self> {
        Ok(Self {
            inner: adhesim::ElasticMaterial::from_two_bodies(first, second).map_err(value_error)?,
        })
    }

    /// The contact modulus E*.
    #[getter]
    fn contact_modulus(&self) -> f64 {
        self.inner.contact_modulus()
    }

    fn __repr__(&self) -> String {
        format!("Material(contact_modulus={})", self.inner.contact_modulus())
    }
}

/// The elastic half-space operator u = K p of a grid: free (DC-FFT with Love's
/// coefficients) or periodic (element-consistent Fourier kernel), chosen by
/// `grid.boundary`. FFTs are planned once, here.
///
/// Signs: pressure p > 0 is compressive, displacement u > 0 points into the body. On a
/// periodic grid the mean displacement is undefined (K̂(0) = 0): a uniform pressure gives
/// u = 0.
#[pyclass(module = "adhesim._adhesim")]
pub struct HalfSpace {
    pub inner: adhesim::HalfSpace,
    pub grid: adhesim::Grid,
    pub material: adhesim::ElasticMaterial,
    scratch: Vec<f64>,
    output: Vec<f64>,
}

#[pymethods]
impl HalfSpace {
    #[new]
    fn new(py: Python<'_>, grid: Grid, material: Material) -> PyResult<Self> {
        fits_in_memory(
            &format!("HalfSpace({}) and its solvers", grid.__repr__()),
            half_space_bytes(&grid.inner),
        )?;
        let inner = py.detach(|| adhesim::HalfSpace::new(grid.inner, material.inner));
        Ok(Self {
            inner,
            grid: grid.inner,
            material: material.inner,
            scratch: Vec::with_capacity(grid.inner.len()),
            output: vec![0.0; grid.inner.len()],
        })
    }

    /// Surface displacement u = K p (length units) of a pressure field.
    ///
    /// Args:
    ///     pressure: float64 array of shape (n, n), > 0 compressive (units of pressure).
    ///
    /// Returns:
    ///     displacement: float64 array of shape (n, n), > 0 into the body.
    ///
    /// Raises:
    ///     TypeError: not a float64 numpy array.  ValueError: wrong shape or non-finite.
    fn apply<'py>(&mut self, py: Python<'py>, pressure: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let grid = self.grid;
        read_field(pressure, "pressure", &grid, false, &mut self.scratch)?;
        let Self {
            inner, scratch, output, ..
        } = self;
        py.detach(|| inner.apply(scratch, output));
        field(py, &self.output, &grid)
    }

    /// The grid the operator acts on.
    #[getter]
    fn grid(&self) -> Grid {
        Grid { inner: self.grid }
    }

    /// The material (contact modulus E*).
    #[getter]
    fn material(&self) -> Material {
        Material { inner: self.material }
    }

    /// K(0,0): displacement of an element under its own unit pressure.
    #[getter]
    fn self_compliance(&self) -> f64 {
        self.inner.self_compliance()
    }

    /// Operator applications (FFT pairs) so far, by `apply` and by the solvers.
    #[getter]
    fn applications(&self) -> u64 {
        self.inner.applications()
    }

    pub fn __repr__(&self) -> String {
        format!(
            "HalfSpace(grid={}, contact_modulus={})",
            describe(&self.grid),
            self.material.contact_modulus()
        )
    }
}

/// Fields of a contact configuration on a grid; also the warm start of the next solve or
/// step (pass the same object again). Starts with no contact and no load.
///
/// The fields (`pressure`, `displacement`, `contact`, `gap`) are read-only float64 (bool
/// for `contact`) arrays of shape (n, n), [row = y, column = x]: two accesses between
/// solves return the same array (no copy), and writing into it raises ValueError. A solve
/// or step on the state makes new arrays; arrays taken before keep their values (use
/// `numpy.array(state.pressure)` for a writeable copy).
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
    fn new(grid: Grid) -> PyResult<Self> {
        // Pressure, displacement, contact and the recorded heights, with numpy's copies.
        fits_in_memory(
            &format!("ContactState({})", grid.__repr__()),
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
    /// solve or step; +inf where the indenter has no surface. Read-only, shape (n, n).
    ///
    /// Raises:
    ///     ValueError: the state has not been solved yet.
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

    /// Largest distance from `centre` = (x, y) to the centre of an element in contact
    /// (the paper's contact radius, Sect. 2.3); 0 without contact.
    #[pyo3(signature = (centre = (0.0, 0.0)), text_signature = "($self, centre=(0.0, 0.0))")]
    fn contact_radius(&self, centre: (f64, f64)) -> f64 {
        self.inner.contact_radius(&self.grid, centre)
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
