//! The contact solvers on numpy heights: non-adhesive (Polonsky–Keer CCG, nested active
//! set) and adhesive (JKR-type active set with its quasi-static step API).
//!
//! Each solver keeps a reference to its `HalfSpace` and copies the heights into a buffer
//! it owns (reused from call to call), then releases the GIL for the solve.

use crate::convert::{count, finite, positive, read_field, solve_error};
use crate::objects::HalfSpace;
use crate::state::ContactState;
use adhesim::{Boundary, Control};
use numpy::PyArray1;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// What a non-adhesive solve did.
#[pyclass(module = "adhesim._adhesim", frozen, get_all)]
pub struct SolveReport {
    /// Iterations of the (outer) solver.
    iterations: usize,
    /// Final convergence measure (solver specific, relative).
    residual: f64,
    /// Number of elements in contact.
    contact_elements: usize,
    /// Real contact area Δ²·|C|.
    contact_area: f64,
    /// Normal force F = Δ²·Σp (> 0 compressive).
    force: f64,
    /// Indentation depth d (> 0 into the body): prescribed, or found under load control.
    depth: f64,
    /// Elastic operator applications (FFT pairs) spent.
    operator_applications: u64,
    /// The state solved (the object passed in, updated in place, or a new one).
    state: Py<ContactState>,
}

#[pymethods]
impl SolveReport {
    fn __repr__(&self) -> String {
        format!(
            "SolveReport(force={:e}, depth={:e}, contact_elements={}, iterations={}, residual={:.3e})",
            self.force, self.depth, self.contact_elements, self.iterations, self.residual
        )
    }
}

/// The state to solve: the one given (checked against the grid) or a new one.
fn state_for(py: Python<'_>, state: Option<Py<ContactState>>, grid: &adhesim::Grid) -> PyResult<Py<ContactState>> {
    match state {
        Some(state) => {
            state.borrow(py).check_grid(grid)?;
            Ok(state)
        }
        None => Py::new(py, ContactState::fresh(*grid)),
    }
}

/// Runs a non-adhesive `solve` on the operator and the state with the GIL released, then
/// records the heights and depth in the state (for its `gap`) and reports.
fn solve_released<F>(
    py: Python<'_>,
    operator: &Py<HalfSpace>,
    heights: &[f64],
    state: Py<ContactState>,
    solve: F,
) -> PyResult<SolveReport>
where
    F: Send
        + FnOnce(
            &mut adhesim::HalfSpace,
            &[f64],
            &mut adhesim::ContactState,
        ) -> Result<adhesim::SolveReport, adhesim::SolveError>,
{
    let mut operator = operator.bind(py).try_borrow_mut()?;
    let mut guard = state.bind(py).try_borrow_mut()?;
    let (op, st) = (&mut operator.inner, guard.fields_mut());
    let report = crate::pool::detached(py, || solve(op, heights, st))?.map_err(solve_error)?;
    guard.record(heights, report.depth);
    drop(guard);
    Ok(solve_report(report, state))
}

fn solve_report(report: adhesim::SolveReport, state: Py<ContactState>) -> SolveReport {
    SolveReport {
        iterations: report.iterations,
        residual: report.residual,
        contact_elements: report.contact_elements,
        contact_area: report.contact_area,
        force: report.force,
        depth: report.depth,
        operator_applications: report.operator_applications,
        state,
    }
}

/// Non-adhesive frictionless normal contact by constrained conjugate gradients
/// (Polonsky & Keer 1999, Wear 231, 206–219), on free and periodic grids.
///
/// Parameters
/// ----------
/// operator
///     the HalfSpace of the grid.
/// tolerance
///     stop when Σ|p_new − p_old|/Σ|p| < tolerance.
/// max_iterations
///     iteration limit; reaching it raises SolveError.
///
/// The defaults are the Rust library's (`CcgParams::default()`): `Ccg.defaults()` lists
/// them.
#[pyclass(module = "adhesim._adhesim")]
pub struct Ccg {
    inner: adhesim::Ccg,
    params: adhesim::CcgParams,
    operator: Py<HalfSpace>,
    grid: adhesim::Grid,
    heights: Vec<f64>,
}

