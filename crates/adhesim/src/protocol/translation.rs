use super::{
    NormalSolver, Observer, Phase, ProtocolCheckpoint, ProtocolError, StepRecord, StepView, TranslationCheckpoint,
};
use crate::elastic::ElasticOperator;
use crate::geometry::{Kinematics, TranslatingContact};
use crate::problem::Problem;
use crate::solver::ContactState;
use std::ops::ControlFlow;

/// Rolling or sliding at fixed indentation (paper Sect. 2.6 and 3, Figs. 6–10): indent to
/// `depth` in `approach_steps` steps, then move the indenter axis from X = 0 to
/// `distance` in `steps` quasi-static steps, the contact set carried from step to step;
/// optionally back again. The profile is evaluated analytically at every X.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Translation {
    /// Depth of first contact (the approach starts there).
    pub start_depth: f64,
    /// Indentation held during the motion.
    pub depth: f64,
    /// Steps of the approach to `depth`.
    pub approach_steps: usize,
    /// Travel of the axis in +x.
    pub distance: f64,
    /// Steps of the travel.
    pub steps: usize,
    /// Travel back to X = 0 after the forward stroke.
    pub return_stroke: bool,
    /// The mean tangential force is taken over the part of the forward stroke beyond this
    /// fraction of `distance` (the stationary part; default 0.5).
    pub stationary_from: f64,
    /// A step is a jump when the normal force changes by more than this at fixed X.
    pub jump_force_threshold: f64,
}

/// Results of a translation.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TranslationSummary {
    /// Steps done (approach and travel).
    pub steps: usize,
    /// Mean over the stationary part of the forward stroke of the tangential force
    /// F_T = ∫p ∂z_moving/∂x dA at the end of each step (the paper's per-step force).
    pub mean_tangential_force: f64,
    /// Work of the driving force per distance over the same part, ∫F_T dX/ΔX, with F_T
    /// on each fixed-set stretch running linearly from the previous step's value to the
    /// value before the configuration change. Equals the dissipated energy per distance;
    /// exceeds the per-step mean by the lattice stick–slip (see docs/validation.md).
    pub mean_tangential_force_work: f64,
    /// Standard deviation of the end-of-step tangential force there.
    pub tangential_force_fluctuation: f64,
    /// Mean normal force there.
    pub mean_normal_force: f64,
    /// Mean contact half-width perpendicular to the motion there.
    pub mean_half_width: f64,
    /// Mean contact radius (farthest element from the axis) there.
    pub mean_radius: f64,
    /// Mean real contact area there.
    pub mean_area: f64,
    /// Mean A_real/(π a²) with a the contact radius there.
    pub compactness: f64,
    /// Energy released by configuration changes during the forward stroke.
    pub dissipated_energy: f64,
    /// Dissipated energy per travelled distance over the stationary part: must equal the
    /// work-based mean tangential force (energy balance).
    pub dissipation_per_distance: f64,
    /// Steps flagged as jumps.
    pub jumps: usize,
    /// Fixed-set solves, CG iterations and FFT pairs.
    pub solves: usize,
    /// CG iterations.
    pub cg_iterations: usize,
    /// Operator applications.
    pub operator_applications: u64,
    /// Of those, the adhesive CG's applications on contact windows.
    #[cfg_attr(feature = "serde", serde(default))]
    pub window_applications: u64,
    /// The CG preconditioner's applications (FFT pairs of the solved grid's own size; not
    /// in `operator_applications`).
    #[cfg_attr(feature = "serde", serde(default))]
    pub preconditioner_applications: u64,
    /// Some step had contact on the border of a free grid.
    pub touches_border: bool,
    /// Energy dissipated by friction at the interface over the run (0 without).
    #[cfg_attr(feature = "serde", serde(default))]
    pub frictional_dissipation: f64,
    /// Friction's dissipation per travelled distance over the stationary part: the mean
    /// interface force of a steady slide (0 without friction).
    #[cfg_attr(feature = "serde", serde(default))]
    pub frictional_dissipation_per_distance: f64,
    /// The worst optimality conditions of any tangential step (friction at the interface).
    #[cfg_attr(feature = "serde", serde(default))]
    pub complementarity: crate::solver::Complementarity,
}

impl Translation {
    /// Runs the approach and the stroke(s).
    pub fn run(
        &self,
        problem: &mut Problem,
        solver: &mut NormalSolver,
        observer: &mut dyn Observer,
    ) -> Result<TranslationSummary, ProtocolError> {
        self.run_from(problem, solver, observer, None)
    }

