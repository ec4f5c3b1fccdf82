use super::{positive, GeometryError, Profile};

/// A measured or generated height map, sampled on a regular rows×columns lattice of
/// spacing `spacing` whose centre sits on the indenter axis; heights between samples are
/// bilinearly interpolated (so sub-sample offsets move the surface continuously), and
/// outside the map the height is +∞ (no surface).
#[derive(Debug, Clone, PartialEq)]
pub struct Topography {
    heights: Vec<f64>,
    rows: usize,
    columns: usize,
    spacing: f64,
}

impl Topography {
    /// Wraps a row-major height map; the heights are shifted so that the lowest is zero.
    pub fn new(heights: Vec<f64>, rows: usize, columns: usize, spacing: f64) -> Result<Self, GeometryError> {
        positive("spacing", spacing)?;
        if rows < 2 || columns < 2 || heights.len() != rows * columns {
            return Err(GeometryError::Topography(format!(
                "need a rows×columns map with rows, columns >= 2; got {} values for {rows}×{columns}",
                heights.len()
            )));
        }
        if let Some(bad) = heights.iter().position(|h| !h.is_finite()) {
            return Err(GeometryError::Topography(format!(
                "height at index {bad} is not finite ({})",
                heights[bad]
            )));
        }
        let lowest = heights.iter().cloned().fold(f64::INFINITY, f64::min);
        let heights = heights.into_iter().map(|h| h - lowest).collect();
        Ok(Self {
            heights,
            rows,
            columns,
            spacing,
        })
    }

    /// (rows, columns) of the map.
    pub fn shape(&self) -> (usize, usize) {
        (self.rows, self.columns)
    }
}

impl Profile for Topography {
    fn height(&self, x: f64, y: f64) -> f64 {
        let column = x / self.spacing + (self.columns - 1) as f64 / 2.0;
        let row = y / self.spacing + (self.rows - 1) as f64 / 2.0;
        if !(column >= 0.0 && row >= 0.0) || column > (self.columns - 1) as f64 || row > (self.rows - 1) as f64 {
            return f64::INFINITY;
        }
        let (c0, r0) = (
            (column as usize).min(self.columns - 2),
            (row as usize).min(self.rows - 2),
        );
        let (fc, fr) = (column - c0 as f64, row - r0 as f64);
        let at = |r: usize, c: usize| self.heights[r * self.columns + c];
        (1.0 - fr) * ((1.0 - fc) * at(r0, c0) + fc * at(r0, c0 + 1))
            + fr * ((1.0 - fc) * at(r0 + 1, c0) + fc * at(r0 + 1, c0 + 1))
    }
    fn reach(&self, _depth: f64) -> Option<f64> {
        let half = 0.5 * self.spacing * (self.rows.max(self.columns) - 1) as f64;
        Some(half * std::f64::consts::SQRT_2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolates_between_samples() {
        let map = Topography::new(vec![1.0, 2.0, 3.0, 4.0], 2, 2, 1.0).unwrap();
        // centre of a 2x2 map of spacing 1 is the middle of the four samples
        assert!((map.height(0.0, 0.0) - 1.5).abs() < 1e-15);
        assert!((map.height(-0.5, -0.5) - 0.0).abs() < 1e-15);
        assert!(map.height(2.0, 0.0).is_infinite());
        assert!(Topography::new(vec![1.0, f64::NAN, 0.0, 0.0], 2, 2, 1.0).is_err());
    }
}
