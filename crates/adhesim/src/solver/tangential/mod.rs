//! Tangential contact with friction: shear tractions, stick and slip, with memory.
//!
//! The normal problem decides the contact set C and the pressure p (Goodman's
//! approximation: a shear traction does not move the surface normally, docs/physics.md
//! §8.1; the coupled operator of §8.1a adds the pressure's tangential displacement,
//! [`TangentialSolver::set_pressure_displacement`]); on C a [`FrictionLaw`] bounds each
//! traction, |q_i| ≤ g_i. The indenter is shifted tangentially by δ. An element sticks when
//! its relative tangential displacement is that of the last step: u_i = u_i⁻ + Δδ =: w_i. An element slips when |q_i| = g_i, with q_i
//! along its slip increment Δs_i = w_i − u_i (friction drags the body along). These are the
//! optimality conditions of min ½qᵀKq − qᵀw over the discs |q_i| ≤ g_i (Kalker 1990, *Three-
//! Dimensional Elastic Bodies in Rolling Contact*, §5), a strictly convex problem with one
//! solution per step.
//!
//! Solved by a semismooth Newton active set (Alart & Curnier 1991, *Comput. Methods Appl.
//! Mech. Eng.* 92, 353; Kalker's active set with the slip directions in the Newton
//! step): each element's point z = q + ρ(w − u), ρ = 1/K_ii, decides it: inside its disc it
//! sticks, outside it slips with q = g·z/|z|. The Newton step is one linear solve by
//! preconditioned CG on the face of the sets: sticking tractions free, slipping ones
//! free only to turn along their circle, held by the spring of the projection's
//! derivative. Rounds repeat until no element changes and no slipping traction turns by
//! more than `direction_tolerance`; every element's optimality conditions are then
//! measured and reported ([`Complementarity`]).

mod law;

pub use law::{FrictionLaw, FrictionLawError};

use super::ContactState;
use crate::elastic::ShearCompliance;
use thiserror::Error;

/// The tangential state of an element.
///
/// # Example
/// ```
/// use adhesim::{SlipStatus, TangentialState};
///
/// let mut state = TangentialState::new(3);
/// state.status = vec![SlipStatus::Stick, SlipStatus::Slip, SlipStatus::Open];
/// assert_eq!(state.counts(), (1, 1));
/// assert_eq!(state.status.iter().map(|s| s.code()).collect::<Vec<_>>(), [1, 2, 0]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum SlipStatus {
    /// Not in contact: no traction.
    #[default]
    Open,
    /// In contact, |q| below its bound, no relative motion in this step.
    Stick,
    /// In contact, |q| at its bound, along the slip.
    Slip,
}

impl SlipStatus {
    /// 0 open, 1 stick, 2 slip (as the field files store it).
    pub fn code(self) -> u8 {
        match self {
            Self::Open => 0,
            Self::Stick => 1,
            Self::Slip => 2,
        }
    }
}

/// Tangential fields of a configuration; also the memory of the next step.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TangentialState {
    /// Shear traction (q_x, q_y) on the body, per element.
    pub traction: [Vec<f64>; 2],
    /// Tangential surface displacement (u_x, u_y) = K q, per element.
    pub displacement: [Vec<f64>; 2],
    /// Accumulated slip (s_x, s_y) of each element: the sum of its slip increments.
    pub slip: [Vec<f64>; 2],
    /// Open, stick or slip, per element.
    pub status: Vec<SlipStatus>,
    /// The indenter's tangential shift δ of the last step.
    pub shift: [f64; 2],
    /// The drive's position X of the last step: the shift itself under a rigid drive, the
    /// far end of the spring under a compliant one ([`TangentialSolver::with_drive_stiffness`]).
    #[cfg_attr(feature = "serde", serde(default))]
    pub drive: [f64; 2],
    /// The last step was a slip event (docs/physics.md §8.2): the contact has come to rest
    /// and every element starts the next step stuck under its static bound.
    #[cfg_attr(feature = "serde", serde(default))]
    pub at_rest: bool,
    /// The slip |s| each element has made since it last stuck, under slip weakening
    /// ([`TangentialSolver::with_slip_weakening`]; empty without it).
    #[cfg_attr(feature = "serde", serde(default, skip_serializing_if = "Vec::is_empty"))]
    pub slip_since_stuck: Vec<f64>,
}

