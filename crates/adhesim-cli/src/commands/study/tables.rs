//! The tables of a study: one row per case (`table.csv`), one per α (`alphas.csv`).

use super::{StudyFile, StudyKind};
use adhesim::analysis::fit::fit_jkr_work_of_adhesion;
use adhesim::analysis::friction::eq12_rolling_resistance;
use adhesim::analysis::reference::Jkr;
use adhesim_scenario::TranslationResults;
use anyhow::{Context, Result};
use serde::Serialize;
use std::path::Path;

/// One translation case's row of `table.csv`.
#[derive(Debug, Clone, Serialize)]
pub struct Row {
    pub alpha: f64,
    pub amplitude: f64,
    pub depth_norm: f64,
    /// Sliding: substrate orientation θ in degrees (empty for rolling).
    pub substrate_angle: Option<f64>,
    pub gamma_approach_norm: Option<f64>,
    pub gamma_pulloff_norm: Option<f64>,
    pub mean_tangential_force_norm: Option<f64>,
    pub mean_tangential_force_work_norm: Option<f64>,
    pub tangential_force_fluctuation_norm: Option<f64>,
    pub eq12_prediction_norm: Option<f64>,
    pub eq12_ratio: Option<f64>,
    pub eq12_ratio_work: Option<f64>,
    pub mean_normal_force_norm: Option<f64>,
    pub contact_half_width_norm: Option<f64>,
    pub contact_radius_norm: Option<f64>,
    pub compactness: f64,
    pub boundary_force_per_width_norm: Option<f64>,
    pub gamma3_norm: Option<f64>,
    pub gamma3_half_width_norm: Option<f64>,
    pub energy_balance_ratio: Option<f64>,
    pub jumps: usize,
    pub border_contact: bool,
    pub wall_seconds: f64,
}

/// One α's row of `alphas.csv`.
#[derive(Debug, Clone, Serialize)]
pub struct AlphaRow {
    pub alpha: f64,
    pub amplitude: f64,
    pub gamma_approach_norm: Option<f64>,
    pub gamma_pulloff_norm: Option<f64>,
    pub normal_wall_seconds: Option<f64>,
    /// γ3/γ0: JKR fit of F_N vs the contact radius (farthest element, as for γ1 and γ2)
    /// over all depths (Fig. 8).
    pub gamma3_norm: Option<f64>,
    /// The same fit against the half-width perpendicular to the motion.
    pub gamma3_half_width_norm: Option<f64>,
    /// Mean over depths of the per-step F_T / 2a(γ2 − γ1).
    pub mean_eq12_ratio: Option<f64>,
    pub mean_eq12_ratio_work: Option<f64>,
    /// Mean over depths of F_T/|F_JKR| (Fig. 10a).
    pub mean_tangential_force_norm: Option<f64>,
    pub mean_tangential_force_work_norm: Option<f64>,
    /// Mean over depths (and substrate angles) of F_T/(2a γ0).
    pub boundary_force_per_width_norm: Option<f64>,
    /// Standard error of that mean over the cases (spread/√n, n ≥ 2 cases).
    pub boundary_force_per_width_sem: Option<f64>,
    /// Standard error of mean_tangential_force_norm over the cases.
    pub mean_tangential_force_sem: Option<f64>,
    /// Mean over depths of A_real/(πa²) (Fig. 10b).
    pub compactness: f64,
}

pub fn mean(values: impl Iterator<Item = Option<f64>>) -> Option<f64> {
    let v: Vec<f64> = values.flatten().filter(|x| x.is_finite()).collect();
    (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
}

/// ", θ = 20°" for a sliding case's substrate angle, "" without one.
pub fn theta_label(angle: Option<f64>) -> String {
    angle.map(|t| format!(", θ = {t}°")).unwrap_or_default()
}

/// Standard error of the mean of the finite values (sample standard deviation / √n), for
/// n ≥ 2.
pub fn standard_error(values: impl Iterator<Item = Option<f64>>) -> Option<f64> {
    let v: Vec<f64> = values.flatten().filter(|x| x.is_finite()).collect();
    let n = v.len() as f64;
    (v.len() >= 2).then(|| {
        let m = v.iter().sum::<f64>() / n;
        (v.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1.0) / n).sqrt()
    })
}

