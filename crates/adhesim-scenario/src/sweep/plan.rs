//! Sweep files: a base scenario plus parameters to vary (`[vary]` cartesian product, `[zip]`
//! equal-length lists, `[random]` seeded draws), pseudo-keys for dimensionless inputs, and
//! the deterministic case list.

use crate as scenario;
use crate::batch::{fnv1a, results_hash};
use crate::error::ScenarioError;
use crate::sweep::keys::{contact_modulus, get, number, set};
use adhesim::analysis::johnson::{JohnsonInputs, JohnsonTarget};
use adhesim::analysis::reference::Jkr;
use adhesim::rng::SplitMix64;
use anyhow::{bail, Context, Result};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Pseudo-keys: dimensionless inputs turned into scenario keys for each case.
pub const PSEUDO_KEYS: [&str; 5] = [
    "lambda_over_radius",
    "h_over_lambda",
    "alpha",
    "size_over_a_jkr",
    "maugis_parameter",
];

/// Keys that `alpha` may solve for ([derived] alpha = "..."), with the library's inversion.
const ALPHA_TARGETS: [(&str, JohnsonTarget); 4] = [
    ("indenter.amplitude", JohnsonTarget::Amplitude),
    ("adhesion.work_of_adhesion", JohnsonTarget::WorkOfAdhesion),
    ("indenter.wavelength", JohnsonTarget::Wavelength),
    ("material.contact_modulus", JohnsonTarget::ContactModulus),
];

/// The scenario keys `alpha` may set, for messages.
fn alpha_target_keys() -> String {
    ALPHA_TARGETS.map(|(key, _)| key).join(", ")
}

/// One case of a sweep.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Case {
    /// 0-based position in the case list.
    pub index: usize,
    /// `<index>-<short hash of the overrides>`, the folder name under `cases/`.
    pub id: String,
    /// Hash of the whole effective scenario; written into the case's `done` marker.
    pub hash: String,
    /// The varied values, in the order of [`Plan::keys`], as table cells.
    pub values: Vec<String>,
    /// The effective scenario (TOML text) the case runs.
    pub scenario: String,
}

/// The whole sweep: what `DIR/sweep.json` holds.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Plan {
    /// Series label for the master-curve plots.
    pub series: String,
    /// Varied keys (dotted scenario keys or pseudo-keys), as the table's columns.
    pub keys: Vec<String>,
    pub cases: Vec<Case>,
    /// Folder that relative file paths in the scenario are resolved against.
    pub base_dir: PathBuf,
}

/// A value as a table cell: numbers in Rust's shortest round-trip form, strings bare.
pub fn cell(value: &toml::Value) -> String {
    match value {
        toml::Value::String(s) => s.clone(),
        toml::Value::Integer(i) => i.to_string(),
        toml::Value::Float(f) => f.to_string(),
        toml::Value::Boolean(b) => b.to_string(),
        other => other.to_string(),
    }
}

/// Rounds to 10 significant digits so that log-scale draws (which go through the
/// platform's `ln`/`exp`) give the same numbers everywhere.
fn round10(x: f64) -> f64 {
    format!("{x:.9e}").parse().unwrap_or(x)
}