impl TangentialState {
    /// No traction, no shift.
    pub fn new(elements: usize) -> Self {
        let zeros = || [vec![0.0; elements], vec![0.0; elements]];
        Self {
            traction: zeros(),
            displacement: zeros(),
            slip: zeros(),
            status: vec![SlipStatus::Open; elements],
            shift: [0.0; 2],
            drive: [0.0; 2],
            at_rest: false,
            slip_since_stuck: Vec::new(),
        }
    }

    /// Δ²Σq: the tangential force on the body (the indenter's resistance to its shift).
    pub fn force(&self, element_area: f64) -> [f64; 2] {
        [0, 1].map(|c| element_area * self.traction[c].iter().sum::<f64>())
    }

    /// (stick, slip) element counts.
    pub fn counts(&self) -> (usize, usize) {
        let stick = self.status.iter().filter(|s| **s == SlipStatus::Stick).count();
        let slip = self.status.iter().filter(|s| **s == SlipStatus::Slip).count();
        (stick, slip)
    }
}

/// Stopping rules of the tangential solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TangentialParams {
    /// The final Newton rounds' CG stops at ‖w − u‖₂ ≤ tolerance·‖w‖₂ over the face
    /// (rounds whose sets still change solve to 1e-5).
    pub tolerance: f64,
    /// CG iterations per Newton round.
    pub max_iterations: usize,
    /// Newton rounds per step.
    pub max_rounds: usize,
    /// A slip traction turning by less than this (radians) no longer counts as a change:
    /// its traction then moves by less than this fraction of its bound. (The directions of
    /// elements that barely slip carry the CG's error; 1e-8 is below that floor.)
    pub direction_tolerance: f64,
}

impl Default for TangentialParams {
    fn default() -> Self {
        Self {
            tolerance: 1e-10,
            max_iterations: 2000,
            max_rounds: 200,
            direction_tolerance: 1e-6,
        }
    }
}

/// How well a solution meets the optimality conditions, each relative: displacements to
/// max|w| over C, tractions to the largest bound.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Complementarity {
    /// max over stick elements of |w − u|.
    pub stick_residual: f64,
    /// max over contact elements of (|q| − g)⁺.
    pub bound_excess: f64,
    /// max over slip elements of the slip increment's part across the traction.
    pub slip_misalignment: f64,
    /// max over slip elements of the slip increment's part against the traction.
    pub backward_slip: f64,
}

/// What a tangential step did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TangentialReport {
    /// Active-set rounds.
    pub rounds: usize,
    /// CG iterations over all rounds.
    pub cg_iterations: usize,
    /// Forward + inverse FFT pairs spent.
    pub transform_pairs: u64,
    /// Elements sticking.
    pub stick_elements: usize,
    /// Elements slipping.
    pub slip_elements: usize,
    /// Δ²Σq at the end of the step.
    pub force: [f64; 2],
    /// Δ²Σ q·Δs over the slipping elements: the energy friction dissipated in the step.
    pub dissipated_energy: f64,
    /// The optimality conditions as met.
    pub complementarity: Complementarity,
    /// The indenter's shift δ at the end of the step (the drive's position under a rigid
    /// drive).
    pub shift: [f64; 2],
    /// Elements that broke loose from their static bound in the step.
    pub broke_loose: usize,
    /// The step was a slip event: elements broke loose and the force along the drive's
    /// motion fell.
    pub slip_event: bool,
    /// Solves of a force-controlled step: 1 when it was solved at once, more when it fell
    /// back to displacement-controlled trials (0: the step was displacement-controlled;
    /// [`TangentialSolver::step_to_force`]).
    #[cfg_attr(feature = "serde", serde(default))]
    pub trials: usize,
}

