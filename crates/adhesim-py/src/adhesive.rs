//! The adhesive solver and its quasi-static step API.

use crate::convert::{finite, non_negative, read_field, read_vector, solve_error, value_error};
use crate::objects::HalfSpace;
use crate::solvers::{adhesive_params, attachment_name, step_columns, step_report, worst_first_fraction, StepReport};
use crate::state::ContactState;
use crate::views::Cached;
use adhesim::WorkOfAdhesion;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Quasi-static JKR-type adhesive contact with the local mesh-dependent detachment
/// criterion (Pohrt & Popov 2015; Popov et al. 2021, Friction 9, Sect. 2.2–2.3): an
/// element is released once its tension exceeds σ_c = √(E*γ/(c_U·Δ)).
///
/// Each `step` brings the state to a stable configuration at one indentation depth
/// (displacement control); the solver remembers the last steps (warm-start extrapolation,
/// carried bans), so drive one load path per solver, or call `reset()` between paths.
///
/// Parameters
/// ----------
/// operator
///     the HalfSpace of the grid (free or periodic).
/// work_of_adhesion
///     γ (energy per area, ≥ 0): a float, or a float64 (n, n) map.
/// relative_tolerance
///     CG stops at ‖r‖_C ≤ this·‖d − z‖_C ...
/// front_tolerance
///     ... and max|r_i| ≤ this·K(0,0)·σ_c,min.
/// max_cg_iterations
///     CG iterations per solve.
/// max_rounds
///     attach/detach rounds per step.
/// attachment
///     "trial" (discrete Griffith closure test) or "penetration_only"
///     (non-adhesive approach, for comparison).
/// worst_first_fraction
///     None (release all over-stressed elements at once) or a
///     fraction: release only those within it of the worst over-stress ratio.
/// preconditioned, carry_bans_when_retracting, retry_after_growth
///     as in the Rust
///     library's AdhesiveParams.
///
/// The defaults are the Rust library's (`AdhesiveParams::default()`):
/// `AdhesiveSolver.defaults()` lists them.
///
/// Raises
/// ------
/// ValueError
///     a negative or non-finite γ, a map of the wrong shape, a bad parameter.
#[pyclass(module = "adhesim._adhesim")]
pub struct AdhesiveSolver {
    inner: adhesim::AdhesiveSolver,
    params: adhesim::AdhesiveParams,
    /// `work_of_adhesion` as the repr shows it: the float, or the map's shape and range.
    gamma_repr: String,
    operator: Py<HalfSpace>,
    grid: adhesim::Grid,
    heights: Vec<f64>,
    /// The read-only `critical_stress` array (fixed at construction).
    critical_stress: Cached<f64>,
}

impl AdhesiveSolver {
    /// One step on the heights already in `self.heights`, GIL released.
    fn step_inner(&mut self, py: Python<'_>, depth: f64, state: &Bound<'_, ContactState>) -> PyResult<StepReport> {
        let mut operator = self.operator.bind(py).try_borrow_mut()?;
        let mut guard = state.try_borrow_mut()?;
        let (solver, heights) = (&mut self.inner, &self.heights);
        let (op, st) = (&mut operator.inner, guard.fields_mut());
        let report = crate::pool::detached(py, || solver.step(op, heights, depth, st))?.map_err(solve_error)?;
        guard.record(&self.heights, depth);
        Ok(step_report(depth, &report, guard.fields()))
    }
}

