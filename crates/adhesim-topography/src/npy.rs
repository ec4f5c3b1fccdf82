//! numpy's `.npy` format (NEP 1, versions 1.0, 2.0 and 3.0) and `.npz` archives of them.
//!
//! An `.npy` file is the magic `\x93NUMPY`, a version, a little-endian header length (u16 in
//! 1.0, u32 in 2.0/3.0), a Python dict literal `{'descr': '<f8', 'fortran_order': False,
//! 'shape': (ny, nx), }` and the raw array. A 2-D array of shape `(rows, columns)` is read as
//! `ny = rows`, `nx = columns`.

use std::collections::BTreeMap;
use std::io::Read;

use crate::bytes::{decode_values, point_count, Endian, Reader, Scalar, MAX_POINTS};
use crate::error::{ParseError, ParseResult};
use crate::{height_unit_option, spacing_option, RawMap, ReadOptions};

pub(crate) const MAGIC: &[u8] = b"\x93NUMPY";

/// A decoded `.npy` array: its shape and its values in C (row-major) order.
#[derive(Debug)]
pub(crate) struct NpyArray {
    pub shape: Vec<usize>,
    pub values: Vec<f64>,
    pub descr: String,
}

/// Parses an `.npy` byte stream of a numeric or boolean dtype.
pub(crate) fn parse_npy(bytes: &[u8]) -> ParseResult<NpyArray> {
    let mut reader = Reader::new(bytes);
    if reader.take(MAGIC.len(), "magic")? != MAGIC {
        return Err(ParseError::malformed("no \\x93NUMPY magic"));
    }
    let major = reader.u8("version")?;
    let _minor = reader.u8("version")?;
    let header_len = match major {
        1 => reader.u16_le("header length")? as usize,
        2 | 3 => reader.u32_le("header length")? as usize,
        v => return Err(ParseError::unsupported(format!("npy version {v}"))),
    };
    let header = reader.take(header_len, "header")?;
    let header = std::str::from_utf8(header).map_err(|_| ParseError::malformed("header is not text"))?;
    let descr = dict_value(header, "descr")?;
    let descr = descr.trim_matches(|c| c == '\'' || c == '"').to_string();
    let fortran = match dict_value(header, "fortran_order")?.as_str() {
        "True" => true,
        "False" => false,
        other => return Err(ParseError::malformed(format!("fortran_order is {other:?}"))),
    };
    let shape = parse_shape(&dict_value(header, "shape")?)?;
    let (scalar, endian) = parse_descr(&descr)?;
    let count = shape
        .iter()
        .try_fold(1usize, |acc, &n| acc.checked_mul(n).filter(|&c| c <= MAX_POINTS));
    let count = count.ok_or_else(|| ParseError::malformed(format!("shape {shape:?} exceeds {MAX_POINTS} points")))?;
    let data = reader.take(reader.remaining(), "data")?;
    let mut values = decode_values(data, count, scalar, endian)?;
    if fortran && shape.len() > 1 {
        values = fortran_to_c(&values, &shape);
    }
    Ok(NpyArray { shape, values, descr })
}

/// Reorders a column-major array into row-major order.
fn fortran_to_c(values: &[f64], shape: &[usize]) -> Vec<f64> {
    let mut out = vec![0.0; values.len()];
    let dims = shape.len();
    let mut index = vec![0usize; dims];
    for value in values {
        // `index` runs in Fortran order: the first axis fastest.
        let mut c_offset = 0;
        for (axis, &i) in index.iter().enumerate() {
            c_offset = c_offset * shape[axis] + i;
        }
        out[c_offset] = *value;
        for axis in 0..dims {
            index[axis] += 1;
            if index[axis] < shape[axis] {
                break;
            }
            index[axis] = 0;
        }
    }
    out
}

/// The text of `key`'s value in the header dict, up to the next top-level comma or brace.
fn dict_value(header: &str, key: &str) -> ParseResult<String> {
    let missing = || ParseError::malformed(format!("header has no {key:?} entry: {header:?}"));
    let start = header
        .find(&format!("'{key}'"))
        .or_else(|| header.find(&format!("\"{key}\"")))
        .ok_or_else(missing)?;
    let after = &header[start + key.len() + 2..];
    let after = after.trim_start().strip_prefix(':').ok_or_else(missing)?;
    let mut depth = 0i32;
    let mut end = after.len();
    for (i, c) in after.char_indices() {
        match c {
            '(' => depth += 1,
            ')' => depth -= 1,
            ',' | '}' if depth == 0 => {
                end = i;
                break;
            }
            _ => {}
        }
    }
    Ok(after[..end].trim().to_string())
}

fn parse_shape(text: &str) -> ParseResult<Vec<usize>> {
    let inner = text
        .strip_prefix('(')
        .and_then(|t| t.strip_suffix(')'))
        .ok_or_else(|| ParseError::malformed(format!("shape {text:?} is not a tuple")))?;
    inner
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| {
            s.trim_end_matches('L')
                .parse::<usize>()
                .map_err(|_| ParseError::malformed(format!("shape {text:?}: {s:?} is not a size")))
        })
        .collect()
}

