//! Closed-form references and fits, evaluated by the library's own functions (so Python
//! and Rust give the same numbers, bit for bit). The `adhesim.reference` and
//! `adhesim.fit` Python modules wrap these with array conversion and docstrings.

use crate::convert::{non_negative, positive, read_vector};
use adhesim::analysis::fit;
use adhesim::analysis::reference::{FlatPunchReference, Hertz, Jkr};
use numpy::PyArray1;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

type Array<'py> = Bound<'py, PyArray1<f64>>;

fn hertz(radius: f64, contact_modulus: f64) -> PyResult<Hertz> {
    Ok(Hertz {
        radius: positive("radius", radius)?,
        contact_modulus: positive("contact_modulus", contact_modulus)?,
    })
}

fn jkr(radius: f64, contact_modulus: f64, work_of_adhesion: f64) -> PyResult<Jkr> {
    Ok(Jkr {
        radius: positive("radius", radius)?,
        contact_modulus: positive("contact_modulus", contact_modulus)?,
        work_of_adhesion: non_negative("work_of_adhesion", work_of_adhesion)?,
    })
}

fn finite_all(name: &str, values: &[f64]) -> PyResult<()> {
    match values.iter().position(|v| !v.is_finite()) {
        Some(k) => Err(PyValueError::new_err(format!(
            "{name}[{k}] must be finite, got {}",
            values[k]
        ))),
        None => Ok(()),
    }
}

/// `ValueError` where a closed form leaves double precision at some input: γ = 1e300 gave
/// −inf and NaN without a word. `inputs` names the arguments with their values.
fn finite_results(what: &str, inputs: &str, outputs: &[(&str, &[f64])]) -> PyResult<()> {
    for (name, values) in outputs {
        if let Some(k) = values.iter().position(|v| !v.is_finite()) {
            return Err(PyValueError::new_err(format!(
                "{what}: {name}[{k}] = {} leaves double precision; it comes from {inputs}: bring them to commensurate units",
                values[k]
            )));
        }
    }
    Ok(())
}

/// Hertz: (force, contact_radius) at each depth.
#[pyfunction]
pub fn _hertz<'py>(
    py: Python<'py>,
    radius: f64,
    contact_modulus: f64,
    depth: &Bound<'py, PyAny>,
) -> PyResult<(Array<'py>, Array<'py>)> {
    let model = hertz(radius, contact_modulus)?;
    let depth = read_vector(depth, "depth")?;
    finite_all("depth", &depth)?;
    let force: Vec<f64> = depth.iter().map(|&d| model.force(d)).collect();
    let contact_radius: Vec<f64> = depth.iter().map(|&d| model.contact_radius(d)).collect();
    finite_results(
        "hertz",
        &format!("radius = {radius:e}, contact_modulus = {contact_modulus:e} and the depths"),
        &[("force", &force), ("contact_radius", &contact_radius)],
    )?;
    Ok((PyArray1::from_vec(py, force), PyArray1::from_vec(py, contact_radius)))
}

/// JKR parametric in the contact radius: (force, depth) at each a.
#[pyfunction]
pub fn _jkr_curve<'py>(
    py: Python<'py>,
    radius: f64,
    contact_modulus: f64,
    work_of_adhesion: f64,
    contact_radius: &Bound<'py, PyAny>,
) -> PyResult<(Array<'py>, Array<'py>)> {
    let model = jkr(radius, contact_modulus, work_of_adhesion)?;
    let a = read_vector(contact_radius, "contact_radius")?;
    if let Some(k) = a.iter().position(|v| !(v.is_finite() && *v >= 0.0)) {
        return Err(PyValueError::new_err(format!(
            "contact_radius[{k}] must be finite and >= 0, got {}",
            a[k]
        )));
    }
    let force: Vec<f64> = a.iter().map(|&a| model.force(a)).collect();
    let depth: Vec<f64> = a.iter().map(|&a| model.depth(a)).collect();
    finite_results(
        "jkr",
        &format!("radius = {radius:e}, contact_modulus = {contact_modulus:e}, work_of_adhesion = {work_of_adhesion:e} and the contact radii"),
        &[("force", &force), ("depth", &depth)],
    )?;
    Ok((PyArray1::from_vec(py, force), PyArray1::from_vec(py, depth)))
}

