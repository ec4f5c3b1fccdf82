//! Normal-force control of a shear whose edge the shear weakens (`protocol.normal_control
//! = "force"`): each shift step finds the depth at which the weakened step's normal force is
//! the one held (docs/physics.md §8.5), as in Savkoor & Briggs' experiments at constant load.

use super::edge::{EdgeWeakening, NormalSide, WeakenedStep};
use super::window::TangentialRoom;
use crate::protocol::ProtocolError;
use crate::solver::TangentialSolver;

/// Trials (weakened steps at a trial depth) allowed per shift step.
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

impl HeldForce {
    /// One shift step at the held normal force: weakened steps at trial depths, each from
    /// the step's starting state (the normal solver's history restored from its checkpoint,
    /// the tangential fields from the room's snapshot), by secant steps kept inside a
    /// bracket once one exists (a regula falsi), since the force rises with the depth.
    /// Returns the step and its depth.
    pub(super) fn step(
        &mut self,
        edge: &mut EdgeWeakening,
        normal: NormalSide<'_>,
        (room, friction): (&mut TangentialRoom, &mut TangentialSolver),
        (shift, step): ([f64; 2], usize),
    ) -> Result<(WeakenedStep, f64), ProtocolError> {
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
        let Some(adhesive) = solver.as_adhesive_mut() else {
            unreachable!("a weakened edge runs the JKR-type adhesive solver")
        };
        let checkpoint = adhesive.checkpoint();
        let start_room = room.snapshot();
        let (mut below, mut above): (Option<Trial>, Option<Trial>) = (None, None);
        let (mut trial_depth, mut last): (f64, Option<Trial>) = (start_depth, None);
        // The work of the trials before the last: counted, not kept.
        let mut spent = Spent::default();
        for trial in 0..MAX_TRIALS {
            if trial > 0 {
                state.clone_from(&start_state);
                let adhesive = solver.as_adhesive_mut().expect("checked above");
                adhesive
                    .restore(&checkpoint, &start_state)
                    .map_err(ProtocolError::InvalidParameter)?;
                spent.transform_pairs += room.restore(&start_room);
            }
            let side = NormalSide {
                operator: &mut *operator,
                heights,
                depth: trial_depth,
                solver: &mut *solver,
                state: &mut *state,
            };
            let mut result = edge.step(side, room, friction, shift, step)?;
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
    tangential_rounds: usize,
    tangential_iterations: usize,
    transform_pairs: u64,
    rounds: usize,
}

impl Spent {
    /// Adds a trial's counters.
    fn count(&mut self, trial: &WeakenedStep) {
        self.solves += trial.normal.solves;
        self.cg_iterations += trial.normal.cg_iterations;
        self.operator_applications += trial.normal.operator_applications;
        self.tangential_rounds += trial.tangential.rounds;
        self.tangential_iterations += trial.tangential.cg_iterations;
        self.transform_pairs += trial.tangential.transform_pairs;
        self.rounds += trial.rounds;
    }

    /// Adds the counters to the accepted trial's.
    fn add_to(self, step: &mut WeakenedStep) {
        step.normal.solves += self.solves;
        step.normal.cg_iterations += self.cg_iterations;
        step.normal.operator_applications += self.operator_applications;
        step.tangential.rounds += self.tangential_rounds;
        step.tangential.cg_iterations += self.tangential_iterations;
        step.tangential.transform_pairs += self.transform_pairs;
        step.rounds += self.rounds;
    }
}
