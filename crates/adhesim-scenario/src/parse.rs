//! Reading a scenario: TOML text into a table, `--set KEY=VALUE` overrides on it, and
//! section-by-section deserialisation whose errors name the dotted key.

use crate::error::{ErrorKind, ScenarioError};
use crate::model::ScenarioFile;
use adhesim_topography::{read_topography, ReadOptions, Topography};
use anyhow::{bail, Result};
use std::path::Path;

/// Parses TOML text into a table (with the file name in the message on failure).
pub(crate) fn parse_toml(text: &str, origin: &str) -> Result<toml::Table> {
    text.parse::<toml::Table>().map_err(|e| {
        let message = format!("{origin}: malformed TOML: {}", e.to_string().trim_end());
        ScenarioError::new(ErrorKind::Syntax, message).into()
    })
}

/// Applies `KEY=VALUE` overrides; VALUE is read as a TOML value (`3`, `0.5`, `"free"`,
/// `[1, 2]`), and as a bare string when it does not parse as one.
pub(crate) fn apply_overrides(table: &mut toml::Table, overrides: &[String]) -> Result<()> {
    for item in overrides {
        let (key, raw) = item.split_once('=').ok_or_else(|| {
            ScenarioError::new(ErrorKind::Syntax, format!("--set expects KEY=VALUE, got `{item}`")).with_value(item)
        })?;
        apply_override(table, key, raw)?;
    }
    Ok(())
}

/// Sets one dotted `key` to `raw`, read as a TOML value (a bare string when it does not
/// parse as one); missing tables on the way are created.
pub(crate) fn apply_override(table: &mut toml::Table, key: &str, raw: &str) -> Result<()> {
    {
        let key = key.trim();
        let raw = raw.trim();
        if key.is_empty() || key.split('.').any(str::is_empty) {
            return Err(
                ScenarioError::new(ErrorKind::Syntax, format!("--set: invalid key `{key}`"))
                    .with_key(key)
                    .into(),
            );
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
            current = entry.as_table_mut().ok_or_else(|| {
                let table = parts[..=depth].join(".");
                let message = format!("--set {key}: `{table}` is not a table");
                ScenarioError::new(ErrorKind::InvalidValue, message).with_key(table)
            })?;
        }
        current.insert(parts[parts.len() - 1].to_string(), value);
    }
    Ok(())
}

const SECTIONS: [&str; 11] = [
    "grid",
    "material",
    "adhesion",
    "indenter",
    "protocol",
    "output",
    "analysis",
    "roughness",
    "substrate_roughness",
    "friction",
    "solver",
];

/// Deserialises the table section by section so that every message names the dotted key.
pub(crate) fn deserialize(table: &toml::Table) -> Result<ScenarioFile> {
    for key in table.keys() {
        if !SECTIONS.contains(&key.as_str()) {
            let message = format!(
                "unknown key `{key}` (expected one of: {})",
                SECTIONS.map(|s| format!("[{s}]")).join(", ")
            );
            return Err(ScenarioError::new(ErrorKind::UnknownKey, message).with_key(key).into());
        }
    }
    fn section<T: serde::de::DeserializeOwned>(table: &toml::Table, name: &str, required: bool) -> Result<Option<T>> {
        let Some(value) = table.get(name) else {
            if required {
                let message = format!("missing section [{name}]");
                return Err(ScenarioError::new(ErrorKind::MissingKey, message).with_key(name).into());
            }
            return Ok(None);
        };
        if !value.is_table() {
            let message = format!("`{name}` must be a table [{name}], got {value}");
            let error = ScenarioError::new(ErrorKind::InvalidValue, message)
                .with_key(name)
                .with_value(value.to_string())
                .with_requirement(format!("a table [{name}]"));
            return Err(error.into());
        }
        T::deserialize(value.clone())
            .map(Some)
            .map_err(|e| section_error::<T>(name, value, e))
    }
    let grid = section(table, "grid", true)?.expect("required");
    let material = section(table, "material", true)?.expect("required");
    let adhesion = section(table, "adhesion", true)?.expect("required");
    let indenter = section(table, "indenter", true)?.expect("required");
    let protocol = section(table, "protocol", true)?.expect("required");
    let output = section(table, "output", false)?.unwrap_or_default();
    let analysis = section(table, "analysis", false)?.unwrap_or_default();
    let roughness = section(table, "roughness", false)?;
    let substrate_roughness = section(table, "substrate_roughness", false)?;
    let friction = section(table, "friction", false)?;
    let solver = section(table, "solver", false)?;
    Ok(ScenarioFile {
        grid,
        material,
        adhesion,
        indenter,
        protocol,
        output,
        analysis,
        roughness,
        substrate_roughness,
        friction,
        solver,
    })
}

