//! Scenario files: a serde mirror of the TOML (`docs/cli.md`, `shared/design/interface.md`),
//! generic `--set KEY=VALUE` overrides on the parsed TOML value, and `validate()` into
//! library objects.
//!
//! Every error names the dotted key at fault and the value it had
//! (`indenter.radius must be > 0, got -1`); nothing here panics on bad input.

use adhesim::analysis::reference::{johnson_parameter, Jkr};
use adhesim::analysis::scale::adhesive_force_scale;
use adhesim::geometry::{EllipticPunch, FlatPunch, Sphere, Topography, WavySphere};
use adhesim::solver::critical_stress;
use adhesim::{
    Axis, Boundary, ElasticMaterial, Grid, Indenter, Kinematics, Profile, TranslatingContact, Translation,
    WorkOfAdhesion,
};
use anyhow::{anyhow, bail, Context, Result};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

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
    fn is_empty(&self) -> bool {
        self.gamma_approach.is_none() && self.gamma_pulloff.is_none() && self.tau0.is_none()
    }
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GridSection {
    /// Elements per side (kept signed so that a negative value gets our own message).
    pub n: i64,
    pub size: f64,
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
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AdhesionSection {
    pub work_of_adhesion: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub field: Option<FieldSpec>,
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

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ShapeName {
    Sphere,
    WavySphere,
    FlatPunch,
    EllipticPunch,
    Topography,
}

impl ShapeName {
    fn name(self) -> &'static str {
        match self {
            Self::Sphere => "sphere",
            Self::WavySphere => "wavy_sphere",
            Self::FlatPunch => "flat_punch",
            Self::EllipticPunch => "elliptic_punch",
            Self::Topography => "topography",
        }
    }
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IndenterSection {
    pub shape: ShapeName,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub amplitude: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wavelength: Option<f64>,
    /// Degrees.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub angle: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub semi_axes: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<PathBuf>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spacing: Option<f64>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ProtocolKind {
    IndentPulloff,
    Roll,
    Slide,
    /// The frictionless control: the whole rough profile translates over a smooth body.
    Translate,
}

impl ProtocolKind {
    pub fn name(self) -> &'static str {
        match self {
            Self::IndentPulloff => "indent_pulloff",
            Self::Roll => "roll",
            Self::Slide => "slide",
            Self::Translate => "translate",
        }
    }

    /// Roll, slide or translate: motion at fixed indentation.
    pub fn is_translation(self) -> bool {
        !matches!(self, Self::IndentPulloff)
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

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProtocolSection {
    pub kind: ProtocolKind,
    /// Deepest indentation of `indent_pulloff`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_depth: Option<f64>,
    #[serde(default)]
    pub depth_unit: DepthUnit,
    /// roll / slide / translate: indentation held during the motion (in `depth_unit`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub depth: Option<f64>,
    /// roll / slide / translate: travel of the indenter axis in +x.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub distance: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub distance_unit: Option<DistanceUnit>,
    /// roll / slide / translate: steps of the approach to `depth` (default 50).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub approach_steps: Option<i64>,
    /// roll / slide / translate: travel back to x = 0 after the forward stroke.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub return_stroke: Option<bool>,
    /// roll / slide / translate: means are taken over x > stationary_from·distance (default 0.5).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stationary_from: Option<f64>,
    /// slide: rotation of the substrate's waviness against the indenter's, degrees (default 30).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub substrate_angle: Option<f64>,
    /// Steps per branch (approach); the retraction uses the same step size.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steps: Option<i64>,
    /// Step size in `depth_unit` (alternative to `steps`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub step: Option<f64>,
    /// Safety limit on retraction steps (default: 20 × the approach steps, at least 1000).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_retract_steps: Option<i64>,
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
pub struct Scenario {
    pub file: ScenarioFile,
    pub grid: Grid,
    pub material: ElasticMaterial,
    /// γ per element.
    pub gamma: Vec<f64>,
    /// Reference γ0.
    pub gamma0: f64,
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
}

/// A validated roll / slide / translate protocol.
#[derive(Debug, Clone, Copy)]
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
}

/// Derived quantities for `summary.json`; `None` is written as null.
#[derive(Debug, Clone, Serialize)]
pub struct Derived {
    pub f_jkr: Option<f64>,
    pub d_jkr: Option<f64>,
    pub a_jkr: Option<f64>,
    pub johnson_parameter: Option<f64>,
    pub element_size: f64,
    pub critical_stress: Option<f64>,
}

/// Parses TOML text into a table (with the file name in the message on failure).
pub fn parse_toml(text: &str, origin: &str) -> Result<toml::Table> {
    text.parse::<toml::Table>()
        .map_err(|e| anyhow!("{origin}: malformed TOML: {}", e.to_string().trim_end()))
}

/// Applies `KEY=VALUE` overrides; VALUE is read as a TOML value (`3`, `0.5`, `"free"`,
/// `[1, 2]`), and as a bare string when it does not parse as one.
pub fn apply_overrides(table: &mut toml::Table, overrides: &[String]) -> Result<()> {
    for item in overrides {
        let (key, raw) = item
            .split_once('=')
            .ok_or_else(|| anyhow!("--set expects KEY=VALUE, got `{item}`"))?;
        let key = key.trim();
        let raw = raw.trim();
        if key.is_empty() || key.split('.').any(str::is_empty) {
            bail!("--set: invalid key `{key}`");
        }
        let value = match format!("v = {raw}").parse::<toml::Table>() {
            Ok(mut t) => t.remove("v").expect("parsed table holds v"),
            Err(_) => toml::Value::String(raw.to_string()),
        };
        let parts: Vec<&str> = key.split('.').collect();
        let mut current = &mut *table;
        for (depth, part) in parts[..parts.len() - 1].iter().enumerate() {
            let entry = current
                .entry(part.to_string())
                .or_insert_with(|| toml::Value::Table(toml::Table::new()));
            current = entry
                .as_table_mut()
                .ok_or_else(|| anyhow!("--set {key}: `{}` is not a table", parts[..=depth].join(".")))?;
        }
        current.insert(parts[parts.len() - 1].to_string(), value);
    }
    Ok(())
}

const SECTIONS: [&str; 7] = [
    "grid", "material", "adhesion", "indenter", "protocol", "output", "analysis",
];

/// Deserialises the table section by section so that every message names the dotted key.
pub fn deserialize(table: &toml::Table) -> Result<ScenarioFile> {
    for key in table.keys() {
        if !SECTIONS.contains(&key.as_str()) {
            bail!(
                "unknown key `{key}` (expected one of: {})",
                SECTIONS.map(|s| format!("[{s}]")).join(", ")
            );
        }
    }
    fn section<T: serde::de::DeserializeOwned>(table: &toml::Table, name: &str, required: bool) -> Result<Option<T>> {
        let Some(value) = table.get(name) else {
            if required {
                bail!("missing section [{name}]");
            }
            return Ok(None);
        };
        if !value.is_table() {
            bail!("`{name}` must be a table [{name}], got {value}");
        }
        T::deserialize(value.clone())
            .map(Some)
            .map_err(|e| section_error(name, value, e))
    }
    let grid = section(table, "grid", true)?.expect("required");
    let material = section(table, "material", true)?.expect("required");
    let adhesion = section(table, "adhesion", true)?.expect("required");
    let indenter = section(table, "indenter", true)?.expect("required");
    let protocol = section(table, "protocol", true)?.expect("required");
    let output = section(table, "output", false)?.unwrap_or_default();
    let analysis = section(table, "analysis", false)?.unwrap_or_default();
    Ok(ScenarioFile {
        grid,
        material,
        adhesion,
        indenter,
        protocol,
        output,
        analysis,
    })
}

/// Turns a serde error inside section `name` into a message with the dotted key.
fn section_error(name: &str, value: &toml::Value, error: toml::de::Error) -> anyhow::Error {
    let message = error.message().trim().to_string();
    if let Some(rest) = message.strip_prefix("unknown field `") {
        if let Some((field, tail)) = rest.split_once('`') {
            let in_field_table = name == "adhesion" && value.get("field").is_some() && value.get(field).is_none();
            let key = if in_field_table {
                format!("{name}.field.{field}")
            } else {
                format!("{name}.{field}")
            };
            let tail = tail.trim_start_matches(',').trim();
            return if tail.is_empty() {
                anyhow!("unknown key `{key}`")
            } else {
                anyhow!("unknown key `{key}` ({tail})")
            };
        }
    }
    if let Some(rest) = message.strip_prefix("missing field `") {
        if let Some((field, _)) = rest.split_once('`') {
            return anyhow!("missing key `{name}.{field}`");
        }
    }
    // A type or value error: name the key whose value the message quotes or whose type
    // it names (serde writes `invalid type: string "a", expected f64`).
    let mut leaves = Vec::new();
    collect_leaves(name, value, &mut leaves);
    let quoted = leaves.iter().find(|(_, item)| {
        let shown = item.to_string();
        let raw = item
            .as_str()
            .map(|s| format!("`{s}`"))
            .unwrap_or_else(|| format!("`{shown}`"));
        message.contains(&raw) || message.contains(&format!(" {shown},"))
    });
    let typed = || {
        leaves
            .iter()
            .find(|(_, item)| message.contains(&format!("invalid type: {}", serde_kind(item.type_str()))))
    };
    if let Some((key, item)) = quoted.or_else(typed) {
        return anyhow!("{key} = {item}: {message}");
    }
    anyhow!("[{name}]: {message}")
}

/// Dotted keys and values of every non-table value below `value`.
fn collect_leaves(prefix: &str, value: &toml::Value, out: &mut Vec<(String, toml::Value)>) {
    match value.as_table() {
        Some(table) => {
            for (key, item) in table {
                collect_leaves(&format!("{prefix}.{key}"), item, out);
            }
        }
        None => out.push((prefix.to_string(), value.clone())),
    }
}

fn serde_kind(toml_type: &str) -> &'static str {
    match toml_type {
        "string" => "string",
        "integer" => "integer",
        "float" => "floating point",
        "boolean" => "boolean",
        "array" => "sequence",
        "table" => "map",
        _ => "?",
    }
}

fn positive(key: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        bail!("{key} must be > 0, got {value}")
    }
}

fn non_negative(key: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        bail!("{key} must be >= 0, got {value}")
    }
}

