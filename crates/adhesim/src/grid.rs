//! Rectangular grids of rectangular boundary elements.
//!
//! An Nx×Ny grid of sides Lx × Ly has elements of sides Δx = Lx/Nx and Δy = Ly/Ny (a
//! square grid, [`Grid::new`], is the case Nx = Ny, Lx = Ly). Fields are stored row-major:
//! index `i * nx + j` is row `i` (coordinate y) and column `j` (coordinate x). Element
//! centres sit at `x_j = (j − Nx/2)·Δx`, `y_i = (i − Ny/2)·Δy`, so the origin is the centre
//! of element `(Ny/2, Nx/2)`: an indenter axis at the origin is centred on an element, which
//! keeps symmetric problems exactly symmetric about that element.

use thiserror::Error;

/// How the elastic half-space is continued outside the simulated rectangle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Boundary {
    /// A single contact on an infinite half-space (non-periodic, DC-FFT).
    Free,
    /// The rectangle is one period of an infinite periodic surface.
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
    /// memory indices: beyond it Nx·Ny wraps around.
    #[error("grid of n = {0} elements per side is too large: its element count (2n per side padded for a free boundary) overflows the index range")]
    TooManyElements(usize),
    /// The element sides and area must be normal floating-point numbers, or every stress
    /// and force of the grid is lost to underflow or overflow.
    #[error("grid element size size/n = {size:e}/{n} has an area Δ² = {area:e} outside the floating-point range: choose a grid size commensurate with n")]
    ElementOutOfRange {
        /// The side length L (of the axis at fault).
        size: f64,
        /// Elements along that side.
        n: usize,
        /// The element area Δx·Δy, 0 or ∞ when out of range.
        area: f64,
    },
}

/// An Nx×Ny grid of rectangular elements of sides `size_x / nx` and `size_y / ny`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    nx: usize,
    ny: usize,
    size_x: f64,
    size_y: f64,
    boundary: Boundary,
}

impl Grid {
    /// A grid of `n`×`n` elements covering a square of side `size`.
    ///
    /// # Example
    /// ```
    /// use adhesim::{Boundary, Grid};
    ///
    /// // 64 × 64 elements over a side of 1: Δ = 1/64, centres symmetric about the axis.
    /// let grid = Grid::new(64, 1.0, Boundary::Free)?;
    /// assert_eq!((grid.len(), grid.dx()), (4096, 1.0 / 64.0));
    /// let (x, y) = grid.centre(0);
    /// assert_eq!((x, y), (-0.5, -0.5));
    /// assert!(Grid::new(64, -1.0, Boundary::Free).is_err());
    /// # Ok::<(), adhesim::GridError>(())
    /// ```
    pub fn new(n: usize, size: f64, boundary: Boundary) -> Result<Self, GridError> {
        Self::rectangular(n, n, size, size, boundary)
    }

    /// A grid of `nx` columns (along x) and `ny` rows (along y) covering a rectangle of
    /// sides `size_x` × `size_y`.
    pub fn rectangular(nx: usize, ny: usize, size_x: f64, size_y: f64, boundary: Boundary) -> Result<Self, GridError> {
        for n in [nx, ny] {
            if n < 2 {
                return Err(GridError::TooFewElements(n));
            }
        }
        for size in [size_x, size_y] {
            if !(size.is_finite() && size > 0.0) {
                return Err(GridError::InvalidSize(size));
            }
        }
        let padding = match boundary {
            Boundary::Free => 2,
            Boundary::Periodic => 1,
        };
        let padded = nx
            .checked_mul(padding)
            .zip(ny.checked_mul(padding))
            .and_then(|(x, y)| x.checked_mul(y));
        if padded.is_none() {
            return Err(GridError::TooManyElements(nx.max(ny)));
        }
        let (dx, dy) = (size_x / nx as f64, size_y / ny as f64);
        let area = dx * dy;
        for (size, n, delta) in [(size_x, nx, dx), (size_y, ny, dy)] {
            if !(delta.is_normal() && area.is_normal()) {
                return Err(GridError::ElementOutOfRange { size, n, area });
            }
        }
        Ok(Self {
            nx,
            ny,
            size_x,
            size_y,
            boundary,
        })
    }

    /// Elements along x (columns), Nx.
    pub fn nx(&self) -> usize {
        self.nx
    }

    /// Elements along y (rows), Ny.
    pub fn ny(&self) -> usize {
        self.ny
    }

    /// True for Nx = Ny and Lx = Ly (square elements on a square).
    pub fn is_square(&self) -> bool {
        self.nx == self.ny && self.size_x == self.size_y
    }

