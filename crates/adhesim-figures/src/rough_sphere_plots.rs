//! Master plots of the rough-sphere study (docs/rough-spheres.md), drawn by
//! `adhesim plot master` next to the wavy-sphere ones when a table carries the roughness
//! statistics of its cases (`rms_height`, `rms_slope`, `work_of_adhesion`,
//! `contact_modulus`, `radius`: the study example's table) or a sweep's case folders hold
//! them (`summary.json`: `derived.roughness` and the inputs); seeds are grouped by
//! `rms_slope_target` or the sweep's `roughness.rms_slope`, series by `roughness.hurst`:
//! - `rough_sphere_master`: γ1/γ0, γ2/γ0 and |F_ad|/|F_JKR| vs the rough-sphere parameter
//!   α_r = √(2γ0/(πE*h_rms h'_rms)) (`adhesim::analysis::johnson::rough_sphere_parameter`,
//!   computed here from the table's input columns); seeds as points, the seed mean of each
//!   (Hurst exponent, rms slope) as a line per series, and the wavy-sphere master curve of
//!   any table with a `johnson_parameter` column at α_r = 2^{1/4}·α (the paper's waviness
//!   h·sin·sin has h_rms = h/2, h'_rms = √2·πh/λ);
//! - `rough_sphere_depth`: the same quantities vs h_rms/|d_JKR|
//!   (`roughness_depth_ratio`), the amplitude-only axis.

use crate::figure::{grey_first, Figure, Mark, Panel, Series, REFERENCE_GREY};
use adhesim::analysis::johnson::{rough_sphere_parameter, roughness_depth_ratio};
use anyhow::{Context, Result};
use plotters::chart::SeriesLabelPosition;
use std::path::{Path, PathBuf};

/// One case: its series, the group its seeds share, both axes and the three quantities.
struct Case {
    series: String,
    group: String,
    parameter: f64,
    depth_ratio: f64,
    /// γ1/γ0, γ2/γ0, |F_ad|/|F_JKR|, then γ1/γ0 and γ2/γ0 with the radius √(A/π).
    values: [Option<f64>; 5],
}

/// Points (x, value) of one line.
type Line = Vec<(f64, f64)>;

/// The wavy-sphere master curve: (α_r, [γ1, γ2, F]) per α, sorted.
type Reference = Vec<(f64, [Option<f64>; 3])>;

const QUANTITIES: [(&str, &str); 3] = [
    ("(a) approach", "γ1 / γ0"),
    ("(b) detachment", "γ2 / γ0"),
    ("(c) adhesive force", "|F_ad| / |F_JKR|"),
];

/// Rough-sphere cases and wavy-sphere reference points of one table.
fn read(path: &Path, cases: &mut Vec<Case>, reference: &mut Reference) -> Result<()> {
    let mut reader = csv::Reader::from_path(path).with_context(|| format!("cannot read {}", path.display()))?;
    let header = reader.headers()?.clone();
    let find = |name: &str| header.iter().position(|h| h == name);
    let columns = [
        "rms_height",
        "rms_slope",
        "work_of_adhesion",
        "contact_modulus",
        "radius",
    ]
    .map(find);
    let quantities = [
        "gamma_approach_norm",
        "gamma_pulloff_norm",
        "adhesive_force_ratio",
        "gamma_approach_area_norm",
        "gamma_pulloff_area_norm",
    ]
    .map(find);
    let (alpha, series, status, case_col) = (find("johnson_parameter"), find("series"), find("status"), find("case"));
    // The study example writes `rms_slope_target`; a sweep its varied keys.
    let (group, hurst) = (
        find("rms_slope_target").or_else(|| find("roughness.rms_slope")),
        find("roughness.hurst"),
    );
    let cases_dir = path.parent().unwrap_or(Path::new(".")).join("cases");
    for record in reader.records() {
        let record = record.with_context(|| format!("{}: malformed row", path.display()))?;
        if status.and_then(|c| record.get(c)).is_some_and(|s| s != "ok") {
            continue;
        }
        let number = |col: Option<usize>| {
            col.and_then(|c| record.get(c))
                .and_then(|s| s.parse::<f64>().ok())
                .filter(|v| v.is_finite())
        };
        let values = quantities.map(number);
        let text = |col: Option<usize>| col.and_then(|c| record.get(c)).unwrap_or_default().to_string();
        let statistics = match columns.map(number) {
            [Some(h), Some(slope), Some(gamma), Some(modulus), Some(radius)] => {
                Some([h, slope, gamma, modulus, radius])
            }
            _ => case_col.and_then(|_| summary_statistics(&cases_dir.join(text(case_col)).join("summary.json"))),
        };
        if let Some([h, slope, gamma, modulus, radius]) = statistics {
            let (Some(parameter), Some(depth_ratio)) = (
                rough_sphere_parameter(h, slope, gamma, modulus),
                roughness_depth_ratio(h, radius, gamma, modulus),
            ) else {
                continue;
            };
            let series = match hurst {
                Some(_) => format!("H = {}", text(hurst)),
                None => text(series),
            };
            cases.push(Case {
                group: format!("{series} {}", text(group)),
                series,
                parameter,
                depth_ratio,
                values,
            });
        } else if let Some(alpha) = number(alpha).filter(|a| *a > 0.0) {
            reference.push((2f64.powf(0.25) * alpha, [values[0], values[1], values[2]]));
        }
    }
    Ok(())
}

