//! Binary contact masks and their morphological cleaning (opening, closing).

use crate::image::check_size;
use crate::{ExperimentError, Roi};

/// Binary contact mask, row-major, one byte per pixel (1 = contact).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ContactMask {
    width: usize,
    height: usize,
    cells: Vec<u8>,
}

impl ContactMask {
    /// Wraps cells whose length the caller has checked.
    pub(crate) fn from_parts(width: usize, height: usize, cells: Vec<u8>) -> Self {
        debug_assert_eq!(cells.len(), width * height);
        Self { width, height, cells }
    }

    /// An all-free mask.
    pub fn empty(width: usize, height: usize) -> Result<Self, ExperimentError> {
        check_size(width, height, width.saturating_mul(height))?;
        Ok(Self {
            width,
            height,
            cells: vec![0; width * height],
        })
    }

    /// Builds a mask from a predicate on pixel (column, row).
    pub fn from_fn(
        width: usize,
        height: usize,
        mut in_contact: impl FnMut(usize, usize) -> bool,
    ) -> Result<Self, ExperimentError> {
        let mut mask = Self::empty(width, height)?;
        for y in 0..height {
            for x in 0..width {
                mask.cells[y * width + x] = u8::from(in_contact(x, y));
            }
        }
        Ok(mask)
    }

    /// Wraps row-major cells; any non-zero value counts as contact.
    pub fn from_cells(width: usize, height: usize, cells: Vec<u8>) -> Result<Self, ExperimentError> {
        check_size(width, height, cells.len())?;
        let cells = cells.into_iter().map(|c| u8::from(c != 0)).collect();
        Ok(Self { width, height, cells })
    }

    /// Width in pixels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// Row-major cells, 1 = contact, 0 = free.
    pub fn cells(&self) -> &[u8] {
        &self.cells
    }

    /// Whether pixel (column `x`, row `y`) is in contact; `false` outside the image.
    pub fn get(&self, x: usize, y: usize) -> bool {
        x < self.width && y < self.height && self.cells[y * self.width + x] != 0
    }

    /// Number of contact pixels.
    pub fn count(&self) -> usize {
        self.cells.iter().map(|&c| c as usize).sum()
    }

    /// Morphological opening (erosion then dilation) with a (2r+1)² square: removes specks
    /// narrower than 2r+1 pixels. Windows are clipped at the image border.
    pub fn open(&self, radius: usize) -> ContactMask {
        let mut mask = self.clone();
        mask.open_in_place(radius);
        mask
    }

    /// Morphological closing (dilation then erosion): fills holes narrower than 2r+1 pixels.
    pub fn close(&self, radius: usize) -> ContactMask {
        let mut mask = self.clone();
        mask.close_in_place(radius);
        mask
    }

    /// Dilation with a (2r+1)² square.
    pub fn dilate(&self, radius: usize) -> ContactMask {
        self.filtered(radius, Window::Dilate)
    }

    pub(crate) fn open_in_place(&mut self, radius: usize) {
        self.filter_in_place(radius, Window::Erode);
        self.filter_in_place(radius, Window::Dilate);
    }

    pub(crate) fn close_in_place(&mut self, radius: usize) {
        self.filter_in_place(radius, Window::Dilate);
        self.filter_in_place(radius, Window::Erode);
    }

    fn filtered(&self, radius: usize, window: Window) -> ContactMask {
        let mut mask = self.clone();
        mask.filter_in_place(radius, window);
        mask
    }

    /// Square-window min/max filter (windows clipped at the border), separable. Small radii
    /// OR/AND shifted rows (vectorises well) in place with a reused per-thread buffer; larger
    /// ones use running counts, O(pixels).
    fn filter_in_place(&mut self, radius: usize, window: Window) {
        if radius == 0 {
            return;
        }
        if radius > SHIFT_FILTER_MAX_RADIUS {
            *self = self.counting_filtered(radius, window);
            return;
        }
        let (w, h) = (self.width, self.height);
        let combine = |dst: &mut [u8], src: &[u8]| match window {
            Window::Dilate => dst.iter_mut().zip(src).for_each(|(d, s)| *d |= s),
            Window::Erode => dst.iter_mut().zip(src).for_each(|(d, s)| *d &= s),
        };
        BYTE_WORK.with(|work| {
            let mut src = work.borrow_mut();
            src.clear();
            src.extend_from_slice(&self.cells);
            for (dst, row) in self.cells.chunks_exact_mut(w).zip(src.chunks_exact(w)) {
                for d in 1..=radius.min(w - 1) {
                    combine(&mut dst[..w - d], &row[d..]);
                    combine(&mut dst[d..], &row[..w - d]);
                }
            }
            src.clear();
            src.extend_from_slice(&self.cells);
            for d in 1..=radius.min(h - 1) {
                combine(&mut self.cells[..(h - d) * w], &src[d * w..]);
                combine(&mut self.cells[d * w..], &src[..(h - d) * w]);
            }
        });
    }

