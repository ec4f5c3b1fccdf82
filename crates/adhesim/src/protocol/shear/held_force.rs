//! Normal-force control of a shear whose normal problem changes with the shift
//! (`protocol.normal_control = "force"`): each shift step finds the depth at which the
//! step's normal force is the one held (docs/physics.md §8.5), as in Savkoor & Briggs'
//! experiments at constant load. The step is a weakened edge's rounds or the coupled
//! operator's ([`TrialStep`]).

use super::edge::{EdgeWeakening, NormalSide, RoundsStep};
use super::shift::ShiftTarget;
use super::window::TangentialRoom;
use crate::protocol::ProtocolError;
use crate::solver::TangentialSolver;

/// Trials (steps at a trial depth) allowed per shift step.
const MAX_TRIALS: usize = 60;
/// The step ends when the normal force is within this share of the held force P (or of
/// the trial's force, where larger).
const FORCE_TOLERANCE: f64 = 1e-8;
/// The first step's second trial moves the depth by this share of an element, to measure
/// the stiffness dF/dd that later steps keep.
const PROBE: f64 = 1e-3;
/// ... or when the bracket of depths around it is this share of an element or narrower:
/// the force jumps across P there (a contact set that changes at one depth).
const DEPTH_TOLERANCE: f64 = 1e-10;

/// The held normal force and the depth that last held it.
#[derive(Debug, Clone, Copy)]
pub(super) struct HeldForce {
    /// The force held: the normal force at the end of the approach (set at the first step).
    pub target: Option<f64>,
    /// The depth of the last step (None before the first: the approach's).
    pub depth: Option<f64>,
    /// The last secant stiffness dF/dd (None before it is measured).
    pub stiffness: Option<f64>,
}

/// A trial's depth and force.
#[derive(Clone, Copy)]
struct Trial {
    depth: f64,
    force: f64,
}

/// A shift step that normal-force control runs at trial depths, each from the step's start.
pub(super) trait TrialStep {
    /// Keeps what the step changes for the next beyond the normal solver's history, the
    /// contact state, the room and the tangential solver's memory, as it is at the start.
    fn keep(&mut self);
    /// Puts back what [`keep`](Self::keep) kept, before the next trial.
    fn put_back(&mut self);
    /// The step to `target` at `normal.depth`.
    fn run(
        &mut self,
        normal: NormalSide<'_>,
        room: &mut TangentialRoom,
        friction: &mut TangentialSolver,
        target: ShiftTarget,
        step: usize,
    ) -> Result<RoundsStep, ProtocolError>;
}

/// A weakened edge carries nothing from step to step: each starts from the unweakened σ_c.
impl TrialStep for EdgeWeakening {
    fn keep(&mut self) {}

    fn put_back(&mut self) {}

    fn run(
        &mut self,
        normal: NormalSide<'_>,
        room: &mut TangentialRoom,
        friction: &mut TangentialSolver,
        target: ShiftTarget,
        step: usize,
    ) -> Result<RoundsStep, ProtocolError> {
        let ShiftTarget::Shift(shift) = target else {
            return Err(ProtocolError::InvalidParameter(
                "an imposed tangential force does not go with a shear-weakened edge".into(),
            ));
        };
        self.step(normal, room, friction, shift, step)
    }
}

