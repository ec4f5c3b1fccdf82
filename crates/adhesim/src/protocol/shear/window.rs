//! The window of the tangential problem: the contact's bounding box as a free grid.

use crate::elastic::{Backend, ShearBody, ShearCompliance};
use crate::grid::{Boundary, Grid};
use crate::protocol::ProtocolError;
use crate::solver::{ContactState, SlipStatus, TangentialState};

/// The tangential fields of a shift step on the whole grid, row-major (no traction, no
/// slip and open outside the window of the tangential problem).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ShearFields {
    /// Shear traction (q_x, q_y) on the body.
    pub traction: [Vec<f64>; 2],
    /// Accumulated slip (s_x, s_y): the sum of each element's slip increments.
    pub slip: [Vec<f64>; 2],
    /// Open, stick or slip.
    pub status: Vec<SlipStatus>,
}

impl ShearFields {
    /// No traction, no slip, all open, on `elements` elements.
    pub fn new(elements: usize) -> Self {
        let zeros = || [vec![0.0; elements], vec![0.0; elements]];
        Self {
            traction: zeros(),
            slip: zeros(),
            status: vec![SlipStatus::Open; elements],
        }
    }
}

/// The contact's bounding box as a free grid of its own. The shear tractions vanish
/// outside the contact and only the displacements on it enter the tangential problem, so
/// the DC-FFT convolution on this window is the full grid's, restricted (the same
/// coefficients; only the transforms' sizes, and so their rounding, differ), at a fraction
/// of its cost.
#[derive(Clone, PartialEq)]
pub(super) struct ContactWindow {
    pub(super) grid: Grid,
    rows: std::ops::Range<usize>,
    columns: std::ops::Range<usize>,
    nx: usize,
}

impl ContactWindow {
    /// The window of `contact` on `grid`, widened by `margin` elements on each side where
    /// the grid allows (at least 2×2 elements, as a grid needs). On a periodic grid the
    /// window is the whole grid: a contact may wrap around its edges, and the periodic
    /// operator couples every element with every other.
    pub(super) fn around(grid: &Grid, contact: &[bool], margin: usize) -> Result<Self, ProtocolError> {
        let nx = grid.nx();
        if grid.boundary() == Boundary::Periodic {
            return Ok(Self {
                grid: *grid,
                rows: 0..grid.ny(),
                columns: 0..nx,
                nx,
            });
        }
        let (mut rows, mut columns) = ((usize::MAX, 0), (usize::MAX, 0));
        for (k, _) in contact.iter().enumerate().filter(|(_, &c)| c) {
            let (i, j) = (k / nx, k % nx);
            rows = (rows.0.min(i), rows.1.max(i + 1));
            columns = (columns.0.min(j), columns.1.max(j + 1));
        }
        let span = |(start, end): (usize, usize), n: usize| {
            let (start, end) = if start >= end {
                (0, 2)
            } else {
                (start.saturating_sub(margin), end + margin)
            };
            let end = end.max(start + 2).min(n);
            end.saturating_sub(2).min(start)..end
        };
        let rows = span(rows, grid.ny());
        let columns = span(columns, nx);
        let window = Grid::rectangular(
            columns.len(),
            rows.len(),
            columns.len() as f64 * grid.dx(),
            rows.len() as f64 * grid.dy(),
            Boundary::Free,
        )
        .map_err(|error| ProtocolError::InvalidParameter(error.to_string()))?;
        Ok(Self {
            grid: window,
            rows,
            columns,
            nx,
        })
    }

    /// The normal state on the window (pressure and contact; the normal displacement is
    /// not used by the tangential solve).
    pub(super) fn gather(&self, state: &ContactState) -> ContactState {
        let mut window = ContactState::new(&self.grid);
        self.gather_into(state, &mut window);
        window
    }

    /// As [`gather`](Self::gather), into `window`. The callers widen the window with the
    /// contact first, so every element in contact lies inside it (checked in debug builds).
    pub(super) fn gather_into(&self, state: &ContactState, window: &mut ContactState) {
        let mut inside = 0;
        for (w, k) in self.elements() {
            window.pressure[w] = state.pressure[k];
            window.contact[w] = state.contact[k];
            inside += usize::from(state.contact[k]);
        }
        debug_assert_eq!(inside, state.contact_elements(), "contact outside the window");
    }

    /// Copies the window's tangential state into `fields` on the whole grid (which is
    /// zero and open outside the window from [`ShearFields::new`]).
    pub(super) fn scatter(&self, state: &TangentialState, fields: &mut ShearFields) {
        for (w, k) in self.elements() {
            for c in 0..2 {
                fields.traction[c][k] = state.traction[c][w];
                fields.slip[c][k] = state.slip[c][w];
            }
            fields.status[k] = state.status[w];
        }
    }

    /// (window index, grid index) of every window element, row-major.
    pub(super) fn elements(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        let width = self.columns.len();
        self.rows.clone().enumerate().flat_map(move |(r, i)| {
            self.columns
                .clone()
                .enumerate()
                .map(move |(c, j)| (r * width + c, i * self.nx + j))
        })
    }
}

