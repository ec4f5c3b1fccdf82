//! Grey-level frames in memory.

use crate::{invalid, ExperimentError};

/// A grey-level frame, row-major, values as fractions of the sensor's full scale (0..1 for
/// frames converted from integer samples).
#[derive(Debug, Clone, PartialEq)]
pub struct GrayImage {
    width: usize,
    height: usize,
    pixels: Vec<f32>,
}

impl GrayImage {
    /// Wraps a row-major buffer; every value must be finite.
    pub fn new(width: usize, height: usize, pixels: Vec<f32>) -> Result<Self, ExperimentError> {
        check_size(width, height, pixels.len())?;
        if let Some(bad) = pixels.iter().find(|v| !v.is_finite()) {
            return Err(invalid("pixel value", "must be finite", bad));
        }
        Ok(Self { width, height, pixels })
    }

    /// Converts 8-bit samples (full scale 255).
    pub fn from_u8(width: usize, height: usize, samples: &[u8]) -> Result<Self, ExperimentError> {
        check_size(width, height, samples.len())?;
        let pixels = samples.iter().map(|&v| f32::from(v) * (1.0 / 255.0)).collect();
        Ok(Self { width, height, pixels })
    }

    /// Converts 16-bit samples (full scale 65535).
    pub fn from_u16(width: usize, height: usize, samples: &[u16]) -> Result<Self, ExperimentError> {
        check_size(width, height, samples.len())?;
        let pixels = samples.iter().map(|&v| f32::from(v) * (1.0 / 65535.0)).collect();
        Ok(Self { width, height, pixels })
    }

    /// Width in pixels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// Row-major pixel values.
    pub fn pixels(&self) -> &[f32] {
        &self.pixels
    }

    /// Mutable row-major pixel values.
    pub fn pixels_mut(&mut self) -> &mut [f32] {
        &mut self.pixels
    }

    /// Consumes the image, returning its buffer.
    pub fn into_pixels(self) -> Vec<f32> {
        self.pixels
    }

    /// Quantises to 8 bits (values clamped to 0..1).
    pub fn to_u8(&self) -> Vec<u8> {
        self.pixels
            .iter()
            .map(|&v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
            .collect()
    }

    /// Quantises to 16 bits (values clamped to 0..1).
    pub fn to_u16(&self) -> Vec<u16> {
        self.pixels
            .iter()
            .map(|&v| (v.clamp(0.0, 1.0) * 65535.0).round() as u16)
            .collect()
    }
}

pub(crate) fn check_size(width: usize, height: usize, len: usize) -> Result<(), ExperimentError> {
    let expected = width.saturating_mul(height);
    if width == 0 || height == 0 || expected != len {
        return Err(ExperimentError::BadImageSize {
            width,
            height,
            expected,
            actual: len,
        });
    }
    Ok(())
}

/// Rectangular region of interest in pixels: columns `x0..x0+width`, rows `y0..y0+height`.
/// Pixels outside never count as contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Roi {
    /// First column.
    pub x0: usize,
    /// First row.
    pub y0: usize,
    /// Number of columns.
    pub width: usize,
    /// Number of rows.
    pub height: usize,
}

impl Roi {
    /// The region clipped to an image of the given size; `None` if nothing is left.
    pub fn clipped(&self, width: usize, height: usize) -> Option<Roi> {
        let x1 = self.x0.saturating_add(self.width).min(width);
        let y1 = self.y0.saturating_add(self.height).min(height);
        (x1 > self.x0 && y1 > self.y0).then(|| Roi {
            x0: self.x0,
            y0: self.y0,
            width: x1 - self.x0,
            height: y1 - self.y0,
        })
    }

    /// Checks that the region lies wholly inside a `width`×`height` frame (`contact.roi`): a
    /// region reaching beyond it would be clipped silently and measure less than asked for.
    pub fn check_inside(&self, width: usize, height: usize) -> Result<(), ExperimentError> {
        let fits =
            |start: usize, len: usize, size: usize| len > 0 && start.checked_add(len).is_some_and(|end| end <= size);
        if fits(self.x0, self.width, width) && fits(self.y0, self.height, height) {
            return Ok(());
        }
        Err(ExperimentError::OutsideImage {
            name: "contact.roi",
            value: format!("[{}, {}, {}, {}]", self.x0, self.y0, self.width, self.height),
            width,
            height,
        })
    }

    /// The whole image.
    pub fn full(width: usize, height: usize) -> Roi {
        Roi {
            x0: 0,
            y0: 0,
            width,
            height,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Size checks reject mismatched buffers and non-finite values instead of panicking.
    #[test]
    fn rejects_bad_buffers() {
        assert!(GrayImage::new(2, 2, vec![0.0; 3]).is_err());
        assert!(GrayImage::new(0, 2, vec![]).is_err());
        assert!(GrayImage::new(1, 1, vec![f32::NAN]).is_err());
        let img = GrayImage::from_u16(2, 1, &[0, 65535]).unwrap();
        assert_eq!(img.pixels(), &[0.0, 1.0]);
        assert_eq!(img.to_u8(), vec![0, 255]);
    }

    /// Clipping keeps the part inside the image and drops regions fully outside.
    #[test]
    fn roi_clipping() {
        let r = Roi {
            x0: 5,
            y0: 5,
            width: 10,
            height: 10,
        };
        assert_eq!(
            r.clipped(8, 20),
            Some(Roi {
                x0: 5,
                y0: 5,
                width: 3,
                height: 10
            })
        );
        assert_eq!(r.clipped(5, 20), None);
    }
}
