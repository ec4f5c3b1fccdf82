//! Force control solved at once against the trials that solved it before.

use crate::solver::tangential::tests::{mindlin_sphere, MindlinSphere, MINDLIN_MU};
use crate::solver::tangential::{FrictionLaw, TangentialParams, TangentialSolver, TangentialState};

#[test]
fn an_imposed_force_solved_at_once_is_the_force_the_trials_find() {
    // The same loading and unloading path as above, once solved at once (the force a
    // constraint of the face's CG) and once by displacement-controlled trials: both meet the
    // force to 1e-8; the shifts agree to 1e-7 of the largest (the force tolerance's 1e-8
    // over the contact's tangential stiffness, with the CG's 1e-10 and a margin of ten),
    // the stick sets are the same, and the optimality conditions hold as tightly.
    let MindlinSphere {
        grid,
        normal,
        mut operator,
        force_normal,
        ..
    } = mindlin_sphere();
    let limit = MINDLIN_MU * force_normal;
    let law = FrictionLaw::coulomb(MINDLIN_MU).unwrap();
    let (mut once, mut trials) = (
        TangentialSolver::new(law, TangentialParams::default()),
        TangentialSolver::new(law, TangentialParams::default()),
    );
    let (mut once_state, mut trials_state) = (TangentialState::new(grid.len()), TangentialState::new(grid.len()));
    let path = (1..=8)
        .map(|k| 0.1 * k as f64)
        .chain((1..=6).map(|k| 0.8 - 0.2 * k as f64));
    let (mut once_pairs, mut trial_pairs) = (0, 0);
    let mut largest_shift = 0.0f64;
    for (step, ratio) in path.enumerate() {
        let force = ratio * limit;
        let a = once
            .step_to_force(&mut operator, &normal, [1.0, 0.0], force, &mut once_state)
            .unwrap();
        let b = trials
            .step_to_force_by_trials(
                &mut operator,
                &normal,
                ([1.0, 0.0], force),
                &mut trials_state,
                1e-8 * limit,
            )
            .unwrap();
        largest_shift = largest_shift.max(b.shift[0].abs());
        (once_pairs, trial_pairs) = (once_pairs + a.transform_pairs, trial_pairs + b.transform_pairs);
        eprintln!(
            "step {step}: shift {:.9e} vs {:.9e}, stick {} vs {}, pairs {} vs {} ({} trials)",
            a.shift[0], b.shift[0], a.stick_elements, b.stick_elements, a.transform_pairs, b.transform_pairs, b.trials
        );
        for report in [&a, &b] {
            assert!(
                (report.force[0] - force).abs() <= 1e-8 * limit,
                "step {step}: {report:?}"
            );
        }
        assert!(
            (a.shift[0] - b.shift[0]).abs() <= 1e-7 * largest_shift,
            "step {step}: shift {} vs {}",
            a.shift[0],
            b.shift[0]
        );
        assert_eq!(a.stick_elements, b.stick_elements, "step {step}");
        // Optimal as a displacement-controlled step is: the stick gaps and slip directions
        // within 2e-9 of the largest target (docs/tangential.md, every step's optimality).
        let optimality = a.complementarity;
        assert!(
            optimality.stick_residual <= 2e-9 && optimality.slip_misalignment <= 2e-9,
            "step {step}: {optimality:?}"
        );
    }
    eprintln!("transform pairs: {once_pairs} at once, {trial_pairs} by trials");
    assert!(2 * once_pairs <= trial_pairs, "{once_pairs} vs {trial_pairs}");
}
