//! Certified local release rounds (docs/fast-step.md, "Local rounds").
//!
//! Releasing an element v of tension t_v from a contact set raises every remaining tension
//! (docs/physics.md §2.4a, F1). Clamping more elements only lowers those rises, so the
//! rises on the infinite lattice with every element clamped except v and the free elements
//! near v (the window G) are rigorous lower bounds: Δt_k = −t_v Σ_g Ŝ(k − g) y_g with
//! Ŝ_GG y = e_v, Ŝ the lattice inverse of the discrete Love operator (scale free: only
//! ratios of Ŝ enter, so Δ = E* = 1 here).

use super::dense::{cholesky_factorise, cholesky_solve, Summation};
use super::shape_cache::ShapeCache;
use crate::elastic::influence::love_coefficient;
use crate::elastic::planner;
use num_complex::Complex;

/// Free elements within this distance (in elements) of a released one are free in the bound.
pub(crate) const WINDOW: i64 = 4;
/// Rises are bounded for contact elements within this distance of the released one (farther
/// ones get no rise: still a lower bound).
pub(crate) const REACH: i64 = 8;
/// Largest offset looked up in the table.
const TABLE: i64 = WINDOW + REACH;
/// Periodic box on which the lattice inverse is evaluated: its diagonal agrees with the
/// 2048² box to 7e-8 relative.
const BOX: usize = 256;
/// Factor below 1 on every bounded rise: covers the box's deviation from the infinite
/// lattice and rounding in the small dense solves.
const SAFETY: f64 = 0.999;

/// Entries Ŝ(a, b) of the lattice inverse for |a|, |b| ≤ `TABLE` (units E*/Δ).
pub(crate) struct LatticeInverse {
    table: Vec<f64>,
}

impl LatticeInverse {
    pub(crate) fn new() -> Self {
        let m = BOX;
        let wrap = |i: usize| if i < m / 2 { i as f64 } else { i as f64 - m as f64 };
        let mut data: Vec<Complex<f64>> = (0..m * m)
            .map(|k| Complex::new(love_coefficient(wrap(k / m), wrap(k % m), 1.0, 1.0), 0.0))
            .collect();
        transform_2d(&mut data, m, &*planner::complex_forward::<f64>(m));
        // The kernel is even, so its transform is real and (checked in the tests) positive.
        for value in data.iter_mut() {
            *value = Complex::new(1.0 / value.re, 0.0);
        }
        transform_2d(&mut data, m, &*planner::complex_inverse::<f64>(m));
        let side = (2 * TABLE + 1) as usize;
        let scale = 1.0 / (m * m) as f64;
        let index = |a: i64| a.rem_euclid(m as i64) as usize;
        let table = (0..side * side)
            .map(|k| {
                let (a, b) = ((k / side) as i64 - TABLE, (k % side) as i64 - TABLE);
                data[index(a) * m + index(b)].re * scale
            })
            .collect();
        Self { table }
    }

    /// Ŝ at offset (a, b) in elements; |a|, |b| ≤ `TABLE`.
    pub(crate) fn at(&self, a: i64, b: i64) -> f64 {
        let side = 2 * TABLE + 1;
        self.table[((a + TABLE) * side + b + TABLE) as usize]
    }
}

/// In-place 2-D FFT of an m×m row-major array.
fn transform_2d(data: &mut [Complex<f64>], m: usize, fft: &dyn rustfft::Fft<f64>) {
    for row in data.chunks_exact_mut(m) {
        fft.process(row);
    }
    let mut column = vec![Complex::new(0.0, 0.0); m];
    for j in 0..m {
        for i in 0..m {
            column[i] = data[i * m + j];
        }
        fft.process(&mut column);
        for i in 0..m {
            data[i * m + j] = column[i];
        }
    }
}

