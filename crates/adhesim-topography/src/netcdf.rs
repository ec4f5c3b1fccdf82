//! Contact fields as a NetCDF classic file (CDF-1, or CDF-2 "64-bit offset" when the data pass
//! 2 GiB), written from the NetCDF Classic Format Specification (Unidata), for xarray users.
//!
//! Layout (all big-endian): `CDF` and the version byte; `numrecs` (0, no record variables);
//! the dimension list (`NC_DIMENSION` = 10, count, then name and length of each); the global
//! attribute list (`NC_ATTRIBUTE` = 12, count, attributes); the variable list (`NC_VARIABLE` =
//! 11, count, then per variable: name, dimension ids, attributes, type, `vsize`, `begin`);
//! then each variable's data at its `begin`, padded to 4 bytes. A name is a 32-bit length and
//! its bytes padded with zeros to 4; an absent list is two zero words. Types used: `NC_BYTE`
//! (1) for masks, `NC_CHAR` (2) for text attributes, `NC_DOUBLE` (6) for fields.

use std::io::Write;
use std::path::Path;

use crate::write_npz::{ArrayData, NamedArray};
use crate::TopographyError;

const NC_DIMENSION: u32 = 10;
const NC_VARIABLE: u32 = 11;
const NC_ATTRIBUTE: u32 = 12;
const NC_BYTE: u32 = 1;
const NC_CHAR: u32 = 2;
const NC_DOUBLE: u32 = 6;

/// The grid of the fields: dimensions `y` (ny) and `x` (nx) with coordinate variables of the
/// point positions `x = ix·dx`, `y = iy·dy` in metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NetcdfGrid {
    pub nx: usize,
    pub ny: usize,
    pub dx: f64,
    pub dy: f64,
}

struct Variable<'a> {
    name: String,
    dims: Vec<usize>,
    data: ArrayData<'a>,
    attributes: Vec<(String, String)>,
}

/// Writes `arrays` to `path` as a NetCDF classic file. Arrays of shape `[ny, nx]` get the
/// dimensions `(y, x)`; other shapes get dimensions named `NAME_0`, `NAME_1`, …; each array's
/// unit becomes its `units` attribute. `global_attributes` are written as text attributes.
pub fn write_netcdf(
    path: impl AsRef<Path>,
    grid: &NetcdfGrid,
    arrays: &[NamedArray<'_>],
    global_attributes: &[(&str, &str)],
) -> Result<(), TopographyError> {
    let path = path.as_ref();
    if grid.nx == 0 || grid.ny == 0 || !(grid.dx > 0.0 && grid.dy > 0.0) || !grid.dx.is_finite() || !grid.dy.is_finite()
    {
        return Err(TopographyError::InvalidArgument {
            name: "NetCDF grid",
            value: format!("{grid:?}"),
            why: "needs positive sizes and finite positive spacings".into(),
        });
    }
    let x: Vec<f64> = (0..grid.nx).map(|i| i as f64 * grid.dx).collect();
    let y: Vec<f64> = (0..grid.ny).map(|i| i as f64 * grid.dy).collect();
    let mut dimensions: Vec<(String, usize)> = vec![("y".into(), grid.ny), ("x".into(), grid.nx)];
    let metres = vec![("units".to_string(), "m".to_string())];
    let mut variables = vec![
        Variable {
            name: "x".into(),
            dims: vec![1],
            data: ArrayData::F64(&x),
            attributes: metres.clone(),
        },
        Variable {
            name: "y".into(),
            dims: vec![0],
            data: ArrayData::F64(&y),
            attributes: metres,
        },
    ];
    for (index, array) in arrays.iter().enumerate() {
        array.validate(path)?;
        if ["x", "y"].contains(&array.name) || arrays[..index].iter().any(|a| a.name == array.name) {
            return Err(TopographyError::InvalidArgument {
                name: "array",
                value: array.name.to_string(),
                why: format!("named twice (x and y are the coordinates) for {}", path.display()),
            });
        }
        let dims = if array.shape == [grid.ny, grid.nx] {
            vec![0, 1]
        } else {
            array
                .shape
                .iter()
                .enumerate()
                .map(|(axis, &len)| {
                    dimensions.push((format!("{}_{axis}", array.name), len));
                    dimensions.len() - 1
                })
                .collect()
        };
        let mut attributes = Vec::new();
        if let Some(unit) = array.unit {
            attributes.push(("units".to_string(), unit.to_string()));
        }
        variables.push(Variable {
            name: array.name.to_string(),
            dims,
            data: array.data,
            attributes,
        });
    }
    let bytes = encode(&dimensions, &variables, global_attributes);
    let io_error = |source| TopographyError::Io {
        path: path.to_path_buf(),
        action: "writing",
        source,
    };
    let mut file = std::io::BufWriter::new(std::fs::File::create(path).map_err(io_error)?);
    file.write_all(&bytes).map_err(io_error)?;
    file.flush().map_err(io_error)
}

fn padded_len(len: usize) -> usize {
    len.div_ceil(4) * 4
}

fn put_u32(out: &mut Vec<u8>, value: u32) {
    out.extend_from_slice(&value.to_be_bytes());
}

fn put_name(out: &mut Vec<u8>, name: &str) {
    put_u32(out, name.len() as u32);
    out.extend_from_slice(name.as_bytes());
    out.resize(out.len() + padded_len(name.len()) - name.len(), 0);
}

fn put_attributes<'s>(out: &mut Vec<u8>, attributes: impl ExactSizeIterator<Item = (&'s str, &'s str)>) {
    if attributes.len() == 0 {
        put_u32(out, 0);
        put_u32(out, 0);
        return;
    }
    put_u32(out, NC_ATTRIBUTE);
    put_u32(out, attributes.len() as u32);
    for (name, text) in attributes {
        put_name(out, name);
        put_u32(out, NC_CHAR);
        put_name(out, text);
    }
}

