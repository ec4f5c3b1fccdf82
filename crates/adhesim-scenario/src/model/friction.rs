//! `[friction]` and `[protocol] kind = "shear"` as written in a scenario file, and the
//! validated shear setup.

use super::DepthUnit;
use adhesim::protocol::ModeMixity;
use adhesim::{FrictionLaw, Shear, ShearMaterial};
use serde::{Deserialize, Serialize};

/// `[friction]`: the interface law of tangential contact (docs/physics.md §8).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionSection {
    pub law: FrictionLawName,
    /// μ of `coulomb` and `coulomb_shear`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coefficient: Option<f64>,
    /// τ0 of `shear_strength` and `coulomb_shear`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shear_strength: Option<f64>,
    /// Normal–tangential coupling: `"none"` (Goodman's approximation) or `"full"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coupling: Option<CouplingName>,
    /// Static μs ≥ μ of `coulomb` and `coulomb_shear` (default μ: no static peak).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub static_coefficient: Option<f64>,
    /// Static τs ≥ τ0 of `shear_strength` and `coulomb_shear` (default τ0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub static_shear_strength: Option<f64>,
    /// D_c of slip weakening: an element's bound falls from the static to the kinetic one
    /// over this slip since it last stuck (needs a static key; default none: the bound
    /// drops at the first slip).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub slip_weakening_distance: Option<f64>,
    /// Share m ∈ [0, 1] of the shear energy that weakens the adhesive edge (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mode_mixity: Option<f64>,
    /// m of the shear across the edge where it points out of the contact (the front of a
    /// slide; default `mode_mixity`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mode_mixity_front: Option<f64>,
    /// m of the shear across the edge where it points into the contact (the rear; default
    /// `mode_mixity`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mode_mixity_rear: Option<f64>,
}

/// `friction.law`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FrictionLawName {
    Coulomb,
    ShearStrength,
    CoulombShear,
    NoSlip,
}

impl FrictionLawName {
    pub fn name(self) -> &'static str {
        match self {
            Self::Coulomb => "coulomb",
            Self::ShearStrength => "shear_strength",
            Self::CoulombShear => "coulomb_shear",
            Self::NoSlip => "no_slip",
        }
    }
}

/// `friction.coupling`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CouplingName {
    /// Goodman's approximation: shear does not move the surface normally, pressure does
    /// not move it tangentially (exact at ν = 1/2).
    #[default]
    None,
    /// The coupled operator (ν < 1/2, or a layer; under protocol.kind = "shear"): shear
    /// moves the surface normally and pressure moves it tangentially.
    Full,
}

/// `kind = "shear"`: approach to `depth`, then shift the indenter tangentially by
/// `distance` at fixed depth, or impose a `tangential_force` instead.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShearProtocol {
    #[serde(default)]
    pub depth_unit: DepthUnit,
    /// Indentation held during the shift (in `depth_unit`).
    pub depth: f64,
    /// A depth the approach presses to before lifting the indenter to `depth` (in
    /// `depth_unit`; absent: straight to `depth`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub press_depth: Option<f64>,
    /// Steps of the approach to `depth` (default 50).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub approach_steps: Option<i64>,
    /// Shift of the indenter (length units); exactly one of it and `tangential_force`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub distance: Option<f64>,
    /// Steps of the shift.
    pub steps: i64,
    /// Direction of the shift, degrees from +x (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub direction: Option<f64>,
    /// Shift back to the start after the forward stroke (and the cycles).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub return_stroke: Option<bool>,
    /// Angle of the indenter's path to the surface, degrees (> 0 into the body; default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub incline: Option<f64>,
    /// Fretting cycles between +distance and −distance after the forward stroke.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cycles: Option<i64>,
    /// Stiffness of a spring between the drive and the indenter (force per length; absent:
    /// a rigid drive).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub drive_stiffness: Option<f64>,
    /// The imposed tangential force along `direction` at the end of the forward stroke
    /// (force control), in `tangential_force_unit`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tangential_force: Option<f64>,
    /// `"force"` (default) or `"friction_limit"`: a share of what the interface holds at
    /// the end of the approach (μP, τ0·A).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tangential_force_unit: Option<TangentialForceUnit>,
    /// What the shift holds: `"depth"` (default) or `"force"`, the normal force of the end
    /// of the approach.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normal_control: Option<NormalControl>,
}

/// `protocol.normal_control` of a shear.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum NormalControl {
    /// The depth is held.
    #[default]
    Depth,
    /// The normal force is held, the depth found at each step.
    Force,
}

/// The unit of `protocol.tangential_force`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TangentialForceUnit {
    /// Force units.
    #[default]
    Force,
    /// A share of Δ²Σg over the contact at the end of the approach (Q/μP).
    FrictionLimit,
}

/// `[friction]` of a roll, slide or translate: the interface laws and the half-space's
/// tangential constants.
#[derive(Debug, Clone, Copy)]
pub struct InterfaceFriction {
    pub law: FrictionLaw,
    /// The static law of elements at rest (None: `law` throughout).
    pub static_law: Option<FrictionLaw>,
    /// D_c of slip weakening (None: the static bound drops at the first slip).
    pub slip_weakening_distance: Option<f64>,
    pub material: ShearMaterial,
    /// The drive's spring of a slide or translate (None: a rigid drive).
    pub drive_stiffness: Option<f64>,
    /// The coupled normal–tangential operator (`friction.coupling = "full"`).
    pub coupled: bool,
    /// `friction.mode_mixity` and its front and rear values (0: the edge is not weakened).
    pub mode_mixity: ModeMixity,
}

/// A validated shear run: the library's protocol, the interface law and the half-space's
/// tangential constants.
#[derive(Debug, Clone, Copy)]
pub struct ShearSetup {
    pub protocol: Shear,
    pub law: FrictionLaw,
    /// The static law of elements stuck at the start of a step (None: `law` throughout).
    pub static_law: Option<FrictionLaw>,
    /// D_c of slip weakening (None: the static bound drops at the first slip).
    pub slip_weakening_distance: Option<f64>,
    /// The drive's spring (None: a rigid drive).
    pub drive_stiffness: Option<f64>,
    pub material: ShearMaterial,
}
