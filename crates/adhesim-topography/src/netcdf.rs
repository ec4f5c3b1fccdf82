//! Contact fields as a NetCDF classic file (CDF-1, or CDF-2 "64-bit offset" when the data pass
//! 2 GiB), written from the NetCDF Classic Format Specification (Unidata), for xarray users.
//!
//! Layout (all big-endian): `CDF` and the version byte; `numrecs` (0, no record variables);
//! the dimension list (`NC_DIMENSION` = 10, count, then name and length of each); the global
//! attribute list (`NC_ATTRIBUTE` = 12, count, attributes); the variable list (`NC_VARIABLE` =
//! 11, count, then per variable: name, dimension ids, attributes, type, `vsize`, `begin`);
//! then each variable's data at its `begin`, padded to 4 bytes. A name is a 32-bit length and
//! its bytes padded with zeros to 4; an absent list is two zero words. Types used: `NC_BYTE`
//! (1) for masks, `NC_CHAR` (2) for text attributes, `NC_INT` (4) for step numbers,
//! `NC_DOUBLE` (6) for fields.

use std::io::Write;
use std::path::Path;

use crate::write_npz::{ArrayData, NamedArray};
use crate::TopographyError;

const NC_DIMENSION: u32 = 10;
const NC_VARIABLE: u32 = 11;
const NC_ATTRIBUTE: u32 = 12;
const NC_BYTE: u32 = 1;
const NC_CHAR: u32 = 2;
const NC_INT: u32 = 4;
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

/// A variable of [`write_netcdf_variables`]: an array, the names of its dimensions (their
/// lengths must be its shape) and its text attributes (the array's unit is added as
/// `units`).
#[derive(Clone, Debug)]
pub struct NcVariable<'a> {
    pub array: NamedArray<'a>,
    pub dims: Vec<&'a str>,
    pub attributes: Vec<(&'a str, String)>,
}

/// Writes `arrays` to `path` as a NetCDF classic file. Arrays of shape `[ny, nx]` get the
/// dimensions `(y, x)`; other shapes get dimensions named `NAME_0`, `NAME_1`, …; each array's
/// unit becomes its `units` attribute. `global_attributes` are written as text attributes.
/// The coordinate variables are `x = j·dx`, `y = i·dy` in metres.
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
    let names: Vec<Vec<String>> = arrays
        .iter()
        .map(|a| (0..a.shape.len()).map(|axis| format!("{}_{axis}", a.name)).collect())
        .collect();
    let mut dimensions: Vec<(&str, usize)> = vec![("y", grid.ny), ("x", grid.nx)];
    let (x_shape, y_shape) = ([grid.nx], [grid.ny]);
    let metres = || vec![("units", "m".to_string())];
    let mut variables = vec![
        NcVariable {
            array: NamedArray::f64("x", &x_shape, &x),
            dims: vec!["x"],
            attributes: metres(),
        },
        NcVariable {
            array: NamedArray::f64("y", &y_shape, &y),
            dims: vec!["y"],
            attributes: metres(),
        },
    ];
    for (array, names) in arrays.iter().zip(&names) {
        let dims = if array.shape == [grid.ny, grid.nx] {
            vec!["y", "x"]
        } else {
            dimensions.extend(names.iter().zip(array.shape).map(|(n, &len)| (n.as_str(), len)));
            names.iter().map(String::as_str).collect()
        };
        variables.push(NcVariable {
            array: *array,
            dims,
            attributes: Vec::new(),
        });
    }
    write_netcdf_variables(path, &dimensions, &variables, global_attributes)
}

/// Writes `variables` on the dimensions `dimensions` (name, length) to `path` as a NetCDF
/// classic file, with the text attributes `global_attributes`. Names must be distinct;
/// each variable's dimensions must exist and their lengths be its shape; floats finite;
/// integers must fit 32 bits (`NC_INT`).
pub fn write_netcdf_variables(
    path: impl AsRef<Path>,
    dimensions: &[(&str, usize)],
    variables: &[NcVariable<'_>],
    global_attributes: &[(&str, &str)],
) -> Result<(), TopographyError> {
    let path = path.as_ref();
    let invalid = |value: &str, why: String| TopographyError::InvalidArgument {
        name: "NetCDF variable",
        value: value.to_string(),
        why: format!("{why} (writing {})", path.display()),
    };
    let mut encoded = Vec::with_capacity(variables.len());
    for (index, variable) in variables.iter().enumerate() {
        let array = &variable.array;
        array.validate(path)?;
        if variables[..index].iter().any(|v| v.array.name == array.name) {
            return Err(invalid(array.name, "named twice".into()));
        }
        let mut dims = Vec::with_capacity(variable.dims.len());
        for name in &variable.dims {
            let id = dimensions
                .iter()
                .position(|(d, _)| d == name)
                .ok_or_else(|| invalid(array.name, format!("has no dimension {name:?}")))?;
            dims.push(id);
        }
        let lengths: Vec<usize> = dims.iter().map(|&d| dimensions[d].1).collect();
        if lengths != array.shape {
            return Err(invalid(
                array.name,
                format!("shape {:?} is not its dimensions' lengths {lengths:?}", array.shape),
            ));
        }
        if let ArrayData::I64(values) = array.data {
            if let Some(v) = values.iter().find(|v| i32::try_from(**v).is_err()) {
                return Err(invalid(array.name, format!("value {v} does not fit a 32-bit NC_INT")));
            }
        }
        let mut attributes: Vec<(String, String)> = Vec::new();
        if let Some(unit) = array.unit {
            attributes.push(("units".into(), unit.into()));
        }
        attributes.extend(variable.attributes.iter().map(|(k, v)| (k.to_string(), v.clone())));
        encoded.push(Variable {
            name: array.name.to_string(),
            dims,
            data: array.data,
            attributes,
        });
    }
    let dimensions: Vec<(String, usize)> = dimensions.iter().map(|(n, l)| (n.to_string(), *l)).collect();
    let bytes = encode(&dimensions, &encoded, global_attributes);
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
        ArrayData::I64(v) => v.len() * 4,
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
                match variable.data {
                    ArrayData::F64(_) => NC_DOUBLE,
                    ArrayData::I64(_) => NC_INT,
                    ArrayData::Bool(_) => NC_BYTE,
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
            // Checked to fit 32 bits by `write_netcdf_variables`.
            ArrayData::I64(values) => values
                .iter()
                .for_each(|&v| out.extend_from_slice(&(v as i32).to_be_bytes())),
        }
        out.resize(padded_len(out.len()), 0);
    }
    out
}
