//! The sweep file's own tables read and checked: its top-level keys, `series`, the
//! `[set]`, `[vary]`, `[zip]` and `[random]` tables, keys given twice and keys that are no
//! scenario key. Each check's [`ScenarioError`] names the sweep file's key as a TOML dotted
//! key (`random.seed`, `vary.alpha`, `zip."grid.n"`, `random."material.contact_modulus".min`,
//! see [`file_key`]); the value a case gives a scenario key is the scenario's to check, and
//! its errors keep the scenario key (`grid.n`).

// SplitMix64 through plan.rs's import, which the draws moved here from.
use super::{round10, Range, SplitMix64, MAX_CASES, PSEUDO_KEYS};
use crate as scenario;
use crate::error::{ErrorKind, ScenarioError};
use crate::sweep::keys::{get, set};
use anyhow::{bail, Context, Result};
use serde::Deserialize;

/// The sweep file's top-level keys.
const TOP: [&str; 8] = ["base", "scenario", "series", "set", "vary", "zip", "random", "derived"];

/// A TOML key as the sweep file spells it: bare where TOML allows (`alpha`), else quoted
/// (`"grid.n"`).
fn toml_key(key: &str) -> String {
    let bare = !key.is_empty() && key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    match bare {
        true => key.to_string(),
        false => format!("\"{}\"", key.replace('\\', "\\\\").replace('"', "\\\"")),
    }
}

/// The key `key` of the sweep file's table `table` as a TOML dotted key: `vary.alpha`,
/// `zip."grid.n"`, `random."material.contact_modulus"`.
pub(super) fn file_key(table: &str, key: &str) -> String {
    format!("{table}.{}", toml_key(key))
}

/// Refuses a top-level key the sweep file does not have.
pub(super) fn check_top_keys(sweep: &toml::Table, origin: &str) -> Result<()> {
    for (key, value) in sweep {
        if !TOP.contains(&key.as_str()) {
            let message = format!("{origin}: unknown key `{key}` (expected: {})", TOP.join(", "));
            bail!(ScenarioError::new(ErrorKind::UnknownKey, message)
                .with_key(key.clone())
                .with_value(value.to_string())
                .with_requirement(format!("one of {}", TOP.join(", "))));
        }
    }
    Ok(())
}

/// The series label: `series = "..."`, by default `stem`.
pub(super) fn series(sweep: &toml::Table, stem: &str) -> Result<String> {
    match sweep.get("series") {
        None => Ok(stem.to_string()),
        Some(toml::Value::String(s)) => Ok(s.clone()),
        Some(other) => bail!(ScenarioError::invalid("series", other, "a string")),
    }
}

/// The sweep file's table `name` (`[vary]`, ...), empty where absent.
pub(super) fn table_of(sweep: &toml::Table, name: &str) -> Result<toml::Table> {
    match sweep.get(name) {
        None => Ok(toml::Table::new()),
        Some(toml::Value::Table(t)) => Ok(t.clone()),
        Some(other) => bail!(ScenarioError::invalid_as(
            name,
            other,
            format!("a table [{name}]"),
            format!("`{name}` must be a table [{name}], got {other}")
        )),
    }
}

/// The sweep's tables of keys: what the case list is built from.
pub(super) struct SweepTables {
    /// `[set]`: the overrides of every case.
    pub fixed: Vec<(String, toml::Value)>,
    /// `[vary]`: non-empty lists, their cartesian product.
    pub vary: Vec<(String, Vec<toml::Value>)>,
    /// `[zip]`: lists of `zip_rows` values each, varied together.
    pub zip: Vec<(String, Vec<toml::Value>)>,
    pub zip_rows: usize,
    /// `[random]`: the seeded draws (one empty draw without `[random]`).
    pub draws: Vec<Vec<(String, toml::Value)>>,
    /// The varied keys: [vary]'s, [zip]'s, then [random]'s.
    pub keys: Vec<String>,
}

