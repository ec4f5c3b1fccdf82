//! Digital Surf `.sur` surfaces (MountainsMap).
//!
//! A 512-byte little-endian header (layout as read by Gwyddion's `surffile` and surfalize):
//! magic `DIGITAL SURF` (or `DSCOMPRESSED`, zlib-compressed data) at 0, the number of objects
//! at 14, the studiable type at 18, the non-measured-points flag at 86, bits per point (16 or
//! 32) at 98, the smallest valid value `zmin` at 100, points per line at 108, lines at 112,
//! the spacings x, y, z (f32) at 120, 124, 128, their step units (16 characters each) at 180,
//! 196, 212, the size of the compressed data (u32) at 324, the comment and private zone sizes
//! (i16) at 334 and 336, and the offsets x, y, z (f32) at 466, 470, 474. The comment and the
//! private zone follow the header, then the data: line after line, x fastest. A height is
//! `raw·spacing_z + offset_z` in the z step unit; with the non-measured flag set, the value
//! `zmin − 2` marks a point that was not measured.

use std::collections::BTreeMap;
use std::io::Read;

use crate::bytes::{check_data_length, decode_values, point_count, Endian, Reader, Scalar};
use crate::error::{ParseError, ParseResult};
use crate::units::{decode_padded_text, parse_length_unit};
use crate::RawMap;

const HEADER_SIZE: usize = 512;

fn field(header: &[u8], offset: usize, len: usize) -> &[u8] {
    &header[offset..offset + len]
}

fn i16_at(header: &[u8], offset: usize) -> i16 {
    i16::from_le_bytes([header[offset], header[offset + 1]])
}

fn i32_at(header: &[u8], offset: usize) -> i32 {
    let mut raw = [0u8; 4];
    raw.copy_from_slice(field(header, offset, 4));
    i32::from_le_bytes(raw)
}

fn f32_at(header: &[u8], offset: usize) -> f64 {
    let mut raw = [0u8; 4];
    raw.copy_from_slice(field(header, offset, 4));
    f64::from(f32::from_le_bytes(raw))
}

/// Reads the first object of a `.sur` file (a surface).
pub(crate) fn read(bytes: &[u8]) -> ParseResult<RawMap> {
    let mut reader = Reader::new(bytes);
    let header = reader.take(HEADER_SIZE, "512-byte header")?;
    let compressed = match &header[..12] {
        b"DIGITAL SURF" => false,
        b"DSCOMPRESSED" => true,
        _ => return Err(ParseError::malformed("no DIGITAL SURF magic")),
    };
    let studiable = i16_at(header, 18);
    // 2 = surface; Gwyddion writes its surfaces as type 1 (profile) with yres lines.
    if !(studiable == 1 || studiable == 2) {
        return Err(ParseError::unsupported(format!(
            "studiable type {studiable}: only surfaces (2) are read"
        )));
    }
    let scalar = match i16_at(header, 98) {
        16 => Scalar::I16,
        32 => Scalar::I32,
        bits => {
            return Err(ParseError::malformed(format!(
                "{bits} bits per point (16 or 32 allowed)"
            )))
        }
    };
    let (nx, ny) = (i32_at(header, 108), i32_at(header, 112));
    let count = point_count(nx.into(), ny.into())?;
    let comment_len =
        usize::try_from(i16_at(header, 334)).map_err(|_| ParseError::malformed("negative comment size"))?;
    let private_len =
        usize::try_from(i16_at(header, 336)).map_err(|_| ParseError::malformed("negative private zone size"))?;
    let comment = decode_padded_text(reader.take(comment_len, "comment zone")?);
    reader.take(private_len, "private zone")?;
    let rest = reader.take(reader.remaining(), "data")?;
    let raw = if compressed {
        let compressed_size = u32::from_le_bytes([header[324], header[325], header[326], header[327]]);
        let data = inflate_blocks(rest, compressed_size as usize, count * scalar.size())?;
        decode_values(&data, count, scalar, Endian::Little)?
    } else {
        check_data_length(count, scalar, rest.len(), "data")?;
        decode_values(rest, count, scalar, Endian::Little)?
    };
    let text = |offset| decode_padded_text(field(header, offset, 16));
    let (x_unit, y_unit, z_unit) = (text(180), text(196), text(212));
    let (x_factor, y_factor, z_factor) = (
        parse_length_unit(&x_unit)?,
        parse_length_unit(&y_unit)?,
        parse_length_unit(&z_unit)?,
    );
    let (spacing_z, offset_z) = (f32_at(header, 128), f32_at(header, 474));
    let non_measured = (i16_at(header, 86) == 1).then(|| i64::from(i32_at(header, 100)) - 2);
    let valid = non_measured.map(|marker| raw.iter().map(|&r| r != marker as f64).collect());
    let heights = raw.iter().map(|&r| (r * spacing_z + offset_z) * z_factor).collect();
    let mut metadata = BTreeMap::new();
    metadata.insert("object name".to_string(), decode_padded_text(field(header, 20, 30)));
    metadata.insert("operator".to_string(), decode_padded_text(field(header, 50, 30)));
    if !comment.is_empty() {
        metadata.insert("comment".to_string(), comment);
    }
    Ok(RawMap {
        nx: nx as usize,
        ny: ny as usize,
        dx: f32_at(header, 120) * x_factor,
        dy: f32_at(header, 124) * y_factor,
        x_offset: f32_at(header, 466) * x_factor,
        y_offset: f32_at(header, 470) * y_factor,
        heights,
        valid,
        channel: decode_padded_text(field(header, 164, 16)),
        height_unit: z_unit,
        lateral_unit: x_unit,
        metadata,
    })
}

/// The data of a `DSCOMPRESSED` object: a u32 count of streams, `(raw length, zipped length)`
/// u32 pairs, then the zlib streams, whose inflated concatenation is the data.
fn inflate_blocks(bytes: &[u8], declared: usize, expected: usize) -> ParseResult<Vec<u8>> {
    let mut reader = Reader::new(bytes);
    let streams = reader.u32_le("stream count")? as usize;
    if streams == 0 || streams > 1 << 16 {
        return Err(ParseError::malformed(format!("{streams} compressed streams")));
    }
    let mut directory = Vec::new();
    for _ in 0..streams {
        directory.push((
            reader.u32_le("stream raw length")? as usize,
            reader.u32_le("stream zipped length")? as usize,
        ));
    }
    let total_raw: usize = directory.iter().map(|d| d.0).sum();
    if total_raw != expected {
        return Err(ParseError::malformed(format!(
            "compressed streams hold {total_raw} bytes, the grid needs {expected}"
        )));
    }
    let total_zipped = 4 + directory.iter().map(|d| 8 + d.1).sum::<usize>();
    if declared != 0 && declared != total_zipped {
        return Err(ParseError::malformed(format!(
            "compressed data size {declared} in the header, {total_zipped} in the directory"
        )));
    }
    // No reservation from the header: the streams must inflate to it first.
    let mut data = Vec::new();
    for (index, &(raw_len, zipped_len)) in directory.iter().enumerate() {
        let stream = reader.take(zipped_len, "compressed stream")?;
        let before = data.len();
        flate2::read::ZlibDecoder::new(stream)
            .take(raw_len as u64 + 1)
            .read_to_end(&mut data)
            .map_err(|e| ParseError::malformed(format!("compressed stream {index}: {e}")))?;
        if data.len() - before != raw_len {
            return Err(ParseError::malformed(format!(
                "compressed stream {index} inflates to {} bytes, {raw_len} declared",
                data.len() - before
            )));
        }
    }
    Ok(data)
}
