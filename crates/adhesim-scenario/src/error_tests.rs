//! The checks of scenario keys give their key, the value at fault and the requirement as
//! fields of [`ScenarioError`], beside the message (docs/python.md: programs read the fields,
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

/// The error of a sweep file made of `MINIMAL` as its inline `[scenario]` and `tail`.
fn sweep_error(tail: &str) -> ScenarioError {
    let mut sweep: toml::Table = toml::from_str(tail).unwrap();
    sweep.insert(
        "scenario".into(),
        toml::Value::Table(parse_toml(MINIMAL, "test").unwrap()),
    );
    let text = toml::to_string(&sweep).unwrap();
    match crate::sweep::plan::from_text(&text, "test.toml", Path::new("."), "test") {
        Ok(plan) => panic!("accepted {tail:?}: {} cases", plan.cases.len()),
        Err(error) => ScenarioError::from_anyhow(error),
    }
}

/// The sweep file's own checks name its key as a TOML dotted key (`random.seed`,
/// `vary.alpha`, `zip."grid.n"`, `random."KEY".min`), with the value and the requirement.
#[test]
fn each_check_of_a_sweep_file_gives_its_key_the_value_and_the_requirement() {
    use ErrorKind::*;
    const RANGE: &str = "[random]\nseed = 1\ncases = 2\n\"adhesion.work_of_adhesion\"";
    const GAMMA: &str = "random.\"adhesion.work_of_adhesion\"";
    let min = format!("{GAMMA}.min");
    let tails = [
        format!("{RANGE} = {{ min = 2.0, max = 1.0 }}"),
        format!("{RANGE} = {{ min = 0.0, max = 1.0, scale = \"log\" }}"),
        format!("{RANGE} = {{ min = 0.1, max = 1.0, scale = \"ln\" }}"),
        format!("{RANGE} = {{ min = 0.1, max = \"big\" }}"),
        format!("{RANGE} = {{ min = 0.1 }}"),
        format!("{RANGE} = {{ min = 0.1, max = 1.0, step = 0.1 }}"),
        format!("{RANGE} = 0.5"),
    ];
    let scale = format!("{GAMMA}.scale");
    let (max, step) = (format!("{GAMMA}.max"), format!("{GAMMA}.step"));
    #[rustfmt::skip]
    let cases: [(&str, ErrorKind, &str, Option<&str>, &str); 21] = [
        ("[random]\nseed = -1\ncases = 2\n\"grid.n\" = { min = 8, max = 16 }", InvalidValue, "random.seed", Some("-1"),
            "an integer >= 0"),
        ("[random]\ncases = 2\n\"grid.n\" = { min = 8, max = 16 }", MissingKey, "random.seed", None, "with [random]"),
        ("[random]\nseed = 1\ncases = 0\n\"grid.n\" = { min = 8, max = 16 }", InvalidValue, "random.cases", Some("0"),
            "an integer >= 1"),
        ("[random]\nseed = 1\ncases = 1000001\n\"grid.n\" = { min = 8, max = 16 }", InvalidValue, "random.cases",
            Some("1000001"), "<= 100000"),
        (&tails[0], InvalidValue, &min, Some("2"), "<= max (1)"),
        (&tails[1], InvalidValue, &min, Some("0"), "> 0 with scale = \"log\""),
        (&tails[2], InvalidValue, &scale, Some("\"ln\""), "\"log\" or \"linear\""),
        (&tails[3], InvalidValue, &max, Some("\"big\""), "a finite number"),
        (&tails[4], MissingKey, &max, None, "in a [random] range"),
        (&tails[5], UnknownKey, &step, None, "one of min, max, scale"),
        (&tails[6], InvalidValue, GAMMA, Some("0.5"), "{ min = .., max = .."),
        ("[vary]\nalpha = []", InvalidValue, "vary.alpha", Some("[]"), "a non-empty list"),
        ("[vary]\n\"grid.n\" = 8", InvalidValue, "vary.\"grid.n\"", Some("8"), "a list of values"),
        ("[zip]\n\"grid.n\" = [8, 16]\n\"grid.size\" = [0.5]", InvalidValue, "zip.\"grid.size\"", Some("[0.5]"),
            "a list of 2 values, as zip.\"grid.n\""),
        ("[vary]\n\"grid.n\" = [8]\n[zip]\n\"grid.n\" = [16]", InvalidValue, "zip.\"grid.n\"", Some("[16]"),
            "given once in [set], [vary], [zip] and [random] (also vary.\"grid.n\")"),
        ("[vary]\nalpha = [1.0]\n[derived]\nalpha = \"indenter.radius\"", InvalidValue, "derived.alpha",
            Some("\"indenter.radius\""), "one of indenter.amplitude, "),
        ("[vary]\nalpha = [1.0]\n[derived]\nbeta = \"x\"", UnknownKey, "derived.beta", Some("\"x\""), "absent"),
        ("[vary]\nalpha = [1.0]\n[derived]\nalpha = \"indenter.wavelength\"", MissingKey, "indenter.wavelength", None,
            "in the base scenario, for alpha"),
        ("[vary]\nalpah = [1.0]", UnknownKey, "alpah", None, "a dotted scenario key or one of"),
        ("series = 3\n[vary]\nalpha = [1.0]", InvalidValue, "series", Some("3"), "a string"),
        ("vary = 3", InvalidValue, "vary", Some("3"), "a table [vary]"),
    ];
    for (tail, kind, key, value, requirement) in cases {
        let error = sweep_error(tail);
        let context = format!("{tail:?}: {error}");
        assert_eq!(error.kind, kind, "{context}");
        assert_eq!(error.key.as_deref(), Some(key), "{context}");
        assert_eq!(error.value.as_deref(), value, "{context}");
        let got = error.requirement.as_deref().unwrap_or_default();
        assert!(got.starts_with(requirement), "{context}: requirement {got:?}");
        // The message names the key (a range's field beside its range) and a scalar value.
        let shown = [".min", ".max", ".scale", ".step"]
            .iter()
            .fold(key, |k, f| k.trim_end_matches(f));
        assert!(error.message().contains(shown), "{context}");
        if let Some(value) = value.filter(|v| !v.starts_with('[') && kind != UnknownKey) {
            assert!(error.message().contains(value.trim_matches('"')), "{context}");
        }
    }
}

