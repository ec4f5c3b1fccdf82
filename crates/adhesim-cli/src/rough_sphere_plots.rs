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

use crate::figure::{grey_first, save_svg_png, Drawing};
use adhesim::analysis::johnson::{rough_sphere_parameter, roughness_depth_ratio};
use anyhow::{anyhow, Context, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
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

fn err<E: std::fmt::Debug>(e: E) -> anyhow::Error {
    anyhow!("plot: {e:?}")
}

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

/// One of the two figures: the x axis it uses and whether the wavy reference belongs on it.
struct Figure<'a> {
    cases: &'a [Case],
    reference: &'a Reference,
    depth_axis: bool,
}

impl Figure<'_> {
    fn x(&self, case: &Case) -> f64 {
        if self.depth_axis {
            case.depth_ratio
        } else {
            case.parameter
        }
    }

    fn panel<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>, q: usize, styles: &[String]) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let reference: Vec<(f64, f64)> = if self.depth_axis {
            Vec::new()
        } else {
            self.reference.iter().filter_map(|(a, v)| Some((*a, v[q]?))).collect()
        };
        let points: Vec<(f64, f64)> = self
            .cases
            .iter()
            .flat_map(|c| {
                let area = if q < 2 { c.values[q + 3] } else { None };
                [c.values[q], area].into_iter().flatten().map(|v| (self.x(c), v))
            })
            .chain(reference.iter().copied())
            .collect();
        let (x_lo, x_hi) = points
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), p| (lo.min(p.0), hi.max(p.0)));
        let (y_lo, y_hi) = points
            .iter()
            .fold((0.0f64, 1.2f64), |(lo, hi), p| (lo.min(p.1), hi.max(p.1)));
        let (x_lo, x_hi) = (x_lo / 1.3, x_hi * 1.3);
        let pad = 0.05 * (y_hi - y_lo);
        let mut chart = ChartBuilder::on(area)
            .caption(QUANTITIES[q].0, ("sans-serif", 18))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(56)
            .build_cartesian_2d((x_lo..x_hi).log_scale(), (y_lo - pad)..(y_hi + pad))
            .map_err(err)?;
        let x_desc = if self.depth_axis {
            "h_rms / |d_JKR|"
        } else {
            "rough-sphere parameter α_r = √(2γ0/(πE* h_rms h'_rms))"
        };
        chart
            .configure_mesh()
            .x_desc(x_desc)
            .y_desc(QUANTITIES[q].1)
            .label_style(("sans-serif", 13))
            .axis_desc_style(("sans-serif", 15))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()
            .map_err(err)?;
        chart
            .draw_series(LineSeries::new([(x_lo, 1.0), (x_hi, 1.0)], BLACK.mix(0.25)))
            .map_err(err)?;
        if !reference.is_empty() {
            let style = BLACK.mix(0.6).stroke_width(1);
            chart
                .draw_series(LineSeries::new(reference.iter().copied(), style))
                .map_err(err)?
                .label("wavy sphere, α_r = 2^¼·α")
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], style));
            chart
                .draw_series(reference.iter().map(|&p| Circle::new(p, 2, BLACK.mix(0.6).filled())))
                .map_err(err)?;
        }
        for (series, line) in means(self.cases, |c| self.x(c), q) {
            let k = styles.iter().position(|s| *s == series).unwrap_or(0);
            let colour = grey_first(k + 1);
            let style = colour.stroke_width(2);
            let seeds: Vec<(f64, f64)> = self
                .cases
                .iter()
                .filter(|c| c.series == series)
                .filter_map(|c| Some((self.x(c), c.values[q]?)))
                .collect();
            chart
                .draw_series(seeds.iter().map(|&p| Circle::new(p, 3, colour.stroke_width(1))))
                .map_err(err)?;
            chart
                .draw_series(LineSeries::new(line, style))
                .map_err(err)?
                .label(format!("{series} (line: seed mean)"))
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], style));
            // γ with the area-equivalent radius: thin line, square markers.
            let area = q + 3;
            if q >= 2 {
                continue;
            }
            let Some((_, area_line)) = means(self.cases, |c| self.x(c), area)
                .into_iter()
                .find(|(s, _)| *s == series)
            else {
                continue;
            };
            let thin = colour.mix(0.7).stroke_width(1);
            chart
                .draw_series(self.cases.iter().filter(|c| c.series == series).filter_map(|c| {
                    let p = (self.x(c), c.values[area]?);
                    Some(EmptyElement::at(p) + Rectangle::new([(-3, -3), (3, 3)], thin))
                }))
                .map_err(err)?;
            chart
                .draw_series(LineSeries::new(area_line, thin))
                .map_err(err)?
                .label(format!("{series}, radius √(A/π)"))
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], thin));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerRight)
            .label_font(("sans-serif", 13))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.3))
            .draw()
            .map_err(err)?;
        Ok(())
    }
}

impl Drawing for Figure<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        area.fill(&WHITE).map_err(err)?;
        let mut styles: Vec<String> = Vec::new();
        for case in self.cases {
            if !styles.contains(&case.series) {
                styles.push(case.series.clone());
            }
        }
        let panels = area.split_evenly((1, 3));
        for (q, panel) in panels.iter().enumerate() {
            self.panel(panel, q, &styles)?;
        }
        area.present().map_err(err)
    }
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
        let figure = Figure {
            cases: &cases,
            reference: &reference,
            depth_axis,
        };
        written.extend(save_svg_png(out, name, (1500, 480), &figure)?);
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
