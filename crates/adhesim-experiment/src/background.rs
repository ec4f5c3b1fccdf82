//! The smooth background of uneven illumination: a quadratic surface least-squares fitted to
//! block means of the free surface of a frame.

use crate::{GrayImage, Roi};

/// The background fit works on means of BLOCK×BLOCK pixel blocks; a block is used only if it and
/// its 8 neighbours hold no provisional contact, which keeps the blurred contact edge (a few
/// pixels wide) out of the fit.
pub(crate) const BLOCK: usize = 8;

/// Quadratic background surface b(u,v) = c·[1, u, v, u², uv, v²] in centred, scaled
/// coordinates; `mean` is its mean over the frame (the corrected frame keeps raw units).
pub(crate) struct Surface {
    pub(crate) coeffs: [f64; 6],
    pub(crate) width: usize,
    pub(crate) height: usize,
    pub(crate) mean: f64,
}

fn basis(u: f64, v: f64) -> [f64; 6] {
    [1.0, u, v, u * u, u * v, v * v]
}

/// Block sums of the ROI pixels of a frame.
pub(crate) struct BlockGrid {
    pub(crate) nx: usize,
    pub(crate) ny: usize,
    /// (sum of values, pixel count, centre column, centre row) per block.
    blocks: Vec<(f64, usize, f64, f64)>,
    width: usize,
    height: usize,
}

impl BlockGrid {
    pub(crate) fn new(frame: &GrayImage, roi: Roi) -> Self {
        let (w, h) = (frame.width(), frame.height());
        let (nx, ny) = (w.div_ceil(BLOCK), h.div_ceil(BLOCK));
        let mut sums = vec![(0.0f64, 0usize); nx * ny];
        for y in roi.y0..roi.y0 + roi.height {
            let row = &frame.pixels()[y * w..(y + 1) * w];
            for bx in roi.x0 / BLOCK..(roi.x0 + roi.width).div_ceil(BLOCK) {
                let x0 = (bx * BLOCK).max(roi.x0);
                let x1 = ((bx + 1) * BLOCK).min(roi.x0 + roi.width);
                let s: f32 = row[x0..x1].iter().sum();
                let e = &mut sums[(y / BLOCK) * nx + bx];
                e.0 += f64::from(s);
                e.1 += x1 - x0;
            }
        }
        let blocks = sums
            .into_iter()
            .enumerate()
            .map(|(i, (s, n))| {
                let (bx, by) = (i % nx, i / nx);
                let cx = ((bx * BLOCK) as f64 + ((bx + 1) * BLOCK).min(w) as f64 - 1.0) / 2.0;
                let cy = ((by * BLOCK) as f64 + ((by + 1) * BLOCK).min(h) as f64 - 1.0) / 2.0;
                (s, n, cx, cy)
            })
            .collect();
        Self {
            nx,
            ny,
            blocks,
            width: w,
            height: h,
        }
    }

    /// Weighted least-squares quadratic through the means of the blocks that neither hold nor
    /// touch contact; `None` with too few such blocks or a singular system.
    #[allow(clippy::needless_range_loop)] // index form mirrors the matrix algebra
    pub(crate) fn fit(&self, contact: &[bool]) -> Option<Surface> {
        let mut normal = [[0.0f64; 6]; 6];
        let mut rhs = [0.0f64; 6];
        let mut used = 0usize;
        for by in 0..self.ny {
            for bx in 0..self.nx {
                let (sum, n, cx, cy) = self.blocks[by * self.nx + bx];
                if n == 0 {
                    continue;
                }
                let near_contact = (by.saturating_sub(1)..(by + 2).min(self.ny))
                    .any(|yy| (bx.saturating_sub(1)..(bx + 2).min(self.nx)).any(|xx| contact[yy * self.nx + xx]));
                if near_contact {
                    continue;
                }
                let b = basis(
                    (cx + 0.5) / self.width as f64 - 0.5,
                    (cy + 0.5) / self.height as f64 - 0.5,
                );
                let (mean, weight) = (sum / n as f64, n as f64);
                for i in 0..6 {
                    rhs[i] += weight * b[i] * mean;
                    for j in 0..=i {
                        normal[i][j] += weight * b[i] * b[j];
                    }
                }
                used += 1;
            }
        }
        if used < 12 {
            return None;
        }
        for i in 0..6 {
            for j in i + 1..6 {
                normal[i][j] = normal[j][i];
            }
        }
        let coeffs = solve6(normal, rhs)?;
        // Exact mean of the quadratic over the frame's pixel centres.
        // Mean of u² over k pixel centres u = (i + 0.5)/k − 0.5; u and uv average to 0.
        let mean_square = |k: usize| (1.0 - 1.0 / (k * k) as f64) / 12.0;
        let mean = coeffs[0] + coeffs[3] * mean_square(self.width) + coeffs[5] * mean_square(self.height);
        (mean.is_finite() && mean > 0.0).then_some(Surface {
            coeffs,
            width: self.width,
            height: self.height,
            mean,
        })
    }
}

/// Gaussian elimination with partial pivoting; `None` if singular.
#[allow(clippy::needless_range_loop)] // index form mirrors the matrix algebra
fn solve6(mut a: [[f64; 6]; 6], mut b: [f64; 6]) -> Option<[f64; 6]> {
    let scale = a.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    for col in 0..6 {
        let pivot = (col..6).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[pivot][col].abs() <= scale * 1e-12 {
            return None;
        }
        a.swap(col, pivot);
        b.swap(col, pivot);
        for row in col + 1..6 {
            let f = a[row][col] / a[col][col];
            for k in col..6 {
                a[row][k] -= f * a[col][k];
            }
            b[row] -= f * b[col];
        }
    }
    let mut x = [0.0; 6];
    for row in (0..6).rev() {
        let s: f64 = (row + 1..6).map(|k| a[row][k] * x[k]).sum();
        x[row] = (b[row] - s) / a[row][row];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}
