//! Unit tests of the checks of what the inputs imply (`guards.rs`): each case was accepted,
//! or blamed on the wrong key, before those checks existed.

use crate::*;

const SPHERE: &str = r#"
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

fn error_of(text: &str, overrides: &[&str]) -> String {
    let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    match load(text, "test", Path::new("."), &overrides) {
        Ok(_) => panic!("accepted: {overrides:?}"),
        Err(e) => format!("{e:#}"),
    }
}

#[test]
fn an_extreme_modulus_is_blamed_not_the_depth() {
    // E* = 1e300: E*² overflows inside d_JKR, which becomes 0; the depth unit then made
    // `protocol.max_depth` look wrong.
    let error = error_of(SPHERE, &["material.contact_modulus=1e300"]);
    assert!(error.contains("material.contact_modulus = 1e300"), "{error}");
    assert!(error.contains("d_JKR"), "{error}");
    assert!(!error.contains("protocol.max_depth must"), "{error}");
    let error = error_of(SPHERE, &["adhesion.work_of_adhesion=1e-200"]);
    assert!(error.contains("adhesion.work_of_adhesion = 1e-200"), "{error}");
}

#[test]
fn a_quadratic_field_negative_inside_the_domain_is_refused() {
    // γ = γ0 [1 + (k − 1)(x/h)²] with k = 0.1 and h = 0.1 is negative for |x| > 0.105.
    let error = error_of(
        SPHERE,
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
        SPHERE,
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
    let valid = load(SPHERE, "test", Path::new("."), &overrides).unwrap();
    assert!(valid.gamma.iter().all(|g| g.is_finite() && *g >= 0.0));
}

#[test]
fn step_counts_are_capped() {
    let error = error_of(SPHERE, &["protocol.steps=10000000"]);
    assert!(
        error.contains("protocol.steps must be in 1..=1000000, got 10000000"),
        "{error}"
    );
    // A step so small that it implies more than MAX_STEPS approach steps.
    let text = SPHERE.replace("depth_unit = \"jkr\"\nsteps = 30", "step = 1e-9");
    let error = error_of(&text, &[]);
    assert!(error.contains("protocol.step"), "{error}");
    assert!(error.contains("approach steps"), "{error}");
}

#[test]
fn a_step_below_the_floating_point_resolution_is_refused() {
    let text = SPHERE.replace("depth_unit = \"jkr\"\nsteps = 30", "step = 1e-20");
    let text = text.replace("max_depth = 3.0", "max_depth = 1e+0");
    let error = error_of(&text, &[]);
    assert!(error.contains("protocol.step"), "{error}");
}

#[test]
fn coarse_grids_give_resolution_warnings() {
    let wavy = SPHERE.replace(
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
    let valid = load(SPHERE, "test", Path::new("."), &[]).unwrap();
    assert!(valid.warnings.is_empty(), "{:?}", valid.warnings);
    // ... but 2.1 at n = 8.
    let valid = load(SPHERE, "test", Path::new("."), &["grid.n=8".to_string()]).unwrap();
    assert!(
        valid.warnings.iter().any(|w| w.contains("a_JKR")),
        "{:?}",
        valid.warnings
    );
    let punch = SPHERE
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
    let big = SPHERE.replace("n = 16", "n = 8192");
    // 1 GiB available: n = 8192 needs tens of GiB.
    let error = load_within(&big, "test", Path::new("."), &[], Some(1 << 30))
        .err()
        .unwrap();
    let error = format!("{error:#}");
    assert!(error.contains("grid.n = 8192 needs about"), "{error}");
    assert!(error.contains("1.0 GiB of memory available"), "{error}");
    assert!(load_within(SPHERE, "test", Path::new("."), &[], Some(1 << 30)).is_ok());
}
