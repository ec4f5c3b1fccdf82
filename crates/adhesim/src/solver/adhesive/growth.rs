//! Attachment and predicted-subset growth of the adhesive step (docs/fast-step.md §3).
//!
//! On the approach the step's result is the least fixed point of X ↦ peel(X ∪ ring(X))
//! (docs/physics.md §2.4a): every stable subset Y with X ⊆ Y ⊆ X ∪ R of a trial ring R, at
//! which no dropped member penetrates, is a safe intermediate set. So after the solve on
//! X ∪ R the solver predicts, with a local replay of the peel, which members of R the peel
//! will release, and attaches only the predicted holders H; the exact peel of X ∪ H (and of
//! any later predicted subset) gives such a Y. A prediction that is wrong costs solves,
//! never the result: if H fails completely, a dropped member penetrates, or Y's stability
//! is a tie within the solve's error bound (a finite-precision decision that a cascade
//! could overturn, docs/fast-step.md §3), the solved state on X ∪ R is restored and R is
//! peeled exactly, as in the reference rule, so the step still ends on the same fixed point.

use super::{AdhesiveSolver, Attachment, Flow, Growth, PredictedGrowth, Round, PREDICTION_MIN_ELEMENTS};
use crate::elastic::ElasticOperator;
use crate::grid::Grid;
use crate::solver::certificate::{classify_releases, Releases};
use crate::solver::{copy_on_pool, ContactState, SolveError, PARALLEL_CHUNK};
use rayon::prelude::*;

