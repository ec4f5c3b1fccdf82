//! Rolling and sliding with friction at the interface: the translation protocol with a
//! tangential step on the contact's window after each normal step (docs/physics.md §8.4).

use super::edge::{add_normal, Weakening};
use super::mixity::ModeMixity;
use super::weakened_slide::adhesive;
use super::window::TangentialRoom;
use super::{contact_split_about, worst, ShearFields};
use crate::elastic::{Backend, ElasticOperator, ShearBody};
use crate::geometry::{Kinematics, TranslatingContact};
use crate::grid::Grid;
use crate::problem::Problem;
use crate::protocol::translation::stationary_means;
use crate::protocol::{
    NormalSolver, Observer, Phase, ProtocolError, StepRecord, StepView, Translation, TranslationCheckpoint,
    TranslationSummary,
};
use crate::solver::{Complementarity, ContactState, StepReport, TangentialReport, TangentialSolver};
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
pub(super) struct Interface<'a> {
    pub(super) grid: Grid,
    pub(super) body: ShearBody,
    /// The run's normal operator's backend, which builds the room's.
    pub(super) backend: Backend,
    pub(super) friction: &'a mut TangentialSolver,
    pub(super) room: Option<TangentialRoom>,
    pub(super) window_state: ContactState,
    pub(super) fields: ShearFields,
    /// The indenter's material moves with the axis (slide, translate) or not (roll).
    pub(super) slides: bool,
    pub(super) frictional_dissipation: f64,
    pub(super) complementarity: Complementarity,
    /// The indenter's shift at the end of the last step (under a compliant drive it lags
    /// the drive's position).
    pub(super) indenter: f64,
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
        let moved = self.room_on(state)?;
        // The spring pulls against the tractions and the boundary's force alike: the
        // solver's drive stands at X − F_B/k so that k(X − δ) = F_B + Δ²Σq_x.
        let shift = match (drive, self.friction.drive_stiffness()) {
            (Some(drive), Some(stiffness)) => drive - record.force_tangential / stiffness,
            _ if self.slides => offset,
            _ => 0.0,
        };
        let report = self.tangential_step(step, shift)?;
        let room = self.room.as_ref().expect("room_on made the room");
        room.window.scatter(&room.state, &mut self.fields);
        self.account(&report, moved, record);
        Ok(report.shift[0])
    }

    /// The tangential step of step `step` to `shift` on the room, the normal state
    /// gathered on its window by [`room_on`](Self::room_on).
    pub(super) fn tangential_step(&mut self, step: usize, shift: f64) -> Result<TangentialReport, ProtocolError> {
        let room = self.room.as_mut().expect("room_on made the room");
        self.friction
            .step(
                room.operator.as_mut(),
                &self.window_state,
                [shift, 0.0],
                &mut room.state,
            )
            .map_err(|source| ProtocolError::Tangential { step, shift, source })
    }

    /// Puts the room on the contact of `state` (made at the stroke's first step, moved onto
    /// the contact when it has left the window) and gathers the normal state on its
    /// window; returns the FFT pairs a move spent.
    pub(super) fn room_on(&mut self, state: &ContactState) -> Result<u64, ProtocolError> {
        let moved = match &mut self.room {
            Some(room) => room.follow(&state.contact)?,
            None => {
                self.room = Some(TangentialRoom::new(
                    &self.grid,
                    &state.contact,
                    TRAVEL_MARGIN,
                    (self.body, self.backend),
                )?);
                0
            }
        };
        let room = self.room.as_mut().expect("the room was just made");
        if self.window_state.contact.len() != room.window.grid.len() {
            self.window_state = ContactState::new(&room.window.grid);
        }
        room.window.gather_into(state, &mut self.window_state);
        Ok(moved)
    }

    /// A step's tangential solve (`report`, and `moved`, the FFT pairs of moving the room)
    /// into its record and the run's totals ([`add_tangential_step`]).
    pub(super) fn account(&mut self, report: &TangentialReport, moved: u64, record: &mut StepRecord) {
        record.report.operator_applications += moved;
        let totals = (&mut self.frictional_dissipation, &mut self.complementarity);
        add_tangential_step(report, record, totals);
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
    /// The share of an element's shear energy that counts toward its detachment, by the
    /// side of the edge (docs/physics.md §8.5; the default, 0: the shear does not weaken
    /// the edge). Above 0 it needs the JKR-type adhesive solver, a rigid drive and
    /// Goodman's approximation.
    pub mode_mixity: ModeMixity,
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
    /// coupled step (docs/physics.md §8.4a). A `friction.mode_mixity` above 0 weakens the
    /// adhesive edge by the shear it carries, each stroke step in rounds
    /// (`Interface::weakened_step`).
    pub fn run_with_friction(
        &self,
        problem: &mut Problem,
        solver: &mut NormalSolver,
        friction: TranslationFriction<'_>,
        observer: &mut dyn Observer,
    ) -> Result<TranslationSummary, ProtocolError> {
        self.check()?;
        let (operator, contact) = problem.translating_parts()?;
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
            mode_mixity,
        } = friction;
        let compliant = friction.drive_stiffness().is_some();
        if mode_mixity.weakens() && (coupled || compliant) {
            return Err(ProtocolError::InvalidParameter(format!(
                "a shear-weakened edge ({mode_mixity:?}) under a roll, slide or translate takes Goodman's approximation and a rigid drive: its rounds are not built around the coupled operator's or a spring's"
            )));
        }
        if coupled {
            return self.run_coupled(operator, contact, solver, (body, friction), observer, phase);
        }
        let mut weakening = match mode_mixity.weakens() {
            true => Some(Weakening::new(adhesive(solver)?, body.material, mode_mixity)),
            false => None,
        };
        let schedule = self.schedule(phase);
        let mut run = TranslationCheckpoint::start(&grid);
        let mut interface = Interface {
            grid,
            body,
            backend: operator.backend(),
            friction,
            room: None,
            window_state: ContactState::new(&grid),
            fields: ShearFields::new(grid.len()),
            slides: phase != Phase::Roll,
            frictional_dissipation: 0.0,
            complementarity: Complementarity::default(),
            indenter: 0.0,
        };
        if compliant && phase == Phase::Roll {
            return Err(ProtocolError::InvalidParameter(
                "a compliant drive pulls a slide or a translation; a rolling indenter does not carry its surface along, so a roll takes a rigid drive".into(),
            ));
        }
        let mut previous = run.state.contact.clone();
        let mut heights = vec![0.0; grid.len()];
        for (step, &(stage, depth, offset)) in schedule.iter().enumerate() {
            previous.copy_from_slice(&run.state.contact);
            let weakened = weakening.as_mut().filter(|_| stage != Phase::Approach);
            let record = if compliant && stage != Phase::Approach {
                let normal = (self, &mut *operator, contact, &mut *solver);
                let record = interface.driven_step(normal, &mut run, (step, stage, depth, offset), &mut heights)?;
                self.count_step(&mut run, &record, offset);
                record
            } else if let Some(weakening) = weakened {
                contact.fill_heights(&grid, offset, &mut heights);
                let normal = (self, &mut *operator, contact, &mut *solver);
                let place = (step, stage, depth, offset);
                let record = interface.weakened_step(normal, weakening, &mut run, place, &heights)?;
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
                restore_edge(weakening.as_ref(), solver)?;
                return Err(ProtocolError::Interrupted(step));
            }
            run.steps_done = step + 1;
        }
        restore_edge(weakening.as_ref(), solver)?;
        let mut summary = run.summary;
        let position = |record: &StepRecord| if compliant { record.drive_offset } else { record.offset };
        stationary_means(&mut summary, &run.stationary, position);
        summary.frictional_dissipation = interface.frictional_dissipation;
        summary.complementarity = interface.complementarity;
        Ok(summary)
    }
}

/// A translation step's tangential solve into its record and the run's totals: its force
/// added to the boundary force the record holds (before and after the configuration
/// change), its stick and slip counts and counters, friction's dissipation so far and the
/// worst optimality conditions.
pub(super) fn add_tangential_step(
    report: &TangentialReport,
    record: &mut StepRecord,
    (frictional_dissipation, complementarity): (&mut f64, &mut Complementarity),
) {
    record.force_tangential += report.force[0];
    record.force_tangential_before_change += report.force[0];
    (record.stick_elements, record.slip_elements) = (report.stick_elements, report.slip_elements);
    record.report.cg_iterations += report.cg_iterations;
    record.report.operator_applications += report.transform_pairs;
    *frictional_dissipation += report.dissipated_energy;
    record.cumulative_frictional_dissipation = *frictional_dissipation;
    worst(complementarity, report.complementarity);
}

/// Gives the solver its unweakened σ_c back after a run that weakened its edge.
fn restore_edge(weakening: Option<&Weakening>, solver: &mut NormalSolver) -> Result<(), ProtocolError> {
    if let Some(weakening) = weakening {
        weakening.restore(adhesive(solver)?);
    }
    Ok(())
}
