//! The exponential cohesive law.

use super::law::CohesiveLaw;

/// Exponential law: energy per area φ(g) = −γ·exp(−g/ρ), traction (γ/ρ)·exp(−g/ρ) towards
/// the indenter, of range ρ (the smooth law of the Adhesion and ContactMechanics
/// packages' smooth contact systems; e.g. Müser 2014, *Beilstein J. Nanotechnol.* 5, 419).
/// It acts on every element; [`range`](CohesiveLaw::range) is infinite.
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

    /// A smooth law has no pieces: the energy at the gap.
    fn held_energy(&self, element: usize, gap: f64, _traction: f64) -> f64 {
        self.energy(element, gap)
    }

    fn range(&self, _element: usize) -> f64 {
        f64::INFINITY
    }

    fn max_traction(&self) -> f64 {
        self.work_of_adhesion.iter().fold(0.0f64, |m, g| m.max(*g)) / self.range
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
    }
}
