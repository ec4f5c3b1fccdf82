//! Fuzz test of the scenario reader, validator and pipeline (docs/reliability.md, "Fuzz
//! test"): scenario texts built from the repository's scenario files, with a line dropped
//! now and then and random `--set` overrides drawn from the key list whose values are
//! mutated (NaN, ±inf, 0, negatives, 1e±300, wrong types, garbage). Asserted through the
//! library API:
//! - nothing panics (reading, overriding, validating or running);
//! - an error names a key (a dotted key, a `[section]`, or the word "key") or the file;
//! - a scenario that validates with a small grid runs to `Ok` with only finite numbers in
//!   its records and results, or to an `Err` with a message.
//!
//! The seed is fixed so that a failure reproduces; `PROPTEST_CASES` sets the case count
//! (default [`DEFAULT_CASES`], about 16 s in `cargo test --release`). A longer run:
//! `PROPTEST_CASES=20000 cargo test --release -p adhesim-scenario --test integration fuzz::`.
//! `PROPTEST_RNG_SEED=N` draws other cases; `FUZZ_SLOW=1` lists the runs that take over 0.2 s and
//! `FUZZ_ERRORS=1` the errors of runs (with `-- --nocapture`).

use adhesim_scenario::{load_within, run, MemoryLimit, RunResults, ValidScenario};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, RngSeed, TestCaseError, TestRunner};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};

/// Cases of the default suite.
const DEFAULT_CASES: u32 = 800;
/// The fixed seed (any value; fixed so that every run draws the same cases).
const SEED: u64 = 20_261_123;
/// Largest grid side that is run (validation runs for every size).
const RUN_MAX_N: usize = 24;
/// Largest expected step count that is run.
const RUN_MAX_STEPS: usize = 60;
/// Memory allowed to a scenario, so that a mutated `grid.n` is refused before it allocates.
const AVAILABLE_MEMORY: u64 = 1 << 30;

const SCENARIOS: [(&str, &str); 16] = [
    ("fig1.toml", include_str!("../../../../scenarios/fig1.toml")),
    (
        "fig12_homogeneous.toml",
        include_str!("../../../../scenarios/fig12_homogeneous.toml"),
    ),
    (
        "fig12_ratio13.toml",
        include_str!("../../../../scenarios/fig12_ratio13.toml"),
    ),
    (
        "fig12_ratio20.toml",
        include_str!("../../../../scenarios/fig12_ratio20.toml"),
    ),
    ("fig2_h029.toml", include_str!("../../../../scenarios/fig2_h029.toml")),
    ("fig2_h050.toml", include_str!("../../../../scenarios/fig2_h050.toml")),
    ("fig2_h090.toml", include_str!("../../../../scenarios/fig2_h090.toml")),
    ("fig2_h120.toml", include_str!("../../../../scenarios/fig2_h120.toml")),
    ("fig4.toml", include_str!("../../../../scenarios/fig4.toml")),
    ("fig6.toml", include_str!("../../../../scenarios/fig6.toml")),
    (
        "fig6_translate_control.toml",
        include_str!("../../../../scenarios/fig6_translate_control.toml"),
    ),
    ("fig9.toml", include_str!("../../../../scenarios/fig9.toml")),
    ("hertz.toml", include_str!("../../../../scenarios/hertz.toml")),
    ("jkr.toml", include_str!("../../../../scenarios/jkr.toml")),
    (
        "rough_sphere.toml",
        include_str!("../../../../scenarios/rough_sphere.toml"),
    ),
    (
        "layer/thin_sphere.toml",
        include_str!("../../../../scenarios/layer/thin_sphere.toml"),
    ),
];

