//! Adhesion under shear: the local detachment rule of the contact's edge weakened by the
//! shear traction each element carries (docs/physics.md §8.5).
//!
//! Pohrt & Popov's rule releases an element when the elastic energy it would give back
//! alone under its tension, c_U·p²Δ³/E*, pays for its surface, γΔ² (σ_c of §2.2). Under a
//! shear traction q the element alone also stores the tangential energy c_U·q²Δ³/E*·r with
//! r = (2 − ν)/(2(1 − ν)) = E*/(4G*), the ratio of a square element's Cerruti and Love self
//! compliances. Counting a fraction m (the mode mixity) of it, the element detaches when
//! (p⁻)² + m·r·q² ≥ σ_c², i.e. when its tension exceeds σ_c,eff = √(σ_c² − m·r·q²)
//! (an element whose σ_c,eff reaches 0 detaches at any tension). Averaged over the edge of
//! a circular contact the tangential term is Savkoor & Briggs' mean mode II + III energy
//! release rate (1977, Proc. R. Soc. A 356, 103), so m = 1 is their brittle criterion and
//! m = 0 leaves the edge as it is (Johnson 1997, Proc. R. Soc. A 453, 163). m may differ
//! with the side of the edge an element is on ([`ModeMixity`]).

use super::mixity::{edge_normal, ModeMixity};
use super::window::{ContactWindow, TangentialRoom};
use crate::elastic::cerruti::ShearMaterial;
use crate::elastic::ElasticOperator;
use crate::protocol::{NormalSolver, ProtocolError};
use crate::solver::{AdhesiveSolver, ContactState, StepReport, TangentialReport, TangentialSolver, TangentialState};

/// Rounds of tangential solve and weakened normal step per shift step before giving up.
const MAX_ROUNDS: usize = 200;

/// σ_c,eff = √(max(σ_c² − m·r·q², 0)): the tension at which an element carrying the shear
/// traction of magnitude `shear_traction` detaches (see the module).
///
/// # Example
/// ```
/// use adhesim::protocol::{element_energy_ratio, shear_weakened_critical_stress};
/// use adhesim::ShearMaterial;
///
/// // At ν = 1/2 an element's shear energy is 3/2 of its tension energy at the same stress.
/// let ratio = element_energy_ratio(ShearMaterial::from_contact_modulus(4.0, 0.5));
/// assert_eq!(ratio, 1.5);
/// // σ_c = 5 and |q|² = 6 with mode mixity 1: σ_eff² = 25 − 1.5·6 = 16.
/// assert_eq!(shear_weakened_critical_stress(5.0, 6f64.sqrt(), 1.0, ratio), 4.0);
/// // Mode mixity 0: the shear does not weaken the edge.
/// assert_eq!(shear_weakened_critical_stress(5.0, 6f64.sqrt(), 0.0, ratio), 5.0);
/// ```
pub fn shear_weakened_critical_stress(
    critical_stress: f64,
    shear_traction: f64,
    mode_mixity: f64,
    energy_ratio: f64,
) -> f64 {
    let squared = critical_stress * critical_stress - mode_mixity * energy_ratio * shear_traction * shear_traction;
    squared.max(0.0).sqrt()
}

/// r = (2 − ν)/(2(1 − ν)) = E*/(4G*): a square element's tangential self compliance over
/// its normal one (Cerruti's kernel averages ν x²/r³ to ν/(2r) over a square, Love's is
/// (1 − ν)/r in the same units).
pub fn element_energy_ratio(material: ShearMaterial) -> f64 {
    let nu = material.poisson_ratio;
    (2.0 - nu) / (2.0 * (1.0 - nu))
}

/// The normal side of a shift step: the half-space, the indenter at `depth` and the
/// normal solver (the JKR-type one when the shear weakens the edge).
pub(super) struct NormalSide<'a> {
    pub operator: &'a mut dyn ElasticOperator,
    pub heights: &'a [f64],
    pub depth: f64,
    pub solver: &'a mut NormalSolver,
    pub state: &'a mut ContactState,
}

/// What a shift step solved in rounds did (a weakened edge's, or the coupled operator's):
/// the final tangential solve (with the counters of all rounds) and the normal steps
/// summed.
pub(super) struct RoundsStep {
    pub tangential: TangentialReport,
    pub normal: StepReport,
    /// Rounds of tangential solve and normal step.
    pub rounds: usize,
}