/// Why a tangential step failed.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum TangentialError {
    /// CG on the stick set reached its iteration limit.
    #[error("tangential CG did not converge in {iterations} iterations: residual {relative_residual:.3e} relative, tolerance {tolerance:.1e}")]
    NotConverged {
        /// Iterations done.
        iterations: usize,
        /// ‖w − u‖₂/‖w‖₂ over the stick set.
        relative_residual: f64,
        /// The tolerance.
        tolerance: f64,
    },
    /// The stick and slip sets still changed after the round limit.
    #[error("stick and slip sets still changing after {rounds} active-set rounds ({changes} changes in the last; with none, slip directions or slip-weakened bounds still moving)")]
    SetsNotSettled {
        /// Rounds done.
        rounds: usize,
        /// Elements that changed in the last round.
        changes: usize,
    },
    /// A non-finite number appeared.
    #[error("non-finite value in the tangential solve at CG iteration {0}")]
    NonFinite(usize),
    /// An imposed force at or beyond what the interface holds: the contact would slide
    /// without end.
    #[error("the imposed tangential force {force:e} reaches what the interface holds, {capacity:e} (Δ² times the sum of the friction bounds over the contact): no shift carries it, the contact slides; impose a smaller force or control the shift")]
    ForceBeyondCapacity {
        /// The imposed force along the direction.
        force: f64,
        /// Δ²Σg over the contact.
        capacity: f64,
    },
    /// The trials of a force-controlled step neither met the force nor bracketed it.
    #[error(
        "the imposed tangential force {target:e} was not reached in {trials} trial steps (last force {reached:e})"
    )]
    ForceNotReached {
        /// The imposed force.
        target: f64,
        /// The force of the last trial.
        reached: f64,
        /// Trial steps done.
        trials: usize,
    },
    /// Force control with a static law or a compliant drive.
    #[error("a tangential force cannot be imposed with a static friction law or a compliant drive: their force falls in a slip event, which no imposed force can follow quasi-statically")]
    ForceControlUnsupported,
    /// The normal state does not match the operator's grid.
    #[error("normal state has {got} elements, the grid {expected}")]
    GridMismatch {
        /// The grid's elements.
        expected: usize,
        /// The state's.
        got: usize,
    },
}

/// CG tolerance of the rounds whose sets still change.
const LOOSE_TOLERANCE: f64 = 1e-5;
/// Below this largest turn (radians) with no set change, the rounds solve tightly.
const LOOSE_TURN: f64 = 1e-3;
/// At most this many loose rounds per step.
const LOOSE_ROUNDS: usize = 4;

/// The tractions before a step and the step's shift increment (the predictor's guide).
pub(crate) type StepHistory = ([Vec<f64>; 2], [f64; 2]);

