//! Shear at fixed indentation: indent, then shift the indenter tangentially with friction
//! at the interface (Cattaneo 1938, Mindlin 1949; docs/physics.md §8).

mod approach;
mod coupled;
mod coupled_slide;
mod edge;
mod held_force;
mod mixity;
mod shift;
mod sliding;
mod weakened_slide;
mod window;

pub use edge::{element_energy_ratio, shear_weakened_critical_stress};
pub use mixity::ModeMixity;
pub use sliding::TranslationFriction;
pub use window::ShearFields;

use super::{NormalSolver, Observer, Phase, ProtocolError, StepRecord, StepView};
use crate::elastic::ShearBody;
use crate::grid::Grid;
use crate::problem::Problem;
use crate::solver::{Complementarity, ContactState, StepReport, TangentialReport, TangentialSolver};
use edge::NormalSide;
use shift::{ShiftStepper, ShiftTarget};
use std::ops::ControlFlow;

/// Indent to `depth` in `approach_steps` displacement steps, then shift the indenter by
/// `distance` along the in-plane angle `direction` in `steps` quasi-static steps at fixed
/// depth (and back to the start in as many more with `return_stroke`).
///
/// The shift is a small rigid-body displacement, as in Cattaneo–Mindlin: the profile stays
/// where it is, and with Goodman's approximation the normal problem does not change during
/// the shift, so the contact set and pressure are those at the end of the approach and
/// only the tangential problem is solved per shift step. With a `mode_mixity` m > 0 the
/// shear weakens the adhesive edge (docs/physics.md §8.5): each shift step then alternates
/// tangential solves and normal steps at the held depth until the contact set settles.
/// With the coupled operator (`coupled`, docs/physics.md §8.1a) friction acts from first
/// contact and every step, of the approach too, solves the two problems in turn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shear {
    /// Depth of first contact (the approach starts there).
    pub start_depth: f64,
    /// Indentation held during the shift.
    pub depth: f64,
    /// A depth the approach presses to before it lifts the indenter to `depth`, as the
    /// paper's sliding experiments do (Sect. 6); `depth` may then lie at or above the first
    /// contact, the contact held by adhesion. None: the approach goes straight to `depth`.
    pub press_depth: Option<f64>,
    /// Steps of the approach to `depth` (the press and the lift together).
    pub approach_steps: usize,
    /// Shift of the indenter (length units).
    pub distance: f64,
    /// Steps of the shift.
    pub steps: usize,
    /// Direction of the shift in the plane, radians from +x.
    pub direction: f64,
    /// Shift back to the start after the forward stroke (and the cycles).
    pub return_stroke: bool,
    /// Fretting cycles after the forward stroke: each goes from +`distance` to −`distance`
    /// and back in 4·`steps` steps (Mindlin & Deresiewicz 1953).
    pub cycles: usize,
    /// A step is a jump when the normal force changes by more than this at fixed depth.
    pub jump_force_threshold: f64,
    /// Angle of the indenter's path to the surface, radians: each step moves it
    /// `tan(incline)` into the body per unit of shift (out of it below 0; 0 keeps the depth).
    pub incline: f64,
    /// Share m ∈ [0, 1] of an element's shear energy that counts toward its detachment
    /// (0: the edge does not feel the shear; 1: Savkoor–Briggs' brittle criterion), by the
    /// side of the edge the element is on. Above 0 it needs the JKR-type adhesive solver.
    pub mode_mixity: ModeMixity,
    /// Force control: the tangential force along `direction` is imposed, and `distance` is
    /// not used. None: the shift is imposed.
    pub force_control: Option<TangentialForce>,
    /// The coupled operator (`friction.coupling = "full"`; ν < 1/2 on a half-space, any ν on
    /// a layer): a shear traction moves
    /// the surface normally and a pressure moves it tangentially, so the approach already
    /// meets friction (Spence's problem) and every step solves both problems in turn.
    /// False: Goodman's approximation.
    pub coupled: bool,
    /// Normal-force control: the shift holds the normal force of the end of the approach,
    /// each step finding its depth, instead of the depth (Savkoor & Briggs' experiments at
    /// constant load). It changes what a weakened edge does; a held normal problem keeps
    /// its force anyway; with the coupled operator each trial depth runs the coupled
    /// rounds; refused with an incline.
    pub hold_normal_force: bool,
}

