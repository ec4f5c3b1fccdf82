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
}

impl ArrayData<'_> {
    fn len(&self) -> usize {
        match self {
            Self::F64(v) => v.len(),
            Self::Bool(v) => v.len(),
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

/// The `.npy` (format version 1.0) bytes of one array, C order, header padded so the data
/// start at a multiple of 64 bytes as numpy writes it.
pub(crate) fn npy_bytes(array: &NamedArray<'_>) -> Vec<u8> {
    let descr = match array.data {
        ArrayData::F64(_) => "<f8",
        ArrayData::Bool(_) => "|b1",
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
    let mut out = Vec::with_capacity(unpadded + 64 + array.data.len() * 8);
    out.extend_from_slice(crate::npy::MAGIC);
    out.extend_from_slice(&[1, 0]);
    // The header of a few fields is far below u16::MAX.
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    match array.data {
        ArrayData::F64(values) => values.iter().for_each(|v| out.extend_from_slice(&v.to_le_bytes())),
        ArrayData::Bool(values) => out.extend(values.iter().map(|&b| u8::from(b))),
    }
    out
}

/// Bytes deflate is tried on to decide whether a member is compressed: four samples spread
/// over the member, so that a field that is zero in one region and dense in another is
/// judged by both.
const SAMPLE_CHUNKS: usize = 4;
const SAMPLE_CHUNK_BYTES: usize = 16 * 1024;

/// Compressed members must be at most this fraction of their size in the samples; a member
/// deflate shrinks less is stored. Dense smooth doubles (displacement and gap fields)
/// shrink by only 10–25 % at a cost of about 3 ms per MB, which was most of the output time
/// of a whole Hertz run at N = 512 (BENCHMARKS.md, issue #14 item 7).
const WORTHWHILE_RATIO: f64 = 0.75;

/// Whether DEFLATE at level 1 shrinks `bytes` to at most [`WORTHWHILE_RATIO`], judged on
/// samples (small members are compressed: the cost is negligible).
fn deflate_pays(bytes: &[u8]) -> bool {
    let sample_total = SAMPLE_CHUNKS * SAMPLE_CHUNK_BYTES;
    if bytes.len() <= 2 * sample_total {
        return true;
    }
    let mut encoder = flate2::write::DeflateEncoder::new(Vec::new(), flate2::Compression::new(1));
    for chunk in 0..SAMPLE_CHUNKS {
        let start = chunk * (bytes.len() - SAMPLE_CHUNK_BYTES) / (SAMPLE_CHUNKS - 1);
        // Writing into a Vec cannot fail.
        let _ = encoder.write_all(&bytes[start..start + SAMPLE_CHUNK_BYTES]);
    }
    let compressed = encoder.finish().map_or(usize::MAX, |out| out.len());
    (compressed as f64) <= WORTHWHILE_RATIO * sample_total as f64
}

/// Writes `arrays` to `path` as an `.npz` archive, as `numpy.savez_compressed` does: member
/// `NAME.npy` per array, DEFLATE-compressed, except members that deflate would shrink by
/// less than a quarter ([`WORTHWHILE_RATIO`]), which are stored (`numpy.load` reads both).
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
        // compression took a quarter of a whole Hertz run at N = 512 (BENCHMARKS.md).
        .compression_level(Some(1))
        .large_file(large_file);
    let stored = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Stored)
        .large_file(large_file);
    for array in arrays {
        let bytes = npy_bytes(array);
        let options = if deflate_pays(&bytes) { deflated } else { stored };
        zip.start_file(format!("{}.npy", array.name), options)
            .map_err(zip_error)?;
        zip.write_all(&bytes).map_err(io_error)?;
    }
    let mut writer = zip.finish().map_err(zip_error)?;
    writer.flush().map_err(io_error)
}
