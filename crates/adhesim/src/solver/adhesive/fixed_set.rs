//! The fixed-set solve of the adhesive step (docs/physics.md §3.2) with certified early
//! stops (docs/fast-step.md).

use super::set_cg::{solve_on_set, Convergence, SetFields, SetRule};
use super::{AdhesiveSolver, Attachment, Detachment, StopRule};
use crate::elastic::influence::SELF_COMPLIANCE_FACTOR;
use crate::elastic::ElasticOperator;
use crate::grid::Boundary;
use crate::solver::certificate::{
    count_releases, gap_error_bound, gap_error_bound_of, largest_magnitude, pressure_error_bound,
    pressure_error_bound_of,
};
use crate::solver::{contact_span, copy_on_pool, count_on_pool, ContactState, SolveError, PARALLEL_CHUNK};
use rayon::prelude::*;
use std::ops::Range;

impl AdhesiveSolver {
    /// How the next solve may stop: never early on the first solve of a step (its outputs
    /// are reported), in the reference rule or another release order; on certain
    /// attachment decisions only when trial neighbours exist (bans as the attachment
    /// phase will see them), so that the step certainly goes on.
    pub(super) fn stop_rule(
        &self,
        first: bool,
        heights: &[f64],
        state: &ContactState,
        retry_high_water: usize,
    ) -> StopRule {
        // The certificates' lattice bounds are those of square elements on a square grid:
        // rectangles converge every solve.
        if first
            || self.params.reference_rule
            || self.params.detachment != Detachment::AllViolators
            || !self.grid.is_square()
        {
            return StopRule::Converge;
        }
        if self.params.attachment != Attachment::Trial {
            return StopRule::Releases;
        }
        let bans_lifted = self.params.retry_after_growth && count_on_pool(&state.contact) > retry_high_water;
        // A trial element lies within `trial_ring_layers` rows of the contact's rows (on a
        // free grid; a periodic one wraps, so every row is looked at).
        let (n, len) = (self.grid.nx(), self.grid.len());
        let near = match self.grid.boundary() {
            Boundary::Free => {
                let reach = self.params.trial_ring_layers.get() * n;
                let span = contact_span(&state.contact, n);
                span.start.saturating_sub(reach)..(span.end + reach).min(len)
            }
            Boundary::Periodic => 0..len,
        };
        // On the pool: whether any element qualifies is the same answer in any order.
        let trial_available = near.into_par_iter().with_min_len(PARALLEL_CHUNK).any(|k| {
            // As find_candidates: only adhesive elements are tried.
            if state.contact[k] || !heights[k].is_finite() || (self.banned[k] && !bans_lifted) {
                return false;
            }
            if self.critical_stress[k] <= 0.0 {
                return false;
            }
            self.within_trial_reach(k, &state.contact)
        });
        if trial_available {
            StopRule::ReleasesOrAttachments
        } else {
            StopRule::Releases
        }
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
    pub(super) fn solve_fixed_set<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
        exact: bool,
        stop: StopRule,
    ) -> Result<usize, SolveError> {
        // Element-wise loops over the grid, on the pool (the same bits for any split).
        state
            .pressure
            .par_chunks_mut(PARALLEL_CHUNK)
            .zip(state.contact.par_chunks(PARALLEL_CHUNK))
            .for_each(|(pressure, contact)| {
                for (p, &c) in pressure.iter_mut().zip(contact) {
                    if !c {
                        *p = 0.0;
                    }
                }
            });
        if exact {
            self.make_displacement_exact(operator, state);
        } else if let Some(changed) =
            pressure_change(&mut self.work.direction, &state.pressure, &self.displacement_pressure)
        {
            // Applied by the CG's start: on its window when the change lies in it.
            self.pending_change = Some(changed);
            self.displacement_drifted = true;
        }
        let mut iterations = self.iterate_fixed_set(operator, heights, depth, state, stop)?;
        if !self.last_solve_certified {
            iterations += self.refine_ties(operator, heights, depth, state)?;
        }
        if self.last_solve_certified {
            self.certified_stops += 1;
            if self.params.check_certificates {
                iterations += self.check_certificate(operator, heights, depth, state)?;
            }
        }
        copy_on_pool(&mut self.displacement_pressure, &state.pressure);
        Ok(iterations)
    }

