//! Writers of test files, byte by byte from the format descriptions cited in each function.
#![allow(dead_code)]

use std::io::Write;

/// A non-symmetric test map in metres: `z = ((ix + 10 iy) − 7) nm + 0.3 nm · sin(ix·iy)`, so a
/// transposed, flipped or shifted read is caught.
pub fn sample_heights(nx: usize, ny: usize) -> Vec<f64> {
    let mut out = Vec::with_capacity(nx * ny);
    for iy in 0..ny {
        for ix in 0..nx {
            let (x, y) = (ix as f64, iy as f64);
            out.push(((x + 10.0 * y) - 7.0 + 0.3 * (x * y).sin()) * 1e-9);
        }
    }
    out
}

pub fn zip_archive(members: &[(&str, &[u8])]) -> Vec<u8> {
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let options = zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    for (name, bytes) in members {
        zip.start_file(*name, options).unwrap();
        zip.write_all(bytes).unwrap();
    }
    zip.finish().unwrap().into_inner()
}

/// An ISO 25178-72 x3p archive: `main.xml` (schema ISO5436_2: Record1 with FeatureType SUR and
/// the axes CX, CY incremental, CZ absolute with the data type; Record3 with MatrixDimension
/// and DataLink), `bindata/data.bin` (x fastest, little-endian) and, with `valid`, the
/// bit-per-point `bindata/valid.bin` (least significant bit first, 1 = valid).
#[allow(clippy::too_many_arguments)]
pub fn x3p_bytes(
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    data_type: char,
    raw: &[f64],
    z_increment: f64,
    z_offset: f64,
    valid: Option<&[bool]>,
) -> Vec<u8> {
    let mut data = Vec::new();
    for &r in raw {
        match data_type {
            'I' => data.extend_from_slice(&(r as i16).to_le_bytes()),
            'L' => data.extend_from_slice(&(r as i32).to_le_bytes()),
            'F' => data.extend_from_slice(&(r as f32).to_le_bytes()),
            'D' => data.extend_from_slice(&r.to_le_bytes()),
            other => panic!("data type {other}"),
        }
    }
    let valid_link = if valid.is_some() {
        "<ValidPointsLink>bindata/valid.bin</ValidPointsLink>"
    } else {
        ""
    };
    let xml = format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<p:ISO5436_2 xmlns:p="http://www.opengps.eu/2008/ISO5436_2">
  <Record1>
    <Revision>ISO5436 - 2000</Revision>
    <FeatureType>SUR</FeatureType>
    <Axes>
      <CX><AxisType>I</AxisType><DataType>D</DataType><Increment>{dx:e}</Increment><Offset>1e-6</Offset></CX>
      <CY><AxisType>I</AxisType><DataType>D</DataType><Increment>{dy:e}</Increment><Offset>0</Offset></CY>
      <CZ><AxisType>A</AxisType><DataType>{data_type}</DataType><Increment>{z_increment:e}</Increment><Offset>{z_offset:e}</Offset></CZ>
    </Axes>
  </Record1>
  <Record2><Date>2026-01-01T00:00:00</Date><Creator>adhesim tests</Creator>
    <Instrument><Manufacturer>none</Manufacturer><Model>test</Model><Serial>0</Serial><Version>1</Version></Instrument>
    <CalibrationDate>2026-01-01T00:00:00</CalibrationDate>
    <ProbingSystem><Type>NonContacting</Type><Identification>x</Identification></ProbingSystem>
    <Comment>written byte by byte</Comment></Record2>
  <Record3>
    <MatrixDimension><SizeX>{nx}</SizeX><SizeY>{ny}</SizeY><SizeZ>1</SizeZ></MatrixDimension>
    <DataLink><PointDataLink>bindata/data.bin</PointDataLink><MD5ChecksumPointData>0</MD5ChecksumPointData>{valid_link}</DataLink>
  </Record3>
  <Record4><ChecksumFile>md5checksum.hex</ChecksumFile></Record4>
</p:ISO5436_2>
"#
    );
    let mut members: Vec<(&str, Vec<u8>)> = vec![("main.xml", xml.into_bytes()), ("bindata/data.bin", data)];
    if let Some(valid) = valid {
        let mut bits = vec![0u8; valid.len().div_ceil(8)];
        for (i, &v) in valid.iter().enumerate() {
            bits[i / 8] |= u8::from(v) << (i % 8);
        }
        members.push(("bindata/valid.bin", bits));
    }
    let borrowed: Vec<(&str, &[u8])> = members.iter().map(|(n, b)| (*n, b.as_slice())).collect();
    zip_archive(&borrowed)
}

/// A Gwyddion GWYP serialised component (user guide, "GWY File Format"): name, NUL, type, value.
pub enum GwyValue {
    Int(i32),
    Double(f64),
    Text(String),
    Object(Vec<u8>),
    Doubles(Vec<f64>),
}

pub fn gwy_object(type_name: &str, components: &[(&str, GwyValue)]) -> Vec<u8> {
    let mut body = Vec::new();
    for (name, value) in components {
        body.extend_from_slice(name.as_bytes());
        body.push(0);
        match value {
            GwyValue::Int(v) => {
                body.push(b'i');
                body.extend_from_slice(&v.to_le_bytes());
            }
            GwyValue::Double(v) => {
                body.push(b'd');
                body.extend_from_slice(&v.to_le_bytes());
            }
            GwyValue::Text(t) => {
                body.push(b's');
                body.extend_from_slice(t.as_bytes());
                body.push(0);
            }
            GwyValue::Object(o) => {
                body.push(b'o');
                body.extend_from_slice(o);
            }
            GwyValue::Doubles(v) => {
                body.push(b'D');
                body.extend_from_slice(&(v.len() as u32).to_le_bytes());
                v.iter().for_each(|x| body.extend_from_slice(&x.to_le_bytes()));
            }
        }
    }
    let mut out = type_name.as_bytes().to_vec();
    out.push(0);
    out.extend_from_slice(&(body.len() as u32).to_le_bytes());
    out.extend_from_slice(&body);
    out
}