impl SweepTables {
    /// Reads `[set]`, `[vary]`, `[zip]` and `[random]`, each list and range checked.
    pub(super) fn read(sweep: &toml::Table) -> Result<Self> {
        let fixed: Vec<(String, toml::Value)> = table_of(sweep, "set")?.into_iter().collect();
        let vary = lists(table_of(sweep, "vary")?, "vary")?;
        let zip = lists(table_of(sweep, "zip")?, "zip")?;
        let zip_rows = zip_rows(&zip)?;
        let mut keys: Vec<String> = vary.iter().chain(&zip).map(|(key, _)| key.clone()).collect();
        let draws = random_draws(table_of(sweep, "random")?, &mut keys)?;
        Ok(Self {
            fixed,
            vary,
            zip,
            zip_rows,
            draws,
            keys,
        })
    }

    /// Refuses a key given twice (in [set], [vary], [zip] or [random]), naming both
    /// places, and an `alpha` whose target (`alpha_target`) the base scenario lacks.
    pub(super) fn check_keys_once(&self, sweep: &toml::Table, base: &toml::Table, alpha_target: &str) -> Result<()> {
        let tables = ["vary", "zip", "random", "set"];
        let entries = tables.iter().flat_map(|name| {
            let table = sweep.get(*name).and_then(toml::Value::as_table);
            table
                .into_iter()
                .flat_map(move |t| t.iter().map(move |(k, v)| (*name, k, v)))
        });
        let mut seen: Vec<(&str, &String)> = Vec::new();
        let ranges =
            |(name, key, _): &(&str, &String, _)| *name != "random" || !["seed", "cases"].contains(&key.as_str());
        for (name, key, value) in entries.filter(ranges) {
            if let Some((first, _)) = seen.iter().find(|(_, k)| *k == key) {
                let (first, second) = (file_key(first, key), file_key(name, key));
                bail!(ScenarioError::invalid_as(
                    &second,
                    value,
                    format!("given once in [set], [vary], [zip] and [random] (also {first})"),
                    format!(
                        "sweep key `{key}` is given more than once (in [set], [vary], [zip] or [random]): {first} and {second}"
                    )
                ));
            }
            seen.push((name, key));
            if key == "alpha" && get(base, alpha_target).is_none() && alpha_target != "indenter.amplitude" {
                bail!(ScenarioError::missing(
                    alpha_target,
                    format!("in the base scenario, for alpha (derived.alpha = \"{alpha_target}\")"),
                    format!("alpha sets {alpha_target}, which the base scenario lacks")
                ));
            }
        }
        Ok(())
    }

    /// Every key must be a scenario key (or a pseudo-key): each is set alone on the base
    /// (its first value) and deserialised, so that an unknown key is named.
    pub(super) fn check_scenario_keys(&self, base: &toml::Table) -> Result<()> {
        let firsts = self.vary.iter().chain(&self.zip).map(|(k, l)| (k, &l[0]));
        let others = self.draws[0].iter().chain(&self.fixed).map(|(k, v)| (k, v));
        for (key, value) in firsts.chain(others) {
            if PSEUDO_KEYS.contains(&key.as_str()) {
                continue;
            }
            if key.split('.').any(str::is_empty) || !key.contains('.') {
                let message = format!(
                    "unknown sweep key `{key}`: expected a dotted scenario key such as \"indenter.amplitude\" or one of {}",
                    PSEUDO_KEYS.join(", ")
                );
                bail!(ScenarioError::new(ErrorKind::UnknownKey, message)
                    .with_key(key.clone())
                    .with_requirement(format!("a dotted scenario key or one of {}", PSEUDO_KEYS.join(", "))));
            }
            let mut table = base.clone();
            if let Err(error) = set(&mut table, key, value.clone()) {
                // A key below a value that is no table (`grid.n.x`): no scenario key.
                bail!(
                    ScenarioError::new(ErrorKind::UnknownKey, format!("sweep key `{key}`: {error}"))
                        .with_key(key.clone())
                        .with_requirement("a key of a scenario table")
                );
            }
            scenario::deserialize(&table).with_context(|| format!("sweep key `{key}`"))?;
        }
        Ok(())
    }
}

