//! The adhesive step (docs/physics.md §2.4, docs/fast-step.md): [`AdhesiveSolver`], its
//! parameters and the per-step loop; the fixed-set solve is in `fixed_set`, the release
//! rules (violators, local rounds, failed-ring prediction) in `release`, attachment and
//! predicted-subset growth in `growth`.

mod aging;
mod checkpoint;
mod fixed_set;
mod growth;
mod params;
mod release;
mod ring;
mod set_cg;
mod window;

pub use checkpoint::AdhesiveCheckpoint;
pub use params::{
    critical_stress, detachment_element_size, AdhesiveParams, Attachment, Detachment, PredictedGrowth, StepReport,
    ELEMENT_ENERGY_FACTOR, PREDICTION_MIN_ELEMENTS,
};

use super::local_peel::LocalPeel;
use super::peel_predictor::PeelPredictor;
use super::workspace::Workspace;
use super::{copy_on_pool, ContactState, SolveError};
use crate::elastic::ElasticOperator;
use crate::grid::{Boundary, Grid};
use ring::{RingAttempt, RingPool};
use set_cg::StopRule;
use window::SetWindows;

/// Solves per step after which u is recomputed in double precision (besides the first).
const EXACT_DISPLACEMENT_PERIOD: usize = 32;

/// Quasi-static JKR-type adhesive contact with the local mesh-dependent detachment
/// criterion (Pohrt & Popov 2015; Popov et al. 2021, Sect. 2.2–2.3).
///
/// Per displacement step (docs/physics.md §2.4): CG on the fixed contact set C (warm
/// started), release of elements whose tension exceeds σ_c (failed trial elements
/// first), attachment of penetrating elements and of trial neighbours, repeated until the
/// configuration is stable. Elements released in a step are banned from trial attachment
/// until the contact grows beyond its largest size so far in the step (then all are
/// retried), which makes the loop terminate.
pub struct AdhesiveSolver {
    params: AdhesiveParams,
    grid: Grid,
    /// E*, and the element size Δ of σ_c (for a work of adhesion replaced during a run).
    contact_modulus: f64,
    detachment_size: f64,
    work_of_adhesion: Vec<f64>,
    critical_stress: Vec<f64>,
    minimum_critical_stress: f64,
    // scratch, allocated once
    /// The whole grid's CG buffers and preconditioner (`direction` also carries the
    /// pending pressure change of the next solve; `residual` and `response` are free
    /// between solves).
    work: Workspace,
    preconditioner_applications: u64,
    banned: Vec<bool>,
    trial: Vec<bool>,
    start_contact: Vec<bool>,
    violators: Vec<usize>,
    candidates: Vec<usize>,
    /// Solution on C saved before a trial ring is attached: restored if the whole ring fails.
    saved_pressure: Vec<f64>,
    /// The pressure that `state.displacement` currently belongs to: later solves of a
    /// step update u by the (sparse) pressure change instead of recomputing it.
    displacement_pressure: Vec<f64>,
    saved_displacement: Vec<f64>,
    /// Final states of the last two steps, for the extrapolated warm start.
    history: Vec<(f64, Vec<f64>, Vec<bool>)>,
    /// Completely failed trial rings of the last two steps, for exact prediction.
    ring_history: Vec<RingAttempt>,
    /// The ring being tried in this step.
    current_ring: Option<RingAttempt>,
    /// Recycled buffers of ring records (no allocation per ring round).
    ring_pool: RingPool,
    /// State of the xorshift generator of [`Detachment::RandomHalf`].
    random_state: u64,
    /// Bound on the pressure error of the last solve (docs/fast-step.md).
    pressure_error_bound: f64,
    /// Bound on the gap error of the last solve.
    gap_error_bound: f64,
    /// Whether the last solve stopped early on certified decisions.
    last_solve_certified: bool,
    /// Whether `state.displacement` has been followed by single-precision updates since it
    /// was last computed exactly (a state that ends a step is then converged again from an
    /// exact u: the drift would otherwise reach the reported force at ≈ 1e-6).
    displacement_drifted: bool,
    /// Whether the state saved before a trial ring came from an early stop or had a
    /// drifted displacement (`last_solve_certified || displacement_drifted` when it was
    /// saved): if the ring fails and the saved state ends the step, it is converged again.
    saved_needs_convergence: bool,
    /// Solves stopped early on a certificate, over the solver's life.
    certified_stops: u64,
    /// Tie refinements (docs/fast-step.md §2), and those that did not reach the refined
    /// tolerances, over the solver's life.
    tie_refinements: u64,
    unresolved_ties: u64,
    /// Certified local release rounds (free grids, fast rule only).
    local_peel: Option<LocalPeel>,
    /// Trial elements released by local certificates (without a solve), over the solver's life.
    local_releases: u64,
    /// Predicted-subset growth (docs/fast-step.md §3): the full trial ring R being grown.
    ring_members: Vec<usize>,
    /// The state solved on X ∪ R (pressure, displacement), restored when a predicted subset
    /// fails completely and R is peeled exactly.
    ring_solved_pressure: Vec<f64>,
    ring_solved_displacement: Vec<f64>,
    /// Error bounds and certified flag of that solve.
    ring_solved_bounds: (f64, f64, bool),
    /// Trial members predicted to fail in the current round.
    predicted_failures: Vec<usize>,
    /// Local replay of a peel (with `local_peel`: free grids, fast rule).
    peel_predictor: Option<PeelPredictor>,
    /// Rings grown through a predicted subset, and predicted subsets that failed
    /// completely (the exact peel of the full ring followed), over the solver's life.
    predicted_rings: u64,
    prediction_fallbacks: u64,
    /// Time spent in the local replays of predicted-subset growth, over the solver's life.
    prediction_seconds: f64,
    /// The fixed-set CG's windows on the contact's bounding box (`window`).
    windows: SetWindows,
    /// Applications of the windows' operators over the solver's life.
    window_applications: u64,
    /// The change of p since u was consistent (in `direction`, nonzero on these elements),
    /// left by a solve's start for its CG to apply.
    pending_change: Option<std::ops::Range<usize>>,
}

