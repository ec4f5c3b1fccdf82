//! The figures of a study: Figs. 7 and 8 (rolling), Fig. 10 (sliding).

use super::tables::{AlphaRow, Row};
use adhesim_figures::figure::{Mark, Panel, Series, INK, PALETTE};
use adhesim_figures::tangential_plots::write_panels;
use anyhow::Result;
use plotters::style::RGBColor;
use std::path::Path;

/// The α range a horizontal reference line spans: the study's, widened by a tenth on each
/// side, so that it shows also where only one α has finished (interim tables).
fn reference_span(alphas: &[AlphaRow]) -> (f64, f64) {
    let lo = alphas.iter().map(|a| a.alpha).fold(f64::INFINITY, f64::min);
    let hi = alphas.iter().map(|a| a.alpha).fold(0.0, f64::max);
    let margin = 0.1 * (hi - lo).max(0.1 * hi);
    (lo - margin, hi + margin)
}

fn by_alpha(alphas: &[AlphaRow], f: impl Fn(&AlphaRow) -> Option<f64>) -> Vec<(f64, f64)> {
    alphas.iter().filter_map(|a| f(a).map(|y| (a.alpha, y))).collect()
}

/// The works of adhesion of Fig. 8: label, colour, mark and value of an α.
type GammaSeries = (&'static str, RGBColor, Mark, fn(&AlphaRow) -> Option<f64>);

const GAMMAS: [GammaSeries; 4] = [
    (
        "γ3 (rolling, F_N vs contact radius)",
        PALETTE[0],
        Mark::LinePoints,
        |a| a.gamma3_norm,
    ),
    // Outline diamonds, not a dashed line: a line of one point (one α) draws nothing.
    ("γ3 (F_N vs half-width)", PALETTE[3], Mark::Marker(3), |a| {
        a.gamma3_half_width_norm
    }),
    ("γ1 (approach)", PALETTE[2], Mark::LinePoints, |a| {
        a.gamma_approach_norm
    }),
    ("γ2 (pull-off)", PALETTE[1], Mark::LinePoints, |a| a.gamma_pulloff_norm),
];

pub fn rolling_plots(dir: &Path, rows: &[Row], alphas: &[AlphaRow]) -> Result<Vec<String>> {
    let mut files = Vec::new();
    for (name, work) in [("fig7", false), ("fig7_work", true)] {
        let mut series = Vec::new();
        let mut top: f64 = 0.0;
        for (k, a) in alphas.iter().enumerate() {
            let points: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| r.alpha == a.alpha)
                .filter_map(|r| {
                    let y = if work {
                        r.mean_tangential_force_work_norm
                    } else {
                        r.mean_tangential_force_norm
                    };
                    Some((r.eq12_prediction_norm?, y?))
                })
                .collect();
            top = points.iter().fold(top, |t, p| t.max(p.0).max(p.1));
            series.push(Series::new(
                format!("α = {:.2}", a.alpha),
                PALETTE[k % PALETTE.len()],
                Mark::Points,
                points,
            ));
        }
        series.push(Series::new(
            "slope 1 (Eq. 12)",
            INK,
            Mark::Dashed,
            vec![(0.0, 0.0), (top, top)],
        ));
        let which = if work { "work-based mean" } else { "per-step mean" };
        files.extend(write_panels(
            dir,
            name,
            &[Panel::new(
                format!("Rolling friction vs Eq. 12 ({which})"),
                "2a(γ2 − γ1) / |F_JKR|",
                "F_T / |F_JKR|",
            )
            .include_y(0.0)
            .with(series)],
        )?);
    }
    let (lo, hi) = reference_span(alphas);
    files.extend(write_panels(
        dir,
        "fig8",
        &[Panel::new(
            "Rolling contact: effective work of adhesion γ3",
            "Johnson parameter α",
            "γ / γ0",
        )
        .include_y(0.0)
        .with(
            GAMMAS
                .iter()
                .map(|&(label, colour, mark, value)| Series::new(label, colour, mark, by_alpha(alphas, value))),
        )
        .with([Series::new(
            "1.15 (paper)",
            INK,
            Mark::Dashed,
            vec![(lo, 1.15), (hi, 1.15)],
        )])],
    )?);
    Ok(files)
}

/// Per-step mean ± one standard error over the cases (substrate angles, depths) where a
/// study has more than one case per α.
fn error_band(alphas: &[AlphaRow]) -> Vec<Series> {
    if alphas.iter().all(|a| a.mean_tangential_force_sem.is_none()) {
        return Vec::new();
    }
    [1.0, -1.0]
        .iter()
        .map(|&sign| {
            Series::new(
                if sign > 0.0 { "± standard error" } else { "" },
                PALETTE[0],
                Mark::Dashed,
                by_alpha(alphas, |a| {
                    Some(a.mean_tangential_force_norm? + sign * a.mean_tangential_force_sem?)
                }),
            )
        })
        .collect()
}

pub fn sliding_plots(dir: &Path, alphas: &[AlphaRow]) -> Result<Vec<String>> {
    let (lo, hi) = reference_span(alphas);
    // Two panels: the per-step mean on its own scale (with the standard error over the
    // cases where there are several), then both means, whose scales differ by 10–50×.
    let per_step = || {
        Series::new(
            "per-step mean",
            PALETTE[0],
            Mark::LinePoints,
            by_alpha(alphas, |a| a.mean_tangential_force_norm),
        )
    };
    let mut files = write_panels(
        dir,
        "fig10a",
        &[
            Panel::new(
                "Sliding: boundary contribution to friction (per-step mean)",
                "Johnson parameter α",
                "F_B / |F_JKR|",
            )
            .include_y(0.0)
            .with(std::iter::once(per_step()).chain(error_band(alphas))),
            Panel::new("Per-step and work-based means", "Johnson parameter α", "F_B / |F_JKR|")
                .include_y(0.0)
                .with(vec![
                    per_step(),
                    Series::new(
                        "work-based mean",
                        PALETTE[4],
                        Mark::LinePoints,
                        by_alpha(alphas, |a| a.mean_tangential_force_work_norm),
                    ),
                ]),
        ],
    )?;
    files.extend(write_panels(
        dir,
        "fig10b",
        &[Panel::new(
            "Sliding: compactness of the contact",
            "Johnson parameter α",
            "A_real / (π a²)",
        )
        .include_y(0.0)
        .with(vec![
            Series::new(
                "A_real/(πa²)",
                PALETTE[0],
                Mark::LinePoints,
                by_alpha(alphas, |a| Some(a.compactness)),
            ),
            Series::new("1", INK, Mark::Dashed, vec![(lo, 1.0), (hi, 1.0)]),
        ])],
    )?);
    Ok(files)
}