/// Applies one case's overrides: plain dotted keys first, then the pseudo-keys in the
/// order lambda_over_radius, h_over_lambda, alpha, size_over_a_jkr, maugis_parameter.
pub fn apply(table: &mut toml::Table, overrides: &[(String, toml::Value)], alpha_target: &str) -> Result<()> {
    let mut pseudo: Vec<(&str, f64)> = Vec::new();
    for (key, value) in overrides {
        if PSEUDO_KEYS.contains(&key.as_str()) {
            let v = value
                .as_float()
                .or_else(|| value.as_integer().map(|i| i as f64))
                .ok_or_else(|| ScenarioError::invalid(key, value, "a number"))?;
            if !(v.is_finite() && v > 0.0) {
                bail!(ScenarioError::invalid(key, v, "a finite number > 0"));
            }
            pseudo.push((key.as_str(), v));
        } else {
            set(table, key, value.clone()).with_context(|| format!("sweep key `{key}`"))?;
        }
    }
    let value_of = |name: &str| pseudo.iter().find(|(k, _)| *k == name).map(|(_, v)| *v);
    if let Some(v) = value_of("lambda_over_radius") {
        let radius = number(table, "indenter.radius", "lambda_over_radius")?;
        set(table, "indenter.wavelength", toml::Value::Float(v * radius))?;
    }
    if let Some(v) = value_of("h_over_lambda") {
        let wavelength = number(table, "indenter.wavelength", "h_over_lambda")?;
        set(table, "indenter.amplitude", toml::Value::Float(v * wavelength))?;
    }
    if let Some(alpha) = value_of("alpha") {
        // α² = 2λγ0/(π²h²E*), solved for the target key by the library.
        let why = "alpha";
        let Some(&(_, target)) = ALPHA_TARGETS.iter().find(|(key, _)| *key == alpha_target) else {
            bail!(
                "[derived] alpha = \"{alpha_target}\": alpha can set one of {}",
                alpha_target_keys()
            );
        };
        if target == JohnsonTarget::ContactModulus && get(table, "material.contact_modulus").is_none() {
            bail!("[derived] alpha = \"material.contact_modulus\" needs material.contact_modulus in the scenario");
        }
        // Only the three inputs the target needs must be in the scenario.
        let input = |wanted: JohnsonTarget, key: &str| -> Result<f64> {
            match wanted == target {
                true => Ok(f64::NAN),
                false if wanted == JohnsonTarget::ContactModulus => contact_modulus(table, why),
                false => number(table, key, why),
            }
        };
        let inputs = JohnsonInputs {
            wavelength: input(JohnsonTarget::Wavelength, "indenter.wavelength")?,
            amplitude: input(JohnsonTarget::Amplitude, "indenter.amplitude")?,
            work_of_adhesion: input(JohnsonTarget::WorkOfAdhesion, "adhesion.work_of_adhesion")?,
            contact_modulus: input(JohnsonTarget::ContactModulus, "")?,
        };
        let solved = target.solve(alpha, &inputs);
        set(table, alpha_target, toml::Value::Float(solved))?;
    }
    if let Some(v) = value_of("size_over_a_jkr") {
        let why = "size_over_a_jkr";
        let jkr = Jkr {
            radius: number(table, "indenter.radius", why)?,
            contact_modulus: contact_modulus(table, why)?,
            work_of_adhesion: number(table, "adhesion.work_of_adhesion", why)?,
        };
        set(table, "grid.size", toml::Value::Float(v * jkr.critical_radius()))?;
    }
    if let Some(v) = value_of("maugis_parameter") {
        if let Some((_, stress)) = overrides.iter().find(|(key, _)| key == "adhesion.cohesive_stress") {
            bail!(ScenarioError::invalid_as(
                "adhesion.cohesive_stress",
                stress,
                "not given with maugis_parameter",
                format!("maugis_parameter = {v} sets adhesion.cohesive_stress: give one of the two, not both")
            ));
        }
        let stress = super::maugis::cohesive_stress(table, v)?;
        set(table, "adhesion.cohesive_stress", toml::Value::Float(stress))?;
    }
    Ok(())
}

/// A [random] range.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Range {
    min: toml::Value,
    max: toml::Value,
    #[serde(default)]
    scale: Option<String>,
}

mod tables;
use tables::SweepTables;

/// Reads the sweep file and builds the validated case list.
pub fn load(path: &Path) -> Result<Plan> {
    let text = scenario::read_input_text(path, "sweep file")?;
    let origin = path.display().to_string();
    let sweep_dir = path.parent().unwrap_or(Path::new(".")).to_path_buf();
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "sweep".into());
    from_text(&text, &origin, &sweep_dir, &stem)
}

