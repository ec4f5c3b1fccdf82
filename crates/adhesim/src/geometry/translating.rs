use super::{GeometryError, Profile, Waviness, WavySphere};
use crate::grid::Grid;
use std::sync::Arc;

/// How a rough rigid indenter moves over the half-space (docs/physics.md §5; paper Sect. 3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Kinematics {
    /// The whole profile translates over a smooth half-space. Translation invariance
    /// makes this frictionless: the control case.
    Translate,
    /// Rolling without slip: the sphere's roughness is laid onto the ground, so the
    /// waviness stays fixed relative to the half-space while the paraboloid moves.
    Roll,
    /// Sliding of a rough sphere over a rough half-space: the whole indenter moves and the
    /// substrate carries its own waviness (the same, rotated by `substrate_angle` radians,
    /// so that the two are incommensurate).
    Slide {
        /// Rotation of the substrate's waviness axes against the indenter's.
        substrate_angle: f64,
    },
}

/// A wavy sphere moving laterally by X over the half-space with given kinematics: the
/// gap profile z(x, y; X) and the moving part whose slope gives the tangential force.
///
/// A slide's substrate may also carry a roughness map h_s (one height per element of the
/// grid, peaks towards the indenter, [`Self::with_substrate_roughness`]): it is fixed to
/// the half-space, so it lowers the gap by h_s at each element centre and adds nothing to
/// the moving slope.
#[derive(Debug, Clone, PartialEq)]
pub struct TranslatingContact {
    indenter: WavySphere,
    kinematics: Kinematics,
    substrate: Option<Waviness>,
    substrate_roughness: Option<Arc<[f64]>>,
}

impl TranslatingContact {
    /// Builds the contact; a slide adds the rotated substrate waviness.
    pub fn new(indenter: WavySphere, kinematics: Kinematics) -> Self {
        let substrate = match kinematics {
            Kinematics::Slide { substrate_angle } => {
                let w = indenter.waviness();
                Waviness::new(w.amplitude(), w.wavelength(), w.angle() + substrate_angle).ok()
            }
            _ => None,
        };
        Self {
            indenter,
            kinematics,
            substrate,
            substrate_roughness: None,
        }
    }

    /// Adds a substrate roughness map (row-major, one finite value per element of `grid`,
    /// peaks positive) to a slide. Other kinematics have a smooth half-space: an error.
    pub fn with_substrate_roughness(mut self, roughness: Vec<f64>, grid: &Grid) -> Result<Self, GeometryError> {
        if !matches!(self.kinematics, Kinematics::Slide { .. }) {
            return Err(GeometryError::Topography(
                "a substrate roughness needs sliding kinematics (the half-space of roll and translate is smooth)"
                    .to_string(),
            ));
        }
        if roughness.len() != grid.len() {
            return Err(GeometryError::Topography(format!(
                "substrate roughness has {} values, the grid has {} elements",
                roughness.len(),
                grid.len()
            )));
        }
        if let Some(bad) = roughness.iter().position(|h| !h.is_finite()) {
            return Err(GeometryError::Topography(format!(
                "substrate roughness at index {bad} is not finite ({})",
                roughness[bad]
            )));
        }
        self.substrate_roughness = Some(roughness.into());
        Ok(self)
    }

    /// The substrate roughness map, if any.
    pub fn substrate_roughness(&self) -> Option<&[f64]> {
        self.substrate_roughness.as_deref()
    }

    /// The indenter.
    pub fn indenter(&self) -> &WavySphere {
        &self.indenter
    }

    /// The kinematics.
    pub fn kinematics(&self) -> Kinematics {
        self.kinematics
    }

    /// Gap profile z at (x, y) with the indenter axis at (X, 0).
    #[inline]
    pub fn height(&self, x: f64, y: f64, offset: f64) -> f64 {
        match self.kinematics {
            Kinematics::Translate => self.indenter.height(x - offset, y),
            Kinematics::Roll => self.indenter.sphere().height(x - offset, y) + self.indenter.waviness().height(x, y),
            Kinematics::Slide { .. } => {
                self.indenter.height(x - offset, y) + self.substrate.as_ref().map_or(0.0, |w| w.height(x, y))
            }
        }
    }