/// The semismooth Newton active-set solver of the tangential problem (see the module).
///
/// # Example
/// A rigid flat punch glued over a 3 × 3 patch of a free grid and shifted by δ: every
/// element sticks, and the force is the stiffness of the patch times δ (positive along the
/// shift, nothing across it).
/// ```
/// use adhesim::{Boundary, ContactState, FrictionLaw, Grid, ShearMaterial};
/// use adhesim::{TangentialOperator, TangentialParams, TangentialSolver, TangentialState};
///
/// let grid = Grid::new(8, 1.0, Boundary::Free)?;
/// let material = ShearMaterial::from_contact_modulus(4.0, 0.5);
/// let mut operator = TangentialOperator::new(grid, material)?;
/// let mut normal = ContactState::new(&grid);
/// for k in 0..grid.len() {
///     let (x, y) = grid.centre(k);
///     if x.abs() < 0.25 && y.abs() < 0.25 {
///         normal.contact[k] = true;
///         normal.pressure[k] = 1.0;
///     }
/// }
/// let mut solver = TangentialSolver::new(FrictionLaw::NoSlip, TangentialParams::default());
/// let mut state = TangentialState::new(grid.len());
/// let report = solver.step(&mut operator, &normal, [1e-3, 0.0], &mut state)?;
/// assert_eq!((report.stick_elements, report.slip_elements), (9, 0));
/// assert!(report.force[0] > 0.0 && report.force[1].abs() < 1e-8 * report.force[0]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct TangentialSolver {
    law: FrictionLaw,
    /// The static law of elements stuck at the start of a step (None: the kinetic `law`).
    static_law: Option<FrictionLaw>,
    /// The kinetic bound per element (0 off contact): an element that breaks loose in a
    /// step drops from its static bound to this one for the rest of the step.
    kinetic: Vec<f64>,
    /// Slip weakening's distance D_c (None: the drop to the kinetic bound is at once).
    weakening_distance: Option<f64>,
    /// The static bound per element, and the slip since it last stuck at the step's start
    /// (under slip weakening).
    static_bound: Vec<f64>,
    slip_before: Vec<f64>,
    params: TangentialParams,
    /// w = u⁻ + Δδ per component.
    target: [Vec<f64>; 2],
    /// CG residual w − u on the stick set.
    residual: [Vec<f64>; 2],
    /// CG search direction (zero off the stick set).
    direction: [Vec<f64>; 2],
    /// K·direction.
    applied: [Vec<f64>; 2],
    /// g per element (0 off contact).
    bound: Vec<f64>,
    /// Unit direction e of each slipping traction in the current round.
    unit: Vec<(f64, f64)>,
    /// Spring σ of each slipping traction's turn in the current round.
    spring: Vec<f64>,
    /// The tractions before the last step and that step's shift increment: the predictor
    /// of the next step's start (None before a first step on this grid).
    history: Option<StepHistory>,
    /// Stiffness k of the spring between the drive and the indenter (None: a rigid drive).
    drive_stiffness: Option<f64>,
    /// Δ²/k of the step (0 under a rigid drive): the indenter lags the drive by this times
    /// Σq per component.
    drive_compliance: f64,
    /// X − δ per component: the spring's stretch, (Δ²/k)·Σq.
    drive_offset: [f64; 2],
    /// Elements that broke loose from a static bound in the step.
    broke_loose: usize,
    /// The secant stiffness dF/dδ of the last force-controlled step: its successor's
    /// first trial.
    force_stiffness: Option<f64>,
    /// The tangential displacement of the step's pressure, per component (empty: none,
    /// Goodman's approximation; [`set_pressure_displacement`](Self::set_pressure_displacement)).
    pressure_displacement: [Vec<f64>; 2],
    /// The slip a solve to the full tolerance resolves, tolerance·‖w‖₂ over the face: a
    /// slipping element whose slip is below it keeps slipping in a gross slide or once the
    /// rounds cycle (`classify`).
    gap_floor: f64,
    /// The imposed force of a step solved at once (None: the shift is imposed).
    constraint: Option<constraint::ForceConstraint>,
    /// The step moves the drive on from a gross slide: no element of the last step's
    /// contact stuck, and the contact is not at rest.
    gross_slide: bool,
}

impl TangentialSolver {
    /// A solver of `law` with `params`.
    pub fn new(law: FrictionLaw, params: TangentialParams) -> Self {
        Self {
            law,
            static_law: None,
            kinetic: Vec::new(),
            weakening_distance: None,
            static_bound: Vec::new(),
            slip_before: Vec::new(),
            params,
            target: [Vec::new(), Vec::new()],
            residual: [Vec::new(), Vec::new()],
            direction: [Vec::new(), Vec::new()],
            applied: [Vec::new(), Vec::new()],
            bound: Vec::new(),
            unit: Vec::new(),
            spring: Vec::new(),
            history: None,
            drive_stiffness: None,
            drive_compliance: 0.0,
            drive_offset: [0.0; 2],
            broke_loose: 0,
            force_stiffness: None,
            pressure_displacement: [Vec::new(), Vec::new()],
            gap_floor: 0.0,
            gross_slide: false,
            constraint: None,
        }
    }

    /// The interface law.
    pub fn law(&self) -> FrictionLaw {
        self.law
    }

