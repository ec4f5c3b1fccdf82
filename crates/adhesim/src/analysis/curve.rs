//! Analysis of one indentation–pull-off run (paper Sect. 2.3–2.5): effective works of
//! adhesion of both branches, boundary friction, pinned phase, compactness.

use super::fit::{fit_jkr_work_of_adhesion, JkrFit};
use super::reference::Jkr;
use crate::protocol::{Phase, StepRecord};

/// Options of [`analyse_indentation`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveAnalysisOptions {
    /// Radius of curvature R of the indenter's paraboloid.
    pub radius: f64,
    /// Contact modulus E*.
    pub contact_modulus: f64,
    /// Reference work of adhesion γ0.
    pub work_of_adhesion: f64,
    /// Points with a smaller contact radius are left out of the fits (the paper fits
    /// a ≥ a few wavelengths; tiny contacts are dominated by discreteness).
    pub min_fit_radius: f64,
}

/// Results of [`analyse_indentation`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CurveAnalysis {
    /// γ1: JKR fit of the approach branch (force vs contact radius).
    pub gamma_approach: Option<JkrFit>,
    /// γ2: JKR fit of the pull-off branch after the pinned phase.
    pub gamma_pulloff: Option<JkrFit>,
    /// γ1 fitted with the area-equivalent radius √(A/π) in place of the farthest contact
    /// element (the paper's radius): the two differ by up to a wavelength on a wavy front,
    /// so the pair brackets the radius-definition part of any difference from the paper.
    pub gamma_approach_area: Option<JkrFit>,
    /// γ2 fitted with the area-equivalent radius, after the same pinned phase.
    pub gamma_pulloff_area: Option<JkrFit>,
    /// q = (γ2 − γ1)/2 (paper Eq. 11).
    pub boundary_friction: Option<f64>,
    /// |F_ad|/|F_JKR|: largest tensile force over (3/2)πγ0R.
    pub adhesive_force_ratio: Option<f64>,
    /// Depth travelled after reversal before the contact set first changes (phase II of
    /// Fig. 1): the pinned phase.
    pub pinned_depth: Option<f64>,
    /// Number of retraction steps in the pinned phase.
    pub pinned_steps: usize,
    /// A_real/(πa²) at the deepest point.
    pub compactness_at_max_depth: Option<f64>,
}

/// The paper's contact radius: the distance of the farthest contact element.
fn farthest_radius(record: &StepRecord) -> f64 {
    record.radius
}

/// The radius of the disc with the contact's area, √(A/π).
fn area_equivalent_radius(record: &StepRecord) -> f64 {
    (record.area / std::f64::consts::PI).sqrt()
}

/// Analyses the records of an `indent_pulloff` run.
pub fn analyse_indentation(records: &[StepRecord], options: &CurveAnalysisOptions) -> CurveAnalysis {
    let mut analysis = CurveAnalysis::default();
    let approach: Vec<&StepRecord> = records.iter().filter(|r| r.phase == Some(Phase::Approach)).collect();
    let retract: Vec<&StepRecord> = records.iter().filter(|r| r.phase == Some(Phase::Retract)).collect();
    // (radius, force) points of a branch with the given radius definition, fitted by JKR.
    let fit = |branch: &[&StepRecord], radius_of: fn(&StepRecord) -> f64| {
        let points: Vec<(f64, f64)> = branch
            .iter()
            .filter(|r| r.contact_elements > 0)
            .map(|r| (radius_of(r), r.force_normal))
            .filter(|&(radius, _)| radius >= options.min_fit_radius)
            .collect();
        fit_jkr_work_of_adhesion(&points, options.radius, options.contact_modulus)
    };
    analysis.gamma_approach = fit(&approach, farthest_radius);
    analysis.gamma_approach_area = fit(&approach, area_equivalent_radius);

    if let Some(deepest) = approach.last() {
        if deepest.radius > 0.0 {
            analysis.compactness_at_max_depth =
                Some(deepest.area / (std::f64::consts::PI * deepest.radius * deepest.radius));
        }
        // Pinned phase: retraction steps before the contact set first changes.
        let mut pinned_steps = 0;
        let mut pinned_depth = None;
        for r in &retract {
            if r.report.attached + r.report.detached > 0 {
                pinned_depth = Some(deepest.depth - r.depth);
                break;
            }
            pinned_steps += 1;
        }
        analysis.pinned_steps = pinned_steps;
        analysis.pinned_depth = pinned_depth;
        let unpinned = &retract[pinned_steps.min(retract.len())..];
        analysis.gamma_pulloff = fit(unpinned, farthest_radius);
        analysis.gamma_pulloff_area = fit(unpinned, area_equivalent_radius);
    }
    if let (Some(g1), Some(g2)) = (analysis.gamma_approach, analysis.gamma_pulloff) {
        analysis.boundary_friction = Some(0.5 * (g2.work_of_adhesion - g1.work_of_adhesion));
    }
    if options.work_of_adhesion > 0.0 {
        let jkr = Jkr {
            radius: options.radius,
            contact_modulus: options.contact_modulus,
            work_of_adhesion: options.work_of_adhesion,
        };
        let max_tension = records.iter().map(|r| -r.force_normal).fold(0.0, f64::max);
        analysis.adhesive_force_ratio = Some(max_tension / jkr.critical_force().abs());
    }
    analysis
}
