//! Unit tests of `adhesion.law` and its keys, and the Maugis–Dugdale scenarios run through
//! the same pipeline as `adhesim run`.

use crate::cohesive::{dugdale_pinning_estimate, dugdale_pinning_per_width};
use crate::tests::MINIMAL;
use crate::*;
use adhesim::analysis::reference::MaugisDugdale;
use adhesim::NormalSolver;
use std::path::Path;

/// The scenario `text` with `overrides`, read as `adhesim run` reads it.
fn loaded(text: &str, overrides: &[String]) -> ValidScenario {
    load(text, "test", Path::new("."), overrides).unwrap()
}

fn error_of(text: &str) -> String {
    load(text, "test", Path::new("."), &[])
        .err()
        .expect("an error")
        .to_string()
}

/// Maugis' λ = 2σ0·(R/(πγ0K²))^(1/3) of MINIMAL's sphere (R = 1, γ0 = 0.01, K = 4E*/3 = 8/3)
/// at the cohesive stress σ0 = `stress`: the closed form the reader's value is checked against.
fn maugis_of_minimal(stress: f64) -> f64 {
    2.0 * stress * (1.0 / (std::f64::consts::PI * 0.01 * (8.0f64 / 3.0).powi(2))).cbrt()
}

fn with_adhesion(keys: &str) -> String {
    MINIMAL.replace("work_of_adhesion = 0.01", &format!("work_of_adhesion = 0.01\n{keys}"))
}

/// Every error names the key at fault and its value; the JKR default takes no law keys.
#[test]
fn law_keys_are_checked_by_name() {
    let error = error_of(&with_adhesion("law = \"dugdale\"\ncohesive_stress = -1.0"));
    assert!(
        error.contains("adhesion.cohesive_stress must be > 0, got -1"),
        "{error}"
    );
    let error = error_of(&with_adhesion("law = \"dugdale\""));
    assert!(error.contains("needs adhesion.cohesive_stress"), "{error}");
    let error = error_of(&with_adhesion("law = \"dugdale\"\ncohesive_stress = 1.0\nrange = 0.1"));
    assert!(
        error.contains("adhesion.range is not a key of adhesion.law = \"dugdale\""),
        "{error}"
    );
    let error = error_of(&with_adhesion("cohesive_stress = 1.0"));
    assert!(
        error.contains("adhesion.cohesive_stress is not a key of adhesion.law = \"jkr\""),
        "{error}"
    );
    let error = error_of(&with_adhesion("law = \"exponential\"\nrange = 0"));
    assert!(error.contains("adhesion.range must be > 0, got 0"), "{error}");
    let error = error_of(&with_adhesion("law = \"exponential\""));
    assert!(error.contains("needs adhesion.range"), "{error}");
    let error = error_of(&with_adhesion(
        "law = \"exponential\"\nrange = 0.1\ncohesive_stress = 1.0",
    ));
    assert!(
        error.contains("adhesion.cohesive_stress is not a key of adhesion.law = \"exponential\""),
        "{error}"
    );
    let error = error_of(&with_adhesion("law = \"coulomb\""));
    assert!(error.contains("adhesion.law"), "{error}");
    let zero = with_adhesion("law = \"dugdale\"\ncohesive_stress = 1.0").replace("= 0.01", "= 0.0");
    let error = error_of(&zero.replace("depth_unit = \"jkr\"", "depth_unit = \"length\""));
    assert!(error.contains("needs adhesion.work_of_adhesion > 0, got 0"), "{error}");
}

/// Both cohesive laws build their solver on a periodic grid (depth control is mean-gap
/// control there, as for the sharp criterion).
#[test]
fn cohesive_laws_run_on_periodic_grids() {
    for keys in [
        "law = \"dugdale\"\ncohesive_stress = 1.0",
        "law = \"exponential\"\nrange = 0.1",
    ] {
        let periodic = with_adhesion(keys).replace("size = 1.0", "size = 1.0\nboundary = \"periodic\"");
        let scenario = loaded(&periodic, &[]);
        assert!(matches!(scenario.normal_solver(), NormalSolver::Cohesive(_)), "{keys}");
    }
}

