//! Round trips: files written here byte by byte in each format are read back with their
//! values, spacing and units. Heights compare to 1e-18 m (exact arithmetic up to the last
//! bits of metres-sized conversions) unless the format stores fewer bits (stated per test).

use crate::common;

use adhesim_topography::{read_topography, ReadOptions, Topography, TopographyError};
use common::*;

fn write_and_read(name: &str, bytes: &[u8], options: &ReadOptions) -> Result<Topography, TopographyError> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, bytes).unwrap();
    read_topography(&path, options)
}

fn with_units(spacing: (f64, f64), height_unit: &str) -> ReadOptions {
    ReadOptions {
        spacing: Some(spacing),
        height_unit: Some(height_unit.into()),
        ..Default::default()
    }
}

#[test]
fn x3p_every_data_type_with_validity_mask() {
    let (nx, ny, dx, dy) = (7, 5, 0.5e-6, 0.25e-6);
    let heights = sample_heights(nx, ny);
    let mut valid = vec![true; nx * ny];
    valid[12] = false;
    for data_type in ['I', 'L', 'F', 'D'] {
        // Integers with an increment of 0.01 nm and an offset; float32 in nanometres (an
        // increment of 1e-9 applies to floats too); float64 in metres.
        let (increment, offset) = match data_type {
            'I' | 'L' => (1e-11, 2e-9),
            'F' => (1e-9, 0.0),
            _ => (1.0, 0.0),
        };
        let raw: Vec<f64> = heights
            .iter()
            .map(|h| match data_type {
                'I' | 'L' => ((h - offset) / increment).round(),
                _ => (h - offset) / increment,
            })
            .collect();
        let bytes = x3p_bytes(nx, ny, dx, dy, data_type, &raw, increment, offset, Some(&valid));
        let map = write_and_read("map.x3p", &bytes, &ReadOptions::default()).unwrap();
        assert_eq!((map.nx, map.ny, map.format), (nx, ny, "x3p"));
        assert_eq!((map.dx, map.dy, map.x_offset), (dx, dy, 1e-6));
        assert_eq!(map.mask.as_deref(), Some(valid.as_slice()));
        // Integers store heights to half an increment; float32 rounds to half an ulp, 2^-24
        // relative: 3e-15 m at the largest height, 50 nm.
        let tolerance = match data_type {
            'I' | 'L' => 0.5e-11 + 1e-20,
            'F' => 3e-15,
            _ => 0.0,
        };
        for i in (0..nx * ny).filter(|&i| valid[i]) {
            assert!(
                (map.heights[i] - heights[i]).abs() <= tolerance,
                "{data_type} point {i}"
            );
        }
        assert_eq!(map.metadata.get("Creator").map(String::as_str), Some("adhesim tests"));
    }
}

#[test]
fn x3p_float_nan_marks_invalid_points() {
    let (nx, ny) = (4, 3);
    let mut raw = sample_heights(nx, ny);
    raw[5] = f64::NAN;
    let bytes = x3p_bytes(nx, ny, 1e-6, 1e-6, 'D', &raw, 1.0, 0.0, None);
    let map = write_and_read("nan.x3p", &bytes, &ReadOptions::default()).unwrap();
    let mask = map.mask.unwrap();
    assert!(!mask[5] && mask.iter().filter(|&&v| !v).count() == 1);
    assert!(map.heights.iter().all(|h| h.is_finite()));
}

fn two_channel_gwy(nx: usize, ny: usize, heights_nm: &[f64], mask: Option<&[f64]>) -> Vec<u8> {
    let mut components = vec![
        (
            "/0/data",
            GwyValue::Object(gwy_field(nx, ny, 1.0, 1.0, "V", "V", &vec![1.0; nx * ny])),
        ),
        ("/0/data/title", GwyValue::Text("Amplitude".into())),
        (
            "/3/data",
            GwyValue::Object(gwy_field(
                nx,
                ny,
                nx as f64 * 0.2,
                ny as f64 * 0.1,
                "µm",
                "nm",
                heights_nm,
            )),
        ),
        ("/3/data/title", GwyValue::Text("Height".into())),
    ];
    if let Some(mask) = mask {
        components.push(("/3/mask", GwyValue::Object(gwy_field(nx, ny, 1.0, 1.0, "", "", mask))));
    }
    gwy_file(&components)
}

