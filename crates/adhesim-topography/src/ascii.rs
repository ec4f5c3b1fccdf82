//! Text height maps: ASCII matrices (bare, or with the header of Gwyddion's "ASCII data
//! matrix" export or of SPIP's ASC export) and xyz point lists on a regular grid.
//!
//! Gwyddion's header lines are `# Channel: NAME`, `# Width: 5.000 µm`, `# Height: 2.5 µm`
//! (the physical extents, `nx·dx` and `ny·dy`) and `# Value units: m`. SPIP's are
//! `# key = value` lines ending at `# Start of Data:`: `x-pixels`, `y-pixels`, `x-length`,
//! `y-length` (nanometres), `x-offset`, `y-offset`, and `z-unit` (a length unit) or `Bit2nm`
//! (the heights times `Bit2nm` are nanometres). Gwyddion's labels are read in every language
//! Gwyddion writes them (`# Kanal:`, `# Breite:`, `# Höhe:` …), and the header without `#` of
//! another export (`h=305 w=75`, `pixel size=3.7e-7 m`, `height conversion factor (-> m)=2.9e-8`).
//! Values are separated by white space, commas or semicolons, one row of the map (one y) per
//! line; `NaN` marks an invalid point; a decimal comma is an error.

use std::collections::BTreeMap;

use crate::bytes::{point_count, MAX_POINTS};
use crate::error::{ParseError, ParseResult};
use crate::units::{parse_length_unit, parse_length_with_unit};
use crate::{height_unit_option, spacing_option, RawMap, ReadOptions};

/// Header entries (keys in lower case, Gwyddion's translated labels mapped to the English
/// ones) and the data rows of a text file.
struct TextFile {
    header: BTreeMap<String, String>,
    rows: Vec<Vec<f64>>,
}

/// Gwyddion's plain-text export translates its header labels into the language of its user
/// interface; these are the labels of every language Gwyddion ships (the list
/// SurfaceTopography 1.27 reads, `IO/Text.py`), mapped to the English key.
const GWYDDION_LABELS: [(&str, &[&str]); 4] = [
    (
        "channel",
        &[
            "channel",
            "kanál",
            "kanal",
            "canal",
            "canale",
            "チャネル",
            "채널",
            "канал",
        ],
    ),
    (
        "width",
        &[
            "width",
            "šířka",
            "breite",
            "anchura",
            "largeur",
            "larghezza",
            "幅",
            "폭",
            "largura",
            "ширина",
        ],
    ),
    (
        "height",
        &[
            "height",
            "výška",
            "höhe",
            "altura",
            "hauteur",
            "altezza",
            "高さ",
            "높이",
            "высота",
        ],
    ),
    (
        "value units",
        &[
            "value units",
            "jednotky hodnot",
            "einheiten",
            "unités",
            "unità valore",
            "値の単位",
            "값 단위",
            "unidades de valor",
            "единицы измерения",
        ],
    ),
];

/// The English key of a header label (lower case), the label itself when it is none of
/// Gwyddion's translated ones.
fn canonical_key(label: &str) -> String {
    let label = label.trim().to_lowercase();
    GWYDDION_LABELS
        .iter()
        .find(|(_, spellings)| spellings.contains(&label.as_str()))
        .map_or(label, |(key, _)| key.to_string())
}

