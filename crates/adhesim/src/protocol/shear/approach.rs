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
            return Ok(None);
        }
        let grid = *operator.grid();
        let inclined = self.incline != 0.0;
        let mut stepper = ShiftStepper::new(&grid, state, body, self.mode_mixity, inclined, true, solver)?;
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
        Ok(Some(stepper))
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
                Phase::Approach,
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

    /// The depth of approach step `step` (from 0): even steps from the first contact to
    /// `depth`, which the last one meets exactly.
    pub(super) fn approach_depth(&self, step: usize) -> f64 {
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
                Phase::Approach,
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
