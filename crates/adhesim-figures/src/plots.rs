//! Figures of a run (SVG and PNG): force vs depth and force vs contact radius, approach
//! and retraction in different colours, jumps marked, with the Hertz (γ0 = 0) or JKR
//! (γ0 > 0, normalised axes) closed form over the points (the paper's Fig. 1 a/b).

use crate::figure::{Figure, Mark, Panel, Series, PALETTE, REFERENCE_GREY};
use adhesim::analysis::reference::{Hertz, Jkr};
use adhesim::{Phase, StepRecord};
use anyhow::Result;
use plotters::style::RGBColor;
use std::path::Path;

/// (x, y) points of a series.
type Points = Vec<(f64, f64)>;

/// Scales for the run's plots: the closed forms and the normalisation.
pub struct PlotContext {
    pub jkr: Option<Jkr>,
    pub hertz: Option<Hertz>,
    pub max_depth: f64,
}

/// A panel of the run's points by phase (approach, retract), with the closed-form
/// `reference` under them and the jumps marked on top.
fn phase_panel(
    (title, x_label, y_label): (&str, &str, &str),
    records: &[StepRecord],
    point: impl Fn(&StepRecord) -> (f64, f64),
    reference: Option<(String, Points)>,
) -> Panel {
    let mut approach = Vec::new();
    let mut retract = Vec::new();
    let mut jumps = Vec::new();
    for r in records {
        let p = point(r);
        match r.phase {
            Some(Phase::Retract) => retract.push(p),
            _ => approach.push(p),
        }
        if r.jumped {
            jumps.push(p);
        }
    }
    // The jumps go under the data (light crosses), so that they mark without hiding.
    Panel::new(title, x_label, y_label)
        .with(reference.map(|(label, curve)| Series::new(label, REFERENCE_GREY, Mark::Line, curve)))
        .with([
            Series::new("jump", JUMP_GREY, Mark::Crosses, jumps),
            Series::new("approach", PALETTE[0], Mark::Trace, approach),
            Series::new("retract", PALETTE[1], Mark::Trace, retract),
        ])
}

/// Jump crosses: light enough that the steps drawn over them stay readable.
const JUMP_GREY: RGBColor = RGBColor(175, 175, 175);

/// The adhesive region of a normalised force–radius panel (F/|F_JKR| vs a/a_JKR): from
/// a = 0 to where the force has risen back to |F_min| (F_min the most tensile force, at
/// least |F_JKR|), the force from 1.25·F_min to |F_min|. `None` without tension.
fn adhesive_zoom(panel: &Panel) -> Option<Panel> {
    let data = || {
        panel
            .series
            .iter()
            .filter(|s| s.mark == Mark::Trace)
            .flat_map(|s| s.points.iter().copied())
    };
    let most_tensile = data().map(|p| p.1).fold(0.0, f64::min);
    if most_tensile >= 0.0 {
        return None;
    }
    let top = most_tensile.abs().max(1.0);
    let right = data().filter(|p| p.1 <= top).map(|p| p.0).fold(0.0, f64::max) * 1.1;
    let mut zoom = panel.clone().x_range(0.0, right.max(1.0)).y_range(1.25 * -top, top);
    zoom.title = "Adhesive region".to_string();
    zoom.series.iter_mut().for_each(|s| s.clipped = true);
    Some(zoom)
}

/// The unit and label of an axis and the closed-form curve in those units.
type Axis = (f64, &'static str, Option<(String, Points)>);

/// Builds the force–depth and force–radius figures.
pub fn figures(records: &[StepRecord], context: &PlotContext) -> Vec<(&'static str, Panel)> {
    let max_radius = records.iter().map(|r| r.radius).fold(0.0, f64::max);
    let (force_unit, force_label, depth_axis, radius_axis): (f64, &str, Axis, Axis) = if let Some(jkr) = context.jkr {
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
        let depth_curve: Points = (0..=400)
            .map(|i| a_low + (a_deepest - a_low) * i as f64 / 400.0)
            .map(|x| (jkr.depth(x) / d, jkr.force(x) / f))
            .collect();
        let radius_curve: Points = (0..=400)
            .map(|i| a_top * i as f64 / 400.0)
            .map(|x| (x / a, jkr.force(x) / f))
            .collect();
        let jkr_curve = |curve| Some(("JKR (γ0)".to_string(), curve));
        (
            f,
            "F / |F_JKR|",
            (d, "d / |d_JKR|", jkr_curve(depth_curve)),
            (a, "a / a_JKR", jkr_curve(radius_curve)),
        )
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
        (
            1.0,
            "F",
            (1.0, "d", depth_reference),
            (1.0, "contact radius a", radius_reference),
        )
    };
    let depth_of: fn(&StepRecord) -> f64 = |r| r.depth;
    let radius_of: fn(&StepRecord) -> f64 = |r| r.radius;
    [
        ("force_depth", "Force vs indentation depth", depth_of, depth_axis),
        ("force_radius", "Force vs contact radius", radius_of, radius_axis),
    ]
    .into_iter()
    .map(|(name, title, x_of, (x_unit, x_label, reference))| {
        let point = |r: &StepRecord| (x_of(r) / x_unit, r.force_normal / force_unit);
        (
            name,
            phase_panel((title, x_label, force_label), records, point, reference),
        )
    })
    .collect()
}

/// The overlays of the figure with this name.
pub type FigureOverlays<'a> = (&'a str, Vec<(String, Vec<(f64, f64)>)>);

/// The fits of γ1 (approach) and γ2 (pull-off) in the colours of their phase.
const OVERLAY_COLOURS: [RGBColor; 2] = [PALETTE[0], PALETTE[1]];

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

/// Writes `NAME.svg` and `NAME.png` for every figure into `dir`, with dashed overlay
/// curves on the figures named in `overlays`; returns the file names.
pub fn write_all_with_overlays(
    dir: &Path,
    figures: &[(&'static str, Panel)],
    overlays: &[FigureOverlays<'_>],
) -> Result<Vec<String>> {
    std::fs::create_dir_all(dir)?;
    let mut written = Vec::new();
    for (name, panel) in figures {
        let curves = overlays
            .iter()
            .filter(|(target, _)| target == name)
            .flat_map(|(_, curves)| curves);
        let fits = curves
            .zip(OVERLAY_COLOURS.iter().cycle())
            .map(|((label, curve), &colour)| {
                // Only the part inside the figure's range: fits can run far off at large radii.
                Series::new(label.as_str(), colour, Mark::Dashed, curve.clone()).clipped()
            });
        let mut panel = panel.clone();
        // The fits go under the steps (the first trace), over the jump crosses.
        let steps_at = panel
            .series
            .iter()
            .position(|s| s.mark == Mark::Trace)
            .unwrap_or(panel.series.len());
        panel.series.splice(steps_at..steps_at, fits);
        // A normalised force–radius figure gets the adhesive region beside it: on the
        // full range it is a sliver under the compressive branch.
        let zoom = (*name == "force_radius" && panel.y_label.starts_with("F / |F_JKR|"))
            .then(|| adhesive_zoom(&panel))
            .flatten();
        let (figure, size) = match zoom {
            Some(zoom) => (Figure::side_by_side(vec![panel, zoom]), (1400, 600)),
            None => (Figure::stacked(vec![panel]), (800, 600)),
        };
        let files = figure.save(dir, name, size)?;
        written.extend(files.map(|file| format!("plots/{file}")));
    }
    Ok(written)
}
