//! The grid of boundary elements (`Grid`) and how a grid is described in messages.

use crate::convert::{count, fits_in_memory, float_argument, int_argument, positive, value_error};
use adhesim::Boundary;
use numpy::PyArray1;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;

/// A grid of boundary elements: `Grid(n, size)` is n × n square elements covering a square
/// of side `size`; `Grid(nx, ny, size_x, size_y)` is nx columns (along x) and ny rows (along
/// y) of Δx × Δy elements covering size_x × size_y.
///
/// Δx = size_x/nx, Δy = size_y/ny. Fields are (ny, nx) arrays indexed [row, column]: row i is
/// the coordinate y, column j the coordinate x; element centres sit at (j − nx//2)·Δx,
/// (i − ny//2)·Δy, so the origin is the centre of element (ny//2, nx//2).
///
/// Parameters
/// ----------
/// n, size : int, float
///     Elements per side (≥ 2) and side length L (> 0, any length unit) of a square.
/// nx, ny, size_x, size_y : int, int, float, float
///     Or the columns, rows and side lengths of a rectangle.
/// boundary : {"free", "periodic"}, default "free"
///     One contact on an infinite half-space, or the rectangle as one period of an
///     infinite surface; positional after the sizes, or a keyword.
///
/// Each parameter is taken by position or by name (`Grid(n=64, size=1.0)`).
///
/// Raises
/// ------
/// ValueError
///     A count < 2 or beyond the index range, a size not finite and > 0, an unknown
///     boundary.
/// TypeError
///     A count that is not an integer or a size that is not a number (naming the
///     parameter and the value), a parameter missing or given twice, or another number of
///     arguments.
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
    #[pyo3(signature = (*args, boundary = None, n = None, size = None, nx = None, ny = None, size_x = None, size_y = None))]
    #[allow(clippy::too_many_arguments)]
    fn new<'py>(
        args: &Bound<'py, pyo3::types::PyTuple>,
        #[pyo3(from_py_with = crate::args::optional_text::boundary)] boundary: Option<String>,
        n: Option<Bound<'py, PyAny>>,
        size: Option<Bound<'py, PyAny>>,
        nx: Option<Bound<'py, PyAny>>,
        ny: Option<Bound<'py, PyAny>>,
        size_x: Option<Bound<'py, PyAny>>,
        size_y: Option<Bound<'py, PyAny>>,
    ) -> PyResult<Self> {
        let mut values: Vec<Bound<'py, PyAny>> = args.iter().collect();
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
        // The named parameters of the two forms (n, size) and (nx, ny, size_x, size_y),
        // filled by position first, then by name.
        let by_name = [&n, &size, &nx, &ny, &size_x, &size_y].iter().any(|v| v.is_some());
        if !by_name && !matches!(values.len(), 2 | 4) {
            return Err(PyValueError::new_err(format!(
                "Grid takes (n, size) or (nx, ny, size_x, size_y), then the boundary; got {} arguments",
                values.len()
            )));
        }
        let rectangular = values.len() > 2 || nx.is_some() || ny.is_some() || size_x.is_some() || size_y.is_some();
        let (names, named): (&[&str], Vec<Option<Bound<'py, PyAny>>>) = if rectangular {
            if n.is_some() || size.is_some() {
                return Err(PyTypeError::new_err(
                    "Grid takes (n, size) or (nx, ny, size_x, size_y), not a mix of both",
                ));
            }
            (&["nx", "ny", "size_x", "size_y"], vec![nx, ny, size_x, size_y])
        } else {
            (&["n", "size"], vec![n, size])
        };
        if values.len() > names.len() {
            return Err(PyTypeError::new_err(format!(
                "Grid takes (n, size) or (nx, ny, size_x, size_y), then the boundary; got {} arguments",
                values.len()
            )));
        }
        let mut slots: Vec<Option<Bound<'py, PyAny>>> = values.into_iter().map(Some).collect();
        slots.resize(names.len(), None);
        for ((slot, keyword), name) in slots.iter_mut().zip(named).zip(names) {
            match (slot.is_some(), keyword) {
                (true, Some(_)) => {
                    return Err(PyTypeError::new_err(format!(
                        "Grid got {name} twice (by position and by name)"
                    )))
                }
                (false, Some(keyword)) => *slot = Some(keyword),
                _ => {}
            }
        }
        let mut slots = slots.into_iter().zip(names.iter()).map(|(slot, name)| {
            slot.ok_or_else(|| {
                PyTypeError::new_err(format!(
                    "Grid needs {name}: Grid(n, size) or Grid(nx, ny, size_x, size_y), then the boundary"
                ))
            })
            .map(|value| (value, *name))
        });
        let mut next = || slots.next().expect("one slot per name");
        let int = |(value, name): (Bound<'py, PyAny>, &str)| count(name, int_argument(&value, name)?, 2);
        let float = |(value, name): (Bound<'py, PyAny>, &str)| positive(name, float_argument(&value, name)?);
        let grid = if rectangular {
            let (nx, ny) = (int(next()?)?, int(next()?)?);
            let (size_x, size_y) = (float(next()?)?, float(next()?)?);
            adhesim::Grid::rectangular(nx, ny, size_x, size_y, boundary)
        } else {
            let n = int(next()?)?;
            adhesim::Grid::new(n, float(next()?)?, boundary)
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

/// The `grid` argument, an `adhesim.Grid` (a `TypeError` naming it otherwise).
pub fn grid_argument(value: &Bound<'_, PyAny>) -> PyResult<Grid> {
    Ok(*crate::args::instance::<Grid>(value, "grid", "an adhesim.Grid")?.get())
}
