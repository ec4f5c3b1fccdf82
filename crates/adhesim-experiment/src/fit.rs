//! Fits of experiment series: straight lines, the power law of Eq. 15, the friction law of
//! Eq. 18 and the pinned phase after reversal. Every line (the power law and the friction
//! law are lines after a change of variables) is the library's one least-squares line,
//! [`adhesim::analysis::fit::fit_line`]. The JKR work of adhesion on a branch of F(a)
//! is the library's one fit, [`adhesim::analysis::fit::fit_jkr_work_of_adhesion`]
//! (docs/physics.md §5), re-exported here so that all fits of an experiment are found in one
//! place.

use crate::{invalid, ExperimentError};
use adhesim::analysis::fit::fit_line;
pub use adhesim::analysis::fit::{fit_jkr_work_of_adhesion, JkrFit};
use std::f64::consts::PI;

/// Least-squares straight line y = slope·x + intercept.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearFit {
    /// Slope.
    pub slope: f64,
    /// Intercept at x = 0.
    pub intercept: f64,
    /// Coefficient of determination (1 when y is constant and fitted exactly).
    pub r2: f64,
    /// Points used.
    pub points: usize,
}

/// Ordinary least squares on finite pairs (non-finite pairs are skipped): the library's one
/// line fit, [`adhesim::analysis::fit::fit_line`], with R² and the point count on top.
pub fn linear_fit(x: &[f64], y: &[f64]) -> Result<LinearFit, ExperimentError> {
    if x.len() != y.len() {
        return Err(ExperimentError::LengthMismatch(x.len(), y.len()));
    }
    let pairs: Vec<(f64, f64)> = x
        .iter()
        .zip(y)
        .map(|(&a, &b)| (a, b))
        .filter(|(a, b)| a.is_finite() && b.is_finite())
        .collect();
    if pairs.len() < 2 {
        return Err(ExperimentError::TooFewPoints {
            fit: "linear",
            needed: 2,
            got: pairs.len(),
        });
    }
    // Abscissae equal to round-off would give a slope of noise, not a line.
    let (low, high) = pairs
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (a, _)| {
            (lo.min(*a), hi.max(*a))
        });
    let degenerate = Err(ExperimentError::Degenerate("linear", "all abscissae are equal"));
    if high - low <= 1e-12 * low.abs().max(high.abs()) {
        return degenerate;
    }
    let Some((slope, intercept)) = fit_line(&pairs) else {
        return degenerate;
    };
    let n = pairs.len() as f64;
    let mean_y = pairs.iter().map(|p| p.1).sum::<f64>() / n;
    let total: f64 = pairs.iter().map(|p| (p.1 - mean_y).powi(2)).sum();
    let residual: f64 = pairs.iter().map(|p| (p.1 - slope * p.0 - intercept).powi(2)).sum();
    let r2 = if total > 0.0 { 1.0 - residual / total } else { 1.0 };
    Ok(LinearFit {
        slope,
        intercept,
        r2,
        points: pairs.len(),
    })
}

/// |F| = coefficient · t^exponent (paper Eq. 15).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PowerLaw {
    /// c in |F| = c·t^n.
    pub coefficient: f64,
    /// n.
    pub exponent: f64,
    /// R² of the log–log line.
    pub r2: f64,
    /// Points used (t > 0, F ≠ 0).
    pub points: usize,
}

/// Fits |F| = c·t^n by a straight line through (ln t, ln|F|); points with t ≤ 0 or F = 0 are
/// skipped.
pub fn power_law_fit(time: &[f64], force: &[f64]) -> Result<PowerLaw, ExperimentError> {
    if time.len() != force.len() {
        return Err(ExperimentError::LengthMismatch(time.len(), force.len()));
    }
    let (lt, lf): (Vec<f64>, Vec<f64>) = time
        .iter()
        .zip(force)
        .filter(|(t, f)| **t > 0.0 && f.abs() > 0.0 && t.is_finite() && f.is_finite())
        .map(|(t, f)| (t.ln(), f.abs().ln()))
        .unzip();
    let line = linear_fit(&lt, &lf).map_err(|e| rename(e, "power-law"))?;
    Ok(PowerLaw {
        coefficient: line.intercept.exp(),
        exponent: line.slope,
        r2: line.r2,
        points: line.points,
    })
}

/// τ_mean = 2q(πA)^(−1/2) + τ0 (paper Eq. 18).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionLaw {
    /// Area contribution τ0 (stress), the intercept.
    pub tau0: f64,
    /// Boundary friction q (force per length), slope·√π/2.
    pub q: f64,
    /// R² of the line τ vs A^(−1/2).
    pub r2: f64,
    /// Points used (A > 0).
    pub points: usize,
}

/// Fits τ_mean against A^(−1/2); points with A ≤ 0 are skipped.
pub fn friction_law_fit(area: &[f64], mean_stress: &[f64]) -> Result<FrictionLaw, ExperimentError> {
    if area.len() != mean_stress.len() {
        return Err(ExperimentError::LengthMismatch(area.len(), mean_stress.len()));
    }
    let (x, y): (Vec<f64>, Vec<f64>) = area
        .iter()
        .zip(mean_stress)
        .filter(|(a, t)| **a > 0.0 && a.is_finite() && t.is_finite())
        .map(|(a, t)| (a.sqrt().recip(), *t))
        .unzip();
    let line = linear_fit(&x, &y).map_err(|e| rename(e, "friction-law"))?;
    Ok(FrictionLaw {
        tau0: line.intercept,
        q: line.slope * PI.sqrt() / 2.0,
        r2: line.r2,
        points: line.points,
    })
}

