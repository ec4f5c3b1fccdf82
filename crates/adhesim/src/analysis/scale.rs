//! Scales of a run that the analysis and the jump detection measure against: the force
//! scale of an adhesive contact and the smallest contact radius the JKR fits use.

use crate::analysis::reference::{elliptic_punch_onset_force, FlatPunchReference, Jkr};
use crate::geometry::Indenter;

/// The magnitude of the adhesive force a run is measured against: |F_JKR| where the JKR
/// closed form applies (a curved indenter with γ0 > 0), Kendall's pull-off force of a flat
/// punch, the onset force of detachment of an elliptic punch, and 0 without adhesion or
/// without a closed form (a topography).
pub fn adhesive_force_scale(
    indenter: &Indenter,
    jkr: Option<&Jkr>,
    contact_modulus: f64,
    work_of_adhesion: f64,
) -> f64 {
    if work_of_adhesion <= 0.0 {
        return 0.0;
    }
    match (jkr, indenter) {
        (Some(jkr), _) => jkr.critical_force().abs(),
        (None, Indenter::FlatPunch(punch)) => FlatPunchReference {
            radius: punch.radius(),
            contact_modulus,
        }
        .kendall_force(work_of_adhesion)
        .abs(),
        (None, Indenter::EllipticPunch(punch)) => {
            elliptic_punch_onset_force(punch.semi_axes(), contact_modulus, work_of_adhesion)
        }
        _ => 0.0,
    }
}

/// The smallest contact radius the JKR fits of γ1, γ2 use by default (paper Sect. 2.3):
/// half the JKR critical radius, and for a wavy sphere at least two wavelengths, so that
/// the fitted contacts span several waves and average over them.
pub fn default_min_fit_radius(jkr: &Jkr, indenter: &Indenter) -> f64 {
    let half = 0.5 * jkr.critical_radius();
    match indenter {
        Indenter::WavySphere(wavy) => half.max(2.0 * wavy.waviness().wavelength()),
        _ => half,
    }
}