#[pymethods]
impl Ccg {
    #[new]
    #[pyo3(signature = (
        operator, tolerance = adhesim::CcgParams::default().tolerance,
        max_iterations = adhesim::CcgParams::default().max_iterations as i64
    ))]
    fn new(
        py: Python<'_>,
        #[pyo3(from_py_with = crate::objects::operator_argument)] operator: Py<HalfSpace>,
        #[pyo3(from_py_with = crate::args::number::tolerance)] tolerance: f64,
        #[pyo3(from_py_with = crate::args::integer::max_iterations)] max_iterations: i64,
    ) -> PyResult<Self> {
        let params = adhesim::CcgParams {
            tolerance: positive("tolerance", tolerance)?,
            max_iterations: count("max_iterations", max_iterations, 1)?,
            ..adhesim::CcgParams::default()
        };
        let grid = operator.borrow(py).grid;
        Ok(Self {
            inner: adhesim::Ccg::new(params),
            params,
            operator,
            grid,
            heights: Vec::with_capacity(grid.len()),
        })
    }

    /// Solves p ≥ 0, g ≥ 0, p·g = 0 for indenter heights z under displacement or load
    /// control (exactly one of `depth`, `load`).
    ///
    /// Parameters
    /// ----------
    /// heights
    ///     float64 (n, n), indenter heights z above its reference point; +inf
    ///     where there is no surface.
    /// depth
    ///     indentation depth d (> 0 into the body). On a periodic grid it controls
    ///     the mean gap (K̂(0) = 0).
    /// load
    ///     normal force F > 0 (compressive) instead of a depth.
    /// state
    ///     ContactState warm start, updated in place; None starts from no contact.
    ///
    /// Returns
    /// -------
    /// SolveReport
    ///     With `.state` the solved state.
    ///
    /// Raises
    /// ------
    /// ValueError
    ///     bad heights, both or neither of depth/load, a non-positive load.
    /// SolveError
    ///     no convergence within max_iterations (the state then holds the
    ///     last iterate: start the next solve from a fresh ContactState).
    #[pyo3(signature = (heights, depth = None, load = None, state = None))]
    fn solve(
        &mut self,
        py: Python<'_>,
        heights: &Bound<'_, PyAny>,
        #[pyo3(from_py_with = crate::args::optional_number::depth)] depth: Option<f64>,
        #[pyo3(from_py_with = crate::args::optional_number::load)] load: Option<f64>,
        #[pyo3(from_py_with = crate::state::state_argument)] state: Option<Py<ContactState>>,
    ) -> PyResult<SolveReport> {
        let control = match (depth, load) {
            (Some(depth), None) => Control::Displacement(finite("depth", depth)?),
            (None, Some(load)) => Control::Load(positive("load", load)?),
            _ => {
                return Err(PyValueError::new_err(format!(
                    "give exactly one of depth and load, got depth={depth:?}, load={load:?}"
                )))
            }
        };
        read_field(heights, "heights", &self.grid, true, &mut self.heights)?;
        let state = state_for(py, state, &self.grid)?;
        let solver = &mut self.inner;
        solve_released(py, &self.operator, &self.heights, state, |op, heights, st| {
            solver.solve(op, heights, control, st)
        })
    }

    /// The default parameters, from the Rust library's `CcgParams::default()`.
    #[staticmethod]
    fn defaults(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
        let p = adhesim::CcgParams::default();
        let dict = PyDict::new(py);
        dict.set_item("tolerance", p.tolerance)?;
        dict.set_item("max_iterations", p.max_iterations)?;
        Ok(dict)
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        format!(
            "Ccg({}, tolerance={:?}, max_iterations={})",
            operator_repr(py, &self.operator),
            self.params.tolerance,
            self.params.max_iterations
        )
    }
}

