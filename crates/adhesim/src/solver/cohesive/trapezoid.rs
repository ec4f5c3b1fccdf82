//! The trapezoidal (smoothed Dugdale) cohesive law.

use super::law::CohesiveLaw;

/// The gap error, as a fraction of the range δ2, that the rounds resolve on the softening
/// part: the compressive solve leaves gap errors of about 1e-8·δ2 on the fig6 roll
/// (traction changes stagnating at 1e-10–4e-9 with σ0 = 0.05, s = 0.5, δ2 = 5.3e-4), so
/// the stop asks for ten times that (docs/validation.md §16).
pub const GAP_RESOLUTION: f64 = 1e-7;

/// Trapezoidal law (Tvergaard & Hutchinson 1992, *J. Mech. Phys. Solids* 40, 1377): the
/// traction σ0 for g ≤ δ1, falling linearly to 0 at δ2, nothing beyond; its work per area is
/// γ = σ0·(δ1 + δ2)/2. The softening fraction s ∈ (0, 1] is the part of the range over which
/// the traction falls, δ1 = (1 − s)·δ2, so δ2 = 2γ/(σ0·(2 − s)): s → 0 is Maugis–Dugdale,
/// s = 1 a triangle. With a map of γ, σ0 and s stay fixed and δ1, δ2 follow γ, as for
/// Dugdale. Its traction is continuous and non-increasing, so φ is concave and the law is
/// [`smooth`](CohesiveLaw::smooth): no traction jumps at the zone's edge (docs/physics.md
/// §2.6, docs/validation.md §16).
#[derive(Debug, Clone, PartialEq)]
pub struct Trapezoid {
    cohesive_stress: f64,
    softening_fraction: f64,
    work_of_adhesion: Vec<f64>,
}

impl Trapezoid {
    /// The law with plateau traction σ0 = `cohesive_stress`, softening fraction
    /// s = `softening_fraction` and the work of adhesion per element.
    ///
    /// # Panics
    /// If σ0 is not finite and > 0, s is not in (0, 1], or a γ is negative or not finite
    /// (validated inputs only: the scenario crate names the key).
    pub fn new(cohesive_stress: f64, softening_fraction: f64, work_of_adhesion: Vec<f64>) -> Self {
        assert!(cohesive_stress.is_finite() && cohesive_stress > 0.0, "σ0 > 0");
        assert!(softening_fraction > 0.0 && softening_fraction <= 1.0, "0 < s ≤ 1");
        assert!(work_of_adhesion.iter().all(|g| g.is_finite() && *g >= 0.0), "γ ≥ 0");
        Self {
            cohesive_stress,
            softening_fraction,
            work_of_adhesion,
        }
    }

    /// σ0.
    pub fn cohesive_stress(&self) -> f64 {
        self.cohesive_stress
    }

    /// s.
    pub fn softening_fraction(&self) -> f64 {
        self.softening_fraction
    }

    /// The end of the plateau δ1 = (1 − s)·δ2 on `element`.
    pub fn plateau_end(&self, element: usize) -> f64 {
        (1.0 - self.softening_fraction) * self.range(element)
    }
}

