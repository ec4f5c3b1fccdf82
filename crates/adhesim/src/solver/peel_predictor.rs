//! Local replay of a trial ring's peel, to predict which members hold (docs/fast-step.md
//! §3, predicted-subset growth).
//!
//! Releasing a contact element v of tension t_v changes the pressures of the others so that
//! their displacements stay put. The predictor solves that on a window A: the contact
//! elements within `RADIUS` of v that lie within `BAND` of a free element (the edge strip,
//! where the tension goes), with every other contact element holding its pressure. That is
//! the dense system K_AA δt_A = K_Av t_v with the exact Love kernel (Δ = E* = 1: only ratios
//! enter). It is a prediction, not a bound: the solver verifies every predicted subset with
//! a solve, so the window's size and shape decide the work, never the result.

use super::dot;
use crate::elastic::influence::love_coefficient;

/// Contact elements within this distance (in elements) of a released one respond to it.
/// The tension of a peeling front is shed far along the front: 8, 12 and 16 give 113, 101
/// and 91 FFT pairs per approach step on the Fig. 1 case at n = 128 (132.8 without
/// prediction), at a dense-solve cost growing as the cube of the strip's length. 16 cuts
/// the FFT pairs further (N = 512, Fig. 1: 252.2 → 223.0 per step, the same contact sets)
/// but not the time: the longer one-thread replays eat the saved transforms (n = 256, the
/// 512² rule: 1.16× the CPU, 1.27× the wall; BENCHMARKS.md §0, 2026-11-26), so 12 stays.
const RADIUS: i64 = 12;
/// ... and within this distance (Chebyshev) of a free element: the edge strip.
const BAND: i64 = 2;
/// At most this many, the nearest first: on a contact broken into many small patches
/// (Fig. 2 at h = 0.006) every element is near a free one, and the dense solve would grow
/// to the whole disk (≈ 450 unknowns).
const MAX_WINDOW: usize = 100;
/// Largest offset between two window elements.
const SPAN: i64 = 2 * RADIUS;

/// Scratch of the predictor, allocated once per solver.
pub(crate) struct PeelPredictor {
    /// Love's coefficient K(a, b) for |a|, |b| ≤ `SPAN`.
    kernel: Vec<f64>,
    /// Offsets (a, b) ≠ 0 with a² + b² ≤ `RADIUS`², nearest first.
    disk: Vec<(i64, i64)>,
    /// Per element: 0 not yet known, 1 within `BAND` of a free element, 2 not.
    near_free: Vec<u8>,
    /// Elements whose `near_free` entry is set (reset by [`finish`](Self::finish)).
    touched: Vec<usize>,
    /// The window: (row, column) of its elements.
    window: Vec<(i64, i64)>,
    matrix: Vec<f64>,
    /// Tension rise per unit tension released, per window element.
    rises: Vec<f64>,
}

impl PeelPredictor {
    pub(crate) fn new(len: usize) -> Self {
        let side = 2 * SPAN + 1;
        let kernel = (0..side * side)
            .map(|k| love_coefficient((k / side - SPAN) as f64, (k % side - SPAN) as f64, 1.0, 1.0))
            .collect();
        let mut disk: Vec<(i64, i64)> = (-RADIUS..=RADIUS)
            .flat_map(|a| (-RADIUS..=RADIUS).map(move |b| (a, b)))
            .filter(|&(a, b)| (a, b) != (0, 0) && a * a + b * b <= RADIUS * RADIUS)
            .collect();
        disk.sort_by_key(|&(a, b)| a * a + b * b);
        Self {
            kernel,
            disk,
            near_free: vec![0; len],
            touched: Vec::new(),
            window: Vec::new(),
            matrix: Vec::new(),
            rises: Vec::new(),
        }
    }

    fn kernel(&self, a: i64, b: i64) -> f64 {
        let side = 2 * SPAN + 1;
        self.kernel[((a + SPAN) * side + b + SPAN) as usize]
    }

