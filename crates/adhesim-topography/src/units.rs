//! Length units to metres: `m` with an SI prefix (`nm`, `um`, `µm`, `mm`, …) and the ångström.

use crate::error::{ParseError, ParseResult};

/// The factor that converts a value in `unit` to metres (`"um"` → 1e-6).
///
/// Accepts `m` with any SI prefix from yocto to yotta (`u`, `µ` (U+00B5) and `μ` (U+03BC) for
/// micro), `Å`/`A`/`angstrom`, and `mum`, a spelling some instruments use for micrometres.
/// Surrounding white space and a trailing NUL padding are ignored; anything else, including an
/// empty string or a unit that is not a length, is an error.
pub fn length_unit_to_metres(unit: &str) -> Result<f64, crate::TopographyError> {
    parse_length_unit(unit).map_err(|_| crate::TopographyError::UnknownUnit {
        context: "length unit".to_string(),
        unit: unit.to_string(),
    })
}

pub(crate) fn parse_length_unit(unit: &str) -> ParseResult<f64> {
    let trimmed = unit.trim_matches(|c: char| c.is_whitespace() || c == '\0');
    let unknown = || ParseError::UnknownUnit(unit.to_string());
    match trimmed {
        "Å" | "A" | "angstrom" | "Angstrom" | "\u{212B}" => return Ok(1e-10),
        "mum" => return Ok(1e-6),
        _ => {}
    }
    let prefix = trimmed.strip_suffix('m').ok_or_else(unknown)?;
    let factor = match prefix {
        "" => 1.0,
        "y" => 1e-24,
        "z" => 1e-21,
        "a" => 1e-18,
        "f" => 1e-15,
        "p" => 1e-12,
        "n" => 1e-9,
        "u" | "µ" | "μ" => 1e-6,
        "m" => 1e-3,
        "c" => 1e-2,
        "d" => 1e-1,
        "da" => 1e1,
        "h" => 1e2,
        "k" => 1e3,
        "M" => 1e6,
        "G" => 1e9,
        "T" => 1e12,
        "P" => 1e15,
        "E" => 1e18,
        "Z" => 1e21,
        "Y" => 1e24,
        _ => return Err(unknown()),
    };
    Ok(factor)
}

/// A value with its unit, such as `"5.000 µm"` or `"1.5e-6 m"`, in metres.
pub(crate) fn parse_length_with_unit(text: &str) -> ParseResult<f64> {
    let text = text.trim();
    let split = text.find(|c: char| c.is_whitespace()).unwrap_or(text.len());
    let (number, unit) = text.split_at(split);
    let value: f64 = number
        .parse()
        .map_err(|_| ParseError::malformed(format!("{text:?} is not a number with a unit")))?;
    let unit = unit.trim();
    if unit.is_empty() {
        return Err(ParseError::malformed(format!("{text:?} has no unit")));
    }
    Ok(value * parse_length_unit(unit)?)
}

/// Decodes a fixed-width, NUL- or space-padded text field: UTF-8 when valid, else Latin-1
/// (older Digital Surf files write `µ` as the single byte 0xB5).
pub(crate) fn decode_padded_text(bytes: &[u8]) -> String {
    let end = bytes.iter().position(|&b| b == 0).unwrap_or(bytes.len());
    let bytes = &bytes[..end];
    let text = match std::str::from_utf8(bytes) {
        Ok(text) => text.to_string(),
        Err(_) => bytes.iter().map(|&b| char::from(b)).collect(),
    };
    text.trim().to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn prefixes_and_spellings() {
        let cases = [
            ("m", 1.0),
            ("mm", 1e-3),
            ("um", 1e-6),
            ("µm", 1e-6),
            ("μm", 1e-6),
            (" nm\0\0", 1e-9),
            ("pm", 1e-12),
            ("Å", 1e-10),
            ("km", 1e3),
        ];
        for (unit, factor) in cases {
            let got = parse_length_unit(unit).unwrap();
            assert!((got / factor - 1.0).abs() < 1e-15, "{unit}: {got}");
        }
        for bad in ["", "deg", "V", "xm", "m2"] {
            assert!(parse_length_unit(bad).is_err(), "{bad} accepted");
        }
    }

    #[test]
    fn latin1_micro_sign() {
        assert_eq!(decode_padded_text(b"\xb5m\0\0\0"), "µm");
        assert_eq!(decode_padded_text("µm  ".as_bytes()), "µm");
        assert!((parse_length_with_unit("5.000 µm").unwrap() - 5e-6).abs() < 1e-20);
    }
}
