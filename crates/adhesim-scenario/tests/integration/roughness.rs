//! `[roughness]` and `[substrate_roughness]` (docs/cli.md): every validation error names
//! `roughness.KEY` and its value; a `rough_sphere` runs, and its heights minus the
//! paraboloid have the requested rms height.

use adhesim::surface::statistics;
use adhesim::{Grid, Profile, Sphere};
use adhesim_scenario::{load, run, RunResults, ValidScenario};
use adhesim_topography::{write_npz, NamedArray};
use std::path::Path;

const ROUGH_SPHERE: &str = r#"
[grid]
n = 32
size = 0.25
boundary = "periodic"
[material]
contact_modulus = 1.0
[adhesion]
work_of_adhesion = 3.5e-5
[indenter]
shape = "rough_sphere"
radius = 1.0
[roughness]
hurst = 0.8
rms_height = 2e-4
rolloff_wavelength = 0.05
seed = 3
[protocol]
kind = "indent_pulloff"
max_depth = 2.0
depth_unit = "jkr"
steps = 20
"#;

const SLIDE: &str = r#"
[grid]
n = 32
size = 0.25
[material]
contact_modulus = 1.0
[adhesion]
work_of_adhesion = 3.5e-5
[indenter]
shape = "sphere"
radius = 1.0
[protocol]
kind = "slide"
depth = 1.0
depth_unit = "jkr"
distance = 0.02
steps = 4
approach_steps = 4
"#;

fn load_with(text: &str, overrides: &[&str]) -> Result<ValidScenario, adhesim_scenario::ScenarioError> {
    let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    load(text, "test.toml", Path::new("."), &overrides)
}

fn error_of(text: &str, overrides: &[&str]) -> String {
    match load_with(text, overrides) {
        Ok(_) => panic!("{overrides:?} validated"),
        Err(e) => format!("{e:#}"),
    }
}

/// rms about the mean.
fn rms(values: &[f64]) -> f64 {
    let mean = values.iter().sum::<f64>() / values.len() as f64;
    (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / values.len() as f64).sqrt()
}

#[test]
fn rough_sphere_heights_minus_the_paraboloid_have_the_requested_rms_and_it_runs() {
    let valid = load_with(ROUGH_SPHERE, &[]).unwrap();
    let sphere = Sphere::new(1.0).unwrap();
    let residual: Vec<f64> = (0..valid.grid.len())
        .map(|k| {
            let (x, y) = valid.grid.centre(k);
            valid.heights[k] - sphere.height(x, y)
        })
        .collect();
    // random_phase on a periodic grid: the requested rms to rounding (1e-10 relative).
    let requested = 2e-4;
    assert!(
        (rms(&residual) - requested).abs() < 1e-10 * requested,
        "rms {:e}",
        rms(&residual)
    );
    // First contact at zero depth, the statistics in derived match the map.
    assert_eq!(valid.start_depth, 0.0);
    let map = valid.roughness.as_ref().expect("the roughness is kept");
    let stats = valid.derived.roughness.expect("derived.roughness");
    assert_eq!(stats.rms_height, statistics(&valid.grid, map).unwrap().rms_height);
    assert!((stats.rms_height - requested).abs() < 1e-10 * requested);
    assert!(stats.rms_slope > 0.0 && stats.rms_curvature > 0.0);
    let outcome = run(&valid, &mut ()).unwrap();
    let RunResults::Indentation(results) = &outcome.results else {
        panic!("an indentation")
    };
    assert!(outcome.records.len() >= 20);
    assert!(results.max_adhesive_force.is_finite() && results.max_adhesive_force > 0.0);
}

#[test]
fn a_sphere_with_roughness_is_a_rough_sphere_and_rms_slope_is_honoured() {
    let rough = load_with(ROUGH_SPHERE, &[]).unwrap();
    let sphere = load_with(ROUGH_SPHERE, &["indenter.shape=sphere"]).unwrap();
    assert_eq!(rough.heights, sphere.heights);
    let by_slope = load_with(ROUGH_SPHERE, &["roughness.rms_height=nan"]);
    assert!(by_slope.is_err());
    let mut table: toml::Table = ROUGH_SPHERE.parse().unwrap();
    table["roughness"].as_table_mut().unwrap().remove("rms_height");
    table["roughness"]
        .as_table_mut()
        .unwrap()
        .insert("rms_slope".into(), 0.05.into());
    let valid = load_with(&table.to_string(), &[]).unwrap();
    let slope = valid.derived.roughness.unwrap().rms_slope;
    // Spectral slope on a periodic grid: the generator's discrete sum, to rounding.
    assert!((slope - 0.05).abs() < 1e-10 * 0.05, "rms slope {slope}");
}

