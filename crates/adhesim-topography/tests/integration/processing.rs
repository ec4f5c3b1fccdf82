//! Detrending and resampling against analytic maps.

use adhesim_topography::{ResampleMethod, Topography, TopographyError};

fn map(nx: usize, ny: usize, dx: f64, dy: f64, f: impl Fn(f64, f64) -> f64) -> Topography {
    let mut heights = Vec::with_capacity(nx * ny);
    for iy in 0..ny {
        for ix in 0..nx {
            heights.push(f(ix as f64 * dx, iy as f64 * dy));
        }
    }
    Topography {
        nx,
        ny,
        dx,
        dy,
        x_offset: 0.0,
        y_offset: 0.0,
        heights,
        mask: None,
        channel: "test".into(),
        height_unit: "m".into(),
        lateral_unit: "m".into(),
        format: "npy",
        metadata: Default::default(),
    }
}

/// A map band-limited below the Nyquist frequency of a 16 × 12 grid of period 16 µm × 6 µm.
fn band_limited(x: f64, y: f64) -> f64 {
    let (lx, ly) = (16e-6, 6e-6);
    let tau = std::f64::consts::TAU;
    1e-9 * ((tau * 2.0 * x / lx).cos()
        + 0.5 * (tau * 3.0 * y / ly).sin()
        + 0.3 * (tau * (5.0 * x / lx + 2.0 * y / ly)).cos()
        + 0.2 * (tau * 7.0 * x / lx).sin())
}

#[test]
fn detrend_removes_a_plane_exactly() {
    let mut plane = map(9, 7, 1e-6, 2e-6, |x, y| 3e-9 + 0.01 * x - 0.02 * y);
    let (a, b, c) = plane.detrend_mean_plane().unwrap();
    // Round-off of sums of ~60 terms of size 1e-7 m.
    assert!(plane.heights.iter().all(|h| h.abs() < 1e-20), "{:?}", plane.heights);
    assert!(
        (a - 3e-9).abs() < 1e-20 && (b - 0.01).abs() < 1e-14 && (c + 0.02).abs() < 1e-14,
        "{a} {b} {c}"
    );
}

#[test]
fn detrended_residual_is_orthogonal_to_the_plane_and_ignores_invalid_points() {
    let mut topo = map(11, 8, 1e-6, 1e-6, |x, y| {
        5e-9 + 0.003 * x + band_limited(x * 1.3, y * 0.7) + (x * y * 1e12).sin() * 1e-9
    });
    let mut mask = vec![true; 88];
    mask[17] = false;
    topo.heights[17] = 1.0; // an outlier of a metre at an invalid point
    topo.mask = Some(mask.clone());
    topo.detrend_mean_plane().unwrap();
    // Least squares: the residual of the valid points has zero sum and zero first moments
    // in x and y (the normal equations), to round-off relative to the sums of magnitudes
    // (1e-12 allows for the 3e-8 m plane subtracted from each point).
    let (mut s, mut sx, mut sy, mut scale) = (0.0, 0.0, 0.0, 0.0);
    for (i, h) in topo.heights.iter().enumerate().filter(|&(i, _)| mask[i]) {
        s += h;
        sx += h * (i % 11) as f64;
        sy += h * (i / 11) as f64;
        scale += h.abs() * 10.0;
    }
    let tolerance = 1e-12 * scale;
    assert!(
        s.abs() < tolerance && sx.abs() < tolerance && sy.abs() < tolerance,
        "{s} {sx} {sy} vs {tolerance}"
    );
    assert_eq!(topo.heights[17], 0.0);
}

#[test]
fn spectral_refinement_of_a_band_limited_map_is_exact() {
    let coarse = map(16, 12, 1e-6, 0.5e-6, band_limited);
    // Three times finer in x, twice in y: target points fall on the refined grid.
    let out = coarse.resample_to(48, 24, 1e-6 / 3.0, 0.25e-6).unwrap();
    assert_eq!(out.method, ResampleMethod::Spectral);
    assert!(out.undersampling.is_none());
    let exact = map(48, 24, 1e-6 / 3.0, 0.25e-6, band_limited);
    for (i, (got, want)) in out.topography.heights.iter().zip(&exact.heights).enumerate() {
        // Trigonometric interpolation reproduces the band-limited map to FFT round-off.
        assert!((got - want).abs() < 1e-22, "point {i}: {got:e} vs {want:e}");
    }
    assert_eq!((out.topography.dx, out.topography.nx), (1e-6 / 3.0, 48));
}

#[test]
fn spectral_refinement_to_a_non_dividing_spacing_is_close() {
    let coarse = map(16, 12, 1e-6, 0.5e-6, band_limited);
    let out = coarse.resample_to(30, 20, 0.37e-6, 0.23e-6).unwrap();
    let exact = map(30, 20, 0.37e-6, 0.23e-6, band_limited);
    // Bilinear between refined points of spacing ≤ the target: the error is below
    // h''·s²/8 ≈ (2π·7/16 µm)²·1e-9 m·(0.37 µm)²/8 ≈ 1.3e-10 m for the shortest component.
    let worst = out
        .topography
        .heights
        .iter()
        .zip(&exact.heights)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(worst < 1.3e-10, "worst {worst:e}");
}

#[test]
fn bilinear_reproduces_a_plane_and_reports_undersampling() {
    let plane = |x: f64, y: f64| 1e-9 + 0.002 * x - 0.001 * y;
    let fine = map(21, 17, 0.5e-6, 0.5e-6, plane);
    let out = fine.resample_to(7, 5, 1.5e-6, 2e-6).unwrap();
    assert_eq!(out.method, ResampleMethod::Bilinear);
    let under = out.undersampling.expect("coarser target reported");
    assert_eq!((under.target_dx, under.measured_dx), (1.5e-6, 0.5e-6));
    assert!(under.to_string().contains("coarser"), "{under}");
    let exact = map(7, 5, 1.5e-6, 2e-6, plane);
    for (got, want) in out.topography.heights.iter().zip(&exact.heights) {
        assert!((got - want).abs() < 1e-21, "{got:e} vs {want:e}");
    }
    // Forced bilinear onto a finer grid is exact for a plane too, off the measured points.
    let out = fine
        .resample_with(23, 19, 0.43e-6, 0.41e-6, ResampleMethod::Bilinear)
        .unwrap();
    let exact = map(23, 19, 0.43e-6, 0.41e-6, plane);
    for (got, want) in out.topography.heights.iter().zip(&exact.heights) {
        assert!((got - want).abs() < 1e-21, "{got:e} vs {want:e}");
    }
}

#[test]
fn a_target_larger_than_the_measurement_is_an_error() {
    let m = map(10, 10, 1e-6, 1e-6, |_, _| 0.0);
    let err = m.resample_to(20, 10, 1e-6, 1e-6).unwrap_err();
    assert!(matches!(err, TopographyError::InvalidArgument { .. }));
    assert!(err.to_string().contains("more than the measurement"), "{err}");
    assert!(m.resample_to(10, 10, f64::NAN, 1e-6).is_err());
    assert!(m.resample_to(0, 10, 1e-6, 1e-6).is_err());
    let mut broken = m.clone();
    broken.heights.pop();
    assert!(broken.resample_to(5, 5, 1e-6, 1e-6).is_err());
    broken.heights.push(f64::NAN);
    assert!(broken
        .detrend_mean_plane()
        .unwrap_err()
        .to_string()
        .contains("not finite"));
    let mut all_masked = m.clone();
    all_masked.mask = Some(vec![false; 100]);
    assert!(all_masked.detrend_mean_plane().is_err());
}
