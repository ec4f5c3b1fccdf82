use super::super::influence::rectangle_quadrature;
use super::*;
use std::f64::consts::PI;

const STEEL_LIKE: ShearMaterial = ShearMaterial {
    shear_modulus: 0.8,
    poisson_ratio: 0.3,
};

/// c·(x, y)/r²: the point force's normal displacement per unit Q_x and Q_y.
fn point(x: f64, y: f64, material: ShearMaterial) -> (f64, f64) {
    let c = (1.0 - 2.0 * material.poisson_ratio) / (4.0 * PI * material.shear_modulus);
    let squared = x * x + y * y;
    (c * x / squared, c * y / squared)
}

#[test]
fn element_coefficients_are_the_integrated_point_force() {
    // Gauss quadrature of the point kernel over elements whose centre is at least one
    // element from the field point (smooth integrand): 1e-10 of the coefficient.
    let (dx, dy) = (0.5, 0.3);
    for (xi, eta) in [
        (0.5, 0.0),
        (0.0, 0.3),
        (0.5, 0.3),
        (-1.5, 0.6),
        (2.0, -2.1),
        (-0.5, -0.9),
    ] {
        let (zx, zy) = coupling_rectangle(xi, eta, dx, dy, STEEL_LIKE);
        let quadrature = |component: usize| {
            rectangle_quadrature(dx, dy, 16, |x, y| {
                let (px, py) = point(xi - x, eta - y, STEEL_LIKE);
                [px, py][component]
            })
        };
        for (value, reference) in [(zx, quadrature(0)), (zy, quadrature(1))] {
            assert!(
                (value - reference).abs() <= 1e-10 * reference.abs().max(1e-3 * dx),
                "({xi}, {eta}): {value} vs {reference}"
            );
        }
    }
    // Odd: nothing on the element itself, and the far field is the point force's (1e-4 at
    // a hundred elements, the element's second moment over r²).
    assert_eq!(coupling_rectangle(0.0, 0.0, dx, dy, STEEL_LIKE), (0.0, 0.0));
    let (xi, eta) = (100.0 * dx, 37.0 * dy);
    let (zx, zy) = coupling_rectangle(xi, eta, dx, dy, STEEL_LIKE);
    let (px, py) = point(xi, eta, STEEL_LIKE);
    assert!((zx / (px * dx * dy) - 1.0).abs() < 1e-4, "{zx} vs {}", px * dx * dy);
    assert!((zy / (py * dx * dy) - 1.0).abs() < 1e-4, "{zy} vs {}", py * dx * dy);
}

/// Fields of some variety on `n` elements.
fn fields(n: usize) -> [Vec<f64>; 3] {
    [
        (0..n).map(|k| ((k * 37 % 11) as f64 - 4.0) / 7.0).collect(),
        (0..n).map(|k| ((k * 53 % 13) as f64 - 6.0) / 9.0).collect(),
        (0..n).map(|k| ((k * 29 % 17) as f64 - 5.0) / 3.0).collect(),
    ]
}

#[test]
fn free_convolution_equals_the_direct_sum() {
    // DC-FFT is exact up to round-off: 1e-12 of the largest displacement.
    let grid = Grid::rectangular(12, 9, 1.2, 0.72, Boundary::Free).unwrap();
    let n = grid.len();
    let [qx, qy, p] = fields(n);
    let mut operator = CouplingOperator::new(grid, STEEL_LIKE).unwrap();
    let mut normal = vec![0.0; n];
    operator.normal_from_shear([&qx, &qy], &mut normal);
    let (mut ux, mut uy) = (vec![0.0; n], vec![0.0; n]);
    operator.shear_from_normal(&p, [&mut ux, &mut uy]);
    let (mut direct_normal, mut direct_x, mut direct_y) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    for target in 0..n {
        let (x, y) = grid.centre(target);
        for source in 0..n {
            let (xs, ys) = grid.centre(source);
            let (zx, zy) = coupling_rectangle(x - xs, y - ys, grid.dx(), grid.dy(), STEEL_LIKE);
            direct_normal[target] += zx * qx[source] + zy * qy[source];
            direct_x[target] -= zx * p[source];
            direct_y[target] -= zy * p[source];
        }
    }
    for (computed, direct) in [(&normal, &direct_normal), (&ux, &direct_x), (&uy, &direct_y)] {
        let scale = direct.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(scale > 0.0);
        for k in 0..n {
            assert!(
                (computed[k] - direct[k]).abs() < 1e-12 * scale,
                "{k}: {} vs {}",
                computed[k],
                direct[k]
            );
        }
    }
    assert_eq!(operator.transform_pairs(), 4);
}