/// Records one header line (without its `#`): `key: value`, `key = value` (a full-width
/// colon too, as the Japanese export writes), or several `key=value` tokens on one line
/// (`h=305 w=75`). `height conversion factor (-> m)=2.9e-8` is stored as the key
/// `height conversion factor` and the unit under `height conversion unit`.
fn record_header(line: &str, header: &mut BTreeMap<String, String>) {
    let tokens: Vec<&str> = line.split_whitespace().collect();
    if tokens.len() > 1 && tokens.iter().all(|t| t.contains('=') && !t.starts_with('=')) {
        for token in tokens {
            let (key, value) = token.split_once('=').unwrap_or((token, ""));
            header.entry(canonical_key(key)).or_insert_with(|| value.to_string());
        }
        return;
    }
    let Some(split) = line.find([':', '=', '：']) else {
        return;
    };
    let separator = line[split..].chars().next().map_or(1, char::len_utf8);
    let key = canonical_key(&line[..split]);
    let value = line[split + separator..].trim().to_string();
    if let Some(rest) = key.strip_prefix("height conversion factor") {
        let unit = rest.trim().trim_start_matches('(').trim_end_matches(')').trim();
        let unit = unit.trim_start_matches("->").trim();
        header
            .entry("height conversion unit".to_string())
            .or_insert_with(|| unit.to_string());
        header.entry("height conversion factor".to_string()).or_insert(value);
        return;
    }
    header.entry(key).or_insert(value);
}

/// Whether a line starts with a number (a data line) rather than a header label.
fn starts_with_number(line: &str) -> bool {
    line.split([' ', '\t', ',', ';'])
        .find(|t| !t.is_empty())
        .is_some_and(|t| t.parse::<f64>().is_ok())
}

/// The values of one data line. Values are separated by white space, `;` or `,`; a comma
/// between two digits of a token that white space or `;` delimits is a decimal comma, which
/// is refused rather than read as two columns.
fn parse_row(line: &str, line_number: usize) -> ParseResult<Vec<f64>> {
    let separated = line.contains([' ', '\t', ';']);
    if separated {
        let decimal_comma = line.split([' ', '\t', ';']).find(|token| {
            let bytes = token.as_bytes();
            bytes
                .windows(3)
                .any(|w| w[0].is_ascii_digit() && w[1] == b',' && w[2].is_ascii_digit())
        });
        if let Some(token) = decimal_comma {
            return Err(ParseError::malformed(format!(
                "line {line_number}: {token:?} has a decimal comma; only decimal points are read (replace the commas by points)"
            )));
        }
    }
    line.split([' ', '\t', ',', ';'])
        .filter(|t| !t.is_empty())
        .map(|token| {
            token
                .parse::<f64>()
                .map_err(|_| ParseError::malformed(format!("line {line_number}: {token:?} is not a number")))
        })
        .collect()
}

fn parse_text(bytes: &[u8]) -> ParseResult<TextFile> {
    let text = std::str::from_utf8(bytes)
        .map_err(|e| ParseError::malformed(format!("not UTF-8 text (byte {})", e.valid_up_to())))?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut header = BTreeMap::new();
    let mut rows = Vec::new();
    let mut total = 0usize;
    for (line_index, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        if let Some(comment) = line.strip_prefix('#') {
            record_header(comment, &mut header);
            continue;
        }
        // Some exports (Gwyddion's `h=… w=…`, `pixel size=…` header) write their header
        // without `#`: lines before the first data line that do not start with a number.
        if rows.is_empty() && !starts_with_number(line) && line.contains([':', '=', '：']) {
            record_header(line, &mut header);
            continue;
        }
        let row = parse_row(line, line_index + 1)?;
        total += row.len();
        if total > MAX_POINTS {
            return Err(ParseError::malformed(format!("more than {MAX_POINTS} values")));
        }
        rows.push(row);
    }
    if rows.is_empty() {
        return Err(ParseError::malformed("no data lines"));
    }
    Ok(TextFile { header, rows })
}

impl TextFile {
    fn number(&self, key: &str) -> ParseResult<Option<f64>> {
        match self.header.get(key) {
            None => Ok(None),
            Some(text) => text
                .parse::<f64>()
                .map(Some)
                .map_err(|_| ParseError::malformed(format!("header {key} = {text:?} is not a number"))),
        }
    }