    fn counting_filtered(&self, radius: usize, window: Window) -> ContactMask {
        let (w, h) = (self.width, self.height);
        let decide = |count: usize, len: usize| match window {
            Window::Dilate => count > 0,
            Window::Erode => count == len,
        };
        let mut rows = vec![0u8; w * h];
        for y in 0..h {
            let src = &self.cells[y * w..(y + 1) * w];
            let dst = &mut rows[y * w..(y + 1) * w];
            let mut count: usize = src[..radius.min(w)].iter().map(|&c| c as usize).sum();
            for x in 0..w {
                if x + radius < w {
                    count += src[x + radius] as usize;
                }
                if x > radius {
                    count -= src[x - radius - 1] as usize;
                }
                let len = (x + radius).min(w - 1) + 1 - x.saturating_sub(radius);
                dst[x] = u8::from(decide(count, len));
            }
        }
        let mut out = vec![0u8; w * h];
        let mut counts = vec![0usize; w];
        for y in 0..radius.min(h) {
            for (c, &v) in counts.iter_mut().zip(&rows[y * w..(y + 1) * w]) {
                *c += v as usize;
            }
        }
        for y in 0..h {
            if y + radius < h {
                let add = &rows[(y + radius) * w..(y + radius + 1) * w];
                for (c, &v) in counts.iter_mut().zip(add) {
                    *c += v as usize;
                }
            }
            if y > radius {
                let sub = &rows[(y - radius - 1) * w..(y - radius) * w];
                for (c, &v) in counts.iter_mut().zip(sub) {
                    *c -= v as usize;
                }
            }
            let len = (y + radius).min(h - 1) + 1 - y.saturating_sub(radius);
            for (o, &c) in out[y * w..(y + 1) * w].iter_mut().zip(&counts) {
                *o = u8::from(decide(c, len));
            }
        }
        ContactMask {
            width: w,
            height: h,
            cells: out,
        }
    }
}

thread_local! {
    /// Per-thread work buffers reused across frames: allocating tens of MB per 1600×1200
    /// frame afresh made page faults about a third of the analysis time.
    static BYTE_WORK: std::cell::RefCell<Vec<u8>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// Up to this radius the shifted-row filter beats running counts.
const SHIFT_FILTER_MAX_RADIUS: usize = 4;

#[derive(Clone, Copy)]
enum Window {
    Erode,
    Dilate,
}

impl ContactMask {
    /// The mask with everything outside `roi` cleared.
    pub(crate) fn restricted(mut self, roi: Roi) -> ContactMask {
        if roi == Roi::full(self.width, self.height) {
            return self;
        }
        for y in 0..self.height {
            for x in 0..self.width {
                let inside = x >= roi.x0 && x < roi.x0 + roi.width && y >= roi.y0 && y < roi.y0 + roi.height;
                if !inside {
                    self.cells[y * self.width + x] = 0;
                }
            }
        }
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn brute(mask: &ContactMask, r: usize, erode: bool) -> ContactMask {
        let (w, h) = (mask.width() as isize, mask.height() as isize);
        ContactMask::from_fn(mask.width(), mask.height(), |x, y| {
            let mut any = false;
            let mut all = true;
            for dy in -(r as isize)..=r as isize {
                for dx in -(r as isize)..=r as isize {
                    let (xx, yy) = (x as isize + dx, y as isize + dy);
                    if xx < 0 || yy < 0 || xx >= w || yy >= h {
                        continue;
                    }
                    let v = mask.get(xx as usize, yy as usize);
                    any |= v;
                    all &= v;
                }
            }
            if erode {
                all
            } else {
                any
            }
        })
        .unwrap()
    }

    /// Both filter implementations (shifted rows for r ≤ 4, running counts above) equal a
    /// brute-force window min/max exactly (pixel logic, no tolerance) on a pseudo-random mask,
    /// including border pixels.
    #[test]
    fn running_filters_match_brute_force() {
        let mut state = 12345u64;
        let mask = ContactMask::from_fn(23, 17, |_, _| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state % 3 >= 1
        })
        .unwrap();
        for r in 1..8 {
            assert_eq!(mask.filtered(r, Window::Erode), brute(&mask, r, true), "erode r={r}");
            assert_eq!(mask.filtered(r, Window::Dilate), brute(&mask, r, false), "dilate r={r}");
        }
    }

    /// Opening removes an isolated speck and closing fills a pinhole; a solid block survives
    /// both unchanged (exact).
    #[test]
    fn open_and_close_clean() {
        let block = |x: usize, y: usize| (5..15).contains(&x) && (5..15).contains(&y);
        let mask = ContactMask::from_fn(20, 20, |x, y| (block(x, y) && (x, y) != (9, 9)) || (x, y) == (1, 1)).unwrap();
        let cleaned = mask.open(1).close(1);
        assert_eq!(cleaned, ContactMask::from_fn(20, 20, block).unwrap());
    }
}
