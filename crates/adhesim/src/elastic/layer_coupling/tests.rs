use super::*;
use crate::elastic::bessel::bessel_j1_over_x;
use crate::elastic::layer::navier::{surface_displacement, Load};
use crate::elastic::test_fields::{lcg_field, xorshift_field};
use crate::elastic::{CouplingOperator, LayerBase, ShearBody};
use crate::grid::Boundary;

fn material(poisson_ratio: f64) -> ShearMaterial {
    ShearMaterial {
        shear_modulus: 1.3,
        poisson_ratio,
    }
}

fn body(poisson_ratio: f64, thickness: f64) -> ShearBody {
    ShearBody {
        material: material(poisson_ratio),
        layer: Some(ElasticLayer::new(thickness, poisson_ratio, LayerBase::Bonded).unwrap()),
    }
}

#[test]
fn coupling_compliance_matches_navier_integration() {
    // h against the shooting solution (G = k = 1): the normal displacement W(0) of a shear
    // wave, whose sign in the shooting's convention is the opposite of the operators'
    // (their h → +(1 − 2ν)/2 where the shooting gives −(1 − 2ν)/2). Tolerance 1e-8, as
    // for the factors of layer_shear.
    for poisson_ratio in [-0.3, 0.0, 0.3, 0.45] {
        for kt in [0.05, 0.3, 1.0, 2.5, 5.0] {
            let [_, normal] = surface_displacement(kt, poisson_ratio, LayerBase::Bonded, 4000, Load::Shear);
            let h = layer_coupling_compliance(kt, poisson_ratio);
            assert!(
                (h + normal).abs() < 1e-8 * normal.abs().max(1e-3),
                "ν = {poisson_ratio}, kt = {kt}: {h} vs {}",
                -normal
            );
        }
    }
    // The thin incompressible layer: h = −s²/2 (C_nt = t²k/(2G)); the half-space's at kt ≥ 25.
    let s = 1e-3;
    assert!((layer_coupling_compliance(s, 0.5) / (-0.5 * s * s) - 1.0).abs() < 4.0 * s * s);
    assert_eq!(layer_coupling_compliance(25.0, 0.3), 0.2);
}

#[test]
fn bessel_j1_over_x_matches_reference_values() {
    // J₁ from Abramowitz & Stegun's Table 9.1 (10 digits); tolerance 2e-10/x.
    for (x, j1) in [
        (1.0, 0.440_050_585_7),
        (5.0, -0.327_579_137_6),
        (10.0, 0.043_472_746_2),
        (15.0, 0.205_104_038_6),
        (20.0, 0.066_833_124_2),
    ] {
        let value = bessel_j1_over_x(x);
        assert!((value * x - j1).abs() < 2e-10, "J1({x}) = {} vs {j1}", value * x);
    }
    assert_eq!(bessel_j1_over_x(0.0), 0.5);
}

/// u_z under a unit traction along x on element `source`.
fn normal_response(operator: &mut CouplingOperator, source: usize) -> Vec<f64> {
    let len = operator.grid().len();
    let (mut qx, qy) = (vec![0.0; len], vec![0.0; len]);
    qx[source] = 1.0;
    let mut uz = vec![0.0; len];
    operator.normal_from_shear([&qx, &qy], &mut uz);
    uz
}

