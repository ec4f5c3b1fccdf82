//! Master-curve plots of sweeps (paper Figs. 2, 3, 5), drawn from one or more `table.csv`:
//! - `fig3_master`: γ1/γ0, γ2/γ0 and |F_ad|/|F_JKR| vs the Johnson parameter α (log axis),
//!   one marker style per series;
//! - `fig5_master`: (γ1+γ2)/(2γ0) and (γ1−γ2)/(2γ0) vs α;
//! - `force_radius_cases`: F/|F_JKR| vs a/a_JKR of up to eight cases (from their curve.csv),
//!   and `contact_shapes.png`: their contact maps at the deepest indentation.
//! - `rough_sphere_master`, `rough_sphere_depth`: the rough-sphere study's master plots, when
//!   a table carries roughness statistics (`crate::rough_sphere_plots`).

use crate::figure::{grey_first, plot_error, register_font, Figure, Mark, Panel, Series as Drawn};
use anyhow::{anyhow, bail, Context, Result};
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// How `fig3_master` and `fig5_master` are drawn (the defaults are a sweep's own plots).
#[derive(Debug, Clone, Copy)]
pub struct MasterStyle {
    /// Each series' points joined by a line.
    pub join: bool,
    /// The γ fits with the area-equivalent radius as series of their own.
    pub area: bool,
}

impl Default for MasterStyle {
    fn default() -> Self {
        Self {
            join: false,
            area: true,
        }
    }
}

/// Rebuilds `DIR/table.csv` of a sweep and its master-curve plots (after
/// [`adhesim_scenario::sweep::table::rebuild`]), as `adhesim sweep merge` does.
pub fn sweep_table_and_plots(
    dir: &Path,
    plan: &adhesim_scenario::sweep::Plan,
) -> Result<(adhesim_scenario::sweep::table::TableSummary, Vec<String>)> {
    let summary = adhesim_scenario::sweep::table::rebuild(dir, plan)?;
    let plots = from_sweep(dir, &summary.path).context("master-curve plots")?;
    Ok((summary, plots))
}

/// Plots of a sweep folder into `DIR/plots/`; returns the file names.
pub fn from_sweep(dir: &Path, table: &Path) -> Result<Vec<String>> {
    write(&[table.to_path_buf()], &dir.join("plots"), MasterStyle::default())
}

/// One table row's numbers.
struct Row {
    case: String,
    series: String,
    alpha: Option<f64>,
    gamma1: Option<f64>,
    gamma2: Option<f64>,
    /// γ1/γ0 and γ2/γ0 fitted with the area-equivalent radius √(A/π) (tables of results
    /// revision 6 and later).
    gamma1_area: Option<f64>,
    gamma2_area: Option<f64>,
    force: Option<f64>,
    /// Case folder, when it exists next to the table.
    folder: Option<PathBuf>,
}

/// The columns `plot master` draws: each cell of a finished row must be a finite number
/// (empty: no value), and `johnson_parameter` one > 0 (the log axis). `plot master` drew
/// NaN, inf, text and α ≤ 0 rows without a word; now the first such cell is an error naming
/// the table, the line, the case and the column.
pub fn check_rows(path: &Path) -> Result<()> {
    let mut reader = csv::Reader::from_path(path).with_context(|| format!("cannot read {}", path.display()))?;
    let header = reader.headers()?.clone();
    let find = |name: &str| header.iter().position(|h| h == name);
    let (case_col, status) = (find("case"), find("status"));
    let columns = [
        "johnson_parameter",
        "gamma_approach_norm",
        "gamma_pulloff_norm",
        "adhesive_force_ratio",
        "gamma_approach_area_norm",
        "gamma_pulloff_area_norm",
    ];
    for (index, record) in reader.records().enumerate() {
        let record = record.with_context(|| format!("{}: malformed row", path.display()))?;
        if status.and_then(|c| record.get(c)).is_some_and(|s| s != "ok") {
            continue;
        }
        for name in columns {
            let Some(text) = find(name).and_then(|c| record.get(c)) else {
                continue;
            };
            let value = text.trim().parse::<f64>().ok().filter(|v| v.is_finite());
            let bad = match value {
                _ if text.trim().is_empty() => name == "johnson_parameter",
                None => true,
                Some(alpha) if name == "johnson_parameter" => alpha <= 0.0,
                Some(_) => false,
            };
            if bad {
                let requirement = if name == "johnson_parameter" {
                    "a number > 0 (the log axis of α)"
                } else {
                    "a finite number or empty"
                };
                bail!(
                    "{} line {}{}: {name} = {text:?} cannot be drawn; it must be {requirement}",
                    path.display(),
                    index + 2,
                    case_col
                        .and_then(|c| record.get(c))
                        .map(|case| format!(" (case {case})"))
                        .unwrap_or_default()
                );
            }
        }
    }
    Ok(())
}

