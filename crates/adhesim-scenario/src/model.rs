//! The serde mirror of a scenario file (one struct per `[section]`) and the validated scenario built from it.

use adhesim::analysis::reference::Jkr;
use adhesim::{ElasticLayer, ElasticMaterial, Grid, Indenter, TranslatingContact, Translation};
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

mod adhesion;
mod friction;
mod law;
mod layer;
mod per_axis;
mod roughness;
mod solver;
pub use adhesion::{AdhesionSection, AgingLawName, AgingSection, LawName};
pub use friction::{
    CouplingName, FrictionLawName, FrictionSection, InterfaceFriction, NormalControl, ShearProtocol, ShearSetup,
    TangentialForceUnit,
};
pub use law::AdhesionLaw;
pub use layer::LayerBaseName;
pub use per_axis::PerAxis;
pub use roughness::{InvalidPoints, InvalidPointsReport, RoughnessMode, RoughnessSection};
pub use solver::{PredictedGrowthName, SolverSection};

/// The whole scenario file.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScenarioFile {
    pub grid: GridSection,
    pub material: MaterialSection,
    pub adhesion: AdhesionSection,
    pub indenter: IndenterSection,
    pub protocol: ProtocolSection,
    #[serde(default)]
    pub output: OutputSection,
    /// Inputs of the analysis of a run (roll/slide: γ1, γ2 for Eq. 12, τ0 for Eq. 16).
    #[serde(default, skip_serializing_if = "AnalysisSection::is_empty")]
    pub analysis: AnalysisSection,
    /// Roughness added to the indenter's heights (any shape; required by `rough_sphere`
    /// and `rough_flat`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub roughness: Option<RoughnessSection>,
    /// Roughness of the substrate of a `slide` (fixed to the half-space).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub substrate_roughness: Option<RoughnessSection>,
    /// Friction at the interface (`kind = "shear"`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction: Option<FrictionSection>,
    /// Rules of the adhesive solver that leave the physics unchanged.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub solver: Option<SolverSection>,
}

/// `[analysis]`: numbers the analysis of a run needs but the run does not produce.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AnalysisSection {
    /// γ1 (approach branch of a normal run at the same α), for Eq. 12 of a rolling run.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gamma_approach: Option<f64>,
    /// γ2 (pull-off branch), for Eq. 12.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gamma_pulloff: Option<f64>,
    /// Shear strength τ0 of the contact area, for the friction law of Eqs. 16–18.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tau0: Option<f64>,
}

impl AnalysisSection {
    pub fn is_empty(&self) -> bool {
        self.gamma_approach.is_none() && self.gamma_pulloff.is_none() && self.tau0.is_none()
    }
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GridSection {
    /// Elements per side, or `[nx, ny]` (kept signed so that a negative value gets our own
    /// message).
    pub n: PerAxis<i64>,
    /// Side length, or `[sx, sy]`.
    pub size: PerAxis<f64>,
    #[serde(default)]
    pub boundary: BoundaryName,
}

#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BoundaryName {
    #[default]
    Free,
    Periodic,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSection {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact_modulus: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub youngs_modulus: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub poisson_ratio: Option<f64>,
    /// Thickness of an elastic layer on a rigid base (length units); absent: a half-space.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thickness: Option<f64>,
    /// How the layer rests on its base; absent means `bonded` (and is echoed absent).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub base: Option<LayerBaseName>,
}

/// Heterogeneous work of adhesion.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum FieldSpec {
    /// γ(s) = γ0·[1 + (k − 1)(s/half_length)²] along `axis`.
    Quadratic {
        ratio_edge_to_centre: f64,
        #[serde(default)]
        axis: AxisName,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        half_length: Option<f64>,
    },
    /// γ = γ0 × the map's value per element (an N×N `.npy` of f64, rows along y).
    Map { file: PathBuf },
}

#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AxisName {
    #[default]
    X,
    Y,
}

/// The kind of an `[indenter]` (its `shape` tag), for messages and dispatch.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShapeName {
    Sphere,
    WavySphere,
    FlatPunch,
    EllipticPunch,
    Topography,
    /// A paraboloid of `radius` carrying the `[roughness]`.
    RoughSphere,
    /// A plane carrying the `[roughness]`.
    RoughFlat,
}

impl ShapeName {
    pub fn name(self) -> &'static str {
        match self {
            Self::Sphere => "sphere",
            Self::WavySphere => "wavy_sphere",
            Self::FlatPunch => "flat_punch",
            Self::EllipticPunch => "elliptic_punch",
            Self::Topography => "topography",
            Self::RoughSphere => "rough_sphere",
            Self::RoughFlat => "rough_flat",
        }
    }
}

