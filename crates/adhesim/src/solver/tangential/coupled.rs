//! The pressure's share of the tangential displacement (the coupled operator,
//! `friction.coupling = "full"`; docs/physics.md §8.1).

use super::{StepHistory, TangentialError, TangentialSolver, TangentialState};

impl TangentialSolver {
    /// Sets the tangential displacement c = K_tz p that the step's pressure gives the
    /// surface (the coupled operator, `friction.coupling = "full"`; docs/physics.md §8.1),
    /// or clears it (None). The steps then hold the total tangential displacement
    /// u = K q + c: an element sticks when u is its last step's plus the shift increment,
    /// so the shear tractions answer the pressure's pull as well as the shift.
    /// [`TangentialState::displacement`] holds u.
    pub fn set_pressure_displacement(&mut self, displacement: Option<[&[f64]; 2]>) {
        for (c, stored) in self.pressure_displacement.iter_mut().enumerate() {
            stored.clear();
            if let Some(displacement) = displacement {
                stored.extend_from_slice(displacement[c]);
            }
        }
    }

    /// Adds c to the step's displacements K q: the memory of the next step is the total.
    pub(super) fn add_pressure_displacement(&self, state: &mut TangentialState) {
        for (total, coupled) in state.displacement.iter_mut().zip(&self.pressure_displacement) {
            for (u, c) in total.iter_mut().zip(coupled) {
                *u += c;
            }
        }
    }

    /// A pressure displacement set for another number of elements than `elements`.
    pub(super) fn check_pressure_displacement(&self, elements: usize) -> Result<(), TangentialError> {
        match self.pressure_displacement[0].len() {
            0 => Ok(()),
            got if got == elements => Ok(()),
            got => Err(TangentialError::GridMismatch {
                expected: elements,
                got,
            }),
        }
    }

    /// Forgets the predictor's memory, and returns it: a step restarted from a better
    /// guess than the last step's (a coupled round after the first) must not be
    /// extrapolated, and a step settled in rounds at one drive position (a translation's
    /// profile following its indenter) keeps its first round's, the drive's move, not a
    /// later round's tiny one.
    pub(crate) fn forget_predictor(&mut self) -> Option<StepHistory> {
        self.history.take()
    }

    /// The predictor's memory of a whole step from the tractions `before` at its start
    /// with the drive's `increment`, as one uninterrupted step leaves it.
    pub(crate) fn remember_step(&mut self, before: &[Vec<f64>; 2], increment: [f64; 2]) {
        self.history = Some((before.clone(), increment));
    }
}
