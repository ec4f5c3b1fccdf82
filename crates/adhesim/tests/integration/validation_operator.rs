//! The elastic operators against Love's and Boussinesq's closed forms.

#![allow(clippy::needless_range_loop)]
use adhesim::elastic::influence::love_coefficient;
use adhesim::{Boundary, ElasticMaterial, ElasticOperator, FreeOperator, Grid, PeriodicKernel, PeriodicOperator};
use std::f64::consts::{PI, TAU};

/// One loaded element: DC-FFT is an exact linear convolution, so the response equals
/// Love's coefficient up to FFT round-off (~1e-15 of the peak, i.e. < 1e-12 relative even
/// at the farthest point where the value is ~100× smaller): tolerance 1e-10 relative.
#[test]
fn single_element_reproduces_love_near_and_far() {
    let n = 64;
    let grid = Grid::new(n, 3.2, Boundary::Free).unwrap();
    let material = ElasticMaterial::new(2.5).unwrap();
    let mut operator = FreeOperator::new(grid, material);
    let delta = grid.dx();
    for &(row, column) in &[(0usize, 0usize), (n - 1, n - 1), (17, 40)] {
        let mut pressure = vec![0.0; grid.len()];
        pressure[row * n + column] = 1.0;
        let mut displacement = vec![0.0; grid.len()];
        operator.apply(&pressure, &mut displacement);
        for k in 0..grid.len() {
            let (i, j) = (k / n, k % n);
            let xi = (j as f64 - column as f64) * delta;
            let eta = (i as f64 - row as f64) * delta;
            let expected = love_coefficient(xi, eta, delta, 2.5);
            assert!(
                (displacement[k] - expected).abs() <= 1e-10 * expected.abs(),
                "load at ({row},{column}), point ({i},{j}): {} vs {expected}",
                displacement[k]
            );
        }
    }
}

