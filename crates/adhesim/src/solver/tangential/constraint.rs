//! Force control in one solve: the imposed force along e is a linear constraint on the
//! tractions, Σ q_i·e = Q/Δ², and the shift along e its Lagrange multiplier (docs/physics.md
//! §8.2). The face's CG then runs projected onto the constraint (projected preconditioned
//! CG: Gould, Hribar & Nocedal 2001, *SIAM J. Sci. Comput.* 23, 1376), as Polonsky & Keer
//! (1999, *Wear* 231, 206) hold the normal load in theirs: each direction is preconditioned
//! and then made orthogonal to the constraint's gradient, so every iterate carries the
//! force, and the gap that remains after the best uniform shift is what converges.

use super::{SlipStatus, TangentialError, TangentialSolver, TangentialState};

/// The imposed force of a step solved at once.
#[derive(Debug, Clone, Copy)]
pub(super) struct ForceConstraint {
    /// The direction e of the imposed force (a unit vector).
    pub unit: [f64; 2],
    /// Σ q·e the tractions carry: Q/Δ².
    pub sum: f64,
    /// The shift along e found beyond the step's first target.
    pub moved: f64,
}

/// The sums of one pass of the face's CG: r·r, r·M⁻¹r, and with a constraint c·r and
/// c·M⁻¹r (c the constraint's gradient on the face, M the diagonal preconditioner).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct FaceSums {
    pub rr: f64,
    pub rz: f64,
    pub cr: f64,
    pub czr: f64,
}

/// The constraint's own sums over the face, fixed through one solve: c·c and c·M⁻¹c.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct ConstraintNorms {
    pub cc: f64,
    pub czc: f64,
}

/// A pass's sums resolved: the shift λ along e that best closes the gaps (in the
/// preconditioner's norm), the squared gap left after it, and r·z of the projected
/// preconditioned residual z = M⁻¹(r + λc).
#[derive(Debug, Clone, Copy)]
pub(super) struct Resolved {
    pub shift: f64,
    pub rr: f64,
    pub rz: f64,
}

impl FaceSums {
    /// Adds element i's residual `r` and constraint gradient `c`, weighted by the inverse
    /// diagonal `inverse`.
    #[inline]
    pub fn add(&mut self, r: (f64, f64), c: (f64, f64), inverse: f64) {
        let squared = r.0 * r.0 + r.1 * r.1;
        self.rr += squared;
        self.rz += squared * inverse;
        self.add_constraint(r, c, inverse);
    }

    /// [`add`](Self::add) with the diagonal itself (a division rather than the product by
    /// its inverse: the CG's update has always divided, and its bits are kept).
    #[inline]
    pub fn add_dividing(&mut self, r: (f64, f64), c: (f64, f64), diagonal: f64) {
        let squared = r.0 * r.0 + r.1 * r.1;
        self.rr += squared;
        self.rz += squared / diagonal;
        self.add_constraint(r, c, 1.0 / diagonal);
    }

    #[inline]
    fn add_constraint(&mut self, r: (f64, f64), c: (f64, f64), inverse: f64) {
        let cr = c.0 * r.0 + c.1 * r.1;
        self.cr += cr;
        self.czr += cr * inverse;
    }

    /// The sums resolved against the constraint's norms (`None`: no constraint, the plain
    /// sums unchanged).
    pub fn resolve(&self, norms: Option<ConstraintNorms>) -> Resolved {
        let Some(ConstraintNorms { cc, czc }) = norms else {
            return Resolved {
                shift: 0.0,
                rr: self.rr,
                rz: self.rz,
            };
        };
        let shift = -self.czr / czc;
        Resolved {
            shift,
            rr: (self.rr + 2.0 * shift * self.cr + shift * shift * cc).max(0.0),
            rz: (self.rz + shift * self.czr).max(0.0),
        }
    }
}

impl ForceConstraint {
    /// The constraint's gradient on element i's face: e where it sticks, e's part along
    /// its circle's tangent where it slips (only the turn is free there), none where open.
    #[inline]
    pub fn gradient(&self, status: SlipStatus, traction_unit: (f64, f64)) -> (f64, f64) {
        super::iterate::project(status, traction_unit, (self.unit[0], self.unit[1]))
    }
}

