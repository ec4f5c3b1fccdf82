//! The interface's operators as the tangential solver and the coupled step apply them,
//! whatever computes them: the shear tractions' tangential displacements
//! ([`ShearCompliance`]) and the normal–tangential coupling ([`CouplingCompliance`]). The
//! CPU's are [`TangentialOperator`] and [`CouplingOperator`]; a device backend implements
//! both beside its [`ElasticOperator`](super::ElasticOperator) (ARCHITECTURE.md, "Compute
//! backends"), and [`Backend`](super::Backend) builds them.

use super::{CouplingOperator, TangentialOperator};
use crate::grid::Grid;

/// Shear tractions → tangential surface displacements, (u_x, u_y) = K (q_x, q_y).
pub trait ShearCompliance: Send {
    /// The grid the operator acts on.
    fn grid(&self) -> &Grid;

    /// K_xx(0,0): the tangential displacement of an element under its own unit traction.
    fn self_compliance(&self) -> f64;

    /// Writes (u_x, u_y) = K (q_x, q_y); each slice holds one value per element, row-major.
    fn apply(&mut self, traction: [&[f64]; 2], displacement: [&mut [f64]; 2]);

    /// Forward + inverse transform pairs done so far.
    fn transform_pairs(&self) -> u64;
}

/// The normal–tangential coupling of a compressible body (ν < 1/2) or a layer
/// (docs/physics.md §8.1a, §9.5).
pub trait CouplingCompliance: Send {
    /// The grid the operator acts on.
    fn grid(&self) -> &Grid;

    /// Writes u_z = K_zx∗q_x + K_zy∗q_y: the normal displacement (into the body) of the
    /// shear tractions on the body.
    fn normal_from_shear(&mut self, traction: [&[f64]; 2], normal: &mut [f64]);

    /// Writes (u_x, u_y) = −(K_zx∗p, K_zy∗p): the tangential displacement of the pressure.
    fn shear_from_normal(&mut self, pressure: &[f64], displacement: [&mut [f64]; 2]);

    /// Forward + inverse transform pairs done so far.
    fn transform_pairs(&self) -> u64;
}

impl ShearCompliance for TangentialOperator {
    fn grid(&self) -> &Grid {
        TangentialOperator::grid(self)
    }

    fn self_compliance(&self) -> f64 {
        TangentialOperator::self_compliance(self)
    }

    fn apply(&mut self, traction: [&[f64]; 2], displacement: [&mut [f64]; 2]) {
        TangentialOperator::apply(self, traction, displacement);
    }

    fn transform_pairs(&self) -> u64 {
        TangentialOperator::transform_pairs(self)
    }
}

impl CouplingCompliance for CouplingOperator {
    fn grid(&self) -> &Grid {
        CouplingOperator::grid(self)
    }

    fn normal_from_shear(&mut self, traction: [&[f64]; 2], normal: &mut [f64]) {
        CouplingOperator::normal_from_shear(self, traction, normal);
    }

    fn shear_from_normal(&mut self, pressure: &[f64], displacement: [&mut [f64]; 2]) {
        CouplingOperator::shear_from_normal(self, pressure, displacement);
    }

    fn transform_pairs(&self) -> u64 {
        CouplingOperator::transform_pairs(self)
    }
}