/// JKR on the branch stable under displacement control: (force, contact_radius,
/// in_contact) at each depth; force and radius 0 below the pull-off jump depth.
#[pyfunction]
pub fn _jkr_at_depth<'py>(
    py: Python<'py>,
    radius: f64,
    contact_modulus: f64,
    work_of_adhesion: f64,
    depth: &Bound<'py, PyAny>,
) -> PyResult<(Array<'py>, Array<'py>, Bound<'py, PyArray1<bool>>)> {
    let model = jkr(radius, contact_modulus, work_of_adhesion)?;
    let depth = read_vector(depth, "depth")?;
    finite_all("depth", &depth)?;
    let radii: Vec<Option<f64>> = depth.iter().map(|&d| model.radius_at_depth(d)).collect();
    let force: Vec<f64> = radii.iter().map(|a| a.map_or(0.0, |a| model.force(a))).collect();
    let contact = radii.iter().map(|a| a.is_some()).collect();
    let radius_values: Vec<f64> = radii.iter().map(|a| a.unwrap_or(0.0)).collect();
    finite_results(
        "jkr_at_depth",
        &format!("radius = {radius:e}, contact_modulus = {contact_modulus:e}, work_of_adhesion = {work_of_adhesion:e} and the depths"),
        &[("force", &force), ("contact_radius", &radius_values)],
    )?;
    Ok((
        PyArray1::from_vec(py, force),
        PyArray1::from_vec(py, radius_values),
        PyArray1::from_vec(py, contact),
    ))
}

/// JKR scales (signed): pull-off force F_JKR = −(3/2)πγR under load control (< 0,
/// tensile), the depth d_JKR = −(3π²γ²R/(64E*²))^{1/3} and contact radius
/// a_JKR = (9πγR²/(8E*))^{1/3} at that point, and the depth −9^{1/3}|d_JKR| of the jump
/// out of contact under displacement control.
///
/// Returns
/// -------
/// dict
///     Keys force, depth, contact_radius, jump_depth.
#[pyfunction]
pub fn jkr_scales<'py>(
    py: Python<'py>,
    radius: f64,
    contact_modulus: f64,
    work_of_adhesion: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let model = jkr(radius, contact_modulus, work_of_adhesion)?;
    let jump_depth = -9f64.cbrt() * model.critical_depth().abs();
    let scales = [
        model.critical_force(),
        model.critical_depth(),
        model.critical_radius(),
        jump_depth,
    ];
    finite_results(
        "jkr_scales",
        &format!("radius = {radius:e}, contact_modulus = {contact_modulus:e}, work_of_adhesion = {work_of_adhesion:e}"),
        &[("[force, depth, contact_radius, jump_depth]", &scales)],
    )?;
    let dict = PyDict::new(py);
    dict.set_item("force", model.critical_force())?;
    dict.set_item("depth", model.critical_depth())?;
    dict.set_item("contact_radius", model.critical_radius())?;
    dict.set_item("jump_depth", -9f64.cbrt() * model.critical_depth().abs())?;
    Ok(dict)
}

/// Flat punch: (stiffness 2E*a, Kendall pull-off force, Kendall pull-off depth); the last
/// two 0 when γ = 0.
#[pyfunction]
pub fn _flat_punch(radius: f64, contact_modulus: f64, work_of_adhesion: f64) -> PyResult<(f64, f64, f64)> {
    let model = FlatPunchReference {
        radius: positive("radius", radius)?,
        contact_modulus: positive("contact_modulus", contact_modulus)?,
    };
    let gamma = non_negative("work_of_adhesion", work_of_adhesion)?;
    Ok((
        model.stiffness(),
        model.kendall_force(gamma),
        model.kendall_depth(gamma),
    ))
}

