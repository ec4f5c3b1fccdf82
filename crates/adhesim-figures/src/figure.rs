//! The one figure builder of the command line: every chart (a run's force curves, the
//! tangential and study plots, the sweep master curves, the experiment's time series) is a
//! [`Figure`] of [`Panel`]s holding labelled [`Series`], drawn with one bundled font, one
//! palette and one set of sizes, and written as `NAME.svg` and `NAME.png` by
//! [`save_svg_png`].
//!
//! A panel's axes cover its series with a 5 % margin (or given ranges, linear or
//! logarithmic); a horizontal line marks y = 0 where the range crosses it; the legend lists
//! the labelled series.

use crate::log_ticks::{log_axis, tick_label};
use anyhow::{anyhow, Result};
use plotters::chart::SeriesAnno;
use plotters::coord::ranged1d::{Ranged, ValueFormatter};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::FontStyle;
use std::path::Path;
use std::sync::OnceLock;

mod axes;
pub mod files;
mod legend;

const FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");
/// The family name the bundled font is registered under.
const FAMILY: &str = "sans-serif";

/// Colours of the series, in order.
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(140, 86, 75),
    RGBColor(23, 190, 207),
    RGBColor(127, 127, 127),
];

/// Closed-form reference curves (Hertz, JKR) under the data.
pub const REFERENCE_GREY: RGBColor = RGBColor(120, 120, 120);
/// Guide lines of a study (slope 1, the paper's values), darker than the references.
pub const INK: RGBColor = RGBColor(60, 60, 60);

/// The colour of the `k`-th series where series 0 is a neutral grey (the reference case
/// of the master-curve figures) and the others follow [`PALETTE`].
pub fn grey_first(k: usize) -> RGBColor {
    PALETTE[(k + PALETTE.len() - 1) % PALETTE.len()]
}

/// Registers the bundled font as "sans-serif" (there are no system fonts to rely on).
pub fn register_font() -> Result<()> {
    static DONE: OnceLock<bool> = OnceLock::new();
    let ok = *DONE.get_or_init(|| plotters::style::register_font(FAMILY, FontStyle::Normal, FONT).is_ok());
    if ok {
        Ok(())
    } else {
        Err(anyhow!("the bundled font could not be loaded"))
    }
}

