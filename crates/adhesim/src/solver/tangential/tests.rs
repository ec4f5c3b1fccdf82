use super::*;
use crate::elastic::cerruti::ShearMaterial;
use crate::elastic::{FreeOperator, TangentialOperator};
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

/// The Cattaneo–Mindlin sphere of the tests below: a = 32Δ on 80² (Δ = 1/256), μ = 0.3.
pub(super) struct MindlinSphere {
    pub(super) grid: Grid,
    pub(super) normal: ContactState,
    pub(super) operator: TangentialOperator,
    /// P.
    pub(super) force_normal: f64,
    /// Elements in contact.
    pub(super) contact: usize,
    /// a from the contact's area.
    pub(super) radius: f64,
    /// δ* = 3μP(2 − ν)/(16Ga).
    pub(super) full_slip_shift: f64,
}

const MINDLIN_ELEMENT: f64 = 1.0 / 256.0;
pub(super) const MINDLIN_MU: f64 = 0.3;

pub(super) fn mindlin_sphere() -> MindlinSphere {
    let delta_x = MINDLIN_ELEMENT;
    let (grid, normal, operator) = pressed_sphere(80, 80.0 * delta_x, (32.0 * delta_x) * (32.0 * delta_x));
    let area = grid.element_area();
    let force_normal = normal.force(area);
    let contact = normal.contact_elements();
    let radius = (contact as f64 * area / std::f64::consts::PI).sqrt();
    let full_slip_shift = 3.0 * MINDLIN_MU * force_normal * 1.5 / (16.0 * radius);
    MindlinSphere {
        grid,
        normal,
        operator,
        force_normal,
        contact,
        radius,
        full_slip_shift,
    }
}

