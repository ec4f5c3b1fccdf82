//! End-to-end tests of the direction-dependent mode mixity of the shear-weakened edge
//! (`friction.mode_mixity_front`, `friction.mode_mixity_rear`; docs/physics.md §8.5). A
//! module of the translation tests.

use super::common::{assert_fails_with, column_values, read_csv, repo, run_with_sets};
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