impl AdhesiveSolver {
    /// A round without violators: bans lifted after growth, then penetrating elements and
    /// trial neighbours attach; the step ends when there is none (or the ring is known to
    /// fail again).
    pub(super) fn attach<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
        round: &mut Round,
    ) -> Result<Flow, SolveError> {
        // Gaps outside the contact are read from here on.
        self.sync_outside(operator, state);
        if round.growth == Growth::Predicted
            && (self.dropped_member_penetrates(heights, depth, state) || self.stability_uncertain(state))
        {
            // The argument needs every dropped member at a gap ≥ 0 (F2) and the subset
            // certainly stable: otherwise peel the full ring exactly instead.
            self.fall_back(state, round);
            return self.release_violators(operator, heights, depth, state, round);
        }
        self.trial.iter_mut().for_each(|t| *t = false);
        round.growth = Growth::Exact;
        if self.params.retry_after_growth {
            let size = state.contact.iter().filter(|&&c| c).count();
            if size > round.retry_high_water {
                round.retry_high_water = size;
                self.banned.iter_mut().for_each(|b| *b = false);
                round.prediction_blocked = false;
            }
        }
        self.find_candidates(heights, depth, state);
        if self.candidates.is_empty() {
            if self.last_solve_certified || self.displacement_drifted {
                // Only if the certified stop's trial test (stop_rule) saw candidates that
                // find_candidates does not: the step must not end on an early stop (nor on
                // a displacement followed in single precision: the outputs need the exact u).
                self.converge_final(operator, heights, depth, state, &mut round.report)?;
            }
            return Ok(Flow::Stop);
        }
        let pure_ring = self.candidates.iter().all(|&k| self.trial[k]);
        if !pure_ring || self.current_ring.is_some() {
            // A ring that partly held (or penetration) breaks the chain of identical
            // failed rings the prediction needs.
            self.clear_ring_history();
        }
        self.drop_current_ring();
        round.ring_restorable = pure_ring;
        if pure_ring {
            if self.predict_failed_ring(depth, state) {
                if self.last_solve_certified || self.displacement_drifted {
                    self.converge_final(operator, heights, depth, state, &mut round.report)?;
                }
                for &k in &self.candidates {
                    self.trial[k] = false;
                    self.banned[k] = true;
                }
                return Ok(Flow::Stop);
            }
            self.saved_needs_convergence = self.last_solve_certified || self.displacement_drifted;
            copy_on_pool(&mut self.saved_pressure, &state.pressure);
            copy_on_pool(&mut self.saved_displacement, &state.displacement);
            self.current_ring = Some(self.ring_pool.attempt(depth, &state.contact));
            if self.prediction_allowed(round) {
                round.growth = Growth::FullRing;
                self.ring_members.clear();
                self.ring_members.extend_from_slice(&self.candidates);
            }
        }
        for &k in &self.candidates {
            state.contact[k] = true;
        }
        round.report.attachment_rounds += 1;
        Ok(Flow::Continue)
    }

    /// Whether free element `k` lies within [`AdhesiveParams::trial_ring_layers`] edge-neighbour
    /// steps ([`Grid::for_each_neighbour`](crate::Grid::for_each_neighbour)) of the contact:
    /// with 1 layer, whether it touches the contact (the paper's rule); with 2, also whether
    /// one of its neighbours does. The walk costs 4^layers look-ups per element.
    ///
    /// [`AdhesiveParams::trial_ring_layers`]: super::AdhesiveParams::trial_ring_layers
    pub(super) fn within_trial_reach(&self, k: usize, contact: &[bool]) -> bool {
        within_steps(&self.grid, contact, k, self.params.trial_ring_layers.get())
    }

    /// Attachment candidates: penetrating elements, then (trial attachment) free
    /// unbanned adhesive elements within the trial reach of the contact (its edge-neighbours
    /// by default), marked as trial.
    fn find_candidates(&mut self, heights: &[f64], depth: f64, state: &ContactState) {
        self.candidates.clear();
        let len = self.grid.len();
        let trial_attachment = self.params.attachment == Attachment::Trial;
        let (grid, layers) = (&self.grid, self.params.trial_ring_layers.get());
        let (banned, critical_stress) = (&self.banned, &self.critical_stress);
        // On the pool, chunk by chunk, the chunks' lists joined in order: the serial scan's
        // list (the test of an element reads nothing the scan writes).
        let found: Vec<Vec<(usize, bool)>> = (0..len.div_ceil(PARALLEL_CHUNK))
            .into_par_iter()
            .map(|chunk| {
                let elements = chunk * PARALLEL_CHUNK..((chunk + 1) * PARALLEL_CHUNK).min(len);
                elements
                    .filter_map(|k| {
                        if state.contact[k] || !heights[k].is_finite() {
                            return None;
                        }
                        let gap = heights[k] - depth + state.displacement[k];
                        if gap < 0.0 {
                            Some((k, false))
                        } else {
                            (trial_attachment
                                && may_try(banned, critical_stress, k)
                                && within_steps(grid, &state.contact, k, layers))
                            .then_some((k, true))
                        }
                    })
                    .collect()
            })
            .collect();
        for (k, trial) in found.into_iter().flatten() {
            self.candidates.push(k);
            if trial {
                self.trial[k] = true;
            }
        }
    }

    /// Whether the ring about to be attached may grow through a predicted subset: the fast
    /// rule on a free grid with retries after growth, one layer per trial ring (the replay
    /// and its evidence, docs/fast-step.md §3, are for that rule), and no element banned (the step is at
    /// its high-water mark, so the reference rule lifts every ban on any growth and the
    /// least-fixed-point argument applies; docs/fast-step.md §3).
    fn prediction_allowed(&self, round: &Round) -> bool {
        let wanted = match self.params.predicted_growth {
            PredictedGrowth::Off => false,
            PredictedGrowth::On => true,
            PredictedGrowth::Auto => self.grid.len() >= PREDICTION_MIN_ELEMENTS,
        };
        wanted
            && !round.prediction_blocked
            && self.params.retry_after_growth
            && self.local_peel.is_some()
            && self.params.trial_ring_layers.get() == 1
            && !self.banned.iter().any(|&b| b)
    }

    /// A round with violators while a ring grows through prediction: after the solve on
    /// X ∪ R, the predicted failures are released (all of R predicted to fail: the exact
    /// peel); after a solve on a predicted subset, the members predicted to fail now are
    /// released, and if that is all of them, the full ring's solved state is restored and
    /// peeled exactly.
    pub(super) fn release_predicted<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
        round: &mut Round,
    ) -> Result<Flow, SolveError> {
        let any_failed_trial = self.violators.iter().any(|&k| self.trial[k]);
        if round.growth == Growth::FullRing {
            self.sync_outside(operator, state);
            copy_on_pool(&mut self.ring_solved_pressure, &state.pressure);
            copy_on_pool(&mut self.ring_solved_displacement, &state.displacement);
            self.ring_solved_bounds = (
                self.pressure_error_bound,
                self.gap_error_bound,
                self.last_solve_certified,
            );
        }
        let members = self.ring_members.iter().filter(|&&k| self.trial[k]).count();
        if any_failed_trial && round.ring_restorable {
            self.predict_failures(state);
        } else {
            // An element of X fails: not a ring peel (possible only through a tie in finite
            // precision): leave the prediction.
            self.predicted_failures.clear();
        }
        let all_fail = self.predicted_failures.len() == members;
        if round.growth == Growth::FullRing && (all_fail || self.predicted_failures.is_empty()) {
            // The whole ring is predicted to fail (the step may end on this ring): its
            // exact peel.
            round.growth = Growth::Exact;
            round.prediction_blocked = true;
            return self.release_violators(operator, heights, depth, state, round);
        }
        if all_fail || self.predicted_failures.is_empty() {
            self.fall_back(state, round);
            return self.release_violators(operator, heights, depth, state, round);
        }
        if round.growth == Growth::FullRing {
            self.predicted_rings += 1;
        }
        for index in 0..self.predicted_failures.len() {
            let k = self.predicted_failures[index];
            let released_pressure = state.pressure[k];
            self.release(k, state);
            self.spread_release(k, released_pressure, state);
        }
        round.growth = Growth::Predicted;
        Ok(Flow::Continue)
    }

    /// Whether a member of the full ring R left out of the stable predicted subset
    /// penetrates (or lies within the gap error bound of 0). Attaching the subset lowers the
    /// free gaps (F2); a dropped member at g < 0 would be attached by penetration, which
    /// lowers pressures, so the subset is no longer certainly part of the full ring's peel.
    fn dropped_member_penetrates(&self, heights: &[f64], depth: f64, state: &ContactState) -> bool {
        self.ring_members
            .iter()
            .any(|&k| !state.contact[k] && heights[k] - depth + state.displacement[k] <= self.gap_error_bound)
    }

    /// Whether the stability of the current set is a tie (docs/fast-step.md §2): some
    /// element's margin |p + σ_c| lies within the pressure error bound of the last solve, so
    /// the exact pressures may release it although the iterate does not. A predicted subset
    /// is accepted only if it is certainly stable: the reference rule meets such a tie on its
    /// own peel of the full ring too (from another iterate), and a release there can cascade
    /// through the whole subset.
    fn stability_uncertain(&self, state: &ContactState) -> bool {
        classify_releases(
            &state.pressure,
            &state.contact,
            &self.critical_stress,
            self.pressure_error_bound,
        ) == Releases::Uncertain
    }

    /// Restores the state solved on X ∪ R (the predicted subset failed completely) and
    /// finds its violators again: R is then peeled exactly, without prediction.
    fn fall_back(&mut self, state: &mut ContactState, round: &mut Round) {
        self.prediction_fallbacks += 1;
        for &k in &self.ring_members {
            state.contact[k] = true;
            self.trial[k] = true;
        }
        copy_on_pool(&mut state.pressure, &self.ring_solved_pressure);
        copy_on_pool(&mut state.displacement, &self.ring_solved_displacement);
        self.windows.discard_lag();
        copy_on_pool(&mut self.displacement_pressure, &self.ring_solved_pressure);
        self.displacement_drifted = true;
        (
            self.pressure_error_bound,
            self.gap_error_bound,
            self.last_solve_certified,
        ) = self.ring_solved_bounds;
        // Every ban of the step was set by the predicted attempt (prediction_allowed).
        self.banned.iter_mut().for_each(|b| *b = false);
        round.growth = Growth::Exact;
        round.prediction_blocked = true;
        self.find_violators(state);
    }

    /// Predicts which current trial members the exact peel releases: the violators, then,
    /// in single local releases (docs/fast-step.md §3), every trial member whose estimated
    /// tension −p + (local rises) exceeds σ_c. Leaves them in `predicted_failures`; the state
    /// is unchanged.
    fn predict_failures(&mut self, state: &mut ContactState) {
        self.predicted_failures.clear();
        let Some(mut peel) = self.local_peel.take() else {
            return;
        };
        let n = self.grid.nx();
        for &k in &self.ring_members {
            if self.trial[k] {
                peel.lower[k] = -state.pressure[k];
            }
        }
        peel.queue.clear();
        for &k in &self.violators {
            if self.trial[k] {
                peel.queue.push(k);
                peel.queued[k] = true;
            }
        }
        let Some(mut predictor) = self.peel_predictor.take() else {
            self.local_peel = Some(peel);
            return;
        };
        let start = std::time::Instant::now();
        // The first batch (the violators of the solve) is released in this order whatever
        // the tensions: its windows are computed ahead, on all threads (the same bits).
        let planned = predictor.plan_batch(n, &peel.queue, &state.contact);
        let batch = peel.queue.len();
        let mut head = 0;
        while head < peel.queue.len() {
            let released = peel.queue[head];
            head += 1;
            let tension = peel.lower[released].max(0.0);
            // Released for the window of the next ones; restored below.
            state.contact[released] = false;
            let centre = ((released / n) as i64, (released % n) as i64);
            let from_plan = planned && head <= batch;
            if from_plan {
                predictor.mark_released(n, centre);
            } else {
                predictor.release(n, centre, |k| state.contact[k]);
            }
            for ((row, column), rise) in predictor.window(from_plan.then(|| head - 1)) {
                let k = row as usize * n + column as usize;
                if !self.trial[k] {
                    continue;
                }
                // Queued members keep collecting rises until they are released.
                peel.lower[k] += rise * tension;
                if !peel.queued[k] && peel.lower[k] > self.critical_stress[k] {
                    peel.queue.push(k);
                    peel.queued[k] = true;
                }
            }
        }
        predictor.finish();
        self.peel_predictor = Some(predictor);
        self.prediction_seconds += start.elapsed().as_secs_f64();
        for &k in &peel.queue {
            peel.queued[k] = false;
            state.contact[k] = true;
        }
        self.predicted_failures.extend_from_slice(&peel.queue);
        self.local_peel = Some(peel);
    }
}

