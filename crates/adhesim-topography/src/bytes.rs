//! Bounds-checked reading of binary data: every read checks the remaining length first, so a
//! truncated file is an error, never a panic or an out-of-bounds read.

use crate::error::{ParseError, ParseResult};

/// Largest number of points a map may have (2^28, 2 GiB of `f64`): a header claiming more is
/// rejected before anything is allocated.
pub const MAX_POINTS: usize = 1 << 28;

/// Byte order of multi-byte values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Endian {
    Little,
    Big,
}

/// The element types the binary formats store.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    I64,
    U64,
    F32,
    F64,
    Bool,
}

impl Scalar {
    pub(crate) fn size(self) -> usize {
        match self {
            Self::I8 | Self::U8 | Self::Bool => 1,
            Self::I16 | Self::U16 => 2,
            Self::I32 | Self::U32 | Self::F32 => 4,
            Self::I64 | Self::U64 | Self::F64 => 8,
        }
    }
}

/// `nx × ny` as a checked point count within [`MAX_POINTS`], both sides at least 1.
pub(crate) fn point_count(nx: i64, ny: i64) -> ParseResult<usize> {
    if nx < 1 || ny < 1 {
        return Err(ParseError::malformed(format!("grid size {nx} × {ny} is not positive")));
    }
    let count = nx
        .checked_mul(ny)
        .filter(|&n| n as u64 <= MAX_POINTS as u64)
        .ok_or_else(|| {
            ParseError::malformed(format!(
                "grid size {nx} × {ny} exceeds the limit of {MAX_POINTS} points"
            ))
        })?;
    Ok(count as usize)
}

/// Checks that `available` bytes hold `count` elements of `scalar` (no more is read than that).
pub(crate) fn check_data_length(count: usize, scalar: Scalar, available: usize, what: &str) -> ParseResult<usize> {
    let needed = count
        .checked_mul(scalar.size())
        .ok_or_else(|| ParseError::malformed(format!("{what}: size overflows")))?;
    if needed > available {
        return Err(ParseError::malformed(format!(
            "{what}: needs {needed} bytes for {count} values, only {available} present (truncated?)"
        )));
    }
    Ok(needed)
}

/// Decodes `count` values of `scalar` from the start of `bytes` into `f64`.
pub(crate) fn decode_values(bytes: &[u8], count: usize, scalar: Scalar, endian: Endian) -> ParseResult<Vec<f64>> {
    let size = scalar.size();
    check_data_length(count, scalar, bytes.len(), "data")?;
    let mut out = Vec::with_capacity(count);
    for chunk in bytes.chunks_exact(size).take(count) {
        out.push(decode_one(chunk, scalar, endian));
    }
    Ok(out)
}

fn decode_one(chunk: &[u8], scalar: Scalar, endian: Endian) -> f64 {
    macro_rules! num {
        ($t:ty) => {{
            let mut raw = [0u8; std::mem::size_of::<$t>()];
            raw.copy_from_slice(chunk);
            match endian {
                Endian::Little => <$t>::from_le_bytes(raw),
                Endian::Big => <$t>::from_be_bytes(raw),
            }
        }};
    }
    match scalar {
        Scalar::I8 => chunk[0] as i8 as f64,
        Scalar::U8 => chunk[0] as f64,
        Scalar::Bool => f64::from(u8::from(chunk[0] != 0)),
        Scalar::I16 => num!(i16) as f64,
        Scalar::U16 => num!(u16) as f64,
        Scalar::I32 => num!(i32) as f64,
        Scalar::U32 => num!(u32) as f64,
        Scalar::I64 => num!(i64) as f64,
        Scalar::U64 => num!(u64) as f64,
        Scalar::F32 => num!(f32) as f64,
        Scalar::F64 => num!(f64),
    }
}

/// A cursor over a byte slice whose reads fail with the field's name when the data end.
pub(crate) struct Reader<'a> {
    data: &'a [u8],
    pos: usize,
}

impl<'a> Reader<'a> {
    pub(crate) fn new(data: &'a [u8]) -> Self {
        Self { data, pos: 0 }
    }

    pub(crate) fn remaining(&self) -> usize {
        self.data.len() - self.pos
    }

    pub(crate) fn take(&mut self, len: usize, what: &str) -> ParseResult<&'a [u8]> {
        if len > self.remaining() {
            return Err(ParseError::malformed(format!(
                "{what} at byte {}: needs {len} bytes, only {} left (truncated?)",
                self.pos,
                self.remaining()
            )));
        }
        let slice = &self.data[self.pos..self.pos + len];
        self.pos += len;
        Ok(slice)
    }

    fn array<const N: usize>(&mut self, what: &str) -> ParseResult<[u8; N]> {
        let mut raw = [0u8; N];
        raw.copy_from_slice(self.take(N, what)?);
        Ok(raw)
    }

    pub(crate) fn u8(&mut self, what: &str) -> ParseResult<u8> {
        Ok(self.array::<1>(what)?[0])
    }

    pub(crate) fn u16_le(&mut self, what: &str) -> ParseResult<u16> {
        Ok(u16::from_le_bytes(self.array(what)?))
    }

    pub(crate) fn i32_le(&mut self, what: &str) -> ParseResult<i32> {
        Ok(i32::from_le_bytes(self.array(what)?))
    }

    pub(crate) fn u32_le(&mut self, what: &str) -> ParseResult<u32> {
        Ok(u32::from_le_bytes(self.array(what)?))
    }

    pub(crate) fn i64_le(&mut self, what: &str) -> ParseResult<i64> {
        Ok(i64::from_le_bytes(self.array(what)?))
    }

    pub(crate) fn f64_le(&mut self, what: &str) -> ParseResult<f64> {
        Ok(f64::from_le_bytes(self.array(what)?))
    }

    /// A NUL-terminated string (the terminator is consumed, not returned).
    pub(crate) fn c_string(&mut self, what: &str) -> ParseResult<&'a str> {
        let rest = &self.data[self.pos..];
        let end = rest.iter().position(|&b| b == 0).ok_or_else(|| {
            ParseError::malformed(format!("{what} at byte {}: no terminating NUL (truncated?)", self.pos))
        })?;
        let text = std::str::from_utf8(&rest[..end])
            .map_err(|_| ParseError::malformed(format!("{what} at byte {}: not UTF-8", self.pos)))?;
        self.pos += end + 1;
        Ok(text)
    }
}
