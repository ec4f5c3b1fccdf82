//! End-to-end tests of a shear whose approach presses in and lifts the indenter to the
//! held depth (`protocol.press_depth`; the paper's sliding experiments, Sect. 6): the lift
//! follows JKR's unloading branch, and the keys at fault are named. A module of the
//! translation tests.

use super::common::{assert_fails_with, column, column_values, curve_with_sets, repo, run_with_sets};
use std::f64::consts::PI;

#[test]
fn a_lift_after_a_press_follows_the_jkr_unloading_branch() {
    // scenarios/shear.toml (R = 1, E* = 4, Δ = 0.5/128) with w = 1e-3, pressed to
    // d = 0.0244 and lifted to d = 0, where the contact holds by adhesion alone. On the
    // lift the contact follows JKR's unloading branch, d = a²/R − √(2πwa/E*); at d = 0
    // a³ = 2πwR²/E* (a = 29.7Δ) with the force P(a) = 4E*a³/(3R) − √(8πwE*a³). The sharp
    // rule lags JKR by the mesh: the pull-off force by 1.4Δ/a (docs/validation.md §3).
    // Tolerances: the radius within Δ/a (3.4 %; measured 1.7 %), the force within 2Δ/a
    // (6.7 %; measured 3.8 %).
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("press");
    let sets = [
        "adhesion.work_of_adhesion=1e-3",
        "protocol.press_depth=0.0244140625",
        "protocol.depth=0.0",
        "protocol.approach_steps=60",
        "protocol.distance=0.001",
        "protocol.steps=2",
    ];
    let (header, rows) = curve_with_sets(&repo().join("scenarios/shear.toml"), &out, &sets);
    let phase = column(&header, &rows, "phase");
    let depth = column_values(&header, &rows, "d");
    let normal = column_values(&header, &rows, "force_normal");
    let area = column_values(&header, &rows, "area");
    let lifted = phase
        .iter()
        .rposition(|p| p == "retract")
        .expect("the lift is recorded as a retraction");
    let pressed = phase.iter().position(|p| p == "retract").unwrap() - 1;
    assert_eq!(depth[pressed], 0.0244140625, "the press reaches press_depth");
    assert_eq!(depth[lifted], 0.0, "the lift ends at depth");
    let (work, modulus, element) = (1e-3, 4.0, 0.5 / 128.0);
    let radius = (2.0 * PI * work / modulus).cbrt();
    let force = 4.0 * modulus * radius.powi(3) / 3.0 - (8.0 * PI * work * modulus * radius.powi(3)).sqrt();
    let measured = (area[lifted] / PI).sqrt();
    println!(
        "d = 0 after the lift: a = {measured:.5} (JKR {radius:.5}), P = {:.5e} (JKR {force:.5e})",
        normal[lifted]
    );
    assert!(
        (measured / radius - 1.0).abs() < element / radius,
        "a = {measured} vs {radius}"
    );
    assert!(
        (normal[lifted] / force - 1.0).abs() < 2.0 * element / radius,
        "P = {} vs {force}",
        normal[lifted]
    );
    assert!(phase[lifted + 1] == "shear", "the shift follows the lift");
}

#[test]
fn press_depth_errors_name_their_keys() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = repo().join("scenarios/shear.toml");
    for (sets, fragments) in [
        (
            vec!["protocol.press_depth=-0.01"],
            vec!["protocol.press_depth", "first contact"],
        ),
        (
            vec!["protocol.press_depth=0.01"],
            vec!["protocol.depth", "below protocol.press_depth"],
        ),
        (
            vec!["protocol.press_depth=0.03", "protocol.approach_steps=1"],
            vec!["protocol.approach_steps = 1", "at least 2"],
        ),
        (
            vec!["protocol.press_depth=0.03", "protocol.depth=-0.05"],
            vec!["no contact is left", "pulled off"],
        ),
    ] {
        let output = run_with_sets(&scenario, &dir.path().join("refused"), &sets);
        assert_fails_with(&output, &fragments);
    }
}
