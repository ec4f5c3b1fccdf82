//! Contact solvers: non-adhesive (Polonsky–Keer CCG; nested-grid preconditioned active
//! set) and adhesive (JKR-type active set; cohesive laws of finite range).
//!
//! A solve takes the operator, the indenter heights on the grid and a control, and a
//! [`ContactState`] that is both the warm start and the result. Gap g = z − d + u ≥ 0,
//! pressure p > 0 compressive; contact means g = 0.

mod adhesive;
mod ccg;
mod certificate;
mod cohesive;
mod contact_window;
mod dense;
mod local_peel;
mod nested;
mod peel_predictor;
mod shape_cache;
mod state;
mod tangential;
mod workspace;

pub use adhesive::{
    critical_stress, detachment_element_size, AdhesiveCheckpoint, AdhesiveParams, AdhesiveSolver, Attachment,
    Detachment, PredictedGrowth, StepReport, ELEMENT_ENERGY_FACTOR, PREDICTION_MIN_ELEMENTS,
};
pub use ccg::{Ccg, CcgParams};
pub use certificate::LATTICE_INVERSE_DIAGONAL;
pub use cohesive::{
    Acceleration, CohesiveCheckpoint, CohesiveLaw, CohesiveParams, CohesiveSolver, Dugdale, Exponential, Trapezoid,
};
pub use nested::{NestedActiveSet, NestedCheckpoint, NestedParams};
pub use state::ContactState;
pub use tangential::{
    Complementarity, FrictionLaw, FrictionLawError, SlipStatus, TangentialError, TangentialParams, TangentialReport,
    TangentialSolver, TangentialState,
};

use crate::elastic::ElasticOperator;
use rayon::prelude::*;
use std::ops::Range;
use thiserror::Error;

/// What is prescribed in a normal contact solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Control {
    /// Indentation depth d of the indenter's reference point (rigid-body approach).
    Displacement(f64),
    /// Total normal force F = Δ²Σp (> 0 compressive).
    Load(f64),
}

/// What a solve did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SolveReport {
    /// Iterations of the (outer) solver.
    pub iterations: usize,
    /// Final convergence measure (solver specific, relative).
    pub residual: f64,
    /// Number of elements in contact.
    pub contact_elements: usize,
    /// Real contact area Δ²·|C|.
    pub contact_area: f64,
    /// Total normal force Δ²Σp.
    pub force: f64,
    /// Indentation depth (prescribed, or found under load control).
    pub depth: f64,
    /// Elastic operator applications (FFT pairs) spent.
    pub operator_applications: u64,
    /// Applications of the CG's spectral preconditioner (FFT pairs of the solved grid's
    /// own size; not in `operator_applications`).
    pub preconditioner_applications: u64,
}

/// Why a solve failed.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum SolveError {
    /// The iteration limit was reached before the tolerance. Every solver states its
    /// residual the same way: the displacement residual on the contact set C,
    /// ‖d − z − u‖₂ over C (length units; for the adhesive and nested CG the residual of the
    /// fixed-set system, for [`Ccg`] the gap on its active set, for its periodic depth
    /// control the mismatch of the reached mean depth), absolute and relative to ‖d − z‖₂
    /// over C. `tolerance` is the solver's own stopping tolerance (its parameters say on
    /// which measure: [`Ccg`] stops on the relative pressure change).
    #[error("solver did not converge in {iterations} iterations: displacement residual {absolute_residual:.3e} ({relative_residual:.3e} relative) with stopping tolerance {tolerance:.1e}")]
    NotConverged {
        /// Iterations done.
        iterations: usize,
        /// ‖d − z − u‖₂ over the contact set when the solver stopped (length units).
        absolute_residual: f64,
        /// The same divided by ‖d − z‖₂ over the contact set.
        relative_residual: f64,
        /// The solver's stopping tolerance.
        tolerance: f64,
    },
    /// The fixed-set operator lost positive definiteness in CG (a direction with
    /// non-positive curvature dᵀKd: a defective operator or rounding on a degenerate set).
    #[error("CG lost positive definiteness at iteration {iteration}: curvature {curvature:e}")]
    NotPositiveDefinite {
        /// Iteration at which it was detected.
        iteration: usize,
        /// dᵀKd of the direction.
        curvature: f64,
    },
    /// The attach/detach rounds of one adhesive step did not reach a stable contact set.
    #[error("no stable contact set after {rounds} attach/detach rounds in one step")]
    TooManyRounds {
        /// The limit that was reached.
        rounds: usize,
    },
    /// A NaN or infinity appeared in the iteration (bad heights or operator).
    #[error("solver produced a non-finite value at iteration {iteration}")]
    NonFinite {
        /// Iteration at which it was detected.
        iteration: usize,
    },
    /// Periodic displacement control asked for a depth the cell cannot reach: the surface
    /// displacement of a periodic half-space has zero mean (K̂(0) = 0), so the mean gap is
    /// mean(z) − d ≥ 0 and full contact is reached at d = mean(z) under a finite load;
    /// a deeper indenter would need a negative mean gap (docs/physics.md §1b).
    #[error("depth {depth:e} lies beyond full contact of the periodic cell (reached at depth {full_contact_depth:e}, the mean height of the indenter: the mean gap mean(z) − d cannot be negative on a periodic half-space)")]
    BeyondFullContact {
        /// The depth asked for.
        depth: f64,
        /// mean(z): the depth at which the whole cell is in contact.
        full_contact_depth: f64,
    },
    /// A load-controlled solve was asked for a non-positive or non-finite load.
    #[error("load control needs a finite load > 0, got {0}")]
    InvalidLoad(f64),
    /// The heights do not match the grid.
    #[error("heights have {got} values, the grid has {expected} elements")]
    SizeMismatch {
        /// Elements of the grid.
        expected: usize,
        /// Values given.
        got: usize,
    },
    /// The solver does not handle this boundary kind.
    #[error("{solver} solves free (non-periodic) grids only: on a periodic half-space displacement control means mean-gap control (use Ccg)")]
    PeriodicUnsupported {
        /// The solver's name.
        solver: &'static str,
    },
}

