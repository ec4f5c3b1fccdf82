//! Text headers in Gwyddion's languages, decimal commas, and files whose units are missing
//! (an empty-unit .gwy): read with the caller's option or refused naming it.

use crate::common;

use adhesim_topography::{read_topography_from_bytes, ReadOptions, TopographyError};
use common::*;

fn read(name: &str, text: &str, options: &ReadOptions) -> Result<adhesim_topography::Topography, TopographyError> {
    read_topography_from_bytes(text.as_bytes(), name, options)
}

/// Gwyddion translates its export labels; the French and the Japanese ones (with the
/// full-width colon Japanese uses) give the same map as the English labels.
#[test]
fn gwyddion_labels_in_other_languages() {
    let english = "# Channel: Z\n# Width: 3 µm\n# Height: 1 µm\n# Value units: nm\n1 2 3\n4 5 6\n";
    let french = "# Canal: Z\n# Largeur: 3 µm\n# Hauteur: 1 µm\n# Unités: nm\n1 2 3\n4 5 6\n";
    let japanese = "# チャネル：Z\n# 幅：3 µm\n# 高さ：1 µm\n# 値の単位：nm\n1 2 3\n4 5 6\n";
    let reference = read("en.txt", english, &ReadOptions::default()).unwrap();
    assert_close(&[reference.dx, reference.dy], &[1e-6, 0.5e-6], 1e-20, "spacing");
    for (name, text) in [("fr.txt", french), ("ja.txt", japanese)] {
        let map = read(name, text, &ReadOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(
            (map.nx, map.ny, map.dx, map.dy, &map.heights, map.channel.as_str()),
            (3, 2, reference.dx, reference.dy, &reference.heights, "Z"),
            "{name}"
        );
    }
}

/// The header without `#` of Gwyddion's other text export: `h` rows of `w` values (which may
/// wrap), one pixel size for x and y, heights times the conversion factor in its unit.
#[test]
fn pixel_size_and_height_conversion_factor_header() {
    let text = "h=2 w=3\npixel size=2.5e-007 m\ndata unit=rad\nheight conversion factor (-> nm)=2\n\
                1 2\n3 4 5 6\n";
    let map = read("scan.txt", text, &ReadOptions::default()).unwrap();
    assert_eq!((map.nx, map.ny), (3, 2));
    assert_close(&[map.dx, map.dy], &[2.5e-7, 2.5e-7], 1e-22, "spacing");
    // value × factor × 1e-9: one rounding of each product, 1e-23 for heights near 1e-8
    assert_close(&map.heights, &[2e-9, 4e-9, 6e-9, 8e-9, 10e-9, 12e-9], 1e-23, "heights");
    let short = text.replace("5 6", "5");
    let error = read("scan.txt", &short, &ReadOptions::default())
        .unwrap_err()
        .to_string();
    assert!(error.contains("5 values for w × h = 3 × 2"), "{error}");
    // a line of text that is neither a header label nor a number is an error, not skipped
    let error = read("scan.txt", "hello world\n1 2\n", &ReadOptions::default())
        .unwrap_err()
        .to_string();
    assert!(error.contains("\"hello\" is not a number"), "{error}");
}

/// A decimal comma is refused with the line and the value, whether the columns are separated
/// by spaces, tabs or semicolons; commas alone (CSV) and commas after a value are separators.
#[test]
fn decimal_commas_are_refused_not_doubled() {
    let options = ReadOptions {
        spacing: Some((1.0, 1.0)),
        height_unit: Some("m".into()),
        ..Default::default()
    };
    for text in ["1,5 2,5\n3,5 4,5\n", "1,5\t2,5\n3,5\t4,5\n", "1,5;2,5\n3,5;4,5\n"] {
        let error = read("comma.txt", text, &options).unwrap_err().to_string();
        assert!(
            error.contains("line 1") && error.contains("\"1,5\"") && error.contains("decimal comma"),
            "{text:?}: {error}"
        );
    }
    for text in ["1,5\n3,4\n", "1, 5\n3, 4\n"] {
        let map = read("plain.csv", text, &options).unwrap();
        assert_eq!(
            (map.nx, map.ny, map.heights.clone()),
            (2, 2, vec![1.0, 5.0, 3.0, 4.0]),
            "{text:?}"
        );
    }
}

/// Gwyddion writes empty SI units when the file it imported recorded none: the lateral unit
/// comes from `lateral_unit` (or the spacing from `spacing`), the height unit from
/// `height_unit`, and without them the error names the option.
#[test]
fn gwy_with_empty_units_needs_the_callers_units() {
    let data = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
    let bytes = gwy_file(&[("/0/data", GwyValue::Object(gwy_field(3, 2, 6.0, 2.0, "", "", &data)))]);
    let read = |options: &ReadOptions| read_topography_from_bytes(&bytes, "empty.gwy", options);
    let error = read(&ReadOptions::default()).unwrap_err();
    assert!(
        matches!(
            error,
            TopographyError::MissingOption {
                option: "lateral_unit",
                ..
            }
        ),
        "{error}"
    );
    let lateral = ReadOptions {
        lateral_unit: Some("um".into()),
        ..Default::default()
    };
    let error = read(&lateral).unwrap_err();
    assert!(
        matches!(
            error,
            TopographyError::MissingOption {
                option: "height_unit",
                ..
            }
        ),
        "{error}"
    );
    let map = read(&ReadOptions {
        height_unit: Some("nm".into()),
        ..lateral.clone()
    })
    .unwrap();
    assert_close(&[map.dx, map.dy], &[2e-6, 1e-6], 1e-20, "spacing from xreal in um");
    assert_close(&map.heights[..2], &[1e-9, 2e-9], 1e-24, "heights in nm");
    let map = read(&ReadOptions {
        spacing: Some((3e-9, 4e-9)),
        height_unit: Some("m".into()),
        ..Default::default()
    })
    .unwrap();
    assert_eq!((map.dx, map.dy), (3e-9, 4e-9));
    // a file that records its units ignores the options
    let recorded = gwy_file(&[("/0/data", GwyValue::Object(gwy_field(3, 2, 6.0, 2.0, "m", "m", &data)))]);
    let map = read_topography_from_bytes(&recorded, "units.gwy", &lateral).unwrap();
    assert_eq!((map.dx, map.heights[0]), (2.0, 1.0));
}
