//! Finite-range (cohesive-zone) adhesion: [`CohesiveSolver`] drives any [`CohesiveLaw`]
//! (docs/physics.md §2.6). Adding a law is adding a module with a type that implements
//! the trait; the solver and the protocols stay as they are.

mod anderson;
mod checkpoint;
mod exponential;
mod law;
mod trapezoid;

pub use checkpoint::CohesiveCheckpoint;
pub use exponential::Exponential;
pub use law::{CohesiveLaw, Dugdale};
pub use trapezoid::Trapezoid;

use super::{
    Ccg, CcgParams, ContactState, Control, NestedActiveSet, NestedParams, SolveError, SolveReport, StepReport,
};
use crate::elastic::ElasticOperator;
use crate::grid::{Boundary, Grid};
use crate::material::ElasticMaterial;

/// Parameters of [`CohesiveSolver`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CohesiveParams {
    /// Give up a step (with [`SolveError::TooManyRounds`]) after this many zone updates
    /// (default 500).
    pub max_rounds: usize,
    /// A round is the last when no traction changes by more than this times the law's
    /// largest traction (default 1e-9; a Dugdale zone stops on an unchanged set, where the
    /// tractions agree exactly).
    pub traction_tolerance: f64,
    /// Solve the compressive part by the nested active set on free grids (default true;
    /// false: Polonsky–Keer CCG, which also runs on periodic grids).
    pub nested: bool,
    /// How the rounds of a smooth law are accelerated (laws with jumps in their traction
    /// always use the plain rounds).
    pub acceleration: Acceleration,
}

/// The iteration of a smooth law's rounds (docs/physics.md §2.6).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Acceleration {
    /// Plain majorise–minimise rounds (for comparison).
    Plain,
    /// Anderson mixing with the energy as safeguard (the default).
    #[default]
    Anderson,
}

impl Default for CohesiveParams {
    fn default() -> Self {
        Self {
            max_rounds: 500,
            traction_tolerance: 1e-9,
            nested: true,
            acceleration: Acceleration::default(),
        }
    }
}

/// The non-adhesive solver of the compressive part q.
enum Compressive {
    Ccg(Ccg),
    Nested(Box<NestedActiveSet>),
}

/// Quasi-static adhesive contact with a cohesive law under displacement control.
///
/// The pressure splits into p = q − t: the law's tensile traction t(g) where the gap is
/// within its range, and a compressive part q ≥ 0 with g ≥ 0 and q·g = 0 (the contact).
/// With t known, q solves a non-adhesive contact problem whose heights carry the
/// displacement of the tractions, z + K(−t); the tractions are then updated from the
/// new gaps, and the two alternate until t no longer changes. For Maugis–Dugdale this is
/// an active set on the cohesive zone χ = {g < δc} (contact included; the three sets of
/// contact, zone and free surface of Maugis 1992). More tension lowers every gap (K has
/// positive entries), so from the previous step's zone the iteration grows the zone
/// monotonically on approach and shrinks it on retraction: it stops in the first stable
/// configuration along the load path, and the jumps and hysteresis follow from the
/// continuation, as in the quasi-static simulations of Maugis' model (e.g. Greenwood 1997,
/// *Proc. R. Soc. A* 453, 1277). The compressive solve is the library's non-adhesive one
/// (the nested active set on free grids, or CCG), warm started from the last round.
///
/// On a periodic grid the compressive part is CCG's: K̂(0) = 0, so the depth controls the
/// mean gap mean(z) − d, as for the sharp criterion, and the tractions' displacement
/// K(−t) has zero mean; the mean pressure −mean(t) + mean(q) is the load per area.
pub struct CohesiveSolver {
    params: CohesiveParams,
    grid: Grid,
    law: Box<dyn CohesiveLaw>,
    compressive: Compressive,
    /// q and its displacement K q, contact set (the warm start of the compressive solve).
    compressive_state: ContactState,
    /// Traction t applied in the current round (tensile > 0).
    traction: Vec<f64>,
    /// −t, the tensile pressure, and its displacement K(−t).
    tensile_pressure: Vec<f64>,
    tensile_displacement: Vec<f64>,
    /// z + K(−t): the heights the compressive solve sees.
    shifted_heights: Vec<f64>,
    start_contact: Vec<bool>,
}