    /// The grid size: SPIP's `x-pixels`/`y-pixels` or Gwyddion's `w`/`h` (values then may
    /// wrap freely), else the rows, which must all be equally long.
    fn grid(&self) -> ParseResult<(usize, usize, Vec<f64>)> {
        let values: Vec<f64> = self.rows.iter().flatten().copied().collect();
        for (x_key, y_key) in [("x-pixels", "y-pixels"), ("w", "h")] {
            if let (Some(nx), Some(ny)) = (self.number(x_key)?, self.number(y_key)?) {
                let count = point_count(nx as i64, ny as i64)?;
                if values.len() != count {
                    return Err(ParseError::malformed(format!(
                        "{} values for {x_key} × {y_key} = {nx} × {ny}",
                        values.len()
                    )));
                }
                return Ok((nx as usize, ny as usize, values));
            }
        }
        let nx = self.rows[0].len();
        if let Some((index, row)) = self.rows.iter().enumerate().find(|(_, r)| r.len() != nx) {
            return Err(ParseError::malformed(format!(
                "data row {} has {} values, the first row {nx}",
                index + 1,
                row.len()
            )));
        }
        Ok((nx, self.rows.len(), values))
    }
}

/// Reads an ASCII matrix.
pub(crate) fn read_matrix(bytes: &[u8], options: &ReadOptions) -> ParseResult<RawMap> {
    let file = parse_text(bytes)?;
    let (nx, ny, values) = file.grid()?;
    if file.number("voidpixels")?.is_some_and(|v| v != 0.0) {
        return Err(ParseError::unsupported("SPIP void pixels"));
    }
    let (dx, dy, lateral_unit) = lateral(&file, nx, ny, options)?;
    let (height_factor, height_unit) = heights(&file, options)?;
    let channel = file.header.get("channel").cloned().unwrap_or_default();
    if let Some(requested) = &options.channel {
        if requested != &channel {
            return Err(ParseError::ChannelNotFound {
                requested: requested.clone(),
                available: vec![channel],
            });
        }
    }
    let nm = 1e-9;
    Ok(RawMap {
        nx,
        ny,
        dx,
        dy,
        x_offset: file.number("x-offset")?.unwrap_or(0.0) * nm,
        y_offset: file.number("y-offset")?.unwrap_or(0.0) * nm,
        heights: values.iter().map(|v| v * height_factor).collect(),
        valid: None,
        channel,
        height_unit,
        lateral_unit,
        metadata: file.header.clone(),
    })
}

/// `(dx, dy, unit)` from a Gwyddion or SPIP header, else from the caller.
fn lateral(file: &TextFile, nx: usize, ny: usize, options: &ReadOptions) -> ParseResult<(f64, f64, String)> {
    if let (Some(width), Some(height)) = (file.header.get("width"), file.header.get("height")) {
        let unit = width.split_whitespace().nth(1).unwrap_or("").to_string();
        return Ok((
            parse_length_with_unit(width)? / nx as f64,
            parse_length_with_unit(height)? / ny as f64,
            unit,
        ));
    }
    if let (Some(x_len), Some(y_len)) = (file.number("x-length")?, file.number("y-length")?) {
        return Ok((x_len * 1e-9 / nx as f64, y_len * 1e-9 / ny as f64, "nm".into()));
    }
    if let Some(pixel) = file.header.get("pixel size") {
        let unit = pixel.split_whitespace().nth(1).unwrap_or("").to_string();
        let spacing = parse_length_with_unit(pixel)?;
        return Ok((spacing, spacing, unit));
    }
    let (dx, dy) = spacing_option(options)?;
    Ok((dx, dy, "m".into()))
}

/// The factor from stored values to metres and the stored unit.
fn heights(file: &TextFile, options: &ReadOptions) -> ParseResult<(f64, String)> {
    for key in ["value units", "z-unit"] {
        if let Some(unit) = file.header.get(key) {
            return Ok((parse_length_unit(unit)?, unit.clone()));
        }
    }
    if let Some(bit2nm) = file.number("bit2nm")? {
        return Ok((bit2nm * 1e-9, format!("{bit2nm} nm")));
    }
    if let Some(factor) = file.number("height conversion factor")? {
        let unit = file.header.get("height conversion unit").map_or("", String::as_str);
        return Ok((factor * parse_length_unit(unit)?, format!("{factor} {unit}")));
    }
    height_unit_option(options)
}

