//! Master-curve plots of sweeps (paper Figs. 2, 3, 5), drawn from one or more `table.csv`:
//! - `fig3_master`: γ1/γ0, γ2/γ0 and |F_ad|/|F_JKR| vs the Johnson parameter α (log axis),
//!   one marker style per series;
//! - `fig5_master`: (γ1+γ2)/(2γ0) and (γ1−γ2)/(2γ0) vs α;
//! - `force_radius_cases`: F/|F_JKR| vs a/a_JKR of up to eight cases (from their curve.csv),
//!   and `contact_shapes.png`: their contact maps at the deepest indentation.
//! - `rough_sphere_master`, `rough_sphere_depth`: the rough-sphere study's master plots, when
//!   a table carries roughness statistics (`crate::rough_sphere_plots`).

use crate::figure::{grey_first, save_svg_png, Drawing};
use anyhow::{anyhow, bail, Context, Result};
use clap::{Args, Subcommand};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// `adhesim plot ...`
#[derive(Args)]
pub struct PlotArgs {
    #[command(subcommand)]
    what: PlotKind,
}

#[derive(Subcommand)]
enum PlotKind {
    /// Master curves (Figs. 2, 3, 5) from one or more sweep tables; rows are grouped into
    /// series by the table's `series` column.
    Master {
        /// table.csv files written by `adhesim sweep` (their case folders are used for the
        /// force–radius plot when present).
        #[arg(required = true)]
        tables: Vec<PathBuf>,
        /// Output folder [default: plots/ next to the first table].
        #[arg(long)]
        out: Option<PathBuf>,
    },
}

/// Entry point of `adhesim plot`.
pub fn command(args: &PlotArgs) -> Result<()> {
    match &args.what {
        PlotKind::Master { tables, out } => {
            let out = match out {
                Some(out) => out.clone(),
                None => tables[0].parent().unwrap_or(Path::new(".")).join("plots"),
            };
            let written = write(tables, &out)?;
            println!("plots in {}/: {}", out.display(), written.join(", "));
            Ok(())
        }
    }
}

/// Plots of a sweep folder into `DIR/plots/`; returns the file names.
pub fn from_sweep(dir: &Path, table: &Path) -> Result<Vec<String>> {
    write(&[table.to_path_buf()], &dir.join("plots"))
}

/// One table row's numbers.
struct Row {
    case: String,
    series: String,
    alpha: Option<f64>,
    gamma1: Option<f64>,
    gamma2: Option<f64>,
    force: Option<f64>,
    /// Case folder, when it exists next to the table.
    folder: Option<PathBuf>,
}

fn read_table(path: &Path) -> Result<Vec<Row>> {
    let mut reader = csv::Reader::from_path(path).with_context(|| format!("cannot read {}", path.display()))?;
    let header = reader.headers()?.clone();
    let find = |name: &str| header.iter().position(|h| h == name);
    let case_col = find("case").ok_or_else(|| anyhow!("{}: no `case` column", path.display()))?;
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
            force: number(force),
            folder: folder.is_dir().then_some(folder),
            case,
        });
    }
    Ok(rows)
}

