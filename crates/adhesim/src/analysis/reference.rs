//! Closed-form solutions used by tests, analysis and the command line.
//!
//! All for a rigid indenter on an elastic half-space of contact modulus E*.

mod maugis;

pub use maugis::{
    cohesive_stress_for, maugis_parameter, reduced_force_and_depth, reduced_jump_off, reduced_pull_off, zone_ratio,
    MaugisDugdale, MaugisPoint,
};

use std::f64::consts::PI;

/// Hertz (1882) contact of a paraboloid of radius R pressed to depth d.
///
/// # Example
/// ```
/// use adhesim::analysis::reference::Hertz;
///
/// // F = (4/3)E*R^{1/2}d^{3/2}: R = 1, E* = 4, d = 0.01 gives 16/3000.
/// let hertz = Hertz { radius: 1.0, contact_modulus: 4.0 };
/// assert!((hertz.force(0.01) - 16.0 / 3000.0).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hertz {
    /// Radius of curvature R.
    pub radius: f64,
    /// Contact modulus E*.
    pub contact_modulus: f64,
}

impl Hertz {
    /// Contact radius a = √(Rd).
    pub fn contact_radius(&self, depth: f64) -> f64 {
        (self.radius * depth.max(0.0)).sqrt()
    }
    /// Force F = (4/3)E*R^½d^{3/2}.
    pub fn force(&self, depth: f64) -> f64 {
        4.0 / 3.0 * self.contact_modulus * self.radius.sqrt() * depth.max(0.0).powf(1.5)
    }
    /// Depth at which the force is F: d = (3F/(4E*√R))^{2/3}.
    pub fn depth_for_force(&self, force: f64) -> f64 {
        (0.75 * force.max(0.0) / (self.contact_modulus * self.radius.sqrt())).powf(2.0 / 3.0)
    }
    /// Pressure p0·√(1 − r²/a²), p0 = 2E*a/(πR).
    pub fn pressure(&self, depth: f64, r: f64) -> f64 {
        let a = self.contact_radius(depth);
        if r >= a {
            0.0
        } else {
            2.0 * self.contact_modulus * a / (PI * self.radius) * (1.0 - r * r / (a * a)).sqrt()
        }
    }
}

/// Johnson, Kendall & Roberts (1971) adhesive contact of a paraboloid, parametric in the
/// contact radius a; with the paper's normalisation (Popov et al. 2021, Eqs. 2–4, with
/// E*² in Eq. 3 where the paper misprints E*).
///
/// # Example
/// ```
/// use adhesim::analysis::reference::Jkr;
///
/// // Pull-off under load control: F = −(3/2)πγR at a = (9πγR²/(8E*))^{1/3}.
/// let jkr = Jkr { radius: 1.0, contact_modulus: 4.0, work_of_adhesion: 1e-3 };
/// assert!((jkr.critical_force() + 1.5 * std::f64::consts::PI * 1e-3).abs() < 1e-15);
/// assert!((jkr.force(jkr.critical_radius()) / jkr.critical_force() - 1.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jkr {
    /// Radius of curvature R.
    pub radius: f64,
    /// Contact modulus E*.
    pub contact_modulus: f64,
    /// Work of adhesion γ.
    pub work_of_adhesion: f64,
}

impl Jkr {
    /// F(a) = 4E*a³/(3R) − √(8πγE*a³).
    pub fn force(&self, a: f64) -> f64 {
        4.0 * self.contact_modulus * a.powi(3) / (3.0 * self.radius)
            - (8.0 * PI * self.work_of_adhesion * self.contact_modulus * a.powi(3)).sqrt()
    }
    /// d(a) = a²/R − √(2πγa/E*).
    pub fn depth(&self, a: f64) -> f64 {
        a * a / self.radius - (2.0 * PI * self.work_of_adhesion * a / self.contact_modulus).sqrt()
    }
    /// F_JKR = −(3/2)πγR: pull-off force under load control (negative: tensile).
    pub fn critical_force(&self) -> f64 {
        -1.5 * PI * self.work_of_adhesion * self.radius
    }
    /// d_JKR = −(3π²γ²R/(64E*²))^{1/3}.
    pub fn critical_depth(&self) -> f64 {
        -(3.0 * PI * PI * self.work_of_adhesion.powi(2) * self.radius / (64.0 * self.contact_modulus.powi(2))).cbrt()
    }
    /// a_JKR = (9πγR²/(8E*))^{1/3}.
    pub fn critical_radius(&self) -> f64 {
        (9.0 * PI * self.work_of_adhesion * self.radius.powi(2) / (8.0 * self.contact_modulus)).cbrt()
    }
    /// Contact radius on the stable-under-displacement-control branch (dd/da > 0,
    /// a ≥ 9^{-1/3}·a_JKR) at depth d, or `None` below the displacement-controlled jump
    /// depth −9^{1/3}|d_JKR|. Bisection on the monotonic branch.
    pub fn radius_at_depth(&self, depth: f64) -> Option<f64> {
        let a_min = self.critical_radius() / 9f64.cbrt();
        if depth < self.depth(a_min) {
            return None;
        }
        let mut high = a_min.max(1e-300);
        while self.depth(high) < depth {
            high *= 2.0;
        }
        let mut low = a_min;
        for _ in 0..200 {
            let middle = 0.5 * (low + high);
            if self.depth(middle) < depth {
                low = middle;
            } else {
                high = middle;
            }
        }
        Some(0.5 * (low + high))
    }
    /// Force at depth d on the displacement-controlled stable branch.
    pub fn force_at_depth(&self, depth: f64) -> Option<f64> {
        self.radius_at_depth(depth).map(|a| self.force(a))
    }
}