    /// As [`run`](Self::run), continued from `start` (a checkpoint of a run of the same
    /// protocol, contact and kind of solver) when given: the steps after it are those of
    /// the uninterrupted run, bit for bit. After every step but the last the observer is
    /// offered a checkpoint ([`Observer::wants_checkpoint`]).
    pub fn run_from(
        &self,
        problem: &mut Problem,
        solver: &mut NormalSolver,
        observer: &mut dyn Observer,
        start: Option<&TranslationCheckpoint>,
    ) -> Result<TranslationSummary, ProtocolError> {
        self.check()?;
        let (operator, contact) = problem.translating_parts()?;
        let grid = *operator.grid();
        solver.reset();
        let phase = match contact.kinematics() {
            Kinematics::Roll => Phase::Roll,
            _ => Phase::Slide,
        };
        let schedule = self.schedule(phase);
        let mut run = match start {
            Some(checkpoint) => {
                checkpoint.check(&grid, schedule.len())?;
                solver
                    .restore(&checkpoint.solver, &checkpoint.state)
                    .map_err(ProtocolError::InvalidParameter)?;
                // The solver's part now lives in the solver; the run carries the rest.
                TranslationCheckpoint {
                    solver: super::SolverCheckpoint::Stateless,
                    ..checkpoint.clone()
                }
            }
            None => TranslationCheckpoint::start(&grid),
        };
        let mut previous = run.state.contact.clone();
        let mut heights = vec![0.0; grid.len()];
        for step in run.steps_done..schedule.len() {
            let (stage, depth, offset) = schedule[step];
            contact.fill_heights(&grid, offset, &mut heights);
            previous.copy_from_slice(&run.state.contact);
            let record = self.run_step(
                operator,
                contact,
                solver,
                &mut run,
                (step, stage, depth, offset),
                &heights,
                &mut |_, _| Ok(()),
            )?;
            if let ControlFlow::Break(()) = observer.on_step(StepView {
                record: &record,
                state: &run.state,
                previous_contact: &previous,
                shear: None,
            }) {
                return Err(ProtocolError::Interrupted(step));
            }
            run.steps_done = step + 1;
            if run.steps_done < schedule.len() && solver.supports_checkpoints() && observer.wants_checkpoint() {
                if let Some(saved) = solver.checkpoint() {
                    run.solver = saved;
                    let offered = ProtocolCheckpoint::Translation(Box::new(run.clone()));
                    run.solver = super::SolverCheckpoint::Stateless;
                    if let ControlFlow::Break(()) = observer.on_checkpoint(offered) {
                        return Err(ProtocolError::Interrupted(step));
                    }
                }
            }
        }
        let mut summary = run.summary;
        stationary_means(&mut summary, &run.stationary, |record| record.offset);
        Ok(summary)
    }

