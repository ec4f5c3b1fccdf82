//! Files written by reference implementations (see tests/data/README.md): x3p by x3pio 2.0.0,
//! .gwy by gwyfile 0.3.0, .sur by surfalize 0.19.2. Each holds the 5 × 4 map
//! `z[row, col] = (col + 10·row − 7) nm`, x spacing 0.5 µm, y spacing 0.25 µm.

use std::path::PathBuf;

use adhesim_topography::{read_topography, ReadOptions};

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(name)
}

fn expected() -> Vec<f64> {
    (0..4)
        .flat_map(|row| (0..5).map(move |col| (col as f64 + 10.0 * row as f64 - 7.0) * 1e-9))
        .collect()
}

fn check(map: &adhesim_topography::Topography, tolerance: f64, skip: &[usize]) {
    assert_eq!((map.nx, map.ny), (5, 4));
    assert!(
        (map.dx - 0.5e-6).abs() < 1e-18 && (map.dy - 0.25e-6).abs() < 1e-18,
        "{} {}",
        map.dx,
        map.dy
    );
    for (i, (got, want)) in map.heights.iter().zip(expected()).enumerate() {
        if !skip.contains(&i) {
            assert!((got - want).abs() <= tolerance, "point {i}: {got:e} vs {want:e}");
        }
    }
}

#[test]
fn x3pio_float64() {
    let map = read_topography(data("reference_float64.x3p"), &ReadOptions::default()).unwrap();
    check(&map, 1e-24, &[]);
    assert!(map.mask.is_none());
    assert_eq!(
        map.metadata.get("Instrument/Manufacturer").map(String::as_str),
        Some("x3pio")
    );
}

#[test]
fn x3pio_int16_with_an_invalid_point() {
    let map = read_topography(data("reference_int16_invalid.x3p"), &ReadOptions::default()).unwrap();
    // x3pio scales int16 so that the largest height is 32767 increments of 8.24e-13 m; the
    // reading is exact to half an increment.
    check(&map, 0.5 * 8.24e-13, &[13]);
    let mask = map.mask.as_ref().unwrap();
    assert!(
        !mask[13] && mask.iter().filter(|&&v| !v).count() == 1,
        "row 2, column 3 invalid"
    );
}

#[test]
fn gwyfile_container_channels_and_mask() {
    let map = read_topography(data("reference.gwy"), &ReadOptions::default()).unwrap();
    assert_eq!(map.channel, "Topography");
    check(&map, 1e-24, &[7]);
    let mask = map.mask.as_ref().unwrap();
    assert!(
        !mask[7] && mask.iter().filter(|&&v| !v).count() == 1,
        "row 1, column 2 masked"
    );
    let phase = ReadOptions {
        channel: Some("Phase".into()),
        ..Default::default()
    };
    let err = read_topography(data("reference.gwy"), &phase).unwrap_err().to_string();
    assert!(err.contains("reference.gwy") && err.contains("\"deg\""), "{err}");
}

#[test]
fn surfalize_int32_in_micrometres() {
    let map = read_topography(data("reference.sur"), &ReadOptions::default()).unwrap();
    // surfalize scales the range onto int32 with a float32 z spacing and offset: the offset
    // (float32, about 16 nm) limits the accuracy to its half ulp, 1e-15 m.
    check(&map, 2e-15, &[]);
    assert_eq!(map.height_unit, "µm");
}