/// `[indenter]`, tagged by `shape`: each shape takes exactly its own keys, so that a key of
/// another shape (`amplitude` on a sphere) is rejected by serde and a missing one is named.
/// The variants' field order is the order `summary.json` echoes them in.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(tag = "shape", rename_all = "snake_case", deny_unknown_fields)]
pub enum IndenterSection {
    Sphere {
        radius: f64,
    },
    /// A sphere with sinusoidal waviness (Eq. 1).
    WavySphere {
        radius: f64,
        amplitude: f64,
        wavelength: f64,
        /// Rotation of the waviness, degrees (default 0).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        angle: Option<f64>,
    },
    FlatPunch {
        radius: f64,
    },
    EllipticPunch {
        /// [a, b].
        semi_axes: Vec<f64>,
        /// Rotation of the ellipse axes, degrees (default 0).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        angle: Option<f64>,
    },
    /// A measured height map.
    Topography {
        file: PathBuf,
        /// Spacing of a file that records none (npy, npz, bare ASCII).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        spacing: Option<f64>,
    },
    /// A paraboloid of `radius` carrying the `[roughness]`.
    RoughSphere {
        radius: f64,
    },
    /// A plane carrying the `[roughness]`.
    RoughFlat {},
}

impl IndenterSection {
    pub fn shape(&self) -> ShapeName {
        match self {
            Self::Sphere { .. } => ShapeName::Sphere,
            Self::WavySphere { .. } => ShapeName::WavySphere,
            Self::FlatPunch { .. } => ShapeName::FlatPunch,
            Self::EllipticPunch { .. } => ShapeName::EllipticPunch,
            Self::Topography { .. } => ShapeName::Topography,
            Self::RoughSphere { .. } => ShapeName::RoughSphere,
            Self::RoughFlat {} => ShapeName::RoughFlat,
        }
    }

    /// `indenter.radius` of the shapes that have one.
    pub fn radius(&self) -> Option<f64> {
        match self {
            Self::Sphere { radius }
            | Self::WavySphere { radius, .. }
            | Self::FlatPunch { radius }
            | Self::RoughSphere { radius } => Some(*radius),
            _ => None,
        }
    }

    /// `indenter.amplitude` and `indenter.wavelength` of a wavy sphere.
    pub fn waviness(&self) -> Option<(f64, f64)> {
        match self {
            Self::WavySphere {
                amplitude, wavelength, ..
            } => Some((*amplitude, *wavelength)),
            _ => None,
        }
    }
}

/// The kind of a `[protocol]` (its `kind` tag), for messages and dispatch.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProtocolKind {
    IndentPulloff,
    Roll,
    Slide,
    /// The frictionless control: the whole rough profile translates over a smooth body.
    Translate,
    /// A tangential shift with friction at fixed indentation.
    Shear,
}

impl ProtocolKind {
    pub fn name(self) -> &'static str {
        match self {
            Self::IndentPulloff => "indent_pulloff",
            Self::Roll => "roll",
            Self::Slide => "slide",
            Self::Translate => "translate",
            Self::Shear => "shear",
        }
    }

    /// Roll, slide or translate: motion at fixed indentation.
    pub fn is_translation(self) -> bool {
        matches!(self, Self::Roll | Self::Slide | Self::Translate)
    }
}

/// Unit of `protocol.distance`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DistanceUnit {
    #[default]
    Length,
    /// Multiples of the waviness wavelength λ.
    Wavelength,
}

#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DepthUnit {
    Jkr,
    #[default]
    Length,
}

/// `[protocol]`, tagged by `kind`: each kind takes exactly its own keys, so that a key of
/// another kind (`max_depth` on a roll) is rejected by serde and a missing one is named.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum ProtocolSection {
    IndentPulloff(IndentationProtocol),
    Roll(MotionProtocol),
    Slide(SlideProtocol),
    Translate(MotionProtocol),
    Shear(ShearProtocol),
}

impl ProtocolSection {
    pub fn kind(&self) -> ProtocolKind {
        match self {
            Self::IndentPulloff(_) => ProtocolKind::IndentPulloff,
            Self::Roll(_) => ProtocolKind::Roll,
            Self::Slide(_) => ProtocolKind::Slide,
            Self::Translate(_) => ProtocolKind::Translate,
            Self::Shear(_) => ProtocolKind::Shear,
        }
    }

    /// The unit of `max_depth`, `step` and `depth`.
    pub fn depth_unit(&self) -> DepthUnit {
        match self {
            Self::IndentPulloff(p) => p.depth_unit,
            Self::Roll(p) | Self::Translate(p) => p.depth_unit,
            Self::Slide(p) => p.depth_unit,
            Self::Shear(p) => p.depth_unit,
        }
    }

