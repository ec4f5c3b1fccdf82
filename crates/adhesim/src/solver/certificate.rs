//! Certified release decisions from an unconverged fixed-set solve (docs/fast-step.md).
//!
//! On a fixed contact set C the pressure error e = p − p* of a CG iterate satisfies
//! K_CC e = −r_C. S_C = K_CC⁻¹ is an M-matrix with positive row sums (docs/physics.md
//! §2.4a), so Σ_j |S_C,ij| < 2·S_C,ii and ‖e‖∞ ≤ 2·max diag(S_C)·‖r‖∞. A diagonal entry of
//! the inverse of a principal submatrix never exceeds that of the whole operator's inverse,
//! so max diag(S_C) ≤ [`LATTICE_INVERSE_DIAGONAL`]·E*/Δ for every set on every grid.

use rayon::prelude::*;

/// Diagonal of the inverse of the discrete Love operator on the infinite square lattice, in
/// units of E*/Δ, rounded up: (2π)⁻²∫∫ dθ / K̂(θ) = 1.162 781 0 (FFT of the lattice
/// kernel on 1024² and 2048² periodic boxes: 1.162 780 98 and 1.162 780 97). The test
/// `lattice_inverse_is_an_m_matrix` checks that finite grids stay below it.
pub const LATTICE_INVERSE_DIAGONAL: f64 = 1.1628;

/// Factor on the rigorous band 2·max diag(S)·‖r‖∞: the CG's residual is updated by
/// recurrence with single-precision responses, so the true residual can differ from it by
/// rounding; a factor 2 keeps the certificate safe against that at the cost of about one
/// CG iteration.
pub const CERTIFICATE_SAFETY: f64 = 2.0;

/// Bound on |p_i − p*_i| over the set for the residual `residual` (zero outside the set):
/// `CERTIFICATE_SAFETY`·2·`LATTICE_INVERSE_DIAGONAL`·(E*/Δ)·‖r‖∞.
pub fn pressure_error_bound(residual: &[f64], contact_modulus: f64, element_size: f64) -> f64 {
    pressure_error_bound_of(largest_magnitude(residual), contact_modulus, element_size)
}

/// [`pressure_error_bound`] of a residual whose ‖r‖∞ is `largest` (known from the pass
/// that updated it).
pub fn pressure_error_bound_of(largest: f64, contact_modulus: f64, element_size: f64) -> f64 {
    CERTIFICATE_SAFETY * 2.0 * LATTICE_INVERSE_DIAGONAL * contact_modulus / element_size * largest
}

/// max |r| (0 for an empty field), on the pool: a maximum is exact in any order.
pub(crate) fn largest_magnitude(residual: &[f64]) -> f64 {
    residual
        .par_chunks(super::PARALLEL_CHUNK)
        .map(|chunk| chunk.iter().fold(0.0f64, |m, r| m.max(r.abs())))
        .reduce(|| 0.0, f64::max)
}

/// The attachment decisions of an iterate (which free elements penetrate) are certain
/// when no free element with a surface has |g| within `band` of 0. The displacement error
/// of a free element i is K_iC·S_C·r: K_iC·S_C is non-negative with row sums below 1 (the
/// M-matrix structure of S_{C∪i}, docs/fast-step.md), so |δu_i| ≤ ‖r‖∞ = the band before
/// the safety factor.
/// Every element is visited (far gaps are large but must be looked at), in parallel.
pub fn attachments_certain(heights: &[f64], depth: f64, displacement: &[f64], contact: &[bool], band: f64) -> bool {
    let chunk = super::PARALLEL_CHUNK;
    heights
        .par_chunks(chunk)
        .zip(displacement.par_chunks(chunk))
        .zip(contact.par_chunks(chunk))
        .all(|((heights, displacement), contact)| {
            (0..heights.len())
                .all(|k| contact[k] || !heights[k].is_finite() || (heights[k] - depth + displacement[k]).abs() > band)
        })
}

/// Bound on |u_i − u*_i| over the free elements: `CERTIFICATE_SAFETY`·‖r‖∞.
pub fn gap_error_bound(residual: &[f64]) -> f64 {
    gap_error_bound_of(largest_magnitude(residual))
}

/// [`gap_error_bound`] of a residual whose ‖r‖∞ is `largest`.
pub fn gap_error_bound_of(largest: f64) -> f64 {
    CERTIFICATE_SAFETY * largest
}

/// The release decision an iterate certifies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Releases {
    /// At least one certain violator, no tie.
    Some,
    /// Certainly no violator.
    None,
    /// Some element lies within the band.
    Uncertain,
}

