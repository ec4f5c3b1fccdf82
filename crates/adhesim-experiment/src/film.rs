//! Films of simulated runs: a run's contact set on its element grid, placed under the
//! camera's frame, becomes the contact mask the camera exposes ([`crate::Camera`]). Filmed
//! and analysed like an experiment, a run whose truth is known tests the whole analysis
//! (docs/experiments.md).

use crate::{invalid, ContactMask, ExperimentError};

/// A run's contact set: `nx` × `ny` elements of `dx` × `dy`, stored row by row along y
/// (row i, column j at index i·nx + j, as in `fields.npz`), element (i, j) centred at
/// ((j − nx/2)·dx, (i − ny/2)·dy) on the surface.
#[derive(Debug, Clone, Copy)]
pub struct GridContact<'a> {
    /// Elements along x.
    pub nx: usize,
    /// Elements along y.
    pub ny: usize,
    /// Element side along x.
    pub dx: f64,
    /// Element side along y.
    pub dy: f64,
    /// The contact set, `ny` rows of `nx`.
    pub contact: &'a [bool],
}

impl GridContact<'_> {
    /// The element whose cell holds the surface point (x, y), if the grid covers it.
    fn element_at(&self, x: f64, y: f64) -> Option<usize> {
        let j = (x / self.dx + self.nx as f64 / 2.0 + 0.5).floor();
        let i = (y / self.dy + self.ny as f64 / 2.0 + 0.5).floor();
        let inside = (0.0..self.nx as f64).contains(&j) && (0.0..self.ny as f64).contains(&i);
        inside.then(|| i as usize * self.nx + j as usize)
    }
}

/// Where the camera's frame lies on the surface: `width` × `height` pixels of `pixel_size`,
/// the frame's lower-left corner at `origin`. Columns run along +x, rows down along −y
/// (row 0 at the top), a pixel's coordinates those of its centre.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FilmFrame {
    /// Frame width in pixels.
    pub width: usize,
    /// Frame height in pixels.
    pub height: usize,
    /// Length per pixel (the run's length unit).
    pub pixel_size: f64,
    /// Surface coordinates of the frame's lower-left corner.
    pub origin: [f64; 2],
}

impl FilmFrame {
    /// A frame centred on `centre` with its corner moved to the nearest element corner of
    /// `grid`, so that pixels whose side divides the element's tile it exactly.
    pub fn centred(width: usize, height: usize, pixel_size: f64, centre: [f64; 2], grid: &GridContact<'_>) -> Self {
        let corner = |c: f64, pixels: usize, side: f64, n: usize| {
            let edge = c - pixels as f64 * pixel_size / 2.0;
            ((edge / side + n as f64 / 2.0 + 0.5).round() - n as f64 / 2.0 - 0.5) * side
        };
        Self {
            width,
            height,
            pixel_size,
            origin: [
                corner(centre[0], width, grid.dx, grid.nx),
                corner(centre[1], height, grid.dy, grid.ny),
            ],
        }
    }

    /// Checks the frame: sizes ≥ 1 pixel, a pixel size finite and > 0, a finite origin.
    pub fn validate(&self) -> Result<(), ExperimentError> {
        if self.width == 0 || self.height == 0 {
            return Err(invalid(
                "film.width×height",
                "must be >= 1",
                format!("{}×{}", self.width, self.height),
            ));
        }
        if !(self.pixel_size.is_finite() && self.pixel_size > 0.0) {
            return Err(invalid("film.pixel_size", "must be > 0", self.pixel_size));
        }
        if !self.origin.iter().all(|v| v.is_finite()) {
            return Err(invalid("film.origin", "must be finite", format!("{:?}", self.origin)));
        }
        Ok(())
    }

    /// The pixel coordinates (column, row) of the surface point (x, y).
    pub fn pixel_of(&self, [x, y]: [f64; 2]) -> [f64; 2] {
        [
            (x - self.origin[0]) / self.pixel_size - 0.5,
            self.height as f64 - 0.5 - (y - self.origin[1]) / self.pixel_size,
        ]
    }

    /// The surface point under the centre of pixel (column, row).
    pub fn surface_of(&self, column: usize, row: usize) -> [f64; 2] {
        [
            self.origin[0] + (column as f64 + 0.5) * self.pixel_size,
            self.origin[1] + (self.height as f64 - row as f64 - 0.5) * self.pixel_size,
        ]
    }

    /// The contact mask of `grid` in this frame: a pixel shows contact where its centre lies
    /// in an element in contact (outside the grid, none).
    pub fn mask(&self, grid: &GridContact<'_>) -> Result<ContactMask, ExperimentError> {
        self.validate()?;
        if grid.contact.len() != grid.nx * grid.ny {
            return Err(invalid(
                "film.contact",
                "must hold nx × ny elements",
                format!("{} for {}×{}", grid.contact.len(), grid.nx, grid.ny),
            ));
        }
        ContactMask::from_fn(self.width, self.height, |column, row| {
            let [x, y] = self.surface_of(column, row);
            grid.element_at(x, y).is_some_and(|k| grid.contact[k])
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{measure, Motion};

    /// A 6 × 4 grid of 0.5 × 0.25 elements with a 3 × 2 block in contact, filmed with
    /// pixels of 0.125 aligned to its elements: the mask's area is the block's exactly, and
    /// the front/rear split about an axis on an element edge is the elements' split.
    #[test]
    fn an_aligned_film_shows_the_elements_area_exactly() {
        let (nx, ny) = (6, 4);
        let mut contact = vec![false; nx * ny];
        for i in 1..3 {
            for j in 2..5 {
                contact[i * nx + j] = true;
            }
        }
        let grid = GridContact {
            nx,
            ny,
            dx: 0.5,
            dy: 0.25,
            contact: &contact,
        };
        let frame = FilmFrame::centred(40, 16, 0.125, [0.1, 0.0], &grid);
        let mask = frame.mask(&grid).unwrap();
        // Element j = 3 starts at x = (3 − 3 − 0.5)·0.5 = −0.25: the axis on that edge.
        let [column, row] = frame.pixel_of([-0.25, 0.0]);
        let area = measure(&mask, 0.125, Some(([column, row], Motion::PosX))).unwrap();
        assert_eq!(mask.count(), 6 * 4 * 2);
        assert!((area.area - 6.0 * 0.5 * 0.25).abs() < 1e-12, "{}", area.area);
        assert!(
            (area.area_front - 4.0 * 0.5 * 0.25).abs() < 1e-12,
            "{}",
            area.area_front
        );
    }

    #[test]
    fn a_frame_needs_pixels_and_a_pixel_size() {
        let contact = [true];
        let grid = GridContact {
            nx: 1,
            ny: 1,
            dx: 1.0,
            dy: 1.0,
            contact: &contact,
        };
        let frame = FilmFrame::centred(4, 4, 0.0, [0.0, 0.0], &grid);
        assert!(frame.mask(&grid).unwrap_err().to_string().contains("film.pixel_size"));
        let wrong = GridContact { nx: 2, ..grid };
        let frame = FilmFrame::centred(4, 4, 0.5, [0.0, 0.0], &wrong);
        assert!(frame.mask(&wrong).unwrap_err().to_string().contains("film.contact"));
    }
}
