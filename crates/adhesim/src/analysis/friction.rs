//! Friction analysis of a roll / slide / translate run (Popov et al. 2021, Sect. 2.6):
//! the stationary means of the library's [`TranslationSummary`], Eq. 12 (rolling
//! resistance 2a(γ2 − γ1)), the γ3 fits of Fig. 8 and Eq. 13, and the friction law of
//! Eqs. 16–18 for sliding.

use crate::analysis::fit::{fit_jkr_depth_work_of_adhesion, fit_jkr_work_of_adhesion};
use crate::analysis::reference::Jkr;
use crate::geometry::Kinematics;
use crate::protocol::{Phase, StepRecord, TranslationSummary};

/// Name of a kinematics as the scenario and `summary.json` spell it.
pub fn kinematics_name(kinematics: &Kinematics) -> &'static str {
    match kinematics {
        Kinematics::Roll => "roll",
        Kinematics::Slide { .. } => "slide",
        Kinematics::Translate => "translate",
    }
}

/// Eq. 12: the rolling resistance 2a(γ2 − γ1) of a contact of half-width a (both edges
/// count), given the effective works of adhesion of approach γ1 and pull-off γ2.
pub fn eq12_rolling_resistance(half_width: f64, gamma_approach: f64, gamma_pulloff: f64) -> f64 {
    2.0 * half_width * (gamma_pulloff - gamma_approach)
}

/// Results of a roll / slide / translate run (the CLI's `docs/friction.md`). Means are over the
/// stationary part of the forward stroke (x > stationary_from·distance); entries that do
/// not apply (Eq. 12 without γ1, γ2; Eqs. 16–18 without τ0; normalised values without
/// γ0 > 0) are null.
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TranslationResults {
    /// roll, slide or translate.
    pub kind: String,
    /// Largest tensile normal force magnitude seen (0 if never tensile).
    pub max_adhesive_force: f64,
    /// Not measured by a translation (null; kept for the shape of `summary.json`).
    pub pull_off_depth: Option<f64>,
    /// Not measured by a translation (null).
    pub gamma_approach: Option<f64>,
    /// Not measured by a translation (null).
    pub gamma_pulloff: Option<f64>,
    /// q = (γ2 − γ1)/2 from `[analysis]` where given (Eq. 11).
    pub boundary_friction: Option<f64>,
    /// Energy released by configuration changes during the forward stroke.
    pub dissipated_energy: f64,
    /// Steps whose contact set changed by a jump.
    pub jumps: usize,
    /// Mean of the end-of-step tangential force F_T = ∫p ∂z_mov/∂x dA (the paper's force).
    pub mean_tangential_force: Option<f64>,
    /// Work of the driving force per distance (includes the force before each slip).
    pub mean_tangential_force_work: f64,
    /// Standard deviation of the end-of-step F_T.
    pub tangential_force_fluctuation: f64,
    /// Mean normal force F_N over the stationary steps.
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
    #[cfg_attr(feature = "serde", serde(default))]
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
    /// Energy dissipated by friction at the interface over the run (null without
    /// `[friction]`; with it, the tangential forces above include the interface's).
    #[cfg_attr(feature = "serde", serde(default))]
    pub frictional_dissipation: Option<f64>,
    /// Friction's dissipation per travelled distance over the stationary part: the
    /// interface's mean force in a steady slide (null without `[friction]`).
    #[cfg_attr(feature = "serde", serde(default))]
    pub interface_friction_force: Option<f64>,
    /// The worst optimality conditions of any tangential step (null without `[friction]`).
    #[cfg_attr(feature = "serde", serde(default))]
    pub complementarity: Option<crate::solver::Complementarity>,
}

/// What the translation analysis needs besides the library summary.
#[derive(Debug, Clone, Copy)]
pub struct TranslationInputs<'a> {
    /// Roll, slide or translate.
    pub kinematics: Kinematics,
    /// Every step of the run, approach included.
    pub records: &'a [StepRecord],
    /// Fraction of the travel after which the motion counts as stationary.
    pub stationary_from: f64,
    /// Travel of the forward stroke.
    pub distance: f64,
    /// JKR closed form of the smooth sphere (None without adhesion).
    pub jkr: Option<Jkr>,
    /// Reference work of adhesion γ0.
    pub work_of_adhesion: f64,
    /// Radius of curvature of the sphere.
    pub radius: f64,
    /// Contact modulus E*.
    pub contact_modulus: f64,
    /// γ1, γ2 of the normal contact (Eq. 12), absolute units.
    pub gammas: Option<(f64, f64)>,
    /// Interfacial shear stress τ0 of Eqs. 16–18.
    pub tau0: Option<f64>,
}

impl TranslationResults {
    /// Analyses a finished run from its summary and step records.
    pub fn new(summary: &TranslationSummary, inputs: &TranslationInputs<'_>) -> Self {
        let a = summary.mean_half_width;
        let f_t = summary.mean_tangential_force;
        let moving: Vec<&StepRecord> = inputs
            .records
            .iter()
            .filter(|r| matches!(r.phase, Some(Phase::Roll | Phase::Slide)))
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
        let stationary: Vec<&&StepRecord> = moving
            .iter()
            .filter(|r| r.step <= turn)
            .filter(|r| r.offset > inputs.stationary_from * inputs.distance && r.contact_elements > 0)
            .collect();
        let max_adhesive_force = inputs.records.iter().map(|r| -r.force_normal).fold(0.0, f64::max);
        let force_scale = inputs.jkr.map(|j| j.critical_force().abs());
        let norm = |v: f64| force_scale.map(|f| v / f);
        let has_stationary = !stationary.is_empty();
        let rolling = matches!(inputs.kinematics, Kinematics::Roll);
        let sliding = matches!(inputs.kinematics, Kinematics::Slide { .. });
        let eq12_prediction = match inputs.gammas {
            Some((g1, g2)) if rolling => Some(eq12_rolling_resistance(a, g1, g2)),
            _ => None,
        };
        let fit_points =
            |f: &dyn Fn(&StepRecord) -> (f64, f64)| -> Vec<(f64, f64)> { stationary.iter().map(|r| f(r)).collect() };
        let fit_force = |radius_of: &dyn Fn(&StepRecord) -> f64| {
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
            kind: kinematics_name(&inputs.kinematics).to_string(),
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
            boundary_scale: (inputs.work_of_adhesion > 0.0).then_some(2.0 * a * inputs.work_of_adhesion),
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
            frictional_dissipation: None,
            interface_friction_force: None,
            complementarity: None,
        }
    }

    /// The results of a run with friction at the interface: its dissipation, its mean
    /// force and its optimality; the boundary friction per width is not measured, since
    /// the tangential force holds the interface's too.
    pub fn with_interface_friction(self, summary: &TranslationSummary) -> Self {
        Self {
            frictional_dissipation: Some(summary.frictional_dissipation),
            interface_friction_force: Some(summary.frictional_dissipation_per_distance),
            complementarity: Some(summary.complementarity),
            measured_q: None,
            ..self
        }
    }
}
