//! The one trait every normal solver family implements for the protocols: a
//! displacement-controlled step, its history (reset, checkpoint, restore) and its
//! pull-off policy. A new family is one `impl NormalStepper` (ARCHITECTURE.md, "How to
//! add a solver family"), run by every protocol through [`NormalSolver::Family`].

use super::checkpoint::SolverCheckpoint;
use crate::elastic::ElasticOperator;
use crate::solver::{
    AdhesiveSolver, Ccg, CohesiveSolver, ContactState, Control, NestedActiveSet, SolveError, SolveReport, StepReport,
};

/// A normal-contact solver as the protocols drive it.
///
/// The operator is passed as `dyn ElasticOperator`: the protocols own no operator type,
/// and the run pipeline builds its operator (half-space, periodic, layer) behind one.
pub trait NormalStepper: Send {
    /// The kind of solver, in words (for errors): "the JKR-type adhesive solver".
    fn name(&self) -> &'static str;

    /// Forgets the history of previous steps before a new load path.
    fn reset(&mut self);

    /// One step at indentation `depth`; `before_change` sees the state on the previous
    /// contact set at the new depth, before the configuration changes.
    fn step_probed(
        &mut self,
        operator: &mut dyn ElasticOperator,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
        before_change: &mut (dyn FnMut(&ContactState) + Send),
    ) -> Result<StepReport, SolveError>;

    /// The history this solver carries into its next step, or `None` where the family
    /// takes no checkpoints (a protocol then offers none and runs as without).
    fn checkpoint(&self) -> Option<SolverCheckpoint>;

    /// Whether [`checkpoint`](Self::checkpoint) gives one, asked before taking one (which
    /// copies the history).
    fn supports_checkpoints(&self) -> bool {
        true
    }

    /// Puts back the history of `checkpoint` (taken by the same family on the same problem
    /// when the step that left `state` ended). An error, nothing changed, for a checkpoint
    /// of another family or another grid.
    fn restore(&mut self, checkpoint: &SolverCheckpoint, state: &ContactState) -> Result<(), String>;

    /// Pull-off policy: whether the body can hold the indenter without contact (a cohesive
    /// law pulls across a gap, so its pull-off ends when the force vanishes, not the
    /// contact).
    fn acts_across_gaps(&self) -> bool {
        false
    }

    /// Pull-off policy: the tensile force at or below which a pull-off has let go, given
    /// the largest adhesive force seen (0: the force must vanish).
    fn released_force(&self, _max_adhesive_force: f64) -> f64 {
        0.0
    }

    /// How far above the first contact an indentation starts (a law of unbounded support
    /// pulls before contact).
    fn approach_margin(&self) -> f64 {
        0.0
    }

    /// Whether the solver's zone reached the border of a free grid at the last step.
    fn zone_touches_border(&self) -> bool {
        false
    }

    /// The JKR-type solver, whose detachment rule a shear may weaken; `None` for others.
    fn as_adhesive_mut(&mut self) -> Option<&mut AdhesiveSolver> {
        None
    }
}

/// The error of a checkpoint taken by another family.
fn other_family(saved: &SolverCheckpoint, solver: &dyn NormalStepper) -> String {
    format!(
        "the checkpoint is of {}, this run's solver is {}",
        saved.solver_name(),
        solver.name()
    )
}

/// One non-adhesive step: the solve, then the step record (nothing is dissipated).
fn non_adhesive_step(
    operator: &mut dyn ElasticOperator,
    state: &mut ContactState,
    before_change: &mut (dyn FnMut(&ContactState) + Send),
    solve: impl FnOnce(&mut dyn ElasticOperator, &mut ContactState) -> Result<SolveReport, SolveError>,
) -> Result<StepReport, SolveError> {
    let before = state.contact.clone();
    let solve = solve(operator, state)?;
    before_change(state);
    let area = operator.grid().element_area();
    let energy = 0.5
        * area
        * state
            .pressure
            .iter()
            .zip(&state.displacement)
            .map(|(p, u)| p * u)
            .sum::<f64>();
    let (attached, detached) = state.changes_from(&before);
    Ok(StepReport {
        solves: 1,
        cg_iterations: solve.iterations,
        operator_applications: solve.operator_applications,
        // The non-adhesive solvers' windows are counted in their applications only.
        window_applications: 0,
        preconditioner_applications: solve.preconditioner_applications,
        attachment_rounds: 0,
        attached,
        detached,
        force_before_change: solve.force,
        force: solve.force,
        energy_before_change: energy,
        energy,
        dissipated_energy: 0.0,
    })
}

