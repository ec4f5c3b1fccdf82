//! The one error type of the crate: every variant names the file (or the argument) and what is
//! wrong with it, so a caller can print it as it is.

use std::path::PathBuf;

/// Why a topography could not be read, processed or a field file written.
#[derive(Debug, thiserror::Error)]
pub enum TopographyError {
    /// The file could not be opened, read or written.
    #[error("{path}: {action} failed: {source}")]
    Io {
        path: PathBuf,
        action: &'static str,
        #[source]
        source: std::io::Error,
    },
    /// The extension names no supported format.
    #[error("{path}: unsupported file extension {extension:?}; supported: x3p, gwy, sur, txt/asc/dat/csv (ASCII matrix), xyz, npy, npz")]
    UnsupportedFormat { path: PathBuf, extension: String },
    /// The file's content contradicts its format (truncated, inconsistent header, bad value).
    #[error("{path}: malformed {format} file: {what}")]
    Malformed {
        path: PathBuf,
        format: &'static str,
        what: String,
    },
    /// The file is valid but uses a feature this reader does not support.
    #[error("{path}: unsupported {format} feature: {what}")]
    Unsupported {
        path: PathBuf,
        format: &'static str,
        what: String,
    },
    /// The format records no such quantity and the caller did not give it.
    #[error("{path}: the {format} file records no {what} (ReadOptions::{option})")]
    MissingOption {
        path: PathBuf,
        format: &'static str,
        what: &'static str,
        option: &'static str,
    },
    /// The requested channel does not exist; `available` lists the ones that do.
    #[error("{path}: no channel named {requested:?}; the file has: {available}")]
    ChannelNotFound {
        path: PathBuf,
        requested: String,
        available: String,
    },
    /// A unit string that is not a length this crate knows.
    #[error("{context}: unknown length unit {unit:?} (known: m with an SI prefix such as mm, um/µm, nm, pm, or Å)")]
    UnknownUnit { context: String, unit: String },
    /// A processing or writing argument out of its range.
    #[error("invalid {name} = {value}: {why}")]
    InvalidArgument {
        name: &'static str,
        value: String,
        why: String,
    },
}

/// What a format parser reports before the dispatcher adds the path and format name.
#[derive(Debug)]
pub(crate) enum ParseError {
    Malformed(String),
    Unsupported(String),
    MissingOption { what: &'static str, option: &'static str },
    ChannelNotFound { requested: String, available: Vec<String> },
    UnknownUnit(String),
}

impl ParseError {
    pub(crate) fn malformed(what: impl Into<String>) -> Self {
        Self::Malformed(what.into())
    }

    pub(crate) fn unsupported(what: impl Into<String>) -> Self {
        Self::Unsupported(what.into())
    }

    pub(crate) fn with_path(self, path: &std::path::Path, format: &'static str) -> TopographyError {
        let path = path.to_path_buf();
        match self {
            Self::Malformed(what) => TopographyError::Malformed { path, format, what },
            Self::Unsupported(what) => TopographyError::Unsupported { path, format, what },
            Self::MissingOption { what, option } => TopographyError::MissingOption {
                path,
                format,
                what,
                option,
            },
            Self::ChannelNotFound { requested, available } => TopographyError::ChannelNotFound {
                path,
                requested,
                available: available.join(", "),
            },
            Self::UnknownUnit(unit) => TopographyError::UnknownUnit {
                context: format!("{}", path.display()),
                unit,
            },
        }
    }
}

pub(crate) type ParseResult<T> = Result<T, ParseError>;
