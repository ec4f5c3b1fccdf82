//! Unit tests of the checks of what the inputs imply (`guards.rs`): each case was accepted,
//! or blamed on the wrong key, before those checks existed.

use crate::tests::{error_of, MINIMAL};
use crate::*;

#[test]
fn an_extreme_modulus_is_blamed_not_the_depth() {
    // E* = 1e300: E*² overflows inside d_JKR, which becomes 0; the depth unit then made
    // `protocol.max_depth` look wrong.
    let error = error_of(MINIMAL, &["material.contact_modulus=1e300"]);
    assert!(error.contains("material.contact_modulus = 1e300"), "{error}");
    assert!(error.contains("d_JKR"), "{error}");
    assert!(!error.contains("protocol.max_depth must"), "{error}");
    let error = error_of(MINIMAL, &["adhesion.work_of_adhesion=1e-200"]);
    assert!(error.contains("adhesion.work_of_adhesion = 1e-200"), "{error}");
}

#[test]
fn a_quadratic_field_negative_inside_the_domain_is_refused() {
    // γ = γ0 [1 + (k − 1)(x/h)²] with k = 0.1 and h = 0.1 is negative for |x| > 0.105.
    let error = error_of(
        MINIMAL,
        &[
            "adhesion.field.kind=\"quadratic\"",
            "adhesion.field.ratio_edge_to_centre=0.1",
            "adhesion.field.half_length=0.1",
        ],
    );
    assert!(error.contains("adhesion.field.ratio_edge_to_centre = 0.1"), "{error}");
    assert!(error.contains("adhesion.field.half_length = 0.1"), "{error}");
    // A huge ratio overflows γ to infinity.
    let error = error_of(
        MINIMAL,
        &[
            "adhesion.field.kind=\"quadratic\"",
            "adhesion.field.ratio_edge_to_centre=1e308",
            "adhesion.field.half_length=0.01",
        ],
    );
    assert!(error.contains("finite and >= 0"), "{error}");
    // Within [1/k·…] the same field is fine: k = 0.5 stays positive up to |x| = √2 h.
    let fine = [
        "adhesion.field.kind=\"quadratic\"",
        "adhesion.field.ratio_edge_to_centre=0.5",
        "adhesion.field.half_length=0.5",
    ];
    let overrides: Vec<String> = fine.iter().map(|s| s.to_string()).collect();
    let valid = load(MINIMAL, "test", Path::new("."), &overrides).unwrap();
    assert!(valid.gamma.iter().all(|g| g.is_finite() && *g >= 0.0));
}

#[test]
fn step_counts_are_capped() {
    let error = error_of(MINIMAL, &["protocol.steps=10000000"]);
    assert!(
        error.contains("protocol.steps must be in 1..=1000000, got 10000000"),
        "{error}"
    );
    // A step so small that it implies more than MAX_STEPS approach steps.
    let text = MINIMAL.replace("depth_unit = \"jkr\"\nsteps = 30", "step = 1e-9");
    let error = error_of(&text, &[]);
    assert!(error.contains("protocol.step"), "{error}");
    assert!(error.contains("approach steps"), "{error}");
}

#[test]
fn a_step_below_the_floating_point_resolution_is_refused() {
    let text = MINIMAL.replace("depth_unit = \"jkr\"\nsteps = 30", "step = 1e-20");
    let text = text.replace("max_depth = 3.0", "max_depth = 1e+0");
    let error = error_of(&text, &[]);
    assert!(error.contains("protocol.step"), "{error}");
}