/// [h_rms, h'_rms, γ0, E*, R] of a sweep case from its summary.json (`derived.roughness`
/// and the scenario inputs); `None` when the file or a value is missing.
fn summary_statistics(path: &Path) -> Option<[f64; 5]> {
    let text = std::fs::read_to_string(path).ok()?;
    let json: serde_json::Value = serde_json::from_str(&text).ok()?;
    let get = |pointer: &str| json.pointer(pointer).and_then(serde_json::Value::as_f64);
    Some([
        get("/derived/roughness/rms_height")?,
        get("/derived/roughness/rms_slope")?,
        get("/inputs/adhesion/work_of_adhesion")?,
        get("/inputs/material/contact_modulus")?,
        get("/inputs/indenter/radius")?,
    ])
}

/// Seed means per group, as (series, points sorted by x) for quantity `q`.
fn means(cases: &[Case], x: impl Fn(&Case) -> f64, q: usize) -> Vec<(String, Line)> {
    let mut groups: Vec<(String, String, Line)> = Vec::new();
    for case in cases {
        let Some(value) = case.values[q] else { continue };
        match groups.iter_mut().find(|(g, _, _)| *g == case.group) {
            Some((_, _, points)) => points.push((x(case), value)),
            None => groups.push((case.group.clone(), case.series.clone(), vec![(x(case), value)])),
        }
    }
    let mut out: Vec<(String, Line)> = Vec::new();
    for (_, series, points) in groups {
        let count = points.len() as f64;
        let mean = (
            points.iter().map(|p| p.0).sum::<f64>() / count,
            points.iter().map(|p| p.1).sum::<f64>() / count,
        );
        match out.iter_mut().find(|(s, _)| *s == series) {
            Some((_, line)) => line.push(mean),
            None => out.push((series, vec![mean])),
        }
    }
    for (_, line) in &mut out {
        line.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    out
}

/// The x value of a case on one of the two figures: α_r, or h_rms/|d_JKR| on the depth axis.
fn x_of(case: &Case, depth_axis: bool) -> f64 {
    if depth_axis {
        case.depth_ratio
    } else {
        case.parameter
    }
}

/// Panel `q` of a figure: the wavy reference (α_r axis only), the y = 1 line, and per series
/// its seeds as dots with their mean as a line; for γ also the area-equivalent-radius
/// values (squares, their mean dashed). `series_order` fixes each series' colour on all panels.
fn panel(cases: &[Case], reference: &Reference, depth_axis: bool, q: usize, series_order: &[String]) -> Panel {
    let x = |case: &Case| x_of(case, depth_axis);
    let x_label = if depth_axis {
        "h_rms / |d_JKR|"
    } else {
        "rough-sphere parameter α_r = √(2γ0/(πE* h_rms h'_rms))"
    };
    let mut series = Vec::new();
    if !depth_axis {
        let wavy: Line = reference.iter().filter_map(|(a, v)| Some((*a, v[q]?))).collect();
        series.push(Series::new(
            "wavy sphere, α_r = 2^¼·α",
            REFERENCE_GREY,
            Mark::Trace,
            wavy,
        ));
    }
    for (name, mean) in means(cases, x, q) {
        let k = series_order.iter().position(|s| *s == name).unwrap_or(0);
        let colour = grey_first(k + 1);
        let seeds = |value: usize| -> Line {
            cases
                .iter()
                .filter(|c| c.series == name)
                .filter_map(|c| Some((x(c), c.values[value]?)))
                .collect()
        };
        series.push(Series::new("", colour, Mark::Points, seeds(q)));
        series.push(Series::new(
            format!("{name} (line: seed mean)"),
            colour,
            Mark::Line,
            mean,
        ));
        // γ with the area-equivalent radius √(A/π).
        let area = q + 3;
        if q >= 2 {
            continue;
        }
        let Some((_, area_mean)) = means(cases, x, area).into_iter().find(|(s, _)| *s == name) else {
            continue;
        };
        // Told once in the title, not per series: ten legend rows would cover the data.
        series.push(Series::new("", colour, Mark::Marker(0), seeds(area)));
        series.push(Series::new("", colour, Mark::Dashed, area_mean));
    }
    // A log axis 1.3× beyond the data each way; y from at least 0 to 1.2.
    let (x_low, x_high) = series
        .iter()
        .flat_map(|s| s.points.iter())
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), p| (lo.min(p.0), hi.max(p.0)));
    let (x_low, x_high) = if x_low.is_finite() && x_low > 0.0 {
        (x_low / 1.3, x_high * 1.3)
    } else {
        (0.1, 10.0)
    };
    let title = if q < 2 {
        format!("{}; □, dashed: radius √(A/π)", QUANTITIES[q].0)
    } else {
        QUANTITIES[q].0.to_string()
    };
    Panel::new(title, x_label, QUANTITIES[q].1)
        .with(series)
        .log_x()
        .x_range(x_low, x_high)
        .include_y(0.0)
        .include_y(1.2)
        .guide_y(1.0)
        .legend_at(legend_corner(depth_axis, q))
}

