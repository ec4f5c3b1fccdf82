//! What a [`CohesiveSolver`] carries from one step to the next, taken between steps and
//! put back into a fresh solver of the same problem (mid-run checkpoints of a protocol).
//!
//! Carried (saved): the tractions of the last round (`traction`: the first round of the
//! next step applies them, and its largest change is measured from them; they also give
//! the zone and its border flag after the step), the compressive part's state (pressure,
//! displacement and contact of q: the warm start of the compressive solve) and the
//! compressive solver's own history ([`NestedCheckpoint`] for the nested active set;
//! nothing for CCG, whose buffers are cleared at every solve).
//!
//! Not carried, by reading `step_probed`, `round`, `solve_compressive`, `update_traction`
//! and `converge_anderson`: `start_contact` (copied from the protocol's state at the start
//! of a step), `tensile_pressure`, `tensile_displacement` and `shifted_heights` (each
//! round writes them from `traction` before reading them; the energies read
//! `tensile_pressure` only after a round), and the Anderson memory, which lives in one
//! step (`converge_anderson` starts each with an empty history). The law holds no state.

use super::{CohesiveSolver, Compressive};
use crate::solver::{ContactState, NestedCheckpoint};

/// The compressive solver's part of a [`CohesiveCheckpoint`].
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
enum CompressiveCheckpoint {
    /// Polonsky–Keer CCG: nothing between solves.
    Ccg,
    /// The nested active set's windows and last depth.
    Nested(NestedCheckpoint),
}

/// The state of a [`CohesiveSolver`] between two steps (see the module text).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CohesiveCheckpoint {
    elements: usize,
    traction: Vec<f64>,
    compressive_state: ContactState,
    compressive: CompressiveCheckpoint,
}

impl CohesiveSolver {
    /// The state this solver carries into its next step.
    pub fn checkpoint(&self) -> CohesiveCheckpoint {
        CohesiveCheckpoint {
            elements: self.grid.len(),
            traction: self.traction.clone(),
            compressive_state: self.compressive_state.clone(),
            compressive: match &self.compressive {
                Compressive::Ccg(_) => CompressiveCheckpoint::Ccg,
                Compressive::Nested(solver) => CompressiveCheckpoint::Nested(solver.checkpoint()),
            },
        }
    }

    /// Puts back the state of `checkpoint` (taken by a solver of the same grid, law and
    /// parameters). An error (nothing changed) when it is of another grid size or of the
    /// other compressive solver.
    pub fn restore(&mut self, checkpoint: &CohesiveCheckpoint) -> Result<(), String> {
        let len = self.grid.len();
        let c = checkpoint;
        let state = &c.compressive_state;
        if c.elements != len
            || c.traction.len() != len
            || state.pressure.len() != len
            || state.displacement.len() != len
            || state.contact.len() != len
        {
            return Err(format!(
                "the cohesive solver's checkpoint is of {} elements (or malformed), the grid has {len}",
                c.elements
            ));
        }
        match (&mut self.compressive, &c.compressive) {
            (Compressive::Ccg(_), CompressiveCheckpoint::Ccg) => {}
            (Compressive::Nested(solver), CompressiveCheckpoint::Nested(saved)) => solver.restore(saved)?,
            _ => {
                return Err(
                    "the cohesive solver's checkpoint is of the other compressive solver (nested active set or CCG)"
                        .to_string(),
                )
            }
        }
        self.traction.copy_from_slice(&c.traction);
        self.compressive_state.clone_from(state);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::{Boundary, Grid};
    use crate::material::ElasticMaterial;
    use crate::solver::{CohesiveParams, Dugdale};

    fn solver(n: usize) -> CohesiveSolver {
        let grid = Grid::new(n, 0.3, Boundary::Free).unwrap();
        let law = Dugdale::new(0.04, vec![1e-4; grid.len()]);
        CohesiveSolver::new(
            grid,
            ElasticMaterial::new(1.0).unwrap(),
            Box::new(law),
            CohesiveParams::default(),
        )
    }

    /// A checkpoint of another grid size is refused, naming both sizes, and changes nothing.
    #[test]
    fn a_checkpoint_of_another_grid_is_refused() {
        let mut saved = solver(32).checkpoint();
        saved.traction[5] = 0.04;
        let mut other = solver(16);
        let before = other.checkpoint();
        let error = other.restore(&saved).unwrap_err();
        assert!(error.contains("1024") && error.contains("256"), "{error}");
        assert_eq!(other.checkpoint(), before);
        let mut same = solver(32);
        same.restore(&saved).unwrap();
        assert_eq!(same.checkpoint(), saved);
    }
}
