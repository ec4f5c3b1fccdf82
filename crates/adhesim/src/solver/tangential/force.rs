//! Force control of the shift: the tangential force along a direction is imposed and the
//! indenter's shift δ that carries it is found (Cattaneo 1938 and Mindlin 1949 state
//! their results this way, for a force Q below μP; docs/physics.md §8.2).
//!
//! The step is solved at once: the force is a linear constraint on the tractions and the
//! shift its multiplier, carried through the face's CG (constraint.rs), one step's rounds
//! in all. Should that solve fail, the step falls back to trials: the force along the
//! direction, F(δ), of one quasi-static step from a given state is the derivative of the
//! step's incremental energy, a convex function of δ, so F rises monotonically with δ;
//! each trial is an exact displacement-controlled step from the same starting state, the
//! shift bracketed from the secant stiffness and then found by the Illinois variant of
//! false position (Dowell & Jarratt 1971, *BIT* 11, 168), which converges superlinearly
//! and never leaves the bracket.

use super::constraint::ForceConstraint;
use super::{TangentialError, TangentialReport, TangentialSolver, TangentialState};
use crate::elastic::ShearCompliance;
use crate::solver::ContactState;

/// The imposed force is met when |F − Q| ≤ this × max(|Q|, |F⁻|), F⁻ the step's starting
/// force: a hundred times the force error left by the solver's CG tolerance (1e-10).
const FORCE_TOLERANCE: f64 = 1e-8;
/// Trial steps per force-controlled step before [`TangentialError::ForceNotReached`].
const MAX_TRIALS: usize = 60;
/// A bracketing trial moves at most this many times the last one's reach.
const MAX_REACH_GROWTH: f64 = 100.0;

/// One trial: the shift along the direction and the force along it.
#[derive(Debug, Clone, Copy)]
struct Trial {
    shift: f64,
    excess: f64,
}

