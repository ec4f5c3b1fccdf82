//! Axis ranges plotters can draw in bounded time and memory. Its tick generation loops
//! until the ticks pass the range's end: on a log axis from 0 or to ∞ (a PSD of heights near
//! 1e300, `topography --spacing 1e300`) it never does and allocates without bound; on a
//! linear axis a NaN bound panics, an infinite span or a span below the rounding of its
//! bounds loops. Every panel's ranges pass through here, so no input decides a plot's
//! memory: a range outside these bounds is clamped (the data files keep the values).

/// Largest magnitude of an axis bound: a span of two such bounds stays finite, and a log
/// axis's decade ticks (×10) stay finite past the end.
const LARGEST: f64 = 1e300;

/// Smallest lower bound of a log axis: a normal number far from underflow.
const SMALLEST_LOG: f64 = 1e-300;

/// Largest ratio of a log axis's bounds: plotters counts the decades as ln(high/low), and
/// loops that many times where few ticks fit; an infinite ratio (1e-300 to 1e300) never ends.
const LARGEST_LOG_RATIO: f64 = 1e200;

/// Smallest span of a linear axis relative to its bounds' magnitude: tick steps are
/// fractions of the span and must move a bound in floating point.
const RELATIVE_SPAN: f64 = 1e-12;

/// Smallest absolute span of a linear axis: tick steps of a tenth and a hundredth of it
/// stay normal numbers.
const ABSOLUTE_SPAN: f64 = 1e-250;

/// A linear range plotters can tick: finite bounds within ±[`LARGEST`], ordered, with a
/// span of at least [`ABSOLUTE_SPAN`] and [`RELATIVE_SPAN`] of its magnitude (widened
/// about its centre otherwise); (0, 1) for NaN.
pub fn linear_range(low: f64, high: f64) -> (f64, f64) {
    if low.is_nan() || high.is_nan() {
        return (0.0, 1.0);
    }
    let (low, high) = (
        low.min(high).clamp(-LARGEST, LARGEST),
        high.max(low).clamp(-LARGEST, LARGEST),
    );
    let least = (RELATIVE_SPAN * low.abs().max(high.abs())).max(ABSOLUTE_SPAN);
    if high - low >= least {
        return (low, high);
    }
    let centre = (0.5 * (low + high)).clamp(-LARGEST + least, LARGEST - least);
    (centre - least, centre + least)
}

/// A log range plotters can tick: bounds in [[`SMALLEST_LOG`], [`LARGEST`]], ordered, at
/// least a factor 1 + [`RELATIVE_SPAN`] apart (a decade each way otherwise) and at most
/// [`LARGEST_LOG_RATIO`] (the lower bound raised: the top of a PSD is what matters); a
/// non-positive or NaN bound is taken at the edge of that window.
pub fn log_range(low: f64, high: f64) -> (f64, f64) {
    let bound = |v: f64, edge: f64| {
        if v.is_nan() || v <= 0.0 {
            edge
        } else {
            v.clamp(SMALLEST_LOG, LARGEST)
        }
    };
    let (low, high) = (bound(low, SMALLEST_LOG), bound(high, LARGEST));
    let (low, high) = (low.min(high), high.max(low));
    let low = low.max(high / LARGEST_LOG_RATIO);
    if high >= low * (1.0 + RELATIVE_SPAN) {
        return (low, high);
    }
    ((low / 10.0).max(SMALLEST_LOG), (high * 10.0).min(LARGEST))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ordinary_ranges_are_kept_as_they_are() {
        assert_eq!(linear_range(-0.3, 2.5), (-0.3, 2.5));
        assert_eq!(log_range(1e-3, 1e4), (1e-3, 1e4));
    }

    #[test]
    fn absurd_ranges_are_clamped_to_drawable_ones() {
        for (low, high) in [
            (f64::NEG_INFINITY, f64::INFINITY),
            (f64::NAN, 1.0),
            (1e308, f64::MAX),
            (1e-310, 2e-310),
            (1e300, 1e300 + 1e280),
            (5.0, -5.0),
        ] {
            let (a, b) = linear_range(low, high);
            assert!(a.is_finite() && b.is_finite() && b > a, "{low} {high} -> {a} {b}");
            assert!(
                (b - a) >= RELATIVE_SPAN * a.abs().max(b.abs()),
                "{low} {high} -> {a} {b}"
            );
            let (a, b) = log_range(low, high);
            assert!(
                a >= SMALLEST_LOG && b <= LARGEST && b > a && (b / a).is_finite(),
                "{low} {high} -> {a} {b}"
            );
        }
        assert_eq!(log_range(0.0, f64::INFINITY), (LARGEST / LARGEST_LOG_RATIO, LARGEST));
        let (a, b) = log_range(1e-300, 1e300);
        assert!(b / a <= LARGEST_LOG_RATIO * (1.0 + 1e-12), "{a} {b}");
    }

    /// Second robustness audit (docs/reliability.md): `topography --spacing 1e300` gave the PSD
    /// plot a log range from 0 or to ∞, and plotters' tick loop allocated until the process was
    /// killed.
    #[test]
    fn panels_of_absurd_ranges_are_drawn() {
        use crate::figure::{Figure, Mark, Panel, Series, PALETTE};
        let dir = tempfile::tempdir().unwrap();
        let data = Series::new("", PALETTE[0], Mark::LinePoints, vec![(1e-300, 1e300), (2e-300, 3e300)]);
        let log = Panel::new("", "q", "C")
            .with([data.clone()])
            .log_x()
            .x_range(0.0, f64::INFINITY)
            .log_y(1e300 / 2.0 * 1e10, f64::INFINITY);
        let linear = Panel::new("", "x", "y")
            .with([data])
            .x_range(f64::NAN, 1.0)
            .include_y(f64::MAX);
        let files = Figure::stacked(vec![log, linear])
            .save(dir.path(), "absurd", (400, 600))
            .unwrap();
        for file in files {
            assert!(
                std::fs::metadata(dir.path().join(&file)).unwrap().len() > 1000,
                "{file}"
            );
        }
    }
}
