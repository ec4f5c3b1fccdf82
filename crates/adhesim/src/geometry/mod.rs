//! Indenter profiles.
//!
//! A profile is the height z(x, y) ≥ 0 of the rigid indenter surface above the reference
//! point of its axis (the apex of the underlying paraboloid, or the face of a punch),
//! for an indenter whose axis sits at the origin. Every profile is evaluated analytically
//! at any lateral offset of the axis (rolling and sliding move the indenter by sub-element
//! distances), never by shifting arrays. Heights are `f64::INFINITY` where the indenter
//! has no surface (outside a flat punch): such elements can never come into contact.

mod elliptic_punch;
mod flat_punch;
mod rough;
mod sphere;
mod topography;
mod translating;
mod waviness;
mod wavy_sphere;

pub use elliptic_punch::EllipticPunch;
pub use flat_punch::FlatPunch;
pub use rough::{RoughBase, RoughProfile};
pub use sphere::Sphere;
pub use topography::Topography;
pub use translating::{Kinematics, TranslatingContact};
pub use waviness::Waviness;
pub use wavy_sphere::WavySphere;

use crate::grid::Grid;
use thiserror::Error;

/// Errors for invalid geometric parameters.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum GeometryError {
    /// A length (radius, wavelength, semi-axis, spacing) must be finite and positive.
    #[error("{name} must be finite and > 0, got {value}")]
    NotPositive {
        /// Parameter name.
        name: &'static str,
        /// Offending value.
        value: f64,
    },
    /// A parameter must be finite (amplitude, angle).
    #[error("{name} must be finite, got {value}")]
    NotFinite {
        /// Parameter name.
        name: &'static str,
        /// Offending value.
        value: f64,
    },
    /// A topography map must be rectangular, at least 2×2 and finite.
    #[error("topography: {0}")]
    Topography(String),
}

pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64, GeometryError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(GeometryError::NotPositive { name, value })
    }
}

pub(crate) fn finite(name: &'static str, value: f64) -> Result<f64, GeometryError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(GeometryError::NotFinite { name, value })
    }
}

/// The surface of a rigid indenter.
pub trait Profile: Send + Sync + std::fmt::Debug {
    /// Height at lateral position (x, y) relative to the indenter axis.
    fn height(&self, x: f64, y: f64) -> f64;

    /// Lateral distance from the axis beyond which the profile cannot touch a flat surface
    /// at the given indentation `depth` (used for the domain-border check); `None` when
    /// unbounded or unknown.
    fn reach(&self, depth: f64) -> Option<f64>;

    /// Fills `heights` with z at every element centre of `grid` for an indenter whose
    /// axis sits at `offset` = (X, Y).
    fn fill_heights(&self, grid: &Grid, offset: (f64, f64), heights: &mut [f64]) {
        assert_eq!(heights.len(), grid.len(), "heights buffer does not match the grid");
        for (k, height) in heights.iter_mut().enumerate() {
            let (x, y) = grid.centre(k);
            *height = self.height(x - offset.0, y - offset.1);
        }
    }

    /// Heights at every element centre with the axis at the origin.
    fn heights(&self, grid: &Grid) -> Vec<f64> {
        let mut heights = vec![0.0; grid.len()];
        self.fill_heights(grid, (0.0, 0.0), &mut heights);
        heights
    }

    /// Radius of curvature of the underlying paraboloid, where there is one (JKR scaling).
    fn radius_of_curvature(&self) -> Option<f64> {
        None
    }

    /// ∂z/∂x at (x, y): the slope that turns pressure into tangential force when the
    /// profile moves in x. Default: central difference with a step of 1e-6 of |x|+|y|+1
    /// relative; profiles with a closed form override it.
    fn slope_x(&self, x: f64, y: f64) -> f64 {
        let h = 1e-6 * (x.abs() + y.abs()).max(1e-12);
        let (right, left) = (self.height(x + h, y), self.height(x - h, y));
        if right.is_finite() && left.is_finite() {
            (right - left) / (2.0 * h)
        } else {
            0.0
        }
    }
}

/// Any indenter the library knows, as one owned type.
#[derive(Debug, Clone, PartialEq)]
pub enum Indenter {
    /// Paraboloid.
    Sphere(Sphere),
    /// Paraboloid with the paper's 2-D waviness (Eq. 1).
    WavySphere(WavySphere),
    /// Flat-ended cylinder.
    FlatPunch(FlatPunch),
    /// Flat punch with an elliptic face.
    EllipticPunch(EllipticPunch),
    /// Measured or generated height map.
    Topography(Topography),
    /// A plane or paraboloid carrying a roughness map (`rough_flat`, `rough_sphere`).
    Rough(RoughProfile),
}

impl Indenter {
    fn inner(&self) -> &dyn Profile {
        match self {
            Self::Sphere(p) => p,
            Self::WavySphere(p) => p,
            Self::FlatPunch(p) => p,
            Self::EllipticPunch(p) => p,
            Self::Topography(p) => p,
            Self::Rough(p) => p,
        }
    }
}

impl Profile for Indenter {
    fn height(&self, x: f64, y: f64) -> f64 {
        self.inner().height(x, y)
    }
    fn reach(&self, depth: f64) -> Option<f64> {
        self.inner().reach(depth)
    }
    fn fill_heights(&self, grid: &Grid, offset: (f64, f64), heights: &mut [f64]) {
        self.inner().fill_heights(grid, offset, heights)
    }
    fn radius_of_curvature(&self) -> Option<f64> {
        self.inner().radius_of_curvature()
    }
    fn slope_x(&self, x: f64, y: f64) -> f64 {
        self.inner().slope_x(x, y)
    }
}
