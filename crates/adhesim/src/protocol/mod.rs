//! Quasi-static load schedules. A protocol drives a solver through displacement steps
//! and reports every step to an [`Observer`] (writing files is an observer's job, not the
//! library's).

mod checkpoint;
mod indentation;
mod observer;
mod shear;
mod stepper;
mod summary;
mod translation;

pub use checkpoint::{IndentCheckpoint, ProtocolCheckpoint, SolverCheckpoint, TranslationCheckpoint};
pub use indentation::{AgingLaw, Hold, IndentPulloff, ProtocolSummary};
pub use observer::{Observer, StepView};
pub use shear::{
    contact_split, element_energy_ratio, shear_weakened_critical_stress, ModeMixity, Shear, ShearFields, ShearSummary,
    TangentialForce, TranslationFriction,
};
pub use stepper::NormalStepper;
pub use summary::{RunCounters, RunSummary};
pub use translation::{Translation, TranslationSummary};

use crate::elastic::ElasticOperator;
use crate::grid::{Boundary, Grid};
use crate::material::ElasticMaterial;
use crate::solver::{
    AdhesiveSolver, Ccg, CcgParams, CohesiveSolver, ContactState, NestedActiveSet, NestedParams, SolveError,
    StepReport, TangentialError,
};
use thiserror::Error;

/// Stage of a protocol a step belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Phase {
    /// Indentation grows.
    Approach,
    /// Indentation shrinks (pull-off).
    Retract,
    /// Rolling at fixed indentation.
    Roll,
    /// Sliding at fixed indentation.
    Slide,
    /// Tangential shift with friction at fixed indentation.
    Shear,
    /// Held at the deepest indentation while time passes (aging adhesion).
    Hold,
}

impl Phase {
    /// Lower-case name as written in `curve.csv`.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Approach => "approach",
            Self::Retract => "retract",
            Self::Roll => "roll",
            Self::Slide => "slide",
            Self::Shear => "shear",
            Self::Hold => "hold",
        }
    }
}

/// One quasi-static step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct StepRecord {
    /// Step counter from 0.
    pub step: usize,
    /// Stage of the protocol.
    pub phase: Option<Phase>,
    /// Indentation depth d.
    pub depth: f64,
    /// Lateral position X of the indenter axis.
    pub offset: f64,
    /// Normal force (> 0 compressive).
    pub force_normal: f64,
    /// Tangential force (resistance to motion in +x); 0 for normal protocols.
    pub force_tangential: f64,
    /// Tangential force on the previous contact set at this position, before the
    /// configuration changed (the top of a stick phase).
    pub force_tangential_before_change: f64,
    /// Real contact area Δ²|C|.
    pub area: f64,
    /// Distance from the indenter axis to the farthest element in contact.
    pub radius: f64,
    /// Largest |y − Y| of the contact, i.e. the half-width perpendicular to the motion.
    pub half_width: f64,
    /// |C|.
    pub contact_elements: usize,
    /// Solver counters and energies of this step.
    pub report: StepReport,
    /// Cumulative dissipated energy up to and including this step.
    pub cumulative_dissipated_energy: f64,
    /// The configuration changed by an instability: the force changed by more than the
    /// protocol's jump threshold at fixed indentation.
    pub jumped: bool,
    /// An element on the border of a free grid is in contact, or (a cohesive law) in its
    /// cohesive zone (domain too small).
    pub touches_border: bool,
    /// Contact elements sticking (friction at the interface; 0 without).
    #[cfg_attr(feature = "serde", serde(default))]
    pub stick_elements: usize,
    /// Contact elements slipping (friction at the interface; 0 without).
    #[cfg_attr(feature = "serde", serde(default))]
    pub slip_elements: usize,
    /// Contact area ahead of the line through the indenter's axis perpendicular to the
    /// shift (friction at the interface; 0 without).
    #[cfg_attr(feature = "serde", serde(default))]
    pub area_front: f64,
    /// Contact area behind that line.
    #[cfg_attr(feature = "serde", serde(default))]
    pub area_rear: f64,
    /// Energy dissipated by friction up to and including this step.
    #[cfg_attr(feature = "serde", serde(default))]
    pub cumulative_frictional_dissipation: f64,
    /// The drive's position along the shift (the shear protocol; `offset` is the
    /// indenter's, which lags it under a compliant drive).
    #[cfg_attr(feature = "serde", serde(default))]
    pub drive_offset: f64,
    /// Time since a hold began (an indentation with a hold; 0 before it, its duration
    /// after it).
    #[cfg_attr(feature = "serde", serde(default))]
    pub time: f64,
}

