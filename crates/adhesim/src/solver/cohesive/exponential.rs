//! The exponential cohesive law.

use super::law::CohesiveLaw;

/// Tractions at most this fraction of γ/ρ count as outside the zone, and a pull-off has
/// let go once the tension is at most this fraction of the largest adhesive force: the
/// force the law would add beyond a domain border whose elements are at this fraction is
/// of the same relative order on a sphere (∫ t dA over r > r_b ≈ 2πRρ·t(g_b)).
pub const NEGLIGIBLE_FRACTION: f64 = 1e-3;

/// Exponential law: energy per area φ(g) = −γ·exp(−g/ρ), traction (γ/ρ)·exp(−g/ρ) towards
/// the indenter, of range ρ (the smooth law of the Adhesion and ContactMechanics
/// packages' smooth contact systems; e.g. Müser 2014, *Beilstein J. Nanotechnol.* 5, 419).
/// It acts on every element; [`range`](CohesiveLaw::range) is infinite, and an element
/// whose traction is at most `NEGLIGIBLE_FRACTION` of the largest counts as outside the
/// cohesive zone.
#[derive(Debug, Clone, PartialEq)]
pub struct Exponential {
    range: f64,
    work_of_adhesion: Vec<f64>,
}

impl Exponential {
    /// The law of range ρ = `range` with the work of adhesion per element.
    ///
    /// # Panics
    /// If ρ is not finite and > 0 or a γ is negative or not finite (validated inputs only).
    pub fn new(range: f64, work_of_adhesion: Vec<f64>) -> Self {
        assert!(range.is_finite() && range > 0.0, "ρ > 0");
        assert!(work_of_adhesion.iter().all(|g| g.is_finite() && *g >= 0.0), "γ ≥ 0");
        Self {
            range,
            work_of_adhesion,
        }
    }
}

impl CohesiveLaw for Exponential {
    fn name(&self) -> &'static str {
        "exponential"
    }

    fn traction(&self, element: usize, gap: f64) -> f64 {
        self.work_of_adhesion[element] / self.range * (-gap / self.range).exp()
    }

    fn energy(&self, element: usize, gap: f64) -> f64 {
        -self.work_of_adhesion[element] * (-gap / self.range).exp()
    }

    /// The tangent of φ at the gap g0 where the traction was set, t = t(g0), continued to
    /// `gap`: φ(g0) + t·(g − g0) = t·(g − g0 − ρ), g0 = ρ·ln(γ/(ρt)). Held fixed, the
    /// traction does the work of this linear piece, so the booked dissipation balances the
    /// work of the indenter as for Dugdale; it equals φ(g) at a converged state.
    fn held_energy(&self, element: usize, gap: f64, traction: f64) -> f64 {
        let gamma = self.work_of_adhesion[element];
        if traction <= 0.0 || gamma <= 0.0 {
            return 0.0;
        }
        let set_at = self.range * (gamma / (self.range * traction)).ln();
        traction * (gap - set_at - self.range)
    }

    fn range(&self, _element: usize) -> f64 {
        f64::INFINITY
    }

    fn max_traction(&self) -> f64 {
        self.work_of_adhesion.iter().fold(0.0f64, |m, g| m.max(*g)) / self.range
    }

    fn smooth(&self) -> bool {
        true
    }

    fn negligible_fraction(&self) -> f64 {
        NEGLIGIBLE_FRACTION
    }

    /// ρ·ln(1/`NEGLIGIBLE_FRACTION`): t(g)/t(0) = e^(−g/ρ) falls to the fraction.
    fn negligible_separation(&self) -> f64 {
        -self.range * NEGLIGIBLE_FRACTION.ln()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// φ(0) = −γ, φ' = t (by a central difference), t(0) = γ/ρ.
    #[test]
    fn exponential_energy_is_the_integral_of_its_traction() {
        let law = Exponential::new(0.5, vec![2.0]);
        assert_eq!(law.energy(0, 0.0), -2.0);
        assert_eq!(law.traction(0, 0.0), 4.0);
        let (g, h) = (0.3, 1e-6);
        let derivative = (law.energy(0, g + h) - law.energy(0, g - h)) / (2.0 * h);
        assert!((derivative - law.traction(0, g)).abs() < 1e-8);
        assert_eq!(law.max_traction(), 4.0);
        // Held at the traction of g0 = 0.3, the energy is φ's tangent there.
        let held = |gap: f64| law.held_energy(0, gap, law.traction(0, g));
        assert!((held(g) - law.energy(0, g)).abs() < 1e-14);
        assert!((held(0.5) - held(0.4) - 0.1 * law.traction(0, g)).abs() < 1e-14);
        // φ is concave: its tangent lies above it.
        assert!(held(0.9) > law.energy(0, 0.9));
    }
}
