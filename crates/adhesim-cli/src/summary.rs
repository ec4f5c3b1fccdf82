//! `summary.json`: inputs echoed, derived quantities, results, performance, warnings.

use crate::scenario::{Derived, ProtocolKind, Scenario, ScenarioFile};
use adhesim::analysis::curve::{analyse_indentation, CurveAnalysis, CurveAnalysisOptions};
use adhesim::{Indenter, ProtocolSummary, StepRecord};
use anyhow::{Context, Result};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Results of an indentation / pull-off run. Entries that do not apply (fits not yet
/// available, tangential quantities of a normal protocol) are null.
#[derive(Debug, Serialize)]
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
pub fn min_fit_radius(scenario: &Scenario) -> Option<f64> {
    let jkr = scenario.jkr?;
    if let Some(radius) = scenario.file.output.min_fit_radius {
        return Some(radius);
    }
    let half = 0.5 * jkr.critical_radius();
    Some(match &scenario.indenter {
        Indenter::WavySphere(w) => half.max(2.0 * w.waviness().wavelength()),
        _ => half,
    })
}

/// Fits γ1 and γ2 to the run's force–radius records; the fitted curves go into the plot.
pub fn fit_results(scenario: &Scenario, records: &[StepRecord]) -> (FitResults, Option<CurveAnalysis>) {
    let (Some(jkr), Some(min_radius)) = (scenario.jkr, min_fit_radius(scenario)) else {
        return (FitResults::default(), None);
    };
    if scenario.file.protocol.kind != ProtocolKind::IndentPulloff {
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

#[derive(Debug, Serialize)]
pub struct Performance {
    pub wall_seconds: f64,
    /// CG iterations summed over all solves.
    pub solver_iterations: usize,
    /// Forward + inverse FFT pairs (elastic operator applications).
    pub fft_pairs: u64,
    pub solves: usize,
    pub steps: usize,
    pub threads: usize,
    /// Averages per quasi-static step.
    pub fft_pairs_per_step: f64,
    pub solves_per_step: f64,
    pub cg_iterations_per_solve: f64,
    /// Solver wall time and steps per phase (approach, retract, roll, slide).
    pub phase_seconds: std::collections::BTreeMap<&'static str, f64>,
    pub phase_steps: std::collections::BTreeMap<&'static str, usize>,
    /// Wall time of writing curve.csv and snapshots during the run.
    pub output_seconds: f64,
}

impl Performance {
    /// Counters of a run, with the per-step averages and the observer's phase timings.
    pub fn new(
        wall_seconds: f64,
        solver_iterations: usize,
        fft_pairs: u64,
        solves: usize,
        steps: usize,
        observer: &crate::output::RunObserver,
    ) -> Self {
        let per = |value: f64, count: usize| if count > 0 { value / count as f64 } else { 0.0 };
        Self {
            wall_seconds,
            solver_iterations,
            fft_pairs,
            solves,
            steps,
            threads: rayon::current_num_threads(),
            fft_pairs_per_step: per(fft_pairs as f64, steps),
            solves_per_step: per(solves as f64, steps),
            cg_iterations_per_solve: per(solver_iterations as f64, solves),
            phase_seconds: observer.phase_seconds.clone(),
            phase_steps: observer.phase_steps.clone(),
            output_seconds: observer.output_seconds,
        }
    }
}

/// The whole `summary.json`; `R` is [`Results`] for indent_pulloff and
/// [`TranslationResults`] for roll / slide / translate.
#[derive(Debug, Serialize)]
pub struct Summary<'a, R = Results> {
    pub adhesim_version: &'static str,
    pub inputs: &'a ScenarioFile,
    pub derived: &'a Derived,
    pub results: R,
    pub performance: Performance,
    pub warnings: Vec<String>,
}

/// Writes `summary.json` with null for non-finite numbers (JSON has no NaN).
pub fn write<R: Serialize>(path: &Path, summary: &Summary<'_, R>) -> Result<()> {
    let text = serde_json::to_string_pretty(summary)?;
    std::fs::write(path, text + "\n").with_context(|| format!("cannot write {}", path.display()))
}

/// Results of a roll / slide / translate run (docs/friction.md). Means are over the
/// stationary part of the forward stroke (x > stationary_from·distance); entries that do
/// not apply (Eq. 12 without γ1, γ2; Eqs. 16–18 without τ0; normalised values without
/// γ0 > 0) are null.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub struct TranslationResults {
    /// roll, slide or translate.
    pub kind: String,
    /// Largest tensile normal force magnitude seen (0 if never tensile).
    pub max_adhesive_force: f64,
    pub pull_off_depth: Option<f64>,
    pub gamma_approach: Option<f64>,
    pub gamma_pulloff: Option<f64>,
    /// q = (γ2 − γ1)/2 from `[analysis]` where given (Eq. 11).
    pub boundary_friction: Option<f64>,
    /// Energy released by configuration changes during the forward stroke.
    pub dissipated_energy: f64,
    pub jumps: usize,
    /// Mean of the end-of-step tangential force F_T = ∫p ∂z_mov/∂x dA (the paper's force).
    pub mean_tangential_force: Option<f64>,
    /// Work of the driving force per distance (includes the force before each slip).
    pub mean_tangential_force_work: f64,
    /// Standard deviation of the end-of-step F_T.
    pub tangential_force_fluctuation: f64,
    pub mean_normal_force: f64,
    /// Mean half-width of the contact perpendicular to the motion (a of Eq. 12).
    pub contact_half_width: f64,
    /// Mean contact radius (farthest contact element from the moving axis).
    pub contact_radius: f64,
    /// Mean real contact area Δ²|C|.
    pub real_contact_area: f64,
    /// Mean A_real/(π a²), a the contact radius.
    pub compactness: f64,
    /// Released energy per travelled distance over the stationary part.
    pub dissipation_per_distance: f64,
    /// dissipation_per_distance / mean_tangential_force_work (1 in a periodic steady state).
    pub energy_balance_ratio: Option<f64>,
    /// 2·a·γ0: the tangential force a hysteresis γ2 − γ1 = γ0 would give by Eq. 12.
    pub boundary_scale: Option<f64>,
    /// mean_tangential_force / |F_JKR|.
    pub mean_tangential_force_norm: Option<f64>,
    /// mean_tangential_force_work / |F_JKR|.
    pub mean_tangential_force_work_norm: Option<f64>,
    /// mean_normal_force / |F_JKR|.
    pub mean_normal_force_norm: Option<f64>,
    /// contact_half_width / a_JKR.
    pub contact_half_width_norm: Option<f64>,
    /// Eq. 12: 2a(γ2 − γ1), a = contact_half_width (both edges count).
    pub eq12_prediction: Option<f64>,
    /// mean_tangential_force / eq12_prediction.
    pub eq12_ratio: Option<f64>,
    /// γ3 (Fig. 8): JKR fit of F_N vs the contact radius over the stationary steps. The
    /// radius is the paper's (Sec. 2.3): distance from the moving axis to the farthest
    /// contact element, the one the γ1, γ2 fits of the normal runs use ("similar to normal
    /// contact", Sec. 2.6).
    pub gamma3: Option<f64>,
    /// The same fit against the half-width perpendicular to the motion (Eq. 12's a).
    #[serde(default)]
    pub gamma3_half_width: Option<f64>,
    /// γ3 from Eq. 13, d = a²/R − √(2πγ3a/E*), with a = half-width.
    pub gamma3_depth: Option<f64>,
    /// Boundary friction per unit width measured in this run: F_B/D with D = 2a.
    pub measured_q: Option<f64>,
    /// Eq. 16 boundary term q·D with q = (γ2 − γ1)/2 from `[analysis]` and D = 2a
    /// (half of Eq. 12's 2a(γ2 − γ1): the paper's two forms differ by this factor).
    pub eq16_boundary_term: Option<f64>,
    /// A_real·τ0 (area contribution, the BEM itself is frictionless).
    pub area_friction: Option<f64>,
    /// Eq. 16: F = F_B + A_real·τ0 with F_B the simulated boundary force.
    pub friction_eq16: Option<f64>,
    /// friction_eq16 / A_real.
    pub tau_mean: Option<f64>,
    /// Eq. 18: 2q(πA)^−½ + τ0 with q = measured_q and A = A_real (equals tau_mean for a
    /// compact contact, A_real = πa²).
    pub tau_mean_eq18: Option<f64>,
    /// Contact on the border of a free grid at some step.
    pub border_contact: bool,
}

/// What the translation analysis needs besides the library summary.
pub struct TranslationInputs<'a> {
    pub kind: crate::scenario::ProtocolKind,
    pub records: &'a [adhesim::StepRecord],
    pub stationary_from: f64,
    pub distance: f64,
    pub jkr: Option<adhesim::analysis::reference::Jkr>,
    pub gamma0: f64,
    pub radius: f64,
    pub contact_modulus: f64,
    pub gammas: Option<(f64, f64)>,
    pub tau0: Option<f64>,
}