#[test]
fn coarse_grids_give_resolution_warnings() {
    let wavy = MINIMAL.replace(
        "shape = \"sphere\"\nradius = 1.0",
        "shape = \"wavy_sphere\"\nradius = 1.0\namplitude = 0.001\nwavelength = 0.1",
    );
    // Δ = 1/16 = 0.0625: λ = 0.1 spans 1.6 elements.
    let valid = load(&wavy, "test", Path::new("."), &[]).unwrap();
    assert!(
        valid
            .warnings
            .iter()
            .any(|w| w.contains("indenter.wavelength") && w.contains("1.60 elements")),
        "{:?}",
        valid.warnings
    );
    // a_JKR = (9π·0.01/(8·2))^{1/3} = 0.26 spans 4.2 elements: no warning at n = 16 ...
    let valid = load(MINIMAL, "test", Path::new("."), &[]).unwrap();
    assert!(valid.warnings.is_empty(), "{:?}", valid.warnings);
    // ... but 2.1 at n = 8.
    let valid = load(MINIMAL, "test", Path::new("."), &["grid.n=8".to_string()]).unwrap();
    assert!(
        valid.warnings.iter().any(|w| w.contains("a_JKR")),
        "{:?}",
        valid.warnings
    );
    let punch = MINIMAL
        .replace(
            "shape = \"sphere\"\nradius = 1.0",
            "shape = \"flat_punch\"\nradius = 0.05",
        )
        .replace("depth_unit = \"jkr\"\n", "")
        .replace("max_depth = 3.0", "max_depth = 0.001");
    let valid = load(&punch, "test", Path::new("."), &[]).unwrap();
    assert!(
        valid.warnings.iter().any(|w| w.contains("punch diameter")),
        "{:?}",
        valid.warnings
    );
    // Features smaller than one element (the first robustness audit, docs/reliability.md: these ran without a warning): a punch
    // of diameter 0.01 = 0.16 Δ (the grid makes it one element) and a wavelength of 0.16 Δ.
    let tiny_punch = punch.replace("radius = 0.05", "radius = 0.005");
    let valid = load(&tiny_punch, "test", Path::new("."), &[]).unwrap();
    assert!(
        valid
            .warnings
            .iter()
            .any(|w| w.contains("punch diameter") && w.contains("0.16 elements")),
        "{:?}",
        valid.warnings
    );
    let fine_waves = wavy.replace("wavelength = 0.1", "wavelength = 0.01");
    let valid = load(&fine_waves, "test", Path::new("."), &[]).unwrap();
    assert!(
        valid
            .warnings
            .iter()
            .any(|w| w.contains("indenter.wavelength") && w.contains("0.16 elements")),
        "{:?}",
        valid.warnings
    );
}

#[test]
fn the_memory_estimate_grows_with_the_grid() {
    let small = memory_estimate(256, BoundaryName::Free);
    let large = memory_estimate(16_384, BoundaryName::Free);
    // 16384² elements: at least the 2n-padded real buffers and the fields, ~ 0.1 TB.
    assert!(large > 50 << 30, "{large}");
    // Proportional to n² (up to the n/2 + 1 columns of the half spectrum).
    assert!((4090..=4096).contains(&(large / small)), "{}", large / small);
    assert!(memory_estimate(256, BoundaryName::Periodic) < small);
}

#[test]
fn a_grid_beyond_the_available_memory_is_refused_before_allocation() {
    let big = MINIMAL.replace("n = 16", "n = 8192");
    // 1 GiB available: n = 8192 needs tens of GiB.
    let limit = MemoryLimit {
        survives_lifting: false,
        bytes: 1 << 30,
        source: "a test's limit".to_string(),
    };
    let error = load_within(&big, "test", Path::new("."), &[], Some(&limit))
        .err()
        .unwrap();
    let error = format!("{error:#}");
    assert!(error.contains("grid.n = 8192 needs about"), "{error}");
    assert!(error.contains("1.0 GiB of memory available"), "{error}");
    assert!(error.contains("a test's limit"), "{error}");
    assert!(load_within(MINIMAL, "test", Path::new("."), &[], Some(&limit)).is_ok());
}

/// First robustness audit (docs/reliability.md): E*, γ0 beyond about 1e±30 passed validation and failed mid-run with "solver
/// produced a non-finite value" (the single-precision FFTs overflow); now refused first.
#[test]
fn units_beyond_single_precision_are_refused_before_the_run() {
    // Both cases ran into "solver produced a non-finite value at iteration 1" before.
    for (modulus, gamma) in [("1e60", "1e60"), ("1e-100", "1e-100")] {
        let overrides = [
            format!("material.contact_modulus={modulus}"),
            format!("adhesion.work_of_adhesion={gamma}"),
        ];
        let overrides: Vec<&str> = overrides.iter().map(String::as_str).collect();
        let error = error_of(MINIMAL, &overrides);
        assert!(error.contains("single-precision"), "{error}");
        assert!(
            error.contains(&format!("material.contact_modulus = {modulus}")),
            "{error}"
        );
        assert!(error.contains("grid.size = 1"), "{error}");
    }
    // A large pressure bound from the depth alone (E*·d/Δ = 1e31 without adhesion).
    let error = error_of(
        MINIMAL,
        &[
            "adhesion.work_of_adhesion=0",
            "protocol.depth_unit=\"length\"",
            "protocol.max_depth=1e29",
        ],
    );
    assert!(error.contains("pressure bound"), "{error}");
    assert!(error.contains("protocol.max_depth"), "{error}");
    // SI-like units far from 1 are fine: E* = 1e11 Pa, γ = 1 J/m², R = 1 m, L = 2 mm give
    // the same F/|F_JKR| as E* = 1, γ = 1e-11 (JKR depends on γ/(E*R) and L/R only).
    let pull_off = |modulus: &str, gamma: &str| {
        let overrides = [
            "grid.n=32".to_string(),
            "grid.size=2e-3".to_string(),
            format!("material.contact_modulus={modulus}"),
            format!("adhesion.work_of_adhesion={gamma}"),
        ];
        let valid = load(MINIMAL, "test", Path::new("."), &overrides).unwrap();
        let outcome = run(&valid, &mut ()).unwrap();
        assert!(outcome.records.iter().all(|r| r.force_normal.is_finite()));
        let RunResults::Indentation(results) = &outcome.results else {
            panic!("not an indentation")
        };
        results.max_adhesive_force / valid.derived.f_jkr.unwrap().abs()
    };
    let (si, unit) = (pull_off("1e11", "1"), pull_off("1", "1e-11"));
    assert!((si / unit - 1.0).abs() < 1e-6, "F/|F_JKR| = {si} (SI), {unit} (E* = 1)");
}

