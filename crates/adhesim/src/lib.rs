//! # adhesim
//!
//! FFT-accelerated boundary element method for normal and tangential contacts of rough,
//! adhesive, elastic bodies, after Popov, Li, Lyashenko & Pohrt (2021), "Adhesion and
//! friction in hard and soft contacts: theory and experiment", *Friction* 9, 1688–1706,
//! doi:10.1007/s40544-020-0482-0.
//!
//! ## Units and signs
//! Any consistent unit system. A rigid indenter touches an elastic half-space of contact
//! modulus E* = E/(1 − ν²).
//! - pressure p > 0 is compressive, p < 0 tensile (adhesion); normal force F = Δ²Σp;
//! - indentation depth d > 0 pushes the indenter into the half-space;
//! - surface displacement u > 0 points into the body; gap g = z − d + u ≥ 0;
//! - the work of adhesion γ is an energy per unit area.
//!
//! ## Modules (one-way dependencies, see ARCHITECTURE.md)
//! `grid`, `material` → `geometry`, `elastic` → `solver` → `protocol` → `analysis`.
#![warn(missing_docs)]
// Numerical kernels index several parallel fields with one index; iterator zips over
// four or five slices would be harder to read.
#![allow(clippy::needless_range_loop)]

/// Revision of the results the algorithms produce: bumped whenever a change alters results
/// (not merely speed), so that sweep and study caches, which include it in their hashes,
/// never reuse a case computed by an older algorithm. 2: failed closure tests are retried
/// once the contact grows within a step (step-size independent approach).
pub const RESULTS_REVISION: u32 = 2;

pub mod analysis;
pub mod elastic;
pub mod experiment;
pub mod geometry;
pub mod grid;
pub mod material;
pub mod protocol;
pub mod solver;
pub mod surface;

pub use elastic::{ElasticOperator, FreeOperator, HalfSpace, PeriodicKernel, PeriodicOperator};
pub use geometry::{
    EllipticPunch, FlatPunch, Indenter, Kinematics, Profile, RoughBase, RoughProfile, Sphere, Topography,
    TranslatingContact, Waviness, WavySphere,
};
pub use grid::{Boundary, Grid, GridError};
pub use material::{Axis, ElasticMaterial, MaterialError, WorkOfAdhesion};
pub use protocol::{
    IndentPulloff, NormalSolver, Observer, Phase, ProtocolError, ProtocolSummary, StepRecord, StepView, Translation,
    TranslationSummary,
};
pub use solver::{
    AdhesiveParams, AdhesiveSolver, Attachment, Ccg, CcgParams, ContactState, Control, Detachment, NestedActiveSet,
    NestedParams, SolveError, SolveReport, StepReport,
};
pub use surface::{Amplitudes, PsdBin, RmsTarget, RoughSurface, SelfAffine, SurfaceError, SurfaceStatistics};