impl CohesiveSolver {
    /// A solver of `law` on `grid` for a half-space of `material`.
    pub fn new(grid: Grid, material: ElasticMaterial, law: Box<dyn CohesiveLaw>, params: CohesiveParams) -> Self {
        let len = grid.len();
        let compressive = if params.nested && grid.boundary() == Boundary::Free {
            Compressive::Nested(Box::new(NestedActiveSet::new(grid, material, NestedParams::default())))
        } else {
            Compressive::Ccg(Ccg::new(CcgParams::default()))
        };
        Self {
            params,
            grid,
            law,
            compressive,
            compressive_state: ContactState::new(&grid),
            traction: vec![0.0; len],
            tensile_pressure: vec![0.0; len],
            tensile_displacement: vec![0.0; len],
            shifted_heights: vec![0.0; len],
            start_contact: vec![false; len],
        }
    }

    /// The law.
    pub fn law(&self) -> &dyn CohesiveLaw {
        self.law.as_ref()
    }

    /// The traction of the last step per element (tensile > 0).
    pub fn traction(&self) -> &[f64] {
        &self.traction
    }

    /// Elements carrying a traction above the law's negligible one at the end of the last
    /// step (the cohesive zone, contact included; [`CohesiveLaw::negligible_fraction`]).
    pub fn zone_elements(&self) -> usize {
        let negligible = self.negligible_traction();
        self.traction.iter().filter(|&&t| t > negligible).count()
    }

    /// Whether an element on the border of a free grid carries a traction above the law's
    /// negligible one: the domain cuts the cohesive zone.
    pub fn zone_touches_border(&self) -> bool {
        let negligible = self.negligible_traction();
        self.grid.boundary() == Boundary::Free
            && self
                .traction
                .iter()
                .enumerate()
                .any(|(k, &t)| t > negligible && self.grid.is_border(k))
    }

    /// Tractions at or below this count as outside the zone (0 for laws of finite range).
    fn negligible_traction(&self) -> f64 {
        self.law.negligible_fraction() * self.law.max_traction()
    }

    /// The tensile force at or below which a pull-off has let go, given the largest
    /// adhesive force seen: 0 for laws of finite range (any tension holds), a fraction of
    /// it for laws of unbounded support ([`CohesiveLaw::negligible_fraction`]).
    pub fn released_force(&self, max_adhesive_force: f64) -> f64 {
        self.law.negligible_fraction() * max_adhesive_force
    }

    /// Forgets the previous load path.
    pub fn reset(&mut self) {
        self.traction.fill(0.0);
        self.compressive_state = ContactState::new(&self.grid);
    }