/// Johnson parameter α = √(2λγ/(π²h²E*)) of a wavy surface (Johnson 1995; Popov et al.
/// 2021, Eq. 5): wavelength λ > 0, amplitude h > 0, work of adhesion γ ≥ 0, contact
/// modulus E* > 0. Dimensionless; α > 1 (about) means the waviness is flattened by
/// adhesion.
#[pyfunction]
pub fn johnson_parameter(
    #[pyo3(from_py_with = crate::args::number::wavelength)] wavelength: f64,
    #[pyo3(from_py_with = crate::args::number::amplitude)] amplitude: f64,
    #[pyo3(from_py_with = crate::args::number::work_of_adhesion)] work_of_adhesion: f64,
    #[pyo3(from_py_with = crate::args::number::contact_modulus)] contact_modulus: f64,
) -> PyResult<f64> {
    Ok(adhesim::analysis::reference::johnson_parameter(
        positive("wavelength", wavelength)?,
        positive("amplitude", amplitude)?,
        non_negative("work_of_adhesion", work_of_adhesion)?,
        positive("contact_modulus", contact_modulus)?,
    ))
}

fn pairs(x: &Bound<'_, PyAny>, x_name: &str, y: &Bound<'_, PyAny>, y_name: &str) -> PyResult<Vec<(f64, f64)>> {
    let (x, y) = (read_vector(x, x_name)?, read_vector(y, y_name)?);
    if x.len() != y.len() {
        return Err(PyValueError::new_err(format!(
            "{x_name} and {y_name} must have the same length, got {} and {}",
            x.len(),
            y.len()
        )));
    }
    // A NaN or inf point would make the fitted value NaN, or be dropped in silence.
    for (name, values) in [(x_name, &x), (y_name, &y)] {
        if let Some(index) = values.iter().position(|v| !v.is_finite()) {
            return Err(PyValueError::new_err(format!(
                "{name} must hold finite numbers, got {} at index {index}",
                values[index]
            )));
        }
    }
    Ok(x.into_iter().zip(y).collect())
}

fn fit_dict<'py>(py: Python<'py>, result: Option<fit::JkrFit>, what: &str) -> PyResult<Bound<'py, PyDict>> {
    let Some(result) = result else {
        return Err(PyValueError::new_err(format!(
            "{what}: no point with a finite, positive contact radius to fit"
        )));
    };
    let dict = PyDict::new(py);
    dict.set_item("work_of_adhesion", result.work_of_adhesion)?;
    dict.set_item("residual_rms", result.residual_rms)?;
    dict.set_item("points", result.points)?;
    Ok(dict)
}

/// Least-squares JKR fit of γ to force–contact-radius pairs of one branch.
#[pyfunction]
pub fn _fit_jkr_force<'py>(
    py: Python<'py>,
    contact_radius: &Bound<'py, PyAny>,
    force: &Bound<'py, PyAny>,
    radius: f64,
    contact_modulus: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let points = pairs(contact_radius, "contact_radius", force, "force")?;
    let result = fit::fit_jkr_work_of_adhesion(
        &points,
        positive("radius", radius)?,
        positive("contact_modulus", contact_modulus)?,
    );
    fit_dict(py, result, "jkr_work_of_adhesion")
}

/// JKR fit of γ to depth–contact-radius pairs (paper Eq. 13).
#[pyfunction]
pub fn _fit_jkr_depth<'py>(
    py: Python<'py>,
    contact_radius: &Bound<'py, PyAny>,
    depth: &Bound<'py, PyAny>,
    radius: f64,
    contact_modulus: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let points = pairs(contact_radius, "contact_radius", depth, "depth")?;
    let result = fit::fit_jkr_depth_work_of_adhesion(
        &points,
        positive("radius", radius)?,
        positive("contact_modulus", contact_modulus)?,
    );
    fit_dict(py, result, "jkr_depth_work_of_adhesion")
}

/// Power law y = c·t^n by least squares in log–log: (c, n).
#[pyfunction]
pub fn _fit_power_law(t: &Bound<'_, PyAny>, y: &Bound<'_, PyAny>) -> PyResult<(f64, f64)> {
    let points = pairs(t, "t", y, "y")?;
    fit::fit_power_law(&points)
        .ok_or_else(|| PyValueError::new_err("power_law: fewer than two points with t > 0 and y > 0"))
}