fn finite(key: &str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        bail!("{key} must be finite, got {value}")
    }
}

fn required<T: Copy>(key: &str, value: Option<T>, shape: ShapeName) -> Result<T> {
    value.ok_or_else(|| anyhow!("{key} is required for indenter.shape = \"{}\"", shape.name()))
}

/// Reads a 2-D `.npy` array of f64 (or f32) as (row-major values, rows, columns).
pub fn read_npy_2d(path: &Path, key: &str) -> Result<(Vec<f64>, usize, usize)> {
    use ndarray_npy::ReadNpyExt;
    let open = || std::fs::File::open(path).with_context(|| format!("{key} = {}: cannot open", path.display()));
    let array: ndarray::Array2<f64> = match ndarray::Array2::<f64>::read_npy(open()?) {
        Ok(a) => a,
        Err(first) => match ndarray::Array2::<f32>::read_npy(open()?) {
            Ok(a) => a.mapv(f64::from),
            Err(_) => bail!(
                "{key} = {}: not a 2-D .npy array of f64 or f32 ({first})",
                path.display()
            ),
        },
    };
    let (rows, columns) = array.dim();
    Ok((array.iter().copied().collect(), rows, columns))
}

impl ScenarioFile {
    /// Checks every value and builds the library objects. `base` resolves relative file paths.
    pub fn validate(self, base: &Path) -> Result<Scenario> {
        // [grid]
        let n = self.grid.n;
        if n < 2 {
            bail!("grid.n must be >= 2, got {n}");
        }
        if n > 16_384 {
            bail!("grid.n must be <= 16384, got {n}");
        }
        let n = n as usize;
        let size = positive("grid.size", self.grid.size)?;
        let boundary = match self.grid.boundary {
            BoundaryName::Free => Boundary::Free,
            BoundaryName::Periodic => Boundary::Periodic,
        };
        let grid = Grid::new(n, size, boundary).map_err(|e| anyhow!("[grid]: {e}"))?;

        // [material]
        let m = &self.material;
        let material = match (m.contact_modulus, m.youngs_modulus, m.poisson_ratio) {
            (Some(e), None, None) => ElasticMaterial::new(positive("material.contact_modulus", e)?)?,
            (None, Some(e), Some(nu)) => {
                positive("material.youngs_modulus", e)?;
                if !(nu > -1.0 && nu <= 0.5) {
                    bail!("material.poisson_ratio must lie in (-1, 0.5], got {nu}");
                }
                ElasticMaterial::from_youngs_modulus(e, nu)?
            }
            (None, Some(_), None) => bail!("material.poisson_ratio is required with material.youngs_modulus"),
            (None, None, Some(_)) => bail!("material.youngs_modulus is required with material.poisson_ratio"),
            (None, None, None) => {
                bail!("[material] needs contact_modulus, or youngs_modulus and poisson_ratio")
            }
            (Some(_), _, _) => bail!(
                "material.contact_modulus cannot be combined with material.youngs_modulus/poisson_ratio; give one form"
            ),
        };
        let contact_modulus = material.contact_modulus();

        // [indenter]
        let ind = &self.indenter;
        let shape = ind.shape;
        let allowed: &[&str] = match shape {
            ShapeName::Sphere => &["radius"],
            ShapeName::WavySphere => &["radius", "amplitude", "wavelength", "angle"],
            ShapeName::FlatPunch => &["radius"],
            ShapeName::EllipticPunch => &["semi_axes", "angle"],
            ShapeName::Topography => &["file", "spacing"],
        };
        let present = [
            ("radius", ind.radius.is_some()),
            ("amplitude", ind.amplitude.is_some()),
            ("wavelength", ind.wavelength.is_some()),
            ("angle", ind.angle.is_some()),
            ("semi_axes", ind.semi_axes.is_some()),
            ("file", ind.file.is_some()),
            ("spacing", ind.spacing.is_some()),
        ];
        for (key, is_set) in present {
            if is_set && !allowed.contains(&key) {
                bail!(
                    "indenter.{key} is not used by indenter.shape = \"{}\" (its keys: {})",
                    shape.name(),
                    allowed.join(", ")
                );
            }
        }
        let angle_degrees = finite("indenter.angle", ind.angle.unwrap_or(0.0))?;
        let angle = angle_degrees.to_radians();
        let indenter = match shape {
            ShapeName::Sphere => {
                let radius = positive("indenter.radius", required("indenter.radius", ind.radius, shape)?)?;
                Indenter::Sphere(Sphere::new(radius)?)
            }
            ShapeName::WavySphere => {
                let radius = positive("indenter.radius", required("indenter.radius", ind.radius, shape)?)?;
                let amplitude = non_negative(
                    "indenter.amplitude",
                    required("indenter.amplitude", ind.amplitude, shape)?,
                )?;
                let wavelength = positive(
                    "indenter.wavelength",
                    required("indenter.wavelength", ind.wavelength, shape)?,
                )?;
                Indenter::WavySphere(WavySphere::new(radius, amplitude, wavelength, angle)?)
            }
            ShapeName::FlatPunch => {
                let radius = positive("indenter.radius", required("indenter.radius", ind.radius, shape)?)?;
                Indenter::FlatPunch(FlatPunch::new(radius)?)
            }
            ShapeName::EllipticPunch => {
                let axes = ind
                    .semi_axes
                    .as_ref()
                    .ok_or_else(|| anyhow!("indenter.semi_axes is required for indenter.shape = \"elliptic_punch\""))?;
                if axes.len() != 2 {
                    bail!("indenter.semi_axes must be [a, b], got {axes:?}");
                }
                let a = positive("indenter.semi_axes[0]", axes[0])?;
                let b = positive("indenter.semi_axes[1]", axes[1])?;
                Indenter::EllipticPunch(EllipticPunch::new((a, b), angle)?)
            }
            ShapeName::Topography => {
                let file = ind
                    .file
                    .as_ref()
                    .ok_or_else(|| anyhow!("indenter.file is required for indenter.shape = \"topography\""))?;
                let spacing = positive("indenter.spacing", required("indenter.spacing", ind.spacing, shape)?)?;
                let (values, rows, columns) = read_npy_2d(&base.join(file), "indenter.file")?;
                Indenter::Topography(
                    Topography::new(values, rows, columns, spacing)
                        .map_err(|e| anyhow!("indenter.file = {}: {e}", file.display()))?,
                )
            }
        };
        let heights = indenter.heights(&grid);
        let start_depth = heights
            .iter()
            .copied()
            .filter(|h| h.is_finite())
            .fold(f64::INFINITY, f64::min);
        if !start_depth.is_finite() {
            bail!(
                "the indenter (indenter.shape = \"{}\") has no surface inside the domain: enlarge grid.size ({size}) or grid.n ({n})",
                shape.name()
            );
        }

        // [adhesion]
        let gamma0 = non_negative("adhesion.work_of_adhesion", self.adhesion.work_of_adhesion)?;
        let adhesion = match &self.adhesion.field {
            None => WorkOfAdhesion::Uniform(gamma0),
            Some(FieldSpec::Quadratic {
                ratio_edge_to_centre,
                axis,
                half_length,
            }) => {
                let ratio = positive("adhesion.field.ratio_edge_to_centre", *ratio_edge_to_centre)?;
                let default_half_length = match (&indenter, axis) {
                    (Indenter::EllipticPunch(p), AxisName::X) => Some(p.semi_axes().0),
                    (Indenter::EllipticPunch(p), AxisName::Y) => Some(p.semi_axes().1),
                    (Indenter::FlatPunch(p), _) => Some(p.radius()),
                    _ => None,
                };
                let half_length = match half_length {
                    Some(h) => positive("adhesion.field.half_length", *h)?,
                    None => default_half_length.ok_or_else(|| {
                        anyhow!(
                            "adhesion.field.half_length is required for indenter.shape = \"{}\" (defaults exist only for punches)",
                            shape.name()
                        )
                    })?,
                };
                WorkOfAdhesion::Quadratic {
                    middle: gamma0,
                    ratio_end_to_middle: ratio,
                    half_length,
                    axis: match axis {
                        AxisName::X => Axis::X,
                        AxisName::Y => Axis::Y,
                    },
                }
            }
            Some(FieldSpec::Map { file }) => {
                let (values, rows, columns) = read_npy_2d(&base.join(file), "adhesion.field.file")?;
                if rows != n || columns != n {
                    bail!(
                        "adhesion.field.file = {}: the map is {rows}×{columns}, the grid is {n}×{n} (grid.n = {n})",
                        file.display()
                    );
                }
                if let Some(bad) = values.iter().find(|v| !(v.is_finite() && **v >= 0.0)) {
                    bail!(
                        "adhesion.field.file = {}: values must be finite and >= 0, found {bad}",
                        file.display()
                    );
                }
                WorkOfAdhesion::Map(values.into_iter().map(|v| v * gamma0).collect())
            }
        };
        let gamma = adhesion.on_grid(&grid).map_err(|e| anyhow!("[adhesion]: {e}"))?;
        if gamma0 == 0.0 && self.adhesion.field.is_some() {
            bail!("adhesion.field needs adhesion.work_of_adhesion > 0, got 0");
        }

        // Derived JKR scales.
        let delta = grid.element_size();
        let jkr = match (gamma0 > 0.0, indenter.radius_of_curvature()) {
            (true, Some(radius)) => Some(Jkr {
                radius,
                contact_modulus,
                work_of_adhesion: gamma0,
            }),
            _ => None,
        };
        let johnson = match &indenter {
            Indenter::WavySphere(w) if w.waviness().amplitude() > 0.0 => Some(johnson_parameter(
                w.waviness().wavelength(),
                w.waviness().amplitude(),
                gamma0,
                contact_modulus,
            )),
            _ => None,
        };
        let derived = Derived {
            f_jkr: jkr.map(|j| j.critical_force()),
            d_jkr: jkr.map(|j| j.critical_depth()),
            a_jkr: jkr.map(|j| j.critical_radius()),
            johnson_parameter: johnson,
            element_size: delta,
            critical_stress: (gamma0 > 0.0).then(|| critical_stress(contact_modulus, gamma0, delta)),
        };

        // [protocol]
        let p = &self.protocol;
        if p.kind.is_translation() && !matches!(shape, ShapeName::Sphere | ShapeName::WavySphere) {
            bail!(
                "protocol.kind = \"{}\" needs indenter.shape = \"wavy_sphere\" or \"sphere\", got \"{}\"",
                p.kind.name(),
                shape.name()
            );
        }
        let unit = match p.depth_unit {
            DepthUnit::Length => 1.0,
            DepthUnit::Jkr => match jkr {
                Some(j) => j.critical_depth().abs(),
                None => bail!(
                    "protocol.depth_unit = \"jkr\" needs adhesion.work_of_adhesion > 0 (got {gamma0}) and a curved indenter (indenter.shape = \"{}\")",
                    shape.name()
                ),
            },
        };
        if p.kind.is_translation() {
            return self.validate_translation(TranslationInputs {
                grid,
                material,
                gamma,
                gamma0,
                indenter,
                unit,
                jkr,
                derived,
            });
        }
        for (key, is_set) in [
            ("depth", p.depth.is_some()),
            ("distance", p.distance.is_some()),
            ("distance_unit", p.distance_unit.is_some()),
            ("approach_steps", p.approach_steps.is_some()),
            ("return_stroke", p.return_stroke.is_some()),
            ("stationary_from", p.stationary_from.is_some()),
            ("substrate_angle", p.substrate_angle.is_some()),
        ] {
            if is_set {
                bail!(
                    "protocol.{key} is not used by protocol.kind = \"indent_pulloff\" (it belongs to \"roll\", \"slide\", \"translate\")"
                );
            }
        }
        if !self.analysis.is_empty() {
            bail!(
                "[analysis] (gamma_approach, gamma_pulloff, tau0) is used by protocol.kind = \"roll\" / \"slide\" only"
            );
        }
        let raw_max_depth = p.max_depth.ok_or_else(|| {
            anyhow!("missing key `protocol.max_depth` (needed by protocol.kind = \"indent_pulloff\")")
        })?;
        let max_depth = finite("protocol.max_depth", raw_max_depth)? * unit;
        if max_depth <= start_depth {
            bail!(
                "protocol.max_depth must exceed the depth of first contact ({:.6e} in length units), got {}",
                start_depth / unit,
                raw_max_depth
            );
        }
        let span = max_depth - start_depth;
        let depth_step = match (p.steps, p.step) {
            (Some(steps), None) => {
                if steps < 1 {
                    bail!("protocol.steps must be >= 1, got {steps}");
                }
                span / steps as f64
            }
            (None, Some(step)) => positive("protocol.step", step)? * unit,
            (Some(_), Some(_)) => bail!("give either protocol.steps or protocol.step, not both"),
            (None, None) => bail!("missing key `protocol.steps` (or `protocol.step`)"),
        };
        let approach_steps = (span / depth_step).ceil() as usize;
        if approach_steps > 10_000_000 {
            bail!("protocol.step is too small: {approach_steps} approach steps");
        }
        let max_retract_steps = match p.max_retract_steps {
            Some(s) if s < 1 => bail!("protocol.max_retract_steps must be >= 1, got {s}"),
            Some(s) => s as usize,
            None => (20 * approach_steps).max(1000),
        };

        let jump_force_threshold = self.output_checks(gamma0, &jkr, &indenter, contact_modulus)?;

        Ok(Scenario {
            file: self,
            grid,
            material,
            gamma,
            gamma0,
            indenter,
            heights,
            start_depth,
            max_depth,
            depth_step,
            approach_steps,
            max_retract_steps,
            jkr,
            derived,
            jump_force_threshold,
            translation: None,
        })
    }