/// Turns a serde error inside section `name` into a message with the dotted key.
fn section_error<T: serde::de::DeserializeOwned>(
    name: &str,
    value: &toml::Value,
    error: toml::de::Error,
) -> anyhow::Error {
    let message = error.message().trim().to_string();
    if let Some(rest) = message.strip_prefix("unknown field `") {
        if let Some((field, tail)) = rest.split_once('`') {
            let in_field_table = name == "adhesion" && value.get("field").is_some() && value.get(field).is_none();
            let key = if in_field_table {
                format!("{name}.field.{field}")
            } else {
                format!("{name}.{field}")
            };
            let tail = match tail.trim_start_matches(',').trim() {
                "there are no fields" => "it takes no keys",
                tail => tail,
            };
            let shape = tagged_by(name, value);
            let hint = (name == "protocol").then(|| protocol_key_owner(field)).flatten();
            let with_hint;
            let tail = match hint {
                Some(hint) => {
                    with_hint = format!("{hint}; {tail}");
                    with_hint.as_str()
                }
                None => tail,
            };
            let message = match (shape.is_empty(), tail.is_empty()) {
                (true, true) => format!("unknown key `{key}`"),
                (true, false) => format!("unknown key `{key}` ({tail})"),
                (false, true) => format!("unknown key `{key}` for {shape}"),
                (false, false) => format!("unknown key `{key}` for {shape} ({tail})"),
            };
            return ScenarioError::new(ErrorKind::UnknownKey, message).with_key(key).into();
        }
    }
    if let Some(rest) = message.strip_prefix("missing field `") {
        if let Some((field, _)) = rest.split_once('`') {
            let shape = tagged_by(name, value);
            let message = if shape.is_empty() {
                format!("missing key `{name}.{field}`")
            } else {
                format!("missing key `{name}.{field}` (needed by {shape})")
            };
            return ScenarioError::new(ErrorKind::MissingKey, message)
                .with_key(format!("{name}.{field}"))
                .into();
        }
    }
    // A type or value error: name the key at fault. serde's message quotes the value, not
    // the key, and a tagged section is read from a buffer that keeps no path, so the key
    // is found by trial: the first key without which the error changes.
    let mut leaves = Vec::new();
    collect_leaves(name, value, &mut leaves);
    let plain = plain_types(&message);
    let at_fault = |key: &str, item: &toml::Value| -> anyhow::Error {
        ScenarioError::new(ErrorKind::InvalidValue, format!("{key} = {item}: {plain}"))
            .with_key(key)
            .with_value(item.to_string())
            .with_requirement(plain.as_str())
            .into()
    };
    if let Some((key, item)) = key_at_fault::<T>(name, value, &message, &leaves) {
        return at_fault(&key, &item);
    }
    let quoted = leaves.iter().find(|(_, item)| quotes(&message, item));
    let typed = || {
        leaves
            .iter()
            .find(|(_, item)| message.contains(&format!("invalid type: {}", serde_kind(item.type_str()))))
    };
    if let Some((key, item)) = quoted.or_else(typed) {
        return at_fault(key, item);
    }
    ScenarioError::new(ErrorKind::InvalidValue, format!("[{name}]: {message}"))
        .with_key(name)
        .with_requirement(message.as_str())
        .into()
}

