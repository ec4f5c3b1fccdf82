use super::*;
use crate::elastic::bessel::bessel_j0;
use crate::elastic::test_fields::{lcg_field, xorshift_field};
use crate::elastic::FreeOperator;

/// C_layer/C_halfspace from Navier's equations integrated across the layer
/// ([`super::navier`]), independently of the closed form; C_halfspace = 2/(E*k) with
/// E* = 2G/(1 − ν) and G = k = 1.
fn shooting_factor(kt: f64, poisson_ratio: f64, base: LayerBase, steps: usize) -> f64 {
    let [_, normal] = navier::surface_displacement(kt, poisson_ratio, base, steps, navier::Load::Pressure);
    normal * (1.0 / (1.0 - poisson_ratio))
}

#[test]
fn factor_matches_navier_integration() {
    // RK4 with 4000 steps (hk ≤ 1.25e-3): truncation ≈ (hk)⁴ ≈ 1e-12 times the growth
    // e^{2kt} ≤ 2e4 of the shooting solutions; tolerance 1e-8.
    let mut worst: f64 = 0.0;
    for poisson_ratio in [-0.3, 0.0, 0.3, 0.45] {
        for kt in [0.05, 0.3, 1.0, 2.5, 5.0] {
            for base in [LayerBase::Bonded, LayerBase::Frictionless] {
                let closed = layer_compliance_factor(kt, poisson_ratio, base);
                let numeric = shooting_factor(kt, poisson_ratio, base, 4000);
                worst = worst.max((closed / numeric - 1.0).abs());
                assert!(
                    (closed - numeric).abs() < 1e-8 * numeric.abs().max(1e-3),
                    "ν = {poisson_ratio}, kt = {kt}, {base:?}: {closed} vs {numeric}"
                );
            }
        }
    }
    println!("closed form against Navier integration: largest relative difference {worst:.1e}");
}

#[test]
fn factor_tends_to_one_and_orders_the_bases() {
    // 1 − f ≈ 2(2s² + (1 + κ²)/2)e^{−2s}/κ (bonded), 2(2s + 1)e^{−2s} (frictionless): at
    // s = 10 below 1e-6, at s ≥ 25 exactly 1.
    for poisson_ratio in [-0.5, 0.0, 0.3, 0.5] {
        for base in [LayerBase::Bonded, LayerBase::Frictionless] {
            let near = layer_compliance_factor(10.0, poisson_ratio, base);
            assert!(near < 1.0 && 1.0 - near < 1e-6, "{near}");
            assert_eq!(layer_compliance_factor(25.0, poisson_ratio, base), 1.0);
            assert_eq!(layer_compliance_factor(1e9, poisson_ratio, base), 1.0);
        }
        // A bonded base constrains the frictionless layer further (u = 0 as well), so by
        // the minimum of the potential energy it is stiffer at every k; both are stiffer
        // than the half-space.
        for i in 1..400 {
            let kt = 0.05 * i as f64;
            let bonded = layer_compliance_factor(kt, poisson_ratio, LayerBase::Bonded);
            let frictionless = layer_compliance_factor(kt, poisson_ratio, LayerBase::Frictionless);
            assert!(0.0 < bonded && bonded < frictionless && frictionless < 1.0, "kt = {kt}");
        }
    }
}

#[test]
fn thin_incompressible_bonded_layer_is_the_lubrication_limit() {
    // Lubrication: G u'' = ∇p across the layer, u = 0 at the base, u' = 0 at the surface,
    // and incompressibility give w = −(t³/(3G))∇²p, i.e. C(k) = t³k²/(3G). With E* = 4G at
    // ν = 1/2, C = f·2/(E*k) = f/(2Gk), so C/(t³k²/(3G)) = 3f/(2s³) = 1 − (9/5)s² + O(s⁴)
    // (series of the closed form). Tolerance 2s², and 1e-12 at s = 1e-6, where the naive
    // κ sinh 2s − 2s would have lost all but five digits.
    for kt in [1e-6, 1e-4, 1e-3, 1e-2] {
        let f = layer_compliance_factor(kt, 0.5, LayerBase::Bonded);
        let ratio = 1.5 * f / kt.powi(3);
        assert!((ratio - 1.0).abs() < (2.0 * kt * kt).max(1e-12), "kt = {kt}: {ratio}");
    }
    // Continuous at ν = 1/2 (κ = 1): no 0/0.
    for kt in [1e-3, 0.1, 1.0, 5.0] {
        let at = layer_compliance_factor(kt, 0.5, LayerBase::Bonded);
        let below = layer_compliance_factor(kt, 0.5 - 1e-9, LayerBase::Bonded);
        assert!(
            at.is_finite() && (at - below).abs() < 1e-8,
            "kt = {kt}: {at} vs {below}"
        );
    }
}

