//! A first contact that changes the surface (the paper's Sect. 5.2: a fresh indenter's
//! first impression pulls off differently from the second and all later ones, which the
//! authors trace to a change of the surface energy where the bodies first touched).
//! `adhesion.first_contact_factor` f: a run writes `first_contact_map.npy`, the γ map of
//! the next impression, γ/γ0 times f on every element it touched; the next run reads it as
//! its `adhesion.field = { kind = "map", file = ... }`.

use crate::checks::positive;
use crate::error::ScenarioError;
use crate::model::*;
use anyhow::{bail, Result};

/// The file a run with `adhesion.first_contact_factor` writes into its folder.
pub const FIRST_CONTACT_MAP: &str = "first_contact_map.npy";

impl ScenarioFile {
    /// `adhesion.first_contact_factor`: > 0 and finite, with γ0 > 0 and an indentation
    /// (None without the key).
    pub(crate) fn first_contact_factor(&self, gamma0: f64) -> Result<Option<f64>> {
        let Some(factor) = self.adhesion.first_contact_factor else {
            return Ok(None);
        };
        let kind = self.protocol.kind();
        if kind != ProtocolKind::IndentPulloff {
            bail!(ScenarioError::invalid_as(
                "adhesion.first_contact_factor",
                factor,
                "absent unless protocol.kind = \"indent_pulloff\"",
                format!(
                    "adhesion.first_contact_factor writes the γ map of the next impression after an indentation (protocol.kind = \"indent_pulloff\"), got protocol.kind = \"{}\"",
                    kind.name()
                )
            ));
        }
        if gamma0 <= 0.0 {
            bail!(ScenarioError::invalid_as(
                "adhesion.work_of_adhesion",
                gamma0,
                "> 0 with adhesion.first_contact_factor",
                "adhesion.first_contact_factor multiplies the work of adhesion, which is 0: give adhesion.work_of_adhesion > 0"
            ));
        }
        positive("adhesion.first_contact_factor", factor).map(Some)
    }
}

/// The γ map of the next impression, relative to γ0: γ/γ0 of each element, times `factor`
/// where the run touched it (`touched`, every element in contact at some step).
pub fn next_impression_map(gamma: &[f64], gamma0: f64, factor: f64, touched: &[bool]) -> Vec<f64> {
    gamma
        .iter()
        .zip(touched)
        .map(|(&g, &t)| g / gamma0 * if t { factor } else { 1.0 })
        .collect()
}