/// Polonsky–Keer CCG at each depth (non-adhesive; on a periodic grid depth control is
/// mean-gap control). Every solve starts from the state alone: no history.
impl NormalStepper for Ccg {
    fn name(&self) -> &'static str {
        "the non-adhesive CCG"
    }

    fn reset(&mut self) {}

    fn step_probed(
        &mut self,
        operator: &mut dyn ElasticOperator,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
        before_change: &mut (dyn FnMut(&ContactState) + Send),
    ) -> Result<StepReport, SolveError> {
        non_adhesive_step(operator, state, before_change, |operator, state| {
            self.solve(operator, heights, Control::Displacement(depth), state)
        })
    }

    fn checkpoint(&self) -> Option<SolverCheckpoint> {
        Some(SolverCheckpoint::Stateless)
    }

    fn restore(&mut self, checkpoint: &SolverCheckpoint, _state: &ContactState) -> Result<(), String> {
        match checkpoint {
            SolverCheckpoint::Stateless => Ok(()),
            saved => Err(other_family(saved, self)),
        }
    }
}

/// The nested-grid active set (non-adhesive, free grids): the same solutions as CCG,
/// several times faster; its history is its contact windows and last depth.
impl NormalStepper for NestedActiveSet {
    fn name(&self) -> &'static str {
        "the non-adhesive nested active set"
    }

    fn reset(&mut self) {}

    fn step_probed(
        &mut self,
        operator: &mut dyn ElasticOperator,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
        before_change: &mut (dyn FnMut(&ContactState) + Send),
    ) -> Result<StepReport, SolveError> {
        non_adhesive_step(operator, state, before_change, |operator, state| {
            self.solve(operator, heights, depth, state)
        })
    }

    fn checkpoint(&self) -> Option<SolverCheckpoint> {
        Some(SolverCheckpoint::Nested(Box::new(NestedActiveSet::checkpoint(self))))
    }

    fn restore(&mut self, checkpoint: &SolverCheckpoint, _state: &ContactState) -> Result<(), String> {
        match checkpoint {
            SolverCheckpoint::Nested(saved) => NestedActiveSet::restore(self, saved),
            saved => Err(other_family(saved, self)),
        }
    }
}

/// The JKR-type adhesive active set.
impl NormalStepper for AdhesiveSolver {
    fn name(&self) -> &'static str {
        "the JKR-type adhesive solver"
    }

    fn reset(&mut self) {
        AdhesiveSolver::reset(self);
    }

    fn step_probed(
        &mut self,
        operator: &mut dyn ElasticOperator,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
        before_change: &mut (dyn FnMut(&ContactState) + Send),
    ) -> Result<StepReport, SolveError> {
        AdhesiveSolver::step_probed(self, operator, heights, depth, state, before_change)
    }

    fn checkpoint(&self) -> Option<SolverCheckpoint> {
        Some(SolverCheckpoint::Adhesive(Box::new(AdhesiveSolver::checkpoint(self))))
    }

    fn restore(&mut self, checkpoint: &SolverCheckpoint, state: &ContactState) -> Result<(), String> {
        match checkpoint {
            SolverCheckpoint::Adhesive(saved) => AdhesiveSolver::restore(self, saved, state),
            saved => Err(other_family(saved, self)),
        }
    }

    fn as_adhesive_mut(&mut self) -> Option<&mut AdhesiveSolver> {
        Some(self)
    }
}

/// Adhesion by a cohesive law of finite range (Maugis–Dugdale, exponential, trapezoid).
impl NormalStepper for CohesiveSolver {
    fn name(&self) -> &'static str {
        "a cohesive law's solver"
    }

    fn reset(&mut self) {
        CohesiveSolver::reset(self);
    }

    fn step_probed(
        &mut self,
        operator: &mut dyn ElasticOperator,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
        before_change: &mut (dyn FnMut(&ContactState) + Send),
    ) -> Result<StepReport, SolveError> {
        CohesiveSolver::step_probed(self, operator, heights, depth, state, before_change)
    }

    fn checkpoint(&self) -> Option<SolverCheckpoint> {
        Some(SolverCheckpoint::Cohesive(Box::new(CohesiveSolver::checkpoint(self))))
    }

    fn restore(&mut self, checkpoint: &SolverCheckpoint, _state: &ContactState) -> Result<(), String> {
        match checkpoint {
            SolverCheckpoint::Cohesive(saved) => CohesiveSolver::restore(self, saved),
            saved => Err(other_family(saved, self)),
        }
    }

    fn acts_across_gaps(&self) -> bool {
        true
    }

    fn released_force(&self, max_adhesive_force: f64) -> f64 {
        CohesiveSolver::released_force(self, max_adhesive_force)
    }

    fn approach_margin(&self) -> f64 {
        self.law().negligible_separation()
    }

    fn zone_touches_border(&self) -> bool {
        CohesiveSolver::zone_touches_border(self)
    }
}

#[cfg(test)]
mod tests;
