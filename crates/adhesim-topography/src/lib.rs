//! Measured surface topographies for adhesim: readers of instrument files and writers of
//! contact fields.
//!
//! [`read_topography`] reads a height map from ISO 25178-72 x3p, Gwyddion `.gwy`, Digital Surf
//! `.sur`, ASCII matrix (with the headers Gwyddion and SPIP export), xyz, `.npy` and `.npz`
//! files, chosen by the file extension, into one [`Topography`] in metres. [`Topography`] has
//! [`Topography::detrend_mean_plane`] and [`Topography::resample_to`]. [`write_npz`] and
//! [`write_netcdf`] write contact fields for numpy and xarray users.
//!
//! Every malformed or truncated file gives a [`TopographyError`] naming the file and what is
//! wrong; sizes in headers are checked against the data present and capped at
//! [`MAX_POINTS`] before anything is allocated. The formats and their details are described
//! in `docs/topography-files.md`.

mod ascii;
mod bytes;
mod error;
mod gwy;
mod netcdf;
mod npy;
mod process;
mod sur;
mod units;
mod write_npz;
mod x3p;

use std::collections::BTreeMap;
use std::path::Path;

pub use bytes::MAX_POINTS;
pub use error::TopographyError;
pub use netcdf::{write_netcdf, write_netcdf_variables, NcVariable, NetcdfGrid};
pub use process::{ResampleMethod, Resampled, Undersampling};
pub use units::length_unit_to_metres;
pub use write_npz::{write_npz, ArrayData, NamedArray};

use error::{ParseError, ParseResult};

/// A measured height map on a regular grid, in metres.
///
/// `heights[iy * nx + ix]` is the height at `x = x_offset + ix·dx`, `y = y_offset + iy·dy`
/// (row-major, x along a row). Points the file marks invalid (a validity mask, a NaN, a
/// Digital Surf "non-measured" value, a Gwyddion mask) are `false` in `mask` and hold the mean
/// of the valid heights, so every height is finite; `mask` is `None` when all points are valid.
#[derive(Clone, Debug, PartialEq)]
pub struct Topography {
    /// Points along x (columns).
    pub nx: usize,
    /// Points along y (rows).
    pub ny: usize,
    /// Spacing along x in metres.
    pub dx: f64,
    /// Spacing along y in metres.
    pub dy: f64,
    /// Position of the first point along x in metres, as the file records it (0 otherwise).
    pub x_offset: f64,
    /// Position of the first point along y in metres, as the file records it (0 otherwise).
    pub y_offset: f64,
    /// Heights in metres, row-major, `nx * ny` values, all finite.
    pub heights: Vec<f64>,
    /// Validity of each point (`true` = measured), `None` when all are valid.
    pub mask: Option<Vec<bool>>,
    /// Name of the channel read (a Gwyddion title, an npz member, an ASCII "Channel").
    pub channel: String,
    /// Unit the file stored the heights in (before conversion to metres).
    pub height_unit: String,
    /// Unit the file stored the lateral spacing in (before conversion to metres).
    pub lateral_unit: String,
    /// Short name of the format read ("x3p", "gwy", "sur", "ascii", "xyz", "npy", "npz").
    pub format: &'static str,
    /// Other header entries of the file, as text.
    pub metadata: BTreeMap<String, String>,
}

/// What the caller supplies for formats that do not record it, and which channel to read.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ReadOptions {
    /// Channel to read: a Gwyddion title (`/N/data/title`), an npz member name (without
    /// `.npy`), or the ASCII "Channel" header. `None` reads the first channel.
    pub channel: Option<String>,
    /// `(dx, dy)` in metres, for formats that record no spacing (npy, npz, bare ASCII
    /// matrices, a .gwy whose lateral unit is empty). Ignored where the file records its
    /// spacing.
    pub spacing: Option<(f64, f64)>,
    /// Unit of the stored heights (`"nm"`, `"um"`, `"m"`, …) for formats that record none
    /// (npy, npz, bare ASCII, xyz without header, a .gwy whose z unit is empty). Ignored
    /// where the file records its unit; never assumed.
    pub height_unit: Option<String>,
    /// Unit of the x and y columns of an xyz file that records none, or of the sizes of a
    /// .gwy whose lateral unit is empty.
    pub lateral_unit: Option<String>,
}

/// Reads the topography in `path`, choosing the reader by the file extension
/// (case-insensitive): `x3p`; `gwy`; `sur`; `txt`, `asc`, `dat`, `csv` (ASCII matrix); `xyz`;
/// `npy`; `npz`. Spacing and units come from the file where the format records them, from
/// `options` otherwise (an error names what is missing).
pub fn read_topography(path: impl AsRef<Path>, options: &ReadOptions) -> Result<Topography, TopographyError> {
    let path = path.as_ref();
    let format = format_of(path)?;
    let bytes = std::fs::read(path).map_err(|source| TopographyError::Io {
        path: path.to_path_buf(),
        action: "reading",
        source,
    })?;
    read_topography_bytes(&bytes, format, options).map_err(|e| e.with_path(path, format))
}

