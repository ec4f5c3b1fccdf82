//! Bad experiment inputs (first robustness audit, docs/reliability.md): every one is an error
//! naming the key or the file (with line and column for log cells), or a run that succeeds with
//! a warning that counts what was dropped. Each sequence is a small synthetic one (6 frames of
//! 320×240 at 1 frame/s, the log sampled at the frame times t = 0 … 5, the header on line 1 and
//! frame k on line k + 2).

use std::path::{Path, PathBuf};

use crate::common;
use common::{adhesim, synth_experiment};

/// A synthetic sequence of `frames` frames in a fresh folder.
fn synth(frames: usize) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    synth_experiment(dir.path(), frames);
    dir
}

fn spec_text(dir: &Path) -> String {
    std::fs::read_to_string(dir.join("experiment.toml")).unwrap()
}

/// Runs the analysis of `spec` (written to `dir/case.toml`) into `dir/out`: (success, stderr).
fn analyse(dir: &Path, spec: &str) -> (bool, String, PathBuf) {
    let path = dir.join("case.toml");
    std::fs::write(&path, spec).unwrap();
    let out_dir = dir.join("out");
    let _ = std::fs::remove_dir_all(&out_dir);
    let out = adhesim(&[
        "experiment",
        path.to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
        "--quiet",
    ]);
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        out_dir,
    )
}

fn assert_error(dir: &Path, spec: &str, expected: &[&str]) {
    let (ok, stderr, out_dir) = analyse(dir, spec);
    assert!(!ok, "accepted; expected an error with {expected:?}; stderr: {stderr}");
    for e in expected {
        assert!(stderr.contains(e), "expected {e:?} in: {stderr}");
    }
    assert!(
        !out_dir.join("frames.csv").exists(),
        "frames.csv written despite the error"
    );
}

/// Rewrites the log: `edit(line_number, cells)` may change the cells of each data line.
fn edit_log(dir: &Path, edit: impl Fn(usize, &mut Vec<String>)) {
    let text = std::fs::read_to_string(dir.join("log.csv")).unwrap();
    let mut out = String::new();
    for (i, line) in text.lines().enumerate() {
        let mut cells: Vec<String> = line.split(',').map(String::from).collect();
        if i > 0 {
            edit(i + 1, &mut cells);
        }
        if !cells.is_empty() {
            out.push_str(&cells.join(","));
            out.push('\n');
        }
    }
    std::fs::write(dir.join("log.csv"), out).unwrap();
}

fn uniform_frame(path: &Path, width: u32, height: u32) {
    image::GrayImage::from_pixel(width, height, image::Luma([40]))
        .save(path)
        .unwrap();
}

/// A frame of another size in the middle of the sequence, whether or not it is one of the
/// calibration frames (10 frames: calibration picks 0, 2, 4, 6, 9), is an error naming the
/// file and both sizes.
#[test]
fn frame_of_another_size_is_an_error() {
    for odd in ["frame_00005.png", "frame_00004.png"] {
        let dir = synth(10);
        uniform_frame(&dir.path().join("frames").join(odd), 300, 200);
        assert_error(dir.path(), &spec_text(dir.path()), &[odd, "300×200", "320×240"]);
    }
    // A background frame of another size names its key.
    let dir = synth(6);
    uniform_frame(&dir.path().join("flat.png"), 300, 200);
    let spec = spec_text(dir.path()).replace("background = \"fit\"", "background = \"flat.png\"");
    assert_error(dir.path(), &spec, &["contact.background", "300×200", "320×240"]);
}

/// A change-map reference beyond the last frame is an error naming the key and the value; the
/// last frame itself (index 5 of 6) is accepted and used; a reference frame that cannot be
/// decoded is an error naming it (it used to leave no change map, silently).
#[test]
fn change_reference_beyond_last_frame() {
    let dir = synth(6);
    let spec = spec_text(dir.path()).replace("reference = \"previous\"", "reference = 6");
    assert_error(dir.path(), &spec, &["changes.reference", "6", "frame_00005.png"]);
    let spec = spec_text(dir.path())
        .replace("reference = \"previous\"", "reference = 5")
        .replace("every = 0", "every = 1");
    let (ok, stderr, out_dir) = analyse(dir.path(), &spec);
    assert!(ok, "{stderr}");
    assert!(out_dir.join("changes/change_00000_vs_00005.png").is_file()); // A reference frame that cannot be decoded is named.
    std::fs::write(dir.path().join("frames/frame_00002.png"), b"not an image").unwrap();
    let spec = spec_text(dir.path()).replace("reference = \"previous\"", "reference = 2");
    assert_error(dir.path(), &spec, &["changes.reference = 2", "frame_00002.png"]);
}

