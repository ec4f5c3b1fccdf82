//! The contact's bounding box as a grid of its own, for the rounds of [`super::NestedActiveSet`]
//! (transforms and loops restricted to where the work is; docs/history.md §2026-11-23: the
//! non-adhesive whole run).
//!
//! On a free half-space the elastic response of elements inside a square window of side B
//! is the DC-FFT convolution on a B×B grid of the same element size: Love's coefficients
//! depend on the offset only, so the window's own [`FreeOperator`] (transforms of 2B
//! instead of 2N) is the restriction of the full operator, exact up to rounding. A
//! non-adhesive contact that covers a quarter of the grid's width is then solved with
//! transforms of a quarter of the area, and every vector loop visits the window only.
//! The window is a pre-solve: the full grid's own rounds follow and decide convergence
//! and the contact set with the full operator, so an element outside the window that
//! should touch, or a rounding difference, is corrected there.

use super::workspace::Workspace;
use super::ContactState;
use crate::elastic::FreeOperator;
use crate::grid::{Boundary, Grid};
use crate::material::ElasticMaterial;

/// Free elements kept around the contact's bounding box on every side, for the front to
/// grow into before the window must be moved.
pub(super) const WINDOW_MARGIN: usize = 6;

/// A window is used only while its side is at most this fraction of the grid's: above it,
/// the full grid's row-pruned transforms cost about the same.
const MAX_WINDOW_FRACTION: f64 = 0.75;

/// Rows and columns spanned by the contact: `[first_row, last_row, first_column, last_column]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Bounds {
    rows: (usize, usize),
    columns: (usize, usize),
}

impl Bounds {
    /// The bounding box of the elements in contact of a grid of rows of n elements (None
    /// without contact).
    pub(super) fn of_contact(contact: &[bool], n: usize) -> Option<Self> {
        let first = contact.iter().position(|&c| c)?;
        let last = contact.iter().rposition(|&c| c)?;
        let (mut low, mut high) = (n, 0);
        for chunk in contact[first / n * n..(last / n + 1) * n].chunks(n) {
            if let Some(column) = chunk.iter().position(|&c| c) {
                low = low.min(column);
                high = high.max(chunk.iter().rposition(|&c| c).unwrap_or(column));
            }
        }
        Some(Self {
            rows: (first / n, last / n),
            columns: (low, high),
        })
    }

    pub(super) fn extent(&self) -> usize {
        (self.rows.1 - self.rows.0).max(self.columns.1 - self.columns.0) + 1
    }
}

/// The smallest side ≥ `side` whose only prime factors are 2, 3 and 5 (fast transforms of
/// twice that length).
pub(super) fn smooth_side(side: usize) -> usize {
    (side.max(1)..)
        .find(|&candidate| {
            let mut rest = candidate;
            for factor in [2, 3, 5] {
                while rest.is_multiple_of(factor) {
                    rest /= factor;
                }
            }
            rest == 1
        })
        .expect("5-smooth numbers are unbounded")
}

/// A window `[row, row + side) × [column, column + side)` of elements (side × side
/// elements, each of the grid's Δx × Δy) of an nx × ny grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Window {
    pub(super) row: usize,
    pub(super) column: usize,
    pub(super) side: usize,
}

impl Window {
    /// The window of side `side` centred on `bounds`, moved inside the nx × ny grid.
    pub(super) fn place(bounds: &Bounds, side: usize, (nx, ny): (usize, usize)) -> Self {
        let start =
            |(low, high): (usize, usize), n: usize| (low + high).div_ceil(2).saturating_sub(side / 2).min(n - side);
        Self {
            row: start(bounds.rows, ny),
            column: start(bounds.columns, nx),
            side,
        }
    }

    /// Whether the window holds every element of `bounds`.
    pub(super) fn holds(&self, bounds: &Bounds) -> bool {
        let inside = |(low, high): (usize, usize), start: usize| start <= low && high < start + self.side;
        inside(bounds.rows, self.row) && inside(bounds.columns, self.column)
    }

    /// Index in the full grid (rows of nx elements) of window element (i, j).
    fn full_index(&self, i: usize, j: usize, nx: usize) -> usize {
        (self.row + i) * nx + self.column + j
    }

    /// Whether an element in contact (in window numbering) lies within the margin of an
    /// edge of the window that is not an edge of the grid: the front may want to grow out.
    fn contact_near_open_edge(&self, contact: &[bool], (nx, ny): (usize, usize)) -> bool {
        let guard = WINDOW_MARGIN / 2;
        let open = |start: usize, n: usize| (start > 0, start + self.side < n);
        let (rows_low, rows_high) = open(self.row, ny);
        let (columns_low, columns_high) = open(self.column, nx);
        contact.chunks(self.side).enumerate().any(|(i, chunk)| {
            chunk.iter().enumerate().any(|(j, &c)| {
                c && ((rows_low && i < guard)
                    || (rows_high && i + guard >= self.side)
                    || (columns_low && j < guard)
                    || (columns_high && j + guard >= self.side))
            })
        })
    }
}

/// The free grid of side × side elements of `grid`'s Δx × Δy (on a square grid the
/// square of side side·Δ).
fn window_grid(side: usize, grid: &Grid) -> Result<Grid, crate::grid::GridError> {
    Grid::rectangular(
        side,
        side,
        side as f64 * grid.dx(),
        side as f64 * grid.dy(),
        Boundary::Free,
    )
}

