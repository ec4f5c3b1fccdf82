//! Per-frame measurements of a contact mask.

use crate::{invalid, ContactMask, ExperimentError};

/// Direction of the indenter's motion in the image.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Motion {
    /// Towards increasing column.
    PosX,
    /// Towards decreasing column.
    NegX,
    /// Towards increasing row (down the image).
    PosY,
    /// Towards decreasing row.
    NegY,
}

impl Motion {
    /// Parses "+x", "-x", "+y", "-y".
    pub fn parse(text: &str) -> Option<Motion> {
        match text.trim() {
            "+x" | "x" => Some(Motion::PosX),
            "-x" => Some(Motion::NegX),
            "+y" | "y" => Some(Motion::PosY),
            "-y" => Some(Motion::NegY),
            _ => None,
        }
    }

    /// Unit vector (column, row) of the motion.
    pub fn direction(self) -> (f64, f64) {
        match self {
            Motion::PosX => (1.0, 0.0),
            Motion::NegX => (-1.0, 0.0),
            Motion::PosY => (0.0, 1.0),
            Motion::NegY => (0.0, -1.0),
        }
    }

    fn along_x(self) -> bool {
        matches!(self, Motion::PosX | Motion::NegX)
    }
}

/// Where the indenter centre is: it moves with the stage,
/// centre(stage_x) = centre_px + (stage_x − stage_x0)/pixel_size along the motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IndenterTrack {
    /// Pixel (column, row) of the centre when `stage_x = stage_x0`.
    pub centre_px: [f64; 2],
    /// Stage position at which the centre is at `centre_px`.
    pub stage_x0: f64,
    /// Direction of motion in the image for increasing stage_x.
    pub motion: Motion,
    /// Length per pixel (same unit as stage_x).
    pub pixel_size: f64,
}

impl IndenterTrack {
    /// Checks the parameters.
    pub fn new(centre_px: [f64; 2], stage_x0: f64, motion: Motion, pixel_size: f64) -> Result<Self, ExperimentError> {
        if !(pixel_size.is_finite() && pixel_size > 0.0) {
            return Err(invalid("frames.pixel_size", "must be > 0", pixel_size));
        }
        if !(centre_px.iter().all(|v| v.is_finite()) && stage_x0.is_finite()) {
            return Err(invalid(
                "indenter.centre_px",
                "must be finite",
                format!("{centre_px:?}"),
            ));
        }
        Ok(Self {
            centre_px,
            stage_x0,
            motion,
            pixel_size,
        })
    }

    /// Checks that the centre at `stage_x0` lies on a pixel of a `width`×`height` frame
    /// (`indenter.centre_px`; pixel centres are at integer coordinates 0 … width − 1): a centre
    /// outside puts the whole contact on one side of the front/rear line.
    pub fn check_inside(&self, width: usize, height: usize) -> Result<(), ExperimentError> {
        let [cx, cy] = self.centre_px;
        let on = |c: f64, size: usize| c >= 0.0 && c <= size as f64 - 1.0;
        if on(cx, width) && on(cy, height) {
            return Ok(());
        }
        Err(ExperimentError::OutsideImage {
            name: "indenter.centre_px",
            value: format!("[{cx}, {cy}]"),
            width,
            height,
        })
    }

    /// Centre (column, row) in pixels at stage position `stage_x`.
    pub fn centre_at(&self, stage_x: f64) -> [f64; 2] {
        let shift = (stage_x - self.stage_x0) / self.pixel_size;
        let (dx, dy) = self.motion.direction();
        [self.centre_px[0] + shift * dx, self.centre_px[1] + shift * dy]
    }
}

/// What one frame's contact mask measures. Lengths and areas in the units of `pixel_size`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AreaMeasurement {
    /// Contact pixels.
    pub pixels: usize,
    /// Contact area, pixels × pixel_size².
    pub area: f64,
    /// Area ahead of the indenter centre line (strictly beyond it in the direction of motion);
    /// 0 without a split.
    pub area_front: f64,
    /// The rest of the area (on or behind the centre line); equals `area` without a split.
    pub area_rear: f64,
    /// Centroid (column, row) in pixels; `None` without contact.
    pub centroid_px: Option<[f64; 2]>,
    /// Extent perpendicular to the motion, (max − min + 1) pixels × pixel_size; 0 without contact.
    pub width: f64,
    /// Extent along the motion, likewise.
    pub length: f64,
}