impl TangentialSolver {
    /// Puts the tractions on the constraint before a solve: the force's deficit is spread
    /// along M⁻¹c (the first preconditioned step of the multiplier), so that every CG
    /// iterate from it carries the force. Returns the constraint's norms over the face,
    /// or an error when no free traction can change the force (every contact element
    /// open, or slipping across e).
    pub(super) fn meet_force(
        &self,
        state: &mut TangentialState,
        diagonal: f64,
    ) -> Result<Option<ConstraintNorms>, TangentialError> {
        let Some(constraint) = self.constraint else {
            return Ok(None);
        };
        let mut carried = 0.0;
        let mut norms = ConstraintNorms::default();
        for i in 0..state.status.len() {
            carried += state.traction[0][i] * constraint.unit[0] + state.traction[1][i] * constraint.unit[1];
            let c = constraint.gradient(self.face_status(state.status[i], i), self.unit[i]);
            let squared = c.0 * c.0 + c.1 * c.1;
            norms.cc += squared;
            norms.czc += squared / (diagonal + self.spring[i]);
        }
        if norms.czc.is_nan() || norms.czc <= 0.0 {
            return Err(TangentialError::ForceNotReached {
                target: constraint.sum,
                reached: carried,
                trials: 1,
            });
        }
        let step = (constraint.sum - carried) / norms.czc;
        for i in 0..state.status.len() {
            let c = constraint.gradient(self.face_status(state.status[i], i), self.unit[i]);
            let inverse = 1.0 / (diagonal + self.spring[i]);
            state.traction[0][i] += step * c.0 * inverse;
            state.traction[1][i] += step * c.1 * inverse;
        }
        Ok(Some(norms))
    }

    /// The constraint's gradient on element i's face ((0, 0) without a constraint).
    #[inline]
    pub(super) fn constraint_gradient(&self, status: SlipStatus, i: usize) -> (f64, f64) {
        match self.constraint {
            Some(constraint) => constraint.gradient(status, self.unit[i]),
            None => (0.0, 0.0),
        }
    }

    /// The CG's next direction p = M⁻¹(r + λc) + βp, λ the pass's shift, with the
    /// residual replaced by r + λc: the gaps as they are once the target has moved by λe
    /// (without it the residual grows along c while its projection shrinks, and the
    /// rounding of their difference let the iterates drift off the force by whole percents
    /// over a hundred iterations). M⁻¹r + βp without a constraint.
    pub(super) fn update_direction(&mut self, state: &TangentialState, diagonal: f64, shift: f64, beta: f64) {
        let constrained = self.constraint.is_some();
        for i in 0..state.status.len() {
            let inverse = 1.0 / (diagonal + self.spring[i]);
            let (mut rx, mut ry) = (self.residual[0][i], self.residual[1][i]);
            if constrained {
                let c = self.constraint_gradient(self.face_status(state.status[i], i), i);
                (rx, ry) = (rx + shift * c.0, ry + shift * c.1);
                (self.residual[0][i], self.residual[1][i]) = (rx, ry);
            }
            self.direction[0][i] = rx * inverse + beta * self.direction[0][i];
            self.direction[1][i] = ry * inverse + beta * self.direction[1][i];
        }
    }

    /// After a solve: the shift λ it found moves every element's target by λe (the stuck
    /// elements' gaps close) and is added to the step's shift.
    pub(super) fn move_target(&mut self, shift: f64) {
        let Some(constraint) = self.constraint.as_mut() else {
            return;
        };
        constraint.moved += shift;
        for c in 0..2 {
            let along = shift * constraint.unit[c];
            for target in self.target[c].iter_mut() {
                *target += along;
            }
        }
    }

    /// The step's shift: `shift`, moved along e by what a force-controlled solve found.
    pub(super) fn solved_shift(&self, shift: [f64; 2]) -> [f64; 2] {
        match self.constraint {
            Some(constraint) => [0, 1].map(|c| shift[c] + constraint.moved * constraint.unit[c]),
            None => shift,
        }
    }
}