    /// Roll, slide, translate: the motion's keys and (slide only) `substrate_angle`.
    pub fn motion(&self) -> Option<(MotionProtocol, Option<f64>)> {
        match self {
            Self::IndentPulloff(_) | Self::Shear(_) => None,
            Self::Roll(p) | Self::Translate(p) => Some((p.clone(), None)),
            Self::Slide(p) => Some((
                MotionProtocol {
                    depth_unit: p.depth_unit,
                    depth: p.depth,
                    distance: p.distance,
                    distance_unit: p.distance_unit,
                    approach_steps: p.approach_steps,
                    return_stroke: p.return_stroke,
                    stationary_from: p.stationary_from,
                    drive_stiffness: p.drive_stiffness,
                    steps: p.steps,
                },
                p.substrate_angle,
            )),
        }
    }
}

/// `kind = "indent_pulloff"`: approach to `max_depth`, then retraction until contact is lost.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IndentationProtocol {
    /// Deepest indentation (in `depth_unit`).
    pub max_depth: f64,
    #[serde(default)]
    pub depth_unit: DepthUnit,
    /// Steps per branch (approach); the retraction uses the same step size.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steps: Option<i64>,
    /// Step size in `depth_unit` (alternative to `steps`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub step: Option<f64>,
    /// Safety limit on retraction steps (default: 20 × the approach steps, at least 1000).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_retract_steps: Option<i64>,
    /// A hold at the deepest indentation before the retraction, in the unit of time of
    /// `adhesion.aging.reference_time`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hold_time: Option<f64>,
    /// The hold's longest time step (default: hold_time/20).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time_step: Option<f64>,
}

/// `kind = "roll"` or `"translate"`: approach to `depth`, then travel by `distance` in +x.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MotionProtocol {
    #[serde(default)]
    pub depth_unit: DepthUnit,
    /// Indentation held during the motion (in `depth_unit`).
    pub depth: f64,
    /// Travel of the indenter axis in +x.
    pub distance: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub distance_unit: Option<DistanceUnit>,
    /// Steps of the approach to `depth` (default 50).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub approach_steps: Option<i64>,
    /// Travel back to x = 0 after the forward stroke.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub return_stroke: Option<bool>,
    /// Means are taken over x > stationary_from·distance (default 0.5).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stationary_from: Option<f64>,
    /// Stiffness of a spring between the drive and the indenter of a translate with
    /// `[friction]` (force per length; absent: a rigid drive).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub drive_stiffness: Option<f64>,
    /// Steps of the travel.
    pub steps: i64,
}

/// `kind = "slide"`: a roll's keys (see [`MotionProtocol`]) and the substrate's angle. The
/// keys are repeated rather than flattened because serde's `flatten` cannot be combined
/// with `deny_unknown_fields`.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SlideProtocol {
    #[serde(default)]
    pub depth_unit: DepthUnit,
    pub depth: f64,
    pub distance: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub distance_unit: Option<DistanceUnit>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub approach_steps: Option<i64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub return_stroke: Option<bool>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stationary_from: Option<f64>,
    /// Rotation of the substrate's waviness against the indenter's, degrees (default 30).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub substrate_angle: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub drive_stiffness: Option<f64>,
    pub steps: i64,
}

fn default_jump_snapshot_elements() -> i64 {
    20
}
fn default_jump_force_threshold() -> f64 {
    1e-3
}
fn default_max_snapshots() -> i64 {
    200
}

/// What the run writes besides `curve.csv`, `summary.json` and the plots.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSection {
    /// Steps (0-based, as in `curve.csv`) that get a contact-map PNG and `.npy` fields.
    #[serde(default)]
    pub snapshot_steps: Vec<i64>,
    /// Also every k-th step (0 = off).
    #[serde(default)]
    pub snapshot_every: i64,
    /// A jump step gets a PNG when at least this many elements attached or detached.
    #[serde(default = "default_jump_snapshot_elements")]
    pub jump_snapshot_elements: i64,
    /// A step is a jump when the force changes at fixed depth by more than this, in units
    /// of the adhesive force scale (|F_JKR|; Kendall's force for a flat punch; the onset
    /// force for an elliptic punch).
    #[serde(default = "default_jump_force_threshold")]
    pub jump_force_threshold: f64,
    /// At most this many jump snapshots (chosen steps are always written).
    #[serde(default = "default_max_snapshots")]
    pub max_snapshots: i64,
    /// Contact radii below this (length units) are left out of the JKR fits of γ1/γ2
    /// [default: max(0.5·a_JKR, 2λ) for a wavy sphere, 0.5·a_JKR otherwise].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_fit_radius: Option<f64>,
}