/// The key of section `name` that `message` (serde's, for `value`) is about: a key whose
/// removal changes the message (serde reads the keys in order and reports a missing key
/// only after the last, so removing a key other than the one at fault leaves the message
/// as it is; a required key of an earlier nested table changes it too, so a key whose
/// value the message quotes or whose type it names is preferred). Tried in this order:
/// the values, then the tables holding them (a table given where a number belongs), then
/// the tags (`indenter.shape`, `protocol.kind`, `adhesion.field.kind`) where the message
/// is about a variant, then any key.
fn key_at_fault<T: serde::de::DeserializeOwned>(
    name: &str,
    value: &toml::Value,
    message: &str,
    leaves: &[(String, toml::Value)],
) -> Option<(String, toml::Value)> {
    let is_tag = |key: &str| key.ends_with(".shape") || key.ends_with(".kind");
    let mut tables = Vec::new();
    collect_tables(name, value, &mut tables);
    let values: Vec<&(String, toml::Value)> = leaves
        .iter()
        .filter(|(key, _)| !is_tag(key))
        .chain(tables.iter().rev())
        .collect();
    let tags: Vec<&(String, toml::Value)> = leaves.iter().filter(|(key, _)| is_tag(key)).collect();
    let changes_without = |key: &str| {
        let mut trial = value.clone();
        let path: Vec<&str> = key[name.len() + 1..].split('.').collect();
        let Some((last, parents)) = path.split_last() else {
            return false;
        };
        let mut table = trial.as_table_mut();
        for part in parents {
            table = table.and_then(|t| t.get_mut(*part)).and_then(toml::Value::as_table_mut);
        }
        if table.and_then(|t| t.remove(*last)).is_none() {
            return false;
        }
        match T::deserialize(trial) {
            Ok(_) => true,
            Err(e) => e.message().trim() != message,
        }
    };
    let named = |item: &toml::Value| {
        quotes(message, item) || message.contains(&format!("invalid type: {}", serde_kind(item.type_str())))
    };
    // A tag's removal changes every message: it is at fault only where the message is
    // about a variant and quotes the tag's value or names its type, or where no other key is.
    let about_variant = message.contains("variant");
    let found = values
        .iter()
        .find(|(key, item)| named(item) && changes_without(key))
        .or_else(|| {
            tags.iter()
                .filter(|(_, item)| about_variant && named(item))
                .find(|(key, _)| changes_without(key))
        })
        .or_else(|| values.iter().chain(&tags).find(|(key, _)| changes_without(key)));
    found.map(|&candidate| candidate.clone())
}

/// Whether serde's `message` quotes `item` (`string "a"`, `` floating point `0.5` ``).
fn quotes(message: &str, item: &toml::Value) -> bool {
    let shown = item.to_string();
    let raw = item
        .as_str()
        .map(|s| format!("`{s}`"))
        .unwrap_or_else(|| format!("`{shown}`"));
    message.contains(&raw) || message.contains(&format!(" {shown},"))
}

/// Dotted keys and values of every table below `value` (not `value` itself), outer first.
fn collect_tables(prefix: &str, value: &toml::Value, out: &mut Vec<(String, toml::Value)>) {
    if let Some(table) = value.as_table() {
        for (key, item) in table {
            if item.is_table() {
                let key = format!("{prefix}.{key}");
                out.push((key.clone(), item.clone()));
                collect_tables(&key, item, out);
            }
        }
    }
}

/// `indenter.shape = "sphere"` for the `[indenter]` and `protocol.kind = "roll"` for the
/// `[protocol]` (whose keys depend on that tag), or an empty string.
fn tagged_by(name: &str, value: &toml::Value) -> String {
    match (name, value.get("shape"), value.get("kind")) {
        ("indenter", Some(shape), _) => format!("indenter.shape = {shape}"),
        ("protocol", _, Some(kind)) => format!("protocol.kind = {kind}"),
        _ => String::new(),
    }
}

/// Which protocol kind a stray `[protocol]` key belongs to, for the message (serde lists
/// the keys the given kind takes, not where the stray one goes).
fn protocol_key_owner(field: &str) -> Option<&'static str> {
    Some(match field {
        "max_depth" => "a key of protocol.kind = \"indent_pulloff\"; a roll, slide or translate holds protocol.depth",
        "step" | "max_retract_steps" => "a key of protocol.kind = \"indent_pulloff\"",
        "substrate_angle" => "a key of protocol.kind = \"slide\"",
        "direction" | "cycles" | "incline" => "a key of protocol.kind = \"shear\"",
        "drive_stiffness" => "a key of protocol.kind = \"shear\", \"slide\" or \"translate\"",
        "depth" | "distance" | "distance_unit" | "approach_steps" | "return_stroke" | "stationary_from" => {
            "a key of protocol.kind = \"roll\", \"slide\", \"translate\""
        }
        _ => return None,
    })
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

