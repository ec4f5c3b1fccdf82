//! The results section of `summary.json`: what an indentation / pull-off run gives
//! (with the JKR fits of γ1, γ2) and, for roll / slide / translate, the library's
//! friction analysis.

use crate::model::{ProtocolKind, ValidScenario};
use adhesim::analysis::curve::{analyse_indentation, CurveAnalysis, CurveAnalysisOptions};
use adhesim::analysis::friction::TranslationResults;
use adhesim::{ProtocolSummary, StepRecord};
use serde::Serialize;

/// The `results` of a run, as `summary.json` holds them.
#[derive(Debug, Clone, Serialize)]
#[serde(untagged)]
pub enum RunResults {
    /// indent_pulloff.
    Indentation(Results),
    /// roll, slide, translate.
    Translation(TranslationResults),
    /// shear.
    Shear(crate::shear::ShearResults),
}

/// Results of an indentation / pull-off run. Entries that do not apply (fits not yet
/// available, tangential quantities of a normal protocol) are null.
#[derive(Debug, Clone, Serialize)]
pub struct Results {
    pub max_adhesive_force: f64,
    pub pull_off_depth: Option<f64>,
    pub depth_at_max_adhesive_force: Option<f64>,
    /// γ1, γ2, q and the other results of the JKR fits (flattened into `results`).
    #[serde(flatten)]
    pub fits: FitResults,
    pub dissipated_energy: f64,
    pub jumps: usize,
    pub mean_tangential_force: Option<f64>,
    pub border_contact: bool,
    pub largest_contact_elements: usize,
    pub largest_contact_step: usize,
}

impl Results {
    /// The protocol's own numbers; the fits are filled in by [`fit_results`].
    pub fn from_protocol(summary: &ProtocolSummary) -> Self {
        Self {
            max_adhesive_force: summary.max_adhesive_force,
            pull_off_depth: summary.pull_off_depth,
            depth_at_max_adhesive_force: (summary.max_adhesive_force > 0.0)
                .then_some(summary.depth_at_max_adhesive_force),
            fits: FitResults::default(),
            dissipated_energy: summary.dissipated_energy,
            jumps: summary.jumps,
            mean_tangential_force: None,
            border_contact: summary.touches_border,
            largest_contact_elements: summary.largest_contact.0,
            largest_contact_step: summary.largest_contact.1,
        }
    }
}

/// Results of the JKR fits of an `indent_pulloff` run with γ0 > 0 and a curved indenter
/// (paper Sect. 2.3; `adhesim::analysis::curve`); all null otherwise.
#[derive(Debug, Clone, Default, Serialize)]
pub struct FitResults {
    /// γ1: effective work of adhesion of the approach branch.
    pub gamma_approach: Option<f64>,
    /// γ2: effective work of adhesion of the pull-off branch after the pinned phase.
    pub gamma_pulloff: Option<f64>,
    /// q = (γ2 − γ1)/2.
    pub boundary_friction: Option<f64>,
    /// γ1/γ0.
    pub gamma_approach_norm: Option<f64>,
    /// γ2/γ0.
    pub gamma_pulloff_norm: Option<f64>,
    /// γ1 fitted with the area-equivalent radius √(A/π) instead of the farthest contact.
    pub gamma_approach_area: Option<f64>,
    /// γ2 fitted with the area-equivalent radius √(A/π).
    pub gamma_pulloff_area: Option<f64>,
    /// γ1 (area-equivalent radius)/γ0.
    pub gamma_approach_area_norm: Option<f64>,
    /// γ2 (area-equivalent radius)/γ0.
    pub gamma_pulloff_area_norm: Option<f64>,
    /// RMS force residual of the γ1 fit.
    pub gamma_approach_residual: Option<f64>,
    /// RMS force residual of the γ2 fit.
    pub gamma_pulloff_residual: Option<f64>,
    /// Points used by the γ1 fit.
    pub gamma_approach_points: Option<usize>,
    /// Points used by the γ2 fit.
    pub gamma_pulloff_points: Option<usize>,
    /// Smallest contact radius used by the fits.
    pub fit_min_radius: Option<f64>,
    /// |F_ad|/|F_JKR|.
    pub adhesive_force_ratio: Option<f64>,
    /// Depth travelled after reversal before the contact set first changes.
    pub pinned_depth: Option<f64>,
    /// Retraction steps of the pinned phase.
    pub pinned_steps: Option<usize>,
    /// A_real/(πa²) at the deepest point.
    pub compactness_at_max_depth: Option<f64>,
}

/// The fits' smallest contact radius: `output.min_fit_radius`, or max(0.5·a_JKR, 2λ) for
/// a wavy sphere, 0.5·a_JKR otherwise. `None` where no JKR scale exists.
pub fn min_fit_radius(scenario: &ValidScenario) -> Option<f64> {
    let jkr = scenario.jkr?;
    if let Some(radius) = scenario.file.output.min_fit_radius {
        return Some(radius);
    }
    Some(adhesim::analysis::scale::default_min_fit_radius(
        &jkr,
        &scenario.indenter,
    ))
}

/// Fits γ1 and γ2 to the run's force–radius records; the fitted curves go into the plot.
pub fn fit_results(scenario: &ValidScenario, records: &[StepRecord]) -> (FitResults, Option<CurveAnalysis>) {
    let (Some(jkr), Some(min_radius)) = (scenario.jkr, min_fit_radius(scenario)) else {
        return (FitResults::default(), None);
    };
    if scenario.file.protocol.kind() != ProtocolKind::IndentPulloff {
        return (FitResults::default(), None);
    }
    let analysis = analyse_indentation(
        records,
        &CurveAnalysisOptions {
            radius: jkr.radius,
            contact_modulus: jkr.contact_modulus,
            work_of_adhesion: jkr.work_of_adhesion,
            min_fit_radius: min_radius,
        },
    );
    let gamma0 = jkr.work_of_adhesion;
    let results = FitResults {
        gamma_approach: analysis.gamma_approach.map(|f| f.work_of_adhesion),
        gamma_pulloff: analysis.gamma_pulloff.map(|f| f.work_of_adhesion),
        boundary_friction: analysis.boundary_friction,
        gamma_approach_norm: analysis.gamma_approach.map(|f| f.work_of_adhesion / gamma0),
        gamma_pulloff_norm: analysis.gamma_pulloff.map(|f| f.work_of_adhesion / gamma0),
        gamma_approach_area: analysis.gamma_approach_area.map(|f| f.work_of_adhesion),
        gamma_pulloff_area: analysis.gamma_pulloff_area.map(|f| f.work_of_adhesion),
        gamma_approach_area_norm: analysis.gamma_approach_area.map(|f| f.work_of_adhesion / gamma0),
        gamma_pulloff_area_norm: analysis.gamma_pulloff_area.map(|f| f.work_of_adhesion / gamma0),
        gamma_approach_residual: analysis.gamma_approach.map(|f| f.residual_rms),
        gamma_pulloff_residual: analysis.gamma_pulloff.map(|f| f.residual_rms),
        gamma_approach_points: analysis.gamma_approach.map(|f| f.points),
        gamma_pulloff_points: analysis.gamma_pulloff.map(|f| f.points),
        fit_min_radius: Some(min_radius),
        adhesive_force_ratio: analysis.adhesive_force_ratio,
        pinned_depth: analysis.pinned_depth,
        pinned_steps: Some(analysis.pinned_steps),
        compactness_at_max_depth: analysis.compactness_at_max_depth,
    };
    (results, Some(analysis))
}