/// Every key of the scenario format (`docs/cli.md`), plus two that do not exist.
const KEYS: [&str; 69] = [
    "grid.n",
    "grid.size",
    "grid.boundary",
    "material.contact_modulus",
    "material.youngs_modulus",
    "material.poisson_ratio",
    "material.thickness",
    "material.base",
    "adhesion.work_of_adhesion",
    "adhesion.field",
    "adhesion.field.kind",
    "adhesion.field.ratio_edge_to_centre",
    "adhesion.field.axis",
    "adhesion.field.half_length",
    "adhesion.field.file",
    "indenter.shape",
    "indenter.radius",
    "indenter.amplitude",
    "indenter.wavelength",
    "indenter.angle",
    "indenter.semi_axes",
    "indenter.file",
    "indenter.spacing",
    "protocol.kind",
    "protocol.max_depth",
    "protocol.depth_unit",
    "protocol.depth",
    "protocol.distance",
    "protocol.distance_unit",
    "protocol.approach_steps",
    "protocol.return_stroke",
    "protocol.stationary_from",
    "protocol.substrate_angle",
    "protocol.steps",
    "protocol.step",
    "protocol.max_retract_steps",
    "output.snapshot_steps",
    "output.snapshot_every",
    "output.jump_snapshot_elements",
    "output.jump_force_threshold",
    "output.max_snapshots",
    "output.min_fit_radius",
    "analysis.gamma_approach",
    "analysis.gamma_pulloff",
    "analysis.tau0",
    "roughness.hurst",
    "roughness.rms_height",
    "roughness.rms_slope",
    "roughness.rolloff_wavelength",
    "roughness.cutoff_wavelength",
    "roughness.seed",
    "roughness.mode",
    "roughness.file",
    "roughness.detrend",
    "roughness.spacing",
    "roughness.channel",
    "substrate_roughness.hurst",
    "substrate_roughness.rms_height",
    "substrate_roughness.rms_slope",
    "substrate_roughness.rolloff_wavelength",
    "substrate_roughness.cutoff_wavelength",
    "substrate_roughness.seed",
    "substrate_roughness.mode",
    "substrate_roughness.file",
    "substrate_roughness.detrend",
    "substrate_roughness.spacing",
    "substrate_roughness.channel",
    "grid.no_such_key",
    "no_such_section.key",
];

/// Values of every class a hostile user tries, as `--set` text.
const VALUES: [&str; 52] = [
    "nan",
    "+nan",
    "inf",
    "-inf",
    "0",
    "0.0",
    "-0.0",
    "-1",
    "-0.5",
    "1",
    "2",
    "7",
    "16",
    "33",
    "1e300",
    "-1e300",
    "1e-300",
    "-1e-300",
    "1e-12",
    "9223372036854775807",
    "-9223372036854775808",
    "65536",
    "\"text\"",
    "\"\"",
    "[1, 2]",
    "[]",
    "[nan, inf]",
    "{ a = 1 }",
    "{ kind = \"quadratic\", ratio_edge_to_centre = -3 }",
    "{ kind = \"map\", file = \"no_such.npy\" }",
    "true",
    "false",
    "\"sphere\"",
    "\"flat_punch\"",
    "\"elliptic_punch\"",
    "\"periodic\"",
    "\"roll\"",
    "\"translate\"",
    "\"jkr\"",
    "\"wavelength\"",
    "\"rough_sphere\"",
    "\"rough_flat\"",
    "\"filtered\"",
    "\"slide\"",
    "{ hurst = 0.5, rms_slope = 0.1, seed = 2 }",
    // Second robustness audit (docs/reliability.md): file keys naming a folder or a device (a
    // device read without end, a folder failed with a bare "Is a directory"), per-element γ
    // beyond the solver's range.
    "\".\"",
    "\"/dev/zero\"",
    "{ kind = \"map\", file = \".\" }",
    "{ kind = \"map\", file = \"/dev/zero\" }",
    "{ kind = \"quadratic\", ratio_edge_to_centre = 1e296 }",
    "{ kind = \"quadratic\", ratio_edge_to_centre = 1e-303 }",
    "{ file = \".\", spacing = 0.01 }",
];

