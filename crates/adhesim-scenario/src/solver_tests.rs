//! `[solver]`: the rules it selects reach the solver, leave the contact sets alone, and are
//! refused where the run's solver would not use them.

use crate::tests::error_of;
use crate::*;

/// The paper's Fig. 1 wavy sphere (α = 1) on a 64² grid, 30 approach steps.
const WAVY: &str = r#"
[grid]
n = 64
size = 0.8
[material]
contact_modulus = 1.0
[adhesion]
work_of_adhesion = 6.16850275068085e-4
[indenter]
shape = "wavy_sphere"
radius = 1.0
amplitude = 0.0025
wavelength = 0.05
[protocol]
kind = "indent_pulloff"
max_depth = 15.0
depth_unit = "jkr"
steps = 30
"#;

fn records_with(rule: &str) -> Vec<adhesim::StepRecord> {
    records_set(&format!("solver.predicted_growth={rule}"))
}

fn records_set(setting: &str) -> Vec<adhesim::StepRecord> {
    let overrides = [setting.to_string()];
    let scenario = load(WAVY, "wavy.toml", Path::new("."), &overrides).unwrap();
    run(&scenario, &mut ()).unwrap().records
}

/// Predicted-subset growth is exact up to ties (docs/fast-step.md §3): on and off give the
/// same contact set size at every step. The key reaches the solver: `on` spends fewer
/// solves on the approach than `off` (the predicted subset replaces attach rounds), and
/// `auto`, off below 512², is `off` bit for bit.
#[test]
fn predicted_growth_rules_keep_the_contact_sets_and_reach_the_solver() {
    let (on, off, auto) = (records_with("\"on\""), records_with("off"), records_with("auto"));
    assert_eq!(on.len(), off.len());
    for (a, b) in on.iter().zip(&off) {
        assert_eq!(a.contact_elements, b.contact_elements, "step {}", a.step);
    }
    let solves = |records: &[adhesim::StepRecord]| records.iter().map(|r| r.report.solves).sum::<usize>();
    assert!(
        solves(&on) < solves(&off),
        "on {} against off {}",
        solves(&on),
        solves(&off)
    );
    assert_eq!(auto.len(), off.len());
    for (a, b) in auto.iter().zip(&off) {
        assert_eq!(a.force_normal.to_bits(), b.force_normal.to_bits(), "step {}", a.step);
        assert_eq!(a.report.solves, b.report.solves, "step {}", a.step);
    }
}

/// The fixed-set CG on the contact's bounding box solves the same K_CC (transforms of
/// another size round differently): the same contact set size at every step, forces equal
/// to 1e-6 of the largest (the solves' relative tolerance is 1e-6, the reported state is
/// converged to a tenth of it). The key reaches the solver: `false` gives other bits, and
/// the default is `true` bit for bit.
#[test]
fn the_contact_window_keeps_the_contact_sets_and_reaches_the_solver() {
    let (on, off, default) = (
        records_set("solver.contact_window=true"),
        records_set("solver.contact_window=false"),
        records_set("solver.predicted_growth=auto"),
    );
    assert_eq!(on.len(), off.len());
    let largest = off.iter().map(|r| r.force_normal.abs()).fold(0.0, f64::max);
    for (a, b) in on.iter().zip(&off) {
        assert_eq!(a.contact_elements, b.contact_elements, "step {}", a.step);
        assert!(
            (a.force_normal - b.force_normal).abs() <= 1e-6 * largest,
            "step {}: {} against {}",
            a.step,
            a.force_normal,
            b.force_normal
        );
    }
    assert!(on
        .iter()
        .zip(&off)
        .any(|(a, b)| a.force_normal.to_bits() != b.force_normal.to_bits()));
    for (a, b) in default.iter().zip(&on) {
        assert_eq!(a.force_normal.to_bits(), b.force_normal.to_bits(), "step {}", a.step);
    }
}

#[test]
fn a_rule_the_solver_would_not_use_is_refused_naming_the_key() {
    let without_adhesion = WAVY
        .replace("work_of_adhesion = 6.16850275068085e-4", "work_of_adhesion = 0.0")
        .replace("depth_unit = \"jkr\"", "depth_unit = \"length\"");
    let error = error_of(&without_adhesion, &["solver.predicted_growth=on"]);
    assert!(
        error.contains("solver.predicted_growth = \"on\"") && error.contains("without adhesion"),
        "{error}"
    );
    let error = error_of(WAVY, &["solver.predicted_growth=on", "grid.boundary=periodic"]);
    assert!(error.contains("grid.boundary = \"periodic\""), "{error}");
    let error = error_of(WAVY, &["solver.contact_window=false", "grid.boundary=periodic"]);
    assert!(
        error.contains("solver.contact_window = false") && error.contains("grid.boundary = \"periodic\""),
        "{error}"
    );
    let error = error_of(WAVY, &["solver.predicted_growth=sometimes"]);
    assert!(
        error.contains("solver.predicted_growth") && error.contains("`auto`, `on`, `off`"),
        "{error}"
    );
}