/// Sorted distinct values of one coordinate, clustered within `tolerance`, as a regular
/// grid `(first, spacing, count)`.
fn regular_axis(mut values: Vec<f64>, name: &str) -> ParseResult<(f64, f64, usize)> {
    values.sort_by(f64::total_cmp);
    let (first, last) = (values[0], values[values.len() - 1]);
    if !(first.is_finite() && last.is_finite()) {
        return Err(ParseError::malformed(format!("a {name} coordinate is not finite")));
    }
    let tolerance = 1e-6 * (last - first);
    let mut distinct = vec![first];
    for &v in &values[1..] {
        if v - distinct[distinct.len() - 1] > tolerance {
            distinct.push(v);
        }
    }
    let count = distinct.len();
    if count < 2 {
        return Err(ParseError::malformed(format!(
            "all points share one {name}; a map needs at least two"
        )));
    }
    let spacing = (last - first) / (count - 1) as f64;
    for (k, &v) in distinct.iter().enumerate() {
        if (v - (first + k as f64 * spacing)).abs() > 1e-3 * spacing {
            return Err(ParseError::malformed(format!(
                "{name} = {v} is off the regular grid of spacing {spacing} from {first}"
            )));
        }
    }
    Ok((first, spacing, count))
}

/// Reads an xyz file: one `x y z` point per line, the points of a regular grid in any order.
pub(crate) fn read_xyz(bytes: &[u8], options: &ReadOptions) -> ParseResult<RawMap> {
    let file = parse_text(bytes)?;
    if let Some((index, row)) = file.rows.iter().enumerate().find(|(_, r)| r.len() != 3) {
        return Err(ParseError::malformed(format!(
            "data line {} has {} values, not x y z",
            index + 1,
            row.len()
        )));
    }
    let (x0, dx, nx) = regular_axis(file.rows.iter().map(|r| r[0]).collect(), "x")?;
    let (y0, dy, ny) = regular_axis(file.rows.iter().map(|r| r[1]).collect(), "y")?;
    let count = point_count(nx as i64, ny as i64)?;
    if count != file.rows.len() {
        return Err(ParseError::malformed(format!(
            "{} points for a {nx} × {ny} grid",
            file.rows.len()
        )));
    }
    let mut heights = vec![f64::NAN; count];
    let mut filled = vec![false; count];
    for row in &file.rows {
        let ix = ((row[0] - x0) / dx).round() as usize;
        let iy = ((row[1] - y0) / dy).round() as usize;
        let index = iy * nx + ix;
        if std::mem::replace(&mut filled[index], true) {
            return Err(ParseError::malformed(format!(
                "two points at x = {}, y = {}",
                row[0], row[1]
            )));
        }
        heights[index] = row[2];
    }
    let lateral_unit = match file.header.get("lateral units").or(file.header.get("x units")) {
        Some(unit) => unit.clone(),
        None => options.lateral_unit.clone().ok_or(ParseError::MissingOption {
            what: "unit of the x and y columns",
            option: "lateral_unit",
        })?,
    };
    let lateral_factor = parse_length_unit(&lateral_unit)?;
    let (height_factor, height_unit) = heights_xyz(&file, options)?;
    Ok(RawMap {
        nx,
        ny,
        dx: dx * lateral_factor,
        dy: dy * lateral_factor,
        x_offset: x0 * lateral_factor,
        y_offset: y0 * lateral_factor,
        heights: heights.iter().map(|v| v * height_factor).collect(),
        valid: None,
        channel: file.header.get("channel").cloned().unwrap_or_default(),
        height_unit,
        lateral_unit,
        metadata: file.header.clone(),
    })
}

fn heights_xyz(file: &TextFile, options: &ReadOptions) -> ParseResult<(f64, String)> {
    match file.header.get("value units").or(file.header.get("z units")) {
        Some(unit) => Ok((parse_length_unit(unit)?, unit.clone())),
        None => height_unit_option(options),
    }
}