/// serde's Rust type names as a user reads them: ``invalid type: floating point `0.01`,
/// expected i64`` becomes ``invalid type: number `0.01`, expected an integer``.
fn plain_types(message: &str) -> String {
    let mut text = message.to_string();
    for (rust, plain) in [
        ("expected i64", "expected an integer"),
        ("expected i32", "expected an integer"),
        ("expected u64", "expected an integer >= 0"),
        ("expected u32", "expected an integer >= 0"),
        ("expected usize", "expected an integer >= 0"),
        ("expected f64", "expected a number"),
        ("expected f32", "expected a number"),
        ("floating point `", "number `"),
    ] {
        text = text.replace(rust, plain);
    }
    text
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

/// Reads a 2-D `.npy` array of f64 (or f32) as (row-major values, rows, columns), through
/// `adhesim_topography`'s reader: a header's shape is checked against the bytes present
/// before anything is allocated. NaN values are an error naming `key` and the file.
pub fn read_npy_2d(path: &Path, key: &str) -> Result<(Vec<f64>, usize, usize)> {
    let options = ReadOptions {
        spacing: Some((1.0, 1.0)),
        height_unit: Some("m".to_string()),
        ..ReadOptions::default()
    };
    crate::files::check_regular_file(path, key)?;
    let map = read_topography(path, &options)
        .map_err(|e| file_error(key, path, "a 2-D .npy array of floats", format!("{key}: {e}")))?;
    refuse_invalid_points(&map, path, key)?;
    Ok((map.heights, map.ny, map.nx))
}

/// A file of `key` that cannot be read as `requirement` says.
fn file_error(key: &str, path: &Path, requirement: &str, message: String) -> anyhow::Error {
    ScenarioError::new(ErrorKind::File, message)
        .with_key(key)
        .with_value(path.display().to_string())
        .with_requirement(requirement)
        .into()
}

/// Errors where the file marks points invalid (NaN, a mask): the reader fills them with the
/// mean height, which would be a silent change of the input.
pub(crate) fn refuse_invalid_points(map: &Topography, path: &Path, key: &str) -> Result<()> {
    if let Some(mask) = &map.mask {
        let invalid = mask.iter().filter(|valid| !**valid).count();
        if invalid > 0 {
            bail!(ScenarioError::invalid_as(
                key,
                path.display(),
                "a map without invalid points",
                format!(
                    "{key} = {}: {invalid} of {} points are invalid (NaN or masked in the file); fill them before use",
                    path.display(),
                    mask.len()
                )
            ));
        }
    }
    Ok(())
}

/// Reads the height map of `indenter.shape = "topography"` in any format of
/// `adhesim_topography::read_topography` (by extension), as (row-major heights, rows,
/// columns, spacing). Formats that record a spacing and units (x3p, gwy, sur, xyz) give
/// heights and spacing in metres; for the others (npy, npz, bare ASCII) the heights are
/// taken in the scenario's length unit and `spacing` (`indenter.spacing`) is required.
pub fn read_height_map(path: &Path, spacing: Option<f64>) -> Result<(Vec<f64>, usize, usize, f64)> {
    let options = ReadOptions {
        spacing: spacing.map(|s| (s, s)),
        height_unit: Some("m".to_string()),
        lateral_unit: Some("m".to_string()),
        ..ReadOptions::default()
    };
    let key = "indenter.file";
    crate::files::check_regular_file(path, key)?;
    let map = read_topography(path, &options).map_err(|e| {
        let hint = if spacing.is_none() {
            " (files that record no spacing need indenter.spacing)"
        } else {
            ""
        };
        file_error(
            key,
            path,
            "a height map file adhesim reads",
            format!("{key}: {e}{hint}"),
        )
    })?;
    refuse_invalid_points(&map, path, key)?;
    if (map.dx - map.dy).abs() > 1e-9 * map.dx.abs() {
        bail!(ScenarioError::invalid_as(
            key,
            path.display(),
            "a map of square spacing",
            format!(
                "{key} = {}: the spacing differs along x ({:e}) and y ({:e}); resample the map to a square spacing",
                path.display(),
                map.dx,
                map.dy
            )
        ));
    }
    if let Some(given) = spacing {
        if (given - map.dx).abs() > 1e-9 * given {
            bail!(ScenarioError::invalid_as(
                "indenter.spacing",
                given,
                format!("absent, or the file's spacing {:e} m", map.dx),
                format!(
                    "indenter.spacing = {given} but {key} = {} records a spacing of {:e} m: leave indenter.spacing out",
                    path.display(),
                    map.dx
                )
            ));
        }
    }
    Ok((map.heights, map.ny, map.nx, map.dx))
}
