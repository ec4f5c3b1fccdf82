//! Scenarios of the adhesim simulator without the terminal: read a scenario (the TOML
//! format of `docs/cli.md`), override keys, validate it into library objects and run it
//! through one pipeline for every protocol. The `adhesim` command line and the Python
//! package are thin layers over this crate. It writes no files itself: outputs are
//! observers the caller passes to [`run`].
//!
//! ```
//! use adhesim_scenario::{run, RunResults, Scenario};
//!
//! let text = r#"
//! [grid]
//! n = 32
//! size = 0.3
//! [material]
//! contact_modulus = 1.0
//! [adhesion]
//! work_of_adhesion = 0.0
//! [indenter]
//! shape = "sphere"
//! radius = 1.0
//! [protocol]
//! kind = "indent_pulloff"
//! max_depth = 0.005
//! steps = 10
//! "#;
//! let mut scenario = Scenario::from_toml_str(text, "hertz.toml").unwrap();
//! scenario.apply_override("grid.n", "24").unwrap();
//! let valid = scenario.validate(std::path::Path::new(".")).unwrap();
//! let outcome = run(&valid, &mut ()).unwrap();
//! let RunResults::Indentation(results) = &outcome.results else { unreachable!() };
//! assert_eq!(results.max_adhesive_force, 0.0); // no adhesion, no tensile force
//! assert!(outcome.records.len() >= 10);
//!
//! // Errors name the key and the value.
//! scenario.apply_override("indenter.radius", "-1").unwrap();
//! let error = scenario.validate(std::path::Path::new(".")).err().unwrap();
//! assert_eq!(error.to_string(), "indenter.radius must be > 0, got -1");
//! ```

pub mod batch;
mod checks;
mod cohesive;
mod curve;
mod error;
pub mod error_text;
mod files;
mod first_contact;
mod guards;
mod hash;
mod hold;
pub mod memory;
mod model;
pub mod output;
mod parse;
mod pipeline;
mod results;
mod roughness;
mod sections;
mod shear;
mod snapshot_fields;
mod snapshot_shear;
mod snapshots;
mod summary;
pub mod sweep;
mod translation;
mod validate;
mod validated;

pub use curve::{CurveCell, CurveColumn, CurveColumns, CurveKind};
pub use error::{ErrorKind, ScenarioError};
pub use files::{check_regular_file, read_input_text, read_own_file, read_own_text};
pub use guards::{
    memory_estimate, memory_estimate_rectangle, unresolved_contact_warning, MAX_GRID_N, MAX_STEPS,
    MIN_ELEMENTS_PER_FEATURE,
};
pub use memory::{memory_available, memory_limit, MemoryLimit};
pub use model::*;
pub use parse::{read_height_map, read_npy_2d};
pub use pipeline::{run, run_from, ProtocolSetup, Resume, RunOutcome};
pub use results::{fit_results, min_fit_radius, FitResults, Results, RunResults};
pub use roughness::{roughness_on_grid, RoughnessMap};
pub use shear::ShearResults;
pub use snapshot_fields::{FieldShapes, SnapshotFields, Stacked};
pub use snapshots::{FieldSnapshot, SnapshotPlan, SnapshotRecorder};
pub use summary::{border_warning, lost_contact_warning, Performance, PhaseTimes, Summary};
pub use translation::{DEFAULT_STATIONARY_FROM, DEFAULT_SUBSTRATE_ANGLE};
pub use validated::DEFAULT_APPROACH_STEPS;

pub use adhesim::analysis::friction::TranslationResults;
use std::path::Path;

/// A scenario as read: its TOML table (overrides applied) and where it came from. Not yet
/// checked; [`Scenario::validate`] turns it into a [`ValidScenario`].
#[derive(Debug, Clone)]
pub struct Scenario {
    table: toml::Table,
    origin: String,
}

impl Scenario {
    /// Parses TOML text; `origin` (a file name) goes into error messages.
    pub fn from_toml_str(text: &str, origin: &str) -> Result<Self, ScenarioError> {
        Ok(Self {
            table: parse_toml(text, origin)?,
            origin: origin.to_string(),
        })
    }

    /// Sets a dotted key (`grid.n`) to a value given as TOML text (`64`, `"free"`,
    /// `[1, 2]`; a bare word is a string), as `adhesim run --set KEY=VALUE` does.
    ///
    /// # Example
    /// ```
    /// use adhesim_scenario::Scenario;
    ///
    /// let text = "[grid]\nn = 32\nsize = 0.5\n[material]\ncontact_modulus = 1.0\n[adhesion]\nwork_of_adhesion = 0.0\n[indenter]\nshape = \"sphere\"\nradius = 1.0\n[protocol]\nkind = \"indent_pulloff\"\nmax_depth = 0.01\nsteps = 10\n";
    /// let mut scenario = Scenario::from_toml_str(text, "hertz.toml")?;
    /// scenario.apply_override("grid.n", "64")?;
    /// scenario.apply_override("grid.boundary", "periodic")?; // a bare word is a string
    /// let valid = scenario.validate(std::path::Path::new("."))?;
    /// assert_eq!((valid.grid.nx(), valid.grid.boundary()), (64, adhesim::Boundary::Periodic));
    /// # Ok::<(), adhesim_scenario::ScenarioError>(())
    /// ```
    pub fn apply_override(&mut self, key: &str, value: &str) -> Result<(), ScenarioError> {
        apply_override(&mut self.table, key, value)
    }