/// Uniform numbers in [0, 1) from a xorshift64 generator (reproducible test fields).
fn uniform_random(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The discrete operator is symmetric: x·Ky = y·Kx for random fields (tolerance 1e-12
/// relative: only FFT round-off separates the two sides).
#[test]
fn operators_are_reciprocal() {
    let n = 48;
    let material = ElasticMaterial::new(1.0).unwrap();
    let mut uniform = uniform_random(0x9E37_79B9_7F4A_7C15);
    let mut random = move || uniform() - 0.5;
    for boundary in [Boundary::Free, Boundary::Periodic] {
        let grid = Grid::new(n, 1.0, boundary).unwrap();
        let mut operator: Box<dyn ElasticOperator> = match boundary {
            Boundary::Free => Box::new(FreeOperator::new(grid, material)),
            Boundary::Periodic => Box::new(PeriodicOperator::new(grid, material, PeriodicKernel::ElementConsistent)),
        };
        let x: Vec<f64> = (0..grid.len()).map(|_| random()).collect();
        let y: Vec<f64> = (0..grid.len()).map(|_| random()).collect();
        let (mut kx, mut ky) = (vec![0.0; grid.len()], vec![0.0; grid.len()]);
        operator.apply(&x, &mut kx);
        operator.apply(&y, &mut ky);
        let xky: f64 = x.iter().zip(&ky).map(|(a, b)| a * b).sum();
        let ykx: f64 = y.iter().zip(&kx).map(|(a, b)| a * b).sum();
        assert!(
            (xky - ykx).abs() <= 1e-12 * xky.abs().max(ykx.abs()),
            "{boundary:?}: {xky} vs {ykx}"
        );
        // positive definite on these samples
        let xkx: f64 = x.iter().zip(&kx).map(|(a, b)| a * b).sum();
        assert!(xkx > 0.0);
    }
}

/// Cosine pressure p = cos(qx) at a grid frequency. Continuous kernel: u = 2p/(E*q)
/// exactly (tolerance 1e-12). Element-consistent kernel: the response of the
/// piecewise-constant cosine at element centres is Σ_m 2·sinc((q+2πm/Δ)Δ/2)/(E*|q+2πm/Δ|)
/// (a 1-D alias sum: the y form factor kills every n ≠ 0 alias); summed here to
/// |m| ≤ 200 000 as an independent reference, the 40-alias kernel must match to 1e-6.
#[test]
fn periodic_operator_reproduces_cosine_pressure() {
    let n = 64;
    let size = 2.0;
    let modulus = 1.7;
    let grid = Grid::new(n, size, Boundary::Periodic).unwrap();
    let material = ElasticMaterial::new(modulus).unwrap();
    let delta = grid.dx();
    for &k in &[1usize, 5, 20] {
        let q = TAU * k as f64 / size;
        let pressure: Vec<f64> = (0..grid.len()).map(|e| (q * grid.centre(e).0).cos()).collect();
        let mut displacement = vec![0.0; grid.len()];

        let mut continuous = PeriodicOperator::new(grid, material, PeriodicKernel::Continuous);
        continuous.apply(&pressure, &mut displacement);
        for e in 0..grid.len() {
            let expected = 2.0 * pressure[e] / (modulus * q);
            assert!((displacement[e] - expected).abs() < 1e-12 * 2.0 / (modulus * q));
        }

        let mut consistent = PeriodicOperator::new(grid, material, PeriodicKernel::ElementConsistent);
        consistent.apply(&pressure, &mut displacement);
        let mut multiplier = 0.0;
        for m in -200_000i64..=200_000 {
            let shifted = q + TAU * m as f64 / delta;
            let t = 0.5 * shifted * delta;
            multiplier += 2.0 * (t.sin() / t) / (modulus * shifted.abs());
        }
        for e in 0..grid.len() {
            let expected = multiplier * pressure[e];
            assert!(
                (displacement[e] - expected).abs() < 1e-6 * multiplier.abs(),
                "k = {k}: {} vs {expected}",
                displacement[e]
            );
        }
        // and the element-consistent response converges to the continuous one as qΔ → 0
        assert!((multiplier * modulus * q / 2.0 - 1.0).abs() < (q * delta).powi(2) / 10.0 + 1e-12);
    }
}

/// The periodic element-consistent kernel and the free operator's Love coefficients
/// describe the same element: their near-field differences K(0,0) − K(Δ,0) agree once the
/// period is large (image contributions to a difference of neighbours decay like Δ²/L²).
/// Tolerance 1e-4 relative at L = 128Δ.
#[test]
fn periodic_near_field_matches_love() {
    let n = 128;
    let grid = Grid::new(n, 1.0, Boundary::Periodic).unwrap();
    let material = ElasticMaterial::new(1.0).unwrap();
    let delta = grid.dx();
    let mut operator = PeriodicOperator::new(grid, material, PeriodicKernel::ElementConsistent);
    let centre = (n / 2) * n + n / 2;
    let mut pressure = vec![0.0; grid.len()];
    pressure[centre] = 1.0;
    let mut displacement = vec![0.0; grid.len()];
    operator.apply(&pressure, &mut displacement);
    for &(di, dj) in &[(0usize, 1usize), (1, 1), (0, 2)] {
        let periodic = displacement[centre] - displacement[centre + di * n + dj];
        let love =
            love_coefficient(0.0, 0.0, delta, 1.0) - love_coefficient(dj as f64 * delta, di as f64 * delta, delta, 1.0);
        assert!(
            (periodic / love - 1.0).abs() < 1e-4,
            "({di},{dj}): {periodic} vs {love}"
        );
    }
    let _ = PI;
}

/// The single-precision application (used for CG search directions) matches the exact
/// one to single-precision round-off: f32 carries 6e-8 relative per operation and a
/// 2N-point transform pair adds ≈ log2(2N) rounding stages, so 2e-6 of max|u| bounds the
/// error with margin (measured 2.5–3.1e-7 at N = 128) and fails if any stage lost precision.
#[test]
fn single_precision_application_matches_double() {
    let n = 128;
    let material = ElasticMaterial::new(1.0).unwrap();
    let mut random = uniform_random(0x2545_F491_4F6C_DD1D);
    for boundary in [Boundary::Free, Boundary::Periodic] {
        let grid = Grid::new(n, 1.0, boundary).unwrap();
        let mut operator: Box<dyn ElasticOperator> = match boundary {
            Boundary::Free => Box::new(FreeOperator::new(grid, material)),
            Boundary::Periodic => Box::new(PeriodicOperator::new(grid, material, PeriodicKernel::ElementConsistent)),
        };
        // a positive pressure patch plus a few isolated sign changes, as at a contact front
        let pressure: Vec<f64> = (0..grid.len())
            .map(|k| if k % 97 == 0 { -5.0 } else { random() })
            .collect();
        let (mut exact, mut single) = (vec![0.0; grid.len()], vec![0.0; grid.len()]);
        operator.apply(&pressure, &mut exact);
        operator.apply_single(&pressure, &mut single);
        let scale = exact.iter().fold(0.0f64, |m, u| m.max(u.abs()));
        let error = exact.iter().zip(&single).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(error > 0.0, "{boundary:?}: the single-precision path must differ");
        assert!(error < 2e-6 * scale, "{boundary:?}: {:e} of max|u|", error / scale);
        assert_eq!(operator.applications(), 2);
    }
}