    /// The same solver with a static law above the kinetic one: an element stuck at the
    /// start of a step holds up to the static bound; once it slips it holds the kinetic
    /// bound until the step ends, and its neighbours take up the difference (stick–slip
    /// needs such a drop; docs/physics.md §8.2). An error for a static law of another kind
    /// or below the kinetic law anywhere.
    pub fn with_static_law(mut self, static_law: FrictionLaw) -> Result<Self, FrictionLawError> {
        if !static_law.holds_at_least(&self.law) {
            return Err(FrictionLawError::StaticBelowKinetic {
                static_law,
                kinetic: self.law,
            });
        }
        self.static_law = Some(static_law);
        Ok(self)
    }

    /// The static law (None: the kinetic law holds throughout).
    pub fn static_law(&self) -> Option<FrictionLaw> {
        self.static_law
    }

    /// Element `i` breaks loose: from its static bound to its kinetic one (under slip
    /// weakening, the bound falls with its slip instead: [`Self::weaken`]).
    #[inline]
    fn break_loose(&mut self, i: usize) {
        if self.bound[i] > self.kinetic[i] {
            self.broke_loose += 1;
        }
        if self.weakening_distance.is_none() {
            self.bound[i] = self.kinetic[i];
        }
    }

    /// One quasi-static step to the shift `shift` = δ on the contact set and pressure of
    /// `normal`; `state` holds the last step's fields and receives this one's. With a
    /// compliant drive, `shift` is the drive's position X and the indenter's δ follows
    /// from the balance of the spring ([`TangentialReport::shift`]).
    pub fn step(
        &mut self,
        operator: &mut dyn ShearCompliance,
        normal: &ContactState,
        shift: [f64; 2],
        state: &mut TangentialState,
    ) -> Result<TangentialReport, TangentialError> {
        let n = operator.grid().len();
        if normal.contact.len() != n || state.status.len() != n {
            return Err(TangentialError::GridMismatch {
                expected: n,
                got: normal.contact.len().min(state.status.len()),
            });
        }
        self.check_pressure_displacement(n)?;
        let pairs_before = operator.transform_pairs();
        let before = state.traction.clone();
        // The drive's increment (the shift's under a rigid drive).
        let increment = [shift[0] - state.drive[0], shift[1] - state.drive[1]];
        self.drive_compliance = self
            .drive_stiffness
            .map_or(0.0, |stiffness| operator.grid().element_area() / stiffness);
        self.broke_loose = 0;
        self.gross_slide = increment != [0.0, 0.0]
            && !state.at_rest
            && state.status.contains(&SlipStatus::Slip)
            && !state.status.contains(&SlipStatus::Stick);
        self.prepare(normal, shift, state, n);
        let rho = 1.0 / operator.self_compliance();
        self.predict(normal, increment, state, rho);
        let mut report = TangentialReport::default();
        // Inexact Newton: while the sets still change, a loose solve decides them as well;
        // the rounds that may end the step solve to the full tolerance.
        let mut settling = true;
        loop {
            let tolerance = if settling {
                LOOSE_TOLERANCE.max(self.params.tolerance)
            } else {
                self.params.tolerance
            };
            report.cg_iterations += self.solve_face(operator, state, tolerance)?;
            report.rounds += 1;
            let (changes, turn) = self.classify(normal, state, rho, report.rounds);
            if !settling && changes == 0 && turn <= self.params.direction_tolerance {
                break;
            }
            // Loose solves decide the sets near their boundary by a margin of their error:
            // a few rounds of them, then the tight ones decide.
            settling = report.rounds < LOOSE_ROUNDS && (changes > 0 || turn > LOOSE_TURN);
            if report.rounds >= self.params.max_rounds {
                return Err(TangentialError::SetsNotSettled {
                    rounds: report.rounds,
                    changes,
                });
            }
        }
        // The displacement of the final tractions, exactly (the last turns of slip
        // tractions below the direction tolerance are not yet in u).
        {
            let [ux, uy] = &mut state.displacement;
            operator.apply([&state.traction[0], &state.traction[1]], [ux, uy]);
        }
        self.refresh_drive_offset(state);
        // Under force control the shift (and with it the targets) is what the solve found;
        // the targets' scale is taken from them as they end.
        let shift = self.solved_shift(shift);
        let scale = self.target_scale(normal);
        let increment = [shift[0] - state.drive[0], shift[1] - state.drive[1]];
        self.record_weakening_slip(normal, state);
        self.finish(operator, normal, shift, state, scale, &mut report);
        self.add_pressure_displacement(state);
        self.note_slip_event(&before, increment, state, &mut report);
        self.history = Some((before, increment));
        report.transform_pairs = operator.transform_pairs() - pairs_before;
        Ok(report)
    }