/// A plotters drawing error as an error of this crate.
pub fn plot_error(error: impl std::fmt::Display) -> anyhow::Error {
    anyhow!("plot: {error}")
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mark {
    /// A 2-pixel line (closed forms).
    Line,
    /// A dashed 2-pixel line (references, means, fitted curves).
    Dashed,
    /// Dots only.
    Points,
    /// Dots joined by a 2-pixel line (a few points per series: study results).
    LinePoints,
    /// Small dots joined by a thin line (many points: the steps of a run).
    Trace,
    /// Crosses (events such as jumps).
    Crosses,
    /// Outline marker number `k` (square, triangle, octagon, diamond, inverted triangle):
    /// series told apart in black-and-white print.
    Marker(usize),
}

/// One labelled series of a panel; an empty label gives no legend row.
#[derive(Clone)]
pub struct Series {
    pub label: String,
    pub colour: RGBColor,
    pub mark: Mark,
    pub points: Vec<(f64, f64)>,
    /// Left out of the panel's range and drawn only inside it (fits that run far off).
    pub clipped: bool,
}

impl Series {
    /// A series of the finite points of `points`.
    pub fn new(label: impl Into<String>, colour: RGBColor, mark: Mark, points: Vec<(f64, f64)>) -> Self {
        Self {
            label: label.into(),
            colour,
            mark,
            points: points
                .into_iter()
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .collect(),
            clipped: false,
        }
    }

    /// The same series, left out of the panel's range and drawn only inside it.
    pub fn clipped(self) -> Self {
        Self { clipped: true, ..self }
    }
}

/// One chart: title, axis labels, series and how its axes are chosen.
#[derive(Clone)]
pub struct Panel {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
    log_x: bool,
    log_y: bool,
    x_range: Option<(f64, f64)>,
    y_range: Option<(f64, f64)>,
    scientific_ticks: bool,
    include_y: Vec<f64>,
    guides_y: Vec<f64>,
    /// Where the legend goes; None: the corner that covers the fewest data (`legend::position`).
    legend: Option<SeriesLabelPosition>,
}

impl Panel {
    /// An empty panel; an empty title draws none.
    pub fn new(title: impl Into<String>, x_label: impl Into<String>, y_label: impl Into<String>) -> Self {
        Self {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            series: Vec::new(),
            log_x: false,
            log_y: false,
            x_range: None,
            y_range: None,
            scientific_ticks: false,
            include_y: Vec::new(),
            guides_y: Vec::new(),
            legend: None,
        }
    }

    /// Adds the series.
    pub fn with(mut self, series: impl IntoIterator<Item = Series>) -> Self {
        self.series.extend(series);
        self
    }

    /// A logarithmic x axis (give its range with [`Panel::x_range`]).
    pub fn log_x(mut self) -> Self {
        self.log_x = true;
        self
    }

    /// This x range, as it is (no margin), instead of the series' one.
    pub fn x_range(mut self, low: f64, high: f64) -> Self {
        self.x_range = Some((low, high));
        self
    }

    /// This y range, as it is (no margin, no [`Panel::include_y`]), instead of the series' one.
    pub fn y_range(mut self, low: f64, high: f64) -> Self {
        self.y_range = Some((low, high));
        self
    }

    /// A logarithmic y axis over this range, as it is (no margin, no [`Panel::include_y`]).
    pub fn log_y(self, low: f64, high: f64) -> Self {
        Self {
            log_y: true,
            y_range: Some((low, high)),
            ..self
        }
    }

    /// Tick labels as `1.0e-3` and about 6 x ticks (log axes over many decades).
    pub fn scientific_ticks(mut self) -> Self {
        self.scientific_ticks = true;
        self
    }

    /// Stretches the y range to contain `y` (before the margin).
    pub fn include_y(mut self, y: f64) -> Self {
        self.include_y.push(y);
        self
    }

    /// A faint horizontal guide line at `y` across the panel.
    pub fn guide_y(mut self, y: f64) -> Self {
        self.guides_y.push(y);
        self
    }

    /// Where the legend goes [default: the corner that covers the fewest data].
    pub fn legend_at(mut self, position: SeriesLabelPosition) -> Self {
        self.legend = Some(position);
        self
    }

    /// The axis ranges, made drawable by [`axes`] (clamped where absurd).
    fn ranges(&self) -> ((f64, f64), (f64, f64)) {
        let ranged = || self.series.iter().filter(|s| !s.clipped).flat_map(|s| s.points.iter());
        let x = self.x_range.unwrap_or_else(|| padded_range(ranged().map(|p| p.0)));
        let y = self
            .y_range
            .unwrap_or_else(|| padded_range(ranged().map(|p| p.1).chain(self.include_y.iter().copied())));
        let drawable = |(low, high): (f64, f64), log: bool| {
            if log {
                axes::log_range(low, high)
            } else {
                axes::linear_range(low, high)
            }
        };
        (drawable(x, self.log_x), drawable(y, self.log_y))
    }
}

/// The finite hull of `values` with a 5 % margin each side; a 5 % margin around a constant
/// and (0, 1) where there is nothing to show.
pub fn padded_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (low, high) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if !low.is_finite() {
        return (0.0, 1.0);
    }
    let span = if high > low {
        high - low
    } else if low != 0.0 {
        low.abs()
    } else {
        1.0
    };
    (low - 0.05 * span, high + 0.05 * span)
}

/// Panels on a grid of `columns` columns (filled row by row), under an optional title.
pub struct Figure {
    title: Option<String>,
    panels: Vec<Panel>,
    columns: usize,
}

impl Figure {
    /// The panels stacked vertically.
    pub fn stacked(panels: Vec<Panel>) -> Self {
        Self {
            title: None,
            panels,
            columns: 1,
        }
    }

    /// The panels side by side.
    pub fn side_by_side(panels: Vec<Panel>) -> Self {
        let columns = panels.len().max(1);
        Self {
            title: None,
            panels,
            columns,
        }
    }

    /// A title over all the panels.
    pub fn titled(self, title: impl Into<String>) -> Self {
        Self {
            title: Some(title.into()),
            ..self
        }
    }