    /// Tie refinement (docs/fast-step.md §2): a converged solve whose iterate leaves some
    /// release decision inside its error band (|p + σ_c| ≤ band) is continued, from u
    /// recomputed in double precision, at tolerances [`TIE_TOLERANCE_SCALE`] times the
    /// solver's, until no decision lies inside the (shrinking) band or those tolerances are
    /// met. The decisions are then those of the exact solution wherever its margin exceeds
    /// the refined band, whatever iterate the solve came from. Returns the iterations.
    fn refine_ties<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
    ) -> Result<usize, SolveError> {
        let span = contact_span(&state.contact, self.grid.nx());
        let (_, uncertain) = count_releases(
            &state.pressure[span.clone()],
            &state.contact[span.clone()],
            &self.critical_stress[span],
            self.pressure_error_bound,
        );
        if uncertain == 0 {
            return Ok(0);
        }
        self.tie_refinements += 1;
        // Even without single-precision updates since the last exact u, the CG's own
        // steps moved u by single-precision responses: the refinement starts exact.
        self.make_displacement_exact(operator, state);
        let iterations = match self.iterate_fixed_set(operator, heights, depth, state, StopRule::Decided) {
            Ok(iterations) => iterations,
            // The refined tolerances out of reach: the decision stays a tie, taken on the
            // iterate, which is at least as converged as the plain solve (p and u stay
            // consistent through every CG iteration).
            Err(SolveError::NotConverged { iterations, .. }) => {
                self.unresolved_ties += 1;
                iterations
            }
            Err(error) => return Err(error),
        };
        // Refined from a converged state: as converged as the plain solve, for the outputs.
        self.last_solve_certified = false;
        Ok(iterations)
    }

    /// Converges the state that ends a step at [`OUTPUT_TOLERANCE_SCALE`] times the
    /// tolerances, from an exact u: the decisions are taken, but the reported force and
    /// energy then do not depend on where the last CG happened to stop within its
    /// tolerance (a warm-started solve may stop just inside it). Returns the iterations.
    pub(super) fn polish_output<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
    ) -> Result<usize, SolveError> {
        if self.displacement_drifted {
            self.make_displacement_exact(operator, state);
        }
        let iterations = self.iterate_fixed_set(operator, heights, depth, state, StopRule::Output)?;
        copy_on_pool(&mut self.displacement_pressure, &state.pressure);
        // The step's outputs and the next step read u everywhere.
        self.sync_outside(operator, state);
        Ok(iterations)
    }

    /// u = K p in double precision, from the pressures alone.
    fn make_displacement_exact<O: ElasticOperator + ?Sized>(&mut self, operator: &mut O, state: &mut ContactState) {
        operator.apply(&state.pressure, &mut state.displacement);
        self.windows.discard_lag();
        self.displacement_drifted = false;
    }

    /// Brings the displacement outside the last solve's window up to its pressure (a
    /// reader of u outside the contact follows: the growth, a probe, the outputs, a saved
    /// state).
    pub(super) fn sync_outside<O: ElasticOperator + ?Sized>(&mut self, operator: &mut O, state: &mut ContactState) {
        // The residual and response are free between solves (the pending change of the
        // next solve is in `direction`).
        self.windows.sync_outside(
            operator,
            &mut state.displacement,
            (&mut self.work.residual, &mut self.work.response),
        );
    }

    /// [`AdhesiveParams::check_certificates`]: converges the solve fully from the early
    /// stop, checks every pressure moved by less than the certified bound and every release
    /// decision stayed, then restores the early state.
    pub(super) fn check_certificate<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
    ) -> Result<usize, SolveError> {
        self.sync_outside(operator, state);
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
                    (converged - certified).abs() <= bound
                        && ((converged < -sigma) == (certified < -sigma) || (-certified - sigma).abs() <= bound),
                    "certificate violated at element {k}: converged p = {converged:e}, early p = {certified:e}, bound {bound:e}, σ_c = {sigma:e}"
                );
            }
        }
        state.pressure.copy_from_slice(&early.pressure);
        state.displacement.copy_from_slice(&early.displacement);
        self.windows.discard_lag();
        (self.pressure_error_bound, self.gap_error_bound) = (bound, gap_bound);
        self.last_solve_certified = true;
        Ok(iterations)
    }

    /// Writes r = (d − z) − u on C (0 elsewhere) and returns (‖d − z‖², ‖r‖²) over C. The
    /// residual vanishes off the contact: only the contact's rows `span` are visited (the
    /// sums meet the contact elements in the same order).
    fn set_residual(&mut self, heights: &[f64], depth: f64, state: &ContactState, span: Range<usize>) -> (f64, f64) {
        let mut target_norm = 0.0;
        let mut residual_norm = 0.0;
        self.work.residual[..span.start].fill(0.0);
        self.work.residual[span.end..].fill(0.0);
        for k in span {
            if state.contact[k] {
                let target = depth - heights[k];
                target_norm += target * target;
                self.work.residual[k] = target - state.displacement[k];
                residual_norm += self.work.residual[k] * self.work.residual[k];
            } else {
                self.work.residual[k] = 0.0;
            }
        }
        (target_norm, residual_norm)
    }

    /// The plain convergence test of a solve whose ‖d − z‖²_C is `target_norm`.
    fn convergence(&self, target_norm: f64, contact_modulus: f64) -> Convergence {
        // A point-wise bound well below the displacement an element of stress σ_c produces
        // by itself.
        let pointwise = if self.minimum_critical_stress > 0.0 {
            self.params.front_tolerance
                * SELF_COMPLIANCE_FACTOR
                * self.minimum_critical_stress
                * self.bound_element_size()
                / contact_modulus
        } else {
            f64::INFINITY
        };
        Convergence {
            relative: self.params.relative_tolerance * target_norm.sqrt(),
            pointwise,
        }
    }

    /// 1 on C, 0 elsewhere: branch-free vector loops (direction and residual are 0 outside
    /// C, so the masked updates equal the element-wise conditional ones). Only the
    /// contact's rows `span` hold ones.
    fn fill_mask(&mut self, contact: &[bool], span: Range<usize>) {
        // On the pool: a full-grid pass (the same values for any split).
        self.work
            .mask
            .par_chunks_mut(PARALLEL_CHUNK)
            .zip(contact.par_chunks(PARALLEL_CHUNK))
            .enumerate()
            .for_each(|(chunk, (mask, contact))| {
                let first = chunk * PARALLEL_CHUNK;
                for (k, (m, &c)) in mask.iter_mut().zip(contact).enumerate() {
                    *m = if c && span.contains(&(first + k)) { 1.0 } else { 0.0 };
                }
            });
    }

    /// The CG iterations of [`solve_fixed_set`](Self::solve_fixed_set), from a state
    /// whose u = K p is up to date (a tie refinement, `StopRule::Decided`, at
    /// [`TIE_TOLERANCE_SCALE`] times the solver's tolerances and at most
    /// [`TIE_MAX_ITERATIONS`] iterations).
    pub(super) fn iterate_fixed_set<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
        stop: StopRule,
    ) -> Result<usize, SolveError> {
        let (tolerance_scale, max_iterations) = match stop {
            StopRule::Decided => (TIE_TOLERANCE_SCALE, TIE_MAX_ITERATIONS),
            StopRule::Output => (OUTPUT_TOLERANCE_SCALE, self.params.max_cg_iterations),
            _ => (1.0, self.params.max_cg_iterations),
        };
        let (contact_modulus, element_size) = (operator.contact_modulus(), self.bound_element_size());
        self.last_solve_certified = false;
        let pending = self.pending_change.take();
        self.enter_window(operator, state, pending);
        let span = contact_span(&state.contact, self.grid.nx());
        let (target_norm, residual_norm) = self.set_residual(heights, depth, state, span.clone());
        if target_norm == 0.0 {
            // d − z = 0 on all of C (a flat face exactly at the depth, e.g. a punch retracted
            // to d = 0): K_CC p_C = 0 has the exact solution p = 0 (K is positive definite),
            // so u = K p = 0; CG could never meet ‖r‖ ≤ ε‖b‖ = 0 on the rounding of p.
            state.pressure.iter_mut().for_each(|p| *p = 0.0);
            state.displacement.iter_mut().for_each(|u| *u = 0.0);
            self.windows.discard_lag();
            (self.pressure_error_bound, self.gap_error_bound) = (0.0, 0.0);
            return Ok(0);
        }
        let convergence = self.convergence(target_norm, contact_modulus);
        let rule = SetRule {
            stop,
            tolerance_scale,
            convergence,
            contact_modulus,
            element_size,
            max_iterations,
        };
        // r and C vanish outside the contact's rows: the test there is the whole grid's.
        let (residual_rows, contact_rows) = (&self.work.residual[span.clone()], &state.contact[span.clone()]);
        if convergence.met(tolerance_scale, residual_norm, residual_rows, contact_rows) {
            self.pressure_error_bound =
                pressure_error_bound(&self.work.residual[span.clone()], contact_modulus, element_size);
            self.gap_error_bound = gap_error_bound(&self.work.residual[span.clone()]);
            self.windows.leave(&mut state.pressure, &mut state.displacement);
            return Ok(0);
        }
        self.fill_mask(&state.contact, span.clone());
        let applications = &mut self.preconditioner_applications;
        let (outcome, certified, largest) = match self.windows.current() {
            Some(window) => {
                window.load_set(
                    &self.work.residual,
                    &self.work.mask,
                    &self.critical_stress,
                    &state.contact,
                );
                let before = window.operator.applications();
                let (buffers, preconditioner) = window.workspace.buffers();
                let sets = SetFields {
                    contact: &window.contact,
                    critical_stress: &window.critical_stress,
                    attachments: None,
                };
                let (outcome, certified) = solve_on_set(
                    window.operator.as_mut(),
                    (&mut window.pressure, &mut window.displacement),
                    buffers,
                    (preconditioner, applications),
                    sets,
                    rule,
                );
                self.window_applications += window.operator.applications() - before;
                let largest = largest_magnitude(&window.workspace.residual);
                self.windows.leave(&mut state.pressure, &mut state.displacement);
                (outcome, certified, largest)
            }
            None => {
                let (buffers, preconditioner) = self.work.buffers();
                let sets = SetFields {
                    contact: &state.contact,
                    critical_stress: &self.critical_stress,
                    attachments: Some((heights, depth)),
                };
                let (outcome, certified) = solve_on_set(
                    operator,
                    (&mut state.pressure, &mut state.displacement),
                    buffers,
                    (preconditioner, applications),
                    sets,
                    rule,
                );
                (outcome, certified, largest_magnitude(&self.work.residual[span]))
            }
        };
        self.last_solve_certified = certified;
        self.pressure_error_bound = pressure_error_bound_of(largest, contact_modulus, element_size);
        self.gap_error_bound = gap_error_bound_of(largest);
        outcome.map(|info| info.iterations).map_err(|error| {
            error.into_solve_error(target_norm.sqrt(), tolerance_scale * self.params.relative_tolerance)
        })
    }

    /// Chooses the CG's window for the contact in `state` and loads it, after bringing u up
    /// to the pressure change `pending` (in `direction`, from the solve's start): on the
    /// window when the change lies inside it, else on the whole grid. A window whose
    /// outside lags is kept while it serves the contact ([`SetWindows::keep`]); otherwise
    /// the outside is brought up first.
    fn enter_window<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        state: &mut ContactState,
        pending: Option<Range<usize>>,
    ) {
        let kept = self.windows.keep(&state.contact);
        if !kept {
            self.sync_outside(operator, state);
            if self.grid.boundary() == Boundary::Free && self.params.contact_window {
                self.windows.enter(operator, &state.contact, self.params.preconditioned);
            } else {
                self.windows.clear();
            }
        }
        let on_window = match (&pending, self.windows.current()) {
            (Some(changed), Some(window)) => window.holds(&self.work.direction, changed.clone()),
            _ => false,
        };
        if let Some(changed) = pending.filter(|_| !on_window) {
            // A change on the whole grid while the outside lags would be counted twice
            // where it lies in the window: bring the outside up first.
            self.sync_outside(operator, state);
            apply_change(
                operator,
                &self.work.direction,
                &mut self.work.response,
                &mut state.displacement,
                changed,
            );
        }
        let lagging = self.windows.lagging();
        if let Some(window) = self.windows.current() {
            let base = if on_window {
                &self.displacement_pressure
            } else {
                &state.pressure
            };
            self.window_applications += window.load_state(&state.pressure, &mut state.displacement, base, lagging);
        }
    }
}

