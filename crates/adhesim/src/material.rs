//! Elastic material of the half-space and the work of adhesion of the interface.

use crate::grid::Grid;
use thiserror::Error;

/// Errors for invalid material or adhesion parameters.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum MaterialError {
    /// E* must be finite and positive.
    #[error("contact modulus must be finite and > 0, got {0}")]
    InvalidContactModulus(f64),
    /// Young's modulus must be finite and positive.
    #[error("Young's modulus must be finite and > 0, got {0}")]
    InvalidYoungsModulus(f64),
    /// Poisson's ratio must lie in (−1, 0.5].
    #[error("Poisson's ratio must lie in (-1, 0.5], got {0}")]
    InvalidPoissonRatio(f64),
    /// The work of adhesion must be finite and non-negative.
    #[error("work of adhesion must be finite and >= 0, got {0}")]
    InvalidWorkOfAdhesion(f64),
    /// The ratio of the quadratic adhesion profile must be positive.
    #[error("end-to-middle ratio of the adhesion profile must be finite and > 0, got {0}")]
    InvalidRatio(f64),
    /// A map of the work of adhesion must have one value per element.
    #[error("work-of-adhesion map has {got} values, the grid has {expected} elements")]
    MapSize {
        /// Elements of the grid.
        expected: usize,
        /// Values in the map.
        got: usize,
    },
}

/// Linear elastic half-space, characterised by its contact modulus E*.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElasticMaterial {
    contact_modulus: f64,
}

impl ElasticMaterial {
    /// A half-space of contact modulus E* (against a rigid indenter).
    pub fn new(contact_modulus: f64) -> Result<Self, MaterialError> {
        if !(contact_modulus.is_finite() && contact_modulus > 0.0) {
            return Err(MaterialError::InvalidContactModulus(contact_modulus));
        }
        Ok(Self { contact_modulus })
    }

    /// E* = E/(1 − ν²) from Young's modulus and Poisson's ratio.
    ///
    /// # Example
    /// ```
    /// use adhesim::ElasticMaterial;
    ///
    /// // Rubber: E = 3, ν = 1/2 gives E* = E/(1 − ν²) = 4.
    /// let rubber = ElasticMaterial::from_youngs_modulus(3.0, 0.5)?;
    /// assert!((rubber.contact_modulus() - 4.0).abs() < 1e-15);
    /// assert!(ElasticMaterial::from_youngs_modulus(3.0, 0.6).is_err());
    /// # Ok::<(), adhesim::MaterialError>(())
    /// ```
    pub fn from_youngs_modulus(youngs_modulus: f64, poisson_ratio: f64) -> Result<Self, MaterialError> {
        if !(youngs_modulus.is_finite() && youngs_modulus > 0.0) {
            return Err(MaterialError::InvalidYoungsModulus(youngs_modulus));
        }
        if !(poisson_ratio > -1.0 && poisson_ratio <= 0.5) {
            return Err(MaterialError::InvalidPoissonRatio(poisson_ratio));
        }
        Self::new(youngs_modulus / (1.0 - poisson_ratio * poisson_ratio))
    }

    /// Two elastic bodies: 1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2.
    pub fn from_two_bodies(first: (f64, f64), second: (f64, f64)) -> Result<Self, MaterialError> {
        let a = Self::from_youngs_modulus(first.0, first.1)?.contact_modulus;
        let b = Self::from_youngs_modulus(second.0, second.1)?.contact_modulus;
        Self::new(1.0 / (1.0 / a + 1.0 / b))
    }

    /// The contact modulus E*.
    pub fn contact_modulus(&self) -> f64 {
        self.contact_modulus
    }
}

/// Lateral axis along which a heterogeneous work of adhesion varies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    /// Along x (columns).
    X,
    /// Along y (rows).
    Y,
}