    /// One step (`step`, its stage, depth and offset) on `heights`: the solve, the record
    /// and the totals of `run`. `interface` completes the record from the normal state
    /// before it counts (friction at the interface adds its force and work there).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn run_step(
        &self,
        operator: &mut dyn ElasticOperator,
        contact: &TranslatingContact,
        solver: &mut NormalSolver,
        run: &mut TranslationCheckpoint,
        (step, stage, depth, offset): (usize, Phase, f64, f64),
        heights: &[f64],
        interface: &mut dyn FnMut(&ContactState, &mut StepRecord) -> Result<(), ProtocolError>,
    ) -> Result<StepRecord, ProtocolError> {
        let mut record = self.solve_step(operator, contact, solver, run, (step, stage, depth, offset), heights)?;
        interface(&run.state, &mut record)?;
        self.count_step(run, &record, offset);
        Ok(record)
    }

    /// The normal solve of a step on `heights` (the profile with its axis at `offset`) and
    /// its record, with the boundary's tangential force while the indenter moves; the
    /// step's released energy joins `run`'s cumulative count, nothing else is counted.
    pub(super) fn solve_step(
        &self,
        operator: &mut dyn ElasticOperator,
        contact: &TranslatingContact,
        solver: &mut NormalSolver,
        run: &mut TranslationCheckpoint,
        (step, stage, depth, offset): (usize, Phase, f64, f64),
        heights: &[f64],
    ) -> Result<StepRecord, ProtocolError> {
        let grid = *operator.grid();
        let mut tangential_before = 0.0;
        let moving = stage != Phase::Approach;
        let report = solver
            .step_probed(operator, heights, depth, &mut run.state, &mut |solved| {
                if moving {
                    tangential_before = contact.tangential_force(&grid, &solved.pressure, offset);
                }
            })
            .map_err(|source| ProtocolError::Solve { step, depth, source })?;
        run.cumulative_dissipated_energy += report.dissipated_energy;
        let mut record = StepRecord::measure(
            step,
            stage,
            depth,
            offset,
            report,
            &run.state,
            &grid,
            run.cumulative_dissipated_energy,
            self.jump_force_threshold,
        );
        if moving {
            record.force_tangential = contact.tangential_force(&grid, &run.state.pressure, offset);
            record.force_tangential_before_change = tangential_before;
        }
        Ok(record)
    }

    /// Counts a finished step into `run`'s totals; a stroke step whose drive stands at
    /// `position` beyond the stationary fraction joins the stationary means.
    pub(super) fn count_step(&self, run: &mut TranslationCheckpoint, record: &StepRecord, position: f64) {
        let forward_end = self.approach_steps + self.steps;
        let report = record.report;
        let summary = &mut run.summary;
        summary.steps += 1;
        summary.solves += report.solves;
        summary.cg_iterations += report.cg_iterations;
        summary.operator_applications += report.operator_applications;
        summary.window_applications += report.window_applications;
        summary.preconditioner_applications += report.preconditioner_applications;
        summary.jumps += record.jumped as usize;
        summary.touches_border |= record.touches_border;
        if record.phase != Some(Phase::Approach) && record.step < forward_end {
            summary.dissipated_energy += report.dissipated_energy;
            if position > self.stationary_from * self.distance {
                run.stationary.push(*record);
            }
        }
    }

    /// The parameters a run needs, checked before anything is allocated.
    pub(super) fn check(&self) -> Result<(), ProtocolError> {
        if self.steps == 0 || self.approach_steps == 0 {
            return Err(ProtocolError::InvalidParameter("steps must be >= 1".into()));
        }
        if !(self.distance.is_finite() && self.distance > 0.0) {
            return Err(ProtocolError::InvalidParameter(format!(
                "distance must be > 0, got {}",
                self.distance
            )));
        }
        if !(self.depth.is_finite() && self.depth > self.start_depth) {
            return Err(ProtocolError::InvalidParameter(format!(
                "depth ({}) must exceed the depth of first contact ({})",
                self.depth, self.start_depth
            )));
        }
        Ok(())
    }

    /// (phase, depth, offset) of every step: the approach at x = 0, the forward stroke and,
    /// if asked, the return stroke.
    pub(super) fn schedule(&self, phase: Phase) -> Vec<(Phase, f64, f64)> {
        let mut schedule: Vec<(Phase, f64, f64)> = (1..=self.approach_steps)
            .map(|i| {
                let depth = self.start_depth + (self.depth - self.start_depth) * i as f64 / self.approach_steps as f64;
                (Phase::Approach, depth, 0.0)
            })
            .collect();
        schedule.extend((1..=self.steps).map(|i| (phase, self.depth, self.distance * i as f64 / self.steps as f64)));
        if self.return_stroke {
            schedule.extend(
                (0..self.steps)
                    .rev()
                    .map(|i| (phase, self.depth, self.distance * i as f64 / self.steps as f64)),
            );
        }
        schedule
    }
}

/// Means over the stationary part of the forward stroke (paper Eqs. 12–18 read these);
/// the work and the dissipation per distance are per distance the drive travels
/// (`position`: the axis's offset, or the drive's under a compliant drive).
pub(super) fn stationary_means(
    summary: &mut TranslationSummary,
    stationary: &[StepRecord],
    position: impl Fn(&StepRecord) -> f64,
) {
    if stationary.is_empty() {
        return;
    }
    let count = stationary.len() as f64;
    let mean = |f: &dyn Fn(&StepRecord) -> f64| stationary.iter().map(f).sum::<f64>() / count;
    summary.mean_tangential_force = mean(&|r| r.force_tangential);
    let mean_force = summary.mean_tangential_force;
    summary.tangential_force_fluctuation = mean(&|r| (r.force_tangential - mean_force).powi(2)).sqrt();
    summary.mean_normal_force = mean(&|r| r.force_normal);
    summary.mean_half_width = mean(&|r| r.half_width);
    summary.mean_radius = mean(&|r| r.radius);
    summary.mean_area = mean(&|r| r.area);
    summary.compactness = mean(&|r| {
        if r.radius > 0.0 {
            r.area / (std::f64::consts::PI * r.radius * r.radius)
        } else {
            0.0
        }
    });
    let travelled = stationary.last().map_or(0.0, &position) - position(&stationary[0]);
    if travelled > 0.0 {
        let work: f64 = stationary
            .windows(2)
            .map(|w| {
                0.5 * (w[0].force_tangential + w[1].force_tangential_before_change)
                    * (position(&w[1]) - position(&w[0]))
            })
            .sum();
        summary.mean_tangential_force_work = work / travelled;
        let mut released: f64 = stationary.iter().skip(1).map(|r| r.report.dissipated_energy).sum();
        // Friction at the interface dissipates too (cumulative in the records).
        let frictional = stationary.last().map_or(0.0, |r| r.cumulative_frictional_dissipation)
            - stationary[0].cumulative_frictional_dissipation;
        if frictional != 0.0 {
            released += frictional;
            summary.frictional_dissipation_per_distance = frictional / travelled;
        }
        summary.dissipation_per_distance = released / travelled;
    }
}