/// A log that does not overlap the frames in time is an error; a partial overlap is a
/// warning with the count of frames without force (on stderr and in summary.json), and those
/// frames have empty force cells.
#[test]
fn force_log_time_overlap() {
    let dir = synth(6);
    edit_log(dir.path(), |_, cells| {
        cells[0] = format!("{}", cells[0].parse::<f64>().unwrap() + 100.0)
    });
    assert_error(dir.path(), &spec_text(dir.path()), &["log.csv", "100", "overlap"]);

    let dir = synth(6);
    edit_log(dir.path(), |line, cells| {
        if line > 4 {
            cells.clear(); // keep t = 0, 1, 2
        }
    });
    let (ok, stderr, out_dir) = analyse(dir.path(), &spec_text(dir.path()));
    assert!(ok, "{stderr}");
    assert!(stderr.contains("3 of 6 frames"), "{stderr}");
    let summary = std::fs::read_to_string(out_dir.join("summary.json")).unwrap();
    assert!(summary.contains("3 of 6 frames"), "{summary}");
    let frames = std::fs::read_to_string(out_dir.join("frames.csv")).unwrap();
    let without_force = frames
        .lines()
        .skip(1)
        .filter(|l| l.split(',').nth(5) == Some(""))
        .count();
    assert_eq!(without_force, 3, "{frames}");
}

/// Log cells: text, NaN and ±inf are errors naming the file, line and column; an empty cell
/// of a data column is a missing sample, dropped with a warning that counts it; an empty
/// time cell is an error.
#[test]
fn log_cells_are_numbers() {
    for (bad, column) in [("abc", 2), ("NaN", 2), ("inf", 2), ("-inf", 2), ("", 0), ("1.2.3", 0)] {
        let dir = synth(6);
        edit_log(dir.path(), |line, cells| {
            if line == 5 {
                cells[column] = bad.to_string()
            }
        });
        let name = ["t", "Fn", "Fx"][column];
        let where_ = format!("line 5, column {} (\"{name}\")", column + 1);
        assert_error(dir.path(), &spec_text(dir.path()), &["log.csv", &where_]);
    }
    let dir = synth(6);
    edit_log(dir.path(), |line, cells| {
        if line == 5 || line == 6 {
            cells[2] = String::new()
        }
    });
    let (ok, stderr, _) = analyse(dir.path(), &spec_text(dir.path()));
    assert!(ok, "{stderr}");
    assert!(stderr.contains("2 empty cells"), "{stderr}");
}

/// Time stamps that go back are an error naming the line, in the log and in the frame
/// time-stamp file; a repeated time in the log is accepted (samples faster than the clock's
/// resolution), a repeated frame time is not. Too few frame time stamps are an error, too
/// many a warning.
#[test]
fn time_stamps_must_not_go_back() {
    let dir = synth(6);
    edit_log(dir.path(), |line, cells| {
        if line == 5 {
            cells[0] = "1.5".into() // after t = 2 on line 4
        }
    });
    assert_error(dir.path(), &spec_text(dir.path()), &["log.csv", "line 5", "1.5"]);

    let dir = synth(6);
    edit_log(dir.path(), |line, cells| {
        if line == 5 {
            cells[0] = "2".into()
        }
    });
    let (ok, stderr, _) = analyse(dir.path(), &spec_text(dir.path()));
    assert!(ok, "repeated log time rejected: {stderr}");

    let dir = synth(6);
    for (times, line) in [
        ("t\n0\n1\n2\n1.5\n4\n5\n", "line 5"),
        ("t\n0\n1\n1\n3\n4\n5\n", "line 4"),
    ] {
        std::fs::write(dir.path().join("times.csv"), times).unwrap();
        let spec = spec_text(dir.path()).replace("rate = 1", "timestamps = \"times.csv\"");
        assert_error(dir.path(), &spec, &["frames.timestamps", "times.csv", line]);
    }
    // Fewer time stamps than frames: an error with both counts; more: a warning.
    std::fs::write(dir.path().join("times.csv"), "t\n0\n1\n2\n").unwrap();
    let spec = spec_text(dir.path()).replace("rate = 1", "timestamps = \"times.csv\"");
    assert_error(dir.path(), &spec, &["frames.timestamps", "3 times for 6 frames"]);
    std::fs::write(dir.path().join("times.csv"), "t\n0\n1\n2\n3\n4\n5\n6\n").unwrap();
    let (ok, stderr, _) = analyse(dir.path(), &spec);
    assert!(ok && stderr.contains("7 times for 6 frames"), "{stderr}");
}

