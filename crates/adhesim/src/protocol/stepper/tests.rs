//! The protocols drive a solver only through [`NormalStepper`]: a family of its own,
//! handed over as [`NormalSolver::Family`], runs an indentation as the named variant does.

use super::*;
use crate::elastic::FreeOperator;
use crate::geometry::{Profile, Sphere};
use crate::grid::{Boundary, Grid};
use crate::material::ElasticMaterial;
use crate::problem::Problem;
use crate::protocol::{IndentPulloff, NormalSolver, Observer, ProtocolCheckpoint, ProtocolError, StepRecord, StepView};
use crate::solver::AdhesiveParams;
use std::ops::ControlFlow;

/// A family outside the library: the JKR-type solver behind a type the protocols cannot
/// name, which takes no checkpoints.
struct Outside(AdhesiveSolver);

impl NormalStepper for Outside {
    fn name(&self) -> &'static str {
        "a family outside the library"
    }

    fn reset(&mut self) {
        self.0.reset();
    }

    fn step_probed(
        &mut self,
        operator: &mut dyn ElasticOperator,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
        before_change: &mut (dyn FnMut(&ContactState) + Send),
    ) -> Result<StepReport, SolveError> {
        self.0.step_probed(operator, heights, depth, state, before_change)
    }

    fn checkpoint(&self) -> Option<SolverCheckpoint> {
        None
    }

    fn supports_checkpoints(&self) -> bool {
        false
    }

    fn restore(&mut self, checkpoint: &SolverCheckpoint, _state: &ContactState) -> Result<(), String> {
        Err(other_family(checkpoint, self))
    }
}

/// Records the steps and asks for a checkpoint after each, counting those offered.
#[derive(Default)]
struct Recorder {
    records: Vec<StepRecord>,
    offered: usize,
}

impl Observer for Recorder {
    fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()> {
        self.records.push(*view.record);
        ControlFlow::Continue(())
    }

    fn wants_checkpoint(&mut self) -> bool {
        true
    }

    fn on_checkpoint(&mut self, _checkpoint: ProtocolCheckpoint) -> ControlFlow<()> {
        self.offered += 1;
        ControlFlow::Continue(())
    }
}

/// A JKR sphere on 32² (about 14 approach steps and its pull-off), by `solver`.
fn indent(solver: &mut NormalSolver) -> Recorder {
    let mut recorder = Recorder::default();
    indent_observed(solver, &mut recorder).unwrap();
    recorder
}

/// The indentation of [`indent`] seen by `observer`.
fn indent_observed(solver: &mut NormalSolver, observer: &mut dyn Observer) -> Result<(), ProtocolError> {
    let grid = grid();
    let material = ElasticMaterial::new(1.0).unwrap();
    let heights = Sphere::new(1.0).unwrap().heights(&grid);
    let protocol = IndentPulloff {
        start_depth: 0.0,
        max_depth: 4e-3,
        depth_step: 3e-4,
        max_retract_steps: 1000,
        jump_force_threshold: 0.0,
    };
    let mut problem = Problem::new(Box::new(FreeOperator::new(grid, material)), heights).unwrap();
    protocol.run(&mut problem, solver, observer).map(|_| ())
}

fn grid() -> Grid {
    Grid::new(32, 0.4, Boundary::Free).unwrap()
}

fn adhesive() -> AdhesiveSolver {
    AdhesiveSolver::new(grid(), 1.0, vec![1e-4; grid().len()], AdhesiveParams::default())
}

#[test]
fn a_family_of_its_own_runs_an_indentation_as_the_named_variant_does() {
    let named = indent(&mut NormalSolver::Adhesive(Box::new(adhesive())));
    let outside = indent(&mut NormalSolver::Family(Box::new(Outside(adhesive()))));
    assert!(named.records.len() > 20, "{} steps", named.records.len());
    assert!(
        named.records.iter().any(|r| r.force_normal < 0.0),
        "the run pulls off under tension"
    );
    // Bit for bit: `{:?}` prints every f64 in its shortest round-trip form.
    assert_eq!(format!("{:?}", outside.records), format!("{:?}", named.records));
    assert_eq!(
        named.offered,
        named.records.len() - 1,
        "a checkpoint after every step but the last"
    );
    assert_eq!(outside.offered, 0, "a family without checkpoints is offered none");
}

#[test]
fn a_checkpoint_of_another_family_is_refused_by_name() {
    let mut outside = NormalSolver::Family(Box::new(Outside(adhesive())));
    let state = ContactState::new(&grid());
    let error = outside.restore(&SolverCheckpoint::Stateless, &state).unwrap_err();
    assert_eq!(
        error,
        "the checkpoint is of the non-adhesive CCG, this run's solver is a family outside the library"
    );
    let mut named = NormalSolver::Adhesive(Box::new(adhesive()));
    let saved = named.checkpoint().unwrap();
    assert!(named.restore(&saved, &state).is_ok());
    let mut ccg = NormalSolver::NonAdhesive(Ccg::new(crate::solver::CcgParams::default()));
    assert_eq!(
        ccg.restore(&saved, &state).unwrap_err(),
        "the checkpoint is of the JKR-type adhesive solver, this run's solver is the non-adhesive CCG"
    );
}

/// Counts the steps it sees and the checkpoints it is handed, asks for none, and stops the
/// run after `stop_after` steps.
struct Counter {
    steps: usize,
    offered: usize,
    stop_after: usize,
}

impl Observer for Counter {
    fn on_step(&mut self, _view: StepView<'_>) -> ControlFlow<()> {
        self.steps += 1;
        if self.steps == self.stop_after {
            return ControlFlow::Break(());
        }
        ControlFlow::Continue(())
    }

    fn on_checkpoint(&mut self, _checkpoint: ProtocolCheckpoint) -> ControlFlow<()> {
        self.offered += 1;
        ControlFlow::Continue(())
    }
}

#[test]
fn composed_observers_see_every_step_and_only_the_checkpoints_they_asked_for() {
    let solver = || NormalSolver::Adhesive(Box::new(adhesive()));
    let alone = indent(&mut solver());
    let quiet = || Counter {
        steps: 0,
        offered: 0,
        stop_after: usize::MAX,
    };
    let absent: Option<Recorder> = None;
    let mut composed = (quiet(), Recorder::default(), (absent, quiet()));
    indent_observed(&mut solver(), &mut composed).unwrap();
    let (first, recorder, (_, last)) = composed;
    assert_eq!(format!("{:?}", recorder.records), format!("{:?}", alone.records));
    assert_eq!(
        recorder.offered, alone.offered,
        "the part that asked is handed every checkpoint"
    );
    assert_eq!((first.steps, last.steps), (alone.records.len(), alone.records.len()));
    assert_eq!(
        (first.offered, last.offered),
        (0, 0),
        "parts that did not ask are handed none"
    );

    // A part that stops the run stops it before the parts after it see that step.
    let mut stopping = (
        Counter {
            stop_after: 5,
            ..quiet()
        },
        quiet(),
    );
    let stopped = indent_observed(&mut solver(), &mut stopping);
    assert!(matches!(stopped, Err(ProtocolError::Interrupted(_))), "{stopped:?}");
    assert_eq!((stopping.0.steps, stopping.1.steps), (5, 4));
}