/// Marker outline (pixel offsets) of series k: square, triangle, circle-ish octagon,
/// diamond, inverted triangle, ...
fn marker_shape(k: usize) -> Vec<(i32, i32)> {
    match k % 5 {
        0 => vec![(-4, -4), (4, -4), (4, 4), (-4, 4), (-4, -4)],
        1 => vec![(0, -5), (5, 4), (-5, 4), (0, -5)],
        2 => vec![
            (-2, -4),
            (2, -4),
            (4, -2),
            (4, 2),
            (2, 4),
            (-2, 4),
            (-4, 2),
            (-4, -2),
            (-2, -4),
        ],
        3 => vec![(0, -5), (5, 0), (0, 5), (-5, 0), (0, -5)],
        _ => vec![(0, 5), (5, -4), (-5, -4), (0, 5)],
    }
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

fn err<E: std::fmt::Debug>(e: E) -> anyhow::Error {
    anyhow!("plot: {e:?}")
}

/// A scatter panel with a log α axis; `styles` maps a series name to its marker index.
fn scatter<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    y_label: &str,
    data: &[(String, Series)],
    styles: &[String],
    alpha_range: (f64, f64),
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let values = data
        .iter()
        .flat_map(|(_, s)| s.iter().flat_map(|(_, p)| p.iter().map(|q| q.1)));
    let (lo, hi) = values.fold((0.0f64, 1.2f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
    let pad = 0.05 * (hi - lo);
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(56)
        .build_cartesian_2d((alpha_range.0..alpha_range.1).log_scale(), (lo - pad)..(hi + pad))
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("Johnson parameter α")
        .y_desc(y_label)
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 15))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(err)?;
    chart
        .draw_series(LineSeries::new(
            [(alpha_range.0, 1.0), (alpha_range.1, 1.0)],
            BLACK.mix(0.25),
        ))
        .map_err(err)?;
    if lo < 0.0 {
        chart
            .draw_series(LineSeries::new(
                [(alpha_range.0, 0.0), (alpha_range.1, 0.0)],
                BLACK.mix(0.4),
            ))
            .map_err(err)?;
    }
    for (q, (quantity, series)) in data.iter().enumerate() {
        for (name, points) in series {
            let k = styles.iter().position(|s| s == name).unwrap_or(0);
            let colour = if data.len() > 1 {
                grey_first(1 + q)
            } else {
                grey_first(k)
            };
            let shape = marker_shape(k);
            let style = colour.stroke_width(2);
            let legend_shape = shape.clone();
            let label = if quantity.is_empty() {
                name.clone()
            } else {
                format!("{quantity}: {name}")
            };
            chart
                .draw_series(
                    points
                        .iter()
                        .map(|&p| EmptyElement::at(p) + PathElement::new(shape.clone(), style)),
                )
                .map_err(err)?
                .label(label)
                .legend(move |(x, y)| EmptyElement::at((x + 9, y)) + PathElement::new(legend_shape.clone(), style));
        }
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

fn force_radius<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, curves: &[(String, Vec<(f64, f64)>)]) -> Result<()>
where
    DB::ErrorType: 'static,
{
    area.fill(&WHITE).map_err(err)?;
    let all = curves.iter().flat_map(|(_, c)| c.iter());
    let (x1, y0, y1) = all.fold((1.0f64, -1.0f64, 1.0f64), |(x1, y0, y1), p| {
        (x1.max(p.0), y0.min(p.1), y1.max(p.1))
    });
    let mut chart = ChartBuilder::on(area)
        .caption("Force vs contact radius (cf. paper Fig. 2a)", ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..x1 * 1.05, (y0 - 0.05 * (y1 - y0))..(y1 + 0.05 * (y1 - y0)))
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("a / a_JKR")
        .y_desc("F / |F_JKR|")
        .label_style(("sans-serif", 14))
        .axis_desc_style(("sans-serif", 16))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(err)?;
    for (k, (label, points)) in curves.iter().enumerate() {
        let colour = grey_first(k + 1);
        chart
            .draw_series(LineSeries::new(points.iter().copied(), colour.stroke_width(1)))
            .map_err(err)?
            .label(label.as_str())
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], colour.stroke_width(2)));
        chart
            .draw_series(points.iter().map(|&p| Circle::new(p, 1, colour.filled())))
            .map_err(err)?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .label_font(("sans-serif", 14))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.3))
        .draw()
        .map_err(err)?;
    area.present().map_err(err)?;
    Ok(())
}

/// Thumbnails of `snapshots/max_depth.png` of each case with a caption, as one PNG.
fn contact_shapes(path: &Path, cases: &[(String, PathBuf)]) -> Result<bool> {
    const TILE: u32 = 200;
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
        root.fill(&WHITE).map_err(err)?;
        for (k, (label, tile)) in tiles.iter().enumerate() {
            let x = 10 + k as i32 * (TILE as i32 + 10);
            let element = BitMapElement::with_owned_buffer((x, 10), (TILE, TILE), tile.as_raw().clone())
                .ok_or_else(|| anyhow!("thumbnail buffer size"))?;
            root.draw(&element).map_err(err)?;
            root.draw(&Text::new(
                label.clone(),
                (x + 4, TILE as i32 + 18),
                ("sans-serif", 15).into_font().color(&BLACK),
            ))
            .map_err(err)?;
        }
        root.present().map_err(err)?;
    }
    image::RgbImage::from_raw(width, height, buffer)
        .ok_or_else(|| anyhow!("image buffer size"))?
        .save(path)
        .with_context(|| format!("cannot write {}", path.display()))?;
    Ok(true)
}

