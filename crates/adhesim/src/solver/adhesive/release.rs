//! Release rules of the adhesive step: violators (all, worst first, random half) and
//! certified local rounds (docs/fast-step.md).

use super::params::over_stress_ratio;
use super::{AdhesiveSolver, Detachment, StopRule};
use crate::elastic::ElasticOperator;
use crate::solver::{ContactState, SolveError, PARALLEL_CHUNK};
use rayon::prelude::*;

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
        let span = crate::solver::contact_span(&state.contact, self.grid.nx());
        let (pressure, contact, critical_stress) = (
            &state.pressure[span.clone()],
            &state.contact[span.clone()],
            &self.critical_stress[span.clone()],
        );
        // On the pool: a minimum and a maximum are exact in any order, and the violators
        // are gathered chunk by chunk in order, so the list is the serial scan's.
        let ratios = || {
            pressure
                .par_chunks(PARALLEL_CHUNK)
                .zip(contact.par_chunks(PARALLEL_CHUNK))
                .zip(critical_stress.par_chunks(PARALLEL_CHUNK))
                .enumerate()
        };
        let Some((smallest, largest)) = ratios()
            .map(|(_, ((pressure, contact), critical_stress))| {
                let mut extremes: Option<(f64, f64)> = None;
                for k in 0..pressure.len() {
                    let ratio = over_stress_ratio(pressure[k], critical_stress[k]);
                    if contact[k] && ratio > 1.0 {
                        let (smallest, largest) = extremes.unwrap_or((f64::INFINITY, 0.0));
                        extremes = Some((smallest.min(ratio), largest.max(ratio)));
                    }
                }
                extremes
            })
            .reduce(
                || None,
                |a, b| match (a, b) {
                    (Some(a), Some(b)) => Some((a.0.min(b.0), a.1.max(b.1))),
                    (a, None) => a,
                    (None, b) => b,
                },
            )
        else {
            return;
        };
        let threshold = match self.params.detachment {
            Detachment::AllViolators | Detachment::RandomHalf { .. } => smallest,
            Detachment::WorstFirst { fraction } => smallest.max(largest * (1.0 - fraction)),
        } * (1.0 - 1e-9);
        let found: Vec<Vec<usize>> = ratios()
            .map(|(chunk, ((pressure, contact), critical_stress))| {
                let first = span.start + chunk * PARALLEL_CHUNK;
                (0..pressure.len())
                    .filter(|&k| contact[k] && over_stress_ratio(pressure[k], critical_stress[k]) >= threshold)
                    .map(|k| first + k)
                    .collect()
            })
            .collect();
        self.violators.extend(found.into_iter().flatten());
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

#[cfg(test)]
mod tests {
    use super::super::{AdhesiveParams, AdhesiveSolver, Detachment};
    use super::over_stress_ratio;
    use crate::grid::{Boundary, Grid};
    use crate::solver::{ContactState, PARALLEL_CHUNK};

    /// The violators found on the pool are the serial scan's, in its order, for the
    /// worst-first rule, whose threshold needs the smallest and the largest ratio over all
    /// chunks: a 128² grid (two pool chunks of the contact's rows) whose largest ratio lies
    /// in the second chunk, on four threads.
    #[test]
    fn violators_found_on_the_pool_are_the_serial_scans() {
        let n = 128;
        let grid = Grid::new(n, 1.0, Boundary::Free).expect("grid");
        let work_of_adhesion: Vec<f64> = (0..grid.len()).map(|k| if k % 13 == 2 { 0.0 } else { 1e-3 }).collect();
        let params = AdhesiveParams {
            detachment: Detachment::WorstFirst { fraction: 0.4 },
            ..AdhesiveParams::default()
        };
        let mut solver = AdhesiveSolver::new(grid, 1.0, work_of_adhesion, params);
        let mut state = ContactState::new(&grid);
        for k in 10 * n..120 * n {
            state.contact[k] = k % 9 != 4;
            // Ratios −p/σ_c between 0.5 and 2; compression where σ_c = 0.
            let ratio = 0.5 + 1.5 * (0.5 + 0.5 * (k as f64 * 0.37).sin());
            let critical_stress = solver.critical_stress[k];
            state.pressure[k] = if critical_stress > 0.0 {
                -critical_stress * ratio
            } else {
                1e-4
            };
        }
        let largest = 100 * n + 8;
        state.pressure[largest] = -solver.critical_stress[largest] * 2.5;
        let ratio = |k: usize| over_stress_ratio(state.pressure[k], solver.critical_stress[k]);
        let violators: Vec<usize> = (0..grid.len())
            .filter(|&k| state.contact[k] && ratio(k) > 1.0)
            .collect();
        let smallest = violators.iter().map(|&k| ratio(k)).fold(f64::INFINITY, f64::min);
        let worst = violators.iter().map(|&k| ratio(k)).fold(0.0, f64::max);
        assert_eq!(worst, ratio(largest), "the largest ratio is the planted one");
        let threshold = smallest.max(worst * (1.0 - 0.4)) * (1.0 - 1e-9);
        let serial: Vec<usize> = violators.into_iter().filter(|&k| ratio(k) >= threshold).collect();
        let pool = rayon::ThreadPoolBuilder::new().num_threads(4).build().expect("pool");
        pool.install(|| solver.find_violators(&state));
        assert!(
            serial.iter().any(|&k| k < 10 * n + PARALLEL_CHUNK) && serial.iter().any(|&k| k >= 10 * n + PARALLEL_CHUNK)
        );
        assert_eq!(solver.violators, serial);
    }
}
