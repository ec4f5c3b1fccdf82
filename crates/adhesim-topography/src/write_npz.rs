//! Contact fields as a numpy `.npz` archive (one `.npy` member per array, DEFLATE-compressed
//! unless deflate would barely shrink it), loadable with `numpy.load`.

use std::io::Write;
use std::path::Path;

use crate::TopographyError;

/// The values of a [`NamedArray`].
#[derive(Clone, Copy, Debug)]
pub enum ArrayData<'a> {
    /// Stored as little-endian float64 (`<f8`).
    F64(&'a [f64]),
    /// Stored as numpy bool (`|b1`).
    Bool(&'a [bool]),
    /// Stored as little-endian int64 (`<i8`); NetCDF classic stores it as 32-bit `NC_INT`.
    I64(&'a [i64]),
}

impl ArrayData<'_> {
    fn len(&self) -> usize {
        match self {
            Self::F64(v) => v.len(),
            Self::Bool(v) => v.len(),
            Self::I64(v) => v.len(),
        }
    }
}

/// An array to write: its name, its shape (`[ny, nx]` for a field, row-major values), its
/// values and, for NetCDF, its unit.
#[derive(Clone, Copy, Debug)]
pub struct NamedArray<'a> {
    pub name: &'a str,
    pub shape: &'a [usize],
    pub data: ArrayData<'a>,
    /// Written as the `units` attribute of a NetCDF variable; npz stores no units.
    pub unit: Option<&'a str>,
}

impl<'a> NamedArray<'a> {
    /// A float64 array.
    pub fn f64(name: &'a str, shape: &'a [usize], values: &'a [f64]) -> Self {
        Self {
            name,
            shape,
            data: ArrayData::F64(values),
            unit: None,
        }
    }

    /// An int64 array (step numbers).
    pub fn i64(name: &'a str, shape: &'a [usize], values: &'a [i64]) -> Self {
        Self {
            name,
            shape,
            data: ArrayData::I64(values),
            unit: None,
        }
    }

    /// A boolean array (a contact mask).
    pub fn bool(name: &'a str, shape: &'a [usize], values: &'a [bool]) -> Self {
        Self {
            name,
            shape,
            data: ArrayData::Bool(values),
            unit: None,
        }
    }

    /// The same array with a unit.
    pub fn with_unit(self, unit: &'a str) -> Self {
        Self {
            unit: Some(unit),
            ..self
        }
    }

    /// Checks the name, that the shape matches the values, and that floats are finite.
    pub(crate) fn validate(&self, path: &Path) -> Result<(), TopographyError> {
        let invalid = |why: String| TopographyError::InvalidArgument {
            name: "array",
            value: format!("{:?} for {}", self.name, path.display()),
            why,
        };
        let name_ok = !self.name.is_empty()
            && self
                .name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
        if !name_ok {
            return Err(invalid("names are non-empty ASCII letters, digits, '_' or '-'".into()));
        }
        let count = self.shape.iter().try_fold(1usize, |acc, &n| acc.checked_mul(n));
        if count != Some(self.data.len()) {
            return Err(invalid(format!(
                "shape {:?} does not hold {} values",
                self.shape,
                self.data.len()
            )));
        }
        if let ArrayData::F64(values) = self.data {
            if let Some(index) = values.iter().position(|v| !v.is_finite()) {
                return Err(invalid(format!("value {index} is {}, not finite", values[index])));
            }
        }
        Ok(())
    }
}

/// The `.npy` (format 1.0) header of `array`: magic, version, header length and the
/// dictionary, padded with spaces and a newline so that the data start at a multiple of
/// 64 bytes as numpy writes it.
fn npy_header(array: &NamedArray<'_>) -> Vec<u8> {
    let descr = match array.data {
        ArrayData::F64(_) => "<f8",
        ArrayData::Bool(_) => "|b1",
        ArrayData::I64(_) => "<i8",
    };
    let shape = match array.shape {
        [] => "()".to_string(),
        [n] => format!("({n},)"),
        dims => format!(
            "({})",
            dims.iter().map(|d| d.to_string()).collect::<Vec<_>>().join(", ")
        ),
    };
    let mut header = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
    let unpadded = crate::npy::MAGIC.len() + 2 + 2 + header.len() + 1;
    header.push_str(&" ".repeat((64 - unpadded % 64) % 64));
    header.push('\n');
    let mut out = Vec::with_capacity(unpadded + 64);
    out.extend_from_slice(crate::npy::MAGIC);
    out.extend_from_slice(&[1, 0]);
    // The header of a few fields is far below u16::MAX.
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    out
}

/// Elements converted to bytes per write: the data go out in pieces of this size
/// instead of as one copy of the whole array.
const PIECE_ELEMENTS: usize = 8192;