#[pymethods]
impl AdhesiveSolver {
    #[new]
    #[pyo3(signature = (
        operator, work_of_adhesion,
        relative_tolerance = adhesim::AdhesiveParams::default().relative_tolerance,
        front_tolerance = adhesim::AdhesiveParams::default().front_tolerance,
        max_cg_iterations = adhesim::AdhesiveParams::default().max_cg_iterations as i64,
        max_rounds = adhesim::AdhesiveParams::default().max_rounds as i64,
        attachment = attachment_name(adhesim::AdhesiveParams::default().attachment).to_string(),
        worst_first_fraction = worst_first_fraction(adhesim::AdhesiveParams::default().detachment),
        preconditioned = adhesim::AdhesiveParams::default().preconditioned,
        carry_bans_when_retracting = adhesim::AdhesiveParams::default().carry_bans_when_retracting,
        retry_after_growth = adhesim::AdhesiveParams::default().retry_after_growth
    ))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        #[pyo3(from_py_with = crate::objects::operator_argument)] operator: Py<HalfSpace>,
        work_of_adhesion: &Bound<'_, PyAny>,
        #[pyo3(from_py_with = crate::args::number::relative_tolerance)] relative_tolerance: f64,
        #[pyo3(from_py_with = crate::args::number::front_tolerance)] front_tolerance: f64,
        #[pyo3(from_py_with = crate::args::integer::max_cg_iterations)] max_cg_iterations: i64,
        #[pyo3(from_py_with = crate::args::integer::max_rounds)] max_rounds: i64,
        #[pyo3(from_py_with = crate::args::text::attachment)] attachment: String,
        #[pyo3(from_py_with = crate::args::optional_number::worst_first_fraction)] worst_first_fraction: Option<f64>,
        #[pyo3(from_py_with = crate::args::flag::preconditioned)] preconditioned: bool,
        #[pyo3(from_py_with = crate::args::flag::carry_bans_when_retracting)] carry_bans_when_retracting: bool,
        #[pyo3(from_py_with = crate::args::flag::retry_after_growth)] retry_after_growth: bool,
    ) -> PyResult<Self> {
        let params = adhesive_params(
            relative_tolerance,
            front_tolerance,
            max_cg_iterations,
            max_rounds,
            &attachment,
            worst_first_fraction,
            preconditioned,
            carry_bans_when_retracting,
            retry_after_growth,
        )?;
        let (grid, material) = {
            let op = operator.borrow(py);
            (op.grid, op.material)
        };
        let gamma = if let Ok(value) = work_of_adhesion.extract::<f64>() {
            WorkOfAdhesion::Uniform(non_negative("work_of_adhesion", value)?)
        } else {
            let mut map = Vec::new();
            read_field(work_of_adhesion, "work_of_adhesion", &grid, false, &mut map)?;
            if let Some(k) = map.iter().position(|&gamma| gamma < 0.0) {
                return Err(PyValueError::new_err(format!(
                    "work_of_adhesion[{}, {}] must be >= 0, got {}",
                    k / grid.nx(),
                    k % grid.nx(),
                    map[k]
                )));
            }
            WorkOfAdhesion::Map(map)
        };
        let gamma_repr = match &gamma {
            WorkOfAdhesion::Uniform(value) => format!("{value:?}"),
            WorkOfAdhesion::Map(map) => {
                let (low, high) = map
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &g| (l.min(g), h.max(g)));
                format!("<map ({}, {}), {low:?} to {high:?}>", grid.ny(), grid.nx())
            }
            // Python builds only a float or a map.
            _ => "<profile>".to_string(),
        };
        let per_element = gamma.on_grid(&grid).map_err(value_error)?;
        let modulus = material.contact_modulus();
        let inner = adhesim::AdhesiveSolver::new(grid, modulus, per_element, params);
        // The scenario crate's single-precision window (1e-30..1e30, docs/reliability.md):
        // `AdhesiveSolver(op, 1e300)` was accepted and overflowed in the first step.
        if let Some(k) = inner
            .critical_stresses()
            .iter()
            .position(|&stress| stress != 0.0 && !(1e-30..=1e30).contains(&stress))
        {
            return Err(PyValueError::new_err(format!(
                "work_of_adhesion = {gamma_repr} gives the critical stress σ_c = {:e} at element [{}, {}] (with contact_modulus = {modulus:e}), outside 1e-30..1e30, the range the solver's single-precision FFTs hold: bring work_of_adhesion and the material to commensurate units",
                inner.critical_stresses()[k],
                k / grid.nx(),
                k % grid.nx()
            )));
        }
        Ok(Self {
            inner,
            params,
            gamma_repr,
            operator,
            grid,
            heights: Vec::with_capacity(grid.len()),
            critical_stress: Cached::default(),
        })
    }

    /// One quasi-static step: brings `state` to a stable configuration at `depth`.
    ///
    /// Parameters
    /// ----------
    /// heights
    ///     float64 (n, n) indenter heights z; +inf where there is no surface.
    /// depth
    ///     indentation depth d (> 0 into the body, < 0 pulled out).
    /// state
    ///     ContactState, the configuration of the previous step (updated in place).
    ///
    /// Returns
    /// -------
    /// StepReport
    ///     Force > 0 compressive, < 0 tensile.
    ///
    /// Raises
    /// ------
    /// ValueError
    ///     bad heights or depth, a state of another grid.
    /// SolveError
    ///     the step did not converge (the state is then partly updated).
    fn step(
        &mut self,
        py: Python<'_>,
        heights: &Bound<'_, PyAny>,
        #[pyo3(from_py_with = crate::args::number::depth)] depth: f64,
        #[pyo3(from_py_with = crate::state::contact_state_argument)] state: Bound<'_, ContactState>,
    ) -> PyResult<StepReport> {
        let depth = finite("depth", depth)?;
        state.borrow().check_grid(&self.grid)?;
        read_field(heights, "heights", &self.grid, true, &mut self.heights)?;
        self.step_inner(py, depth, &state)
    }

    /// A sequence of steps at the given depths on fixed heights, in one call.
    ///
    /// Between steps the Python signal handlers run (Ctrl-C raises KeyboardInterrupt,
    /// leaving `state` at the last completed step) and `progress(index, report)` is
    /// called when given (return value ignored; an exception it raises stops the
    /// sequence). A single step is not interruptible: the library has no hook inside it.
    ///
    /// Parameters
    /// ----------
    /// heights
    ///     float64 (n, n) indenter heights z.
    /// depths
    ///     float64 1-D array of depths d, in order.
    /// state
    ///     ContactState, updated in place.
    /// progress
    ///     optional callable(index: int, report: StepReport).
    ///
    /// Returns
    /// -------
    /// dict of 1-D numpy arrays, one entry per step
    ///     depth, force, force_before_change,
    ///     contact_radius (largest distance of a contact element centre from the origin,
    ///     0 without contact), contact_elements, attached, detached, energy,
    ///     dissipated_energy, cg_iterations.
    #[pyo3(signature = (heights, depths, state, progress = None))]
    fn steps<'py>(
        &mut self,
        py: Python<'py>,
        heights: &Bound<'py, PyAny>,
        depths: &Bound<'py, PyAny>,
        #[pyo3(from_py_with = crate::state::contact_state_argument)] state: Bound<'py, ContactState>,
        progress: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let depths = read_vector(depths, "depths")?;
        if let Some(k) = depths.iter().position(|d| !d.is_finite()) {
            return Err(PyValueError::new_err(format!(
                "depths[{k}] must be finite, got {}",
                depths[k]
            )));
        }
        state.borrow().check_grid(&self.grid)?;
        read_field(heights, "heights", &self.grid, true, &mut self.heights)?;
        let mut rows = Vec::with_capacity(depths.len());
        for (index, &depth) in depths.iter().enumerate() {
            let report = self.step_inner(py, depth, &state)?;
            let radius = state.borrow().fields().contact_radius(&self.grid, (0.0, 0.0));
            rows.push((report, radius));
            py.check_signals()?;
            if let Some(callback) = progress {
                callback.call1((index, report))?;
            }
        }
        step_columns(py, &rows)
    }

    /// The default parameters, from the Rust library's `AdhesiveParams::default()`.
    #[staticmethod]
    fn defaults(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
        let p = adhesim::AdhesiveParams::default();
        let dict = PyDict::new(py);
        dict.set_item("relative_tolerance", p.relative_tolerance)?;
        dict.set_item("front_tolerance", p.front_tolerance)?;
        dict.set_item("max_cg_iterations", p.max_cg_iterations)?;
        dict.set_item("max_rounds", p.max_rounds)?;
        dict.set_item("attachment", attachment_name(p.attachment))?;
        dict.set_item("worst_first_fraction", worst_first_fraction(p.detachment))?;
        dict.set_item("preconditioned", p.preconditioned)?;
        dict.set_item("carry_bans_when_retracting", p.carry_bans_when_retracting)?;
        dict.set_item("retry_after_growth", p.retry_after_growth)?;
        Ok(dict)
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        let p = &self.params;
        let attachment = format!("'{}'", attachment_name(p.attachment));
        let worst_first = worst_first_fraction(p.detachment).map_or("None".to_string(), |f| format!("{f:?}"));
        let flag = |b: bool| if b { "True" } else { "False" };
        format!(
            "AdhesiveSolver({}, work_of_adhesion={}, relative_tolerance={:?}, front_tolerance={:?}, \
             max_cg_iterations={}, max_rounds={}, attachment={attachment}, worst_first_fraction={worst_first}, \
             preconditioned={}, carry_bans_when_retracting={}, retry_after_growth={})",
            crate::solvers::operator_repr(py, &self.operator),
            self.gamma_repr,
            p.relative_tolerance,
            p.front_tolerance,
            p.max_cg_iterations,
            p.max_rounds,
            flag(p.preconditioned),
            flag(p.carry_bans_when_retracting),
            flag(p.retry_after_growth)
        )
    }

    /// Forgets the history of previous steps (warm-start extrapolation, carried bans):
    /// call before driving a new, unrelated load path with the same solver.
    fn reset(&mut self) {
        self.inner.reset();
    }

    /// Π = ½Δ²Σp·u − Δ²Σ_C γ of a state: elastic energy minus adhesion energy.
    fn energy(
        &self,
        #[pyo3(from_py_with = crate::state::contact_state_argument)] state: Bound<'_, ContactState>,
    ) -> PyResult<f64> {
        let state = state.borrow();
        state.check_grid(&self.grid)?;
        Ok(self.inner.energy(state.fields()))
    }

    /// Critical tensile stress σ_c = √(E*γ/(c_U·Δ)) per element, float64 (ny, nx),
    /// read-only (the same array at every access).
    #[getter]
    fn critical_stress<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
        self.critical_stress.get(py, || {
            crate::convert::field(py, self.inner.critical_stresses(), &self.grid)
        })
    }
}