#[test]
fn gwy_channel_by_title_with_units_and_mask() {
    let (nx, ny) = (6, 4);
    let heights = sample_heights(nx, ny);
    let heights_nm: Vec<f64> = heights.iter().map(|h| h * 1e9).collect();
    let mut mask = vec![0.0; nx * ny];
    mask[7] = 1.0;
    let bytes = two_channel_gwy(nx, ny, &heights_nm, Some(&mask));
    let options = ReadOptions {
        channel: Some("Height".into()),
        ..Default::default()
    };
    let map = write_and_read("scan.gwy", &bytes, &options).unwrap();
    assert_eq!((map.nx, map.ny, map.channel.as_str()), (nx, ny, "Height"));
    assert!((map.dx - 0.2e-6).abs() < 1e-20 && (map.dy - 0.1e-6).abs() < 1e-20);
    assert_eq!((map.height_unit.as_str(), map.lateral_unit.as_str()), ("nm", "µm"));
    let valid = map.mask.clone().unwrap();
    assert!(!valid[7] && valid.iter().filter(|&&v| v).count() == nx * ny - 1);
    for i in (0..nx * ny).filter(|&i| i != 7) {
        assert!((map.heights[i] - heights[i]).abs() < 1e-22, "point {i}");
    }
    // The first channel is a voltage: reading it as a topography names the unit.
    let err = write_and_read("scan.gwy", &bytes, &ReadOptions::default()).unwrap_err();
    assert!(
        matches!(err, TopographyError::UnknownUnit { ref unit, .. } if unit == "V"),
        "{err}"
    );
    let missing = ReadOptions {
        channel: Some("Phase".into()),
        ..Default::default()
    };
    let err = write_and_read("scan.gwy", &bytes, &missing).unwrap_err().to_string();
    assert!(
        err.contains("scan.gwy") && err.contains("\"Phase\"") && err.contains("Amplitude, Height"),
        "{err}"
    );
}

fn sur_header<'a>(bits: i16, compressed: bool, non_measured: bool) -> SurHeader<'a> {
    SurHeader {
        nx: 5,
        ny: 3,
        bits,
        dx: 0.5,
        dy: 0.25,
        spacing_z: 0.01,
        offset_z: 2.0,
        lateral_unit: b"\xb5m",
        z_unit: b"nm",
        zmin: -30000,
        non_measured,
        compressed,
        comment: b"a comment",
    }
}

#[test]
fn sur_16_and_32_bit_plain_and_compressed_with_non_measured_points() {
    for (bits, compressed) in [(16, false), (32, false), (32, true), (16, true)] {
        let header = sur_header(bits, compressed, true);
        let mut raw: Vec<i32> = (0..15).map(|i| i * 37 - 200).collect();
        raw[4] = header.zmin - 2;
        let map = write_and_read("m.sur", &sur_bytes(&header, &raw), &ReadOptions::default())
            .unwrap_or_else(|e| panic!("{bits} bit, compressed {compressed}: {e}"));
        assert_eq!((map.nx, map.ny), (5, 3));
        // Spacings are float32 in the file: 0.5 and 0.25 are exact.
        assert_eq!((map.dx, map.dy), (0.5e-6, 0.25e-6));
        assert_eq!(
            (
                map.lateral_unit.as_str(),
                map.height_unit.as_str(),
                map.channel.as_str()
            ),
            ("µm", "nm", "Height")
        );
        assert_eq!(map.metadata.get("comment").map(String::as_str), Some("a comment"));
        let mask = map.mask.as_ref().unwrap();
        for (i, &r) in raw.iter().enumerate().filter(|&(i, _)| i != 4) {
            // spacing_z = 0.01 in float32: relative 3e-8.
            let want = (r as f64 * 0.01 + 2.0) * 1e-9;
            assert!(mask[i] && (map.heights[i] - want).abs() < 1e-16, "{bits} bit point {i}");
        }
        assert!(!mask[4]);
    }
}

#[test]
fn ascii_matrix_with_gwyddion_header() {
    let text = "# Channel: Topography\n# Width: 1.500 µm\n# Height: 500 nm\n# Value units: nm\n\
                1 2 3\n4 5 6\n";
    let map = write_and_read("export.txt", text.as_bytes(), &ReadOptions::default()).unwrap();
    assert_eq!((map.nx, map.ny, map.channel.as_str()), (3, 2, "Topography"));
    assert_close(&[map.dx, map.dy], &[0.5e-6, 0.25e-6], 1e-20, "spacing");
    assert_close(&map.heights, &[1e-9, 2e-9, 3e-9, 4e-9, 5e-9, 6e-9], 1e-24, "heights");
}