/// How many elements of the set are certain violators (−p − σ_c > `band`) and how many lie
/// within the band (|−p − σ_c| ≤ `band`). On the pool: counts do not depend on order.
pub fn count_releases(pressure: &[f64], contact: &[bool], critical_stress: &[f64], band: f64) -> (usize, usize) {
    let chunk = super::PARALLEL_CHUNK;
    pressure
        .par_chunks(chunk)
        .zip(contact.par_chunks(chunk))
        .zip(critical_stress.par_chunks(chunk))
        .map(|((pressure, contact), critical_stress)| {
            let (mut certain, mut uncertain) = (0, 0);
            for k in 0..pressure.len() {
                if contact[k] {
                    let excess = -pressure[k] - critical_stress[k];
                    if excess.abs() <= band {
                        uncertain += 1;
                    } else if excess > 0.0 {
                        certain += 1;
                    }
                }
            }
            (certain, uncertain)
        })
        .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1))
}

/// Classifies the release decisions of an iterate for the pressure error bound `band`:
/// [`count_releases`] read as "some element within the band", else "some certain violator".
pub fn classify_releases(pressure: &[f64], contact: &[bool], critical_stress: &[f64], band: f64) -> Releases {
    match count_releases(pressure, contact, critical_stress, band) {
        (_, uncertain) if uncertain > 0 => Releases::Uncertain,
        (certain, _) if certain > 0 => Releases::Some,
        _ => Releases::None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::elastic::influence::love_coefficient;

    /// Dense Love matrix of an n×n grid (Δ = 1, E* = 1), row-major elements.
    fn love_matrix(n: usize) -> Vec<Vec<f64>> {
        let len = n * n;
        (0..len)
            .map(|i| {
                (0..len)
                    .map(|j| {
                        let dx = (i % n) as f64 - (j % n) as f64;
                        let dy = (i / n) as f64 - (j / n) as f64;
                        love_coefficient(dx, dy, 1.0, 1.0)
                    })
                    .collect()
            })
            .collect()
    }

    /// Gauss–Jordan inverse with partial pivoting (small dense SPD matrices only).
    fn inverse(mut a: Vec<Vec<f64>>) -> Vec<Vec<f64>> {
        let n = a.len();
        let mut inv: Vec<Vec<f64>> = (0..n)
            .map(|i| (0..n).map(|j| (i == j) as u8 as f64).collect())
            .collect();
        for col in 0..n {
            let pivot = (col..n)
                .max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs()))
                .unwrap();
            a.swap(col, pivot);
            inv.swap(col, pivot);
            let scale = 1.0 / a[col][col];
            for j in 0..n {
                a[col][j] *= scale;
                inv[col][j] *= scale;
            }
            for row in 0..n {
                if row != col {
                    let factor = a[row][col];
                    if factor != 0.0 {
                        for j in 0..n {
                            a[row][j] -= factor * a[col][j];
                            inv[row][j] -= factor * inv[col][j];
                        }
                    }
                }
            }
        }
        inv
    }

    /// Checks the M-matrix signs of the inverse of `matrix` restricted to `subset`: every
    /// off-diagonal entry < 0, every row sum > 0, every diagonal below the lattice bound.
    fn check_inverse_m_matrix(matrix: &[Vec<f64>], subset: &[usize], label: &str) {
        let sub: Vec<Vec<f64>> = subset
            .iter()
            .map(|&i| subset.iter().map(|&j| matrix[i][j]).collect())
            .collect();
        let s = inverse(sub);
        for (i, row) in s.iter().enumerate() {
            let sum: f64 = row.iter().sum();
            assert!(sum > 0.0, "{label}: row {i} sums to {sum:e}");
            assert!(
                row[i] > 0.0 && row[i] < LATTICE_INVERSE_DIAGONAL,
                "{label}: diagonal {i} = {}",
                row[i]
            );
            for (j, &v) in row.iter().enumerate() {
                assert!(i == j || v < 0.0, "{label}: S[{i}][{j}] = {v:e} is not negative");
            }
        }
    }

    /// docs/physics.md §2.4a: K⁻¹ of the discrete Love operator is an M-matrix (negative
    /// off-diagonal, positive row sums), on full grids and on random principal subsets (the
    /// contact sets of a solve), with diagonal below the lattice value used by the
    /// certificate. Exact property checked in double precision: any sign failure is real.
    #[test]
    fn lattice_inverse_is_an_m_matrix() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut random = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for n in [8usize, 16, 32] {
            let matrix = love_matrix(n);
            let all: Vec<usize> = (0..n * n).collect();
            check_inverse_m_matrix(&matrix, &all, &format!("full {n}²"));
            for trial in 0..3 {
                let keep = [2u64, 4, 8][trial];
                let subset: Vec<usize> = all.iter().cloned().filter(|_| random() % keep != 0).collect();
                check_inverse_m_matrix(
                    &matrix,
                    &subset,
                    &format!("{n}², subset {trial} ({} elements)", subset.len()),
                );
            }
        }
        // The diagonal approaches the lattice value from below as the grid grows.
        let full = inverse(love_matrix(16));
        let centre = 8 * 16 + 8;
        assert!(full[centre][centre] > 1.15 && full[centre][centre] < LATTICE_INVERSE_DIAGONAL);
    }

    /// The bound holds for an actual solve: for a random set, a residual r and e = S_C r,
    /// ‖e‖∞ ≤ 2·max diag·‖r‖∞.
    #[test]
    fn pressure_error_bound_covers_the_error() {
        let n = 12;
        let matrix = love_matrix(n);
        let subset: Vec<usize> = (0..n * n).filter(|k| (k * 7919) % 5 != 0).collect();
        let sub: Vec<Vec<f64>> = subset
            .iter()
            .map(|&i| subset.iter().map(|&j| matrix[i][j]).collect())
            .collect();
        let s = inverse(sub);
        // The worst residual for row i is r_j = sign(S_ij) (unit ∞-norm).
        let mut residual = vec![0.0; n * n];
        residual[subset[0]] = 1.0;
        let bound = pressure_error_bound(&residual, 1.0, 1.0);
        for row in &s {
            let worst: f64 = row.iter().map(|v| v.abs()).sum();
            assert!(worst <= bound / CERTIFICATE_SAFETY, "{worst} > {bound}");
        }
    }

    #[test]
    fn decisions_are_certain_outside_the_band() {
        let sigma = [1.0, 1.0, 1.0];
        let contact = [true, true, false];
        let classify = |p: [f64; 3]| classify_releases(&p, &contact, &sigma, 0.1);
        assert_eq!(classify([-1.5, 0.2, -9.0]), Releases::Some);
        assert_eq!(classify([-1.05, 0.2, -9.0]), Releases::Uncertain, "tie at σ_c");
        assert_eq!(classify([-0.5, 0.2, -9.0]), Releases::None, "no violator");
        let heights = [0.0, 0.0, 1.0];
        assert!(attachments_certain(&heights, 0.5, &[0.0, 0.0, 0.0], &contact, 0.1));
        assert!(
            !attachments_certain(&heights, 0.95, &[0.0, 0.0, 0.0], &contact, 0.1),
            "gap 0.05 < band"
        );
    }

    #[test]
    fn releases_are_counted_by_certainty() {
        // σ_c = 1 (2 on the last element), band 1/8; every value is exact in binary so the
        // band's edge is met exactly. Tension −p against σ_c: 1.5 and 1.25 certain,
        // 1.0625 and 0.9375 within the band (ties either way), 0.5 and compression safe, a
        // free element at any tension ignored, and 2.125 against σ_c = 2 on the band's
        // edge, a tie (|excess| ≤ band). The pattern is repeated past one of the pool's
        // chunks, so the counts are summed across chunks.
        let band = 0.125;
        let pattern = [-1.5, -1.25, -1.0625, -0.9375, -0.5, 0.3, -9.0, -2.125];
        let contact_pattern = [true, true, true, true, true, true, false, true];
        let sigma_pattern = [1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 2.0];
        let copies = super::super::PARALLEL_CHUNK / pattern.len() + 3;
        let pressure: Vec<f64> = pattern.iter().copied().cycle().take(copies * pattern.len()).collect();
        let contact: Vec<bool> = contact_pattern.iter().copied().cycle().take(pressure.len()).collect();
        let sigma: Vec<f64> = sigma_pattern.iter().copied().cycle().take(pressure.len()).collect();
        assert_eq!(
            count_releases(&pressure, &contact, &sigma, band),
            (2 * copies, 3 * copies)
        );
        assert_eq!(
            count_releases(&pressure, &contact, &sigma, 0.0),
            (4 * copies, 0),
            "no band"
        );
        assert_eq!(
            classify_releases(&pressure, &contact, &sigma, band),
            Releases::Uncertain
        );
        assert_eq!(classify_releases(&pressure, &contact, &sigma, 0.0), Releases::Some);
    }
}
