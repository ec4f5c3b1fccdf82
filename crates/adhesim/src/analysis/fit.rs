//! Effective works of adhesion from simulated or measured curves (paper Sect. 2.3).

use std::f64::consts::PI;

/// Result of a JKR fit of the work of adhesion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JkrFit {
    /// Fitted effective work of adhesion γ (≥ 0).
    pub work_of_adhesion: f64,
    /// Root-mean-square force residual of the fit.
    pub residual_rms: f64,
    /// Number of points used.
    pub points: usize,
}

/// Least-squares JKR fit of γ to force–contact-radius pairs of one branch:
/// F = 4E*a³/(3R) − √(8πγE*a³) is linear in s = √γ, so with A_i = 4E*a_i³/(3R),
/// B_i = √(8πE*a_i³): s = Σ B_i(A_i − F_i)/Σ B_i², γ = max(s, 0)². `None` without points
/// of positive radius.
pub fn fit_jkr_work_of_adhesion(points: &[(f64, f64)], radius: f64, contact_modulus: f64) -> Option<JkrFit> {
    let (mut numerator, mut denominator, mut count) = (0.0, 0.0, 0usize);
    for &(a, force) in points {
        if !(a > 0.0 && a.is_finite() && force.is_finite()) {
            continue;
        }
        let hertz = 4.0 * contact_modulus * a.powi(3) / (3.0 * radius);
        let adhesive = (8.0 * PI * contact_modulus * a.powi(3)).sqrt();
        numerator += adhesive * (hertz - force);
        denominator += adhesive * adhesive;
        count += 1;
    }
    if count == 0 {
        return None;
    }
    let root = (numerator / denominator).max(0.0);
    let mut squared = 0.0;
    for &(a, force) in points {
        if !(a > 0.0 && a.is_finite() && force.is_finite()) {
            continue;
        }
        let model =
            4.0 * contact_modulus * a.powi(3) / (3.0 * radius) - root * (8.0 * PI * contact_modulus * a.powi(3)).sqrt();
        squared += (force - model).powi(2);
    }
    Some(JkrFit {
        work_of_adhesion: root * root,
        residual_rms: (squared / count as f64).sqrt(),
        points: count,
    })
}

/// JKR fit of γ to the depth–contact-radius relation d = a²/R − √(2πγa/E*), linear in √γ
/// (paper Eq. 13, used for γ3 of rolling contacts).
pub fn fit_jkr_depth_work_of_adhesion(points: &[(f64, f64)], radius: f64, contact_modulus: f64) -> Option<JkrFit> {
    let (mut numerator, mut denominator, mut count) = (0.0, 0.0, 0usize);
    for &(a, depth) in points {
        if !(a > 0.0 && a.is_finite() && depth.is_finite()) {
            continue;
        }
        let basis = (2.0 * PI * a / contact_modulus).sqrt();
        numerator += basis * (a * a / radius - depth);
        denominator += basis * basis;
        count += 1;
    }
    if count == 0 {
        return None;
    }
    let root = (numerator / denominator).max(0.0);
    let squared: f64 = points
        .iter()
        .filter(|(a, d)| *a > 0.0 && a.is_finite() && d.is_finite())
        .map(|&(a, d)| (d - (a * a / radius - root * (2.0 * PI * a / contact_modulus).sqrt())).powi(2))
        .sum();
    Some(JkrFit {
        work_of_adhesion: root * root,
        residual_rms: (squared / count as f64).sqrt(),
        points: count,
    })
}

/// Power law y = c·t^n fitted by linear least squares in log–log (paper Eq. 15).
/// Returns (c, n), or `None` with fewer than two positive points.
pub fn fit_power_law(points: &[(f64, f64)]) -> Option<(f64, f64)> {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(t, y)| *t > 0.0 && *y > 0.0)
        .map(|&(t, y)| (t.ln(), y.ln()))
        .collect();
    let (slope, intercept) = fit_line(&logs)?;
    Some((intercept.exp(), slope))
}

/// Straight line y = slope·x + intercept by least squares; `None` with fewer than two
/// distinct x.
pub fn fit_line(points: &[(f64, f64)]) -> Option<(f64, f64)> {
    let count = points.len() as f64;
    if points.len() < 2 {
        return None;
    }
    let mean_x = points.iter().map(|p| p.0).sum::<f64>() / count;
    let mean_y = points.iter().map(|p| p.1).sum::<f64>() / count;
    let sxx: f64 = points.iter().map(|p| (p.0 - mean_x).powi(2)).sum();
    if sxx <= 0.0 {
        return None;
    }
    let sxy: f64 = points.iter().map(|p| (p.0 - mean_x) * (p.1 - mean_y)).sum();
    let slope = sxy / sxx;
    Some((slope, mean_y - slope * mean_x))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::reference::Jkr;

    /// Exact JKR data: γ recovered to 1e-6 relative (round-off only), zero residual.
    #[test]
    fn recovers_gamma_from_synthetic_jkr_data() {
        let jkr = Jkr {
            radius: 2.0,
            contact_modulus: 3.0,
            work_of_adhesion: 0.0123,
        };
        let a0 = jkr.critical_radius();
        let force: Vec<(f64, f64)> = (1..60)
            .map(|i| (a0 * i as f64 / 20.0, jkr.force(a0 * i as f64 / 20.0)))
            .collect();
        let fit = fit_jkr_work_of_adhesion(&force, 2.0, 3.0).unwrap();
        assert!((fit.work_of_adhesion / 0.0123 - 1.0).abs() < 1e-6);
        assert!(fit.residual_rms < 1e-9 * jkr.critical_force().abs());
        let depth: Vec<(f64, f64)> = (1..60)
            .map(|i| (a0 * i as f64 / 20.0, jkr.depth(a0 * i as f64 / 20.0)))
            .collect();
        let fit = fit_jkr_depth_work_of_adhesion(&depth, 2.0, 3.0).unwrap();
        assert!((fit.work_of_adhesion / 0.0123 - 1.0).abs() < 1e-6);
        assert!(fit_jkr_work_of_adhesion(&[], 1.0, 1.0).is_none());
    }

    #[test]
    fn power_law_and_line() {
        let points: Vec<(f64, f64)> = (1..20).map(|t| (t as f64, 0.07292 * (t as f64).powf(0.0883))).collect();
        let (c, n) = fit_power_law(&points).unwrap();
        assert!((c / 0.07292 - 1.0).abs() < 1e-12 && (n / 0.0883 - 1.0).abs() < 1e-12);
        assert!(fit_line(&[(1.0, 1.0)]).is_none());
    }
}
