use super::{positive, GeometryError, Profile};

/// Flat-ended rigid cylinder of radius a: z = 0 for r ≤ a, no surface outside
/// (height +∞), so the contact is the face's element centres inside the circle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlatPunch {
    radius: f64,
}

impl FlatPunch {
    /// A punch of face radius `radius` (> 0).
    pub fn new(radius: f64) -> Result<Self, GeometryError> {
        Ok(Self {
            radius: positive("radius", radius)?,
        })
    }

    /// Face radius a.
    pub fn radius(&self) -> f64 {
        self.radius
    }
}

impl Profile for FlatPunch {
    #[inline]
    fn height(&self, x: f64, y: f64) -> f64 {
        if x * x + y * y <= self.radius * self.radius {
            0.0
        } else {
            f64::INFINITY
        }
    }
    fn slope_x(&self, _x: f64, _y: f64) -> f64 {
        0.0
    }
    fn reach(&self, _depth: f64) -> Option<f64> {
        Some(self.radius)
    }
}