/// Work of adhesion γ (energy per unit area) of the interface, possibly varying in space.
#[derive(Debug, Clone, PartialEq)]
pub enum WorkOfAdhesion {
    /// The same γ0 everywhere.
    Uniform(f64),
    /// γ(s) = γ_mid·[1 + (k − 1)(s/half_length)²] along `axis` (s measured from the origin),
    /// k = `ratio_end_to_middle`: the paper's Fig. 12 heterogeneity.
    Quadratic {
        /// γ at the centre line.
        middle: f64,
        /// γ(±half_length)/γ(0).
        ratio_end_to_middle: f64,
        /// Distance from the centre at which the ratio is reached.
        half_length: f64,
        /// Direction of variation.
        axis: Axis,
    },
    /// One value per element, row-major.
    Map(Vec<f64>),
}

impl WorkOfAdhesion {
    /// The reference value γ0 used for JKR normalisation (uniform value, centre value,
    /// or the mean of a map).
    pub fn reference(&self) -> f64 {
        match self {
            Self::Uniform(gamma) => *gamma,
            Self::Quadratic { middle, .. } => *middle,
            Self::Map(values) => values.iter().sum::<f64>() / values.len().max(1) as f64,
        }
    }

    /// Checks the parameters and evaluates γ at every element centre of `grid`.
    pub fn on_grid(&self, grid: &Grid) -> Result<Vec<f64>, MaterialError> {
        let check = |gamma: f64| {
            if gamma.is_finite() && gamma >= 0.0 {
                Ok(gamma)
            } else {
                Err(MaterialError::InvalidWorkOfAdhesion(gamma))
            }
        };
        match self {
            Self::Uniform(gamma) => Ok(vec![check(*gamma)?; grid.len()]),
            Self::Quadratic {
                middle,
                ratio_end_to_middle,
                half_length,
                axis,
            } => {
                check(*middle)?;
                if !(ratio_end_to_middle.is_finite() && *ratio_end_to_middle > 0.0) {
                    return Err(MaterialError::InvalidRatio(*ratio_end_to_middle));
                }
                Ok((0..grid.len())
                    .map(|k| {
                        let (x, y) = grid.centre(k);
                        let s = match axis {
                            Axis::X => x,
                            Axis::Y => y,
                        } / half_length;
                        middle * (1.0 + (ratio_end_to_middle - 1.0) * s * s)
                    })
                    .collect())
            }
            Self::Map(values) => {
                if values.len() != grid.len() {
                    return Err(MaterialError::MapSize {
                        expected: grid.len(),
                        got: values.len(),
                    });
                }
                values.iter().map(|&gamma| check(gamma)).collect()
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::Boundary;

    #[test]
    fn contact_modulus_from_youngs_modulus() {
        let material = ElasticMaterial::from_youngs_modulus(3.0, 0.5).unwrap();
        assert!((material.contact_modulus() - 4.0).abs() < 1e-15);
        assert!(ElasticMaterial::from_youngs_modulus(1.0, 0.7).is_err());
        assert!(ElasticMaterial::new(-1.0).is_err());
        let two = ElasticMaterial::from_two_bodies((3.0, 0.5), (3.0, 0.5)).unwrap();
        assert!((two.contact_modulus() - 2.0).abs() < 1e-15);
    }

    #[test]
    fn quadratic_adhesion_reaches_its_ratio() {
        let grid = Grid::new(8, 8.0, Boundary::Free).unwrap();
        let field = WorkOfAdhesion::Quadratic {
            middle: 2.0,
            ratio_end_to_middle: 20.0,
            half_length: 3.0,
            axis: Axis::X,
        };
        let values = field.on_grid(&grid).unwrap();
        // column 4 is x = 0, column 7 is x = 3
        assert_eq!(values[4], 2.0);
        assert!((values[7] - 40.0).abs() < 1e-12);
        assert!(WorkOfAdhesion::Uniform(-1.0).on_grid(&grid).is_err());
        assert!(WorkOfAdhesion::Map(vec![1.0; 3]).on_grid(&grid).is_err());
    }
}