impl TangentialSolver {
    /// One quasi-static step that imposes the tangential force `force` (Δ²Σq·e) along the
    /// unit vector `unit` = e: the indenter shifts along e by what carries it, from the
    /// step's starting shift δ⁻ (`state.shift`). Across e the shift does not change; the
    /// force across it is the contact's (zero for a contact symmetric about e).
    ///
    /// The step is one [`step`](Self::step) whose solves carry the force, so its fields
    /// are those of a displacement-controlled step to the shift found, to |F − Q| ≤
    /// 1e-8·max(|Q|, |F⁻|) (F⁻ the starting force); [`TangentialReport::trials`] is 1. If
    /// that solve fails or misses the force, the step is found by trials from the same
    /// start (each a displacement-controlled step), and the report's counters add up every
    /// trial's, the failed solve counted as a trial and in the transform pairs.
    ///
    /// Errors: [`TangentialError::ForceBeyondCapacity`] when |Q| reaches what the interface
    /// holds, Δ²Σg, to the tolerance (gross slip: no shift carries it);
    /// [`TangentialError::ForceControlUnsupported`] with a static law or a compliant drive
    /// (their force falls in a slip event, so a force cannot be held through one);
    /// [`TangentialError::ForceNotReached`] when the trials neither meet the force nor
    /// bracket it.
    ///
    /// # Example
    /// A glued patch under an imposed force: the shift found carries it.
    /// ```
    /// use adhesim::{Boundary, ContactState, FrictionLaw, Grid, ShearMaterial};
    /// use adhesim::{TangentialOperator, TangentialParams, TangentialSolver, TangentialState};
    ///
    /// let grid = Grid::new(8, 1.0, Boundary::Free)?;
    /// let mut operator = TangentialOperator::new(grid, ShearMaterial::from_contact_modulus(4.0, 0.5))?;
    /// let mut normal = ContactState::new(&grid);
    /// for k in [27, 28, 35, 36] {
    ///     normal.contact[k] = true;
    ///     normal.pressure[k] = 1.0;
    /// }
    /// let mut solver = TangentialSolver::new(FrictionLaw::NoSlip, TangentialParams::default());
    /// let mut state = TangentialState::new(grid.len());
    /// let report = solver.step_to_force(&mut operator, &normal, [1.0, 0.0], 2e-3, &mut state)?;
    /// assert!((report.force[0] / 2e-3 - 1.0).abs() < 1e-8);
    /// assert!(report.shift[0] > 0.0 && report.shift[1] == 0.0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn step_to_force(
        &mut self,
        operator: &mut dyn ShearCompliance,
        normal: &ContactState,
        unit: [f64; 2],
        force: f64,
        state: &mut TangentialState,
    ) -> Result<TangentialReport, TangentialError> {
        if self.static_law.is_some() || self.drive_stiffness.is_some() {
            return Err(TangentialError::ForceControlUnsupported);
        }
        let area = operator.grid().element_area();
        let capacity = self.capacity(normal, area);
        // Within the tolerance of the capacity any long enough slide meets the force.
        if !force.is_finite() || force.abs() >= capacity * (1.0 - FORCE_TOLERANCE) {
            return Err(TangentialError::ForceBeyondCapacity { force, capacity });
        }
        let start_force = along(unit, state.force(area));
        let tolerance = FORCE_TOLERANCE * force.abs().max(start_force.abs());
        let (start, history) = (state.clone(), self.history.clone());
        let pairs_before = operator.transform_pairs();
        let mut report = match self.step_to_force_at_once(operator, normal, (unit, force), state, tolerance) {
            Ok(report) => report,
            Err(_) => {
                // The trials from the same start; the single solve's transforms counted.
                state.clone_from(&start);
                self.history = history;
                let mut report = self.step_to_force_by_trials(operator, normal, (unit, force), state, tolerance)?;
                report.trials += 1;
                report
            }
        };
        report.transform_pairs = operator.transform_pairs() - pairs_before;
        Ok(report)
    }

    /// The force-controlled step as one step whose face CG carries the force
    /// (constraint.rs): the shift is the solve's multiplier. Its first target is the
    /// shift the last secant stiffness predicts (as the trials' first). An error when the
    /// solve fails or its final tractions (each slipping one back on its circle) miss the
    /// force by more than `tolerance`: the caller then falls back to the trials.
    fn step_to_force_at_once(
        &mut self,
        operator: &mut dyn ShearCompliance,
        normal: &ContactState,
        (unit, force): ([f64; 2], f64),
        state: &mut TangentialState,
        tolerance: f64,
    ) -> Result<TangentialReport, TangentialError> {
        let area = operator.grid().element_area();
        let start_force = along(unit, state.force(area));
        let origin = along(unit, state.shift);
        let stiffness = self
            .force_stiffness
            .unwrap_or_else(|| uncoupled_stiffness(operator, normal));
        let reach = (force - start_force) / stiffness;
        let first = [0, 1].map(|c| state.shift[c] + reach * unit[c]);
        self.constraint = Some(ForceConstraint {
            unit,
            sum: force / area,
            moved: 0.0,
        });
        let result = self.step(operator, normal, first, state);
        self.constraint = None;
        let mut report = result?;
        let reached = along(unit, report.force);
        let miss = (reached - force).abs();
        if miss.is_nan() || miss > tolerance {
            return Err(TangentialError::ForceNotReached {
                target: force,
                reached,
                trials: 1,
            });
        }
        self.keep_force_stiffness(reached - start_force, along(unit, report.shift) - origin);
        report.trials = 1;
        Ok(report)
    }

    /// The force-controlled step by trials: displacement-controlled steps from the same
    /// starting state, bracketed along the secant and closed by the Illinois rule.
    pub(super) fn step_to_force_by_trials(
        &mut self,
        operator: &mut dyn ShearCompliance,
        normal: &ContactState,
        (unit, force): ([f64; 2], f64),
        state: &mut TangentialState,
        tolerance: f64,
    ) -> Result<TangentialReport, TangentialError> {
        let area = operator.grid().element_area();
        let start_force = along(unit, state.force(area));
        let mut search = Search {
            start: state.clone(),
            history: self.history.clone(),
            unit,
            force,
            origin: along(unit, state.shift),
            total: TangentialReport::default(),
        };
        let first = Trial {
            shift: search.origin,
            excess: start_force - force,
        };
        let stiffness = self
            .force_stiffness
            .unwrap_or_else(|| uncoupled_stiffness(operator, normal));
        let reach = -first.excess / stiffness;
        let (mut last, mut report) = search.trial(self, operator, normal, state, first.shift + reach)?;
        // Bracket: extend along the secant until the excess changes sign.
        let mut retained = first;
        while last.excess.abs() > tolerance && last.excess.signum() == retained.excess.signum() {
            let slope = (last.excess - retained.excess) / (last.shift - retained.shift);
            if search.total.trials >= MAX_TRIALS || slope.is_nan() || slope <= 0.0 {
                return Err(search.not_reached(&last));
            }
            let limit = MAX_REACH_GROWTH * (last.shift - retained.shift).abs();
            let shift = last.shift + (-last.excess / slope).clamp(-limit, limit);
            retained = last;
            (last, report) = search.trial(self, operator, normal, state, shift)?;
        }
        // Illinois: false position between the latest trial and the retained end of the
        // other sign, whose excess is halved each time the new trial falls on the latest's
        // side (so the retained end moves too).
        while last.excess.abs() > tolerance {
            if search.total.trials >= MAX_TRIALS || last.shift == retained.shift {
                return Err(search.not_reached(&last));
            }
            let shift = last.shift - last.excess * (last.shift - retained.shift) / (last.excess - retained.excess);
            let (next, next_report) = search.trial(self, operator, normal, state, shift)?;
            report = next_report;
            if next.excess.signum() == last.excess.signum() {
                retained.excess *= 0.5;
            } else {
                retained = last;
            }
            last = next;
        }
        self.keep_force_stiffness(last.excess - first.excess, last.shift - first.shift);
        let total = search.total;
        report.rounds = total.rounds;
        report.cg_iterations = total.cg_iterations;
        report.transform_pairs = total.transform_pairs;
        report.trials = total.trials;
        Ok(report)
    }

    /// Keeps a force-controlled step's secant stiffness dF/dδ (the force's change over the
    /// shift's), when the shift moved and the secant is a positive number: its successor's
    /// first target.
    fn keep_force_stiffness(&mut self, force_change: f64, shift_change: f64) {
        if shift_change != 0.0 {
            let secant = force_change / shift_change;
            self.force_stiffness = (secant.is_finite() && secant > 0.0).then_some(secant);
        }
    }

    /// Δ²Σg over the contact of `normal` (`area` = Δ²): the largest tangential force the
    /// interface holds under the kinetic law (∞ glued).
    pub fn capacity(&self, normal: &ContactState, area: f64) -> f64 {
        let bounds = (0..normal.contact.len()).filter(|&i| normal.contact[i]);
        area * bounds.map(|i| self.law.bound(normal.pressure[i])).sum::<f64>()
    }
}

