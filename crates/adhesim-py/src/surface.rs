//! The rough path from Python: the self-affine generator (`adhesim::surface::SelfAffine`),
//! the statistics and PSD of any height map (`adhesim::surface::HeightMap`: a rectangle with
//! its own spacings and invalid points), the harmonic filling of invalid points, and
//! `adhesim_topography::read_topography`. The Python module `adhesim.surface` and
//! `adhesim.read_topography` wrap these with docstrings.

use crate::convert::{positive, value_error};
use crate::grid::Grid;
use adhesim::surface::{fill_invalid_harmonic, Amplitudes, HeightMap, RmsTarget, SelfAffine};
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Draws a random self-affine surface on `grid` (exactly one of rms_height and rms_slope);
/// the heights as an (n, n) array.
#[pyfunction]
#[pyo3(signature = (grid, hurst, seed, rms_height=None, rms_slope=None, rolloff_wavelength=None, cutoff_wavelength=None, mode="random_phase"))]
#[allow(clippy::too_many_arguments)]
pub fn _self_affine<'py>(
    py: Python<'py>,
    grid: Grid,
    hurst: f64,
    seed: u64,
    rms_height: Option<f64>,
    rms_slope: Option<f64>,
    rolloff_wavelength: Option<f64>,
    cutoff_wavelength: Option<f64>,
    mode: &str,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let target = match (rms_height, rms_slope) {
        (Some(h), None) => RmsTarget::Height(positive("rms_height", h)?),
        (None, Some(s)) => RmsTarget::Slope(positive("rms_slope", s)?),
        (h, s) => {
            return Err(PyValueError::new_err(format!(
                "give exactly one of rms_height and rms_slope, got rms_height = {h:?}, rms_slope = {s:?}"
            )))
        }
    };
    let amplitudes = match mode {
        "random_phase" => Amplitudes::RandomPhase,
        "filtered" => Amplitudes::Filtered,
        other => {
            return Err(PyValueError::new_err(format!(
                "mode must be \"random_phase\" or \"filtered\", got {other:?}"
            )))
        }
    };
    let mut generator = SelfAffine::new(hurst, target).with_amplitudes(amplitudes);
    if let Some(wavelength) = rolloff_wavelength {
        generator = generator.with_rolloff_wavelength(positive("rolloff_wavelength", wavelength)?);
    }
    if let Some(wavelength) = cutoff_wavelength {
        generator = generator.with_cutoff_wavelength(positive("cutoff_wavelength", wavelength)?);
    }
    let surface = py
        .detach(|| generator.generate(&grid.inner, seed))
        .map_err(value_error)?;
    PyArray1::from_slice(py, &surface.heights).reshape([grid.inner.ny(), grid.inner.nx()])
}

/// A height map copied from numpy: (ny, nx), row-major values, an optional validity mask.
struct MapData {
    ny: usize,
    nx: usize,
    values: Vec<f64>,
    mask: Option<Vec<bool>>,
}

/// A 2-D float64 array and a bool mask of the same shape.
fn read_map(heights: &PyReadonlyArray2<'_, f64>, valid: Option<&PyReadonlyArray2<'_, bool>>) -> PyResult<MapData> {
    let shape = heights.shape();
    let (ny, nx) = (shape[0], shape[1]);
    let values: Vec<f64> = heights.as_array().iter().copied().collect();
    let mask = match valid {
        None => None,
        Some(mask) if mask.shape() != shape => {
            return Err(PyValueError::new_err(format!(
                "valid must have the shape of heights {shape:?}, got {:?}",
                mask.shape()
            )))
        }
        Some(mask) => Some(mask.as_array().iter().copied().collect()),
    };
    Ok(MapData { ny, nx, values, mask })
}

/// rms height, finite-difference and (periodic, fully valid maps) spectral rms slope and
/// curvature of a map of shape (ny, nx) with spacings (dx, dy), invalid points left out.
#[pyfunction]
#[pyo3(signature = (heights, dx, dy, valid=None, periodic=false))]
pub fn _height_map_statistics<'py>(
    py: Python<'py>,
    heights: PyReadonlyArray2<'py, f64>,
    dx: f64,
    dy: f64,
    valid: Option<PyReadonlyArray2<'py, bool>>,
    periodic: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let MapData { ny, nx, values, mask } = read_map(&heights, valid.as_ref())?;
    let map = HeightMap::new((nx, ny), (dx, dy), &values, mask.as_deref(), periodic).map_err(value_error)?;
    let result = PyDict::new(py);
    result.set_item("rms_height", map.rms_height())?;
    result.set_item("rms_slope_finite_differences", map.rms_slope_finite_differences())?;
    result.set_item(
        "rms_curvature_finite_differences",
        map.rms_curvature_finite_differences(),
    )?;
    let spectral = map.spectral_slope_and_curvature();
    result.set_item("rms_slope_spectral", spectral.map(|s| s.0))?;
    result.set_item("rms_curvature_spectral", spectral.map(|s| s.1))?;
    result.set_item("valid_points", map.valid_count())?;
    Ok(result)
}