/// As [`load`], from text (`sweep_dir` resolves `base`).
pub fn from_text(text: &str, origin: &str, sweep_dir: &Path, stem: &str) -> Result<Plan> {
    let sweep = scenario::parse_toml(text, origin)?;
    tables::check_top_keys(&sweep, origin)?;
    let (base, base_dir) = base_scenario(&sweep, origin, sweep_dir)?;
    scenario::deserialize(&base)
        .and_then(|file| file.validate(&base_dir).map(|_| ()))
        .context("base scenario")?;
    let series = tables::series(&sweep, stem)?;
    let alpha_target = alpha_target(&tables::table_of(&sweep, "derived")?)?;
    let tables = SweepTables::read(&sweep)?;
    tables.check_keys_once(&sweep, &base, &alpha_target)?;
    tables.check_scenario_keys(&base)?;
    let cases = case_list(&CaseInputs {
        base: &base,
        base_dir: &base_dir,
        fixed: &tables.fixed,
        vary: &tables.vary,
        zip: &tables.zip,
        zip_rows: tables.zip_rows,
        draws: &tables.draws,
        alpha_target: &alpha_target,
    })?;
    Ok(Plan {
        series,
        keys: tables.keys,
        cases,
        base_dir,
    })
}

/// The base scenario (`base = "file.toml"` or an inline `[scenario]`) and the folder its
/// relative paths are resolved against.
fn base_scenario(sweep: &toml::Table, origin: &str, sweep_dir: &Path) -> Result<(toml::Table, PathBuf)> {
    Ok(match (sweep.get("base"), sweep.get("scenario")) {
        (Some(toml::Value::String(file)), None) => {
            let base_path = sweep_dir.join(file);
            let text = scenario::read_input_text(&base_path, &format!("the base scenario (base = \"{file}\")"))?;
            let table = scenario::parse_toml(&text, &base_path.display().to_string())?;
            (table, base_path.parent().unwrap_or(Path::new(".")).to_path_buf())
        }
        (None, Some(toml::Value::Table(table))) => (table.clone(), sweep_dir.to_path_buf()),
        (Some(base), Some(_)) => bail!(ScenarioError::invalid_as(
            "base",
            base,
            "absent with an inline [scenario]",
            format!("{origin}: give either base = \"file.toml\" or an inline [scenario], not both")
        )),
        (Some(other), None) => bail!(ScenarioError::invalid_as(
            "base",
            other,
            "a file name (string)",
            format!("base must be a file name (string), got {other}")
        )),
        (None, Some(other)) => bail!(ScenarioError::invalid_as(
            "scenario",
            other,
            "a table [scenario]",
            format!("scenario must be a table [scenario], got {other}")
        )),
        (None, None) => bail!(ScenarioError::missing(
            "base",
            "unless an inline [scenario] is given",
            format!("{origin}: missing base = \"scenario.toml\" (or an inline [scenario] table)")
        )),
    })
}

/// The key `alpha` sets (`[derived] alpha = "..."`, indenter.amplitude by default).
fn alpha_target(derived: &toml::Table) -> Result<String> {
    let mut alpha_target = "indenter.amplitude".to_string();
    for (key, value) in derived {
        match (key.as_str(), value) {
            ("alpha", toml::Value::String(target)) if ALPHA_TARGETS.iter().any(|(key, _)| key == target) => {
                alpha_target = target.clone()
            }
            ("alpha", other) => bail!(ScenarioError::invalid_as(
                "derived.alpha",
                other,
                format!("one of {}", alpha_target_keys()),
                format!(
                    "derived.alpha must name the key alpha sets, one of {}; got {other}",
                    alpha_target_keys()
                )
            )),
            (_, other) => {
                let key = tables::file_key("derived", key);
                bail!(ScenarioError::new(
                    crate::error::ErrorKind::UnknownKey,
                    format!("unknown key `{key}` (known: alpha)")
                )
                .with_key(key)
                .with_value(other.to_string())
                .with_requirement("absent (the key of [derived] is alpha)"))
            }
        }
    }
    Ok(alpha_target)
}