/// Scratch vectors of [`masked_pcg`], one value per grid element.
struct PcgBuffers<'a> {
    residual: &'a mut [f64],
    preconditioned: &'a mut [f64],
    direction: &'a mut [f64],
    response: &'a mut [f64],
    /// 1 on the fixed set, 0 elsewhere.
    mask: &'a [f64],
}

/// What [`masked_pcg`] did when its stopping test accepted.
#[derive(Debug, Clone, Copy, PartialEq)]
struct PcgInfo {
    /// Iterations done.
    iterations: usize,
}

/// Why [`masked_pcg`] stopped without its stopping test accepting.
#[derive(Debug, Clone, Copy, PartialEq)]
enum PcgError {
    /// The iteration limit was reached; ‖r‖₂ of the last residual (on the set).
    NotConverged { iterations: usize, residual_norm: f64 },
    /// A residual the stopping test rejected as non-finite, or a non-finite curvature.
    NonFinite { iteration: usize },
    /// A direction with dᵀKd ≤ 0.
    NotPositiveDefinite { iteration: usize, curvature: f64 },
}

impl PcgError {
    /// The [`SolveError`] of a solver whose right-hand side has ‖d − z‖₂ = `target_norm`
    /// over the set and whose stopping tolerance is `tolerance`.
    fn into_solve_error(self, target_norm: f64, tolerance: f64) -> SolveError {
        match self {
            PcgError::NotConverged {
                iterations,
                residual_norm,
            } => SolveError::NotConverged {
                iterations,
                absolute_residual: residual_norm,
                relative_residual: residual_norm / target_norm.max(f64::MIN_POSITIVE),
                tolerance,
            },
            PcgError::NonFinite { iteration } => SolveError::NonFinite { iteration },
            PcgError::NotPositiveDefinite { iteration, curvature } => {
                SolveError::NotPositiveDefinite { iteration, curvature }
            }
        }
    }
}

