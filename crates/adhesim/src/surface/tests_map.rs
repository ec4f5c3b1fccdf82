//! Tests of [`super::HeightMap`] and [`super::fill_invalid_harmonic`] against closed forms and
//! SurfaceTopography's values on a small map.

use super::{fill_invalid_harmonic, HeightMap, SurfaceError};
use std::f64::consts::TAU;

/// h = a·sin(q_x·x) + b·cos(q_y·y) on a periodic rectangle with dx ≠ dy. The spectral forms
/// are exact: h'_rms² = (a²q_x² + b²q_y²)/2, κ_rms² = (a²q_x⁴ + b²q_y⁴)/8 (mean curvature
/// ∇²h/2; the cross term averages out). The forward differences see 2·sin(qΔ/2)/Δ for q,
/// the second differences 4·sin²(qΔ/2)/Δ², also exactly on the periodic map: both to
/// rounding, 1e-12.
#[test]
fn periodic_rectangle_with_unequal_spacings() {
    let (nx, ny, dx, dy) = (48usize, 20usize, 0.5, 1.25);
    let (a, b) = (0.3, 0.7);
    let (qx, qy) = (TAU * 5.0 / (nx as f64 * dx), TAU * 3.0 / (ny as f64 * dy));
    let heights: Vec<f64> = (0..nx * ny)
        .map(|k| {
            let (x, y) = ((k % nx) as f64 * dx, (k / nx) as f64 * dy);
            a * (qx * x).sin() + b * (qy * y).cos()
        })
        .collect();
    let map = HeightMap::new((nx, ny), (dx, dy), &heights, None, true).unwrap();
    let close = |got: f64, want: f64, what: &str| {
        assert!((got / want - 1.0).abs() < 1e-12, "{what}: {got} vs {want}");
    };
    close(map.rms_height(), ((a * a + b * b) / 2.0).sqrt(), "rms height");
    let (slope, curvature) = map.spectral_slope_and_curvature().unwrap();
    close(
        slope,
        ((a * a * qx * qx + b * b * qy * qy) / 2.0).sqrt(),
        "spectral slope",
    );
    close(
        curvature,
        ((a * a * qx.powi(4) + b * b * qy.powi(4)) / 8.0).sqrt(),
        "spectral curvature",
    );
    let first = |q: f64, d: f64| 2.0 * (q * d / 2.0).sin() / d;
    let second = |q: f64, d: f64| 4.0 * (q * d / 2.0).sin().powi(2) / (d * d);
    close(
        map.rms_slope_finite_differences().unwrap(),
        ((a * a * first(qx, dx).powi(2) + b * b * first(qy, dy).powi(2)) / 2.0).sqrt(),
        "finite-difference slope",
    );
    close(
        map.rms_curvature_finite_differences().unwrap(),
        ((a * a * second(qx, dx).powi(2) + b * b * second(qy, dy).powi(2)) / 8.0).sqrt(),
        "finite-difference curvature",
    );
}

/// SurfaceTopography 1.27 on its fixture `xyz-1.txt` (a 4 × 4 map, unit spacing, a bump of
/// four points of height 2 on a plane of 1): rms_height_from_area 0.33071891388307384,
/// rms_gradient 0.816496580927726, rms_curvature_from_area 1.118033988749895. The same
/// stencils on the same points: to rounding, 1e-14.
#[test]
fn surfacetopography_values_of_a_small_free_map() {
    // rows are y: SurfaceTopography's heights[x, y] transposed
    let heights = [
        1.0, 1.0, 1.0, 1.0, //
        1.0, 2.0, 1.0, 1.0, //
        1.0, 2.0, 1.0, 1.0, //
        1.0, 1.0, 1.0, 1.0,
    ];
    let map = HeightMap::new((4, 4), (1.0, 1.0), &heights, None, false).unwrap();
    let close = |got: f64, want: f64| assert!((got / want - 1.0).abs() < 1e-14, "{got} vs {want}");
    close(map.rms_height(), 0.33071891388307384);
    close(map.rms_slope_finite_differences().unwrap(), 0.816496580927726);
    close(map.rms_curvature_finite_differences().unwrap(), 1.118033988749895);
    assert!(
        map.spectral_slope_and_curvature().is_none(),
        "free maps have no spectral form"
    );
}

