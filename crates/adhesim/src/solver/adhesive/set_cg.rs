//! The preconditioned CG of a fixed-set solve with its stopping tests (docs/physics.md
//! §3.2, docs/fast-step.md): shared by the solve on the whole grid and on a window.

use crate::elastic::{ElasticOperator, SpectralPreconditioner};
use crate::solver::certificate::{attachments_certain, count_releases, gap_error_bound_of, pressure_error_bound_of};
use crate::solver::workspace::precondition_rows;
use crate::solver::{masked_pcg, PcgBuffers, PcgError, PcgInfo, PARALLEL_CHUNK};
use rayon::prelude::*;

/// When a fixed-set solve may stop (docs/fast-step.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum StopRule {
    /// Converge fully (outputs, reference rule, oracle).
    Converge,
    /// Stop once the release decisions are certain and release something.
    Releases,
    /// As `Releases`, or once there is certainly no release and the attachment decisions
    /// are certain (the step goes on to attach: trial neighbours exist).
    ReleasesOrAttachments,
    /// Tie refinement: stop once no release decision lies inside the error band.
    Decided,
    /// The state that ends a step: converge at `OUTPUT_TOLERANCE_SCALE` times the
    /// tolerances, for the reported force and energy.
    Output,
}

/// How a fixed-set CG stops (see [`StopRule`]) and what it is measured against.
#[derive(Clone, Copy)]
pub(super) struct SetRule {
    pub(super) stop: StopRule,
    pub(super) tolerance_scale: f64,
    pub(super) convergence: Convergence,
    pub(super) contact_modulus: f64,
    pub(super) element_size: f64,
    pub(super) max_iterations: usize,
}

/// The set's fields on the CG's grid (the whole grid or a window): contact, critical
/// stresses, and the heights and depth where the attachment decisions may stop the CG
/// (only on the whole grid: a window does not see the gaps outside it).
pub(super) struct SetFields<'a> {
    pub(super) contact: &'a [bool],
    pub(super) critical_stress: &'a [f64],
    pub(super) attachments: Option<(&'a [f64], f64)>,
}

/// The preconditioned CG of a fixed-set solve with its stopping tests: the plain
/// convergence, or the certified early stops of `rule.stop` (docs/fast-step.md). Returns
/// the CG's outcome and whether it stopped on a certificate.
pub(super) fn solve_on_set<O: ElasticOperator + ?Sized>(
    operator: &mut O,
    (pressure, displacement): (&mut [f64], &mut [f64]),
    buffers: PcgBuffers<'_>,
    (mut preconditioner, applications): (Option<&mut SpectralPreconditioner>, &mut u64),
    fields: SetFields<'_>,
    rule: SetRule,
) -> (Result<PcgInfo, PcgError>, bool) {
    let SetFields {
        contact,
        critical_stress,
        attachments,
    } = fields;
    let SetRule {
        stop,
        tolerance_scale,
        convergence,
        contact_modulus,
        element_size,
        max_iterations,
    } = rule;
    let n = operator.grid().nx();
    let converged = |scale, norm2, residual: &[f64], contact: &[bool]| convergence.met(scale, norm2, residual, contact);
    let mut certified = false;
    let outcome = masked_pcg(
        operator,
        pressure,
        displacement,
        buffers,
        |residual, preconditioned, rows| {
            let preconditioner = preconditioner.as_deref_mut();
            precondition_rows(preconditioner, (residual, preconditioned), rows, n, applications);
        },
        |measured, residual, pressure, displacement, set| {
            let norm2 = measured.norm2;
            // r and the set lie in `set`: the scans there see every element that counts.
            let (residual, contact_rows) = (&residual[set.clone()], &contact[set.clone()]);
            if converged(tolerance_scale, norm2, residual, contact_rows) {
                return Some(true);
            }
            // Stop once the release decisions cannot change (docs/fast-step.md).
            if stop != StopRule::Converge && stop != StopRule::Output {
                let band = pressure_error_bound_of(measured.largest, contact_modulus, element_size);
                let critical_stress = &critical_stress[set.clone()];
                let (certain, uncertain) = count_releases(&pressure[set], contact_rows, critical_stress, band);
                certified = if stop == StopRule::Decided {
                    // Certain decisions on a state converged at least as the plain solve
                    // (its u is exact now, so the plain criterion may not hold yet).
                    uncertain == 0 && converged(1.0, norm2, residual, contact_rows)
                } else if certain > 0 {
                    uncertain <= certain
                } else if uncertain == 0 && stop == StopRule::ReleasesOrAttachments {
                    attachments.is_some_and(|(heights, depth)| {
                        attachments_certain(
                            heights,
                            depth,
                            displacement,
                            contact,
                            gap_error_bound_of(measured.largest),
                        )
                    })
                } else {
                    false
                };
            }
            Some(certified)
        },
        max_iterations,
    );
    (outcome, certified)
}

/// The plain convergence test of a fixed-set solve: ‖r‖ ≤ ε‖b‖ (`relative` = ε‖b‖) and,
/// with σ_c > 0, |r_k| ≤ `pointwise` on C.
#[derive(Debug, Clone, Copy)]
pub(super) struct Convergence {
    pub(super) relative: f64,
    pub(super) pointwise: f64,
}

impl Convergence {
    /// Whether the residual (squared norm `norm2`) meets `scale` times the tolerances.
    pub(super) fn met(&self, scale: f64, norm2: f64, residual: &[f64], contact: &[bool]) -> bool {
        if norm2.sqrt() > scale * self.relative {
            return false;
        }
        if self.pointwise.is_finite() {
            // On the pool: a test of every element, the same answer in any order.
            let bound = scale * self.pointwise;
            residual
                .par_chunks(PARALLEL_CHUNK)
                .zip(contact.par_chunks(PARALLEL_CHUNK))
                .all(|(residual, contact)| residual.iter().zip(contact).all(|(r, &c)| !c || r.abs() <= bound))
        } else {
            true
        }
    }
}
