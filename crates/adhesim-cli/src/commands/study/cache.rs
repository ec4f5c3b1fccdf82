//! The study's cache of finished runs.

use crate::commands::batch::write_atomically;
use adhesim_scenario::TranslationResults;
use anyhow::{Context, Result};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Finished runs of a study are kept under `<out>/cache/` so that a killed study resumes
/// where it stopped: one JSON file per run, named by its kind, index and a hash of the
/// exact scenario it ran (base after `set`, plus the case's overrides) and of the library's
/// results revision, written atomically.
pub struct RunCache {
    pub folder: PathBuf,
}

impl RunCache {
    pub fn new(out: &Path) -> Result<Self> {
        let folder = out.join("cache");
        std::fs::create_dir_all(&folder).with_context(|| format!("cannot create {}", folder.display()))?;
        Ok(Self { folder })
    }

    pub fn path(&self, name: &str, table: &toml::Table, changes: &[String]) -> PathBuf {
        let text = format!("{table}\n{}", changes.join("\n"));
        self.folder.join(format!(
            "{name}-{:016x}.json",
            crate::commands::sweep::plan::results_hash(&text)
        ))
    }

    /// The stored result, if a readable one exists (a damaged file is simply redone).
    pub fn load<T: for<'de> Deserialize<'de>>(path: &Path) -> Option<T> {
        let text = std::fs::read_to_string(path).ok()?;
        serde_json::from_str(&text).ok()
    }

    pub fn store<T: Serialize>(path: &Path, value: &T) -> Result<()> {
        write_atomically(path, (serde_json::to_string_pretty(value)? + "\n").as_bytes())
    }
}

/// Part of a rolling case's cache key: cached rolls from before γ3 was fitted against the
/// contact radius (they hold the half-width fit under `gamma3`) are redone, not misread.
pub const ROLLING_ANALYSIS: &str = "gamma3 against the contact radius, gamma3_half_width";

/// A cached normal run: γ1, γ2 and its wall time.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct NormalRecord {
    pub gamma_approach: Option<f64>,
    pub gamma_pulloff: Option<f64>,
    pub wall_seconds: f64,
}

/// A cached translation run.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct CaseRecord {
    pub results: TranslationResults,
    pub wall_seconds: f64,
}