    /// Checks every value and builds the library objects; relative file paths (height
    /// maps, adhesion maps) are resolved against `base`. Errors name the key and value.
    ///
    /// # Example
    /// ```
    /// use adhesim_scenario::Scenario;
    ///
    /// let text = r#"
    /// [grid]
    /// n = 32
    /// size = 0.5
    /// [material]
    /// youngs_modulus = 3.0
    /// poisson_ratio = 0.5
    /// [adhesion]
    /// work_of_adhesion = 0.0
    /// [indenter]
    /// shape = "sphere"
    /// radius = 1.0
    /// [friction]
    /// law = "coulomb"
    /// [protocol]
    /// kind = "shear"
    /// depth = 0.01
    /// depth_unit = "length"
    /// distance = 0.004
    /// steps = 4
    /// "#;
    /// let mut scenario = Scenario::from_toml_str(text, "shear.toml")?;
    /// let error = scenario.validate(std::path::Path::new(".")).err().unwrap();
    /// assert!(error.to_string().contains("friction.coefficient"), "{error}");
    /// scenario.apply_override("friction.coefficient", "0.3")?;
    /// scenario.apply_override("friction.mode_mixity", "2.0")?;
    /// let error = scenario.validate(std::path::Path::new(".")).err().unwrap();
    /// assert!(error.to_string().contains("friction.mode_mixity"), "{error}");
    /// # Ok::<(), adhesim_scenario::ScenarioError>(())
    /// ```
    pub fn validate(&self, base: &Path) -> Result<ValidScenario, ScenarioError> {
        deserialize(&self.table)?.validate(base)
    }

    /// The TOML table (after overrides).
    pub fn table(&self) -> &toml::Table {
        &self.table
    }

    /// Where the text came from.
    pub fn origin(&self) -> &str {
        &self.origin
    }
}

/// Parses TOML text into a table (with `origin`, the file name, in the message on failure).
pub fn parse_toml(text: &str, origin: &str) -> Result<toml::Table, ScenarioError> {
    parse::parse_toml(text, origin).map_err(ScenarioError::from_anyhow)
}

/// Applies `KEY=VALUE` overrides, as `--set` does; VALUE is read as a TOML value (`3`,
/// `0.5`, `"free"`, `[1, 2]`), and as a bare string when it does not parse as one.
pub fn apply_overrides(table: &mut toml::Table, overrides: &[String]) -> Result<(), ScenarioError> {
    parse::apply_overrides(table, overrides).map_err(ScenarioError::from_anyhow)
}

/// Sets one dotted `key` to `raw`, read as a TOML value (a bare string when it does not
/// parse as one); missing tables on the way are created.
pub fn apply_override(table: &mut toml::Table, key: &str, raw: &str) -> Result<(), ScenarioError> {
    parse::apply_override(table, key, raw).map_err(ScenarioError::from_anyhow)
}

/// Deserialises the table section by section; every error names the dotted key.
pub fn deserialize(table: &toml::Table) -> Result<ScenarioFile, ScenarioError> {
    parse::deserialize(table).map_err(ScenarioError::from_anyhow)
}

impl ScenarioFile {
    /// Checks every value and builds the library objects, one section after the other.
    /// `base` resolves relative file paths. Errors name the key and the value.
    pub fn validate(self, base: &Path) -> Result<ValidScenario, ScenarioError> {
        self.validate_sections(base).map_err(ScenarioError::from_anyhow)
    }

    /// Refuses ([`ErrorKind::Resources`], naming `grid.n`, the estimate and the limit) a
    /// scenario of which `runs` concurrent runs need more than `limit` allows. Call it
    /// before [`ScenarioFile::validate`], which allocates the grid's fields.
    pub fn check_memory(&self, limit: &MemoryLimit, runs: u64) -> Result<(), ScenarioError> {
        self.check_memory_of_runs(limit, runs)
            .map_err(ScenarioError::from_anyhow)
    }
}

/// Reads, overrides (`KEY=VALUE` items), deserialises and validates a scenario.
pub fn load(text: &str, origin: &str, base: &Path, overrides: &[String]) -> Result<ValidScenario, ScenarioError> {
    load_within(text, origin, base, overrides, None)
}

/// [`load`], refusing before the grid's fields are allocated a scenario whose
/// [`memory_estimate`] exceeds `available_memory` (`None`: no limit; [`memory_available`]
/// reads the limits of this process).
pub fn load_within(
    text: &str,
    origin: &str,
    base: &Path,
    overrides: &[String],
    available_memory: Option<&MemoryLimit>,
) -> Result<ValidScenario, ScenarioError> {
    let mut table = parse_toml(text, origin)?;
    apply_overrides(&mut table, overrides)?;
    let file = deserialize(&table)?;
    if let Some(limit) = available_memory {
        file.check_memory(limit, 1)?;
    }
    file.validate(base)
}

#[cfg(test)]
mod aging_tests;
#[cfg(test)]
mod cohesive_tests;
#[cfg(test)]
mod error_tests;
#[cfg(test)]
mod first_contact_tests;
#[cfg(test)]
mod friction_tests;
#[cfg(test)]
mod guards_tests;
#[cfg(test)]
mod layer_tests;
#[cfg(test)]
mod shull_tests;
#[cfg(test)]
mod solver_tests;
#[cfg(test)]
mod tests;
