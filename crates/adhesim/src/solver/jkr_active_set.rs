use super::certificate::{attachments_certain, classify_releases, gap_error_bound, pressure_error_bound, Releases};
use super::local_peel::{LocalPeel, REACH};
use super::{masked_pcg, ContactState, PcgBuffers, SolveError};
use crate::elastic::influence::SELF_COMPLIANCE_FACTOR;
use crate::elastic::{ElasticOperator, SpectralPreconditioner};
use crate::grid::{Boundary, Grid};

/// c_U = [2 ln(1+√2) − (2/3)(√2 − 1)]/π: elastic energy U = c_U σ²Δ³/E* stored by one
/// square element under uniform tension σ (mean displacement; physics notes §2.2).
pub const ELEMENT_ENERGY_FACTOR: f64 = 0.473_201_004_409_338_54;

/// Critical tensile stress of the local mesh-dependent detachment criterion,
/// σ_c = √(E*γ/(c_U Δ)) (Pohrt & Popov 2015, *FU Mech. Eng.* 13(1), 3–10): an element is
/// released once the elastic energy it stores pays for its new free surface γΔ².
pub fn critical_stress(contact_modulus: f64, work_of_adhesion: f64, element_size: f64) -> f64 {
    (contact_modulus * work_of_adhesion / (ELEMENT_ENERGY_FACTOR * element_size)).sqrt()
}

/// How new contact is formed (physics notes §2.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Attachment {
    /// Penetrating elements attach, and every free edge-neighbour of the contact is
    /// tentatively attached; those that cannot hold (p < −σ_c) are released and banned for
    /// the rest of the step: the discrete Griffith closure test with the same σ_c.
    #[default]
    Trial,
    /// Only penetrating elements (g < 0) attach: a non-adhesive approach (strong
    /// artificial hysteresis), kept for comparison.
    PenetrationOnly,
}

/// Solves per step after which u is recomputed in double precision (besides the first).
const EXACT_DISPLACEMENT_PERIOD: usize = 32;

/// Which over-stressed elements are released per round.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Detachment {
    /// All elements with p < −σ_c at once (the standard choice).
    #[default]
    AllViolators,
    /// Only those within `fraction` of the largest over-stress ratio −p/σ_c (path studies).
    WorstFirst {
        /// Relative band below the largest ratio, e.g. 0.01.
        fraction: f64,
    },
    /// A random half of the violators (at least the worst one) per round, drawn from
    /// `seed`: a deliberately different release order, the independent oracle of the
    /// order-independence argument (docs/fast-step.md). Solves are fully converged.
    RandomHalf {
        /// Seed of the xorshift generator.
        seed: u64,
    },
}

/// Parameters of [`AdhesiveSolver`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdhesiveParams {
    /// CG stops when ‖r‖_C ≤ this·‖d − z‖_C (default 1e-6; the front criterion below is
    /// the one the contact set depends on: 1e-9 gives the same contact sets at every step
    /// with 35 % more CG iterations, see BENCHMARKS.md) ...
    pub relative_tolerance: f64,
    /// ... and max|r_i| ≤ this·K(0,0)·σ_c,min (default 1e-4): the stress error at the front
    /// must be far below σ_c or the contact set flickers.
    pub front_tolerance: f64,
    /// CG iteration limit per solve (default 5 000).
    pub max_cg_iterations: usize,
    /// Limit on solve/attach/detach rounds per displacement step (default 100 000).
    pub max_rounds: usize,
    /// Attachment rule.
    pub attachment: Attachment,
    /// Detachment rule.
    pub detachment: Detachment,
    /// Precondition the fixed-set CG with the |q| spectral preconditioner (default true).
    pub preconditioned: bool,
    /// Keep the bans of the previous step while the depth keeps decreasing (default true).
    /// On a fixed set p(d) = p₀ + d·p₁ with p₁ ≥ 0 (the positive equilibrium pressure of
    /// a flat punch of that shape), so at a smaller depth every trial element would be
    /// more tensile than when it failed: re-testing it is futile. This removes the trial
    /// cascade from quiet retraction steps; the tests check it leaves curves unchanged.
    pub carry_bans_when_retracting: bool,
    /// Once the contact has grown within a step, every element banned so far in the step
    /// is tried again (default true). Under continuous loading an element that failed its
    /// closure test is re-tested as soon as the contact around it changes; keeping it
    /// banned for the rest of a finite step makes the contact lag behind by a step-size
    /// dependent amount (γ1 on Fig. 1 at N = 128: 1.115, 1.167, 1.192, 1.206 for 75, 150,
    /// 300, 600 approach steps without retries, 1.219, 1.218, 1.217 with them). Bans are
    /// lifted only when the contact is larger than at every earlier retry of the step, so
    /// the step still ends.
    pub retry_after_growth: bool,
    /// The pre-issue-14 rule (default false): every fixed-set solve converges fully before
    /// its release decisions. Otherwise a solve whose release decisions are certified
    /// (docs/fast-step.md) stops early; contact sets are the same, the reference mode is
    /// kept to show it.
    pub reference_rule: bool,
    /// Test aid (default false): after every certified early stop, converge the solve
    /// fully on a copy and panic if a pressure moved by more than the certified bound or a
    /// release decision changed. Costs a full solve per early stop.
    pub check_certificates: bool,
}