/// The isotropic PSD in `bins` logarithmic bins: (q_low, q_high, q, psd, modes) arrays.
#[pyfunction]
#[pyo3(signature = (heights, dx, dy, bins, valid=None, periodic=false))]
pub fn _isotropic_psd<'py>(
    py: Python<'py>,
    heights: PyReadonlyArray2<'py, f64>,
    dx: f64,
    dy: f64,
    bins: usize,
    valid: Option<PyReadonlyArray2<'py, bool>>,
    periodic: bool,
) -> PyResult<Vec<Bound<'py, PyArray1<f64>>>> {
    let max_bins = adhesim::surface::MAX_PSD_BINS;
    if !(1..=max_bins).contains(&bins) {
        return Err(PyValueError::new_err(format!(
            "bins must be an integer 1 … {max_bins}, got {bins}"
        )));
    }
    crate::convert::fits_in_memory(
        &format!("psd(bins={bins})"),
        bins as u128 * adhesim_scenario::memory::PSD_BYTES_PER_BIN,
    )?;
    let MapData { ny, nx, values, mask } = read_map(&heights, valid.as_ref())?;
    let map = HeightMap::new((nx, ny), (dx, dy), &values, mask.as_deref(), periodic).map_err(value_error)?;
    let psd = map.isotropic_psd(bins).map_err(value_error)?;
    let column =
        |f: &dyn Fn(&adhesim::surface::PsdBin) -> f64| PyArray1::from_vec(py, psd.iter().map(f).collect::<Vec<f64>>());
    Ok(vec![
        column(&|b| b.edges.0),
        column(&|b| b.edges.1),
        column(&|b| b.wavevector),
        column(&|b| b.psd),
        column(&|b| b.modes as f64),
    ])
}

/// The heights with the invalid points (false in `valid`) filled by harmonic interpolation.
#[pyfunction]
#[pyo3(signature = (heights, valid, periodic=false))]
pub fn _fill_invalid<'py>(
    py: Python<'py>,
    heights: PyReadonlyArray2<'py, f64>,
    valid: PyReadonlyArray2<'py, bool>,
    periodic: bool,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let MapData { ny, nx, values, mask } = read_map(&heights, Some(&valid))?;
    let mask = mask.unwrap_or_default();
    let filled = py
        .detach(|| fill_invalid_harmonic((nx, ny), &values, &mask, periodic))
        .map_err(value_error)?;
    PyArray1::from_slice(py, &filled).reshape([ny, nx])
}

/// Reads an instrument file: a dict of heights (ny, nx; NaN at invalid points), valid
/// (bool, ny × nx), dx, dy (metres), x_offset, y_offset, channel, height_unit, lateral_unit,
/// format, metadata.
#[pyfunction]
#[pyo3(signature = (path, channel=None, spacing=None, height_unit=None, lateral_unit=None))]
pub fn _read_topography<'py>(
    py: Python<'py>,
    path: std::path::PathBuf,
    channel: Option<String>,
    spacing: Option<(f64, f64)>,
    height_unit: Option<String>,
    lateral_unit: Option<String>,
) -> PyResult<Bound<'py, PyDict>> {
    // A FIFO blocked forever, a device read without end: refused by name as on the
    // command line, as is a file larger than the memory available.
    if !path.exists() {
        return Err(pyo3::exceptions::PyFileNotFoundError::new_err(format!(
            "path: {} does not exist",
            path.display()
        )));
    }
    adhesim_scenario::check_regular_file(&path, "path")
        .map_err(|e| PyValueError::new_err(adhesim_scenario::error_text::error_line(e.chain())))?;
    if let Some((dx, dy)) = spacing {
        positive("spacing[0]", dx)?;
        positive("spacing[1]", dy)?;
    }
    let options = adhesim_topography::ReadOptions {
        channel,
        spacing,
        height_unit,
        lateral_unit,
    };
    let map = adhesim_topography::read_topography(&path, &options).map_err(|e| match e {
        adhesim_topography::TopographyError::Io { .. } => PyOSError::new_err(e.to_string()),
        adhesim_topography::TopographyError::MissingOption { option, .. } => {
            PyValueError::new_err(format!("{e}; give {option}="))
        }
        other => value_error(other),
    })?;
    let valid = map.mask.clone().unwrap_or_else(|| vec![true; map.heights.len()]);
    let heights: Vec<f64> = map
        .heights
        .iter()
        .zip(&valid)
        .map(|(&h, &v)| if v { h } else { f64::NAN })
        .collect();
    let result = PyDict::new(py);
    result.set_item("heights", PyArray1::from_vec(py, heights).reshape([map.ny, map.nx])?)?;
    result.set_item("valid", PyArray1::from_vec(py, valid).reshape([map.ny, map.nx])?)?;
    result.set_item("dx", map.dx)?;
    result.set_item("dy", map.dy)?;
    result.set_item("x_offset", map.x_offset)?;
    result.set_item("y_offset", map.y_offset)?;
    result.set_item("channel", &map.channel)?;
    result.set_item("height_unit", &map.height_unit)?;
    result.set_item("lateral_unit", &map.lateral_unit)?;
    result.set_item("format", map.format)?;
    result.set_item("metadata", &map.metadata)?;
    Ok(result)
}
