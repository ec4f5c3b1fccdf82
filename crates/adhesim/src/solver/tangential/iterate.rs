//! The rounds of the tangential active set: CG on the face of the sets, the set changes,
//! and the final measurements.

use super::constraint::FaceSums;
use super::{SlipStatus, TangentialError, TangentialReport, TangentialSolver, TangentialState};
use crate::elastic::ShearCompliance;
use crate::solver::ContactState;

/// The free part of element i's traction change: both components on a sticking element,
/// the component along the tangent (−e_y, e_x) of its traction's circle on a slipping one
/// (its magnitude is held at the bound), none elsewhere. `unit` holds e per element.
#[inline]
pub(super) fn project(status: SlipStatus, unit: (f64, f64), v: (f64, f64)) -> (f64, f64) {
    match status {
        SlipStatus::Stick => v,
        SlipStatus::Slip => {
            let (tx, ty) = (-unit.1, unit.0);
            let along = v.0 * tx + v.1 * ty;
            (along * tx, along * ty)
        }
        SlipStatus::Open => (0.0, 0.0),
    }
}

/// The round from which a step's sub-resolution slips keep their state whatever the step
/// (`classify`): a cycle breaker, since a step whose noise flips elements never ends,
/// while most steps end within ten rounds.
const CYCLE_ROUNDS: usize = 50;

impl TangentialSolver {
    /// The linear solve of one Newton round, CG on the face of the current sets: sticking
    /// tractions free (their slip must vanish), slipping ones free to turn along their
    /// circle's tangent t by θ, held there by the spring σ of the linearised projection
    /// (t·s = σθ); the rest fixed. Leaves u = K q up to the CG's recursion in
    /// `state.displacement`. Returns the iterations.
    ///
    /// Preconditioned by the diagonal K_ii + σ_i: without it the stiff springs of elements
    /// with a small bound (the contact's edge) stall CG. Stops at ‖w − u‖₂ ≤ `tolerance`·‖w‖₂
    /// over the face; under an imposed force, projected onto it, on the gaps left after the
    /// best uniform shift along the force (constraint.rs).
    pub(super) fn solve_face(
        &mut self,
        operator: &mut dyn ShearCompliance,
        state: &mut TangentialState,
        tolerance: f64,
    ) -> Result<usize, TangentialError> {
        let n = state.status.len();
        let diagonal = operator.self_compliance();
        // Under force control the tractions first carry the force (constraint.rs).
        let norms = self.meet_force(state, diagonal)?;
        {
            let [ux, uy] = &mut state.displacement;
            operator.apply([&state.traction[0], &state.traction[1]], [ux, uy]);
        }
        self.refresh_drive_offset(state);
        let compliance = self.drive_compliance;
        let mut target_norm = 0.0;
        let mut sums = FaceSums::default();
        for i in 0..n {
            let status = self.face_status(state.status[i], i);
            if status != SlipStatus::Open {
                target_norm += self.target[0][i].powi(2) + self.target[1][i].powi(2);
            }
            // The spring's force is zero at the round's start (θ = 0).
            let (rx, ry) = project(status, self.unit[i], self.gap(state, i));
            (self.residual[0][i], self.residual[1][i]) = (rx, ry);
            let inverse = 1.0 / (diagonal + self.spring[i]);
            (self.direction[0][i], self.direction[1][i]) = (rx * inverse, ry * inverse);
            sums.add((rx, ry), self.constraint_gradient(status, i), inverse);
        }
        let mut resolved = sums.resolve(norms);
        // The shift along the force found in this solve (constraint.rs).
        let mut moved = 0.0;
        if norms.is_some() {
            self.update_direction(state, diagonal, resolved.shift, 0.0);
            moved += resolved.shift;
        }
        let goal = tolerance * target_norm.sqrt();
        self.gap_floor = self.params.tolerance * target_norm.sqrt();
        let mut iterations = 0;
        while resolved.rr.sqrt() > goal {
            if iterations >= self.params.max_iterations {
                return Err(TangentialError::NotConverged {
                    iterations,
                    relative_residual: resolved.rr.sqrt() / target_norm.sqrt().max(f64::MIN_POSITIVE),
                    tolerance,
                });
            }
            {
                let [ax, ay] = &mut self.applied;
                operator.apply([&self.direction[0], &self.direction[1]], [ax, ay]);
            }
            let mut curvature = 0.0;
            for i in 0..n {
                let (dx, dy) = (self.direction[0][i], self.direction[1][i]);
                curvature += dx * self.applied[0][i] + dy * self.applied[1][i] + self.spring[i] * (dx * dx + dy * dy);
            }
            // A compliant drive's rank-one spring (Δ²/k)·𝟙𝟙ᵀ: a uniform displacement.
            let mut drive = [0.0; 2];
            if compliance > 0.0 {
                let sums = [0, 1].map(|c| self.direction[c].iter().sum::<f64>());
                drive = sums.map(|sum| compliance * sum);
                curvature += drive[0] * sums[0] + drive[1] * sums[1];
            }
            if !(curvature.is_finite() && curvature > 0.0) {
                return Err(TangentialError::NonFinite(iterations));
            }
            let alpha = resolved.rz / curvature;
            let mut next = FaceSums::default();
            for i in 0..n {
                let status = self.face_status(state.status[i], i);
                let (dx, dy) = (self.direction[0][i], self.direction[1][i]);
                let (mut ax, mut ay) = (self.applied[0][i], self.applied[1][i]);
                if compliance > 0.0 {
                    (ax, ay) = (ax + drive[0], ay + drive[1]);
                }
                let (ax, ay) = project(status, self.unit[i], (ax, ay));
                let spring = self.spring[i];
                for c in 0..2 {
                    state.displacement[c][i] += alpha * self.applied[c][i];
                }
                state.traction[0][i] += alpha * dx;
                state.traction[1][i] += alpha * dy;
                self.residual[0][i] -= alpha * (ax + spring * dx);
                self.residual[1][i] -= alpha * (ay + spring * dy);
                let residual = (self.residual[0][i], self.residual[1][i]);
                next.add_dividing(residual, self.constraint_gradient(status, i), diagonal + spring);
            }
            for c in 0..2 {
                self.drive_offset[c] += alpha * drive[c];
            }
            let next = next.resolve(norms);
            let beta = next.rz / resolved.rz;
            resolved = next;
            self.update_direction(state, diagonal, resolved.shift, beta);
            moved += resolved.shift;
            iterations += 1;
        }
        if !resolved.rr.is_finite() {
            return Err(TangentialError::NonFinite(iterations));
        }
        self.move_target(moved);
        Ok(iterations)
    }