/// Writes a table atomically (a killed or failing write leaves the previous file or none).
pub fn write_csv<T: Serialize>(path: &Path, rows: &[T]) -> Result<()> {
    let mut w = csv::Writer::from_writer(Vec::new());
    for row in rows {
        w.serialize(row)
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    let bytes = w
        .into_inner()
        .map_err(|e| anyhow::anyhow!("cannot write {}: {e}", path.display()))?;
    adhesim_scenario::batch::write_atomically(path, &bytes)
}

/// A case's α index and its analysed results.
pub type CaseResults = (usize, TranslationResults);

/// The row of each case (`table.csv`) and its results, in the order of the plan; `gammas`
/// holds (γ1, γ2, wall time) of each α's normal run.
pub fn case_rows(
    cases: &[(usize, f64, Option<f64>)],
    results: Vec<(TranslationResults, f64)>,
    study: &StudyFile,
    amplitudes: &[f64],
    gammas: &[(Option<f64>, Option<f64>, Option<f64>)],
    jkr: &Jkr,
) -> (Vec<Row>, Vec<CaseResults>) {
    let gamma0 = jkr.work_of_adhesion;
    let f_jkr = jkr.critical_force().abs();
    let a_jkr = jkr.critical_radius();
    let mut rows = Vec::new();
    let mut per_case: Vec<(usize, TranslationResults)> = Vec::new();
    for ((i, d, angle), (r, seconds)) in cases.iter().zip(results) {
        let (g1, g2, _) = gammas[*i];
        let prediction = match (g1, g2) {
            (Some(g1), Some(g2)) => Some(eq12_rolling_resistance(r.contact_half_width, g1, g2)),
            _ => None,
        };
        let ratio = |f: Option<f64>| match (f, prediction) {
            (Some(f), Some(p)) if p != 0.0 => Some(f / p),
            _ => None,
        };
        rows.push(Row {
            alpha: study.alphas[*i],
            amplitude: amplitudes[*i],
            depth_norm: *d,
            substrate_angle: *angle,
            gamma_approach_norm: g1.map(|g| g / gamma0),
            gamma_pulloff_norm: g2.map(|g| g / gamma0),
            mean_tangential_force_norm: r.mean_tangential_force.map(|f| f / f_jkr),
            mean_tangential_force_work_norm: Some(r.mean_tangential_force_work / f_jkr),
            tangential_force_fluctuation_norm: Some(r.tangential_force_fluctuation / f_jkr),
            eq12_prediction_norm: prediction.map(|p| p / f_jkr),
            eq12_ratio: ratio(r.mean_tangential_force),
            eq12_ratio_work: ratio(Some(r.mean_tangential_force_work)),
            mean_normal_force_norm: Some(r.mean_normal_force / f_jkr),
            contact_half_width_norm: Some(r.contact_half_width / a_jkr),
            contact_radius_norm: Some(r.contact_radius / a_jkr),
            compactness: r.compactness,
            boundary_force_per_width_norm: r
                .mean_tangential_force
                .filter(|_| r.contact_half_width > 0.0)
                .map(|f| f / (2.0 * r.contact_half_width * gamma0)),
            gamma3_norm: r.gamma3.map(|g| g / gamma0),
            gamma3_half_width_norm: r.gamma3_half_width.map(|g| g / gamma0),
            energy_balance_ratio: r.energy_balance_ratio,
            jumps: r.jumps,
            border_contact: r.border_contact,
            wall_seconds: seconds,
        });
        per_case.push((*i, r));
    }
    (rows, per_case)
}

/// The row of each α (`alphas.csv`): means over its cases, their standard errors and the
/// γ3 fits over its depths (rolling).
pub fn alpha_rows(
    study: &StudyFile,
    amplitudes: &[f64],
    gammas: &[(Option<f64>, Option<f64>, Option<f64>)],
    rows: &[Row],
    per_case: &[(usize, TranslationResults)],
    jkr: &Jkr,
) -> Vec<AlphaRow> {
    let gamma0 = jkr.work_of_adhesion;
    let mut alpha_rows = Vec::new();
    for (i, &alpha) in study.alphas.iter().enumerate() {
        let mine: Vec<&Row> = rows
            .iter()
            .filter(|r| r.alpha == alpha && r.amplitude == amplitudes[i])
            .collect();
        let fit_gamma3 = |radius_of: fn(&TranslationResults) -> f64| {
            let points: Vec<(f64, f64)> = per_case
                .iter()
                .filter(|(j, _)| *j == i)
                .map(|(_, r)| (radius_of(r), r.mean_normal_force))
                .collect();
            fit_jkr_work_of_adhesion(&points, jkr.radius, jkr.contact_modulus).map(|f| f.work_of_adhesion / gamma0)
        };
        let rolling = study.kind == StudyKind::Rolling;
        let gamma3 = fit_gamma3(|r| r.contact_radius).filter(|_| rolling);
        let gamma3_half_width = fit_gamma3(|r| r.contact_half_width).filter(|_| rolling);
        let (g1, g2, normal_seconds) = gammas[i];
        alpha_rows.push(AlphaRow {
            alpha,
            amplitude: amplitudes[i],
            gamma_approach_norm: g1.map(|g| g / gamma0),
            gamma_pulloff_norm: g2.map(|g| g / gamma0),
            normal_wall_seconds: normal_seconds,
            gamma3_norm: gamma3,
            gamma3_half_width_norm: gamma3_half_width,
            mean_eq12_ratio: mean(mine.iter().map(|r| r.eq12_ratio)),
            mean_eq12_ratio_work: mean(mine.iter().map(|r| r.eq12_ratio_work)),
            mean_tangential_force_norm: mean(mine.iter().map(|r| r.mean_tangential_force_norm)),
            mean_tangential_force_work_norm: mean(mine.iter().map(|r| r.mean_tangential_force_work_norm)),
            boundary_force_per_width_norm: mean(mine.iter().map(|r| r.boundary_force_per_width_norm)),
            boundary_force_per_width_sem: standard_error(mine.iter().map(|r| r.boundary_force_per_width_norm)),
            mean_tangential_force_sem: standard_error(mine.iter().map(|r| r.mean_tangential_force_norm)),
            compactness: mean(mine.iter().map(|r| Some(r.compactness))).unwrap_or(f64::NAN),
        });
    }
    alpha_rows
}
