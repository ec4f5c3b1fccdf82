//! What a [`NestedActiveSet`] carries from one solve to the next, taken between solves and
//! put back into a fresh solver of the same problem (mid-run checkpoints of a protocol,
//! directly or inside a [`CohesiveSolver`](crate::solver::CohesiveSolver)).
//!
//! Carried (saved):
//! - the side of each level's contact window, the fine level's and each coarse level's: a
//!   window is reused while its side is between the side needed and twice it
//!   ([`WindowLevel::enter`]), so the side kept decides the side used, hence the window
//!   pre-solve's arithmetic and the pressures the full grid's rounds start from;
//! - `last_depth`, which decides whether a warm start is an unload (then a cold start
//!   through the coarse levels);
//! - whether each coarse level had built its whole-level operator (rebuilt, not saved: it
//!   changes no number, only when its planning is paid);
//! - the operator-application counters of the last solve (reported by
//!   [`NestedActiveSet::coarse_applications`] and
//!   [`NestedActiveSet::window_applications`]; every solve zeroes them first).
//!
//! Not carried, by reading the code (and checked by the bit-identical resume tests in
//! `tests/integration/checkpoint.rs`, which restore into a fresh solver whose buffers are
//! all zero):
//! - a window's position: [`WindowLevel::enter`] places it on the contact before use;
//! - a window's and a coarse level's heights, contact and pressure: `enter` copies the
//!   whole window's from the level, `restrict` writes every coarse height, and `cold_start`
//!   (the coarsest level) or `prolong` (the others) writes every coarse contact flag and
//!   pressure before any is read; the coarse levels run only on a cold start, so their
//!   states are not warm starts from one solve to the next;
//! - every displacement of a level or window: each active-set round applies the operator
//!   (or zeroes it) before reading it;
//! - the workspaces' vectors: `solve_level` writes the target and, each round, the mask and
//!   the residual; `masked_pcg` zeroes the preconditioned and search directions outside the
//!   set's rows and writes them within, and the operator writes every response row;
//! - operators and preconditioners: built from the geometry alone (their application
//!   counters are only read as differences).

use super::NestedActiveSet;
use crate::elastic::FreeOperator;
use crate::solver::contact_window::WindowLevel;
use crate::solver::workspace::Workspace;

/// A coarse level's part of a [`NestedCheckpoint`].
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct LevelCheckpoint {
    /// Side (elements) of the level's contact window, if it had one.
    window: Option<usize>,
    /// Whether the level had built its whole-level operator.
    full: bool,
}

/// The state of a [`NestedActiveSet`] between two solves (see the module text).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct NestedCheckpoint {
    elements: usize,
    /// The coarse levels, finest first.
    levels: Vec<LevelCheckpoint>,
    /// Side of the fine level's contact window, if it had one.
    fine_window: Option<usize>,
    last_depth: Option<f64>,
    coarse_applications: u64,
    window_applications: u64,
}

impl NestedActiveSet {
    /// The state this solver carries into its next solve.
    pub fn checkpoint(&self) -> NestedCheckpoint {
        NestedCheckpoint {
            elements: self.grid.len(),
            levels: self
                .coarse
                .iter()
                .map(|level| LevelCheckpoint {
                    window: level.window.as_ref().map(WindowLevel::side),
                    full: level.full.is_some(),
                })
                .collect(),
            fine_window: self.fine_window.as_ref().map(WindowLevel::side),
            last_depth: self.last_depth,
            coarse_applications: self.coarse_applications,
            window_applications: self.window_applications,
        }
    }

    /// Puts back the state of `checkpoint` (taken by a solver of the same grid, material
    /// and parameters). An error (nothing changed) when it is of another grid, another
    /// number of levels, or a window does not fit its level.
    pub fn restore(&mut self, checkpoint: &NestedCheckpoint) -> Result<(), String> {
        let len = self.grid.len();
        let mismatch = || {
            format!(
                "the nested solver's checkpoint is of {} elements and {} coarse levels (or malformed), \
                 the grid has {len} elements and {} coarse levels",
                checkpoint.elements,
                checkpoint.levels.len(),
                self.coarse.len()
            )
        };
        if checkpoint.elements != len
            || checkpoint.levels.len() != self.coarse.len()
            || checkpoint.last_depth.is_some_and(|depth| !depth.is_finite())
        {
            return Err(mismatch());
        }
        let material = self.material;
        let window = |grid, side: Option<usize>| match side {
            None => Ok(None),
            Some(side) => WindowLevel::restored(grid, material, side)
                .map(Some)
                .ok_or_else(mismatch),
        };
        // Every window is made before anything changes.
        let fine_window = window(&self.grid, checkpoint.fine_window)?;
        let coarse_windows = self
            .coarse
            .iter()
            .zip(&checkpoint.levels)
            .map(|(level, saved)| window(&level.grid, saved.window))
            .collect::<Result<Vec<_>, _>>()?;
        self.fine_window = fine_window;
        for ((level, saved), window) in self.coarse.iter_mut().zip(&checkpoint.levels).zip(coarse_windows) {
            level.window = window;
            if !saved.full {
                level.full = None;
            } else if level.full.is_none() {
                level.full = Some((
                    FreeOperator::new(level.grid, material),
                    Workspace::with_target(&level.grid, material.contact_modulus()),
                ));
            }
        }
        self.last_depth = checkpoint.last_depth;
        self.coarse_applications = checkpoint.coarse_applications;
        self.window_applications = checkpoint.window_applications;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Profile, Sphere};
    use crate::grid::{Boundary, Grid};
    use crate::material::ElasticMaterial;
    use crate::solver::{ContactState, NestedParams};

    /// A solver on an n × n free grid after a Hertz solve at depth 1e-3 (windows in use).
    fn solved(n: usize) -> NestedActiveSet {
        let grid = Grid::new(n, 0.45, Boundary::Free).unwrap();
        let material = ElasticMaterial::new(1.0).unwrap();
        let mut solver = NestedActiveSet::new(grid, material, NestedParams::default());
        let heights = Sphere::new(1.0).unwrap().heights(&grid);
        let mut state = ContactState::new(&grid);
        solver
            .solve(&mut FreeOperator::new(grid, material), &heights, 1e-3, &mut state)
            .unwrap();
        solver
    }

    /// A checkpoint of another grid, or whose window would not fit its level, is refused
    /// and leaves the solver as it was; one of the same grid is taken back as saved.
    #[test]
    fn restore_checks_the_grid_and_the_windows() {
        let saved = solved(64).checkpoint();
        assert!(saved.fine_window.is_some() && saved.levels[0].window.is_some());
        assert!(saved.last_depth == Some(1e-3) && saved.window_applications > 0);
        let mut other = solved(32);
        let before = other.checkpoint();
        assert!(other.restore(&saved).unwrap_err().contains("checkpoint"));
        assert_eq!(other.checkpoint(), before, "nothing changed");
        let mut fresh = solved(64);
        let mut too_wide = saved.clone();
        too_wide.levels[0].window = Some(33);
        let before = fresh.checkpoint();
        assert!(fresh.restore(&too_wide).is_err());
        assert_eq!(fresh.checkpoint(), before, "nothing changed");
        let mut changed = saved.clone();
        changed.fine_window = None;
        changed.last_depth = Some(2e-3);
        fresh.restore(&changed).unwrap();
        assert_eq!(fresh.checkpoint(), changed);
        fresh.restore(&saved).unwrap();
        assert_eq!(fresh.checkpoint(), saved);
    }
}
