//! A work of adhesion that changes during a run (aging bonds, docs/physics.md §2.7).

use super::params::critical_stress;
use super::AdhesiveSolver;

impl AdhesiveSolver {
    /// Replaces γ per element (row-major) and with it each element's detachment stress
    /// σ_c = √(E*γ/(c_U Δ)) (docs/physics.md §2.2), for bonds whose strength grows with
    /// the time they have been in contact. The failed-ring records of earlier steps were
    /// judged against the old values and are forgotten.
    ///
    /// # Panics
    /// If `work_of_adhesion` does not have one value per element.
    pub fn set_work_of_adhesion(&mut self, work_of_adhesion: &[f64]) {
        self.work_of_adhesion.copy_from_slice(work_of_adhesion);
        let stresses: Vec<f64> = work_of_adhesion
            .iter()
            .map(|&gamma| critical_stress(self.contact_modulus, gamma, self.detachment_size))
            .collect();
        self.set_critical_stresses(&stresses);
    }
}