#[test]
fn cattaneo_mindlin_stick_radius_and_compliance() {
    // a = √(Rd) = 32Δ. Cattaneo–Mindlin (Johnson 1985 §7.2), rigid sphere, ν = 1/2, G = 1:
    // c/a = (1 − Q/μP)^{1/3}, δ = 3μP(2 − ν)/(16Ga)·[1 − (1 − Q/μP)^{2/3}], with a and P
    // the discrete contact's (a from its area). Tolerance 2 % (the target at a/Δ ≥ 32: the
    // staircase edge of the contact and of the stick zone, ~1/(2·32) per radius, partly
    // cancels in the ratios); c/a is checked while the stick zone's radius spans ≥ 12
    // elements (below, the staircase error of a radius from an area grows as Δ/c).
    let MindlinSphere {
        grid,
        normal,
        mut operator,
        force_normal,
        contact,
        radius,
        full_slip_shift,
    } = mindlin_sphere();
    let (delta_x, mu) = (MINDLIN_ELEMENT, MINDLIN_MU);
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

/// Shear strength with a static value twice the kinetic one on a pressed sphere, shifted
/// into gross sliding, against the kinetic law alone: at every step the static law holds
/// at least as many elements stuck and at least the kinetic law's force (a stuck element
/// holds up to τs before it breaks loose), strictly more stuck at some step; no step
/// exceeds τs·A; both slide at exactly τk·A (every element at its kinetic bound; 1e-9, the
/// tractions' rounding). A static law equal to the kinetic one gives the kinetic law's bits.
#[test]
fn a_static_shear_strength_delays_slip_and_slides_at_the_kinetic_bound() {
    let delta_x = 1.0 / 128.0;
    let (grid, normal, mut operator) = pressed_sphere(48, 48.0 * delta_x, (16.0 * delta_x) * (16.0 * delta_x));
    let area = grid.element_area();
    let contact_area = normal.contact_elements() as f64 * area;
    let (kinetic, stuck) = (1e-2, 2e-2);
    let law = FrictionLaw::shear_strength(kinetic).unwrap();
    let mut run = |solver: &mut TangentialSolver| -> Vec<(f64, usize, bool)> {
        let mut state = TangentialState::new(grid.len());
        (1..=40)
            .map(|step| {
                let shift = 4e-3 * step as f64 / 40.0;
                let report = solver.step(&mut operator, &normal, [shift, 0.0], &mut state).unwrap();
                assert!(
                    report.complementarity.bound_excess < 1e-9,
                    "{:?}",
                    report.complementarity
                );
                (report.force[0], report.stick_elements, report.slip_event)
            })
            .collect()
    };
    let with_static = run(&mut TangentialSolver::new(law, TangentialParams::default())
        .with_static_law(FrictionLaw::shear_strength(stuck).unwrap())
        .unwrap());
    let plain = run(&mut TangentialSolver::new(law, TangentialParams::default()));
    // Up to the first slip event the static law holds more at every step.
    let first_event = with_static.iter().position(|s| s.2).expect("a slip event");
    for (step, (s, k)) in with_static.iter().zip(&plain).enumerate().take(first_event + 1) {
        assert!(
            s.1 >= k.1 && s.0 >= k.0 * (1.0 - 1e-9),
            "step {step}: static {s:?}, kinetic {k:?}"
        );
    }
    assert!(with_static.iter().zip(&plain).any(|(s, k)| s.1 > k.1));
    // Each event: the force falls, the whole contact slides at the kinetic bound, and the
    // contact comes to rest; the next step sticks again and the force rises.
    let sliding = kinetic * contact_area;
    for (step, s) in with_static.iter().enumerate() {
        assert!(s.0 <= stuck * contact_area * (1.0 + 1e-9));
        if s.2 {
            assert!(s.0 < with_static[step - 1].0 && s.1 == 0, "step {step}: {s:?}");
            assert!(
                s.0 <= sliding * (1.0 + 1e-9) && s.0 > 0.99 * sliding,
                "step {step}: {s:?}"
            );
            if let Some(next) = with_static.get(step + 1) {
                assert!(next.0 > s.0 && !next.2, "step {}: {next:?}", step + 1);
            }
        }
    }
    let last_event = with_static.iter().rposition(|s| s.2).unwrap();
    assert!((with_static[last_event].0 / sliding - 1.0).abs() < 1e-9);
    let end = plain.last().unwrap();
    assert!(plain.iter().all(|k| !k.2));
    assert_eq!(end.1, 0, "gross sliding at the end");
    assert!((end.0 / sliding - 1.0).abs() < 1e-9);
    let same = run(&mut TangentialSolver::new(law, TangentialParams::default())
        .with_static_law(law)
        .unwrap());
    assert_eq!(format!("{plain:?}"), format!("{same:?}"));
}

#[test]
fn a_static_law_below_or_unlike_the_kinetic_one_is_refused() {
    let kinetic = FrictionLaw::coulomb(0.3).unwrap();
    let solver = || TangentialSolver::new(kinetic, TangentialParams::default());
    assert!(solver().with_static_law(FrictionLaw::coulomb(0.2).unwrap()).is_err());
    assert!(solver()
        .with_static_law(FrictionLaw::shear_strength(1.0).unwrap())
        .is_err());
    assert!(solver().with_static_law(FrictionLaw::NoSlip).is_err());
    let accepted = solver().with_static_law(FrictionLaw::coulomb(0.5).unwrap()).unwrap();
    assert_eq!(accepted.static_law(), Some(FrictionLaw::coulomb(0.5).unwrap()));
}

/// A disc of `radius` elements in contact at the centre of a free n×n grid of unit
/// side, under unit pressure, and the operator (G = 1, ν = 1/2).
fn pressed_disc(n: usize, radius: f64) -> (Grid, ContactState, TangentialOperator) {
    let grid = Grid::new(n, 1.0, Boundary::Free).unwrap();
    let mut normal = ContactState::new(&grid);
    for k in 0..grid.len() {
        let (x, y) = grid.centre(k);
        if x.hypot(y) < radius * grid.dx() {
            normal.contact[k] = true;
            normal.pressure[k] = 1.0;
        }
    }
    let operator = TangentialOperator::new(grid, ShearMaterial::from_contact_modulus(4.0, 0.5)).unwrap();
    (grid, normal, operator)
}

#[test]
fn a_compliant_drive_is_a_spring_in_series_with_the_contact() {
    // A glued contact is linear: F = K_c·δ. Pulled through a spring k by a drive at X, the
    // indenter stops at δ = X·k/(k + K_c), the two springs in series. Tolerance 1e-8: the
    // CG solves to 1e-10 of the target, and K_c comes from a second such solve.
    let (grid, normal, mut operator) = pressed_disc(32, 8.0);
    let rigid_shift = 1e-3;
    let mut rigid = TangentialSolver::new(FrictionLaw::NoSlip, TangentialParams::default());
    let report = rigid
        .step(
            &mut operator,
            &normal,
            [rigid_shift, 0.0],
            &mut TangentialState::new(grid.len()),
        )
        .unwrap();
    let contact_stiffness = report.force[0] / rigid_shift;
    assert_eq!(report.shift, [rigid_shift, 0.0]);
    for ratio in [0.1, 1.0, 10.0] {
        let stiffness = ratio * contact_stiffness;
        let mut solver = TangentialSolver::new(FrictionLaw::NoSlip, TangentialParams::default())
            .with_drive_stiffness(stiffness)
            .unwrap();
        let mut state = TangentialState::new(grid.len());
        for step in 1..=3 {
            let drive = 1e-3 * step as f64;
            let report = solver.step(&mut operator, &normal, [drive, 0.0], &mut state).unwrap();
            let expected = drive * stiffness / (stiffness + contact_stiffness);
            assert!(
                (report.shift[0] / expected - 1.0).abs() < 1e-8,
                "k/K_c = {ratio}, X = {drive}: δ {} vs {expected}",
                report.shift[0]
            );
            assert!((report.force[0] / (stiffness * (drive - report.shift[0])) - 1.0).abs() < 1e-12);
            assert!(report.shift[1].abs() < 1e-12 * expected && !report.slip_event);
            assert_eq!((state.shift, state.drive), (report.shift, [drive, 0.0]));
        }
    }
}

#[test]
fn a_static_shear_strength_under_a_compliant_drive_sticks_and_slips() {
    // A flat contact under a shear strength τk with a static τs = 3τk, pulled through a
    // spring as stiff as the contact. Stick: the force rises with the drive at the series
    // stiffness kK_c/(k + K_c) (exact while every element sticks: the step is linear). A
    // slip event: the contact breaks loose, the force falls to the kinetic τk·A (every
    // element slides at τk) and the indenter jumps ahead. The
    // contact then rests and sticks again, so the events repeat: a sawtooth.
    let (grid, normal, mut operator) = pressed_disc(32, 8.0);
    let contact_area = normal.contact_elements() as f64 * grid.element_area();
    let (kinetic, stuck) = (0.05, 0.15);
    let mut rigid = TangentialSolver::new(FrictionLaw::NoSlip, TangentialParams::default());
    let contact_stiffness = rigid
        .step(
            &mut operator,
            &normal,
            [1e-3, 0.0],
            &mut TangentialState::new(grid.len()),
        )
        .unwrap()
        .force[0]
        / 1e-3;
    let stiffness = contact_stiffness;
    let series = stiffness * contact_stiffness / (stiffness + contact_stiffness);
    let mut solver = TangentialSolver::new(
        FrictionLaw::shear_strength(kinetic).unwrap(),
        TangentialParams::default(),
    )
    .with_static_law(FrictionLaw::shear_strength(stuck).unwrap())
    .unwrap()
    .with_drive_stiffness(stiffness)
    .unwrap();
    let mut state = TangentialState::new(grid.len());
    let drive_step = 2e-3;
    let (mut events, mut last_force, mut last_shift, mut resting) = (0, 0.0, 0.0, false);
    for step in 1..=60 {
        let drive = drive_step * step as f64;
        let report = solver.step(&mut operator, &normal, [drive, 0.0], &mut state).unwrap();
        let force = report.force[0];
        let c = report.complementarity;
        assert!(c.stick_residual < 1e-8 && c.bound_excess < 1e-12, "step {step}: {c:?}");
        assert!(force <= stuck * contact_area * (1.0 + 1e-9), "step {step}: above τs·A");
        if report.slip_event {
            events += 1;
            assert!(force < last_force, "step {step}: an event drops the force");
            assert_eq!(report.stick_elements, 0, "step {step}: the whole contact slides");
            // Every traction at τk; the directions keep some of the stuck tractions'
            // sideways part (as Cattaneo–Mindlin's gross slip), so F is just below τk·A.
            let ratio = force / (kinetic * contact_area);
            assert!(ratio <= 1.0 + 1e-9 && ratio > 0.999, "step {step}: F/τkA {ratio}");
            assert!(
                report.shift[0] - last_shift > drive_step,
                "step {step}: the indenter jumps"
            );
        }
        if resting && report.slip_elements == 0 {
            let slope = (force - last_force) / drive_step;
            assert!(
                (slope / series - 1.0).abs() < 1e-8,
                "step {step}: stick slope {slope} vs {series}"
            );
        }
        assert_eq!(state.at_rest, report.slip_event);
        (last_force, last_shift, resting) = (force, report.shift[0], report.slip_event);
    }
    assert!(events >= 3, "{events} slip events: no sawtooth");
}

#[test]
fn an_imposed_force_follows_cattaneo_mindlin_and_mindlin_deresiewicz() {
    // The sphere of `cattaneo_mindlin_stick_radius_and_compliance` (a = 32Δ, ν = 1/2, G = 1,
    // μ = 0.3) under an imposed force: Q/μP = 0.1 … 0.8, then unloaded to −0.4.
    // Loading: δ = δ*[1 − (1 − Q/μP)^{2/3}] and c/a = (1 − Q/μP)^{1/3} (Cattaneo–Mindlin).
    // Unloading from Q*: δ = δ*[2(1 − (Q* − Q)/(2μP))^{2/3} − (1 − Q*/μP)^{2/3} − 1]
    // (Mindlin & Deresiewicz 1953; Johnson 1985 §7.4). Tolerance 2 %, as the displacement-
    // controlled test (the staircase edges). The force is met to 1e-8 relative (the search's
    // tolerance), and a displacement-controlled solver driven through the shifts found
    // gives the same forces to 1e-7 (each step is one from the same state).
    let MindlinSphere {
        grid,
        normal,
        mut operator,
        force_normal,
        contact,
        radius,
        full_slip_shift,
    } = mindlin_sphere();
    let (delta_x, mu) = (MINDLIN_ELEMENT, MINDLIN_MU);
    let limit = mu * force_normal;
    let law = FrictionLaw::coulomb(mu).unwrap();
    let mut solver = TangentialSolver::new(law, TangentialParams::default());
    let mut twin = TangentialSolver::new(law, TangentialParams::default());
    let (mut state, mut twin_state) = (TangentialState::new(grid.len()), TangentialState::new(grid.len()));
    let peak = 0.8;
    let path = (1..=8)
        .map(|k| 0.1 * k as f64)
        .chain((1..=6).map(|k| peak - 0.2 * k as f64));
    let mut trials = 0;
    for (step, ratio) in path.enumerate() {
        let report = solver
            .step_to_force(&mut operator, &normal, [1.0, 0.0], ratio * limit, &mut state)
            .unwrap();
        trials += report.trials;
        assert_eq!(report.trials, 1, "step {step} fell back to trials");
        assert!(
            (report.force[0] - ratio * limit).abs() <= 1e-8 * limit,
            "step {step}: force {} vs {}",
            report.force[0],
            ratio * limit
        );
        let shift = report.shift[0];
        assert_eq!(report.shift[1], 0.0);
        let expected = if step < 8 {
            full_slip_shift * (1.0 - (1.0 - ratio).powf(2.0 / 3.0))
        } else {
            let unloaded = (peak - ratio) / 2.0;
            full_slip_shift * (2.0 * (1.0 - unloaded).powf(2.0 / 3.0) - (1.0 - peak).powf(2.0 / 3.0) - 1.0)
        };
        eprintln!(
            "step {step}: Q/μP {ratio:.2} δ/δ* {:.5} vs {:.5}; trials {} pairs {}",
            shift / full_slip_shift,
            expected / full_slip_shift,
            report.trials,
            report.transform_pairs
        );
        if expected.abs() > 0.05 * full_slip_shift {
            assert!(
                (shift / expected - 1.0).abs() < 0.02,
                "step {step}: δ {shift} vs {expected}"
            );
        }
        if step < 8 && (1.0 - ratio).cbrt() * radius >= 12.0 * delta_x {
            let stick_ratio = (report.stick_elements as f64 / contact as f64).sqrt();
            assert!(
                ((stick_ratio / (1.0 - ratio).cbrt()) - 1.0).abs() < 0.02,
                "step {step}: c/a {stick_ratio}"
            );
        }
        let twin_report = twin
            .step(&mut operator, &normal, report.shift, &mut twin_state)
            .unwrap();
        assert!(
            (twin_report.force[0] - report.force[0]).abs() <= 1e-7 * limit,
            "step {step}: the displacement-controlled twin's force {} vs {}",
            twin_report.force[0],
            report.force[0]
        );
    }
    assert_eq!(trials, 14, "{trials} solves for 14 steps");
    // At and beyond what the interface holds no shift carries the force.
    for ratio in [1.0, -1.0, 1.5] {
        let beyond = solver.step_to_force(&mut operator, &normal, [1.0, 0.0], ratio * limit, &mut state);
        assert!(
            matches!(beyond, Err(TangentialError::ForceBeyondCapacity { .. })),
            "{beyond:?}"
        );
    }
    let with_static = TangentialSolver::new(law, TangentialParams::default())
        .with_static_law(FrictionLaw::coulomb(0.4).unwrap())
        .unwrap()
        .step_to_force(
            &mut operator,
            &normal,
            [1.0, 0.0],
            0.1 * limit,
            &mut TangentialState::new(grid.len()),
        );
    assert_eq!(with_static.unwrap_err(), TangentialError::ForceControlUnsupported);
}

#[test]
fn a_slide_advanced_by_less_than_the_solve_resolves_keeps_sliding() {
    // Gross sliding under a shear strength, kinetic alone and with a static value 1.5τ0,
    // then twelve steps of 10⁻¹² and of 10⁻¹⁵ of an element: far below the slip a solve to
    // 1e-10 resolves, so each element's stick-or-slip would be the CG's noise (before the
    // rule of `classify`, the sixth step of 10⁻¹² flipped 323 elements a round for 200
    // rounds and failed). Every element keeps slipping, in at most 3 rounds, at F = τ0·A
    // (1e-12, the tractions' rounding). A step that does not move is a hold: every element
    // sticks and the force stays.
    let delta_x = 1.0 / 128.0;
    let (grid, normal, mut operator) = pressed_sphere(48, 48.0 * delta_x, (16.0 * delta_x) * (16.0 * delta_x));
    let tau0 = 0.01;
    let sliding = tau0 * normal.contact_elements() as f64 * grid.element_area();
    for static_law in [None, Some(FrictionLaw::shear_strength(1.5 * tau0).unwrap())] {
        for advance in [1e-12, 1e-15, 0.0] {
            let mut solver =
                TangentialSolver::new(FrictionLaw::shear_strength(tau0).unwrap(), TangentialParams::default());
            if let Some(law) = static_law {
                solver = solver.with_static_law(law).unwrap();
            }
            let mut state = TangentialState::new(grid.len());
            let mut shift = 0.0;
            for _ in 0..8 {
                shift += 0.002;
                solver.step(&mut operator, &normal, [shift, 0.0], &mut state).unwrap();
            }
            for k in 0..12 {
                shift += advance * delta_x;
                let report = solver
                    .step(&mut operator, &normal, [shift, 0.0], &mut state)
                    .unwrap_or_else(|e| panic!("{static_law:?}, advance {advance:e}, step {k}: {e}"));
                let moving = advance > 0.0;
                let (stick, slip) = if moving {
                    (0, normal.contact_elements())
                } else {
                    (normal.contact_elements(), 0)
                };
                assert_eq!(
                    (report.stick_elements, report.slip_elements),
                    (stick, slip),
                    "{static_law:?} {advance:e} {k}"
                );
                assert!(
                    report.rounds <= 3,
                    "{static_law:?} {advance:e} {k}: {} rounds",
                    report.rounds
                );
                assert!(
                    (report.force[0] / sliding - 1.0).abs() < 1e-12,
                    "{} vs {sliding}",
                    report.force[0]
                );
            }
        }
    }
}