#[test]
fn rough_flat_and_a_rough_punch_add_the_roughness_to_the_shape() {
    let flat = load_with(ROUGH_SPHERE, &["indenter.shape=rough_flat", "indenter.radius=nan"]);
    assert!(flat.is_err(), "rough_flat takes no radius");
    let mut table: toml::Table = ROUGH_SPHERE.parse().unwrap();
    table["indenter"].as_table_mut().unwrap().remove("radius");
    table["indenter"]
        .as_table_mut()
        .unwrap()
        .insert("shape".into(), "rough_flat".into());
    table["protocol"]
        .as_table_mut()
        .unwrap()
        .insert("depth_unit".into(), "length".into());
    table["protocol"]
        .as_table_mut()
        .unwrap()
        .insert("max_depth".into(), 4e-4.into());
    let flat = load_with(&table.to_string(), &[]).unwrap();
    let map = flat.roughness.clone().unwrap();
    let highest = map.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    for (z, h) in flat.heights.iter().zip(&map) {
        assert!((z - (highest - h)).abs() < 1e-15, "z = max h − h");
    }
    // A flat punch of radius 0.1 with the same roughness: z = punch − h, shifted.
    let punch = load_with(
        &table.to_string(),
        &["indenter.shape=flat_punch", "indenter.radius=0.1"],
    )
    .unwrap();
    let inside: Vec<usize> = (0..punch.grid.len())
        .filter(|&k| punch.heights[k].is_finite())
        .collect();
    assert!(!inside.is_empty() && inside.len() < punch.grid.len());
    let lowest = inside.iter().map(|&k| -map[k]).fold(f64::INFINITY, f64::min);
    for &k in &inside {
        assert!((punch.heights[k] - (-map[k] - lowest)).abs() < 1e-15);
    }
    assert_eq!(punch.start_depth, 0.0);
}

