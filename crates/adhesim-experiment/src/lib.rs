//! # adhesim-experiment
//!
//! Analysis of filmed contact experiments (Popov, Li, Lyashenko & Pohrt 2021, *Friction* 9,
//! Sects. 4–6): a camera films the contact of a steel sphere through a transparent rubber
//! layer while a log records forces and stage position. The user guide, the spec file and the
//! outputs of `adhesim experiment` are in `docs/experiments.md` and
//! `docs/interface-experiment.md` of the repository; the quantities are those of
//! `docs/physics.md` §7.
//!
//! Pure numerics on in-memory frames; reading image files, plotting and the command line
//! live in `adhesim-cli`. The pipeline per frame is
//! [`GrayImage`] → [`Segmenter::segment`] (background flattening, threshold, morphological
//! cleaning, region of interest) → [`ContactMask`] → [`measure`] (area, centroid, width,
//! front/rear split about the moving indenter centre line) and [`change_map`] (new and
//! vanished contact against a reference). Sequence-level tools: [`detect_jumps`],
//! [`classify_phases`] and the fits in [`fit`] (the JKR fit is the library's
//! [`adhesim::analysis::fit::fit_jkr_work_of_adhesion`]). [`synthetic`] renders camera-like
//! frames from a known contact sequence for testing, with the library's seeded generator
//! [`adhesim::rng::SplitMix64`].
//!
//! Pixel coordinates: column `x` (0 at the left), row `y` (0 at the top); a pixel's
//! coordinates are those of its centre.
//!
//! ```
//! use adhesim_experiment::{measure, ContactMask, Motion};
//! // A 3×2-pixel contact in a 10×10 frame of 0.5 µm pixels, moving along +x with the
//! // indenter centre line at column 4: area 6 · 0.25 µm², one column of two pixels ahead.
//! let mask = ContactMask::from_fn(10, 10, |x, y| (3..6).contains(&x) && (4..6).contains(&y)).unwrap();
//! let area = measure(&mask, 0.5, Some(([4.0, 5.0], Motion::PosX))).unwrap();
//! assert_eq!((area.pixels, area.area, area.area_front), (6, 1.5, 0.5));
//! ```
#![warn(missing_docs)]

mod background;
mod camera;
mod changes;
pub mod film;
pub mod fit;
mod image;
mod mask;
mod measure;
mod phases;
mod segment;
pub mod synthetic;

pub use camera::Camera;
pub use changes::{change_map, Change, ChangeMap};
pub use image::{GrayImage, Roi};
pub use mask::ContactMask;
pub use measure::{measure, AreaMeasurement, IndenterTrack, Motion};
pub use phases::{classify_phases, detect_jumps, Phase, PhaseParams};
pub use segment::{BackgroundModel, Correction, Polarity, SegmentationParams, Segmenter, ThresholdRule};

/// Errors of the experiment analysis.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ExperimentError {
    /// Image dimensions and buffer length disagree, or an image is empty.
    #[error("image of {width}×{height} pixels needs {expected} values, got {actual}")]
    BadImageSize {
        /// Width in pixels.
        width: usize,
        /// Height in pixels.
        height: usize,
        /// Expected buffer length.
        expected: usize,
        /// Actual buffer length.
        actual: usize,
    },
    /// Two images or masks that must have the same size do not.
    #[error("size mismatch: {0}×{1} vs {2}×{3} pixels")]
    SizeMismatch(usize, usize, usize, usize),
    /// A position or region (a spec key) does not lie inside the frames.
    #[error("{name} = {value} is not inside the {width}×{height} pixel frames")]
    OutsideImage {
        /// Parameter name.
        name: &'static str,
        /// The offending value, formatted.
        value: String,
        /// Frame width in pixels.
        width: usize,
        /// Frame height in pixels.
        height: usize,
    },
    /// A parameter is out of range; names the parameter and the value.
    #[error("{name} {requirement}, got {value}")]
    InvalidParameter {
        /// Parameter name.
        name: &'static str,
        /// What the value must satisfy, e.g. "must be > 0".
        requirement: &'static str,
        /// The offending value, formatted.
        value: String,
    },
    /// Input series have different lengths.
    #[error("series lengths differ: {0} vs {1}")]
    LengthMismatch(usize, usize),
    /// A fit has too few usable points.
    #[error("{fit} fit needs at least {needed} usable points, got {got}")]
    TooFewPoints {
        /// Which fit.
        fit: &'static str,
        /// Minimum number of points.
        needed: usize,
        /// Usable points found.
        got: usize,
    },
    /// The fit's design is degenerate (e.g. all abscissae equal).
    #[error("{0} fit is degenerate: {1}")]
    Degenerate(&'static str, &'static str),
}

/// The Rust examples of `docs/experiments.md` (the crate's page) run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../../docs/experiments.md")]
struct ExperimentsPage;

pub(crate) fn invalid(name: &'static str, requirement: &'static str, value: impl ToString) -> ExperimentError {
    ExperimentError::InvalidParameter {
        name,
        requirement,
        value: value.to_string(),
    }
}
