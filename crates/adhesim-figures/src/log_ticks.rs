//! Tick positions and labels of logarithmic axes. plotters labels a log axis only at the
//! few points its own rule picks (on a 0.25–4 axis only 1 and 2, on a PSD over 12 decades
//! a handful of the decades), so the figures choose their own: every decade when the axis
//! spans many, 1-2-5 within a few decades, and finer steps within one, labelled in
//! plain numbers on an axis within 1e-3 … 1e4 and as `1e-11` on others. Linear axes keep
//! plotters' labels, with the zero tick snapped (`zero_snapped`).

use plotters::coord::combinators::{BindKeyPoints, IntoLogRange, LogCoord, WithKeyPoints};
use plotters::coord::ranged1d::ValueFormatter;

/// Labelled (bold) and unlabelled (light) tick positions inside [low, high] (low > 0).
pub fn log_ticks(low: f64, high: f64) -> (Vec<f64>, Vec<f64>) {
    if !(low > 0.0 && high > low && low.is_finite() && high.is_finite()) {
        return (Vec::new(), Vec::new());
    }
    let decades = (high / low).log10();
    let first = low.log10().floor() as i32;
    let last = high.log10().ceil() as i32;
    let inside = |v: &f64| *v >= low * (1.0 - 1e-12) && *v <= high * (1.0 + 1e-12);
    let with = |mantissas: &[f64], every: i32| -> Vec<f64> {
        (first..=last)
            .filter(|k| k.rem_euclid(every) == 0)
            .flat_map(|k| mantissas.iter().map(move |m| m * 10f64.powi(k)))
            .filter(inside)
            .collect()
    };
    let bold = if decades > 10.0 {
        with(&[1.0], (decades / 8.0).ceil() as i32)
    } else if decades > 3.0 {
        with(&[1.0], 1)
    } else if decades > 1.5 {
        with(&[1.0, 2.0, 5.0], 1)
    } else {
        // within about one decade: enough steps for at least five labels
        let steps: [&[f64]; 3] = [
            &[1.0, 2.0, 5.0],
            &[1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 7.0],
            &[
                1.0, 1.2, 1.4, 1.6, 1.8, 2.0, 2.5, 3.0, 3.5, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0,
            ],
        ];
        steps
            .iter()
            .map(|m| with(m, 1))
            .find(|ticks| ticks.len() >= 5)
            .unwrap_or_else(|| with(steps[2], 1))
    };
    let light = if decades <= 12.0 {
        with(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0], 1)
    } else {
        with(&[1.0], 1)
    };
    (bold, light)
}

/// A tick label on an axis over `range`: plain and short (`0.25`, `1`, `40`) where the
/// whole axis lies within 1e-3 … 1e4 and spans at most 4 decades, else `1e-11` or
/// `2.5e-11`, so that one axis never mixes the two.
pub fn log_tick_label(value: f64, (low, high): (f64, f64)) -> String {
    if value == 0.0 || !value.is_finite() {
        return format!("{value}");
    }
    let plain = low >= 1e-3 && high < 1e4 && high / low <= 1e4;
    let exponent = value.abs().log10().floor() as i32;
    if plain {
        // three significant digits, trailing zeros dropped
        let decimals = (2 - exponent).max(0) as usize;
        let text = format!("{value:.decimals$}");
        if text.contains('.') {
            text.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            text
        }
    } else {
        let mantissa = value / 10f64.powi(exponent);
        if (mantissa - mantissa.round()).abs() < 1e-9 {
            format!("{}e{exponent}", mantissa.round())
        } else {
            format!("{mantissa:.1}e{exponent}")
        }
    }
}

/// A logarithmic axis over [low, high] with its ticks chosen by [`log_ticks`].
pub fn log_axis(low: f64, high: f64) -> WithKeyPoints<LogCoord<f64>> {
    let (bold, light) = log_ticks(low, high);
    (low..high).log_scale().with_key_points(bold).with_light_points(light)
}