/// Writes the values of `data` from element `start` to `end` as little-endian bytes.
fn write_values(data: &ArrayData<'_>, range: std::ops::Range<usize>, out: &mut impl Write) -> std::io::Result<()> {
    let mut piece = Vec::with_capacity(PIECE_ELEMENTS * 8);
    let mut start = range.start;
    while start < range.end {
        let end = (start + PIECE_ELEMENTS).min(range.end);
        piece.clear();
        match data {
            ArrayData::F64(values) => values[start..end]
                .iter()
                .for_each(|v| piece.extend_from_slice(&v.to_le_bytes())),
            ArrayData::Bool(values) => piece.extend(values[start..end].iter().map(|&b| u8::from(b))),
            ArrayData::I64(values) => values[start..end]
                .iter()
                .for_each(|v| piece.extend_from_slice(&v.to_le_bytes())),
        }
        out.write_all(&piece)?;
        start = end;
    }
    Ok(())
}

/// Bytes deflate is tried on to decide whether a member is compressed: four samples spread
/// over the member, so that a field that is zero in one region and dense in another is
/// judged by both.
const SAMPLE_CHUNKS: usize = 4;
const SAMPLE_CHUNK_BYTES: usize = 16 * 1024;

/// Compressed members must be at most this fraction of their size in the samples; a member
/// deflate shrinks less is stored. Dense smooth doubles (displacement and gap fields)
/// shrink by only 10–25 % at a cost of about 3 ms per MB, which was most of the output time
/// of a whole Hertz run at N = 512 (docs/history.md §2026-11-23: the non-adhesive whole run).
const WORTHWHILE_RATIO: f64 = 0.75;

/// Whether DEFLATE at level 1 shrinks the values of `data` to at most
/// [`WORTHWHILE_RATIO`], judged on samples (small arrays are compressed: the cost is
/// negligible).
fn deflate_pays(data: &ArrayData<'_>) -> bool {
    let element_bytes = match data {
        ArrayData::F64(_) | ArrayData::I64(_) => 8,
        ArrayData::Bool(_) => 1,
    };
    let chunk = SAMPLE_CHUNK_BYTES / element_bytes;
    let len = data.len();
    if len <= 2 * SAMPLE_CHUNKS * chunk {
        return true;
    }
    let mut encoder = flate2::write::DeflateEncoder::new(Vec::new(), flate2::Compression::new(1));
    for index in 0..SAMPLE_CHUNKS {
        let start = index * (len - chunk) / (SAMPLE_CHUNKS - 1);
        // Writing into a Vec cannot fail.
        let _ = write_values(data, start..start + chunk, &mut encoder);
    }
    let compressed = encoder.finish().map_or(usize::MAX, |out| out.len());
    (compressed as f64) <= WORTHWHILE_RATIO * (SAMPLE_CHUNKS * SAMPLE_CHUNK_BYTES) as f64
}

/// Writes `arrays` to `path` as an `.npz` archive, as `numpy.savez_compressed` does: member
/// `NAME.npy` per array, DEFLATE-compressed, except members that deflate would shrink by
/// less than a quarter (`WORTHWHILE_RATIO`), which are stored (`numpy.load` reads both).
/// Names must be distinct; float values finite.
pub fn write_npz(path: impl AsRef<Path>, arrays: &[NamedArray<'_>]) -> Result<(), TopographyError> {
    let path = path.as_ref();
    for (index, array) in arrays.iter().enumerate() {
        array.validate(path)?;
        if arrays[..index].iter().any(|a| a.name == array.name) {
            return Err(TopographyError::InvalidArgument {
                name: "array",
                value: array.name.to_string(),
                why: format!("named twice for {}", path.display()),
            });
        }
    }
    let io_error = |source: std::io::Error| TopographyError::Io {
        path: path.to_path_buf(),
        action: "writing",
        source,
    };
    let zip_error = |e: zip::result::ZipError| io_error(std::io::Error::other(e));
    let file = std::fs::File::create(path).map_err(io_error)?;
    let mut zip = zip::ZipWriter::new(std::io::BufWriter::new(file));
    let large_file = arrays.iter().any(|a| a.data.len() * 8 > u32::MAX as usize / 2);
    let deflated = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated)
        // Level 1: the fields are doubles, which deflate shrinks by their runs of zeros
        // (free elements, no contact) about as well at the fastest level; at level 6 the
        // compression took a quarter of a whole Hertz run at N = 512 (docs/history.md
        // §2026-11-23: the non-adhesive whole run).
        .compression_level(Some(1))
        .large_file(large_file);
    let stored = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Stored)
        .large_file(large_file);
    for array in arrays {
        let options = if deflate_pays(&array.data) { deflated } else { stored };
        zip.start_file(format!("{}.npy", array.name), options)
            .map_err(zip_error)?;
        zip.write_all(&npy_header(array)).map_err(io_error)?;
        write_values(&array.data, 0..array.data.len(), &mut zip).map_err(io_error)?;
    }
    let mut writer = zip.finish().map_err(zip_error)?;
    writer.flush().map_err(io_error)
}
