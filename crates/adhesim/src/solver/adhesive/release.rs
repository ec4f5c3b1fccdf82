//! Release rules of the adhesive step: violators (all, worst first, random half) and
//! certified local rounds (docs/fast-step.md).

use super::params::over_stress_ratio;
use super::{AdhesiveSolver, Detachment, StopRule};
use crate::elastic::ElasticOperator;
use crate::solver::{ContactState, SolveError};

impl AdhesiveSolver {
    /// Releases the violators (only the failed trial elements with `trial_only`), then,
    /// with local rounds, every element of the same kind whose tension a local lower bound
    /// certifies above σ_c, in a sequence of single releases (docs/fast-step.md). These are
    /// elements the following rounds of the reference rule would release. Each release
    /// also spreads its load over the contact nearby as the next solve's warm start
    /// ([`spread_release`](Self::spread_release)). Returns the number of the extra releases.
    pub(super) fn release_with_local_rounds(&mut self, state: &mut ContactState, trial_only: bool) -> usize {
        let Some(mut peel) = self.local_peel.take() else {
            for index in 0..self.violators.len() {
                let k = self.violators[index];
                if self.trial[k] || !trial_only {
                    self.release(k, state);
                }
            }
            return 0;
        };
        let n = self.grid.nx();
        for k in crate::solver::contact_span(&state.contact, n) {
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
            let released_pressure = state.pressure[released];
            self.release(released, state);
            let centre = ((released / n) as i64, (released % n) as i64);
            peel.contact_rises(n, centre, |k| state.contact[k]);
            for index in 0..peel.rises.len() {
                let (k, rise) = peel.rises[index];
                // Warm start of the next solve (see `spread_release`).
                state.pressure[k] += rise * released_pressure;
                if (trial_only && !self.trial[k]) || peel.queued[k] {
                    continue;
                }
                peel.lower[k] += rise * tension;
                if peel.lower[k] > self.critical_stress[k] {
                    peel.queue.push(k);
                    peel.queued[k] = true;
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
    pub(super) fn check_local_bounds<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
        trial_only: bool,
    ) -> Result<(), SolveError> {
        self.sync_outside(operator, state);
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
        self.windows.discard_lag();
        self.displacement_pressure = displacement_pressure;
        (
            self.pressure_error_bound,
            self.gap_error_bound,
            self.last_solve_certified,
        ) = (bound, gap_bound, certified);
        Ok(())
    }

    /// Warm start of the next solve after releasing element `released`, whose pressure was
    /// `released_pressure`: the contact elements within `REACH` take up that load by the
    /// local rises (with v's load p_v, the exact new pressures are p_i − (S_iv/S_vv)·p_v,
    /// docs/fast-step.md "Warm starts"). Only where the next CG starts changes, never the
    /// set it solves, so the decisions stay those of the solved pressures.
    pub(super) fn spread_release(&mut self, released: usize, released_pressure: f64, state: &mut ContactState) {
        let Some(mut peel) = self.local_peel.take() else {
            return;
        };
        let n = self.grid.nx();
        let centre = ((released / n) as i64, (released % n) as i64);
        peel.contact_rises(n, centre, |k| state.contact[k]);
        for &(k, rise) in &peel.rises {
            state.pressure[k] += rise * released_pressure;
        }
        self.local_peel = Some(peel);
    }

    pub(super) fn release(&mut self, k: usize, state: &mut ContactState) {
        state.contact[k] = false;
        state.pressure[k] = 0.0;
        self.banned[k] = true;
        self.trial[k] = false;
    }

    /// Collects elements of C with p < −σ_c. Exact ties (symmetric geometries) are treated
    /// alike: every element whose over-stress ratio is within 1e-9 of the smallest violating
    /// ratio is included. Elements with γ = 0 under tension have an infinite ratio
    /// ([`over_stress_ratio`]): they are violators under every rule, and the worst ones.
    pub(super) fn find_violators(&mut self, state: &ContactState) {
        self.violators.clear();
        let mut any_violator = false;
        let mut smallest = f64::INFINITY;
        let mut largest: f64 = 0.0;
        let span = crate::solver::contact_span(&state.contact, self.grid.nx());
        for k in span.clone() {
            if state.contact[k] {
                let ratio = over_stress_ratio(state.pressure[k], self.critical_stress[k]);
                if ratio > 1.0 {
                    any_violator = true;
                    smallest = smallest.min(ratio);
                    largest = largest.max(ratio);
                }
            }
        }
        if !any_violator {
            return;
        }
        let threshold = match self.params.detachment {
            Detachment::AllViolators | Detachment::RandomHalf { .. } => smallest,
            Detachment::WorstFirst { fraction } => smallest.max(largest * (1.0 - fraction)),
        } * (1.0 - 1e-9);
        for k in span {
            if state.contact[k] && over_stress_ratio(state.pressure[k], self.critical_stress[k]) >= threshold {
                self.violators.push(k);
            }
        }
        if let Detachment::RandomHalf { .. } = self.params.detachment {
            self.keep_random_half(state, largest);
        }
        if self.last_solve_certified {
            // A certified stop may leave elements inside the error band: only the certain
            // violators go now (any subset of violators is a valid release, §2.4a).
            let band = self.pressure_error_bound;
            let (pressure, critical_stress) = (&state.pressure, &self.critical_stress);
            self.violators.retain(|&k| -pressure[k] - critical_stress[k] > band);
        }
    }

    /// Keeps a random half of the violators, always including one of the worst.
    pub(super) fn keep_random_half(&mut self, state: &ContactState, largest: f64) {
        let worst = self
            .violators
            .iter()
            .position(|&k| over_stress_ratio(state.pressure[k], self.critical_stress[k]) >= largest);
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
}