/// The repr of a solver's operator (its grid and modulus), or `HalfSpace(...)` while a
/// solve in another thread holds it.
pub fn operator_repr(py: Python<'_>, operator: &Py<HalfSpace>) -> String {
    operator
        .bind(py)
        .try_borrow()
        .map_or_else(|_| "HalfSpace(...)".to_string(), |op| op.__repr__())
}

/// Non-adhesive contact by a preconditioned active set on nested grids (coarse-to-fine
/// continuation; Brandt & Lubrecht 1990), under displacement control on free grids.
///
/// Parameters
/// ----------
/// operator
///     the HalfSpace of a free grid.
/// relative_tolerance
///     converged when ‖d − z − u‖_C ≤ this·‖d − z‖_C on a contact set
///     that no longer changes.
/// max_cg_iterations
///     CG iterations per active-set round.
/// max_rounds
///     active-set rounds per grid level.
/// coarsest
///     coarsest grid of the continuation (above n disables it).
///
/// The defaults are the Rust library's (`NestedParams::default()`):
/// `NestedActiveSet.defaults()` lists them.
///
/// Raises
/// ------
/// ValueError
///     a periodic grid (use Ccg) or a bad parameter.
#[pyclass(module = "adhesim._adhesim")]
pub struct NestedActiveSet {
    inner: adhesim::NestedActiveSet,
    params: adhesim::NestedParams,
    operator: Py<HalfSpace>,
    grid: adhesim::Grid,
    heights: Vec<f64>,
}

#[pymethods]
impl NestedActiveSet {
    #[new]
    #[pyo3(signature = (
        operator, relative_tolerance = adhesim::NestedParams::default().relative_tolerance,
        max_cg_iterations = adhesim::NestedParams::default().max_cg_iterations as i64,
        max_rounds = adhesim::NestedParams::default().max_rounds as i64,
        coarsest = adhesim::NestedParams::default().coarsest as i64
    ))]
    fn new(
        py: Python<'_>,
        #[pyo3(from_py_with = crate::objects::operator_argument)] operator: Py<HalfSpace>,
        #[pyo3(from_py_with = crate::args::number::relative_tolerance)] relative_tolerance: f64,
        #[pyo3(from_py_with = crate::args::integer::max_cg_iterations)] max_cg_iterations: i64,
        #[pyo3(from_py_with = crate::args::integer::max_rounds)] max_rounds: i64,
        #[pyo3(from_py_with = crate::args::integer::coarsest)] coarsest: i64,
    ) -> PyResult<Self> {
        let params = adhesim::NestedParams {
            relative_tolerance: positive("relative_tolerance", relative_tolerance)?,
            max_cg_iterations: count("max_cg_iterations", max_cg_iterations, 1)?,
            max_rounds: count("max_rounds", max_rounds, 1)?,
            coarsest: count("coarsest", coarsest, 2)?,
            ..adhesim::NestedParams::default()
        };
        let (grid, material) = {
            let op = operator.borrow(py);
            (op.grid, op.material)
        };
        if grid.boundary() != Boundary::Free {
            return Err(PyValueError::new_err(
                "NestedActiveSet solves free grids only (operator has a periodic grid: use Ccg)",
            ));
        }
        let inner = crate::pool::detached(py, || adhesim::NestedActiveSet::new(grid, material, params))?;
        Ok(Self {
            inner,
            params,
            operator,
            grid,
            heights: Vec::with_capacity(grid.len()),
        })
    }

    /// Solves at indentation `depth` (> 0 into the body). A `state` with contact is the
    /// warm start (no continuation); otherwise coarse grids supply the first contact set.
    ///
    /// Parameters
    /// ----------
    /// heights
    ///     float64 (n, n) indenter heights z; +inf where there is no surface.
    /// depth
    ///     indentation depth d.
    /// state
    ///     ContactState, updated in place; None starts from no contact.
    ///
    /// Returns
    /// -------
    /// SolveReport
    ///     With `.state` the solved state.
    ///
    /// Raises
    /// ------
    /// ValueError
    ///     bad heights or depth.
    /// SolveError
    ///     no convergence (the state then holds the last iterate).
    #[pyo3(signature = (heights, depth, state = None))]
    fn solve(
        &mut self,
        py: Python<'_>,
        heights: &Bound<'_, PyAny>,
        #[pyo3(from_py_with = crate::args::number::depth)] depth: f64,
        #[pyo3(from_py_with = crate::state::state_argument)] state: Option<Py<ContactState>>,
    ) -> PyResult<SolveReport> {
        let depth = finite("depth", depth)?;
        read_field(heights, "heights", &self.grid, true, &mut self.heights)?;
        let state = state_for(py, state, &self.grid)?;
        let solver = &mut self.inner;
        solve_released(py, &self.operator, &self.heights, state, |op, heights, st| {
            solver.solve(op, heights, depth, st)
        })
    }

    /// The default parameters, from the Rust library's `NestedParams::default()`.
    #[staticmethod]
    fn defaults(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
        let p = adhesim::NestedParams::default();
        let dict = PyDict::new(py);
        dict.set_item("relative_tolerance", p.relative_tolerance)?;
        dict.set_item("max_cg_iterations", p.max_cg_iterations)?;
        dict.set_item("max_rounds", p.max_rounds)?;
        dict.set_item("coarsest", p.coarsest)?;
        Ok(dict)
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        let p = &self.params;
        format!(
            "NestedActiveSet({}, relative_tolerance={:?}, max_cg_iterations={}, max_rounds={}, coarsest={})",
            operator_repr(py, &self.operator),
            p.relative_tolerance,
            p.max_cg_iterations,
            p.max_rounds,
            p.coarsest
        )
    }

    /// Grid levels below the fine one used by the continuation.
    #[getter]
    fn coarse_levels(&self) -> usize {
        self.inner.coarse_levels()
    }
}