#[test]
fn thin_compressible_layer_is_in_uniaxial_strain() {
    // Bonded, k → 0: every point is in uniaxial strain, ε_zz = p(1 + ν)(1 − 2ν)/(E(1 − ν)),
    // so C(0) = t(1 − 2ν)(1 + ν)/(E(1 − ν)); with E = E*(1 − ν²) the ratio to the closed
    // form is 2f(1 − ν)²/(s(1 − 2ν)). Frictionless, k → 0: σ_xx averages to zero over the
    // thickness (no shear on either face), plane strain gives ε_zz = p(1 − ν²)/E, so
    // C(0) = t/E* and the ratio is 2f/s. The closed form's next term is O(s²) (f is odd
    // in s), below 0.7 s² for ν ≤ 0.4; tolerance 1e-6 at s = 1e-3.
    let s = 1e-3;
    for poisson_ratio in [-0.5, 0.0, 0.25, 0.4] {
        let bonded = layer_compliance_factor(s, poisson_ratio, LayerBase::Bonded);
        let ratio = 2.0 * bonded * (1.0 - poisson_ratio).powi(2) / (s * (1.0 - 2.0 * poisson_ratio));
        assert!((ratio - 1.0).abs() < 1e-6, "ν = {poisson_ratio}: {ratio}");
        let frictionless = layer_compliance_factor(s, poisson_ratio, LayerBase::Frictionless);
        assert!((2.0 * frictionless / s - 1.0).abs() < 1e-6, "{frictionless}");
    }
}

#[test]
fn bessel_j0_matches_reference_values() {
    // Values of mpmath.besselj(0, x) to 17 digits; tolerance 2e-11 (the expansions' error
    // at the switch, x = 13).
    let reference = [
        (1.0, 0.765_197_686_557_966_6),
        (5.0, -0.177_596_771_314_338_3),
        (10.0, -0.245_935_764_451_348_34),
        (12.9, 0.198_842_437_136_330_99),
        (13.0, 0.206_926_102_377_067_81),
        (13.1, 0.212_888_197_522_060_36),
        (20.0, 0.167_024_664_340_583_15),
        (50.0, 0.055_812_327_669_251_815),
        (300.0, -0.033_298_554_876_305_67),
    ];
    for (x, expected) in reference {
        assert!(
            (bessel_j0(x) - expected).abs() < 2e-11,
            "J0({x}) = {} vs {expected}",
            bessel_j0(x)
        );
    }
}

#[test]
fn point_correction_cancels_boussinesq_far_away() {
    // Far from the load the layer carries nothing (its kernel decays as e^{−0.739 r/t}), so
    // D → −1/(πE* r): d(ρ) + 1/ρ must vanish at the end of the table, to the quadrature's
    // accuracy (1e-9 of 1/ρ), and join −1/ρ continuously.
    for base in [LayerBase::Bonded, LayerBase::Frictionless] {
        for poisson_ratio in [0.0, 0.5] {
            let layer = ElasticLayer::new(1.0, poisson_ratio, base).unwrap();
            let table = PointCorrection::new(&layer);
            for rho in [45.0, 55.0, TABLE_RANGE - 1e-9] {
                let d = table.value(rho);
                assert!(
                    (d * rho + 1.0).abs() < 1e-9,
                    "{base:?}, ν = {poisson_ratio}, ρ = {rho}: {d}"
                );
            }
        }
    }
}

fn grid(n: usize, boundary: Boundary) -> Grid {
    Grid::new(n, 1.0, boundary).unwrap()
}

/// The displacement under unit pressure on element `source`.
fn unit_response(operator: &mut dyn ElasticOperator, source: usize) -> Vec<f64> {
    let len = operator.grid().len();
    let mut pressure = vec![0.0; len];
    pressure[source] = 1.0;
    let mut displacement = vec![0.0; len];
    operator.apply(&pressure, &mut displacement);
    displacement
}

