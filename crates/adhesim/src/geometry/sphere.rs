use super::{positive, GeometryError, Profile};

/// Paraboloid z = (x² + y²)/(2R): the sphere of radius R in the small-slope limit of
/// Hertz and JKR theory.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere {
    radius: f64,
}

impl Sphere {
    /// A sphere of radius `radius` (> 0).
    pub fn new(radius: f64) -> Result<Self, GeometryError> {
        Ok(Self {
            radius: positive("radius", radius)?,
        })
    }

    /// Radius R.
    pub fn radius(&self) -> f64 {
        self.radius
    }
}

impl Profile for Sphere {
    #[inline]
    fn height(&self, x: f64, y: f64) -> f64 {
        (x * x + y * y) / (2.0 * self.radius)
    }
    fn reach(&self, depth: f64) -> Option<f64> {
        Some((2.0 * self.radius * depth.max(0.0)).sqrt())
    }
    fn radius_of_curvature(&self) -> Option<f64> {
        Some(self.radius)
    }
    #[inline]
    fn slope_x(&self, x: f64, _y: f64) -> f64 {
        x / self.radius
    }
}