/// Preconditioned CG for K_CC p_C = r_C on the fixed set given by `buffers.mask`, starting
/// from the residual in `buffers.residual` (zero outside the set); updates `pressure` p and
/// `displacement` u = K p. Search directions are applied in single precision (`apply_single`): each
/// caller restarts from an exact residual, so the rounding stays far below its goals.
/// `precondition` writes M⁻¹r on the given rows (the set's; other rows are not read);
/// `converged` sees ‖r‖², r, p and u after each iteration, with the element range of the
/// set's rows (r and the change of p vanish outside it), and answers `None` for a residual
/// it rejects as non-finite.
/// Shared by the adhesive solver and the nested active set (their stopping rules differ).
///
/// Only the set's rows are visited where the vectors vanish outside them, and the
/// element-wise loops over the whole grid run on the rayon pool: the results are the bits
/// of the plain full-grid loops (element-wise updates do not depend on the split, and the
/// skipped dot-product terms are exact zeros in the same lanes, [`dot_on`]).
fn masked_pcg<O: ElasticOperator + ?Sized>(
    operator: &mut O,
    pressure: &mut [f64],
    displacement: &mut [f64],
    buffers: PcgBuffers<'_>,
    mut precondition: impl FnMut(&[f64], &mut [f64], Range<usize>),
    mut converged: impl FnMut(Residual, &[f64], &[f64], &[f64], Range<usize>) -> Option<bool>,
    max_iterations: usize,
) -> Result<PcgInfo, PcgError> {
    let PcgBuffers {
        residual,
        preconditioned,
        direction,
        response,
        mask,
    } = buffers;
    let (n, rows) = (operator.grid().nx(), operator.grid().ny());
    // The directions vanish outside the set's rows: their row transforms are skipped.
    let (support, rows) = (mask_rows(mask, n), 0..rows);
    let set = support.start * n..support.end * n;
    let mut apply_preconditioner = |residual: &[f64], preconditioned: &mut [f64]| -> f64 {
        precondition(residual, preconditioned, support.clone());
        preconditioned[set.clone()]
            .par_chunks_mut(PARALLEL_CHUNK)
            .zip(mask[set.clone()].par_chunks(PARALLEL_CHUNK))
            .for_each(|(z, m)| z.iter_mut().zip(m).for_each(|(z, m)| *z *= m));
        dot_on(residual, preconditioned, set.clone())
    };
    // Outside the set's rows only the widened lanes of `dot_on` are read: zero there.
    for vector in [&mut *preconditioned, &mut *direction] {
        vector[..set.start].fill(0.0);
        vector[set.end..].fill(0.0);
    }
    let mut rho = apply_preconditioner(residual, preconditioned);
    direction[set.clone()].copy_from_slice(&preconditioned[set.clone()]);
    let mut norm2 = f64::INFINITY;
    for iteration in 1..=max_iterations {
        operator.apply_single_rows(direction, response, support.clone(), rows.clone());
        let curvature = dot_on(direction, response, set.clone());
        if !curvature.is_finite() {
            return Err(PcgError::NonFinite { iteration });
        }
        if curvature <= 0.0 {
            return Err(PcgError::NotPositiveDefinite { iteration, curvature });
        }
        let step = rho / curvature;
        displacement
            .par_chunks_mut(PARALLEL_CHUNK)
            .zip(response.par_chunks(PARALLEL_CHUNK))
            .for_each(|(u, du)| u.iter_mut().zip(du).for_each(|(u, du)| *u += step * du));
        let largest = pressure[set.clone()]
            .par_chunks_mut(PARALLEL_CHUNK)
            .zip(residual[set.clone()].par_chunks_mut(PARALLEL_CHUNK))
            .zip(direction[set.clone()].par_chunks(PARALLEL_CHUNK))
            .zip(
                response[set.clone()]
                    .par_chunks(PARALLEL_CHUNK)
                    .zip(mask[set.clone()].par_chunks(PARALLEL_CHUNK)),
            )
            .map(|(((p, r), d), (du, m))| {
                // ‖r‖∞ in the same pass (a maximum is exact in any order).
                let mut largest = 0.0f64;
                for k in 0..p.len() {
                    p[k] += step * d[k];
                    r[k] -= step * du[k] * m[k];
                    largest = largest.max(r[k].abs());
                }
                largest
            })
            .reduce(|| 0.0, f64::max);
        norm2 = dot_on(residual, residual, set.clone());
        let measured = Residual { norm2, largest };
        if converged(measured, residual, pressure, displacement, set.clone())
            .ok_or(PcgError::NonFinite { iteration })?
        {
            return Ok(PcgInfo { iterations: iteration });
        }
        let new_rho = apply_preconditioner(residual, preconditioned);
        let ratio = new_rho / rho;
        rho = new_rho;
        direction[set.clone()]
            .par_chunks_mut(PARALLEL_CHUNK)
            .zip(preconditioned[set.clone()].par_chunks(PARALLEL_CHUNK))
            .zip(mask[set.clone()].par_chunks(PARALLEL_CHUNK))
            .for_each(|((d, z), m)| {
                for k in 0..d.len() {
                    d[k] = (z[k] + ratio * d[k]) * m[k];
                }
            });
    }
    Err(PcgError::NotConverged {
        iterations: max_iterations,
        residual_norm: norm2.sqrt(),
    })
}

/// The residual of a CG iterate as the update measured it: ‖r‖² (the serial `dot_on`) and
/// ‖r‖∞ over the set.
#[derive(Debug, Clone, Copy)]
struct Residual {
    norm2: f64,
    largest: f64,
}

/// Elements per rayon task in the element-wise loops and exact reductions (max, any) over
/// the grid or the set's rows: 16 rows of 512.
pub(crate) const PARALLEL_CHUNK: usize = 1 << 13;

/// `target.copy_from_slice(source)` on the pool: a full-grid copy made by one thread is
/// a serial stretch the other threads wait out (a copy gives the same values for any split).
pub(crate) fn copy_on_pool<T: Copy + Send + Sync>(target: &mut [T], source: &[T]) {
    assert_eq!(target.len(), source.len(), "copy between fields of different sizes");
    target
        .par_chunks_mut(PARALLEL_CHUNK)
        .zip(source.par_chunks(PARALLEL_CHUNK))
        .for_each(|(target, source)| target.copy_from_slice(source));
}

