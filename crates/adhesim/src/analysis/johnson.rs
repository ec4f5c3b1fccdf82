//! Inversions of the Johnson parameter α = √(2λγ/(π²h²E*)) (Johnson 1995; paper Eq. 5):
//! given α and three of wavelength λ, amplitude h, work of adhesion γ and contact modulus
//! E*, the fourth. Sweeps and studies use them to set a case's Johnson parameter.
//! Two parameters of randomly rough spheres ([`rough_sphere_parameter`],
//! [`roughness_depth_ratio`]) place a random roughness on the same axis (docs/physics.md §4).

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

/// Johnson-type adhesion parameter of a random roughness,
/// α_r = √(2γ/(π·E*·h_rms·h'_rms)), from the rms height h_rms and rms slope h'_rms of the
/// roughness, the work of adhesion γ and the contact modulus E*.
///
/// Johnson's α = √(2λγ/(π²h²E*)) (Johnson 1995, *Int. J. Solids Struct.* 32, 423; paper
/// Eq. 5) compares γ with the elastic energy per area E*h²/λ that flattening a sinusoid of
/// amplitude h and wavelength λ stores. A random surface has no single λ; the wavelength
/// of the sinusoid with the same h_rms and h'_rms, λ = 2π·h_rms/h'_rms (amplitude
/// √2·h_rms), turns α into α_r, so α_r = α exactly for z = h·cos(2πx/λ), and
/// α_r = 2^{1/4}·α for the paper's two-dimensional waviness h·sin(2πx/λ)·sin(2πy/λ).
/// Li, Pohrt & Popov ("Adhesive strength of contacts of rough spheres", *Front. Mech.
/// Eng.* 5:7, 2019, doi:10.3389/fmech.2019.00007) show that one such parameter governs the
/// adhesive strength of randomly rough spheres; this is adhesim's form of it
/// (docs/physics.md §4, docs/rough-spheres.md). `None` unless every input is finite and > 0.
pub fn rough_sphere_parameter(
    rms_height: f64,
    rms_slope: f64,
    work_of_adhesion: f64,
    contact_modulus: f64,
) -> Option<f64> {
    let positive = |v: f64| v.is_finite() && v > 0.0;
    if ![rms_height, rms_slope, work_of_adhesion, contact_modulus]
        .into_iter()
        .all(positive)
    {
        return None;
    }
    Some((2.0 * work_of_adhesion / (PI * contact_modulus * rms_height * rms_slope)).sqrt())
}

/// The rms roughness in units of the JKR critical depth of the smooth sphere,
/// h_rms/|d_JKR| with |d_JKR| = (3π²γ²R/(64E*²))^{1/3} (paper Eq. 3 with E*², docs/physics.md
/// §4): the amplitude-only measure of a rough sphere's roughness (Fuller & Tabor 1975,
/// *Proc. R. Soc. A* 345, 327, compare h_rms with the pull-off deformation of an asperity),
/// the second axis of the rough-sphere study. `None` unless every input is finite and > 0.
pub fn roughness_depth_ratio(rms_height: f64, radius: f64, work_of_adhesion: f64, contact_modulus: f64) -> Option<f64> {
    let positive = |v: f64| v.is_finite() && v > 0.0;
    if ![rms_height, radius, work_of_adhesion, contact_modulus]
        .into_iter()
        .all(positive)
    {
        return None;
    }
    let critical_depth = (3.0 * PI * PI * work_of_adhesion * work_of_adhesion * radius
        / (64.0 * contact_modulus * contact_modulus))
        .cbrt();
    Some(rms_height / critical_depth)
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
    #[test]
    fn rough_sphere_parameter_matches_its_definition_and_johnson() {
        // Hand computation: h_rms = 1e-3, h'_rms = 0.05, γ = 6e-4, E* = 1:
        // 2γ/(π E* h h') = 1.2e-3/(π·5e-5) = 7.639437268, √ = 2.763953196.
        let alpha = rough_sphere_parameter(1e-3, 0.05, 6e-4, 1.0).unwrap();
        assert!((alpha - 2.763_953_196).abs() < 1e-8, "α_r = {alpha}");
        // A 1-D sinusoid h·cos(2πx/λ): h_rms = h/√2, h'_rms = 2πh/(λ√2); α_r must be
        // Johnson's α (rounding only).
        let (wavelength, amplitude, gamma, modulus) = (0.05, 5.627e-4, 2e-5, 1.3);
        let rms_height = amplitude / 2f64.sqrt();
        let rms_slope = 2.0 * PI * amplitude / (wavelength * 2f64.sqrt());
        let mapped = rough_sphere_parameter(rms_height, rms_slope, gamma, modulus).unwrap();
        let johnson = johnson_parameter(wavelength, amplitude, gamma, modulus);
        assert!((mapped / johnson - 1.0).abs() < 1e-14, "{mapped} vs {johnson}");
        assert_eq!(rough_sphere_parameter(0.0, 0.05, 6e-4, 1.0), None);
        assert_eq!(rough_sphere_parameter(1e-3, f64::NAN, 6e-4, 1.0), None);
    }

    #[test]
    fn roughness_depth_ratio_matches_its_definition() {
        // R = E* = 1, γ = 6.168502750680850e-4: |d_JKR| = (3π²γ²/64)^{1/3} = 5.6045e-3
        // (hand: 3π² = 29.6088, γ² = 3.80504e-7, product/64 = 1.76034e-7, cube root
        // 5.60437e-3); h_rms = 1.12087e-3 is then 0.2 |d_JKR|.
        let ratio = roughness_depth_ratio(1.120_891e-3, 1.0, 6.168_502_750_680_85e-4, 1.0).unwrap();
        assert!((ratio - 0.2).abs() < 1e-5, "h/|d_JKR| = {ratio}");
        assert_eq!(roughness_depth_ratio(1e-3, -1.0, 6e-4, 1.0), None);
    }
}