/// Invalid points are left out: their heights (here absurd) change nothing, and the rms
/// height is that of the valid points alone. A difference counts only where both of its
/// points are valid.
#[test]
fn invalid_points_are_left_out() {
    let (nx, ny) = (5, 4);
    let mut heights: Vec<f64> = (0..nx * ny).map(|k| ((k * 7) % 11) as f64 * 0.1).collect();
    let mut valid = vec![true; nx * ny];
    for k in [3, 12] {
        valid[k] = false;
        heights[k] = 1e30;
    }
    let map = HeightMap::new((nx, ny), (1.0, 2.0), &heights, Some(&valid), false).unwrap();
    let kept: Vec<f64> = (0..nx * ny).filter(|&k| valid[k]).map(|k| heights[k]).collect();
    let mean = kept.iter().sum::<f64>() / kept.len() as f64;
    let rms = (kept.iter().map(|h| (h - mean).powi(2)).sum::<f64>() / kept.len() as f64).sqrt();
    assert!((map.rms_height() / rms - 1.0).abs() < 1e-14);
    let slope = map.rms_slope_finite_differences().unwrap();
    let curvature = map.rms_curvature_finite_differences().unwrap();
    assert!(slope < 10.0 && curvature < 10.0, "{slope} {curvature}");
    assert!(map.spectral_slope_and_curvature().is_none());
    let psd = map.isotropic_psd(8).unwrap();
    assert!(psd.iter().all(|b| b.psd.is_finite() && b.psd < 10.0));
    heights[3] = f64::NAN; // an invalid NaN is not read either
    assert!(HeightMap::new((nx, ny), (1.0, 2.0), &heights, Some(&valid), false).is_ok());
    assert!(matches!(
        HeightMap::new((nx, ny), (1.0, 2.0), &heights, None, false),
        Err(SurfaceError::NonFiniteHeight { index: 3, .. })
    ));
}

/// A plane a + b·x + c·y is harmonic, and its discrete Laplacian vanishes: holes away from
/// the edge are filled with the plane exactly (to the solver's 1e-13 relative residual).
/// A hole on the edge of a free map sees a zero normal derivative there, so it is filled
/// with a plane only along the edge: it is just finite and bounded by the data.
#[test]
fn harmonic_filling_restores_a_plane() {
    let (nx, ny) = (30, 20);
    let plane = |k: usize| 0.5 + 0.02 * (k % nx) as f64 - 0.03 * (k / nx) as f64;
    let mut heights: Vec<f64> = (0..nx * ny).map(plane).collect();
    let mut valid = vec![true; nx * ny];
    for iy in 5..12 {
        for ix in 8..19 {
            valid[iy * nx + ix] = false;
            heights[iy * nx + ix] = -7.0;
        }
    }
    valid[nx + 20] = false;
    let filled = fill_invalid_harmonic((nx, ny), &heights, &valid, false).unwrap();
    for k in 0..nx * ny {
        assert!(
            (filled[k] - plane(k)).abs() < 1e-11,
            "point {k}: {} vs {}",
            filled[k],
            plane(k)
        );
    }
}

#[test]
fn harmonic_filling_needs_a_valid_neighbour() {
    let valid = vec![false; 9];
    assert_eq!(
        fill_invalid_harmonic((3, 3), &[0.0; 9], &valid, false),
        Err(SurfaceError::NoValidPoint)
    );
    // an invalid corner region touches data through its neighbours and is filled
    let mut valid = vec![true; 16];
    valid[0] = false;
    valid[1] = false;
    let filled = fill_invalid_harmonic((4, 4), &[1.0; 16], &valid, false).unwrap();
    assert!(filled.iter().all(|&h| (h - 1.0).abs() < 1e-12));
}

/// One mode on a periodic rectangle: all the power A·h_rms² in the bin holding its |q|.
#[test]
fn psd_of_one_mode_on_a_rectangle() {
    let (nx, ny, dx, dy) = (40usize, 24usize, 1.0, 2.0);
    let q = TAU * 4.0 / (ny as f64 * dy);
    let heights: Vec<f64> = (0..nx * ny).map(|k| 0.5 * (q * (k / nx) as f64 * dy).cos()).collect();
    let map = HeightMap::new((nx, ny), (dx, dy), &heights, None, true).unwrap();
    let bins = map.isotropic_psd(10).unwrap();
    let area = nx as f64 * dx * ny as f64 * dy;
    let total: f64 = bins.iter().map(|b| b.psd * b.modes as f64).sum::<f64>() / area;
    assert!((total / 0.125 - 1.0).abs() < 1e-12, "{total}");
    let holder = bins.iter().find(|b| b.edges.0 <= q && q <= b.edges.1).unwrap();
    assert!((holder.psd * holder.modes as f64 / area / 0.125 - 1.0).abs() < 1e-12);
}