    /// Writes `dir/NAME.svg` and `dir/NAME.png` of `size` pixels; see [`save_svg_png`].
    pub fn save(&self, dir: &Path, name: &str, size: (u32, u32)) -> Result<[String; 2]> {
        save_svg_png(dir, name, size, self)
    }
}

impl Drawing for Figure {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        area.fill(&WHITE).map_err(plot_error)?;
        let inner = match &self.title {
            Some(title) => area.titled(title, (FAMILY, 22)).map_err(plot_error)?,
            None => area.clone(),
        };
        let rows = self.panels.len().div_ceil(self.columns).max(1);
        for (cell, panel) in inner.split_evenly((rows, self.columns)).iter().zip(&self.panels) {
            draw_panel(cell, panel)?;
        }
        area.present().map_err(plot_error)?;
        Ok(())
    }
}

fn draw_panel<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, panel: &Panel) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let ((x0, x1), (y0, y1)) = panel.ranges();
    let mut builder = ChartBuilder::on(area);
    builder.margin(12).x_label_area_size(44).y_label_area_size(70);
    if !panel.title.is_empty() {
        builder.caption(&panel.title, (FAMILY, 20));
    }
    let ranges = ((x0, x1), (y0, y1));
    match (panel.log_x, panel.log_y) {
        (false, false) => {
            let chart = builder.build_cartesian_2d(x0..x1, y0..y1).map_err(plot_error)?;
            draw_contents(chart, panel, ranges)
        }
        (true, false) => {
            let chart = builder
                .build_cartesian_2d(log_axis(x0, x1), y0..y1)
                .map_err(plot_error)?;
            draw_contents(chart, panel, ranges)
        }
        (false, true) => {
            let chart = builder
                .build_cartesian_2d(x0..x1, log_axis(y0, y1))
                .map_err(plot_error)?;
            draw_contents(chart, panel, ranges)
        }
        (true, true) => {
            let chart = builder
                .build_cartesian_2d(log_axis(x0, x1), log_axis(y0, y1))
                .map_err(plot_error)?;
            draw_contents(chart, panel, ranges)
        }
    }
}

/// Mesh, guide lines, series and legend of a panel whose axes are built (linear or log).
fn draw_contents<'a, DB, X, Y>(
    mut chart: ChartContext<'a, DB, Cartesian2d<X, Y>>,
    panel: &Panel,
    ((x0, x1), (y0, y1)): ((f64, f64), (f64, f64)),
) -> Result<()>
where
    DB: DrawingBackend + 'a,
    DB::ErrorType: 'static,
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let mut mesh = chart.configure_mesh();
    mesh.x_desc(&panel.x_label)
        .y_desc(&panel.y_label)
        .label_style((FAMILY, 14))
        .axis_desc_style((FAMILY, 16))
        .light_line_style(RGBColor(235, 235, 235));
    let label_x = |v: &f64| tick_label::<X>(*v, (x0, x1), panel.log_x, panel.scientific_ticks);
    let label_y = |v: &f64| tick_label::<Y>(*v, (y0, y1), panel.log_y, panel.scientific_ticks);
    if panel.scientific_ticks && !panel.log_x {
        mesh.x_labels(6);
    }
    mesh.x_label_formatter(&label_x).y_label_formatter(&label_y);
    mesh.draw().map_err(plot_error)?;
    let zero = (y0 < 0.0 && y1 > 0.0).then_some((0.0, 0.4));
    for (y, opacity) in zero.into_iter().chain(panel.guides_y.iter().map(|&y| (y, 0.25))) {
        chart
            .draw_series(LineSeries::new([(x0, y), (x1, y)], BLACK.mix(opacity)))
            .map_err(plot_error)?;
    }
    let inside = |&(x, y): &(f64, f64)| x >= x0 && x <= x1 && y >= y0 && y <= y1;
    for series in panel.series.iter().filter(|s| !s.points.is_empty()) {
        let points: Vec<(f64, f64)> = if series.clipped {
            series.points.iter().copied().filter(inside).collect()
        } else {
            series.points.clone()
        };
        let drawn = draw_marks(&mut chart, series.mark, series.colour, &points)?;
        if !series.label.is_empty() {
            add_legend(drawn, &series.label, series.mark, series.colour);
        }
    }
    if let Some(position) = legend::position(panel, (x0, x1), (y0, y1)) {
        chart
            .configure_series_labels()
            .position(position)
            .label_font((FAMILY, 13))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.3))
            .draw()
            .map_err(plot_error)?;
    }
    Ok(())
}