/// Δ²Σ 1/K_ii over the contact: the stiffness if its elements did not share their
/// displacements, above the true one; a first trial from it falls short, and the secant
/// through it is the contact's.
fn uncoupled_stiffness(operator: &dyn ShearCompliance, normal: &ContactState) -> f64 {
    let elements = normal.contact.iter().filter(|&&c| c).count().max(1);
    operator.grid().element_area() * elements as f64 / operator.self_compliance()
}

/// The component of `vector` along `unit`.
fn along(unit: [f64; 2], vector: [f64; 2]) -> f64 {
    vector[0] * unit[0] + vector[1] * unit[1]
}

/// The trials of one force-controlled step: each a displacement-controlled step from the
/// same starting state.
struct Search {
    /// The step's starting state.
    start: TangentialState,
    /// The solver's predictor history at the step's start.
    history: Option<([Vec<f64>; 2], [f64; 2])>,
    unit: [f64; 2],
    force: f64,
    /// The starting shift along `unit`.
    origin: f64,
    /// The counters of all trials.
    total: TangentialReport,
}

impl Search {
    /// A step from the starting state to `shift` along the direction (the shift across it
    /// kept).
    fn trial(
        &mut self,
        solver: &mut TangentialSolver,
        operator: &mut dyn ShearCompliance,
        normal: &ContactState,
        state: &mut TangentialState,
        shift: f64,
    ) -> Result<(Trial, TangentialReport), TangentialError> {
        state.clone_from(&self.start);
        solver.history.clone_from(&self.history);
        let target = [0, 1].map(|c| self.start.shift[c] + (shift - self.origin) * self.unit[c]);
        let report = solver.step(operator, normal, target, state)?;
        self.total.rounds += report.rounds;
        self.total.cg_iterations += report.cg_iterations;
        self.total.transform_pairs += report.transform_pairs;
        self.total.trials += 1;
        let excess = along(self.unit, report.force) - self.force;
        Ok((Trial { shift, excess }, report))
    }

    fn not_reached(&self, last: &Trial) -> TangentialError {
        TangentialError::ForceNotReached {
            target: self.force,
            reached: self.force + last.excess,
            trials: self.total.trials,
        }
    }
}

#[cfg(test)]
#[path = "force_tests.rs"]
mod tests;