    /// ∂z_moving/∂x at (x, y): the slope of the part of the profile that moves with X.
    #[inline]
    pub fn moving_slope_x(&self, x: f64, y: f64, offset: f64) -> f64 {
        match self.kinematics {
            Kinematics::Roll => self.indenter.sphere().slope_x(x - offset, y),
            Kinematics::Translate | Kinematics::Slide { .. } => self.indenter.slope_x(x - offset, y),
        }
    }

    /// Fills `heights` at every element centre for the axis at X = `offset` (minus the
    /// substrate roughness of a slide, which must be sampled on this grid).
    pub fn fill_heights(&self, grid: &Grid, offset: f64, heights: &mut [f64]) {
        assert_eq!(heights.len(), grid.len(), "heights buffer does not match the grid");
        for (k, height) in heights.iter_mut().enumerate() {
            let (x, y) = grid.centre(k);
            *height = self.height(x, y, offset);
        }
        if let Some(roughness) = &self.substrate_roughness {
            assert_eq!(
                roughness.len(),
                grid.len(),
                "substrate roughness does not match the grid"
            );
            heights.iter_mut().zip(roughness.iter()).for_each(|(z, h)| *z -= h);
        }
    }

    /// F_T = Δ²Σ_C p·∂z_moving/∂x: the force needed to keep moving in +x at fixed contact
    /// set, equal to dΠ/dX (docs/physics.md §5); positive resists the motion.
    pub fn tangential_force(&self, grid: &Grid, pressure: &[f64], offset: f64) -> f64 {
        let mut force = 0.0;
        for (k, &p) in pressure.iter().enumerate() {
            if p != 0.0 {
                let (x, y) = grid.centre(k);
                force += p * self.moving_slope_x(x, y, offset);
            }
        }
        force * grid.element_area()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn substrate_roughness_lowers_the_gap_of_a_slide_only() {
        let grid = Grid::new(4, 1.0, crate::grid::Boundary::Free).unwrap();
        let indenter = WavySphere::new(1.0, 0.01, 0.25, 0.0).unwrap();
        let roughness: Vec<f64> = (0..16).map(|k| 1e-3 * k as f64).collect();
        let slide = TranslatingContact::new(indenter, Kinematics::Slide { substrate_angle: 0.3 });
        let rough = slide
            .clone()
            .with_substrate_roughness(roughness.clone(), &grid)
            .unwrap();
        let (mut smooth_gap, mut rough_gap) = (vec![0.0; 16], vec![0.0; 16]);
        slide.fill_heights(&grid, 0.1, &mut smooth_gap);
        rough.fill_heights(&grid, 0.1, &mut rough_gap);
        for k in 0..16 {
            assert_eq!(rough_gap[k], smooth_gap[k] - roughness[k]);
        }
        // fixed to the half-space: no change of the moving slope
        assert_eq!(rough.moving_slope_x(0.1, 0.2, 0.1), slide.moving_slope_x(0.1, 0.2, 0.1));
        let roll = TranslatingContact::new(indenter, Kinematics::Roll);
        assert!(roll.with_substrate_roughness(roughness.clone(), &grid).is_err());
        assert!(slide.clone().with_substrate_roughness(vec![0.0; 15], &grid).is_err());
        assert!(slide.with_substrate_roughness(vec![f64::NAN; 16], &grid).is_err());
    }

    #[test]
    fn slopes_match_finite_differences() {
        let indenter = WavySphere::new(1.0, 0.01, 0.1, 0.3).unwrap();
        for kinematics in [
            Kinematics::Translate,
            Kinematics::Roll,
            Kinematics::Slide { substrate_angle: 0.5 },
        ] {
            let contact = TranslatingContact::new(indenter, kinematics);
            let (x, y, offset) = (0.037, -0.021, 0.013);
            let h = 1e-6;
            // moving part only: difference in X at fixed (x, y) is −∂z_mov/∂x
            let numeric = -(contact.height(x, y, offset + h) - contact.height(x, y, offset - h)) / (2.0 * h);
            let analytic = contact.moving_slope_x(x, y, offset);
            assert!(
                (numeric - analytic).abs() < 1e-6 * analytic.abs().max(1.0),
                "{kinematics:?}"
            );
        }
    }
}
