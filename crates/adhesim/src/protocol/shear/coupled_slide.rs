//! Rolling and sliding with the coupled operator (`friction.coupling = "full"`): each step
//! of the translation, the approach's too, is a coupled step (docs/physics.md §8.1a and
//! §8.4) on the profile where its axis stands.

use super::edge::NormalSide;
use super::mixity::ModeMixity;
use super::shift::{ShiftStepper, ShiftTarget};
use super::sliding::add_tangential_step;
use super::{contact_split_about, ShearFields};
use crate::elastic::{ElasticOperator, ShearBody};
use crate::geometry::TranslatingContact;
use crate::protocol::translation::stationary_means;
use crate::protocol::{
    NormalSolver, Observer, Phase, ProtocolError, StepRecord, StepView, Translation, TranslationCheckpoint,
    TranslationSummary,
};
use crate::solver::{Complementarity, TangentialSolver};
use std::ops::ControlFlow;

impl Translation {
    /// A roll, slide or translation with friction through the coupled operator: the
    /// normal problem sees the tractions' normal displacement K_zt q and the tangential
    /// problem the pressure's tangential one K_tz p, solved in turn each step until they
    /// agree (the rounds of the shear protocol's coupled step). Friction acts from the
    /// first contact, as in Spence's problem. A slide shifts the indenter's material with
    /// its axis; a roll holds it (free rolling at zero creepage: the tractions the coupling
    /// draws are Bentall & Johnson's dissimilar-body effect, here a rigid indenter on a
    /// compressible body). `phase` is the stroke's.
    ///
    /// The rounds give no state before a step's configuration change: a record's force
    /// before the change is its force at the step's end, and the work-based mean takes the
    /// trapezoid of the end-of-step forces.
    pub(super) fn run_coupled(
        &self,
        operator: &mut dyn ElasticOperator,
        contact: &TranslatingContact,
        solver: &mut NormalSolver,
        (body, friction): (ShearBody, &mut TangentialSolver),
        observer: &mut dyn Observer,
        phase: Phase,
    ) -> Result<TranslationSummary, ProtocolError> {
        if friction.drive_stiffness().is_some() {
            return Err(ProtocolError::InvalidParameter(
                "a compliant drive's rounds (the profile moved to the indenter's shift) are not built around the coupled operator's rounds: use a rigid drive with the coupled operator, or Goodman's approximation with the spring".into(),
            ));
        }
        let grid = *operator.grid();
        let schedule = self.schedule(phase);
        let mut run = TranslationCheckpoint::start(&grid);
        let mut stepper = ShiftStepper::new(&*operator, &run.state, body, ModeMixity::default(), false, true, solver)?;
        let mut fields = ShearFields::new(grid.len());
        let (mut frictional_dissipation, mut complementarity) = (0.0, Complementarity::default());
        let mut previous = run.state.contact.clone();
        let mut heights = vec![0.0; grid.len()];
        for (step, &(stage, depth, offset)) in schedule.iter().enumerate() {
            contact.fill_heights(&grid, offset, &mut heights);
            previous.copy_from_slice(&run.state.contact);
            let carried = if phase == Phase::Slide { offset } else { 0.0 };
            let outcome = stepper.step(
                NormalSide {
                    operator: &mut *operator,
                    heights: &heights,
                    depth,
                    solver: &mut *solver,
                    state: &mut run.state,
                },
                friction,
                ShiftTarget::Shift([carried, 0.0]),
                step,
                0.0,
            )?;
            run.cumulative_dissipated_energy += outcome.normal.dissipated_energy;
            let mut record = StepRecord::measure(
                step,
                stage,
                depth,
                offset,
                outcome.normal,
                &run.state,
                &grid,
                run.cumulative_dissipated_energy,
                self.jump_force_threshold,
            );
            let boundary = if stage == Phase::Approach {
                0.0
            } else {
                contact.tangential_force(&grid, &run.state.pressure, offset)
            };
            (record.force_tangential, record.force_tangential_before_change) = (boundary, boundary);
            let totals = (&mut frictional_dissipation, &mut complementarity);
            add_tangential_step(&outcome.tangential, &mut record, totals);
            (_, record.area_front, record.area_rear) = contact_split_about(&grid, &run.state.contact, 0.0, offset);
            self.count_step(&mut run, &record, offset);
            stepper.room.window.scatter(&stepper.room.state, &mut fields);
            let view = StepView {
                record: &record,
                state: &run.state,
                previous_contact: &previous,
                shear: (stage != Phase::Approach).then_some(&fields),
            };
            if let ControlFlow::Break(()) = observer.on_step(view) {
                stepper.finish(solver);
                return Err(ProtocolError::Interrupted(step));
            }
            run.steps_done = step + 1;
        }
        stepper.finish(solver);
        let mut summary = run.summary;
        stationary_means(&mut summary, &run.stationary, |record| record.offset);
        summary.frictional_dissipation = frictional_dissipation;
        summary.complementarity = complementarity;
        Ok(summary)
    }
}
