//! Square grids of square boundary elements.
//!
//! An N×N grid of side `size` = L has elements of side Δ = L/N. Fields are stored
//! row-major: index `i * n + j` is row `i` (coordinate y) and column `j` (coordinate x).
//! Element centres sit at `x_j = (j − N/2)·Δ`, so the origin is the centre of element
//! `(N/2, N/2)`: an indenter axis at the origin is centred on an element, which keeps
//! symmetric problems exactly symmetric about that element.

use thiserror::Error;

/// How the elastic half-space is continued outside the simulated square.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Boundary {
    /// A single contact on an infinite half-space (non-periodic, DC-FFT).
    Free,
    /// The square is one period of an infinite periodic surface.
    Periodic,
}

/// Errors raised when a grid is built from invalid numbers.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum GridError {
    /// The number of elements per side must be at least 2.
    #[error("grid must have at least 2 elements per side, got {0}")]
    TooFewElements(usize),
    /// The side length must be finite and positive.
    #[error("grid size must be finite and > 0, got {0}")]
    InvalidSize(f64),
    /// The element count (of the padded grid of a free boundary, 2N per side) must fit in
    /// memory indices: beyond it N² wraps around.
    #[error("grid of n = {0} elements per side is too large: its element count (2n per side padded for a free boundary) overflows the index range")]
    TooManyElements(usize),
    /// The element side and area must be normal floating-point numbers, or every stress
    /// and force of the grid is lost to underflow or overflow.
    #[error("grid element size size/n = {size:e}/{n} has an area Δ² = {area:e} outside the floating-point range: choose a grid size commensurate with n")]
    ElementOutOfRange {
        /// The side length L.
        size: f64,
        /// Elements per side N.
        n: usize,
        /// The element area (L/N)², 0 or ∞ when out of range.
        area: f64,
    },
}

/// An N×N grid of square elements of side `size / n`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    n: usize,
    size: f64,
    boundary: Boundary,
}

impl Grid {
    /// A grid of `n`×`n` elements covering a square of side `size`.
    pub fn new(n: usize, size: f64, boundary: Boundary) -> Result<Self, GridError> {
        if n < 2 {
            return Err(GridError::TooFewElements(n));
        }
        if !(size.is_finite() && size > 0.0) {
            return Err(GridError::InvalidSize(size));
        }
        let padded = match boundary {
            Boundary::Free => n.checked_mul(2),
            Boundary::Periodic => Some(n),
        };
        if padded.and_then(|side| side.checked_mul(side)).is_none() {
            return Err(GridError::TooManyElements(n));
        }
        let delta = size / n as f64;
        let area = delta * delta;
        if !(delta.is_normal() && area.is_normal()) {
            return Err(GridError::ElementOutOfRange { size, n, area });
        }
        Ok(Self { n, size, boundary })
    }

    /// Elements per side, N.
    pub fn n(&self) -> usize {
        self.n
    }

    /// Total number of elements, N².
    pub fn len(&self) -> usize {
        self.n * self.n
    }

    /// Always false: a grid has at least 2×2 elements.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Side length L of the square.
    pub fn size(&self) -> f64 {
        self.size
    }

    /// Element side Δ = L/N.
    pub fn element_size(&self) -> f64 {
        self.size / self.n as f64
    }

    /// Element area Δ².
    pub fn element_area(&self) -> f64 {
        let delta = self.element_size();
        delta * delta
    }

    /// Boundary condition of the half-space.
    pub fn boundary(&self) -> Boundary {
        self.boundary
    }

    /// Coordinate of the centre of column (or row) `index`: (index − N/2)·Δ.
    pub fn coordinate(&self, index: usize) -> f64 {
        (index as f64 - (self.n / 2) as f64) * self.element_size()
    }

    /// Centre (x, y) of the element at flat index `k = row·N + column`.
    pub fn centre(&self, k: usize) -> (f64, f64) {
        (self.coordinate(k % self.n), self.coordinate(k / self.n))
    }

    /// True when the element touches the outer border of the square.
    pub fn is_border(&self, k: usize) -> bool {
        let (row, column) = (k / self.n, k % self.n);
        row == 0 || column == 0 || row + 1 == self.n || column + 1 == self.n
    }

    /// Calls `visit` with the flat index of each edge-adjacent (4-)neighbour of element `k`.
    /// On a periodic grid the neighbours wrap around.
    #[inline]
    pub fn for_each_neighbour(&self, k: usize, mut visit: impl FnMut(usize)) {
        let n = self.n;
        let (row, column) = (k / n, k % n);
        let periodic = self.boundary == Boundary::Periodic;
        if column > 0 {
            visit(k - 1);
        } else if periodic {
            visit(k + n - 1);
        }
        if column + 1 < n {
            visit(k + 1);
        } else if periodic {
            visit(k + 1 - n);
        }
        if row > 0 {
            visit(k - n);
        } else if periodic {
            visit(k + n * (n - 1));
        }
        if row + 1 < n {
            visit(k + n);
        } else if periodic {
            visit(k - n * (n - 1));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_bad_grids() {
        assert_eq!(Grid::new(1, 1.0, Boundary::Free), Err(GridError::TooFewElements(1)));
        assert!(Grid::new(4, 0.0, Boundary::Free).is_err());
        // Issue #29: n² wrapped to 0 elements at n = 2³²; a subnormal element was accepted.
        assert_eq!(
            Grid::new(1 << 32, 1.0, Boundary::Periodic),
            Err(GridError::TooManyElements(1 << 32))
        );
        assert_eq!(
            Grid::new(1 << 31, 1.0, Boundary::Free),
            Err(GridError::TooManyElements(1 << 31))
        );
        assert!(Grid::new((1 << 31) - 1, 1.0, Boundary::Free).is_ok());
        assert!(matches!(
            Grid::new(32, 1e-310, Boundary::Free),
            Err(GridError::ElementOutOfRange { .. })
        ));
        assert!(matches!(
            Grid::new(32, 1e300, Boundary::Free),
            Err(GridError::ElementOutOfRange { .. })
        ));
        assert!(Grid::new(4, f64::NAN, Boundary::Free).is_err());
    }

    #[test]
    fn origin_is_an_element_centre() {
        let grid = Grid::new(8, 8.0, Boundary::Free).unwrap();
        assert_eq!(grid.coordinate(4), 0.0);
        assert_eq!(grid.centre(4 * 8 + 4), (0.0, 0.0));
        assert_eq!(grid.coordinate(0), -4.0);
    }

    #[test]
    fn neighbours_wrap_only_when_periodic() {
        let free = Grid::new(4, 1.0, Boundary::Free).unwrap();
        let mut seen = Vec::new();
        free.for_each_neighbour(0, |k| seen.push(k));
        seen.sort();
        assert_eq!(seen, vec![1, 4]);
        let periodic = Grid::new(4, 1.0, Boundary::Periodic).unwrap();
        seen.clear();
        periodic.for_each_neighbour(0, |k| seen.push(k));
        seen.sort();
        assert_eq!(seen, vec![1, 3, 4, 12]);
    }
}
