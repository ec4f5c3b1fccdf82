//! ISO 25178-72 (XML 3-D surface profile, "x3p") surfaces.
//!
//! An x3p file is a zip archive with `main.xml` (schema ISO5436_2) and, for
//! binary data, the point file named by `Record3/DataLink/PointDataLink` (conventionally
//! `bindata/data.bin`) and optionally the validity file `ValidPointsLink` (`bindata/valid.bin`).
//! The axes `CX`, `CY`, `CZ` of `Record1/Axes` give `AxisType` (`I` incremental, `A` absolute),
//! `DataType` (`I` int16, `L` int32, `F` float32, `D` float64), `Increment` and `Offset`; lengths
//! are in metres. Points are stored x fastest, then y, little-endian;
//! `z = Offset + Increment·raw` for every type. The validity file holds one bit per point,
//! least significant bit first, 1 = valid; float data may also mark invalid points with NaN.
//! Data given inline as `Record3/DataList/Datum` text are read too. The MD5 checksums are not
//! verified: the zip CRC-32 of each member already detects corrupted members.

use std::collections::BTreeMap;

use quick_xml::events::Event;

use crate::bytes::{check_data_length, decode_values, point_count, Endian, Scalar};
use crate::error::{ParseError, ParseResult};
use crate::npy::read_zip_member;
use crate::RawMap;

/// Largest `main.xml` read (inline `DataList` data make it large; 256 MiB is millions of
/// points).
const MAX_XML_BYTES: u64 = 256 << 20;

/// The text of the leaf elements of `main.xml`, keyed by their path of local names
/// (`Record1/Axes/CX/Increment`), plus the `Datum` values of an inline data list.
struct MainXml {
    leaves: BTreeMap<String, String>,
    data_list: Vec<String>,
}

fn parse_main_xml(text: &str) -> ParseResult<MainXml> {
    let mut reader = quick_xml::Reader::from_str(text);
    let mut stack: Vec<String> = Vec::new();
    let mut leaves = BTreeMap::new();
    let mut data_list = Vec::new();
    let mut current_text = String::new();
    loop {
        let event = reader
            .read_event()
            .map_err(|e| ParseError::malformed(format!("main.xml at byte {}: {e}", reader.buffer_position())))?;
        match event {
            Event::Start(start) => {
                if stack.len() > 64 {
                    return Err(ParseError::malformed("main.xml nests deeper than 64 elements"));
                }
                let name = start.local_name().as_ref().to_string();
                stack.push(name);
                current_text.clear();
            }
            Event::Empty(start) => {
                let name = start.local_name().as_ref().to_string();
                if name == "Datum" && stack.last().map(String::as_str) == Some("DataList") {
                    data_list.push(String::new());
                }
            }
            Event::Text(content) => current_text.push_str(&content.xml10_content()),
            Event::CData(content) => current_text.push_str(&content.xml10_content()),
            Event::End(_) => {
                let path = stack.join("/");
                // The root element's name carries the schema prefix; keep paths relative to it.
                let relative = path.split_once('/').map(|(_, rest)| rest.to_string());
                if let Some(relative) = relative {
                    if relative.ends_with("DataList/Datum") {
                        data_list.push(current_text.trim().to_string());
                    } else {
                        leaves
                            .entry(relative)
                            .or_insert_with(|| current_text.trim().to_string());
                    }
                }
                stack.pop();
                current_text.clear();
            }
            Event::Eof => break,
            _ => {}
        }
    }
    if !stack.is_empty() {
        return Err(ParseError::malformed(format!(
            "main.xml ends inside <{}> (truncated?)",
            stack.join("/")
        )));
    }
    Ok(MainXml { leaves, data_list })
}

impl MainXml {
    fn text(&self, path: &str) -> ParseResult<&str> {
        self.leaves
            .get(path)
            .map(String::as_str)
            .ok_or_else(|| ParseError::malformed(format!("main.xml has no {path}")))
    }

    fn number(&self, path: &str) -> ParseResult<f64> {
        let text = self.text(path)?;
        text.parse::<f64>()
            .map_err(|_| ParseError::malformed(format!("main.xml {path} = {text:?} is not a number")))
    }

    /// An optional number (absent → `default`), an error when present but not a number.
    fn number_or(&self, path: &str, default: f64) -> ParseResult<f64> {
        match self.leaves.get(path) {
            None => Ok(default),
            Some(t) if t.is_empty() => Ok(default),
            Some(_) => self.number(path),
        }
    }
}

struct Axis {
    increment: f64,
    offset: f64,
    scalar: Option<Scalar>,
}

fn axis(xml: &MainXml, name: &str) -> ParseResult<Axis> {
    let base = format!("Record1/Axes/{name}");
    let axis_type = xml.text(&format!("{base}/AxisType"))?;
    let scalar = match xml.leaves.get(&format!("{base}/DataType")).map(String::as_str) {
        None | Some("") => None,
        Some("I") => Some(Scalar::I16),
        Some("L") => Some(Scalar::I32),
        Some("F") => Some(Scalar::F32),
        Some("D") => Some(Scalar::F64),
        Some(other) => {
            return Err(ParseError::malformed(format!(
                "{base}/DataType = {other:?} (ISO 25178-72 allows I, L, F, D)"
            )))
        }
    };
    if name != "CZ" && axis_type != "I" {
        return Err(ParseError::unsupported(format!(
            "{name} axis type {axis_type:?}: only incremental (I) lateral axes are read"
        )));
    }
    // A lateral axis without its increment has no spacing; a z axis without one stores
    // metres (increment 1), as ISO 25178-72 readers take it.
    let increment = if name == "CZ" {
        xml.number_or(&format!("{base}/Increment"), 1.0)?
    } else {
        xml.number(&format!("{base}/Increment"))?
    };
    Ok(Axis {
        increment,
        offset: xml.number_or(&format!("{base}/Offset"), 0.0)?,
        scalar,
    })
}

