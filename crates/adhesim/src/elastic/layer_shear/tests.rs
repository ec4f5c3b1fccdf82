use super::*;
use crate::elastic::bessel::bessel_j2;
use crate::elastic::layer::navier::{surface_displacement, Load};
use crate::elastic::test_fields::{lcg_field, xorshift_field};
use crate::elastic::{LayerError, TangentialOperator, TangentialOperatorError};
use crate::grid::Boundary;

const RUBBER: ShearMaterial = ShearMaterial {
    shear_modulus: 1.0,
    poisson_ratio: 0.5,
};

fn material(poisson_ratio: f64) -> ShearMaterial {
    ShearMaterial {
        shear_modulus: 1.3,
        poisson_ratio,
    }
}

#[test]
fn factors_match_navier_integration() {
    // The closed forms against the shooting solution of Navier's equations (G = k = 1):
    // C_tt = −U(0) under a shear wave, C_nn = W(0) under a pressure wave, C_nt = W(0) under
    // the shear wave, which Betti's reciprocity makes −U(0) under the pressure wave. RK4
    // with 4000 steps: truncation ≈ 1e-12 times the growth e^{2kt} ≤ 2e4; tolerance 1e-8.
    let mut worst: f64 = 0.0;
    for poisson_ratio in [-0.3, 0.0, 0.3, 0.45] {
        for kt in [0.05, 0.3, 1.0, 2.5, 5.0] {
            let [u_shear, w_shear] = surface_displacement(kt, poisson_ratio, LayerBase::Bonded, 4000, Load::Shear);
            let [u_pressure, w_pressure] =
                surface_displacement(kt, poisson_ratio, LayerBase::Bonded, 4000, Load::Pressure);
            let longitudinal = layer_longitudinal_factor(kt, poisson_ratio);
            let numeric = -u_shear / (1.0 - poisson_ratio);
            worst = worst.max((longitudinal / numeric - 1.0).abs());
            assert!(
                (longitudinal - numeric).abs() < 1e-8 * numeric,
                "ν = {poisson_ratio}, kt = {kt}: {longitudinal} vs {numeric}"
            );
            assert!(
                (w_shear + u_pressure).abs() < 1e-8 * w_shear.abs().max(1e-3),
                "reciprocity at ν = {poisson_ratio}, kt = {kt}: {w_shear} vs {u_pressure}"
            );
            let ratio = w_shear.abs() / (w_pressure * -u_shear).sqrt();
            assert!(
                (layer_coupling_ratio(kt, poisson_ratio) - ratio).abs() < 1e-8,
                "ν = {poisson_ratio}, kt = {kt}: {} vs {ratio}",
                layer_coupling_ratio(kt, poisson_ratio)
            );
        }
    }
    println!("longitudinal factor against Navier integration: largest relative difference {worst:.1e}");
}

#[test]
fn thin_layers_shear_simply_and_rubber_couples() {
    // kt → 0: both factors give the simple shear C = t/G, (1 − ν)f_L/s → 1 and tanh s/s → 1,
    // with O(s²) corrections (both are odd in s; the largest here, −(5/3)s² at ν = 1/2, from
    // the series of the closed form); tolerance 2s² at s = 1e-3. For
    // incompressible rubber the coupling ratio tends to √3/2: C_nn = t³k²/(3G),
    // C_tt = t/G, C_nt = t²k/(2G). Continuous at ν = 1/2 (no 0/0), checked where the
    // squeeze term s³ of C_nn outweighs the compressible one (1 − 2ν)s (kt ≥ 0.1 at
    // 1 − 2ν = 2e-9); the longitudinal factor is 1 at kt ≥ 25.
    let s = 1e-3;
    for poisson_ratio in [-0.5, 0.0, 0.3, 0.5] {
        let simple = (1.0 - poisson_ratio) * layer_longitudinal_factor(s, poisson_ratio) / s;
        assert!((simple - 1.0).abs() < 2.0 * s * s, "ν = {poisson_ratio}: {simple}");
        assert_eq!(layer_longitudinal_factor(25.0, poisson_ratio), 1.0);
    }
    assert!((layer_transverse_factor(s) / s - 1.0).abs() < s * s);
    assert!((layer_coupling_ratio(s, 0.5) - 0.75f64.sqrt()).abs() < s);
    for kt in [0.1, 1.0, 5.0] {
        let (at, below) = (layer_coupling_ratio(kt, 0.5), layer_coupling_ratio(kt, 0.5 - 1e-9));
        assert!(
            at.is_finite() && (at - below).abs() < 1e-6,
            "kt = {kt}: {at} vs {below}"
        );
    }
}