/// Scratch of the local rounds, allocated once per solver.
pub(crate) struct LocalPeel {
    pub(crate) inverse: LatticeInverse,
    /// Lower bound on the tension −p of each trial element.
    pub(crate) lower: Vec<f64>,
    /// Whether an element is queued for release.
    pub(crate) queued: Vec<bool>,
    /// Elements to release, in order.
    pub(crate) queue: Vec<usize>,
    /// (element, rise) at the contact elements within `REACH` of the last released
    /// element, row-major ([`Self::contact_rises`]).
    pub(crate) rises: Vec<(usize, f64)>,
    window: Vec<(i64, i64)>,
    matrix: Vec<f64>,
    solution: Vec<f64>,
    /// Window solutions by shape: the solution depends only on the window's offsets from
    /// its centre, so a shape solved before gives the same bits.
    solved: ShapeCache,
}

impl LocalPeel {
    pub(crate) fn new(len: usize) -> Self {
        Self {
            inverse: LatticeInverse::new(),
            lower: vec![0.0; len],
            queued: vec![false; len],
            queue: Vec::new(),
            rises: Vec::new(),
            window: Vec::new(),
            matrix: Vec::new(),
            solution: Vec::new(),
            solved: ShapeCache::default(),
        }
    }

    /// Sets up the window around the released element at `centre` (row, column) of an n×n
    /// grid: the element itself first, then every free element within `WINDOW`; solves
    /// Ŝ_GG y = e_first. `free(k)` tells whether element k is out of contact.
    pub(crate) fn prepare(&mut self, n: usize, centre: (i64, i64), free: impl Fn(usize) -> bool) {
        self.window.clear();
        self.window.push(centre);
        for a in -WINDOW..=WINDOW {
            for b in -WINDOW..=WINDOW {
                let (row, column) = (centre.0 + a, centre.1 + b);
                if (a, b) == (0, 0) || a * a + b * b > WINDOW * WINDOW {
                    continue;
                }
                let inside = row >= 0 && column >= 0 && (row as usize) < n && (column as usize) < n;
                if inside && free(row as usize * n + column as usize) {
                    self.window.push((row, column));
                }
            }
        }
        if let Some(stored) = self.solved.look_up(&self.window, centre) {
            self.solution.clear();
            self.solution.extend_from_slice(stored);
            return;
        }
        let size = self.window.len();
        self.matrix.clear();
        for &(ri, ci) in &self.window {
            for &(rj, cj) in &self.window {
                self.matrix.push(self.inverse.at(ri - rj, ci - cj));
            }
        }
        self.solution.clear();
        self.solution.resize(size, 0.0);
        // Ŝ_GG is a principal block of the SPD lattice inverse; should rounding make it
        // indefinite, the solution stays 0, whose rises (none) are still lower bounds.
        if cholesky_factorise(&mut self.matrix, size, Summation::InOrder).is_ok() {
            self.solution[0] = 1.0;
            cholesky_solve(&self.matrix, size, &mut self.solution, Summation::InOrder);
        }
        self.solved.store(&self.solution);
    }

    /// Prepares the window of the element released at `centre` (row, column) of an n×n
    /// grid and lists in [`Self::rises`] the rise at every element within ±`REACH` that
    /// `in_contact(k)`, row by row: what a release spreads over the contact near it.
    ///
    /// A row's rises are summed together, the window's elements outermost: each rise is the
    /// sum of `rise` (the single-element form, kept for the tests) in the same order from
    /// the same start, so the same bits, while the table's entries for one row of elements
    /// lie side by side and the products vectorise.
    pub(crate) fn contact_rises(&mut self, n: usize, centre: (i64, i64), in_contact: impl Fn(usize) -> bool) {
        const SPAN: usize = (2 * REACH + 1) as usize;
        self.prepare(n, centre, |k| !in_contact(k));
        self.rises.clear();
        // The start of `Iterator::sum` for f64, as `rise` sums.
        let start: f64 = std::iter::empty::<f64>().sum();
        let side = 2 * TABLE + 1;
        for a in -REACH..=REACH {
            let row = centre.0 + a;
            if row < 0 || row as usize >= n {
                continue;
            }
            let mut contact = [None; SPAN];
            for (b, slot) in (-REACH..=REACH).zip(contact.iter_mut()) {
                let column = centre.1 + b;
                if column >= 0 && (column as usize) < n {
                    let k = row as usize * n + column as usize;
                    *slot = in_contact(k).then_some(k);
                }
            }
            if contact.iter().all(Option::is_none) {
                continue;
            }
            let mut sums = [start; SPAN];
            for (&(r, c), &y) in self.window.iter().zip(&self.solution) {
                // Offsets (row − r, centre.1 + b − c) for b = −REACH..=REACH: |row − r| and
                // |centre.1 + b − c| ≤ REACH + WINDOW = TABLE, inside the table.
                let first = ((row - r + TABLE) * side + centre.1 - REACH - c + TABLE) as usize;
                for (sum, &entry) in sums.iter_mut().zip(&self.inverse.table[first..first + SPAN]) {
                    *sum += entry * y;
                }
            }
            for (slot, sum) in contact.iter().zip(sums) {
                if let Some(k) = *slot {
                    self.rises.push((k, (-sum * SAFETY).max(0.0)));
                }
            }
        }
    }

