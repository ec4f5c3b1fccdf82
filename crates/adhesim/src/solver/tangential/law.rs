//! Interface laws: the largest shear traction an element in contact can carry.

use thiserror::Error;

/// A friction law's bound on |q| per contact element.
///
/// # Example
/// ```
/// use adhesim::FrictionLaw;
///
/// // Coulomb's bound is μ times the compressive pressure; a tensile element carries none.
/// let coulomb = FrictionLaw::coulomb(0.3)?;
/// assert_eq!(coulomb.bound(2.0), 0.6);
/// assert_eq!(coulomb.bound(-1.0), 0.0);
/// // A shear strength bounds every contact element, tensile ones included.
/// let tresca = FrictionLaw::shear_strength(0.05)?;
/// assert_eq!(tresca.bound(-1.0), 0.05);
/// assert_eq!(FrictionLaw::NoSlip.bound(0.0), f64::INFINITY);
/// assert!(FrictionLaw::coulomb(-0.1).is_err());
/// # Ok::<(), adhesim::FrictionLawError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FrictionLaw {
    /// Coulomb: |q| ≤ μ·max(p, 0). With adhesion, only compressive pressure bounds the
    /// traction: a tensile element (the adhesive edge of a JKR-type contact) carries no
    /// shear and slips freely (docs/physics.md §8.2).
    Coulomb {
        /// μ.
        coefficient: f64,
    },
    /// Constant shear strength (Tresca; the paper's area friction, Eqs. 16–18):
    /// |q| ≤ τ0 in every contact element, tensile ones included.
    ShearStrength {
        /// τ0.
        shear_strength: f64,
    },
    /// Both: |q| ≤ max(τ0 + μp, 0).
    CoulombShear {
        /// μ.
        coefficient: f64,
        /// τ0.
        shear_strength: f64,
    },
    /// No slip: the body is glued to the indenter, every contact element moving with its
    /// shift whatever its traction, an element that touches again included (Mindlin's fully
    /// stuck contact; the reversible contact of Savkoor & Briggs' energy balance under shear).
    NoSlip,
}

/// A friction law's parameter is out of range.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum FrictionLawError {
    /// μ must be finite and ≥ 0.
    #[error("friction coefficient must be finite and >= 0, got {0}")]
    Coefficient(f64),
    /// τ0 must be finite and ≥ 0.
    #[error("shear strength must be finite and >= 0, got {0}")]
    ShearStrength(f64),
    /// A static law must be of the kinetic law's kind with every parameter at least the
    /// kinetic one (so that breaking a stuck element never raises its bound).
    #[error("the static friction law must be of the kinetic law's kind with every parameter at least the kinetic one: static {static_law:?}, kinetic {kinetic:?}")]
    StaticBelowKinetic {
        /// The static law.
        static_law: FrictionLaw,
        /// The kinetic law.
        kinetic: FrictionLaw,
    },
    /// The drive's spring must be finite and > 0.
    #[error("drive stiffness must be finite and > 0, got {0}")]
    DriveStiffness(f64),
    /// Slip weakening needs a static law to weaken from.
    #[error("slip weakening (over a distance {0}) needs a static friction law above the kinetic one")]
    WeakeningWithoutStaticLaw(f64),
    /// The slip weakening distance must be finite and > 0.
    #[error("slip weakening distance must be finite and > 0, got {0}")]
    WeakeningDistance(f64),
}

fn check(value: f64, error: fn(f64) -> FrictionLawError) -> Result<f64, FrictionLawError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(error(value))
    }
}

impl FrictionLaw {
    /// Coulomb's law of coefficient μ.
    pub fn coulomb(coefficient: f64) -> Result<Self, FrictionLawError> {
        Ok(Self::Coulomb {
            coefficient: check(coefficient, FrictionLawError::Coefficient)?,
        })
    }

    /// A constant shear strength τ0.
    pub fn shear_strength(shear_strength: f64) -> Result<Self, FrictionLawError> {
        Ok(Self::ShearStrength {
            shear_strength: check(shear_strength, FrictionLawError::ShearStrength)?,
        })
    }

    /// τ0 + μp.
    pub fn coulomb_shear(coefficient: f64, shear_strength: f64) -> Result<Self, FrictionLawError> {
        Ok(Self::CoulombShear {
            coefficient: check(coefficient, FrictionLawError::Coefficient)?,
            shear_strength: check(shear_strength, FrictionLawError::ShearStrength)?,
        })
    }

    /// The bound on |q| of a contact element under pressure p (> 0 compressive).
    pub fn bound(&self, pressure: f64) -> f64 {
        match *self {
            Self::Coulomb { coefficient } => coefficient * pressure.max(0.0),
            Self::ShearStrength { shear_strength } => shear_strength,
            Self::CoulombShear {
                coefficient,
                shear_strength,
            } => (shear_strength + coefficient * pressure).max(0.0),
            Self::NoSlip => f64::INFINITY,
        }
    }

    /// Whether this law, as the static law of `kinetic`, bounds every element at least as
    /// `kinetic` does: the same kind, each parameter at least the kinetic one.
    pub fn holds_at_least(&self, kinetic: &FrictionLaw) -> bool {
        match (*self, *kinetic) {
            (Self::Coulomb { coefficient: s }, Self::Coulomb { coefficient: k }) => s >= k,
            (Self::ShearStrength { shear_strength: s }, Self::ShearStrength { shear_strength: k }) => s >= k,
            (
                Self::CoulombShear {
                    coefficient: s,
                    shear_strength: t,
                },
                Self::CoulombShear {
                    coefficient: k,
                    shear_strength: u,
                },
            ) => s >= k && t >= u,
            _ => false,
        }
    }

    /// The name as written in scenario files.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Coulomb { .. } => "coulomb",
            Self::ShearStrength { .. } => "shear_strength",
            Self::CoulombShear { .. } => "coulomb_shear",
            Self::NoSlip => "no_slip",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_follow_each_law() {
        let coulomb = FrictionLaw::coulomb(0.5).unwrap();
        assert_eq!(coulomb.bound(2.0), 1.0);
        assert_eq!(coulomb.bound(-2.0), 0.0);
        let tresca = FrictionLaw::shear_strength(0.3).unwrap();
        assert_eq!(tresca.bound(-5.0), 0.3);
        let both = FrictionLaw::coulomb_shear(0.5, 0.3).unwrap();
        assert_eq!(both.bound(2.0), 1.3);
        assert_eq!(both.bound(-2.0), 0.0);
        assert_eq!(FrictionLaw::coulomb(-1.0), Err(FrictionLawError::Coefficient(-1.0)));
        assert!(FrictionLaw::shear_strength(f64::NAN).is_err());
        assert_eq!(FrictionLaw::NoSlip.bound(-2.0), f64::INFINITY);
    }
}
