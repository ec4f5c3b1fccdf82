//! Measured roughness files in a scenario (docs/topography-files.md): the unit of a file that
//! records none is a key (`roughness.height_unit`), never metres by default; a map with invalid
//! points needs `roughness.invalid_points` ("interpolate" or "refuse"), and the choice is in
//! the derived values of summary.json.

use adhesim_scenario::{load, InvalidPoints, ValidScenario};
use adhesim_topography::{write_npz, NamedArray};
use std::path::{Path, PathBuf};

/// A free 16 × 16 grid of spacing 0.01 carrying a measured roughness on a flat indenter.
fn scenario(file: &Path, extra: &str) -> String {
    format!(
        r#"
[grid]
n = 16
size = 0.16
[material]
contact_modulus = 1.0
[adhesion]
work_of_adhesion = 3.5e-5
[indenter]
shape = "rough_flat"
[roughness]
file = "{}"
spacing = 0.01
{extra}
[protocol]
kind = "indent_pulloff"
max_depth = 1e-4
steps = 2
"#,
        file.display()
    )
}

fn load_text(text: &str) -> Result<ValidScenario, adhesim_scenario::ScenarioError> {
    load(text, "test.toml", Path::new("."), &[])
}

fn error_of(text: &str) -> String {
    match load_text(text) {
        Ok(_) => panic!("validated: {text}"),
        Err(e) => format!("{e:#}"),
    }
}

fn tempdir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("adhesim-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A plane in nanometres: its resampled heights are the plane in metres.
fn plane(k: usize) -> f64 {
    2.0 + 0.5 * (k % 16) as f64 - 0.25 * (k / 16) as f64
}

#[test]
fn a_file_without_a_unit_needs_roughness_height_unit() {
    let dir = tempdir("height-unit");
    let path = dir.join("plane.npz");
    let values: Vec<f64> = (0..256).map(plane).collect();
    write_npz(&path, &[NamedArray::f64("heights", &[16, 16], &values)]).unwrap();
    let error = error_of(&scenario(&path, ""));
    assert!(
        error.contains("roughness.file")
            && error.contains("unit of the heights")
            && error.contains("set roughness.height_unit"),
        "{error}"
    );
    let error = error_of(&scenario(&path, "height_unit = \"furlong\""));
    assert!(error.contains("furlong"), "{error}");
    let valid = load_text(&scenario(&path, "height_unit = \"nm\"")).unwrap();
    let heights = valid.roughness.unwrap();
    // the indenter's roughness is the map as read (rows y), converted from nm
    let mean = heights.iter().sum::<f64>() / 256.0;
    let values_mean = values.iter().sum::<f64>() / 256.0 * 1e-9;
    for k in 0..256 {
        let want = values[k] * 1e-9 - values_mean;
        assert!(((heights[k] - mean) - want).abs() < 1e-20, "point {k}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn invalid_points_need_an_explicit_choice_reported_in_the_summary() {
    let dir = tempdir("invalid-points");
    // a bare ASCII matrix (NaN marks an invalid point; npz writers refuse NaN)
    let path = dir.join("holed.txt");
    let holes = [5 * 16 + 5, 5 * 16 + 6, 6 * 16 + 5, 10 * 16 + 12];
    let text: String = (0..16)
        .map(|row| {
            let line: Vec<String> = (0..16)
                .map(|column| {
                    let k = row * 16 + column;
                    if holes.contains(&k) {
                        "NaN".to_string()
                    } else {
                        format!("{:e}", plane(k))
                    }
                })
                .collect();
            line.join(" ") + "\n"
        })
        .collect();
    std::fs::write(&path, text).unwrap();
    let unit = "height_unit = \"nm\"";
    let error = error_of(&scenario(&path, unit));
    assert!(
        error.contains("4 of 256 points are invalid") && error.contains("roughness.invalid_points = \"interpolate\""),
        "{error}"
    );
    let refused = error_of(&scenario(&path, &format!("{unit}\ninvalid_points = \"refuse\"")));
    assert!(refused.contains("roughness.invalid_points = \"refuse\""), "{refused}");
    let error = error_of(&scenario(&path, &format!("{unit}\ninvalid_points = \"guess\"")));
    assert!(
        error.contains("roughness.invalid_points") && error.contains("guess"),
        "{error}"
    );
    let valid = load_text(&scenario(&path, &format!("{unit}\ninvalid_points = \"interpolate\""))).unwrap();
    let report = valid.derived.roughness.unwrap().invalid_points.unwrap();
    assert_eq!(
        (report.count, report.of, report.handling),
        (4, 256, InvalidPoints::Interpolate)
    );
    let json = serde_json::to_string(&valid.derived).unwrap();
    assert!(
        json.contains(r#""invalid_points":{"count":4,"of":256,"handling":"interpolate"}"#),
        "{json}"
    );
    // A plane is harmonic: the holes are filled with the plane itself (CG to 1e-13).
    let heights = valid.roughness.unwrap();
    let offset = heights[0] - plane(0) * 1e-9;
    for (k, h) in heights.iter().enumerate() {
        assert!((h - offset - plane(k) * 1e-9).abs() < 1e-20, "point {k}: {h}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