#[test]
fn bessel_j2_matches_reference_values() {
    // J2 = 2J1/x − J0 from Abramowitz & Stegun's Table 9.1 (10 digits); tolerance 2e-10.
    let reference = [
        (1.0, 0.440_050_585_7, 0.765_197_686_6),
        (5.0, -0.327_579_137_6, -0.177_596_771_3),
        (10.0, 0.043_472_746_2, -0.245_935_764_5),
        (15.0, 0.205_104_038_6, -0.014_224_472_8),
        (20.0, 0.066_833_124_2, 0.167_024_664_3),
    ];
    for (x, j1, j0) in reference {
        let expected = 2.0 * j1 / x - j0;
        assert!(
            (bessel_j2(x) - expected).abs() < 2e-10,
            "J2({x}) = {} vs {expected}",
            bessel_j2(x)
        );
    }
    // Both expansions meet at the switch to their accuracy (J0's, 2e-11).
    assert!((bessel_j2(13.0 - 1e-12) - bessel_j2(13.0)).abs() < 2e-11);
}

#[test]
fn correction_cancels_cerruti_far_away() {
    // Far from the load the layer carries nothing, so d0·ρ → −(2 − ν)/2 and d2·ρ → ν/2, to
    // the quadrature's accuracy (1e-9) at the end of the table.
    for poisson_ratio in [0.0, 0.3, 0.5] {
        let layer = ElasticLayer::new(1.0, poisson_ratio, LayerBase::Bonded).unwrap();
        let correction = ShearCorrection::new(&layer);
        for rho in [45.0, 55.0, 60.0 - 1e-9] {
            let d0 = correction.isotropic.value(rho) * rho;
            let d2 = correction.deviatoric.value(rho) * rho;
            assert!(
                (d0 + 0.5 * (2.0 - poisson_ratio)).abs() < 1e-9,
                "ν = {poisson_ratio}, ρ = {rho}: {d0}"
            );
            assert!(
                (d2 - 0.5 * poisson_ratio).abs() < 1e-9,
                "ν = {poisson_ratio}, ρ = {rho}: {d2}"
            );
        }
    }
}

/// (u_x, u_y) under a unit traction along x on element `source`.
fn unit_response(operator: &mut TangentialOperator, source: usize) -> (Vec<f64>, Vec<f64>) {
    let len = operator.grid().len();
    let (mut qx, qy) = (vec![0.0; len], vec![0.0; len]);
    qx[source] = 1.0;
    let (mut ux, mut uy) = (vec![0.0; len], vec![0.0; len]);
    operator.apply([&qx, &qy], [&mut ux, &mut uy]);
    (ux, uy)
}

#[test]
fn free_coefficients_match_a_large_periodic_cell() {
    // Two independent routes to the coefficients: the free operator's Cerruti + Hankel
    // (J0 and J2) correction in real space, and the periodic operator's alias sum of the
    // Fourier compliance tensor on a cell of 256 elements whose images lie ≥ 46t away
    // (their share is below e^{−0.739·46}). The periodic operator drops the mean mode: add
    // back (t/G)/M² to K_xx. K_xy (odd in x and y) checks the sign of the J2 part.
    // Tolerance 2e-5 of K_xx(0,0), the periodic alias sum's near-field accuracy.
    let (n, cell) = (24, 256);
    let delta = 1.0 / cell as f64;
    for (thickness, poisson_ratio) in [(2.0, 0.5), (5.0, 0.3), (0.5, 0.5), (3.0, 0.0)] {
        let material = material(poisson_ratio);
        let layer = ElasticLayer::new(thickness * delta, poisson_ratio, LayerBase::Bonded).unwrap();
        let free_grid = Grid::new(n, n as f64 * delta, Boundary::Free).unwrap();
        let periodic_grid = Grid::new(cell, 1.0, Boundary::Periodic).unwrap();
        let mut free = TangentialOperator::on_layer(free_grid, material, layer).unwrap();
        let mut periodic = TangentialOperator::on_layer(periodic_grid, material, layer).unwrap();
        let mean = layer.thickness() / material.shear_modulus / (cell * cell) as f64;
        let (free_x, free_y) = unit_response(&mut free, 0);
        let (periodic_x, periodic_y) = unit_response(&mut periodic, 0);
        let scale = free.self_compliance();
        let mut worst: f64 = 0.0;
        for m in 0..n {
            for l in 0..n {
                let along = free_x[m * n + l] - periodic_x[m * cell + l] - mean;
                let across = free_y[m * n + l] - periodic_y[m * cell + l];
                worst = worst.max(along.abs().max(across.abs()) / scale);
            }
        }
        println!("t = {thickness}Δ, ν = {poisson_ratio}: free against periodic cell {worst:.1e} of K_xx(0,0)");
        assert!(worst < 2e-5, "t = {thickness}Δ, ν = {poisson_ratio}: {worst:e}");
    }
}