    /// Lower bound on the tension rise at `element` (row, column) per unit of tension
    /// released at the window's centre (≥ 0).
    #[cfg(test)]
    pub(crate) fn rise(&self, element: (i64, i64)) -> f64 {
        let sum: f64 = self
            .window
            .iter()
            .zip(&self.solution)
            .map(|(&(r, c), y)| self.inverse.at(element.0 - r, element.1 - c) * y)
            .sum();
        (-sum * SAFETY).max(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solver::LATTICE_INVERSE_DIAGONAL;

    /// The tabulated lattice inverse has the M-matrix signs and the diagonal the
    /// certificate's bound rests on (1.162 781, docs/fast-step.md).
    #[test]
    fn lattice_inverse_table_has_m_matrix_signs() {
        let inverse = LatticeInverse::new();
        let diagonal = inverse.at(0, 0);
        assert!(
            (diagonal - 1.162_781).abs() < 1e-5 && diagonal < LATTICE_INVERSE_DIAGONAL,
            "{diagonal}"
        );
        for a in -TABLE..=TABLE {
            for b in -TABLE..=TABLE {
                assert!(
                    (a, b) == (0, 0) || inverse.at(a, b) < 0.0,
                    "Ŝ({a},{b}) = {}",
                    inverse.at(a, b)
                );
            }
        }
    }

    /// Releasing one element with all else clamped (an empty window) raises the tension
    /// of its neighbour by −Ŝ(0,1)/Ŝ(0,0) per unit released, less than with free elements
    /// around it (the free ones carry nothing, so the clamped rest carries more).
    #[test]
    fn rise_grows_when_more_elements_are_free() {
        let mut peel = LocalPeel::new(64 * 64);
        peel.prepare(64, (32, 32), |_| false);
        let clamped = peel.rise((32, 33));
        let expected = -peel.inverse.at(0, 1) / peel.inverse.at(0, 0) * SAFETY;
        assert!((clamped - expected).abs() < 1e-12, "{clamped} vs {expected}");
        peel.prepare(64, (32, 32), |k| k % 64 < 32);
        let half_free = peel.rise((32, 33));
        assert!(half_free > clamped, "{half_free} ≤ {clamped}");
    }

    /// A window of a shape met before takes the stored solution: the bits of a fresh solve.
    #[test]
    fn a_window_shape_met_before_gives_the_fresh_solution() {
        let n = 48usize;
        // Free: a half-plane to the left of each centre, cut by a slanted line.
        let free_about = |centre: (i64, i64)| {
            move |k: usize| {
                let (row, column) = ((k / n) as i64 - centre.0, (k % n) as i64 - centre.1);
                column < 0 && row + 2 * column < 3
            }
        };
        let (first, second) = ((20i64, 20i64), (30i64, 12i64));
        let mut cached = LocalPeel::new(n * n);
        cached.prepare(n, first, free_about(first));
        cached.prepare(n, second, free_about(second));
        assert_eq!(cached.solved.len(), 1, "the second window was not a hit");
        assert!(cached.window.len() > 10, "window of {} elements", cached.window.len());
        let mut fresh = LocalPeel::new(n * n);
        fresh.prepare(n, second, free_about(second));
        let bits = |values: &[f64]| values.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&cached.solution), bits(&fresh.solution));
    }