/// The empty corner of panel `q`: γ falls with α_r and rises with h_rms/|d_JKR|; the force
/// ratio stays near 1 for large α_r and small depths.
fn legend_corner(depth_axis: bool, q: usize) -> SeriesLabelPosition {
    match (depth_axis, q >= 2) {
        (false, false) => SeriesLabelPosition::UpperRight,
        (false, true) => SeriesLabelPosition::LowerRight,
        (true, false) => SeriesLabelPosition::UpperLeft,
        (true, true) => SeriesLabelPosition::LowerLeft,
    }
}

/// One of the two figures: three panels side by side.
fn figure(cases: &[Case], reference: &Reference, depth_axis: bool) -> Figure {
    let mut series_order: Vec<String> = Vec::new();
    for case in cases {
        if !series_order.contains(&case.series) {
            series_order.push(case.series.clone());
        }
    }
    Figure::side_by_side(
        (0..QUANTITIES.len())
            .map(|q| panel(cases, reference, depth_axis, q, &series_order))
            .collect(),
    )
}

/// Draws the rough-sphere figures into `out` when some table has rough-sphere cases;
/// returns the file names written (none otherwise).
pub fn write(tables: &[PathBuf], out: &Path) -> Result<Vec<String>> {
    let (mut cases, mut reference) = (Vec::new(), Vec::new());
    for table in tables {
        read(table, &mut cases, &mut reference)?;
    }
    if cases.is_empty() {
        return Ok(Vec::new());
    }
    reference.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut written = Vec::new();
    for (name, depth_axis) in [("rough_sphere_master", false), ("rough_sphere_depth", true)] {
        written.extend(figure(&cases, &reference, depth_axis).save(out, name, (1500, 480))?);
    }
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two seeds of one (H, slope) group and a wavy-sphere row: the parameter is computed
    /// from the rms columns through the library (hand value: h = 1e-3, h' = 0.05, γ = 6e-4,
    /// E* = 1 give α_r = 2.763953), the seed mean is the mean of both, the wavy row lands
    /// at 2^{1/4}·α, and both figures are written.
    #[test]
    fn table_rows_give_parameters_means_and_figures() {
        let dir = tempfile::tempdir().unwrap();
        let table = dir.path().join("table.csv");
        std::fs::write(
            &table,
            "case,series,rms_slope_target,radius,contact_modulus,work_of_adhesion,rms_height,rms_slope,johnson_parameter,adhesive_force_ratio,gamma_approach_norm,gamma_pulloff_norm,status\n\
             a,H = 0.8,0.05,1,1,6e-4,1e-3,0.05,,1.0,1.1,1.2,ok\n\
             b,H = 0.8,0.05,1,1,6e-4,1e-3,0.05,,0.8,0.9,1.0,ok\n\
             c,H = 0.8,0.05,1,1,6e-4,1e-3,0.05,,9.0,9.0,9.0,error\n\
             w,wavy,,,,,,,0.5,0.7,0.8,0.9,ok\n",
        )
        .unwrap();
        let (mut cases, mut reference) = (Vec::new(), Vec::new());
        read(&table, &mut cases, &mut reference).unwrap();
        assert_eq!(cases.len(), 2, "the error row is skipped");
        assert!((cases[0].parameter - 2.763_953_196).abs() < 1e-8);
        let line = means(&cases, |c| c.parameter, 0);
        assert_eq!(line.len(), 1);
        assert_eq!(line[0].1.len(), 1);
        assert!((line[0].1[0].1 - 1.0).abs() < 1e-12, "{:?}", line);
        assert_eq!(reference.len(), 1);
        assert!((reference[0].0 - 0.5 * 2f64.powf(0.25)).abs() < 1e-12);
        let written = write(&[table], dir.path()).unwrap();
        for name in ["rough_sphere_master.png", "rough_sphere_depth.png"] {
            assert!(written.iter().any(|w| w == name), "{written:?}");
            assert!(dir.path().join(name).is_file());
        }
    }
}
