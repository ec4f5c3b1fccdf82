//! `material.base` as written in a scenario file.

use serde::{Deserialize, Serialize};

/// `material.base`: the layer bonded to its rigid base, or sliding on it without friction.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LayerBaseName {
    #[default]
    Bonded,
    Frictionless,
}