impl AdhesiveSolver {
    /// A solver for `grid` with the work of adhesion γ per element (row-major) and the
    /// half-space's contact modulus.
    ///
    /// # Panics
    /// If `work_of_adhesion` does not have one value per element.
    pub fn new(grid: Grid, contact_modulus: f64, work_of_adhesion: Vec<f64>, params: AdhesiveParams) -> Self {
        assert_eq!(work_of_adhesion.len(), grid.len(), "one work of adhesion per element");
        let delta = detachment_element_size(grid.dx(), grid.dy());
        let critical_stress: Vec<f64> = work_of_adhesion
            .iter()
            .map(|&gamma| critical_stress(contact_modulus, gamma, delta))
            .collect();
        let minimum_critical_stress = front_critical_stress(&critical_stress);
        let len = grid.len();
        // The local rises are tabulated for square elements, and their windows are
        // indexed on an n × n grid: free square grids only.
        let local_bounds_hold = grid.boundary() == Boundary::Free && grid.is_square();
        Self {
            params,
            grid,
            contact_modulus,
            detachment_size: delta,
            work_of_adhesion,
            critical_stress,
            minimum_critical_stress,
            work: Workspace::new(&grid, contact_modulus, params.preconditioned),
            preconditioner_applications: 0,
            banned: vec![false; len],
            trial: vec![false; len],
            start_contact: vec![false; len],
            violators: Vec::new(),
            candidates: Vec::new(),
            saved_pressure: vec![0.0; len],
            displacement_pressure: vec![0.0; len],
            saved_displacement: vec![0.0; len],
            history: Vec::with_capacity(2),
            ring_history: Vec::with_capacity(2),
            current_ring: None,
            ring_pool: RingPool::default(),
            random_state: match params.detachment {
                Detachment::RandomHalf { seed } => seed | 1,
                _ => 1,
            },
            pressure_error_bound: 0.0,
            gap_error_bound: 0.0,
            last_solve_certified: false,
            displacement_drifted: false,
            saved_needs_convergence: false,
            certified_stops: 0,
            tie_refinements: 0,
            unresolved_ties: 0,
            local_peel: (local_bounds_hold && !params.reference_rule && params.detachment == Detachment::AllViolators)
                .then(|| LocalPeel::new(len)),
            local_releases: 0,
            ring_members: Vec::new(),
            ring_solved_pressure: vec![0.0; len],
            ring_solved_displacement: vec![0.0; len],
            ring_solved_bounds: (0.0, 0.0, false),
            predicted_failures: Vec::new(),
            peel_predictor: (local_bounds_hold
                && !params.reference_rule
                && params.detachment == Detachment::AllViolators)
                .then(|| PeelPredictor::new(len)),
            predicted_rings: 0,
            prediction_fallbacks: 0,
            prediction_seconds: 0.0,
            windows: SetWindows::default(),
            window_applications: 0,
            pending_change: None,
        }
    }