/// How many elements of `flags` are set, counted on the pool (a count is exact in any order).
pub(crate) fn count_on_pool(flags: &[bool]) -> usize {
    flags
        .par_chunks(PARALLEL_CHUNK)
        .map(|chunk| chunk.iter().filter(|&&flag| flag).count())
        .sum()
}

/// [`dot`] of two vectors whose products vanish outside `range`, with the bits of the dot
/// over the whole vectors: the range is widened to whole lanes of four, so every nonzero
/// product meets the same partial sum in the same order, and the skipped ones are exact
/// zeros (adding a zero leaves a partial sum unchanged).
pub(crate) fn dot_on(a: &[f64], b: &[f64], range: Range<usize>) -> f64 {
    let start = range.start - range.start % 4;
    let end = (range.end.div_ceil(4) * 4).min(a.len());
    if start >= end {
        return 0.0;
    }
    dot(&a[start..end], &b[start..end])
}

/// The elements of the rows (of `row_length` elements) that hold contact, first such row to
/// last (empty without contact): a field that vanishes off the contact needs no visit
/// outside them, and a loop over them meets the contact elements in the same order.
pub(crate) fn contact_span(contact: &[bool], row_length: usize) -> Range<usize> {
    let first = contact.iter().position(|&c| c);
    let last = contact.iter().rposition(|&c| c);
    match (first, last) {
        (Some(first), Some(last)) => first / row_length * row_length..(last / row_length + 1) * row_length,
        _ => 0..0,
    }
}

/// The rows (of `row_length` elements) that hold a nonzero of `mask`, first to last.
fn mask_rows(mask: &[f64], row_length: usize) -> std::ops::Range<usize> {
    let first = mask.iter().position(|&m| m != 0.0);
    let last = mask.iter().rposition(|&m| m != 0.0);
    match (first, last) {
        (Some(first), Some(last)) => first / row_length..last / row_length + 1,
        _ => 0..0,
    }
}

/// Runs `op` on a worker thread of the current rayon pool (directly when already on one).
///
/// The operator's transforms are rayon loops of three phases each. Called from a thread
/// outside the pool, every phase is handed to the workers while the caller sleeps on a
/// latch, so each application costs several cross-thread wake-ups; on a worker the caller
/// takes its own share of every phase. Measured on the Fig. 1 cycle at N = 256 on 2
/// cores: 22.3 s → 15.5 s wall, identical results (every transform is independent of the
/// split, `elastic::spectral`).
pub(crate) fn on_worker<R: Send>(op: impl FnOnce() -> R + Send) -> R {
    if rayon::current_thread_index().is_some() {
        op()
    } else {
        rayon::scope(|_| op())
    }
}

/// Σ a_k b_k with four interleaved partial sums (vectorisable; deterministic). Inlined:
/// the peel predictor calls it on short rows of its window solves.
#[inline(always)]
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut partial = [0.0; 4];
    let (a_chunks, b_chunks) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = a_chunks
        .remainder()
        .iter()
        .zip(b_chunks.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in a_chunks.zip(b_chunks) {
        for lane in 0..4 {
            partial[lane] += x[lane] * y[lane];
        }
    }
    (partial[0] + partial[1]) + (partial[2] + partial[3]) + tail
}

#[cfg(test)]
mod tests {
    use super::{contact_span, dot, dot_on};

    /// `dot_on` over the nonzero range has the bits of `dot` over the whole vectors, for
    /// ranges at every alignment to the four lanes and lengths with and without a tail.
    #[test]
    fn dot_on_a_range_has_the_bits_of_the_whole_dot() {
        for len in [37, 40, 41] {
            for start in 0..9 {
                for end in [start, start + 1, start + 5, len - 3, len] {
                    let end = end.max(start).min(len);
                    let value = |k: usize| {
                        if (start..end).contains(&k) {
                            (k as f64 * 0.37).sin() * 1e3
                        } else {
                            0.0
                        }
                    };
                    let a: Vec<f64> = (0..len).map(value).collect();
                    let b: Vec<f64> = (0..len).map(|k| (k as f64 * 1.3).cos() + 1e-9 * k as f64).collect();
                    assert_eq!(
                        dot_on(&a, &b, start..end).to_bits(),
                        dot(&a, &b).to_bits(),
                        "len {len}, range {start}..{end}"
                    );
                }
            }
        }
    }

    /// The span covers whole rows from the first contact row to the last.
    #[test]
    fn contact_span_is_whole_rows() {
        let mut contact = vec![false; 25];
        assert_eq!(contact_span(&contact, 5), 0..0);
        contact[7] = true;
        contact[13] = true;
        assert_eq!(contact_span(&contact, 5), 5..15);
    }
}