/// The imposed tangential force of a force-controlled shear: the forward stroke ramps it
/// from 0 to this amplitude, the cycles go between ± it, the return brings it back to 0
/// (the force-controlled loading of Cattaneo 1938, Mindlin 1949 and Mindlin & Deresiewicz
/// 1953).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TangentialForce {
    /// In force units.
    Absolute(f64),
    /// As a share of what the interface holds at the end of the approach, Δ²Σg over the
    /// contact (μP for Coulomb, τ0·A for a shear strength): Q/μP of Cattaneo–Mindlin.
    OfCapacity(f64),
}

/// The part of the shift path a step belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Stroke {
    Forward,
    /// The fretting cycle of this number (from 1).
    Cycle(usize),
    Return,
}

/// Totals of a shear run.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ShearSummary {
    /// Steps done (approach and shift).
    pub steps: usize,
    /// Normal fixed-set solves.
    pub solves: usize,
    /// CG iterations, normal and tangential.
    pub cg_iterations: usize,
    /// FFT pairs, normal and tangential.
    pub operator_applications: u64,
    /// FFT pairs of the tangential solves alone.
    pub tangential_transform_pairs: u64,
    /// FFT pairs of the adhesive CG on contact windows.
    #[cfg_attr(feature = "serde", serde(default))]
    pub window_applications: u64,
    /// The CG preconditioner's applications (FFT pairs of the solved grid's own size; not
    /// in `operator_applications`).
    #[cfg_attr(feature = "serde", serde(default))]
    pub preconditioner_applications: u64,
    /// Active-set rounds of the tangential solves.
    pub tangential_rounds: usize,
    /// Largest tangential force along the shift during the forward stroke (the static
    /// friction force when gross slip follows).
    pub peak_tangential_force: f64,
    /// Tangential force at the end of the forward stroke.
    pub final_tangential_force: f64,
    /// Normal force at the end of the forward stroke (the whole shift's when the normal
    /// problem is held: no weakened edge, no incline).
    pub normal_force: f64,
    /// Contact area at the end of the forward stroke.
    pub area: f64,
    /// Energy dissipated by friction (Δ²Σ q·Δs over slipping elements, all steps).
    pub frictional_dissipation: f64,
    /// Energy dissipated by friction in the last fretting cycle (0 without cycles).
    pub last_cycle_dissipation: f64,
    /// The most tensile (smallest) normal force during the shift: the pull-off force of an
    /// inclined path out of the body.
    pub min_normal_force: f64,
    /// The shift at which an inclined path lost the contact (the run stops there).
    pub contact_lost_at: Option<f64>,
    /// Energy released by normal configuration changes (adhesive jumps) on the approach.
    pub dissipated_energy: f64,
    /// Slip events: steps in which elements broke loose from their static bound and the
    /// tangential force fell (a static friction law; docs/physics.md §8.2).
    #[cfg_attr(feature = "serde", serde(default))]
    pub slip_events: usize,
    /// The worst optimality conditions met by any step.
    pub complementarity: Complementarity,
    /// Some step had contact on the border of a free grid.
    pub touches_border: bool,
}

