//! Reading a scenario: TOML text into a table, `--set KEY=VALUE` overrides on it, and
//! section-by-section deserialisation whose errors name the dotted key.

use crate::model::ScenarioFile;
use anyhow::{anyhow, bail, Context, Result};
use std::path::Path;

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
        apply_override(table, key, raw)?;
    }
    Ok(())
}

/// Sets one dotted `key` to `raw`, read as a TOML value (a bare string when it does not
/// parse as one); missing tables on the way are created.
pub fn apply_override(table: &mut toml::Table, key: &str, raw: &str) -> Result<()> {
    {
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
