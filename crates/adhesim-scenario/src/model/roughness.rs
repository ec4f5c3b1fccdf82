//! `[roughness]` and `[substrate_roughness]` of the scenario file (re-exported by `model`).

use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// `[roughness]` and `[substrate_roughness]`: a random self-affine surface (generator keys)
/// or a measured one (`file` keys), never both.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoughnessSection {
    /// Hurst exponent H ∈ (0, 1] of C(q) ∝ q^(−2−2H).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hurst: Option<f64>,
    /// rms height about the mean plane (exactly one of rms_height, rms_slope).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rms_height: Option<f64>,
    /// rms slope ⟨|∇h|²⟩^½.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rms_slope: Option<f64>,
    /// Roll-off wavelength λ_r (plateau of the spectrum beyond it; default: none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rolloff_wavelength: Option<f64>,
    /// Short-wavelength cutoff λ_s (default: the grid's Nyquist wavelength 2Δ).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cutoff_wavelength: Option<f64>,
    /// Seed of the random phases (an integer >= 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<i64>,
    /// Exact amplitudes (`random_phase`, default) or Gaussian ones (`filtered`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mode: Option<RoughnessMode>,
    /// A measured height map in any format `adhesim_topography` reads.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<PathBuf>,
    /// Subtract the least-squares mean plane of the file's map (default false).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub detrend: Option<bool>,
    /// Spacing of a file that records none (npy, npz, bare ASCII), in length units.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spacing: Option<f64>,
    /// Channel of a multi-channel file (Gwyddion title, npz member, ASCII "Channel").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub channel: Option<String>,
    /// Unit of the heights of a file that records none (npy, npz, bare ASCII, xyz without
    /// header, a .gwy with an empty unit): `"nm"`, `"um"`, `"m"`, … converted to metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height_unit: Option<String>,
    /// Unit of the x and y columns of an xyz file without header (or of a .gwy's sizes
    /// whose unit is empty), converted to metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lateral_unit: Option<String>,
    /// What to do with the points a file marks invalid: `"interpolate"` (harmonic filling,
    /// as SurfaceTopography's `interpolate_undefined_data`) or `"refuse"` (an error). A
    /// file with invalid points needs it; it is reported in summary.json.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub invalid_points: Option<InvalidPoints>,
}

/// The choice for the invalid points of a measured map.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum InvalidPoints {
    /// Fill them with the harmonic interpolation of the valid points.
    Interpolate,
    /// Stop with an error naming the count.
    Refuse,
}

/// How the generator draws its Fourier amplitudes.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RoughnessMode {
    #[default]
    RandomPhase,
    Filtered,
}

/// The invalid points of a measured map as summary.json reports them.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct InvalidPointsReport {
    /// Points the file marks invalid.
    pub count: usize,
    /// Points of the map.
    pub of: usize,
    /// `"interpolate"`: filled by harmonic interpolation before resampling onto the grid.
    pub handling: InvalidPoints,
}
