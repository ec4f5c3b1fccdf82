//! End-to-end tests of the shear-weakened edge (docs/physics.md §8.5): its
//! direction-dependent mode mixity (`friction.mode_mixity_front`, `friction.mode_mixity_rear`)
//! and the weakened edge of a slide. A module of the translation tests.

use super::common::{assert_fails_with, column, column_values, curve_with_sets, read_csv, repo, run_with_sets};
use super::run_scenario;

/// (n_contact, area_front, area_rear) per row of a run of the glued adhesive sphere.
fn areas(sets: &[&str]) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let dir = tempfile::tempdir().unwrap();
    let (out, _) = run_scenario(dir.path(), "friction/adhesive_shear.toml", sets);
    let (header, rows) = read_csv(&out.join("curve.csv"));
    let column = |name| column_values(&header, &rows, name);
    (column("n_contact"), column("area_front"), column("area_rear"))
}

#[test]
fn a_front_weakened_edge_loses_the_front_and_its_mirror_the_rear() {
    // scenarios/friction/adhesive_shear.toml (glued sphere, a0 = 36Δ, centred on an
    // element so that its contact is mirror-symmetric about the centre column), sheared to
    // δ = 0.008 with the mode II share counted at one side of the edge only.
    // (1) Front only and rear only are mirror images: the same number of contact elements
    //     at every step (exact: the problem and its mirror have the same contact sets).
    // (2) The weakened side loses at least twice the area the other side loses (measured:
    //     the front 4.7 % against the rear 1.6 %; the unweakened side recedes only as the
    //     contact's adhesive load shifts onto it).
    // (3) Uniform values given side by side are the constant mixity: the same contact.
    let mode_ii = |side: &str| format!("friction.mode_mixity_{side}=1");
    let (front_count, front_front, front_rear) = areas(&["friction.mode_mixity=0", &mode_ii("front")]);
    let (rear_count, rear_front, rear_rear) = areas(&["friction.mode_mixity=0", &mode_ii("rear")]);
    assert_eq!(front_count, rear_count, "mirror images have the same contact sizes");
    let rest = 19;
    let last = front_count.len() - 1;
    let loss = |area: &[f64]| 1.0 - area[last] / area[rest];
    let (lost_front, kept_rear) = (loss(&front_front), loss(&front_rear));
    assert!(
        lost_front > 0.03 && lost_front > 2.0 * kept_rear,
        "front only: front lost {lost_front}, rear {kept_rear}"
    );
    let (lost_rear, kept_front) = (loss(&rear_rear), loss(&rear_front));
    assert!(
        lost_rear > 0.03 && lost_rear > 2.0 * kept_front,
        "rear only: rear lost {lost_rear}, front {kept_front}"
    );
    let (uniform, _, _) = areas(&[]);
    let (spelled, _, _) = areas(&[&mode_ii("front"), &mode_ii("rear")]);
    assert_eq!(uniform, spelled);
    assert!(
        uniform[last] < front_count[last],
        "the sides and both edges lose more than one edge"
    );
}

#[test]
fn mode_mixity_sides_name_their_keys() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = repo().join("scenarios/friction/adhesive_shear.toml");
    let run = |sets: &[&str]| run_with_sets(&scenario, &dir.path().join("out"), sets);
    assert_fails_with(
        &run(&["friction.mode_mixity_front=1.5"]),
        &["friction.mode_mixity_front", "1.5", "[0, 1]"],
    );
    assert_fails_with(
        &run(&[
            "friction.mode_mixity=0",
            "friction.mode_mixity_rear=0.5",
            "adhesion.work_of_adhesion=0",
        ]),
        &["friction.mode_mixity_rear", "adhesion.work_of_adhesion"],
    );
}

#[test]
fn normal_control_names_its_key() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = repo().join("scenarios/friction/adhesive_shear.toml");
    let run = |sets: &[&str]| run_with_sets(&scenario, &dir.path().join("out"), sets);
    let force = "protocol.normal_control=\"force\"";
    assert_fails_with(
        &run(&[force, "protocol.incline=5"]),
        &["protocol.normal_control", "protocol.incline"],
    );
    assert_fails_with(
        &run(&["protocol.normal_control=\"sideways\""]),
        &["normal_control", "sideways"],
    );
}

#[test]
fn a_weakened_slide_under_a_shear_strength_is_the_slide_at_the_reduced_work_of_adhesion() {
    // scenarios/layer/paper_r22_slide.toml (the paper's sphere slid over its rubber layer
    // under τ0 = 36 kPa) at 192 × 48 (Δ = 0.2 mm), slid 0.6 mm with mode mixity 1. Once
    // the contact slides, every element carries |q| = τ0, so the element rule's
    // σ_c,eff² = σ_c² − m·r·τ0² (r = 3/2 at ν = 1/2) is the σ_c of the uniformly reduced
    // work of adhesion w(1 − m·r·τ0²/σ_c²), σ_c = √(E*w/(c_U Δ)): 0.646 w here. The
    // weakened slide must be the unweakened slide at that w from the first stroke step on
    // (its approach, unweakened, is the full w's): the same contact, front, rear, stick
    // and slip counts at every stroke step, forces to 1e-6 of each (the normal and
    // tangential solves' tolerances from other starting points; measured 5e-8). The
    // contact loses 4.5 % of its area against the full w's (1.6 % at Δ = 0.1 mm: a
    // bounded traction's weakening is the lattice's, σ_c² ∝ 1/Δ).
    let dir = tempfile::tempdir().unwrap();
    let scenario = repo().join("scenarios/layer/paper_r22_slide.toml");
    let coarse = ["grid.n=[192, 48]", "protocol.distance=0.6", "protocol.steps=12"];
    let (work_of_adhesion, shear_strength, contact_modulus, element) = (3.9e-4, 0.036, 1.0 / 0.75, 0.2);
    let sigma = adhesim::solver::critical_stress(contact_modulus, work_of_adhesion, element);
    let reduced = work_of_adhesion * (1.0 - 1.5 * shear_strength * shear_strength / (sigma * sigma));
    assert!((reduced / work_of_adhesion - 0.646).abs() < 1e-3, "{reduced}");
    let weakened_sets = [&coarse[..], &["friction.mode_mixity=1"]].concat();
    let (header, weakened) = curve_with_sets(&scenario, &dir.path().join("weakened"), &weakened_sets);
    let reduced_set = format!("adhesion.work_of_adhesion={reduced:e}");
    let reduced_sets = [&coarse[..], &[reduced_set.as_str()]].concat();
    let (header_reduced, at_reduced) = curve_with_sets(&scenario, &dir.path().join("reduced"), &reduced_sets);
    let approach = 20;
    assert_eq!(weakened.len(), approach + 12);
    for name in ["n_contact", "area_front", "area_rear", "n_stick", "n_slip"] {
        assert_eq!(
            column(&header, &weakened, name)[approach..],
            column(&header_reduced, &at_reduced, name)[approach..],
            "{name}"
        );
    }
    for name in ["force_normal", "force_tangential"] {
        let (a, b) = (
            column_values(&header, &weakened, name),
            column_values(&header_reduced, &at_reduced, name),
        );
        for k in approach..a.len() {
            assert!(
                (a[k] / b[k] - 1.0).abs() < 1e-6,
                "step {k}: {name} {} vs {}",
                a[k],
                b[k]
            );
        }
    }
    let contact = column_values(&header, &weakened, "n_contact");
    assert!(
        contact[weakened.len() - 1] < 0.97 * contact[approach - 1],
        "{contact:?}"
    );
}
