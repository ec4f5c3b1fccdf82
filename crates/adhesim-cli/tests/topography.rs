//! `adhesim topography FILE|SCENARIO` (issue #18 item 2): statistics, PSD and pictures of a
//! scenario's random roughness and of an instrument file; errors name the file or section.

use adhesim_topography::{write_npz, NamedArray};
use std::path::Path;
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_adhesim");

fn adhesim(args: &[&str]) -> Output {
    Command::new(BIN).args(args).output().expect("binary runs")
}

fn statistics(out: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(out.join("statistics.json")).unwrap()).unwrap()
}

const PERIODIC_ROUGH_SPHERE: &str = r#"
[grid]
n = 128
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
seed = 1
[protocol]
kind = "indent_pulloff"
max_depth = 2.0
depth_unit = "jkr"
steps = 20
"#;

#[test]
fn a_scenarios_roughness_has_its_requested_rms_and_hurst_exponent() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = dir.path().join("rough.toml");
    std::fs::write(&scenario, PERIODIC_ROUGH_SPHERE).unwrap();
    let out = dir.path().join("out");
    let output = adhesim(&["topography", scenario.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(
        stdout.contains("rms height") && stdout.contains("Hurst estimate H = "),
        "{stdout}"
    );
    let stats = statistics(&out);
    assert_eq!(stats["n"], 128);
    assert_eq!(stats["boundary"], "periodic");
    // random_phase on a periodic grid: the requested rms to rounding.
    let rms = stats["rms_height"].as_f64().unwrap();
    assert!((rms - 2e-4).abs() < 1e-10 * 2e-4, "rms {rms}");
    // Exact amplitudes |H(q)|² ∝ q^(−2−2H) mode by mode: the fit over bins recovers H up to
    // the bias of averaging q and C over a logarithmic bin (0.799 found; 0.02 allowed).
    let hurst = stats["hurst_estimate"].as_f64().unwrap();
    assert!((hurst - 0.8).abs() < 0.02, "H = {hurst}");
    let psd = std::fs::read_to_string(out.join("psd.csv")).unwrap();
    assert!(psd.starts_with("q_low,q_high,q,psd,modes\n"), "{psd}");
    assert!(psd.lines().count() > 10);
    for file in ["psd.png", "psd.svg", "heights.png"] {
        assert!(std::fs::metadata(out.join(file)).unwrap().len() > 0, "{file}");
    }
}

#[test]
fn an_instrument_file_gives_its_size_spacing_and_rms() {
    let dir = tempfile::tempdir().unwrap();
    // 40 × 32 samples (x along a row) of spacing 0.5: h = A·sin(2πx/8) has 2 whole periods
    // across the 32 × 32 square analysed, so its rms height is A/√2 exactly.
    let amplitude = 0.3;
    let values: Vec<f64> = (0..40 * 32)
        .map(|k| amplitude * (std::f64::consts::TAU * (k % 40) as f64 * 0.5 / 8.0).sin())
        .collect();
    let path = dir.path().join("wave.npz");
    write_npz(&path, &[NamedArray::f64("height", &[32, 40], &values)]).unwrap();
    let out = dir.path().join("out");
    let args = ["topography", path.to_str().unwrap(), "--out", out.to_str().unwrap()];
    let missing = adhesim(&args);
    assert!(!missing.status.success());
    assert!(String::from_utf8_lossy(&missing.stderr).contains("--spacing"));
    let output = adhesim(&[&args[..], &["--spacing", "0.5"]].concat());
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(stdout.contains("40 × 32 points"), "{stdout}");
    assert!(stdout.contains("first 32 × 32 square"), "{stdout}");
    let stats = statistics(&out);
    assert_eq!(stats["n"], 32);
    assert_eq!(stats["spacing"], 0.5);
    let rms = stats["rms_height"].as_f64().unwrap();
    assert!((rms - amplitude / 2f64.sqrt()).abs() < 1e-12, "rms {rms}");
}

#[test]
fn bad_inputs_name_the_file_or_the_section() {
    let dir = tempfile::tempdir().unwrap();
    let output = adhesim(&["topography", "no_such_map.x3p"]);
    assert_eq!(output.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&output.stderr).contains("no_such_map.x3p"));
    let scenario = dir.path().join("smooth.toml");
    let smooth = PERIODIC_ROUGH_SPHERE
        .replace("rough_sphere", "sphere")
        .split("[roughness]")
        .next()
        .unwrap()
        .to_string()
        + "[protocol]\nkind = \"indent_pulloff\"\nmax_depth = 2.0\ndepth_unit = \"jkr\"\nsteps = 20\n";
    std::fs::write(&scenario, smooth).unwrap();
    let output = adhesim(&["topography", scenario.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("has no [roughness] section"), "{stderr}");
    let output = adhesim(&["topography", scenario.to_str().unwrap(), "--spacing=-1"]);
    assert!(String::from_utf8_lossy(&output.stderr).contains("--spacing must be > 0, got -1"));
}
