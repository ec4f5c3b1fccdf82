//! The compute-backend seam: the operators of a run are built here, by the backend that
//! will run them: the normal operator, and the interface's tangential and coupling
//! operators. The CPU (rustfft and realfft transforms planned by `planner.rs`, rayon's
//! threads) is the only backend built; a device backend is one more variant and an
//! implementation of [`ElasticOperator`], [`ShearCompliance`] and [`CouplingCompliance`]
//! (ARCHITECTURE.md, "Compute backends").

use super::{
    CouplingCompliance, CouplingOperator, ElasticLayer, ElasticOperator, HalfSpace, LayerError, LayerOperator,
    ShearBody, ShearCompliance, TangentialOperator, TangentialOperatorError,
};
use crate::grid::Grid;
use crate::material::ElasticMaterial;

/// Where a run's elastic operators compute.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum Backend {
    /// The host's cores: transforms by rustfft/realfft, vectors on rayon's threads.
    #[default]
    Cpu,
}

impl Backend {
    /// The normal operator u = K p of a body on `grid` (free or periodic, as the grid
    /// says): the elastic half-space of `material`, or a layer of it on its base.
    ///
    /// # Errors
    /// A layer the layer operator refuses ([`LayerOperator::new`]).
    ///
    /// # Examples
    /// The half-space's response to a unit pressure on one element is its largest at
    /// that element.
    /// ```
    /// use adhesim::{Backend, Boundary, ElasticMaterial, Grid};
    ///
    /// let grid = Grid::new(16, 1.0, Boundary::Free)?;
    /// let mut operator = Backend::Cpu.normal_operator(grid, ElasticMaterial::new(1.0)?, None)?;
    /// let mut pressure = vec![0.0; grid.len()];
    /// pressure[8 * 16 + 8] = 1.0;
    /// let mut displacement = vec![0.0; grid.len()];
    /// operator.apply(&pressure, &mut displacement);
    /// let largest = displacement.iter().cloned().fold(0.0, f64::max);
    /// assert_eq!(largest, displacement[8 * 16 + 8]);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn normal_operator(
        self,
        grid: Grid,
        material: ElasticMaterial,
        layer: Option<ElasticLayer>,
    ) -> Result<Box<dyn ElasticOperator>, LayerError> {
        match self {
            Self::Cpu => Ok(match layer {
                Some(layer) => Box::new(LayerOperator::new(grid, material, layer)?),
                None => Box::new(HalfSpace::new(grid, material)),
            }),
        }
    }

    /// The tangential operator (u_x, u_y) = K (q_x, q_y) of `body` on `grid`: Cerruti's
    /// half-space, or the bonded layer's shear compliance.
    ///
    /// # Errors
    /// A material or layer the operator refuses ([`TangentialOperator::for_body`]).
    ///
    /// # Examples
    /// A unit traction along x on one element moves that element along x by its own
    /// compliance.
    /// ```
    /// use adhesim::{Backend, Boundary, Grid, ShearMaterial};
    ///
    /// let grid = Grid::new(16, 1.0, Boundary::Free)?;
    /// let body = ShearMaterial::from_contact_modulus(4.0, 0.5).into();
    /// let mut operator = Backend::Cpu.shear_operator(grid, body)?;
    /// let mut qx = vec![0.0; grid.len()];
    /// qx[8 * 16 + 8] = 1.0;
    /// let qy = vec![0.0; grid.len()];
    /// let (mut ux, mut uy) = (vec![0.0; grid.len()], vec![0.0; grid.len()]);
    /// operator.apply([&qx, &qy], [&mut ux, &mut uy]);
    /// assert!((ux[8 * 16 + 8] / operator.self_compliance() - 1.0).abs() < 1e-9);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn shear_operator(
        self,
        grid: Grid,
        body: ShearBody,
    ) -> Result<Box<dyn ShearCompliance>, TangentialOperatorError> {
        match self {
            Self::Cpu => Ok(Box::new(TangentialOperator::for_body(grid, body)?)),
        }
    }

    /// The normal–tangential coupling of `body` on `grid` (zero on a half-space at
    /// ν = 1/2, not on a layer).
    ///
    /// # Errors
    /// A material or layer the operator refuses ([`CouplingOperator::for_body`]).
    pub fn coupling_operator(
        self,
        grid: Grid,
        body: ShearBody,
    ) -> Result<Box<dyn CouplingCompliance>, TangentialOperatorError> {
        match self {
            Self::Cpu => Ok(Box::new(CouplingOperator::for_body(grid, body)?)),
        }
    }
}