    /// Checks `[output]` and returns the absolute jump force threshold.
    fn output_checks(&self, gamma0: f64, jkr: &Option<Jkr>, indenter: &Indenter, contact_modulus: f64) -> Result<f64> {
        let o = &self.output;
        for &s in &o.snapshot_steps {
            if s < 0 {
                bail!("output.snapshot_steps must hold steps >= 0, got {s}");
            }
        }
        if o.snapshot_every < 0 {
            bail!("output.snapshot_every must be >= 0, got {}", o.snapshot_every);
        }
        if o.jump_snapshot_elements < 1 {
            bail!(
                "output.jump_snapshot_elements must be >= 1, got {}",
                o.jump_snapshot_elements
            );
        }
        if o.max_snapshots < 0 {
            bail!("output.max_snapshots must be >= 0, got {}", o.max_snapshots);
        }
        non_negative("output.jump_force_threshold", o.jump_force_threshold)?;
        if let Some(radius) = o.min_fit_radius {
            non_negative("output.min_fit_radius", radius)?;
        }
        let force_scale = adhesive_force_scale(indenter, jkr.as_ref(), contact_modulus, gamma0);
        Ok(o.jump_force_threshold * force_scale)
    }
}

/// What `validate` has built before the protocol section, handed to the roll/slide part.
struct TranslationInputs {
    grid: Grid,
    material: ElasticMaterial,
    gamma: Vec<f64>,
    gamma0: f64,
    indenter: Indenter,
    /// Length of one `depth_unit`.
    unit: f64,
    jkr: Option<Jkr>,
    derived: Derived,
}

