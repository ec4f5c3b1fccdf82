//! `[adhesion]` as written in a scenario file: the work of adhesion, its law, and its
//! aging (a work of adhesion that grows with the time an element has been in contact,
//! during a hold, `protocol.hold_time`).

use super::FieldSpec;
use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AdhesionSection {
    pub work_of_adhesion: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub field: Option<FieldSpec>,
    /// The adhesion law; absent means `jkr` (and is echoed absent).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub law: Option<LawName>,
    /// σ0 of `law = "dugdale"` or `"trapezoid"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cohesive_stress: Option<f64>,
    /// s ∈ (0, 1] of `law = "trapezoid"`: the fraction of the range over which the
    /// traction falls.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub softening_fraction: Option<f64>,
    /// ρ of `law = "exponential"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub range: Option<f64>,
    /// f: the surface energy changes by this factor where the indentation touched; the run
    /// writes the γ map of the next impression (`first_contact_map.npy`; the paper's
    /// Sect. 5.2).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub first_contact_factor: Option<f64>,
    /// Aging bonds during a hold (`protocol.hold_time`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub aging: Option<AgingSection>,
}

/// `adhesion.law`: the paper's sharp JKR-type criterion, or a cohesive law of finite range.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LawName {
    #[default]
    Jkr,
    Dugdale,
    Exponential,
    Trapezoid,
}

impl LawName {
    pub fn name(self) -> &'static str {
        match self {
            Self::Jkr => "jkr",
            Self::Dugdale => "dugdale",
            Self::Exponential => "exponential",
            Self::Trapezoid => "trapezoid",
        }
    }
}

/// `adhesion.aging`: γ(t) = γ0·(1 + t/t_ref)^β (`law = "power"`, `exponent` β) or
/// γ0·[1 + b·ln(1 + t/t_ref)] (`law = "logarithmic"`, `coefficient` b), with t the time an
/// element has been in contact, in the unit of `protocol.hold_time`.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AgingSection {
    pub law: AgingLawName,
    /// β of `power`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub exponent: Option<f64>,
    /// b of `logarithmic`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coefficient: Option<f64>,
    /// t_ref > 0.
    pub reference_time: f64,
}

/// `adhesion.aging.law`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AgingLawName {
    Power,
    Logarithmic,
}