impl Shear {
    /// Runs the approach and the shift; reports each step to `observer`.
    pub fn run(
        &self,
        problem: &mut Problem,
        solver: &mut NormalSolver,
        body: impl Into<ShearBody>,
        friction: &mut TangentialSolver,
        observer: &mut dyn Observer,
    ) -> Result<ShearSummary, ProtocolError> {
        self.check()?;
        let (operator, heights) = problem.parts_mut();
        let (body, grid): (ShearBody, _) = (body.into(), *operator.grid());
        solver.reset();
        let mut state = ContactState::new(&grid);
        let mut previous = state.contact.clone();
        let mut summary = ShearSummary::default();
        let inclined = self.incline != 0.0;
        let coupled = self.approach_either(
            NormalSide {
                operator: &mut *operator,
                heights,
                depth: self.depth,
                solver: &mut *solver,
                state: &mut state,
            },
            (body, &mut *friction),
            &mut previous,
            &mut summary,
            observer,
        )?;
        let compliant = compliant_drive(inclined, friction)?;
        let amplitude = match self.force_control {
            None => self.distance,
            Some(TangentialForce::Absolute(force)) => force,
            Some(TangentialForce::OfCapacity(share)) => share * friction.capacity(&state, grid.element_area()),
        };
        let mut stepper = coupled.map_or_else(
            || ShiftStepper::new(&*operator, &state, body, self.mode_mixity, inclined, false, solver),
            Ok,
        )?;
        stepper.hold_normal_force(self.hold_normal_force)?;
        stepper.weaken_coupled_edge(self.mode_mixity, body.material, solver)?;
        let mut fields = ShearFields::new(grid.len());
        let unit = [self.direction.cos(), self.direction.sin()];
        let slope = self.incline.tan();
        summary.normal_force = state.force(grid.element_area());
        summary.area = state.contact_elements() as f64 * grid.element_area();
        summary.min_normal_force = summary.normal_force;
        for (k, (value, stroke)) in self.path(amplitude).enumerate() {
            let step = self.approach_steps + k;
            let forward = stroke == Stroke::Forward;
            let target = match self.force_control {
                None => ShiftTarget::Shift([value * unit[0], value * unit[1]]),
                Some(_) => ShiftTarget::Force { unit, force: value },
            };
            // The imposed shift, or under force control the indenter's at the step's start.
            let shift = match target {
                ShiftTarget::Shift(_) => value,
                ShiftTarget::Force { .. } => {
                    stepper.room.state.shift[0] * unit[0] + stepper.room.state.shift[1] * unit[1]
                }
            };
            let depth = if inclined {
                self.depth + shift * slope
            } else {
                self.depth
            };
            previous.copy_from_slice(&state.contact);
            let outcome = stepper.step(
                NormalSide {
                    operator: &mut *operator,
                    heights,
                    depth,
                    solver: &mut *solver,
                    state: &mut state,
                },
                friction,
                target,
                step,
                summary.normal_force,
            )?;
            let (report, mut normal) = (outcome.tangential, outcome.normal);
            add_shift_counters(&mut summary, &mut normal, &report, stroke == Stroke::Cycle(self.cycles));
            let mut record = self.record(
                step,
                Phase::Shear,
                outcome.depth.unwrap_or(depth),
                normal,
                &state,
                &grid,
                summary.dissipated_energy,
            );
            let along = self.add_tangential_columns(&mut record, &report, &summary, &state.contact, &grid);
            // The indenter's shift (under a compliant drive it lags the drive's; under force
            // control it is found).
            let indenter = report.shift[0] * unit[0] + report.shift[1] * unit[1];
            let controlled_force = self.force_control.is_some();
            record.offset = if compliant || controlled_force { indenter } else { shift };
            record.drive_offset = if controlled_force { indenter } else { shift };
            if forward {
                summary.peak_tangential_force = summary.peak_tangential_force.max(along);
                summary.final_tangential_force = along;
                summary.normal_force = record.force_normal;
                summary.area = record.area;
            }
            summary.min_normal_force = summary.min_normal_force.min(record.force_normal);
            stepper.room.window.scatter(&stepper.room.state, &mut fields);
            self.report(&mut summary, &record, (&state, &previous, Some(&fields)), observer)?;
            if record.contact_elements == 0 {
                // An inclined path out of the body has pulled the indenter off.
                summary.contact_lost_at = Some(record.offset);
                break;
            }
        }
        stepper.finish(solver);
        Ok(summary)
    }

    /// Steps of the shift: the forward stroke, the cycles and the return.
    pub fn shift_steps(&self) -> usize {
        self.steps * (1 + 4 * self.cycles + usize::from(self.return_stroke))
    }

