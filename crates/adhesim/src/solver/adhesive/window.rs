//! The fixed-set CG of the adhesive step on the contact's bounding box.
//!
//! The CG of a fixed-set solve (docs/physics.md §3.2) reads and writes only the contact
//! set C: its residual, direction and pressure vanish off C. Where the operator has a
//! window restriction ([`ElasticOperator::window_operator`]: the free half-space, whose
//! DC-FFT kernel depends on the offset only), K_CC is the same matrix on any square window
//! that holds C, so the CG runs there with transforms of twice the window's side instead
//! of twice the grid's, and its vector loops visit the window only (the contact window of
//! the non-adhesive solver, `solver::contact_window`, made for the adhesive step). The
//! displacement outside the window, which the growth and the outputs read, lags: it is
//! brought up to the window's pressure by one single-precision application of the change
//! on the whole grid when something reads it ([`SetWindows::sync_outside`]). A cascade of
//! releases reads only pressures, so its solves keep their window and their lag, and the
//! whole grid is transformed once after it instead of once a solve. A step's first window
//! is chosen from the contact alone (its bounding box, centred) and a step ends with the
//! displacement brought up everywhere, so a resumed run chooses the same windows as an
//! uninterrupted one.

use crate::elastic::ElasticOperator;
use crate::grid::Grid;
use crate::solver::contact_window::{smooth_side, Bounds, Window};
use crate::solver::workspace::Workspace;
use crate::solver::PARALLEL_CHUNK;
use rayon::prelude::*;
use std::ops::Range;

/// A window is used while its side is at most this fraction of the grid's shorter side:
/// above it, its transforms save little against the grid's row-pruned ones, and bringing
/// the whole grid up after it costs more than they save.
const MAX_WINDOW_FRACTION: f64 = 0.8;

/// Windows kept planned, by side (the least recently used is dropped): a growing or
/// shrinking contact passes through a few sides, and each is planned once.
const KEPT_SIDES: usize = 4;

/// A lagging window is kept for the next solve while the side its contact would choose is
/// at least this fraction of its own: below it, the smaller window's cheaper iterations
/// (their transforms scale with the side squared) are expected to repay bringing the whole
/// grid up. An estimate from those costs, not a measured optimum.
const KEEP_SIDE_RATIO: f64 = 0.9;

/// One window's operator, the CG's buffers and preconditioner on it, and copies of the
/// set's fields.
pub(super) struct SetWindow {
    pub(super) placement: Window,
    pub(super) operator: Box<dyn ElasticOperator + Sync>,
    /// The CG's buffers, and its preconditioner where `AdhesiveParams::preconditioned`.
    pub(super) workspace: Workspace,
    pub(super) pressure: Vec<f64>,
    pub(super) displacement: Vec<f64>,
    pub(super) critical_stress: Vec<f64>,
    pub(super) contact: Vec<bool>,
    /// The pressure the full grid's displacement belonged to when the window was loaded.
    base_pressure: Vec<f64>,
    /// The pressure the displacement outside the window belongs to (while it lags).
    outside_pressure: Vec<f64>,
    /// Elements per row of the full grid.
    nx: usize,
    last_used: u64,
}

/// The planned windows of a solver.
#[derive(Default)]
pub(super) struct SetWindows {
    kept: Vec<SetWindow>,
    /// Index in `kept` of the window of the solve under way.
    current: Option<usize>,
    /// Whether the displacement outside the current window lags its pressure.
    lagging: bool,
    clock: u64,
}

