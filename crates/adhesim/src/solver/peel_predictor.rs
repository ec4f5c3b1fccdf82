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

use super::dense::{cholesky_factorise, cholesky_solve, Summation};
use super::shape_cache::{window_shape, Shape, ShapeCache};
use crate::elastic::influence::love_coefficient;
use rayon::prelude::*;

/// Contact elements within this distance (in elements) of a released one respond to it.
/// The tension of a peeling front is shed far along the front: 8, 12 and 16 give 113, 101
/// and 91 FFT pairs per approach step on the Fig. 1 case at n = 128 (132.8 without
/// prediction), at a dense-solve cost growing as the cube of the strip's length. 16 cuts
/// the FFT pairs further (N = 512, Fig. 1: 252.2 → 223.0 per step, the same contact sets)
/// but not the time: the longer one-thread replays eat the saved transforms (n = 256, the
/// 512² rule: 1.16× the CPU, 1.27× the wall; BENCHMARKS.md §What did not pay, replay
/// radius 16), so 12 stays.
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
    /// The window of the last [`release`](Self::release) and its rises.
    last: Released,
    matrix: Vec<f64>,
    /// Windows of a planned batch of releases ([`plan_batch`](Self::plan_batch)), in order.
    planned: Vec<Released>,
    /// Per element: its place in the planned batch plus one, 0 if not in it.
    batch_rank: Vec<u32>,
    /// One dense matrix and one shape key per thread for the planned windows.
    matrices: Vec<(Vec<f64>, Shape)>,
    /// Rises already solved, by window shape about the released element.
    solved: ShapeCache,
}

/// The window of one release, (row, column) of its elements, and their tension rises per
/// unit tension released.
#[derive(Default)]
struct Released {
    window: Vec<(i64, i64)>,
    rises: Vec<f64>,
    /// Solved here rather than found in the cache (a planned window, to be stored).
    solved: bool,
}

