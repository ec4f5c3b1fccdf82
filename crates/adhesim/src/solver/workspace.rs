//! The buffers and preconditioner of the fixed-set CG on one grid ([`Workspace`]): one per
//! level of [`super::NestedActiveSet`] (its fine grid, each coarse level and each contact
//! window), and the JKR-type solver's on its whole grid and on each of its windows. It
//! lives apart from its holders so that none imports another's.

use super::PcgBuffers;
use crate::elastic::SpectralPreconditioner;
use crate::grid::Grid;
use std::ops::Range;

/// Buffers and preconditioner of the fixed-set CG on one grid.
pub(super) struct Workspace {
    /// The displacement the nested levels aim at (empty where unused).
    pub(super) target: Vec<f64>,
    pub(super) residual: Vec<f64>,
    pub(super) preconditioned: Vec<f64>,
    pub(super) direction: Vec<f64>,
    pub(super) response: Vec<f64>,
    pub(super) mask: Vec<f64>,
    /// None where the CG runs unpreconditioned (`AdhesiveParams::preconditioned`).
    pub(super) preconditioner: Option<SpectralPreconditioner>,
    /// Applications of the preconditioner by the nested levels' CG on this workspace.
    pub(super) preconditioner_applications: u64,
}

impl Workspace {
    /// The CG's buffers on `grid`, with the spectral preconditioner planned where
    /// `preconditioned`.
    pub(super) fn new(grid: &Grid, contact_modulus: f64, preconditioned: bool) -> Self {
        let len = grid.len();
        Self {
            target: Vec::new(),
            residual: vec![0.0; len],
            preconditioned: vec![0.0; len],
            direction: vec![0.0; len],
            response: vec![0.0; len],
            mask: vec![0.0; len],
            preconditioner: preconditioned.then(|| SpectralPreconditioner::new(grid, contact_modulus)),
            preconditioner_applications: 0,
        }
    }

    /// The workspace of a level of the nested active set: preconditioned, with its target.
    pub(super) fn with_target(grid: &Grid, contact_modulus: f64) -> Self {
        Self {
            target: vec![0.0; grid.len()],
            ..Self::new(grid, contact_modulus, true)
        }
    }

    /// The CG's buffers and the preconditioner, borrowed apart.
    pub(super) fn buffers(&mut self) -> (PcgBuffers<'_>, Option<&mut SpectralPreconditioner>) {
        let buffers = PcgBuffers {
            residual: &mut self.residual,
            preconditioned: &mut self.preconditioned,
            direction: &mut self.direction,
            response: &mut self.response,
            mask: &self.mask,
        };
        (buffers, self.preconditioner.as_mut())
    }
}

/// M⁻¹r on the grid rows `rows` (of `row_length` elements): the spectral preconditioner's,
/// counted in `applications`, or r itself without one.
pub(super) fn precondition_rows(
    preconditioner: Option<&mut SpectralPreconditioner>,
    (residual, preconditioned): (&[f64], &mut [f64]),
    rows: Range<usize>,
    row_length: usize,
    applications: &mut u64,
) {
    match preconditioner {
        Some(preconditioner) => {
            preconditioner.apply_rows(residual, preconditioned, rows);
            *applications += 1;
        }
        None => {
            let set = rows.start * row_length..rows.end * row_length;
            preconditioned[set.clone()].copy_from_slice(&residual[set]);
        }
    }
}
