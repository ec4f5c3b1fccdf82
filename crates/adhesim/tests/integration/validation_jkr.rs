//! Adhesive smooth-sphere indentation and pull-off against JKR (Johnson, Kendall &
//! Roberts 1971), and the energy balance of the quasi-static cycle.
//!
//! The lattice detachment criterion converges to JKR at first order in Δ/a_JKR, from
//! above: |F_min|/|F_JKR| ≈ 1 + 1.4Δ/a_JKR (docs/physics.md §4). The default tests run at
//! a_JKR/Δ = 8 and 16 (seconds); the 3 % accuracy at a_JKR/Δ ≥ 60 is checked by the
//! ignored tests (`cargo test --release -- --ignored`), which take minutes.

use crate::common;

use adhesim::{AdhesiveParams, Phase};
use common::{loop_area, JkrCase};
use std::num::NonZeroUsize;

/// Pull-off force converges at first order from above: the error at a_JKR/Δ = 16 is
/// between 0.3 and 0.7 of that at 8 (0.5 for exact first order; the staircase front makes
/// it irregular), and both lie within ±50 % of the expected 1.4Δ/a_JKR.
#[test]
fn pull_off_force_converges_at_first_order() {
    let mut errors = Vec::new();
    for resolution in [8.0, 16.0] {
        let case = JkrCase::new(resolution, 2.0);
        let (summary, _) = case.run(2.0, 40.0);
        let error = summary.max_adhesive_force / case.jkr.critical_force().abs() - 1.0;
        let expected = 1.4 / resolution;
        assert!(
            error > 0.5 * expected && error < 1.5 * expected,
            "a/Δ = {resolution}: |F_min|/|F_JKR| − 1 = {error:.4}, expected ≈ {expected:.4}"
        );
        errors.push(error);
    }
    let ratio = errors[1] / errors[0];
    assert!((0.3..0.7).contains(&ratio), "error ratio {ratio:.3}");
}

/// Two layers per trial ring (`AdhesiveParams::trial_ring_layers` = 2, the rule-level
/// change measured in BENCHMARKS.md §What did not pay, two layers per trial ring): the
/// pull-off force must still lie within ±50 % of the first-order mesh error 1.4Δ/a_JKR, the
/// tolerance of [`pull_off_force_converges_at_first_order`] for the exact rule (the same
/// closed form, the same mesh error; the rule changes only which closures are tested), at
/// a_JKR/Δ = 8 and 16.
#[test]
fn two_layer_rings_keep_the_jkr_pull_off_force() {
    for resolution in [8.0, 16.0] {
        let case = JkrCase::new(resolution, 2.0);
        let params = AdhesiveParams {
            trial_ring_layers: NonZeroUsize::new(2).unwrap(),
            ..AdhesiveParams::default()
        };
        let (summary, _) = case.run_with(params, 2.0, 40.0);
        let (exact, _) = case.run(2.0, 40.0);
        let f_jkr = case.jkr.critical_force().abs();
        let error = summary.max_adhesive_force / f_jkr - 1.0;
        let expected = 1.4 / resolution;
        println!(
            "a/Δ = {resolution}: |F_min|/|F_JKR| two layers {:.5}, one layer {:.5}",
            summary.max_adhesive_force / f_jkr,
            exact.max_adhesive_force / f_jkr
        );
        assert!(
            error > 0.5 * expected && error < 1.5 * expected,
            "a/Δ = {resolution}: two layers |F_min|/|F_JKR| − 1 = {error:.4}, expected ≈ {expected:.4}"
        );
    }
}

/// At a_JKR/Δ = 16: the retraction branch stays within 0.08|F_JKR| of JKR for
/// d ≥ 0.5|d_JKR| (issue target 0.03 at a/Δ ≥ 60, where the first-order error is 2.3×
/// smaller — see the ignored test), the approach branch within 0.08|F_JKR| for
/// d ≥ 2|d_JKR| (trial attachment gives γ1 → γ0 on smooth spheres), and the final jump
/// under displacement control lies within 0.3|d_JKR| of −9^{1/3}|d_JKR| = −2.080|d_JKR|.
#[test]
fn branches_follow_jkr_at_moderate_resolution() {
    let case = JkrCase::new(16.0, 3.0);
    let (summary, records) = case.run(3.0, 50.0);
    check_branches(&case, &summary, &records, 0.08, 0.08, 0.3);
}

fn check_branches(
    case: &JkrCase,
    summary: &adhesim::ProtocolSummary,
    records: &[adhesim::StepRecord],
    retract_tolerance: f64,
    approach_tolerance: f64,
    jump_tolerance: f64,
) {
    let f_jkr = case.jkr.critical_force().abs();
    let d_jkr = case.jkr.critical_depth().abs();
    for record in records {
        let d = record.depth / d_jkr;
        let Some(expected) = case.jkr.force_at_depth(record.depth) else {
            continue;
        };
        let error = (record.force_normal - expected).abs() / f_jkr;
        match record.phase {
            Some(Phase::Retract) if d >= 0.5 => {
                assert!(
                    error < retract_tolerance,
                    "retract d/|d_JKR| = {d:.3}: error {error:.4}"
                )
            }
            Some(Phase::Approach) if d >= 2.0 => {
                assert!(
                    error < approach_tolerance,
                    "approach d/|d_JKR| = {d:.3}: error {error:.4}"
                )
            }
            _ => {}
        }
    }
    let final_jump = summary.pull_off_depth.unwrap() / d_jkr;
    assert!(
        (final_jump + 9f64.cbrt()).abs() < jump_tolerance,
        "final jump at d/|d_JKR| = {final_jump:.3}"
    );
}