impl Default for AdhesiveParams {
    fn default() -> Self {
        Self {
            relative_tolerance: 1e-6,
            front_tolerance: 1e-4,
            max_cg_iterations: 5_000,
            max_rounds: 100_000,
            attachment: Attachment::Trial,
            detachment: Detachment::AllViolators,
            preconditioned: true,
            carry_bans_when_retracting: true,
            retry_after_growth: true,
            reference_rule: false,
            check_certificates: false,
        }
    }
}

/// What one quasi-static step did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepReport {
    /// Fixed-set solves (rounds of the step loop).
    pub solves: usize,
    /// CG iterations over all solves.
    pub cg_iterations: usize,
    /// Elastic operator applications (FFT pairs).
    pub operator_applications: u64,
    /// Elements in C at the end that were not at the start.
    pub attached: usize,
    /// Elements in C at the start that are not at the end.
    pub detached: usize,
    /// Normal force Δ²Σp after the first solve with the previous contact set.
    pub force_before_change: f64,
    /// Normal force at the end of the step.
    pub force: f64,
    /// Energy Π = ½Δ²Σp·u − Δ²Σ_C γ after the first solve with the previous set.
    pub energy_before_change: f64,
    /// Π at the end of the step.
    pub energy: f64,
    /// Energy released by the configuration change of this step, Π_before − Π_end. Real
    /// instabilities make it positive; on a lattice a closure that passes the σ_c test can
    /// raise Π slightly (lattice trapping), so it is not clamped: the sum over a cycle then
    /// equals ∮F dd exactly.
    pub dissipated_energy: f64,
}

/// Quasi-static JKR-type adhesive contact with the local mesh-dependent detachment
/// criterion (Pohrt & Popov 2015; Popov et al. 2021, Sect. 2.2–2.3).
///
/// Per displacement step (physics notes §2.4): CG on the fixed contact set C (warm
/// started), release of elements whose tension exceeds σ_c (failed trial elements
/// first), attachment of penetrating elements and of trial neighbours, repeated until the
/// configuration is stable. Elements released in a step are banned from trial attachment
/// until the contact grows beyond its largest size so far in the step (then all are
/// retried), which makes the loop terminate.
pub struct AdhesiveSolver {
    params: AdhesiveParams,
    grid: Grid,
    work_of_adhesion: Vec<f64>,
    critical_stress: Vec<f64>,
    minimum_critical_stress: f64,
    // scratch, allocated once
    residual: Vec<f64>,
    mask: Vec<f64>,
    preconditioned_residual: Vec<f64>,
    direction: Vec<f64>,
    preconditioner: Option<SpectralPreconditioner>,
    preconditioner_applications: u64,
    response: Vec<f64>,
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
    /// State of the xorshift generator of [`Detachment::RandomHalf`].
    random_state: u64,
    /// Bound on the pressure error of the last solve (docs/fast-step.md).
    pressure_error_bound: f64,
    /// Bound on the gap error of the last solve.
    gap_error_bound: f64,
    /// Whether the last solve stopped early on certified decisions.
    last_solve_certified: bool,
    /// Whether the state saved before a trial ring came from such an early stop.
    saved_certified: bool,
    /// Solves stopped early on a certificate, over the solver's life.
    certified_stops: u64,
    /// Certified local release rounds (free grids, fast rule only).
    local_peel: Option<LocalPeel>,
    /// Trial elements released by local certificates (without a solve), over the solver's life.
    local_releases: u64,
}

/// When a fixed-set solve may stop (docs/fast-step.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum StopRule {
    /// Converge fully (outputs, reference rule, oracle).
    Converge,
    /// Stop once the release decisions are certain and release something.
    Releases,
    /// As `Releases`, or once there is certainly no release and the attachment decisions
    /// are certain (the step goes on to attach: trial neighbours exist).
    ReleasesOrAttachments,
}

/// One round of a trial-ring peel: the trial elements present, their pressures after the
/// solve, and which of them failed.
#[derive(Debug, Clone, PartialEq)]
struct RingRound {
    members: Vec<usize>,
    pressures: Vec<f64>,
    failed: Vec<bool>,
    /// Bound on the error of `pressures` (the solve may have stopped on a certificate).
    error_bound: f64,
}

