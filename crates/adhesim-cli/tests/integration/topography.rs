//! `adhesim topography FILE|SCENARIO` (docs/topography-files.md): statistics, PSD and pictures
//! of a scenario's random roughness and of an instrument file; errors name the file or section.

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
    // a periodic grid has both definitions of slope and curvature, each labelled
    for label in ["rms slope      (finite differences)", "rms slope      (spectral)"] {
        assert!(stdout.contains(label), "{label}: {stdout}");
    }
    let stats = statistics(&out);
    assert_eq!((stats["nx"].as_u64(), stats["ny"].as_u64()), (Some(128), Some(128)));
    assert_eq!(stats["boundary"], "periodic");
    // spectral ≥ finite differences: a forward difference sees 2·sin(qΔ/2)/Δ ≤ q
    let spectral = stats["spectral"]["rms_slope"].as_f64().unwrap();
    let differences = stats["finite_differences"]["rms_slope"].as_f64().unwrap();
    assert!(spectral > differences, "{spectral} vs {differences}");
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
fn an_instrument_file_is_analysed_whole_with_its_spacing_and_unit() {
    let dir = tempfile::tempdir().unwrap();
    // 40 × 32 samples (x along a row) of spacing 0.5 nm, heights in nm: h = A·sin(2πy/8)
    // has 2 whole periods along the 32 rows, so the rms height of the whole rectangle is
    // A/√2 exactly (the first 32 × 32 square is no longer what is analysed).
    let amplitude = 0.3;
    let values: Vec<f64> = (0..40 * 32)
        .map(|k| amplitude * (std::f64::consts::TAU * (k / 40) as f64 * 0.5 / 8.0).sin())
        .collect();
    let path = dir.path().join("wave.npz");
    write_npz(&path, &[NamedArray::f64("height", &[32, 40], &values)]).unwrap();
    let out = dir.path().join("out");
    let args = ["topography", path.to_str().unwrap(), "--out", out.to_str().unwrap()];
    let missing = adhesim(&args);
    assert!(!missing.status.success());
    assert!(String::from_utf8_lossy(&missing.stderr).contains("give --spacing"));
    let no_unit = adhesim(&[&args[..], &["--spacing", "0.5e-9"]].concat());
    let stderr = String::from_utf8_lossy(&no_unit.stderr);
    assert!(
        stderr.contains("unit of the heights") && stderr.contains("give --height-unit"),
        "{stderr}"
    );
    let bad_unit = adhesim(&[&args[..], &["--spacing", "0.5e-9", "--height-unit", "furlong"]].concat());
    assert!(String::from_utf8_lossy(&bad_unit.stderr).contains("--height-unit \"furlong\""));
    let output = adhesim(&[&args[..], &["--spacing", "0.5e-9", "--height-unit", "nm"]].concat());
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(stdout.contains("the whole map, 40 × 32 points"), "{stdout}");
    let stats = statistics(&out);
    assert_eq!((stats["nx"].as_u64(), stats["ny"].as_u64()), (Some(40), Some(32)));
    assert_eq!(
        (stats["dx"].as_f64(), stats["dy"].as_f64()),
        (Some(0.5e-9), Some(0.5e-9))
    );
    let rms = stats["rms_height"].as_f64().unwrap();
    assert!(
        (rms / (amplitude * 1e-9 / 2f64.sqrt()) - 1.0).abs() < 1e-12,
        "rms {rms}"
    );
    assert!(stats["spectral"].is_null(), "a measured map is free: no spectral slope");
}

/// SurfaceTopography's fixture path (its own test files, copied with their licence).
fn fixture(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../adhesim-topography/tests/data/surfacetopography")
        .join(name)
}