impl StepRecord {
    /// The record of a finished step, with the contact measured about the indenter axis
    /// at (`offset`, 0); tangential forces are left at zero for the caller to fill.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn measure(
        step: usize,
        phase: Phase,
        depth: f64,
        offset: f64,
        report: StepReport,
        state: &ContactState,
        grid: &Grid,
        cumulative_dissipated_energy: f64,
        jump_force_threshold: f64,
    ) -> Self {
        let contact_elements = state.contact_elements();
        Self {
            step,
            phase: Some(phase),
            depth,
            offset,
            force_normal: report.force,
            force_tangential: 0.0,
            force_tangential_before_change: 0.0,
            area: contact_elements as f64 * grid.element_area(),
            radius: state.contact_radius(grid, (offset, 0.0)),
            half_width: state.half_width(grid),
            contact_elements,
            report,
            cumulative_dissipated_energy,
            jumped: (report.attached + report.detached) > 0
                && (report.force - report.force_before_change).abs() > jump_force_threshold,
            touches_border: grid.boundary() == Boundary::Free && state.touches_border(grid),
            ..Self::default()
        }
    }
}

/// Why a protocol stopped early.
#[derive(Debug, Error)]
pub enum ProtocolError {
    /// A solve failed.
    #[error("step {step} (d = {depth:e}): {source}")]
    Solve {
        /// Step at which it failed.
        step: usize,
        /// Depth of that step.
        depth: f64,
        /// The solver's error.
        source: SolveError,
    },
    /// A tangential (friction) solve failed.
    #[error("step {step} (shift {shift:e}): {source}")]
    Tangential {
        /// Step at which it failed.
        step: usize,
        /// The indenter's shift at that step.
        shift: f64,
        /// The tangential solver's error.
        source: TangentialError,
    },
    /// The rounds of tangential solve and shear-weakened normal step did not settle.
    #[error("step {step} (shift {shift:e}): the contact set still changed after {rounds} rounds of shear-weakened detachment")]
    DetachmentNotSettled {
        /// Step at which it failed.
        step: usize,
        /// The indenter's shift at that step.
        shift: f64,
        /// Rounds done.
        rounds: usize,
    },
    /// No depth held the normal force under normal-force control.
    #[error("step {step}: no depth held the normal force {force:e} after {trials} trial depths (protocol.normal_control = \"force\"); use protocol.normal_control = \"depth\" or smaller steps")]
    NormalForceNotHeld {
        /// Step at which it failed.
        step: usize,
        /// The force held.
        force: f64,
        /// Trials done.
        trials: usize,
    },
    /// The indenter's shift under a compliant drive of a translation did not settle.
    #[error("step {step} (drive at {drive:e}): the indenter's shift still moved by {change:.3e} elements after {rounds} rounds of a normal step where the indenter is and a tangential step to the drive (protocol.drive_stiffness); use smaller steps or a stiffer drive")]
    DriveNotSettled {
        /// Step at which it failed.
        step: usize,
        /// The drive's position at that step.
        drive: f64,
        /// Rounds done.
        rounds: usize,
        /// The last round's move of the indenter's shift, in elements.
        change: f64,
    },
    /// The rounds of normal and tangential solves of the coupled operator did not meet.
    #[error("step {step} (shift {shift:e}): the coupled normal and tangential solves did not converge in {rounds} rounds (last change {change:.3e} of the normal displacement the shear gives, tolerance {tolerance:.1e}{}); use friction.coupling = \"none\"", if *alternating { "; the contact set alternates between two sets" } else { "" })]
    CouplingNotConverged {
        /// Step at which it failed.
        step: usize,
        /// The indenter's shift at that step.
        shift: f64,
        /// Rounds done.
        rounds: usize,
        /// The last round's largest change of K_zt q, relative to its largest value.
        change: f64,
        /// The tolerance on that change.
        tolerance: f64,
        /// The contact set returned to the one of two rounds before.
        alternating: bool,
    },
    /// The observer asked to stop.
    #[error("stopped by the observer at step {0}")]
    Interrupted(usize),
    /// Pull-off did not end within the step limit.
    #[error("contact not lost after {steps} retraction steps (d = {depth:e}); raise the step limit")]
    ContactNotLost {
        /// Retraction steps done.
        steps: usize,
        /// Depth reached.
        depth: f64,
    },
    /// Parameters out of range.
    #[error("invalid protocol parameter: {0}")]
    InvalidParameter(String),
    /// The problem does not fit the protocol (fixed heights given to a translation).
    #[error(transparent)]
    Problem(#[from] crate::problem::ProblemError),
}

/// The normal-contact solver a protocol drives: the library's families by name, or any
/// other [`NormalStepper`] as [`Family`](Self::Family). Every method goes through the
/// trait ([`stepper`](Self::stepper)); the named variants are for building and matching.
pub enum NormalSolver {
    /// Non-adhesive (γ = 0): Polonsky–Keer CCG at each depth.
    NonAdhesive(Ccg),
    /// Non-adhesive (γ = 0) on a free grid: the nested-grid active set at each depth
    /// (the same solutions as CCG, several times faster).
    NonAdhesiveNested(Box<NestedActiveSet>),
    /// JKR-type adhesive active set.
    Adhesive(Box<AdhesiveSolver>),
    /// Adhesion by a cohesive law of finite range (Maugis–Dugdale, exponential).
    Cohesive(Box<CohesiveSolver>),
    /// Any other solver family.
    Family(Box<dyn NormalStepper>),
}

/// The non-adhesive solver for `grid`: the nested active set on a free grid, CCG on a
/// periodic one (where depth control is mean-gap control).
pub fn non_adhesive_solver(grid: Grid, material: ElasticMaterial) -> NormalSolver {
    match grid.boundary() {
        Boundary::Free => {
            NormalSolver::NonAdhesiveNested(Box::new(NestedActiveSet::new(grid, material, NestedParams::default())))
        }
        Boundary::Periodic => NormalSolver::NonAdhesive(Ccg::new(CcgParams::default())),
    }
}

impl NormalSolver {
    /// The solver as its family's trait.
    pub fn stepper(&self) -> &dyn NormalStepper {
        match self {
            Self::NonAdhesive(solver) => solver,
            Self::NonAdhesiveNested(solver) => solver.as_ref(),
            Self::Adhesive(solver) => solver.as_ref(),
            Self::Cohesive(solver) => solver.as_ref(),
            Self::Family(solver) => solver.as_ref(),
        }
    }