impl SetWindows {
    /// Chooses the window that holds the contact `contact` of `operator`'s grid (planned
    /// and placed; its fields are not loaded) as the current one; false, and no current
    /// window, when the operator has no window restriction, the contact is empty, or its
    /// window would not be much smaller than the grid. The displacement must not lag.
    pub(super) fn enter<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &O,
        contact: &[bool],
        preconditioned: bool,
    ) -> bool {
        debug_assert!(!self.lagging, "a window chosen while the displacement lags");
        self.current = self.place(operator, contact, preconditioned);
        self.current.is_some()
    }

    /// No window for the solve under way (the displacement must not lag).
    pub(super) fn clear(&mut self) {
        debug_assert!(!self.lagging, "a window left while the displacement lags");
        self.current = None;
    }

    /// Whether the lagging current window serves the next solve on `contact` too: it holds
    /// the contact, and the side the contact would choose is not much smaller.
    pub(super) fn keep(&self, contact: &[bool]) -> bool {
        let Some(window) = self.current.filter(|_| self.lagging).map(|index| &self.kept[index]) else {
            return false;
        };
        Bounds::of_contact(contact, window.nx).is_some_and(|bounds| {
            smooth_side(bounds.extent()) as f64 >= KEEP_SIDE_RATIO * window.placement.side as f64
                && window.placement.holds(&bounds)
        })
    }

    /// The window chosen by the last [`enter`](Self::enter).
    pub(super) fn current(&mut self) -> Option<&mut SetWindow> {
        self.current.map(|index| &mut self.kept[index])
    }

    /// Writes the current window's pressure and displacement back into the full grid's
    /// (the pressure vanishes outside, where there is no contact); the displacement outside
    /// the window lags from here on, until [`sync_outside`](Self::sync_outside).
    pub(super) fn leave(&mut self, pressure: &mut [f64], displacement: &mut [f64]) {
        if let Some(index) = self.current {
            let window = &self.kept[index];
            window.scatter(&window.pressure, pressure);
            window.scatter(&window.displacement, displacement);
            self.lagging = !same_values(&window.pressure, &window.outside_pressure);
        }
    }

    /// Brings the displacement outside the current window up to the window's pressure:
    /// u += K·(p − p_outside) there, in single precision on the whole grid, with
    /// `change` and `response` as the full grid's scratch vectors (nothing when it does
    /// not lag).
    pub(super) fn sync_outside<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        displacement: &mut [f64],
        (change, response): (&mut [f64], &mut [f64]),
    ) {
        if let Some(index) = self.current.filter(|_| self.lagging) {
            self.lagging = false;
            self.kept[index].apply_outside(operator, displacement, (change, response));
        }
    }

    /// Forgets the lag: the displacement was recomputed or restored on the whole grid.
    pub(super) fn discard_lag(&mut self) {
        self.lagging = false;
    }

    /// Whether the displacement outside the current window lags its pressure.
    pub(super) fn lagging(&self) -> bool {
        self.lagging
    }

    fn place<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &O,
        contact: &[bool],
        preconditioned: bool,
    ) -> Option<usize> {
        let grid = *operator.grid();
        let (nx, ny) = (grid.nx(), grid.ny());
        let bounds = Bounds::of_contact(contact, nx)?;
        let side = smooth_side(bounds.extent());
        if side as f64 > MAX_WINDOW_FRACTION * nx.min(ny) as f64 {
            return None;
        }
        self.clock += 1;
        let index = match self.kept.iter().position(|window| window.placement.side == side) {
            Some(index) => index,
            None => {
                let window = SetWindow::new(operator, &grid, side, preconditioned)?;
                if self.kept.len() == KEPT_SIDES {
                    let oldest = (0..self.kept.len()).min_by_key(|&i| self.kept[i].last_used)?;
                    self.kept.swap_remove(oldest);
                }
                self.kept.push(window);
                self.kept.len() - 1
            }
        };
        let window = &mut self.kept[index];
        window.last_used = self.clock;
        window.placement = Window::place(&bounds, side, (nx, ny));
        Some(index)
    }
}

impl SetWindow {
    fn new<O: ElasticOperator + ?Sized>(operator: &O, grid: &Grid, side: usize, preconditioned: bool) -> Option<Self> {
        let window_operator = operator.window_operator(side)?;
        let window_grid = *window_operator.grid();
        let len = side * side;
        Some(Self {
            placement: Window {
                row: 0,
                column: 0,
                side,
            },
            nx: grid.nx(),
            workspace: Workspace::new(&window_grid, operator.contact_modulus(), preconditioned),
            operator: window_operator,
            pressure: vec![0.0; len],
            displacement: vec![0.0; len],
            critical_stress: vec![0.0; len],
            contact: vec![false; len],
            base_pressure: vec![0.0; len],
            outside_pressure: vec![0.0; len],
            last_used: 0,
        })
    }

    /// Copies the window field `local` into the window's part of the full-grid `full`,
    /// rows on the pool.
    fn scatter(&self, local: &[f64], full: &mut [f64]) {
        let (Window { row, column, side }, nx) = (self.placement, self.nx);
        full[row * nx..(row + side) * nx]
            .par_chunks_mut(nx)
            .zip(local.par_chunks(side))
            .with_min_len(ROWS_PER_TASK)
            .for_each(|(full, local)| full[column..column + side].copy_from_slice(local));
    }

    /// Whether every nonzero of a full-grid field on the elements `span` lies in the window.
    pub(super) fn holds(&self, field: &[f64], span: Range<usize>) -> bool {
        let Window { row, column, side } = self.placement;
        let nx = self.nx;
        span.into_iter().all(|k| {
            field[k] == 0.0 || ((row..row + side).contains(&(k / nx)) && (column..column + side).contains(&(k % nx)))
        })
    }

