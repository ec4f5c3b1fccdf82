//! A compliant drive and the slip events it lets through: the indenter is pulled through a
//! spring of stiffness k by a drive at X, so its shift δ = X − F/k follows from the
//! tractions (docs/physics.md §8.2).

use super::{FrictionLawError, TangentialReport, TangentialSolver, TangentialState};

impl TangentialSolver {
    /// The same solver pulling the indenter through a spring of `stiffness` k (force per
    /// length, per component): [`step`](Self::step)'s shift is then the drive's position X,
    /// and the indenter's δ = X − F/k with F = Δ²Σq the tractions' force. Eliminating δ
    /// leaves the stuck elements' conditions K q + (Δ²/k)·𝟙𝟙ᵀq = u⁻ + X − δ⁻ per
    /// component: the elastic operator plus a rank-one spring, still symmetric positive
    /// definite, so the same active set solves it. A drop of F (a slip event) moves the
    /// indenter ahead of the drive's pace, as in a spring–block slider. An error for k not
    /// finite and > 0.
    ///
    /// # Example
    /// A glued patch pulled through a spring: the indenter lags the drive so that the
    /// spring's force equals the tractions', F = k(X − δ).
    /// ```
    /// use adhesim::{Boundary, ContactState, FrictionLaw, Grid, ShearMaterial};
    /// use adhesim::{TangentialOperator, TangentialParams, TangentialSolver, TangentialState};
    ///
    /// let grid = Grid::new(8, 1.0, Boundary::Free)?;
    /// let mut operator = TangentialOperator::new(grid, ShearMaterial::from_contact_modulus(4.0, 0.5))?;
    /// let mut normal = ContactState::new(&grid);
    /// for k in [27, 28, 35, 36] {
    ///     normal.contact[k] = true;
    ///     normal.pressure[k] = 1.0;
    /// }
    /// let stiffness = 0.05;
    /// let mut solver = TangentialSolver::new(FrictionLaw::NoSlip, TangentialParams::default())
    ///     .with_drive_stiffness(stiffness)?;
    /// let mut state = TangentialState::new(grid.len());
    /// let report = solver.step(&mut operator, &normal, [1e-3, 0.0], &mut state)?;
    /// let lag = 1e-3 - report.shift[0];
    /// assert!(lag > 0.0 && (report.force[0] / (stiffness * lag) - 1.0).abs() < 1e-12);
    /// assert!(TangentialSolver::new(FrictionLaw::NoSlip, TangentialParams::default())
    ///     .with_drive_stiffness(0.0)
    ///     .is_err());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_drive_stiffness(mut self, stiffness: f64) -> Result<Self, FrictionLawError> {
        if !(stiffness.is_finite() && stiffness > 0.0) {
            return Err(FrictionLawError::DriveStiffness(stiffness));
        }
        self.drive_stiffness = Some(stiffness);
        Ok(self)
    }

    /// The drive's spring (None: a rigid drive, the shift is the indenter's).
    pub fn drive_stiffness(&self) -> Option<f64> {
        self.drive_stiffness
    }

    /// The spring's stretch X − δ = (Δ²/k)·Σq of the current tractions.
    pub(super) fn refresh_drive_offset(&mut self, state: &TangentialState) {
        if self.drive_compliance > 0.0 {
            self.drive_offset = [0, 1].map(|c| self.drive_compliance * state.traction[c].iter().sum::<f64>());
        }
    }

    /// w_i − u_i of element i: the slip the element would make, its target less its
    /// displacement, less the spring's stretch under a compliant drive.
    #[inline]
    pub(super) fn gap(&self, state: &TangentialState, i: usize) -> (f64, f64) {
        let x = self.target[0][i] - state.displacement[0][i];
        let y = self.target[1][i] - state.displacement[1][i];
        if self.drive_compliance > 0.0 {
            (x - self.drive_offset[0], y - self.drive_offset[1])
        } else {
            (x, y)
        }
    }

    /// The indenter's shift at the end of a step to the drive's position `drive`.
    pub(super) fn indenter_shift(&self, drive: [f64; 2]) -> [f64; 2] {
        if self.drive_compliance > 0.0 {
            [drive[0] - self.drive_offset[0], drive[1] - self.drive_offset[1]]
        } else {
            drive
        }
    }

    /// Decides whether the step was a slip event: elements broke loose from their static
    /// bound and the force along the drive's `increment` fell (from the tractions
    /// `before`). The event's slip is fast next to the drive (quasi-static), so it ends
    /// with the contact at rest: every element starts the next step stuck under its
    /// static bound (a spring–block slider without inertia stops where the kinetic force
    /// balances its spring: Baumberger & Caroli 2006, *Adv. Phys.* 55, 279).
    pub(super) fn note_slip_event(
        &self,
        before: &[Vec<f64>; 2],
        increment: [f64; 2],
        state: &mut TangentialState,
        report: &mut TangentialReport,
    ) {
        report.shift = state.shift;
        report.broke_loose = self.broke_loose;
        let change: f64 = (0..2)
            .map(|c| {
                let was: f64 = before[c].iter().sum();
                let now: f64 = state.traction[c].iter().sum();
                (now - was) * increment[c]
            })
            .sum();
        report.slip_event = self.broke_loose > 0 && change < 0.0;
        state.at_rest = report.slip_event;
    }
}
