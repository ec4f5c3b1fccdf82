//! Unit tests of reading and validating scenarios.

use crate::*;

/// A small valid JKR sphere scenario, shared with `guards_tests`.
pub(crate) const MINIMAL: &str = r#"
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

/// The error (with its causes) of the scenario `text` with `overrides`, as text.
pub(crate) fn error_of(text: &str, overrides: &[&str]) -> String {
    let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    match load(text, "test", Path::new("."), &overrides) {
        Ok(_) => panic!("accepted: {overrides:?}"),
        Err(e) => format!("{e:#}"),
    }
}

/// The error of `MINIMAL` with `overrides`, as text.
fn error_with(overrides: &[&str]) -> String {
    error_of(MINIMAL, overrides)
}

#[test]
fn each_indenter_shape_takes_exactly_its_own_keys() {
    // A key of another shape is refused by the tagged enum, naming the key and the shape.
    let stray = [
        ("indenter.amplitude=0.1", "sphere", "indenter.amplitude"),
        ("indenter.semi_axes=[1, 2]", "sphere", "indenter.semi_axes"),
        ("indenter.angle=30", "sphere", "indenter.angle"),
        ("indenter.file=\"map.npy\"", "sphere", "indenter.file"),
    ];
    for (set, shape, key) in stray {
        let error = error_with(&[set]);
        let expected = format!("unknown key `{key}` for indenter.shape = \"{shape}\" (expected `radius`)");
        assert_eq!(error, expected, "{set}");
    }
    let error = error_with(&["indenter.shape=flat_punch", "indenter.spacing=1"]);
    assert!(
        error.starts_with("unknown key `indenter.spacing` for indenter.shape = \"flat_punch\""),
        "{error}"
    );
    // A missing key names itself and the shape that needs it.
    let error = error_with(&["indenter.shape=wavy_sphere", "indenter.amplitude=0.01"]);
    assert_eq!(
        error,
        "missing key `indenter.wavelength` (needed by indenter.shape = \"wavy_sphere\")"
    );
    let error = error_with(&["indenter.shape=elliptic_punch"]);
    assert!(
        error.starts_with("unknown key `indenter.radius` for indenter.shape = \"elliptic_punch\""),
        "{error}"
    );
    // Numbers keep their own range checks.
    let error = error_with(&[
        "indenter.shape=wavy_sphere",
        "indenter.amplitude=-1",
        "indenter.wavelength=0.1",
    ]);
    assert_eq!(error, "indenter.amplitude must be >= 0, got -1");
    let error = error_with(&[
        "indenter.shape=wavy_sphere",
        "indenter.amplitude=0",
        "indenter.wavelength=0.1",
        "indenter.angle=inf",
    ]);
    assert_eq!(error, "indenter.angle must be finite, got inf");
}

