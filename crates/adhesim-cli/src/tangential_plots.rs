//! Figures of tangential motion (paper Figs. 6–10): forces vs travelled distance, strips
//! of consecutive contact maps with the moving axis marked, and the study plots (generic
//! multi-series charts with optional reference lines).

use crate::figure::{save_svg_png, Drawing};
use adhesim::analysis::reference::Jkr;
use adhesim::{Grid, Phase, StepRecord};
use anyhow::{anyhow, Context, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

pub use crate::figure::PALETTE;

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    /// Points joined by a line.
    LinePoints,
    /// Points only.
    Points,
    /// A line only.
    Line,
    /// A dashed line only (references, means).
    Dashed,
}

/// One series of a chart.
pub struct Series {
    pub label: String,
    pub colour: RGBColor,
    pub style: Style,
    pub points: Vec<(f64, f64)>,
}

impl Series {
    pub fn new(label: impl Into<String>, colour: RGBColor, style: Style, points: Vec<(f64, f64)>) -> Self {
        Self {
            label: label.into(),
            colour,
            style,
            points: points
                .into_iter()
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .collect(),
        }
    }
}

/// One chart (a panel).
pub struct Chart {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
    /// Forces y = 0 into the range.
    pub include_zero: bool,
}

fn ranges(chart: &Chart) -> ((f64, f64), (f64, f64)) {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for &(x, y) in chart.series.iter().flat_map(|s| s.points.iter()) {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if chart.include_zero && y0.is_finite() {
        y0 = y0.min(0.0);
        y1 = y1.max(0.0);
    }
    let pad = |lo: f64, hi: f64| {
        if !(lo.is_finite() && hi.is_finite()) {
            return (0.0, 1.0);
        }
        let span = if hi > lo { hi - lo } else { lo.abs().max(1e-12) };
        (lo - 0.05 * span, hi + 0.05 * span)
    };
    (pad(x0, x1), pad(y0, y1))
}

fn draw_chart<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, chart: &Chart) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("plot: {e}");
    let ((x0, x1), (y0, y1)) = ranges(chart);
    let mut c = ChartBuilder::on(area)
        .caption(&chart.title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(e)?;
    c.configure_mesh()
        .x_desc(&chart.x_label)
        .y_desc(&chart.y_label)
        .label_style(("sans-serif", 14))
        .axis_desc_style(("sans-serif", 16))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(e)?;
    if y0 < 0.0 && y1 > 0.0 {
        c.draw_series(LineSeries::new([(x0, 0.0), (x1, 0.0)], BLACK.mix(0.4)))
            .map_err(e)?;
    }
    for s in &chart.series {
        if s.points.is_empty() {
            continue;
        }
        let colour = s.colour;
        let label = s.label.as_str();
        match s.style {
            Style::Line | Style::LinePoints => {
                let drawn = c
                    .draw_series(LineSeries::new(s.points.iter().copied(), colour.stroke_width(2)))
                    .map_err(e)?;
                if s.style == Style::Line {
                    drawn
                        .label(label)
                        .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], colour.stroke_width(2)));
                }
            }
            Style::Dashed => {
                let drawn = c
                    .draw_series(DashedLineSeries::new(
                        s.points.iter().copied(),
                        6,
                        4,
                        colour.stroke_width(2),
                    ))
                    .map_err(e)?;
                // An unlabelled series (e.g. the second line of a band) gets no legend row.
                if !label.is_empty() {
                    drawn
                        .label(label)
                        .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], colour.stroke_width(2)));
                }
            }
            Style::Points => {}
        }
        if matches!(s.style, Style::Points | Style::LinePoints) {
            c.draw_series(s.points.iter().map(|&p| Circle::new(p, 3, colour.filled())))
                .map_err(e)?
                .label(label)
                .legend(move |(x, y)| Circle::new((x + 9, y), 3, colour.filled()));
        }
    }
    if chart.series.iter().any(|s| !s.label.is_empty()) {
        c.configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .label_font(("sans-serif", 13))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.3))
            .draw()
            .map_err(e)?;
    }
    Ok(())
}

