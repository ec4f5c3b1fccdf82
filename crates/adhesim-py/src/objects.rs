//! The material and the elastic half-space operator (the grid: `grid.rs`; the contact
//! state: `state.rs`).

use crate::convert::{field, fits_in_memory, float_argument, half_space_bytes, positive, read_field, value_error};
use adhesim::ElasticOperator;
use numpy::PyArray2;
use pyo3::prelude::*;

use crate::grid::{describe, Grid};
/// Linear elastic half-space, characterised by its contact modulus E* = E/(1 − ν²)
/// (against a rigid indenter; units of pressure).
///
/// Parameters
/// ----------
/// contact_modulus : float
///     E* (> 0).
///
/// Raises
/// ------
/// ValueError
///     contact_modulus not finite and > 0.
#[pyclass(module = "adhesim._adhesim", frozen, from_py_object)]
#[derive(Clone, Copy)]
pub struct Material {
    pub inner: adhesim::ElasticMaterial,
}

#[pymethods]
impl Material {
    #[new]
    fn new(contact_modulus: &Bound<'_, PyAny>) -> PyResult<Self> {
        // Converted here to name the argument (`Material("1")` said "must be real number").
        let contact_modulus = positive("contact_modulus", float_argument(contact_modulus, "contact_modulus")?)?;
        Ok(Self {
            inner: adhesim::ElasticMaterial::new(contact_modulus).map_err(value_error)?,
        })
    }

    /// E* = E/(1 − ν²) from Young's modulus and Poisson's ratio.
    ///
    /// Parameters
    /// ----------
    /// youngs_modulus : float
    ///     E (> 0).
    /// poisson_ratio : float
    ///     ν in (−1, 0.5].
    ///
    /// Returns
    /// -------
    /// Material
    ///
    /// Raises
    /// ------
    /// ValueError
    ///     E or ν out of range.
    #[staticmethod]
    fn from_youngs_modulus(youngs_modulus: &Bound<'_, PyAny>, poisson_ratio: &Bound<'_, PyAny>) -> PyResult<Self> {
        let youngs_modulus = float_argument(youngs_modulus, "youngs_modulus")?;
        let poisson_ratio = float_argument(poisson_ratio, "poisson_ratio")?;
        Ok(Self {
            inner: adhesim::ElasticMaterial::from_youngs_modulus(youngs_modulus, poisson_ratio).map_err(value_error)?,
        })
    }

    /// Two elastic bodies: 1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2.
    ///
    /// Parameters
    /// ----------
    /// first, second : tuple of float
    ///     (E, ν) of each body, E > 0 and ν in (−1, 0.5].
    ///
    /// Returns
    /// -------
    /// Material
    ///
    /// Raises
    /// ------
    /// ValueError
    ///     E or ν out of range.
    #[staticmethod]
    fn from_two_bodies(
        #[pyo3(from_py_with = crate::args::pair::first)] first: (f64, f64),
        #[pyo3(from_py_with = crate::args::pair::second)] second: (f64, f64),
    ) -> PyResult<Self> {
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
///
/// Parameters
/// ----------
/// grid : Grid
/// material : Material
///
/// Raises
/// ------
/// MemoryError
///     The operator's FFT buffers exceed the memory available.
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
    fn new(
        py: Python<'_>,
        #[pyo3(from_py_with = crate::grid::grid_argument)] grid: Grid,
        #[pyo3(from_py_with = crate::objects::material_argument)] material: Material,
    ) -> PyResult<Self> {
        fits_in_memory(
            &format!("HalfSpace({}) and its solvers", describe(&grid.inner)),
            half_space_bytes(&grid.inner),
        )?;
        let inner = crate::pool::detached(py, || adhesim::HalfSpace::new(grid.inner, material.inner))?;
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
    /// Parameters
    /// ----------
    /// pressure : array_like of float, shape (ny, nx)
    ///     Pressure per element, > 0 compressive (units of pressure).
    ///
    /// Returns
    /// -------
    /// displacement : numpy.ndarray of float64, shape (ny, nx)
    ///     > 0 into the body; a new, writeable array.
    ///
    /// Raises
    /// ------
    /// TypeError
    ///     Not an array of real numbers.
    /// ValueError
    ///     Wrong shape or non-finite values.
    fn apply<'py>(&mut self, py: Python<'py>, pressure: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let grid = self.grid;
        read_field(pressure, "pressure", &grid, false, &mut self.scratch)?;
        let Self {
            inner, scratch, output, ..
        } = self;
        crate::pool::detached(py, || inner.apply(scratch, output))?;
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

/// The `material` argument, an `adhesim.Material`.
pub fn material_argument(value: &Bound<'_, PyAny>) -> PyResult<Material> {
    Ok(*crate::args::instance::<Material>(value, "material", "an adhesim.Material")?.get())
}

/// The `operator` argument, an `adhesim.HalfSpace`.
pub fn operator_argument(value: &Bound<'_, PyAny>) -> PyResult<Py<HalfSpace>> {
    Ok(crate::args::instance::<HalfSpace>(value, "operator", "an adhesim.HalfSpace")?.unbind())
}
