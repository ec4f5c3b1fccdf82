//! The rounds of a smooth cohesive law, accelerated by Anderson mixing with the energy as
//! safeguard.
//!
//! For a smooth law φ is concave (t non-increasing in g), so the tangent of φ at the
//! current gaps lies above φ: a round, which solves the contact problem under the tangent's
//! fixed tractions exactly, minimises a majoriser of the energy Π that touches Π at the
//! current state. The plain rounds are thus a majorise–minimise (concave–convex) iteration
//! t ↦ F(t) whose energy never rises (Yuille & Rangarajan 2003, *Neural Comput.* 15, 915;
//! Hunter & Lange 2004, *Am. Stat.* 58, 30). Linearised, F contracts at the spectral radius
//! of diag(t/ρ)·K, which tends to 1 on the approach to a jump and stays close to it while a
//! detached surface still bulges towards the indenter. Anderson mixing (Anderson 1965,
//! *J. ACM* 12, 547; Walker & Ni 2011, *SIAM J. Numer. Anal.* 49, 1715) combines the last
//! [`MEMORY`] rounds: on a linear map it is GMRES on the residual t − F(t). A mixed
//! traction field is kept only if the energy of its state is no higher than that of the
//! state before it (to [`ENERGY_ROUNDING`]) and its residual ‖F(t) − t‖₂ is smaller
//! (a safeguard in the manner of Zhang, O'Donoghue & Boyd 2020, *SIAM J. Optim.* 30, 3170).
//! Both are needed: near a state that lost its stability, mixing extrapolates back towards
//! that state, whose residual is small, while a change of a few elements moves the energy
//! by less than its rounding (docs/validation.md §16 traced steps where an energy-only test
//! cycled for ever). Otherwise the memory is cleared and the plain round taken. A plain
//! round that grows the residual is an escape from such a state: a forward-tracking line
//! search extends it, and mixing waits until a plain round shrinks the residual again.
//! The energy so decreases along the rounds from the previous step's state, and the step
//! ends in a local minimum reached along the load path: the jumps and
//! the hysteresis are kept.

use super::{CohesiveSolver, Interface};
use crate::elastic::ElasticOperator;
use crate::solver::dense::{cholesky_factorise, cholesky_solve, Summation};
use crate::solver::{ContactState, SolveError, StepReport};
use std::collections::VecDeque;

/// Rounds combined by one mixing.
pub(super) const MEMORY: usize = 5;

/// Energy rises relative to |Π| below this count as rounding, not as a rise (the energies of
/// successive rounds near convergence differ by less than the rounding of their sums).
const ENERGY_ROUNDING: f64 = 1e-8;

/// Differences of the residuals f = F(t) − t and of the images F(t) of successive rounds.
struct History {
    residual_changes: VecDeque<Vec<f64>>,
    image_changes: VecDeque<Vec<f64>>,
}

impl History {
    fn new() -> Self {
        Self {
            residual_changes: VecDeque::with_capacity(MEMORY),
            image_changes: VecDeque::with_capacity(MEMORY),
        }
    }

    fn is_empty(&self) -> bool {
        self.residual_changes.is_empty()
    }

    fn clear(&mut self) {
        self.residual_changes.clear();
        self.image_changes.clear();
    }

    fn push(&mut self, residual_change: Vec<f64>, image_change: Vec<f64>) {
        if self.residual_changes.len() == MEMORY {
            self.residual_changes.pop_front();
            self.image_changes.pop_front();
        }
        self.residual_changes.push_back(residual_change);
        self.image_changes.push_back(image_change);
    }

    /// The mixed iterate F(t) − ΔG·c with c the least-squares solution of ΔF·c ≈ f (normal
    /// equations with a relative Tikhonov shift of 1e-12 against rank loss).
    fn mix(&self, residual: &[f64], image: &[f64], out: &mut [f64]) {
        let m = self.residual_changes.len();
        out.copy_from_slice(image);
        if m == 0 {
            return;
        }
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        let mut matrix = vec![0.0; m * m];
        let mut rhs = vec![0.0; m];
        for i in 0..m {
            rhs[i] = dot(&self.residual_changes[i], residual);
            for j in 0..=i {
                let value = dot(&self.residual_changes[i], &self.residual_changes[j]);
                matrix[i * m + j] = value;
                matrix[j * m + i] = value;
            }
        }
        let shift = 1e-12 * (0..m).map(|i| matrix[i * m + i]).fold(0.0, f64::max);
        for i in 0..m {
            matrix[i * m + i] += shift;
        }
        if cholesky_factorise(&mut matrix, m, Summation::InOrder).is_err() {
            return;
        }
        cholesky_solve(&matrix, m, &mut rhs, Summation::InOrder);
        for (c, change) in rhs.iter().zip(&self.image_changes) {
            for (o, d) in out.iter_mut().zip(change) {
                *o -= c * d;
            }
        }
    }
}

/// The Euclidean norm.
fn norm(values: &[f64]) -> f64 {
    values.iter().map(|v| v * v).sum::<f64>().sqrt()
}

impl CohesiveSolver {
    /// ‖F(t) − t‖₂ of the last round: its image `traction` less the applied tractions.
    fn residual_norm(&self) -> f64 {
        self.traction
            .iter()
            .zip(&self.tensile_pressure)
            .map(|(image, pressure)| (image + pressure) * (image + pressure))
            .sum::<f64>()
            .sqrt()
    }

