//! Heights of the scenario file's analytic indenter shapes on a grid, as float64 arrays of
//! shape (ny, nx): the functions behind `adhesim.geometry`.

use crate::convert::{elements, field, fits_in_memory, value_error};
use crate::grid::{describe, Grid};
use adhesim::Profile;
use numpy::PyArray2;
use pyo3::prelude::*;

/// Heights z = (x² + y²)/(2R) of a sphere (paraboloid) of radius R at the element centres,
/// axis at the origin; shape (ny, nx).
#[pyfunction]
pub fn sphere_heights<'py>(
    py: Python<'py>,
    #[pyo3(from_py_with = crate::grid::grid_argument)] grid: Grid,
    #[pyo3(from_py_with = crate::args::number::radius)] radius: f64,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let sphere = adhesim::Sphere::new(radius).map_err(value_error)?;
    fits_in_memory(
        &format!("sphere_heights({})", describe(&grid.inner)),
        elements(&grid.inner) * 16,
    )?;
    field(py, &sphere.heights(&grid.inner), &grid.inner)
}

/// Heights of a flat circular punch of radius a: 0 on the face, +inf outside (no surface
/// there: those elements never touch); shape (ny, nx).
#[pyfunction]
pub fn flat_punch_heights<'py>(
    py: Python<'py>,
    #[pyo3(from_py_with = crate::grid::grid_argument)] grid: Grid,
    #[pyo3(from_py_with = crate::args::number::radius)] radius: f64,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let punch = adhesim::FlatPunch::new(radius).map_err(value_error)?;
    fits_in_memory(
        &format!("flat_punch_heights({})", describe(&grid.inner)),
        elements(&grid.inner) * 16,
    )?;
    field(py, &punch.heights(&grid.inner), &grid.inner)
}

/// Heights of the paper's wavy sphere (Eq. 1), z = (x² + y²)/(2R) + h·sin(2πx′/λ)·sin(2πy′/λ)
/// with the waviness rotated by `angle_degrees`, measured from the paraboloid's apex (the
/// scenario file's `wavy_sphere`); shape (ny, nx).
#[pyfunction]
pub fn wavy_sphere_heights<'py>(
    py: Python<'py>,
    #[pyo3(from_py_with = crate::grid::grid_argument)] grid: Grid,
    #[pyo3(from_py_with = crate::args::number::radius)] radius: f64,
    #[pyo3(from_py_with = crate::args::number::amplitude)] amplitude: f64,
    #[pyo3(from_py_with = crate::args::number::wavelength)] wavelength: f64,
    #[pyo3(from_py_with = crate::args::number::angle_degrees)] angle_degrees: f64,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let angle = crate::convert::finite("angle", angle_degrees)?.to_radians();
    let profile = adhesim::WavySphere::new(radius, amplitude, wavelength, angle).map_err(value_error)?;
    fits_in_memory(
        &format!("wavy_sphere_heights({})", describe(&grid.inner)),
        elements(&grid.inner) * 16,
    )?;
    field(py, &profile.heights(&grid.inner), &grid.inner)
}

/// Heights of a flat punch with an elliptic face of semi-axes (a, b) rotated by
/// `angle_degrees`: 0 on the face, +inf outside (the scenario file's `elliptic_punch`);
/// shape (ny, nx).
#[pyfunction]
pub fn elliptic_punch_heights<'py>(
    py: Python<'py>,
    #[pyo3(from_py_with = crate::grid::grid_argument)] grid: Grid,
    #[pyo3(from_py_with = crate::args::pair::semi_axes)] semi_axes: (f64, f64),
    #[pyo3(from_py_with = crate::args::number::angle_degrees)] angle_degrees: f64,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let angle = crate::convert::finite("angle", angle_degrees)?.to_radians();
    let punch = adhesim::EllipticPunch::new(semi_axes, angle).map_err(value_error)?;
    fits_in_memory(
        &format!("elliptic_punch_heights({})", describe(&grid.inner)),
        elements(&grid.inner) * 16,
    )?;
    field(py, &punch.heights(&grid.inner), &grid.inner)
}