#[test]
fn free_coefficients_match_a_large_periodic_cell() {
    // Two independent routes to the same element coefficients: the free operator's Love +
    // Hankel-transformed correction in real space, and the periodic operator's alias sum
    // of the Fourier compliance on a cell of 256 elements, whose images lie ≥ 232Δ ≥ 46t
    // away (their share is below e^{−0.739·46} ≈ 2e-15). The periodic operator drops the
    // mean mode: add back C(0)/M² (C(0) = 2t f'(0)/E*, f'(0) = 4(κ − 1)/(1 + κ)² bonded,
    // 1/2 frictionless). Tolerance 2e-5 of K(0,0): the periodic kernel's 40 aliases
    // reproduce Love's near field to 1e-5 (docs/physics.md §1b).
    let (n, cell) = (24, 256);
    let material = ElasticMaterial::new(1.3).unwrap();
    let delta = 1.0 / cell as f64;
    for (thickness, poisson_ratio, base) in [
        (2.0, 0.5, LayerBase::Bonded),
        (5.0, 0.3, LayerBase::Bonded),
        (3.0, 0.5, LayerBase::Frictionless),
        (0.5, 0.5, LayerBase::Bonded),
    ] {
        let layer = ElasticLayer::new(thickness * delta, poisson_ratio, base).unwrap();
        let free_grid = Grid::new(n, n as f64 * delta, Boundary::Free).unwrap();
        let mut free = LayerOperator::new(free_grid, material, layer).unwrap();
        let mut periodic = LayerOperator::new(grid(cell, Boundary::Periodic), material, layer).unwrap();
        let kappa = 3.0 - 4.0 * poisson_ratio;
        let slope = match base {
            LayerBase::Bonded => 4.0 * (kappa - 1.0) / (1.0 + kappa).powi(2),
            LayerBase::Frictionless => 0.5,
        };
        let mean = 2.0 * layer.thickness() * slope / material.contact_modulus() / (cell * cell) as f64;
        let free_response = unit_response(&mut free, 0);
        let periodic_response = unit_response(&mut periodic, 0);
        let scale = free.self_compliance();
        let mut worst: f64 = 0.0;
        for m in 0..n {
            for l in 0..n {
                let difference = free_response[m * n + l] - periodic_response[m * cell + l] - mean;
                worst = worst.max(difference.abs() / scale);
            }
        }
        println!("t = {thickness}Δ, ν = {poisson_ratio}, {base:?}: free against periodic cell {worst:.1e} of K(0,0)");
        assert!(
            worst < 2e-5,
            "t = {thickness}Δ, ν = {poisson_ratio}, {base:?}: {worst:e}"
        );
    }
}

#[test]
fn thick_layer_is_the_half_space() {
    // t = 1e6 L: on the grid the layer's correction is the uniform shift d(0)/(πE*t) per
    // unit force, ≈ 1e-6 of the displacements; tolerance 1e-3 (the brief's), measured ~1e-6.
    let n = 32;
    let material = ElasticMaterial::new(2.0).unwrap();
    let layer = ElasticLayer::new(1e6, 0.5, LayerBase::Bonded).unwrap();
    let pressure = xorshift_field(&mut 0x2545_f491_4f6c_dd1du64, n * n);
    let (mut expected, mut got) = (vec![0.0; n * n], vec![0.0; n * n]);
    FreeOperator::new(grid(n, Boundary::Free), material).apply(&pressure, &mut expected);
    LayerOperator::new(grid(n, Boundary::Free), material, layer)
        .unwrap()
        .apply(&pressure, &mut got);
    let largest = expected.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
    let worst = expected.iter().zip(&got).fold(0.0f64, |a, (e, g)| a.max((e - g).abs()));
    println!(
        "t = 1e6 L against the free half-space: {:.1e} of max|u|",
        worst / largest
    );
    assert!(worst < 1e-3 * largest, "{worst:e} of {largest:e}");
    // Periodic: every wavenumber of the grid and its aliases has kt ≥ 25, so the factor
    // is exactly 1 and the operator is the half-space's bit for bit.
    let periodic = grid(n, Boundary::Periodic);
    let mut half_space = PeriodicOperator::new(periodic, material, PeriodicKernel::ElementConsistent);
    half_space.apply(&pressure, &mut expected);
    LayerOperator::new(periodic, material, layer)
        .unwrap()
        .apply(&pressure, &mut got);
    assert_eq!(expected, got);
}

