//! Figures of tangential motion (paper Figs. 6–10): forces vs travelled distance, strips
//! of consecutive contact maps with the moving axis marked, and [`write_panels`], which
//! the study plots share.

use crate::figure::{Figure, Mark, Panel, Series, PALETTE};
use adhesim::analysis::reference::Jkr;
use adhesim::{Grid, Phase, StepRecord};
use anyhow::{Context, Result};
use std::path::Path;

/// Writes `NAME.svg` and `NAME.png` with the charts stacked vertically; returns the paths
/// relative to the parent of `dir` (`plots/NAME.svg`, ...).
pub fn write_panels(dir: &Path, name: &str, panels: &[Panel]) -> Result<Vec<String>> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let height = 420 * panels.len().max(1) as u32 + 60;
    Figure::stacked(panels.to_vec()).save(dir, name, (800, height))?;
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
) -> Vec<Panel> {
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
        Mark::LinePoints,
        pts(forward, &|r| r.force_normal),
    )];
    let mut tangential = vec![Series::new(
        "forward (end of step)",
        PALETTE[0],
        Mark::LinePoints,
        pts(forward, &|r| r.force_tangential),
    )];
    if !back.is_empty() {
        normal.push(Series::new(
            "return",
            PALETTE[1],
            Mark::LinePoints,
            pts(back, &|r| r.force_normal),
        ));
        tangential.push(Series::new(
            "return (end of step)",
            PALETTE[1],
            Mark::LinePoints,
            pts(back, &|r| r.force_tangential),
        ));
    }
    let x_end = forward.last().map_or(0.0, |r| r.offset) / length;
    let x_start = stationary_start / length;
    tangential.push(Series::new(
        format!("per-step mean {:.4}", means.0 / force),
        PALETTE[2],
        Mark::Dashed,
        vec![(x_start, means.0 / force), (x_end, means.0 / force)],
    ));
    tangential.push(Series::new(
        format!("work-based mean {:.4}", means.1 / force),
        PALETTE[4],
        Mark::Dashed,
        vec![(x_start, means.1 / force), (x_end, means.1 / force)],
    ));
    vec![
        Panel::new("Normal force vs travelled distance", x_label, format!("F_N{f_unit}"))
            .include_y(0.0)
            .with(normal),
        Panel::new(
            "Tangential force vs travelled distance",
            x_label,
            format!("F_T{f_unit}"),
        )
        .include_y(0.0)
        .with(tangential),
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
    let (n, rows) = (grid.nx(), grid.ny());
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
        (c0, c1, r0, r1) = (0, n - 1, 0, rows - 1);
    }
    let margin = 2;
    let (c0, r0) = (c0.saturating_sub(margin), r0.saturating_sub(margin));
    let (c1, r1) = ((c1 + margin).min(n - 1), (r1 + margin).min(rows - 1));
    let (w, h) = (c1 - c0 + 1, r1 - r0 + 1);
    let scale = (400 / w.max(h)).clamp(1, 16);
    let gap = 8;
    let count = frames.len().max(1);
    let width = (count * w * scale + (count - 1) * gap) as u32;
    let height = (h * scale) as u32;
    let mut image = image::RgbImage::from_pixel(width, height, image::Rgb([255, 255, 255]));
    let delta = grid.dx();
    for (i, (contact, previous, offset)) in frames.iter().enumerate() {
        let left = i * (w * scale + gap);
        // Column of the indenter axis: element centres are at (c + 0.5)Δ − L/2.
        let axis_column = ((offset + 0.5 * grid.size_x()) / delta - 0.5).round() as i64 - c0 as i64;
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
    let legend = [
        (STAYING, "in contact"),
        (ATTACHED, "attached"),
        (DETACHED, "detached"),
        (AXIS, "indenter axis"),
    ];
    let pixels_per_length = scale as f64 / delta;
    let keyed = crate::map_key::with_key(&image, pixels_per_length, crate::map_key::Legend::Categories(&legend))?;
    crate::figure::files::save_image(&keyed, path)
}
