//! Rolling and sliding with friction at the interface: the translation protocol with a
//! tangential step on the contact's window after each normal step (docs/physics.md §8.4).

use super::window::TangentialRoom;
use super::{contact_split_about, worst, ShearFields};
use crate::elastic::{ElasticOperator, ShearBody};
use crate::geometry::{Kinematics, TranslatingContact};
use crate::grid::Grid;
use crate::protocol::translation::stationary_means;
use crate::protocol::{
    NormalSolver, Observer, Phase, ProtocolError, SolverCheckpoint, StepRecord, StepView, Translation,
    TranslationCheckpoint, TranslationSummary,
};
use crate::solver::{Complementarity, ContactState, TangentialSolver};
use std::ops::ControlFlow;

/// Elements of margin around the contact in the window of a translation: room to travel
/// before the window moves with the contact.
const TRAVEL_MARGIN: usize = 8;

/// The tangential side of a translation with friction: the room, the solver and what the
/// run has summed.
struct Interface<'a> {
    grid: Grid,
    body: ShearBody,
    friction: &'a mut TangentialSolver,
    room: Option<TangentialRoom>,
    window_state: ContactState,
    fields: ShearFields,
    /// The indenter's material moves with the axis (slide, translate) or not (roll).
    slides: bool,
    frictional_dissipation: f64,
    complementarity: Complementarity,
}

impl Interface<'_> {
    /// Completes a step's record: during the approach, every contact element sticks;
    /// during the stroke, the tangential step to the indenter's shift at `offset`, its
    /// force added to the boundary force, its work to the step's counters.
    fn complete(
        &mut self,
        (step, stage, offset): (usize, Phase, f64),
        state: &ContactState,
        record: &mut StepRecord,
    ) -> Result<(), ProtocolError> {
        let (count, front, rear) = contact_split_about(&self.grid, &state.contact, 0.0, offset);
        (record.area_front, record.area_rear) = (front, rear);
        if stage == Phase::Approach {
            record.stick_elements = count;
            return Ok(());
        }
        let moved = match &mut self.room {
            Some(room) => room.follow(&state.contact)?,
            None => {
                self.room = Some(TangentialRoom::new(
                    &self.grid,
                    &state.contact,
                    TRAVEL_MARGIN,
                    self.body,
                )?);
                0
            }
        };
        let room = self.room.as_mut().expect("the room was just made");
        if self.window_state.contact.len() != room.window.grid.len() {
            self.window_state = ContactState::new(&room.window.grid);
        }
        room.window.gather_into(state, &mut self.window_state);
        let shift = if self.slides { offset } else { 0.0 };
        let report = self
            .friction
            .step(&mut room.operator, &self.window_state, [shift, 0.0], &mut room.state)
            .map_err(|source| ProtocolError::Tangential { step, shift, source })?;
        room.window.scatter(&room.state, &mut self.fields);
        record.force_tangential += report.force[0];
        record.force_tangential_before_change += report.force[0];
        (record.stick_elements, record.slip_elements) = (report.stick_elements, report.slip_elements);
        record.report.cg_iterations += report.cg_iterations;
        record.report.operator_applications += report.transform_pairs + moved;
        self.frictional_dissipation += report.dissipated_energy;
        record.cumulative_frictional_dissipation = self.frictional_dissipation;
        worst(&mut self.complementarity, report.complementarity);
        Ok(())
    }
}

impl Translation {
    /// Rolling or sliding with friction at the interface ([`TangentialSolver`]): after each normal step of the stroke, a tangential step on the contact's
    /// window. A slide (and a translation) shifts the indenter's material with its axis; a
    /// roll does not (free rolling: the surfaces do not slip where they touch). New contact
    /// sticks where it touches. The step's tangential force is the boundary force of the
    /// normal problem plus the interface's Δ²Σq_x; the energy balance counts friction's
    /// dissipation. Offers no checkpoints. The normal problem does not see the shear
    /// (Goodman's approximation). The tangential operator is `body`'s: a half-space, or the
    /// layer whose normal operator `operator` is.
    pub fn run_with_friction(
        &self,
        operator: &mut dyn ElasticOperator,
        contact: &TranslatingContact,
        solver: &mut NormalSolver,
        (body, friction): (ShearBody, &mut TangentialSolver),
        observer: &mut dyn Observer,
    ) -> Result<TranslationSummary, ProtocolError> {
        self.check()?;
        let grid = *operator.grid();
        solver.reset();
        let phase = match contact.kinematics() {
            Kinematics::Roll => Phase::Roll,
            _ => Phase::Slide,
        };
        let schedule = self.schedule(phase);
        let mut run = TranslationCheckpoint {
            steps_done: 0,
            state: ContactState::new(&grid),
            cumulative_dissipated_energy: 0.0,
            summary: TranslationSummary::default(),
            stationary: Vec::new(),
            solver: SolverCheckpoint::Stateless,
        };
        let mut interface = Interface {
            grid,
            body,
            friction,
            room: None,
            window_state: ContactState::new(&grid),
            fields: ShearFields::new(grid.len()),
            slides: phase != Phase::Roll,
            frictional_dissipation: 0.0,
            complementarity: Complementarity::default(),
        };
        let mut previous = run.state.contact.clone();
        let mut heights = vec![0.0; grid.len()];
        for (step, &(stage, depth, offset)) in schedule.iter().enumerate() {
            contact.fill_heights(&grid, offset, &mut heights);
            previous.copy_from_slice(&run.state.contact);
            let record = self.run_step(
                operator,
                contact,
                solver,
                &mut run,
                (step, stage, depth, offset),
                &heights,
                &mut |state, record| interface.complete((step, stage, offset), state, record),
            )?;
            let view = StepView {
                record: &record,
                state: &run.state,
                previous_contact: &previous,
                shear: (stage != Phase::Approach).then_some(&interface.fields),
            };
            if let ControlFlow::Break(()) = observer.on_step(view) {
                return Err(ProtocolError::Interrupted(step));
            }
            run.steps_done = step + 1;
        }
        let mut summary = run.summary;
        stationary_means(&mut summary, &run.stationary);
        summary.frictional_dissipation = interface.frictional_dissipation;
        summary.complementarity = interface.complementarity;
        Ok(summary)
    }
}
