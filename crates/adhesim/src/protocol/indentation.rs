use super::{IndentCheckpoint, NormalSolver, Observer, Phase, ProtocolCheckpoint, ProtocolError, StepRecord, StepView};
use crate::elastic::ElasticOperator;
use crate::grid::Grid;
use crate::problem::Problem;
use crate::solver::ContactState;
use std::ops::ControlFlow;

mod hold;

pub use hold::{AgingLaw, Hold};

/// Displacement-controlled indentation to `max_depth` and retraction until contact is
/// lost, in fixed steps of `depth_step` (paper Sect. 2.1, Fig. 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IndentPulloff {
    /// Depth of the first step's reference (first contact; the approach starts above it).
    pub start_depth: f64,
    /// Deepest indentation.
    pub max_depth: f64,
    /// Depth increment per step (> 0).
    pub depth_step: f64,
    /// Retraction stops with an error after this many steps without losing contact.
    pub max_retract_steps: usize,
    /// A step is a jump when the force changes by more than this at fixed depth.
    pub jump_force_threshold: f64,
}

/// Totals over a protocol run.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ProtocolSummary {
    /// Steps done.
    pub steps: usize,
    /// Largest tensile force magnitude seen (0 if never tensile).
    pub max_adhesive_force: f64,
    /// Depth at which the largest tensile force was seen.
    pub depth_at_max_adhesive_force: f64,
    /// Depth of the last step in contact before contact was lost (the final jump).
    pub pull_off_depth: Option<f64>,
    /// Steps flagged as jumps.
    pub jumps: usize,
    /// Total dissipated energy.
    pub dissipated_energy: f64,
    /// Fixed-set solves.
    pub solves: usize,
    /// CG iterations.
    pub cg_iterations: usize,
    /// Operator applications (FFT pairs).
    pub operator_applications: u64,
    /// Of those, the adhesive CG's applications on contact windows.
    #[cfg_attr(feature = "serde", serde(default))]
    pub window_applications: u64,
    /// The CG preconditioner's applications (FFT pairs of the solved grid's own size; not
    /// in `operator_applications`).
    #[cfg_attr(feature = "serde", serde(default))]
    pub preconditioner_applications: u64,
    /// Largest contact (elements) and the step where it occurred.
    pub largest_contact: (usize, usize),
    /// Some step had contact on the border of a free grid.
    pub touches_border: bool,
}

impl IndentPulloff {
    /// Runs approach then retraction; reports each step to `observer`.
    pub fn run(
        &self,
        problem: &mut Problem,
        solver: &mut NormalSolver,
        observer: &mut dyn Observer,
    ) -> Result<ProtocolSummary, ProtocolError> {
        self.run_from(problem, solver, observer, None)
    }

    /// As [`run`](Self::run), continued from `start` (a checkpoint of a run of the same
    /// protocol, problem and kind of solver) when given: the steps after it are those of
    /// the uninterrupted run, bit for bit. After every step the observer is offered a
    /// checkpoint ([`Observer::wants_checkpoint`]) where the solver supports them.
    pub fn run_from(
        &self,
        problem: &mut Problem,
        solver: &mut NormalSolver,
        observer: &mut dyn Observer,
        start: Option<&IndentCheckpoint>,
    ) -> Result<ProtocolSummary, ProtocolError> {
        self.run_phases(problem, solver, observer, start, None)
    }

    /// The approach, the `hold` at the deepest indentation when given, and the retraction;
    /// from `start` when given. With a hold, checkpoints are offered during the approach
    /// only (the hold's ages are not in them), so a resumed run holds from its start.
    fn run_phases(
        &self,
        problem: &mut Problem,
        solver: &mut NormalSolver,
        observer: &mut dyn Observer,
        start: Option<&IndentCheckpoint>,
        hold: Option<&Hold>,
    ) -> Result<ProtocolSummary, ProtocolError> {
        self.check()?;
        let (operator, heights) = problem.parts_mut();
        let grid = *operator.grid();
        solver.reset();
        let acts_across_gaps = solver.acts_across_gaps();
        let released_fraction = solver.released_force(1.0);
        // A law of unbounded support approaches from where its pull is negligible.
        let start_depth = self.start_depth - solver.approach_margin();
        let approach_steps = ((self.max_depth - start_depth) / self.depth_step).ceil() as usize;
        let mut run = match start {
            Some(checkpoint) => {
                checkpoint.check(&grid, approach_steps)?;
                solver
                    .restore(&checkpoint.solver, &checkpoint.state)
                    .map_err(ProtocolError::InvalidParameter)?;
                RunState::restored(checkpoint)
            }
            None => RunState::new(&grid, self.max_depth),
        };
        if hold.is_some() && run.step > approach_steps {
            return Err(ProtocolError::InvalidParameter(
                "a run with a hold resumes only from a checkpoint of its approach".into(),
            ));
        }
        while run.step < approach_steps {
            let depth = (start_depth + (run.step + 1) as f64 * self.depth_step).min(self.max_depth);
            self.run_step(operator, heights, solver, observer, &mut run, depth, Phase::Approach)?;
            run.offer_checkpoint(solver, observer)?;
        }
        if let Some(hold) = hold {
            self.hold(operator, heights, solver, observer, &mut run, hold)?;
        }
        while run.step - approach_steps < self.max_retract_steps {
            run.depth -= self.depth_step;
            let depth = run.depth;
            let record = self.run_step(operator, heights, solver, observer, &mut run, depth, Phase::Retract)?;
            let released_force = released_fraction * run.summary.max_adhesive_force;
            // Without contact, a cohesive law may still pull (a tensile force): retraction
            // goes on until it lets go (for a law of unbounded support, until the tension
            // is negligible).
            let holds_across_gap = acts_across_gaps && -record.force_normal > released_force;
            if record.contact_elements == 0 && !holds_across_gap {
                run.summary.pull_off_depth = run.last_in_contact;
                return Ok(run.summary);
            }
            if record.contact_elements > 0 {
                run.last_in_contact = Some(depth);
            }
            if hold.is_none() {
                run.offer_checkpoint(solver, observer)?;
            }
        }
        Err(ProtocolError::ContactNotLost {
            steps: self.max_retract_steps,
            depth: run.depth,
        })
    }

