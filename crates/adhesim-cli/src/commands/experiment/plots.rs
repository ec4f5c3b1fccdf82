//! Time-series figures (SVG and PNG) with plotters.

use anyhow::{anyhow, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// One line of a panel: label, colour, (t, y) points (gaps already removed).
pub struct Series {
    pub label: &'static str,
    pub color: RGBColor,
    pub points: Vec<(f64, f64)>,
}

/// One stacked panel.
pub struct Panel {
    pub y_label: &'static str,
    pub series: Vec<Series>,
}

/// The stacked panels of one figure, drawn by the shared figure module.
struct PanelFigure<'a> {
    title: &'a str,
    panels: &'a [Panel],
}

impl crate::figure::Drawing for PanelFigure<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        draw(area.clone(), self.title, self.panels)
    }
}

/// Writes `<stem>.svg` and `<stem>.png`: panels stacked vertically over a shared time axis.
pub fn write_panels(dir: &Path, stem: &str, title: &str, panels: &[Panel]) -> Result<()> {
    let height = 80 + 260 * panels.len() as u32;
    crate::figure::save_svg_png(dir, stem, (900, height), &PanelFigure { title, panels })?;
    Ok(())
}

fn draw<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, title: &str, panels: &[Panel]) -> Result<()> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("plot: {e:?}");
    root.fill(&WHITE).map_err(err)?;
    let root = root.titled(title, ("sans-serif", 22)).map_err(err)?;
    let areas = root.split_evenly((panels.len().max(1), 1));
    let t_range = range(
        panels
            .iter()
            .flat_map(|p| p.series.iter().flat_map(|s| s.points.iter().map(|q| q.0))),
    );
    for (area, panel) in areas.iter().zip(panels) {
        let y_range = range(panel.series.iter().flat_map(|s| s.points.iter().map(|q| q.1)));
        let mut chart = ChartBuilder::on(area)
            .margin(8)
            .x_label_area_size(36)
            .y_label_area_size(80)
            .build_cartesian_2d(t_range.0..t_range.1, y_range.0..y_range.1)
            .map_err(err)?;
        chart
            .configure_mesh()
            .light_line_style(TRANSPARENT) // fine grid lines add clutter (and PNG size)
            .x_desc("time")
            .y_desc(panel.y_label)
            .label_style(("sans-serif", 14))
            .draw()
            .map_err(err)?;
        for s in &panel.series {
            let color = s.color;
            chart
                .draw_series(LineSeries::new(s.points.iter().copied(), color.stroke_width(2)))
                .map_err(err)?
                .label(s.label)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2)));
        }
        if panel.series.len() > 1 {
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .label_font(("sans-serif", 14))
                .draw()
                .map_err(err)?;
        }
    }
    root.present().map_err(err)?;
    Ok(())
}

/// Finite min/max with padding; a unit range around a constant or empty series.
fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    if hi - lo <= f64::EPSILON * lo.abs().max(1.0) {
        let pad = lo.abs().max(1.0) * 0.05;
        return (lo - pad, hi + pad);
    }
    let pad = 0.05 * (hi - lo);
    (lo - pad, hi + pad)
}