/// Default approach steps of roll / slide / translate.
pub const DEFAULT_APPROACH_STEPS: i64 = 50;
/// Default stationary fraction.
pub const DEFAULT_STATIONARY_FROM: f64 = 0.5;
/// Default substrate angle of a slide, degrees.
pub const DEFAULT_SUBSTRATE_ANGLE: f64 = 30.0;

impl ScenarioFile {
    /// `[protocol]` of kind roll / slide / translate (and `[analysis]`).
    fn validate_translation(self, inputs: TranslationInputs) -> Result<Scenario> {
        let TranslationInputs {
            grid,
            material,
            gamma,
            gamma0,
            indenter,
            unit,
            jkr,
            derived,
        } = inputs;
        let p = &self.protocol;
        let kind = p.kind;
        let name = kind.name();
        for (key, is_set) in [
            ("max_depth", p.max_depth.is_some()),
            ("step", p.step.is_some()),
            ("max_retract_steps", p.max_retract_steps.is_some()),
        ] {
            if is_set {
                let hint = if key == "max_depth" {
                    " (use protocol.depth)"
                } else {
                    ""
                };
                bail!("protocol.{key} is not used by protocol.kind = \"{name}\"{hint}");
            }
        }
        if p.substrate_angle.is_some() && kind != ProtocolKind::Slide {
            bail!("protocol.substrate_angle is used by protocol.kind = \"slide\" only, not \"{name}\"");
        }
        let wavy = match &indenter {
            Indenter::WavySphere(w) => *w,
            Indenter::Sphere(s) => WavySphere::new(s.radius(), 0.0, grid.size(), 0.0)?,
            _ => bail!(
                "protocol.kind = \"{name}\" needs indenter.shape = \"wavy_sphere\" or \"sphere\", got \"{}\"",
                self.indenter.shape.name()
            ),
        };
        let wavelength = matches!(indenter, Indenter::WavySphere(_)).then(|| wavy.waviness().wavelength());
        let kinematics = match kind {
            ProtocolKind::Roll => Kinematics::Roll,
            ProtocolKind::Translate => Kinematics::Translate,
            _ => {
                let degrees = finite(
                    "protocol.substrate_angle",
                    p.substrate_angle.unwrap_or(DEFAULT_SUBSTRATE_ANGLE),
                )?;
                Kinematics::Slide {
                    substrate_angle: degrees.to_radians(),
                }
            }
        };
        let contact = TranslatingContact::new(wavy, kinematics);
        let mut heights = vec![0.0; grid.len()];
        contact.fill_heights(&grid, 0.0, &mut heights);
        let start_depth = heights.iter().copied().fold(f64::INFINITY, f64::min);
        let raw_depth = p
            .depth
            .ok_or_else(|| anyhow!("missing key `protocol.depth` (needed by protocol.kind = \"{name}\")"))?;
        let depth = finite("protocol.depth", raw_depth)? * unit;
        if depth <= start_depth {
            bail!(
                "protocol.depth must exceed the depth of first contact ({:.6e} in depth_unit), got {raw_depth}",
                start_depth / unit
            );
        }
        let raw_distance = p
            .distance
            .ok_or_else(|| anyhow!("missing key `protocol.distance` (needed by protocol.kind = \"{name}\")"))?;
        let distance_scale = match p.distance_unit.unwrap_or_default() {
            DistanceUnit::Length => 1.0,
            DistanceUnit::Wavelength => wavelength.ok_or_else(|| {
                anyhow!(
                    "protocol.distance_unit = \"wavelength\" needs indenter.shape = \"wavy_sphere\" (its indenter.wavelength)"
                )
            })?,
        };
        let distance = positive("protocol.distance", raw_distance)? * distance_scale;
        let steps = p
            .steps
            .ok_or_else(|| anyhow!("missing key `protocol.steps` (steps of the travel, protocol.kind = \"{name}\")"))?;
        if !(1..=10_000_000).contains(&steps) {
            bail!("protocol.steps must be in 1..=10000000, got {steps}");
        }
        let approach_steps = p.approach_steps.unwrap_or(DEFAULT_APPROACH_STEPS);
        if !(1..=10_000_000).contains(&approach_steps) {
            bail!("protocol.approach_steps must be in 1..=10000000, got {approach_steps}");
        }
        let stationary_from = p.stationary_from.unwrap_or(DEFAULT_STATIONARY_FROM);
        if !(0.0..1.0).contains(&stationary_from) {
            bail!("protocol.stationary_from must lie in [0, 1), got {stationary_from}");
        }
        let a = &self.analysis;
        let gammas = match (a.gamma_approach, a.gamma_pulloff) {
            (Some(g1), Some(g2)) => Some((
                non_negative("analysis.gamma_approach", g1)?,
                non_negative("analysis.gamma_pulloff", g2)?,
            )),
            (None, None) => None,
            (Some(_), None) => bail!("analysis.gamma_pulloff is required with analysis.gamma_approach"),
            (None, Some(_)) => bail!("analysis.gamma_approach is required with analysis.gamma_pulloff"),
        };
        let tau0 = a.tau0.map(|t| non_negative("analysis.tau0", t)).transpose()?;
        let jump_force_threshold = self.output_checks(gamma0, &jkr, &indenter, material.contact_modulus())?;
        let protocol = Translation {
            start_depth,
            depth,
            approach_steps: approach_steps as usize,
            distance,
            steps: steps as usize,
            return_stroke: p.return_stroke.unwrap_or(false),
            stationary_from,
            jump_force_threshold,
        };
        Ok(Scenario {
            file: self,
            grid,
            material,
            gamma,
            gamma0,
            indenter,
            heights,
            start_depth,
            max_depth: depth,
            depth_step: (depth - start_depth) / approach_steps as f64,
            approach_steps: approach_steps as usize,
            max_retract_steps: 0,
            jkr,
            derived,
            jump_force_threshold,
            translation: Some(TranslationSetup {
                kind,
                contact,
                protocol,
                gammas,
                tau0,
                wavelength,
            }),
        })
    }
}