fn read_table(path: &Path) -> Result<Vec<Row>> {
    let mut reader = csv::Reader::from_path(path).with_context(|| format!("cannot read {}", path.display()))?;
    let header = reader.headers()?.clone();
    let find = |name: &str| header.iter().position(|h| h == name);
    let case_col = find("case").ok_or_else(|| anyhow!("{}: no `case` column", path.display()))?;
    let (g1_area, g2_area) = (find("gamma_approach_area_norm"), find("gamma_pulloff_area_norm"));
    let (alpha, g1, g2, force, series, status) = (
        find("johnson_parameter"),
        find("gamma_approach_norm"),
        find("gamma_pulloff_norm"),
        find("adhesive_force_ratio"),
        find("series"),
        find("status"),
    );
    let default_series = path
        .parent()
        .and_then(|p| p.file_name())
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "sweep".into());
    let cases_dir = path.parent().unwrap_or(Path::new(".")).join("cases");
    let mut rows = Vec::new();
    for record in reader.records() {
        let record = record.with_context(|| format!("{}: malformed row", path.display()))?;
        if status.and_then(|c| record.get(c)).is_some_and(|s| s != "ok") {
            continue;
        }
        let number = |col: Option<usize>| col.and_then(|c| record.get(c)).and_then(|s| s.parse::<f64>().ok());
        let case = record.get(case_col).unwrap_or_default().to_string();
        let folder = cases_dir.join(&case);
        rows.push(Row {
            series: series
                .and_then(|c| record.get(c))
                .filter(|s| !s.is_empty())
                .map(str::to_string)
                .unwrap_or_else(|| default_series.clone()),
            alpha: number(alpha).filter(|a| *a > 0.0),
            gamma1: number(g1),
            gamma2: number(g2),
            gamma1_area: number(g1_area),
            gamma2_area: number(g2_area),
            force: number(force),
            folder: folder.is_dir().then_some(folder),
            case,
        });
    }
    Ok(rows)
}

type Series = Vec<(String, Vec<(f64, f64)>)>;

/// Points (α, value) grouped by series, in order of first appearance.
fn group(rows: &[Row], value: impl Fn(&Row) -> Option<f64>) -> Series {
    let mut out: Series = Vec::new();
    for row in rows {
        let (Some(alpha), Some(v)) = (row.alpha, value(row)) else {
            continue;
        };
        if !v.is_finite() {
            continue;
        }
        match out.iter_mut().find(|(s, _)| *s == row.series) {
            Some((_, points)) => points.push((alpha, v)),
            None => out.push((row.series.clone(), vec![(alpha, v)])),
        }
    }
    out
}

/// A scatter panel with a log α axis; `styles` maps a series name to its marker index;
/// `join` draws a line through each series' points in α order.
fn scatter(
    title: &str,
    y_label: &str,
    data: &[(String, Series)],
    styles: &[String],
    alpha_range: (f64, f64),
    join: bool,
) -> Panel {
    let mut panel = Panel::new(title, "Johnson parameter α", y_label)
        .log_x()
        .x_range(alpha_range.0, alpha_range.1)
        .include_y(0.0)
        .include_y(1.2)
        .guide_y(1.0)
        .legend_at(SeriesLabelPosition::LowerRight);
    for (q, (quantity, series)) in data.iter().enumerate() {
        for (name, points) in series {
            let k = styles.iter().position(|s| s == name).unwrap_or(0);
            let colour = if data.len() > 1 {
                grey_first(1 + q)
            } else {
                grey_first(k)
            };
            let label = if quantity.is_empty() {
                name.clone()
            } else {
                format!("{quantity}: {name}")
            };
            if join {
                let mut sorted = points.clone();
                sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
                panel = panel.with([Drawn::new("", colour, Mark::Line, sorted)]);
            }
            panel = panel.with([Drawn::new(label, colour, Mark::Marker(k), points.clone())]);
        }
    }
    panel
}