/// One override: a key (sometimes garbage) and a value (sometimes garbage or a scaled
/// original value).
fn override_strategy() -> impl Strategy<Value = String> {
    let key = prop_oneof![
        8 => prop::sample::select(&KEYS[..]).prop_map(str::to_string),
        1 => "[a-z._ ]{0,12}",
    ];
    let value = prop_oneof![
        6 => prop::sample::select(&VALUES[..]).prop_map(str::to_string),
        2 => (-8i32..8, 1u32..10).prop_map(|(e, m)| format!("{m}e{e}")),
        1 => prop::collection::vec(any::<u8>(), 0..16)
            .prop_map(|bytes| String::from_utf8_lossy(&bytes).into_owned()),
    ];
    (key, value).prop_map(|(key, value)| format!("{key}={value}"))
}

/// Keeps a run to milliseconds unless an override changes it again; the step keys are
/// those of the file's protocol (the others are refused as unused).
fn small_run_overrides(text: &str, n: usize, steps: usize) -> Vec<String> {
    let kind = text
        .parse::<toml::Table>()
        .ok()
        .and_then(|t| t.get("protocol")?.get("kind")?.as_str().map(str::to_string));
    let mut overrides = vec![format!("grid.n={n}"), format!("protocol.steps={steps}")];
    if kind.as_deref() == Some("indent_pulloff") {
        overrides.push("protocol.max_retract_steps=24".to_string());
    } else {
        overrides.push(format!("protocol.approach_steps={steps}"));
    }
    overrides
}

fn dotted_key_in(message: &str) -> bool {
    const SECTIONS: [&str; 11] = [
        "grid",
        "material",
        "adhesion",
        "indenter",
        "protocol",
        "output",
        "analysis",
        "roughness",
        "substrate_roughness",
        "friction",
        "--set",
    ];
    message.contains("key")
        || SECTIONS
            .iter()
            .any(|s| message.contains(&format!("{s}.")) || message.contains(&format!("[{s}]")))
}

/// Ok(true) for a run to Ok, Ok(false) for a run to Err with a message; Err unless the records or results hold a non-finite number.
fn check_finite(valid: &ValidScenario) -> Result<bool, String> {
    let outcome = match catch_unwind(AssertUnwindSafe(|| run(valid, &mut ()))) {
        Err(_) => return Err("run panicked".to_string()),
        Ok(Err(error)) if error.to_string().trim().is_empty() => {
            return Err("run failed with an empty message".to_string())
        }
        Ok(Err(error)) => {
            if std::env::var_os("FUZZ_ERRORS").is_some() {
                eprintln!("run error: {error}");
            }
            return Ok(false);
        }
        Ok(Ok(outcome)) => outcome,
    };
    for r in &outcome.records {
        let numbers = [
            r.depth,
            r.offset,
            r.force_normal,
            r.force_tangential,
            r.force_tangential_before_change,
            r.area,
            r.radius,
            r.half_width,
            r.cumulative_dissipated_energy,
            r.report.force_before_change,
            r.report.force,
            r.report.energy_before_change,
            r.report.energy,
        ];
        if let Some(x) = numbers.iter().find(|x| !x.is_finite()) {
            return Err(format!("record of step {} holds {x}: {r:?}", r.step));
        }
    }
    let results = match &outcome.results {
        RunResults::Indentation(results) => toml::Value::try_from(results),
        RunResults::Translation(results) => toml::Value::try_from(results),
        RunResults::Shear(results) => toml::Value::try_from(results),
    }
    .map_err(|e| format!("results do not serialise: {e}"))?;
    non_finite_in(&results, "results").map(|()| true)
}

fn non_finite_in(value: &toml::Value, path: &str) -> Result<(), String> {
    match value {
        toml::Value::Float(x) if !x.is_finite() => Err(format!("{path} = {x}")),
        toml::Value::Array(items) => items
            .iter()
            .enumerate()
            .try_for_each(|(i, v)| non_finite_in(v, &format!("{path}[{i}]"))),
        toml::Value::Table(table) => table
            .iter()
            .try_for_each(|(k, v)| non_finite_in(v, &format!("{path}.{k}"))),
        _ => Ok(()),
    }
}