    /// Loads the pressure and displacement, with `base` the pressure the displacement
    /// belongs to (on the whole grid, where it differs from the pressure only inside the
    /// window). A base other than the pressure is applied on the window, and the window's
    /// displacement written back on the window: on the window u = K p from here on, and
    /// outside it u lags, behind `base` (or, with `lagging`, behind the pressure it already
    /// lagged). Returns the window's operator applications (0 or 1).
    pub(super) fn load_state(
        &mut self,
        pressure: &[f64],
        displacement: &mut [f64],
        base: &[f64],
        lagging: bool,
    ) -> u64 {
        let (placement, nx) = (self.placement, self.nx);
        gather(placement, nx, pressure, &mut self.pressure);
        gather(placement, nx, displacement, &mut self.displacement);
        gather(placement, nx, base, &mut self.base_pressure);
        if !lagging {
            gather(placement, nx, base, &mut self.outside_pressure);
        }
        if same_values(&self.pressure, &self.base_pressure) {
            return 0;
        }
        self.workspace
            .direction
            .par_chunks_mut(PARALLEL_CHUNK)
            .zip(self.pressure.par_chunks(PARALLEL_CHUNK))
            .zip(self.base_pressure.par_chunks(PARALLEL_CHUNK))
            .for_each(|((change, now), before)| {
                for ((change, &now), &before) in change.iter_mut().zip(now).zip(before) {
                    *change = now - before;
                }
            });
        self.operator
            .apply_single(&self.workspace.direction, &mut self.workspace.response);
        self.displacement
            .par_chunks_mut(PARALLEL_CHUNK)
            .zip(self.workspace.response.par_chunks(PARALLEL_CHUNK))
            .for_each(|(u, du)| u.iter_mut().zip(du).for_each(|(u, du)| *u += du));
        self.scatter(&self.displacement, displacement);
        1
    }

    /// Loads the set's fields for the CG (each one value per full-grid element).
    pub(super) fn load_set(&mut self, residual: &[f64], mask: &[f64], critical_stress: &[f64], contact: &[bool]) {
        let (placement, nx) = (self.placement, self.nx);
        gather(placement, nx, residual, &mut self.workspace.residual);
        gather(placement, nx, mask, &mut self.workspace.mask);
        gather(placement, nx, critical_stress, &mut self.critical_stress);
        gather(placement, nx, contact, &mut self.contact);
    }

    /// u += K·(p − p_outside) outside the window (the change applied in single precision
    /// on the whole grid, only the window's rows transformed forward).
    fn apply_outside<O: ElasticOperator + ?Sized>(
        &self,
        operator: &mut O,
        displacement: &mut [f64],
        (change, response): (&mut [f64], &mut [f64]),
    ) {
        let (nx, ny) = (operator.grid().nx(), operator.grid().ny());
        let Window { row, column, side } = self.placement;
        let rows = row..row + side;
        change[rows.start * nx..rows.end * nx]
            .par_chunks_mut(nx)
            .zip(
                self.pressure
                    .par_chunks(side)
                    .zip(self.outside_pressure.par_chunks(side)),
            )
            .with_min_len(ROWS_PER_TASK)
            .for_each(|(change, (now, before))| {
                change.fill(0.0);
                for ((target, &now), &before) in change[column..column + side].iter_mut().zip(now).zip(before) {
                    *target = now - before;
                }
            });
        operator.apply_single_rows(change, response, rows.clone(), 0..ny);
        displacement
            .par_chunks_mut(nx)
            .zip(response.par_chunks(nx))
            .enumerate()
            .for_each(|(i, (u, du))| {
                let inside = if rows.contains(&i) { column..column + side } else { 0..0 };
                for (j, (u, du)) in u.iter_mut().zip(du).enumerate() {
                    if !inside.contains(&j) {
                        *u += du;
                    }
                }
            });
    }
}

/// Window rows per rayon task of the copies between the grid and a window.
const ROWS_PER_TASK: usize = 16;

/// Copies the window's part of the full-grid field `full` (rows of `nx`) into the window
/// field `local`, rows on the pool (a copy: the same values for any split).
fn gather<T: Copy + Send + Sync>(placement: Window, nx: usize, full: &[T], local: &mut [T]) {
    let Window { row, column, side } = placement;
    local
        .par_chunks_mut(side)
        .zip(full[row * nx..(row + side) * nx].par_chunks(nx))
        .with_min_len(ROWS_PER_TASK)
        .for_each(|(local, full)| local.copy_from_slice(&full[column..column + side]));
}

/// Whether two fields hold the same values (`==` element by element, as for slices).
fn same_values(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len()
        && a.par_chunks(PARALLEL_CHUNK)
            .zip(b.par_chunks(PARALLEL_CHUNK))
            .all(|(a, b)| a == b)
}