/// Batches shorter than this are replayed one release at a time (the same bits either way).
const PLAN_MIN_BATCH: usize = 8;

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
            last: Released::default(),
            matrix: Vec::new(),
            planned: Vec::new(),
            batch_rank: vec![0; len],
            matrices: vec![(Vec::new(), Vec::new()); rayon::current_num_threads().max(1)],
            solved: ShapeCache::default(),
        }
    }

    #[cfg(test)]
    fn kernel(&self, a: i64, b: i64) -> f64 {
        kernel_at(&self.kernel, a, b)
    }

    /// Releases the element at `centre` (row, column) of an n×n grid from the contact given
    /// by `contact(k)` (which must already exclude it): afterwards [`window`](Self::window)
    /// holds the strip's contact elements within `RADIUS` (at most `MAX_WINDOW`, the nearest)
    /// and their tension rises per unit tension released.
    pub(crate) fn release(&mut self, n: usize, centre: (i64, i64), contact: impl Fn(usize) -> bool) {
        self.mark_released(n, centre);
        let Self {
            kernel,
            disk,
            near_free: cache,
            touched,
            last,
            matrix,
            solved,
            ..
        } = self;
        collect_window(disk, n, centre, &mut last.window, |row, column| {
            let k = row as usize * n + column as usize;
            if !contact(k) {
                return false;
            }
            // In the strip: looked up once per replay (cached; releases mark their own).
            if cache[k] == 0 {
                cache[k] = if near_free(n, row, column, &contact) { 1 } else { 2 };
                touched.push(k);
            }
            cache[k] == 1
        });
        if let Some(stored) = solved.look_up(&last.window, centre) {
            last.rises.clear();
            last.rises.extend_from_slice(stored);
            return;
        }
        solve_rises(kernel, &last.window, centre, matrix, &mut last.rises);
        solved.store(&last.rises);
    }

    /// Computes, on all threads, the windows of releasing `batch` one after the other from
    /// `contact` (the j-th with the first j released), as [`release`](Self::release) would
    /// in that order: a window depends on which elements are in contact, never on the
    /// tensions, and the strip cache that `release` keeps equals a fresh look at the
    /// contact (a release marks its own strip). The same bits, in parallel. Returns whether
    /// the batch was planned (short batches are not: replay them with `release`).
    pub(crate) fn plan_batch(&mut self, n: usize, batch: &[usize], contact: &[bool]) -> bool {
        if batch.len() < PLAN_MIN_BATCH {
            return false;
        }
        for (place, &k) in batch.iter().enumerate() {
            self.batch_rank[k] = place as u32 + 1;
        }
        if self.planned.len() < batch.len() {
            self.planned.resize_with(batch.len(), Released::default);
        }
        let per_thread = batch.len().div_ceil(self.matrices.len());
        let (kernel, disk, rank, stored) = (&self.kernel, &self.disk, &self.batch_rank, &self.solved);
        self.planned[..batch.len()]
            .par_chunks_mut(per_thread)
            .zip(batch.par_chunks(per_thread))
            .zip(self.matrices.par_iter_mut())
            .enumerate()
            .for_each(|(chunk, ((planned, released), (matrix, key)))| {
                for (offset, (slot, &k)) in planned.iter_mut().zip(released).enumerate() {
                    // Released so far: batch[..=place].
                    let place = (chunk * per_thread + offset) as u32 + 1;
                    let in_contact = |e: usize| contact[e] && !(rank[e] != 0 && rank[e] <= place);
                    let centre = ((k / n) as i64, (k % n) as i64);
                    collect_window(disk, n, centre, &mut slot.window, |row, column| {
                        in_contact(row as usize * n + column as usize) && near_free(n, row, column, &in_contact)
                    });
                    window_shape(&slot.window, centre, key);
                    slot.solved = match stored.get(key.as_slice()) {
                        Some(rises) => {
                            slot.rises.clear();
                            slot.rises.extend_from_slice(rises);
                            false
                        }
                        None => {
                            solve_rises(kernel, &slot.window, centre, matrix, &mut slot.rises);
                            true
                        }
                    };
                }
            });
        for (slot, &k) in self.planned[..batch.len()].iter().zip(batch) {
            self.batch_rank[k] = 0;
            if slot.solved {
                self.solved
                    .insert(&slot.window, ((k / n) as i64, (k % n) as i64), &slot.rises);
            }
        }
        true
    }

    /// The released element is free now: its strip neighbours are near a free element
    /// (the cache kept for [`release`](Self::release); also called for each release of a
    /// planned batch, for the releases replayed after it).
    pub(crate) fn mark_released(&mut self, n: usize, centre: (i64, i64)) {
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
    }

    /// A release's window, (row, column) and tension rise per unit released: of the last
    /// [`release`](Self::release) (`planned` None) or of the release at that place of the
    /// planned batch ([`plan_batch`](Self::plan_batch)).
    pub(crate) fn window(&self, planned: Option<usize>) -> impl Iterator<Item = ((i64, i64), f64)> + '_ {
        let released = planned.map_or(&self.last, |place| &self.planned[place]);
        released.window.iter().cloned().zip(released.rises.iter().cloned())
    }

    /// Ends a replay: forgets the cached strip (the contact changes before the next one).
    pub(crate) fn finish(&mut self) {
        for &k in &self.touched {
            self.near_free[k] = 0;
        }
        self.touched.clear();
    }
}

/// The window of a release at `centre`: the offsets of `disk` (nearest first) inside the
/// grid where `keep(row, column)` (in contact, in the strip), at most `MAX_WINDOW`.
fn collect_window(
    disk: &[(i64, i64)],
    n: usize,
    centre: (i64, i64),
    window: &mut Vec<(i64, i64)>,
    mut keep: impl FnMut(i64, i64) -> bool,
) {
    window.clear();
    for &(a, b) in disk {
        let (row, column) = (centre.0 + a, centre.1 + b);
        let inside = row >= 0 && column >= 0 && (row as usize) < n && (column as usize) < n;
        if inside && keep(row, column) {
            window.push((row, column));
            if window.len() == MAX_WINDOW {
                break;
            }
        }
    }
}

fn kernel_at(kernel: &[f64], a: i64, b: i64) -> f64 {
    let side = 2 * SPAN + 1;
    kernel[((a + SPAN) * side + b + SPAN) as usize]
}

/// Whether contact element (row, column) lies within `BAND` (Chebyshev) of a free element.
fn near_free(n: usize, row: i64, column: i64, contact: &impl Fn(usize) -> bool) -> bool {
    for a in -BAND..=BAND {
        for b in -BAND..=BAND {
            let (r, c) = (row + a, column + b);
            let inside = r >= 0 && c >= 0 && (r as usize) < n && (c as usize) < n;
            if inside && !contact(r as usize * n + c as usize) {
                return true;
            }
        }
    }
    false
}