/// What the case list is built from.
struct CaseInputs<'a> {
    base: &'a toml::Table,
    base_dir: &'a Path,
    fixed: &'a [(String, toml::Value)],
    vary: &'a [(String, Vec<toml::Value>)],
    zip: &'a [(String, Vec<toml::Value>)],
    zip_rows: usize,
    draws: &'a [Vec<(String, toml::Value)>],
    alpha_target: &'a str,
}

/// Most cases a sweep plan may hold: each is validated when the plan is made and gets a
/// folder; beyond this a plan is a mistake or a job for several sweeps (shards of one plan
/// still list every case).
pub const MAX_CASES: usize = 100_000;

/// The case count of vary × zip rows × draws, refused above [`MAX_CASES`] before any case
/// is built.
fn check_case_count(vary: &[(String, Vec<toml::Value>)], zip_rows: usize, draws: usize) -> Result<()> {
    let mut count = (zip_rows as u128) * (draws as u128);
    for (_, list) in vary {
        count = count.saturating_mul(list.len() as u128);
    }
    if count > MAX_CASES as u128 {
        let sizes: Vec<String> = vary.iter().map(|(k, l)| format!("{k}: {}", l.len())).collect();
        bail!(ScenarioError::derived(
            count,
            format!("<= {MAX_CASES} cases"),
            format!(
                "the sweep has {count} cases ([vary] {} × [zip] {zip_rows} rows × [random] {draws} draws), more than the cap of {MAX_CASES}: split it into several sweeps",
                if sizes.is_empty() { "none".to_string() } else { sizes.join(" × ") }
            )
        ));
    }
    Ok(())
}

/// The case list: vary (last key fastest) × zip rows × random draws, each case validated.
fn case_list(inputs: &CaseInputs<'_>) -> Result<Vec<Case>> {
    let CaseInputs {
        base,
        base_dir,
        fixed,
        vary,
        zip,
        zip_rows,
        draws,
        alpha_target,
    } = *inputs;
    check_case_count(vary, zip_rows, draws.len())?;
    let mut combos: Vec<Vec<(String, toml::Value)>> = vec![Vec::new()];
    for (key, list) in vary {
        let mut next = Vec::with_capacity(combos.len() * list.len());
        for combo in &combos {
            for value in list {
                let mut c = combo.clone();
                c.push((key.clone(), value.clone()));
                next.push(c);
            }
        }
        combos = next;
    }
    let mut cases = Vec::new();
    for combo in &combos {
        for row in 0..zip_rows {
            for draw in draws {
                let mut overrides = combo.clone();
                overrides.extend(zip.iter().map(|(k, l)| (k.clone(), l[row].clone())));
                overrides.extend(draw.iter().cloned());
                let index = cases.len();
                let values: Vec<String> = overrides.iter().map(|(_, v)| cell(v)).collect();
                let canonical: String = overrides.iter().map(|(k, v)| format!("{k}={v}\n")).collect();
                let mut table = base.clone();
                let all: Vec<(String, toml::Value)> = fixed.iter().cloned().chain(overrides.iter().cloned()).collect();
                let describe = || {
                    let list: Vec<String> = overrides.iter().map(|(k, v)| format!("{k} = {v}")).collect();
                    format!("case {index} ({})", list.join(", "))
                };
                apply(&mut table, &all, alpha_target).with_context(describe)?;
                scenario::deserialize(&table)
                    .and_then(|file| file.validate(base_dir).map(|_| ()))
                    .with_context(describe)?;
                let scenario_text = toml::to_string(&table).context("cannot serialise a case scenario")?;
                cases.push(Case {
                    index,
                    id: format!("{index:04}-{:08x}", fnv1a(&canonical) >> 32),
                    hash: format!("{:016x}", results_hash(&scenario_text)),
                    values,
                    scenario: scenario_text,
                });
            }
        }
    }
    Ok(cases)
}