impl TranslationResults {
    pub fn new(summary: &adhesim::TranslationSummary, inputs: &TranslationInputs<'_>) -> Self {
        use crate::scenario::ProtocolKind;
        use adhesim::analysis::fit::{fit_jkr_depth_work_of_adhesion, fit_jkr_work_of_adhesion};
        let a = summary.mean_half_width;
        let f_t = summary.mean_tangential_force;
        let moving: Vec<&adhesim::StepRecord> = inputs
            .records
            .iter()
            .filter(|r| matches!(r.phase, Some(adhesim::Phase::Roll | adhesim::Phase::Slide)))
            .collect();
        // The forward stroke ends at the first step with the largest offset.
        let turn = moving
            .iter()
            .fold((usize::MAX, f64::NEG_INFINITY), |best, r| {
                if r.offset > best.1 {
                    (r.step, r.offset)
                } else {
                    best
                }
            })
            .0;
        let stationary: Vec<&&adhesim::StepRecord> = moving
            .iter()
            .filter(|r| r.step <= turn)
            .filter(|r| r.offset > inputs.stationary_from * inputs.distance && r.contact_elements > 0)
            .collect();
        let max_adhesive_force = inputs.records.iter().map(|r| -r.force_normal).fold(0.0, f64::max);
        let force_scale = inputs.jkr.map(|j| j.critical_force().abs());
        let norm = |v: f64| force_scale.map(|f| v / f);
        let has_stationary = !stationary.is_empty();
        let rolling = inputs.kind == ProtocolKind::Roll;
        let sliding = inputs.kind == ProtocolKind::Slide;
        let eq12_prediction = match inputs.gammas {
            Some((g1, g2)) if rolling => Some(2.0 * a * (g2 - g1)),
            _ => None,
        };
        let fit_points = |f: &dyn Fn(&adhesim::StepRecord) -> (f64, f64)| -> Vec<(f64, f64)> {
            stationary.iter().map(|r| f(r)).collect()
        };
        let fit_force = |radius_of: &dyn Fn(&adhesim::StepRecord) -> f64| {
            rolling
                .then(|| {
                    fit_jkr_work_of_adhesion(
                        &fit_points(&|r| (radius_of(r), r.force_normal)),
                        inputs.radius,
                        inputs.contact_modulus,
                    )
                })
                .flatten()
                .map(|f| f.work_of_adhesion)
        };
        let gamma3 = fit_force(&|r| r.radius);
        let gamma3_half_width = fit_force(&|r| r.half_width);
        let gamma3_depth = rolling
            .then(|| {
                fit_jkr_depth_work_of_adhesion(
                    &fit_points(&|r| (r.half_width, r.depth)),
                    inputs.radius,
                    inputs.contact_modulus,
                )
            })
            .flatten()
            .map(|f| f.work_of_adhesion);
        let measured_q = (sliding && a > 0.0).then(|| f_t / (2.0 * a));
        let area = summary.mean_area;
        let area_friction = inputs.tau0.map(|t| t * area);
        let friction_eq16 = match area_friction {
            Some(c) if sliding => Some(f_t + c),
            _ => None,
        };
        Self {
            kind: inputs.kind.name().to_string(),
            max_adhesive_force,
            pull_off_depth: None,
            gamma_approach: None,
            gamma_pulloff: None,
            boundary_friction: inputs.gammas.map(|(g1, g2)| 0.5 * (g2 - g1)),
            dissipated_energy: summary.dissipated_energy,
            jumps: summary.jumps,
            mean_tangential_force: has_stationary.then_some(f_t),
            mean_tangential_force_work: summary.mean_tangential_force_work,
            tangential_force_fluctuation: summary.tangential_force_fluctuation,
            mean_normal_force: summary.mean_normal_force,
            contact_half_width: a,
            contact_radius: summary.mean_radius,
            real_contact_area: area,
            compactness: summary.compactness,
            dissipation_per_distance: summary.dissipation_per_distance,
            energy_balance_ratio: (summary.mean_tangential_force_work.abs() > 0.0)
                .then(|| summary.dissipation_per_distance / summary.mean_tangential_force_work),
            boundary_scale: (inputs.gamma0 > 0.0).then_some(2.0 * a * inputs.gamma0),
            mean_tangential_force_norm: norm(f_t),
            mean_tangential_force_work_norm: norm(summary.mean_tangential_force_work),
            mean_normal_force_norm: norm(summary.mean_normal_force),
            contact_half_width_norm: inputs.jkr.map(|j| a / j.critical_radius()),
            eq12_prediction,
            eq12_ratio: eq12_prediction.filter(|p| *p != 0.0).map(|p| f_t / p),
            gamma3,
            gamma3_half_width,
            gamma3_depth,
            measured_q,
            eq16_boundary_term: match inputs.gammas {
                Some((g1, g2)) if sliding => Some(0.5 * (g2 - g1) * 2.0 * a),
                _ => None,
            },
            area_friction,
            friction_eq16,
            tau_mean: friction_eq16.filter(|_| area > 0.0).map(|f| f / area),
            tau_mean_eq18: match (measured_q, inputs.tau0) {
                (Some(q), Some(t)) if area > 0.0 => Some(2.0 * q / (std::f64::consts::PI * area).sqrt() + t),
                _ => None,
            },
            border_contact: summary.touches_border,
        }
    }
}