/// The pinned phase after the reversal of an indentation (paper Fig. 14a, phase II): the
/// contact radius stays at its value at maximum depth while the force falls linearly.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PinnedPhase {
    /// Index of maximum depth (the reversal).
    pub reversal: usize,
    /// Index of the last pinned sample.
    pub last: usize,
    /// Depth retracted while pinned, `depth[reversal] − depth[last]`.
    pub depth_span: f64,
}

/// Samples after the maximum of `depth` whose radius stays within `relative_tolerance` of the
/// radius at the reversal. `None` without a retraction or without contact at reversal.
pub fn pinned_phase(
    depth: &[f64],
    radius: &[f64],
    relative_tolerance: f64,
) -> Result<Option<PinnedPhase>, ExperimentError> {
    if depth.len() != radius.len() {
        return Err(ExperimentError::LengthMismatch(depth.len(), radius.len()));
    }
    if !(relative_tolerance.is_finite() && relative_tolerance >= 0.0) {
        return Err(invalid("fits.pinned_tolerance", "must be >= 0", relative_tolerance));
    }
    let Some(reversal) = (0..depth.len())
        .filter(|&i| depth[i].is_finite())
        .max_by(|&i, &j| depth[i].total_cmp(&depth[j]))
    else {
        return Ok(None);
    };
    let a0 = radius[reversal];
    if !(a0.is_finite() && a0 > 0.0) || reversal + 1 >= depth.len() {
        return Ok(None);
    }
    let mut last = reversal;
    for i in reversal + 1..depth.len() {
        if !(radius[i].is_finite() && depth[i].is_finite()) || (radius[i] - a0).abs() > relative_tolerance * a0 {
            break;
        }
        last = i;
    }
    Ok(Some(PinnedPhase {
        reversal,
        last,
        depth_span: depth[reversal] - depth[last],
    }))
}

fn rename(e: ExperimentError, fit: &'static str) -> ExperimentError {
    match e {
        ExperimentError::TooFewPoints { needed, got, .. } => ExperimentError::TooFewPoints { fit, needed, got },
        ExperimentError::Degenerate(_, why) => ExperimentError::Degenerate(fit, why),
        other => other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use adhesim::rng::SplitMix64;

    /// Eq. 15 with the paper's constants (c = 0.07292, n = 0.0883), t = 1…100 min, 1 %
    /// multiplicative Gaussian noise (seed 7): c and n recovered within 1 %. 40 points of 1 %
    /// noise give a standard error of n of ≈ 0.0015·√(1/40)/spread ≈ 0.2 % of n.
    #[test]
    fn power_law_recovers_eq15() {
        let mut rng = SplitMix64::new(7);
        let t: Vec<f64> = (0..40).map(|i| 10f64.powf(2.0 * i as f64 / 39.0)).collect();
        let f: Vec<f64> = t
            .iter()
            .map(|t| -0.07292 * t.powf(0.0883) * (1.0 + 0.01 * rng.gaussian()))
            .collect();
        let fit = power_law_fit(&t, &f).unwrap();
        assert!((fit.coefficient / 0.07292 - 1.0).abs() < 0.01, "{fit:?}");
        assert!((fit.exponent / 0.0883 - 1.0).abs() < 0.01, "{fit:?}");
    }

    /// Eq. 18 with τ0 = 36 kPa, q = 5 N/m, areas 1–100 mm² (SI units), 0.2 % stress noise
    /// (seed 11): τ0 and q within 1 %. The boundary term 2q/√(πA) is 0.6–6 kPa here, so q is
    /// the harder parameter; 60 points of 70 Pa noise give a standard error well below 1 %.
    #[test]
    fn friction_law_recovers_eq18() {
        let mut rng = SplitMix64::new(11);
        let (tau0, q) = (36e3, 5.0);
        let area: Vec<f64> = (0..60).map(|i| 1e-6 * (1.0 + 99.0 * i as f64 / 59.0)).collect();
        let tau: Vec<f64> = area
            .iter()
            .map(|a| (2.0 * q / (PI * a).sqrt() + tau0) * (1.0 + 0.002 * rng.gaussian()))
            .collect();
        let fit = friction_law_fit(&area, &tau).unwrap();
        assert!((fit.tau0 / tau0 - 1.0).abs() < 0.01, "{fit:?}");
        assert!((fit.q / q - 1.0).abs() < 0.01, "{fit:?}");
    }

    /// Radius constant for 5 samples after the reversal, then shrinking: the pinned phase
    /// ends at the 5th (exact indices).
    #[test]
    fn pinned_phase_after_reversal() {
        let depth = [0.0, 1.0, 2.0, 3.0, 2.9, 2.8, 2.7, 2.6, 2.5, 2.4, 2.3];
        let radius = [0.0, 1.0, 1.5, 2.0, 2.0, 2.0, 2.0, 2.0, 2.0, 1.8, 1.6];
        let p = pinned_phase(&depth, &radius, 0.01).unwrap().unwrap();
        assert_eq!((p.reversal, p.last), (3, 8));
        assert!((p.depth_span - 0.5).abs() < 1e-12);
    }

    /// Degenerate input is an error, never a NaN result.
    #[test]
    fn degenerate_fits_are_errors() {
        assert!(linear_fit(&[1.0, 1.0], &[2.0, 3.0]).is_err());
        assert!(power_law_fit(&[0.0, -1.0], &[1.0, 2.0]).is_err());
        assert!(friction_law_fit(&[1.0], &[1.0]).is_err());
    }
}