/// Reads a topography held in memory; `file_name`'s extension chooses the format as in
/// [`read_topography`], and errors name it.
pub fn read_topography_from_bytes(
    bytes: &[u8],
    file_name: impl AsRef<Path>,
    options: &ReadOptions,
) -> Result<Topography, TopographyError> {
    let path = file_name.as_ref();
    let format = format_of(path)?;
    read_topography_bytes(bytes, format, options).map_err(|e| e.with_path(path, format))
}

fn format_of(path: &Path) -> Result<&'static str, TopographyError> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    Ok(match extension.as_str() {
        "x3p" => "x3p",
        "gwy" => "gwy",
        "sur" => "sur",
        "txt" | "asc" | "dat" | "csv" => "ascii",
        "xyz" => "xyz",
        "npy" => "npy",
        "npz" => "npz",
        _ => {
            return Err(TopographyError::UnsupportedFormat {
                path: path.to_path_buf(),
                extension,
            })
        }
    })
}

/// Parses `bytes` as `format` (one of the names in [`Topography::format`]).
fn read_topography_bytes(bytes: &[u8], format: &'static str, options: &ReadOptions) -> ParseResult<Topography> {
    let raw = match format {
        "x3p" => x3p::read(bytes)?,
        "gwy" => gwy::read(bytes, options)?,
        "sur" => sur::read(bytes)?,
        "ascii" => ascii::read_matrix(bytes, options)?,
        "xyz" => ascii::read_xyz(bytes, options)?,
        "npy" => npy::read_npy_map(bytes, "heights", options)?,
        "npz" => npy::read_npz_map(bytes, options)?,
        _ => return Err(ParseError::unsupported(format!("format {format}"))),
    };
    raw.finish(format)
}

/// A map as a reader produces it, before the checks and the filling of invalid points.
pub(crate) struct RawMap {
    pub nx: usize,
    pub ny: usize,
    pub dx: f64,
    pub dy: f64,
    pub x_offset: f64,
    pub y_offset: f64,
    pub heights: Vec<f64>,
    pub valid: Option<Vec<bool>>,
    pub channel: String,
    pub height_unit: String,
    pub lateral_unit: String,
    pub metadata: BTreeMap<String, String>,
}

impl RawMap {
    /// Checks sizes and spacing, marks non-finite heights invalid and fills invalid points
    /// with the mean of the valid ones.
    fn finish(self, format: &'static str) -> ParseResult<Topography> {
        let count = bytes::point_count(self.nx as i64, self.ny as i64)?;
        if self.heights.len() != count {
            return Err(ParseError::malformed(format!(
                "{} heights for a {} × {} grid",
                self.heights.len(),
                self.nx,
                self.ny
            )));
        }
        for (name, value) in [("x spacing", self.dx), ("y spacing", self.dy)] {
            if !(value.is_finite() && value > 0.0) {
                return Err(ParseError::malformed(format!(
                    "{name} is {value} m, not a positive number"
                )));
            }
        }
        let mut valid = match self.valid {
            Some(v) if v.len() != count => {
                return Err(ParseError::malformed(format!(
                    "validity mask has {} points for {count}",
                    v.len()
                )))
            }
            Some(v) => v,
            None => vec![true; count],
        };
        for (flag, h) in valid.iter_mut().zip(&self.heights) {
            *flag &= h.is_finite();
        }
        let valid_count = valid.iter().filter(|&&v| v).count();
        if valid_count == 0 {
            return Err(ParseError::malformed("no valid height in the map"));
        }
        let mean = self
            .heights
            .iter()
            .zip(&valid)
            .filter(|(_, &v)| v)
            .map(|(h, _)| h)
            .sum::<f64>()
            / valid_count as f64;
        if !mean.is_finite() {
            return Err(ParseError::malformed("heights overflow to infinity in metres"));
        }
        let mut heights = self.heights;
        for (h, &v) in heights.iter_mut().zip(&valid) {
            if !v {
                *h = mean;
            }
        }
        Ok(Topography {
            nx: self.nx,
            ny: self.ny,
            dx: self.dx,
            dy: self.dy,
            x_offset: finite_or_zero(self.x_offset),
            y_offset: finite_or_zero(self.y_offset),
            heights,
            mask: (valid_count < count).then_some(valid),
            channel: self.channel,
            height_unit: self.height_unit,
            lateral_unit: self.lateral_unit,
            format,
            metadata: self.metadata,
        })
    }
}

fn finite_or_zero(value: f64) -> f64 {
    if value.is_finite() {
        value
    } else {
        0.0
    }
}

/// The caller's spacing for a format that records none, checked.
pub(crate) fn spacing_option(options: &ReadOptions) -> ParseResult<(f64, f64)> {
    options.spacing.ok_or(ParseError::MissingOption {
        what: "lateral spacing",
        option: "spacing",
    })
}

/// The caller's height unit (as factor to metres and name) for a format that records none.
pub(crate) fn height_unit_option(options: &ReadOptions) -> ParseResult<(f64, String)> {
    let unit = options.height_unit.as_deref().ok_or(ParseError::MissingOption {
        what: "unit of the heights",
        option: "height_unit",
    })?;
    Ok((units::parse_length_unit(unit)?, unit.to_string()))
}