fn alpha_label(row: &Row) -> String {
    match row.alpha {
        Some(a) => format!("α = {a:.3}"),
        None => row.case.clone(),
    }
}

fn draw_fig3<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    data: &[Series; 3],
    styles: &[String],
    range: (f64, f64),
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(err)?;
    let panels = root.split_evenly((1, 3));
    let one = |s: &Series| vec![(String::new(), s.clone())];
    scatter(&panels[0], "(a) approach", "γ1 / γ0", &one(&data[0]), styles, range)?;
    scatter(&panels[1], "(b) detachment", "γ2 / γ0", &one(&data[1]), styles, range)?;
    scatter(
        &panels[2],
        "(c) adhesive force",
        "|F_ad| / |F_JKR|",
        &one(&data[2]),
        styles,
        range,
    )?;
    root.present().map_err(err)
}

fn draw_fig5<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    data: &[(String, Series)],
    styles: &[String],
    range: (f64, f64),
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(err)?;
    scatter(
        &root,
        "Mean and half difference (cf. paper Fig. 5)",
        "",
        data,
        styles,
        range,
    )?;
    root.present().map_err(err)
}

/// Draws every plot the tables allow into `out`; returns the file names written.
pub fn write(tables: &[PathBuf], out: &Path) -> Result<Vec<String>> {
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
        let g1 = group(&rows, |r| r.gamma1);
        let g2 = group(&rows, |r| r.gamma2);
        let force = group(&rows, |r| r.force);
        let mean = group(&rows, |r| Some((r.gamma1? + r.gamma2?) / 2.0));
        let half_difference = group(&rows, |r| Some((r.gamma1? - r.gamma2?) / 2.0));
        let fig3 = [g1, g2, force];
        let fig5 = vec![
            ("(γ1+γ2)/(2γ0)".to_string(), mean),
            ("(γ1−γ2)/(2γ0)".to_string(), half_difference),
        ];
        for (name, size, figure) in [
            ("fig3_master", (1500, 480), MasterFigure::Fig3(&fig3)),
            ("fig5_master", (800, 560), MasterFigure::Fig5(&fig5)),
        ] {
            let drawing = Master {
                figure,
                styles: &styles,
                range,
            };
            written.extend(save_svg_png(out, name, size, &drawing)?);
        }
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
        written.extend(save_svg_png(
            out,
            "force_radius_cases",
            (900, 640),
            &CaseCurves(&curves),
        )?);
        if contact_shapes(&out.join("contact_shapes.png"), &thumbnails)? {
            written.push("contact_shapes.png".into());
        }
    }
    written.extend(crate::rough_sphere_plots::write(tables, out)?);
    Ok(written)
}

/// Fig. 3 (γ1, γ2, force vs α) or Fig. 5 (mean and half difference) of the master curves.
enum MasterFigure<'a> {
    Fig3(&'a [Series; 3]),
    Fig5(&'a [(String, Series)]),
}

/// A master-curve figure with its series styles and α range, as a [`Drawing`].
struct Master<'a> {
    figure: MasterFigure<'a>,
    styles: &'a [String],
    range: (f64, f64),
}

impl Drawing for Master<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        match self.figure {
            MasterFigure::Fig3(data) => draw_fig3(area.clone(), data, self.styles, self.range),
            MasterFigure::Fig5(data) => draw_fig5(area.clone(), data, self.styles, self.range),
        }
    }
}

/// The force–radius curves of chosen cases, as a [`Drawing`].
struct CaseCurves<'a>(&'a [(String, Vec<(f64, f64)>)]);

impl Drawing for CaseCurves<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        force_radius(area, self.0)
    }
}