    /// `contact_rises` sums a row of rises at once; each must be the single-element `rise`
    /// to the bit, on a contact with holes and cut by the grid's edge.
    #[test]
    fn row_sums_are_the_single_element_rises_to_the_bit() {
        let n = 40usize;
        let in_contact = |k: usize| {
            let (row, column) = ((k / n) as i64, (k % n) as i64);
            (row - 20).pow(2) + (column - 3).pow(2) <= 144 && (row * 7 + column * 3) % 11 != 0
        };
        for centre in [(20i64, 3i64), (14, 9), (25, 0), (9, 6)] {
            let mut peel = LocalPeel::new(n * n);
            peel.contact_rises(n, centre, in_contact);
            assert!(peel.rises.len() > 20, "{} rises at {centre:?}", peel.rises.len());
            for &(k, rise) in &peel.rises {
                let single = peel.rise(((k / n) as i64, (k % n) as i64));
                assert_eq!(
                    rise.to_bits(),
                    single.to_bits(),
                    "element {k} at {centre:?}: {rise:e} vs {single:e}"
                );
            }
        }
    }

    /// The rises a release spreads (`contact_rises`, the warm start and the local rounds'
    /// bounds) against the exact ones of a dense solve on a finite contact: releasing v
    /// from C changes every other pressure by −(S_iv/S_vv)·p_v, S = K_CC⁻¹ (Schur
    /// complement), so the exact tension rise per unit released is −S_iv/S_vv. The bound
    /// clamps everything but v's free neighbours on the infinite lattice, more than C's
    /// complement is clamped, so each rise must lie in [0, exact] (to rounding: 1e-12).
    /// Next to v it must also be most of the exact rise, or the warm start would be idle.
    #[test]
    fn contact_rises_are_lower_bounds_of_the_exact_rises() {
        let n = 24usize;
        let centre = (12i64, 12i64);
        let in_disc = |k: usize| {
            let (row, column) = ((k / n) as i64, (k % n) as i64);
            (row - centre.0).pow(2) + (column - centre.1).pow(2) <= 49
        };
        let set: Vec<usize> = (0..n * n).filter(|&k| in_disc(k)).collect();
        let released = (12i64, 19i64);
        let v = released.0 as usize * n + released.1 as usize;
        let position = set.iter().position(|&k| k == v).expect("v is in C");
        // K_CC from Love's coefficients (Δ = E* = 1: only ratios enter), then S e_v.
        let size = set.len();
        let mut matrix = Vec::with_capacity(size * size);
        for &i in &set {
            for &j in &set {
                let offset = |k: usize| ((k / n) as f64, (k % n) as f64);
                let ((ri, ci), (rj, cj)) = (offset(i), offset(j));
                matrix.push(love_coefficient(ci - cj, ri - rj, 1.0, 1.0));
            }
        }
        cholesky_factorise(&mut matrix, size, Summation::InOrder).unwrap();
        let mut column = vec![0.0; size];
        column[position] = 1.0;
        cholesky_solve(&matrix, size, &mut column, Summation::InOrder);
        let exact = |k: usize| -column[set.iter().position(|&j| j == k).unwrap()] / column[position];

        let mut peel = LocalPeel::new(n * n);
        peel.contact_rises(n, released, |k| in_disc(k) && k != v);
        assert!(!peel.rises.is_empty());
        for &(k, rise) in &peel.rises {
            let exact = exact(k);
            assert!(
                rise >= 0.0 && rise <= exact + 1e-12,
                "element {k}: bound {rise:e} > exact {exact:e}"
            );
        }
        // The nearest neighbours (distance ≤ √2) carry most of the load: measured 0.96–0.98
        // of the exact rise here (the rest is the far free complement the window clamps,
        // and SAFETY); 0.9 leaves room for rounding, not for a broken window.
        let mut near = 0;
        for &(k, rise) in &peel.rises {
            let distance2 = ((k / n) as i64 - released.0).pow(2) + ((k % n) as i64 - released.1).pow(2);
            if distance2 <= 2 {
                near += 1;
                assert!(
                    rise >= 0.9 * exact(k),
                    "element {k}: bound {rise:e}, exact {:e}",
                    exact(k)
                );
            }
        }
        assert_eq!(near, 3, "v − 1 and its two diagonal neighbours inside the disc");
    }
}