/// A trial ring tried on contact set `contact` at `depth` that failed completely.
#[derive(Debug, Clone, PartialEq)]
struct RingAttempt {
    depth: f64,
    contact: Vec<bool>,
    rounds: Vec<RingRound>,
}

impl AdhesiveSolver {
    /// A solver for `grid` with the work of adhesion γ per element (row-major) and the
    /// half-space's contact modulus.
    ///
    /// # Panics
    /// If `work_of_adhesion` does not have one value per element.
    pub fn new(grid: Grid, contact_modulus: f64, work_of_adhesion: Vec<f64>, params: AdhesiveParams) -> Self {
        assert_eq!(work_of_adhesion.len(), grid.len(), "one work of adhesion per element");
        let delta = grid.element_size();
        let critical_stress: Vec<f64> = work_of_adhesion
            .iter()
            .map(|&gamma| critical_stress(contact_modulus, gamma, delta))
            .collect();
        let minimum_critical_stress = critical_stress.iter().cloned().fold(f64::INFINITY, f64::min);
        let len = grid.len();
        Self {
            params,
            grid,
            work_of_adhesion,
            critical_stress,
            minimum_critical_stress,
            residual: vec![0.0; len],
            mask: vec![0.0; len],
            preconditioned_residual: vec![0.0; len],
            direction: vec![0.0; len],
            preconditioner: params
                .preconditioned
                .then(|| SpectralPreconditioner::new(&grid, contact_modulus)),
            preconditioner_applications: 0,
            response: vec![0.0; len],
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
            random_state: match params.detachment {
                Detachment::RandomHalf { seed } => seed | 1,
                _ => 1,
            },
            pressure_error_bound: 0.0,
            gap_error_bound: 0.0,
            last_solve_certified: false,
            saved_certified: false,
            certified_stops: 0,
            local_peel: (grid.boundary() == Boundary::Free
                && !params.reference_rule
                && params.detachment == Detachment::AllViolators)
                .then(|| LocalPeel::new(len)),
            local_releases: 0,
        }
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

    /// The parameters.
    pub fn params(&self) -> &AdhesiveParams {
        &self.params
    }

    /// σ_c per element.
    pub fn critical_stresses(&self) -> &[f64] {
        &self.critical_stress
    }

    /// γ per element.
    pub fn work_of_adhesion(&self) -> &[f64] {
        &self.work_of_adhesion
    }

    /// Forgets the history of previous steps (warm-start extrapolation, carried bans):
    /// call before driving a new, unrelated load path with the same solver.
    pub fn reset(&mut self) {
        self.history.clear();
        self.ring_history.clear();
        self.current_ring = None;
        self.banned.iter_mut().for_each(|b| *b = false);
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
        before_change: &mut dyn FnMut(&ContactState),
    ) -> Result<StepReport, SolveError> {
        let len = self.grid.len();
        if heights.len() != len {
            return Err(SolveError::SizeMismatch {
                expected: len,
                got: heights.len(),
            });
        }
        let applications_before = operator.applications();
        let mut report = StepReport::default();
        let retracting = self.history.last().is_some_and(|last| depth < last.0);
        if !(retracting && self.params.carry_bans_when_retracting) {
            self.banned.iter_mut().for_each(|b| *b = false);
        }
        self.trial.iter_mut().for_each(|t| *t = false);
        self.start_contact.copy_from_slice(&state.contact);
        // Elements that can no longer exist (no surface) leave the contact.
        for k in 0..len {
            if state.contact[k] && !heights[k].is_finite() {
                state.contact[k] = false;
            }
        }
        // Warm start: on a contact set unchanged over the last two steps p is linear in d
        // (physics notes §2.5), so extrapolate; CG then only cleans up round-off.
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
        let mut retry_high_water = state.contact.iter().filter(|&&c| c).count();
        let mut first = true;
        let mut ring_restorable = false;
        loop {
            report.solves += 1;
            if report.solves > self.params.max_rounds {
                return Err(SolveError::TooManyRounds {
                    rounds: self.params.max_rounds,
                });
            }
            // u is recomputed exactly at the start of every step (and every
            // EXACT_DISPLACEMENT_PERIOD solves); in between it follows the pressure changes.
            let exact = report.solves % EXACT_DISPLACEMENT_PERIOD == 1;
            // The first solve gives the outputs before any change: always converged.
            let stop = self.stop_rule(first, heights, state, retry_high_water);
            report.cg_iterations += self.solve_fixed_set(operator, heights, depth, state, exact, stop)?;
            if first {
                report.force_before_change = state.force(self.grid.element_area());
                report.energy_before_change = self.solved_energy(state, heights, depth);
                before_change(state);
                first = false;
            }
            self.find_violators(state);
            if ring_restorable {
                if let Some(ring) = self.current_ring.as_mut() {
                    let members: Vec<usize> = (0..len).filter(|&k| self.trial[k]).collect();
                    let pressures = members.iter().map(|&k| state.pressure[k]).collect();
                    let mut failed = vec![false; members.len()];
                    for &k in &self.violators {
                        if let Ok(position) = members.binary_search(&k) {
                            failed[position] = true;
                        }
                    }
                    ring.rounds.push(RingRound {
                        members,
                        pressures,
                        failed,
                        error_bound: self.pressure_error_bound,
                    });
                }
            }
            if !self.violators.is_empty() {
                let any_failed_trial = self.violators.iter().any(|&k| self.trial[k]);
                if any_failed_trial {
                    // Failed trial elements go first; ordinary violators wait for the
                    // next solve (a badly placed trial element must not start a cascade).
                    if self.release_with_local_rounds(state, true) > 0 {
                        // Rounds released without a solve are not the recorded rounds that
                        // the failed-ring prediction extrapolates.
                        self.current_ring = None;
                        self.ring_history.clear();
                        if self.params.check_certificates {
                            self.check_local_bounds(operator, heights, depth, state, true)?;
                        }
                    }
                    if ring_restorable && !self.trial.iter().any(|&t| t) {
                        // The whole ring failed and nothing else changed: C is the saved
                        // set, stable before the ring was tried. Restore and stop.
                        state.pressure.copy_from_slice(&self.saved_pressure);
                        state.displacement.copy_from_slice(&self.saved_displacement);
                        self.displacement_pressure.copy_from_slice(&self.saved_pressure);
                        if self.saved_certified {
                            report.solves += 1;
                            report.cg_iterations +=
                                self.solve_fixed_set(operator, heights, depth, state, false, StopRule::Converge)?;
                        }
                        if let Some(ring) = self.current_ring.take() {
                            if self.ring_history.len() == 2 {
                                self.ring_history.remove(0);
                            }
                            self.ring_history.push(ring);
                        }
                        break;
                    }
                    continue;
                }
                ring_restorable = false;
                self.trial.iter_mut().for_each(|t| *t = false);
                if self.release_with_local_rounds(state, false) > 0 {
                    self.ring_history.clear();
                    if self.params.check_certificates {
                        self.check_local_bounds(operator, heights, depth, state, false)?;
                    }
                }
                continue;
            }
            self.trial.iter_mut().for_each(|t| *t = false);
            if self.params.retry_after_growth {
                let size = state.contact.iter().filter(|&&c| c).count();
                if size > retry_high_water {
                    retry_high_water = size;
                    self.banned.iter_mut().for_each(|b| *b = false);
                }
            }
            // Attachment: penetration, then trial neighbours.
            self.candidates.clear();
            for k in 0..len {
                if state.contact[k] || !heights[k].is_finite() {
                    continue;
                }
                let gap = heights[k] - depth + state.displacement[k];
                if gap < 0.0 {
                    self.candidates.push(k);
                } else if self.params.attachment == Attachment::Trial && !self.banned[k] {
                    let mut touches = false;
                    self.grid
                        .for_each_neighbour(k, |neighbour| touches |= state.contact[neighbour]);
                    if touches {
                        self.candidates.push(k);
                        self.trial[k] = true;
                    }
                }
            }
            if self.candidates.is_empty() {
                break;
            }
            let pure_ring = self.candidates.iter().all(|&k| self.trial[k]);
            if !pure_ring || self.current_ring.is_some() {
                // A ring that partly held (or penetration) breaks the chain of identical
                // failed rings the prediction needs.
                self.ring_history.clear();
            }
            self.current_ring = None;
            ring_restorable = pure_ring;
            if ring_restorable {
                if self.predict_failed_ring(depth, state) {
                    if self.last_solve_certified {
                        // This state ends the step: its outputs need the converged solve.
                        report.solves += 1;
                        report.cg_iterations +=
                            self.solve_fixed_set(operator, heights, depth, state, false, StopRule::Converge)?;
                    }
                    for &k in &self.candidates {
                        self.trial[k] = false;
                        self.banned[k] = true;
                    }
                    break;
                }
                self.saved_certified = self.last_solve_certified;
                self.saved_pressure.copy_from_slice(&state.pressure);
                self.saved_displacement.copy_from_slice(&state.displacement);
                self.current_ring = Some(RingAttempt {
                    depth,
                    contact: state.contact.clone(),
                    rounds: Vec::new(),
                });
            }
            for &k in &self.candidates {
                state.contact[k] = true;
            }
        }
        (report.attached, report.detached) = state.changes_from(&self.start_contact);
        if self.history.len() == 2 {
            let mut oldest = self.history.remove(0);
            oldest.0 = depth;
            oldest.1.copy_from_slice(&state.pressure);
            oldest.2.copy_from_slice(&state.contact);
            self.history.push(oldest);
        } else {
            self.history
                .push((depth, state.pressure.clone(), state.contact.clone()));
        }
        report.force = state.force(self.grid.element_area());
        report.energy = self.solved_energy(state, heights, depth);
        report.dissipated_energy = report.energy_before_change - report.energy;
        report.operator_applications = operator.applications() - applications_before;
        Ok(report)
    }

    /// How the next solve may stop: never early on the first solve of a step (its outputs
    /// are reported), in the reference rule or another release order; on certain
    /// attachment decisions only when trial neighbours exist (bans as the attachment
    /// phase will see them), so that the step certainly goes on.
    fn stop_rule(&self, first: bool, heights: &[f64], state: &ContactState, retry_high_water: usize) -> StopRule {
        if first || self.params.reference_rule || self.params.detachment != Detachment::AllViolators {
            return StopRule::Converge;
        }
        if self.params.attachment != Attachment::Trial {
            return StopRule::Releases;
        }
        let bans_lifted =
            self.params.retry_after_growth && state.contact.iter().filter(|&&c| c).count() > retry_high_water;
        let trial_available = (0..self.grid.len()).any(|k| {
            if state.contact[k] || !heights[k].is_finite() || (self.banned[k] && !bans_lifted) {
                return false;
            }
            let mut touches = false;
            self.grid
                .for_each_neighbour(k, |neighbour| touches |= state.contact[neighbour]);
            touches
        });
        if trial_available {
            StopRule::ReleasesOrAttachments
        } else {
            StopRule::Releases
        }
    }

    /// Exact shortcut for a quiet step: if the last two steps tried the same trial ring on
    /// the same contact set and every round of its peel released the same elements, the
    /// trial pressures of each round are linear in d (fixed sets), so this step's rounds
    /// are known by extrapolation. When every extrapolated round releases exactly the
    /// recorded elements, the ring fails again: record it and report `true` (no solve).
    fn predict_failed_ring(&mut self, depth: f64, state: &ContactState) -> bool {
        if self.params.detachment != Detachment::AllViolators || self.ring_history.len() < 2 {
            return false;
        }
        let (older, newer) = (&self.ring_history[0], &self.ring_history[1]);
        if older.depth == newer.depth
            || newer.depth == depth
            || older.rounds.len() != newer.rounds.len()
            || newer.contact != state.contact
            || older.contact != state.contact
        {
            return false;
        }
        if newer.rounds.first().map(|r| &r.members) != Some(&self.candidates) {
            return false;
        }
        let factor = (depth - newer.depth) / (newer.depth - older.depth);
        let mut predicted = Vec::with_capacity(newer.rounds.len());
        for (a, b) in older.rounds.iter().zip(&newer.rounds) {
            if a.members != b.members || a.failed != b.failed {
                return false;
            }
            let pressures: Vec<f64> = a
                .pressures
                .iter()
                .zip(&b.pressures)
                .map(|(p0, p1)| p1 + factor * (p1 - p0))
                .collect();
            // The same violator rule as find_violators, on the trial members.
            let ratios: Vec<f64> = b
                .members
                .iter()
                .zip(&pressures)
                .map(|(&k, p)| -p / self.critical_stress[k])
                .collect();
            let smallest = ratios
                .iter()
                .cloned()
                .filter(|&r| r > 1.0)
                .fold(f64::INFINITY, f64::min);
            let failed: Vec<bool> = ratios
                .iter()
                .map(|&r| smallest.is_finite() && r >= smallest * (1.0 - 1e-9))
                .collect();
            if failed != b.failed {
                return false;
            }
            // Extrapolated from pressures known to ±error_bound: predict only decisions
            // that bound cannot flip (the reference rule trusts converged pressures).
            let error_bound = (1.0 + factor.abs()) * b.error_bound + factor.abs() * a.error_bound;
            if !self.params.reference_rule
                && b.members
                    .iter()
                    .zip(&pressures)
                    .any(|(&k, p)| (-p - self.critical_stress[k]).abs() <= error_bound)
            {
                return false;
            }
            predicted.push(RingRound {
                members: b.members.clone(),
                pressures,
                failed,
                error_bound,
            });
        }
        self.ring_history.remove(0);
        self.ring_history.push(RingAttempt {
            depth,
            contact: state.contact.clone(),
            rounds: predicted,
        });
        true
    }

    /// Releases the violators (only the failed trial elements with `trial_only`), then,
    /// with local rounds, every element of the same kind whose tension a local lower bound
    /// certifies above σ_c, in a sequence of single releases (docs/fast-step.md). These are
    /// elements the following rounds of the reference rule would release. Returns the
    /// number of the extra releases.
    fn release_with_local_rounds(&mut self, state: &mut ContactState, trial_only: bool) -> usize {
        let Some(mut peel) = self.local_peel.take() else {
            for index in 0..self.violators.len() {
                let k = self.violators[index];
                if self.trial[k] || !trial_only {
                    self.release(k, state);
                }
            }
            return 0;
        };
        let len = self.grid.len();
        let n = self.grid.n();
        for k in 0..len {
            if state.contact[k] && (self.trial[k] || !trial_only) {
                peel.lower[k] = -state.pressure[k] - self.pressure_error_bound;
            }
        }
        peel.queue.clear();
        for &k in &self.violators {
            if self.trial[k] || !trial_only {
                peel.queue.push(k);
                peel.queued[k] = true;
            }
        }
        let certain = peel.queue.len();
        let mut head = 0;
        while head < peel.queue.len() {
            let released = peel.queue[head];
            head += 1;
            let tension = peel.lower[released].max(0.0);
            self.release(released, state);
            let centre = ((released / n) as i64, (released % n) as i64);
            peel.prepare(n, centre, |k| !state.contact[k]);
            for a in -REACH..=REACH {
                for b in -REACH..=REACH {
                    let (row, column) = (centre.0 + a, centre.1 + b);
                    if row < 0 || column < 0 || row as usize >= n || column as usize >= n {
                        continue;
                    }
                    let k = row as usize * n + column as usize;
                    if !state.contact[k] || (trial_only && !self.trial[k]) || peel.queued[k] {
                        continue;
                    }
                    peel.lower[k] += peel.rise((row, column)) * tension;
                    if peel.lower[k] > self.critical_stress[k] {
                        peel.queue.push(k);
                        peel.queued[k] = true;
                    }
                }
            }
        }
        for &k in &peel.queue {
            peel.queued[k] = false;
        }
        let extra = peel.queue.len() - certain;
        self.local_releases += extra as u64;
        self.local_peel = Some(peel);
        extra
    }

    /// [`AdhesiveParams::check_certificates`] for local rounds: solves the set left by them
    /// on a copy and panics if a remaining trial element's tension is below its certified
    /// lower bound; leaves the state and the solver as they were.
    fn check_local_bounds<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
        trial_only: bool,
    ) -> Result<(), SolveError> {
        let before = state.clone();
        let displacement_pressure = self.displacement_pressure.clone();
        let (bound, gap_bound, certified) = (
            self.pressure_error_bound,
            self.gap_error_bound,
            self.last_solve_certified,
        );
        self.solve_fixed_set(operator, heights, depth, state, true, StopRule::Converge)?;
        if let Some(peel) = &self.local_peel {
            for k in 0..self.grid.len() {
                if state.contact[k] && (self.trial[k] || !trial_only) {
                    let tension = -state.pressure[k] + self.pressure_error_bound;
                    assert!(
                        peel.lower[k] <= tension,
                        "local bound violated at element {k}: lower bound {:e} > tension {tension:e}",
                        peel.lower[k]
                    );
                }
            }
        }
        *state = before;
        self.displacement_pressure = displacement_pressure;
        (
            self.pressure_error_bound,
            self.gap_error_bound,
            self.last_solve_certified,
        ) = (bound, gap_bound, certified);
        Ok(())
    }