/// Whether free element `k` may be tried as a trial neighbour: not banned, and adhesive.
/// An element with σ_c = 0 (γ = 0) attached at a positive gap carries tension (the Schur
/// complement of K_CC is positive) and would fail at once, so it attaches only by
/// penetration (docs/physics.md §2.2).
fn may_try(banned: &[bool], critical_stress: &[f64], k: usize) -> bool {
    !banned[k] && critical_stress[k] > 0.0
}

/// Whether an element of `contact` lies within `steps` edge-neighbour steps of element `k`
/// (`k` itself excluded): a walk over [`Grid::for_each_neighbour`] through any elements.
fn within_steps(grid: &Grid, contact: &[bool], k: usize, steps: usize) -> bool {
    let mut found = false;
    grid.for_each_neighbour(k, |neighbour| {
        found = found || contact[neighbour] || (steps > 1 && within_steps(grid, contact, neighbour, steps - 1));
    });
    found
}

#[cfg(test)]
mod tests {
    use super::super::{AdhesiveParams, StepReport};
    use super::*;
    use crate::elastic::FreeOperator;
    use crate::grid::{Boundary, Grid};
    use crate::material::ElasticMaterial;

    /// A solver in the state after a stable-looking solve on a predicted subset: contact
    /// block X ∪ H' of a 16² grid, one ring member dropped (free, positive gap), and one
    /// element of H' at tension (1 − 1e-7)·σ_c; returns the solver, the state and the round.
    fn predicted_subset() -> (AdhesiveSolver, ContactState, Round, Grid) {
        let grid = Grid::new(16, 1.0, Boundary::Free).expect("grid");
        let params = AdhesiveParams {
            predicted_growth: PredictedGrowth::On,
            ..AdhesiveParams::default()
        };
        let mut solver = AdhesiveSolver::new(grid, 1.0, vec![1e-3; grid.len()], params);
        let mut state = ContactState::new(&grid);
        let held = 8 * 16 + 10;
        let dropped = 8 * 16 + 11;
        for row in 6..10 {
            for column in 6..11 {
                state.contact[row * 16 + column] = true;
                state.pressure[row * 16 + column] = 0.1;
            }
        }
        state.pressure[held] = -(1.0 - 1e-7) * solver.critical_stress[held];
        solver.ring_members = vec![held, dropped];
        solver.ring_solved_pressure.copy_from_slice(&state.pressure);
        solver.ring_solved_displacement.copy_from_slice(&state.displacement);
        let round = Round {
            report: StepReport::default(),
            retry_high_water: 0,
            ring_restorable: true,
            growth: Growth::Predicted,
            prediction_blocked: false,
        };
        (solver, state, round, grid)
    }

