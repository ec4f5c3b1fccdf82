//! Maugis (1992) adhesive contact of a paraboloid with a Dugdale cohesive zone.
//!
//! D. Maugis, "Adhesion of spheres: the JKR-DMT transition using a Dugdale model", *J.
//! Colloid Interface Sci.* 150 (1992) 243–269. A constant tensile traction σ0 acts where
//! the gap lies below δc = γ0/σ0, between the contact radius a and the zone's outer edge
//! c = m·a. In Maugis' reduced units (docs/physics.md §4)
//!
//! - A = a/(πγ0R²/K)^(1/3), P̄ = P/(πγ0R), δ̄ = δ/(π²γ0²R/K²)^(1/3), K = 4E*/3,
//! - 1 = (λA²/2)[√(m²−1) + (m²−2)·atan√(m²−1)] + (4λ²A/3)[√(m²−1)·atan√(m²−1) − m + 1],
//! - P̄ = A³ − λA²[√(m²−1) + m²·atan√(m²−1)], δ̄ = A² − (4/3)λA√(m²−1),
//!
//! with the Maugis parameter λ = 2σ0·(R/(πγ0K²))^(1/3). The pull-off force runs from
//! 2πγ0R (DMT, λ → 0) to 1.5πγ0R (JKR, λ → ∞).

use std::f64::consts::PI;

/// The Maugis–Dugdale sphere: a paraboloid of radius R on a half-space of contact modulus
/// E*, with work of adhesion γ0 and cohesive stress σ0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MaugisDugdale {
    /// Radius of curvature R.
    pub radius: f64,
    /// Contact modulus E*.
    pub contact_modulus: f64,
    /// Work of adhesion γ0.
    pub work_of_adhesion: f64,
    /// Cohesive stress σ0 (the Dugdale traction).
    pub cohesive_stress: f64,
}

/// One point of the Maugis curve, in length and force units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MaugisPoint {
    /// Contact radius a.
    pub contact_radius: f64,
    /// Outer radius c of the cohesive zone.
    pub zone_radius: f64,
    /// Normal force P (> 0 compressive).
    pub force: f64,
    /// Approach δ (the indentation depth from first contact).
    pub depth: f64,
}

/// λ = 2σ0·(R/(πγ0K²))^(1/3), K = 4E*/3.
pub fn maugis_parameter(radius: f64, contact_modulus: f64, work_of_adhesion: f64, cohesive_stress: f64) -> f64 {
    let k = 4.0 / 3.0 * contact_modulus;
    2.0 * cohesive_stress * (radius / (PI * work_of_adhesion * k * k)).cbrt()
}

/// σ0 of a Maugis parameter λ: the inverse of [`maugis_parameter`].
pub fn cohesive_stress_for(radius: f64, contact_modulus: f64, work_of_adhesion: f64, lambda: f64) -> f64 {
    lambda / maugis_parameter(radius, contact_modulus, work_of_adhesion, 1.0)
}

/// The zone's edge m = c/a of the reduced contact radius `a` (A) at Maugis parameter
/// `lambda`: the root m > 1 of Maugis' Eq. (the right-hand side grows from 0 at m = 1
/// without bound), by bisection to machine precision.
pub fn zone_ratio(lambda: f64, a: f64) -> f64 {
    let excess = |m: f64| {
        let s = (m * m - 1.0).sqrt();
        let t = s.atan();
        0.5 * lambda * a * a * (s + (m * m - 2.0) * t) + 4.0 / 3.0 * lambda * lambda * a * (s * t - m + 1.0) - 1.0
    };
    let (mut low, mut high) = (1.0, 2.0);
    while excess(high) < 0.0 {
        low = high;
        high *= 2.0;
    }
    for _ in 0..200 {
        let middle = 0.5 * (low + high);
        if middle <= low || middle >= high {
            break;
        }
        if excess(middle) < 0.0 {
            low = middle;
        } else {
            high = middle;
        }
    }
    0.5 * (low + high)
}

/// Reduced force P̄ and approach δ̄ at reduced contact radius A (Maugis' units).
pub fn reduced_force_and_depth(lambda: f64, a: f64) -> (f64, f64) {
    let m = zone_ratio(lambda, a);
    let s = (m * m - 1.0).sqrt();
    let t = s.atan();
    let force = a.powi(3) - lambda * a * a * (s + m * m * t);
    let depth = a * a - 4.0 / 3.0 * lambda * a * s;
    (force, depth)
}

