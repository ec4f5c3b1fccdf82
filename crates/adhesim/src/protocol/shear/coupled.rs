//! A shear step with the coupled operator (`friction.coupling = "full"`; ν < 1/2, or a
//! layer): the
//! normal and tangential problems solved in turn until they agree (docs/physics.md §8.1).

use super::edge::{add_normal, add_tangential, NormalSide, RoundsStep, Weakening};
use super::held_force::TrialStep;
use super::shift::ShiftTarget;
use super::weakened_slide::adhesive;
use super::window::TangentialRoom;
use crate::elastic::{Backend, CouplingCompliance, ShearBody};
use crate::grid::Grid;
use crate::protocol::{NormalSolver, ProtocolError};
use crate::solver::{ContactState, StepReport, TangentialReport, TangentialSolver, TangentialState};

/// The rounds stop when the normal displacement of the shear tractions, K_zt q, differs
/// from the lift the normal step saw by at most this share of its largest value (and the
/// contact set no longer changes).
const COUPLING_TOLERANCE: f64 = 1e-8;
/// Rounds allowed per step.
const MAX_COUPLING_ROUNDS: usize = 100;
/// Rounds of a step whose contact set returns to the one two rounds back before the rounds
/// are said to alternate: an edge element whose pressure is near nought may leave and come
/// back once while the lift still converges (a translating contact's edge), a ring that
/// flips with the lift does so again and again.
const MAX_ALTERNATIONS: usize = 4;

/// The coupled steps of a run: the coupling operator on the whole grid and the fields it
/// carries from round to round.
pub(super) struct Coupling {
    operator: Box<dyn CouplingCompliance>,
    /// The profile plus the lift: what the normal solver sees.
    heights: Vec<f64>,
    /// The lift v of the profile in the round's normal solve: K_zt q of the tractions,
    /// relaxed (v ← v + ω r).
    lift: Vec<f64>,
    /// K_zt q of the round's tractions.
    image: Vec<f64>,
    /// The residual r = K_zt q − v of this round and of the last.
    residual: [Vec<f64>; 2],
    /// Aitken's relaxation factor ω of the last round.
    relaxation: f64,
    /// K_tz p, per component, of the round's pressure on the whole grid.
    pressure_shift: [Vec<f64>; 2],
    /// K_tz p at the step's start: the pressure's share of the memory's displacement.
    start_shift: [Vec<f64>; 2],
    /// K_tz p on the room's window.
    window_shift: [Vec<f64>; 2],
    /// The shear tractions on the whole grid (zero outside the window).
    traction: [Vec<f64>; 2],
    /// The tangential state at the step's start: each round restarts from it.
    saved: TangentialState,
    /// The last round's tractions on the window: the next round's starting guess (None
    /// once the window has moved).
    warm: Option<[Vec<f64>; 2]>,
    window_state: ContactState,
    /// The edge weakened by the shear it carries (a mode mixity above 0), or None.
    weakening: Option<Weakening>,
    /// The fields a step carries into the next, kept at a step's start for the trials of
    /// normal-force control ([`TrialStep::keep`]).
    kept: Carried,
}

/// The fields of a [`Coupling`] that a step leaves for the next.
#[derive(Default)]
struct Carried {
    lift: Vec<f64>,
    relaxation: f64,
    pressure_shift: [Vec<f64>; 2],
    window_shift: [Vec<f64>; 2],
}

impl Coupling {
    /// The coupling of `grid`: its operator, built by `backend`, acts on the whole grid
    /// (the normal displacement of the tractions reaches every gap), the tangential problem
    /// on the room's window.
    pub(super) fn new(grid: &Grid, (body, backend): (ShearBody, Backend)) -> Result<Self, ProtocolError> {
        let operator = backend
            .coupling_operator(*grid, body)
            .map_err(|error| ProtocolError::InvalidParameter(error.to_string()))?;
        let n = grid.len();
        Ok(Self {
            operator,
            heights: vec![0.0; n],
            lift: vec![0.0; n],
            image: vec![0.0; n],
            residual: [vec![0.0; n], vec![0.0; n]],
            relaxation: 1.0,
            pressure_shift: [vec![0.0; n], vec![0.0; n]],
            start_shift: [vec![0.0; n], vec![0.0; n]],
            window_shift: [Vec::new(), Vec::new()],
            traction: [vec![0.0; n], vec![0.0; n]],
            saved: TangentialState::new(0),
            warm: None,
            window_state: ContactState::new(grid),
            weakening: None,
            kept: Carried::default(),
        })
    }

    /// Weakens the adhesive edge by the shear it carries in every round (docs/physics.md
    /// §8.5): after each tangential solve, σ_c of each contact element is lowered by its
    /// traction (never raised within the step), and the next round's normal step detaches
    /// with it.
    pub(super) fn weaken_edge(&mut self, weakening: Weakening) {
        self.weakening = Some(weakening);
    }