/// Draws the points with their mark; returns the annotation of the part the legend shows.
fn draw_marks<'c, 'a: 'c, DB, X, Y>(
    chart: &'c mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    mark: Mark,
    colour: RGBColor,
    points: &[(f64, f64)],
) -> Result<&'c mut SeriesAnno<'a, DB>>
where
    DB: DrawingBackend + 'a,
    DB::ErrorType: 'static,
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let line = |width: u32| LineSeries::new(points.iter().copied(), colour.stroke_width(width));
    let dots = |radius: u32| points.iter().map(move |&p| Circle::new(p, radius, colour.filled()));
    let drawn = match mark {
        Mark::Line => chart.draw_series(line(2)),
        Mark::Dashed => chart.draw_series(DashedLineSeries::new(
            points.iter().copied(),
            6,
            4,
            colour.stroke_width(2),
        )),
        Mark::Points => chart.draw_series(dots(3)),
        Mark::LinePoints => {
            chart.draw_series(line(2)).map_err(plot_error)?;
            chart.draw_series(dots(3))
        }
        Mark::Trace => {
            chart.draw_series(line(1)).map_err(plot_error)?;
            chart.draw_series(dots(2))
        }
        Mark::Crosses => chart.draw_series(points.iter().map(|&p| Cross::new(p, 4, colour.stroke_width(1)))),
        Mark::Marker(k) => {
            let shape = marker_shape(k);
            chart.draw_series(
                points
                    .iter()
                    .map(|&p| EmptyElement::at(p) + PathElement::new(shape.clone(), colour.stroke_width(2))),
            )
        }
    };
    drawn.map_err(plot_error)
}

/// Gives the series its legend row: a sample of its mark, centred 9 pixels right of the
/// row's anchor.
fn add_legend<'a, DB: DrawingBackend + 'a>(anno: &mut SeriesAnno<'a, DB>, label: &str, mark: Mark, colour: RGBColor) {
    anno.label(label);
    let style = colour.stroke_width(2);
    match mark {
        Mark::Line | Mark::Dashed => anno.legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], style)),
        Mark::Points | Mark::LinePoints | Mark::Trace => {
            anno.legend(move |(x, y)| Circle::new((x + 9, y), 3, colour.filled()))
        }
        Mark::Crosses => anno.legend(move |(x, y)| Cross::new((x + 9, y), 4, colour.stroke_width(1))),
        Mark::Marker(k) => {
            anno.legend(move |(x, y)| EmptyElement::at((x + 9, y)) + PathElement::new(marker_shape(k), style))
        }
    };
}

/// Outline (pixel offsets) of marker `k`: square, triangle, octagon, diamond, inverted
/// triangle, then again.
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

/// A figure that can draw itself on any plotters backend.
pub trait Drawing {
    /// Draws the whole figure on `area`.
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static;
}

