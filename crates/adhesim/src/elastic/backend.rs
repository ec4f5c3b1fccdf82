//! The compute-backend seam: the normal operator of a run is built here, by the backend
//! that will run it. The CPU (rustfft and realfft transforms planned by `planner.rs`,
//! rayon's threads) is the only backend built; a device backend is one more variant and
//! an implementation of [`ElasticOperator`] (ARCHITECTURE.md, "Compute backends").

use super::{ElasticLayer, ElasticOperator, HalfSpace, LayerError, LayerOperator};
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
}