impl CohesiveLaw for Trapezoid {
    fn name(&self) -> &'static str {
        "trapezoid"
    }

    fn traction(&self, element: usize, gap: f64) -> f64 {
        let (d1, d2) = (self.plateau_end(element), self.range(element));
        if gap <= d1 {
            // Also an element without adhesion (d2 = 0) at g ≤ 0: no traction.
            if d2 > 0.0 {
                self.cohesive_stress
            } else {
                0.0
            }
        } else if gap < d2 {
            self.cohesive_stress * (d2 - gap) / (d2 - d1)
        } else {
            0.0
        }
    }

    fn energy(&self, element: usize, gap: f64) -> f64 {
        let (d1, d2) = (self.plateau_end(element), self.range(element));
        if gap >= d2 {
            0.0
        } else if gap > d1 {
            // −∫_g^δ2 t = −σ0·(δ2 − g)²/(2(δ2 − δ1)).
            -0.5 * self.cohesive_stress * (d2 - gap) * (d2 - gap) / (d2 - d1)
        } else {
            -self.work_of_adhesion[element] + self.cohesive_stress * gap
        }
    }

    /// The tangent of φ at the gap g0 where the traction t was set, continued to `gap`:
    /// on the plateau (t = σ0) the plateau's line −γ + σ0·g; on the softening part
    /// g0 = δ2 − (t/σ0)(δ2 − δ1) and φ(g0) + t·(g − g0); beyond δ2 (t = 0) nothing. Held
    /// fixed, the traction does the work of this linear piece (as for the exponential law);
    /// it equals φ(g) at a converged state.
    fn held_energy(&self, element: usize, gap: f64, traction: f64) -> f64 {
        let gamma = self.work_of_adhesion[element];
        if traction <= 0.0 || gamma <= 0.0 {
            return 0.0;
        }
        if traction >= self.cohesive_stress {
            return -gamma + self.cohesive_stress * gap;
        }
        let (d1, d2) = (self.plateau_end(element), self.range(element));
        let set_at = d2 - traction / self.cohesive_stress * (d2 - d1);
        self.energy(element, set_at) + traction * (gap - set_at)
    }

    /// δ2 = 2γ/(σ0·(2 − s)).
    fn range(&self, element: usize) -> f64 {
        2.0 * self.work_of_adhesion[element] / (self.cohesive_stress * (2.0 - self.softening_fraction))
    }

    fn max_traction(&self) -> f64 {
        self.cohesive_stress
    }

    fn smooth(&self) -> bool {
        true
    }

    /// The traction change of a gap change of `GAP_RESOLUTION`·δ2 on the softening part,
    /// |t'|·GAP_RESOLUTION·δ2 = σ0·GAP_RESOLUTION/s (the same on every element).
    fn traction_resolution(&self) -> f64 {
        self.cohesive_stress * GAP_RESOLUTION / self.softening_fraction
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// φ(0) = −γ, φ(δ2) = 0, φ' = t (central differences on both pieces), the traction is
    /// continuous at δ1 and δ2, and the held energy is φ's tangent at the set point.
    #[test]
    fn trapezoid_energy_is_the_integral_of_its_traction() {
        let law = Trapezoid::new(2.0, 0.5, vec![1.5, 0.0]);
        // δ2 = 2·1.5/(2·1.5) = 1, δ1 = 0.5; γ = σ0(δ1 + δ2)/2 = 1.5.
        assert!((law.range(0) - 1.0).abs() < 1e-15);
        assert!((law.plateau_end(0) - 0.5).abs() < 1e-15);
        assert_eq!(law.energy(0, 0.0), -1.5);
        assert_eq!(law.energy(0, 1.0), 0.0);
        assert_eq!(law.traction(0, 0.25), 2.0);
        assert_eq!(law.traction(0, 0.75), 1.0);
        assert_eq!(law.traction(0, 1.0), 0.0);
        assert!((law.traction(0, 0.5 + 1e-12) - 2.0).abs() < 1e-10);
        let h = 1e-6;
        for g in [0.2, 0.6, 0.9] {
            let derivative = (law.energy(0, g + h) - law.energy(0, g - h)) / (2.0 * h);
            assert!((derivative - law.traction(0, g)).abs() < 1e-8, "g = {g}");
        }
        // Continuous energy at δ1.
        assert!((law.energy(0, 0.5 + 1e-12) - law.energy(0, 0.5 - 1e-12)).abs() < 1e-10);
        // No adhesion: no range, no traction.
        assert_eq!(law.traction(1, 0.0), 0.0);
        assert_eq!(law.energy(1, 0.0), 0.0);
        assert_eq!(law.held_energy(1, 0.0, 0.0), 0.0);
    }

    #[test]
    fn trapezoid_held_energy_is_the_tangent_at_the_set_point() {
        let law = Trapezoid::new(2.0, 0.5, vec![1.5]);
        for g0 in [0.0, 0.3, 0.6, 0.8, 0.99] {
            let t = law.traction(0, g0);
            let held = |gap: f64| law.held_energy(0, gap, t);
            assert!((held(g0) - law.energy(0, g0)).abs() < 1e-14, "g0 = {g0}");
            assert!((held(g0 + 0.2) - held(g0 + 0.1) - 0.1 * t).abs() < 1e-14);
            // φ is concave: its tangent lies on or above it.
            for g in [0.0, 0.4, 0.7, 1.2] {
                assert!(held(g) >= law.energy(0, g) - 1e-14, "g0 = {g0}, g = {g}");
            }
        }
        assert_eq!(law.held_energy(0, 1.3, 0.0), 0.0);
    }

    /// s = 1 is the triangle: δ2 = 2γ/σ0 and the traction falls from g = 0.
    #[test]
    fn trapezoid_with_full_softening_is_a_triangle() {
        let law = Trapezoid::new(1.0, 1.0, vec![1.0]);
        assert_eq!(law.range(0), 2.0);
        assert_eq!(law.plateau_end(0), 0.0);
        assert_eq!(law.traction(0, 0.0), 1.0);
        assert_eq!(law.traction(0, 1.0), 0.5);
        assert_eq!(law.energy(0, 0.0), -1.0);
    }
}