/// What one quasi-static adhesive step did.
#[pyclass(module = "adhesim._adhesim", frozen, get_all)]
#[derive(Clone, Copy)]
pub struct StepReport {
    /// Indentation depth d of the step (> 0 into the body).
    depth: f64,
    /// Normal force F = Δ²·Σp at the end of the step (> 0 compressive, < 0 tensile).
    force: f64,
    /// Force after the first solve with the previous contact set.
    force_before_change: f64,
    /// Elements in contact at the end of the step.
    contact_elements: usize,
    /// Elements that joined the contact in this step.
    attached: usize,
    /// Elements that left the contact in this step.
    detached: usize,
    /// Energy Π = ½Δ²Σp·u − Δ²Σ_C γ at the end of the step.
    energy: f64,
    /// Π after the first solve with the previous contact set.
    energy_before_change: f64,
    /// Energy released by the configuration change, Π_before − Π_end.
    dissipated_energy: f64,
    /// Fixed-set solves (rounds) of the step.
    solves: usize,
    /// CG iterations over all solves.
    cg_iterations: usize,
    /// Elastic operator applications (FFT pairs).
    operator_applications: u64,
}

#[pymethods]
impl StepReport {
    fn __repr__(&self) -> String {
        format!(
            "StepReport(depth={:e}, force={:e}, contact_elements={}, attached={}, detached={})",
            self.depth, self.force, self.contact_elements, self.attached, self.detached
        )
    }
}