#[test]
fn the_sweep_file_messages_keep_their_wording() {
    let error = sweep_error("[random]\nseed = 1\ncases = 2\n\"grid.size\" = { min = 2.0, max = 1.0 }");
    assert_eq!(error.to_string(), "random.\"grid.size\": min (2) > max (1)");
    let error = sweep_error("[random]\nseed = 1\ncases = 1000001\n\"grid.n\" = { min = 8, max = 16 }");
    assert_eq!(
        error.to_string(),
        "random.cases must be <= 100000 (the cap on a sweep's cases), got 1000001"
    );
    let error = sweep_error("[zip]\n\"grid.n\" = [8, 16]\n\"grid.size\" = [0.5]");
    assert_eq!(
        error.to_string(),
        "[zip] lists must have equal lengths: zip.\"grid.size\" has 1, zip.\"grid.n\" has 2"
    );
    // A key given twice names both places.
    let error = sweep_error("[set]\n\"grid.n\" = 8\n[vary]\n\"grid.n\" = [16]");
    assert_eq!(
        error.to_string(),
        "sweep key `grid.n` is given more than once (in [set], [vary], [zip] or [random]): vary.\"grid.n\" and set.\"grid.n\""
    );
    assert_eq!(error.key.as_deref(), Some("set.\"grid.n\""));
    // A case count over the cap is a quantity of several tables: no single key.
    let error = sweep_error("[vary]\n\"grid.n\" = [8, 9, 10, 11, 12, 13, 14, 15, 16, 17]\n[random]\nseed = 1\ncases = 100000\n\"grid.size\" = { min = 1.0, max = 2.0 }");
    assert_eq!(
        (error.key.as_deref(), error.value.as_deref()),
        (None, Some("1000000")),
        "{error}"
    );
    assert!(error.to_string().contains("1000000 cases"), "{error}");
}