/// Over a full cycle the work done on the indenter, ∮F dd, equals the energy released by
/// the configuration changes: exactly when each step's fixed-set path is integrated with
/// the force before the change (F is linear in d on a fixed set; 1e-6 relative: forces
/// carry the CG error (relative residual 1e-6, front residual 1e-4·σ_c·K(0,0)) over ~400
/// steps; the energies are evaluated in a form whose CG error is second order), and within
/// 2 % for the recorded polyline at 100 steps per |d_JKR| (the polyline cuts the corners of
/// the jumps).
#[test]
fn loop_area_equals_dissipated_energy() {
    let case = JkrCase::new(8.0, 2.0);
    let (summary, records) = case.run(2.0, 100.0);
    let mut exact = 0.5 * records[0].report.force_before_change * records[0].depth;
    for pair in records.windows(2) {
        exact += 0.5 * (pair[0].force_normal + pair[1].report.force_before_change) * (pair[1].depth - pair[0].depth);
    }
    let dissipated: f64 = records.iter().map(|r| r.report.dissipated_energy).sum();
    assert!((dissipated - summary.dissipated_energy).abs() < 1e-12 * dissipated.abs());
    assert!(dissipated > 0.0);
    assert!((exact / dissipated - 1.0).abs() < 1e-6, "{exact} vs {dissipated}");
    let polyline = loop_area(&records);
    assert!((polyline / dissipated - 1.0).abs() < 0.02, "{polyline} vs {dissipated}");
    // the jump steps carry the dissipation: steps without configuration change release nothing
    for record in &records {
        if record.report.attached + record.report.detached == 0 {
            assert!(record.report.dissipated_energy.abs() < 1e-9 * dissipated);
        }
    }
}

/// The JKR validation targets (docs/validation.md §3) at a_JKR/Δ = 64 (≥ 60): pull-off force
/// within 3 %, retraction branch within 0.03|F_JKR| for d ≥ 0.5|d_JKR|, approach within
/// 0.05|F_JKR| for d ≥ 2|d_JKR|, final jump near −2.08|d_JKR| (0.15 tolerance: the last stage
/// involves few elements).
#[test]
#[ignore = "minutes: run with cargo test --release -- --ignored"]
fn jkr_targets_at_high_resolution() {
    let case = JkrCase::new(64.0, 3.0);
    let (summary, records) = case.run(3.0, 50.0);
    let error = summary.max_adhesive_force / case.jkr.critical_force().abs() - 1.0;
    assert!(error.abs() < 0.03, "pull-off error {error:.4}");
    check_branches(&case, &summary, &records, 0.03, 0.05, 0.15);
}

/// Second robustness audit (docs/reliability.md): γ → 0 through the adhesive solver. The
/// cycle's dissipated energy is then the CG error of ∮F dd (loading and unloading pass through
/// the same unique non-adhesive states), of either sign: it must be negligible against the work
/// of the loading branch, and the per-step values (signed by design: docs/validation.md §4)
/// must cancel. The bound 1e-4 is a hundredfold the CG tolerance's relative residual 1e-6 (an
/// energy error is second order in the pressure error, but the ~200 steps' errors add up).
#[test]
fn vanishing_adhesion_dissipates_nothing_beyond_the_solver_error() {
    // the grid and depths of the a_JKR/Δ = 8 case (to 2|d_JKR| in steps of |d_JKR|/50);
    // d_JKR ∝ γ^(2/3) shrinks by 1e-8 with γ, so they are given in the new units
    let mut case = JkrCase::new(8.0, 2.0);
    case.jkr.work_of_adhesion *= 1e-12;
    let (summary, records) = case.run(2.0e8, 50.0e-8);
    let loading_work: f64 = records
        .windows(2)
        .filter(|pair| pair[1].phase == Some(Phase::Approach))
        .map(|pair| 0.5 * (pair[0].force_normal + pair[1].force_normal) * (pair[1].depth - pair[0].depth))
        .sum();
    let negative: f64 = records.iter().map(|r| r.report.dissipated_energy.min(0.0)).sum();
    println!(
        "loading work {loading_work:.4e}, cycle dissipation {:.3e} ({:.2e} of it), negative steps {negative:.3e}",
        summary.dissipated_energy,
        summary.dissipated_energy / loading_work
    );
    assert!(loading_work > 0.0);
    assert!(summary.dissipated_energy.abs() < 1e-4 * loading_work);
}