/// Conformance with SurfaceTopography (docs/topography-files.md): an x3p map of 650 × 650
/// points with dx = 1.277e-7 m ≠ dy = 3.146e-7 m gave an rms slope of 0.0878 and an rms
/// curvature of 2.84e5 (the resampling to the finer spacing was skipped); SurfaceTopography
/// 1.27.1 gives rms_gradient 0.06207007399844295 and rms_curvature_from_area
/// 111566.12196886608. The same stencils on the same points agree to the rounding of the sums:
/// 1e-9 relative.
#[test]
fn unequal_spacings_give_surfacetopographys_slope_and_curvature() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let path = fixture("x3p-2.x3p");
    let output = adhesim(&["topography", path.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let stats = statistics(&out);
    let close = |got: &serde_json::Value, want: f64| {
        let got = got.as_f64().unwrap();
        assert!((got / want - 1.0).abs() < 1e-9, "{got} vs {want}");
    };
    close(&stats["finite_differences"]["rms_slope"], 0.06207007399844295);
    close(&stats["finite_differences"]["rms_curvature"], 111566.12196886608);
    close(&stats["rms_height"], 7.728033273597876e-08);
    close(&stats["size_y"], 0.0002044783737930349);
}

/// Conformance with SurfaceTopography (docs/topography-files.md): a .sur map with 233 009
/// invalid points had an rms height of 3.71e-4 m (the invalid points counted, at the mean
/// height); SurfaceTopography, which leaves them out, gives 0.0011131994265859693 m. Same
/// points, same sum: 1e-9 relative.
#[test]
fn invalid_points_are_left_out_of_the_statistics() {
    let dir = tempfile::tempdir().unwrap();
    let mut bytes = Vec::new();
    let compressed = std::fs::read(fixture("sur-3.sur.gz")).unwrap();
    std::io::Read::read_to_end(&mut flate2::read::GzDecoder::new(&compressed[..]), &mut bytes).unwrap();
    let path = dir.path().join("sur-3.sur");
    std::fs::write(&path, bytes).unwrap();
    let out = dir.path().join("out");
    let output = adhesim(&["topography", path.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(stdout.contains("233009 invalid points left out"), "{stdout}");
    let stats = statistics(&out);
    assert_eq!(stats["invalid_points"], 233009);
    let rms = stats["rms_height"].as_f64().unwrap();
    assert!((rms / 0.0011131994265859693 - 1.0).abs() < 1e-9, "rms {rms}");
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

/// Gwyddion's German text export is read (SurfaceTopography's fixture: 3 × 4 points, 12.34 µm
/// × 5678.9 nm); a decimal comma is refused naming the line and the value, not read as twice
/// the columns.
#[test]
fn a_german_gwyddion_export_reads_and_a_decimal_comma_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let german = fixture("gwyddion-export-german.txt");
    let output = adhesim(&["topography", german.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let stats = statistics(&out);
    assert_eq!((stats["nx"].as_u64(), stats["ny"].as_u64()), (Some(3), Some(4)));
    let size_x = stats["size_x"].as_f64().unwrap();
    assert!((size_x / 12.34e-6 - 1.0).abs() < 1e-12, "{size_x}");
    let comma = dir.path().join("comma.txt");
    std::fs::write(&comma, "1,5 2,5 3,5\n4,5 5,5 6,5\n7,5 8,5 9,5\n").unwrap();
    let output = adhesim(&[
        "topography",
        comma.to_str().unwrap(),
        "--spacing",
        "1e-6",
        "--height-unit",
        "nm",
    ]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        !output.status.success() && stderr.contains("line 1: \"1,5\" has a decimal comma"),
        "{stderr}"
    );
}

/// A Gwyddion object: type name, u32 size, components (name, type, value), as
/// `adhesim-topography`'s gwy reader documents the format.
fn gwy_object(type_name: &str, components: &[(&str, u8, Vec<u8>)]) -> Vec<u8> {
    let mut body = Vec::new();
    for (name, kind, value) in components {
        body.extend_from_slice(name.as_bytes());
        body.push(0);
        body.push(*kind);
        body.extend_from_slice(value);
    }
    let mut out = type_name.as_bytes().to_vec();
    out.push(0);
    out.extend_from_slice(&(body.len() as u32).to_le_bytes());
    out.extend_from_slice(&body);
    out
}

/// Units (docs/topography-files.md): a .gwy whose SI units are empty was refused with a hint to
/// --spacing, which did not help. The error now names the flag that does (--lateral-unit, then
/// --height-unit), and with both the map reads: xreal = 6 in µm over 3 points is dx = 2 µm.
#[test]
fn an_empty_unit_gwy_reads_with_the_units_the_error_names() {
    let dir = tempfile::tempdir().unwrap();
    let unit = |text: &str| gwy_object("GwySIUnit", &[("unitstr", b's', [text.as_bytes(), &[0]].concat())]);
    let doubles: Vec<u8> = [
        6u32.to_le_bytes().to_vec(),
        (1..=6).flat_map(|v| f64::from(v).to_le_bytes()).collect(),
    ]
    .concat();
    let field = gwy_object(
        "GwyDataField",
        &[
            ("xres", b'i', 3i32.to_le_bytes().to_vec()),
            ("yres", b'i', 2i32.to_le_bytes().to_vec()),
            ("xreal", b'd', 6f64.to_le_bytes().to_vec()),
            ("yreal", b'd', 2f64.to_le_bytes().to_vec()),
            ("si_unit_xy", b'o', unit("")),
            ("si_unit_z", b'o', unit("")),
            ("data", b'D', doubles),
        ],
    );
    let bytes = [
        b"GWYP".to_vec(),
        gwy_object("GwyContainer", &[("/0/data", b'o', field)]),
    ]
    .concat();
    let path = dir.path().join("empty.gwy");
    std::fs::write(&path, bytes).unwrap();
    let out = dir.path().join("out");
    let base = ["topography", path.to_str().unwrap(), "--out", out.to_str().unwrap()];
    let stderr = |args: &[&str]| String::from_utf8_lossy(&adhesim(args).stderr).to_string();
    let first = stderr(&base);
    assert!(
        first.contains("give --lateral-unit") && !first.contains("--spacing"),
        "{first}"
    );
    let second = stderr(&[&base[..], &["--lateral-unit", "um"]].concat());
    assert!(second.contains("give --height-unit"), "{second}");
    let output = adhesim(&[&base[..], &["--lateral-unit", "um", "--height-unit", "nm"]].concat());
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let stats = statistics(&out);
    assert_eq!((stats["dx"].as_f64(), stats["dy"].as_f64()), (Some(2e-6), Some(1e-6)));
}

/// The worked example of docs/topography-files.md runs as written: its `toml` block is
/// `scenarios/measured_map_sphere.toml` (so the page and the file cannot drift apart), and
/// its `sh` block runs in bash from a stand-in repository root with this build's `adhesim`
/// first on PATH; the run's scales are SI (F_JKR = −1.5πγR in N) and its pull-off lies
/// between no adhesion and the smooth sphere's (roughness lowers it).
#[test]
fn worked_example_of_the_topography_page_runs_as_written() {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let page = std::fs::read_to_string(repo.join("docs/topography-files.md")).unwrap();
    let start = page
        .find("## Worked example: a measured map pressed by a sphere")
        .expect("the section");
    let section = &page[start..];
    let section = &section[..section[3..].find("\n## ").map_or(section.len(), |end| end + 3)];
    let block = |lang: &str| {
        let fence = format!("```{lang}\n");
        let from = section.find(&fence).unwrap_or_else(|| panic!("a {lang} block")) + fence.len();
        section[from..from + section[from..].find("```").unwrap()].to_string()
    };
    let scenario = std::fs::read_to_string(repo.join("scenarios/measured_map_sphere.toml")).unwrap();
    assert_eq!(
        block("toml"),
        scenario,
        "the page shows scenarios/measured_map_sphere.toml"
    );
    let root = tempfile::tempdir().unwrap();
    for entry in ["scenarios", "crates"] {
        std::os::unix::fs::symlink(repo.join(entry).canonicalize().unwrap(), root.path().join(entry)).unwrap();
    }
    let bin_dir = Path::new(BIN).parent().unwrap();
    let path = format!("{}:{}", bin_dir.display(), std::env::var("PATH").unwrap_or_default());
    let output = Command::new("bash")
        .args(["-e", "-o", "pipefail", "-c", &block("sh")])
        .current_dir(root.path())
        .env("PATH", path)
        .output()
        .unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let summary: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(root.path().join("out/measured_map_sphere/summary.json")).unwrap(),
    )
    .unwrap();
    let f_jkr = summary["derived"]["f_jkr"].as_f64().unwrap();
    let closed_form = -1.5 * std::f64::consts::PI * 0.05 * 100e-6;
    assert!((f_jkr / closed_form - 1.0).abs() < 1e-12, "F_JKR = {f_jkr} N");
    let pull_off = summary["results"]["max_adhesive_force"].as_f64().unwrap() / f_jkr.abs();
    assert!(
        pull_off > 0.1 && pull_off < 1.0,
        "max adhesive force {pull_off} |F_JKR|"
    );
    assert!(root.path().join("out/topography/x3p-2/statistics.json").exists());
}
