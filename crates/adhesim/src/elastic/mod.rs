//! Linear elastic half-space: pressure → normal surface displacement; shear traction →
//! tangential surface displacement ([`TangentialOperator`]); the coupling of the two at
//! ν < 1/2 ([`CouplingOperator`]).
//!
//! Sign convention: pressure p > 0 is compressive, displacement u > 0 points into the
//! body. Both operators discretise Boussinesq's solution with uniform pressure on square
//! elements and collocation at element centres.

mod backend;
mod bessel;
pub mod cerruti;
mod coupling;
mod free;
pub mod influence;
mod layer;
mod layer_coupling;
mod layer_shear;
mod layer_tables;
#[cfg(test)]
mod layer_tables_shipped;
mod periodic;
pub(crate) mod planner;
mod preconditioner;
mod shear_compliance;
mod spectral;
mod tangential;
mod tangential_periodic;
#[cfg(test)]
pub(crate) mod test_fields;

pub use backend::Backend;
pub use coupling::{coupling_rectangle, CouplingOperator};
pub use free::FreeOperator;
pub use layer::{layer_compliance_factor, ElasticLayer, LayerBase, LayerError, LayerOperator};
pub use layer_shear::{layer_coupling_ratio, layer_longitudinal_factor, layer_transverse_factor};
pub use periodic::{PeriodicKernel, PeriodicOperator};
pub use preconditioner::SpectralPreconditioner;
pub use shear_compliance::{CouplingCompliance, ShearCompliance};
pub use tangential::{ShearBody, TangentialOperator, TangentialOperatorError};

use crate::grid::{Boundary, Grid};
use crate::material::ElasticMaterial;
use std::ops::Range;

/// Matrix-free, symmetric positive (semi-)definite compliance operator u = K p.
pub trait ElasticOperator: Send {
    /// The grid the operator acts on.
    fn grid(&self) -> &Grid;

    /// Contact modulus E* of the half-space.
    fn contact_modulus(&self) -> f64;

    /// Writes u = K p. Both slices hold one value per element, row-major.
    ///
    /// # Panics
    /// If a slice length differs from the number of elements.
    fn apply(&mut self, pressure: &[f64], displacement: &mut [f64]);

    /// Writes u ≈ K p with the transforms done in single precision (error ≈ 1e-7 of
    /// max|u|, about 40 % cheaper). For the search directions of iterative solvers, whose
    /// rounding only perturbs the iteration: the solution is always checked against a
    /// residual from [`apply`](Self::apply). The default is the exact `apply`.
    fn apply_single(&mut self, pressure: &[f64], displacement: &mut [f64]) {
        self.apply(pressure, displacement);
    }

    /// [`apply_single`](Self::apply_single) for a pressure that is zero outside the grid
    /// rows `input_rows` (its values there are not read), writing the displacement on the
    /// rows `output_rows` only. On those rows the result is bit for bit what `apply_single`
    /// gives: the transforms of rows that are zero are exactly zero and are skipped (issue
    /// a fixed-set CG's search direction lives on the set's bounding box, docs/fast-step.md).
    /// Values outside `output_rows` are unspecified (the spectral operators leave them
    /// untouched, this default writes them): callers must not read them. Counts as one
    /// application.
    ///
    /// # Panics
    /// If a slice length differs from the number of elements or a range exceeds the rows.
    fn apply_single_rows(
        &mut self,
        pressure: &[f64],
        displacement: &mut [f64],
        input_rows: Range<usize>,
        output_rows: Range<usize>,
    ) {
        let _ = (input_rows, output_rows);
        self.apply_single(pressure, displacement);
    }

    /// Diagonal entry K(0,0): displacement of an element under its own unit pressure.
    fn self_compliance(&self) -> f64;

    /// The same operator on a free grid of `side` × `side` elements of this grid's size:
    /// where the kernel depends on the offset between two elements only and has no images
    /// (a free half-space), its restriction to any window of that side. A fixed-set CG on
    /// a contact inside such a window then transforms twice the window's side instead of
    /// twice the grid's. None (the default) where the operator has no such restriction.
    fn window_operator(&self, side: usize) -> Option<Box<dyn ElasticOperator + Sync>> {
        let _ = side;
        None
    }

    /// Number of applications so far (each is one forward+inverse FFT pair, in double or
    /// single precision).
    fn applications(&self) -> u64;

    /// The backend that computes this operator: the interface's tangential and coupling
    /// operators of a run are built by the same one ([`Backend::shear_operator`]).
    fn backend(&self) -> Backend {
        Backend::Cpu
    }
}

/// The half-space operator of either boundary kind, chosen by the grid's [`Boundary`].
pub enum HalfSpace {
    /// Non-periodic, DC-FFT.
    Free(FreeOperator),
    /// Periodic, element-consistent kernel.
    Periodic(PeriodicOperator),
}

impl HalfSpace {
    /// Builds the operator that matches `grid.boundary()` (plans FFTs and computes the
    /// kernel spectrum once).
    pub fn new(grid: Grid, material: ElasticMaterial) -> Self {
        match grid.boundary() {
            Boundary::Free => Self::Free(FreeOperator::new(grid, material)),
            Boundary::Periodic => {
                Self::Periodic(PeriodicOperator::new(grid, material, PeriodicKernel::ElementConsistent))
            }
        }
    }

    fn inner(&self) -> &dyn ElasticOperator {
        match self {
            Self::Free(op) => op,
            Self::Periodic(op) => op,
        }
    }
}

impl ElasticOperator for HalfSpace {
    fn grid(&self) -> &Grid {
        self.inner().grid()
    }
    fn contact_modulus(&self) -> f64 {
        self.inner().contact_modulus()
    }
    fn apply(&mut self, pressure: &[f64], displacement: &mut [f64]) {
        match self {
            Self::Free(op) => op.apply(pressure, displacement),
            Self::Periodic(op) => op.apply(pressure, displacement),
        }
    }
    fn apply_single(&mut self, pressure: &[f64], displacement: &mut [f64]) {
        match self {
            Self::Free(op) => op.apply_single(pressure, displacement),
            Self::Periodic(op) => op.apply_single(pressure, displacement),
        }
    }
    fn apply_single_rows(
        &mut self,
        pressure: &[f64],
        displacement: &mut [f64],
        input_rows: Range<usize>,
        output_rows: Range<usize>,
    ) {
        match self {
            Self::Free(op) => op.apply_single_rows(pressure, displacement, input_rows, output_rows),
            Self::Periodic(op) => op.apply_single_rows(pressure, displacement, input_rows, output_rows),
        }
    }
    fn self_compliance(&self) -> f64 {
        self.inner().self_compliance()
    }
    fn window_operator(&self, side: usize) -> Option<Box<dyn ElasticOperator + Sync>> {
        self.inner().window_operator(side)
    }
    fn applications(&self) -> u64 {
        self.inner().applications()
    }
}