/// The window's grid, operator and copies of the fields, kept between solves and remade
/// only when a larger window is needed.
pub(super) struct WindowLevel {
    pub(super) operator: FreeOperator,
    pub(super) heights: Vec<f64>,
    pub(super) state: ContactState,
    pub(super) workspace: Workspace,
    window: Window,
}

impl WindowLevel {
    /// The window's side in elements: with the grid and the material, all a window carries
    /// from one solve to the next (see [`WindowLevel::enter`] and `nested/checkpoint.rs`).
    pub(super) fn side(&self) -> usize {
        self.window.side
    }

    /// A window of `side` × `side` elements of `grid` (operator, preconditioner and
    /// buffers planned; placed at the grid's corner until [`WindowLevel::enter`] places it).
    fn new(grid: &Grid, material: ElasticMaterial, side: usize) -> Self {
        let window_grid = window_grid(side, grid).expect("a window of a valid free grid is valid");
        WindowLevel {
            operator: FreeOperator::new(window_grid, material),
            heights: vec![0.0; window_grid.len()],
            state: ContactState::new(&window_grid),
            workspace: Workspace::with_target(&window_grid, material.contact_modulus()),
            window: Window {
                row: 0,
                column: 0,
                side,
            },
        }
    }

    /// The window of `side` that a solver on `grid` had kept (a checkpoint put back); None
    /// when no window of that side fits the grid.
    pub(super) fn restored(grid: &Grid, material: ElasticMaterial, side: usize) -> Option<Self> {
        (side >= 1 && side <= grid.nx().min(grid.ny())).then(|| Self::new(grid, material, side))
    }

    /// Chooses the window for the contact in `state` on `grid` (reusing `cache` when its
    /// side suffices and is not more than twice what is needed), copies heights, contact
    /// and pressures into it and returns it; None when the contact is empty or its window
    /// would not be much smaller than the grid.
    pub(super) fn enter<'a>(
        cache: &'a mut Option<WindowLevel>,
        grid: &Grid,
        material: ElasticMaterial,
        heights: &[f64],
        state: &ContactState,
    ) -> Option<&'a mut WindowLevel> {
        let (n, counts) = (grid.nx(), (grid.nx(), grid.ny()));
        let bounds = Bounds::of_contact(&state.contact, n)?;
        let side = smooth_side(bounds.extent() + 2 * WINDOW_MARGIN);
        if side as f64 > MAX_WINDOW_FRACTION * n.min(grid.ny()) as f64 {
            return None;
        }
        let reusable = cache
            .as_ref()
            .is_some_and(|level| level.side() >= side && level.side() <= 2 * side);
        if !reusable {
            *cache = Some(WindowLevel::new(grid, material, side));
        }
        let level = cache.as_mut()?;
        level.window = Window::place(&bounds, level.side(), counts);
        let window = level.window;
        for i in 0..window.side {
            for j in 0..window.side {
                let (k, full) = (i * window.side + j, window.full_index(i, j, n));
                level.heights[k] = heights[full];
                level.state.contact[k] = state.contact[full];
                level.state.pressure[k] = state.pressure[full];
            }
        }
        Some(level)
    }

    /// Copies the window's contact and pressures back into `state` (elements outside the
    /// window are out of contact: the window holds the whole contact) and tells whether
    /// the contact reached an open edge of the window.
    pub(super) fn leave(&self, (n, ny): (usize, usize), state: &mut ContactState) -> bool {
        state.contact.fill(false);
        state.pressure.fill(0.0);
        let window = self.window;
        for i in 0..window.side {
            for j in 0..window.side {
                let (k, full) = (i * window.side + j, window.full_index(i, j, n));
                state.contact[full] = self.state.contact[k];
                state.pressure[full] = self.state.pressure[k];
            }
        }
        window.contact_near_open_edge(&self.state.contact, (n, ny))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smooth_sides_have_factors_two_three_five_only() {
        assert_eq!(smooth_side(257), 270);
        assert_eq!(smooth_side(256), 256);
        assert_eq!(smooth_side(7), 8);
        assert_eq!(smooth_side(0), 1);
    }

    #[test]
    fn bounds_and_window_hold_the_contact() {
        let n = 40;
        let mut contact = vec![false; n * n];
        for (i, j) in [(5, 30), (12, 33), (9, 28)] {
            contact[i * n + j] = true;
        }
        let bounds = Bounds::of_contact(&contact, n).unwrap();
        assert_eq!(
            bounds,
            Bounds {
                rows: (5, 12),
                columns: (28, 33)
            }
        );
        assert_eq!(bounds.extent(), 8);
        let window = Window::place(&bounds, 20, (n, n));
        // Centred on rows 5..=12 (start 9 − 10 → 0) and moved inside on the right.
        assert_eq!(
            window,
            Window {
                row: 0,
                column: 20,
                side: 20
            }
        );
        for (i, j) in [(5, 30), (12, 33), (9, 28)] {
            assert!(i >= window.row && i < window.row + 20 && j >= window.column && j < window.column + 20);
        }
        assert_eq!(Bounds::of_contact(&vec![false; n * n], n), None);
    }
}