/// Flat circular punch of radius a (Boussinesq 1885; Kendall 1971 for adhesion).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlatPunchReference {
    /// Punch radius a.
    pub radius: f64,
    /// Contact modulus E*.
    pub contact_modulus: f64,
}

impl FlatPunchReference {
    /// Normal stiffness dF/dd = 2E*a.
    pub fn stiffness(&self) -> f64 {
        2.0 * self.contact_modulus * self.radius
    }
    /// Kendall's pull-off force −√(8πa³E*γ) (negative: tensile).
    pub fn kendall_force(&self, work_of_adhesion: f64) -> f64 {
        -(8.0 * PI * self.radius.powi(3) * self.contact_modulus * work_of_adhesion).sqrt()
    }
    /// Depth at Kendall pull-off, −√(2πaγ/E*).
    pub fn kendall_depth(&self, work_of_adhesion: f64) -> f64 {
        -(2.0 * PI * self.radius * work_of_adhesion / self.contact_modulus).sqrt()
    }
}

/// Tensile force magnitude at which detachment starts at the major-axis ends of a flat
/// elliptic punch (semi-axes a ≥ b): 2√(2πE*γ)·b·√a (docs/physics.md §4).
pub fn elliptic_punch_onset_force(semi_axes: (f64, f64), contact_modulus: f64, work_of_adhesion: f64) -> f64 {
    let (a, b) = if semi_axes.0 >= semi_axes.1 {
        semi_axes
    } else {
        (semi_axes.1, semi_axes.0)
    };
    2.0 * (2.0 * PI * contact_modulus * work_of_adhesion).sqrt() * b * a.sqrt()
}

/// Johnson parameter α = √(2λγ/(π²h²E*)) (Johnson 1995; paper Eq. 5).
pub fn johnson_parameter(wavelength: f64, amplitude: f64, work_of_adhesion: f64, contact_modulus: f64) -> f64 {
    (2.0 * wavelength * work_of_adhesion / (PI * PI * amplitude * amplitude * contact_modulus)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jkr_normalised_values() {
        // Normalised JKR (docs/physics.md §4): F/|F_JKR| = Â³ − 2Â^{3/2}, d/|d_JKR| = 3Â² − 4Â^{1/2}.
        let jkr = Jkr {
            radius: 1.3,
            contact_modulus: 2.1,
            work_of_adhesion: 0.07,
        };
        let (f, d, a) = (
            jkr.critical_force().abs(),
            jkr.critical_depth().abs(),
            jkr.critical_radius(),
        );
        for &ah in &[0.3f64, 1.0, 1.2114, 2.68] {
            let expected_f = ah.powi(3) - 2.0 * ah.powf(1.5);
            let expected_d = 3.0 * ah * ah - 4.0 * ah.sqrt();
            assert!((jkr.force(ah * a) / f - expected_f).abs() < 1e-12);
            assert!((jkr.depth(ah * a) / d - expected_d).abs() < 1e-12);
        }
        // F_JKR is the minimum of F(a) and d_JKR the depth there.
        assert!((jkr.force(a) - jkr.critical_force()).abs() < 1e-12 * f);
        assert!((jkr.depth(a) - jkr.critical_depth()).abs() < 1e-12 * d);
        // displacement-controlled jump at −9^{1/3}|d_JKR| with F = −(5/9)|F_JKR|
        let a_jump = jkr.radius_at_depth(-9f64.cbrt() * d * (1.0 - 1e-12)).unwrap();
        assert!((a_jump / a - 9f64.powf(-1.0 / 3.0)).abs() < 1e-4);
        assert!((jkr.force(a_jump) / f + 5.0 / 9.0).abs() < 1e-6);
        assert!(jkr.radius_at_depth(-2.1 * d).is_none());
        assert!((jkr.force_at_depth(15.0 * d).unwrap() / f - 10.475).abs() < 1e-3);
    }

    #[test]
    fn hertz_consistency() {
        let hertz = Hertz {
            radius: 2.0,
            contact_modulus: 3.0,
        };
        let d = 0.01;
        let a = hertz.contact_radius(d);
        let p0 = hertz.pressure(d, 0.0);
        assert!((p0 - 1.5 * hertz.force(d) / (PI * a * a)).abs() < 1e-12 * p0);
        assert!((hertz.depth_for_force(hertz.force(d)) - d).abs() < 1e-15);
    }

    #[test]
    fn johnson_parameter_formula() {
        let alpha = johnson_parameter(PI * PI / 2.0, 1.0, 1.0, 1.0);
        assert!((alpha - 1.0).abs() < 1e-15);
    }
}
