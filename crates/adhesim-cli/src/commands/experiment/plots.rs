//! Time-series figures (SVG and PNG) with plotters. Units: time in seconds (the frame rate
//! or time stamps), lengths in the unit of `frames.pixel_size`, forces in the force log's
//! unit; the axis labels name them so.

use super::{ratio, FrameRow};
use adhesim_figures::figure::{padded_range, Figure, Mark, Panel, Series, PALETTE};
use anyhow::Result;
use plotters::style::{RGBColor, BLACK};
use std::path::Path;

/// Writes `<stem>.svg` and `<stem>.png`: panels stacked vertically over a shared time axis.
fn write_panels(dir: &Path, stem: &str, title: &str, panels: Vec<Panel>) -> Result<()> {
    let height = 80 + 260 * panels.len() as u32;
    let times = padded_range(
        panels
            .iter()
            .flat_map(|p| p.series.iter().flat_map(|s| s.points.iter().map(|q| q.0))),
    );
    let panels = panels.into_iter().map(|p| p.x_range(times.0, times.1)).collect();
    Figure::stacked(panels).titled(title).save(dir, stem, (900, height))?;
    Ok(())
}

/// A time series of the rows' finite values; `label` empty where it is the panel's only one.
fn series(rows: &[FrameRow], label: &str, colour: RGBColor, value: impl Fn(&FrameRow) -> Option<f64>) -> Series {
    let points = rows.iter().filter_map(|r| value(r).map(|v| (r.time, v))).collect();
    Series::new(label, colour, Mark::Line, points)
}

/// A panel over time.
fn panel(y_label: &str, series: Vec<Series>) -> Panel {
    Panel::new("", "time (s)", y_label).with(series)
}

/// The experiment's figures: areas, sliding (paper Fig. 19) and forces (Fig. 22).
pub(super) fn write_plots(dir: &Path, rows: &[FrameRow]) -> Result<()> {
    let area_panel = || {
        panel(
            "area (length²)",
            vec![
                series(rows, "total", BLACK, |r| Some(r.m.area)),
                series(rows, "front", PALETTE[1], |r| Some(r.m.area_front)),
                series(rows, "rear", PALETTE[0], |r| Some(r.m.area_rear)),
            ],
        )
    };
    write_panels(dir, "areas", "Contact area", vec![area_panel()])?;
    let fx = || panel("F_x (force)", vec![series(rows, "", BLACK, |r| r.force_tangential)]);
    let tau = || {
        let stress = |r: &FrameRow| ratio(r.force_tangential, r.m.area);
        panel("τ = F_x/A (force/length²)", vec![series(rows, "", BLACK, stress)])
    };
    // Paper Fig. 19: F_x, areas (total/front/rear), τ.
    write_panels(
        dir,
        "sliding",
        "Tangential force, contact areas, tangential stress",
        vec![fx(), area_panel(), tau()],
    )?;
    // Paper Fig. 22: F_N, F_x, p, τ.
    let fn_panel = panel("F_N (force)", vec![series(rows, "", BLACK, |r| r.force_normal)]);
    let pressure = |r: &FrameRow| ratio(r.force_normal, r.m.area);
    let p_panel = panel("p = F_N/A (force/length²)", vec![series(rows, "", BLACK, pressure)]);
    write_panels(
        dir,
        "forces",
        "Normal force, tangential force, pressure, tangential stress",
        vec![fn_panel, fx(), p_panel, tau()],
    )?;
    Ok(())
}
