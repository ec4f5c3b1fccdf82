//! Speed run of `adhesim experiment` on 1,000 synthetic 1600×1200 frames (BENCHMARKS.md
//! §How fast is a run of each kind › Experiment analysis).
//!
//! Ignored by default: it writes ≈ 1.7 GB of PNG frames and takes minutes. Run with
//! `cargo test --release -p adhesim-cli --test integration experiment_speed:: -- --ignored --nocapture`.
//! `ADHESIM_SPEED_DIR=DIR` reuses (or creates) the synthetic sequence in DIR instead of a
//! temporary folder; `ADHESIM_MIN_FPS` (default 50) is the required analysis rate.

use std::path::Path;
use std::process::Command;

/// Analysis throughput ≥ ADHESIM_MIN_FPS frames/s (summary.json `frames_per_second`, decode
/// included), and every frame with > 2,000 true contact pixels within 1 % of the true area.
/// Wall-clock rates depend on what else runs on the machine; see BENCHMARKS.md §How fast is
/// a run of each kind › Experiment analysis.
#[test]
#[ignore = "a wall-clock benchmark of 1,000 frames (BENCHMARKS.md §5): cargo test --release -p adhesim-cli --test integration experiment_speed:: -- --ignored"]
fn thousand_frames_1600x1200() {
    let temp = tempfile::tempdir().unwrap();
    let dir = std::env::var_os("ADHESIM_SPEED_DIR").map_or_else(|| temp.path().to_path_buf(), Into::into);
    let bin = env!("CARGO_BIN_EXE_adhesim");
    if !dir.join("experiment.toml").is_file() {
        let status = Command::new(bin)
            .args(["experiment", "synth", "--frames", "1000", "--quiet", "--out"])
            .arg(&dir)
            .status()
            .unwrap();
        assert!(status.success());
    }
    let out = dir.join("speed-analysis");
    let status = Command::new(bin)
        .args(["experiment", "--quiet", "--out"])
        .arg(&out)
        .arg(dir.join("experiment.toml"))
        .status()
        .unwrap();
    assert!(status.success());
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
    let fps: f64 = summary
        .split("\"frames_per_second\":")
        .nth(1)
        .and_then(|s| s.split([',', '\n', '}']).next())
        .and_then(|s| s.trim().parse().ok())
        .expect("frames_per_second in summary.json");
    let min_fps: f64 = std::env::var("ADHESIM_MIN_FPS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(50.0);
    println!("analysis rate: {fps:.1} frames/s");
    assert_area_within(&out.join("frames.csv"), &dir.join("truth.csv"), 0.005, 0.01);
    assert!(fps >= min_fps, "{fps:.1} frames/s < {min_fps}");
}

fn assert_area_within(frames: &Path, truth: &Path, pixel_size: f64, tolerance: f64) {
    let measured: Vec<(usize, f64)> = csv::Reader::from_path(frames)
        .unwrap()
        .records()
        .map(|r| {
            let r = r.unwrap();
            (r[0].parse().unwrap(), r[2].parse().unwrap())
        })
        .collect();
    let true_area: Vec<f64> = csv::Reader::from_path(truth)
        .unwrap()
        .records()
        .map(|r| r.unwrap()[2].parse().unwrap())
        .collect();
    for (frame, area) in measured {
        let t = true_area[frame];
        if t / (pixel_size * pixel_size) > 2000.0 {
            assert!((area / t - 1.0).abs() < tolerance, "frame {frame}: {area} vs {t}");
        }
    }
}