    /// Gives the solver its unweakened σ_c back.
    pub(super) fn finish(&self, solver: &mut NormalSolver) {
        if let (Some(weakening), Some(adhesive)) = (&self.weakening, solver.as_adhesive_mut()) {
            weakening.restore(adhesive);
        }
    }

    /// One step to `target` at `normal.depth` (a block Gauss–Seidel of the coupled problem,
    /// Kalker 1990 §5 / Panagiotopoulos' process): the normal step on the profile raised by
    /// the lift v, the tangential step with the pressure's pull K_tz p, and again, each
    /// round from the step's starting tangential state and v relaxed towards K_zt q
    /// ([`relax`](Self::relax)), until K_zt q meets v and the contact set no longer changes.
    /// Under an imposed force each round's tangential step is force-controlled
    /// ([`TangentialSolver::step_to_force`]): the shift is found again with each round's
    /// pressure and contact.
    pub(super) fn step(
        &mut self,
        normal: NormalSide<'_>,
        room: &mut TangentialRoom,
        friction: &mut TangentialSolver,
        target: ShiftTarget,
        step: usize,
    ) -> Result<RoundsStep, ProtocolError> {
        let along = target.named_shift(room.state.shift);
        let mut total = RoundsStep {
            tangential: TangentialReport::default(),
            normal: StepReport::default(),
            rounds: 0,
        };
        self.saved.clone_from(&room.state);
        self.warm = None;
        for c in 0..2 {
            self.start_shift[c].copy_from_slice(&self.pressure_shift[c]);
        }
        if let Some(weakening) = &mut self.weakening {
            // Each step starts from the unweakened σ_c, as a weakened edge's does.
            weakening.begin();
            weakening.apply(adhesive(normal.solver)?);
        }
        let mut before = normal.state.contact.clone();
        // The contact set two rounds back: a set that returns to it alternates.
        let mut two_back = before.clone();
        let (mut rounds, mut alternations) = (0, 0);
        loop {
            rounds += 1;
            for ((raised, height), lift) in self.heights.iter_mut().zip(normal.heights).zip(&self.lift) {
                *raised = height + lift;
            }
            two_back.copy_from_slice(&before);
            before.copy_from_slice(&normal.state.contact);
            let report = normal
                .solver
                .step(normal.operator, &self.heights, normal.depth, normal.state)
                .map_err(|source| ProtocolError::Solve {
                    step,
                    depth: normal.depth,
                    source,
                })?;
            add_normal(&mut total.normal, report);
            total.tangential.transform_pairs += self.pull(normal.state);
            if rounds > 1 {
                room.state.clone_from(&self.saved);
                friction.forget_predictor();
            }
            total.tangential.transform_pairs += self.follow(room, &normal.state.contact)?;
            if let Some(warm) = &self.warm {
                // The step's memory, from the last round's tractions (the solution is
                // unique: only the start of its rounds changes).
                room.state.traction.clone_from(warm);
            }
            friction.set_pressure_displacement(Some([&self.window_shift[0], &self.window_shift[1]]));
            room.window.gather_into(normal.state, &mut self.window_state);
            let tangential = target.solve(friction, room, &self.window_state, step);
            friction.set_pressure_displacement(None);
            let tangential = tangential?;
            add_tangential(&mut total.tangential, tangential);
            self.warm = Some(room.state.traction.clone());
            let change = self.residual_of(room);
            total.tangential.transform_pairs += 2;
            // A σ_c lowered by this round's tractions: the normal step must see it.
            let lowered = match &mut self.weakening {
                Some(weakening) => {
                    weakening.weaken(&room.window, &self.window_state.contact, &room.state);
                    weakening.apply(adhesive(normal.solver)?)
                }
                None => false,
            };
            let settled = change <= COUPLING_TOLERANCE && (rounds > 1 || change == 0.0);
            if settled && !lowered && normal.state.contact == before {
                let drive = target.drive(&tangential);
                let increment = [0, 1].map(|c| drive[c] - self.saved.drive[c]);
                friction.remember_step(&self.saved.traction, increment);
                total.rounds = rounds;
                return Ok(total);
            }
            // An adhesive edge can flip a ring of elements back and forth with the
            // tractions' lift: the rounds then never settle.
            let returned = rounds > 2 && normal.state.contact != before && normal.state.contact == two_back;
            alternations += usize::from(returned);
            let alternating = alternations >= MAX_ALTERNATIONS;
            if rounds >= MAX_COUPLING_ROUNDS || alternating {
                return Err(ProtocolError::CouplingNotConverged {
                    step,
                    shift: along,
                    rounds,
                    change,
                    tolerance: COUPLING_TOLERANCE,
                    alternating,
                });
            }
            self.relax(rounds == 1);
        }
    }