/// σ_c of the contact elements lowered by the shear they carry, within a step (never
/// raised there), from the unweakened σ_c at each step's start.
pub(super) struct Weakening {
    mode_mixity: ModeMixity,
    energy_ratio: f64,
    /// σ_c per element without shear.
    base: Vec<f64>,
    /// σ_c,eff per element in the current step.
    weakened: Vec<f64>,
}

impl Weakening {
    pub(super) fn new(solver: &AdhesiveSolver, material: ShearMaterial, mode_mixity: ModeMixity) -> Self {
        let base = solver.critical_stresses().to_vec();
        Self {
            mode_mixity,
            energy_ratio: element_energy_ratio(material),
            weakened: base.clone(),
            base,
        }
    }

    /// A step starts from the unweakened σ_c.
    pub(super) fn begin(&mut self) {
        self.weakened.copy_from_slice(&self.base);
    }

    /// Lowers σ_c,eff of each element in `contact` (on the window) by its current shear
    /// traction in `state`.
    pub(super) fn weaken(&mut self, window: &ContactWindow, contact: &[bool], state: &TangentialState) {
        for (w, k) in window.elements() {
            if !contact[w] {
                continue;
            }
            let traction = [state.traction[0][w], state.traction[1][w]];
            let sigma = if self.mode_mixity.is_uniform() {
                let magnitude = traction[0].hypot(traction[1]);
                shear_weakened_critical_stress(self.base[k], magnitude, self.mode_mixity.along, self.energy_ratio)
            } else {
                let normal = edge_normal(&window.grid, contact, w);
                let counted = self.mode_mixity.counted_square(traction, normal);
                (self.base[k] * self.base[k] - self.energy_ratio * counted)
                    .max(0.0)
                    .sqrt()
            };
            self.weakened[k] = self.weakened[k].min(sigma);
        }
    }

    /// Gives `solver` the step's σ_c,eff; false where it has them already.
    pub(super) fn apply(&self, solver: &mut AdhesiveSolver) -> bool {
        if solver.critical_stresses() == self.weakened.as_slice() {
            return false;
        }
        solver.set_critical_stresses(&self.weakened);
        true
    }

    /// Gives the solver its unweakened σ_c back.
    pub(super) fn restore(&self, solver: &mut AdhesiveSolver) {
        solver.set_critical_stresses(&self.base);
    }
}

/// The shear-weakened detachment rule across the shift steps of a run.
pub(super) struct EdgeWeakening {
    weakening: Weakening,
    /// The tangential state at the end of the last step: each round restarts from it.
    saved: TangentialState,
    /// The normal state on the window.
    window_state: ContactState,
}

impl EdgeWeakening {
    pub(super) fn new(
        solver: &AdhesiveSolver,
        material: ShearMaterial,
        mode_mixity: ModeMixity,
        window: &ContactWindow,
    ) -> Self {
        Self {
            weakening: Weakening::new(solver, material, mode_mixity),
            saved: TangentialState::new(window.grid.len()),
            window_state: ContactState::new(&window.grid),
        }
    }

    /// One shift step to `shift` with the edge weakened by its shear: solve the tangential
    /// problem on the contact, lower σ_c of each contact element by its traction (never
    /// raising it within the step), redo the normal step at the step's depth, and repeat
    /// until the contact set no longer changes. Each step starts from the unweakened σ_c,
    /// so an element released in an earlier step may attach again if it holds without the
    /// shear it would carry.
    pub(super) fn step(
        &mut self,
        normal: NormalSide<'_>,
        room: &mut TangentialRoom,
        friction: &mut TangentialSolver,
        shift: [f64; 2],
        step: usize,
    ) -> Result<RoundsStep, ProtocolError> {
        let along = shift[0].hypot(shift[1]);
        let Some(solver) = normal.solver.as_adhesive_mut() else {
            unreachable!("the shear checks for the adhesive solver before its shift")
        };
        self.weakening.begin();
        let mut total = RoundsStep {
            tangential: TangentialReport::default(),
            normal: StepReport::default(),
            rounds: 0,
        };
        let mut before = normal.state.contact.clone();
        loop {
            total.rounds += 1;
            if total.rounds > MAX_ROUNDS {
                return Err(ProtocolError::DetachmentNotSettled {
                    step,
                    shift: along,
                    rounds: MAX_ROUNDS,
                });
            }
            if total.rounds > 1 {
                // Every round restarts from the step's starting fields.
                room.state.clone_from(&self.saved);
            }
            let widened = room.cover(&normal.state.contact)?;
            total.tangential.transform_pairs += widened;
            if total.rounds == 1 || widened > 0 {
                self.saved.clone_from(&room.state);
            }
            if self.window_state.contact.len() != room.window.grid.len() {
                self.window_state = ContactState::new(&room.window.grid);
            }
            room.window.gather_into(normal.state, &mut self.window_state);
            let report = friction
                .step(room.operator.as_mut(), &self.window_state, shift, &mut room.state)
                .map_err(|source| ProtocolError::Tangential {
                    step,
                    shift: along,
                    source,
                })?;
            add_tangential(&mut total.tangential, report);
            self.weakening
                .weaken(&room.window, &self.window_state.contact, &room.state);
            solver.set_critical_stresses(&self.weakening.weakened);
            before.copy_from_slice(&normal.state.contact);
            let report = solver
                .step(normal.operator, normal.heights, normal.depth, normal.state)
                .map_err(|source| ProtocolError::Solve {
                    step,
                    depth: normal.depth,
                    source,
                })?;
            add_normal(&mut total.normal, report);
            if normal.state.contact == before {
                return Ok(total);
            }
        }
    }