    /// Total number of elements, Nx·Ny.
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// Always false: a grid has at least 2×2 elements.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Side length Lx along x.
    pub fn size_x(&self) -> f64 {
        self.size_x
    }

    /// Side length Ly along y.
    pub fn size_y(&self) -> f64 {
        self.size_y
    }

    /// Element side along x, Δx = Lx/Nx.
    pub fn dx(&self) -> f64 {
        self.size_x / self.nx as f64
    }

    /// Element side along y, Δy = Ly/Ny.
    pub fn dy(&self) -> f64 {
        self.size_y / self.ny as f64
    }

    /// Element area Δx·Δy.
    pub fn element_area(&self) -> f64 {
        self.dx() * self.dy()
    }

    /// Boundary condition of the half-space.
    pub fn boundary(&self) -> Boundary {
        self.boundary
    }

    /// Coordinate of the centre of column `column`: (column − Nx/2)·Δx.
    pub fn x(&self, column: usize) -> f64 {
        (column as f64 - (self.nx / 2) as f64) * self.dx()
    }

    /// Coordinate of the centre of row `row`: (row − Ny/2)·Δy.
    pub fn y(&self, row: usize) -> f64 {
        (row as f64 - (self.ny / 2) as f64) * self.dy()
    }

    /// Centre (x, y) of the element at flat index `k = row·Nx + column`.
    pub fn centre(&self, k: usize) -> (f64, f64) {
        (self.x(k % self.nx), self.y(k / self.nx))
    }

    /// True when the element touches the outer border of the rectangle.
    pub fn is_border(&self, k: usize) -> bool {
        let (row, column) = (k / self.nx, k % self.nx);
        row == 0 || column == 0 || row + 1 == self.ny || column + 1 == self.nx
    }

    /// Calls `visit` with the flat index of each edge-adjacent (4-)neighbour of element `k`.
    /// On a periodic grid the neighbours wrap around.
    #[inline]
    pub fn for_each_neighbour(&self, k: usize, mut visit: impl FnMut(usize)) {
        let (nx, ny) = (self.nx, self.ny);
        let (row, column) = (k / nx, k % nx);
        let periodic = self.boundary == Boundary::Periodic;
        if column > 0 {
            visit(k - 1);
        } else if periodic {
            visit(k + nx - 1);
        }
        if column + 1 < nx {
            visit(k + 1);
        } else if periodic {
            visit(k + 1 - nx);
        }
        if row > 0 {
            visit(k - nx);
        } else if periodic {
            visit(k + nx * (ny - 1));
        }
        if row + 1 < ny {
            visit(k + nx);
        } else if periodic {
            visit(k - nx * (ny - 1));
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
        // Second robustness audit (docs/reliability.md): n² wrapped to 0 elements at
        // n = 2³²; a subnormal element was accepted.
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
        assert_eq!(grid.x(4), 0.0);
        assert_eq!(grid.centre(4 * 8 + 4), (0.0, 0.0));
        assert_eq!(grid.y(0), -4.0);
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

    #[test]
    fn rectangles_have_their_own_spacings() {
        let grid = Grid::rectangular(6, 4, 3.0, 8.0, Boundary::Periodic).unwrap();
        assert_eq!((grid.nx(), grid.ny(), grid.len()), (6, 4, 24));
        assert_eq!((grid.dx(), grid.dy(), grid.element_area()), (0.5, 2.0, 1.0));
        assert!(!grid.is_square());
        // Element (row 2, column 3) is the origin; row 0 is y = −4, column 0 is x = −1.5.
        assert_eq!(grid.centre(2 * 6 + 3), (0.0, 0.0));
        assert_eq!(grid.centre(0), (-1.5, -4.0));
        let mut seen = Vec::new();
        grid.for_each_neighbour(0, |k| seen.push(k));
        seen.sort();
        assert_eq!(seen, vec![1, 5, 6, 18]);
        assert!(grid.is_border(5) && grid.is_border(18) && !grid.is_border(7));
        assert_eq!(
            Grid::rectangular(6, 1, 1.0, 1.0, Boundary::Free),
            Err(GridError::TooFewElements(1))
        );
        assert_eq!(
            Grid::rectangular(6, 4, 1.0, -1.0, Boundary::Free),
            Err(GridError::InvalidSize(-1.0))
        );
        assert_eq!(
            Grid::rectangular(1 << 20, 1 << 44, 1.0, 1.0, Boundary::Free),
            Err(GridError::TooManyElements(1 << 44))
        );
    }
}