fn data_bytes(data: &ArrayData<'_>) -> usize {
    match data {
        ArrayData::F64(v) => v.len() * 8,
        ArrayData::Bool(v) => v.len(),
    }
}

/// The whole file: the header (sized first with placeholder offsets, as its size does not
/// depend on their values), then the data.
fn encode(dimensions: &[(String, usize)], variables: &[Variable<'_>], globals: &[(&str, &str)]) -> Vec<u8> {
    let data_total: usize = variables.iter().map(|v| padded_len(data_bytes(&v.data))).sum();
    let wide = data_total + 4096 > i32::MAX as usize;
    let header = |begins: &[u64]| -> Vec<u8> {
        let mut out = Vec::new();
        out.extend_from_slice(b"CDF");
        out.push(if wide { 2 } else { 1 });
        put_u32(&mut out, 0);
        put_u32(&mut out, NC_DIMENSION);
        put_u32(&mut out, dimensions.len() as u32);
        for (name, len) in dimensions {
            put_name(&mut out, name);
            put_u32(&mut out, *len as u32);
        }
        put_attributes(&mut out, globals.iter().map(|(k, v)| (*k, *v)));
        put_u32(&mut out, NC_VARIABLE);
        put_u32(&mut out, variables.len() as u32);
        for (variable, &begin) in variables.iter().zip(begins) {
            put_name(&mut out, &variable.name);
            put_u32(&mut out, variable.dims.len() as u32);
            for &dim in &variable.dims {
                put_u32(&mut out, dim as u32);
            }
            put_attributes(
                &mut out,
                variable.attributes.iter().map(|(k, v)| (k.as_str(), v.as_str())),
            );
            put_u32(
                &mut out,
                if matches!(variable.data, ArrayData::F64(_)) {
                    NC_DOUBLE
                } else {
                    NC_BYTE
                },
            );
            let vsize = padded_len(data_bytes(&variable.data));
            put_u32(&mut out, u32::try_from(vsize).unwrap_or(u32::MAX));
            if wide {
                out.extend_from_slice(&begin.to_be_bytes());
            } else {
                out.extend_from_slice(&(begin as u32).to_be_bytes());
            }
        }
        out
    };
    let header_len = header(&vec![0; variables.len()]).len();
    let mut begins = Vec::with_capacity(variables.len());
    let mut offset = header_len as u64;
    for variable in variables {
        begins.push(offset);
        offset += padded_len(data_bytes(&variable.data)) as u64;
    }
    let mut out = header(&begins);
    out.reserve(data_total);
    for variable in variables {
        match variable.data {
            ArrayData::F64(values) => values.iter().for_each(|v| out.extend_from_slice(&v.to_be_bytes())),
            ArrayData::Bool(values) => out.extend(values.iter().map(|&b| u8::from(b))),
        }
        out.resize(padded_len(out.len()), 0);
    }
    out
}