/// The tangential problem's room: the contact's window, its operator and the tangential
/// fields on it. It widens when the contact grows out of the window (an inclined motion
/// into the body), carrying the fields over.
pub(super) struct TangentialRoom {
    pub(super) window: ContactWindow,
    pub(super) operator: Box<dyn ShearCompliance>,
    pub(super) state: TangentialState,
    grid: Grid,
    body: ShearBody,
    /// The backend that builds the room's operator (the run's normal operator's).
    backend: Backend,
    margin: usize,
}

impl TangentialRoom {
    /// The room of `contact` on `grid`, `margin` elements wider on each side, its operator
    /// built by `backend`.
    pub(super) fn new(
        grid: &Grid,
        contact: &[bool],
        margin: usize,
        (body, backend): (ShearBody, Backend),
    ) -> Result<Self, ProtocolError> {
        let window = ContactWindow::around(grid, contact, margin)?;
        let operator = backend
            .shear_operator(window.grid, body)
            .map_err(|error| ProtocolError::InvalidParameter(error.to_string()))?;
        Ok(Self {
            state: TangentialState::new(window.grid.len()),
            window,
            operator,
            grid: *grid,
            body,
            backend,
            margin,
        })
    }

    /// Widens the window to hold `contact` as well as the old window: tractions, slips and
    /// states carry over (they vanish outside the old window), the displacements are
    /// recomputed on the new one (u = K q is the same field, now seen on more elements).
    /// Returns the FFT pairs this spent (0 when the window already held the contact).
    pub(super) fn cover(&mut self, contact: &[bool]) -> Result<u64, ProtocolError> {
        if !self.outside(contact) {
            return Ok(0);
        }
        let mut union = contact.to_vec();
        for (_, k) in self.window.elements() {
            union[k] = true;
        }
        let wider = Self::new(&self.grid, &union, self.margin, (self.body, self.backend))?;
        Ok(self.move_into(wider))
    }

    /// Moves the window onto `contact` when the contact has left it (a translation): the
    /// new window holds the contact, the elements that still carry a traction and the
    /// margin, not the path behind. The fields of the elements both windows hold carry
    /// over; those left behind carry no traction, so u = K q, recomputed, is the same
    /// field. Returns the FFT pairs this spent.
    pub(super) fn follow(&mut self, contact: &[bool]) -> Result<u64, ProtocolError> {
        if !self.outside(contact) {
            return Ok(0);
        }
        let mut loaded = contact.to_vec();
        for (w, k) in self.window.elements() {
            if self.state.traction[0][w] != 0.0 || self.state.traction[1][w] != 0.0 {
                loaded[k] = true;
            }
        }
        let moved = Self::new(&self.grid, &loaded, self.margin, (self.body, self.backend))?;
        Ok(self.move_into(moved))
    }

    /// The window and the fields, to go back to with [`restore`](Self::restore).
    pub(super) fn snapshot(&self) -> (ContactWindow, TangentialState) {
        (self.window.clone(), self.state.clone())
    }

    /// Goes back to the fields of `snapshot` after a trial: in place where the window is
    /// the same, else carried into the trial's (wider) window as [`cover`](Self::cover)
    /// carries them. Returns the FFT pairs this spent.
    pub(super) fn restore(&mut self, (window, state): &(ContactWindow, TangentialState)) -> u64 {
        if *window == self.window {
            self.state.clone_from(state);
            return 0;
        }
        let mut next = TangentialState::new(self.window.grid.len());
        carry_fields((window, state), (&self.window, &mut next), self.grid.len());
        let before = self.operator.transform_pairs();
        recompute_displacements(self.operator.as_mut(), &mut next);
        self.state = next;
        self.operator.transform_pairs() - before
    }

    /// Some element of `contact` lies outside the window.
    fn outside(&self, contact: &[bool]) -> bool {
        let nx = self.grid.nx();
        contact
            .iter()
            .enumerate()
            .any(|(k, &c)| c && !(self.window.rows.contains(&(k / nx)) && self.window.columns.contains(&(k % nx))))
    }

    /// Carries the fields into the room `next` and takes its place; returns the FFT pairs
    /// of recomputing the displacements there.
    fn move_into(&mut self, mut next: Self) -> u64 {
        carry_fields(
            (&self.window, &self.state),
            (&next.window, &mut next.state),
            self.grid.len(),
        );
        recompute_displacements(next.operator.as_mut(), &mut next.state);
        let pairs = next.operator.transform_pairs();
        *self = next;
        pairs
    }
}