const ROLL: &str = r#"
[grid]
n = 32
size = 0.4
[material]
contact_modulus = 1.0
[adhesion]
work_of_adhesion = 2e-5
[indenter]
shape = "wavy_sphere"
radius = 1.0
amplitude = 5.627e-4
wavelength = 0.05
[protocol]
kind = "roll"
depth = 5.0
depth_unit = "jkr"
approach_steps = 10
distance = 2.0
distance_unit = "wavelength"
steps = 20
"#;

/// First robustness audit (docs/reliability.md): rolling far beyond the domain exited 0 with zero force and no warning.
/// At 5|d_JKR| the JKR contact radius is a = 0.0772 (R = E* = 1, γ = 2e-5), the domain's
/// half-width 0.2: the travel may reach X = 0.2 − 0.0772 = 0.1228 (2.46 λ).
#[test]
fn a_travel_beyond_the_domain_is_refused() {
    for kind in ["roll", "slide", "translate"] {
        let text = ROLL.replace("kind = \"roll\"", &format!("kind = \"{kind}\""));
        assert!(load(&text, "test", Path::new("."), &[]).is_ok(), "{kind}: 2λ fits");
        let error = error_of(&text, &["protocol.distance=50"]);
        assert!(
            error.contains("protocol.distance = 50 carries the contact off the grid"),
            "{error}"
        );
        assert!(error.contains("X = 2.5000e0"), "{error}");
        assert!(error.contains("a ≈ 7.72"), "{error}");
        assert!(error.contains("grid.size/2 = 2.0000e-1"), "{error}");
        assert!(error.contains("protocol.distance at most 2.455"), "{error}");
    }
    // Just inside and just outside the limit of 2.46 λ.
    assert!(load(ROLL, "test", Path::new("."), &["protocol.distance=2.4".into()]).is_ok());
    let error = error_of(ROLL, &["protocol.distance=2.5"]);
    assert!(error.contains("off the grid"), "{error}");
    // Without adhesion the Hertz radius √(R d) is used: d = 0.005 gives a = 0.0707. (A
    // wavy sphere without adhesion has the Johnson parameter 0, a legitimate value that
    // the check of the derived scales refused before.)
    let hertz = ROLL
        .replace("work_of_adhesion = 2e-5", "work_of_adhesion = 0.0")
        .replace("depth_unit = \"jkr\"", "depth_unit = \"length\"")
        .replace("depth = 5.0", "depth = 0.005")
        .replace("distance_unit = \"wavelength\"", "distance_unit = \"length\"");
    assert!(load(&hertz, "test", Path::new("."), &["protocol.distance=0.12".into()]).is_ok());
    let error = error_of(&hertz, &["protocol.distance=0.13"]);
    assert!(error.contains("Hertz contact radius"), "{error}");
    assert!(error.contains("a ≈ 7.07"), "{error}");
    assert!(error.contains("protocol.distance at most 1.29"), "{error}");
}

#[test]
fn per_element_critical_stresses_beyond_single_precision_are_refused() {
    // Second robustness audit (docs/reliability.md): a quadratic field of edge/centre ratio 1e296 keeps every γ finite (so the
    // field check passes), but σ_c of the outer elements leaves the single-precision range
    // (it overflowed mid-run). `check_field_stresses` must name the element, its γ and the
    // field's keys. (Maps with such values: the CLI test `guards.rs`
    // `adhesion_maps_beyond_single_precision_are_refused_naming_the_element`.)
    let overrides = [
        "adhesion.field.kind=\"quadratic\"",
        "adhesion.field.ratio_edge_to_centre=1e296",
        "adhesion.field.half_length=0.5",
    ];
    let error = error_of(MINIMAL, &overrides);
    assert!(error.contains("the critical stress σ_c = "), "{error}");
    assert!(error.contains("of the element at x = "), "{error}");
    assert!(error.contains("adhesion.field.ratio_edge_to_centre = 1e296"), "{error}");
    assert!(error.contains("single-precision"), "{error}");
    // A moderate ratio of the same field passes the check.
    let fine: Vec<String> = overrides.iter().map(|s| s.replace("1e296", "13")).collect();
    assert!(load(MINIMAL, "test", Path::new("."), &fine).is_ok());
}