    fn release(&mut self, k: usize, state: &mut ContactState) {
        state.contact[k] = false;
        state.pressure[k] = 0.0;
        self.banned[k] = true;
        self.trial[k] = false;
    }

    /// Collects elements of C with p < −σ_c. Exact ties (symmetric geometries) are treated
    /// alike: every element whose over-stress ratio is within 1e-9 of the smallest violating
    /// ratio is included.
    fn find_violators(&mut self, state: &ContactState) {
        self.violators.clear();
        let mut smallest = f64::INFINITY;
        let mut largest: f64 = 0.0;
        for k in 0..self.grid.len() {
            if state.contact[k] {
                let ratio = -state.pressure[k] / self.critical_stress[k];
                if ratio > 1.0 {
                    smallest = smallest.min(ratio);
                    largest = largest.max(ratio);
                }
            }
        }
        if !smallest.is_finite() {
            return;
        }
        let threshold = match self.params.detachment {
            Detachment::AllViolators | Detachment::RandomHalf { .. } => smallest,
            Detachment::WorstFirst { fraction } => smallest.max(largest * (1.0 - fraction)),
        } * (1.0 - 1e-9);
        for k in 0..self.grid.len() {
            if state.contact[k] && -state.pressure[k] / self.critical_stress[k] >= threshold {
                self.violators.push(k);
            }
        }
        if let Detachment::RandomHalf { .. } = self.params.detachment {
            self.keep_random_half(state, largest);
        }
    }