pub fn gwy_unit(unit: &str) -> Vec<u8> {
    gwy_object("GwySIUnit", &[("unitstr", GwyValue::Text(unit.into()))])
}

#[allow(clippy::too_many_arguments)]
pub fn gwy_field(nx: usize, ny: usize, xreal: f64, yreal: f64, xy_unit: &str, z_unit: &str, data: &[f64]) -> Vec<u8> {
    gwy_object(
        "GwyDataField",
        &[
            ("xres", GwyValue::Int(nx as i32)),
            ("yres", GwyValue::Int(ny as i32)),
            ("xreal", GwyValue::Double(xreal)),
            ("yreal", GwyValue::Double(yreal)),
            ("xoff", GwyValue::Double(0.0)),
            ("yoff", GwyValue::Double(0.0)),
            ("si_unit_xy", GwyValue::Object(gwy_unit(xy_unit))),
            ("si_unit_z", GwyValue::Object(gwy_unit(z_unit))),
            ("data", GwyValue::Doubles(data.to_vec())),
        ],
    )
}

pub fn gwy_file(container_components: &[(&str, GwyValue)]) -> Vec<u8> {
    let mut out = b"GWYP".to_vec();
    out.extend_from_slice(&gwy_object("GwyContainer", container_components));
    out
}

/// Parameters of a Digital Surf header (the 512-byte layout documented in `src/sur.rs`).
pub struct SurHeader<'a> {
    pub nx: usize,
    pub ny: usize,
    pub bits: i16,
    pub dx: f32,
    pub dy: f32,
    pub spacing_z: f32,
    pub offset_z: f32,
    pub lateral_unit: &'a [u8],
    pub z_unit: &'a [u8],
    pub zmin: i32,
    pub non_measured: bool,
    pub compressed: bool,
    pub comment: &'a [u8],
}

pub fn sur_bytes(h: &SurHeader<'_>, raw: &[i32]) -> Vec<u8> {
    let mut data = Vec::new();
    for &r in raw {
        if h.bits == 16 {
            data.extend_from_slice(&(r as i16).to_le_bytes());
        } else {
            data.extend_from_slice(&r.to_le_bytes());
        }
    }
    let mut header = vec![0u8; 512];
    let put =
        |header: &mut Vec<u8>, offset: usize, bytes: &[u8]| header[offset..offset + bytes.len()].copy_from_slice(bytes);
    put(
        &mut header,
        0,
        if h.compressed { b"DSCOMPRESSED" } else { b"DIGITAL SURF" },
    );
    put(&mut header, 14, &1i16.to_le_bytes());
    put(&mut header, 16, &1i16.to_le_bytes());
    put(&mut header, 18, &2i16.to_le_bytes());
    put(&mut header, 20, b"test object");
    put(&mut header, 86, &i16::from(h.non_measured).to_le_bytes());
    put(&mut header, 98, &h.bits.to_le_bytes());
    put(&mut header, 100, &h.zmin.to_le_bytes());
    put(&mut header, 104, &i32::MAX.to_le_bytes());
    put(&mut header, 108, &(h.nx as i32).to_le_bytes());
    put(&mut header, 112, &(h.ny as i32).to_le_bytes());
    put(&mut header, 116, &((h.nx * h.ny) as i32).to_le_bytes());
    put(&mut header, 120, &h.dx.to_le_bytes());
    put(&mut header, 124, &h.dy.to_le_bytes());
    put(&mut header, 128, &h.spacing_z.to_le_bytes());
    put(&mut header, 132, b"X");
    put(&mut header, 148, b"Y");
    put(&mut header, 164, b"Height");
    put(&mut header, 180, h.lateral_unit);
    put(&mut header, 196, h.lateral_unit);
    put(&mut header, 212, h.z_unit);
    put(&mut header, 334, &(h.comment.len() as i16).to_le_bytes());
    put(&mut header, 474, &h.offset_z.to_le_bytes());
    let body = if h.compressed {
        let mut encoder = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
        encoder.write_all(&data).unwrap();
        let zipped = encoder.finish().unwrap();
        let mut body = Vec::new();
        body.extend_from_slice(&1u32.to_le_bytes());
        body.extend_from_slice(&(data.len() as u32).to_le_bytes());
        body.extend_from_slice(&(zipped.len() as u32).to_le_bytes());
        body.extend_from_slice(&zipped);
        put(&mut header, 324, &(body.len() as u32).to_le_bytes());
        body
    } else {
        data
    };
    let mut out = header;
    out.extend_from_slice(h.comment);
    out.extend_from_slice(&body);
    out
}

/// An `.npy` file (NEP 1, version 1.0) with the given dtype text, order, shape and raw bytes.
pub fn npy_raw(descr: &str, fortran: bool, shape: &str, data: &[u8]) -> Vec<u8> {
    let order = if fortran { "True" } else { "False" };
    let mut header = format!("{{'descr': '{descr}', 'fortran_order': {order}, 'shape': {shape}, }}");
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    out.extend_from_slice(data);
    out
}

pub fn assert_close(got: &[f64], want: &[f64], tolerance: f64, what: &str) {
    assert_eq!(got.len(), want.len(), "{what}: lengths");
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!(
            (g - w).abs() <= tolerance,
            "{what}[{i}]: got {g:e}, want {w:e} (tolerance {tolerance:e})"
        );
    }
}
