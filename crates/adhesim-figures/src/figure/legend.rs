//! Where a panel's legend goes when the caller does not say: the corner of the plot that
//! covers the fewest data, so that the legend box does not hide points or lines.

use super::{Mark, Panel};
use plotters::chart::SeriesLabelPosition;

/// Corners in the order of preference on a tie (upper left first, the old default).
const CORNERS: [SeriesLabelPosition; 4] = [
    SeriesLabelPosition::UpperLeft,
    SeriesLabelPosition::UpperRight,
    SeriesLabelPosition::LowerRight,
    SeriesLabelPosition::LowerLeft,
];

/// Samples taken along each segment of a line, so that a line through a corner counts.
const SAMPLES_PER_SEGMENT: usize = 16;

/// Where the legend of `panel` goes on the plot area x in `x_range`, y in `y_range`: where
/// the panel says, else [`emptiest_corner`]; None when no drawn series has a label.
pub(super) fn position(panel: &Panel, x_range: (f64, f64), y_range: (f64, f64)) -> Option<SeriesLabelPosition> {
    let labels = panel
        .series
        .iter()
        .filter(|s| !s.label.is_empty() && !s.points.is_empty());
    let count = labels.clone().count();
    let longest = labels.map(|s| s.label.chars().count()).max()?;
    Some(
        panel
            .legend
            .clone()
            .unwrap_or_else(|| emptiest_corner(panel, x_range, y_range, count, longest)),
    )
}

/// The corner of the plot area (x in `x_range`, y in `y_range`, drawn on log axes where
/// `log_x`, `log_y`) whose legend box, of `labels` lines of up to `longest` characters,
/// covers the fewest points of the panel's series (lines sampled along their segments).
fn emptiest_corner(
    panel: &Panel,
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
    labels: usize,
    longest: usize,
) -> SeriesLabelPosition {
    // The legend box as a fraction of the plot area: 13-px labels about 7 px per character
    // plus the marker, about 19 px per line, on a plot area of roughly 700 × 330 px.
    let width = ((longest as f64 * 7.0 + 45.0) / 700.0).min(0.9);
    let height = ((labels as f64 * 19.0 + 14.0) / 330.0).min(0.9);
    let scale = |v: f64, (low, high): (f64, f64), log: bool| {
        if log {
            (v.ln() - low.ln()) / (high.ln() - low.ln())
        } else {
            (v - low) / (high - low)
        }
    };
    let mut counts = [0usize; 4];
    let mut count = |x: f64, y: f64| {
        let (u, v) = (scale(x, (x0, x1), panel.log_x), scale(y, (y0, y1), panel.log_y));
        // A NaN or infinite coordinate lies in no range.
        if !((0.0..=1.0).contains(&u) && (0.0..=1.0).contains(&v)) {
            return;
        }
        let (left, right, top, bottom) = (u <= width, u >= 1.0 - width, v >= 1.0 - height, v <= height);
        for (corner, inside) in [top && left, top && right, bottom && right, bottom && left]
            .iter()
            .enumerate()
        {
            counts[corner] += *inside as usize;
        }
    };
    for series in &panel.series {
        let line = matches!(series.mark, Mark::Line | Mark::Dashed);
        for (k, &(x, y)) in series.points.iter().enumerate() {
            count(x, y);
            if let (true, Some(&(next_x, next_y))) = (line, series.points.get(k + 1)) {
                for s in 1..SAMPLES_PER_SEGMENT {
                    let t = s as f64 / SAMPLES_PER_SEGMENT as f64;
                    count(x + t * (next_x - x), y + t * (next_y - y));
                }
            }
        }
    }
    let best = (0..4).min_by_key(|&corner| (counts[corner], corner)).unwrap_or(0);
    CORNERS[best].clone()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figure::{Series, INK};

    fn corner_of(points: Vec<(f64, f64)>, mark: Mark) -> SeriesLabelPosition {
        let panel = Panel::new("", "x", "y").with([Series::new("data", INK, mark, points)]);
        emptiest_corner(&panel, (0.0, 1.0), (0.0, 1.0), 2, 10)
    }

    /// The legend avoids the corner the data lie in, and keeps the upper left when it is
    /// free.
    #[test]
    fn the_legend_goes_to_an_empty_corner() {
        let rising = vec![(0.0, 0.0), (1.0, 1.0)];
        assert!(matches!(corner_of(rising, Mark::Line), SeriesLabelPosition::UpperLeft));
        let falling = vec![(0.0, 1.0), (1.0, 0.0)];
        assert!(matches!(
            corner_of(falling, Mark::Line),
            SeriesLabelPosition::UpperRight
        ));
        let upper = vec![(0.02, 0.98), (0.98, 0.98), (0.5, 0.5)];
        assert!(matches!(
            corner_of(upper, Mark::Points),
            SeriesLabelPosition::LowerRight
        ));
    }
}