    /// The next round's lift, v ← v + ω r, with Aitken's ω from the last two residuals
    /// (Irons & Tuck 1969; Küttler & Wall 2008 for coupled problems): for a linear
    /// contraction by ρ it is 1/(1 − ρ), which lands on the fixed point. The first round
    /// of a step takes ω = 1 (a plain Gauss–Seidel round).
    fn relax(&mut self, first: bool) {
        let [current, last] = &self.residual;
        self.relaxation = if first {
            1.0
        } else {
            let (mut along, mut squared) = (0.0, 0.0);
            for (now, then) in current.iter().zip(last) {
                let difference = now - then;
                along += then * difference;
                squared += difference * difference;
            }
            let omega = -self.relaxation * along / squared;
            // Kept within a safe range (a set change can make two residuals unrelated).
            if omega.is_finite() {
                omega.clamp(0.1, 2.0)
            } else {
                1.0
            }
        };
        for (lift, residual) in self.lift.iter_mut().zip(current) {
            *lift += self.relaxation * residual;
        }
    }

    /// Moves the room's window onto the contact where it has left it (the approach's
    /// growing contact; `TangentialRoom::follow`), then gathers K_tz p onto the window.
    /// A moved window recomputes the memory's displacement as K q alone, so the pressure's
    /// share at the step's start is added back, and the rounds restart from there. Returns
    /// the FFT pairs.
    fn follow(&mut self, room: &mut TangentialRoom, contact: &[bool]) -> Result<u64, ProtocolError> {
        let pairs = room.follow(contact)?;
        let window_len = room.window.grid.len();
        if pairs > 0 || self.window_shift[0].len() != window_len {
            for (w, k) in room.window.elements() {
                for c in 0..2 {
                    room.state.displacement[c][w] += self.start_shift[c][k];
                }
            }
            self.saved.clone_from(&room.state);
            self.warm = None;
            self.window_state = ContactState::new(&room.window.grid);
            for shift in &mut self.window_shift {
                shift.clear();
                shift.resize(window_len, 0.0);
            }
        }
        for (w, k) in room.window.elements() {
            for c in 0..2 {
                self.window_shift[c][w] = self.pressure_shift[c][k];
            }
        }
        Ok(pairs)
    }

    /// K_tz p of the normal state into `pressure_shift`; returns the FFT pairs.
    fn pull(&mut self, state: &ContactState) -> u64 {
        let [x, y] = &mut self.pressure_shift;
        self.operator.shear_from_normal(&state.pressure, [x, y]);
        2
    }

    /// K_zt q of the room's tractions into `image` and the residual r = K_zt q − v into
    /// `residual[0]` (the last one into `residual[1]`); returns max|r| relative to
    /// max|K_zt q| (max|r| when that vanishes).
    fn residual_of(&mut self, room: &TangentialRoom) -> f64 {
        for (c, traction) in self.traction.iter_mut().enumerate() {
            traction.fill(0.0);
            for (w, k) in room.window.elements() {
                traction[k] = room.state.traction[c][w];
            }
        }
        self.operator
            .normal_from_shear([&self.traction[0], &self.traction[1]], &mut self.image);
        let [current, last] = &mut self.residual;
        std::mem::swap(current, last);
        let (mut change, mut largest) = (0.0f64, 0.0f64);
        for ((residual, image), lift) in current.iter_mut().zip(&self.image).zip(&self.lift) {
            *residual = image - lift;
            change = change.max(residual.abs());
            largest = largest.max(image.abs());
        }
        if largest > 0.0 {
            change / largest
        } else {
            change
        }
    }
}

/// The coupled step under normal-force control: its lift and the pressure's pull are what
/// one step leaves the next, kept at the step's start and put back before each trial.
impl TrialStep for Coupling {
    fn keep(&mut self) {
        self.kept.lift.clone_from(&self.lift);
        self.kept.relaxation = self.relaxation;
        self.kept.pressure_shift.clone_from(&self.pressure_shift);
        self.kept.window_shift.clone_from(&self.window_shift);
    }

    /// A room whose window a trial widened comes back with the memory's displacement K q
    /// alone; the kept window's K_tz p has another size then, so the next round adds the
    /// pressure's share back (`follow`).
    fn put_back(&mut self) {
        self.lift.clone_from(&self.kept.lift);
        self.relaxation = self.kept.relaxation;
        self.pressure_shift.clone_from(&self.kept.pressure_shift);
        self.window_shift.clone_from(&self.kept.window_shift);
    }

    fn run(
        &mut self,
        normal: NormalSide<'_>,
        room: &mut TangentialRoom,
        friction: &mut TangentialSolver,
        target: ShiftTarget,
        step: usize,
    ) -> Result<RoundsStep, ProtocolError> {
        self.step(normal, room, friction, target, step)
    }
}