/// The rises of the window's elements per unit tension released at `centre`: the dense
/// system K_AA δt_A = K_Av (lower triangle assembled, Cholesky, substitution).
fn solve_rises(kernel: &[f64], window: &[(i64, i64)], centre: (i64, i64), matrix: &mut Vec<f64>, rises: &mut Vec<f64>) {
    let size = window.len();
    matrix.clear();
    rises.clear();
    matrix.resize(size * size, 0.0);
    for (i, &(ri, ci)) in window.iter().enumerate() {
        // Lower triangle only: the factorisation reads nothing else.
        for (j, &(rj, cj)) in window[..=i].iter().enumerate() {
            matrix[i * size + j] = kernel_at(kernel, ri - rj, ci - cj);
        }
        rises.push(kernel_at(kernel, ri - centre.0, ci - centre.1));
    }
    // K_AA is a principal block of the SPD influence matrix; should rounding make it
    // indefinite, the window predicts no rises (a prediction is a guess, checked later).
    match cholesky_factorise(matrix, size, Summation::FourLanes) {
        Ok(()) => cholesky_solve(matrix, size, rises, Summation::FourLanes),
        Err(_) => rises.iter_mut().for_each(|rise| *rise = 0.0),
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
        let window: Vec<((i64, i64), f64)> = predictor.window(None).collect();
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

    /// A window of a shape met before takes its rises from the cache, and they are the
    /// bits a fresh solve gives: two releases on a straight edge, far from each other and
    /// from the grid's sides, share one shape; the second is not solved again.
    #[test]
    fn a_cached_shape_gives_the_rises_of_a_fresh_solve() {
        let n = 64;
        let contact = |k: usize| k % n < 40;
        let mut predictor = PeelPredictor::new(n * n);
        predictor.release(n, (20, 39), |k| contact(k) && k != 20 * n + 39);
        predictor.finish();
        assert_eq!(predictor.solved.len(), 1);
        predictor.release(n, (44, 39), |k| contact(k) && k != 44 * n + 39);
        assert_eq!(predictor.solved.len(), 1, "the second release is a hit");
        let cached: Vec<((i64, i64), u64)> = predictor.window(None).map(|(w, r)| (w, r.to_bits())).collect();
        let (mut matrix, mut fresh) = (Vec::new(), Vec::new());
        solve_rises(
            &predictor.kernel,
            &predictor.last.window,
            (44, 39),
            &mut matrix,
            &mut fresh,
        );
        let solved: Vec<((i64, i64), u64)> = predictor
            .last
            .window
            .iter()
            .cloned()
            .zip(fresh.iter().map(|r| r.to_bits()))
            .collect();
        assert!(!cached.is_empty());
        assert_eq!(cached, solved);
        // A different shape (a release near the grid's side) is solved and stored.
        predictor.finish();
        predictor.release(n, (2, 39), |k| contact(k) && k != 2 * n + 39);
        assert_eq!(predictor.solved.len(), 2);
    }

    /// A planned batch gives every release the window and rises, to the bit, that the
    /// one-at-a-time replay gives in the same order: on a rough contact (a disc with
    /// holes), releasing 40 elements of its edge, neighbours of each other included.
    #[test]
    fn a_planned_batch_replays_the_releases_bit_for_bit() {
        let n = 64;
        let mut contact: Vec<bool> = (0..n * n)
            .map(|k| {
                let (r, c) = ((k / n) as f64 - 31.5, (k % n) as f64 - 31.5);
                r * r + c * c < 26.0 * 26.0 && (k * 2_654_435_761) % 97 > 6
            })
            .collect();
        let edge: Vec<usize> = (0..n * n)
            .filter(|&k| contact[k] && near_free(n, (k / n) as i64, (k % n) as i64, &|e: usize| contact[e]))
            .step_by(3)
            .take(40)
            .collect();
        assert_eq!(edge.len(), 40);
        let mut planner = PeelPredictor::new(n * n);
        assert!(planner.plan_batch(n, &edge, &contact));
        let mut serial = PeelPredictor::new(n * n);
        for (place, &k) in edge.iter().enumerate() {
            contact[k] = false;
            serial.release(n, ((k / n) as i64, (k % n) as i64), |e| contact[e]);
            let one: Vec<((i64, i64), u64)> = serial.window(None).map(|(w, r)| (w, r.to_bits())).collect();
            let planned: Vec<((i64, i64), u64)> = planner.window(Some(place)).map(|(w, r)| (w, r.to_bits())).collect();
            assert!(!one.is_empty());
            assert_eq!(one, planned, "release {place} (element {k})");
        }
        serial.finish();
        assert!(planner.batch_rank.iter().all(|&r| r == 0));
        // Too short a batch is left to the one-at-a-time replay.
        assert!(!planner.plan_batch(n, &edge[..PLAN_MIN_BATCH - 1], &contact));
    }
}