fn draw_panels<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, charts: &[Chart]) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("plot: {e}");
    root.fill(&WHITE).map_err(e)?;
    let areas = root.split_evenly((charts.len().max(1), 1));
    for (area, chart) in areas.iter().zip(charts) {
        draw_chart(area, chart)?;
    }
    root.present().map_err(e)?;
    Ok(())
}

/// Writes `NAME.svg` and `NAME.png` with the charts stacked vertically; returns the paths
/// relative to the parent of `dir` (`plots/NAME.svg`, ...).
pub fn write_panels(dir: &Path, name: &str, charts: &[Chart]) -> Result<Vec<String>> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let height = 420 * charts.len().max(1) as u32 + 60;
    save_svg_png(dir, name, (800, height), &Panels(charts))?;
    let folder = dir
        .file_name()
        .map(|f| f.to_string_lossy().into_owned())
        .unwrap_or_default();
    Ok(vec![format!("{folder}/{name}.svg"), format!("{folder}/{name}.png")])
}

/// Paper Fig. 6a: F_N and F_T vs travelled distance x (normalised by |F_JKR| and, where
/// the indenter is wavy, x by λ), with the two means of F_T over the stationary part.
pub fn force_distance(
    records: &[StepRecord],
    jkr: Option<Jkr>,
    wavelength: Option<f64>,
    means: (f64, f64),
    stationary_start: f64,
) -> Vec<Chart> {
    let moving: Vec<&StepRecord> = records
        .iter()
        .filter(|r| matches!(r.phase, Some(Phase::Roll | Phase::Slide)))
        .collect();
    let force = jkr.map_or(1.0, |j| j.critical_force().abs());
    let length = wavelength.unwrap_or(1.0);
    let (x_label, f_unit) = (
        if wavelength.is_some() { "x / λ" } else { "x" },
        if jkr.is_some() { " / |F_JKR|" } else { "" },
    );
    // Forward and return strokes as separate series.
    let turn = moving
        .iter()
        .position(|r| r.offset >= moving.iter().map(|m| m.offset).fold(f64::NEG_INFINITY, f64::max))
        .unwrap_or(moving.len());
    let (forward, back) = moving.split_at((turn + 1).min(moving.len()));
    let pts = |rs: &[&StepRecord], f: &dyn Fn(&StepRecord) -> f64| -> Vec<(f64, f64)> {
        rs.iter().map(|r| (r.offset / length, f(r) / force)).collect()
    };
    let mut normal = vec![Series::new(
        "forward",
        PALETTE[0],
        Style::LinePoints,
        pts(forward, &|r| r.force_normal),
    )];
    let mut tangential = vec![Series::new(
        "forward (end of step)",
        PALETTE[0],
        Style::LinePoints,
        pts(forward, &|r| r.force_tangential),
    )];
    if !back.is_empty() {
        normal.push(Series::new(
            "return",
            PALETTE[1],
            Style::LinePoints,
            pts(back, &|r| r.force_normal),
        ));
        tangential.push(Series::new(
            "return (end of step)",
            PALETTE[1],
            Style::LinePoints,
            pts(back, &|r| r.force_tangential),
        ));
    }
    let x_end = forward.last().map_or(0.0, |r| r.offset) / length;
    let x_start = stationary_start / length;
    tangential.push(Series::new(
        format!("per-step mean {:.4}", means.0 / force),
        PALETTE[2],
        Style::Dashed,
        vec![(x_start, means.0 / force), (x_end, means.0 / force)],
    ));
    tangential.push(Series::new(
        format!("work-based mean {:.4}", means.1 / force),
        PALETTE[4],
        Style::Dashed,
        vec![(x_start, means.1 / force), (x_end, means.1 / force)],
    ));
    vec![
        Chart {
            title: "Normal force vs travelled distance".into(),
            x_label: x_label.into(),
            y_label: format!("F_N{f_unit}"),
            series: normal,
            include_zero: true,
        },
        Chart {
            title: "Tangential force vs travelled distance".into(),
            x_label: x_label.into(),
            y_label: format!("F_T{f_unit}"),
            series: tangential,
            include_zero: true,
        },
    ]
}