/// Reads an x3p archive.
pub(crate) fn read(bytes: &[u8]) -> ParseResult<RawMap> {
    let mut archive = zip::ZipArchive::new(std::io::Cursor::new(bytes))
        .map_err(|e| ParseError::malformed(format!("not a zip archive: {e}")))?;
    // Each member is read only up to the size the header implies.
    let mut member = |name: &str, limit: u64| -> ParseResult<Vec<u8>> {
        let mut file = archive
            .by_name(name)
            .map_err(|e| ParseError::malformed(format!("member {name}: {e}")))?;
        read_zip_member(&mut file, name, limit)
    };
    let main = member("main.xml", MAX_XML_BYTES)?;
    let main = std::str::from_utf8(&main).map_err(|_| ParseError::malformed("main.xml is not UTF-8"))?;
    let xml = parse_main_xml(main)?;
    let feature = xml.text("Record1/FeatureType")?;
    if feature != "SUR" {
        return Err(ParseError::unsupported(format!(
            "feature type {feature:?}: only areal surfaces (SUR) are read"
        )));
    }
    let (cx, cy, cz) = (axis(&xml, "CX")?, axis(&xml, "CY")?, axis(&xml, "CZ")?);
    let size = |name: &str| -> ParseResult<i64> {
        let text = xml.text(&format!("Record3/MatrixDimension/{name}"))?;
        text.parse()
            .map_err(|_| ParseError::malformed(format!("{name} = {text:?} is not an integer")))
    };
    let (nx, ny, nz) = (size("SizeX")?, size("SizeY")?, size("SizeZ")?);
    if nz != 1 {
        return Err(ParseError::unsupported(format!("SizeZ = {nz}: only one layer is read")));
    }
    let count = point_count(nx, ny)?;
    let (raw, valid) = if let Some(link) = xml.leaves.get("Record3/DataLink/PointDataLink") {
        let scalar = cz
            .scalar
            .ok_or_else(|| ParseError::malformed("Record1/Axes/CZ has no DataType"))?;
        let expected = count as u64 * scalar.size() as u64;
        let data = member(link, expected)?;
        let needed = check_data_length(count, scalar, data.len(), link)?;
        if needed != data.len() {
            return Err(ParseError::malformed(format!(
                "{link} has {} bytes, {needed} expected for {nx} × {ny} values",
                data.len()
            )));
        }
        let raw = decode_values(&data, count, scalar, Endian::Little)?;
        let valid = match xml.leaves.get("Record3/DataLink/ValidPointsLink") {
            Some(valid_link) => {
                let bits = member(valid_link, count.div_ceil(8) as u64 + 4096)?;
                Some(unpack_valid_bits(&bits, count, valid_link)?)
            }
            None => None,
        };
        (raw, valid)
    } else {
        inline_data(&xml, count)?
    };
    // Every data type is scaled (x3pio does the same; float data usually carry increment 1).
    let heights = raw.iter().map(|&r| cz.offset + cz.increment * r).collect();
    let mut metadata = BTreeMap::new();
    for (key, value) in &xml.leaves {
        if key.starts_with("Record2/") && !value.is_empty() {
            metadata.insert(key["Record2/".len()..].to_string(), value.clone());
        }
    }
    Ok(RawMap {
        nx: nx as usize,
        ny: ny as usize,
        dx: cx.increment,
        dy: cy.increment,
        x_offset: cx.offset,
        y_offset: cy.offset,
        heights,
        valid,
        channel: "Z".to_string(),
        height_unit: "m".to_string(),
        lateral_unit: "m".to_string(),
        metadata,
    })
}

/// Heights given as `<Datum>` text; an empty datum is an invalid point.
fn inline_data(xml: &MainXml, count: usize) -> ParseResult<(Vec<f64>, Option<Vec<bool>>)> {
    if xml.data_list.len() != count {
        return Err(ParseError::malformed(format!(
            "Record3 has neither a PointDataLink nor {count} Datum entries ({} found)",
            xml.data_list.len()
        )));
    }
    let mut raw = Vec::with_capacity(count);
    let mut valid = Vec::with_capacity(count);
    for (index, datum) in xml.data_list.iter().enumerate() {
        // A datum of a surface holds only z when the lateral axes are incremental; take the last.
        let z_text = datum.split([';', ' ', '\t']).rfind(|s| !s.is_empty());
        match z_text {
            None => {
                raw.push(f64::NAN);
                valid.push(false);
            }
            Some(z) => {
                let value = z
                    .parse::<f64>()
                    .map_err(|_| ParseError::malformed(format!("Datum {index} = {datum:?} is not a number")))?;
                raw.push(value);
                valid.push(true);
            }
        }
    }
    Ok((raw, Some(valid)))
}

/// One bit per point, least significant bit first, 1 = valid (ISO 25178-72, valid-points file).
fn unpack_valid_bits(bits: &[u8], count: usize, name: &str) -> ParseResult<Vec<bool>> {
    let needed = count.div_ceil(8);
    if bits.len() < needed {
        return Err(ParseError::malformed(format!(
            "{name} has {} bytes, {needed} needed for {count} points",
            bits.len()
        )));
    }
    Ok((0..count).map(|i| bits[i / 8] >> (i % 8) & 1 == 1).collect())
}