    /// The candidates found on the pool are the serial scan's, in its order, with the same
    /// trial marks: a 128² grid (two pool chunks) whose ragged contact, penetrating
    /// elements, banned and non-adhesive elements lie on both sides of the chunks' border,
    /// on a pool of four threads (each chunk's list joined in order; a wrong join or a
    /// dropped chunk reorders or loses candidates).
    #[test]
    fn candidates_found_on_the_pool_are_the_serial_scans() {
        let n = 128;
        let grid = Grid::new(n, 1.0, Boundary::Free).expect("grid");
        let work_of_adhesion: Vec<f64> = (0..grid.len()).map(|k| if k % 7 == 3 { 0.0 } else { 1e-3 }).collect();
        let mut solver = AdhesiveSolver::new(grid, 1.0, work_of_adhesion, AdhesiveParams::default());
        let mut state = ContactState::new(&grid);
        let (centre, depth) = (63.5, 0.0);
        let mut heights = vec![0.0; grid.len()];
        for k in 0..grid.len() {
            let (row, column) = ((k / n) as f64 - centre, (k % n) as f64 - centre);
            let radius = (row * row + column * column).sqrt();
            // A ragged disc of radius 37–43 in contact, and a shallow bowl that penetrates
            // out to radius 41: its ragged edge has free neighbours that penetrate and
            // free neighbours that do not (the trial ones).
            state.contact[k] = radius < 40.0 + 3.0 * (column * 0.7).sin();
            heights[k] = 1e-4 * (radius - 41.0);
            solver.banned[k] = k % 11 == 5;
        }
        heights[5] = f64::INFINITY;
        let serial: Vec<(usize, bool)> = (0..grid.len())
            .filter(|&k| !state.contact[k] && heights[k].is_finite())
            .filter_map(|k| {
                if heights[k] - depth + state.displacement[k] < 0.0 {
                    Some((k, false))
                } else {
                    let tried = !solver.banned[k] && solver.critical_stress[k] > 0.0;
                    (tried && within_steps(&grid, &state.contact, k, 1)).then_some((k, true))
                }
            })
            .collect();
        let pool = rayon::ThreadPoolBuilder::new().num_threads(4).build().expect("pool");
        pool.install(|| solver.find_candidates(&heights, depth, &state));
        let found: Vec<(usize, bool)> = solver.candidates.iter().map(|&k| (k, solver.trial[k])).collect();
        let (tried, penetrating) = (
            serial.iter().filter(|c| c.1).count(),
            serial.iter().filter(|c| !c.1).count(),
        );
        assert!(
            tried > 50 && penetrating > 50,
            "{tried} trial, {penetrating} penetrating candidates"
        );
        assert!(serial.iter().any(|c| c.0 < PARALLEL_CHUNK) && serial.iter().any(|c| c.0 >= PARALLEL_CHUNK));
        assert_eq!(found, serial);
        assert_eq!(
            solver.trial.iter().filter(|&&t| t).count(),
            serial.iter().filter(|c| c.1).count()
        );
    }

