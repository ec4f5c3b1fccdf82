//! [`AdhesionLaw`]: `[adhesion]`'s law with its parameters, as validation builds it from
//! the file's `adhesion.law` and its keys (`adhesion_law` in cohesive.rs). The file keeps
//! the flat keys of docs/cli.md (`law`, `cohesive_stress`, `range`, `softening_fraction`);
//! the run, the warnings and the summary read this type, never the raw keys.

use super::LawName;

/// The adhesion law of a validated scenario (docs/physics.md §2.6), its parameters checked:
/// positive, within the magnitudes the solver can use, the softening fraction in
/// 1e-6..=1 (`MIN_SOFTENING_FRACTION` in cohesive.rs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AdhesionLaw {
    /// The paper's sharp JKR-type criterion: an element detaches when its energy release
    /// rate reaches γ (Popov et al. 2021, Sect. 2.1).
    Jkr,
    /// Maugis–Dugdale: the traction σ0 up to the gap γ/σ0 (Maugis 1992).
    Dugdale { cohesive_stress: f64 },
    /// The exponential law of range ρ: traction (γ/ρ)·e^(−g/ρ) (docs/physics.md §2.6).
    Exponential { range: f64 },
    /// σ0 up to the gap (1 − s)·g_c, falling linearly to 0 at g_c = 2γ/((2 − s)σ0).
    Trapezoid {
        cohesive_stress: f64,
        softening_fraction: f64,
    },
}

impl AdhesionLaw {
    /// The law's name as the file writes it.
    pub fn name(&self) -> LawName {
        match self {
            Self::Jkr => LawName::Jkr,
            Self::Dugdale { .. } => LawName::Dugdale,
            Self::Exponential { .. } => LawName::Exponential,
            Self::Trapezoid { .. } => LawName::Trapezoid,
        }
    }

    /// σ0 of Dugdale's and the trapezoidal law (None for the others).
    pub fn cohesive_stress(&self) -> Option<f64> {
        match *self {
            Self::Dugdale { cohesive_stress } | Self::Trapezoid { cohesive_stress, .. } => Some(cohesive_stress),
            Self::Jkr | Self::Exponential { .. } => None,
        }
    }
}