/// u += K·change in single precision on the whole grid, for a change that vanishes outside
/// the elements `changed` (only their rows are transformed forward: the same bits).
fn apply_change<O: ElasticOperator + ?Sized>(
    operator: &mut O,
    change: &[f64],
    response: &mut [f64],
    displacement: &mut [f64],
    changed: Range<usize>,
) {
    let (n, rows) = (operator.grid().nx(), operator.grid().ny());
    let input_rows = changed.start / n..changed.end.div_ceil(n);
    operator.apply_single_rows(change, response, input_rows, 0..rows);
    displacement
        .par_chunks_mut(PARALLEL_CHUNK)
        .zip(response.par_chunks(PARALLEL_CHUNK))
        .for_each(|(u, du)| u.iter_mut().zip(du).for_each(|(u, du)| *u += du));
}

/// Tolerances of a tie refinement relative to the solver's (relative residual 1e-6 →
/// 1e-10, front 1e-4 → 1e-8 by default): the band of a converged refinement is ≈ 5e-8·σ_c.
const TIE_TOLERANCE_SCALE: f64 = 1e-4;

/// Tolerances of the state that ends a step relative to the solver's (`polish_output`).
const OUTPUT_TOLERANCE_SCALE: f64 = 0.1;

/// Iterations a tie refinement may take (from a converged state it needs ≈ 10 to reach the
/// refined tolerances; more means they are out of reach of the single-precision directions).
const TIE_MAX_ITERATIONS: usize = 100;

/// Writes direction = p − p_last and returns the range from the first to the last element
/// where it is nonzero (`None` when p has not changed).
fn pressure_change(direction: &mut [f64], pressure: &[f64], last: &[f64]) -> Option<Range<usize>> {
    direction
        .par_chunks_mut(PARALLEL_CHUNK)
        .zip(pressure.par_chunks(PARALLEL_CHUNK))
        .zip(last.par_chunks(PARALLEL_CHUNK))
        .enumerate()
        .map(|(chunk, ((direction, pressure), last))| {
            let mut changed: Option<(usize, usize)> = None;
            for (i, ((d, p), q)) in direction.iter_mut().zip(pressure).zip(last).enumerate() {
                *d = p - q;
                if *d != 0.0 {
                    let k = chunk * PARALLEL_CHUNK + i;
                    changed = Some((changed.map_or(k, |(first, _)| first), k + 1));
                }
            }
            changed
        })
        .reduce(
            || None,
            |a, b| match (a, b) {
                (None, x) | (x, None) => x,
                (Some((a0, a1)), Some((b0, b1))) => Some((a0.min(b0), a1.max(b1))),
            },
        )
        .map(|(first, end)| first..end)
}