#[test]
fn ascii_matrix_with_spip_header() {
    let text = "# File Format = ASCII\n# Created by SPIP 6.0\n# x-pixels = 2\n# y-pixels = 2\n\
                # x-length = 1000\n# y-length = 500\n# Bit2nm = 0.5\n# Start of Data:\n\
                2\t4\n6\tNaN\n";
    let map = write_and_read("spip.asc", text.as_bytes(), &ReadOptions::default()).unwrap();
    assert_close(&[map.dx, map.dy], &[500e-9, 250e-9], 1e-20, "spacing");
    assert_close(&map.heights[..3], &[1e-9, 2e-9, 3e-9], 1e-24, "heights");
    assert_eq!(map.mask, Some(vec![true, true, true, false]));
    let z_unit = text.replace("# Bit2nm = 0.5", "# z-unit = um");
    let map = write_and_read("spip.asc", z_unit.as_bytes(), &ReadOptions::default()).unwrap();
    assert_close(&map.heights[..3], &[2e-6, 4e-6, 6e-6], 1e-20, "heights in um");
}

#[test]
fn bare_matrix_needs_spacing_and_unit_from_the_caller() {
    let text = "0.1, 0.2, 0.3\n0.4, 0.5, 0.6\n";
    let err = write_and_read("bare.csv", text.as_bytes(), &ReadOptions::default()).unwrap_err();
    assert!(
        matches!(err, TopographyError::MissingOption { option: "spacing", .. }),
        "{err}"
    );
    let spacing_only = ReadOptions {
        spacing: Some((1e-6, 2e-6)),
        ..Default::default()
    };
    let err = write_and_read("bare.csv", text.as_bytes(), &spacing_only).unwrap_err();
    assert!(
        err.to_string().contains("bare.csv") && err.to_string().contains("height_unit"),
        "{err}"
    );
    let map = write_and_read("bare.csv", text.as_bytes(), &with_units((1e-6, 2e-6), "um")).unwrap();
    assert_eq!((map.nx, map.ny, map.dx, map.dy), (3, 2, 1e-6, 2e-6));
    assert_close(
        &map.heights,
        &[0.1e-6, 0.2e-6, 0.3e-6, 0.4e-6, 0.5e-6, 0.6e-6],
        1e-20,
        "heights",
    );
}

#[test]
fn xyz_points_in_any_order_on_a_regular_grid() {
    let (nx, ny) = (4, 3);
    let heights = sample_heights(nx, ny);
    let mut lines = vec!["# Lateral units: um".to_string(), "# Value units: m".to_string()];
    // Written y-major backwards, so the reader must place points by their coordinates.
    for i in (0..nx * ny).rev() {
        let (ix, iy) = (i % nx, i / nx);
        lines.push(format!(
            "{} {} {:e}",
            3.0 + 0.5 * ix as f64,
            0.25 * iy as f64,
            heights[i]
        ));
    }
    let map = write_and_read("pts.xyz", lines.join("\n").as_bytes(), &ReadOptions::default()).unwrap();
    assert_eq!((map.nx, map.ny), (nx, ny));
    assert_close(&[map.dx, map.dy, map.x_offset], &[0.5e-6, 0.25e-6, 3e-6], 1e-20, "grid");
    assert_close(&map.heights, &heights, 1e-24, "heights");
    let bare = lines[2..].join("\n");
    let err = write_and_read("pts.xyz", bare.as_bytes(), &ReadOptions::default()).unwrap_err();
    assert!(
        matches!(
            err,
            TopographyError::MissingOption {
                option: "lateral_unit",
                ..
            }
        ),
        "{err}"
    );
}

#[test]
fn npy_dtypes_orders_and_byte_orders() {
    // The 2 × 3 array [[0, 1, 2], [3, 4, 5]] in each encoding.
    let c_order = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
    let f_order = [0.0, 3.0, 1.0, 4.0, 2.0, 5.0];
    let encode = |values: &[f64], descr: &str| -> Vec<u8> {
        values
            .iter()
            .flat_map(|&v| match descr {
                "<f8" => v.to_le_bytes().to_vec(),
                ">f8" => v.to_be_bytes().to_vec(),
                "<f4" => (v as f32).to_le_bytes().to_vec(),
                ">f4" => (v as f32).to_be_bytes().to_vec(),
                "<i4" => (v as i32).to_le_bytes().to_vec(),
                ">i2" => (v as i16).to_be_bytes().to_vec(),
                "|u1" => vec![v as u8],
                _ => unreachable!(),
            })
            .collect()
    };
    for descr in ["<f8", ">f8", "<f4", ">f4", "<i4", ">i2", "|u1"] {
        for fortran in [false, true] {
            let data = encode(if fortran { &f_order } else { &c_order }, descr);
            let bytes = npy_raw(descr, fortran, "(2, 3)", &data);
            let map = write_and_read("h.npy", &bytes, &with_units((1e-6, 1e-6), "nm")).unwrap();
            assert_eq!((map.nx, map.ny), (3, 2), "{descr}");
            let want: Vec<f64> = c_order.iter().map(|v| v * 1e-9).collect();
            assert_close(&map.heights, &want, 1e-24, descr);
        }
    }
    let err = write_and_read(
        "h.npy",
        &npy_raw("<c16", false, "(1, 1)", &[0; 16]),
        &with_units((1.0, 1.0), "m"),
    )
    .unwrap_err();
    assert!(err.to_string().contains("<c16"), "{err}");
}

