//! Rolling and sliding with friction at the interface: the translation protocol with a
//! tangential step on the contact's window after each normal step (docs/physics.md §8.4).

use super::edge::add_normal;
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
use crate::solver::{Complementarity, ContactState, StepReport, TangentialSolver};
use std::ops::ControlFlow;

/// Elements of margin around the contact in the window of a translation: room to travel
/// before the window moves with the contact.
const TRAVEL_MARGIN: usize = 8;
/// Rounds of a step under a compliant drive (a normal step with the profile where the
/// indenter is, then a tangential step to the drive) before the indenter's shift must have
/// settled.
const MAX_DRIVE_ROUNDS: usize = 60;
/// The rounds end when the indenter's shift moves by no more than this share of an element.
const DRIVE_TOLERANCE: f64 = 1e-6;

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
    /// The indenter's shift at the end of the last step (under a compliant drive it lags
    /// the drive's position).
    indenter: f64,
}

impl Interface<'_> {
    /// Completes a step's record: during the approach, every contact element sticks;
    /// during the stroke, the tangential step to the indenter's shift at `offset` (or,
    /// under a compliant drive, to the drive at `drive`), its force added to the boundary
    /// force, its work to the step's counters. Returns the indenter's shift after the step.
    fn complete(
        &mut self,
        (step, stage, offset, drive): (usize, Phase, f64, Option<f64>),
        state: &ContactState,
        record: &mut StepRecord,
    ) -> Result<f64, ProtocolError> {
        let (count, front, rear) = contact_split_about(&self.grid, &state.contact, 0.0, offset);
        (record.area_front, record.area_rear) = (front, rear);
        if stage == Phase::Approach {
            record.stick_elements = count;
            return Ok(offset);
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
        // The spring pulls against the tractions and the boundary's force alike: the
        // solver's drive stands at X − F_B/k so that k(X − δ) = F_B + Δ²Σq_x.
        let shift = match (drive, self.friction.drive_stiffness()) {
            (Some(drive), Some(stiffness)) => drive - record.force_tangential / stiffness,
            _ if self.slides => offset,
            _ => 0.0,
        };
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
        Ok(report.shift[0])
    }

    /// A stroke step under a compliant drive at `drive`: rounds of a normal step with the
    /// profile's axis at the indenter's shift and a tangential step to the drive, until the
    /// shift the tangential step returns is the one the profile stood at (a fixed point: the
    /// contact goes where the indenter goes, the jump of a slip event included, in as many
    /// quasi-static moves as rounds). The record is the last round's with every round's
    /// counters, its configuration change counted from the step's start.
    fn driven_step(
        &mut self,
        (protocol, operator, contact, solver): (
            &Translation,
            &mut (dyn ElasticOperator + '_),
            &TranslatingContact,
            &mut NormalSolver,
        ),
        run: &mut TranslationCheckpoint,
        (step, stage, depth, drive): (usize, Phase, f64, f64),
        heights: &mut [f64],
    ) -> Result<StepRecord, ProtocolError> {
        let grid = *operator.grid();
        let element = grid.dx().max(grid.dy());
        // Every round's counters, the step's start as the configuration before its change.
        let mut spent = StepReport::default();
        let mut change = f64::INFINITY;
        let mut drive_history = None;
        for round in 0..MAX_DRIVE_ROUNDS {
            let offset = self.indenter;
            contact.fill_heights(&grid, offset, heights);
            let mut record =
                protocol.solve_step(operator, contact, solver, run, (step, stage, depth, offset), heights)?;
            self.indenter = self.complete((step, stage, offset, Some(drive)), &run.state, &mut record)?;
            change = (self.indenter - offset).abs() / element;
            if round == 0 {
                drive_history = self.friction.forget_predictor();
            }
            add_normal(&mut spent, record.report);
            if change <= DRIVE_TOLERANCE {
                match &drive_history {
                    Some((before, increment)) => self.friction.remember_step(before, *increment),
                    None => drop(self.friction.forget_predictor()),
                }
                record.report = spent;
                let report = &record.report;
                record.drive_offset = drive;
                record.jumped = (report.attached + report.detached) > 0
                    && (report.force - report.force_before_change).abs() > protocol.jump_force_threshold;
                return Ok(record);
            }
        }
        Err(ProtocolError::DriveNotSettled {
            step,
            drive,
            rounds: MAX_DRIVE_ROUNDS,
            change,
        })
    }
}

/// Friction at a translation's interface: the body's tangential constants, the interface's
/// solver, and whether the normal and tangential problems are coupled.
pub struct TranslationFriction<'a> {
    /// The tangential operator's body: a half-space, or the layer whose normal operator the
    /// run's is.
    pub body: ShearBody,
    /// The interface law's solver.
    pub solver: &'a mut TangentialSolver,
    /// The coupled operator (`friction.coupling = "full"`, docs/physics.md §8.1a): each
    /// step solves the two problems in turn. False: Goodman's approximation.
    pub coupled: bool,
}