/// Reads, overrides, deserialises and validates a scenario from TOML text.
pub fn load(text: &str, origin: &str, base: &Path, overrides: &[String]) -> Result<Scenario> {
    let mut table = parse_toml(text, origin)?;
    apply_overrides(&mut table, overrides)?;
    deserialize(&table)?.validate(base)
}

#[cfg(test)]
mod tests {
    use super::*;

    const MINIMAL: &str = r#"
[grid]
n = 16
size = 1.0
[material]
contact_modulus = 2.0
[adhesion]
work_of_adhesion = 0.01
[indenter]
shape = "sphere"
radius = 1.0
[protocol]
kind = "indent_pulloff"
max_depth = 3.0
depth_unit = "jkr"
steps = 30
"#;

    #[test]
    fn overrides_set_nested_keys_and_parse_toml_values() {
        let mut table = parse_toml(MINIMAL, "test").unwrap();
        let overrides = [
            "grid.n=32".to_string(),
            "grid.boundary = periodic".to_string(),
            "adhesion.field.kind=\"quadratic\"".to_string(),
            "output.snapshot_steps=[1, 2]".to_string(),
        ];
        apply_overrides(&mut table, &overrides).unwrap();
        assert_eq!(table["grid"]["n"].as_integer(), Some(32));
        assert_eq!(table["grid"]["boundary"].as_str(), Some("periodic"));
        assert_eq!(table["adhesion"]["field"]["kind"].as_str(), Some("quadratic"));
        assert_eq!(table["output"]["snapshot_steps"].as_array().unwrap().len(), 2);
        let error = apply_overrides(&mut table, &["grid.n.x=1".to_string()]).unwrap_err();
        assert!(error.to_string().contains("`grid.n` is not a table"), "{error}");
    }