    /// One displacement-controlled step to `depth`; `before_change` sees the state with
    /// the previous step's tractions at the new depth.
    pub fn step_probed<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
        before_change: &mut (dyn FnMut(&ContactState) + Send),
    ) -> Result<StepReport, SolveError> {
        let len = self.grid.len();
        if heights.len() != len {
            return Err(SolveError::SizeMismatch {
                expected: len,
                got: heights.len(),
            });
        }
        self.start_contact.copy_from_slice(&state.contact);
        let element_area = self.grid.element_area();
        let mut report = StepReport::default();
        let mut rounds = 0;
        let change = self.round(operator, heights, depth, state, &mut report, &mut rounds)?;
        before_change(state);
        report.force_before_change = state.force(element_area);
        report.energy_before_change = self.energy(state, heights, depth, Interface::Held);
        let acceleration = if self.law.smooth() {
            self.params.acceleration
        } else {
            Acceleration::Plain
        };
        if acceleration == Acceleration::Anderson {
            self.converge_anderson(operator, heights, depth, state, &mut report, &mut rounds, change)?;
        } else {
            let mut change = change;
            while change > self.tolerance() {
                report.attachment_rounds += 1;
                change = self.round(operator, heights, depth, state, &mut report, &mut rounds)?;
            }
        }
        // The state was computed with the tractions now in `traction` (to the tolerance).
        report.force = state.force(element_area);
        report.energy = self.energy(state, heights, depth, Interface::Held);
        report.dissipated_energy = report.energy_before_change - report.energy;
        (report.attached, report.detached) = state.changes_from(&self.start_contact);
        Ok(report)
    }

    /// The largest traction change that ends a step.
    fn tolerance(&self) -> f64 {
        (self.params.traction_tolerance * self.law.max_traction()).max(self.law.traction_resolution())
    }

    /// One round (the `rounds`-th of the step, counted): solves for q under the tractions
    /// in `traction`, then sets them from the new gaps; returns the largest change, or
    /// [`SolveError::TooManyRounds`] when the step has used its rounds.
    fn round<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
        report: &mut StepReport,
        rounds: &mut usize,
    ) -> Result<f64, SolveError> {
        if *rounds == self.params.max_rounds {
            return Err(SolveError::TooManyRounds {
                rounds: self.params.max_rounds,
            });
        }
        *rounds += 1;
        let inner = self.solve_compressive(operator, heights, depth, state)?;
        report.solves += 1;
        report.cg_iterations += inner.iterations;
        // One application for the tractions' displacement, and the compressive solve's.
        report.operator_applications += 1 + inner.operator_applications;
        Ok(self.update_traction(heights, depth, state))
    }

    /// Solves for q under the current tractions and writes the whole state p = q − t,
    /// u = K q + K(−t); returns the compressive solve's report.
    fn solve_compressive<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
    ) -> Result<SolveReport, SolveError> {
        for (p, t) in self.tensile_pressure.iter_mut().zip(&self.traction) {
            *p = -t;
        }
        operator.apply(&self.tensile_pressure, &mut self.tensile_displacement);
        for ((shifted, z), u) in self
            .shifted_heights
            .iter_mut()
            .zip(heights)
            .zip(&self.tensile_displacement)
        {
            *shifted = z + u;
        }
        let inner = match &mut self.compressive {
            Compressive::Nested(solver) => {
                solver.solve(operator, &self.shifted_heights, depth, &mut self.compressive_state)?
            }
            Compressive::Ccg(solver) => solver.solve(
                operator,
                &self.shifted_heights,
                Control::Displacement(depth),
                &mut self.compressive_state,
            )?,
        };
        let q = &self.compressive_state;
        for k in 0..self.grid.len() {
            state.pressure[k] = q.pressure[k] - self.traction[k];
            state.displacement[k] = q.displacement[k] + self.tensile_displacement[k];
            state.contact[k] = q.contact[k];
        }
        Ok(inner)
    }

    /// Sets the tractions from the gaps of `state` (contact elements at gap 0) and returns
    /// the largest change.
    fn update_traction(&mut self, heights: &[f64], depth: f64, state: &ContactState) -> f64 {
        let mut change = 0.0f64;
        for k in 0..self.grid.len() {
            let gap = if state.contact[k] {
                0.0
            } else {
                (heights[k] - depth + state.displacement[k]).max(0.0)
            };
            let traction = if heights[k].is_finite() {
                self.law.traction(k, gap)
            } else {
                0.0
            };
            change = change.max((traction - self.traction[k]).abs());
            self.traction[k] = traction;
        }
        change
    }

    /// Π = ½Δ²Σp·u + Δ²Σφ(g): with [`Interface::Held`] each element's interface energy is
    /// that of the piece of the law its applied traction belongs to, with
    /// [`Interface::Law`] the law's φ(g) (the merit of the accelerated rounds).
    fn energy(&self, state: &ContactState, heights: &[f64], depth: f64, interface_energy: Interface) -> f64 {
        let mut elastic = 0.0;
        let mut interface = 0.0;
        for k in 0..self.grid.len() {
            elastic += state.pressure[k] * state.displacement[k];
            if heights[k].is_finite() {
                let gap = if state.contact[k] {
                    0.0
                } else {
                    (heights[k] - depth + state.displacement[k]).max(0.0)
                };
                interface += match interface_energy {
                    // The state was computed with the traction −(tensile pressure).
                    Interface::Held => self.law.held_energy(k, gap, -self.tensile_pressure[k]),
                    Interface::Law => self.law.energy(k, gap),
                };
            }
        }
        self.grid.element_area() * (0.5 * elastic + interface)
    }
}

