//! One shift step of the shear protocol: the normal problem held (Cattaneo–Mindlin),
//! moved along an inclined path, weakened at its edge by the shear or solved in turn with
//! the tangential problem (the coupled operator), and the tangential problem solved on the
//! contact's room.

use super::coupled::Coupling;
use super::edge::{EdgeWeakening, NormalSide, Weakening};
use super::held_force::{HeldForce, TrialStep};
use super::mixity::ModeMixity;
use super::window::TangentialRoom;
use crate::elastic::cerruti::ShearMaterial;
use crate::elastic::{ElasticOperator, ShearBody};
use crate::protocol::{NormalSolver, ProtocolError};
use crate::solver::{ContactState, StepReport, TangentialReport, TangentialSolver};

/// Elements of margin around the contact at rest in the window of a shear whose contact
/// changes (weakened or inclined): room to move before the window must widen.
const MOVING_WINDOW_MARGIN: usize = 4;

/// How the normal problem behaves during the shift.
enum NormalMode {
    /// Held: the contact and pressure of the end of the approach (Goodman).
    Held,
    /// Solved again at each step's depth (an inclined path).
    Moving,
    /// Solved again with the shear-weakened detachment rule, in rounds.
    Weakened(Box<EdgeWeakening>),
    /// Solved in turn with the tangential problem through the coupled operator.
    Coupled(Box<Coupling>),
}

/// What a shift step imposes.
#[derive(Debug, Clone, Copy)]
pub(super) enum ShiftTarget {
    /// The indenter's shift (the drive's position under a compliant drive).
    Shift([f64; 2]),
    /// The tangential force along the unit vector (the normal problem held, or solved in
    /// turn with the tangential one by the coupled operator).
    Force { unit: [f64; 2], force: f64 },
}

impl ShiftTarget {
    /// The tangential step on `room` to this target, the normal problem `normal` (on the
    /// room's window) given: to the shift, or to the force, the shift found with it.
    pub(super) fn solve(
        self,
        friction: &mut TangentialSolver,
        room: &mut TangentialRoom,
        normal: &ContactState,
        step: usize,
    ) -> Result<TangentialReport, ProtocolError> {
        let along = self.named_shift(room.state.shift);
        let solved = match self {
            Self::Shift(shift) => friction.step(room.operator.as_mut(), normal, shift, &mut room.state),
            Self::Force { unit, force } => {
                friction.step_to_force(room.operator.as_mut(), normal, unit, force, &mut room.state)
            }
        };
        solved.map_err(|source| ProtocolError::Tangential {
            step,
            shift: along,
            source,
        })
    }

    /// The shift an error names: the imposed one, or the indenter's `start` at the step's
    /// start.
    pub(super) fn named_shift(self, start: [f64; 2]) -> f64 {
        let shift = match self {
            Self::Shift(shift) => shift,
            Self::Force { .. } => start,
        };
        shift[0].hypot(shift[1])
    }

    /// The drive's position after a step that reported `solved`: the imposed shift, or the
    /// one the force found.
    pub(super) fn drive(self, solved: &TangentialReport) -> [f64; 2] {
        match self {
            Self::Shift(shift) => shift,
            Self::Force { .. } => solved.shift,
        }
    }
}

/// What a shift step did.
pub(super) struct ShiftOutcome {
    /// The final tangential solve, with the counters of all its rounds.
    pub tangential: TangentialReport,
    /// The normal steps of the shift step (the held force alone when held).
    pub normal: StepReport,
    /// The depth found under normal-force control (None: the step's depth).
    pub depth: Option<f64>,
}

/// The state of the shift steps of a run.
pub(super) struct ShiftStepper {
    pub(super) room: TangentialRoom,
    mode: NormalMode,
    /// Normal-force control of a weakened edge (None: the depth is held).
    held: Option<HeldForce>,
    /// The normal state on the room's window.
    window_state: ContactState,
}

impl ShiftStepper {
    /// The stepper for the contact of `state` at the end of the approach; `inclined` when
    /// the depth changes along the shift. Its operators are built on the grid and by the
    /// backend of the run's normal `operator`.
    pub(super) fn new(
        operator: &dyn ElasticOperator,
        state: &ContactState,
        body: ShearBody,
        mode_mixity: ModeMixity,
        inclined: bool,
        coupled: bool,
        solver: &mut NormalSolver,
    ) -> Result<Self, ProtocolError> {
        let material = body.material;
        let (grid, backend) = (operator.grid(), operator.backend());
        if coupled {
            // The room follows the contact as it grows from nothing in the approach.
            let room = TangentialRoom::new(grid, &state.contact, MOVING_WINDOW_MARGIN, (body, backend))?;
            return Ok(Self {
                window_state: room.window.gather(state),
                room,
                mode: NormalMode::Coupled(Box::new(Coupling::new(grid, (body, backend))?)),
                held: None,
            });
        }
        let changes = mode_mixity.weakens() || inclined;
        let margin = if changes { MOVING_WINDOW_MARGIN } else { 0 };
        let room = TangentialRoom::new(grid, &state.contact, margin, (body, backend))?;
        let mode = match (mode_mixity.weakens(), solver.as_adhesive_mut()) {
            (true, Some(adhesive)) => NormalMode::Weakened(Box::new(EdgeWeakening::new(
                adhesive,
                material,
                mode_mixity,
                &room.window,
            ))),
            (true, None) => return Err(needs_adhesion(mode_mixity)),
            (false, _) if inclined => NormalMode::Moving,
            (false, _) => NormalMode::Held,
        };
        Ok(Self {
            window_state: room.window.gather(state),
            room,
            mode,
            held: None,
        })
    }