impl HeldForce {
    /// One shift step at the held normal force: `trials` at trial depths, each from the
    /// step's starting state (the normal solver's history restored from its checkpoint,
    /// the tangential fields from the room's snapshot, the tangential solver's memory and
    /// the step's own carried fields put back), by secant steps kept inside a bracket once
    /// one exists (a regula falsi), since the force rises with the depth. The step kept is
    /// the one a depth-controlled run would take at its depth. Returns it and its depth.
    pub(super) fn step(
        &mut self,
        trials: &mut dyn TrialStep,
        normal: NormalSide<'_>,
        (room, friction): (&mut TangentialRoom, &mut TangentialSolver),
        (shift_target, step): (ShiftTarget, usize),
    ) -> Result<(RoundsStep, f64), ProtocolError> {
        let NormalSide {
            operator,
            heights,
            depth,
            solver,
            state,
        } = normal;
        let target = *self
            .target
            .get_or_insert_with(|| state.force(operator.grid().element_area()));
        let start_depth = self.depth.unwrap_or(depth);
        let element = operator.grid().dx().max(operator.grid().dy());
        let mut stiffness = self.stiffness;
        let start_state = state.clone();
        let Some(checkpoint) = solver.checkpoint() else {
            return Err(ProtocolError::InvalidParameter(format!(
                "normal-force control restarts each trial depth from the step's start, which the {} solver cannot checkpoint: hold the depth instead",
                solver.stepper().name()
            )));
        };
        let start_room = room.snapshot();
        let memory = friction.memory();
        trials.keep();
        let (mut below, mut above): (Option<Trial>, Option<Trial>) = (None, None);
        let (mut trial_depth, mut last): (f64, Option<Trial>) = (start_depth, None);
        // The work of the trials before the last: counted, not kept.
        let mut spent = Spent::default();
        for trial in 0..MAX_TRIALS {
            if trial > 0 {
                state.clone_from(&start_state);
                solver
                    .restore(&checkpoint, &start_state)
                    .map_err(ProtocolError::InvalidParameter)?;
                spent.transform_pairs += room.restore(&start_room);
                friction.put_back_memory(&memory);
                trials.put_back();
            }
            let side = NormalSide {
                operator: &mut *operator,
                heights,
                depth: trial_depth,
                solver: &mut *solver,
                state: &mut *state,
            };
            let mut result = trials.run(side, room, friction, shift_target, step)?;
            let now = Trial {
                depth: trial_depth,
                force: result.normal.force,
            };
            let keep = spent;
            spent.count(&result);
            if let Some(previous) = last {
                let secant = (now.force - previous.force) / (now.depth - previous.depth);
                if secant.is_finite() && secant > 0.0 {
                    stiffness = Some(secant);
                }
            }
            if now.force < target {
                below = Some(now);
            } else {
                above = Some(now);
            }
            let narrow =
                matches!((below, above), (Some(b), Some(a)) if (a.depth - b.depth).abs() <= DEPTH_TOLERANCE * element);
            let scale = target.abs().max(now.force.abs());
            if (now.force - target).abs() <= FORCE_TOLERANCE * scale || narrow {
                self.depth = Some(trial_depth);
                self.stiffness = stiffness;
                keep.add_to(&mut result);
                return Ok((result, trial_depth));
            }
            trial_depth = match (below, above) {
                // Regula falsi inside the bracket, moved halfway to its middle when the
                // same end is replaced twice running, so that it cannot stall at one end.
                (Some(b), Some(a)) => {
                    let falsi = b.depth + (target - b.force) * (a.depth - b.depth) / (a.force - b.force);
                    let middle = 0.5 * (a.depth + b.depth);
                    if last.is_some_and(|l| (l.force < target) == (now.force < target)) {
                        0.5 * (falsi + middle)
                    } else {
                        falsi
                    }
                }
                _ => match stiffness {
                    Some(stiffness) => now.depth + (target - now.force) / stiffness,
                    None => now.depth + (target - now.force).signum() * PROBE * element,
                },
            };
            last = Some(now);
        }
        Err(ProtocolError::NormalForceNotHeld {
            step,
            force: target,
            trials: MAX_TRIALS,
        })
    }
}

/// The counters of rejected trials (their fields and energies are undone with them).
#[derive(Debug, Clone, Copy, Default)]
struct Spent {
    solves: usize,
    cg_iterations: usize,
    operator_applications: u64,
    window_applications: u64,
    preconditioner_applications: u64,
    tangential_rounds: usize,
    tangential_iterations: usize,
    transform_pairs: u64,
    rounds: usize,
}

impl Spent {
    /// Adds a trial's counters.
    fn count(&mut self, trial: &RoundsStep) {
        self.solves += trial.normal.solves;
        self.cg_iterations += trial.normal.cg_iterations;
        self.operator_applications += trial.normal.operator_applications;
        self.window_applications += trial.normal.window_applications;
        self.preconditioner_applications += trial.normal.preconditioner_applications;
        self.tangential_rounds += trial.tangential.rounds;
        self.tangential_iterations += trial.tangential.cg_iterations;
        self.transform_pairs += trial.tangential.transform_pairs;
        self.rounds += trial.rounds;
    }

    /// Adds the counters to the accepted trial's.
    fn add_to(self, step: &mut RoundsStep) {
        step.normal.solves += self.solves;
        step.normal.cg_iterations += self.cg_iterations;
        step.normal.operator_applications += self.operator_applications;
        step.normal.window_applications += self.window_applications;
        step.normal.preconditioner_applications += self.preconditioner_applications;
        step.tangential.rounds += self.tangential_rounds;
        step.tangential.cg_iterations += self.tangential_iterations;
        step.tangential.transform_pairs += self.transform_pairs;
        step.rounds += self.rounds;
    }
}