#[test]
fn the_indenter_echo_keeps_the_keys_and_their_order() {
    // `summary.json`'s `inputs` echo the indenter as the flat table of before: the tag
    // first, then the shape's keys in the order of the old struct; absent options left out.
    let overrides = [
        "indenter.shape=wavy_sphere".to_string(),
        "indenter.amplitude=0".to_string(),
        "indenter.wavelength=0.25".to_string(),
        "indenter.radius=2".to_string(),
    ];
    let scenario = load(MINIMAL, "test", Path::new("."), &overrides).unwrap();
    let echo = serde_json::to_string(&scenario.file.indenter).unwrap();
    assert_eq!(
        echo,
        r#"{"shape":"wavy_sphere","radius":2.0,"amplitude":0.0,"wavelength":0.25}"#
    );
    let with_angle = [overrides.as_slice(), &["indenter.angle=15".to_string()]].concat();
    let scenario = load(MINIMAL, "test", Path::new("."), &with_angle).unwrap();
    let echo = serde_json::to_string(&scenario.file.indenter).unwrap();
    assert!(echo.ends_with(r#""wavelength":0.25,"angle":15.0}"#), "{echo}");
}

/// A roll of a wavy sphere (fig. 6 of the paper, small).
const ROLL: &str = r#"
[grid]
n = 32
size = 1.0
[material]
contact_modulus = 1.0
[adhesion]
work_of_adhesion = 0.001
[indenter]
shape = "wavy_sphere"
radius = 1.0
amplitude = 0.001
wavelength = 0.1
[protocol]
kind = "roll"
depth_unit = "jkr"
depth = 3.0
distance = 0.1
steps = 10
"#;

#[test]
fn each_protocol_kind_takes_exactly_its_own_keys() {
    let error_of = |text: &str, overrides: &[&str]| {
        let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
        match load(text, "test", Path::new("."), &overrides) {
            Ok(_) => panic!("{overrides:?} should be refused"),
            Err(error) => error.to_string(),
        }
    };
    // A key of another kind is refused by the tagged enum, naming the key and the kind.
    for (set, key) in [
        ("protocol.depth=2", "protocol.depth"),
        ("protocol.distance=1", "protocol.distance"),
        ("protocol.substrate_angle=30", "protocol.substrate_angle"),
        ("protocol.return_stroke=true", "protocol.return_stroke"),
    ] {
        let error = error_of(MINIMAL, &[set]);
        // The message says which kind the key belongs to, and what this kind takes.
        let expected = format!("unknown key `{key}` for protocol.kind = \"indent_pulloff\" (a key of protocol.kind = ");
        assert!(error.starts_with(&expected), "{set}: {error}");
        assert!(
            error.ends_with(
                "; expected one of `max_depth`, `depth_unit`, `steps`, `step`, `max_retract_steps`, `hold_time`, `time_step`)"
            ),
            "{error}"
        );
    }
    for (set, kind) in [
        ("protocol.max_depth=3", "roll"),
        ("protocol.step=0.1", "roll"),
        ("protocol.max_retract_steps=9", "roll"),
        ("protocol.substrate_angle=30", "roll"),
    ] {
        let error = error_of(ROLL, &[set]);
        let key = set.split('=').next().unwrap();
        assert!(
            error.starts_with(&format!("unknown key `{key}` for protocol.kind = \"{kind}\"")),
            "{set}: {error}"
        );
    }
    let slide = load(
        ROLL,
        "test",
        Path::new("."),
        &["protocol.kind=slide".into(), "protocol.substrate_angle=45".into()],
    );
    let slide = slide.unwrap().translation.unwrap();
    assert_eq!(slide.kind, ProtocolKind::Slide);
    // A missing key names itself and the kind that needs it.
    let without = |key: &str| ROLL.replace(&format!("\n{key} = "), "\n# ");
    assert_eq!(
        error_of(&without("distance"), &[]),
        "missing key `protocol.distance` (needed by protocol.kind = \"roll\")"
    );
    assert_eq!(
        error_of(&without("steps"), &[]),
        "missing key `protocol.steps` (needed by protocol.kind = \"roll\")"
    );
    assert_eq!(
        error_of(&MINIMAL.replace("max_depth = 3.0", ""), &[]),
        "missing key `protocol.max_depth` (needed by protocol.kind = \"indent_pulloff\")"
    );
    assert_eq!(
        error_of(&MINIMAL.replace("kind = \"indent_pulloff\"", ""), &[]),
        "missing key `protocol.kind`"
    );
    // Numbers keep their own range checks.
    let error = error_of(ROLL, &["protocol.steps=0"]);
    assert!(error.starts_with("protocol.steps must be in 1..="), "{error}");
}

#[test]
fn the_protocol_echo_keeps_the_keys_and_their_order() {
    let roll = load(ROLL, "test", Path::new("."), &["protocol.approach_steps=5".into()]).unwrap();
    assert_eq!(
        serde_json::to_string(&roll.file.protocol).unwrap(),
        r#"{"kind":"roll","depth_unit":"jkr","depth":3.0,"distance":0.1,"approach_steps":5,"steps":10}"#
    );
    let indent = load(MINIMAL, "test", Path::new("."), &[]).unwrap();
    assert_eq!(
        serde_json::to_string(&indent.file.protocol).unwrap(),
        r#"{"kind":"indent_pulloff","max_depth":3.0,"depth_unit":"jkr","steps":30}"#
    );
}