#[test]
fn thick_layer_is_the_half_space() {
    // t = 1e6 L: the correction on the grid is a near-uniform shift of order 1/t, ≈ 1e-6
    // of the displacements (free); on the periodic grid every wave has kt ≥ 25, where both
    // factors are 1, so the spectra agree to rounding. Tolerances 1e-3 and 1e-12.
    let n = 32;
    let mut random = 0x2545_f491_4f6c_dd1du64;
    let mut field = || -> Vec<f64> { xorshift_field(&mut random, n * n).iter().map(|v| v - 0.5).collect() };
    let (qx, qy) = (field(), field());
    let layer = ElasticLayer::new(1e6, 0.3, LayerBase::Bonded).unwrap();
    for (boundary, tolerance) in [(Boundary::Free, 1e-3), (Boundary::Periodic, 1e-12)] {
        let grid = Grid::new(n, 1.0, boundary).unwrap();
        let mut half_space = TangentialOperator::new(grid, material(0.3)).unwrap();
        let mut layered = TangentialOperator::on_layer(grid, material(0.3), layer).unwrap();
        let (mut expected, mut got) = (
            [vec![0.0; n * n], vec![0.0; n * n]],
            [vec![0.0; n * n], vec![0.0; n * n]],
        );
        let [ex, ey] = &mut expected;
        half_space.apply([&qx, &qy], [ex, ey]);
        let [gx, gy] = &mut got;
        layered.apply([&qx, &qy], [gx, gy]);
        let largest = expected.iter().flatten().fold(0.0f64, |a, &b| a.max(b.abs()));
        let worst = expected
            .iter()
            .flatten()
            .zip(got.iter().flatten())
            .fold(0.0f64, |a, (e, g)| a.max((e - g).abs()));
        println!(
            "{boundary:?}: t = 1e6 L against the half-space {:.1e} of max|u|",
            worst / largest
        );
        assert!(worst < tolerance * largest, "{boundary:?}: {worst:e} of {largest:e}");
    }
}

#[test]
fn layer_operator_is_symmetric_and_positive() {
    // Betti: ⟨a, Kb⟩ = ⟨b, Ka⟩ for random traction fields (1e-12); positive definite:
    // qᵀKq > 0 for random fields and the checkerboard, on a rectangle of a thin rubber
    // layer (t = 1.5Δx) and a compressible one.
    let (nx, ny) = (12, 9);
    let grid = Grid::rectangular(nx, ny, 1.2, 0.63, Boundary::Free).unwrap();
    for (thickness, poisson_ratio) in [(0.15, 0.5), (0.4, 0.2)] {
        let layer = ElasticLayer::new(thickness, poisson_ratio, LayerBase::Bonded).unwrap();
        let mut operator = TangentialOperator::on_layer(grid, material(poisson_ratio), layer).unwrap();
        let mut random = 0x9e37_79b9_7f4a_7c15u64;
        let mut field = || lcg_field(&mut random, nx * ny);
        let mut apply = |q: &[Vec<f64>; 2]| {
            let (mut ux, mut uy) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
            operator.apply([&q[0], &q[1]], [&mut ux, &mut uy]);
            [ux, uy]
        };
        let dot = |a: &[Vec<f64>; 2], b: &[Vec<f64>; 2]| -> f64 {
            a.iter()
                .zip(b)
                .map(|(x, y)| x.iter().zip(y).map(|(p, q)| p * q).sum::<f64>())
                .sum()
        };
        let (a, b) = ([field(), field()], [field(), field()]);
        let (ka, kb) = (apply(&a), apply(&b));
        let (ab, ba) = (dot(&a, &kb), dot(&b, &ka));
        assert!((ab - ba).abs() < 1e-12 * dot(&a, &ka), "{ab} vs {ba}");
        let checker: Vec<f64> = (0..nx * ny)
            .map(|k| if (k % nx + k / nx) % 2 == 0 { 1.0 } else { -1.0 })
            .collect();
        for q in [a, b, [checker.clone(), vec![0.0; nx * ny]], [checker.clone(), checker]] {
            let energy = dot(&q, &apply(&q));
            assert!(energy > 0.0, "t = {thickness}: qᵀKq = {energy}");
        }
    }
}