    /// Guard (b) of docs/fast-step.md §3: a predicted subset whose stability is a tie (a
    /// member's margin 1e-7·σ_c inside an error bound of 1e-3·σ_c) is not accepted: the full
    /// ring is restored (the dropped member is back in contact) for the exact peel. With an
    /// error bound below the margin the same subset is accepted and its own ring (which
    /// holds the dropped member again) is attached, to be grown through a prediction.
    #[test]
    fn a_tie_on_a_predicted_subset_falls_back_to_the_full_ring() {
        let heights = vec![1.0; 256];
        for (bound_in_sigma, falls_back) in [(1e-3, true), (1e-9, false)] {
            let (mut solver, mut state, mut round, grid) = predicted_subset();
            solver.pressure_error_bound = bound_in_sigma * solver.critical_stress[0];
            let mut operator = FreeOperator::new(grid, ElasticMaterial::new(1.0).expect("modulus"));
            solver
                .attach(&mut operator, &heights, 0.0, &mut state, &mut round)
                .expect("attach");
            let dropped = 8 * 16 + 11;
            assert_eq!(solver.predicted_growth().1, falls_back as u64, "bound {bound_in_sigma}");
            assert_eq!(round.prediction_blocked, falls_back, "bound {bound_in_sigma}");
            // Restored (fallback) or attached again as a member of the next ring (accepted).
            assert!(state.contact[dropped]);
            let growth = if falls_back { Growth::Exact } else { Growth::FullRing };
            assert_eq!(round.growth, growth, "bound {bound_in_sigma}");
        }
    }