/// Writes `dir/NAME.svg` and `dir/NAME.png` of `size` pixels (`dir` exists); returns the
/// two file names. Both are drawn in memory and written by [`files::write_file`] (checked
/// through the last byte, renamed into place).
pub fn save_svg_png(dir: &Path, name: &str, size: (u32, u32), drawing: &impl Drawing) -> Result<[String; 2]> {
    register_font()?;
    let svg = format!("{name}.svg");
    let mut text = String::new();
    drawing.draw(&SVGBackend::with_string(&mut text, size).into_drawing_area())?;
    files::write_file(&dir.join(&svg), text.as_bytes())?;
    let png = format!("{name}.png");
    let mut pixels = vec![0u8; size.0 as usize * size.1 as usize * 3];
    drawing.draw(&BitMapBackend::with_buffer(&mut pixels, size).into_drawing_area())?;
    files::save_figure_png(pixels, size, &dir.join(&png))?;
    Ok([svg, png])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_cover_the_series_with_margins_and_leave_clipped_ones_out() {
        let far_fit = Series::new("fit", PALETTE[1], Mark::Dashed, vec![(0.0, 0.0), (100.0, 1e6)]).clipped();
        let data = Series::new(
            "data",
            PALETTE[0],
            Mark::Trace,
            vec![(1.0, -2.0), (3.0, 2.0), (f64::NAN, 9.0)],
        );
        let panel = Panel::new("", "x", "y").with([data, far_fit]).include_y(4.0);
        // x over [1, 3], y over [-2, 4] (include_y), each widened by 5 % of its span; the
        // non-finite point is dropped and the clipped fit does not stretch the axes.
        let ((x0, x1), (y0, y1)) = panel.ranges();
        let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
        assert!(close(x0, 0.9) && close(x1, 3.1), "{x0} {x1}");
        assert!(close(y0, -2.3) && close(y1, 4.3), "{y0} {y1}");
        let given = Panel::new("", "α", "y").log_x().x_range(0.1, 10.0).ranges().0;
        assert_eq!(given, (0.1, 10.0));
        // A log y range is taken as it is: include_y does not stretch it.
        let log_y = Panel::new("", "q", "C").include_y(1e6).log_y(1e-3, 1e2).ranges().1;
        assert_eq!(log_y, (1e-3, 1e2));
    }

    #[test]
    fn a_log_log_panel_draws_scientific_ticks() {
        let dir = tempfile::tempdir().unwrap();
        let power_law = (0..8).map(|k| 10f64.powi(k - 4)).map(|q| (q, q.powi(-2))).collect();
        let panel = Panel::new("psd", "q", "C")
            .with([Series::new("C", PALETTE[0], Mark::LinePoints, power_law)])
            .log_x()
            .x_range(1e-5, 1e4)
            .log_y(1e-9, 1e9)
            .scientific_ticks();
        Figure::stacked(vec![panel]).save(dir.path(), "p", (500, 400)).unwrap();
        let svg = std::fs::read_to_string(dir.path().join("p.svg")).unwrap();
        // Decade ticks over 18 decades read as 1eN, the y axis every third decade; a plain
        // formatter would write 0.000001.
        let label = |t: &str| svg.contains(&format!(">{t}<")) || svg.lines().any(|l| l.trim() == t);
        for tick in ["1e0", "1e-3", "1e3", "1e-9", "1e9"] {
            assert!(label(tick), "{tick} missing: {svg}");
        }
        assert!(!svg.contains("0.000001") && !svg.contains(">0.001<"), "{svg}");
    }

    #[test]
    fn degenerate_ranges_stay_drawable() {
        assert_eq!(padded_range(std::iter::empty()), (0.0, 1.0));
        assert_eq!(padded_range([f64::NAN, f64::INFINITY].into_iter()), (0.0, 1.0));
        assert_eq!(padded_range([0.0, 0.0].into_iter()), (-0.05, 0.05));
        let (low, high) = padded_range([2e-9].into_iter());
        assert!(low < 2e-9 && high > 2e-9 && high - low < 1e-9, "{low} {high}");
    }

    #[test]
    fn a_figure_writes_svg_and_png() {
        let dir = tempfile::tempdir().unwrap();
        let panel = Panel::new("t", "x", "y")
            .with([Series::new(
                "a",
                PALETTE[0],
                Mark::Marker(2),
                vec![(1.0, 1.0), (2.0, 3.0)],
            )])
            .guide_y(1.0);
        let files = Figure::side_by_side(vec![panel.clone(), panel.log_x().x_range(0.5, 4.0)])
            .titled("two")
            .save(dir.path(), "f", (600, 300))
            .unwrap();
        assert_eq!(files, ["f.svg".to_string(), "f.png".to_string()]);
        let svg = std::fs::read_to_string(dir.path().join("f.svg")).unwrap();
        // The title once and each panel's legend row of "a".
        let texts = |t: &str| svg.lines().filter(|line| line.trim() == t).count();
        assert!(texts("two") == 1 && texts("a") == 2, "{svg}");
        assert!(image::open(dir.path().join("f.png")).is_ok());
    }
}
