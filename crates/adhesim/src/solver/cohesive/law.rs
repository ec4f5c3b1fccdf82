//! Traction–separation laws of finite-range adhesion (docs/physics.md §2.6). A law is one
//! type implementing [`CohesiveLaw`]; the [`super::CohesiveSolver`] uses nothing else of it.

/// A cohesive (traction–separation) law per element: the tensile traction t(g) ≥ 0 that
/// pulls the surface towards the indenter at gap g ≥ 0, and its interface energy per area
/// φ(g) with φ' = t and φ(0) = −γ (the element's work of adhesion), φ(∞) = 0.
pub trait CohesiveLaw: Send {
    /// The law's name as written in scenario files (`"dugdale"`).
    fn name(&self) -> &'static str;

    /// Tensile traction t(g) ≥ 0 on `element` at gap `gap` ≥ 0.
    fn traction(&self, element: usize, gap: f64) -> f64;

    /// Interface energy per area φ(g) ≤ 0 on `element` at gap `gap`.
    fn energy(&self, element: usize, gap: f64) -> f64;

    /// The energy per area of `element` at gap `gap` while it is held at the traction
    /// `traction` the solver applied (the linear piece of the law that traction belongs to,
    /// continued to `gap`). At a converged state it equals [`energy`](Self::energy); before
    /// the traction is updated it is the energy of the configuration still holding it, so
    /// that the energy a jump releases is booked as dissipation.
    fn held_energy(&self, element: usize, gap: f64, traction: f64) -> f64;

    /// Gap beyond which no traction acts on `element` (δc for Dugdale; infinite for laws of
    /// unbounded support).
    fn range(&self, element: usize) -> f64;

    /// The largest traction of the law over all elements (σ0 for Dugdale).
    fn max_traction(&self) -> f64;

    /// Whether the traction is continuous and non-increasing in the gap on every element
    /// (φ concave and smooth): the solver then accelerates its rounds, with the energy as
    /// merit (docs/physics.md §2.6). False (the default) keeps the plain rounds, which a
    /// law with jumps in its traction (Dugdale) needs.
    fn smooth(&self) -> bool {
        false
    }

    /// The smallest traction change the rounds can resolve on this law: a floor under the
    /// stop tolerance [`CohesiveParams::traction_tolerance`](super::CohesiveParams) times
    /// [`max_traction`](Self::max_traction). A steep softening turns the compressive solve's
    /// gap error into a traction error of |t'|·δg, and rounds asked for less stagnate at that
    /// noise (0, the default: no floor).
    fn traction_resolution(&self) -> f64 {
        0.0
    }

    /// For a law of unbounded support: the fraction of [`max_traction`](Self::max_traction)
    /// at or below which an element counts as outside the cohesive zone, and of the
    /// largest adhesive force below which a pull-off has let go (0, the default, for laws
    /// of finite range: any traction is in the zone, any tension holds).
    fn negligible_fraction(&self) -> f64 {
        0.0
    }

    /// For a law of unbounded support: the gap at which its traction has fallen to
    /// [`negligible_fraction`](Self::negligible_fraction) of the largest; an indentation
    /// starts this far above first contact (0, the default: laws of finite range start at
    /// first contact).
    fn negligible_separation(&self) -> f64 {
        0.0
    }
}

/// Maugis–Dugdale law: the constant traction σ0 for g < δc = γ/σ0, nothing beyond
/// (Dugdale 1960, *J. Mech. Phys. Solids* 8, 100; Maugis 1992, *J. Colloid Interface Sci.*
/// 150, 243). With a map of γ, σ0 stays fixed and δc follows γ.
#[derive(Debug, Clone, PartialEq)]
pub struct Dugdale {
    cohesive_stress: f64,
    work_of_adhesion: Vec<f64>,
}

impl Dugdale {
    /// The law with traction σ0 = `cohesive_stress` and the work of adhesion per element.
    ///
    /// # Panics
    /// If σ0 is not finite and > 0 or a γ is negative or not finite (validated inputs
    /// only: the scenario crate names the key).
    pub fn new(cohesive_stress: f64, work_of_adhesion: Vec<f64>) -> Self {
        assert!(cohesive_stress.is_finite() && cohesive_stress > 0.0, "σ0 > 0");
        assert!(work_of_adhesion.iter().all(|g| g.is_finite() && *g >= 0.0), "γ ≥ 0");
        Self {
            cohesive_stress,
            work_of_adhesion,
        }
    }

    /// σ0.
    pub fn cohesive_stress(&self) -> f64 {
        self.cohesive_stress
    }
}

impl CohesiveLaw for Dugdale {
    fn name(&self) -> &'static str {
        "dugdale"
    }

    fn traction(&self, element: usize, gap: f64) -> f64 {
        if gap < self.range(element) {
            self.cohesive_stress
        } else {
            0.0
        }
    }

    fn energy(&self, element: usize, gap: f64) -> f64 {
        let range = self.range(element);
        if gap < range {
            self.cohesive_stress * (gap - range)
        } else {
            0.0
        }
    }

    fn held_energy(&self, element: usize, gap: f64, traction: f64) -> f64 {
        if traction > 0.0 {
            self.cohesive_stress * (gap - self.range(element))
        } else {
            0.0
        }
    }

    fn range(&self, element: usize) -> f64 {
        self.work_of_adhesion[element] / self.cohesive_stress
    }

    fn max_traction(&self) -> f64 {
        self.cohesive_stress
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The energy integrates the traction: φ(0) = −γ, φ(δc) = 0, and φ' = σ0 inside.
    #[test]
    fn dugdale_energy_is_the_integral_of_its_traction() {
        let law = Dugdale::new(2.0, vec![1.0, 0.0]);
        assert_eq!(law.range(0), 0.5);
        assert_eq!(law.energy(0, 0.0), -1.0);
        assert_eq!(law.energy(0, 0.5), 0.0);
        assert_eq!(law.traction(0, 0.25), 2.0);
        assert_eq!(law.traction(0, 0.5), 0.0);
        assert!((law.energy(0, 0.3) - law.energy(0, 0.1) - 2.0 * 0.2).abs() < 1e-15);
        // No adhesion: no range, no traction.
        assert_eq!(law.traction(1, 0.0), 0.0);
        assert_eq!(law.energy(1, 0.0), 0.0);
        // Held beyond its range, an element keeps the energy of its bonded piece.
        assert!((law.held_energy(0, 0.7, 2.0) - 0.4).abs() < 1e-15);
        assert_eq!(law.held_energy(0, 0.3, 0.0), 0.0);
    }
}