    /// Iterates from a state computed under the applied tractions −`tensile_pressure`,
    /// whose round set `traction` = F(applied) with the largest change `change`, to a
    /// converged state (no traction changing by more than the tolerance).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn converge_anderson<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
        report: &mut StepReport,
        rounds: &mut usize,
        mut change: f64,
    ) -> Result<(), SolveError> {
        let tolerance = self.tolerance();
        let len = self.grid.len();
        let mut history = History::new();
        let mut merit = self.energy(state, heights, depth, Interface::Law);
        // The image F(t) and residual F(t) − t of the current state.
        let mut image = self.traction.clone();
        let mut residual: Vec<f64> = image.iter().zip(&self.tensile_pressure).map(|(g, p)| g + p).collect();
        let mut applied: Vec<f64> = self.tensile_pressure.iter().map(|p| -p).collect();
        let mut mixed = vec![0.0; len];
        // Whether the last plain round grew the residual: the rounds are escaping from a state
        // that lost its stability, and mixing (which extrapolates back towards it) waits.
        let mut escaping = false;
        while change > tolerance {
            // The residual of the current state, ‖F(t) − t‖₂.
            let current = norm(&residual);
            let mut accepted = false;
            if !history.is_empty() && !escaping {
                history.mix(&residual, &image, &mut mixed);
                self.set_within_law(&mixed, &image);
                report.attachment_rounds += 1;
                change = self.round(operator, heights, depth, state, report, rounds)?;
                let new_merit = self.energy(state, heights, depth, Interface::Law);
                // Energy alone cannot judge a mixing that moves a few elements near a lost
                // stability (its change lies below the energy's rounding), and a smaller
                // residual alone would lead back to that unstable state: both must agree.
                accepted = new_merit <= merit + ENERGY_ROUNDING * merit.abs() && self.residual_norm() < current;
                if accepted {
                    merit = new_merit;
                } else {
                    history.clear();
                }
            }
            if !accepted {
                // The plain round (the first of a step, after a rejected mixing, or while
                // escaping), with the line search when it grows the residual.
                let plain;
                (change, merit, plain) = self.forward_tracking(
                    operator, heights, depth, state, report, rounds, &applied, &image, merit, current,
                )?;
                escaping = plain > current;
            }
            // The applied tractions were −tensile_pressure; their image is in `traction`.
            let mut residual_change = vec![0.0; len];
            let mut image_change = vec![0.0; len];
            for k in 0..len {
                let new_applied = -self.tensile_pressure[k];
                let new_image = self.traction[k];
                let new_residual = new_image - new_applied;
                residual_change[k] = new_residual - residual[k];
                image_change[k] = new_image - image[k];
                residual[k] = new_residual;
                image[k] = new_image;
                applied[k] = new_applied;
            }
            history.push(residual_change, image_change);
        }
        Ok(())
    }

    /// Sets `traction` to `tractions` kept within the law's [0, t(0)] (0 where the image is 0:
    /// elements outside the indenter or without adhesion).
    fn set_within_law(&mut self, tractions: &[f64], image: &[f64]) {
        for k in 0..tractions.len() {
            let upper = if image[k] > 0.0 { self.law.traction(k, 0.0) } else { 0.0 };
            self.traction[k] = tractions[k].clamp(0.0, upper);
        }
    }

    /// The plain round from `applied` (whose image is `image`, energy `merit` and residual
    /// `current`); when it grows the residual (an escape from a state that lost its
    /// stability, where the plain round moves by little and mixing extrapolates back
    /// towards the unstable state), rounds from applied + β·(image − applied) follow for
    /// β = 2, 4, … while the energy of their states decreases: a forward-tracking line
    /// search. Ends on the state of the best β; returns the last round's change, that
    /// state's energy and the plain round's residual ‖F(t) − t‖₂.
    #[allow(clippy::too_many_arguments)]
    fn forward_tracking<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
        report: &mut StepReport,
        rounds: &mut usize,
        applied: &[f64],
        image: &[f64],
        merit: f64,
        current: f64,
    ) -> Result<(f64, f64, f64), SolveError> {
        self.traction.copy_from_slice(image);
        report.attachment_rounds += 1;
        let mut change = self.round(operator, heights, depth, state, report, rounds)?;
        let plain = self.residual_norm();
        let mut best = (1.0, self.energy(state, heights, depth, Interface::Law));
        // A plain round that shrinks the residual is converging, not escaping (the energy
        // cannot tell: near a lost stability its changes lie below its rounding).
        if plain <= current {
            return Ok((change, best.1, plain));
        }
        let mut trial = vec![0.0; applied.len()];
        let mut beta = 2.0;
        loop {
            for k in 0..trial.len() {
                trial[k] = applied[k] + beta * (image[k] - applied[k]);
            }
            self.set_within_law(&trial, image);
            report.attachment_rounds += 1;
            change = self.round(operator, heights, depth, state, report, rounds)?;
            let energy = self.energy(state, heights, depth, Interface::Law);
            if energy < best.1 {
                best = (beta, energy);
                beta *= 2.0;
            } else if energy <= merit {
                // Past the best, but still below the start: kept (the energy still decreases
                // from round to round), saving the round that would return to the best.
                return Ok((change, energy, plain));
            } else {
                break;
            }
        }
        for k in 0..trial.len() {
            trial[k] = applied[k] + best.0 * (image[k] - applied[k]);
        }
        self.set_within_law(&trial, image);
        report.attachment_rounds += 1;
        change = self.round(operator, heights, depth, state, report, rounds)?;
        best.1 = self.energy(state, heights, depth, Interface::Law);
        Ok((change, best.1, plain))
    }
}