    /// The parameters are usable.
    fn check(&self) -> Result<(), ProtocolError> {
        if !(self.depth_step.is_finite() && self.depth_step > 0.0) {
            return Err(ProtocolError::InvalidParameter(format!(
                "depth step must be > 0, got {}",
                self.depth_step
            )));
        }
        if !(self.max_depth.is_finite() && self.max_depth > self.start_depth) {
            return Err(ProtocolError::InvalidParameter(format!(
                "max depth ({}) must exceed the depth of first contact ({})",
                self.max_depth, self.start_depth
            )));
        }
        Ok(())
    }

    /// One step at `depth`: the solve, the record, the totals, the observer.
    #[allow(clippy::too_many_arguments)]
    fn run_step(
        &self,
        operator: &mut dyn ElasticOperator,
        heights: &[f64],
        solver: &mut NormalSolver,
        observer: &mut dyn Observer,
        run: &mut RunState,
        depth: f64,
        phase: Phase,
    ) -> Result<StepRecord, ProtocolError> {
        let (grid, step) = (*operator.grid(), run.step);
        let (state, previous, summary) = (&mut run.state, &mut run.previous, &mut run.summary);
        previous.copy_from_slice(&state.contact);
        let report = solver
            .step(operator, heights, depth, state)
            .map_err(|source| ProtocolError::Solve { step, depth, source })?;
        summary.dissipated_energy += report.dissipated_energy;
        let mut record = StepRecord::measure(
            step,
            phase,
            depth,
            0.0,
            report,
            state,
            &grid,
            summary.dissipated_energy,
            self.jump_force_threshold,
        );
        // A cohesive zone cut by the border is as wrong as a contact cut by it.
        record.touches_border |= solver.zone_touches_border();
        record.time = run.time;
        let contact_elements = record.contact_elements;
        summary.steps += 1;
        summary.solves += report.solves;
        summary.cg_iterations += report.cg_iterations;
        summary.operator_applications += report.operator_applications;
        summary.window_applications += report.window_applications;
        summary.preconditioner_applications += report.preconditioner_applications;
        summary.jumps += record.jumped as usize;
        summary.touches_border |= record.touches_border;
        if -record.force_normal > summary.max_adhesive_force {
            summary.max_adhesive_force = -record.force_normal;
            summary.depth_at_max_adhesive_force = depth;
        }
        if contact_elements > summary.largest_contact.0 {
            summary.largest_contact = (contact_elements, step);
        }
        if let ControlFlow::Break(()) = observer.on_step(StepView {
            record: &record,
            state,
            previous_contact: previous,
            shear: None,
        }) {
            return Err(ProtocolError::Interrupted(step));
        }
        run.step += 1;
        run.phase = phase;
        Ok(record)
    }
}

/// Where a run stands between two steps (what a checkpoint holds, less the solver's).
struct RunState {
    /// Steps done.
    step: usize,
    phase: Phase,
    /// Depth of the retraction (the maximum depth until it starts).
    depth: f64,
    last_in_contact: Option<f64>,
    state: ContactState,
    previous: Vec<bool>,
    summary: ProtocolSummary,
    /// Time since the hold began.
    time: f64,
}

impl RunState {
    fn new(grid: &Grid, max_depth: f64) -> Self {
        let state = ContactState::new(grid);
        Self {
            step: 0,
            phase: Phase::Approach,
            depth: max_depth,
            last_in_contact: None,
            previous: state.contact.clone(),
            state,
            summary: ProtocolSummary::default(),
            time: 0.0,
        }
    }

    fn restored(checkpoint: &IndentCheckpoint) -> Self {
        Self {
            step: checkpoint.steps_done,
            phase: checkpoint.phase,
            depth: checkpoint.depth,
            last_in_contact: checkpoint.last_in_contact,
            state: checkpoint.state.clone(),
            previous: checkpoint.previous.clone(),
            summary: checkpoint.summary,
            time: 0.0,
        }
    }

    /// Offers the observer a checkpoint of the run after the step just done, if it wants
    /// one and the solver supports them.
    fn offer_checkpoint(&self, solver: &NormalSolver, observer: &mut dyn Observer) -> Result<(), ProtocolError> {
        if !solver.supports_checkpoints() || !observer.wants_checkpoint() {
            return Ok(());
        }
        let Some(solver) = solver.checkpoint() else {
            return Ok(());
        };
        let checkpoint = IndentCheckpoint {
            steps_done: self.step,
            phase: self.phase,
            depth: self.depth,
            last_in_contact: self.last_in_contact,
            state: self.state.clone(),
            previous: self.previous.clone(),
            summary: self.summary,
            solver,
        };
        match observer.on_checkpoint(ProtocolCheckpoint::Indentation(Box::new(checkpoint))) {
            ControlFlow::Continue(()) => Ok(()),
            ControlFlow::Break(()) => Err(ProtocolError::Interrupted(self.step - 1)),
        }
    }
}
