//! `[solver]`: choices of the adhesive solver's rules that leave the physics unchanged
//! (each is exact up to the ties of docs/fast-step.md), for measuring them against each
//! other through `adhesim run` (BENCHMARKS.md).

use super::{BoundaryName, LawName};
use crate::error::ScenarioError;
use adhesim::solver::PredictedGrowth;
use serde::{Deserialize, Serialize};

/// `[solver]` as written in a scenario file.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSection {
    /// Predicted-subset growth of the adhesive step (docs/fast-step.md §3); default `auto`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub predicted_growth: Option<PredictedGrowthName>,
    /// The fixed-set CG on the contact's bounding box (the library's
    /// `AdhesiveParams::contact_window`); default `true`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact_window: Option<bool>,
}

/// `solver.predicted_growth`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PredictedGrowthName {
    /// From 512² elements on (the library's default).
    Auto,
    /// On every grid.
    On,
    /// Never: every ring peeled exactly.
    Off,
}

impl PredictedGrowthName {
    /// The library's rule.
    pub fn rule(self) -> PredictedGrowth {
        match self {
            Self::Auto => PredictedGrowth::Auto,
            Self::On => PredictedGrowth::On,
            Self::Off => PredictedGrowth::Off,
        }
    }

    /// As written in a scenario file.
    pub fn name(self) -> &'static str {
        match self {
            Self::Auto => "auto",
            Self::On => "on",
            Self::Off => "off",
        }
    }
}

impl SolverSection {
    /// The keys given, each with its value as written in a scenario file.
    pub(crate) fn given(&self) -> Vec<(&'static str, String)> {
        let mut keys = Vec::new();
        if let Some(rule) = self.predicted_growth {
            keys.push(("solver.predicted_growth", format!("\"{}\"", rule.name())));
        }
        if let Some(window) = self.contact_window {
            keys.push(("solver.contact_window", window.to_string()));
        }
        keys
    }

    /// Refuses a rule the run's solver would not use (a silent default otherwise): the
    /// rules of `[solver]` act in the sharp adhesive solver (γ0 > 0, `adhesion.law` absent
    /// or `"jkr"`) on free grids.
    pub(crate) fn check(&self, adhesive: bool, law: LawName, boundary: BoundaryName) -> Result<(), ScenarioError> {
        let Some((key, value)) = self.given().into_iter().next() else {
            return Ok(());
        };
        let reason = if !adhesive {
            "a run without adhesion (adhesion.work_of_adhesion = 0)".to_string()
        } else if law != LawName::Jkr {
            format!(
                "adhesion.law = \"{}\" (the cohesive solver has neither rule)",
                law.name()
            )
        } else if boundary == BoundaryName::Periodic {
            "grid.boundary = \"periodic\"".to_string()
        } else {
            return Ok(());
        };
        Err(ScenarioError::invalid_as(
            key,
            value.clone(),
            "the sharp adhesive solver on a free grid",
            format!(
                "{key} = {value} acts in the sharp adhesive solver on a free grid only; this scenario has {reason}: remove the key"
            ),
        ))
    }
}
