use super::{finite, positive, GeometryError, Profile};

/// Flat punch with an elliptic face of semi-axes a (along x′) and b (along y′), the axes
/// rotated by `angle` radians against the grid (paper Sect. 3.2, Fig. 12).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EllipticPunch {
    semi_axes: (f64, f64),
    angle: f64,
}

impl EllipticPunch {
    /// A punch with semi-axes `(a, b)` rotated by `angle` radians.
    pub fn new(semi_axes: (f64, f64), angle: f64) -> Result<Self, GeometryError> {
        positive("semi_axes[0]", semi_axes.0)?;
        positive("semi_axes[1]", semi_axes.1)?;
        finite("angle", angle)?;
        Ok(Self { semi_axes, angle })
    }

    /// Semi-axes (a, b).
    pub fn semi_axes(&self) -> (f64, f64) {
        self.semi_axes
    }
}

impl Profile for EllipticPunch {
    #[inline]
    fn height(&self, x: f64, y: f64) -> f64 {
        let (sin, cos) = self.angle.sin_cos();
        let along = (cos * x + sin * y) / self.semi_axes.0;
        let across = (-sin * x + cos * y) / self.semi_axes.1;
        if along * along + across * across <= 1.0 {
            0.0
        } else {
            f64::INFINITY
        }
    }
    fn slope_x(&self, _x: f64, _y: f64) -> f64 {
        0.0
    }
    fn reach(&self, _depth: f64) -> Option<f64> {
        Some(self.semi_axes.0.max(self.semi_axes.1))
    }
}