    /// Keeps a random half of the violators, always including one of the worst.
    fn keep_random_half(&mut self, state: &ContactState, largest: f64) {
        let worst = self
            .violators
            .iter()
            .position(|&k| -state.pressure[k] / self.critical_stress[k] >= largest);
        let mut random = self.random_state;
        let mut index = 0;
        self.violators.retain(|_| {
            random ^= random << 13;
            random ^= random >> 7;
            random ^= random << 17;
            index += 1;
            Some(index - 1) == worst || random & 1 == 0
        });
        self.random_state = random;
    }

    /// Applications of the preconditioner so far (each an N×N FFT pair).
    pub fn preconditioner_applications(&self) -> u64 {
        self.preconditioner_applications
    }

    /// CG for K_CC p_C = (d − z)_C with p = 0 outside C, warm started from `state`.
    /// Keeps u = K p on the whole grid up to date (incrementally). Returns iterations.
    ///
    /// With `exact`, u is recomputed from p in double precision first; otherwise it is
    /// updated by K applied (in single precision) to the change of p since u was last
    /// consistent: releases and warm starts change few elements or change p smoothly, so
    /// the rounding (≈ 1e-7 of that change's response) stays far below the front criterion.
    fn solve_fixed_set<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
        exact: bool,
        stop: StopRule,
    ) -> Result<usize, SolveError> {
        let len = self.grid.len();
        for k in 0..len {
            if !state.contact[k] {
                state.pressure[k] = 0.0;
            }
        }
        if exact {
            operator.apply(&state.pressure, &mut state.displacement);
        } else {
            let mut changed = false;
            for k in 0..len {
                self.direction[k] = state.pressure[k] - self.displacement_pressure[k];
                changed |= self.direction[k] != 0.0;
            }
            if changed {
                operator.apply_single(&self.direction, &mut self.response);
                for (u, du) in state.displacement.iter_mut().zip(&self.response) {
                    *u += du;
                }
            }
        }
        let mut iterations = self.iterate_fixed_set(operator, heights, depth, state, stop)?;
        if self.last_solve_certified {
            self.certified_stops += 1;
            if self.params.check_certificates {
                iterations += self.check_certificate(operator, heights, depth, state)?;
            }
        }
        self.displacement_pressure.copy_from_slice(&state.pressure);
        Ok(iterations)
    }

    /// [`AdhesiveParams::check_certificates`]: converges the solve fully from the early
    /// stop, checks every pressure moved by less than the certified bound and every release
    /// decision stayed, then restores the early state.
    fn check_certificate<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
    ) -> Result<usize, SolveError> {
        let early = state.clone();
        let (bound, gap_bound) = (self.pressure_error_bound, self.gap_error_bound);
        let iterations = self.iterate_fixed_set(operator, heights, depth, state, StopRule::Converge)?;
        for k in 0..self.grid.len() {
            if !state.contact[k] && heights[k].is_finite() {
                let converged = heights[k] - depth + state.displacement[k];
                let certified = heights[k] - depth + early.displacement[k];
                assert!(
                    (converged - certified).abs() <= gap_bound,
                    "gap certificate violated at element {k}: converged g = {converged:e}, early g = {certified:e}, bound {gap_bound:e}"
                );
            }
            if state.contact[k] {
                let (converged, certified) = (state.pressure[k], early.pressure[k]);
                let sigma = self.critical_stress[k];
                assert!(
                    (converged - certified).abs() <= bound && (converged < -sigma) == (certified < -sigma),
                    "certificate violated at element {k}: converged p = {converged:e}, early p = {certified:e}, bound {bound:e}, σ_c = {sigma:e}"
                );
            }
        }
        state.pressure.copy_from_slice(&early.pressure);
        state.displacement.copy_from_slice(&early.displacement);
        (self.pressure_error_bound, self.gap_error_bound) = (bound, gap_bound);
        self.last_solve_certified = true;
        Ok(iterations)
    }

    /// The CG iterations of [`solve_fixed_set`](Self::solve_fixed_set), from a state
    /// whose u = K p is up to date.
    fn iterate_fixed_set<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
        stop: StopRule,
    ) -> Result<usize, SolveError> {
        self.last_solve_certified = false;
        let len = self.grid.len();
        let mut target_norm = 0.0;
        let mut residual_norm = 0.0;
        for k in 0..len {
            if state.contact[k] {
                let target = depth - heights[k];
                target_norm += target * target;
                self.residual[k] = target - state.displacement[k];
                residual_norm += self.residual[k] * self.residual[k];
            } else {
                self.residual[k] = 0.0;
            }
        }
        if target_norm == 0.0 && residual_norm == 0.0 {
            (self.pressure_error_bound, self.gap_error_bound) = (0.0, 0.0);
            return Ok(0);
        }
        // Stop on ‖r‖ ≤ ε‖b‖ and on a point-wise bound well below the displacement an
        // element of stress σ_c produces by itself.
        let delta = self.grid.element_size();
        let pointwise = if self.minimum_critical_stress > 0.0 {
            self.params.front_tolerance * SELF_COMPLIANCE_FACTOR * self.minimum_critical_stress * delta
                / operator.contact_modulus()
        } else {
            f64::INFINITY
        };
        let relative = self.params.relative_tolerance * target_norm.sqrt();
        let converged = |norm2: f64, residual: &[f64], contact: &[bool]| -> bool {
            if norm2.sqrt() > relative {
                return false;
            }
            if pointwise.is_finite() {
                residual.iter().zip(contact).all(|(r, &c)| !c || r.abs() <= pointwise)
            } else {
                true
            }
        };
        let (contact_modulus, element_size) = (operator.contact_modulus(), delta);
        if converged(residual_norm, &self.residual, &state.contact) {
            self.pressure_error_bound = pressure_error_bound(&self.residual, contact_modulus, element_size);
            self.gap_error_bound = gap_error_bound(&self.residual);
            return Ok(0);
        }
        // 1 on C, 0 elsewhere: branch-free vector loops (direction and residual are 0
        // outside C, so the masked updates equal the element-wise conditional ones).
        for (m, &c) in self.mask.iter_mut().zip(&state.contact) {
            *m = if c { 1.0 } else { 0.0 };
        }
        let contact = &state.contact;
        let critical_stress = &self.critical_stress;
        let mut certified = false;
        let mut preconditioner = self.preconditioner.as_mut();
        let applications = &mut self.preconditioner_applications;
        let buffers = PcgBuffers {
            residual: &mut self.residual,
            preconditioned: &mut self.preconditioned_residual,
            direction: &mut self.direction,
            response: &mut self.response,
            mask: &self.mask,
        };
        let outcome = masked_pcg(
            operator,
            &mut state.pressure,
            &mut state.displacement,
            buffers,
            |residual, preconditioned| match preconditioner.as_mut() {
                Some(preconditioner) => {
                    preconditioner.apply(residual, preconditioned);
                    *applications += 1;
                }
                None => preconditioned.copy_from_slice(residual),
            },
            |norm2, residual, pressure, displacement| {
                if converged(norm2, residual, contact) {
                    return Some(true);
                }
                // Stop once the release decisions cannot change (docs/fast-step.md).
                if stop != StopRule::Converge {
                    let band = pressure_error_bound(residual, contact_modulus, element_size);
                    certified = match classify_releases(pressure, contact, critical_stress, band) {
                        Releases::Some => true,
                        Releases::None if stop == StopRule::ReleasesOrAttachments => {
                            attachments_certain(heights, depth, displacement, contact, gap_error_bound(residual))
                        }
                        _ => false,
                    };
                }
                Some(certified)
            },
            self.params.max_cg_iterations,
        );
        self.last_solve_certified = certified;
        self.pressure_error_bound = pressure_error_bound(&self.residual, contact_modulus, element_size);
        self.gap_error_bound = gap_error_bound(&self.residual);
        outcome?.map_err(|norm2| SolveError::NotConverged {
            iterations: self.params.max_cg_iterations,
            residual: norm2.sqrt() / target_norm.sqrt().max(f64::MIN_POSITIVE),
            tolerance: self.params.relative_tolerance,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn element_energy_factor_is_the_closed_form() {
        let sqrt2 = 2f64.sqrt();
        let expected = (2.0 * (1.0 + sqrt2).ln() - 2.0 / 3.0 * (sqrt2 - 1.0)) / std::f64::consts::PI;
        assert!((ELEMENT_ENERGY_FACTOR - expected).abs() < 1e-15, "{expected}");
        // σ_c = 1.453708·√(E*γ/Δ) (physics notes §2.2)
        assert!((critical_stress(1.0, 1.0, 1.0) - 1.453_708).abs() < 1e-6);
    }

    /// The [likely] constant c_U checked independently: U = ½σΔ²·w̄ with w̄ the mean of
    /// Love's coefficient over the element itself, by 2-D Gauss–Legendre quadrature of the
    /// (continuous, log-kinked) coefficient; 1e-5 covers the quadrature error at the kink.
    #[test]
    fn element_energy_factor_from_love_coefficient() {
        use crate::elastic::influence::{love_coefficient, square_quadrature};
        let mean = square_quadrature(1.0, 32, |x, y| love_coefficient(x, y, 1.0, 1.0));
        assert!(
            (0.5 * mean / ELEMENT_ENERGY_FACTOR - 1.0).abs() < 1e-5,
            "{}",
            0.5 * mean
        );
    }
}