#[test]
fn the_coupled_operator_is_symmetric_and_draws_the_surface_in() {
    // Betti: ⟨p, K_zt q⟩ = ⟨q, K_tz p⟩ (the two halves of a symmetric 3×3 operator) on both
    // boundaries, to rounding.
    for boundary in [Boundary::Free, Boundary::Periodic] {
        let grid = Grid::rectangular(16, 12, 1.0, 0.9, boundary).unwrap();
        let n = grid.len();
        let [qx, qy, p] = fields(n);
        let mut operator = CouplingOperator::new(grid, STEEL_LIKE).unwrap();
        let mut normal = vec![0.0; n];
        operator.normal_from_shear([&qx, &qy], &mut normal);
        let (mut ux, mut uy) = (vec![0.0; n], vec![0.0; n]);
        operator.shear_from_normal(&p, [&mut ux, &mut uy]);
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(a, b)| a * b).sum::<f64>();
        let left = dot(&p, &normal);
        let right = dot(&qx, &ux) + dot(&qy, &uy);
        assert!(
            (left - right).abs() < 1e-12 * left.abs().max(right.abs()),
            "{boundary:?}: {left} vs {right}"
        );
        // A pressure on one element pulls the surface towards it (Boussinesq): its right
        // neighbour moves along −x, its upper neighbour along −y.
        let centre = (grid.ny() / 2) * grid.nx() + grid.nx() / 2;
        let mut single = vec![0.0; n];
        single[centre] = 1.0;
        operator.shear_from_normal(&single, [&mut ux, &mut uy]);
        assert!(ux[centre + 1] < 0.0 && ux[centre - 1] > 0.0, "{boundary:?}");
        assert!(
            uy[centre + grid.nx()] < 0.0 && uy[centre - grid.nx()] > 0.0,
            "{boundary:?}"
        );
    }
}

#[test]
fn periodic_near_field_is_the_free_one_and_incompressible_decouples() {
    // A unit traction q_x on one element of an n² grid with Δx ≠ Δy. The periodic normal
    // displacement around it differs from the free one by the images' share, whose
    // gradient near the element is of order (Δ/L)² of the near field's: the differences
    // across the element (u at +offset less u at −offset) must agree within 1e-3 of the
    // nearest one's at n = 128 (measured 4.5e-5 to 7.5e-4 for offsets up to 5Δ), and the
    // disagreement must fall at least 3-fold from n = 64 to 128 (the images' share
    // quarters; measured 3.6–11).
    let disagreement = |n: usize| -> Vec<f64> {
        let response = |boundary| {
            let grid = Grid::rectangular(n, n, 1.0, 0.75, boundary).unwrap();
            let mut operator = CouplingOperator::new(grid, STEEL_LIKE).unwrap();
            let centre = (n / 2) * n + n / 2;
            let (mut qx, qy) = (vec![0.0; n * n], vec![0.0; n * n]);
            qx[centre] = 1.0;
            let mut normal = vec![0.0; n * n];
            operator.normal_from_shear([&qx, &qy], &mut normal);
            (normal, centre)
        };
        let (free, centre) = response(Boundary::Free);
        let (periodic, _) = response(Boundary::Periodic);
        let scale = free[centre + 1] - free[centre - 1];
        assert!(scale > 0.0, "the surface ahead of the traction sinks: {scale}");
        [1, 2, 5, n + 1, 2 * n + 3]
            .iter()
            .map(|&offset| {
                let free_difference = free[centre + offset] - free[centre - offset];
                let periodic_difference = periodic[centre + offset] - periodic[centre - offset];
                (free_difference - periodic_difference).abs() / scale
            })
            .collect()
    };
    let (coarse, fine) = (disagreement(64), disagreement(128));
    for (k, (coarse, fine)) in coarse.iter().zip(&fine).enumerate() {
        assert!(*fine < 1e-3, "offset {k}: {fine:e} of the near field");
        assert!(
            *fine < coarse / 3.0,
            "offset {k}: {coarse:e} at n = 64, {fine:e} at 128"
        );
    }
    // ν = 1/2: no coupling at all.
    let rubber = ShearMaterial::from_contact_modulus(4.0, 0.5);
    let grid = Grid::new(16, 1.0, Boundary::Free).unwrap();
    let mut operator = CouplingOperator::new(grid, rubber).unwrap();
    let [qx, qy, _] = fields(grid.len());
    let mut normal = vec![1.0; grid.len()];
    operator.normal_from_shear([&qx, &qy], &mut normal);
    assert!(normal.iter().all(|&u| u == 0.0));
}