/// Measures a mask. `split` = (indenter centre in pixels, motion) for the front/rear split;
/// without it, the motion is taken as +x for width/length and everything counts as rear.
pub fn measure(
    mask: &ContactMask,
    pixel_size: f64,
    split: Option<([f64; 2], Motion)>,
) -> Result<AreaMeasurement, ExperimentError> {
    if !(pixel_size.is_finite() && pixel_size > 0.0) {
        return Err(invalid("frames.pixel_size", "must be > 0", pixel_size));
    }
    let motion = split.map_or(Motion::PosX, |(_, m)| m);
    let (w, h) = (mask.width(), mask.height());
    let (mut n, mut front, mut sx, mut sy) = (0usize, 0usize, 0.0f64, 0.0f64);
    let (mut xmin, mut xmax, mut ymin, mut ymax) = (usize::MAX, 0usize, usize::MAX, 0usize);
    for y in 0..h {
        let row = &mask.cells()[y * w..(y + 1) * w];
        let (mut row_n, mut row_sx) = (0usize, 0usize);
        let mut row_front = 0usize;
        // Front pixels of a row: a threshold on the column for ±x motion, the whole row or
        // nothing for ±y motion.
        let front_of = |x: usize| -> bool {
            match split {
                None => false,
                Some((c, Motion::PosX)) => x as f64 > c[0],
                Some((c, Motion::NegX)) => (x as f64) < c[0],
                Some((c, Motion::PosY)) => y as f64 > c[1],
                Some((c, Motion::NegY)) => (y as f64) < c[1],
            }
        };
        for (x, &cell) in row.iter().enumerate() {
            if cell != 0 {
                row_n += 1;
                row_sx += x;
                xmin = xmin.min(x);
                xmax = xmax.max(x);
                row_front += usize::from(front_of(x));
            }
        }
        if row_n > 0 {
            n += row_n;
            front += row_front;
            sx += row_sx as f64;
            sy += (y * row_n) as f64;
            ymin = ymin.min(y);
            ymax = ymax.max(y);
        }
    }
    let cell_area = pixel_size * pixel_size;
    if n == 0 {
        return Ok(AreaMeasurement::default());
    }
    let (extent_x, extent_y) = (
        (xmax - xmin + 1) as f64 * pixel_size,
        (ymax - ymin + 1) as f64 * pixel_size,
    );
    let (width, length) = if motion.along_x() {
        (extent_y, extent_x)
    } else {
        (extent_x, extent_y)
    };
    Ok(AreaMeasurement {
        pixels: n,
        area: n as f64 * cell_area,
        area_front: front as f64 * cell_area,
        area_rear: (n - front) as f64 * cell_area,
        centroid_px: Some([sx / n as f64, sy / n as f64]),
        width,
        length,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn disc(w: usize, h: usize, cx: f64, cy: f64, r: f64) -> ContactMask {
        ContactMask::from_fn(w, h, |x, y| (x as f64 - cx).powi(2) + (y as f64 - cy).powi(2) <= r * r).unwrap()
    }

    /// Front/rear split of a disc centred on the indenter centre line is exact: with the line
    /// between pixel columns the halves are equal to the pixel; with the line through a pixel
    /// column, that column goes to the rear and front = rear − column, again exactly. Checked
    /// for all four motion directions (symmetry of the disc makes them equal).
    #[test]
    fn front_rear_split_exact_for_centred_disc() {
        let mask = disc(200, 160, 99.5, 79.5, 40.0);
        for motion in [Motion::PosX, Motion::NegX, Motion::PosY, Motion::NegY] {
            let m = measure(&mask, 0.5, Some(([99.5, 79.5], motion))).unwrap();
            assert_eq!(m.pixels % 2, 0);
            assert_eq!(m.area_front, m.area_rear, "{motion:?}");
            assert_eq!(m.area_front + m.area_rear, m.area);
        }
        let mask = disc(200, 160, 100.0, 80.0, 40.0);
        let column = (0..160).filter(|&y| mask.get(100, y)).count() as f64;
        for motion in [Motion::PosX, Motion::NegX] {
            let m = measure(&mask, 1.0, Some(([100.0, 80.0], motion))).unwrap();
            assert_eq!(m.area_front + column, m.area_rear, "{motion:?}");
        }
        let m = measure(&mask, 1.0, Some(([100.0, 80.0], Motion::PosX))).unwrap();
        assert_eq!(m.width, 81.0);
        assert_eq!(m.length, 81.0);
        assert_eq!(m.centroid_px, Some([100.0, 80.0]));
    }

    /// The centre line moves with the stage: shifting the stage by k pixel sizes moves it by k
    /// pixels along the motion (exact arithmetic on these values).
    #[test]
    fn centre_follows_stage() {
        let track = IndenterTrack::new([10.0, 20.0], 1.0, Motion::NegY, 0.25).unwrap();
        assert_eq!(track.centre_at(2.0), [10.0, 16.0]);
        assert!(IndenterTrack::new([0.0, 0.0], 0.0, Motion::PosX, -1.0)
            .unwrap_err()
            .to_string()
            .contains("frames.pixel_size must be > 0, got -1"));
    }

    /// An empty mask measures zero everywhere (no NaN centroid).
    #[test]
    fn empty_mask_is_zero() {
        let m = measure(&ContactMask::empty(4, 4).unwrap(), 1.0, None).unwrap();
        assert_eq!(m, AreaMeasurement::default());
    }
}
