use super::*;
use crate::elastic::cerruti::ShearMaterial;
use crate::elastic::FreeOperator;
use crate::geometry::{Profile, Sphere};
use crate::grid::{Boundary, Grid};
use crate::material::ElasticMaterial;
use crate::solver::{NestedActiveSet, NestedParams};

/// A sphere of R = 1 pressed to depth d on a free n×n grid of side `size`, E* = 4, ν = 1/2
/// (G = 1): the normal state and the operators.
fn pressed_sphere(n: usize, size: f64, depth: f64) -> (Grid, ContactState, TangentialOperator) {
    let grid = Grid::new(n, size, Boundary::Free).unwrap();
    let material = ElasticMaterial::new(4.0).unwrap();
    let mut operator = FreeOperator::new(grid, material);
    let heights = Sphere::new(1.0).unwrap().heights(&grid);
    let mut state = ContactState::new(&grid);
    NestedActiveSet::new(grid, material, NestedParams::default())
        .solve(&mut operator, &heights, depth, &mut state)
        .unwrap();
    let tangential = TangentialOperator::new(grid, ShearMaterial::from_contact_modulus(4.0, 0.5)).unwrap();
    (grid, state, tangential)
}

#[test]
fn cattaneo_mindlin_stick_radius_and_compliance() {
    // a = √(Rd) = 32Δ. Cattaneo–Mindlin (Johnson 1985 §7.2), rigid sphere, ν = 1/2, G = 1:
    // c/a = (1 − Q/μP)^{1/3}, δ = 3μP(2 − ν)/(16Ga)·[1 − (1 − Q/μP)^{2/3}], with a and P
    // the discrete contact's (a from its area). Tolerance 2 % (the target at a/Δ ≥ 32: the
    // staircase edge of the contact and of the stick zone, ~1/(2·32) per radius, partly
    // cancels in the ratios); c/a is checked while the stick zone's radius spans ≥ 12
    // elements (below, the staircase error of a radius from an area grows as Δ/c).
    let delta_x = 1.0 / 256.0;
    let (grid, normal, mut operator) = pressed_sphere(80, 80.0 * delta_x, (32.0 * delta_x) * (32.0 * delta_x));
    let area = grid.element_area();
    let force_normal = normal.force(area);
    let contact = normal.contact_elements();
    let radius = (contact as f64 * area / std::f64::consts::PI).sqrt();
    let mu = 0.3;
    let full_slip_shift = 3.0 * mu * force_normal * 1.5 / (16.0 * radius);
    let mut solver = TangentialSolver::new(FrictionLaw::coulomb(mu).unwrap(), TangentialParams::default());
    let mut state = TangentialState::new(grid.len());
    let steps = 12;
    for step in 1..=steps {
        let shift = full_slip_shift * 1.1 * step as f64 / steps as f64;
        let report = solver.step(&mut operator, &normal, [shift, 0.0], &mut state).unwrap();
        let ratio = report.force[0] / (mu * force_normal);
        let stick_ratio = (report.stick_elements as f64 / contact as f64).sqrt();
        eprintln!(
            "step {step}: Q/μP {ratio:.5} c/a {stick_ratio:.4} vs {:.4}; rounds {} cg {} pairs {} {:?}",
            (1.0 - ratio.min(1.0)).cbrt(),
            report.rounds,
            report.cg_iterations,
            report.transform_pairs,
            report.complementarity
        );
        if shift < full_slip_shift {
            let expected_shift = full_slip_shift * (1.0 - (1.0 - ratio).powf(2.0 / 3.0));
            assert!(
                (shift / expected_shift - 1.0).abs() < 0.02,
                "step {step}: δ {shift} vs Cattaneo–Mindlin {expected_shift}"
            );
            let expected_stick = (1.0 - ratio).cbrt();
            if expected_stick * radius >= 12.0 * delta_x {
                assert!(
                    (stick_ratio / expected_stick - 1.0).abs() < 0.02,
                    "step {step}: c/a {stick_ratio} vs {expected_stick}"
                );
            }
        } else {
            assert_eq!(report.stick_elements, 0, "step {step}: full slip beyond δ*");
        }
        let c = report.complementarity;
        assert!(c.stick_residual < 1e-8 && c.bound_excess < 1e-12, "{c:?}");
        assert!(c.slip_misalignment < 1e-6 && c.backward_slip < 1e-8, "{c:?}");
        assert_eq!(report.stick_elements + report.slip_elements, contact);
    }
    // In gross slip the tractions keep a memory of the last stick zone's sideways
    // relaxation (Q/μP = 0.9994 at 1.1δ*); a long slide of 20δ* aligns them with the shift:
    // their residual angle falls with the ratio of the relaxed displacement (≲ δ*) to the
    // slide, so Q/μP is 1 to ~1e-6.
    let report = solver
        .step(&mut operator, &normal, [full_slip_shift * 21.0, 0.0], &mut state)
        .unwrap();
    let ratio = report.force[0] / (mu * force_normal);
    assert!((ratio - 1.0).abs() < 1e-5, "gross slip at μP: {ratio}");
}

#[test]
fn shear_strength_slides_at_tau0_times_area() {
    // Gross sliding under a constant shear strength: F_T = τ0·A exactly (to the solver's
    // tolerance), tensile elements included.
    let delta_x = 1.0 / 128.0;
    let (grid, normal, mut operator) = pressed_sphere(48, 48.0 * delta_x, (16.0 * delta_x) * (16.0 * delta_x));
    let tau0 = 0.01;
    let mut solver = TangentialSolver::new(FrictionLaw::shear_strength(tau0).unwrap(), TangentialParams::default());
    let mut state = TangentialState::new(grid.len());
    let mut last = TangentialReport::default();
    for step in 1..=8 {
        last = solver
            .step(&mut operator, &normal, [0.002 * step as f64, 0.0], &mut state)
            .unwrap();
    }
    let expected = tau0 * normal.contact_elements() as f64 * grid.element_area();
    assert!(
        (last.force[0] / expected - 1.0).abs() < 1e-12,
        "{} vs {expected}",
        last.force[0]
    );
    assert!(last.force[1].abs() < 1e-12 * expected);
    assert_eq!(last.stick_elements, 0);
}

#[test]
fn reversal_after_gross_slip_settles() {
    // A stroke reversal after gross slip: every slipping traction must turn over (the
    // Mindlin–Deresiewicz unloading); the rounds must settle and the optimality hold.
    let delta_x = 1.0 / 128.0;
    let (grid, normal, mut operator) = pressed_sphere(48, 48.0 * delta_x, (16.0 * delta_x) * (16.0 * delta_x));
    let tau0 = 0.01;
    let mut solver = TangentialSolver::new(FrictionLaw::shear_strength(tau0).unwrap(), TangentialParams::default());
    let mut state = TangentialState::new(grid.len());
    for step in 1..=8 {
        solver
            .step(&mut operator, &normal, [0.002 * step as f64, 0.0], &mut state)
            .unwrap();
    }
    for step in (0..8).rev() {
        let report = solver
            .step(&mut operator, &normal, [0.002 * step as f64, 0.0], &mut state)
            .unwrap_or_else(|e| panic!("back to {step}: {e}"));
        let c = report.complementarity;
        assert!(
            c.stick_residual < 1e-8 && c.slip_misalignment < 1e-6 && c.backward_slip < 1e-8,
            "{c:?}"
        );
    }
}
