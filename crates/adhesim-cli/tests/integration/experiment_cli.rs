//! Integration tests of `adhesim experiment` on small synthetic sequences.

use crate::common;
use common::{adhesim, read_csv, read_json, synth_experiment as synth};

/// A corrupt frame (text with a .png name) and an empty .tif among 8 good frames: the run
/// succeeds, names both on stderr, and frames.csv has exactly the 8 good frames (exact count).
#[test]
fn unreadable_frames_reported_and_skipped() {
    let dir = tempfile::tempdir().unwrap();
    synth(dir.path(), 8);
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
    synth(dir.path(), 30);
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
    synth(dir.path(), 2);
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

/// 16-bit TIFF frames are read like 8-bit PNGs (exact row count, areas > 0).
#[test]
fn sixteen_bit_tiff_frames() {
    let dir = tempfile::tempdir().unwrap();
    let out = adhesim(&[
        "experiment",
        "synth",
        "--out",
        dir.path().to_str().unwrap(),
        "--frames",
        "3",
        "--width",
        "240",
        "--height",
        "180",
        "--format",
        "tiff",
        "--bits",
        "16",
        "--quiet",
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(dir.path().join("frames/frame_00000.tif").is_file());
    let out_dir = dir.path().join("out");
    let out = adhesim(&[
        "experiment",
        dir.path().join("experiment.toml").to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let (header, rows) = read_csv(&out_dir.join("frames.csv"));
    let area = header.iter().position(|h| h == "area").unwrap();
    assert_eq!(rows.len(), 3);
    assert!(rows.iter().all(|r| r[area].parse::<f64>().unwrap() > 0.0));
}

/// Indentation and pull-off filmed from below: noise-free disc frames of radius a_i with the
/// JKR force F = 4E*a³/(3R) − √(8πγE*a³), γ1 = 0.01 on approach, five frames pinned at the
/// reversal, then γ2 = 0.02 on pull-off. The summary's JKR fits recover γ1 and γ2 within 1 %
/// (discs of 40–170 px radius give √(A/π) to ≈ 0.1 %, which γ ∝ (force gap)² amplifies a
/// few times; measured 0.003 %), the
/// pinned phase spans exactly its 5 depth steps of 0.01, and q = (γ2 − γ1)/2 follows.
#[test]
fn normal_curve_jkr_fits_and_pinned_phase() {
    let dir = tempfile::tempdir().unwrap();
    let frames = dir.path().join("frames");
    std::fs::create_dir_all(&frames).unwrap();
    let (e, r, pixel) = (1.0f64, 1.0f64, 0.002f64);
    let jkr = |a: f64, gamma: f64| {
        4.0 * e * a.powi(3) / (3.0 * r) - (8.0 * std::f64::consts::PI * gamma * e * a.powi(3)).sqrt()
    };
    // (radius, force, depth) per frame
    let mut samples = Vec::new();
    for i in 0..12 {
        let a = 0.08 + 0.02 * i as f64;
        samples.push((a, jkr(a, 0.01), 0.1 * i as f64));
    }
    let (a_max, d_max) = (samples[11].0, samples[11].2);
    for k in 1..=5 {
        samples.push((a_max, jkr(a_max, 0.01) - 0.001 * k as f64, d_max - 0.01 * k as f64));
    }
    for i in 1..10 {
        let a = a_max - 0.02 * i as f64;
        samples.push((a, jkr(a, 0.02), d_max - 0.05 - 0.05 * i as f64));
    }
    let mut log = String::from("t,F,z\n");
    for (k, (a, f, d)) in samples.iter().enumerate() {
        let radius_px = a / pixel;
        let img = image::GrayImage::from_fn(400, 400, |x, y| {
            let (dx, dy) = (x as f64 - 199.5, y as f64 - 199.5);
            image::Luma([if dx * dx + dy * dy <= radius_px * radius_px {
                220
            } else {
                30
            }])
        });
        img.save(frames.join(format!("f{k:03}.png"))).unwrap();
        log.push_str(&format!("{k},{f},{d}\n"));
    }
    std::fs::write(dir.path().join("log.csv"), log).unwrap();
    let spec = "[frames]\npath = \"frames\"\npixel_size = 0.002\nrate = 1.0\n\
                [forces]\npath = \"log.csv\"\ntime = \"t\"\nnormal = \"F\"\nstage_z = \"z\"\n\
                [contact]\nthreshold = 0.5\n\
                [fits]\ncontact_modulus = 1.0\nindenter_radius = 1.0\n";
    std::fs::write(dir.path().join("normal.toml"), spec).unwrap();
    let out_dir = dir.path().join("out");
    let out = adhesim(&[
        "experiment",
        dir.path().join("normal.toml").to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let summary: serde_json::Value = read_json(&out_dir.join("summary.json"));
    let results = &summary["results"];
    let g1 = results["gamma_approach"].as_f64().unwrap();
    let g2 = results["gamma_pulloff"].as_f64().unwrap();
    assert!((g1 / 0.01 - 1.0).abs() < 0.01, "gamma_approach {g1}");
    assert!((g2 / 0.02 - 1.0).abs() < 0.01, "gamma_pulloff {g2}");
    assert!(
        (results["pinned_phase_depth"].as_f64().unwrap() - 0.05).abs() < 1e-9,
        "{results}"
    );
    assert!((results["boundary_friction"].as_f64().unwrap() - (g2 - g1) / 2.0).abs() < 1e-12);
    assert!(results["max_adhesive_force"].as_f64().unwrap() > 0.0);
}
