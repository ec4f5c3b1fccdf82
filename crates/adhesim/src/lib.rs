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
//! ## Example: a Hertz contact against the closed form
//! A rigid sphere of radius R = 1 pressed to depth d = 1/64 into a half-space of E* = 1,
//! on a free (non-periodic) 64×64 grid of side 1: the contact radius √(Rd) = 1/8 spans
//! 8 elements. Solved with the Polonsky–Keer constrained conjugate gradient method, the
//! force is compared with Hertz's F = (4/3)E*R^{1/2}d^{3/2}.
//! ```
//! use adhesim::analysis::reference::Hertz;
//! use adhesim::{Boundary, Ccg, CcgParams, ContactState, Control, ElasticMaterial, FreeOperator, Grid, Profile, Sphere};
//!
//! let grid = Grid::new(64, 1.0, Boundary::Free)?;
//! let material = ElasticMaterial::new(1.0)?;
//! let mut operator = FreeOperator::new(grid, material); // plans the FFTs once
//! let heights = Sphere::new(1.0)?.heights(&grid);
//! let depth = 1.0 / 64.0;
//! let mut state = ContactState::new(&grid);
//! let report = Ccg::new(CcgParams::default()).solve(&mut operator, &heights, Control::Displacement(depth), &mut state)?;
//!
//! let hertz = Hertz { radius: 1.0, contact_modulus: 1.0 };
//! let force_error = report.force / hertz.force(depth) - 1.0;
//! // 0.5 %, the bound tests/integration/validation_hertz.rs sets at 32 elements: the
//! // staircase edge of the discrete contact costs far less here (measured 0.04 % at 8
//! // elements).
//! assert!(force_error.abs() < 0.005, "force error {force_error}");
//! // The contact radius (farthest element centre in contact) is within one element of √(Rd).
//! let radius_error = state.contact_radius(&grid, (0.0, 0.0)) - hertz.contact_radius(depth);
//! assert!(radius_error.abs() <= grid.dx(), "radius error {radius_error}");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//! The physics and the algorithms are stated in `docs/physics.md` of the repository, the
//! files the command line writes in `docs/output.md`.
//!
//! ## Modules (one-way dependencies, see ARCHITECTURE.md)
//! `grid`, `material` → `geometry`, `elastic` → `solver` → `problem` → `protocol` → `analysis`;
//! `rng` (the seeded generator) stands alone.
#![warn(missing_docs)]
// Numerical kernels index several parallel fields with one index; iterator zips over
// four or five slices would be harder to read.
#![allow(clippy::needless_range_loop)]

