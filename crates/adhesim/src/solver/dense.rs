//! Small dense symmetric positive definite systems by Cholesky's factorisation (Golub & Van
//! Loan, Matrix Computations, 4th ed., Alg. 4.2.1): the windows of the local peel and of
//! the peel predictor, and the normal equations of Anderson's mixing. The matrices are
//! row-major and at most a few hundred rows, so each inner product is a contiguous slice.
//! Its [`Summation`] order is the caller's: the predictor's hot windows take the
//! vectorisable four-lane [`dot`]; the local peel and the mixing subtract in order, as they
//! always did, so that their results keep their bits.

use super::dot;

/// The factorisation met a pivot that is not positive (or not a number): the matrix is not
/// numerically positive definite.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct NotPositiveDefinite {
    /// The column of the first such pivot.
    pub column: usize,
}

/// How `value − Σ a_k b_k` is summed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Summation {
    /// Term by term, k = 0, 1, …: `((value − a₀b₀) − a₁b₁) − …`.
    InOrder,
    /// `value − dot(a, b)` with the four interleaved partial sums of [`dot`].
    FourLanes,
}

impl Summation {
    #[inline(always)]
    fn subtract(self, value: f64, a: &[f64], b: &[f64]) -> f64 {
        match self {
            Self::InOrder => a.iter().zip(b).fold(value, |value, (x, y)| value - x * y),
            Self::FourLanes => value - dot(a, b),
        }
    }
}

/// Overwrites the lower triangle of the size×size row-major `matrix` (the only part read)
/// with its Cholesky factor L, L Lᵀ = A. The upper triangle is left as it was.
pub(crate) fn cholesky_factorise(
    matrix: &mut [f64],
    size: usize,
    summation: Summation,
) -> Result<(), NotPositiveDefinite> {
    for j in 0..size {
        let (row_j, below) = matrix[j * size..].split_at_mut(size);
        let pivot = summation.subtract(row_j[j], &row_j[..j], &row_j[..j]);
        if pivot.is_nan() || pivot <= 0.0 {
            return Err(NotPositiveDefinite { column: j });
        }
        let diagonal = pivot.sqrt();
        row_j[j] = diagonal;
        for row_i in below.chunks_exact_mut(size) {
            row_i[j] = summation.subtract(row_i[j], &row_i[..j], &row_j[..j]) / diagonal;
        }
    }
    Ok(())
}

/// Solves L Lᵀ x = b with the factor of [`cholesky_factorise`]; `x` holds b on entry.
pub(crate) fn cholesky_solve(factor: &[f64], size: usize, x: &mut [f64], summation: Summation) {
    for i in 0..size {
        let row = &factor[i * size..i * size + i];
        x[i] = summation.subtract(x[i], row, &x[..i]) / factor[i * size + i];
    }
    for i in (0..size).rev() {
        let mut value = x[i];
        for k in i + 1..size {
            value -= factor[k * size + i] * x[k];
        }
        x[i] = value / factor[i * size + i];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A Hilbert-like SPD matrix of size 7 is solved to rounding (residual below 1e-10 of
    /// its right-hand side, its condition number being about 1e4 after the diagonal shift),
    /// and a matrix with a negative pivot is refused at that column.
    #[test]
    fn solves_an_spd_system_and_refuses_an_indefinite_one() {
        let size = 7;
        let entry = |i: usize, j: usize| 1.0 / (i + j + 1) as f64 + if i == j { 0.1 } else { 0.0 };
        let matrix: Vec<f64> = (0..size * size).map(|k| entry(k / size, k % size)).collect();
        let rhs: Vec<f64> = (0..size).map(|i| (i as f64 - 2.5).sin()).collect();
        for summation in [Summation::InOrder, Summation::FourLanes] {
            let mut factor = matrix.clone();
            let mut x = rhs.clone();
            cholesky_factorise(&mut factor, size, summation).unwrap();
            cholesky_solve(&factor, size, &mut x, summation);
            for i in 0..size {
                let applied: f64 = (0..size).map(|j| entry(i, j) * x[j]).sum();
                assert!((applied - rhs[i]).abs() < 1e-10, "row {i}: {applied} vs {}", rhs[i]);
            }
            let mut indefinite = vec![4.0, 0.0, 0.0, 2.0, 1.0, 0.0, 0.0, 0.0, -1.0];
            assert_eq!(
                cholesky_factorise(&mut indefinite, 3, summation),
                Err(NotPositiveDefinite { column: 1 })
            );
        }
    }
}
