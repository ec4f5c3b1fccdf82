//! Unit tests of reading and validating scenarios.

use crate::*;

const MINIMAL: &str = r#"
[grid]
n = 16
size = 1.0
[material]
contact_modulus = 2.0
[adhesion]
work_of_adhesion = 0.01
[indenter]
shape = "sphere"
radius = 1.0
[protocol]
kind = "indent_pulloff"
max_depth = 3.0
depth_unit = "jkr"
steps = 30
"#;

#[test]
fn overrides_set_nested_keys_and_parse_toml_values() {
    let mut table = parse_toml(MINIMAL, "test").unwrap();
    let overrides = [
        "grid.n=32".to_string(),
        "grid.boundary = periodic".to_string(),
        "adhesion.field.kind=\"quadratic\"".to_string(),
        "output.snapshot_steps=[1, 2]".to_string(),
    ];
    apply_overrides(&mut table, &overrides).unwrap();
    assert_eq!(table["grid"]["n"].as_integer(), Some(32));
    assert_eq!(table["grid"]["boundary"].as_str(), Some("periodic"));
    assert_eq!(table["adhesion"]["field"]["kind"].as_str(), Some("quadratic"));
    assert_eq!(table["output"]["snapshot_steps"].as_array().unwrap().len(), 2);
    let error = apply_overrides(&mut table, &["grid.n.x=1".to_string()]).unwrap_err();
    assert!(error.to_string().contains("`grid.n` is not a table"), "{error}");
}

#[test]
fn jkr_units_scale_the_depth() {
    let scenario = load(MINIMAL, "test", Path::new("."), &[]).unwrap();
    let jkr = scenario.jkr.unwrap();
    let d = jkr.critical_depth().abs();
    assert!((scenario.max_depth - 3.0 * d).abs() < 1e-15);
    assert_eq!(scenario.start_depth, 0.0);
    assert_eq!(scenario.approach_steps, 30);
    assert!((scenario.depth_step - 0.1 * d).abs() < 1e-15);
    assert_eq!(scenario.derived.f_jkr, Some(jkr.critical_force()));
    assert!(scenario.derived.johnson_parameter.is_none());
}

#[test]
fn material_forms_are_exclusive() {
    let both = MINIMAL.replace("contact_modulus = 2.0", "contact_modulus = 2.0\nyoungs_modulus = 1.0");
    let error = load(&both, "test", Path::new("."), &[]).err().unwrap();
    assert!(error
        .to_string()
        .contains("material.contact_modulus cannot be combined"));
    let young = MINIMAL.replace("contact_modulus = 2.0", "youngs_modulus = 1.5\npoisson_ratio = 0.5");
    let scenario = load(&young, "test", Path::new("."), &[]).unwrap();
    assert!((scenario.material.contact_modulus() - 2.0).abs() < 1e-15);
    let error = load(MINIMAL, "test", Path::new("."), &["material.contact_modulus=-2".into()])
        .err()
        .unwrap();
    assert_eq!(error.to_string(), "material.contact_modulus must be > 0, got -2");
}