/// A `[vary]` or `[zip]` table (`name`) as its lists; `[vary]`'s must not be empty.
fn lists(table: toml::Table, name: &str) -> Result<Vec<(String, Vec<toml::Value>)>> {
    let mut lists = Vec::new();
    for (key, value) in table {
        match value {
            toml::Value::Array(list) if !list.is_empty() || name == "zip" => lists.push((key, list)),
            toml::Value::Array(_) => bail!(ScenarioError::invalid_as(
                &file_key(name, &key),
                "[]",
                "a non-empty list",
                format!("{} is an empty list", file_key(name, &key))
            )),
            other => bail!(ScenarioError::invalid(&file_key(name, &key), other, "a list of values")),
        }
    }
    Ok(lists)
}

/// The rows of `[zip]`: the length its lists share (1 without `[zip]`).
fn zip_rows(zip: &[(String, Vec<toml::Value>)]) -> Result<usize> {
    let Some((first_key, first)) = zip.first() else {
        return Ok(1);
    };
    let first_key = file_key("zip", first_key);
    for (key, list) in zip {
        if list.len() != first.len() {
            let key = file_key("zip", key);
            bail!(ScenarioError::invalid_as(
                &key,
                toml::Value::Array(list.clone()),
                format!("a list of {} values, as {first_key}", first.len()),
                format!(
                    "[zip] lists must have equal lengths: {key} has {}, {first_key} has {}",
                    list.len(),
                    first.len()
                )
            ));
        }
    }
    if first.is_empty() {
        bail!(ScenarioError::invalid_as(
            &first_key,
            "[]",
            "a non-empty list",
            format!("{first_key} is an empty list")
        ));
    }
    Ok(first.len())
}

/// `random.seed`: an integer >= 0.
fn random_seed(random: &mut toml::Table) -> Result<u64> {
    match random.remove("seed") {
        Some(toml::Value::Integer(s)) if s >= 0 => Ok(s as u64),
        Some(other) => bail!(ScenarioError::invalid("random.seed", other, "an integer >= 0")),
        None => bail!(ScenarioError::missing(
            "random.seed",
            "with [random]",
            "missing key `random.seed`"
        )),
    }
}

/// `random.cases`: an integer in 1..=[`MAX_CASES`].
fn random_cases(random: &mut toml::Table) -> Result<usize> {
    match random.remove("cases") {
        Some(toml::Value::Integer(c)) if c > MAX_CASES as i64 => bail!(ScenarioError::invalid(
            "random.cases",
            c,
            &format!("<= {MAX_CASES} (the cap on a sweep's cases)")
        )),
        Some(toml::Value::Integer(c)) if c >= 1 => Ok(c as usize),
        Some(other) => bail!(ScenarioError::invalid("random.cases", other, "an integer >= 1")),
        None => bail!(ScenarioError::missing(
            "random.cases",
            "with [random]",
            "missing key `random.cases`"
        )),
    }
}

/// One `[random]` range, `random."KEY" = { min, max, scale }`, checked.
struct Draw {
    min: f64,
    max: f64,
    log: bool,
    /// Integer bounds: integer draws.
    integer: bool,
}

const RANGE_SHAPE: &str = "{ min = .., max = .., scale = \"log\"|\"linear\" }";