/// Revision of the results the algorithms produce: bumped whenever a change alters results
/// (not merely speed), so that sweep and study caches, which include it in their hashes,
/// never reuse a case computed by an older algorithm. 2: failed closure tests are retried
/// once the contact grows within a step (step-size independent approach). 3: elements with
/// γ = 0 detach under any tension and attach only by penetration (docs/physics.md §2.2;
/// cases with γ = 0 elements, from adhesion maps or quadratic fields reaching 0, change),
/// and a non-adhesive unload starts cold with the nested continuation (forces move by
/// ~1e-11, the same contact sets). 4: release decisions inside a solve's error band are
/// refined (docs/fast-step.md §2: the solve continues at 1e-4 of its tolerances until they
/// are certain), so that the decision no longer depends on the iterate; forces move by
/// ≲ 1e-6 of the largest force, and a contact set changes only where the old rule decided
/// such a tie otherwise. 5: the non-adhesive solver pre-solves on the contact's bounding
/// box (`NestedActiveSet`, docs/physics.md §3.3): the same contact sets, forces move by
/// ~1e-11 (another point inside the 1e-10 tolerance); adhesive results are unchanged.
/// 6: predicted-subset growth is the product's default from 512² (`PredictedGrowth::Auto`;
/// the same contact sets as the exact peel, forces may move in their last bits), and the
/// periodic non-adhesive solve no longer fails on an empty or one-element contact set.
/// 7: CCG's load-controlled mean gap is refined to be exact on equal gaps (docs/physics.md
/// §3.1: it stalled on a strip contact one row wide); periodic and cohesive-periodic
/// forces move in their last digits (≤ 4.5e-12 of the largest force without adhesion,
/// ≤ 4e-10 with the exponential law), free-grid results are bit-identical to revision 6.
/// 8: the accelerated rounds of smooth cohesive laws keep a mixing only if it also lowers
/// the residual, and hold mixing back while the plain rounds escape (docs/physics.md §2.6):
/// trapezoid and exponential runs move (rolls that failed now converge; where jumps happen
/// another local minimum may be reached), the JKR criterion and Dugdale are bit-identical.
/// 9: a static friction law lets the contact come to rest after a slip event (elements
/// broke loose and the tangential force fell; docs/physics.md §8.2): the next step starts
/// stuck under the static bound instead of sliding on at the kinetic one. Shear runs with
/// a static law and such a drop move; every other result is bit-identical to revision 8.
/// 10: the adhesive solver's fixed-set CG runs on the contact's bounding box on a free
/// half-space (`AdhesiveParams::contact_window`, docs/physics.md §3.2): the same matrix
/// through transforms of another size, so forces move in their last digits (≤ 6e-8 of the
/// largest force on the Fig. 1 cycle at 256² and 512², the same contact sizes at every
/// step); periodic grids, layers, cohesive laws and non-adhesive runs are bit-identical.
/// 11: the displacement outside the adhesive CG's window lags until something reads it
/// (docs/physics.md §3.2): a cascade of releases keeps its window and brings the whole grid
/// up once, so the single-precision updates outside are summed differently; forces move in
/// their last digits (≤ 1.2e-7 of the largest force on the Fig. 1 cycle at 256², ≤ 1.3e-8
/// at 512², the same contact sizes at every step); `contact_window = false`, periodic grids,
/// layers, cohesive laws and non-adhesive runs are bit-identical.
/// 12: a force-controlled shear step (`protocol.tangential_force`) is solved at once, the
/// force a constraint of the face's CG and the shift its multiplier (docs/physics.md §8.2),
/// instead of by displacement-controlled trials: the same step to its tolerances, so shifts
/// and forces move by ≤ 3.1e-9 of their largest on `scenarios/friction/fretting_force.toml`
/// (the same stick and slip counts at every step); every other result is bit-identical.
pub const RESULTS_REVISION: u32 = 12;

pub mod analysis;
#[cfg(feature = "serde")]
pub mod bit_string;
pub mod elastic;
pub mod geometry;
pub mod grid;
pub mod material;
pub mod problem;
pub mod protocol;
pub mod rng;
pub mod solver;
pub mod surface;

pub use elastic::cerruti::ShearMaterial;
pub use elastic::{
    Backend, CouplingCompliance, CouplingOperator, ElasticLayer, ElasticOperator, FreeOperator, HalfSpace, LayerBase,
    LayerError, LayerOperator, PeriodicKernel, PeriodicOperator, ShearBody, ShearCompliance, TangentialOperator,
    TangentialOperatorError,
};
pub use geometry::{
    EllipticPunch, FlatPunch, Indenter, Kinematics, Profile, RoughBase, RoughProfile, Sphere, Topography,
    TranslatingContact, Waviness, WavySphere,
};
pub use grid::{Boundary, Grid, GridError};
pub use material::{Axis, ElasticMaterial, MaterialError, WorkOfAdhesion};
pub use problem::{Problem, ProblemError};
pub use protocol::{
    AgingLaw, Hold, IndentCheckpoint, IndentPulloff, NormalSolver, NormalStepper, Observer, Phase, ProtocolCheckpoint,
    ProtocolError, ProtocolSummary, RunCounters, RunSummary, Shear, ShearFields, ShearSummary, SolverCheckpoint,
    StepRecord, StepView, TangentialForce, Translation, TranslationCheckpoint, TranslationFriction, TranslationSummary,
};
pub use solver::{
    Acceleration, AdhesiveParams, AdhesiveSolver, Attachment, Ccg, CcgParams, CohesiveLaw, CohesiveParams,
    CohesiveSolver, Complementarity, ContactState, Control, Detachment, Dugdale, Exponential, FrictionLaw,
    FrictionLawError, NestedActiveSet, NestedParams, SlipStatus, SolveError, SolveReport, StepReport, TangentialError,
    TangentialParams, TangentialReport, TangentialSolver, TangentialState, Trapezoid,
};
pub use surface::{Amplitudes, PsdBin, RmsTarget, RoughSurface, SelfAffine, SurfaceError, SurfaceStatistics};