#[test]
fn periodic_waves_carry_the_longitudinal_and_transverse_factors() {
    // A sampled traction wave q_x = cos(qx) is longitudinal, q_x = cos(qy) transverse; on a
    // periodic 128² grid (t = 0.1 = 12.8Δ) the layer's response over the half-space's is
    // f_L(qt) and tanh(qt), up to the element form factor's aliases (relative size below
    // (qΔ)²/12 on the part where the two differ, as for the normal operator). Tolerance
    // (1 − f)(qΔ)²/6.
    let n = 128;
    let grid = Grid::new(n, 1.0, Boundary::Periodic).unwrap();
    let layer = ElasticLayer::new(0.1, 0.5, LayerBase::Bonded).unwrap();
    let mut layered = TangentialOperator::on_layer(grid, RUBBER, layer).unwrap();
    let mut half_space = TangentialOperator::new(grid, RUBBER).unwrap();
    let zero = vec![0.0; n * n];
    for mode in [1, 2, 4, 8] {
        let q = std::f64::consts::TAU * mode as f64;
        for longitudinal in [true, false] {
            let traction: Vec<f64> = (0..n * n)
                .map(|k| {
                    let (x, y) = grid.centre(k);
                    (q * if longitudinal { x } else { y }).cos()
                })
                .collect();
            let (mut u_layer, mut u_half, mut across) = (vec![0.0; n * n], vec![0.0; n * n], vec![0.0; n * n]);
            layered.apply([&traction, &zero], [&mut u_layer, &mut across]);
            half_space.apply([&traction, &zero], [&mut u_half, &mut across]);
            let at = (n / 2) * n + n / 2;
            let ratio = u_layer[at] / u_half[at];
            let f = if longitudinal {
                layer_longitudinal_factor(q * 0.1, 0.5)
            } else {
                layer_transverse_factor(q * 0.1)
            };
            let tolerance = (1.0 - f) * (q / n as f64).powi(2) / 6.0;
            assert!(
                (ratio - f).abs() < tolerance,
                "qt = {}, longitudinal {longitudinal}: {ratio} vs {f} (tolerance {tolerance:e})",
                q * 0.1
            );
        }
    }
}

#[test]
fn thin_layer_under_a_uniform_patch_shears_simply() {
    // A uniform traction over 56 × 56 elements of a free grid on a layer t = Δ: 28t from
    // the patch's edge the layer is in simple shear, u_x = q t/G, u_y = 0. The edge's
    // disturbance decays as e^{−0.739 r/t} (the nearest pole of f_L at ν = 1/2, kt = 0.739i;
    // tanh's is at iπ/2), 1e-9 there; tolerance 1e-6, the Hankel table's.
    let n = 64;
    let grid = Grid::new(n, 1.0, Boundary::Free).unwrap();
    let layer = ElasticLayer::new(grid.dx(), 0.5, LayerBase::Bonded).unwrap();
    let mut operator = TangentialOperator::on_layer(grid, RUBBER, layer).unwrap();
    let qx: Vec<f64> = (0..n * n)
        .map(|k| {
            if (4..60).contains(&(k % n)) && (4..60).contains(&(k / n)) {
                1.0
            } else {
                0.0
            }
        })
        .collect();
    let (mut ux, mut uy) = (vec![0.0; n * n], vec![0.0; n * n]);
    operator.apply([&qx, &vec![0.0; n * n]], [&mut ux, &mut uy]);
    let centre = (n / 2) * n + n / 2;
    assert!(
        (ux[centre] / layer.thickness() - 1.0).abs() < 1e-6,
        "{}",
        ux[centre] / layer.thickness()
    );
    assert!(uy[centre].abs() < 1e-6 * layer.thickness(), "{}", uy[centre]);
}

#[test]
fn unsupported_layers_are_refused() {
    let grid = Grid::new(16, 1.0, Boundary::Free).unwrap();
    let frictionless = ElasticLayer::new(0.5, 0.5, LayerBase::Frictionless).unwrap();
    assert!(matches!(
        TangentialOperator::on_layer(grid, RUBBER, frictionless),
        Err(TangentialOperatorError::LayerSlidesOnBase)
    ));
    let other = ElasticLayer::new(0.5, 0.3, LayerBase::Bonded).unwrap();
    assert!(matches!(
        TangentialOperator::on_layer(grid, RUBBER, other),
        Err(TangentialOperatorError::LayerPoissonRatio { .. })
    ));
    let thin = ElasticLayer::new(grid.dx() / 20.0, 0.5, LayerBase::Bonded).unwrap();
    assert!(matches!(
        TangentialOperator::on_layer(grid, RUBBER, thin),
        Err(TangentialOperatorError::Layer(LayerError::ThinnerThanElements { .. }))
    ));
}