    /// Operator applications of the fixed-set CGs on contact windows over the solver's life
    /// (each a DC-FFT pair of twice a window's side; counted in the steps' applications too).
    pub fn window_applications(&self) -> u64 {
        self.window_applications
    }

    /// Trial rings grown through a predicted held subset (docs/fast-step.md §3), and how
    /// many of those predictions failed completely (the full ring was then peeled exactly),
    /// over the solver's life.
    pub fn predicted_growth(&self) -> (u64, u64) {
        (self.predicted_rings, self.prediction_fallbacks)
    }

    /// Wall time spent in the local replays that predict a ring's held subset (the local
    /// work of predicted-subset growth), over the solver's life.
    pub fn prediction_seconds(&self) -> f64 {
        self.prediction_seconds
    }

    /// Trial elements released by certified local rounds (docs/fast-step.md) instead of
    /// after a solve, over the solver's life.
    pub fn local_releases(&self) -> u64 {
        self.local_releases
    }

    /// Fixed-set solves that stopped early on certified release decisions (docs/fast-step.md),
    /// over the solver's life.
    pub fn certified_stops(&self) -> u64 {
        self.certified_stops
    }

    /// Converged solves continued because a release decision lay inside the error band
    /// (docs/fast-step.md §2), over the solver's life.
    pub fn tie_refinements(&self) -> u64 {
        self.tie_refinements
    }

    /// Tie refinements that stopped at their iteration limit before the refined tolerances
    /// (the decision was then taken on that iterate), over the solver's life.
    pub fn unresolved_ties(&self) -> u64 {
        self.unresolved_ties
    }

    /// The element size Δ of the tolerance and error-bound scales (E*/Δ, σ_c·Δ/E*): the
    /// shorter side of a rectangular element (the larger stiffness, the stricter scale).
    fn bound_element_size(&self) -> f64 {
        self.grid.dx().min(self.grid.dy())
    }

    /// The parameters.
    pub fn params(&self) -> &AdhesiveParams {
        &self.params
    }

    /// σ_c per element.
    pub fn critical_stresses(&self) -> &[f64] {
        &self.critical_stress
    }

    /// Replaces σ_c per element (row-major), for a detachment rule that weakens elements
    /// during a run (shear at the edge, docs/physics.md §8.5). The failed-ring records of
    /// earlier steps were judged against the old values and are forgotten.
    ///
    /// # Panics
    /// If `critical_stresses` does not have one value per element.
    pub fn set_critical_stresses(&mut self, critical_stresses: &[f64]) {
        self.critical_stress.copy_from_slice(critical_stresses);
        self.minimum_critical_stress = front_critical_stress(&self.critical_stress);
        self.clear_ring_history();
        self.drop_current_ring();
    }