    /// The elements within `steps` of one contact element at (row, column) on an n² grid.
    fn reach(boundary: Boundary, n: usize, (row, column): (usize, usize), steps: usize) -> Vec<(usize, usize)> {
        let grid = Grid::new(n, 1.0, boundary).unwrap();
        let mut contact = vec![false; n * n];
        contact[row * n + column] = true;
        (0..n * n)
            .filter(|&k| !contact[k] && within_steps(&grid, &contact, k, steps))
            .map(|k| (k / n, k % n))
            .collect()
    }

    /// One step is the edge-neighbour test of the paper's rule (the 4 neighbours); two steps
    /// are the diamond |Δrow| + |Δcolumn| ≤ 2 (12 elements), cut at a free edge and wrapped
    /// on a periodic grid, as `Grid::for_each_neighbour` is.
    #[test]
    fn trial_reach_is_the_edge_neighbour_distance() {
        assert_eq!(
            reach(Boundary::Free, 7, (3, 3), 1),
            vec![(2, 3), (3, 2), (3, 4), (4, 3)]
        );
        let diamond = reach(Boundary::Free, 7, (3, 3), 2);
        assert_eq!(diamond.len(), 12);
        assert!(diamond
            .iter()
            .all(|&(r, c)| (r as i64 - 3).abs() + (c as i64 - 3).abs() <= 2));
        // At the corner of a free grid: (0,1), (1,0), (0,2), (1,1), (2,0).
        assert_eq!(reach(Boundary::Free, 7, (0, 0), 2).len(), 5);
        // On a periodic grid the corner's diamond wraps: 12 elements, e.g. (6, 6) and (0, 5).
        let wrapped = reach(Boundary::Periodic, 7, (0, 0), 2);
        assert_eq!(wrapped.len(), 12);
        assert!(wrapped.contains(&(6, 6)) && wrapped.contains(&(0, 5)));
    }
}