#[test]
fn npz_member_by_name() {
    let a = npy_raw(
        "<f8",
        false,
        "(1, 2)",
        &[1.0f64.to_le_bytes(), 2.0f64.to_le_bytes()].concat(),
    );
    let b = npy_raw(
        "<f8",
        false,
        "(2, 1)",
        &[3.0f64.to_le_bytes(), 4.0f64.to_le_bytes()].concat(),
    );
    let bytes = zip_archive(&[("first.npy", &a), ("second.npy", &b)]);
    let map = write_and_read("f.npz", &bytes, &with_units((1.0, 1.0), "m")).unwrap();
    assert_eq!((map.channel.as_str(), map.heights.clone()), ("first", vec![1.0, 2.0]));
    let options = ReadOptions {
        channel: Some("second".into()),
        ..with_units((1.0, 1.0), "mm")
    };
    let map = write_and_read("f.npz", &bytes, &options).unwrap();
    assert_eq!((map.nx, map.ny, map.heights.clone()), (1, 2, vec![3e-3, 4e-3]));
    let options = ReadOptions {
        channel: Some("third".into()),
        ..with_units((1.0, 1.0), "m")
    };
    let err = write_and_read("f.npz", &bytes, &options).unwrap_err().to_string();
    assert!(err.contains("first, second"), "{err}");
}

#[test]
fn unknown_extension_is_named() {
    let err = write_and_read("map.bmp", b"", &ReadOptions::default())
        .unwrap_err()
        .to_string();
    assert!(err.contains("map.bmp") && err.contains("\"bmp\""), "{err}");
}

#[test]
fn x3p_inline_data_list_with_an_empty_datum() {
    // ISO 25178-72 allows the points as Record3/DataList/Datum text instead of a binary file;
    // an empty datum is an invalid point.
    let xml = r#"<?xml version="1.0" encoding="UTF-8"?>
<p:ISO5436_2 xmlns:p="http://www.opengps.eu/2008/ISO5436_2"><Record1><Revision>ISO5436 - 2000</Revision>
<FeatureType>SUR</FeatureType><Axes>
<CX><AxisType>I</AxisType><DataType>D</DataType><Increment>2e-6</Increment><Offset>0</Offset></CX>
<CY><AxisType>I</AxisType><DataType>D</DataType><Increment>3e-6</Increment><Offset>0</Offset></CY>
<CZ><AxisType>A</AxisType><DataType>D</DataType><Increment>1e-9</Increment><Offset>0</Offset></CZ>
</Axes></Record1><Record3><MatrixDimension><SizeX>2</SizeX><SizeY>2</SizeY><SizeZ>1</SizeZ></MatrixDimension>
<DataList><Datum>1.5</Datum><Datum>2.5</Datum><Datum/><Datum>-4</Datum></DataList></Record3></p:ISO5436_2>"#;
    let bytes = zip_archive(&[("main.xml", xml.as_bytes())]);
    let map = write_and_read("inline.x3p", &bytes, &ReadOptions::default()).unwrap();
    assert_eq!((map.nx, map.ny, map.dx, map.dy), (2, 2, 2e-6, 3e-6));
    assert_eq!(map.mask, Some(vec![true, true, false, true]));
    assert_close(
        &[map.heights[0], map.heights[1], map.heights[3]],
        &[1.5e-9, 2.5e-9, -4e-9],
        1e-24,
        "heights",
    );
    // Without the lateral increment the spacing is unknown: an error, not a default.
    let no_increment = xml.replace("<Increment>2e-6</Increment>", "");
    let bytes = zip_archive(&[("main.xml", no_increment.as_bytes())]);
    let err = write_and_read("inline.x3p", &bytes, &ReadOptions::default()).unwrap_err();
    assert!(err.to_string().contains("Record1/Axes/CX/Increment"), "{err}");
}
