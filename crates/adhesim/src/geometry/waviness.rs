use super::{finite, positive, GeometryError, Profile};

/// The paper's 2-D waviness h·sin(2πx′/λ)·sin(2πy′/λ) (Popov et al. 2021, Eq. 1), with
/// (x′, y′) the coordinates rotated by `angle` (radians) against the grid axes.
/// Zero mean; values in [−h, h].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Waviness {
    amplitude: f64,
    wavelength: f64,
    angle: f64,
    cos_angle: f64,
    sin_angle: f64,
}

impl Waviness {
    /// Waviness of amplitude h, wavelength λ, axes rotated by `angle` radians.
    pub fn new(amplitude: f64, wavelength: f64, angle: f64) -> Result<Self, GeometryError> {
        finite("amplitude", amplitude)?;
        positive("wavelength", wavelength)?;
        finite("angle", angle)?;
        Ok(Self {
            amplitude,
            wavelength,
            angle,
            cos_angle: angle.cos(),
            sin_angle: angle.sin(),
        })
    }

    /// Amplitude h.
    pub fn amplitude(&self) -> f64 {
        self.amplitude
    }

    /// Wavelength λ.
    pub fn wavelength(&self) -> f64 {
        self.wavelength
    }

    /// Rotation of the waviness axes in radians.
    pub fn angle(&self) -> f64 {
        self.angle
    }
}

impl Profile for Waviness {
    #[inline]
    fn height(&self, x: f64, y: f64) -> f64 {
        let along = self.cos_angle * x + self.sin_angle * y;
        let across = -self.sin_angle * x + self.cos_angle * y;
        let wavenumber = std::f64::consts::TAU / self.wavelength;
        self.amplitude * (wavenumber * along).sin() * (wavenumber * across).sin()
    }
    fn reach(&self, _depth: f64) -> Option<f64> {
        None
    }
    #[inline]
    fn slope_x(&self, x: f64, y: f64) -> f64 {
        let along = self.cos_angle * x + self.sin_angle * y;
        let across = -self.sin_angle * x + self.cos_angle * y;
        let k = std::f64::consts::TAU / self.wavelength;
        // d/dx of h·sin(k·along)·sin(k·across), along_x = cos θ, across_x = −sin θ
        self.amplitude
            * k
            * (self.cos_angle * (k * along).cos() * (k * across).sin()
                - self.sin_angle * (k * along).sin() * (k * across).cos())
    }
}
