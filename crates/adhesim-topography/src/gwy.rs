//! Gwyddion native files (`.gwy`, the serialised object format "GWYP").
//!
//! The format (Gwyddion user guide, "GWY File Format"): the magic `GWYP`, then one serialised
//! object. An object is its type name (NUL-terminated), a u32 little-endian byte size of its
//! components, and the components; a component is a name (NUL-terminated), a one-character
//! type and the value: `b` bool and `c` char (1 byte), `i` int32, `q` int64, `d` double, `s`
//! NUL-terminated string, `o` object; the capital letters are arrays, a u32 count then the
//! items. The top object is a `GwyContainer` whose components are keyed `/N/data` (a
//! `GwyDataField`: `xres`, `yres`, `xreal`, `yreal`, `xoff`, `yoff`, `si_unit_xy`, `si_unit_z`
//! (`GwySIUnit` objects with a `unitstr`), `data` (row-major doubles)), `/N/data/title` and the
//! mask `/N/mask` (a data field, 1 where the point is masked).

use std::collections::BTreeMap;

use crate::bytes::{point_count, Reader};
use crate::error::{ParseError, ParseResult};
use crate::units::parse_length_unit;
use crate::{height_unit_option, RawMap, ReadOptions};

/// Objects nest this deep at most (a GwyContainer holding a data field holding a unit is 3).
const MAX_DEPTH: usize = 16;

/// A deserialised value; arrays other than doubles are skipped, not stored.
#[derive(Debug)]
enum Value {
    Int(i64),
    Double(f64),
    Text(String),
    Object(Object),
    Doubles(Vec<f64>),
    Other,
}

#[derive(Debug)]
struct Object {
    type_name: String,
    components: Vec<(String, Value)>,
}

impl Object {
    fn get(&self, name: &str) -> Option<&Value> {
        self.components.iter().find(|(n, _)| n == name).map(|(_, v)| v)
    }

    fn int(&self, name: &str) -> ParseResult<i64> {
        match self.get(name) {
            Some(Value::Int(v)) => Ok(*v),
            _ => Err(self.missing(name, "an integer")),
        }
    }

    fn double_or(&self, name: &str, default: f64) -> ParseResult<f64> {
        match self.get(name) {
            Some(Value::Double(v)) => Ok(*v),
            None => Ok(default),
            _ => Err(self.missing(name, "a double")),
        }
    }

    fn unit(&self, name: &str) -> String {
        match self.get(name) {
            Some(Value::Object(unit)) => match unit.get("unitstr") {
                Some(Value::Text(text)) => text.clone(),
                _ => String::new(),
            },
            _ => String::new(),
        }
    }

    fn missing(&self, name: &str, kind: &str) -> ParseError {
        ParseError::malformed(format!("{} has no {name} that is {kind}", self.type_name))
    }
}

fn parse_object(reader: &mut Reader<'_>, depth: usize) -> ParseResult<Object> {
    if depth > MAX_DEPTH {
        return Err(ParseError::malformed(format!("objects nest deeper than {MAX_DEPTH}")));
    }
    let type_name = reader.c_string("object type name")?.to_string();
    let size = reader.u32_le("object size")? as usize;
    let body = reader.take(size, &format!("components of {type_name}"))?;
    let mut inner = Reader::new(body);
    let mut components = Vec::new();
    while inner.remaining() > 0 {
        let name = inner.c_string("component name")?.to_string();
        let kind = inner.u8("component type")?;
        let value = parse_value(&mut inner, kind, &name, depth)?;
        components.push((name, value));
    }
    Ok(Object { type_name, components })
}

fn parse_value(reader: &mut Reader<'_>, kind: u8, name: &str, depth: usize) -> ParseResult<Value> {
    let array_len = |reader: &mut Reader<'_>, item: usize| -> ParseResult<usize> {
        let count = reader.u32_le(name)? as usize;
        let bytes = count.checked_mul(item).filter(|&b| b <= reader.remaining());
        bytes.map(|_| count).ok_or_else(|| {
            ParseError::malformed(format!(
                "array {name} of {count} items does not fit in the {} bytes left (truncated?)",
                reader.remaining()
            ))
        })
    };
    Ok(match kind {
        b'b' | b'c' => Value::Int(i64::from(reader.u8(name)?)),
        b'i' => Value::Int(i64::from(reader.i32_le(name)?)),
        b'q' => Value::Int(reader.i64_le(name)?),
        b'd' => Value::Double(reader.f64_le(name)?),
        b's' => Value::Text(reader.c_string(name)?.to_string()),
        b'o' => Value::Object(parse_object(reader, depth + 1)?),
        b'D' => {
            let count = array_len(reader, 8)?;
            let mut values = Vec::with_capacity(count);
            for _ in 0..count {
                values.push(reader.f64_le(name)?);
            }
            Value::Doubles(values)
        }
        b'B' | b'C' | b'I' | b'Q' => {
            let item = match kind {
                b'I' => 4,
                b'Q' => 8,
                _ => 1,
            };
            let count = array_len(reader, item)?;
            reader.take(count * item, name)?;
            Value::Other
        }
        b'S' => {
            let count = reader.u32_le(name)?;
            for _ in 0..count {
                reader.c_string(name)?;
            }
            Value::Other
        }
        b'O' => {
            let count = reader.u32_le(name)?;
            for _ in 0..count {
                parse_object(reader, depth + 1)?;
            }
            Value::Other
        }
        other => {
            return Err(ParseError::malformed(format!(
                "component {name} has unknown type {:?}",
                char::from(other)
            )))
        }
    })
}