    /// γ per element.
    pub fn work_of_adhesion(&self) -> &[f64] {
        &self.work_of_adhesion
    }

    /// Forgets the history of previous steps (warm-start extrapolation, carried bans):
    /// call before driving a new, unrelated load path with the same solver.
    pub fn reset(&mut self) {
        self.history.clear();
        self.clear_ring_history();
        self.drop_current_ring();
        self.banned.iter_mut().for_each(|b| *b = false);
        self.windows.discard_lag();
    }

    /// Π = ½Δ²Σp·u − Δ²Σ_C γ: elastic energy minus adhesion energy of the state.
    pub fn energy(&self, state: &ContactState) -> f64 {
        let area = self.grid.element_area();
        let mut elastic = 0.0;
        let mut adhesion = 0.0;
        for k in 0..self.grid.len() {
            elastic += state.pressure[k] * state.displacement[k];
            if state.contact[k] {
                adhesion += self.work_of_adhesion[k];
            }
        }
        area * (0.5 * elastic - adhesion)
    }

    /// Π of a state solved on its contact set, evaluated as Δ²[Σ_C p(d − z) − ½Σp·u] −
    /// Δ²Σ_C γ. At the exact solution this equals [`energy`](Self::energy) (u = d − z on
    /// C); for a CG iterate with pressure error e it is off by −½eᵀKe only (the fixed-set
    /// solution maximises this functional), while ½Σp·u is off to first order in e. So the
    /// energy bookkeeping stays exact at a CG tolerance set by the contact front alone.
    fn solved_energy(&self, state: &ContactState, heights: &[f64], depth: f64) -> f64 {
        let mut work = 0.0;
        let mut elastic = 0.0;
        let mut adhesion = 0.0;
        for k in 0..self.grid.len() {
            elastic += state.pressure[k] * state.displacement[k];
            if state.contact[k] {
                work += state.pressure[k] * (depth - heights[k]);
                adhesion += self.work_of_adhesion[k];
            }
        }
        self.grid.element_area() * (work - 0.5 * elastic - adhesion)
    }