/// Colours of the contact maps (as in `output.rs`).
const STAYING: [u8; 3] = [70, 70, 70];
const ATTACHED: [u8; 3] = [215, 25, 28];
const DETACHED: [u8; 3] = [30, 90, 220];
const AXIS: [u8; 3] = [40, 170, 40];

/// Paper Figs. 6b and 9: consecutive contact maps side by side, cropped to the union of
/// the contacts, with newly attached elements red, just detached blue, staying grey and
/// the moving indenter axis as a green vertical line (motion in +x, to the right: the
/// leading edge is on the right, the trailing edge on the left).
pub fn write_snapshot_strip(path: &Path, grid: &Grid, frames: &[(Vec<bool>, Vec<bool>, f64)]) -> Result<()> {
    let n = grid.n();
    let (mut c0, mut c1, mut r0, mut r1) = (usize::MAX, 0, usize::MAX, 0);
    for (contact, previous, _) in frames {
        for (k, (&a, &b)) in contact.iter().zip(previous).enumerate() {
            if a || b {
                let (row, column) = (k / n, k % n);
                c0 = c0.min(column);
                c1 = c1.max(column);
                r0 = r0.min(row);
                r1 = r1.max(row);
            }
        }
    }
    if c0 == usize::MAX {
        (c0, c1, r0, r1) = (0, n - 1, 0, n - 1);
    }
    let margin = 2;
    let (c0, r0) = (c0.saturating_sub(margin), r0.saturating_sub(margin));
    let (c1, r1) = ((c1 + margin).min(n - 1), (r1 + margin).min(n - 1));
    let (w, h) = (c1 - c0 + 1, r1 - r0 + 1);
    let scale = (400 / w.max(h)).clamp(1, 16);
    let gap = 8;
    let count = frames.len().max(1);
    let width = (count * w * scale + (count - 1) * gap) as u32;
    let height = (h * scale) as u32;
    let mut image = image::RgbImage::from_pixel(width, height, image::Rgb([255, 255, 255]));
    let delta = grid.element_size();
    for (i, (contact, previous, offset)) in frames.iter().enumerate() {
        let left = i * (w * scale + gap);
        // Column of the indenter axis: element centres are at (c + 0.5)Δ − L/2.
        let axis_column = ((offset + 0.5 * grid.size()) / delta - 0.5).round() as i64 - c0 as i64;
        for py in 0..h * scale {
            let row = r1 - py / scale;
            for px in 0..w * scale {
                let column = c0 + px / scale;
                let k = row * n + column;
                let colour = match (previous[k], contact[k]) {
                    (true, true) => Some(STAYING),
                    (false, true) => Some(ATTACHED),
                    (true, false) => Some(DETACHED),
                    (false, false) => None,
                };
                let on_axis = (px / scale) as i64 == axis_column && px % scale == scale / 2;
                let pixel = if on_axis { Some(AXIS) } else { colour };
                if let Some(rgb) = pixel {
                    image.put_pixel((left + px) as u32, py as u32, image::Rgb(rgb));
                }
            }
        }
        // Frame border in light grey.
        for px in 0..w * scale {
            for py in [0, h * scale - 1] {
                let p = image.get_pixel_mut((left + px) as u32, py as u32);
                if p.0 == [255, 255, 255] {
                    p.0 = [200, 200, 200];
                }
            }
        }
    }
    image
        .save(path)
        .with_context(|| format!("cannot write {}", path.display()))
}

/// Charts stacked vertically, as a [`Drawing`].
struct Panels<'a>(&'a [Chart]);

impl Drawing for Panels<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        draw_panels(area, self.0)
    }
}
