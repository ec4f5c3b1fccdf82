//! Time-series figures (SVG and PNG) with plotters.

use super::{ratio, FrameRow};
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

const RED: RGBColor = RGBColor(214, 39, 40);
const BLUE: RGBColor = RGBColor(31, 119, 180);
const BLACK: RGBColor = RGBColor(0, 0, 0);

fn series(rows: &[FrameRow], label: &'static str, color: RGBColor, value: impl Fn(&FrameRow) -> Option<f64>) -> Series {
    Series {
        label,
        color,
        points: rows
            .iter()
            .filter_map(|r| value(r).filter(|v| v.is_finite()).map(|v| (r.time, v)))
            .collect(),
    }
}

/// The experiment's figures: areas, sliding (paper Fig. 19) and forces (Fig. 22).
pub(super) fn write_plots(dir: &Path, rows: &[FrameRow]) -> Result<()> {
    let area_panel = || Panel {
        y_label: "area",
        series: vec![
            series(rows, "total", BLACK, |r| Some(r.m.area)),
            series(rows, "front", RED, |r| Some(r.m.area_front)),
            series(rows, "rear", BLUE, |r| Some(r.m.area_rear)),
        ],
    };
    write_panels(dir, "areas", "Contact area", &[area_panel()])?;
    let fx = || Panel {
        y_label: "F_x",
        series: vec![series(rows, "F_x", BLACK, |r| r.force_tangential)],
    };
    let tau = || Panel {
        y_label: "tau = F_x/A",
        series: vec![series(rows, "tau", BLACK, |r| ratio(r.force_tangential, r.m.area))],
    };
    // Paper Fig. 19: F_x, areas (total/front/rear), τ.
    write_panels(
        dir,
        "sliding",
        "Tangential force, contact areas, tangential stress",
        &[fx(), area_panel(), tau()],
    )?;
    // Paper Fig. 22: F_N, F_x, p, τ.
    let fn_panel = Panel {
        y_label: "F_N",
        series: vec![series(rows, "F_N", BLACK, |r| r.force_normal)],
    };
    let p_panel = Panel {
        y_label: "p = F_N/A",
        series: vec![series(rows, "p", BLACK, |r| ratio(r.force_normal, r.m.area))],
    };
    write_panels(
        dir,
        "forces",
        "Normal force, tangential force, pressure, tangential stress",
        &[fn_panel, fx(), p_panel, tau()],
    )?;
    Ok(())
}