    /// The shift (or imposed force) of every step after the approach, for the stroke's
    /// `amplitude`, and the stroke it belongs to.
    fn path(&self, amplitude: f64) -> impl Iterator<Item = (f64, Stroke)> + '_ {
        let steps = self.steps as i64;
        let shift = move |travelled: i64| amplitude * travelled as f64 / steps as f64;
        let forward = (1..=steps).map(move |k| (shift(k), Stroke::Forward));
        // A cycle: from +distance down to −distance and back up, 2·steps steps each way.
        let cycles = (1..=self.cycles).flat_map(move |cycle| {
            (1..=4 * steps).map(move |k| {
                let travelled = if k <= 2 * steps { steps - k } else { k - 3 * steps };
                (shift(travelled), Stroke::Cycle(cycle))
            })
        });
        let back = (1..=steps)
            .filter(move |_| self.return_stroke)
            .map(move |k| (shift(steps - k), Stroke::Return));
        forward.chain(cycles).chain(back)
    }

    /// The parameters are usable.
    fn check(&self) -> Result<(), ProtocolError> {
        let invalid = |message: String| Err(ProtocolError::InvalidParameter(message));
        if self.approach_steps == 0 || self.steps == 0 {
            return invalid(format!(
                "approach_steps ({}) and steps ({}) must be >= 1",
                self.approach_steps, self.steps
            ));
        }
        match self.press_depth {
            None if !(self.depth.is_finite() && self.depth > self.start_depth) => {
                return invalid(format!(
                    "depth ({}) must exceed the depth of first contact ({})",
                    self.depth, self.start_depth
                ));
            }
            Some(press)
                if !(press.is_finite() && press > self.start_depth && self.depth.is_finite() && self.depth < press) =>
            {
                return invalid(format!(
                    "press_depth ({press}) must exceed the depth of first contact ({}) and depth ({})",
                    self.start_depth, self.depth
                ));
            }
            Some(_) if self.approach_steps < 2 => {
                return invalid(format!(
                    "a press and a lift take at least 2 approach steps, got {}",
                    self.approach_steps
                ));
            }
            _ => {}
        }
        if !(self.incline.is_finite() && self.incline.abs() < std::f64::consts::FRAC_PI_2) {
            return invalid(format!(
                "incline ({} rad) must lie strictly between −π/2 and π/2",
                self.incline
            ));
        }
        for (side, mixity) in self.mode_mixity.named() {
            if !(0.0..=1.0).contains(&mixity) {
                return invalid(format!("mode_mixity ({side}: {mixity}) must lie in [0, 1]"));
            }
        }
        if let Some(force) = self.force_control {
            let (TangentialForce::Absolute(value) | TangentialForce::OfCapacity(value)) = force;
            if !value.is_finite() || matches!(force, TangentialForce::OfCapacity(share) if share.abs() >= 1.0) {
                return invalid(format!(
                    "the imposed tangential force ({force:?}) must be finite, and as a share of what the interface holds below 1"
                ));
            }
            if self.incline != 0.0 || self.mode_mixity.weakens() {
                return invalid(format!(
                    "an imposed tangential force holds the normal problem fixed (or solves it with the coupled operator): it takes incline = 0 and mode_mixity = 0 (got {} rad and {:?})",
                    self.incline, self.mode_mixity
                ));
            }
        }
        if !(self.distance.is_finite() && self.direction.is_finite()) {
            return invalid(format!(
                "distance ({}) and direction ({}) must be finite",
                self.distance, self.direction
            ));
        }
        Ok(())
    }

    /// The step's record with the contact measured about the indenter axis at the origin.
    #[allow(clippy::too_many_arguments)]
    fn record(
        &self,
        step: usize,
        phase: Phase,
        depth: f64,
        report: StepReport,
        state: &ContactState,
        grid: &Grid,
        dissipated: f64,
    ) -> StepRecord {
        StepRecord::measure(
            step,
            phase,
            depth,
            0.0,
            report,
            state,
            grid,
            dissipated,
            self.jump_force_threshold,
        )
    }

    /// The tangential columns of a step's record: the force along the shift (returned),
    /// the stick and slip counts, friction's dissipation so far, and the front and rear
    /// areas about the indenter's axis.
    fn add_tangential_columns(
        &self,
        record: &mut StepRecord,
        report: &TangentialReport,
        summary: &ShearSummary,
        contact: &[bool],
        grid: &Grid,
    ) -> f64 {
        let unit = [self.direction.cos(), self.direction.sin()];
        let along = report.force[0] * unit[0] + report.force[1] * unit[1];
        record.force_tangential = along;
        record.force_tangential_before_change = along;
        record.stick_elements = report.stick_elements;
        record.slip_elements = report.slip_elements;
        record.cumulative_frictional_dissipation = summary.frictional_dissipation;
        (_, record.area_front, record.area_rear) = contact_split(grid, contact, self.direction);
        along
    }

    /// Totals, then the observer; `view` is the normal state, the contact at the step's
    /// start and the tangential fields of a shift step.
    fn report(
        &self,
        summary: &mut ShearSummary,
        record: &StepRecord,
        view: (&ContactState, &[bool], Option<&ShearFields>),
        observer: &mut dyn Observer,
    ) -> Result<(), ProtocolError> {
        let (state, previous, shear) = view;
        summary.steps += 1;
        summary.touches_border |= record.touches_border;
        match observer.on_step(StepView {
            record,
            state,
            previous_contact: previous,
            shear,
        }) {
            ControlFlow::Continue(()) => Ok(()),
            ControlFlow::Break(()) => Err(ProtocolError::Interrupted(record.step)),
        }
    }
}