/// A case's (a/a_JKR, F/|F_JKR|) from its curve.csv.
fn case_curve(folder: &Path) -> Result<Vec<(f64, f64)>> {
    let path = folder.join("curve.csv");
    let mut reader = csv::Reader::from_path(&path).with_context(|| format!("cannot read {}", path.display()))?;
    let header = reader.headers()?.clone();
    let (Some(a), Some(f)) = (
        header.iter().position(|h| h == "radius_norm"),
        header.iter().position(|h| h == "force_norm"),
    ) else {
        bail!("{}: no radius_norm/force_norm columns (γ0 = 0?)", path.display());
    };
    let mut points = Vec::new();
    for record in reader.records() {
        let record = record?;
        if let (Some(x), Some(y)) = (
            record.get(a).and_then(|s| s.parse::<f64>().ok()),
            record.get(f).and_then(|s| s.parse::<f64>().ok()),
        ) {
            if x.is_finite() && y.is_finite() {
                points.push((x, y));
            }
        }
    }
    Ok(points)
}

/// Paper Fig. 2a: F/|F_JKR| vs a/a_JKR of the chosen cases, from a = 0.
fn force_radius(curves: &[(String, Vec<(f64, f64)>)]) -> Figure {
    let x_top = curves
        .iter()
        .flat_map(|(_, c)| c.iter())
        .fold(1.0f64, |top, p| top.max(p.0));
    let series = curves
        .iter()
        .enumerate()
        .map(|(k, (label, points))| Drawn::new(label.as_str(), grey_first(k + 1), Mark::Trace, points.clone()));
    let panel = Panel::new(
        "Force vs contact radius (cf. paper Fig. 2a)",
        "a / a_JKR",
        "F / |F_JKR|",
    )
    .x_range(0.0, x_top * 1.05)
    .include_y(-1.0)
    .include_y(1.0)
    .with(series);
    Figure::stacked(vec![panel])
}