#[test]
fn free_coefficients_match_a_large_periodic_cell() {
    // The free grid's half-space coefficients plus the J₁-Hankel excess in real space
    // against the periodic alias sum of −i(Q_x/Q)h(Qt)/(GQ) on a 256² cell whose images lie
    // ≥ 46t away. K_zx is odd, so the periodic convention K̂(0) = 0 costs nothing.
    // Tolerance 2e-5 of the largest response at ν = 1/2, where h decays exponentially in
    // Q and the 40 aliases are exact; 2e-4 at ν < 1/2, where the half-space's part of the
    // multiplier decays as 1/Q and its truncation at 40 aliases is ≈ 1e-4 of the largest
    // coefficient (a nearest neighbour: K_zx has no diagonal). The half-space operator alone
    // disagrees by 1.2e-3 on these grids: its 1/r kernel's images, which the layer screens.
    let (n, cell) = (24, 256);
    let delta = 1.0 / cell as f64;
    for (thickness, poisson_ratio) in [(2.0, 0.5), (5.0, 0.3), (0.5, 0.5), (3.0, 0.0)] {
        let body = body(poisson_ratio, thickness * delta);
        let free_grid = Grid::new(n, n as f64 * delta, Boundary::Free).unwrap();
        let periodic_grid = Grid::new(cell, 1.0, Boundary::Periodic).unwrap();
        let mut free = CouplingOperator::for_body(free_grid, body).unwrap();
        let mut periodic = CouplingOperator::for_body(periodic_grid, body).unwrap();
        let (free_z, periodic_z) = (normal_response(&mut free, 0), normal_response(&mut periodic, 0));
        let scale = free_z.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
        let disagreement = |free: &[f64], periodic: &[f64]| {
            let mut worst: f64 = 0.0;
            for m in 0..n {
                for l in 0..n {
                    worst = worst.max((free[m * n + l] - periodic[m * cell + l]).abs() / scale);
                }
            }
            worst
        };
        let worst = disagreement(&free_z, &periodic_z);
        let mut half_free = CouplingOperator::new(free_grid, body.material).unwrap();
        let mut half_periodic = CouplingOperator::new(periodic_grid, body.material).unwrap();
        let half_space = disagreement(
            &normal_response(&mut half_free, 0),
            &normal_response(&mut half_periodic, 0),
        );
        println!(
            "t = {thickness}Δ, ν = {poisson_ratio}: free against periodic cell {worst:.1e} of max|K_zx| (half-space {half_space:.1e})"
        );
        let tolerance = if poisson_ratio == 0.5 { 2e-5 } else { 2e-4 };
        assert!(worst < tolerance, "t = {thickness}Δ, ν = {poisson_ratio}: {worst:e}");
    }
}

#[test]
fn thick_layer_couples_as_the_half_space() {
    // t = 1e6 L: the layer's excess on the grid is of order L/t (free, tolerance 1e-3 of
    // max|u|); on a periodic grid h is the half-space's at every alias (to rounding).
    let n = 32;
    let mut random = 0x2545_f491_4f6c_dd1du64;
    let mut field = || -> Vec<f64> { xorshift_field(&mut random, n * n).iter().map(|v| v - 0.5).collect() };
    let (qx, qy) = (field(), field());
    for (boundary, tolerance) in [(Boundary::Free, 1e-3), (Boundary::Periodic, 1e-12)] {
        let grid = Grid::new(n, 1.0, boundary).unwrap();
        let mut half_space = CouplingOperator::new(grid, material(0.3)).unwrap();
        let mut layered = CouplingOperator::for_body(grid, body(0.3, 1e6)).unwrap();
        let (mut expected, mut got) = (vec![0.0; n * n], vec![0.0; n * n]);
        half_space.normal_from_shear([&qx, &qy], &mut expected);
        layered.normal_from_shear([&qx, &qy], &mut got);
        let largest = expected.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
        let worst = expected.iter().zip(&got).fold(0.0f64, |a, (e, g)| a.max((e - g).abs()));
        println!(
            "{boundary:?}: t = 1e6 L against the half-space {:.1e} of max|u|",
            worst / largest
        );
        assert!(worst < tolerance * largest, "{boundary:?}: {worst:e} of {largest:e}");
    }
}

#[test]
fn layer_coupling_is_reciprocal() {
    // Betti: the work of a pressure on the normal displacement of shear tractions equals
    // the work of the tractions on the tangential displacement of the pressure,
    // ⟨p, K_zt q⟩ = ⟨q, K_tz p⟩, to 1e-12 (at ν = 1/2 too, where only a layer couples).
    let (nx, ny) = (12, 9);
    let grid = Grid::rectangular(nx, ny, 1.2, 0.63, Boundary::Free).unwrap();
    let mut random = 0x9e37_79b9_7f4a_7c15u64;
    let mut field = || lcg_field(&mut random, nx * ny);
    let (pressure, qx, qy) = (field(), field(), field());
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    for poisson_ratio in [0.5, 0.2] {
        let mut operator = CouplingOperator::for_body(grid, body(poisson_ratio, 0.15)).unwrap();
        let mut uz = vec![0.0; nx * ny];
        operator.normal_from_shear([&qx, &qy], &mut uz);
        let (mut ux, mut uy) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
        operator.shear_from_normal(&pressure, [&mut ux, &mut uy]);
        let forward = dot(&pressure, &uz);
        let backward = dot(&qx, &ux) + dot(&qy, &uy);
        assert!(
            (forward - backward).abs() < 1e-12 * forward.abs(),
            "{forward} vs {backward}"
        );
    }
}
