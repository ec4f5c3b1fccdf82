//! [`ScenarioError`]: the typed error of reading, overriding and validating a scenario,
//! with the key at fault, its value and what it must satisfy, so that a program (the
//! Python package's `adhesim.ScenarioError`) reads them as fields, not from the text.
//!
//! The checks build it where they know the key ([`ScenarioError::invalid`] and friends)
//! and may pass it through `anyhow` inside the crate; the public functions
//! ([`crate::load`], [`crate::parse_toml`], ...) return it with the whole one-line message
//! ([`ScenarioError::from_anyhow`]), the same text the command line prints.

use crate::error_text::error_line;

/// What went wrong.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ErrorKind {
    /// The text is not TOML, or an override is not `KEY=VALUE`.
    Syntax,
    /// A key (or section) the scenario format does not have.
    UnknownKey,
    /// A required key (or section) is missing.
    MissingKey,
    /// A value its key does not accept (type, range, or with the other keys).
    InvalidValue,
    /// An input file that cannot be read or is not a regular file.
    File,
    /// The run would need more memory than this process may use.
    Resources,
}

impl ErrorKind {
    /// The kind as a word (`invalid_value`, ...), as Python's `ScenarioError.kind` gives it.
    pub fn name(self) -> &'static str {
        match self {
            ErrorKind::Syntax => "syntax",
            ErrorKind::UnknownKey => "unknown_key",
            ErrorKind::MissingKey => "missing_key",
            ErrorKind::InvalidValue => "invalid_value",
            ErrorKind::File => "file",
            ErrorKind::Resources => "resources",
        }
    }
}

/// A scenario that cannot be read or run: the kind, the dotted key at fault (`grid.n`)
/// with its value and the requirement it fails (`>= 2`) where they are known, and the
/// message naming them.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{message}")]
pub struct ScenarioError {
    /// What went wrong.
    pub kind: ErrorKind,
    /// The dotted key at fault (`grid.n`, `adhesion.law`), where there is one.
    pub key: Option<String>,
    /// Its value as written (TOML text or the number), where known.
    pub value: Option<String>,
    /// What the value must satisfy (`> 0`, serde's "expected ..."), where known.
    pub requirement: Option<String>,
    message: String,
}

impl ScenarioError {
    /// An error of `kind` with its message and no key.
    pub fn new(kind: ErrorKind, message: impl Into<String>) -> Self {
        Self {
            kind,
            key: None,
            value: None,
            requirement: None,
            message: message.into(),
        }
    }

    /// `KEY must be REQUIREMENT, got VALUE`.
    pub fn invalid(key: &str, value: impl std::fmt::Display, requirement: &str) -> Self {
        let value = value.to_string();
        Self {
            message: format!("{key} must be {requirement}, got {value}"),
            kind: ErrorKind::InvalidValue,
            key: Some(key.to_string()),
            value: Some(value),
            requirement: Some(requirement.to_string()),
        }
    }

    /// `invalid`'s fields with a message of the check's own, which names the key and the
    /// value in words fitting the check (the other keys involved, the file, a hint).
    pub fn invalid_as(
        key: &str,
        value: impl std::fmt::Display,
        requirement: impl Into<String>,
        message: impl Into<String>,
    ) -> Self {
        Self {
            kind: ErrorKind::InvalidValue,
            key: Some(key.to_string()),
            value: Some(value.to_string()),
            requirement: Some(requirement.into()),
            message: message.into(),
        }
    }

    /// A required key that is missing: `requirement` says when it is required.
    pub fn missing(key: &str, requirement: impl Into<String>, message: impl Into<String>) -> Self {
        Self {
            kind: ErrorKind::MissingKey,
            key: Some(key.to_string()),
            value: None,
            requirement: Some(requirement.into()),
            message: message.into(),
        }
    }

    /// A quantity derived from several keys (named in `message`) that fails
    /// `requirement`: no single key is at fault, so `key` is None and `value` is the
    /// derived quantity's.
    pub fn derived(value: impl std::fmt::Display, requirement: impl Into<String>, message: impl Into<String>) -> Self {
        Self {
            kind: ErrorKind::InvalidValue,
            key: None,
            value: Some(value.to_string()),
            requirement: Some(requirement.into()),
            message: message.into(),
        }
    }

    /// The same error naming `key`.
    pub fn with_key(mut self, key: impl Into<String>) -> Self {
        self.key = Some(key.into());
        self
    }

    /// The same error with the value at fault.
    pub fn with_value(mut self, value: impl Into<String>) -> Self {
        self.value = Some(value.into());
        self
    }

    /// The same error with the requirement the value fails.
    pub fn with_requirement(mut self, requirement: impl Into<String>) -> Self {
        self.requirement = Some(requirement.into());
        self
    }

    /// The message: the key, the value and what is wrong (with the context it was met
    /// in, such as the sweep case).
    pub fn message(&self) -> &str {
        &self.message
    }

    /// The typed error inside `error`'s chain, if any, carrying the chain's whole text.
    pub fn find(error: &anyhow::Error) -> Option<Self> {
        let typed = error.chain().find_map(|cause| cause.downcast_ref::<ScenarioError>())?;
        Some(Self {
            message: error_line(error.chain()),
            ..typed.clone()
        })
    }

    /// An error of this crate's internals as a [`ScenarioError`]: the typed error in its
    /// chain, or, for a check not (yet) typed, an [`ErrorKind::InvalidValue`] without key;
    /// the message is the chain on one line either way.
    pub fn from_anyhow(error: anyhow::Error) -> Self {
        Self::find(&error).unwrap_or_else(|| Self::new(ErrorKind::InvalidValue, error_line(error.chain())))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_typed_error_keeps_its_fields_and_takes_the_context_into_its_message() {
        let typed = ScenarioError::invalid("grid.n", -4, ">= 2");
        assert_eq!(typed.to_string(), "grid.n must be >= 2, got -4");
        let wrapped = anyhow::Error::new(typed.clone()).context("case 0 (grid.n = -4)");
        let found = ScenarioError::from_anyhow(wrapped);
        assert_eq!(found.message(), "case 0 (grid.n = -4): grid.n must be >= 2, got -4");
        assert_eq!(
            (
                found.kind,
                found.key.as_deref(),
                found.value.as_deref(),
                found.requirement.as_deref()
            ),
            (ErrorKind::InvalidValue, Some("grid.n"), Some("-4"), Some(">= 2"))
        );
        let untyped = ScenarioError::from_anyhow(anyhow::anyhow!("something else"));
        assert_eq!((untyped.key, untyped.message.as_str()), (None, "something else"));
    }
}