    #[test]
    fn jkr_units_scale_the_depth() {
        let scenario = load(MINIMAL, "test", Path::new("."), &[]).unwrap();
        let jkr = scenario.jkr.unwrap();
        let d = jkr.critical_depth().abs();
        assert!((scenario.max_depth - 3.0 * d).abs() < 1e-15);
        assert_eq!(scenario.start_depth, 0.0);
        assert_eq!(scenario.approach_steps, 30);
        assert!((scenario.depth_step - 0.1 * d).abs() < 1e-15);
        assert_eq!(scenario.derived.f_jkr, Some(jkr.critical_force()));
        assert!(scenario.derived.johnson_parameter.is_none());
    }

    #[test]
    fn material_forms_are_exclusive() {
        let both = MINIMAL.replace("contact_modulus = 2.0", "contact_modulus = 2.0\nyoungs_modulus = 1.0");
        let error = load(&both, "test", Path::new("."), &[]).err().unwrap();
        assert!(error
            .to_string()
            .contains("material.contact_modulus cannot be combined"));
        let young = MINIMAL.replace("contact_modulus = 2.0", "youngs_modulus = 1.5\npoisson_ratio = 0.5");
        let scenario = load(&young, "test", Path::new("."), &[]).unwrap();
        assert!((scenario.material.contact_modulus() - 2.0).abs() < 1e-15);
        let error = load(MINIMAL, "test", Path::new("."), &["material.contact_modulus=-2".into()])
            .err()
            .unwrap();
        assert_eq!(error.to_string(), "material.contact_modulus must be > 0, got -2");
    }
}