    /// Brings `state` to a stable configuration at indentation `depth` (displacement
    /// control). `heights` are the indenter heights z (+∞ where there is no surface).
    pub fn step<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
    ) -> Result<StepReport, SolveError> {
        self.step_probed(operator, heights, depth, state, &mut |_| {})
    }

    /// As [`step`](Self::step), calling `before_change` with the state solved on the
    /// previous contact set at the new depth/position, before any attachment or release
    /// (e.g. to measure the tangential force at the end of a stick phase).
    pub fn step_probed<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
        before_change: &mut (dyn FnMut(&ContactState) + Send),
    ) -> Result<StepReport, SolveError> {
        crate::solver::on_worker(|| self.step_on_worker(operator, heights, depth, state, before_change))
    }

    fn step_on_worker<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
        before_change: &mut (dyn FnMut(&ContactState) + Send),
    ) -> Result<StepReport, SolveError> {
        let len = self.grid.len();
        if heights.len() != len {
            return Err(SolveError::SizeMismatch {
                expected: len,
                got: heights.len(),
            });
        }
        let applications_before = (
            operator.applications(),
            self.window_applications,
            self.preconditioner_applications,
        );
        let mut round = Round {
            report: StepReport::default(),
            retry_high_water: self.begin_step(heights, depth, state),
            ring_restorable: false,
            growth: Growth::Exact,
            prediction_blocked: false,
        };
        loop {
            round.report.solves += 1;
            if round.report.solves > self.params.max_rounds {
                return Err(SolveError::TooManyRounds {
                    rounds: self.params.max_rounds,
                });
            }
            let first = round.report.solves == 1;
            // u is recomputed exactly at the start of every step (and every
            // EXACT_DISPLACEMENT_PERIOD solves); in between it follows the pressure changes.
            let exact = round.report.solves % EXACT_DISPLACEMENT_PERIOD == 1;
            let stop = self.stop_rule(first, heights, state, round.retry_high_water);
            round.report.cg_iterations += self.solve_fixed_set(operator, heights, depth, state, exact, stop)?;
            if first {
                self.sync_outside(operator, state);
                round.report.force_before_change = state.force(self.grid.element_area());
                round.report.energy_before_change = self.solved_energy(state, heights, depth);
                before_change(state);
            }
            self.find_violators(state);
            if round.ring_restorable && round.growth != Growth::Predicted {
                self.record_ring_round(state);
            }
            let flow = if self.violators.is_empty() {
                self.attach(operator, heights, depth, state, &mut round)?
            } else if round.growth != Growth::Exact {
                self.release_predicted(operator, heights, depth, state, &mut round)?
            } else {
                self.release_violators(operator, heights, depth, state, &mut round)?
            };
            if flow == Flow::Stop {
                break;
            }
        }
        round.report.cg_iterations += self.polish_output(operator, heights, depth, state)?;
        Ok(self.finish_step(operator, heights, depth, state, round.report, applications_before))
    }

    /// Start of a step: bans (kept while retracting), trial marks, elements without a
    /// surface leave, and the extrapolated warm start. Returns the contact size (the first
    /// high-water mark of the retry rule).
    fn begin_step(&mut self, heights: &[f64], depth: f64, state: &mut ContactState) -> usize {
        let len = self.grid.len();
        let retracting = self.history.last().is_some_and(|last| depth < last.0);
        if !(retracting && self.params.carry_bans_when_retracting) {
            self.banned.iter_mut().for_each(|b| *b = false);
        }
        self.trial.iter_mut().for_each(|t| *t = false);
        copy_on_pool(&mut self.start_contact, &state.contact);
        for k in 0..len {
            if state.contact[k] && !heights[k].is_finite() {
                state.contact[k] = false;
            }
        }
        // Warm start: on a contact set unchanged over the last two steps p is linear in d
        // (docs/physics.md §2.5), so extrapolate; CG then only cleans up round-off.
        if self.history.len() == 2 && self.history[0].2 == state.contact && self.history[1].2 == state.contact {
            let (d0, d1) = (self.history[0].0, self.history[1].0);
            if d1 != d0 && state.pressure == self.history[1].1 {
                let factor = (depth - d1) / (d1 - d0);
                for k in 0..len {
                    if state.contact[k] {
                        state.pressure[k] += factor * (self.history[1].1[k] - self.history[0].1[k]);
                    }
                }
            }
        }
        state.contact.iter().filter(|&&c| c).count()
    }

    /// A round with violators: failed trial elements go first, ordinary violators wait for
    /// the next solve (a badly placed trial element must not start a cascade); when the
    /// whole trial ring failed, the saved state before it is restored and the step ends.
    fn release_violators<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
        round: &mut Round,
    ) -> Result<Flow, SolveError> {
        let any_failed_trial = self.violators.iter().any(|&k| self.trial[k]);
        if !any_failed_trial {
            round.ring_restorable = false;
            self.trial.iter_mut().for_each(|t| *t = false);
        }
        if self.release_with_local_rounds(state, any_failed_trial) > 0 {
            // Rounds released without a solve are not the recorded rounds that the
            // failed-ring prediction extrapolates.
            self.drop_current_ring();
            self.clear_ring_history();
            if self.params.check_certificates {
                self.check_local_bounds(operator, heights, depth, state, any_failed_trial)?;
            }
        }
        if !(any_failed_trial && round.ring_restorable && !self.trial.iter().any(|&t| t)) {
            return Ok(Flow::Continue);
        }
        // The whole ring failed and nothing else changed: C is the saved set, stable
        // before the ring was tried. Restore and stop.
        copy_on_pool(&mut state.pressure, &self.saved_pressure);
        copy_on_pool(&mut state.displacement, &self.saved_displacement);
        self.windows.discard_lag();
        copy_on_pool(&mut self.displacement_pressure, &self.saved_pressure);
        if self.saved_needs_convergence {
            self.converge_final(operator, heights, depth, state, &mut round.report)?;
        }
        if let Some(ring) = self.current_ring.take() {
            self.push_ring_history(ring);
        }
        Ok(Flow::Stop)
    }

    /// A state that ends the step after a certified early stop is converged first: the
    /// step's outputs (force, energy) need the converged solve.
    fn converge_final<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
        report: &mut StepReport,
    ) -> Result<(), SolveError> {
        report.solves += 1;
        report.cg_iterations += self.solve_fixed_set(operator, heights, depth, state, true, StopRule::Converge)?;
        Ok(())
    }

    /// End of a step: history for the next warm start, and the report.
    fn finish_step<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &O,
        heights: &[f64],
        depth: f64,
        state: &ContactState,
        mut report: StepReport,
        applications_before: (u64, u64, u64),
    ) -> StepReport {
        (report.attached, report.detached) = state.changes_from(&self.start_contact);
        if self.history.len() == 2 {
            let mut oldest = self.history.remove(0);
            oldest.0 = depth;
            copy_on_pool(&mut oldest.1, &state.pressure);
            copy_on_pool(&mut oldest.2, &state.contact);
            self.history.push(oldest);
        } else {
            self.history
                .push((depth, state.pressure.clone(), state.contact.clone()));
        }
        report.force = state.force(self.grid.element_area());
        report.energy = self.solved_energy(state, heights, depth);
        report.dissipated_energy = report.energy_before_change - report.energy;
        // A window's pairs are transforms of twice its side (counted alike, as the nested
        // solver counts its windows').
        report.window_applications = self.window_applications - applications_before.1;
        report.preconditioner_applications = self.preconditioner_applications - applications_before.2;
        report.operator_applications = operator.applications() - applications_before.0 + report.window_applications;
        report
    }
}

