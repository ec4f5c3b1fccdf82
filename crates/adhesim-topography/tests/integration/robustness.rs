//! Malformed, truncated and hostile files give errors naming the file and the problem, never a
//! panic, an abort or a huge allocation.

use crate::common;

use adhesim_topography::{read_topography_from_bytes, ReadOptions, TopographyError};
use common::*;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

fn options() -> ReadOptions {
    ReadOptions {
        spacing: Some((1e-6, 1e-6)),
        height_unit: Some("nm".into()),
        lateral_unit: Some("um".into()),
        ..Default::default()
    }
}

fn reference(name: &str) -> Vec<u8> {
    std::fs::read(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data")
            .join(name),
    )
    .unwrap()
}

/// One valid file of each format: `(file name, bytes, binary)`; a prefix of a binary file is
/// always invalid, a prefix of a text file may be a smaller valid map.
fn fixtures() -> Vec<(&'static str, Vec<u8>, bool)> {
    let (nx, ny) = (4, 3);
    let heights = sample_heights(nx, ny);
    let raw: Vec<f64> = heights.iter().map(|h| (h / 1e-11).round()).collect();
    let valid: Vec<bool> = (0..nx * ny).map(|i| i != 5).collect();
    let sur = |compressed| SurHeader {
        nx,
        ny,
        bits: 16,
        dx: 1.0,
        dy: 1.0,
        spacing_z: 1.0,
        offset_z: 0.0,
        lateral_unit: b"um",
        z_unit: b"nm",
        zmin: -100,
        non_measured: true,
        compressed,
        comment: b"c",
    };
    let sur_raw: Vec<i32> = (0..12).collect();
    let npy = npy_raw(
        "<f8",
        false,
        "(3, 4)",
        &heights.iter().flat_map(|h| h.to_le_bytes()).collect::<Vec<_>>(),
    );
    vec![
        ("ref.x3p", reference("reference_int16_invalid.x3p"), true),
        ("ref.gwy", reference("reference.gwy"), true),
        ("ref.sur", reference("reference.sur"), true),
        ("own.x3p", x3p_bytes(nx, ny, 1e-6, 1e-6, 'L', &raw, 1e-11, 0.0, Some(&valid)), true),
        ("own.sur", sur_bytes(&sur(true), &sur_raw), true),
        ("own.npy", npy.clone(), true),
        ("own.npz", zip_archive(&[("heights.npy", &npy)]), true),
        ("gwy.txt", b"# Channel: Z\n# Width: 4 um\n# Height: 3 um\n# Value units: nm\n1 2 3 4\n5 6 7 8\n9 10 11 12\n".to_vec(), false),
        ("spip.asc", b"# File Format = ASCII\n# x-pixels = 2\n# y-pixels = 2\n# x-length = 10\n# y-length = 10\n# Bit2nm = 1\n# Start of Data:\n1 2\n3 4\n".to_vec(), false),
        ("p.xyz", b"0 0 1\n1 0 2\n0 1 3\n1 1 4\n".to_vec(), false),
    ]
}

#[test]
fn every_fixture_reads() {
    for (name, bytes, _) in fixtures() {
        read_topography_from_bytes(&bytes, name, &options()).unwrap_or_else(|e| panic!("{e}"));
    }
}

#[test]
fn every_truncation_of_a_binary_file_is_a_named_error() {
    for (name, bytes, binary) in fixtures() {
        for len in 0..bytes.len() {
            let result = read_topography_from_bytes(&bytes[..len], name, &options());
            if binary {
                let err = result.expect_err(&format!("{name} cut to {len} bytes was accepted"));
                assert!(err.to_string().starts_with(name), "{name} at {len}: {err}");
            }
        }
    }
}

