//! A roll, slide or translate whose adhesive edge the shear weakens (`friction.mode_mixity`
//! with the translation protocols, docs/physics.md §8.5): each stroke step alternates
//! tangential solves and normal steps on the moving profile until the contact settles.

use super::contact_split_about;
use super::edge::{add_normal, add_tangential, Weakening};
use super::sliding::Interface;
use crate::elastic::ElasticOperator;
use crate::geometry::TranslatingContact;
use crate::protocol::{NormalSolver, Phase, ProtocolError, StepRecord, Translation, TranslationCheckpoint};
use crate::solver::{AdhesiveSolver, TangentialReport, TangentialState};

/// Rounds of tangential solve and weakened normal step per stroke step before giving up.
const MAX_WEAKENED_ROUNDS: usize = 200;

impl Interface<'_> {
    /// A stroke step at `offset` with the edge weakened by its shear. σ_c,eff starts each
    /// step from the unweakened σ_c lowered by the tractions the contact carries into it
    /// (an element keeps its weakening while it holds its traction), then the normal step
    /// on the moved profile. Rounds follow: the tangential step to the shift from the
    /// step's starting tangential state, σ_c,eff lowered by its tractions (never raised
    /// within the step), and, where that lowered it, the normal step again at the same
    /// profile, until a round lowers nothing or leaves the contact as it found it (then
    /// the pressure, and with it the tangential solution, is the round's). With a mode
    /// mixity of 0 nothing is lowered and the step is the unweakened one.
    pub(super) fn weakened_step(
        &mut self,
        (protocol, operator, contact, solver): (
            &Translation,
            &mut (dyn ElasticOperator + '_),
            &TranslatingContact,
            &mut NormalSolver,
        ),
        weakening: &mut Weakening,
        run: &mut TranslationCheckpoint,
        (step, stage, depth, offset): (usize, Phase, f64, f64),
        heights: &[f64],
    ) -> Result<StepRecord, ProtocolError> {
        weakening.begin();
        if let Some(room) = &self.room {
            weakening.weaken(&room.window, &self.window_state.contact, &room.state);
        }
        weakening.apply(adhesive(solver)?);
        let first = protocol.solve_step(operator, contact, solver, run, (step, stage, depth, offset), heights)?;
        let mut normal = first.report;
        let mut tangential = TangentialReport::default();
        let shift = if self.slides { offset } else { 0.0 };
        let mut start: Option<TangentialState> = None;
        let mut before = run.state.contact.clone();
        for _ in 0..MAX_WEAKENED_ROUNDS {
            if let (Some(start), Some(room)) = (&start, &mut self.room) {
                room.state.clone_from(start);
            }
            let moved = self.room_on(&run.state)?;
            tangential.transform_pairs += moved;
            if moved > 0 || start.is_none() {
                // The step's starting fields, in the layout of the room's window.
                start = self.room.as_ref().map(|room| room.state.clone());
            }
            let report = self.tangential_step(step, shift)?;
            add_tangential(&mut tangential, report);
            let room = self.room.as_ref().expect("room_on made the room");
            weakening.weaken(&room.window, &self.window_state.contact, &room.state);
            let settled = !weakening.apply(adhesive(solver)?) || {
                before.copy_from_slice(&run.state.contact);
                let report = solver
                    .step(operator, heights, depth, &mut run.state)
                    .map_err(|source| ProtocolError::Solve { step, depth, source })?;
                run.cumulative_dissipated_energy += report.dissipated_energy;
                add_normal(&mut normal, report);
                run.state.contact == before
            };
            if settled {
                let grid = self.grid;
                let mut record = StepRecord::measure(
                    step,
                    stage,
                    depth,
                    offset,
                    normal,
                    &run.state,
                    &grid,
                    run.cumulative_dissipated_energy,
                    protocol.jump_force_threshold,
                );
                record.force_tangential = contact.tangential_force(&grid, &run.state.pressure, offset);
                record.force_tangential_before_change = first.force_tangential_before_change;
                (_, record.area_front, record.area_rear) = contact_split_about(&grid, &run.state.contact, 0.0, offset);
                let room = self.room.as_ref().expect("room_on made the room");
                room.window.scatter(&room.state, &mut self.fields);
                self.account(&tangential, 0, &mut record);
                return Ok(record);
            }
        }
        Err(ProtocolError::DetachmentNotSettled {
            step,
            shift: offset,
            rounds: MAX_WEAKENED_ROUNDS,
        })
    }
}

/// The JKR-type solver a weakened edge needs.
pub(super) fn adhesive(solver: &mut NormalSolver) -> Result<&mut AdhesiveSolver, ProtocolError> {
    solver.as_adhesive_mut().ok_or_else(|| {
        ProtocolError::InvalidParameter("a shear-weakened edge needs the JKR-type adhesive solver".into())
    })
}
