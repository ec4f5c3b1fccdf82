//! A case's scenario table read and written by dotted key (`adhesion.law`,
//! `material.contact_modulus`): the value of a key, a number a pseudo-key needs (naming
//! the key and the pseudo-key when it is missing or no number), the contact modulus from
//! either of its spellings, and a key set with its tables made on the way. The case list
//! (`plan.rs`, `plan/tables.rs`) and the `maugis_parameter` pseudo-key (`maugis.rs`) share
//! them; this module imports neither, so that those two do not import each other.

use crate::error::ScenarioError;
use adhesim::ElasticMaterial;
use anyhow::{anyhow, bail, Result};

pub(super) fn get<'a>(table: &'a toml::Table, key: &str) -> Option<&'a toml::Value> {
    let mut parts = key.split('.');
    let mut value = table.get(parts.next()?)?;
    for part in parts {
        value = value.as_table()?.get(part)?;
    }
    Some(value)
}

pub(super) fn number(table: &toml::Table, key: &str, why: &str) -> Result<f64> {
    match get(table, key) {
        Some(toml::Value::Float(f)) => Ok(*f),
        Some(toml::Value::Integer(i)) => Ok(*i as f64),
        Some(other) => bail!(ScenarioError::invalid_as(
            key,
            other,
            format!("a number (for {why})"),
            format!("{why} needs {key} to be a number, got {other}")
        )),
        None => bail!(ScenarioError::missing(
            key,
            format!("for {why}"),
            format!("{why} needs {key} in the scenario")
        )),
    }
}

pub(super) fn set(table: &mut toml::Table, key: &str, value: toml::Value) -> Result<()> {
    let parts: Vec<&str> = key.split('.').collect();
    if parts.iter().any(|p| p.is_empty()) {
        bail!("invalid key `{key}`");
    }
    let mut current = table;
    for (depth, part) in parts[..parts.len() - 1].iter().enumerate() {
        current = current
            .entry(part.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()))
            .as_table_mut()
            .ok_or_else(|| anyhow!("`{}` is not a table", parts[..=depth].join(".")))?;
    }
    current.insert(parts[parts.len() - 1].to_string(), value);
    Ok(())
}

pub(super) fn contact_modulus(table: &toml::Table, why: &str) -> Result<f64> {
    if get(table, "material.contact_modulus").is_some() {
        return number(table, "material.contact_modulus", why);
    }
    let youngs_modulus = number(table, "material.youngs_modulus", why)?;
    let poisson_ratio = number(table, "material.poisson_ratio", why)?;
    let material = ElasticMaterial::from_youngs_modulus(youngs_modulus, poisson_ratio).map_err(|e| {
        ScenarioError::derived(
            format!("youngs_modulus = {youngs_modulus}, poisson_ratio = {poisson_ratio}"),
            "a valid elastic material",
            format!("{why}: {e}"),
        )
    })?;
    Ok(material.contact_modulus())
}