impl Default for OutputSection {
    fn default() -> Self {
        Self {
            snapshot_steps: Vec::new(),
            snapshot_every: 0,
            jump_snapshot_elements: default_jump_snapshot_elements(),
            jump_force_threshold: default_jump_force_threshold(),
            max_snapshots: default_max_snapshots(),
            min_fit_radius: None,
        }
    }
}

/// A scenario ready to run: library objects plus derived numbers.
pub struct ValidScenario {
    pub file: ScenarioFile,
    pub grid: Grid,
    pub material: ElasticMaterial,
    /// The elastic layer of `material.thickness` (None: the half-space).
    pub layer: Option<ElasticLayer>,
    /// γ per element.
    pub gamma: Vec<f64>,
    /// Reference γ0.
    pub gamma0: f64,
    /// `adhesion.first_contact_factor` of an indentation: the factor by which a first
    /// contact changes γ where it touched (`first_contact_map.npy` written after the run).
    pub first_contact_factor: Option<f64>,
    /// `[adhesion]`'s law with its parameters, checked (the run reads this, not the
    /// file's keys).
    pub law: AdhesionLaw,
    pub indenter: Indenter,
    pub heights: Vec<f64>,
    /// Depth of first contact (lowest finite height).
    pub start_depth: f64,
    pub max_depth: f64,
    pub depth_step: f64,
    pub approach_steps: usize,
    pub max_retract_steps: usize,
    /// JKR closed form where γ0 > 0 and the indenter has a radius of curvature.
    pub jkr: Option<Jkr>,
    pub derived: Derived,
    /// Absolute force threshold for a jump.
    pub jump_force_threshold: f64,
    /// roll / slide / translate: the motion (`None` for indent_pulloff).
    pub translation: Option<TranslationSetup>,
    /// shear: the protocol and the interface law (`None` otherwise).
    pub shear: Option<ShearSetup>,
    /// The hold of an indentation (`protocol.hold_time`), with its aging.
    pub hold: Option<adhesim::Hold>,
    /// Resolution warnings (elements per wavelength, across a punch, per a_JKR), for
    /// stderr and `summary.json`.
    pub warnings: Vec<String>,
    /// The `[roughness]` as sampled on the grid (peaks positive, row-major), if any.
    pub roughness: Option<Vec<f64>>,
}

/// A validated roll / slide / translate protocol.
#[derive(Debug, Clone)]
pub struct TranslationSetup {
    pub kind: ProtocolKind,
    pub contact: TranslatingContact,
    /// Library protocol (start_depth is the depth of first contact at x = 0).
    pub protocol: Translation,
    /// γ1, γ2 from `[analysis]` (Eq. 12), absolute units.
    pub gammas: Option<(f64, f64)>,
    /// τ0 from `[analysis]` (Eqs. 16–18).
    pub tau0: Option<f64>,
    /// Waviness wavelength λ (None for a smooth sphere).
    pub wavelength: Option<f64>,
    /// `[friction]` at the interface (None: frictionless, the paper's model).
    pub friction: Option<InterfaceFriction>,
}

/// Derived quantities for `summary.json`; `None` is written as null.
#[derive(Debug, Clone, Serialize)]
pub struct Derived {
    pub f_jkr: Option<f64>,
    pub d_jkr: Option<f64>,
    pub a_jkr: Option<f64>,
    pub johnson_parameter: Option<f64>,
    /// Δx (the element side on square elements).
    pub element_size: f64,
    /// Δy where it differs from Δx (rectangular elements; absent otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub element_size_y: Option<f64>,
    pub critical_stress: Option<f64>,
    /// Maugis' λ = 2σ0·(R/(πγ0K²))^(1/3) of `adhesion.law = "dugdale"` (or of the
    /// plateau traction σ0 of `"trapezoid"`) on a curved indenter (absent otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub maugis_parameter: Option<f64>,
    /// Tabor's μ = (Rγ0²/(E*²ρ³))^(1/3) of `adhesion.law = "exponential"` on a curved
    /// indenter (absent otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tabor_parameter: Option<f64>,
    /// Statistics of the `[roughness]` as sampled on the grid (absent without one).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub roughness: Option<RoughnessStatistics>,
    /// Statistics of the `[substrate_roughness]` on the grid (absent without one).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub substrate_roughness: Option<RoughnessStatistics>,
}

/// rms height, slope and curvature of a roughness as sampled on the grid (spectral on a
/// periodic grid, finite differences on a free one: `adhesim::surface::statistics`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RoughnessStatistics {
    pub rms_height: f64,
    pub rms_slope: f64,
    pub rms_curvature: f64,
    /// The invalid points of a measured map and what was done with them; absent when the
    /// map has none (or is generated).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub invalid_points: Option<InvalidPointsReport>,
}