    /// The status as the face sees it: a slipping element without a bound is fixed (its
    /// traction is zero).
    #[inline]
    pub(super) fn face_status(&self, status: SlipStatus, i: usize) -> SlipStatus {
        if status == SlipStatus::Slip && self.bound[i] == 0.0 {
            SlipStatus::Open
        } else {
            status
        }
    }

    /// The semismooth Newton point of every contact element with a bound, from u = K q in
    /// `state.displacement`: z = q + ρ(w − u) with ρ = 1/K_ii (Alart & Curnier 1991). Inside
    /// its disc (|z| ≤ g) the element sticks; outside it slips with q = g·z/|z| and the
    /// spring σ = (|z| − g)/(gρ) of the projection's tangent. In a step that moves a gross
    /// slide on, and in any step from its `round` [`CYCLE_ROUNDS`] on, a slipping element
    /// whose slip w − u is below what a full-tolerance solve resolves keeps slipping as it
    /// was: whether it sticks is then the solve's noise, and a step of almost no slip with
    /// every element on its bound (a slide advanced by 10⁻¹² of an element) let the noise
    /// flip hundreds of elements each round without end. (Before, a step is left to the
    /// disc: a hold's elements stick, and so does an element whose slip dies out.) Returns
    /// the number of status changes and the largest turn of a slipping traction.
    pub(super) fn classify(
        &mut self,
        normal: &ContactState,
        state: &mut TangentialState,
        rho: f64,
        round: usize,
    ) -> (usize, f64) {
        let floor = if self.gross_slide || round >= CYCLE_ROUNDS {
            self.gap_floor
        } else {
            0.0
        };
        let mut changes = 0;
        let mut largest_turn = 0.0f64;
        for i in 0..state.status.len() {
            self.spring[i] = 0.0;
            let bound = self.bound[i];
            if !normal.contact[i] || bound == 0.0 {
                continue;
            }
            let (qx, qy) = (state.traction[0][i], state.traction[1][i]);
            let (gx, gy) = self.gap(state, i);
            let was = state.status[i];
            if was == SlipStatus::Slip && floor > 0.0 && gx.hypot(gy) <= floor {
                continue;
            }
            let (zx, zy) = (qx + rho * gx, qy + rho * gy);
            let magnitude = zx.hypot(zy);
            if magnitude <= bound {
                if was != SlipStatus::Stick {
                    state.status[i] = SlipStatus::Stick;
                    changes += 1;
                }
                continue;
            }
            let (ex, ey) = (zx / magnitude, zy / magnitude);
            if was == SlipStatus::Slip && ex * self.unit[i].0 + ey * self.unit[i].1 < 0.0 {
                // A slip that turns over (a reversal) passes through the disc: the element
                // sticks first and its stuck traction decides where it slips, if it does.
                // Turning it over directly lets elements that barely slip flip each round.
                state.status[i] = SlipStatus::Stick;
                changes += 1;
                continue;
            }
            if was == SlipStatus::Slip {
                largest_turn = largest_turn.max((ex - self.unit[i].0).hypot(ey - self.unit[i].1));
            } else {
                state.status[i] = SlipStatus::Slip;
                changes += 1;
                self.break_loose(i);
            }
            // Under slip weakening the bound falls with the slip the Newton point estimates;
            // the fall of an element that was slipping counts as a turn (the rounds go on
            // while bounds still move; a break is a change already).
            let fall = self.weaken(i, (magnitude - self.bound[i]) / rho);
            if was == SlipStatus::Slip {
                largest_turn = largest_turn.max(fall);
            }
            // The bound after a break (the kinetic one, or the weakened one) when a static
            // law holds.
            let bound = self.bound[i];
            self.unit[i] = (ex, ey);
            if bound == 0.0 {
                // Broken loose to no kinetic bound: slips freely, no traction.
                state.traction[0][i] = 0.0;
                state.traction[1][i] = 0.0;
                continue;
            }
            self.spring[i] = (magnitude - bound) / (bound * rho);
            state.traction[0][i] = bound * ex;
            state.traction[1][i] = bound * ey;
        }
        (changes, largest_turn)
    }