#[test]
fn headers_claiming_huge_maps_are_errors_not_allocations() {
    // A Gwyddion field of 10^6 × 10^6 points with 4 doubles of data.
    let field = gwy_object(
        "GwyDataField",
        &[
            ("xres", GwyValue::Int(1_000_000)),
            ("yres", GwyValue::Int(1_000_000)),
            ("xreal", GwyValue::Double(1.0)),
            ("yreal", GwyValue::Double(1.0)),
            ("si_unit_xy", GwyValue::Object(gwy_unit("m"))),
            ("si_unit_z", GwyValue::Object(gwy_unit("m"))),
            ("data", GwyValue::Doubles(vec![0.0; 4])),
        ],
    );
    let gwy = gwy_file(&[("/0/data", GwyValue::Object(field))]);
    let err = read_topography_from_bytes(&gwy, "huge.gwy", &options())
        .unwrap_err()
        .to_string();
    assert!(err.contains("huge.gwy") && err.contains("1000000 × 1000000"), "{err}");

    // A double array whose count claims 2^32 − 1 items.
    let mut lying = gwy_file(&[(
        "/0/data",
        GwyValue::Object(gwy_field(2, 2, 1.0, 1.0, "m", "m", &[0.0; 4])),
    )]);
    let count_at = lying.windows(6).position(|w| w == b"data\0D").unwrap() + 6;
    lying[count_at..count_at + 4].copy_from_slice(&u32::MAX.to_le_bytes());
    let err = read_topography_from_bytes(&lying, "lying.gwy", &options()).unwrap_err();
    assert!(matches!(err, TopographyError::Malformed { .. }), "{err}");

    let mut sur = sur_bytes(
        &SurHeader {
            nx: 2,
            ny: 2,
            bits: 32,
            dx: 1.0,
            dy: 1.0,
            spacing_z: 1.0,
            offset_z: 0.0,
            lateral_unit: b"m",
            z_unit: b"m",
            zmin: 0,
            non_measured: false,
            compressed: false,
            comment: b"",
        },
        &[1, 2, 3, 4],
    );
    sur[108..112].copy_from_slice(&1_000_000i32.to_le_bytes());
    sur[112..116].copy_from_slice(&1_000_000i32.to_le_bytes());
    let err = read_topography_from_bytes(&sur, "huge.sur", &options())
        .unwrap_err()
        .to_string();
    assert!(err.contains("huge.sur") && err.contains("exceeds"), "{err}");

    let npy = npy_raw("<f8", false, "(1000000, 1000000)", &[0; 32]);
    let err = read_topography_from_bytes(&npy, "huge.npy", &options())
        .unwrap_err()
        .to_string();
    assert!(err.contains("huge.npy") && err.contains("exceeds"), "{err}");

    let x3p = x3p_bytes(2, 2, 1e-6, 1e-6, 'D', &[0.0; 4], 1.0, 0.0, None);
    let patched = patch_zip_member(&x3p, "main.xml", |xml| {
        xml.replace("<SizeX>2</SizeX>", "<SizeX>1000000000</SizeX>")
    });
    let err = read_topography_from_bytes(&patched, "huge.x3p", &options())
        .unwrap_err()
        .to_string();
    assert!(err.contains("huge.x3p") && err.contains("exceeds"), "{err}");
}

#[test]
fn x3p_data_of_the_wrong_length_is_named() {
    let x3p = x3p_bytes(2, 2, 1e-6, 1e-6, 'D', &[0.0; 4], 1.0, 0.0, None);
    let patched = patch_zip_member(&x3p, "main.xml", |xml| {
        xml.replace("<SizeY>2</SizeY>", "<SizeY>3</SizeY>")
    });
    let err = read_topography_from_bytes(&patched, "short.x3p", &options())
        .unwrap_err()
        .to_string();
    assert!(err.contains("short.x3p") && err.contains("bindata/data.bin"), "{err}");
    let long = patch_zip_member(&x3p, "main.xml", |xml| {
        xml.replace("<SizeY>2</SizeY>", "<SizeY>1</SizeY>")
    });
    let err = read_topography_from_bytes(&long, "long.x3p", &options())
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("long.x3p") && err.contains("bindata/data.bin declares 32 bytes"),
        "{err}"
    );
    let unclosed = patch_zip_member(&x3p, "main.xml", |xml| xml.replace("</p:ISO5436_2>", ""));
    let err = read_topography_from_bytes(&unclosed, "cut.x3p", &options())
        .unwrap_err()
        .to_string();
    assert!(err.contains("cut.x3p") && err.contains("main.xml"), "{err}");
}

fn patch_zip_member(archive: &[u8], name: &str, edit: impl Fn(&str) -> String) -> Vec<u8> {
    let mut zip = zip::ZipArchive::new(std::io::Cursor::new(archive)).unwrap();
    let mut members = Vec::new();
    for i in 0..zip.len() {
        let mut file = zip.by_index(i).unwrap();
        let member_name = file.name().unwrap().to_string();
        let mut bytes = Vec::new();
        std::io::Read::read_to_end(&mut file, &mut bytes).unwrap();
        if member_name == name {
            bytes = edit(std::str::from_utf8(&bytes).unwrap()).into_bytes();
        }
        members.push((member_name, bytes));
    }
    let borrowed: Vec<(&str, &[u8])> = members.iter().map(|(n, b)| (n.as_str(), b.as_slice())).collect();
    zip_archive(&borrowed)
}

proptest! {
    #![proptest_config(Config {
        cases: 3000,
        rng_seed: RngSeed::Fixed(0x5eed_ad5e),
        failure_persistence: None,
        ..Config::default()
    })]

    /// Overwrites up to four bytes of a valid file: the reader returns a map with finite
    /// heights or an error naming the file, and never panics.
    #[test]
    fn corrupted_bytes_never_panic(
        which in 0usize..10,
        edits in proptest::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 1..5),
    ) {
        let fixtures = fixtures();
        let (name, mut bytes, _) = fixtures[which % fixtures.len()].clone();
        for (index, value) in edits {
            let at = index.index(bytes.len());
            bytes[at] = value;
        }
        match read_topography_from_bytes(&bytes, name, &options()) {
            Ok(map) => {
                prop_assert_eq!(map.heights.len(), map.nx * map.ny);
                prop_assert!(map.heights.iter().all(|h| h.is_finite()));
                prop_assert!(map.dx > 0.0 && map.dy > 0.0);
            }
            Err(err) => prop_assert!(err.to_string().starts_with(name), "{}", err),
        }
    }
}