pub fn step_report(depth: f64, report: &adhesim::StepReport, state: &adhesim::ContactState) -> StepReport {
    StepReport {
        depth,
        force: report.force,
        force_before_change: report.force_before_change,
        contact_elements: state.contact_elements(),
        attached: report.attached,
        detached: report.detached,
        energy: report.energy,
        energy_before_change: report.energy_before_change,
        dissipated_energy: report.dissipated_energy,
        solves: report.solves,
        cg_iterations: report.cg_iterations,
        operator_applications: report.operator_applications,
    }
}

/// Columns of a step sequence as a dict of 1-D numpy arrays.
pub fn step_columns<'py>(py: Python<'py>, rows: &[(StepReport, f64)]) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    let float = |f: fn(&(StepReport, f64)) -> f64| PyArray1::from_vec(py, rows.iter().map(f).collect());
    let int = |f: fn(&(StepReport, f64)) -> u64| PyArray1::from_vec(py, rows.iter().map(f).collect());
    dict.set_item("depth", float(|r| r.0.depth))?;
    dict.set_item("force", float(|r| r.0.force))?;
    dict.set_item("force_before_change", float(|r| r.0.force_before_change))?;
    dict.set_item("contact_radius", float(|r| r.1))?;
    dict.set_item("contact_elements", int(|r| r.0.contact_elements as u64))?;
    dict.set_item("attached", int(|r| r.0.attached as u64))?;
    dict.set_item("detached", int(|r| r.0.detached as u64))?;
    dict.set_item("energy", float(|r| r.0.energy))?;
    dict.set_item("dissipated_energy", float(|r| r.0.dissipated_energy))?;
    dict.set_item("cg_iterations", int(|r| r.0.cg_iterations as u64))?;
    Ok(dict)
}

/// The Python name of an attachment rule.
pub fn attachment_name(attachment: adhesim::Attachment) -> &'static str {
    match attachment {
        adhesim::Attachment::Trial => "trial",
        adhesim::Attachment::PenetrationOnly => "penetration_only",
    }
}

/// `worst_first_fraction` of a detachment rule: the fraction, or None (all violators;
/// the other rules are not offered in Python).
pub fn worst_first_fraction(detachment: adhesim::Detachment) -> Option<f64> {
    match detachment {
        adhesim::Detachment::WorstFirst { fraction } => Some(fraction),
        _ => None,
    }
}

/// Parameters shared by the constructor of the adhesive solver, checked.
#[allow(clippy::too_many_arguments)]
pub fn adhesive_params(
    relative_tolerance: f64,
    front_tolerance: f64,
    max_cg_iterations: i64,
    max_rounds: i64,
    attachment: &str,
    worst_first_fraction: Option<f64>,
    preconditioned: bool,
    carry_bans_when_retracting: bool,
    retry_after_growth: bool,
) -> PyResult<adhesim::AdhesiveParams> {
    let attachment = match attachment {
        "trial" => adhesim::Attachment::Trial,
        "penetration_only" => adhesim::Attachment::PenetrationOnly,
        other => {
            return Err(PyValueError::new_err(format!(
                "attachment must be 'trial' or 'penetration_only', got {other:?}"
            )))
        }
    };
    let detachment = match worst_first_fraction {
        None => adhesim::Detachment::AllViolators,
        Some(fraction) if !(0.0..=1.0).contains(&fraction) => {
            return Err(PyValueError::new_err(format!(
                "worst_first_fraction must be a fraction in [0, 1] or None, got {fraction}"
            )))
        }
        Some(fraction) => adhesim::Detachment::WorstFirst { fraction },
    };
    Ok(adhesim::AdhesiveParams {
        relative_tolerance: positive("relative_tolerance", relative_tolerance)?,
        front_tolerance: positive("front_tolerance", front_tolerance)?,
        max_cg_iterations: count("max_cg_iterations", max_cg_iterations, 1)?,
        max_rounds: count("max_rounds", max_rounds, 1)?,
        attachment,
        detachment,
        preconditioned,
        carry_bans_when_retracting,
        retry_after_growth,
        ..adhesim::AdhesiveParams::default()
    })
}
