//! The checks of scenario keys give their key, the value at fault and the requirement as
//! fields of [`ScenarioError`], beside the message (issue #28: programs read the fields,
//! never the text).

use crate::tests::MINIMAL;
use crate::*;

/// The error of `MINIMAL` with `replace` applied to its text and `overrides` set.
fn typed_error(replace: (&str, &str), overrides: &[&str]) -> ScenarioError {
    let text = MINIMAL.replace(replace.0, replace.1);
    assert!(replace.0.is_empty() || text != MINIMAL, "{replace:?} changes nothing");
    let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    match load(&text, "test", Path::new("."), &overrides) {
        Ok(_) => panic!("accepted: {replace:?} {overrides:?}"),
        Err(error) => error,
    }
}

const NONE: (&str, &str) = ("", "");

/// A bad scenario (a text replacement and overrides of `MINIMAL`) and the error's kind,
/// key, value and the start of its requirement.
type Case<'a> = (
    (&'a str, &'a str),
    &'a [&'a str],
    ErrorKind,
    &'a str,
    Option<&'a str>,
    &'a str,
);
const ROUGH: &str = "[roughness]\nseed = 1\nrms_height = 0.001\nhurst = 0.8\n[indenter]";

#[test]
fn each_check_of_a_key_gives_the_key_the_value_and_the_requirement() {
    use ErrorKind::*;
    #[rustfmt::skip]
    let cases: [Case; 14] = [
        (NONE, &["protocol.max_retract_steps=0"], InvalidValue, "protocol.max_retract_steps", Some("0"), ">= 1"),
        (NONE, &["protocol.steps=0"], InvalidValue, "protocol.steps", Some("0"), "in 1..=1000000"),
        (NONE, &["protocol.step=0.1"], InvalidValue, "protocol.step", Some("0.1"), "absent when protocol.steps is given"),
        (NONE, &["protocol.max_depth=-1"], InvalidValue, "protocol.max_depth", Some("-1"), "> 0.000000e0 (the depth of first contact)"),
        (NONE, &["output.snapshot_every=-2"], InvalidValue, "output.snapshot_every", Some("-2"), ">= 0"),
        (NONE, &["output.snapshot_steps=[3, -1]"], InvalidValue, "output.snapshot_steps", Some("-1"), "steps >= 0"),
        (("contact_modulus = 2.0", "youngs_modulus = 1.5\npoisson_ratio = 0.7"), &[], InvalidValue,
            "material.poisson_ratio", Some("0.7"), "in (-1, 0.5]"),
        (("contact_modulus = 2.0", "youngs_modulus = 1.5"), &[], MissingKey, "material.poisson_ratio", None,
            "with material.youngs_modulus"),
        (("[indenter]", ROUGH), &["roughness.hurst=1.5"], InvalidValue, "roughness.hurst", Some("1.5"), "in (0, 1]"),
        (("[indenter]", &ROUGH.replace("seed = 1\n", "")), &[], MissingKey, "roughness.seed", None,
            "for a random surface"),
        (NONE, &["adhesion.law=\"dugdale\""], MissingKey, "adhesion.cohesive_stress", None,
            "with adhesion.law = \"dugdale\""),
        (NONE, &["adhesion.range=0.5"], UnknownKey, "adhesion.range", Some("0.5"), "absent with adhesion.law = \"jkr\""),
        (NONE, &["analysis.tau0=1"], InvalidValue, "protocol.kind", Some("\"indent_pulloff\""),
            "\"roll\" or \"slide\" with [analysis]"),
        (("shape = \"sphere\"\nradius = 1.0", "shape = \"topography\"\nfile = \"no-such-map.npy\"\nspacing = 0.01"),
            &[], File, "indenter.file", Some("./no-such-map.npy"), "a height map file adhesim reads"),
    ];
    for (replace, overrides, kind, key, value, requirement) in cases {
        let error = typed_error(replace, overrides);
        let context = format!("{replace:?} {overrides:?}: {error}");
        assert_eq!(error.kind, kind, "{context}");
        assert_eq!(error.key.as_deref(), Some(key), "{context}");
        assert_eq!(error.value.as_deref(), value, "{context}");
        let got = error.requirement.as_deref().unwrap_or_default();
        assert!(got.starts_with(requirement), "{context}: requirement {got:?}");
        // The message still names the key, and the value where there is one.
        assert!(error.message().contains(key.rsplit('.').next().unwrap()), "{context}");
        if let Some(value) = value.filter(|v| !v.starts_with('.')) {
            assert!(error.message().contains(value.trim_matches('"')), "{context}");
        }
    }
}

#[test]
fn a_quantity_derived_from_several_keys_gives_its_value_and_requirement_without_a_key() {
    let error = typed_error(NONE, &["adhesion.work_of_adhesion=1e-200"]);
    assert_eq!(
        (error.kind, error.key.as_deref()),
        (ErrorKind::InvalidValue, None),
        "{error}"
    );
    assert!(error.value.is_some() && error.requirement.is_some(), "{error:?}");
    assert!(
        error.message().contains("adhesion.work_of_adhesion = 1e-200"),
        "{error}"
    );
}

#[test]
fn the_messages_keep_their_wording() {
    let error = typed_error(NONE, &["protocol.max_retract_steps=0"]);
    assert_eq!(error.to_string(), "protocol.max_retract_steps must be >= 1, got 0");
    let error = typed_error(NONE, &["protocol.step=0.1"]);
    assert_eq!(
        error.to_string(),
        "give either protocol.steps or protocol.step, not both (protocol.steps = 30, protocol.step = 0.1)"
    );
}

#[test]
fn a_sweep_pseudo_key_and_the_key_it_needs_are_typed() {
    let mut table = parse_toml(MINIMAL, "test").unwrap();
    let error = crate::sweep::plan::apply(&mut table, &[("alpha".into(), toml::Value::Float(-1.0))], "")
        .map_err(ScenarioError::from_anyhow)
        .unwrap_err();
    let fields = (
        error.key.as_deref(),
        error.value.as_deref(),
        error.requirement.as_deref(),
    );
    assert_eq!(
        fields,
        (Some("alpha"), Some("-1"), Some("a finite number > 0")),
        "{error}"
    );
    let error = crate::sweep::plan::apply(&mut table, &[("h_over_lambda".into(), toml::Value::Float(0.1))], "")
        .map_err(ScenarioError::from_anyhow)
        .unwrap_err();
    assert_eq!(
        (error.kind, error.key.as_deref(), error.requirement.as_deref()),
        (
            ErrorKind::MissingKey,
            Some("indenter.wavelength"),
            Some("for h_over_lambda")
        ),
        "{error}"
    );
    assert_eq!(
        error.to_string(),
        "h_over_lambda needs indenter.wavelength in the scenario"
    );
}