/// Which interface energy [`CohesiveSolver::energy`] sums.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Interface {
    /// The piece of the law the applied traction belongs to (booked energies).
    Held,
    /// φ(g) of the law.
    Law,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::elastic::FreeOperator;
    use crate::geometry::{Profile, Sphere};

    /// A sphere pressed into a half-space whose work of adhesion is γ0 for x > 0 and γ0/4
    /// for x < 0, with σ0 fixed: the converged step is a Dugdale state element by element.
    fn pressed(max_rounds: usize) -> (Result<StepReport, SolveError>, ContactState, CohesiveSolver, Vec<f64>) {
        let grid = Grid::new(32, 0.3, Boundary::Free).unwrap();
        let material = ElasticMaterial::new(1.0).unwrap();
        let mut operator = FreeOperator::new(grid, material);
        let heights = Sphere::new(1.0).unwrap().heights(&grid);
        let gamma: Vec<f64> = (0..grid.len())
            .map(|k| if grid.centre(k).0 > 0.0 { 1e-4 } else { 2.5e-5 })
            .collect();
        let law = Dugdale::new(0.04, gamma);
        let params = CohesiveParams {
            max_rounds,
            ..CohesiveParams::default()
        };
        let mut solver = CohesiveSolver::new(grid, material, Box::new(law), params);
        let mut state = ContactState::new(&grid);
        let report = solver.step_probed(&mut operator, &heights, 1e-3, &mut state, &mut |_| {});
        (report, state, solver, heights)
    }

    /// Tractions σ0 exactly where g < δc = γ/σ0 (contact included), q = p + t ≥ 0, and no
    /// penetration beyond 1e-8·d (the nested solver stops at an ℓ2 residual of 1e-10 of
    /// ‖d − z‖ over the contact, so one element may be off by a few 1e-9·d; measured
    /// 1.7e-9·d); the zone reaches farther on the side of the larger γ.
    #[test]
    fn a_converged_step_is_a_dugdale_state_with_the_local_range() {
        let (report, state, solver, heights) = pressed(500);
        let report = report.unwrap();
        assert!(report.solves >= 2 && report.force < report.force_before_change + 1e-12);
        let grid = solver.grid;
        let (mut right, mut left) = (0, 0);
        for k in 0..grid.len() {
            let gap = heights[k] - 1e-3 + state.displacement[k];
            assert!(gap > -1e-11, "element {k}: gap {gap:e}");
            let gap = if state.contact[k] { 0.0 } else { gap.max(0.0) };
            let in_zone = gap < solver.law().range(k);
            assert_eq!(solver.traction()[k] > 0.0, in_zone, "element {k}");
            assert!(state.pressure[k] + solver.traction()[k] >= 0.0);
            if in_zone {
                if grid.centre(k).0 > 0.0 {
                    right += 1;
                } else {
                    left += 1;
                }
            }
        }
        assert!(right > left, "zone elements: {right} (γ0) vs {left} (γ0/4)");
        assert_eq!(solver.zone_elements(), right + left);
        assert!(!solver.zone_touches_border());
    }

    /// A step that needs more zone updates than allowed says so with a typed error.
    #[test]
    fn too_few_rounds_is_a_typed_error() {
        let (report, ..) = pressed(1);
        assert_eq!(report.unwrap_err(), SolveError::TooManyRounds { rounds: 1 });
    }
}