/// The smallest reduced force min P̄ over the curve, and the A where it is reached: the
/// largest adhesive force under displacement control is −min P̄·πγ0R. A scan of A on a
/// geometric grid from 1e-4 to 10 brackets the minimum, golden-section search refines it.
pub fn reduced_pull_off(lambda: f64) -> (f64, f64) {
    let a = golden_minimum(|a| reduced_force_and_depth(lambda, a).0);
    (reduced_force_and_depth(lambda, a).0, a)
}

/// The reduced contact radius A where the approach δ̄ is smallest: the vertical tangent of
/// the force–approach curve, where contact is lost under displacement control. A scan of
/// A on a geometric grid from 1e-4 to 10 brackets it, golden-section search refines it.
pub fn reduced_jump_off(lambda: f64) -> f64 {
    golden_minimum(|a| reduced_force_and_depth(lambda, a).1)
}

/// The A in (1e-4, 10) where `value` is smallest: a scan on a geometric grid of 2000
/// points brackets it, golden-section search refines it.
fn golden_minimum(value: impl Fn(f64) -> f64) -> f64 {
    let samples = 2000;
    let a_of = |i: usize| 1e-4 * (1e5f64).powf(i as f64 / samples as f64);
    let best = (0..=samples)
        .map(|i| (i, value(a_of(i))))
        .min_by(|x, y| x.1.total_cmp(&y.1))
        .map(|(i, _)| i)
        .unwrap_or(0);
    let (mut low, mut high) = (a_of(best.saturating_sub(1)), a_of((best + 1).min(samples)));
    let golden = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..100 {
        let left = high - golden * (high - low);
        let right = low + golden * (high - low);
        if value(left) < value(right) {
            high = right;
        } else {
            low = left;
        }
    }
    0.5 * (low + high)
}

impl MaugisDugdale {
    /// The force on the branch that displacement control follows (A beyond the vertical
    /// tangent, where δ grows with A) at approach `depth`; None below the jump-off depth.
    /// Bisection on A, the branch's δ̄ being increasing.
    pub fn force_at_depth(&self, depth: f64) -> Option<f64> {
        let lambda = self.lambda();
        let target = depth / self.depth_unit();
        let depth_of = |a: f64| reduced_force_and_depth(lambda, a).1;
        let mut low = reduced_jump_off(lambda);
        if target < depth_of(low) {
            return None;
        }
        let mut high = 2.0 * low.max(1.0);
        while depth_of(high) < target {
            low = high;
            high *= 2.0;
        }
        for _ in 0..200 {
            let middle = 0.5 * (low + high);
            if middle <= low || middle >= high {
                break;
            }
            if depth_of(middle) < target {
                low = middle;
            } else {
                high = middle;
            }
        }
        Some(reduced_force_and_depth(lambda, 0.5 * (low + high)).0 * self.force_unit())
    }

    /// K = 4E*/3.
    fn k(&self) -> f64 {
        4.0 / 3.0 * self.contact_modulus
    }

    /// The Maugis parameter λ of this contact.
    pub fn lambda(&self) -> f64 {
        maugis_parameter(
            self.radius,
            self.contact_modulus,
            self.work_of_adhesion,
            self.cohesive_stress,
        )
    }

    /// Unit of the contact radius, (πγ0R²/K)^(1/3).
    pub fn radius_unit(&self) -> f64 {
        (PI * self.work_of_adhesion * self.radius * self.radius / self.k()).cbrt()
    }

    /// Unit of force, πγ0R.
    pub fn force_unit(&self) -> f64 {
        PI * self.work_of_adhesion * self.radius
    }

    /// Unit of the approach, (π²γ0²R/K²)^(1/3).
    pub fn depth_unit(&self) -> f64 {
        (PI * PI * self.work_of_adhesion.powi(2) * self.radius / self.k().powi(2)).cbrt()
    }

    /// The state at contact radius a.
    pub fn at_contact_radius(&self, contact_radius: f64) -> MaugisPoint {
        let lambda = self.lambda();
        let a = contact_radius / self.radius_unit();
        let (force, depth) = reduced_force_and_depth(lambda, a);
        MaugisPoint {
            contact_radius,
            zone_radius: zone_ratio(lambda, a) * contact_radius,
            force: force * self.force_unit(),
            depth: depth * self.depth_unit(),
        }
    }

    /// The largest adhesive force under displacement control, −min P (> 0).
    pub fn max_adhesive_force(&self) -> f64 {
        -reduced_pull_off(self.lambda()).0 * self.force_unit()
    }

