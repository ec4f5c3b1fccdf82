//! Inversions of the Johnson parameter α = √(2λγ/(π²h²E*)) (Johnson 1995; paper Eq. 5):
//! given α and three of wavelength λ, amplitude h, work of adhesion γ and contact modulus
//! E*, the fourth. Sweeps and studies use them to set a case's Johnson parameter.

use std::f64::consts::PI;

/// The quantity an inversion of the Johnson parameter solves for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JohnsonTarget {
    /// Waviness amplitude h.
    Amplitude,
    /// Work of adhesion γ.
    WorkOfAdhesion,
    /// Waviness wavelength λ.
    Wavelength,
    /// Contact modulus E*.
    ContactModulus,
}

/// The four inputs of the Johnson parameter; the one being solved for is ignored.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JohnsonInputs {
    /// Waviness wavelength λ.
    pub wavelength: f64,
    /// Waviness amplitude h.
    pub amplitude: f64,
    /// Work of adhesion γ.
    pub work_of_adhesion: f64,
    /// Contact modulus E*.
    pub contact_modulus: f64,
}

impl JohnsonTarget {
    /// Solves α(λ, h, γ, E*) = `alpha` for this target, the other three taken from `inputs`.
    pub fn solve(self, alpha: f64, inputs: &JohnsonInputs) -> f64 {
        let JohnsonInputs {
            wavelength,
            amplitude,
            work_of_adhesion,
            contact_modulus,
        } = *inputs;
        match self {
            Self::Amplitude => amplitude_for_johnson_parameter(alpha, wavelength, work_of_adhesion, contact_modulus),
            Self::WorkOfAdhesion => {
                work_of_adhesion_for_johnson_parameter(alpha, wavelength, amplitude, contact_modulus)
            }
            Self::Wavelength => wavelength_for_johnson_parameter(alpha, amplitude, work_of_adhesion, contact_modulus),
            Self::ContactModulus => {
                contact_modulus_for_johnson_parameter(alpha, wavelength, amplitude, work_of_adhesion)
            }
        }
    }
}

/// h = √(2λγ/(π²E*α²)).
pub fn amplitude_for_johnson_parameter(
    alpha: f64,
    wavelength: f64,
    work_of_adhesion: f64,
    contact_modulus: f64,
) -> f64 {
    (2.0 * wavelength * work_of_adhesion / (PI.powi(2) * contact_modulus * alpha * alpha)).sqrt()
}

/// γ = α²π²h²E*/(2λ).
pub fn work_of_adhesion_for_johnson_parameter(
    alpha: f64,
    wavelength: f64,
    amplitude: f64,
    contact_modulus: f64,
) -> f64 {
    alpha * alpha * PI.powi(2) * amplitude.powi(2) * contact_modulus / (2.0 * wavelength)
}

/// λ = α²π²h²E*/(2γ).
pub fn wavelength_for_johnson_parameter(
    alpha: f64,
    amplitude: f64,
    work_of_adhesion: f64,
    contact_modulus: f64,
) -> f64 {
    alpha * alpha * PI.powi(2) * amplitude.powi(2) * contact_modulus / (2.0 * work_of_adhesion)
}

/// E* = 2λγ/(π²h²α²).
pub fn contact_modulus_for_johnson_parameter(
    alpha: f64,
    wavelength: f64,
    amplitude: f64,
    work_of_adhesion: f64,
) -> f64 {
    2.0 * wavelength * work_of_adhesion / (PI.powi(2) * amplitude.powi(2) * alpha * alpha)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::reference::johnson_parameter;

    #[test]
    fn every_inversion_gives_back_its_alpha() {
        // Each target solved for α = 0.7 must give α(λ, h, γ, E*) = 0.7 again; the
        // tolerance is a few roundings of the square root and products.
        let inputs = JohnsonInputs {
            wavelength: 0.05,
            amplitude: 5.627e-4,
            work_of_adhesion: 2e-5,
            contact_modulus: 1.3,
        };
        for target in [
            JohnsonTarget::Amplitude,
            JohnsonTarget::WorkOfAdhesion,
            JohnsonTarget::Wavelength,
            JohnsonTarget::ContactModulus,
        ] {
            let solved = target.solve(0.7, &inputs);
            let mut set = inputs;
            match target {
                JohnsonTarget::Amplitude => set.amplitude = solved,
                JohnsonTarget::WorkOfAdhesion => set.work_of_adhesion = solved,
                JohnsonTarget::Wavelength => set.wavelength = solved,
                JohnsonTarget::ContactModulus => set.contact_modulus = solved,
            }
            let alpha = johnson_parameter(set.wavelength, set.amplitude, set.work_of_adhesion, set.contact_modulus);
            assert!((alpha - 0.7).abs() < 1e-14, "{target:?}: α = {alpha}");
        }
    }
}