/// Thumbnails of `snapshots/max_depth.png` of each case with a caption, as one PNG.
fn contact_shapes(path: &Path, cases: &[(String, PathBuf)]) -> Result<bool> {
    const TILE: u32 = 200;
    register_font()?;
    let mut tiles = Vec::new();
    for (label, folder) in cases {
        let Ok(image) = image::open(folder.join("snapshots/max_depth.png")) else {
            continue;
        };
        let small = image::imageops::resize(&image.to_rgb8(), TILE, TILE, image::imageops::FilterType::Triangle);
        tiles.push((label.clone(), small));
    }
    if tiles.is_empty() {
        return Ok(false);
    }
    let width = TILE * tiles.len() as u32 + 10 * (tiles.len() as u32 + 1);
    let height = TILE + 50;
    let mut buffer = vec![255u8; (width * height * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(plot_error)?;
        for (k, (label, tile)) in tiles.iter().enumerate() {
            let x = 10 + k as i32 * (TILE as i32 + 10);
            let element = BitMapElement::with_owned_buffer((x, 10), (TILE, TILE), tile.as_raw().clone())
                .ok_or_else(|| anyhow!("thumbnail buffer size"))?;
            root.draw(&element).map_err(plot_error)?;
            root.draw(&Text::new(
                label.clone(),
                (x + 4, TILE as i32 + 18),
                ("sans-serif", 15).into_font().color(&BLACK),
            ))
            .map_err(plot_error)?;
        }
        root.present().map_err(plot_error)?;
    }
    let image = image::RgbImage::from_raw(width, height, buffer).ok_or_else(|| anyhow!("image buffer size"))?;
    crate::figure::files::save_image(&image, path)?;
    Ok(true)
}

fn alpha_label(row: &Row) -> String {
    match row.alpha {
        Some(a) => format!("α = {a:.3}"),
        None => row.case.clone(),
    }
}

/// Legend suffix of the γ fitted with the area-equivalent radius.
const AREA_SUFFIX: &str = ", radius √(A/π)";

/// Paper Fig. 3: γ1/γ0, γ2/γ0 and |F_ad|/|F_JKR| vs α, side by side; (a) and (b) also with
/// the area-equivalent radius where the tables have it.
fn fig3(data: &[Series; 3], styles: &[String], range: (f64, f64), join: bool) -> Figure {
    let one = |s: &Series| vec![(String::new(), s.clone())];
    Figure::side_by_side(vec![
        scatter("(a) approach", "γ1 / γ0", &one(&data[0]), styles, range, join),
        scatter("(b) detachment", "γ2 / γ0", &one(&data[1]), styles, range, join),
        scatter(
            "(c) adhesive force",
            "|F_ad| / |F_JKR|",
            &one(&data[2]),
            styles,
            range,
            join,
        ),
    ])
}

/// Paper Fig. 5: the mean and half difference of γ1 and γ2 vs α.
fn fig5(data: &[(String, Series)], styles: &[String], range: (f64, f64), join: bool) -> Figure {
    let title = "Mean and half difference (cf. paper Fig. 5)";
    Figure::stacked(vec![scatter(title, "(γ1 ± γ2) / (2γ0)", data, styles, range, join)])
}

/// Draws every plot the tables allow into `out`; returns the file names written.
pub fn write(tables: &[PathBuf], out: &Path, style: MasterStyle) -> Result<Vec<String>> {
    let mut rows = Vec::new();
    for table in tables {
        rows.extend(read_table(table)?);
    }
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    let mut written = Vec::new();
    let mut styles: Vec<String> = Vec::new();
    for row in &rows {
        if !styles.contains(&row.series) {
            styles.push(row.series.clone());
        }
    }
    let alphas: Vec<f64> = rows.iter().filter_map(|r| r.alpha).collect();
    if !alphas.is_empty() {
        let lo = alphas.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = alphas.iter().copied().fold(0.0, f64::max);
        let range = (lo / 1.3, hi * 1.3);
        let mut g1 = group(&rows, |r| r.gamma1);
        let mut g2 = group(&rows, |r| r.gamma2);
        // The same fits with the area-equivalent radius, as series of their own (markers
        // after the tables' own), where the tables have them.
        let area = |value: fn(&Row) -> Option<f64>| {
            let mut series = group(&rows, value);
            series.iter_mut().for_each(|(name, _)| name.push_str(AREA_SUFFIX));
            series
        };
        if style.area {
            g1.extend(area(|r| r.gamma1_area));
            g2.extend(area(|r| r.gamma2_area));
        }
        for (name, _) in g1.iter().chain(&g2) {
            if !styles.contains(name) {
                styles.push(name.clone());
            }
        }
        let force = group(&rows, |r| r.force);
        let mean = group(&rows, |r| Some((r.gamma1? + r.gamma2?) / 2.0));
        let half_difference = group(&rows, |r| Some((r.gamma1? - r.gamma2?) / 2.0));
        let gammas_force = [g1, g2, force];
        let mean_difference = vec![
            ("(γ1+γ2)/(2γ0)".to_string(), mean),
            ("(γ1−γ2)/(2γ0)".to_string(), half_difference),
        ];
        let fig3 = fig3(&gammas_force, &styles, range, style.join);
        written.extend(fig3.save(out, "fig3_master", (1500, 480))?);
        let fig5 = fig5(&mean_difference, &styles, range, style.join);
        written.extend(fig5.save(out, "fig5_master", (800, 560))?);
    }
    // Fig. 2: up to eight cases with folders, spread over the α range.
    let mut with_folders: Vec<&Row> = rows.iter().filter(|r| r.folder.is_some()).collect();
    with_folders.sort_by(|a, b| a.alpha.unwrap_or(0.0).total_cmp(&b.alpha.unwrap_or(0.0)).reverse());
    let chosen: Vec<&Row> = if with_folders.len() <= 8 {
        with_folders
    } else {
        (0..8).map(|k| with_folders[k * (with_folders.len() - 1) / 7]).collect()
    };
    let mut curves = Vec::new();
    let mut thumbnails = Vec::new();
    for row in &chosen {
        let folder = row.folder.as_ref().expect("filtered");
        if let Ok(curve) = case_curve(folder) {
            curves.push((alpha_label(row), curve));
            thumbnails.push((alpha_label(row), folder.clone()));
        }
    }
    if !curves.is_empty() {
        written.extend(force_radius(&curves).save(out, "force_radius_cases", (900, 640))?);
        if contact_shapes(&out.join("contact_shapes.png"), &thumbnails)? {
            written.push("contact_shapes.png".into());
        }
    }
    written.extend(crate::rough_sphere_plots::write(tables, out)?);
    Ok(written)
}