    /// One step to the tangential `target` at `normal.depth`; `held_force` is the normal
    /// force of a held normal problem.
    pub(super) fn step(
        &mut self,
        normal: NormalSide<'_>,
        friction: &mut TangentialSolver,
        target: ShiftTarget,
        step: usize,
        held_force: f64,
    ) -> Result<ShiftOutcome, ProtocolError> {
        if let (ShiftTarget::Force { .. }, NormalMode::Moving | NormalMode::Weakened(_)) = (target, &self.mode) {
            return Err(ProtocolError::InvalidParameter(
                "an imposed tangential force holds the normal problem fixed or solves it with the coupled operator's rounds (no incline, no mode_mixity)".into(),
            ));
        }
        let rounds: &mut dyn TrialStep = match &mut self.mode {
            NormalMode::Coupled(coupling) => coupling.as_mut(),
            NormalMode::Weakened(edge) => edge.as_mut(),
            NormalMode::Moving | NormalMode::Held => {
                return self.step_whole(normal, friction, target, step, held_force)
            }
        };
        let (solved, depth) = match &mut self.held {
            Some(held) => {
                let (solved, depth) = held.step(rounds, normal, (&mut self.room, friction), (target, step))?;
                (solved, Some(depth))
            }
            None => (rounds.run(normal, &mut self.room, friction, target, step)?, None),
        };
        Ok(ShiftOutcome {
            tangential: solved.tangential,
            normal: solved.normal,
            depth,
        })
    }

    /// A step of a normal problem held or moved along an incline (no rounds): the normal
    /// step at the step's depth where it moves, then the tangential step to `target`.
    fn step_whole(
        &mut self,
        normal: NormalSide<'_>,
        friction: &mut TangentialSolver,
        target: ShiftTarget,
        step: usize,
        held_force: f64,
    ) -> Result<ShiftOutcome, ProtocolError> {
        let mut outcome = ShiftOutcome {
            tangential: TangentialReport::default(),
            normal: held(held_force),
            depth: None,
        };
        let mut widened = 0;
        if let NormalMode::Moving = self.mode {
            outcome.normal = normal
                .solver
                .step(normal.operator, normal.heights, normal.depth, normal.state)
                .map_err(|source| ProtocolError::Solve {
                    step,
                    depth: normal.depth,
                    source,
                })?;
            widened = self.room.cover(&normal.state.contact)?;
            if self.window_state.contact.len() != self.room.window.grid.len() {
                self.window_state = ContactState::new(&self.room.window.grid);
            }
            self.room.window.gather_into(normal.state, &mut self.window_state);
        }
        outcome.tangential = target.solve(friction, &mut self.room, &self.window_state, step)?;
        outcome.tangential.transform_pairs += widened;
        Ok(outcome)
    }

    /// Holds the normal force instead of the depth during the shift (`hold`; else nothing).
    /// Only a weakened edge changes the normal problem at a held depth; a held one keeps its
    /// force anyway, and an inclined or coupled one is refused.
    pub(super) fn hold_normal_force(&mut self, hold: bool) -> Result<(), ProtocolError> {
        if !hold {
            return Ok(());
        }
        match self.mode {
            NormalMode::Weakened(_) | NormalMode::Coupled(_) => {
                self.held = Some(HeldForce {
                    target: None,
                    depth: None,
                    stiffness: None,
                });
                Ok(())
            }
            NormalMode::Held => Ok(()),
            NormalMode::Moving => Err(ProtocolError::InvalidParameter(
                "normal-force control finds each shift step's depth, which an inclined path (incline ≠ 0) prescribes: hold the depth instead".into(),
            )),
        }
    }

    /// Weakens the adhesive edge of a coupled shift by the shear it carries (`mode_mixity`
    /// above 0; else nothing), from the σ_c the approach ends with: the shift's steps, not
    /// the approach's, weaken the edge, as without the coupling.
    pub(super) fn weaken_coupled_edge(
        &mut self,
        mode_mixity: ModeMixity,
        material: ShearMaterial,
        solver: &mut NormalSolver,
    ) -> Result<(), ProtocolError> {
        let NormalMode::Coupled(coupling) = &mut self.mode else {
            return Ok(());
        };
        if !mode_mixity.weakens() {
            return Ok(());
        }
        let Some(adhesive) = solver.as_adhesive_mut() else {
            return Err(needs_adhesion(mode_mixity));
        };
        coupling.weaken_edge(Weakening::new(adhesive, material, mode_mixity));
        Ok(())
    }

    /// Gives the normal solver back its unweakened detachment rule.
    pub(super) fn finish(self, solver: &mut NormalSolver) {
        match (self.mode, solver.as_adhesive_mut()) {
            (NormalMode::Weakened(edge), Some(adhesive)) => edge.restore(adhesive),
            (NormalMode::Coupled(coupling), _) => coupling.finish(solver),
            _ => {}
        }
    }
}

/// The report of a held normal problem: unchanged, no normal solve in the step.
fn held(force: f64) -> StepReport {
    StepReport {
        force,
        force_before_change: force,
        ..StepReport::default()
    }
}

/// The refusal of a mode mixity without the JKR-type adhesive solver.
fn needs_adhesion(mode_mixity: ModeMixity) -> ProtocolError {
    ProtocolError::InvalidParameter(format!(
        "mode_mixity ({mode_mixity:?}) weakens an adhesive edge: it needs the JKR-type adhesive solver"
    ))
}