    /// Gives the solver its unweakened σ_c back.
    pub(super) fn restore(&self, solver: &mut AdhesiveSolver) {
        self.weakening.restore(solver);
    }
}

/// The last round's fields with the counters of all rounds.
pub(super) fn add_tangential(total: &mut TangentialReport, round: TangentialReport) {
    let (rounds, iterations, pairs) = (total.rounds, total.cg_iterations, total.transform_pairs);
    *total = round;
    total.rounds += rounds;
    total.cg_iterations += iterations;
    total.transform_pairs += pairs;
}

/// The last normal step's forces and energies with the counters and releases of all.
pub(super) fn add_normal(total: &mut StepReport, round: StepReport) {
    let first = total.solves == 0;
    let mut sum = round;
    sum.solves += total.solves;
    sum.cg_iterations += total.cg_iterations;
    sum.operator_applications += total.operator_applications;
    sum.window_applications += total.window_applications;
    sum.preconditioner_applications += total.preconditioner_applications;
    sum.attachment_rounds += total.attachment_rounds;
    sum.attached += total.attached;
    sum.detached += total.detached;
    sum.dissipated_energy += total.dissipated_energy;
    if !first {
        sum.force_before_change = total.force_before_change;
        sum.energy_before_change = total.energy_before_change;
    }
    *total = sum;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weakening_follows_the_element_energy_balance() {
        // ν = 1/2: r = 1.5 (Cerruti's self compliance is 3/2 of Love's).
        let material = ShearMaterial::from_contact_modulus(4.0, 0.5);
        assert_eq!(element_energy_ratio(material), 1.5);
        // ν = 0: r = 1.
        assert_eq!(element_energy_ratio(ShearMaterial::from_contact_modulus(2.0, 0.0)), 1.0);
        // σ_c = 5, m = 1, r = 1.5, q² = 6 ⇒ σ_eff² = 25 − 9 = 16.
        assert_eq!(shear_weakened_critical_stress(5.0, 6f64.sqrt(), 1.0, 1.5), 4.0);
        // m = 0 leaves σ_c; a shear beyond the element's whole budget leaves 0.
        assert_eq!(shear_weakened_critical_stress(5.0, 100.0, 0.0, 1.5), 5.0);
        assert_eq!(shear_weakened_critical_stress(5.0, 100.0, 1.0, 1.5), 0.0);
    }

    #[test]
    fn energy_ratio_is_the_ratio_of_the_operators_self_compliances() {
        // The closed form r = (2 − ν)/(2(1 − ν)) against the discrete operators' own
        // diagonals on square elements (Cerruti's and Love's coefficients, independent code),
        // to rounding.
        use crate::elastic::{FreeOperator, TangentialOperator};
        use crate::grid::{Boundary, Grid};
        use crate::material::ElasticMaterial;
        let grid = Grid::rectangular(8, 8, 0.8, 0.8, Boundary::Free).unwrap();
        for poisson_ratio in [0.0, 0.3, 0.5] {
            let normal = FreeOperator::new(grid, ElasticMaterial::from_youngs_modulus(3.0, poisson_ratio).unwrap());
            let contact_modulus = normal.contact_modulus();
            let material = ShearMaterial::from_contact_modulus(contact_modulus, poisson_ratio);
            let tangential = TangentialOperator::new(grid, material).unwrap();
            let ratio = tangential.self_compliance() / normal.self_compliance();
            assert!(
                (ratio / element_energy_ratio(material) - 1.0).abs() < 1e-12,
                "ν = {poisson_ratio}: {ratio} vs {}",
                element_energy_ratio(material)
            );
        }
    }
}
