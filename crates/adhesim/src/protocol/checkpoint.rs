//! Mid-run checkpoints of an [`IndentPulloff`](super::IndentPulloff) or a
//! [`Translation`](super::Translation) run: everything the steps after a given step depend
//! on, so that a run restored from a checkpoint (in a fresh solver of the same problem)
//! gives the records of the uninterrupted run bit for bit.
//!
//! A protocol offers one after every step to its [`Observer`](super::Observer), which
//! decides whether to take it ([`Observer::wants_checkpoint`](super::Observer::wants_checkpoint));
//! writing it anywhere is the observer's business. Every normal solver supports them (the
//! non-adhesive CCG and nested active set, the JKR-type active set, a cohesive law); a
//! family that did not would return `None` from
//! [`NormalStepper::checkpoint`](super::NormalStepper::checkpoint): the protocol then offers
//! none and runs as without.

use super::{Phase, ProtocolError, ProtocolSummary, StepRecord, TranslationSummary};
use crate::grid::Grid;
use crate::solver::{AdhesiveCheckpoint, CohesiveCheckpoint, ContactState, NestedCheckpoint};

/// What the normal solver carries from one step to the next.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum SolverCheckpoint {
    /// Nothing (the non-adhesive CCG: every solve starts from the state alone).
    Stateless,
    /// The adhesive active set's history (warm start, failed rings, bans, generator).
    Adhesive(Box<AdhesiveCheckpoint>),
    /// The nested non-adhesive active set's contact windows and last depth.
    Nested(Box<NestedCheckpoint>),
    /// A cohesive law's tractions, its compressive part's warm start and the compressive
    /// solver's history.
    Cohesive(Box<CohesiveCheckpoint>),
}

/// The state of an indentation run after a step.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct IndentCheckpoint {
    /// Steps done (the next step's number).
    pub steps_done: usize,
    /// Phase of the last step done.
    pub phase: Phase,
    /// Depth of the last step done (the retraction goes on from it).
    pub depth: f64,
    /// Depth of the last retraction step in contact.
    pub last_in_contact: Option<f64>,
    /// The configuration after the last step (the next step's warm start).
    pub state: ContactState,
    /// The contact set at the start of the last step.
    #[cfg_attr(feature = "serde", serde(with = "crate::bit_string"))]
    pub previous: Vec<bool>,
    /// The run's totals so far.
    pub summary: ProtocolSummary,
    /// The solver's history.
    pub solver: SolverCheckpoint,
}

/// The state of a translation (roll, slide, translate) after a step.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TranslationCheckpoint {
    /// Steps done (the next step's number).
    pub steps_done: usize,
    /// The configuration after the last step (the next step's warm start).
    pub state: ContactState,
    /// Energy dissipated up to the last step (the records' cumulative column).
    pub cumulative_dissipated_energy: f64,
    /// The run's totals so far (the stationary means are taken at the end).
    pub summary: TranslationSummary,
    /// The records of the stationary part of the forward stroke so far.
    pub stationary: Vec<StepRecord>,
    /// The solver's history.
    pub solver: SolverCheckpoint,
}

/// The checkpoint a protocol offers its observer.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ProtocolCheckpoint {
    /// Of an indent–pull-off run.
    Indentation(Box<IndentCheckpoint>),
    /// Of a roll, slide or translate run.
    Translation(Box<TranslationCheckpoint>),
}

impl ProtocolCheckpoint {
    /// Steps done (the next step's number).
    pub fn steps_done(&self) -> usize {
        match self {
            Self::Indentation(c) => c.steps_done,
            Self::Translation(c) => c.steps_done,
        }
    }

    /// The configuration after the last step.
    pub fn state(&self) -> &ContactState {
        match self {
            Self::Indentation(c) => &c.state,
            Self::Translation(c) => &c.state,
        }
    }

    /// The protocol it belongs to, in words (for errors).
    pub fn protocol_name(&self) -> &'static str {
        match self {
            Self::Indentation(_) => "an indent–pull-off run",
            Self::Translation(_) => "a roll, slide or translate run",
        }
    }
}

impl SolverCheckpoint {
    /// The kind of solver that took it, in words (for errors).
    pub(super) fn solver_name(&self) -> &'static str {
        match self {
            Self::Stateless => "the non-adhesive CCG",
            Self::Nested(_) => "the non-adhesive nested active set",
            Self::Adhesive(_) => "the JKR-type adhesive solver",
            Self::Cohesive(_) => "a cohesive law's solver",
        }
    }
}

impl IndentCheckpoint {
    /// Checks that the checkpoint fits `grid` and a run of `approach_steps` approach steps.
    pub(super) fn check(&self, grid: &Grid, approach_steps: usize) -> Result<(), ProtocolError> {
        let len = grid.len();
        let fits = self.state.pressure.len() == len
            && self.state.displacement.len() == len
            && self.state.contact.len() == len
            && self.previous.len() == len
            && self.steps_done > 0
            && self.summary.steps == self.steps_done
            && (self.phase == Phase::Approach) == (self.steps_done <= approach_steps)
            && matches!(self.phase, Phase::Approach | Phase::Retract);
        if fits {
            Ok(())
        } else {
            Err(ProtocolError::InvalidParameter(format!(
                "the checkpoint (after step {}, {} elements) does not fit this run ({} approach steps, {len} elements)",
                self.steps_done.saturating_sub(1),
                self.state.pressure.len(),
                approach_steps
            )))
        }
    }
}

impl TranslationCheckpoint {
    /// The state of a translation on `grid` before its first step: no contact, nothing
    /// counted.
    pub(super) fn start(grid: &Grid) -> Self {
        Self {
            steps_done: 0,
            state: ContactState::new(grid),
            cumulative_dissipated_energy: 0.0,
            summary: TranslationSummary::default(),
            stationary: Vec::new(),
            solver: SolverCheckpoint::Stateless,
        }
    }

    /// Checks that the checkpoint fits `grid` and a run of `steps` steps in all.
    pub(super) fn check(&self, grid: &Grid, steps: usize) -> Result<(), ProtocolError> {
        let len = grid.len();
        let fits = self.state.pressure.len() == len
            && self.state.displacement.len() == len
            && self.state.contact.len() == len
            && self.steps_done > 0
            && self.steps_done < steps
            && self.summary.steps == self.steps_done;
        if fits {
            Ok(())
        } else {
            Err(ProtocolError::InvalidParameter(format!(
                "the checkpoint (after step {}, {} elements) does not fit this run ({steps} steps, {len} elements)",
                self.steps_done.saturating_sub(1),
                self.state.pressure.len(),
            )))
        }
    }
}