    /// The solver as its family's trait, mutably.
    pub fn stepper_mut(&mut self) -> &mut dyn NormalStepper {
        match self {
            Self::NonAdhesive(solver) => solver,
            Self::NonAdhesiveNested(solver) => solver.as_mut(),
            Self::Adhesive(solver) => solver.as_mut(),
            Self::Cohesive(solver) => solver.as_mut(),
            Self::Family(solver) => solver.as_mut(),
        }
    }

    /// [`NormalStepper::reset`].
    pub fn reset(&mut self) {
        self.stepper_mut().reset();
    }

    /// [`NormalStepper::as_adhesive_mut`].
    pub fn as_adhesive_mut(&mut self) -> Option<&mut AdhesiveSolver> {
        self.stepper_mut().as_adhesive_mut()
    }

    /// [`NormalStepper::acts_across_gaps`].
    pub fn acts_across_gaps(&self) -> bool {
        self.stepper().acts_across_gaps()
    }

    /// [`NormalStepper::released_force`].
    pub fn released_force(&self, max_adhesive_force: f64) -> f64 {
        self.stepper().released_force(max_adhesive_force)
    }

    /// [`NormalStepper::approach_margin`].
    pub fn approach_margin(&self) -> f64 {
        self.stepper().approach_margin()
    }

    /// [`NormalStepper::zone_touches_border`].
    pub fn zone_touches_border(&self) -> bool {
        self.stepper().zone_touches_border()
    }

    /// [`NormalStepper::checkpoint`].
    pub fn checkpoint(&self) -> Option<SolverCheckpoint> {
        self.stepper().checkpoint()
    }

    /// [`NormalStepper::supports_checkpoints`].
    pub fn supports_checkpoints(&self) -> bool {
        self.stepper().supports_checkpoints()
    }

    /// [`NormalStepper::restore`].
    pub fn restore(&mut self, checkpoint: &SolverCheckpoint, state: &ContactState) -> Result<(), String> {
        self.stepper_mut().restore(checkpoint, state)
    }

    /// One displacement-controlled step.
    pub fn step(
        &mut self,
        operator: &mut dyn ElasticOperator,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
    ) -> Result<StepReport, SolveError> {
        self.step_probed(operator, heights, depth, state, &mut |_| {})
    }

    /// [`NormalStepper::step_probed`].
    pub fn step_probed(
        &mut self,
        operator: &mut dyn ElasticOperator,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
        before_change: &mut (dyn FnMut(&ContactState) + Send),
    ) -> Result<StepReport, SolveError> {
        self.stepper_mut()
            .step_probed(operator, heights, depth, state, before_change)
    }
}
