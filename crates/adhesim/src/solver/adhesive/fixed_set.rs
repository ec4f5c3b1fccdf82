//! The fixed-set solve of the adhesive step (docs/physics.md §3.2) with certified early
//! stops (docs/fast-step.md).

use super::{AdhesiveSolver, Attachment, Detachment, StopRule};
use crate::elastic::influence::SELF_COMPLIANCE_FACTOR;
use crate::elastic::ElasticOperator;
use crate::solver::certificate::{
    attachments_certain, classify_releases, gap_error_bound, pressure_error_bound, Releases,
};
use crate::solver::{masked_pcg, ContactState, PcgBuffers, SolveError};

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
        if first || self.params.reference_rule || self.params.detachment != Detachment::AllViolators {
            return StopRule::Converge;
        }
        if self.params.attachment != Attachment::Trial {
            return StopRule::Releases;
        }
        let bans_lifted =
            self.params.retry_after_growth && state.contact.iter().filter(|&&c| c).count() > retry_high_water;
        let trial_available = (0..self.grid.len()).any(|k| {
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
    pub(super) fn check_certificate<O: ElasticOperator + ?Sized>(
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
    pub(super) fn iterate_fixed_set<O: ElasticOperator + ?Sized>(
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
        if target_norm == 0.0 {
            // d − z = 0 on all of C (a flat face exactly at the depth, e.g. a punch retracted
            // to d = 0): K_CC p_C = 0 has the exact solution p = 0 (K is positive definite),
            // so u = K p = 0; CG could never meet ‖r‖ ≤ ε‖b‖ = 0 on the rounding of p.
            state.pressure.iter_mut().for_each(|p| *p = 0.0);
            state.displacement.iter_mut().for_each(|u| *u = 0.0);
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
        outcome
            .map(|info| info.iterations)
            .map_err(|error| error.into_solve_error(target_norm.sqrt(), self.params.relative_tolerance))
    }
}
