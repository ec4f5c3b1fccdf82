//! The approach of the shear protocol: displacement steps to the held depth, with the
//! normal problem alone (Goodman) or with friction from first contact (the coupled
//! operator).

use super::edge::NormalSide;
use super::shift::{ShiftStepper, ShiftTarget};
use super::{add_normal_counters, add_shift_counters, contact_split, Shear, ShearSummary};
use crate::elastic::{ElasticOperator, ShearBody};
use crate::protocol::{NormalSolver, Observer, Phase, ProtocolError};
use crate::solver::{ContactState, TangentialSolver};

impl Shear {
    /// The approach of a run: Goodman's, or with the coupled operator the coupled one,
    /// which returns the shift stepper it made (the shift goes on with its room).
    pub(super) fn approach_either(
        &self,
        normal: NormalSide<'_>,
        (body, friction): (ShearBody, &mut TangentialSolver),
        previous: &mut Vec<bool>,
        summary: &mut ShearSummary,
        observer: &mut dyn Observer,
    ) -> Result<Option<ShiftStepper>, ProtocolError> {
        let NormalSide {
            operator,
            heights,
            depth,
            solver,
            state,
        } = normal;
        if !self.coupled {
            self.approach(operator, heights, solver, (state, previous), summary, observer)?;
            return self.contact_held(state).map(|_| None);
        }
        let inclined = self.incline != 0.0;
        let mut stepper = ShiftStepper::new(&*operator, state, body, self.mode_mixity, inclined, true, solver)?;
        self.approach_coupled(
            NormalSide {
                operator,
                heights,
                depth,
                solver,
                state,
            },
            (&mut stepper, friction),
            previous,
            summary,
            observer,
        )?;
        self.contact_held(state).map(|_| Some(stepper))
    }

    /// The contact left at the end of the approach: a lift after a press may pull it off.
    fn contact_held(&self, state: &ContactState) -> Result<(), ProtocolError> {
        if state.contact_elements() == 0 {
            return Err(ProtocolError::InvalidParameter(format!(
                "no contact is left at depth {} after the lift from press_depth {:?}: the indenter was pulled off before the shift",
                self.depth, self.press_depth
            )));
        }
        Ok(())
    }

    /// The approach to `depth` in `approach_steps` displacement steps; `contact` is the
    /// normal state and the contact set at each step's start.
    pub(super) fn approach(
        &self,
        operator: &mut dyn ElasticOperator,
        heights: &[f64],
        solver: &mut NormalSolver,
        contact: (&mut ContactState, &mut Vec<bool>),
        summary: &mut ShearSummary,
        observer: &mut dyn Observer,
    ) -> Result<(), ProtocolError> {
        let (state, previous) = contact;
        let grid = *operator.grid();
        for step in 0..self.approach_steps {
            let depth = self.approach_depth(step);
            previous.copy_from_slice(&state.contact);
            let report = solver
                .step(operator, heights, depth, state)
                .map_err(|source| ProtocolError::Solve { step, depth, source })?;
            add_normal_counters(summary, &report);
            let mut record = self.record(
                step,
                self.approach_phase(step),
                depth,
                report,
                state,
                &grid,
                summary.dissipated_energy,
            );
            let (stick, front, rear) = contact_split(&grid, &state.contact, self.direction);
            (record.stick_elements, record.area_front, record.area_rear) = (stick, front, rear);
            self.report(summary, &record, (state, previous, None), observer)?;
        }
        Ok(())
    }

    /// The steps of the press and of the lift: the approach's steps shared in proportion
    /// to the distances, at least one each (None without a press).
    fn press_and_lift(&self) -> Option<(f64, usize, usize)> {
        let press = self.press_depth?;
        let (down, up) = (press - self.start_depth, press - self.depth);
        let pressing =
            ((self.approach_steps as f64 * down / (down + up)).round() as usize).clamp(1, self.approach_steps - 1);
        Some((press, pressing, self.approach_steps - pressing))
    }

    /// The phase of approach step `step`: the lift after a press retracts.
    fn approach_phase(&self, step: usize) -> Phase {
        match self.press_and_lift() {
            Some((_, pressing, _)) if step >= pressing => Phase::Retract,
            _ => Phase::Approach,
        }
    }

    /// The depth of approach step `step` (from 0): even steps from the first contact to
    /// `depth`, which the last one meets exactly; with a press, even steps down to it and
    /// then even steps up to `depth`.
    pub(super) fn approach_depth(&self, step: usize) -> f64 {
        if let Some((press, pressing, lifting)) = self.press_and_lift() {
            return if step + 1 == self.approach_steps {
                self.depth
            } else if step + 1 == pressing {
                press
            } else if step < pressing {
                self.start_depth + (step + 1) as f64 * (press - self.start_depth) / pressing as f64
            } else {
                press - (step + 1 - pressing) as f64 * (press - self.depth) / lifting as f64
            };
        }
        let depth_step = (self.depth - self.start_depth) / self.approach_steps as f64;
        if step + 1 == self.approach_steps {
            self.depth
        } else {
            self.start_depth + (step + 1) as f64 * depth_step
        }
    }

    /// The approach to `depth` with the coupled operator: friction acts from the first
    /// contact (Spence's problem: the pressure draws the surface in, the tractions hold
    /// it), each step a coupled step at zero shift. `normal.depth` is not used.
    pub(super) fn approach_coupled(
        &self,
        normal: NormalSide<'_>,
        (stepper, friction): (&mut ShiftStepper, &mut TangentialSolver),
        previous: &mut [bool],
        summary: &mut ShearSummary,
        observer: &mut dyn Observer,
    ) -> Result<(), ProtocolError> {
        let NormalSide {
            operator,
            heights,
            solver,
            state,
            ..
        } = normal;
        let grid = *operator.grid();
        for step in 0..self.approach_steps {
            let depth = self.approach_depth(step);
            previous.copy_from_slice(&state.contact);
            let outcome = stepper.step(
                NormalSide {
                    operator: &mut *operator,
                    heights,
                    depth,
                    solver: &mut *solver,
                    state: &mut *state,
                },
                friction,
                ShiftTarget::Shift([0.0; 2]),
                step,
                0.0,
            )?;
            let (report, mut normal) = (outcome.tangential, outcome.normal);
            add_shift_counters(summary, &mut normal, &report, false);
            let mut record = self.record(
                step,
                self.approach_phase(step),
                depth,
                normal,
                state,
                &grid,
                summary.dissipated_energy,
            );
            self.add_tangential_columns(&mut record, &report, summary, &state.contact, &grid);
            self.report(summary, &record, (state, previous, None), observer)?;
        }
        Ok(())
    }
}