/// Copies the tractions, slips, states (and slip weakening's slips since the elements last
/// stuck) of the elements that both windows hold from `from` into the fresh state of
/// `into` (the others stay open and unloaded), with the shift, the drive and the rest
/// flag; `elements` is the whole grid's count.
fn carry_fields(
    (from_window, from): (&ContactWindow, &TangentialState),
    (into_window, into): (&ContactWindow, &mut TangentialState),
    elements: usize,
) {
    let mut at = vec![usize::MAX; elements];
    for (w, k) in from_window.elements() {
        at[k] = w;
    }
    for (w, k) in into_window.elements() {
        let Some(&source) = at.get(k).filter(|&&source| source != usize::MAX) else {
            continue;
        };
        for c in 0..2 {
            into.traction[c][w] = from.traction[c][source];
            into.slip[c][w] = from.slip[c][source];
        }
        into.status[w] = from.status[source];
    }
    if !from.slip_since_stuck.is_empty() {
        // Slip weakening's memory, by grid element as the rest.
        into.slip_since_stuck = vec![0.0; into.status.len()];
        for (w, k) in into_window.elements() {
            if let Some(&source) = at.get(k).filter(|&&source| source != usize::MAX) {
                into.slip_since_stuck[w] = from.slip_since_stuck[source];
            }
        }
    }
    (into.shift, into.drive, into.at_rest) = (from.shift, from.drive, from.at_rest);
}

/// u = K q of the state's tractions: the same field on whatever window holds them.
fn recompute_displacements(operator: &mut dyn ShearCompliance, state: &mut TangentialState) {
    let [ux, uy] = &mut state.displacement;
    operator.apply([&state.traction[0], &state.traction[1]], [ux, uy]);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::elastic::cerruti::ShearMaterial;
    use crate::solver::SlipStatus;

    /// A disc of radius² `r2` elements about the centre of a 32² grid.
    fn disc(r2: i64) -> Vec<bool> {
        (0..32 * 32)
            .map(|k| {
                let (i, j) = (k / 32 - 16, k % 32 - 16);
                i * i + j * j <= r2
            })
            .collect()
    }

    /// A snapshot restored after a trial widened the window keeps every element's traction,
    /// slip, state and slip since it last stuck (slip weakening's), now in the wider window, and its displacements are K q there: those
    /// of the narrow window where both hold the element, to the rounding of transforms of
    /// other sizes (1e-12 of the largest asserted).
    #[test]
    fn a_restore_into_a_wider_window_keeps_the_fields() {
        let grid = Grid::new(32, 1.0, Boundary::Free).unwrap();
        let material = ShearMaterial::from_contact_modulus(4.0, 0.5);
        let contact = disc(16);
        let mut room = TangentialRoom::new(&grid, &contact, 2, (material.into(), Backend::Cpu)).unwrap();
        let window = room.window.clone();
        room.state.slip_since_stuck = vec![0.0; window.grid.len()];
        for (w, k) in window.elements() {
            if contact[k] {
                room.state.traction[0][w] = 1.0 + (k % 7) as f64;
                room.state.traction[1][w] = 0.5 - (k % 3) as f64;
                room.state.slip[0][w] = 1e-3 * (k % 5) as f64;
                room.state.slip_since_stuck[w] = 1e-4 * (k % 11) as f64;
                room.state.status[w] = if k % 2 == 0 {
                    SlipStatus::Stick
                } else {
                    SlipStatus::Slip
                };
            }
        }
        {
            let [ux, uy] = &mut room.state.displacement;
            room.operator
                .apply([&room.state.traction[0], &room.state.traction[1]], [ux, uy]);
        }
        room.state.shift = [0.25, -0.125];
        let narrow = room.state.clone();
        let snapshot = room.snapshot();
        assert_eq!(room.restore(&snapshot), 0, "the same window: no transform");
        assert_eq!(room.state, narrow);
        room.cover(&disc(100)).unwrap();
        assert!(room.window != window, "the trial widened the window");
        room.state.traction[0].iter_mut().for_each(|t| *t = 0.0);
        assert!(room.restore(&snapshot) > 0);
        let largest = narrow.displacement[0].iter().fold(0.0f64, |m, u| m.max(u.abs()));
        let mut at = vec![usize::MAX; grid.len()];
        for (w, k) in window.elements() {
            at[k] = w;
        }
        for (w, k) in room.window.elements() {
            let Some(&from) = at.get(k).filter(|&&from| from != usize::MAX) else {
                assert_eq!(room.state.traction[0][w], 0.0, "outside the snapshot: no traction");
                assert_eq!(room.state.slip_since_stuck[w], 0.0);
                continue;
            };
            assert_eq!(room.state.traction[0][w], narrow.traction[0][from]);
            assert_eq!(room.state.traction[1][w], narrow.traction[1][from]);
            assert_eq!(room.state.slip[0][w], narrow.slip[0][from]);
            assert_eq!(room.state.status[w], narrow.status[from]);
            assert_eq!(room.state.slip_since_stuck[w], narrow.slip_since_stuck[from]);
            for c in 0..2 {
                let difference = (room.state.displacement[c][w] - narrow.displacement[c][from]).abs();
                assert!(difference <= 1e-12 * largest, "element {k}: {difference:e}");
            }
        }
        assert_eq!(room.state.shift, narrow.shift);
    }
}
