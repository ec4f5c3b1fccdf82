use super::*;
use crate::elastic::cerruti::ShearMaterial;
use crate::elastic::TangentialOperator;
use crate::grid::{Boundary, Grid};
use crate::solver::tangential::{FrictionLaw, TangentialParams, TangentialState};

/// τk and τs of the tests: a static shear strength three times the kinetic one.
const KINETIC: f64 = 0.05;
const STATIC: f64 = 0.15;

/// A disc of radius 1/4 in contact at the centre of a free n×n grid of unit side, under
/// unit pressure, and the operator (G = 1, ν = 1/2).
fn pressed_disc(n: usize) -> (Grid, ContactState, TangentialOperator) {
    let grid = Grid::new(n, 1.0, Boundary::Free).unwrap();
    let mut normal = ContactState::new(&grid);
    for k in 0..grid.len() {
        let (x, y) = grid.centre(k);
        if x.hypot(y) < 0.25 {
            normal.contact[k] = true;
            normal.pressure[k] = 1.0;
        }
    }
    let operator = TangentialOperator::new(grid, ShearMaterial::from_contact_modulus(4.0, 0.5)).unwrap();
    (grid, normal, operator)
}

/// The force of each step of a rigid shift of the disc on n² to 0.04 in 80 steps, over
/// τk·A, under τk with a static τs, weakened over `distance` when given.
fn shift_forces(n: usize, distance: Option<f64>) -> Vec<f64> {
    let (grid, normal, mut operator) = pressed_disc(n);
    let area = normal.contact_elements() as f64 * grid.element_area();
    let mut solver = TangentialSolver::new(
        FrictionLaw::shear_strength(KINETIC).unwrap(),
        TangentialParams::default(),
    )
    .with_static_law(FrictionLaw::shear_strength(STATIC).unwrap())
    .unwrap();
    if let Some(distance) = distance {
        solver = solver.with_slip_weakening(distance).unwrap();
        assert_eq!(solver.slip_weakening_distance(), Some(distance));
    }
    let mut state = TangentialState::new(grid.len());
    (1..=80)
        .map(|step| {
            let shift = 5e-4 * step as f64;
            let report = solver
                .step(&mut operator, &normal, [shift, 0.0], &mut state)
                .unwrap_or_else(|e| panic!("n = {n}, D_c = {distance:?}, step {step}: {e}"));
            // The stick residual carries the last turns of slip tractions below the 1e-6
            // direction tolerance.
            let c = report.complementarity;
            assert!(c.stick_residual < 1e-6 && c.bound_excess < 1e-12, "step {step}: {c:?}");
            assert_eq!(state.slip_since_stuck.is_empty(), distance.is_none());
            report.force[0] / (KINETIC * area)
        })
        .collect()
}

fn peak(forces: &[f64]) -> f64 {
    forces.iter().copied().fold(0.0, f64::max)
}

#[test]
fn slip_weakening_makes_the_peak_independent_of_the_mesh() {
    // A flat disc (a = 8Δ and 16Δ) shifted under τk with τs = 3τk. The static law drops an
    // element's bound at its first slip, and the stuck traction is singular at the edge, so
    // the edge element's load, and with it the peak, falls with Δ: 1.91 and 1.61 τk·A (a
    // further 1.40 at 32Δ). Weakened over D_c = 0.004 (Palmer & Rice's zone, about
    // (9π/32)·2G·D_c/(τs − τk) = 0.071, spans 2.3 and 4.5Δ), the break costs an energy and
    // the peak moves by 1.1 % (2.435, 2.408; 2.389 at 32Δ). Asserted: the static law's
    // peaks more than 10 % apart, the weakened ones within 2 %, and higher than the static
    // law's (the broken elements still hold more than τk).
    let static_peaks = [32, 64].map(|n| peak(&shift_forces(n, None)));
    let weakened_peaks = [32, 64].map(|n| peak(&shift_forces(n, Some(0.004))));
    assert!(static_peaks[0] / static_peaks[1] > 1.1, "static law: {static_peaks:?}");
    assert!(
        (weakened_peaks[0] / weakened_peaks[1] - 1.0).abs() < 0.02,
        "weakened: {weakened_peaks:?}"
    );
    assert!(
        weakened_peaks[1] > static_peaks[1],
        "{weakened_peaks:?} vs {static_peaks:?}"
    );
    assert!(weakened_peaks.iter().all(|&p| p < STATIC / KINETIC));
}

#[test]
#[ignore = "two 128² discs (about a minute): cargo test --release -p adhesim --lib weakening -- --ignored"]
fn slip_weakening_peak_holds_at_a_finer_mesh() {
    // The disc of `slip_weakening_makes_the_peak_independent_of_the_mesh` at a = 32Δ (the
    // zone 9Δ): the weakened peak within 2 % of the 16Δ one (2.389 against 2.408), the
    // static law's another 10 % lower (1.399 against 1.613).
    let weakened = [64, 128].map(|n| peak(&shift_forces(n, Some(0.004))));
    let static_peaks = [64, 128].map(|n| peak(&shift_forces(n, None)));
    assert!((weakened[1] / weakened[0] - 1.0).abs() < 0.02, "{weakened:?}");
    assert!(static_peaks[0] / static_peaks[1] > 1.1, "{static_peaks:?}");
}

#[test]
fn a_vanishing_weakening_distance_is_the_static_law() {
    // D_c = 1e-12, below any slip a breaking element is estimated to make: its bound falls
    // to τk as it breaks, where the static law drops it, in the rounds and in the
    // predictor alike. Every step's force is the static law's, bit for bit, through the
    // slip events of the 80 steps.
    let static_forces = shift_forces(32, None);
    let weakened = shift_forces(32, Some(1e-12));
    assert!(static_forces.windows(2).any(|pair| pair[1] < pair[0]), "no slip event");
    assert_eq!(static_forces, weakened);
}

#[test]
fn slip_weakening_needs_a_static_law_and_a_positive_distance() {
    let kinetic = || {
        TangentialSolver::new(
            FrictionLaw::shear_strength(KINETIC).unwrap(),
            TangentialParams::default(),
        )
    };
    assert!(matches!(
        kinetic().with_slip_weakening(0.01),
        Err(FrictionLawError::WeakeningWithoutStaticLaw(_))
    ));
    let with_static = || {
        kinetic()
            .with_static_law(FrictionLaw::shear_strength(STATIC).unwrap())
            .unwrap()
    };
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            with_static().with_slip_weakening(bad),
            Err(FrictionLawError::WeakeningDistance(_))
        ));
    }
    assert_eq!(weakened_bound(3.0, 1.0, 0.5, 2.0), 2.5);
    assert_eq!(weakened_bound(3.0, 1.0, 4.0, 2.0), 1.0);
}