    /// Targets, bounds and the starting sets (with [`FrictionLaw::NoSlip`] the target is the
    /// shift itself: the body is glued to the indenter): open off contact; an element with no bound
    /// slips freely; a slipping element keeps its direction at its new bound; the others
    /// (new ones with no traction) start stuck.
    fn prepare(&mut self, normal: &ContactState, shift: [f64; 2], state: &mut TangentialState, n: usize) {
        for buffer in [
            &mut self.target,
            &mut self.residual,
            &mut self.direction,
            &mut self.applied,
        ] {
            for component in buffer.iter_mut() {
                component.clear();
                component.resize(n, 0.0);
            }
        }
        self.bound.clear();
        self.bound.resize(n, 0.0);
        self.kinetic.clear();
        self.kinetic.resize(n, 0.0);
        for buffer in [&mut self.static_bound, &mut self.slip_before] {
            buffer.clear();
            buffer.resize(n, 0.0);
        }
        self.unit.clear();
        self.unit.resize(n, (0.0, 0.0));
        self.spring.clear();
        self.spring.resize(n, 0.0);
        // X − δ⁻: the stuck displacement's advance if the spring keeps its stretch.
        let advance = [shift[0] - state.shift[0], shift[1] - state.shift[1]];
        // Glued (no slip): every contact element moves with the indenter, one that
        // touches again included; otherwise an element sticks where it is.
        let glued = self.law == FrictionLaw::NoSlip;
        for i in 0..n {
            for c in 0..2 {
                self.target[c][i] = if glued {
                    shift[c]
                } else {
                    state.displacement[c][i] + advance[c]
                };
            }
            if let Some(coupled) = self.pressure_displacement[0].get(i) {
                // The solve works on K q: the pressure's share is off the target.
                self.target[0][i] -= coupled;
                self.target[1][i] -= self.pressure_displacement[1][i];
            }
            if !normal.contact[i] {
                state.status[i] = SlipStatus::Open;
                state.traction[0][i] = 0.0;
                state.traction[1][i] = 0.0;
                continue;
            }
            let (qx, qy) = (state.traction[0][i], state.traction[1][i]);
            let magnitude = qx.hypot(qy);
            let kinetic = self.law.bound(normal.pressure[i]);
            // After a slip event the contact is at rest: every element starts stuck.
            let slipping = !state.at_rest && state.status[i] == SlipStatus::Slip && magnitude > 0.0;
            // A slipping element keeps slipping at the kinetic bound; the others start stuck
            // under the static one.
            self.kinetic[i] = kinetic;
            let bound = match self.static_law {
                Some(law) if self.weakening_distance.is_some() => {
                    self.start_weakening(i, law.bound(normal.pressure[i]), slipping, state)
                }
                Some(law) if !slipping => law.bound(normal.pressure[i]),
                _ => kinetic,
            };
            self.bound[i] = bound;
            if bound == 0.0 {
                state.status[i] = SlipStatus::Slip;
                state.traction[0][i] = 0.0;
                state.traction[1][i] = 0.0;
            } else if slipping {
                self.unit[i] = (qx / magnitude, qy / magnitude);
                state.traction[0][i] = bound * qx / magnitude;
                state.traction[1][i] = bound * qy / magnitude;
            } else {
                state.status[i] = SlipStatus::Stick;
            }
        }
    }
}

mod constraint;
mod coupled;
mod drive;
mod force;
mod iterate;
mod predict;
mod weakening;

#[cfg(test)]
mod tests;