fn scenarios_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios")
}

/// [`SEED`], or `PROPTEST_RNG_SEED` to draw other cases.
fn seed() -> u64 {
    std::env::var("PROPTEST_RNG_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(SEED)
}

fn config() -> Config {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(DEFAULT_CASES);
    Config {
        cases,
        rng_algorithm: RngAlgorithm::ChaCha,
        rng_seed: RngSeed::Fixed(seed()),
        failure_persistence: None,
        ..Config::default()
    }
}

/// How many cases ended where: (error at load, run to Ok, run to Err).
#[derive(Debug, Default)]
struct Tally {
    load_errors: usize,
    runs_ok: usize,
    run_errors: usize,
    not_run: usize,
}

/// One case: reads, overrides and validates the scenario; runs it if it is small.
fn check_case(
    (file, dropped_line, n, steps, overrides): (usize, Option<usize>, usize, usize, Vec<String>),
    tally: &mut Tally,
) -> Result<(), TestCaseError> {
    let (origin, text) = SCENARIOS[file];
    let text: String = text
        .lines()
        .enumerate()
        .filter(|(i, _)| Some(*i) != dropped_line)
        .map(|(_, line)| format!("{line}\n"))
        .collect();
    let mut all = small_run_overrides(&text, n, steps);
    all.extend(overrides);
    let base = scenarios_dir();
    let loaded = catch_unwind(AssertUnwindSafe(|| {
        load_within(
            &text,
            origin,
            &base,
            &all,
            Some(&MemoryLimit {
                survives_lifting: false,
                bytes: AVAILABLE_MEMORY,
                source: "the fuzz test's limit".to_string(),
            }),
        )
    }))
    .map_err(|_| TestCaseError::fail(format!("load panicked: {origin} --set {all:?}")))?;
    match loaded {
        Err(error) => {
            tally.load_errors += 1;
            let message = format!("{error:#}");
            prop_assert!(
                dotted_key_in(&message) || message.contains(origin) || message.contains(".npy"),
                "error names no key or file: `{message}` ({origin} --set {all:?})"
            );
        }
        Ok(valid) if valid.grid.nx().max(valid.grid.ny()) <= RUN_MAX_N && valid.expected_steps() <= RUN_MAX_STEPS => {
            let started = std::time::Instant::now();
            let checked = check_finite(&valid);
            let seconds = started.elapsed().as_secs_f64();
            if std::env::var_os("FUZZ_SLOW").is_some() && seconds > 0.2 {
                eprintln!("slow {seconds:.2} s {checked:?} {origin} {all:?}");
            }
            match checked {
                Err(problem) => return Err(TestCaseError::fail(format!("{problem} ({origin} --set {all:?})"))),
                Ok(true) => tally.runs_ok += 1,
                Ok(false) => tally.run_errors += 1,
            }
        }
        Ok(_) => tally.not_run += 1,
    }
    Ok(())
}

#[test]
fn hostile_scenarios_give_a_result_or_a_clear_error() {
    let strategy = (
        0..SCENARIOS.len(),
        prop::option::weighted(0.2, 0usize..40),
        8usize..=RUN_MAX_N,
        2usize..=12,
        prop::collection::vec(override_strategy(), 0..4),
    );
    let mut runner = TestRunner::new(config());
    let tally = std::cell::RefCell::new(Tally::default());
    let outcome = runner.run(&strategy, |case| check_case(case, &mut tally.borrow_mut()));
    let tally = tally.into_inner();
    eprintln!("fuzz: {} cases with seed {}: {tally:?}", runner.config().cases, seed());
    if let Err(failure) = outcome {
        panic!("{failure}");
    }
    // A fuzz test that never reaches the solver checks only the reader.
    let cases = runner.config().cases as usize;
    assert!(
        tally.runs_ok * 10 >= cases,
        "only {} of {cases} cases ran to a result: {tally:?}",
        tally.runs_ok
    );
}
