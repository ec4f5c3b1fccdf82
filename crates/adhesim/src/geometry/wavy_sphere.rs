use super::{GeometryError, Profile, Sphere, Waviness};

/// The paper's indenter (Popov et al. 2021, Eq. 1): a paraboloid with superposed 2-D
/// waviness, z = (x² + y²)/(2R) + h·sin(2πx′/λ)·sin(2πy′/λ).
///
/// Heights are measured from the apex of the paraboloid, i.e. from the mean plane of the
/// waviness at the axis; the lowest point of the surface lies up to h below it, so the
/// indentation depth d of a wavy sphere is that of the underlying smooth sphere, which
/// is what the paper compares with JKR.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WavySphere {
    sphere: Sphere,
    waviness: Waviness,
}

impl WavySphere {
    /// Sphere of radius R with waviness of amplitude h, wavelength λ, rotated by `angle` radians.
    pub fn new(radius: f64, amplitude: f64, wavelength: f64, angle: f64) -> Result<Self, GeometryError> {
        Ok(Self {
            sphere: Sphere::new(radius)?,
            waviness: Waviness::new(amplitude, wavelength, angle)?,
        })
    }

    /// The underlying paraboloid.
    pub fn sphere(&self) -> &Sphere {
        &self.sphere
    }

    /// The waviness.
    pub fn waviness(&self) -> &Waviness {
        &self.waviness
    }
}

impl Profile for WavySphere {
    #[inline]
    fn height(&self, x: f64, y: f64) -> f64 {
        self.sphere.height(x, y) + self.waviness.height(x, y)
    }
    fn reach(&self, depth: f64) -> Option<f64> {
        self.sphere.reach(depth + self.waviness.amplitude().abs())
    }
    fn radius_of_curvature(&self) -> Option<f64> {
        Some(self.sphere.radius())
    }
    #[inline]
    fn slope_x(&self, x: f64, y: f64) -> f64 {
        self.sphere.slope_x(x, y) + self.waviness.slope_x(x, y)
    }
}
