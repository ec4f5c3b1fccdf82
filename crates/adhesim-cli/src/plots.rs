//! Figures of a run (SVG and PNG): force vs depth and force vs contact radius, approach
//! and retraction in different colours, jumps marked, with the Hertz (γ0 = 0) or JKR
//! (γ0 > 0, normalised axes) closed form over the points (the paper's Fig. 1 a/b).

use crate::figure::{save_svg_png, Drawing};
use adhesim::analysis::reference::{Hertz, Jkr};
use adhesim::{Phase, StepRecord};
use anyhow::{anyhow, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

const APPROACH: RGBColor = RGBColor(31, 119, 180);
const RETRACT: RGBColor = RGBColor(214, 39, 40);
const REFERENCE: RGBColor = RGBColor(120, 120, 120);

/// (x, y) points of a series.
type Points = Vec<(f64, f64)>;

/// One figure: points by phase, jump markers and an optional closed-form curve.
pub struct Figure {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub approach: Vec<(f64, f64)>,
    pub retract: Vec<(f64, f64)>,
    pub jumps: Vec<(f64, f64)>,
    pub reference: Option<(String, Vec<(f64, f64)>)>,
}

/// Scales for the run's plots: the closed forms and the normalisation.
pub struct PlotContext {
    pub jkr: Option<Jkr>,
    pub hertz: Option<Hertz>,
    pub max_depth: f64,
}

fn split(records: &[StepRecord], point: impl Fn(&StepRecord) -> (f64, f64)) -> (Points, Points, Points) {
    let mut approach = Vec::new();
    let mut retract = Vec::new();
    let mut jumps = Vec::new();
    for r in records {
        let p = point(r);
        if !(p.0.is_finite() && p.1.is_finite()) {
            continue;
        }
        match r.phase {
            Some(Phase::Retract) => retract.push(p),
            _ => approach.push(p),
        }
        if r.jumped {
            jumps.push(p);
        }
    }
    (approach, retract, jumps)
}

/// Builds the force–depth and force–radius figures.
pub fn figures(records: &[StepRecord], context: &PlotContext) -> Vec<(&'static str, Figure)> {
    let mut out = Vec::new();
    let max_radius = records.iter().map(|r| r.radius).fold(0.0, f64::max);
    if let Some(jkr) = context.jkr {
        let (f, d, a) = (
            jkr.critical_force().abs(),
            jkr.critical_depth().abs(),
            jkr.critical_radius(),
        );
        let a_deepest = jkr.radius_at_depth(context.max_depth).unwrap_or(3.0 * a);
        let a_top = a_deepest.max(max_radius) * 1.05;
        // Displacement control: the JKR branch from the instability a = 9^(-1/3) a_JKR up
        // to the deepest indentation.
        let a_low = a / 9f64.cbrt();
        let depth_curve: Vec<(f64, f64)> = (0..=400)
            .map(|i| a_low + (a_deepest - a_low) * i as f64 / 400.0)
            .map(|x| (jkr.depth(x) / d, jkr.force(x) / f))
            .collect();
        let radius_curve: Vec<(f64, f64)> = (0..=400)
            .map(|i| a_top * i as f64 / 400.0)
            .map(|x| (x / a, jkr.force(x) / f))
            .collect();
        let (approach, retract, jumps) = split(records, |r| (r.depth / d, r.force_normal / f));
        out.push((
            "force_depth",
            Figure {
                title: "Force vs indentation depth".into(),
                x_label: "d / |d_JKR|".into(),
                y_label: "F / |F_JKR|".into(),
                approach,
                retract,
                jumps,
                reference: Some(("JKR (γ0)".into(), depth_curve)),
            },
        ));
        let (approach, retract, jumps) = split(records, |r| (r.radius / a, r.force_normal / f));
        out.push((
            "force_radius",
            Figure {
                title: "Force vs contact radius".into(),
                x_label: "a / a_JKR".into(),
                y_label: "F / |F_JKR|".into(),
                approach,
                retract,
                jumps,
                reference: Some(("JKR (γ0)".into(), radius_curve)),
            },
        ));
    } else {
        let max_depth = context.max_depth.max(0.0);
        let depth_reference = context.hertz.map(|h| {
            let curve = (0..=200)
                .map(|i| max_depth * i as f64 / 200.0)
                .map(|x| (x, h.force(x)))
                .collect();
            ("Hertz".to_string(), curve)
        });
        let radius_reference = context.hertz.map(|h| {
            let top = h.contact_radius(max_depth).max(max_radius) * 1.05;
            let curve = (0..=200)
                .map(|i| top * i as f64 / 200.0)
                .map(|x| (x, 4.0 * h.contact_modulus * x.powi(3) / (3.0 * h.radius)))
                .collect();
            ("Hertz".to_string(), curve)
        });
        let (approach, retract, jumps) = split(records, |r| (r.depth, r.force_normal));
        out.push((
            "force_depth",
            Figure {
                title: "Force vs indentation depth".into(),
                x_label: "d".into(),
                y_label: "F".into(),
                approach,
                retract,
                jumps,
                reference: depth_reference,
            },
        ));
        let (approach, retract, jumps) = split(records, |r| (r.radius, r.force_normal));
        out.push((
            "force_radius",
            Figure {
                title: "Force vs contact radius".into(),
                x_label: "contact radius a".into(),
                y_label: "F".into(),
                approach,
                retract,
                jumps,
                reference: radius_reference,
            },
        ));
    }
    out
}

fn range(figure: &Figure) -> ((f64, f64), (f64, f64)) {
    let all = figure
        .approach
        .iter()
        .chain(&figure.retract)
        .chain(figure.reference.iter().flat_map(|(_, c)| c.iter()))
        .filter(|p| p.0.is_finite() && p.1.is_finite());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for &(x, y) in all {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    let pad = |lo: f64, hi: f64| {
        if !(lo.is_finite() && hi.is_finite()) {
            return (0.0, 1.0);
        }
        let span = if hi > lo { hi - lo } else { lo.abs().max(1.0) };
        (lo - 0.05 * span, hi + 0.05 * span)
    };
    (pad(x0, x1), pad(y0, y1))
}

/// Dashed curves drawn over a figure (fitted JKR curves), with their legend labels.
pub type Overlays = [(String, Vec<(f64, f64)>)];

/// The overlays of the figure with this name.
pub type FigureOverlays<'a> = (&'a str, Vec<(String, Vec<(f64, f64)>)>);

const OVERLAY_COLOURS: [RGBColor; 2] = [RGBColor(23, 120, 200), RGBColor(200, 30, 30)];

/// The fitted JKR curves F(a) for γ1 and γ2 in the force–radius plot's units (normalised
/// by a_JKR and |F_JKR|), over contact radii up to the largest one seen.
pub fn fitted_jkr_overlays(
    jkr: &Jkr,
    records: &[StepRecord],
    gamma_approach: Option<f64>,
    gamma_pulloff: Option<f64>,
) -> Vec<(String, Vec<(f64, f64)>)> {
    let (f, a) = (jkr.critical_force().abs(), jkr.critical_radius());
    let top = records.iter().map(|r| r.radius).fold(0.0, f64::max) * 1.05;
    let mut out = Vec::new();
    for (name, gamma) in [("γ1", gamma_approach), ("γ2", gamma_pulloff)] {
        let Some(gamma) = gamma else { continue };
        let fitted = Jkr {
            work_of_adhesion: gamma,
            ..*jkr
        };
        let curve = (0..=300)
            .map(|i| top * i as f64 / 300.0)
            .map(|x| (x / a, fitted.force(x) / f))
            .collect();
        out.push((
            format!("JKR fit {name}/γ0 = {:.3}", gamma / jkr.work_of_adhesion),
            curve,
        ));
    }
    out
}

fn draw_with_overlays<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    figure: &Figure,
    overlays: &Overlays,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("plot: {e}");
    root.fill(&WHITE).map_err(e)?;
    let ((x0, x1), (y0, y1)) = range(figure);
    let mut chart = ChartBuilder::on(root)
        .caption(&figure.title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc(&figure.x_label)
        .y_desc(&figure.y_label)
        .label_style(("sans-serif", 14))
        .axis_desc_style(("sans-serif", 16))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(e)?;
    if y0 < 0.0 && y1 > 0.0 {
        chart
            .draw_series(LineSeries::new([(x0, 0.0), (x1, 0.0)], BLACK.mix(0.4)))
            .map_err(e)?;
    }
    if let Some((label, curve)) = &figure.reference {
        chart
            .draw_series(LineSeries::new(curve.iter().copied(), REFERENCE.stroke_width(2)))
            .map_err(e)?
            .label(label.as_str())
            .legend(|(x, y)| PathElement::new([(x, y), (x + 18, y)], REFERENCE.stroke_width(2)));
    }
    for (points, colour, label) in [
        (&figure.approach, APPROACH, "approach"),
        (&figure.retract, RETRACT, "retract"),
    ] {
        if points.is_empty() {
            continue;
        }
        chart
            .draw_series(LineSeries::new(points.iter().copied(), colour.stroke_width(1)))
            .map_err(e)?;
        chart
            .draw_series(points.iter().map(|&p| Circle::new(p, 2, colour.filled())))
            .map_err(e)?
            .label(label)
            .legend(move |(x, y)| Circle::new((x + 9, y), 3, colour.filled()));
    }
    for (k, (label, curve)) in overlays.iter().enumerate() {
        let colour = OVERLAY_COLOURS[k % OVERLAY_COLOURS.len()];
        // Only the part inside the figure's range: fits can run far off at large radii.
        let inside = curve
            .iter()
            .copied()
            .filter(|&(x, y)| x >= x0 && x <= x1 && y >= y0 && y <= y1);
        chart
            .draw_series(DashedLineSeries::new(inside, 8, 5, colour.stroke_width(2)))
            .map_err(e)?
            .label(label.as_str())
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], colour.stroke_width(2)));
    }
    if !figure.jumps.is_empty() {
        chart
            .draw_series(figure.jumps.iter().map(|&p| Cross::new(p, 4, BLACK.stroke_width(1))))
            .map_err(e)?
            .label("jump")
            .legend(|(x, y)| Cross::new((x + 9, y), 4, BLACK.stroke_width(1)));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .label_font(("sans-serif", 14))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.3))
        .draw()
        .map_err(e)?;
    root.present().map_err(e)?;
    Ok(())
}

/// Writes `NAME.svg` and `NAME.png` for every figure into `dir`, with dashed overlay
/// curves on the figures named in `overlays`; returns the file names.
pub fn write_all_with_overlays(
    dir: &Path,
    figures: &[(&'static str, Figure)],
    overlays: &[FigureOverlays<'_>],
) -> Result<Vec<String>> {
    std::fs::create_dir_all(dir)?;
    let mut written = Vec::new();
    for (name, figure) in figures {
        let extra: &Overlays = overlays
            .iter()
            .find(|(target, _)| target == name)
            .map(|(_, curves)| curves.as_slice())
            .unwrap_or(&[]);
        let files = save_svg_png(dir, name, (800, 600), &WithOverlays(figure, extra))?;
        written.extend(files.map(|file| format!("plots/{file}")));
    }
    Ok(written)
}

/// A figure with its overlay curves, as a [`Drawing`].
struct WithOverlays<'a>(&'a Figure, &'a Overlays);

impl Drawing for WithOverlays<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        draw_with_overlays(area, self.0, self.1)
    }
}