#[test]
fn free_operator_is_the_direct_sum_symmetric_and_positive() {
    // DC-FFT against the direct sum of the coefficients on a rectangle (12 × 9 elements of
    // 0.1 × 0.07), tolerance 1e-12 of max|u| (FFT round-off); symmetry ⟨a, Kb⟩ = ⟨b, Ka⟩ to
    // 1e-12; positivity pᵀKp > 0 for random signed fields and the checkerboard, the
    // shortest wave, on a bonded incompressible layer whose kernel has a negative lobe.
    let (nx, ny) = (12, 9);
    let grid = Grid::rectangular(nx, ny, 1.2, 0.63, Boundary::Free).unwrap();
    let material = ElasticMaterial::new(1.0).unwrap();
    for (thickness, base) in [(0.15, LayerBase::Bonded), (0.3, LayerBase::Frictionless)] {
        let layer = ElasticLayer::new(thickness, 0.5, base).unwrap();
        let table = layer_coefficients(&grid, 1.0, &layer);
        let mut operator = LayerOperator::new(grid, material, layer).unwrap();
        let mut random = 0x9e37_79b9_7f4a_7c15u64;
        let mut field = || lcg_field(&mut random, nx * ny);
        let (a, b) = (field(), field());
        let (mut ka, mut kb) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
        operator.apply(&a, &mut ka);
        operator.apply(&b, &mut kb);
        let largest = ka.iter().fold(0.0f64, |m, &v| m.max(v.abs()));
        for i in 0..nx * ny {
            let direct: f64 = (0..nx * ny)
                .map(|j| {
                    let l = (i % nx).abs_diff(j % nx);
                    let m = (i / nx).abs_diff(j / nx);
                    table[m * nx + l] * a[j]
                })
                .sum();
            assert!((direct - ka[i]).abs() < 1e-12 * largest, "element {i}");
        }
        let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(p, q)| p * q).sum::<f64>();
        let (ab, ba) = (dot(&a, &kb), dot(&b, &ka));
        assert!((ab - ba).abs() < 1e-12 * dot(&a, &ka).abs(), "{ab} vs {ba}");
        let checkerboard: Vec<f64> = (0..nx * ny)
            .map(|k| if (k % nx + k / nx) % 2 == 0 { 1.0 } else { -1.0 })
            .collect();
        for p in [a, b, checkerboard] {
            let mut kp = vec![0.0; nx * ny];
            operator.apply(&p, &mut kp);
            assert!(dot(&p, &kp) > 0.0, "{base:?}");
            let mut single = vec![0.0; nx * ny];
            operator.apply_single(&p, &mut single);
            let largest = kp.iter().fold(0.0f64, |m, &v| m.max(v.abs()));
            assert!(kp.iter().zip(&single).all(|(x, y)| (x - y).abs() < 1e-5 * largest));
        }
        assert_eq!(operator.applications(), 8);
    }
}

#[test]
fn bad_layers_are_refused() {
    for thickness in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            ElasticLayer::new(thickness, 0.3, LayerBase::Bonded),
            Err(LayerError::InvalidThickness(_))
        ));
    }
    for poisson_ratio in [-1.0, 0.5000001, f64::NAN] {
        assert!(matches!(
            ElasticLayer::new(1.0, poisson_ratio, LayerBase::Bonded),
            Err(LayerError::InvalidPoissonRatio(_))
        ));
    }
    let layer = ElasticLayer::new(1.0 / 64.0 / 17.0, 0.5, LayerBase::Bonded).unwrap();
    let material = ElasticMaterial::new(1.0).unwrap();
    assert!(matches!(
        LayerOperator::new(grid(64, Boundary::Free), material, layer),
        Err(LayerError::ThinnerThanElements { .. })
    ));
}

#[test]
fn periodic_operator_applies_the_factor_to_a_pressure_wave() {
    // A sampled wave p = cos(qx) on a periodic 128² grid (L = 1, t = 0.1 = 12.8Δ): the
    // layer's response over the half-space's is f(qt), up to the aliases of the element
    // form factor. Those add terms of alternating sign to both, of relative size below
    // Σ_{m≠0} (qΔ)²/(4π²m²) = (qΔ)²/12, on the part where the two differ (1 − f; the
    // aliases' own factors are 1 at |G|t ≥ 80). Tolerance (1 − f)(qΔ)²/6.
    let n = 128;
    let periodic = grid(n, Boundary::Periodic);
    let material = ElasticMaterial::new(1.0).unwrap();
    for base in [LayerBase::Bonded, LayerBase::Frictionless] {
        let layer = ElasticLayer::new(0.1, 0.5, base).unwrap();
        let mut layered = LayerOperator::new(periodic, material, layer).unwrap();
        let mut half_space = PeriodicOperator::new(periodic, material, PeriodicKernel::ElementConsistent);
        for mode in [1, 2, 4, 8] {
            let q = std::f64::consts::TAU * mode as f64;
            let pressure: Vec<f64> = (0..n * n).map(|k| (q * periodic.centre(k).0).cos()).collect();
            let (mut u_layer, mut u_half) = (vec![0.0; n * n], vec![0.0; n * n]);
            layered.apply(&pressure, &mut u_layer);
            half_space.apply(&pressure, &mut u_half);
            let at = n / 2; // x = 0, where cos = 1
            let ratio = u_layer[at] / u_half[at];
            let f = layer.compliance_factor(q);
            let delta = 1.0 / n as f64;
            let tolerance = (1.0 - f) * (q * delta).powi(2) / 6.0;
            assert!(
                (ratio - f).abs() < tolerance,
                "{base:?}, qt = {}: {ratio} vs {f} (tolerance {tolerance:e})",
                q * 0.1
            );
        }
    }
}