/// A linear tick's value as labelled: tick positions are sums of float steps, so the zero
/// tick can land at −1e-17 and print as "-0.0"; a tick within 1e-9 of the span from zero
/// is zero.
pub fn zero_snapped(value: f64, (low, high): (f64, f64)) -> f64 {
    if value.abs() <= 1e-9 * (high - low).abs() {
        0.0
    } else {
        value
    }
}

/// A tick's label: `log_tick_label` on a log axis, else the zero-snapped value in
/// scientific notation or in the axis type's own format (plotters' plain numbers).
pub fn tick_label<Axis: ValueFormatter<f64>>(value: f64, range: (f64, f64), log: bool, scientific: bool) -> String {
    if log {
        log_tick_label(value, range)
    } else if scientific {
        format!("{:.1e}", zero_snapped(value, range))
    } else {
        Axis::format(&zero_snapped(value, range))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_zero_tick_off_by_rounding_is_labelled_zero() {
        // 0.2 · 3 − 0.6 ≠ 0 in floating point: the tick a step sum lands on.
        let off = 0.2 * 3.0 - 0.6;
        assert!(off != 0.0);
        assert_eq!(zero_snapped(-off, (-0.5, 1.3)), 0.0);
        assert!(zero_snapped(-off, (-0.5, 1.3)).is_sign_positive());
        assert_eq!(format!("{:.1}", zero_snapped(-1e-17, (-0.5, 1.3))), "0.0");
        // A real small value on a small axis is kept.
        assert_eq!(zero_snapped(-1e-17, (-1e-16, 1e-16)), -1e-17);
        assert_eq!(zero_snapped(0.1, (-0.5, 1.3)), 0.1);
    }

    #[test]
    fn a_johnson_parameter_axis_is_labelled_beyond_1_and_2() {
        let (bold, _) = log_ticks(0.22, 4.5);
        let labels: Vec<String> = bold.iter().map(|&v| log_tick_label(v, (0.22, 4.5))).collect();
        assert!(labels.len() >= 6, "{labels:?}");
        for wanted in ["0.3", "0.5", "1", "2", "3", "4"] {
            assert!(labels.contains(&wanted.to_string()), "{labels:?}");
        }
    }

    #[test]
    fn a_psd_axis_over_many_decades_gets_every_decade_or_every_other() {
        let (bold, light) = log_ticks(3e-20, 2e-9);
        let labels: Vec<String> = bold.iter().map(|&v| log_tick_label(v, (3e-20, 2e-9))).collect();
        assert!(labels.len() >= 5 && labels.len() <= 12, "{labels:?}");
        assert!(
            labels.contains(&"1e-10".to_string()) || labels.contains(&"1e-11".to_string()),
            "{labels:?}"
        );
        assert!(light.len() >= bold.len());
    }

    #[test]
    fn labels_are_short_and_one_style_per_axis() {
        let alpha = (0.25, 4.0);
        assert_eq!(log_tick_label(0.25, alpha), "0.25");
        assert_eq!(log_tick_label(1.0, alpha), "1");
        assert_eq!(log_tick_label(1.5, alpha), "1.5");
        assert_eq!(log_tick_label(40.0, (1.0, 100.0)), "40");
        let psd = (1e-20, 1e-9);
        assert_eq!(log_tick_label(1e-11, psd), "1e-11");
        assert_eq!(log_tick_label(2.5e-11, psd), "2.5e-11");
        // an axis over many decades writes even 0.001 and 1 with exponents
        assert_eq!(log_tick_label(1e-3, (1e-9, 1e9)), "1e-3");
        assert_eq!(log_tick_label(1.0, (1e-9, 1e9)), "1e0");
        assert_eq!(log_tick_label(1e5, (1e3, 1e6)), "1e5");
    }

    #[test]
    fn a_narrow_axis_has_at_least_three_labels_and_a_bad_one_none() {
        assert!(log_ticks(1.1, 1.9).0.len() >= 3);
        assert_eq!(log_ticks(0.0, 1.0), (Vec::new(), Vec::new()));
        assert_eq!(log_ticks(f64::NAN, 1.0), (Vec::new(), Vec::new()));
    }
}