/// The channel numbers `N` of the container's `/N/data` data fields, ascending.
fn channel_ids(container: &Object) -> Vec<u32> {
    let mut ids: Vec<u32> = container
        .components
        .iter()
        .filter_map(|(key, value)| {
            let id = key.strip_prefix('/')?.strip_suffix("/data")?.parse().ok()?;
            matches!(value, Value::Object(o) if o.type_name == "GwyDataField").then_some(id)
        })
        .collect();
    ids.sort_unstable();
    ids
}

fn title(container: &Object, id: u32) -> String {
    match container.get(&format!("/{id}/data/title")) {
        Some(Value::Text(t)) => t.clone(),
        _ => format!("/{id}/data"),
    }
}

/// Reads the first channel of a `.gwy` file, or the one whose title is `options.channel`.
pub(crate) fn read(bytes: &[u8], options: &ReadOptions) -> ParseResult<RawMap> {
    let mut reader = Reader::new(bytes);
    if reader.take(4, "magic")? != b"GWYP" {
        return Err(ParseError::malformed("no GWYP magic (or an old GWYO file)"));
    }
    let container = parse_object(&mut reader, 0)?;
    if container.type_name != "GwyContainer" {
        return Err(ParseError::malformed(format!(
            "top object is a {}, not a GwyContainer",
            container.type_name
        )));
    }
    let ids = channel_ids(&container);
    let id = match &options.channel {
        None => *ids
            .first()
            .ok_or_else(|| ParseError::malformed("the container has no /N/data channel"))?,
        Some(requested) => *ids
            .iter()
            .find(|&&id| &title(&container, id) == requested)
            .ok_or_else(|| ParseError::ChannelNotFound {
                requested: requested.clone(),
                available: ids.iter().map(|&id| title(&container, id)).collect(),
            })?,
    };
    let Some(Value::Object(field)) = container.get(&format!("/{id}/data")) else {
        return Err(ParseError::malformed(format!("/{id}/data is not an object")));
    };
    let (nx, ny, values) = field_values(field)?;
    let LateralScale {
        factor: xy_factor,
        unit: xy_unit,
        spacing: given_spacing,
    } = lateral_unit(field, options)?;
    let (z_factor, z_unit) = match field.unit("si_unit_z") {
        unit if unit.trim().is_empty() => height_unit_option(options)?,
        unit => (parse_length_unit(&unit)?, unit),
    };
    let valid = match container.get(&format!("/{id}/mask")) {
        Some(Value::Object(mask)) => {
            let (mx, my, mask_values) = field_values(mask)?;
            if (mx, my) != (nx, ny) {
                return Err(ParseError::malformed(format!(
                    "/{id}/mask is {mx} × {my}, the data {nx} × {ny}"
                )));
            }
            Some(mask_values.iter().map(|&m| m < 0.5).collect())
        }
        _ => None,
    };
    let (dx, dy) = match given_spacing {
        Some(spacing) => spacing,
        None => (
            field.double_or("xreal", f64::NAN)? / nx as f64 * xy_factor,
            field.double_or("yreal", f64::NAN)? / ny as f64 * xy_factor,
        ),
    };
    let mut metadata = BTreeMap::new();
    metadata.insert("channel id".to_string(), format!("/{id}/data"));
    Ok(RawMap {
        nx,
        ny,
        dx,
        dy,
        x_offset: field.double_or("xoff", 0.0)? * xy_factor,
        y_offset: field.double_or("yoff", 0.0)? * xy_factor,
        heights: values.iter().map(|v| v * z_factor).collect(),
        valid,
        channel: title(&container, id),
        height_unit: z_unit,
        lateral_unit: xy_unit,
        metadata,
    })
}

/// How a data field's lateral sizes become metres.
struct LateralScale {
    /// Metres per unit of `xreal`, `yreal`, `xoff`, `yoff`.
    factor: f64,
    unit: String,
    /// The caller's spacing, replacing `xreal/xres` where the file's unit is empty.
    spacing: Option<(f64, f64)>,
}

/// The factor of the lateral unit to metres, the unit, and the caller's spacing where the
/// file's `si_unit_xy` is empty: Gwyddion writes an empty unit when the instrument file it
/// imported recorded none. Then `options.spacing` (metres) or `options.lateral_unit` (the
/// unit of `xreal`, `yreal`) must say what the file does not.
fn lateral_unit(field: &Object, options: &ReadOptions) -> ParseResult<LateralScale> {
    let unit = field.unit("si_unit_xy");
    let scale = |factor, unit, spacing| LateralScale { factor, unit, spacing };
    if !unit.trim().is_empty() {
        return Ok(scale(parse_length_unit(&unit)?, unit, None));
    }
    if let Some(spacing) = options.spacing {
        return Ok(scale(1.0, "m".to_string(), Some(spacing)));
    }
    match &options.lateral_unit {
        Some(given) => Ok(scale(parse_length_unit(given)?, given.clone(), None)),
        None => Err(ParseError::MissingOption {
            what: "lateral unit (its si_unit_xy is empty)",
            option: "lateral_unit",
        }),
    }
}

/// `(xres, yres, data)` of a GwyDataField, the data length checked against the size.
fn field_values(field: &Object) -> ParseResult<(usize, usize, &[f64])> {
    let (nx, ny) = (field.int("xres")?, field.int("yres")?);
    let count = point_count(nx, ny)?;
    match field.get("data") {
        Some(Value::Doubles(values)) if values.len() == count => Ok((nx as usize, ny as usize, values)),
        Some(Value::Doubles(values)) => Err(ParseError::malformed(format!(
            "GwyDataField data has {} values for {nx} × {ny}",
            values.len()
        ))),
        _ => Err(field.missing("data", "an array of doubles")),
    }
}