/// `law` absent is `jkr`: the JKR solver, no Maugis parameter, and the echoed section
/// has no law key (summary.json unchanged); `dugdale` builds the cohesive solver.
#[test]
fn the_law_picks_the_solver() {
    let jkr = loaded(MINIMAL, &[]);
    assert!(matches!(jkr.normal_solver(), NormalSolver::Adhesive(_)));
    assert!(jkr.derived.maugis_parameter.is_none());
    let echoed = serde_json::to_string(&jkr.file.adhesion).unwrap();
    assert_eq!(echoed, r#"{"work_of_adhesion":0.01}"#);
    let dugdale = loaded(&with_adhesion("law = \"dugdale\"\ncohesive_stress = 0.5"), &[]);
    assert!(matches!(dugdale.normal_solver(), NormalSolver::Cohesive(_)));
    assert!((dugdale.derived.maugis_parameter.unwrap() - maugis_of_minimal(0.5)).abs() < 1e-12);
    assert!(dugdale.derived.tabor_parameter.is_none());
    let exponential = loaded(&with_adhesion("law = \"exponential\"\nrange = 0.05"), &[]);
    assert!(matches!(exponential.normal_solver(), NormalSolver::Cohesive(_)));
    // μ = (Rγ0²/(E*²ρ³))^(1/3) with E* = 2 (MINIMAL's material).
    let expected = (1e-4 / (4.0 * 0.05f64.powi(3))).cbrt();
    assert!((exponential.derived.tabor_parameter.unwrap() - expected).abs() < 1e-12);
    assert!(exponential.derived.maugis_parameter.is_none());
}

/// A zone of fewer than 15 elements at Maugis' pull-off is warned about, naming the keys;
/// the scenario files resolve it (λ = 1 at N = 256: 21.7 elements).
#[test]
fn an_unresolved_zone_is_warned_about() {
    let text = include_str!("../../../scenarios/cohesive/maugis_lambda1.toml");
    let resolved = loaded(text, &[]);
    assert!(resolved.warnings.is_empty(), "{:?}", resolved.warnings);
    let coarse = loaded(text, &["grid.n=64".to_string()]);
    let warning = coarse.warnings.join("\n");
    assert!(
        warning.contains("spans 5.4 elements") && warning.contains("grid.n") && warning.contains("about 7 %"),
        "{warning}"
    );
    // A zone inside one element gets no percentage (the first-order estimate would give
    // thousands of per cent): it says the law then acts as a stress criterion.
    let inside = loaded(text, &["adhesion.cohesive_stress=100".to_string()]);
    let warning = inside.warnings.join("\n");
    assert!(
        warning.contains("stress criterion") && !warning.contains(" %"),
        "{warning}"
    );
}

/// An exponential range whose cohesive length πE*ρ²/(4γ0) spans fewer than 2 elements is
/// warned about, naming the keys; `scenarios/cohesive/exponential_mu1.toml` resolves it.
#[test]
fn an_unresolved_exponential_range_is_warned_about() {
    let text = include_str!("../../../scenarios/cohesive/exponential_mu1.toml");
    let resolved = loaded(text, &[]);
    assert!(resolved.warnings.is_empty(), "{:?}", resolved.warnings);
    let coarse = loaded(text, &["grid.n=16".to_string()]);
    let warning = coarse.warnings.join("\n");
    assert!(
        warning.contains("cohesive length") && warning.contains("adhesion.range") && warning.contains("grid.n"),
        "{warning}"
    );
}

/// Runs a scenario of `scenarios/cohesive/` and returns (simulated, Maugis) largest
/// adhesive force.
fn maugis_scenario(text: &str, overrides: &[String]) -> (f64, f64) {
    let scenario = loaded(text, overrides);
    let outcome = run(&scenario, &mut ()).unwrap();
    let RunResults::Indentation(results) = outcome.results else {
        panic!("an indentation")
    };
    let adhesion = &scenario.file.adhesion;
    let model = MaugisDugdale {
        radius: 1.0,
        contact_modulus: scenario.material.contact_modulus(),
        work_of_adhesion: adhesion.work_of_adhesion,
        cohesive_stress: adhesion.cohesive_stress.unwrap(),
    };
    (results.max_adhesive_force, model.max_adhesive_force())
}

/// The issue's acceptance at λ = 0.3 (3 %) and 0.1 (5 %) through the run pipeline of
/// `adhesim run`, on the scenario files' grids: measured +0.71 % (N = 128, 27 elements
/// across the zone at pull-off) and +0.05 % (N = 128); about 2 s each.
#[test]
fn dugdale_scenarios_give_maugis_pull_off_at_small_lambda() {
    let (force, expected) = maugis_scenario(include_str!("../../../scenarios/cohesive/maugis_lambda0p3.toml"), &[]);
    assert!(
        (force / expected - 1.0).abs() < 0.03,
        "λ = 0.3: {force:e} vs {expected:e}"
    );
    let (force, expected) = maugis_scenario(include_str!("../../../scenarios/cohesive/maugis_lambda0p1.toml"), &[]);
    assert!(
        (force / expected - 1.0).abs() < 0.05,
        "λ = 0.1: {force:e} vs {expected:e}"
    );
}

/// λ = 1 within 3 % on its scenario's grid (N = 256, 22 elements across the zone):
/// measured +1.63 %, about 15 s on 2 cores. Run with
/// `cargo test --release -p adhesim-scenario dugdale_scenario_lambda_one -- --ignored`.
#[test]
#[ignore = "15 s: cargo test --release -p adhesim-scenario dugdale_scenario_lambda_one -- --ignored"]
fn dugdale_scenario_lambda_one_gives_maugis_pull_off() {
    let (force, expected) = maugis_scenario(include_str!("../../../scenarios/cohesive/maugis_lambda1.toml"), &[]);
    assert!(
        (force / expected - 1.0).abs() < 0.03,
        "λ = 1: {force:e} vs {expected:e}"
    );
}

/// The exponential law through the run pipeline: at μ = 1 the pull-off lies between the
/// JKR and DMT limits (1.5πγ0R < F < 2πγ0R; no closed form in between) and matches the
/// library's mesh-converged value 1.663πγ0R (N = 64 and 128 agree to 0.07 %,
/// docs/validation.md §11) within 0.5 %; about 5 s.
#[test]
fn exponential_scenario_pulls_off_between_the_limits() {
    let text = include_str!("../../../scenarios/cohesive/exponential_mu1.toml");
    let scenario = loaded(text, &[]);
    assert!((scenario.derived.tabor_parameter.unwrap() - 1.0).abs() < 1e-6);
    let outcome = run(&scenario, &mut ()).unwrap();
    let RunResults::Indentation(results) = outcome.results else {
        panic!("an indentation")
    };
    let ratio = results.max_adhesive_force / (std::f64::consts::PI * 1e-4);
    assert!((ratio / 1.663 - 1.0).abs() < 5e-3, "F/(πγ0R) = {ratio}");
    assert!(results.dissipated_energy > 0.0);
}

/// `law = "trapezoid"` needs σ0 and s ∈ (0, 1], takes no range, and reports Maugis' λ of
/// its σ0; the other laws refuse `softening_fraction`.
#[test]
fn trapezoid_keys_are_checked_by_name() {
    let error = error_of(&with_adhesion("law = \"trapezoid\"\nsoftening_fraction = 0.5"));
    assert!(error.contains("needs adhesion.cohesive_stress"), "{error}");
    let error = error_of(&with_adhesion("law = \"trapezoid\"\ncohesive_stress = 1.0"));
    assert!(error.contains("needs adhesion.softening_fraction"), "{error}");
    for (value, shown) in [("0.0", "0"), ("-0.5", "-0.5")] {
        let keys = format!("law = \"trapezoid\"\ncohesive_stress = 1.0\nsoftening_fraction = {value}");
        let error = error_of(&with_adhesion(&keys));
        assert!(
            error.contains(&format!("adhesion.softening_fraction must be > 0, got {shown}")),
            "{error}"
        );
    }
    let error = error_of(&with_adhesion(
        "law = \"trapezoid\"\ncohesive_stress = 1.0\nsoftening_fraction = 1.5",
    ));
    assert!(
        error.contains("adhesion.softening_fraction must be in (0, 1]") && error.contains("got 1.5"),
        "{error}"
    );
    let error = error_of(&with_adhesion(
        "law = \"trapezoid\"\ncohesive_stress = 1.0\nsoftening_fraction = 0.5\nrange = 0.1",
    ));
    assert!(
        error.contains("adhesion.range is not a key of adhesion.law = \"trapezoid\""),
        "{error}"
    );
    let error = error_of(&with_adhesion(
        "law = \"dugdale\"\ncohesive_stress = 1.0\nsoftening_fraction = 0.5",
    ));
    assert!(
        error.contains("adhesion.softening_fraction is not a key of adhesion.law = \"dugdale\""),
        "{error}"
    );
    let error = error_of(&with_adhesion("softening_fraction = 0.5"));
    assert!(
        error.contains("adhesion.softening_fraction is not a key of adhesion.law = \"jkr\""),
        "{error}"
    );
    let trapezoid = loaded(
        &with_adhesion("law = \"trapezoid\"\ncohesive_stress = 0.5\nsoftening_fraction = 1.0"),
        &[],
    );
    assert!(matches!(trapezoid.normal_solver(), NormalSolver::Cohesive(_)));
    assert!((trapezoid.derived.maugis_parameter.unwrap() - maugis_of_minimal(0.5)).abs() < 1e-12);
}

/// The trapezoidal law on the smooth sphere of `maugis_lambda0p3.toml` (λ = 0.3 of its σ0,
/// N = 128), the pull-off over πγ0R with `overrides`.
fn maugis_lambda0p3_pull_off(overrides: &[&str]) -> f64 {
    let text = include_str!("../../../scenarios/cohesive/maugis_lambda0p3.toml");
    let overrides: Vec<String> = overrides.iter().map(|o| o.to_string()).collect();
    let outcome = run(&loaded(text, &overrides), &mut ()).unwrap();
    let RunResults::Indentation(results) = outcome.results else {
        panic!("an indentation")
    };
    results.max_adhesive_force / (std::f64::consts::PI * 1e-4)
}

/// The triangle (s = 1) pulls off between the JKR and DMT limits (1.5πγ0R < F < 2πγ0R;
/// measured 1.847πγ0R against Dugdale's 1.828: the triangle of the same σ0 reaches twice
/// as far, a smaller λ). About 4 s.
#[test]
fn trapezoid_pulls_off_between_the_limits() {
    let triangle = maugis_lambda0p3_pull_off(&["adhesion.law=\"trapezoid\"", "adhesion.softening_fraction=1.0"]);
    assert!(triangle > 1.5 && triangle < 2.0, "s = 1: F/(πγ0R) = {triangle}");
}

/// At s = 0.2 the trapezoid pulls off between the limits and within 3 % of Dugdale's on the
/// same grid and σ0 (the law differs from Dugdale's only in the last 20 % of its range;
/// measured −0.67 %). About 10 s on 2 busy cores.
#[test]
#[ignore = "10 s: cargo test --release -p adhesim-scenario trapezoid -- --ignored"]
fn trapezoid_pulls_off_near_dugdale() {
    let dugdale = maugis_lambda0p3_pull_off(&[]);
    let trapezoid = maugis_lambda0p3_pull_off(&["adhesion.law=\"trapezoid\"", "adhesion.softening_fraction=0.2"]);
    assert!(trapezoid > 1.5 && trapezoid < 2.0, "s = 0.2: F/(πγ0R) = {trapezoid}");
    assert!((trapezoid / dugdale - 1.0).abs() < 0.03, "{trapezoid} vs {dugdale}");
}

/// The trapezoid at its smallest accepted softening fraction (1e-6) is Maugis–Dugdale: on
/// `maugis_lambda0p3.toml` its pull-off lies within 3 % of Maugis' closed form (the first-
/// order mesh error of the zone's edge, as for Dugdale's law on this grid: measured
/// +0.71 %), and its dissipated energy within 0.1 % of the Dugdale run's (the laws differ
/// in the last 1e-6 of the range; measured 5e-12; the bound leaves room for the rounds'
/// coarser stop at small s). Below 1e-6 the run is refused naming the key: at s ≤ 1e-7 the
/// rounds' traction resolution σ0·1e-7/s reached σ0 and the run dissipated exactly 0.
/// About 4 s.
#[test]
fn trapezoid_near_the_dugdale_limit_matches_maugis_or_is_refused() {
    let text = include_str!("../../../scenarios/cohesive/maugis_lambda0p3.toml");
    let results = |overrides: &[String]| {
        let outcome = run(&loaded(text, overrides), &mut ()).unwrap();
        let RunResults::Indentation(results) = outcome.results else {
            panic!("an indentation")
        };
        results
    };
    let trapezoid = |s: f64| {
        vec![
            "adhesion.law=\"trapezoid\"".to_string(),
            format!("adhesion.softening_fraction={s:e}"),
        ]
    };
    let dugdale = results(&[]);
    let smallest = results(&trapezoid(crate::cohesive::MIN_SOFTENING_FRACTION));
    let scenario = loaded(text, &[]);
    let maugis = MaugisDugdale {
        radius: 1.0,
        contact_modulus: scenario.material.contact_modulus(),
        work_of_adhesion: scenario.file.adhesion.work_of_adhesion,
        cohesive_stress: scenario.file.adhesion.cohesive_stress.unwrap(),
    }
    .max_adhesive_force();
    let pull_off_error = smallest.max_adhesive_force / maugis - 1.0;
    assert!(
        pull_off_error.abs() < 0.03,
        "pull-off {:+.2} % off Maugis",
        100.0 * pull_off_error
    );
    assert!(dugdale.dissipated_energy > 0.0);
    let mismatch = smallest.dissipated_energy / dugdale.dissipated_energy - 1.0;
    assert!(
        mismatch.abs() < 1e-3,
        "dissipated {:e}, Dugdale's {:e}",
        smallest.dissipated_energy,
        dugdale.dissipated_energy
    );
    for s in ["9.9e-7", "1e-7", "1e-9"] {
        let overrides = [
            "adhesion.law=\"trapezoid\"".to_string(),
            format!("adhesion.softening_fraction={s}"),
        ];
        let error = load(text, "test", Path::new("."), &overrides)
            .err()
            .expect("refused")
            .to_string();
        assert!(
            error.contains(&format!("adhesion.softening_fraction = {s} is below 1e-6"))
                && error.contains("adhesion.law = \"dugdale\""),
            "{error}"
        );
    }
}

/// Every cohesive law is accepted for every translation; Dugdale with a warning that
/// names its lattice pinning and the trapezoid that removes it (docs/validation.md §15),
/// the trapezoid and the exponential law (resolved here) without one.
#[test]
fn every_law_runs_under_translation_dugdale_with_its_pinning_warned() {
    let text = include_str!("../../../scenarios/fig6.toml");
    let with = |keys: &[&str], kind: &str| -> Vec<String> {
        let mut overrides: Vec<String> = keys.iter().map(|k| k.to_string()).collect();
        overrides.push(format!("protocol.kind=\"{kind}\""));
        overrides
    };
    let pinning = |scenario: &ValidScenario| scenario.warnings.iter().any(|w| w.contains("the grid pins it"));
    for kind in ["roll", "slide", "translate"] {
        let dugdale = with(&["adhesion.law=\"dugdale\"", "adhesion.cohesive_stress=0.05"], kind);
        let scenario = load(text, "test", Path::new("."), &dugdale).unwrap();
        let warning = scenario.warnings.iter().find(|w| w.contains("the grid pins it"));
        assert!(
            warning.is_some_and(|w| w.contains(&format!("protocol.kind = \"{kind}\"")) && w.contains("\"trapezoid\"")),
            "{:?}",
            scenario.warnings
        );
        for accepted in [
            with(
                &[
                    "adhesion.law=\"trapezoid\"",
                    "adhesion.cohesive_stress=0.05",
                    "adhesion.softening_fraction=1.0",
                ],
                kind,
            ),
            with(&["adhesion.law=\"exponential\"", "adhesion.range=4e-4"], kind),
        ] {
            let scenario = load(text, "test", Path::new("."), &accepted).unwrap();
            assert!(!pinning(&scenario), "{accepted:?}: {:?}", scenario.warnings);
        }
    }
    let indentation = load(
        include_str!("../../../scenarios/fig1.toml"),
        "test",
        Path::new("."),
        &["adhesion.law=\"dugdale\"".into(), "adhesion.cohesive_stress=0.2".into()],
    )
    .unwrap();
    assert!(!pinning(&indentation), "{:?}", indentation.warnings);
    // A zone far inside one element: the estimate is given with the caveat that it was
    // not measured there.
    let unresolved = load(
        text,
        "test",
        Path::new("."),
        &with(&["adhesion.law=\"dugdale\"", "adhesion.cohesive_stress=1e3"], "roll"),
    )
    .unwrap();
    assert!(
        unresolved
            .warnings
            .iter()
            .any(|w| w.contains("the grid pins it") && w.contains("was not measured")),
        "{:?}",
        unresolved.warnings
    );
}

/// Dugdale's rolling resistance on the smooth sphere of `fig6.toml` (amplitude 0, whose
/// true rolling resistance is 0) is the grid's: it halves with the element size (first
/// order; a resolved zone would give 4 or more per halving, a physical resistance 1),
/// measured 7.07e-7 at N = 64 and 3.85e-7 at N = 128 (ratio 1.84, ℓ = 4 and 8 elements at
/// σ0 = 0.025). Each is the lattice estimate γ0·2b·Δ/ℓ within 0.8–1.3 (measured 1.03 and
/// 1.12; docs/validation.md §15 measured 0.88–1.11 over grids and σ0), which the summary
/// sets beside F_T. About 2 s.
#[test]
fn a_dugdale_roll_on_the_smooth_sphere_is_pinned_at_first_order_in_the_element() {
    let mut forces = Vec::new();
    for n in ["64", "128"] {
        let grid = format!("grid.n={n}");
        let (scenario, results) = rolled(&[
            "indenter.amplitude=0",
            "adhesion.law=\"dugdale\"",
            "adhesion.cohesive_stress=0.025",
            &grid,
        ]);
        let force = results.mean_tangential_force.unwrap();
        let estimate = 2.0 * results.contact_half_width * dugdale_pinning_per_width(0.025, scenario.grid.dx(), 1.0);
        assert!(
            (0.8..1.3).contains(&(force / estimate)),
            "N = {n}: F_T = {force:e}, estimate {estimate:e}"
        );
        let message = dugdale_pinning_estimate(&scenario, &RunResults::Translation(results)).unwrap();
        assert!(message.contains(&format!("{estimate:.4e}")), "{message}");
        forces.push(force);
    }
    let ratio = forces[0] / forces[1];
    assert!((1.5..2.5).contains(&ratio), "F_T(64)/F_T(128) = {ratio}");
}

/// Runs `fig6.toml` (a roll) with `overrides` and returns its results.
fn rolled(overrides: &[&str]) -> (ValidScenario, TranslationResults) {
    let text = include_str!("../../../scenarios/fig6.toml");
    let overrides: Vec<String> = overrides.iter().map(|o| o.to_string()).collect();
    let scenario = loaded(text, &overrides);
    let outcome = run(&scenario, &mut ()).unwrap();
    let RunResults::Translation(results) = outcome.results else {
        panic!("a roll")
    };
    (scenario, results)
}

/// The trapezoid does not pin its zone's edge to the grid: on the smooth sphere of
/// `fig6.toml` (amplitude 0, N = 64, σ0 = 0.05, s = 1), whose true rolling resistance is 0,
/// |F_T| stays below 1 % of Dugdale's lattice pinning γ0·2b·Δ/ℓ (ℓ = πE*γ0/(4σ0²);
/// Dugdale measures 1.0–1.1 times it, docs/validation.md §15). Measured |F_T| ≈ 4e-14
/// against 3.0e-6 (docs/validation.md §16). About 3 s.
#[test]
fn a_trapezoid_roll_on_the_smooth_sphere_is_not_pinned() {
    let (scenario, results) = rolled(&[
        "indenter.amplitude=0",
        "adhesion.law=\"trapezoid\"",
        "adhesion.cohesive_stress=0.05",
        "adhesion.softening_fraction=1.0",
    ]);
    let gamma = 2e-5;
    let length = std::f64::consts::PI * gamma / (4.0 * 0.05 * 0.05);
    let pinning = gamma * 2.0 * results.contact_half_width * scenario.grid.dx() / length;
    let force = results.mean_tangential_force.unwrap();
    assert!(
        force.abs() < 0.01 * pinning,
        "F_T = {force:e}, Dugdale's pinning {pinning:e}"
    );
}

/// Cohesive rolls converge and book their energy: the dissipation summed over the jumps
/// equals the work of the tangential force, ∮F_T dX, within 5 % (the roll covers 2λ from a
/// fresh contact, not a periodic steady state; §15 measured 0.97–1.02 on every cohesive
/// roll). The wavy sphere of `fig6.toml` at N = 64 with a trapezoid of s = 0.5 is a roll
/// whose accelerated rounds used to cycle for ever at step 70 ("no stable contact set after
/// 500 rounds", docs/validation.md §16); measured ratio 1.007. The exponential law at
/// ρ = 4e-4 (its cohesive length one element) was refused under translation; measured 0.996.
#[test]
fn cohesive_rolls_converge_and_book_their_energy() {
    for keys in [
        &[
            "grid.n=64",
            "adhesion.law=\"trapezoid\"",
            "adhesion.cohesive_stress=0.05",
            "adhesion.softening_fraction=0.5",
        ][..],
        &["grid.n=64", "adhesion.law=\"exponential\"", "adhesion.range=4e-4"][..],
    ] {
        let (_, results) = rolled(keys);
        let ratio = results.energy_balance_ratio.unwrap();
        assert!((ratio - 1.0).abs() < 0.05, "{keys:?}: energy balance {ratio}");
    }
}

/// A translation whose trapezoidal softening length spans under one element is warned
/// about, naming the keys; fig6's N = 64 at σ0 = 0.05, s = 1 (1.0 element) is not.
#[test]
fn an_unresolved_softening_length_is_warned_about_under_translation() {
    let text = include_str!("../../../scenarios/fig6.toml");
    let keys = |s: &str| {
        vec![
            "adhesion.law=\"trapezoid\"".to_string(),
            "adhesion.cohesive_stress=0.05".to_string(),
            format!("adhesion.softening_fraction={s}"),
        ]
    };
    // (The Maugis zone at pull-off, 0.8 elements, is warned about as for Dugdale.)
    let resolved = loaded(text, &keys("1.0"));
    assert!(
        !resolved.warnings.iter().any(|w| w.contains("softening length")),
        "{:?}",
        resolved.warnings
    );
    let coarse = loaded(text, &keys("0.2"));
    let warning = coarse.warnings.join("\n");
    assert!(
        warning.contains("softening length") && warning.contains("adhesion.softening_fraction = 0.2"),
        "{warning}"
    );
}

fn law_of(keys: &str) -> AdhesionLaw {
    loaded(&with_adhesion(keys), &[]).law
}

/// The validated scenario carries each law with the parameters the file gives, and no
/// other: what the run builds its solver from.
#[test]
fn each_law_is_read_with_its_own_parameters() {
    assert_eq!(law_of(""), AdhesionLaw::Jkr);
    assert_eq!(law_of("law = \"jkr\""), AdhesionLaw::Jkr);
    assert_eq!(
        law_of("law = \"dugdale\"\ncohesive_stress = 0.25"),
        AdhesionLaw::Dugdale { cohesive_stress: 0.25 }
    );
    assert_eq!(
        law_of("law = \"exponential\"\nrange = 0.002"),
        AdhesionLaw::Exponential { range: 0.002 }
    );
    let trapezoid = law_of("law = \"trapezoid\"\ncohesive_stress = 0.25\nsoftening_fraction = 0.5");
    assert_eq!(
        trapezoid,
        AdhesionLaw::Trapezoid {
            cohesive_stress: 0.25,
            softening_fraction: 0.5
        }
    );
    assert_eq!(trapezoid.name(), LawName::Trapezoid);
    assert_eq!(trapezoid.cohesive_stress(), Some(0.25));
    assert_eq!(law_of("law = \"exponential\"\nrange = 0.002").cohesive_stress(), None);
}

/// Another law's key is refused as an unknown key, naming the law it belongs to.
#[test]
fn a_key_of_another_law_is_refused_by_name() {
    let section = AdhesionSection {
        work_of_adhesion: 0.01,
        field: None,
        law: Some(LawName::Dugdale),
        cohesive_stress: Some(0.25),
        softening_fraction: None,
        range: Some(0.002),
        first_contact_factor: None,
        aging: None,
    };
    let error = crate::cohesive::adhesion_law(&section).unwrap_err();
    let error = error.downcast_ref::<ScenarioError>().expect("a ScenarioError");
    assert_eq!(error.kind, ErrorKind::UnknownKey);
    assert_eq!(error.key.as_deref(), Some("adhesion.range"));
    assert!(error.to_string().contains("range to \"exponential\""), "{error}");
}
