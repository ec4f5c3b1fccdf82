//! What a protocol shows of each step ([`StepView`]) and who sees it ([`Observer`]).
//! Observers compose: a pair or a triple of observers is one, each part seeing every step
//! in turn, and `&mut` of an observer is one, so that a caller's observer can be a part.

use super::checkpoint::ProtocolCheckpoint;
use super::shear::ShearFields;
use super::StepRecord;
use crate::solver::ContactState;
use std::ops::ControlFlow;

/// What an observer sees of a step.
#[derive(Clone, Copy)]
pub struct StepView<'a> {
    /// The record.
    pub record: &'a StepRecord,
    /// The configuration at the end of the step.
    pub state: &'a ContactState,
    /// The contact set at the start of the step (to mark attached/detached elements).
    pub previous_contact: &'a [bool],
    /// The tangential fields of a shift step of a shear (None otherwise).
    pub shear: Option<&'a ShearFields>,
}

/// Receives every step of a protocol; returning `ControlFlow::Break` stops the protocol.
///
/// # Examples
/// Two observers as one: the records of every step, and the largest contact seen.
/// ```
/// use adhesim::{Observer, StepRecord, StepView};
/// use std::ops::ControlFlow;
///
/// #[derive(Default)]
/// struct LargestContact(usize);
///
/// impl Observer for LargestContact {
///     fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()> {
///         self.0 = self.0.max(view.record.contact_elements);
///         ControlFlow::Continue(())
///     }
/// }
///
/// let mut both = (Vec::<StepRecord>::new(), LargestContact::default());
/// // `protocol.run(&mut problem, &mut solver, &mut both)` would fill both.
/// let (records, largest) = both;
/// assert!(records.is_empty() && largest.0 == 0);
/// ```
pub trait Observer {
    /// Called after each step.
    fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()>;

    /// Asked after each step of a protocol that offers checkpoints (an indentation or a
    /// translation, on a solver that supports them): whether to take one now. Default:
    /// never. An answer from the observer's state, without side effects: a composed
    /// observer asks its parts again to hand the checkpoint to those that want it.
    fn wants_checkpoint(&mut self) -> bool {
        false
    }

    /// The checkpoint asked for by [`wants_checkpoint`](Self::wants_checkpoint), after the
    /// step [`on_step`](Self::on_step) has seen; `Break` stops the protocol as there.
    fn on_checkpoint(&mut self, _checkpoint: ProtocolCheckpoint) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
}

/// An observer that does nothing.
impl Observer for () {
    fn on_step(&mut self, _view: StepView<'_>) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
}

/// Collects the records (handy in tests and small studies).
impl Observer for Vec<StepRecord> {
    fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()> {
        self.push(*view.record);
        ControlFlow::Continue(())
    }
}

/// An observer borrowed: a caller's observer as a part of a composed one.
impl<O: Observer + ?Sized> Observer for &mut O {
    fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()> {
        (**self).on_step(view)
    }

    fn wants_checkpoint(&mut self) -> bool {
        (**self).wants_checkpoint()
    }

    fn on_checkpoint(&mut self, checkpoint: ProtocolCheckpoint) -> ControlFlow<()> {
        (**self).on_checkpoint(checkpoint)
    }
}

/// Two observers as one. Each step goes to the first, then to the second; a `Break` of
/// the first stops the protocol before the second sees the step. A checkpoint is taken
/// when either asks (both are asked), and the one taken is handed to the parts that
/// asked for it, in order; neither part sees a checkpoint it did not ask for.
impl<A: Observer, B: Observer> Observer for (A, B) {
    fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()> {
        self.0.on_step(view)?;
        self.1.on_step(view)
    }

    fn wants_checkpoint(&mut self) -> bool {
        let (first, second) = (self.0.wants_checkpoint(), self.1.wants_checkpoint());
        first || second
    }

    fn on_checkpoint(&mut self, checkpoint: ProtocolCheckpoint) -> ControlFlow<()> {
        // Asked again, to route: `wants_checkpoint` is a question about the time since
        // the last checkpoint, which nothing between the two calls changes.
        if !self.1.wants_checkpoint() {
            return self.0.on_checkpoint(checkpoint);
        }
        if self.0.wants_checkpoint() {
            self.0.on_checkpoint(checkpoint.clone())?;
        }
        self.1.on_checkpoint(checkpoint)
    }
}

/// Three observers as one: `(a, (b, c))`, each step to a, b, c in turn.
impl<A: Observer, B: Observer, C: Observer> Observer for (A, B, C) {
    fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()> {
        self.0.on_step(view)?;
        self.1.on_step(view)?;
        self.2.on_step(view)
    }

    fn wants_checkpoint(&mut self) -> bool {
        (&mut self.0, (&mut self.1, &mut self.2)).wants_checkpoint()
    }

    fn on_checkpoint(&mut self, checkpoint: ProtocolCheckpoint) -> ControlFlow<()> {
        (&mut self.0, (&mut self.1, &mut self.2)).on_checkpoint(checkpoint)
    }
}

/// An observer that may be absent: `None` sees nothing and never asks for a checkpoint.
impl<O: Observer> Observer for Option<O> {
    fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()> {
        match self {
            Some(observer) => observer.on_step(view),
            None => ControlFlow::Continue(()),
        }
    }

    fn wants_checkpoint(&mut self) -> bool {
        self.as_mut().is_some_and(|observer| observer.wants_checkpoint())
    }

    fn on_checkpoint(&mut self, checkpoint: ProtocolCheckpoint) -> ControlFlow<()> {
        match self {
            Some(observer) => observer.on_checkpoint(checkpoint),
            None => ControlFlow::Continue(()),
        }
    }
}