fn parse_descr(descr: &str) -> ParseResult<(Scalar, Endian)> {
    let unsupported = || {
        ParseError::unsupported(format!(
            "dtype {descr:?} (supported: bool, int8-64, uint8-64, float32, float64)"
        ))
    };
    let mut chars = descr.chars();
    let order = chars.next().ok_or_else(unsupported)?;
    let endian = match order {
        '<' | '|' => Endian::Little,
        '>' => Endian::Big,
        '=' if cfg!(target_endian = "big") => Endian::Big,
        '=' => Endian::Little,
        _ => return Err(unsupported()),
    };
    let scalar = match chars.as_str() {
        "b1" => Scalar::Bool,
        "i1" => Scalar::I8,
        "u1" => Scalar::U8,
        "i2" => Scalar::I16,
        "u2" => Scalar::U16,
        "i4" => Scalar::I32,
        "u4" => Scalar::U32,
        "i8" => Scalar::I64,
        "u8" => Scalar::U64,
        "f4" => Scalar::F32,
        "f8" => Scalar::F64,
        _ => return Err(unsupported()),
    };
    Ok((scalar, endian))
}

/// A 2-D `.npy` height map; spacing and height unit come from `options`.
pub(crate) fn read_npy_map(bytes: &[u8], channel: &str, options: &ReadOptions) -> ParseResult<RawMap> {
    let array = parse_npy(bytes)?;
    let (ny, nx) = match array.shape[..] {
        [ny, nx] => (ny, nx),
        _ => {
            return Err(ParseError::unsupported(format!(
                "array of shape {:?}; a height map is 2-D",
                array.shape
            )))
        }
    };
    point_count(nx as i64, ny as i64)?;
    let (dx, dy) = spacing_option(options)?;
    let (factor, unit) = height_unit_option(options)?;
    let mut metadata = BTreeMap::new();
    metadata.insert("dtype".to_string(), array.descr.clone());
    Ok(RawMap {
        nx,
        ny,
        dx,
        dy,
        x_offset: 0.0,
        y_offset: 0.0,
        heights: array.values.into_iter().map(|v| v * factor).collect(),
        valid: None,
        channel: channel.to_string(),
        height_unit: unit,
        lateral_unit: "m".to_string(),
        metadata,
    })
}

/// The members of an npz archive as `(name without .npy, bytes)`, in archive order.
pub(crate) fn npz_members(bytes: &[u8]) -> ParseResult<Vec<(String, Vec<u8>)>> {
    let mut archive = zip::ZipArchive::new(std::io::Cursor::new(bytes))
        .map_err(|e| ParseError::malformed(format!("not a zip archive: {e}")))?;
    let mut members = Vec::new();
    for index in 0..archive.len() {
        let mut file = archive
            .by_index(index)
            .map_err(|e| ParseError::malformed(format!("zip member {index}: {e}")))?;
        let name = file
            .name()
            .map_err(|e| ParseError::malformed(format!("zip member {index} name: {e}")))?
            .to_string();
        let data = read_zip_member(&mut file, &name, MAX_MEMBER_BYTES)?;
        members.push((name.trim_end_matches(".npy").to_string(), data));
    }
    Ok(members)
}

/// The most bytes an npz member may hold: [`MAX_POINTS`] doubles and a header.
pub(crate) const MAX_MEMBER_BYTES: u64 = (MAX_POINTS as u64) * 8 + 65536;

/// Reads one zip member whose declared size is at most `limit`, and no more than that size
/// (a zip bomb stops there, before inflating).
pub(crate) fn read_zip_member(
    file: &mut zip::read::ZipFile<'_, impl Read>,
    name: &str,
    limit: u64,
) -> ParseResult<Vec<u8>> {
    let declared = file.size();
    if declared > limit {
        return Err(ParseError::malformed(format!(
            "member {name} declares {declared} bytes, more than the {limit} it may hold"
        )));
    }
    let mut data = Vec::new();
    file.take(declared + 1)
        .read_to_end(&mut data)
        .map_err(|e| ParseError::malformed(format!("member {name}: {e}")))?;
    if data.len() as u64 != declared {
        return Err(ParseError::malformed(format!(
            "member {name}: {} bytes where {declared} were declared",
            data.len()
        )));
    }
    Ok(data)
}

/// The height map of an npz archive: the member named by `options.channel`, else the only
/// member, else the member `heights`, else the first member.
pub(crate) fn read_npz_map(bytes: &[u8], options: &ReadOptions) -> ParseResult<RawMap> {
    let members = npz_members(bytes)?;
    let names: Vec<String> = members.iter().map(|(n, _)| n.clone()).collect();
    let chosen = match &options.channel {
        Some(requested) => members
            .iter()
            .find(|(n, _)| n == requested)
            .ok_or_else(|| ParseError::ChannelNotFound {
                requested: requested.clone(),
                available: names.clone(),
            })?,
        None => members
            .iter()
            .find(|(n, _)| n == "heights")
            .or(members.first())
            .ok_or_else(|| ParseError::malformed("the archive has no member"))?,
    };
    read_npy_map(&chosen.1, &chosen.0, options).map_err(|e| match e {
        ParseError::Malformed(what) => ParseError::Malformed(format!("member {}: {what}", chosen.0)),
        other => other,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fortran_order_is_transposed_back() {
        // shape (2, 3): C order 0 1 2 / 3 4 5; Fortran order stores columns first.
        let fortran = [0.0, 3.0, 1.0, 4.0, 2.0, 5.0];
        assert_eq!(fortran_to_c(&fortran, &[2, 3]), vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0]);
    }

    #[test]
    fn header_dict_is_parsed() {
        let header = "{'descr': '>f4', 'fortran_order': False, 'shape': (3, 4), }";
        assert_eq!(dict_value(header, "descr").unwrap(), "'>f4'");
        assert_eq!(parse_shape(&dict_value(header, "shape").unwrap()).unwrap(), vec![3, 4]);
        assert_eq!(parse_shape("(5,)").unwrap(), vec![5]);
    }
}
