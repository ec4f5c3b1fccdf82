//! Python bindings of adhesim (the extension module `adhesim._adhesim`; the Python package
//! `adhesim` in `python/` re-exports it with docstrings, type stubs and numpy helpers).
//!
//! Numbers cross the boundary as float64 numpy arrays of shape (n, n), row-major like the
//! library's fields; every input is checked (shape, dtype, finiteness, ranges) and refused
//! with a `TypeError`/`ValueError` naming the argument and value, never a panic. Solves
//! release the GIL. The one-call runs (`adhesim.run`, `load`, `sweep`) go through the
//! scenario crate's pipeline (`scenario.rs`).

mod adhesive;
mod args;
mod cli;
mod convert;
mod grid;
mod objects;
mod pool;
mod reference;
mod scenario;
mod shapes;
mod solvers;
mod state;
mod surface;
mod sweep;
mod views;

use pyo3::prelude::*;

#[pymodule]
fn _adhesim(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("RESULTS_REVISION", adhesim::RESULTS_REVISION)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(cli::cli_main, m)?)?;
    m.add("SolveError", m.py().get_type::<convert::SolveError>())?;
    m.add("ScenarioError", m.py().get_type::<convert::ScenarioError>())?;
    m.add_class::<grid::Grid>()?;
    m.add_class::<objects::Material>()?;
    m.add_class::<objects::HalfSpace>()?;
    m.add_class::<state::ContactState>()?;
    m.add_class::<solvers::SolveReport>()?;
    m.add_class::<solvers::StepReport>()?;
    m.add_class::<solvers::Ccg>()?;
    m.add_class::<solvers::NestedActiveSet>()?;
    m.add_class::<adhesive::AdhesiveSolver>()?;
    m.add_function(wrap_pyfunction!(shapes::sphere_heights, m)?)?;
    m.add_function(wrap_pyfunction!(shapes::flat_punch_heights, m)?)?;
    m.add_function(wrap_pyfunction!(shapes::wavy_sphere_heights, m)?)?;
    m.add_function(wrap_pyfunction!(shapes::elliptic_punch_heights, m)?)?;
    m.add_function(wrap_pyfunction!(reference::_hertz, m)?)?;
    m.add_function(wrap_pyfunction!(reference::_jkr_curve, m)?)?;
    m.add_function(wrap_pyfunction!(reference::_jkr_at_depth, m)?)?;
    m.add_function(wrap_pyfunction!(reference::jkr_scales, m)?)?;
    m.add_function(wrap_pyfunction!(reference::_flat_punch, m)?)?;
    m.add_function(wrap_pyfunction!(reference::johnson_parameter, m)?)?;
    m.add_function(wrap_pyfunction!(reference::_fit_jkr_force, m)?)?;
    m.add_function(wrap_pyfunction!(reference::_fit_jkr_depth, m)?)?;
    m.add_function(wrap_pyfunction!(reference::_fit_power_law, m)?)?;
    m.add_class::<scenario::RunFields>()?;
    m.add_function(wrap_pyfunction!(scenario::_run_scenario, m)?)?;
    m.add_function(wrap_pyfunction!(scenario::_scenario_heights, m)?)?;
    m.add_function(wrap_pyfunction!(scenario::_curve_column_kinds, m)?)?;
    m.add_function(wrap_pyfunction!(scenario::_toml_value, m)?)?;
    m.add_function(wrap_pyfunction!(scenario::_toml_document, m)?)?;
    m.add_function(wrap_pyfunction!(scenario::_read_input_text, m)?)?;
    m.add_class::<sweep::SweepFolder>()?;
    m.add_function(wrap_pyfunction!(sweep::_sweep_open, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::_sweep_run_case, m)?)?;
    m.add_function(wrap_pyfunction!(surface::_self_affine, m)?)?;
    m.add_function(wrap_pyfunction!(surface::_height_map_statistics, m)?)?;
    m.add_function(wrap_pyfunction!(surface::_isotropic_psd, m)?)?;
    m.add_function(wrap_pyfunction!(surface::_fill_invalid, m)?)?;
    m.add_function(wrap_pyfunction!(surface::_read_topography, m)?)?;
    Ok(())
}