/// The range of `random."KEY"` (`value`), each field checked.
fn random_range(key: &str, value: &toml::Value) -> Result<Draw> {
    let range_key = file_key("random", key);
    let field_key = |field: &str| format!("{range_key}.{}", toml_key(field));
    let shape_error = |detail: String| format!("{range_key} must be {RANGE_SHAPE}: {detail}");
    let Some(table) = value.as_table() else {
        bail!(ScenarioError::invalid_as(
            &range_key,
            value,
            RANGE_SHAPE,
            shape_error(format!("got {value}"))
        ));
    };
    if let Some(field) = table.keys().find(|f| !["min", "max", "scale"].contains(&f.as_str())) {
        let message = shape_error(format!(
            "unknown field `{field}`, expected one of `min`, `max`, `scale`"
        ));
        bail!(ScenarioError::new(ErrorKind::UnknownKey, message)
            .with_key(field_key(field))
            .with_requirement("one of min, max, scale"));
    }
    if let Some(field) = ["min", "max"].into_iter().find(|f| !table.contains_key(*f)) {
        let message = shape_error(format!("missing field `{field}`"));
        bail!(ScenarioError::missing(
            &field_key(field),
            "in a [random] range",
            message
        ));
    }
    let range = Range::deserialize(value.clone()).map_err(|e| {
        let scale = table.get("scale").map(ToString::to_string).unwrap_or_default();
        ScenarioError::invalid_as(
            &field_key("scale"),
            scale,
            "\"log\" or \"linear\"",
            shape_error(e.message().into()),
        )
    })?;
    let as_f64 = |v: &toml::Value, which: &str| -> Result<f64> {
        v.as_float()
            .or_else(|| v.as_integer().map(|i| i as f64))
            .filter(|x| x.is_finite())
            .ok_or_else(|| {
                let key = field_key(which);
                ScenarioError::invalid_as(&key, v, "a finite number", format!("{key} must be a number, got {v}")).into()
            })
    };
    let (min, max) = (as_f64(&range.min, "min")?, as_f64(&range.max, "max")?);
    if min > max {
        bail!(ScenarioError::invalid_as(
            &field_key("min"),
            min,
            format!("<= max ({max})"),
            format!("{range_key}: min ({min}) > max ({max})")
        ));
    }
    let log = match range.scale.as_deref() {
        None | Some("linear") => false,
        Some("log") if min <= 0.0 => bail!(ScenarioError::invalid_as(
            &field_key("min"),
            min,
            "> 0 with scale = \"log\"",
            format!("{range_key}: scale = \"log\" needs min > 0, got {min}")
        )),
        Some("log") => true,
        Some(other) => bail!(ScenarioError::invalid_as(
            &field_key("scale"),
            format!("\"{other}\""),
            "\"log\" or \"linear\"",
            format!("{} must be \"log\" or \"linear\", got \"{other}\"", field_key("scale"))
        )),
    };
    let integer = range.min.is_integer() && range.max.is_integer();
    Ok(Draw { min, max, log, integer })
}

/// `[random]`: `cases` seeded draws of each range (keys appended to `keys`); one empty draw
/// without a `[random]` table.
fn random_draws(mut random: toml::Table, keys: &mut Vec<String>) -> Result<Vec<Vec<(String, toml::Value)>>> {
    if random.is_empty() {
        return Ok(vec![Vec::new()]);
    }
    let seed = random_seed(&mut random)?;
    let cases = random_cases(&mut random)?;
    let mut ranges = Vec::new();
    for (key, value) in random {
        ranges.push((key.clone(), random_range(&key, &value)?));
        keys.push(key);
    }
    let mut draws: Vec<Vec<(String, toml::Value)>> = Vec::new();
    let mut rng = SplitMix64::new(seed);
    for _ in 0..cases {
        let mut draw = Vec::new();
        for (key, Draw { min, max, log, integer }) in &ranges {
            let u = rng.next_f64();
            let x = if *log {
                (min.ln() + u * (max.ln() - min.ln())).exp()
            } else if *integer {
                (min + (u * (max - min + 1.0)).floor()).min(*max)
            } else {
                min + u * (max - min)
            };
            let value = if *integer {
                toml::Value::Integer(x.round() as i64)
            } else {
                toml::Value::Float(round10(x))
            };
            draw.push((key.clone(), value));
        }
        draws.push(draw);
    }
    if draws.is_empty() {
        draws.push(Vec::new());
    }
    Ok(draws)
}
