//! Integration tests of `adhesim experiment` on small synthetic sequences.

use std::path::Path;
use std::process::{Command, Output};

fn adhesim(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_adhesim"))
        .args(args)
        .output()
        .expect("binary runs")
}

fn synth(dir: &Path, frames: &str) {
    let out = adhesim(&[
        "experiment",
        "synth",
        "--out",
        dir.to_str().unwrap(),
        "--frames",
        frames,
        "--width",
        "320",
        "--height",
        "240",
        "--quiet",
    ]);
    assert!(
        out.status.success(),
        "synth failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    (
        header,
        lines.map(|l| l.split(',').map(String::from).collect()).collect(),
    )
}

/// A corrupt frame (text with a .png name) and an empty .tif among 8 good frames: the run
/// succeeds, names both on stderr, and frames.csv has exactly the 8 good frames (exact count).
#[test]
fn unreadable_frames_reported_and_skipped() {
    let dir = tempfile::tempdir().unwrap();
    synth(dir.path(), "8");
    std::fs::write(dir.path().join("frames/frame_00003b.png"), b"not an image").unwrap();
    std::fs::write(dir.path().join("frames/frame_00005b.tif"), b"").unwrap();
    let out_dir = dir.path().join("out");
    let out = adhesim(&[
        "experiment",
        dir.path().join("experiment.toml").to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
        "--quiet",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("frame_00003b.png"), "{stderr}");
    assert!(stderr.contains("frame_00005b.tif"), "{stderr}");
    let (_, rows) = read_csv(&out_dir.join("frames.csv"));
    assert_eq!(rows.len(), 8);
    let summary = std::fs::read_to_string(out_dir.join("summary.json")).unwrap();
    assert!(summary.contains("frame_00003b.png"));
}

/// The outputs of the contract exist, frames.csv has the contract columns, no NaN anywhere,
/// and the measured area tracks truth.csv within 1 % (SNR 10, contacts ≈ 15,000 px: the
/// issue's accuracy target, end to end through 8-bit PNG quantisation).
#[test]
fn outputs_follow_contract() {
    let dir = tempfile::tempdir().unwrap();
    synth(dir.path(), "30");
    let out_dir = dir.path().join("out");
    let out = adhesim(&[
        "experiment",
        dir.path().join("experiment.toml").to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let (header, rows) = read_csv(&out_dir.join("frames.csv"));
    for col in [
        "frame",
        "time",
        "area",
        "area_front",
        "area_rear",
        "force_normal",
        "force_tangential",
        "pressure",
        "tangential_stress",
        "stage_x",
        "stage_z",
        "jump",
        "centroid_x_px",
        "centroid_y_px",
        "width",
    ] {
        assert!(header.iter().any(|h| h == col), "missing column {col}");
    }
    let text = std::fs::read_to_string(out_dir.join("frames.csv")).unwrap()
        + &std::fs::read_to_string(out_dir.join("summary.json")).unwrap();
    assert!(!text.to_lowercase().contains("nan"), "NaN in outputs");
    let (_, truth) = read_csv(&dir.path().join("truth.csv"));
    let area_col = header.iter().position(|h| h == "area").unwrap();
    for (row, t) in rows.iter().zip(&truth) {
        let (measured, expected): (f64, f64) = (row[area_col].parse().unwrap(), t[2].parse().unwrap());
        assert!(
            (measured / expected - 1.0).abs() < 0.01,
            "frame {}: {measured} vs {expected}",
            row[0]
        );
    }
    for plot in ["areas", "sliding", "forces"] {
        for ext in ["svg", "png"] {
            assert!(out_dir.join(format!("plots/{plot}.{ext}")).is_file(), "{plot}.{ext}");
        }
    }
    assert!(
        std::fs::read_dir(out_dir.join("changes")).unwrap().count() > 0,
        "no change maps"
    );
}

/// Spec errors name the key and value; unknown keys are rejected; no frames.csv is written.
#[test]
fn spec_errors_name_key_and_value() {
    let dir = tempfile::tempdir().unwrap();
    synth(dir.path(), "2");
    let spec = std::fs::read_to_string(dir.path().join("experiment.toml")).unwrap();
    let cases = [
        (
            spec.replace("pixel_size = 0.005", "pixel_size = -1"),
            "frames.pixel_size must be > 0, got -1",
        ),
        (
            spec.replace("contact_is = \"bright\"", "contact_is = \"shiny\""),
            "contact.contact_is",
        ),
        (spec.replace("motion = \"+x\"", "motion = \"+z\""), "indenter.motion"),
        (spec.replace("[contact]", "[contact]\ncolour = 1"), "colour"),
    ];
    for (text, expected) in cases {
        let path = dir.path().join("bad.toml");
        std::fs::write(&path, text).unwrap();
        let out = adhesim(&[
            "experiment",
            path.to_str().unwrap(),
            "--out",
            dir.path().join("bad").to_str().unwrap(),
        ]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success());
        assert!(stderr.contains(expected), "expected {expected:?} in {stderr}");
        assert!(!dir.path().join("bad/frames.csv").exists());
    }
}
