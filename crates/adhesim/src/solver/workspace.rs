//! The buffers and preconditioner of the fixed-set CG on one grid ([`Workspace`]), one per
//! level of [`super::NestedActiveSet`]: its fine grid, each coarse level and each contact
//! window. The window (`contact_window.rs`) and the continuation (`nested.rs`) both hold
//! one, and the active-set rounds of `nested.rs` fill it; it lives apart from both so
//! that neither imports the other's.

use super::PcgBuffers;
use crate::elastic::SpectralPreconditioner;
use crate::grid::Grid;

/// Buffers and preconditioner of the fixed-set CG on one grid.
pub(super) struct Workspace {
    pub(super) target: Vec<f64>,
    pub(super) residual: Vec<f64>,
    pub(super) preconditioned: Vec<f64>,
    pub(super) direction: Vec<f64>,
    pub(super) response: Vec<f64>,
    pub(super) mask: Vec<f64>,
    pub(super) preconditioner: SpectralPreconditioner,
}

impl Workspace {
    pub(super) fn new(grid: &Grid, contact_modulus: f64) -> Self {
        let len = grid.len();
        Self {
            target: vec![0.0; len],
            residual: vec![0.0; len],
            preconditioned: vec![0.0; len],
            direction: vec![0.0; len],
            response: vec![0.0; len],
            mask: vec![0.0; len],
            preconditioner: SpectralPreconditioner::new(grid, contact_modulus),
        }
    }

    /// The CG's buffers and the preconditioner, borrowed apart.
    pub(super) fn buffers(&mut self) -> (PcgBuffers<'_>, &mut SpectralPreconditioner) {
        let buffers = PcgBuffers {
            residual: &mut self.residual,
            preconditioned: &mut self.preconditioned,
            direction: &mut self.direction,
            response: &mut self.response,
            mask: &self.mask,
        };
        (buffers, &mut self.preconditioner)
    }
}