/// Ratio floor of [`front_critical_stress`]: γ contrasts up to 10⁶ keep the front
/// criterion of their weakest adhesive element.
const FRONT_STRESS_FLOOR: f64 = 1e-3;

/// The σ_c the CG front criterion is scaled by: the smallest positive σ_c (elements with
/// γ = 0 decide on the sign of p, not on a stress scale of their own), but not below
/// [`FRONT_STRESS_FLOOR`] times the largest, so that a γ field reaching 0 smoothly does not
/// ask CG for a residual below its rounding. +∞ (relative criterion only) without adhesion.
fn front_critical_stress(critical_stress: &[f64]) -> f64 {
    let largest = critical_stress.iter().cloned().fold(0.0, f64::max);
    let smallest_positive = critical_stress
        .iter()
        .cloned()
        .filter(|&sigma| sigma > 0.0)
        .fold(f64::INFINITY, f64::min);
    smallest_positive.max(FRONT_STRESS_FLOOR * largest)
}

/// What the step loop does after a round.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Flow {
    Continue,
    Stop,
}

/// Per-step loop state.
struct Round {
    report: StepReport,
    /// Contact size at the last lifting of bans (retry rule).
    retry_high_water: usize,
    /// The last attachment was a pure trial ring whose failure restores the saved state.
    ring_restorable: bool,
    /// Where the current ring's growth stands (docs/fast-step.md §3).
    growth: Growth,
    /// A predicted subset of the current stable set's ring failed completely (or the whole
    /// ring was predicted to fail): its ring is peeled exactly, no prediction until growth.
    prediction_blocked: bool,
}

/// Predicted-subset growth of a trial ring R on a stable set X (docs/fast-step.md §3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Growth {
    /// The exact peel of the reference rule.
    Exact,
    /// R was attached and is being solved: its held subset will be predicted.
    FullRing,
    /// A predicted subset of R is attached and peeled.
    Predicted,
}