/// A normal step's solves, iterations, transforms and released energy into the totals.
fn add_normal_counters(summary: &mut ShearSummary, report: &StepReport) {
    summary.dissipated_energy += report.dissipated_energy;
    summary.solves += report.solves;
    summary.cg_iterations += report.cg_iterations;
    summary.operator_applications += report.operator_applications;
    summary.window_applications += report.window_applications;
    summary.preconditioner_applications += report.preconditioner_applications;
}

/// A shift step's normal and tangential counters into the totals, and the tangential ones
/// into the step's `normal` report; `last_cycle`: the step belongs to the last fretting
/// cycle.
fn add_shift_counters(
    summary: &mut ShearSummary,
    normal: &mut StepReport,
    report: &TangentialReport,
    last_cycle: bool,
) {
    add_normal_counters(summary, normal);
    normal.cg_iterations += report.cg_iterations;
    normal.operator_applications += report.transform_pairs;
    summary.tangential_transform_pairs += report.transform_pairs;
    summary.operator_applications += report.transform_pairs;
    summary.cg_iterations += report.cg_iterations;
    summary.tangential_rounds += report.rounds;
    summary.frictional_dissipation += report.dissipated_energy;
    summary.slip_events += usize::from(report.slip_event);
    if last_cycle {
        summary.last_cycle_dissipation += report.dissipated_energy;
    }
    worst(&mut summary.complementarity, report.complementarity);
}

/// The worse of each optimality measure.
fn worst(into: &mut Complementarity, from: Complementarity) {
    into.stick_residual = into.stick_residual.max(from.stick_residual);
    into.bound_excess = into.bound_excess.max(from.bound_excess);
    into.slip_misalignment = into.slip_misalignment.max(from.slip_misalignment);
    into.backward_slip = into.backward_slip.max(from.backward_slip);
}

/// (elements in contact, front area, rear area): the contact split at the line through
/// the indenter's axis perpendicular to the shift; front = strictly ahead of it, rear = the
/// rest, as the analysis of filmed experiments splits it (docs/physics.md §7; the paper's
/// Figs. 17 and 19).
///
/// # Example
/// ```
/// use adhesim::protocol::contact_split;
/// use adhesim::{Boundary, Grid};
///
/// // Four elements in contact on an 8 × 8 grid of unit elements, at x = ±1, shifted
/// // along +x: the two at x = 1 are ahead (front), the two at x = −1 behind (rear).
/// let grid = Grid::new(8, 8.0, Boundary::Free)?;
/// let mut contact = vec![false; grid.len()];
/// for k in [3 * 8 + 3, 3 * 8 + 5, 4 * 8 + 3, 4 * 8 + 5] {
///     contact[k] = true;
/// }
/// let (count, front, rear) = contact_split(&grid, &contact, 0.0);
/// assert_eq!((count, front, rear), (4, 2.0, 2.0));
/// # Ok::<(), adhesim::GridError>(())
/// ```
pub fn contact_split(grid: &Grid, contact: &[bool], direction: f64) -> (usize, f64, f64) {
    contact_split_about(grid, contact, direction, 0.0)
}

/// [`contact_split`] about the indenter's axis at (`axis`, 0) (a translation's).
pub(super) fn contact_split_about(grid: &Grid, contact: &[bool], direction: f64, axis: f64) -> (usize, f64, f64) {
    let (ux, uy) = (direction.cos(), direction.sin());
    let (mut count, mut front, mut rear) = (0, 0.0, 0.0);
    let area = grid.element_area();
    let tolerance = 1e-9 * grid.dx().min(grid.dy());
    for (k, _) in contact.iter().enumerate().filter(|(_, &c)| c) {
        count += 1;
        let (x, y) = grid.centre(k);
        if (x - axis) * ux + y * uy > tolerance {
            front += area;
        } else {
            rear += area;
        }
    }
    (count, front, rear)
}

/// Whether `friction` pulls the indenter through a spring; an error on an inclined path.
fn compliant_drive(inclined: bool, friction: &TangentialSolver) -> Result<bool, ProtocolError> {
    let compliant = friction.drive_stiffness().is_some();
    if inclined && compliant {
        return Err(ProtocolError::InvalidParameter(
            "a compliant drive moves the indenter along the surface only: an inclined path (incline ≠ 0) takes a rigid drive".into(),
        ));
    }
    Ok(compliant)
}