#[test]
fn a_measured_file_is_resampled_onto_the_grid() {
    let dir = tempdir();
    let grid = Grid::new(16, 0.16, adhesim::Boundary::Free).unwrap();
    // A map of 16×16 samples at the grid's spacing: resampled exactly at its own samples.
    let values: Vec<f64> = (0..256)
        .map(|k| 1e-4 * ((k % 16) as f64 * 0.3).sin() + 1e-6 * (k / 16) as f64)
        .collect();
    let path = dir.join("map.npz");
    write_npz(&path, &[NamedArray::f64("heights", &[16, 16], &values)]).unwrap();
    let text = format!(
        "{}\n",
        ROUGH_SPHERE
            .replace("n = 32", "n = 16")
            .replace("size = 0.25", "size = 0.16")
            .replace("boundary = \"periodic\"", "boundary = \"free\"")
    );
    let mut table: toml::Table = text.parse().unwrap();
    let mut section = toml::Table::new();
    section.insert("file".into(), path.display().to_string().into());
    section.insert("spacing".into(), 0.01.into());
    section.insert("height_unit".into(), "m".into());
    table.insert("roughness".into(), section.into());
    let valid = load_with(&table.to_string(), &[]).unwrap();
    let map = valid.roughness.unwrap();
    assert_eq!(valid.grid, grid);
    for (a, b) in map.iter().zip(&values) {
        assert!((a - b).abs() < 1e-15, "{a} vs {b}");
    }
    // Coarser grid spacing than the measurement: a warning; a larger grid: an error.
    let warned = load_with(&table.to_string(), &["grid.n=8"]).unwrap();
    assert!(
        warned
            .warnings
            .iter()
            .any(|w| w.contains("roughness.file") && w.contains("coarser")),
        "{:?}",
        warned.warnings
    );
    let error = error_of(&table.to_string(), &["grid.size=0.5"]);
    assert!(
        error.contains("roughness.file") && error.contains("does not fit"),
        "{error}"
    );
    // Detrending removes a tilt of the map.
    let tilt: Vec<f64> = (0..256).map(|k| 1e-3 * (k % 16) as f64).collect();
    write_npz(&path, &[NamedArray::f64("heights", &[16, 16], &tilt)]).unwrap();
    let detrended = load_with(&table.to_string(), &["roughness.detrend=true"]).unwrap();
    assert!(rms(detrended.roughness.as_ref().unwrap()) < 1e-15);
    let error = error_of(&table.to_string(), &["roughness.spacing=-1"]);
    assert!(error.contains("roughness.spacing must be > 0, got -1"), "{error}");
    let error = error_of(&table.to_string(), &["roughness.file=no_such.npz"]);
    assert!(
        error.contains("roughness.file") && error.contains("no_such.npz"),
        "{error}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

fn tempdir() -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("adhesim-roughness-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn substrate_roughness_lowers_the_gap_of_a_slide() {
    let substrate = "\n[substrate_roughness]\nhurst = 0.7\nrms_height = 1e-4\nseed = 5\n";
    let smooth = load_with(SLIDE, &[]).unwrap();
    let rough = load_with(&format!("{SLIDE}{substrate}"), &[]).unwrap();
    let map = rough
        .translation
        .as_ref()
        .unwrap()
        .contact
        .substrate_roughness()
        .unwrap()
        .to_vec();
    assert!(rough.derived.substrate_roughness.is_some() && rough.derived.roughness.is_none());
    let (mut a, mut b) = (vec![0.0; 1024], vec![0.0; 1024]);
    let grid = smooth.grid;
    smooth
        .translation
        .as_ref()
        .unwrap()
        .contact
        .fill_heights(&grid, 0.01, &mut a);
    rough
        .translation
        .as_ref()
        .unwrap()
        .contact
        .fill_heights(&grid, 0.01, &mut b);
    for k in 0..grid.len() {
        assert!((a[k] - map[k] - b[k]).abs() < 1e-15);
    }
    let outcome = run(&rough, &mut ()).unwrap();
    assert!(outcome
        .records
        .iter()
        .all(|r| r.report.force.is_finite() && r.force_tangential.is_finite()));
    let error = error_of(&format!("{SLIDE}{substrate}"), &["protocol.kind=roll"]);
    assert!(
        error.contains("[substrate_roughness]") && error.contains("\"roll\""),
        "{error}"
    );
    let error = error_of(&format!("{SLIDE}{}", substrate.replace("substrate_", "")), &[]);
    assert!(error.contains("[roughness]") && error.contains("\"slide\""), "{error}");
}

#[test]
fn every_roughness_error_names_the_key_and_the_value() {
    let cases: &[(&[&str], &str)] = &[
        (&["roughness.hurst=1.5"], "roughness.hurst must lie in (0, 1], got 1.5"),
        (&["roughness.hurst=0"], "roughness.hurst must lie in (0, 1], got 0"),
        (&["roughness.hurst=nan"], "roughness.hurst must lie in (0, 1], got NaN"),
        (&["roughness.rms_height=-2"], "roughness.rms_height must be > 0, got -2"),
        (
            &["roughness.rms_slope=0.1"],
            "give exactly one of roughness.rms_height and roughness.rms_slope, got both (roughness.rms_height = 0.0002, roughness.rms_slope = 0.1)",
        ),
        (&["roughness.seed=-1"], "roughness.seed must be >= 0, got -1"),
        (&["roughness.mode=smooth"], "roughness.mode = \"smooth\""),
        (&["roughness.colour=1"], "unknown key `roughness.colour`"),
        (&["roughness.rolloff_wavelength=0"], "roughness.rolloff_wavelength must be > 0, got 0"),
        (
            &["roughness.rolloff_wavelength=0.01", "roughness.cutoff_wavelength=0.02"],
            "roughness.rolloff_wavelength must be longer than the cutoff wavelength",
        ),
        (
            &["roughness.cutoff_wavelength=0.001"],
            "roughness.cutoff_wavelength must be at least two elements",
        ),
        (&["roughness.cutoff_wavelength=inf"], "roughness.cutoff_wavelength must be > 0, got inf"),
        (
            &["roughness.file=map.npy"],
            "[roughness] mixes the generator key roughness.hurst with the file key roughness.file",
        ),
        (&["roughness=[]"], "`roughness` must be a table [roughness]"),
        (&["roughness.seed=1.5"], "roughness.seed = 1.5"),
        (
            &["indenter.shape=rough_flat"],
            "unknown key `indenter.radius` for indenter.shape = \"rough_flat\" (it takes no keys)",
        ),
        (
            &["indenter.amplitude=0.1"],
            "unknown key `indenter.amplitude` for indenter.shape = \"rough_sphere\" (expected `radius`)",
        ),
    ];
    for (overrides, expected) in cases {
        let error = error_of(ROUGH_SPHERE, overrides);
        assert!(error.contains(expected), "{overrides:?}: {error}");
    }
    // Missing keys and an empty section.
    let without = |key: &str| {
        let mut table: toml::Table = ROUGH_SPHERE.parse().unwrap();
        table["roughness"].as_table_mut().unwrap().remove(key);
        error_of(&table.to_string(), &[])
    };
    assert!(without("hurst").contains("missing key `roughness.hurst`"));
    assert!(without("seed").contains("missing key `roughness.seed`"));
    let mut table: toml::Table = ROUGH_SPHERE.parse().unwrap();
    let mut detrend_only = toml::Table::new();
    detrend_only.insert("detrend".into(), true.into());
    table.insert("roughness".into(), detrend_only.into());
    assert!(error_of(&table.to_string(), &[]).contains("missing key `roughness.file`"));
    assert!(
        without("rms_height").contains("give exactly one of roughness.rms_height and roughness.rms_slope, got neither")
    );
    let mut table: toml::Table = ROUGH_SPHERE.parse().unwrap();
    table.insert("roughness".into(), toml::Table::new().into());
    assert!(error_of(&table.to_string(), &[]).contains("[roughness] is empty: give roughness.file"));
    table.remove("roughness");
    let error = error_of(&table.to_string(), &[]);
    assert!(
        error.contains("indenter.shape = \"rough_sphere\" needs a [roughness] section"),
        "{error}"
    );
    let error = error_of(&table.to_string(), &["indenter.shape=sphere", "indenter.radius=-1"]);
    assert_eq!(error, "indenter.radius must be > 0, got -1");
    let error = error_of(ROUGH_SPHERE, &["indenter.radius=-1"]);
    assert_eq!(error, "indenter.radius must be > 0, got -1");
}