    /// The state at the largest adhesive force.
    pub fn at_max_adhesive_force(&self) -> MaugisPoint {
        let (_, a) = reduced_pull_off(self.lambda());
        self.at_contact_radius(a * self.radius_unit())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The zone equation holds at the root, and m → 1 when λ grows (the zone shrinks to
    /// the JKR crack tip).
    #[test]
    fn zone_ratio_solves_the_zone_equation() {
        for (lambda, a) in [(0.1, 0.5), (1.0, 1.0), (5.0, 2.0)] {
            let m = zone_ratio(lambda, a);
            let s = (m * m - 1.0).sqrt();
            let t = s.atan();
            let rhs =
                0.5 * lambda * a * a * (s + (m * m - 2.0) * t) + 4.0 / 3.0 * lambda * lambda * a * (s * t - m + 1.0);
            assert!((rhs - 1.0).abs() < 1e-12, "λ {lambda}, A {a}: {rhs}");
        }
        assert!(zone_ratio(1000.0, 1.0) < 1.01);
    }

    /// DMT limit: λ → 0 gives a pull-off of 2πγ0R. The DMT value is approached as λ^(2/3)
    /// (Maugis 1992, Fig. 5): at λ = 1e-3 the difference is below 1 %.
    #[test]
    fn pull_off_tends_to_dmt_at_small_lambda() {
        let (force, _) = reduced_pull_off(1e-3);
        assert!((-force - 2.0).abs() < 0.02, "{force}");
    }

    /// JKR limit: λ → ∞ gives 1.5πγ0R (the JKR force at fixed load, reached under
    /// displacement control before the jump), and Maugis' curve becomes the JKR curve.
    #[test]
    fn pull_off_tends_to_jkr_at_large_lambda() {
        let (force, _) = reduced_pull_off(1e3);
        assert!((-force - 1.5).abs() < 0.01, "{force}");
        // The JKR curve in the same units: P̄ = A³ − A^(3/2)·√6, δ̄ = A² − (2/3)·√(6A).
        let lambda = 1e4;
        for a in [0.5, 1.0, 2.0] {
            let (force, depth) = reduced_force_and_depth(lambda, a);
            let jkr_force = a.powi(3) - (6.0 * a.powi(3)).sqrt();
            let jkr_depth = a * a - 2.0 / 3.0 * (6.0 * a).sqrt();
            assert!((force - jkr_force).abs() < 1e-2, "A {a}: {force} vs {jkr_force}");
            assert!((depth - jkr_depth).abs() < 1e-2, "A {a}: {depth} vs {jkr_depth}");
        }
    }

    /// On the displacement-controlled branch the force at the depth of a point is the
    /// point's force; below the jump-off depth there is none. In the JKR limit the vertical
    /// tangent of δ̄ = A² − (2/3)√(6A) is at A = (√6/6)^(2/3) (the JKR jump-off).
    #[test]
    fn force_at_depth_inverts_the_branch() {
        let model = MaugisDugdale {
            radius: 1.0,
            contact_modulus: 1.0,
            work_of_adhesion: 1e-4,
            cohesive_stress: cohesive_stress_for(1.0, 1.0, 1e-4, 1.0),
        };
        for a in [0.06, 0.08, 0.1] {
            let point = model.at_contact_radius(a);
            let force = model.force_at_depth(point.depth).unwrap();
            assert!((force - point.force).abs() < 1e-12 * model.force_unit(), "a {a}");
        }
        let jump = reduced_jump_off(1.0);
        let lowest = reduced_force_and_depth(1.0, jump).1 * model.depth_unit();
        assert!(model.force_at_depth(1.01 * lowest).is_none());
        let jkr_jump = reduced_jump_off(1e4);
        let expected = (6f64.sqrt() / 6.0).powf(2.0 / 3.0);
        assert!((jkr_jump - expected).abs() < 1e-2, "{jkr_jump} vs {expected}");
    }

    /// The pull-off decreases monotonically from DMT to JKR, and the dimensional helpers
    /// are consistent with the reduced curve.
    #[test]
    fn pull_off_is_monotone_in_lambda_and_units_agree() {
        let mut previous = f64::INFINITY;
        for lambda in [0.01, 0.1, 0.3, 1.0, 3.0, 10.0] {
            let force = -reduced_pull_off(lambda).0;
            assert!(force < previous && force > 1.5 && force < 2.0, "λ {lambda}: {force}");
            previous = force;
        }
        let gamma = 1e-4;
        let sigma = cohesive_stress_for(1.0, 1.0, gamma, 0.3);
        let model = MaugisDugdale {
            radius: 1.0,
            contact_modulus: 1.0,
            work_of_adhesion: gamma,
            cohesive_stress: sigma,
        };
        assert!((model.lambda() - 0.3).abs() < 1e-12);
        let expected = -reduced_pull_off(0.3).0 * PI * gamma;
        assert!((model.max_adhesive_force() - expected).abs() < 1e-15);
    }
}
