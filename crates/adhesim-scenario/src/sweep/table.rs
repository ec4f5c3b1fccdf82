//! `DIR/table.csv`: one row per finished case, rebuilt from the case folders.
//!
//! Columns: `case`, the varied keys (as written in the sweep file), `johnson_parameter`,
//! `grid.n` and `element_size` (the resolution; left out when `grid.n` is varied), every
//! key of `results` in `summary.json` (in its order; null → empty cell), then
//! `status` (`ok` or `error`; the message is in the case's `error.txt`) and `series`.
//! Rows are sorted by case index. No wall-clock numbers: the table of a resumed or
//! sharded sweep is byte-identical to an uninterrupted one.

use super::plan::Plan;
use crate::batch::write_atomically;
use crate::batch::{case_state, CaseState};
use anyhow::{Context, Result};
use serde::de::{Deserializer, MapAccess, Visitor};
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// A JSON object with its keys in file order (serde_json's `Map` sorts them).
struct Ordered(Vec<(String, serde_json::Value)>);

impl<'de> Deserialize<'de> for Ordered {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct OrderedVisitor;
        impl<'de> Visitor<'de> for OrderedVisitor {
            type Value = Ordered;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a JSON object")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Ordered, A::Error> {
                let mut entries = Vec::new();
                while let Some((key, value)) = map.next_entry::<String, serde_json::Value>()? {
                    entries.push((key, value));
                }
                Ok(Ordered(entries))
            }
        }
        deserializer.deserialize_map(OrderedVisitor)
    }
}

#[derive(Deserialize)]
struct SummaryFile {
    inputs: serde_json::Value,
    derived: serde_json::Value,
    results: Ordered,
}

/// A cell: numbers as serde_json writes them (shortest round trip), null → empty.
fn cell(value: &serde_json::Value) -> String {
    match value {
        serde_json::Value::Null => String::new(),
        serde_json::Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// What [`rebuild`] wrote.
pub struct TableSummary {
    pub path: PathBuf,
    pub finished: usize,
    pub errors: usize,
}

/// Rebuilds `DIR/table.csv` from every finished case folder of the plan.
pub fn rebuild(dir: &Path, plan: &Plan) -> Result<TableSummary> {
    struct Row {
        id: String,
        values: Vec<String>,
        johnson: String,
        /// `grid.n` and the element size: the resolution of every row, varied or not.
        resolution: [String; 2],
        results: Vec<(String, serde_json::Value)>,
        ok: bool,
    }
    let mut rows = Vec::new();
    let mut result_keys: Vec<String> = Vec::new();
    for case in &plan.cases {
        let CaseState::Finished { ok } = case_state(dir, &case.id, &case.hash) else {
            continue;
        };
        let folder = dir.join("cases").join(&case.id);
        let (johnson, resolution, results) = if ok {
            let path = folder.join("summary.json");
            let text = crate::files::read_own_text(&path, "summary.json", u64::MAX)?;
            let summary: SummaryFile =
                serde_json::from_str(&text).with_context(|| format!("{} is not a run summary", path.display()))?;
            let johnson = summary.derived.get("johnson_parameter").map(cell).unwrap_or_default();
            let grid_n = summary.inputs.pointer("/grid/n").map(cell).unwrap_or_default();
            let element_size = summary.derived.get("element_size").map(cell).unwrap_or_default();
            (johnson, [grid_n, element_size], summary.results.0)
        } else {
            (String::new(), [String::new(), String::new()], Vec::new())
        };
        for (key, _) in &results {
            if !result_keys.contains(key) {
                result_keys.push(key.clone());
            }
        }
        rows.push(Row {
            id: case.id.clone(),
            values: case.values.clone(),
            johnson,
            resolution,
            results,
            ok,
        });
    }
    let mut writer = csv::Writer::from_writer(Vec::new());
    let mut header: Vec<String> = vec!["case".into()];
    header.extend(plan.keys.iter().cloned());
    header.push("johnson_parameter".into());
    // The resolution of every row (unless grid.n is varied, and so already a column).
    let resolution_columns = !plan.keys.iter().any(|k| k == "grid.n");
    if resolution_columns {
        header.extend(["grid.n".to_string(), "element_size".to_string()]);
    }
    header.extend(result_keys.iter().cloned());
    header.extend(["status".to_string(), "series".to_string()]);
    writer.write_record(&header)?;
    let mut errors = 0;
    for row in &rows {
        let mut record = vec![row.id.clone()];
        record.extend(row.values.iter().cloned());
        record.push(row.johnson.clone());
        if resolution_columns {
            record.extend(row.resolution.iter().cloned());
        }
        for key in &result_keys {
            let value = row.results.iter().find(|(k, _)| k == key).map(|(_, v)| cell(v));
            record.push(value.unwrap_or_default());
        }
        if !row.ok {
            errors += 1;
        }
        record.push(if row.ok { "ok" } else { "error" }.to_string());
        record.push(plan.series.clone());
        writer.write_record(&record)?;
    }
    let bytes = writer.into_inner().map_err(|e| anyhow::anyhow!("csv: {e}"))?;
    let path = dir.join("table.csv");
    write_atomically(&path, &bytes)?;
    Ok(TableSummary {
        path,
        finished: rows.len(),
        errors,
    })
}