    /// Whether contact element (row, column) lies within `BAND` of a free element (cached).
    fn in_strip(&mut self, n: usize, row: i64, column: i64, contact: &impl Fn(usize) -> bool) -> bool {
        let k = row as usize * n + column as usize;
        if self.near_free[k] == 0 {
            let mut near = false;
            'search: for a in -BAND..=BAND {
                for b in -BAND..=BAND {
                    let (r, c) = (row + a, column + b);
                    let inside = r >= 0 && c >= 0 && (r as usize) < n && (c as usize) < n;
                    if inside && !contact(r as usize * n + c as usize) {
                        near = true;
                        break 'search;
                    }
                }
            }
            self.near_free[k] = if near { 1 } else { 2 };
            self.touched.push(k);
        }
        self.near_free[k] == 1
    }

    /// Releases the element at `centre` (row, column) of an n×n grid from the contact given
    /// by `contact(k)` (which must already exclude it): afterwards [`window`](Self::window)
    /// holds the strip's contact elements within `RADIUS` (at most `MAX_WINDOW`, the nearest)
    /// and their tension rises per unit tension released.
    pub(crate) fn release(&mut self, n: usize, centre: (i64, i64), contact: impl Fn(usize) -> bool) {
        // The released element is free now: its strip neighbours are near a free element.
        for a in -BAND..=BAND {
            for b in -BAND..=BAND {
                let (r, c) = (centre.0 + a, centre.1 + b);
                if r >= 0 && c >= 0 && (r as usize) < n && (c as usize) < n {
                    let k = r as usize * n + c as usize;
                    if self.near_free[k] == 0 {
                        self.touched.push(k);
                    }
                    self.near_free[k] = 1;
                }
            }
        }
        self.window.clear();
        for index in 0..self.disk.len() {
            let (row, column) = (centre.0 + self.disk[index].0, centre.1 + self.disk[index].1);
            let inside = row >= 0 && column >= 0 && (row as usize) < n && (column as usize) < n;
            if inside && contact(row as usize * n + column as usize) && self.in_strip(n, row, column, &contact) {
                self.window.push((row, column));
                if self.window.len() == MAX_WINDOW {
                    break;
                }
            }
        }
        let size = self.window.len();
        self.matrix.clear();
        self.rises.clear();
        self.matrix.resize(size * size, 0.0);
        for (i, &(ri, ci)) in self.window.iter().enumerate() {
            // Lower triangle only: the factorisation reads nothing else.
            for (j, &(rj, cj)) in self.window[..=i].iter().enumerate() {
                self.matrix[i * size + j] = self.kernel(ri - rj, ci - cj);
            }
            self.rises.push(self.kernel(ri - centre.0, ci - centre.1));
        }
        if size > 0 {
            factorise(&mut self.matrix, size);
            substitute(&self.matrix, size, &mut self.rises);
        }
    }

    /// The window of the last release: (row, column) and tension rise per unit released.
    pub(crate) fn window(&self) -> impl Iterator<Item = ((i64, i64), f64)> + '_ {
        self.window.iter().cloned().zip(self.rises.iter().cloned())
    }

    /// Ends a replay: forgets the cached strip (the contact changes before the next one).
    pub(crate) fn finish(&mut self) {
        for &k in &self.touched {
            self.near_free[k] = 0;
        }
        self.touched.clear();
    }
}

/// Cholesky factor L (lower triangle, row-major, in place) of the SPD size×size `a`, whose
/// lower triangle is read. Rows are contiguous, so every inner product is a slice `dot`.
fn factorise(a: &mut [f64], size: usize) {
    for j in 0..size {
        let (row_j, below) = a[j * size..].split_at_mut(size);
        let diagonal = (row_j[j] - dot(&row_j[..j], &row_j[..j])).sqrt();
        row_j[j] = diagonal;
        for row_i in below.chunks_exact_mut(size) {
            row_i[j] = (row_i[j] - dot(&row_i[..j], &row_j[..j])) / diagonal;
        }
    }
}

/// Solves L Lᵀ x = b for the factor of [`factorise`]; `x` holds b on entry.
fn substitute(factor: &[f64], size: usize, x: &mut [f64]) {
    for i in 0..size {
        let row = &factor[i * size..i * size + i];
        x[i] = (x[i] - dot(row, &x[..i])) / factor[i * size + i];
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

    /// The window solve is exact on its window (K_AA δt_A = K_Av to rounding), the window
    /// is the strip along the free region, and the nearest contact neighbour of the
    /// released element takes up tension (F1, docs/physics.md §2.4a).
    #[test]
    fn window_solve_restores_the_displacements() {
        let mut predictor = PeelPredictor::new(32 * 32);
        let n = 32;
        // Contact: columns < 20; release (16, 19) on its edge.
        predictor.release(n, (16, 19), |k| k % n < 20 && k != 16 * n + 19);
        let window: Vec<((i64, i64), f64)> = predictor.window().collect();
        assert!(!window.is_empty());
        assert!(window.iter().all(|&((_, c), _)| (17..20).contains(&c)), "{window:?}");
        for &((ri, ci), _) in &window {
            let applied: f64 = window
                .iter()
                .map(|&((rj, cj), rise)| predictor.kernel(ri - rj, ci - cj) * rise)
                .sum();
            let target = predictor.kernel(ri - 16, ci - 19);
            assert!((applied - target).abs() < 1e-12, "{applied} vs {target}");
        }
        let neighbour = window.iter().find(|w| w.0 == (15, 19)).unwrap().1;
        assert!(neighbour > 0.0, "{neighbour}");
        predictor.finish();
        assert!(predictor.near_free.iter().all(|&v| v == 0));
    }
}