    /// Slip, dissipation, counts, force and the optimality conditions of the final
    /// fields; records the shift.
    pub(super) fn finish(
        &self,
        operator: &dyn ShearCompliance,
        normal: &ContactState,
        shift: [f64; 2],
        state: &mut TangentialState,
        scale: f64,
        report: &mut TangentialReport,
    ) {
        let area = operator.grid().element_area();
        let largest_bound = self.bound.iter().fold(0.0f64, |m, &b| m.max(b));
        let mut c = super::Complementarity::default();
        let mut dissipated = 0.0;
        for i in 0..state.status.len() {
            if !normal.contact[i] {
                continue;
            }
            let (sx, sy) = self.gap(state, i);
            let (qx, qy) = (state.traction[0][i], state.traction[1][i]);
            let magnitude = qx.hypot(qy);
            c.bound_excess = c.bound_excess.max((magnitude - self.bound[i]).max(0.0));
            match state.status[i] {
                SlipStatus::Stick => c.stick_residual = c.stick_residual.max(sx.hypot(sy)),
                SlipStatus::Slip => {
                    state.slip[0][i] += sx;
                    state.slip[1][i] += sy;
                    dissipated += area * (qx * sx + qy * sy);
                    if magnitude > 0.0 {
                        let along = (sx * qx + sy * qy) / magnitude;
                        let across = (sx * qy - sy * qx) / magnitude;
                        c.slip_misalignment = c.slip_misalignment.max(across.abs());
                        c.backward_slip = c.backward_slip.max(-along);
                    }
                }
                SlipStatus::Open => {}
            }
        }
        c.stick_residual /= scale;
        c.slip_misalignment /= scale;
        c.backward_slip = c.backward_slip.max(0.0) / scale;
        c.bound_excess /= largest_bound.max(f64::MIN_POSITIVE);
        report.complementarity = c;
        report.dissipated_energy = dissipated;
        (report.stick_elements, report.slip_elements) = state.counts();
        report.force = state.force(area);
        state.shift = self.indenter_shift(shift);
        state.drive = shift;
    }

    /// max|w| over the contact set (1 where it vanishes: nothing moves).
    pub(super) fn target_scale(&self, normal: &ContactState) -> f64 {
        let scale = (0..normal.contact.len())
            .filter(|&i| normal.contact[i])
            .map(|i| self.target[0][i].hypot(self.target[1][i]))
            .fold(0.0, f64::max);
        if scale > 0.0 {
            scale
        } else {
            1.0
        }
    }
}