/// The indenter centre and the region of interest must lie inside the image (320×240).
#[test]
fn centre_and_region_inside_the_image() {
    let dir = synth(6);
    let spec = spec_text(dir.path());
    let centre = spec.lines().find(|l| l.starts_with("centre_px")).unwrap().to_string();
    for bad in [
        "centre_px = [320, 120]",
        "centre_px = [-1, 120]",
        "centre_px = [140, 240.5]",
    ] {
        assert_error(
            dir.path(),
            &spec.replace(&centre, bad),
            &["indenter.centre_px", "320×240"],
        );
    }
    for bad in [
        "roi = [300, 0, 40, 100]",
        "roi = [0, 0, 320, 241]",
        "roi = [400, 300, 10, 10]",
    ] {
        let spec = spec.replace("[contact]", &format!("[contact]\n{bad}"));
        assert_error(dir.path(), &spec, &["contact.roi", "320×240"]);
    }
    // The whole image is a valid region; the last pixel is a valid centre.
    let spec = spec
        .replace(&centre, "centre_px = [319, 239]")
        .replace("[contact]", "[contact]\nroi = [0, 0, 320, 240]");
    let (ok, stderr, _) = analyse(dir.path(), &spec);
    assert!(ok, "{stderr}");
}

/// Keys the analysis would not use are errors naming the key: unknown keys at every level,
/// and keys that have no effect without another one.
#[test]
fn unused_keys_are_errors() {
    let dir = synth(2);
    let spec = spec_text(dir.path());
    let cases = [
        (format!("{spec}\n[plots]\ndpi = 300\n"), "plots"),
        (spec.replace("[analysis]", "") + "\n[analysis]\njump = 0.1\n", "jump"),
        (
            spec.replace("stage_z = \"z\"", "stage_z = \"z\"\nforce = \"Fn\""),
            "force",
        ),
        (
            format!("{spec}\n[fits]\npower_law = {{ path = \"p.csv\", time = \"t\", force = \"F\", unit = \"N\" }}\n"),
            "unit",
        ),
        (
            format!("{spec}\n[fits]\ncontact_modulus = 1.0\n"),
            "fits.indenter_radius",
        ),
        (
            format!("{spec}\n[fits]\nindenter_radius = 1.0\n"),
            "fits.contact_modulus",
        ),
        (
            spec.replace(
                "background = \"fit\"",
                "background = \"none\"\ncorrection = \"subtract\"",
            ),
            "contact.correction",
        ),
        (spec.replace("stage_x = \"x\"\n", ""), "indenter.stage_x0"),
    ];
    for (text, expected) in cases {
        assert_error(dir.path(), &text, &[expected]);
    }
}

/// Arrays with extra values were accepted (`contact.roi` of five values, `centre_px` of
/// three): an error naming the key and both counts; too few values stay an error.
#[test]
fn arrays_of_the_wrong_length_are_errors() {
    let dir = synth(2);
    let spec = spec_text(dir.path());
    let centre = spec.lines().find(|l| l.starts_with("centre_px")).unwrap().to_string();
    assert_error(
        dir.path(),
        &spec.replace(&centre, "centre_px = [140, 120, 7]"),
        &["centre_px", "expected 2 values, got 3"],
    );
    let with_roi = spec.replace("[contact]", "[contact]\nroi = [0, 0, 10, 10, 99]");
    assert_error(dir.path(), &with_roi, &["roi", "expected 4 values, got 5"]);
    let with_roi = spec.replace("[contact]", "[contact]\nroi = [0, 0, 10]");
    assert_error(dir.path(), &with_roi, &["roi", "expected 4 values, got 3"]);
}

/// A grey and a colour JPEG (tests/data/jpeg, README there) read as the grey levels
/// image 0.25.10's reader gave them (written beside them as PNG, which decodes without
/// loss): every pixel equal. The colour frame checks the luma conversion too.
#[test]
fn jpeg_frames_read_as_image_0_25_read_them() {
    let data = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/jpeg");
    for name in ["grey", "colour"] {
        let jpeg = adhesim_cli::read_frame(&data.join(format!("{name}.jpg"))).unwrap();
        let reference = adhesim_cli::read_frame(&data.join(format!("{name}_levels.png"))).unwrap();
        assert_eq!((jpeg.width(), jpeg.height()), (64, 48), "{name}");
        assert_eq!(jpeg.pixels(), reference.pixels(), "{name}");
    }
}