impl Translation {
    /// Rolling or sliding with friction at the interface ([`TangentialSolver`]): after each
    /// normal step of the stroke, a tangential step on the contact's window. A slide (and a
    /// translation) shifts the indenter's material with its axis; a roll does not (free
    /// rolling: the surfaces do not slip where they touch). New contact sticks where it
    /// touches. The step's tangential force is the boundary force of the normal problem
    /// plus the interface's Δ²Σq_x; the energy balance counts friction's dissipation.
    /// Offers no checkpoints. Without `friction.coupled` the normal problem does not see
    /// the shear (Goodman's approximation); with it each step, the approach's too, is a
    /// coupled step (docs/physics.md §8.4a).
    pub fn run_with_friction(
        &self,
        operator: &mut dyn ElasticOperator,
        contact: &TranslatingContact,
        solver: &mut NormalSolver,
        friction: TranslationFriction<'_>,
        observer: &mut dyn Observer,
    ) -> Result<TranslationSummary, ProtocolError> {
        self.check()?;
        let grid = *operator.grid();
        solver.reset();
        let phase = match contact.kinematics() {
            Kinematics::Roll => Phase::Roll,
            _ => Phase::Slide,
        };
        let TranslationFriction {
            body,
            solver: friction,
            coupled,
        } = friction;
        if coupled {
            return self.run_coupled(operator, contact, solver, (body, friction), observer, phase);
        }
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
            indenter: 0.0,
        };
        let compliant = interface.friction.drive_stiffness().is_some();
        if compliant && phase == Phase::Roll {
            return Err(ProtocolError::InvalidParameter(
                "a compliant drive pulls a slide or a translation; a rolling indenter does not carry its surface along, so a roll takes a rigid drive".into(),
            ));
        }
        let mut previous = run.state.contact.clone();
        let mut heights = vec![0.0; grid.len()];
        for (step, &(stage, depth, offset)) in schedule.iter().enumerate() {
            previous.copy_from_slice(&run.state.contact);
            let record = if compliant && stage != Phase::Approach {
                let normal = (self, &mut *operator, contact, &mut *solver);
                let record = interface.driven_step(normal, &mut run, (step, stage, depth, offset), &mut heights)?;
                self.count_step(&mut run, &record, offset);
                record
            } else {
                contact.fill_heights(&grid, offset, &mut heights);
                self.run_step(
                    operator,
                    contact,
                    solver,
                    &mut run,
                    (step, stage, depth, offset),
                    &heights,
                    &mut |state, record| {
                        interface
                            .complete((step, stage, offset, None), state, record)
                            .map(|_| ())
                    },
                )?
            };
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
        let position = |record: &StepRecord| if compliant { record.drive_offset } else { record.offset };
        stationary_means(&mut summary, &run.stationary, position);
        summary.frictional_dissipation = interface.frictional_dissipation;
        summary.complementarity = interface.complementarity;
        Ok(summary)
    }
}
